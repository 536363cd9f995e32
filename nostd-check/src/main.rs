//! no_std link check: see Cargo.toml.
#![no_std]
#![no_main]

use core::hint::black_box;
use radiometry::glam::Vec3;
use radiometry::{Brdf, Frame};

// Link the C runtime (for `__libc_start_main`, `memcpy`, `memset`) so the
// release build links and runs on x86_64 Linux.
#[link(name = "c")]
unsafe extern "C" {}

#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}

#[cfg(not(feature = "prove-no-panic"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

// With `--features prove-no-panic` (release, LTO), the panic handler calls a
// function that does not exist: the binary links only if the optimiser
// removed every panic path from the code reachable from `main`.
#[cfg(feature = "prove-no-panic")]
unsafe extern "C" {
    fn radiometry_panic_path_survived_optimisation() -> !;
}

#[cfg(feature = "prove-no-panic")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: never called in a binary that links; see above.
    unsafe { radiometry_panic_path_survived_optimisation() }
}

struct Toy;
impl Brdf for Toy {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z > 0.0 && wo.z > 0.0 { 0.3 } else { 0.0 }
    }
}

fn exercise<B: Brdf>(b: &B, acc: &mut f32) {
    let wo = black_box(Vec3::new(0.3, 0.1, 0.9).normalize());
    let wi = black_box(Vec3::new(-0.2, 0.4, 0.8).normalize());
    *acc += b.eval(wi, wo).average();
    *acc += b.pdf(wi, wo);
    if let Some(s) = b.sample(wo, black_box([0.25, 0.75])) {
        *acc += s.pdf + s.weight.average();
    }
}

use radiometry::Spectrum;

