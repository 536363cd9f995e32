//! The calls the image makes, in the same order on the Cortex-M and natively: every case returns the values it
//! computed ([`Out`]); the runner prints them (value and bits) and, on the target, measures the case.
//!
//! Each case is one logical call (one `eval`, one integration, one counts → lux conversion); the objects it
//! calls are built before the case, outside the measurement.

use core::hint::black_box;
use radiometry::glam::Vec3;
use radiometry::integrator::{
    Adaptive, Auto, DirectionalAlbedo, GaussLegendre, Heuristic, MonteCarlo, PointSet, Strategy,
    WarpedGaussLegendre,
};
use radiometry::light::{Cap, CapIntegrand, Directional, Light, LightIntegrals, UniformSky};
use radiometry::{Brdf, Estimate, IntegrateError, Integrator, Spectrum};
use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
use radiometry_brdfs::*;

/// The budget of every integration: the firmware configuration of the stack target (≤ 8 KB per integrator).
pub const BUDGET: u32 = 1024;

/// One printed value.
#[derive(Clone, Copy, Debug)]
pub enum V {
    /// An `f32` (printed with its 8 hex digits).
    F32(f32),
    /// An `f64` (16 hex digits).
    F64(f64),
    /// A count or a code.
    U64(u64),
}

/// The values of one case (at most [`Out::CAP`]).
#[derive(Clone, Copy, Debug)]
pub struct Out {
    vals: [V; Out::CAP],
    len: usize,
}

impl Out {
    /// Most values per case.
    pub const CAP: usize = 8;

    /// No values.
    pub const EMPTY: Out = Out {
        vals: [V::U64(0); Out::CAP],
        len: 0,
    };

    /// Appends a value (ignored past [`Out::CAP`]).
    pub fn push(mut self, v: V) -> Self {
        if let Some(slot) = self.vals.get_mut(self.len) {
            *slot = v;
            self.len += 1;
        }
        self
    }

    /// Appends an `f32`.
    pub fn f(self, x: f32) -> Self {
        self.push(V::F32(x))
    }

    /// The values.
    pub fn values(&self) -> &[V] {
        self.vals.get(..self.len).unwrap_or(&[])
    }
}

/// Runs the cases: prints their values; on the target also counts instructions and stack.
pub trait Runner {
    /// A group of cases starts.
    fn phase(&mut self, name: &str);
    /// Runs one case (measured on the target) and prints what it returned.
    fn case(&mut self, name: &str, f: &mut dyn FnMut() -> Out);
}

/// An error code for a failed call (printed instead of values, so the two runs must fail alike).
fn err_code(e: IntegrateError) -> u64 {
    match e {
        IntegrateError::BudgetTooSmall { .. } => 0xE1,
        IntegrateError::NoSamplingMap => 0xE2,
        IntegrateError::NonFiniteIntegrand => 0xE3,
        IntegrateError::InvalidConfig(_) => 0xE4,
        _ => 0xEF,
    }
}

/// Value, error, evaluations and resolved-ness of an integration (first channel).
fn est<W: radiometry::spectrum::WideSpectrum>(r: Result<Estimate<W>, IntegrateError>) -> Out {
    match r {
        Ok(e) => Out::EMPTY
            .push(V::F64(e.value.channel(0)))
            .push(V::F64(e.error.channel(0)))
            .push(V::U64(e.evaluations))
            .push(V::U64(e.is_resolved() as u64)),
        Err(e) => Out::EMPTY.push(V::U64(err_code(e))),
    }
}

fn v3(o: Out, w: Vec3) -> Out {
    o.f(w.x).f(w.y).f(w.z)
}

fn wo() -> Vec3 {
    black_box(Vec3::new(0.3, 0.1, 0.9).normalize())
}

fn wi() -> Vec3 {
    black_box(Vec3::new(-0.2, 0.4, 0.8).normalize())
}

