//! no_std link check: see Cargo.toml.
#![no_std]
#![no_main]

use core::hint::black_box;
use radiometry::glam::Vec3;
use radiometry::{Brdf, Frame};

// Link the C runtime (for `__libc_start_main`, `memcpy`, `memset`) so the
// release build links and runs on x86_64 Linux.
#[cfg(not(target_os = "none"))]
#[link(name = "c")]
unsafe extern "C" {}

#[cfg(not(target_os = "none"))]
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
    // The mixture components (the warped rule's squares).
    for k in 0..black_box(b.sampling_components()).min(9) {
        *acc += b.component_weight(wo, k);
        if let Some(w) = b.sample_component(wo, k, black_box([0.25, 0.75])) {
            *acc += w.z;
        }
    }
}

use radiometry::Spectrum;

/// Hosted entry (x86_64 Linux, through the C runtime): the binary also runs.
#[cfg(not(target_os = "none"))]
#[unsafe(no_mangle)]
pub extern "C" fn main(_argc: i32, _argv: *const *const u8) -> i32 {
    run()
}

/// Bare-metal entry (thumbv7em-none-eabihf): the image is linked (the proof), not run.
#[cfg(target_os = "none")]
#[unsafe(no_mangle)]
pub extern "C" fn _start() -> ! {
    black_box(run());
    loop {
        core::hint::spin_loop();
    }
}

/// Every group, each in its own never-inlined function (so that a group is optimised without the
/// constants of the others), and the integrators once more all in one function.
fn run() -> i32 {
    let mut acc = 0.0f32;
    brdfs(&mut acc);
    let budget = black_box(1024u32);
    if let Some(g) = albedo() {
        acc += each_integrator(&g, budget);
        acc += all_integrators(&g, budget);
    }
    if let Some(g) = cap_integrand() {
        acc += each_integrator(&g, budget);
    }
    // A mixture sampling map (EON's uniform/cosine): the warped adaptive rule's
    // per-component squares.
    if let Ok(b) = radiometry_brdfs::Eon::new(black_box(0.9f32), 1.0) {
        let g = DirectionalAlbedo {
            brdf: b,
            wo: black_box(Vec3::new(0.9, 0.0, 0.436)),
        };
        acc += adaptive_warped(&g, budget);
    }
    // The light / BRDF / MIS integrand of a cap (the strategy is a run-time value).
    for s in [CapStrategy::Light, CapStrategy::Brdf, CapStrategy::Mis] {
        if let Some(g) = cap_sampled(black_box(s)) {
            acc += each_integrator(&g, budget);
        }
    }
    // The full-hemisphere reflection integrand of an environment light.
    let env = Environment::new(|w: Vec3| 1.0 + black_box(0.5) * w.z);
    if let Ok(d) = Ggx::new(black_box(0.3)) {
        let g = EnvironmentIntegrand {
            brdf: Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel),
            wo: black_box(Vec3::new(0.3, 0.1, 0.9)),
            light: &env,
        };
        acc += each_integrator(&g, budget);
    }
    acc += lights(budget);
    acc += light_sums(budget);
    acc += sensors();
    acc += colour();
    acc += calibration();
    acc += spectral();
    acc += uplift();
    if acc.is_finite() { 0 } else { 1 }
}

