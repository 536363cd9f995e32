//! The batch methods must return, element by element, what the scalar
//! methods return — with the vectorised kernels of the `simd` feature and
//! with the default loops alike:
//!
//! ```text
//! cargo test -p radiometry-brdfs --test integration batch:: -- --nocapture
//! cargo test -p radiometry-brdfs --test integration batch:: --features simd -- --nocapture
//! ```
//!
//! Every configuration is checked three ways: `eval_batch` (`&[Vec3]`) and
//! `eval_batch_soa` ([`Vec3Soa`]) against `eval`, and `pdf_batch` against
//! `pdf`.
//!
//! Tolerance: **0 ulp** for every configuration — the kernels perform the
//! scalar operations in the scalar order, and their `exp`/`log1p`/`pow` are
//! bit-exact ports of `libm`'s, so they are bit-identical (`+0` where the
//! scalar value is `+0`); configurations without a kernel use the scalar
//! loop.
//!
//! Every batch value must be finite and `≥ 0`, elements past the shortest
//! input must be zeroed (the batch length rule, `radiometry::batch::zero_tail`,
//! whatever they held), and the deterministic tests print the measured
//! worst error per kernel.

use proptest::prelude::*;
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use radiometry::{Brdf, SampledSpectrum, Spectrum};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Dielectric, Eon, Fon, Ggx, HeightCorrelated, Lambertian, Microfacet,
    ModifiedPhong, NoFresnel, OrenNayar, Schlick, Separable,
};
use std::collections::BTreeMap;

/// Distance in units in the last place between two finite non-negative floats.
fn ulp(a: f32, b: f32) -> u32 {
    a.to_bits().abs_diff(b.to_bits())
}

/// Compares one channel: bit-identical, finite and `≥ 0`; returns the ulp
/// distance (0, or the assertion fails).
/// The description `what` is built only when the check fails.
fn check(scalar: f32, batch: f32, what: impl Fn() -> String) -> Result<f64, TestCaseError> {
    prop_assert!(batch.is_finite() && batch >= 0.0, "{}: batch {batch}", what());
    prop_assert!(
        scalar.to_bits() == batch.to_bits(),
        "{}: scalar {scalar} batch {batch} ({} ulp)",
        what(),
        ulp(scalar, batch)
    );
    Ok(ulp(scalar, batch) as f64)
}

/// Worst ulp distance per `configuration/method`, and how many values
/// were compared.
#[derive(Default)]
struct Report(BTreeMap<String, (f64, usize)>);

impl Report {
    fn add(&mut self, key: String, err: f64, count: usize) {
        let e = self.0.entry(key).or_insert((0.0, 0));
        e.0 = e.0.max(err);
        e.1 += count;
    }
    /// One line per configuration: the worst ulp distance of each method.
    fn print(&self, title: &str) {
        eprintln!("{title}");
        let mut line = String::new();
        let mut current = "";
        for (k, (e, count)) in &self.0 {
            let (config, method) = k.split_once('/').unwrap();
            if config != current {
                if !line.is_empty() {
                    eprintln!("{line}");
                }
                line = format!("  {config:<24}");
                current = config;
            }
            line += &format!(" {method} {e:.0} ulp ({count} values);");
        }
        eprintln!("{line}");
    }
}

/// Structure-of-arrays copies of the two direction lists.
struct Soa {
    x: Vec<f32>,
    y: Vec<f32>,
    z: Vec<f32>,
}

impl Soa {
    fn of(v: &[Vec3]) -> Soa {
        Soa {
            x: v.iter().map(|w| w.x).collect(),
            y: v.iter().map(|w| w.y).collect(),
            z: v.iter().map(|w| w.z).collect(),
        }
    }
    fn view(&self) -> Vec3Soa<'_> {
        Vec3Soa::new(&self.x, &self.y, &self.z)
    }
}

