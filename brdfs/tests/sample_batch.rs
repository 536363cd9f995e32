//! `sample_batch` must return, element by element, what `sample` returns —
//! with the vector kernels of the `simd` feature (GGX and Beckmann, either
//! shadowing–masking variant, every Fresnel term; modified Phong and
//! Blinn–Phong for exponents from 0 to 10⁷ and diffuse/specular mixes
//! including `kd = 0`, `ks = 0` and both; Lambertian; EON, FON and the classic
//! Oren–Nayar for roughnesses from 0 to 1) and with the default loop:
//!
//! ```text
//! cargo test -p radiometry-brdfs --test integration sample_batch:: -- --nocapture
//! cargo test -p radiometry-brdfs --test integration sample_batch:: --features simd -- --nocapture
//! ```
//!
//! Tolerance: **0 ulp** in `wi` (each component), `pdf` and every channel
//! of `weight`, and the same `None` decisions: the kernels perform the
//! scalar operations in the scalar order (the azimuths' `sincos_turn` is a
//! bit-exact port of the scalar one). The returned pdf must also equal `pdf_batch` (and `pdf`) of
//! the returned `wi` bit for bit.
//!
//! Inputs: `wo` over the whole sphere with grazing (`z` down to `10⁻⁴⁵`),
//! non-unit, degenerate and non-finite directions; `u` with `0`, `1 − ε`,
//! `1`, out-of-range and NaN coordinates; `α` at both ends of its range;
//! signed-zero components of `wo` (`u₀ = 0` makes the Phong samplers'
//! `1 − cos θ` a negative zero).

use proptest::prelude::*;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, SampledSpectrum, Spectrum};
use radiometry_brdfs::{
    Beckmann, BlinnPhong, Conductor, Dielectric, Eon, Fon, Ggx, HeightCorrelated, Lambertian, Microfacet,
    ModifiedPhong, NoFresnel, OrenNayar, Schlick, Separable,
};

const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;

/// Bits of one sample (`None` as an empty vector).
fn bits<S: Spectrum>(s: &Option<BrdfSample<S>>) -> Option<Vec<u32>> {
    s.map(|s| {
        let mut v = vec![
            s.wi.x.to_bits(),
            s.wi.y.to_bits(),
            s.wi.z.to_bits(),
            s.pdf.to_bits(),
        ];
        v.extend((0..S::CHANNELS).map(|c| s.weight.channel(c).to_bits()));
        v
    })
}

/// Checks `sample_batch` of `b` on `(wo, u)` against `sample`; returns how
/// many samples were `Some`.
fn compare<B: Brdf>(b: &B, name: &str, wo: &[Vec3], u: &[[f32; 2]]) -> Result<usize, TestCaseError> {
    let n = wo.len();
    let marker = Some(BrdfSample {
        wi: Vec3::X,
        pdf: -7.0,
        weight: B::Spectrum::splat(-7.0),
    });
    let mut out = vec![marker; n + 3];
    b.sample_batch(wo, u, &mut out);
    let mut some = 0;
    let (mut wis, mut wos) = (Vec::new(), Vec::new());
    for k in 0..n {
        let s = b.sample(wo[k], u[k]);
        prop_assert!(
            bits(&s) == bits(&out[k]),
            "{name} k={k} wo={:?} u={:?}: scalar {s:?}, batch {:?}",
            wo[k],
            u[k],
            out[k]
        );
        if let Some(s) = out[k] {
            some += 1;
            prop_assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{name} k={k}: pdf {}", s.pdf);
            for c in 0..B::Spectrum::CHANNELS {
                let w = s.weight.channel(c);
                prop_assert!(w >= 0.0 && w.is_finite(), "{name} k={k}: weight {w}");
            }
            wis.push(s.wi);
            wos.push(wo[k]);
        }
    }
    for (k, o) in out.iter().enumerate().skip(n) {
        prop_assert!(
            o.is_none(),
            "{name}: sample_batch left a stale element {k} past the inputs"
        );
    }
    // The pdf of each returned direction, batched and scalar.
    let mut pdf = vec![0.0f32; wis.len()];
    b.pdf_batch(&wis, &wos, &mut pdf);
    for (j, s) in out[..n].iter().flatten().enumerate() {
        prop_assert!(
            s.pdf.to_bits() == pdf[j].to_bits(),
            "{name}: pdf {} vs pdf_batch {}",
            s.pdf,
            pdf[j]
        );
        prop_assert!(
            s.pdf.to_bits() == b.pdf(wis[j], wos[j]).to_bits(),
            "{name}: pdf vs pdf()"
        );
    }
    // A shorter `u` limits the batch.
    if n > 0 {
        let mut short = vec![marker; n];
        b.sample_batch(wo, &u[..n - 1], &mut short);
        prop_assert!(short[n - 1].is_none(), "{name}: past a short u");
    }
    Ok(some)
}