/// `eval` / `pdf` / `sample` of the frame, every plugin and the combinators.
#[inline(never)]
fn brdfs(acc: &mut f32) {
    exercise(&Toy, acc);
    let f = Frame::from_normal(black_box(Vec3::new(0.0, 1.0, 1.0)));
    if let Some(f) = f {
        *acc += f.to_local(Vec3::X).x;
    }
    // Every plugin's eval / pdf / sample path.
    use radiometry_brdfs::*;
    if let Ok(b) = Lambertian::new(black_box(0.5f32)) {
        exercise(&b, acc);
    }
    if let Ok(b) = ModifiedPhong::new(black_box(0.2f32), 0.7, 100.0) {
        exercise(&b, acc);
    }
    if let Ok(b) = BlinnPhong::new(black_box(0.2f32), 0.7, 100.0) {
        exercise(&b, acc);
    }
    if let Ok(d) = Ggx::new(black_box(0.3)) {
        exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel), acc);
        if let Ok(f) = Conductor::new(0.2f32, 3.9) {
            exercise(&Microfacet::<_, Separable, _>::new(d, f), acc);
        }
    }
    if let Ok(d) = Beckmann::new(black_box(0.3)) {
        if let Ok(f) = Dielectric::new(1.5) {
            exercise(&Microfacet::<_, HeightCorrelated, _>::new(d, f), acc);
        }
        if let Ok(f) = Schlick::new(0.04f32) {
            exercise(&Microfacet::<_, Separable, _>::new(d, f), acc);
        }
    }
    // Kulla–Conty compensation: every (D, G) table, F = 1 and a conductor.
    if let Ok(d) = Ggx::new(black_box(0.7)) {
        exercise(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel), acc);
        if let Ok(f) = Conductor::new(0.2f32, 3.9) {
            exercise(&KullaConty::<_, Separable, _>::new(d, f), acc);
        }
    }
    if let Ok(d) = Beckmann::new(black_box(0.7)) {
        exercise(&KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel), acc);
        if let Ok(f) = Schlick::new(0.9f32) {
            exercise(&KullaConty::<_, Separable, _>::new(d, f), acc);
        }
    }
    // Rough diffuse: FON, EON (with its closed-form albedo) and the classic Oren–Nayar.
    if let Ok(b) = Fon::new(black_box(0.8f32), 0.5) {
        exercise(&b, acc);
    }
    if let Ok(b) = Eon::new(black_box(Vec3::new(0.9, 0.5, 0.2)), 1.0) {
        exercise(&b, acc);
        *acc += b
            .directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8)))
            .value
            .average();
    }
    if let Ok(b) = OrenNayar::new(black_box(0.5f32), 0.35) {
        exercise(&b, acc);
        *acc += b.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).value;
    }
    // Metals: the F82-tint Fresnel, the directional albedo from the tables
    // (with the Fresnel bounds search), and the named metals' tables.
    if let Ok(d) = Ggx::new(black_box(0.4)) {
        if let Ok(f) = F82Tint::new(black_box(0.9f32), 0.7) {
            let b = Microfacet::<_, HeightCorrelated, _>::new(d, f);
            exercise(&b, acc);
            *acc += b.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).value;
            let k = KullaConty::<_, Separable, _>::new(d, f);
            exercise(&k, acc);
            *acc += k.directional_albedo(black_box(Vec3::new(0.6, 0.0, 0.8))).error;
        }
        let m = metals::Metal::ALL[black_box(2usize) % metals::Metal::ALL.len()];
        let c = Conductor::metal_luminance(m);
        *acc += Microfacet::<_, HeightCorrelated, _>::new(d, c)
            .directional_albedo(black_box(Vec3::Z))
            .value;
        if let Ok(c) = Conductor::metal_sampled(m, &black_box([450.0, 550.0, 650.0, 750.0])) {
            *acc += Microfacet::<_, HeightCorrelated, _>::new(d, c)
                .eval(black_box(Vec3::Z), Vec3::Z)
                .average();
        }
        *acc += m.eta_k_clamped(black_box(1e4)).0 + m.reflectance_rgb().x;
    }
    // Tabulated: a small table and sampling buffer on the stack.
    {
        use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
        let values = black_box([0.3f32; 4 * 4 * 4]);
        let mut buf = [0.0f32; 33];
        if let Ok(g) = RusinkiewiczGrid::new(black_box(4), 4, 4)
            && let Ok(t) = Tabulated::new(g, &values[..])
        {
            exercise(&t, acc);
            if let Ok(t) = t.with_sampling(&mut buf[..]) {
                exercise(&t, acc);
            }
        }
    }
    // The combinators of `radiometry::compose`.
    {
        use radiometry::compose::{Coated, Mix, Sum};
        if let (Ok(d), Ok(l)) = (Ggx::new(black_box(0.2)), Lambertian::new(black_box(0.4f32))) {
            let spec = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
            exercise(&Sum::new(l, spec), acc);
            if let Ok(m) = Mix::new(black_box(0.3), l, spec) {
                exercise(&m, acc);
            }
            if let Ok(f) = Dielectric::new(1.5) {
                exercise(
                    &Coated::new(Microfacet::<_, HeightCorrelated, _>::new(d, f), l),
                    acc,
                );
            }
        }
    }
}