/// `eval`, `sample` and `pdf` of one BRDF, three cases.
pub fn brdf<B: Brdf>(r: &mut dyn Runner, name: &str, b: &B) {
    let (wi, wo) = (wi(), wo());
    let mut buf = [0u8; 48];
    r.case(join(&mut buf, name, ".eval"), &mut || {
        let f = b.eval(wi, wo);
        let mut o = Out::EMPTY;
        for c in 0..B::Spectrum::CHANNELS.min(3) {
            o = o.f(f.channel(c));
        }
        o
    });
    r.case(
        join(&mut buf, name, ".sample"),
        &mut || match b.sample(wo, black_box([0.25, 0.75])) {
            Some(s) => v3(Out::EMPTY, s.wi).f(s.pdf).f(s.weight.channel(0)),
            None => Out::EMPTY.push(V::U64(0xE0)),
        },
    );
    r.case(join(&mut buf, name, ".pdf"), &mut || Out::EMPTY.f(b.pdf(wi, wo)));
}

/// `a` + `b` in `buf` (truncated to its length).
fn join<'a>(buf: &'a mut [u8; 48], a: &str, b: &str) -> &'a str {
    let mut n = 0;
    for &c in a.as_bytes().iter().chain(b.as_bytes()) {
        if let Some(slot) = buf.get_mut(n) {
            *slot = c;
            n += 1;
        }
    }
    // Only ASCII names are used; a cut inside a UTF-8 sequence prints as "?".
    core::str::from_utf8(buf.get(..n).unwrap_or(&[])).unwrap_or("?")
}

/// The ambient-light-sensor path: calibration from a reference reading, spectral correction, counts → lux.
pub fn als(r: &mut dyn Runner) {
    use radiometry::sensor::als::AlsCalibration;
    r.phase("als");
    let mut cal = None;
    r.case("als.from_reference", &mut || {
        cal = AlsCalibration::from_reference(
            black_box(16.0),
            black_box(12_016.0),
            black_box(1.0),
            black_box(0.1),
            black_box(500.0),
            black_box(65_535),
        )
        .ok();
        cal.map_or(Out::EMPTY.push(V::U64(0xE0)), |c| {
            Out::EMPTY.f(c.lux_per_count_s())
        })
    });
    let Some(cal) = cal else { return };
    let mut corrected = cal;
    r.case("als.with_spectral_correction", &mut || {
        corrected = cal.with_spectral_correction(black_box(1.08)).unwrap_or(cal);
        Out::EMPTY.f(corrected.spectral_correction())
    });
    r.case(
        "als.lux",
        &mut || match corrected.lux(black_box(3016), black_box(4.0), black_box(0.025)) {
            Ok(l) => Out::EMPTY.f(l),
            Err(_) => Out::EMPTY.push(V::U64(0xE0)),
        },
    );
    r.case("als.lux.saturated", &mut || {
        Out::EMPTY.push(V::U64(corrected.lux(black_box(65_535), 1.0, 0.1).is_err() as u64))
    });
}

/// The frame helpers every sampler and caller uses.
pub fn frame(r: &mut dyn Runner) {
    use radiometry::Frame;
    use radiometry::frame::spherical_direction;
    r.phase("frame");
    r.case("frame.spherical_direction", &mut || {
        v3(
            Out::EMPTY,
            spherical_direction(black_box(core::f32::consts::FRAC_PI_3), black_box(2.5)),
        )
    });
    r.case(
        "frame.from_normal.to_local",
        &mut || match Frame::from_normal(black_box(Vec3::new(0.0, 1.0, 1.0))) {
            Some(f) => v3(Out::EMPTY, f.to_local(black_box(Vec3::new(0.6, 0.0, 0.8)))),
            None => Out::EMPTY.push(V::U64(0xE0)),
        },
    );
}