/// Every microfacet configuration with a kernel (and its spectra).
/// OpenPBR Surface: its `sample_batch` draws each GGX lobe's samples with
/// the lobe's kernel and evaluates the drawn directions through the lobes'
/// batches — every layer on or off, both layering modes, `f32` and RGB.
fn compare_openpbr(alpha: f32, wo: &[Vec3], u: &[[f32; 2]]) -> Result<usize, TestCaseError> {
    let (energy, recip, rgb) = crate::batch::openpbr_materials(alpha);
    let some = compare(&energy, "openpbr", wo, u)?;
    compare(&recip, "openpbr-reciprocal", wo, u)?;
    compare(&rgb, "openpbr-rgb", wo, u)?;
    Ok(some)
}

fn compare_all(alpha: f32, wo: &[Vec3], u: &[[f32; 2]]) -> Result<usize, TestCaseError> {
    compare_openpbr(alpha, wo, u)?;
    type Hc = HeightCorrelated;
    let ggx = Ggx::new(alpha).unwrap();
    let beck = Beckmann::new(alpha).unwrap();
    let schlick_rgb = Schlick::new(Vec3::new(0.04, 0.5, 0.95)).unwrap();
    let gold = Conductor::new(Vec3::new(0.18, 0.42, 1.37), Vec3::new(3.42, 2.35, 1.77)).unwrap();
    let s4 = Conductor::new(
        SampledSpectrum([0.2, 1.0, 1.5, 3.0]),
        SampledSpectrum([0.0, 1.0, 3.0, 9.0]),
    )
    .unwrap();
    let mut some = compare(&Microfacet::<_, Hc, _>::new(ggx, NoFresnel), "ggx-hc", wo, u)?;
    compare(
        &Microfacet::<_, Separable, _>::new(ggx, NoFresnel),
        "ggx-sep",
        wo,
        u,
    )?;
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, schlick_rgb),
        "ggx-hc-schlick-rgb",
        wo,
        u,
    )?;
    let diel = Dielectric::new(1.5).unwrap();
    compare(
        &Microfacet::<_, Separable, _>::new(ggx, diel),
        "ggx-sep-dielectric",
        wo,
        u,
    )?;
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, gold),
        "ggx-hc-conductor-rgb",
        wo,
        u,
    )?;
    compare(
        &Microfacet::<_, Hc, _>::new(ggx, s4),
        "ggx-hc-conductor-s4",
        wo,
        u,
    )?;
    some += compare(
        &Microfacet::<_, Hc, _>::new(beck, NoFresnel),
        "beckmann-hc",
        wo,
        u,
    )?;
    compare(
        &Microfacet::<_, Separable, _>::new(beck, schlick_rgb),
        "beckmann-sep-schlick-rgb",
        wo,
        u,
    )?;
    Ok(some)
}

/// `(kd, ks, n)` of the Phong-family configurations (`f32` spectra):
/// exponents 0, 1, 100, 10⁴, 10⁷ with a mix, the pure lobe, and at
/// `n = 100` the pure diffuse, the black and a lobe-heavy mix.
const PHONG_PARAMS: [(f32, f32, f32); 12] = [
    (0.5, 0.5, 0.0),
    (0.3, 0.7, 1.0),
    (0.0, 1.0, 1.0),
    (0.3, 0.7, 100.0),
    (0.0, 1.0, 100.0),
    (1.0, 0.0, 100.0),
    (0.0, 0.0, 100.0),
    (0.05, 0.95, 100.0),
    (0.3, 0.7, 1e4),
    (0.0, 1.0, 1e4),
    (0.3, 0.7, 1e7),
    (0.0, 1.0, 1e7),
];