use radiometry::integrator::{
    Adaptive, Auto, DirectionalAlbedo, GaussLegendre, Heuristic, MonteCarlo, PointSet, Strategy,
    WarpedGaussLegendre, integrate_to_tolerance,
};
use radiometry::light::{Cap, CapSampled, CapStrategy, Environment, EnvironmentIntegrand};
use radiometry::spectrum::WideSpectrum;
use radiometry::{Estimate, Integrand, IntegrateError, Integrator};
use radiometry_brdfs::{Ggx, HeightCorrelated, Microfacet, NoFresnel};

type Ggx02 = Microfacet<Ggx, HeightCorrelated, NoFresnel>;

/// GGX (α = 0.2) directional albedo at θo = 60°.
fn albedo() -> Option<DirectionalAlbedo<Ggx02>> {
    let d = Ggx::new(black_box(0.2)).ok()?;
    Some(DirectionalAlbedo {
        brdf: Microfacet::new(d, NoFresnel),
        wo: black_box(Vec3::new(0.5, 0.0, 0.866)),
    })
}

/// The cap light's integrand with a sampling strategy, under a GGX lobe.
fn cap_sampled(strategy: CapStrategy) -> Option<CapSampled<Ggx02>> {
    let d = Ggx::new(black_box(0.2)).ok()?;
    let cap = Cap::new(black_box(Vec3::new(0.4, 0.0, 1.0)), black_box(0.05), 1.0f32).ok()?;
    let g = CapSampled::new(
        Microfacet::new(d, NoFresnel),
        black_box(Vec3::new(-0.4, 0.0, 1.0).normalize()),
        &cap,
        strategy,
    );
    (g.strategy() == strategy).then_some(g)
}

/// A small cap light through a sharp GGX lobe.
fn cap_integrand() -> Option<radiometry::light::CapIntegrand<Ggx02>> {
    use radiometry::light::CapIntegrand;
    let d = Ggx::new(black_box(0.05)).ok()?;
    let cap = Cap::new(black_box(Vec3::new(1.0, 0.0, 0.02)), black_box(0.01), 1.0f32).ok()?;
    let b = Microfacet::new(d, NoFresnel);
    Some(CapIntegrand::new(
        b,
        black_box(Vec3::new(-1.0, 0.0, 0.02).normalize()),
        &cap,
    ))
}

fn value<W: WideSpectrum>(r: Result<Estimate<W>, IntegrateError>) -> f32 {
    r.map_or(0.0, |e| (e.value.channel(0) + e.error.channel(0)) as f32)
}

const STRATEGIES: [Strategy; 5] = [
    Strategy::Uniform,
    Strategy::Cosine,
    Strategy::Integrand,
    Strategy::Mis(Heuristic::Balance),
    Strategy::Mis(Heuristic::Power),
];
const POINT_SETS: [PointSet; 4] = [
    PointSet::Prng,
    PointSet::Stratified,
    PointSet::Fibonacci,
    PointSet::Sobol,
];

#[inline(never)]
fn gauss_legendre<G: Integrand>(g: &G, budget: u32) -> f32 {
    value(GaussLegendre::new().integrate(g, budget))
}

#[inline(never)]
fn warped_gauss_legendre<G: Integrand>(g: &G, budget: u32) -> f32 {
    value(WarpedGaussLegendre::new().integrate(g, budget))
}

#[inline(never)]
fn horizon_split<G: Integrand>(g: &G, budget: u32) -> f32 {
    value(WarpedGaussLegendre::horizon_split().integrate(g, budget))
}

#[inline(never)]
fn adaptive<G: Integrand>(g: &G, budget: u32) -> f32 {
    Adaptive::new(black_box(1e-6), 0.0).map_or(0.0, |a| value(a.integrate(g, budget)))
}

#[inline(never)]
fn adaptive_warped<G: Integrand>(g: &G, budget: u32) -> f32 {
    Adaptive::new(black_box(1e-6), 0.0).map_or(0.0, |a| value(a.warped().integrate(g, budget)))
}