#[unsafe(no_mangle)]
pub extern "C" fn main(_argc: i32, _argv: *const *const u8) -> i32 {
    let mut acc = 0.0f32;
    exercise(&Toy, &mut acc);
    let f = Frame::from_normal(black_box(Vec3::new(0.0, 1.0, 1.0)));
    if let Some(f) = f {
        acc += f.to_local(Vec3::X).x;
    }
    // Every plugin's eval / pdf / sample path.
    use radiometry_brdfs::*;
    if let Ok(b) = Lambertian::new(black_box(0.5f32)) {
        exercise(&b, &mut acc);
    }
    if let Ok(b) = ModifiedPhong::new(black_box(0.2f32), 0.7, 100.0) {
        exercise(&b, &mut acc);
    }
    if let Ok(b) = BlinnPhong::new(black_box(0.2f32), 0.7, 100.0) {
        exercise(&b, &mut acc);
    }
    if let Ok(d) = Ggx::new(black_box(0.3)) {
        exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel), &mut acc);
        if let Ok(f) = Conductor::new(0.2f32, 3.9) {
            exercise(&Microfacet::<_, Separable, _>::new(d, f), &mut acc);
        }
    }
    if let Ok(d) = Beckmann::new(black_box(0.3)) {
        if let Ok(f) = Dielectric::new(1.5) {
            exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, f), &mut acc);
        }
        if let Ok(f) = Schlick::new(0.04f32) {
            exercise(&Microfacet::<_, Separable, _>::new(d, f), &mut acc);
        }
    }
    // Kulla–Conty compensation: every (D, G) table, F = 1 and a conductor.
    if let Ok(d) = Ggx::new(black_box(0.7)) {
        exercise(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel), &mut acc);
        if let Ok(f) = Conductor::new(0.2f32, 3.9) {
            exercise(&KullaConty::<_, Separable, _>::new(d, f), &mut acc);
        }
    }
    if let Ok(d) = Beckmann::new(black_box(0.7)) {
        exercise(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel), &mut acc);
        if let Ok(f) = Schlick::new(0.9f32) {
            exercise(&KullaConty::<_, Separable, _>::new(d, f), &mut acc);
        }
    }
    // Rough diffuse: FON, EON (with its closed-form albedo) and the classic Oren–Nayar.
    if let Ok(b) = Fon::new(black_box(0.8f32), 0.5) {
        exercise(&b, &mut acc);
    }
    if let Ok(b) = Eon::new(black_box(Vec3::new(0.9, 0.5, 0.2)), 1.0) {
        exercise(&b, &mut acc);
        acc += b.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).value.average();
    }
    if let Ok(b) = OrenNayar::new(black_box(0.5f32), 0.35) {
        exercise(&b, &mut acc);
        acc += b.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).value;
    }
    // Metals: the F82-tint Fresnel, the directional albedo from the tables
    // (with the Fresnel bounds search), and the named metals' tables.
    if let Ok(d) = Ggx::new(black_box(0.4)) {
        if let Ok(f) = F82Tint::new(black_box(0.9f32), 0.7) {
            let b = Microfacet::<_, HeightCorrelated, _>::new(d, f);
            exercise(&b, &mut acc);
            acc += b.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).value;
            let k = KullaConty::<_, Separable, _>::new(d, f);
            exercise(&k, &mut acc);
            acc += k.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).error;
        }
        let m = metals::Metal::ALL[black_box(2usize) % metals::Metal::ALL.len()];
        let c = Conductor::metal_luminance(m);
        acc += Microfacet::<_, HeightCorrelated, _>::new(d, c)
            .directional_albedo(black_box(Vec3::Z))
            .value;
        if let Ok(c) = Conductor::metal_sampled(m, &black_box([450.0, 550.0, 650.0, 750.0])) {
            acc += Microfacet::<_, HeightCorrelated, _>::new(d, c)
                .eval(black_box(Vec3::Z), Vec3::Z)
                .average();
        }
        acc += m.eta_k_clamped(black_box(1e4)).0 + m.reflectance_rgb().x;
    }
    // Tabulated: a small table and sampling buffer on the stack.
    {
        use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
        let values = black_box([0.3f32; 4 * 4 * 4]);
        let mut buf = [0.0f32; 33];
        if let Ok(g) = RusinkiewiczGrid::new(black_box(4), 4, 4) {
            if let Ok(t) = Tabulated::new(g, &values[..]) {
                exercise(&t, &mut acc);
                if let Ok(t) = t.with_sampling(&mut buf[..]) {
                    exercise(&t, &mut acc);
                }
            }
        }
    }
    // Integrators on a directional-albedo integrand (stack only, no heap):
    // every quadrature rule and every Monte Carlo strategy × point set under
    // the no-panic proof too.
    {
        use radiometry::Integrator;
        use radiometry::integrator::{Adaptive, DirectionalAlbedo, GaussLegendre, WarpedGaussLegendre};
        if let Ok(d) = Ggx::new(black_box(0.2)) {
            let g = DirectionalAlbedo {
                brdf: Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel),
                wo: black_box(Vec3::new(0.5, 0.0, 0.866)),
            };
            let budget = black_box(1024u32);
            if let Ok(e) = GaussLegendre::new().integrate(&g, budget) {
                acc += e.value as f32;
            }
            if let Ok(e) = WarpedGaussLegendre::new().integrate(&g, budget) {
                acc += e.value as f32;
            }
            if let Ok(e) = WarpedGaussLegendre::horizon_split().integrate(&g, budget) {
                acc += e.value as f32;
            }
            if let Ok(a) = Adaptive::new(1e-6, 0.0) {
                if let Ok(e) = a.integrate(&g, budget) {
                    acc += e.value as f32;
                }
                if let Ok(e) = a.warped().integrate(&g, budget) {
                    acc += e.value as f32;
                }
            }
            {
                use radiometry::integrator::{Heuristic, MonteCarlo, PointSet, Strategy};
                let strategies = [
                    Strategy::Uniform,
                    Strategy::Cosine,
                    Strategy::Integrand,
                    Strategy::Mis(Heuristic::Balance),
                    Strategy::Mis(Heuristic::Power),
                ];
                for p in [
                    PointSet::Prng,
                    PointSet::Stratified,
                    PointSet::Fibonacci,
                    PointSet::Sobol,
                ] {
                    for s in strategies {
                        let mc = MonteCarlo::new(s, p, black_box(7));
                        if let Ok(e) = mc.integrate(&g, budget) {
                            acc += e.value as f32;
                        }
                    }
                }
            }
        }
    }
    // A cap light's reflected radiance through its integrand, by quadrature.
    {
        use radiometry::Integrator;
        use radiometry::integrator::{Adaptive, GaussLegendre};
        use radiometry::light::{Cap, CapIntegrand};
        if let (Ok(d), Ok(cap)) = (
            Ggx::new(black_box(0.05)),
            Cap::new(black_box(Vec3::new(1.0, 0.0, 0.02)), black_box(0.01), 1.0f32),
        ) {
            let b = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
            let g = CapIntegrand::new(b, black_box(Vec3::new(-1.0, 0.0, 0.02).normalize()), &cap);
            if let Ok(e) = GaussLegendre::new().integrate(&g, black_box(1024)) {
                acc += e.value as f32;
            }
            if let Ok(a) = Adaptive::new(1e-6, 0.0) {
                if let Ok(e) = a.integrate(&g, black_box(1024)) {
                    acc += e.value as f32;
                }
            }
        }
    }
    if acc.is_finite() { 0 } else { 1 }
}