/// Every Phong-family configuration of [`PHONG_PARAMS`], both models, and
/// an RGB and a 4-channel one of each; and Lambertian (whose kernel shares
/// the Phong family's cosine-hemisphere warp) in `f32`, RGB and 4 channels.
fn compare_phong(wo: &[Vec3], u: &[[f32; 2]]) -> Result<usize, TestCaseError> {
    let mut some = compare(&Lambertian::new(0.7f32).unwrap(), "lambertian", wo, u)?;
    compare(
        &Lambertian::new(Vec3::new(0.2, 0.5, 0.9)).unwrap(),
        "lambertian-rgb",
        wo,
        u,
    )?;
    compare(
        &Lambertian::new(SampledSpectrum([0.0, 0.3, 0.6, 1.0])).unwrap(),
        "lambertian-s4",
        wo,
        u,
    )?;
    for (kd, ks, n) in PHONG_PARAMS {
        let name = format!("modified-phong kd={kd} ks={ks} n={n}");
        some += compare(&ModifiedPhong::new(kd, ks, n).unwrap(), &name, wo, u)?;
        let name = format!("blinn-phong kd={kd} ks={ks} n={n}");
        some += compare(&BlinnPhong::new(kd, ks, n).unwrap(), &name, wo, u)?;
    }
    let (kd, ks) = (Vec3::new(0.1, 0.5, 0.0), Vec3::new(0.6, 0.3, 0.9));
    compare(
        &ModifiedPhong::new(kd, ks, 30.0).unwrap(),
        "modified-phong-rgb",
        wo,
        u,
    )?;
    compare(&BlinnPhong::new(kd, ks, 30.0).unwrap(), "blinn-phong-rgb", wo, u)?;
    let (kd, ks) = (
        SampledSpectrum([0.0, 0.2, 0.5, 1.0]),
        SampledSpectrum([1.0, 0.8, 0.0, 0.0]),
    );
    compare(
        &ModifiedPhong::new(kd, ks, 500.0).unwrap(),
        "modified-phong-s4",
        wo,
        u,
    )?;
    compare(&BlinnPhong::new(kd, ks, 500.0).unwrap(), "blinn-phong-s4", wo, u)?;
    Ok(some)
}

/// The roughnesses of the rough diffuse configurations (`σ` of EON and
/// FON; the classic Oren–Nayar at `σ · π/2` radians).
const ROUGH_SIGMAS: [f32; 5] = [0.0, 0.1, 0.5, 0.9, 1.0];