#[inline(never)]
fn auto<G: Integrand>(g: &G, budget: u32) -> f32 {
    value(Auto::new().integrate(g, budget))
}

#[inline(never)]
fn monte_carlo<G: Integrand>(g: &G, budget: u32) -> f32 {
    let mut acc = 0.0;
    for p in POINT_SETS {
        for s in STRATEGIES {
            acc += value(MonteCarlo::new(s, p, black_box(7)).integrate(g, budget));
        }
    }
    acc
}

/// The tolerance driver over the quadrature rule and `Auto` (budgets doubling from `budget / 4`).
#[inline(never)]
fn to_tolerance<G: Integrand>(g: &G, budget: u32) -> f32 {
    let tol = black_box(1e-5);
    let mut acc = 0.0;
    for o in [
        integrate_to_tolerance(&GaussLegendre::new(), g, tol, budget / 4, budget),
        integrate_to_tolerance(&Auto::new(), g, tol, budget / 4, budget),
    ]
    .into_iter()
    .flatten()
    {
        acc += o.estimate.value.channel(0) as f32;
    }
    acc
}

/// Every integrator, each in its own function.
#[inline(never)]
fn each_integrator<G: Integrand>(g: &G, budget: u32) -> f32 {
    gauss_legendre(g, budget)
        + warped_gauss_legendre(g, budget)
        + horizon_split(g, budget)
        + adaptive(g, budget)
        + adaptive_warped(g, budget)
        + auto(g, budget)
        + monte_carlo(g, budget)
        + to_tolerance(g, budget)
}

/// Every integrator called from one function.
#[inline(never)]
fn all_integrators<G: Integrand>(g: &G, budget: u32) -> f32 {
    let mut acc = value(GaussLegendre::new().integrate(g, budget));
    acc += value(WarpedGaussLegendre::new().integrate(g, budget));
    acc += value(WarpedGaussLegendre::horizon_split().integrate(g, budget));
    if let Ok(a) = Adaptive::new(black_box(1e-6), 0.0) {
        acc += value(a.integrate(g, budget));
        acc += value(a.warped().integrate(g, budget));
    }
    acc += value(Auto::new().integrate(g, budget));
    for p in POINT_SETS {
        for s in STRATEGIES {
            acc += value(MonteCarlo::new(s, p, black_box(7)).integrate(g, budget));
        }
    }
    acc
}

/// The lights: closed forms, the reflection equation and the irradiance through a sum of lights.
#[inline(never)]
fn lights(budget: u32) -> f32 {
    use radiometry::light::{self, Cap, Directional, Light, UniformSky};
    use radiometry::radiometric::*;
    let mut acc = cap_solid_angle(black_box(0.3))
        + cap_projected_solid_angle(black_box(0.2), black_box(0.4))
        + cap_irradiance(black_box(2.0e7f32), black_box(0.5), black_box(0.00465))
        + cap_normal_irradiance(black_box(2.0e7f32), black_box(0.00465))
        + sky_irradiance(black_box(1.0f32))
        + directional_irradiance(black_box(1.0f32), black_box(0.5));
    let (Ok(sun), Ok(sky), Ok(lamp)) = (
        Cap::new(black_box(Vec3::new(0.3, 0.0, 1.0)), black_box(0.00465), 2.0e7f32),
        UniformSky::new(black_box(1.0e3f32)),
        Directional::new(black_box(Vec3::new(0.0, 0.6, 0.8)), black_box(10.0f32)),
    ) else {
        return acc;
    };
    acc += sun.irradiance() + sky.irradiance() + lamp.irradiance() + sun.solid_angle();
    acc += sun.contains(black_box(Vec3::Z)) as u8 as f32;
    let lights = (sun, sky, lamp);
    acc += lights.closed_form_irradiance().unwrap_or(0.0);
    acc += value(light::irradiance(&lights, &GaussLegendre::new(), budget));
    if let Ok(d) = Ggx::new(black_box(0.3)) {
        let b = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
        let wo = black_box(Vec3::new(0.3, 0.1, 0.9));
        acc += value(light::reflected_radiance(
            &b,
            &lights,
            wo,
            &GaussLegendre::new(),
            budget,
        ));
        acc += value(light::reflected_radiance(&b, &lights, wo, &Auto::new(), budget));
    }
    acc
}