/// Checks `eval_batch`, `eval_batch_soa` and `pdf_batch` of `b` on `pairs`
/// (with longer output buffers whose extra elements must be zeroed)
/// and records the worst errors.
fn compare<B: Brdf>(
    b: &B,
    name: &str,
    pairs: &[(Vec3, Vec3)],
    rep: &mut Report,
) -> Result<(), TestCaseError> {
    let n = pairs.len();
    let wi: Vec<Vec3> = pairs.iter().map(|p| p.0).collect();
    let wo: Vec<Vec3> = pairs.iter().map(|p| p.1).collect();
    let (si, so) = (Soa::of(&wi), Soa::of(&wo));
    let sentinel = B::Spectrum::splat(-7.0);
    let mut aos = vec![sentinel; n + 3];
    b.eval_batch(&wi, &wo, &mut aos);
    let mut soa = vec![sentinel; n + 3];
    b.eval_batch_soa(si.view(), so.view(), &mut soa);
    let mut pdf = vec![-7.0f32; n + 3];
    b.pdf_batch(&wi, &wo, &mut pdf);
    let (mut w_aos, mut w_soa, mut w_pdf) = (0.0f64, 0.0f64, 0.0f64);
    for (k, &(a, c)) in pairs.iter().enumerate() {
        let s = b.eval(a, c);
        for ch in 0..B::Spectrum::CHANNELS {
            let what = |m: &str| format!("{m} {name} k={k} ch={ch} wi={a:?} wo={c:?}");
            let x = s.channel(ch);
            w_aos = w_aos.max(check(x, aos[k].channel(ch), || what("eval_batch"))?);
            w_soa = w_soa.max(check(x, soa[k].channel(ch), || what("eval_batch_soa"))?);
        }
        let what = || format!("pdf_batch {name} k={k} wi={a:?} wo={c:?}");
        w_pdf = w_pdf.max(check(b.pdf(a, c), pdf[k], what)?);
    }
    for k in n..n + 3 {
        prop_assert!(
            aos[k] == B::Spectrum::zero(),
            "{name}: eval_batch left a stale value past the inputs"
        );
        prop_assert!(
            soa[k] == B::Spectrum::zero(),
            "{name}: eval_batch_soa left a stale value past the inputs"
        );
        prop_assert!(
            pdf[k] == 0.0,
            "{name}: pdf_batch left a stale value past the inputs"
        );
    }
    // A shorter `wo` limits the batch too (and one short component slice
    // shortens a `Vec3Soa`).
    if n > 0 {
        let mut out = vec![sentinel; n];
        b.eval_batch(&wi, &wo[..n - 1], &mut out);
        prop_assert!(
            out[n - 1] == B::Spectrum::zero(),
            "{name}: eval_batch past a short wo"
        );
        let mut out = vec![sentinel; n];
        let short = Vec3Soa::new(&so.x, &so.y[..n - 1], &so.z);
        b.eval_batch_soa(si.view(), short, &mut out);
        prop_assert!(
            out[n - 1] == B::Spectrum::zero(),
            "{name}: eval_batch_soa past a short wo"
        );
        for k in 0..n - 1 {
            prop_assert!(out[k] == soa[k], "{name}: eval_batch_soa prefix differs at {k}");
        }
        let mut out = vec![-7.0f32; n];
        b.pdf_batch(&wi[..n - 1], &wo, &mut out);
        prop_assert!(out[n - 1] == 0.0, "{name}: pdf_batch past a short wi");
    }
    // The directional albedo's values: bit for bit the scalar reads, zeros
    // past the inputs.
    let mut albedo = vec![sentinel; n + 3];
    b.directional_albedo_batch(&wo, &mut albedo);
    let mut w_albedo = 0.0f64;
    for (k, &c) in wo.iter().enumerate() {
        let e = b.directional_albedo(c).value;
        for ch in 0..B::Spectrum::CHANNELS {
            let what = || format!("directional_albedo_batch {name} k={k} ch={ch} wo={c:?}");
            w_albedo = w_albedo.max(check(e.channel(ch), albedo[k].channel(ch), what)?);
        }
    }
    prop_assert!(
        albedo[n..].iter().all(|&e| e == B::Spectrum::zero()),
        "{name}: directional_albedo_batch left a stale value past the inputs"
    );
    let values = n * B::Spectrum::CHANNELS;
    rep.add(format!("{name}/directional_albedo_batch"), w_albedo, values);
    rep.add(format!("{name}/eval_batch"), w_aos, values);
    rep.add(format!("{name}/eval_batch_soa"), w_soa, values);
    rep.add(format!("{name}/pdf_batch"), w_pdf, n);
    Ok(())
}

/// A 20-channel spectrum: exercises the kernels' spectrum store past its
/// 16-channel group.
type S20 = SampledSpectrum<20>;

fn s20(f: impl Fn(f32) -> f32) -> S20 {
    S20::from_fn(|i| f(i as f32 / 19.0))
}