/// EON (`f32`, white, RGB, 4 channels), FON and the classic Oren–Nayar
/// (`f32`, RGB) at roughness `sigma`; returns the `Some` count of the
/// `f32` EON.
fn compare_rough(sigma: f32, wo: &[Vec3], u: &[[f32; 2]]) -> Result<usize, TestCaseError> {
    let name = |m: &str| format!("{m} sigma={sigma}");
    let some = compare(&Eon::new(0.8f32, sigma).unwrap(), &name("eon"), wo, u)?;
    compare(&Eon::new(1.0f32, sigma).unwrap(), &name("eon-white"), wo, u)?;
    let rgb = Vec3::new(0.9, 0.2, 0.0);
    compare(&Eon::new(rgb, sigma).unwrap(), &name("eon-rgb"), wo, u)?;
    let s4 = SampledSpectrum([0.0, 0.3, 0.6, 1.0]);
    compare(&Eon::new(s4, sigma).unwrap(), &name("eon-s4"), wo, u)?;
    compare(&Fon::new(0.8f32, sigma).unwrap(), &name("fon"), wo, u)?;
    compare(&Fon::new(rgb, sigma).unwrap(), &name("fon-rgb"), wo, u)?;
    let sigma_rad = sigma * core::f32::consts::FRAC_PI_2;
    let rho = OrenNayar::<f32>::max_rho(sigma_rad);
    compare(
        &OrenNayar::new(rho, sigma_rad).unwrap(),
        &name("oren-nayar"),
        wo,
        u,
    )?;
    let rgb = Vec3::new(rho, 0.5 * rho, 0.0);
    compare(
        &OrenNayar::new(rgb, sigma_rad).unwrap(),
        &name("oren-nayar-rgb"),
        wo,
        u,
    )?;
    // The plastic (`Coated`'s own `sample_batch`: the lobes' kernels per
    // pick), in both layerings and through an absorbing coat.
    use radiometry::compose::{Coated, Layering};
    let coat = Microfacet::<_, HeightCorrelated, _>::new(
        Ggx::new((0.4 * sigma).max(1e-3)).unwrap(),
        Dielectric::new(1.5).unwrap(),
    );
    let eon = Eon::new(0.8f32, sigma).unwrap();
    compare(&Coated::new(coat, eon), &name("coated-plastic"), wo, u)?;
    let reciprocal = Coated::new(coat, eon).with_layering(Layering::Reciprocal);
    compare(&reciprocal, &name("coated-plastic-reciprocal"), wo, u)?;
    let absorbing = Coated::with_absorption(coat, eon, 0.4f32, 1.5).unwrap();
    compare(&absorbing, &name("coated-absorbing"), wo, u)?;
    Ok(some)
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
        Vec3::new(0.6, -0.8, 1e-30),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, f32::INFINITY, 1.0),
        Vec3::new(0.3, 0.4, f32::MAX),
        Vec3::new(f32::MIN_POSITIVE, 0.0, f32::MIN_POSITIVE),
        Vec3::new(3.0, 1.0, 2.0),
        Vec3::new(-0.001, 0.0, 0.002),
        Vec3::new(0.0, 0.0, 1.0 + 2.0 * f32::EPSILON),
        Vec3::new(-0.0, -0.0, 1.0),
        Vec3::new(0.0, -0.0, 1.0),
        Vec3::new(-0.0, 0.0, 1.0),
        Vec3::new(0.6, -0.0, 0.8),
        Vec3::new(-0.0, -0.6, 0.8),
        Vec3::new(0.999_999_9, 0.0, 4.8e-4),
    ]
}

fn hard_us() -> Vec<[f32; 2]> {
    let c = [0.0f32, -0.0, 1e-45, f32::EPSILON, 0.5, ONE_MINUS_EPS, 1.0];
    let mut v = Vec::new();
    for &a in &c {
        for &b in &c {
            v.push([a, b]);
        }
    }
    v.extend([
        [f32::NAN, 0.5],
        [0.5, f32::NAN],
        [-1.0, 2.0],
        [2.0, -1.0],
        [0.25, 0.75],
    ]);
    v
}

/// SplitMix64 uniform `f32` in `[0, 1)`.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Mostly unit upper-hemisphere directions (a fifth near grazing), some
    /// below the horizon and some non-unit.
    fn wo(&mut self, k: usize) -> Vec3 {
        let z = match k % 10 {
            0 => 1e-3 * self.next(),
            1 => 1e-6 * self.next(),
            2 => -self.next(),
            _ => self.next(),
        };
        let r = (1.0 - z * z).max(0.0).sqrt();
        let p = core::f32::consts::TAU * self.next();
        let w = Vec3::new(r * p.cos(), r * p.sin(), z);
        if k % 17 == 5 { w * 3.5 } else { w }
    }
}

/// Every hard `wo` with every hard `u`, in batches of every length 0..=35
/// and at every lane position, for the extreme roughnesses.
#[test]
fn hard_cases_every_lane_and_tail() {
    let (dirs, us) = (hard_directions(), hard_us());
    let mut all = Vec::new();
    for &w in &dirs {
        for &u in &us {
            all.push((w, u));
        }
    }
    for alpha in [1e-4f32, 0.3, 1.0] {
        for len in 0..=35usize {
            for start in (0..all.len()).step_by(37) {
                let (wo, u): (Vec<Vec3>, Vec<[f32; 2]>) =
                    (0..len).map(|j| all[(start + j) % all.len()]).unzip();
                compare_all(alpha, &wo, &u).unwrap();
            }
        }
    }
}