/// Sums of lights as arrays, slices and `dyn` arrays, an environment light, and the cap's other
/// constructor and accessors.
#[inline(never)]
fn light_sums(budget: u32) -> f32 {
    use radiometry::light::{self, Directional, Light, LightIntegrals, UniformSky};
    let mut acc = 0.0;
    let gl = GaussLegendre::new();
    let (Ok(a), Ok(b), Ok(sky), Ok(lamp), Ok(d)) = (
        Cap::new(black_box(Vec3::new(0.3, 0.0, 1.0)), black_box(0.1), 5.0f32),
        Cap::from_normal_irradiance(black_box(Vec3::new(-0.5, 0.2, 1.0)), black_box(0.2), 3.0f32),
        UniformSky::new(black_box(2.0f32)),
        Directional::new(black_box(Vec3::new(0.0, 0.6, 0.8)), black_box(10.0f32)),
        Ggx::new(black_box(0.3)),
    ) else {
        return acc;
    };
    acc += b.axis().x + b.half_angle() + b.cap_radiance() + b.radiance(black_box(Vec3::Z));
    acc += a.has_delta() as u8 as f32 + lamp.has_delta() as u8 as f32;
    acc += sky.sky_radiance() + lamp.direction().y + lamp.normal_irradiance();
    let brdf = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
    let wo = black_box(Vec3::new(0.3, 0.1, 0.9));
    // An array and a slice of caps.
    let caps = [a, b];
    acc += caps.closed_form_irradiance().unwrap_or(0.0) + caps.radiance(black_box(Vec3::Z));
    acc += value(light::irradiance(&caps, &gl, budget));
    acc += value(light::reflected_radiance(&brdf, &caps, wo, &gl, budget));
    let slice: &[Cap<f32>] = black_box(&caps[..]);
    acc += value(slice.irradiance_estimate(&gl, budget));
    acc += value(slice.reflected_radiance(&brdf, wo, &Auto::new(), budget));
    // Lights chosen at run time, behind `&dyn Light`, with an environment.
    let env = Environment::new(|w: Vec3| 1.0 + black_box(0.5) * w.z);
    acc += env.radiance(black_box(Vec3::new(0.0, 0.0, 2.0))) + env.function()(Vec3::Z);
    let mixed: [&dyn Light<Spectrum = f32>; 4] = [&sky, &lamp, &a, &env];
    acc += value(mixed.irradiance_estimate(&gl, budget));
    acc += value(mixed.reflected_radiance(&brdf, wo, &gl, budget));
    acc += value(light::irradiance(&env, &Auto::new(), budget));
    acc += value(light::reflected_radiance(&brdf, &env, wo, &Auto::new(), budget));
    acc
}