/// Every microfacet configuration: both distributions, both `G2`, every
/// Fresnel term, spectra `f32`, RGB, 4 and 20 channels.
fn compare_microfacet(alpha: f32, pairs: &[(Vec3, Vec3)], rep: &mut Report) -> Result<(), TestCaseError> {
    let ggx = Ggx::new(alpha).unwrap();
    let beck = Beckmann::new(alpha).unwrap();
    type Hc = HeightCorrelated;
    let schlick_rgb = Schlick::new(Vec3::new(0.04, 0.5, 0.95)).unwrap();
    let schlick4 = Schlick::new(SampledSpectrum([0.0, 0.3, 0.9, 1.0])).unwrap();
    let gold = Conductor::new(Vec3::new(0.18, 0.42, 1.37), Vec3::new(3.42, 2.35, 1.77)).unwrap();
    let wide = Conductor::new(s20(|t| 1e-3 + 3.0 * t), s20(|t| 1e3 * t * t)).unwrap();
    let mf = |n: &str| format!("ggx-{n}");
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, NoFresnel),
        &mf("hc"),
        pairs,
        rep,
    )?;
    compare(
        &Microfacet::<_, Separable, _>::new(ggx, NoFresnel),
        &mf("sep"),
        pairs,
        rep,
    )?;
    let b = Microfacet::<_, Hc, _>::new(ggx, schlick_rgb);
    compare(&b, &mf("hc-schlick-rgb"), pairs, rep)?;
    let b = Microfacet::<_, Separable, _>::new(ggx, Schlick::new(0.04f32).unwrap());
    compare(&b, &mf("sep-schlick"), pairs, rep)?;
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, schlick4),
        &mf("hc-schlick-s4"),
        pairs,
        rep,
    )?;
    let b = Microfacet::<_, Hc, _>::new(ggx, Dielectric::new(1.5).unwrap());
    compare(&b, &mf("hc-dielectric-1.5"), pairs, rep)?;
    let b = Microfacet::<_, Separable, _>::new(ggx, Dielectric::new(1.0 / 1.5).unwrap());
    compare(&b, &mf("sep-dielectric-0.67"), pairs, rep)?;
    let b = Microfacet::<_, Separable, _>::new(ggx, Dielectric::new(1.0).unwrap());
    compare(&b, &mf("sep-dielectric-1"), pairs, rep)?;
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, gold),
        &mf("hc-conductor-rgb"),
        pairs,
        rep,
    )?;
    let b = Microfacet::<_, Separable, _>::new(ggx, Conductor::new(1.5f32, 0.0).unwrap());
    compare(&b, &mf("sep-conductor-k0"), pairs, rep)?;
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, wide),
        &mf("hc-conductor-s20"),
        pairs,
        rep,
    )?;
    let b = Microfacet::<_, Hc, _>::new(beck, NoFresnel);
    compare(&b, "beckmann-hc", pairs, rep)?;
    let b = Microfacet::<_, Separable, _>::new(beck, Schlick::new(0.04f32).unwrap());
    compare(&b, "beckmann-sep-schlick", pairs, rep)?;
    Ok(())
}

/// Lambertian, modified Phong and Blinn–Phong (exponent `n`).
fn compare_phong_family(n: f32, pairs: &[(Vec3, Vec3)], rep: &mut Report) -> Result<(), TestCaseError> {
    compare(&Lambertian::new(0.7f32).unwrap(), "lambertian", pairs, rep)?;
    let rgb = Lambertian::new(Vec3::new(0.1, 0.5, 1.0)).unwrap();
    compare(&rgb, "lambertian-rgb", pairs, rep)?;
    compare(
        &Lambertian::new(s20(|t| t)).unwrap(),
        "lambertian-s20",
        pairs,
        rep,
    )?;

    let (kd, ks) = (Vec3::new(0.2, 0.0, 0.5), Vec3::new(0.7, 0.9, 0.1));
    compare(&ModifiedPhong::new(0.3f32, 0.6, n).unwrap(), "phong", pairs, rep)?;
    compare(
        &ModifiedPhong::new(0.0f32, 1.0, n).unwrap(),
        "phong-lobe",
        pairs,
        rep,
    )?;
    compare(&ModifiedPhong::new(kd, ks, n).unwrap(), "phong-rgb", pairs, rep)?;
    compare(&BlinnPhong::new(0.3f32, 0.6, n).unwrap(), "blinn", pairs, rep)?;
    compare(
        &BlinnPhong::new(0.0f32, 1.0, n).unwrap(),
        "blinn-lobe",
        pairs,
        rep,
    )?;
    compare(&BlinnPhong::new(kd, ks, n).unwrap(), "blinn-rgb", pairs, rep)?;
    Ok(())
}