/// The same for the Phong family: every hard `wo` with every hard `u` in
/// every lane position and tail length.
#[test]
fn phong_hard_cases_every_lane_and_tail() {
    let (dirs, us) = (hard_directions(), hard_us());
    let mut all = Vec::new();
    for &w in &dirs {
        for &u in &us {
            all.push((w, u));
        }
    }
    for len in 0..=35usize {
        for start in (0..all.len()).step_by(37) {
            let (wo, u): (Vec<Vec3>, Vec<[f32; 2]>) = (0..len).map(|j| all[(start + j) % all.len()]).unzip();
            compare_phong(&wo, &u).unwrap();
        }
    }
}

/// The same for the rough diffuse family at each of [`ROUGH_SIGMAS`].
#[test]
fn rough_diffuse_hard_cases_every_lane_and_tail() {
    let (dirs, us) = (hard_directions(), hard_us());
    let mut all = Vec::new();
    for &w in &dirs {
        for &u in &us {
            all.push((w, u));
        }
    }
    for sigma in ROUGH_SIGMAS {
        for len in 0..=35usize {
            for start in (0..all.len()).step_by(37) {
                let (wo, u): (Vec<Vec3>, Vec<[f32; 2]>) =
                    (0..len).map(|j| all[(start + j) % all.len()]).unzip();
                compare_rough(sigma, &wo, &u).unwrap();
            }
        }
    }
}

/// 5,000 random `ωo` (drawn first), then 5,000 random `u` with a tenth of
/// the coordinates at `0` or `1 − ε`: the inputs of one round of the sweeps.
fn sweep_inputs(rng: &mut Rng) -> (Vec<Vec3>, Vec<[f32; 2]>) {
    let wo: Vec<Vec3> = (0..5000).map(|k| rng.wo(k)).collect();
    let u: Vec<[f32; 2]> = (0..5000)
        .map(|k| {
            let mut u = [rng.next(), rng.next()];
            match k % 20 {
                0 => u[0] = 0.0,
                1 => u[1] = ONE_MINUS_EPS,
                2 => u[0] = ONE_MINUS_EPS,
                3 => u[1] = 0.0,
                _ => {}
            }
            u
        })
        .collect();
    (wo, u)
}

/// 100 000 random `(wo, u)` per roughness (both ends of the range and
/// between), a tenth of the `u` coordinates at `0` or `1 − ε`.
#[test]
fn sample_batch_sweep() {
    let mut rng = Rng(0x5EED_0007);
    let mut some = 0;
    let mut total = 0;
    for alpha in [1e-4f32, 1e-3, 0.05, 0.3, 0.7, 1.0] {
        for _ in 0..20 {
            let (wo, u) = sweep_inputs(&mut rng);
            some += compare_all(alpha, &wo, &u).unwrap();
            total += 2 * wo.len();
        }
    }
    eprintln!(
        "sample_batch vs sample: {total} samples (GGX and Beckmann, height-correlated), {some} Some; 0 ulp; simd feature: {}",
        cfg!(feature = "simd")
    );
    assert!(some > total / 2, "{some} of {total}");
}

/// 100 000 random `(wo, u)` for each Phong-family configuration, as in
/// [`sample_batch_sweep`].
#[test]
fn phong_sample_batch_sweep() {
    let mut rng = Rng(0x5EED_0008);
    let (mut some, mut total) = (0, 0);
    for _ in 0..20 {
        let (wo, u) = sweep_inputs(&mut rng);
        some += compare_phong(&wo, &u).unwrap();
        total += (2 * PHONG_PARAMS.len() + 1) * wo.len();
    }
    eprintln!(
        "Phong family and Lambertian sample_batch vs sample: {total} samples, {some} Some; 0 ulp; simd feature: {}",
        cfg!(feature = "simd")
    );
    assert!(some > total / 3, "{some} of {total}");
}