/// `eval` / `sample` / `pdf` of every plugin (and the combinators of `radiometry::compose`).
pub fn plugins(r: &mut dyn Runner) {
    use radiometry::compose::{Coated, Mix, Sum};
    r.phase("brdf");
    if let Ok(b) = Lambertian::new(black_box(0.5f32)) {
        brdf(r, "lambertian", &b);
    }
    if let Ok(b) = ModifiedPhong::new(black_box(0.2f32), 0.7, 100.0) {
        brdf(r, "phong", &b);
    }
    if let Ok(b) = BlinnPhong::new(black_box(0.2f32), 0.7, 100.0) {
        brdf(r, "blinn-phong", &b);
    }
    if let Ok(d) = Ggx::new(black_box(0.3)) {
        brdf(r, "ggx", &Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel));
        if let Ok(f) = Conductor::new(0.2f32, 3.9) {
            brdf(r, "ggx-sep-conductor", &Microfacet::<_, Separable, _>::new(d, f));
        }
        if let Ok(f) = Schlick::new(Vec3::new(0.9, 0.6, 0.3)) {
            brdf(
                r,
                "ggx-schlick-rgb",
                &Microfacet::<_, HeightCorrelated, _>::new(d, f),
            );
        }
    }
    if let Ok(d) = Beckmann::new(black_box(0.3)) {
        if let Ok(f) = Dielectric::new(1.5) {
            brdf(
                r,
                "beckmann-dielectric",
                &Microfacet::<_, HeightCorrelated, _>::new(d, f),
            );
        }
        if let Ok(f) = Schlick::new(0.04f32) {
            brdf(
                r,
                "beckmann-sep-schlick",
                &Microfacet::<_, Separable, _>::new(d, f),
            );
        }
    }
    if let Ok(d) = Ggx::new(black_box(0.7)) {
        brdf(
            r,
            "kc-ggx",
            &KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel),
        );
        if let Ok(f) = Conductor::new(0.2f32, 3.9) {
            brdf(
                r,
                "kc-ggx-sep-conductor",
                &KullaConty::<_, Separable, _>::new(d, f),
            );
        }
    }
    if let Ok(d) = Beckmann::new(black_box(0.7)) {
        brdf(
            r,
            "kc-beckmann",
            &KullaConty::<_, HeightCorrelated, _>::new(d, NoFresnel),
        );
        if let Ok(f) = Schlick::new(0.9f32) {
            brdf(
                r,
                "kc-beckmann-sep-schlick",
                &KullaConty::<_, Separable, _>::new(d, f),
            );
        }
    }
    {
        let values = black_box([0.3f32; 4 * 4 * 4]);
        let mut buf = [0.0f32; 33];
        if let Ok(g) = RusinkiewiczGrid::new(black_box(4), 4, 4)
            && let Ok(t) = Tabulated::new(g, &values[..])
        {
            brdf(r, "tabulated", &t);
            if let Ok(t) = t.with_sampling(&mut buf[..]) {
                brdf(r, "tabulated-sampled", &t);
            }
        }
    }
    if let (Ok(d), Ok(l)) = (Ggx::new(black_box(0.2)), Lambertian::new(black_box(0.4f32))) {
        let spec = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
        brdf(r, "sum(lambertian,ggx)", &Sum::new(l, spec));
        if let Ok(m) = Mix::new(black_box(0.3), l, spec) {
            brdf(r, "mix(0.3,lambertian,ggx)", &m);
        }
        if let Ok(f) = Dielectric::new(1.5) {
            let top = Microfacet::<_, HeightCorrelated, _>::new(d, f);
            brdf(r, "coated(ggx,lambertian)", &Coated::new(top, l));
        }
    }
}

/// Closed-form irradiance of each light, and the reflection equation through them.
pub fn lights(r: &mut dyn Runner) {
    use radiometry::radiometric::{cap_irradiance, cap_projected_solid_angle, cap_solid_angle};
    r.phase("lights");
    r.case("radiometric.cap_solid_angle", &mut || {
        Out::EMPTY.f(cap_solid_angle(black_box(0.3)))
    });
    r.case("radiometric.cap_projected_solid_angle", &mut || {
        Out::EMPTY
            .f(cap_projected_solid_angle(black_box(0.2), black_box(0.4)))
            .f(cap_projected_solid_angle(black_box(0.9), black_box(0.01)))
    });
    r.case("radiometric.cap_irradiance", &mut || {
        Out::EMPTY.f(cap_irradiance(
            black_box(2.0e7f32),
            black_box(0.5),
            black_box(0.00465),
        ))
    });
    let (Ok(sun), Ok(sky), Ok(lamp)) = (
        Cap::new(black_box(Vec3::new(0.3, 0.0, 1.0)), black_box(0.00465), 2.0e7f32),
        UniformSky::new(black_box(1.0e3f32)),
        Directional::new(black_box(Vec3::new(0.0, 0.6, 0.8)), black_box(10.0f32)),
    ) else {
        return;
    };
    r.case("cap.irradiance", &mut || Out::EMPTY.f(sun.irradiance()));
    r.case("sky.irradiance", &mut || Out::EMPTY.f(sky.irradiance()));
    r.case("directional.irradiance", &mut || Out::EMPTY.f(lamp.irradiance()));
    let lights = (sun, sky, lamp);
    r.case("sum.closed_form_irradiance", &mut || {
        Out::EMPTY.f(lights.closed_form_irradiance().unwrap_or(-1.0))
    });
    if let Ok(d) = Ggx::new(black_box(0.3)) {
        let b = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
        r.case("sum.reflected_radiance.ggx.gl256", &mut || {
            est(lights.reflected_radiance(&b, wo(), &GaussLegendre::new(), black_box(256)))
        });
    }
}