/// The sensor models: ALS, response curves, noise, the EMVA 1288 camera, colour filter arrays.
#[inline(never)]
fn sensors() -> f32 {
    use radiometry::sensor::als::{self, AlsCalibration};
    use radiometry::sensor::color::{self, BayerPattern};
    use radiometry::sensor::response::{Gamma, Linear, Response, Srgb, TabulatedResponse};
    use radiometry::sensor::{
        Emva1288, FillFactor, FnAperture, FnField, Full, Monochromatic, Pcg32, Pixel, Sampling, Sensor,
        UniformSpectral, noise,
    };
    use radiometry::spectral::{self, FnCurve, Scaled};
    let mut acc = 0.0;
    if let Ok(cal) = AlsCalibration::from_reference(
        black_box(16.0),
        black_box(12_016.0),
        black_box(1.0),
        black_box(0.1),
        black_box(500.0),
        black_box(65_535),
    ) {
        let cal = cal.with_spectral_correction(black_box(1.08)).unwrap_or(cal);
        acc += cal
            .lux(black_box(3016), black_box(4.0), black_box(0.025))
            .unwrap_or(0.0);
        acc += cal.dark_counts() + cal.lux_per_count_s() + cal.max_count() as f32;
        acc += cal.spectral_correction();
    }
    if let Ok(cal) = AlsCalibration::new(
        black_box(16.0),
        black_box(0.04),
        black_box(1.0),
        black_box(65_535),
    ) {
        acc += cal
            .lux(black_box(6016), black_box(1.0), black_box(0.1))
            .unwrap_or(0.0);
    }
    let s = spectral::photopic_v();
    acc += als::spectral_correction(&s, &spectral::d65(), &spectral::IlluminantA).unwrap_or(0.0);
    acc += als::simulate_counts(&s, &spectral::d65(), 1e3, 1.0, 0.1, 16.0, 65_535) as f32;
    acc += als::source_lux(&Scaled::new(spectral::d65(), black_box(0.01)));
    // Response curves.
    let x = black_box(0.3);
    acc += Srgb.apply(x) + Srgb.inverse(x) + Linear.apply(x) + Linear.inverse(x);
    if let Ok(g) = Gamma::new(black_box(2.2)) {
        acc += g.apply(x) + g.inverse(x);
    }
    let table = black_box([0.0f32, 0.1, 0.3, 0.6, 1.0]);
    if let Ok(t) = TabulatedResponse::new(&table) {
        acc += t.apply(x) + t.inverse(x);
    }
    // Noise.
    let mut rng = Pcg32::new(black_box(1));
    let mut stream = Pcg32::with_stream(black_box(3), black_box(5));
    acc += stream.next_u32() as f32 + stream.next_f32() + stream.next_f64() as f32;
    acc += noise::uniform(&mut rng) + noise::standard_normal(&mut rng);
    acc += noise::poisson(&mut rng, black_box(3.0)) + noise::poisson(&mut rng, black_box(300.0));
    // The EMVA 1288 camera.
    if let (Ok(ff), Ok(px)) = (
        FillFactor::new(black_box(0.6)),
        FillFactor::new(1.0).and_then(|ff| {
            Pixel::new(
                ff,
                FnCurve::new(380.0, 780.0, |_| 0.6),
                16e-12,
                1e-3,
                Sampling::default(),
            )
        }),
    ) {
        if let Ok(cam) = Emva1288::ideal(px, black_box(0.5), 8_000.0, 12) {
            let cam = cam.with_shot_noise();
            acc += cam.digitize(black_box(1000.0), 3, &mut rng);
            if let Ok(cam) = cam.with_dark_noise(black_box(3.0)) {
                let field = UniformSpectral(Scaled::new(spectral::d65(), black_box(1e-4)));
                acc += cam.read_pixel(&field, 5, &mut rng).unwrap_or(0.0);
            }
        }
        acc += radiometry::sensor::Aperture::mean(&black_box(ff), 1);
    }
    // A camera with a non-uniform aperture, fixed-pattern noise and a dark offset, reading fields
    // that vary in space, time and wavelength (small sample counts: the hosted build also runs).
    let sampling = Sampling {
        space: black_box(3),
        time: black_box(2),
        wavelength_step_nm: black_box(10.0),
    };
    let corner = FnAperture(|x: f32, y: f32| if x < 0.5 && y < black_box(0.7) { 1.0 } else { 0.2 });
    acc += radiometry::sensor::Aperture::mean(&corner, black_box(4));
    if let Ok(px) = Pixel::new(
        corner,
        FnCurve::new(380.0, 780.0, |l| 0.6 - 1e-4 * (l - 550.0)),
        black_box(16e-12),
        black_box(1e-3),
        sampling,
    ) {
        let px = px.with_exposure(black_box(2e-3)).unwrap_or(px);
        acc += px.exposure();
        let mono = Monochromatic::new(black_box(532.0), black_box(0.1));
        let moving = FnField::new(400.0, 700.0, |x, y, _l, t| black_box(1e-3) * (1.0 + x - y + t));
        acc += px.mean_electrons(&mono).unwrap_or(0.0);
        acc += px.mean_electrons(&Full::new(mono, black_box(0.5))).unwrap_or(0.0);
        acc += px.mean_electrons(&moving).unwrap_or(0.0);
        if let Ok(cam) = Emva1288::ideal(px, black_box(0.5), black_box(8_000.0), black_box(10))
            .and_then(|c| c.with_dark_offset(black_box(20.0)))
            .and_then(|c| c.with_fixed_pattern(black_box(1.5), black_box(0.01), 7))
        {
            acc += cam.gain() + cam.saturation() + cam.max_dn() + cam.mean_dn(black_box(1e3));
            acc += cam.digitize(black_box(500.0), black_box(9), &mut rng);
            acc += cam.read(&mono, &mut rng).unwrap_or(0.0);
            acc += cam.read_pixel(&moving, black_box(4), &mut rng).unwrap_or(0.0);
        }
    }
    // Colour filter arrays.
    let rgb = black_box([[0.2f32, 0.5, 0.7]; 16]);
    let mut raw = [0.0f32; 16];
    let mut out = [[0.0f32; 3]; 16];
    let (w, h) = (black_box(4), black_box(4));
    if color::mosaic(&rgb, w, h, BayerPattern::Rggb, &mut raw).is_ok()
        && color::demosaic_bilinear(&raw, w, h, BayerPattern::Rggb, &mut out).is_ok()
    {
        acc += out[5][1];
    }
    acc
}