/// 100 000 random `(wo, u)` for each rough diffuse configuration and
/// roughness of [`ROUGH_SIGMAS`], as in [`sample_batch_sweep`]; counts the
/// samples that took the uniform branch (`u₀ < p_u`).
#[test]
fn rough_diffuse_sample_batch_sweep() {
    let mut rng = Rng(0x5EED_0009);
    let (mut some, mut total, mut uniform) = (0, 0, 0);
    for sigma in ROUGH_SIGMAS {
        for _ in 0..20 {
            let (wo, u) = sweep_inputs(&mut rng);
            some += compare_rough(sigma, &wo, &u).unwrap();
            total += wo.len();
            uniform += wo
                .iter()
                .zip(&u)
                .filter(|(w, u)| {
                    let c = 1.0 - w.normalize_or_zero().z;
                    w.z > 0.0 && u[0] < 0.5 * sigma * (c * c * c)
                })
                .count();
        }
    }
    eprintln!(
        "rough diffuse sample_batch vs sample: {total} EON samples ({uniform} uniform-branch), {some} Some, and as many for 7 more configurations; 0 ulp; simd feature: {}",
        cfg!(feature = "simd")
    );
    assert!(some > total / 2, "{some} of {total}");
    assert!(uniform > total / 100, "{uniform} of {total}");
}

fn direction() -> impl Strategy<Value = Vec3> {
    let unit = (0.0f32..1.0, 0.0f32..1.0).prop_map(|(u, v)| {
        let z = 1.0 - 2.0 * u;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let p = core::f32::consts::TAU * v;
        Vec3::new(r * p.cos(), r * p.sin(), z)
    });
    let scaled = (unit.clone(), -25i32..25).prop_map(|(w, e)| w * 10f32.powi(e));
    prop_oneof![6 => unit.prop_map(|w| Vec3::new(w.x, w.y, w.z.abs())), 2 => scaled, 1 => prop::sample::select(hard_directions())]
}

fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![8 => 0.0f32..1.0, 1 => prop::sample::select(vec![0.0f32, ONE_MINUS_EPS, 1.0, -0.5, 1.5, f32::NAN])]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 500,
        // Failures are saved to, and replayed from, `sample_batch.proptest-regressions` next to this
        // file (named explicitly: the default location depends on the name of the harness file).
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::WithSource("proptest-regressions"),
        )),
        ..ProptestConfig::default()
    })]

    /// Batches of 0..40 samples: every tail length and lane position.
    #[test]
    fn sample_batch_matches_sample(
        wo in prop::collection::vec(direction(), 0..40),
        u in prop::collection::vec((coordinate(), coordinate()), 40),
        log_alpha in -4.0f32..0.0,
    ) {
        let alpha = 10f32.powf(log_alpha).clamp(1e-4, 1.0);
        let u: Vec<[f32; 2]> = u.iter().take(wo.len()).map(|&(a, b)| [a, b]).collect();
        compare_all(alpha, &wo, &u)?;
    }

    /// The Phong family on the same inputs, with a random exponent and mix.
    #[test]
    fn phong_sample_batch_matches_sample(
        wo in prop::collection::vec(direction(), 0..40),
        u in prop::collection::vec((coordinate(), coordinate()), 40),
        log_n in -1.0f32..7.0,
        kd in 0.0f32..1.0,
        ks_frac in 0.0f32..1.0,
    ) {
        let n = 10f32.powf(log_n).min(1e7);
        let ks = (1.0 - kd) * ks_frac;
        let u: Vec<[f32; 2]> = u.iter().take(wo.len()).map(|&(a, b)| [a, b]).collect();
        compare(&ModifiedPhong::new(kd, ks, n).unwrap(), "modified-phong", &wo, &u)?;
        compare(&BlinnPhong::new(kd, ks, n).unwrap(), "blinn-phong", &wo, &u)?;
        compare_phong(&wo[..wo.len().min(8)], &u[..wo.len().min(8)])?;
    }

    /// The rough diffuse family on the same inputs, with a random roughness.
    #[test]
    fn rough_diffuse_sample_batch_matches_sample(
        wo in prop::collection::vec(direction(), 0..40),
        u in prop::collection::vec((coordinate(), coordinate()), 40),
        sigma in prop_oneof![8 => 0.0f32..1.0, 1 => prop::sample::select(vec![0.0f32, 1.0])],
    ) {
        let u: Vec<[f32; 2]> = u.iter().take(wo.len()).map(|&(a, b)| [a, b]).collect();
        compare_rough(sigma, &wo, &u)?;
    }
}
