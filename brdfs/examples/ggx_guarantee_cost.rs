//! What each guarantee of the GGX (height-correlated, `F = 1`, `α = 0.3`)
//! SoA kernel costs: plain loops over SoA slices that LLVM auto-vectorises,
//! starting from the fewest-division formulation (un-normalised half vector,
//! one division, two square roots; Heitz 2014, Filament) and adding one
//! guarantee of `Microfacet::eval` at a time, timed interleaved with the
//! plugin's `eval_batch_soa` and its scalar `eval` loop — each level once as
//! an auto-vectorised loop and once one pair at a time — on n = 4096 pairs
//! (the `radiometry bench` distribution: θ uniform in [0, 1.55), φ uniform)
//! in golden-ratio order and in random order. Best of 40 rounds.
//!
//! ```sh
//! RUSTFLAGS="-C target-cpu=native" cargo run --release -p radiometry-brdfs --features simd,examples --example ggx_guarantee_cost
//! ```

use radiometry::Brdf;
use radiometry::batch::Vec3Soa;
use radiometry::frame::spherical_direction;
use radiometry::glam::Vec3;
use radiometry::rng::Pcg32;
use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, NoFresnel};
use std::f32::consts::PI;
use std::hint::black_box;
use std::time::Instant;

const ALPHA: f32 = 0.3;

/// One pair's components.
#[derive(Clone, Copy)]
struct Pair {
    i: [f32; 3],
    o: [f32; 3],
}

/// `f_r` of the pair at level `LV` (see `NAMES`); sets `cold` where a
/// level-1 or level-4 check fails.
#[inline(always)]
fn level<const LV: u32>(p: Pair, cold: &mut bool) -> f32 {
    let a2 = ALPHA * ALPHA;
    let [xi, yi, zi] = p.i;
    let [xo, yo, zo] = p.o;
    let (mut hx, mut hy, mut hz) = (xi + xo, yi + yo, zi + zo);
    if LV >= 1 {
        // Both directions unit to within 4ε (else the cold path).
        let li = xi * xi + yi * yi + zi * zi;
        let lo = xo * xo + yo * yo + zo * zo;
        *cold |= ((li - 1.0).abs() > 4.0 * f32::EPSILON) | ((lo - 1.0).abs() > 4.0 * f32::EPSILON);
    }
    if LV >= 2 {
        // The half-vector length correction where |ωi + ωo|² < 1.
        let sum2 = hx * hx + hy * hy + hz * hz;
        let (dx, dy, dz) = (xi - xo, yi - yo, zi - zo);
        let k = (0.25 * dx) * hx + (0.25 * dy) * hy + (0.25 * dz) * hz;
        let c = sum2 < 1.0;
        hx = if c { hx - k * dx } else { hx };
        hy = if c { hy - k * dy } else { hy };
        hz = if c { hz - k * dz } else { hz };
    }
    let (mut hz2, mut hxy) = (hz * hz, hx * hx + hy * hy);
    if LV >= 4 {
        // The plugin's rescaling of tiny squares (θd near 90°).
        let scale = if hxy + hz2 < 1e-20 { 1e20 } else { 1.0 };
        (hz2, hxy) = (hz2 * scale, hxy * scale);
    }
    let l = hxy + hz2;
    let d = a2 * hz2 + hxy;
    let mut f = if LV >= 3 {
        // The projected areas A = (z + √(z² + α² (x² + y²)))/2 of the plugin.
        let ai = 0.5 * (zi + (zi * zi + a2 * (xi * xi + yi * yi)).sqrt());
        let ao = 0.5 * (zo + (zo * zo + a2 * (xo * xo + yo * yo)).sqrt());
        let inv_v = 4.0 * ((zo * ai + zi * ao) - zi * zo);
        ((a2 * l) * l) / (((PI * d) * d) * inv_v)
    } else {
        let ri = (zi * zi * (1.0 - a2) + a2).sqrt();
        let ro = (zo * zo * (1.0 - a2) + a2).sqrt();
        (a2 / (2.0 * PI)) * (l * l) / (d * d * (zo * ri + zi * ro))
    };
    if LV >= 4 {
        // Validity masks, finite_nonneg and the test of the denominator.
        let valid = zi > 0.0 && zo > 0.0 && l > 1e-14;
        f = if f > 0.0 { f.min(f32::MAX) } else { 0.0 };
        *cold |= valid & (f.is_nan());
        if valid { f } else { 0.0 }
    } else if zi > 0.0 && zo > 0.0 {
        f
    } else {
        0.0
    }
}

/// The loop of one level over SoA slices.
#[inline(never)]
fn pass<const LV: u32>(wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]) -> bool {
    let n = out.len();
    let (xi, yi, zi) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (xo, yo, zo) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let mut cold = false;
    for (k, o) in out.iter_mut().enumerate() {
        let p = Pair {
            i: [xi[k], yi[k], zi[k]],
            o: [xo[k], yo[k], zo[k]],
        };
        *o = level::<LV>(p, &mut cold);
    }
    cold
}