/// The rough diffuse family at roughness `sigma ∈ [0, 1]` (EON, FON; the
/// classic Oren–Nayar at `σ = sigma · π/2` radians, with the largest `ρ` it
/// allows): `f32`, RGB and 20 channels.
fn compare_rough_diffuse(sigma: f32, pairs: &[(Vec3, Vec3)], rep: &mut Report) -> Result<(), TestCaseError> {
    compare(&Eon::new(0.8f32, sigma).unwrap(), "eon", pairs, rep)?;
    compare(&Eon::new(1.0f32, sigma).unwrap(), "eon-white", pairs, rep)?;
    let rgb = Vec3::new(0.9, 0.2, 0.0);
    compare(&Eon::new(rgb, sigma).unwrap(), "eon-rgb", pairs, rep)?;
    compare(&Eon::new(s20(|t| t), sigma).unwrap(), "eon-s20", pairs, rep)?;
    compare(&Fon::new(0.8f32, sigma).unwrap(), "fon", pairs, rep)?;
    compare(&Fon::new(rgb, sigma).unwrap(), "fon-rgb", pairs, rep)?;
    let sigma_rad = sigma * core::f32::consts::FRAC_PI_2;
    let rho = OrenNayar::<f32>::max_rho(sigma_rad).min(1.0);
    compare(&OrenNayar::new(rho, sigma_rad).unwrap(), "oren-nayar", pairs, rep)?;
    compare(
        &OrenNayar::new(Vec3::new(rho, 0.5 * rho, 0.0), sigma_rad).unwrap(),
        "oren-nayar-rgb",
        pairs,
        rep,
    )?;
    Ok(())
}

/// The composites (`radiometry::compose`): their batch paths run the lobes'
/// own kernels (AoS and SoA) and combine element by element, so they too
/// must equal the scalar path bit for bit.
fn compare_composites(
    alpha: f32,
    sigma: f32,
    pairs: &[(Vec3, Vec3)],
    rep: &mut Report,
) -> Result<(), TestCaseError> {
    use radiometry::compose::{Coated, Mix, Scaled, Sum};
    let coat =
        Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), Dielectric::new(1.5).unwrap());
    let eon = Eon::new(0.8f32, sigma).unwrap();
    compare(&Coated::new(coat, eon), "coated-plastic", pairs, rep)?;
    // The top as `Coated::new` keeps it: its albedo read in vector lanes.
    compare(&coat.with_prepared_albedo(), "coat-prepared", pairs, rep)?;
    let coat_low = Microfacet::<_, HeightCorrelated, _>::new(
        Ggx::new(alpha).unwrap(),
        Dielectric::new(1.0 + alpha).unwrap(),
    );
    compare(&coat_low.with_prepared_albedo(), "coat-prepared-eta", pairs, rep)?;
    let reciprocal = Coated::new(coat, eon).with_layering(radiometry::compose::Layering::Reciprocal);
    compare(&reciprocal, "coated-plastic-reciprocal", pairs, rep)?;
    let metal = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), NoFresnel);
    let half = |x| Scaled::new(x, 0.5f32).unwrap();
    compare(
        &Sum::new(half(metal), Scaled::new(eon, 0.5f32).unwrap()),
        "sum",
        pairs,
        rep,
    )?;
    compare(&Mix::new(0.3, metal, eon).unwrap(), "mix", pairs, rep)?;
    Ok(())
}