/// The colour architectures: the slanted-edge chart, Bayer mosaic and Malvar demosaicing, the
/// false-colour energy, the dichroic prism, the filter wheel and stacked layers.
#[inline(never)]
fn colour() -> f32 {
    use radiometry::sensor::color::*;
    use radiometry::spectral::{self, FnCurve, Scaled, SpectralCurve};
    let mut acc = 0.0;
    let (w, h) = (black_box(4), black_box(4));
    let mut img = [[0.0f32; 3]; 16];
    let mut raw = [0.0f32; 16];
    let mut out = [[0.0f32; 3]; 16];
    let pattern = BayerPattern::ALL[black_box(1usize) % BayerPattern::ALL.len()];
    if slanted_edge(w, h, black_box(0.2), black_box(1.5), &mut img).is_ok()
        && mosaic(&img, w, h, pattern, &mut raw).is_ok()
        && demosaic_malvar(&raw, w, h, pattern, &mut out).is_ok()
    {
        acc += false_colour_energy(&out) + out[5][1];
    }
    let light = Scaled::new(spectral::d65(), black_box(1e-3));
    let qe = FnCurve::new(400.0, 700.0, |_| black_box(0.6));
    if let Ok(p) = DichroicPrism::new(black_box(490.0), black_box(590.0), black_box(5.0)) {
        let s = p.split(&light, &qe);
        acc += s[0] + s[1] + s[2] + p.transmittances(black_box(520.0))[1];
    }
    if let Ok(wheel) = FilterWheel::new(black_box(3), black_box(0.01), black_box(4)) {
        let mut frames = [0.0f32; 3 * 16];
        if wheel
            .capture(|x, y, t, k| x - y + 10.0 * t + k as f32, w, h, &mut frames)
            .is_ok()
        {
            acc += frames[20] + wheel.slot_start(black_box(2));
        }
    }
    let l = black_box(550.0);
    acc += silicon_absorption().value(l);
    let f = StackedLayers::foveon();
    acc += f.fractions(l)[1] + f.transmitted(l) + f.respond(&light)[2];
    if let Ok(s) = StackedLayers::new(black_box([0.3f32, 0.9, 2.5, 5.0])) {
        acc += s.fractions(l)[3] + s.transmitted(l) + s.respond(&light)[0];
    }
    acc
}