/// The same levels one pair at a time: an opaque index keeps LLVM from
/// vectorising across pairs (as the bench's `reference-ggx-scalar` does), so
/// each row is the scalar limit of its level.
#[inline(never)]
#[allow(clippy::needless_range_loop)] // the opaque index is the point
fn pass_scalar<const LV: u32>(wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [f32]) -> bool {
    let n = out.len();
    let (xi, yi, zi) = (&wi.x[..n], &wi.y[..n], &wi.z[..n]);
    let (xo, yo, zo) = (&wo.x[..n], &wo.y[..n], &wo.z[..n]);
    let mut cold = false;
    for k in 0..n {
        let k = black_box(k);
        let p = Pair {
            i: [xi[k], yi[k], zi[k]],
            o: [xo[k], yo[k], zo[k]],
        };
        out[k] = level::<LV>(p, &mut cold);
    }
    cold
}

const NAMES: [&str; 12] = [
    "L0 fewest-division loop",
    "L1 + unit checks",
    "L2 + half-vector length correction",
    "L3 + projected-area form",
    "L4 + masks, rescaling, finite_nonneg",
    "Microfacet eval_batch_soa",
    "scalar L0 fewest-division loop",
    "scalar L1 + unit checks",
    "scalar L2 + half-vector length correction",
    "scalar L3 + projected-area form",
    "scalar L4 + masks, rescaling, finite_nonneg",
    "Microfacet eval (scalar loop)",
];

fn main() {
    let n = 4096;
    let plugin = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(ALPHA).expect("valid α"), NoFresnel);
    for random in [false, true] {
        let mut rng = Pcg32::new(7);
        let frac = |k: usize, g: f64| (k as f64 * g).fract();
        let (mut wi, mut wo) = (Vec::new(), Vec::new());
        for k in 0..n {
            let [a, b, c, d] = if random {
                std::array::from_fn(|_| rng.next_f64())
            } else {
                [
                    frac(k, 0.618_033_988_749_894_9),
                    frac(k, 0.381_966_011_250_105_1),
                    frac(k, 0.754_877_666_246_692_7),
                    frac(k, 0.569_840_290_998_053_2),
                ]
            };
            let tau = std::f64::consts::TAU;
            wi.push(spherical_direction((a * 1.55) as f32, (b * tau) as f32));
            wo.push(spherical_direction((c * 1.55) as f32, (d * tau) as f32));
        }
        let comp = |w: &[Vec3], j: usize| w.iter().map(|v| v[j]).collect::<Vec<f32>>();
        let (ix, iy, iz) = (comp(&wi, 0), comp(&wi, 1), comp(&wi, 2));
        let (ox, oy, oz) = (comp(&wo, 0), comp(&wo, 1), comp(&wo, 2));
        let (si, so) = (Vec3Soa::new(&ix, &iy, &iz), Vec3Soa::new(&ox, &oy, &oz));
        let mut out = vec![0.0f32; n];
        let mut best = [f64::INFINITY; 12];
        for _ in 0..40 {
            for (lv, b) in best.iter_mut().enumerate() {
                let t = Instant::now();
                for _ in 0..50 {
                    let (a, c, o) = (black_box(si), black_box(so), black_box(&mut out[..]));
                    match lv {
                        0 => black_box(pass::<0>(a, c, o)),
                        1 => black_box(pass::<1>(a, c, o)),
                        2 => black_box(pass::<2>(a, c, o)),
                        3 => black_box(pass::<3>(a, c, o)),
                        4 => black_box(pass::<4>(a, c, o)),
                        5 => {
                            plugin.eval_batch_soa(a, c, o);
                            false
                        }
                        6 => black_box(pass_scalar::<0>(a, c, o)),
                        7 => black_box(pass_scalar::<1>(a, c, o)),
                        8 => black_box(pass_scalar::<2>(a, c, o)),
                        9 => black_box(pass_scalar::<3>(a, c, o)),
                        10 => black_box(pass_scalar::<4>(a, c, o)),
                        _ => {
                            let (x, y) = black_box((&wi, &wo));
                            for ((o, &x), &y) in o.iter_mut().zip(x).zip(y) {
                                *o = plugin.eval(x, y);
                            }
                            false
                        }
                    };
                }
                *b = b.min(t.elapsed().as_secs_f64() / 50.0);
            }
        }
        println!(
            "{} directions, n = {n}:",
            if random { "random" } else { "golden-ratio" }
        );
        for (i, (name, b)) in NAMES.iter().zip(best).enumerate() {
            // Vector rows against the vector L0, scalar rows against the scalar L0.
            let (base, l0) = if i < 6 {
                (best[0], "L0")
            } else {
                (best[6], "scalar L0")
            };
            println!(
                "  {name:<44} {:8.1} M/s  {:.3}x {l0}",
                n as f64 / b * 1e-6,
                base / b
            );
        }
    }
}