/// The OpenPBR materials the batch suites compare (`batch`, `sample_batch`):
/// roughnesses from `α` (the specular lobe at `r = √α`, so the readers'
/// shared and per-row paths both occur), every layer on above `α = 0.05` and
/// off below — in `f32` (energy-conserving and reciprocal) and RGB.
pub(crate) fn openpbr_materials(
    alpha: f32,
) -> (
    radiometry_brdfs::OpenPbr<f32>,
    radiometry_brdfs::OpenPbr<f32>,
    radiometry_brdfs::OpenPbr<Vec3>,
) {
    use radiometry_brdfs::{Layering, OpenPbr, OpenPbrParams};
    let r = alpha.sqrt();
    let on = |x: f32| if alpha < 0.05 { 0.0 } else { x };
    let p = OpenPbrParams::<f32> {
        specular_roughness: r,
        base_metalness: on(0.4),
        coat_weight: on(0.7),
        coat_roughness: 1.0 - r,
        fuzz_weight: on(0.5),
        ..OpenPbrParams::default()
    };
    let rgb = OpenPbrParams::<Vec3> {
        specular_roughness: r,
        base_color: Vec3::new(0.9, 0.3, 0.1),
        base_metalness: on(1.0),
        coat_weight: on(1.0),
        coat_color: Vec3::new(0.8, 0.9, 1.0),
        coat_ior: 1.3 + alpha,
        ..OpenPbrParams::default()
    };
    (
        OpenPbr::new(p).unwrap(),
        OpenPbr::with_layering(p, Layering::Reciprocal).unwrap(),
        OpenPbr::new(rgb).unwrap(),
    )
}

/// OpenPBR Surface (`radiometry_brdfs::OpenPbr`): its batches run the
/// lobes' own kernels and read the layers' albedos in lanes, so they too must
/// equal the scalar path bit for bit.
fn compare_openpbr(alpha: f32, pairs: &[(Vec3, Vec3)], rep: &mut Report) -> Result<(), TestCaseError> {
    let (energy, recip, rgb) = openpbr_materials(alpha);
    compare(&energy, "openpbr", pairs, rep)?;
    compare(&recip, "openpbr-reciprocal", pairs, rep)?;
    compare(&rgb, "openpbr-rgb", pairs, rep)
}

fn compare_all(alpha: f32, n: f32, pairs: &[(Vec3, Vec3)], rep: &mut Report) -> Result<(), TestCaseError> {
    compare_microfacet(alpha, pairs, rep)?;
    compare_openpbr(alpha, pairs, rep)?;
    compare_phong_family(n, pairs, rep)?;
    compare_composites(alpha, ((alpha.log10() + 4.0) / 4.0).clamp(0.0, 1.0), pairs, rep)?;
    // The roughness range [10⁻⁴, 1] of α mapped onto σ ∈ [0, 1] (both ends).
    compare_rough_diffuse(((alpha.log10() + 4.0) / 4.0).clamp(0.0, 1.0), pairs, rep)
}

/// Directions: mostly upper-hemisphere unit vectors (where the BRDFs are
/// non-zero), plus full-sphere, non-unit (including outside the kernels'
/// fast path), grazing, degenerate and non-finite ones.
fn direction() -> impl Strategy<Value = Vec3> {
    let unit = (0.0f32..1.0, 0.0f32..1.0).prop_map(|(u, v)| {
        let z = 1.0 - 2.0 * u;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let p = core::f32::consts::TAU * v;
        Vec3::new(r * p.cos(), r * p.sin(), z)
    });
    let upper = unit.clone().prop_map(|w| Vec3::new(w.x, w.y, w.z.abs()));
    let scaled = (upper.clone(), -25i32..25).prop_map(|(w, e)| w * 10f32.powi(e));
    let grazing = (
        upper.clone(),
        prop::sample::select(vec![0.0f32, 1e-7, -1e-7, 1e-20, 1e-30, -0.0, 1e-45]),
    )
        .prop_map(|(w, z)| {
            let r = (w.x * w.x + w.y * w.y).sqrt().max(1e-3);
            Vec3::new(w.x / r, w.y / r, z)
        });
    let special = prop::sample::select(hard_directions());
    prop_oneof![6 => upper, 2 => unit, 2 => scaled, 1 => grazing, 1 => special]
}

fn hard_directions() -> Vec<Vec3> {
    vec![
        Vec3::ZERO,
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        Vec3::new(1.0, 0.0, 1e-7),
        Vec3::new(1.0, 0.0, 1e-20),
        Vec3::new(0.6, 0.8, 1e-45),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, f32::INFINITY, 1.0),
        Vec3::new(0.3, 0.4, f32::MAX),
        Vec3::new(f32::MIN_POSITIVE, 0.0, f32::MIN_POSITIVE),
        Vec3::new(3.0, 1.0, 2.0),
        Vec3::new(-0.001, 0.0, 0.002),
    ]
}