/// The radiometric calibration fits (Mitsunaga–Nayar, Debevec–Malik), the linear solver and the
/// fitted responses.
#[inline(never)]
fn calibration() -> f32 {
    use radiometry::sensor::calibration::*;
    use radiometry::sensor::response::{Gamma, Response};
    let mut acc = 0.0;
    // Six pixels at three exposures through a γ = 2.2 response.
    let exposures = black_box([0.1f32, 0.3, 1.0]);
    let mut readings = [0.0f32; 6 * 3];
    let mut levels = [0u16; 6 * 3];
    if let Ok(r) = Gamma::new(black_box(2.2)) {
        for (p, (px, lv)) in readings
            .chunks_exact_mut(3)
            .zip(levels.chunks_exact_mut(3))
            .enumerate()
        {
            let e = 0.1 + 0.17 * p as f32;
            for ((m, z), &t) in px.iter_mut().zip(lv.iter_mut()).zip(&exposures) {
                *m = r.apply(e * t);
                *z = (*m * 7.0 + 0.5) as u16;
            }
        }
    }
    let (readings, levels) = (black_box(readings), black_box(levels));
    if let Ok(g) = mitsunaga_nayar::<4>(&readings, &exposures, black_box(0.02), black_box(0.98)) {
        let x = black_box(0.4);
        acc += g.apply(x) + g.inverse(x) + g.eval(black_box(0.01)) + g.m_lo() + g.coeffs()[1];
    }
    if let Ok(g) = PolynomialInverseResponse::new(black_box([0.0f32, 0.6, 0.4]), black_box(0.0)) {
        acc += g.apply(black_box(0.5)) + g.inverse(black_box(0.5));
    }
    if let Ok(g) = debevec_malik::<8, 16>(&levels, &exposures, black_box(2.0)) {
        let x = black_box(0.4);
        acc += g.apply(x) + g.inverse(x) + g.exposures()[3];
    }
    let mut a = black_box([[4.0f64, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]]);
    let mut b = black_box([1.0f64, 2.0, 3.0]);
    if let Ok(x) = solve::<3>(&mut a, &mut b, black_box(3)) {
        acc += x[0] as f32;
    }
    acc
}

/// Spectral curves, photometry and colorimetry.
#[inline(never)]
fn spectral() -> f32 {
    use radiometry::spectral::photometry::*;
    use radiometry::spectral::{self, Blackbody, FnCurve, Irregular, Scaled, SpectralCurve, Tabulated};
    let mut acc = 0.0;
    let l = black_box(555.5);
    acc += spectral::x_bar().value(l) + spectral::y_bar().value(l) + spectral::z_bar().value(l);
    acc += spectral::d65().try_value(l).unwrap_or(0.0) + spectral::IlluminantA.value(l);
    let v = black_box([0.1f32, 0.5, 0.9, 0.4]);
    if let Ok(t) = Tabulated::new(black_box(400.0), black_box(100.0), &v) {
        acc += t.value(l) + t.end() + t.start() + t.step() + t.values().len() as f32;
        acc += t.try_value(black_box(1000.0)).unwrap_or(0.0);
    }
    let lambdas = black_box([400.0f32, 450.0, 600.0, 700.0]);
    if let Ok(t) = Irregular::new(&lambdas, &v) {
        acc += t.value(l);
    }
    if let Ok(b) = Blackbody::new(black_box(5000.0)) {
        acc += b.value(l);
        let xyz = xyz(&b);
        acc += chromaticity(xyz).map_or(0.0, |c| c[0]) + xyz_to_linear_srgb(xyz)[1];
        acc += illuminance_lux(&b);
    }
    acc += illuminance_monochromatic(l, black_box(1.0));
    acc += spectral::integrate_product(&spectral::d65(), &spectral::photopic_v(), black_box(5.0));
    let curve = FnCurve::new(black_box(400.0), black_box(700.0), |x| 1e-3 * x);
    acc += curve.value(l) + Scaled::new(curve, black_box(2.0)).support().1;
    acc += spectral::integrate_fn(black_box(380.0), black_box(780.0), black_box(2.0), |x| {
        spectral::IlluminantA.value(x) * 1e-2
    });
    acc
}

/// RGB → spectrum uplift, the sRGB observer and RGB illuminants.
#[inline(never)]
fn uplift() -> f32 {
    use radiometry::spectral::SpectralCurve;
    use radiometry::spectral::uplift::*;
    let mut acc = 0.0;
    let rgb = black_box([0.6f32, 0.1, 0.05]);
    if let Ok(s) = uplift_reflectance(rgb) {
        acc += s.eval(black_box(550.0)) + s.value(black_box(f32::NAN)) + s.residual();
        acc += reflectance_to_linear_srgb(|l| s.eval(l))[0];
    }
    if let Ok(s) = SigmoidSpectrum::constant(black_box(0.3)) {
        acc += s.coefficients()[2];
    }
    let obs = SrgbObserver::new();
    acc += obs.weights(black_box(512.0))[1];
    if let Ok(ill) = RgbIlluminant::new(black_box([0.5, 0.7, 1.0])) {
        acc += obs.radiance_to_linear_srgb(|l| ill.value(l))[2];
    }
    acc += srgb8_to_linear(black_box(128));
    acc
}
