//! Throwaway (not committed): GGX batch paths vs an auto-vectorised SoA loop of the same formula.
use radiometry::Brdf;
use radiometry::batch::Vec3Soa;
use radiometry::frame::spherical_direction;
use radiometry::glam::Vec3;
use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, NoFresnel, Schlick, Separable};
use std::hint::black_box;
use std::time::Instant;

const N: usize = 4096;

#[inline(never)]
fn reference_soa(alpha: f32, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]) {
    let n = out.len();
    let (xi, yi, zi) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (xo, yo, zo) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let a2 = alpha * alpha;
    for k in 0..n {
        let (hx, hy, hz) = (xi[k] + xo[k], yi[k] + yo[k], zi[k] + zo[k]);
        let len2 = hx * hx + hy * hy + hz * hz;
        let inv = 1.0 / len2;
        let cos2 = hz * hz * inv;
        let sin2 = (hx * hx + hy * hy) * inv;
        let t = a2 * cos2 + sin2;
        let d = a2 / (core::f32::consts::PI * t * t);
        let ai = 0.5 * (zi[k] + (zi[k] * zi[k] + a2 * (xi[k] * xi[k] + yi[k] * yi[k])).sqrt());
        let ao = 0.5 * (zo[k] + (zo[k] * zo[k] + a2 * (xo[k] * xo[k] + yo[k] * yo[k])).sqrt());
        let v = 1.0 / (4.0 * ((zo[k] * ai + zi[k] * ao) - zi[k] * zo[k]));
        out[k] = d * v;
    }
}

#[inline(never)]
fn scalar_loop<B: Brdf>(b: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum]) {
    for ((o, &a), &c) in out.iter_mut().zip(wi).zip(wo) {
        *o = b.eval(a, c);
    }
}
#[inline(never)]
fn batch<B: Brdf>(b: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum]) {
    b.eval_batch(wi, wo, out)
}
#[inline(never)]
fn batch_soa<B: Brdf>(b: &B, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [B::Spectrum]) {
    b.eval_batch_soa(wi, wo, out)
}
#[inline(never)]
fn pdf_batch<B: Brdf>(b: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    b.pdf_batch(wi, wo, out)
}

fn best(mut f: impl FnMut()) -> f64 {
    for _ in 0..50 {
        f();
    }
    let mut best = f64::INFINITY;
    for _ in 0..400 {
        let t = Instant::now();
        for _ in 0..5 {
            f();
        }
        best = best.min(t.elapsed().as_secs_f64() / 5.0);
    }
    best * 1e9 / N as f64
}

fn main() {
    let g = 0.618_034_f32;
    let (mut wi, mut wo) = (Vec::new(), Vec::new());
    for k in 0..N {
        let a = (k as f32 * g).fract();
        let b = (k as f32 * g * g).fract();
        let c = (k as f32 * 0.7548777).fract();
        let d = (k as f32 * 0.5698403).fract();
        wi.push(spherical_direction(a * 1.55, b * core::f32::consts::TAU));
        wo.push(spherical_direction(c * 1.55, d * core::f32::consts::TAU));
    }
    let sx = |v: &[Vec3]| -> (Vec<f32>, Vec<f32>, Vec<f32>) {
        (
            v.iter().map(|w| w.x).collect(),
            v.iter().map(|w| w.y).collect(),
            v.iter().map(|w| w.z).collect(),
        )
    };
    let (ix, iy, iz) = sx(&wi);
    let (ox, oy, oz) = sx(&wo);
    let si = Vec3Soa::new(&ix, &iy, &iz);
    let so = Vec3Soa::new(&ox, &oy, &oz);
    let mut out = vec![0.0f32; N];
    let mut out3 = vec![Vec3::ZERO; N];
    let r = best(|| reference_soa(black_box(0.3), black_box(si), black_box(so), black_box(&mut out)));
    println!("reference SoA (same formula, auto-vectorised): {r:.3} ns/elem");
    let hc = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(0.3).unwrap(), NoFresnel);
    let sep = Microfacet::<_, Separable, _>::new(Ggx::new(0.3).unwrap(), NoFresnel);
    let sch = Microfacet::<_, HeightCorrelated, _>::new(
        Ggx::new(0.3).unwrap(),
        Schlick::new(Vec3::new(1.0, 0.71, 0.29)).unwrap(),
    );
    macro_rules! row {
        ($name:expr, $b:expr, $out:expr) => {{
            let s = best(|| scalar_loop(black_box(&$b), black_box(&wi), black_box(&wo), black_box(&mut $out)));
            let a = best(|| batch(black_box(&$b), black_box(&wi), black_box(&wo), black_box(&mut $out)));
            let q = best(|| batch_soa(black_box(&$b), black_box(si), black_box(so), black_box(&mut $out)));
            let p = best(|| pdf_batch(black_box(&$b), black_box(&wi), black_box(&wo), black_box(&mut out)));
            println!(
                "{:<22} eval {s:.3}  eval_batch {a:.3}  eval_batch_soa {q:.3}  pdf_batch {p:.3} ns/elem | batch/ref {:.2} soa/ref {:.2} (ref/time) | batch vs eval {:.2}x soa vs eval {:.2}x",
                $name, r / a, r / q, s / a, s / q
            );
        }};
    }
    row!("ggx-hc", hc, out);
    row!("ggx-sep", sep, out);
    row!("ggx-hc-schlick-rgb", sch, out3);
    // sanity: same values
    reference_soa(0.3, si, so, &mut out);
    let mut o2 = vec![0.0f32; N];
    hc.eval_batch_soa(si, so, &mut o2);
    let maxrel = out
        .iter()
        .zip(&o2)
        .map(|(a, b)| ((a - b) / b.max(1e-30)).abs())
        .fold(0.0f32, f32::max);
    println!("reference vs kernel max rel diff {maxrel:e}");
}