/// Pairs: independent, `ωi = −ωo`, mirror (`ωi = (−x, −y, z)` of `ωo`: the
/// GGX peak) and `ωi = ωo`.
fn pair() -> impl Strategy<Value = (Vec3, Vec3)> {
    (direction(), direction(), 0u8..10).prop_map(|(a, c, k)| match k {
        0 => (-c, c),
        1 | 2 => (Vec3::new(-c.x, -c.y, c.z), c),
        3 => (c, c),
        _ => (a, c),
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 1000,
        // Failures are saved to, and replayed from, `batch.proptest-regressions` next to this
        // file (named explicitly: the default location depends on the name of the harness file).
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        ..ProptestConfig::default()
    })]

    /// Batches of 0..40 pairs (so every tail length and every lane position
    /// of an edge case occur) for every configuration.
    #[test]
    fn batch_methods_match_scalar(
        pairs in prop::collection::vec(pair(), 0..40),
        log_alpha in -4.0f32..0.0,
        n in prop::sample::select(vec![0.0f32, 0.01, 1.0, 30.0, 1e4, 1e7]),
    ) {
        let alpha = 10f32.powf(log_alpha).clamp(1e-4, 1.0);
        compare_all(alpha, n, &pairs, &mut Report::default())?;
    }
}

/// Every hard direction paired with every other (and with its negation and
/// mirror image), in batches of every length 0..=35 (two chunks of 16 lanes plus a tail) and at every lane
/// position, for the extreme roughnesses and exponents.
#[test]
fn hard_cases_every_lane_and_tail() {
    let dirs = hard_directions();
    let mut all = Vec::new();
    for &a in &dirs {
        for &c in &dirs {
            all.push((a, c));
        }
        all.push((-a, a));
        all.push((Vec3::new(-a.x, -a.y, a.z), a));
    }
    let mut rep = Report::default();
    for (&alpha, &n) in [1e-4f32, 0.3, 1.0].iter().zip(&[0.01f32, 30.0, 1e7]) {
        for len in 0..=35usize {
            for start in (0..all.len()).step_by(7) {
                let pairs: Vec<_> = (0..len).map(|j| all[(start + j) % all.len()]).collect();
                compare_all(alpha, n, &pairs, &mut rep).unwrap();
            }
        }
    }
    rep.print("hard cases (every lane, lengths 0..=35):");
}

/// Deterministic sweep (SplitMix64, 200 000 pairs in batches of 1000, eight
/// roughnesses including both ends of the range, Phong exponents 0 to 10⁷):
/// prints the worst error of every kernel (0 ulp by design for the exact
/// ones).
#[test]
fn batch_worst_error_sweep() {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut dir = |upper: bool| {
        let z = if upper { next() } else { 1.0 - 2.0 * next() };
        let r = (1.0 - z * z).max(0.0).sqrt();
        let p = core::f32::consts::TAU * next();
        Vec3::new(r * p.cos(), r * p.sin(), z)
    };
    let mut rep = Report::default();
    let mut nonzero = 0usize;
    let exponents = [0.0f32, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5, 1e7];
    for (&alpha, &n) in [1e-4f32, 1e-3, 0.01, 0.05, 0.2, 0.5, 0.8, 1.0]
        .iter()
        .zip(&exponents)
    {
        for _ in 0..25 {
            let pairs: Vec<(Vec3, Vec3)> = (0..1000)
                .map(|k| {
                    let wo = dir(k % 7 != 0);
                    // A third of the pairs near the mirror direction (large D,
                    // Phong lobe peak).
                    let wi = if k % 3 == 0 {
                        let spread = (0.1 * alpha).max(1.0 / (1.0 + n).sqrt());
                        (Vec3::new(-wo.x, -wo.y, wo.z) + spread * dir(false)).normalize()
                    } else {
                        dir(k % 5 != 0)
                    };
                    (wi, wo)
                })
                .collect();
            let b = Microfacet::<_, HeightCorrelated, _>::new(Ggx::new(alpha).unwrap(), NoFresnel);
            nonzero += pairs.iter().filter(|p| b.eval(p.0, p.1) > 0.0).count();
            compare_all(alpha, n, &pairs, &mut rep).unwrap();
        }
    }
    rep.print(&format!(
        "batch vs scalar over 200000 pairs ({nonzero} non-zero GGX values), simd feature: {}",
        cfg!(feature = "simd")
    ));
    assert!(nonzero > 100_000, "{nonzero}");
}