/// Every integrator at [`BUDGET`] on the directional albedo of GGX (α = 0.2, θo = 60°), and the quadrature
/// rules on a small cap light through a sharp GGX lobe.
pub fn integrators(r: &mut dyn Runner) {
    r.phase("integrators");
    let budget = black_box(BUDGET);
    let Ok(d) = Ggx::new(black_box(0.2)) else { return };
    let g = DirectionalAlbedo {
        brdf: Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel),
        wo: black_box(Vec3::new(0.5, 0.0, 0.866)),
    };
    r.case("gauss-legendre", &mut || {
        est(GaussLegendre::new().integrate(&g, budget))
    });
    r.case("warped-gauss-legendre", &mut || {
        est(WarpedGaussLegendre::new().integrate(&g, budget))
    });
    r.case("warped-gauss-legendre.horizon_split", &mut || {
        est(WarpedGaussLegendre::horizon_split().integrate(&g, budget))
    });
    if let Ok(a) = Adaptive::new(1e-6, 0.0) {
        r.case("adaptive", &mut || est(a.integrate(&g, budget)));
        r.case("adaptive-warped", &mut || est(a.warped().integrate(&g, budget)));
    }
    r.case("auto", &mut || est(Auto::new().integrate(&g, budget)));
    let strategies = [
        (Strategy::Uniform, "uniform"),
        (Strategy::Cosine, "cosine"),
        (Strategy::Integrand, "integrand"),
        (Strategy::Mis(Heuristic::Balance), "mis-balance"),
        (Strategy::Mis(Heuristic::Power), "mis-power"),
    ];
    for (p, pn) in [
        (PointSet::Prng, ".prng"),
        (PointSet::Stratified, ".stratified"),
        (PointSet::Fibonacci, ".fibonacci"),
        (PointSet::Sobol, ".sobol"),
    ] {
        for (s, sn) in strategies {
            let mc = MonteCarlo::new(s, p, black_box(7));
            let mut buf = [0u8; 48];
            let mut name = [0u8; 48];
            let first = join(&mut buf, "mc-", sn);
            let label = join(&mut name, first, pn);
            r.case(label, &mut || est(mc.integrate(&g, budget)));
        }
    }
    if let (Ok(d), Ok(cap)) = (
        Ggx::new(black_box(0.05)),
        Cap::new(black_box(Vec3::new(1.0, 0.0, 0.02)), black_box(0.01), 1.0f32),
    ) {
        let b = Microfacet::<_, HeightCorrelated, _>::new(d, NoFresnel);
        let g = CapIntegrand::new(b, black_box(Vec3::new(-1.0, 0.0, 0.02).normalize()), &cap);
        r.case("cap.gauss-legendre", &mut || {
            est(GaussLegendre::new().integrate(&g, budget))
        });
        if let Ok(a) = Adaptive::new(1e-6, 0.0) {
            r.case("cap.adaptive", &mut || est(a.integrate(&g, budget)));
        }
    }
}

/// Every group, in order.
pub fn all(r: &mut dyn Runner) {
    als(r);
    frame(r);
    plugins(r);
    lights(r);
    integrators(r);
}
