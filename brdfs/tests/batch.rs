//! `Brdf::eval_batch` must return, element by element, what `Brdf::eval`
//! returns — with the vectorised kernels of the `simd` feature and with the
//! default loop alike:
//!
//! ```text
//! cargo test -p radiometry-brdfs --test batch
//! cargo test -p radiometry-brdfs --test batch --features simd
//! ```
//!
//! Tolerance: where `eval` is 0 the batch value must be exactly 0; elsewhere
//! at most `MAX_ULP` = 2 units in the last place (the kernels are designed to
//! be bit-identical — same operations in the same order — and the
//! deterministic test below reports the measured maximum, 0 on x86_64; the
//! 2-ulp allowance covers a target where the compiler could fuse a
//! multiply–add differently in one of the two paths). Every batch value must
//! be finite and `≥ 0`.
//!
//! `ModifiedPhong` is the exception: its kernel evaluates `cos^n α =
//! exp(n ln(1 − δ))` with `wide`'s vector `exp`/`ln_1p` instead of `libm`,
//! so the tolerance is the propagated one, relative `(8 + 8|y|)·2⁻²⁴` with
//! `y = n ln(1 − δ)` (computed in `f64` here; `|y|` is the condition number
//! of `exp`), plus an absolute `10⁻⁴⁴ (1 + ks (n+2)/(2π))` for a lobe value
//! in or below the subnormal range. Structural zeros (below the horizon,
//! degenerate input) must still be exact zeros (checked with `kd > 0`).

use proptest::prelude::*;
use radiometry::Brdf;
use radiometry::glam::Vec3;
use radiometry_brdfs::{
    Beckmann, Ggx, HeightCorrelated, Lambertian, Microfacet, ModifiedPhong, NoFresnel, Schlick, Separable,
};

const MAX_ULP: u32 = 2;

/// Distance in units in the last place between two finite non-negative floats.
fn ulp(a: f32, b: f32) -> u32 {
    assert!(a >= 0.0 && b >= 0.0, "{a} {b}");
    a.to_bits().abs_diff(b.to_bits())
}

/// How a configuration's batch values must match `eval`.
#[derive(Clone, Copy)]
enum Tol {
    /// At most `MAX_ULP`, exact zeros.
    Ulp,
    /// The propagated tolerance of the Phong kernel (see the file docs).
    Phong { n: f32, ks: f32, structural_zeros: bool },
}

/// Compares one channel; returns the ulp distance (for `Tol::Ulp`) or the
/// error in units of `(1 + |y|)·2⁻²⁴` relative (for `Tol::Phong`).
fn check(scalar: f32, batch: f32, tol: Tol, wi: Vec3, wo: Vec3, what: &str) -> Result<f64, TestCaseError> {
    prop_assert!(batch.is_finite() && batch >= 0.0, "{what}: batch {batch}");
    match tol {
        Tol::Ulp => {
            if scalar == 0.0 {
                prop_assert!(batch == 0.0, "{what}: scalar 0, batch {batch}");
                return Ok(0.0);
            }
            let d = ulp(scalar, batch);
            prop_assert!(d <= MAX_ULP, "{what}: scalar {scalar} batch {batch} ({d} ulp)");
            Ok(d as f64)
        }
        Tol::Phong {
            n,
            ks,
            structural_zeros,
        } => {
            if scalar == 0.0 && structural_zeros {
                prop_assert!(batch == 0.0, "{what}: scalar 0, batch {batch}");
                return Ok(0.0);
            }
            // y = n ln(1 − δ), δ = 1 − cos α, in f64 from the normalised inputs.
            let y = match (wi.as_dvec3().try_normalize(), wo.as_dvec3().try_normalize()) {
                (Some(a), Some(c)) => {
                    let cos_alpha = a.dot(radiometry::glam::DVec3::new(-c.x, -c.y, c.z));
                    if cos_alpha > 0.0 {
                        n as f64 * cos_alpha.ln()
                    } else {
                        0.0
                    }
                }
                _ => 0.0,
            };
            let unit = (1.0 + y.abs()) * (-24f64).exp2();
            let norm = (n as f64 + 2.0) / (2.0 * core::f64::consts::PI);
            let abs = 1e-44 * (1.0 + ks as f64 * norm);
            let err = (batch as f64 - scalar as f64).abs();
            prop_assert!(
                err <= 8.0 * unit * scalar as f64 + abs,
                "{what}: scalar {scalar} batch {batch} (y = {y})"
            );
            // Error beyond the absolute allowance, in units of the relative one.
            Ok(if scalar > 0.0 {
                (err - abs).max(0.0) / (unit * scalar as f64)
            } else {
                0.0
            })
        }
    }
}

trait Channels: Copy {
    fn channels(self) -> Vec<f32>;
    fn sentinel() -> Self;
}
impl Channels for f32 {
    fn channels(self) -> Vec<f32> {
        vec![self]
    }
    fn sentinel() -> Self {
        -7.0
    }
}
impl Channels for Vec3 {
    fn channels(self) -> Vec<f32> {
        self.to_array().to_vec()
    }
    fn sentinel() -> Self {
        Vec3::splat(-7.0)
    }
}

/// Runs `eval_batch` on `pairs` (with a longer output buffer whose extra
/// elements must stay untouched) and compares with `eval`; returns the
/// largest ulp distance.
fn compare<B>(b: &B, name: &str, tol: Tol, pairs: &[(Vec3, Vec3)]) -> Result<f64, TestCaseError>
where
    B: Brdf,
    B::Spectrum: Channels,
{
    let wi: Vec<Vec3> = pairs.iter().map(|p| p.0).collect();
    let wo: Vec<Vec3> = pairs.iter().map(|p| p.1).collect();
    let mut out = vec![B::Spectrum::sentinel(); pairs.len() + 3];
    b.eval_batch(&wi, &wo, &mut out);
    let mut worst = 0.0f64;
    for (k, &(a, c)) in pairs.iter().enumerate() {
        let s = b.eval(a, c);
        for (ch, (x, y)) in s.channels().into_iter().zip(out[k].channels()).enumerate() {
            let what = format!("{name} k={k} ch={ch} wi={a:?} wo={c:?}");
            worst = worst.max(check(x, y, tol, a, c, &what)?);
        }
    }
    for o in &out[pairs.len()..] {
        prop_assert!(
            o.channels() == B::Spectrum::sentinel().channels(),
            "{name}: wrote past the inputs"
        );
    }
    // A shorter `wo` limits the batch too.
    if !pairs.is_empty() {
        let mut out2 = vec![B::Spectrum::sentinel(); pairs.len()];
        b.eval_batch(&wi, &wo[..pairs.len() - 1], &mut out2);
        prop_assert!(out2[pairs.len() - 1].channels() == B::Spectrum::sentinel().channels());
    }
    Ok(worst)
}

/// Every configuration that has a batch kernel, plus a scalar fallback
/// (Beckmann). Returns the worst ulp distance of the exact kernels and the
/// worst scaled error of the Phong kernel.
fn compare_all(alpha: f32, n: f32, pairs: &[(Vec3, Vec3)]) -> Result<(f64, f64), TestCaseError> {
    let ggx = Ggx::new(alpha).unwrap();
    let u = Tol::Ulp;
    let mut w = 0.0f64;
    w = w.max(compare(
        &Microfacet::<_, HeightCorrelated, _>::new(ggx, NoFresnel),
        "ggx-hc",
        u,
        pairs,
    )?);
    w = w.max(compare(
        &Microfacet::<_, Separable, _>::new(ggx, NoFresnel),
        "ggx-sep",
        u,
        pairs,
    )?);
    let schlick = Schlick::new(Vec3::new(0.04, 0.5, 0.95)).unwrap();
    let b = Microfacet::<_, HeightCorrelated, _>::new(ggx, schlick);
    w = w.max(compare(&b, "ggx-hc-schlick", u, pairs)?);
    let beck = Beckmann::new(alpha).unwrap();
    w = w.max(compare(
        &Microfacet::<_, Separable, _>::new(beck, NoFresnel),
        "beckmann-sep",
        u,
        pairs,
    )?);
    w = w.max(compare(
        &Lambertian::new(0.7f32).unwrap(),
        "lambertian",
        u,
        pairs,
    )?);
    let rgb = Lambertian::new(Vec3::new(0.1, 0.5, 1.0)).unwrap();
    w = w.max(compare(&rgb, "lambertian-rgb", u, pairs)?);
    let mut p = 0.0f64;
    let tol = Tol::Phong {
        n,
        ks: 0.6,
        structural_zeros: true,
    };
    p = p.max(compare(
        &ModifiedPhong::new(0.3f32, 0.6, n).unwrap(),
        "phong",
        tol,
        pairs,
    )?);
    let tol = Tol::Phong {
        n,
        ks: 1.0,
        structural_zeros: false,
    };
    p = p.max(compare(
        &ModifiedPhong::new(0.0f32, 1.0, n).unwrap(),
        "phong-lobe",
        tol,
        pairs,
    )?);
    let (kd, ks) = (Vec3::new(0.2, 0.0, 0.5), Vec3::new(0.7, 0.9, 0.1));
    let tol = Tol::Phong {
        n,
        ks: 0.9,
        structural_zeros: false,
    };
    p = p.max(compare(
        &ModifiedPhong::new(kd, ks, n).unwrap(),
        "phong-rgb",
        tol,
        pairs,
    )?);
    Ok((w, p))
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
    let special = prop::sample::select(vec![
        Vec3::ZERO,
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, f32::INFINITY, 1.0),
        Vec3::new(0.3, 0.4, f32::MAX),
        Vec3::new(f32::MIN_POSITIVE, 0.0, f32::MIN_POSITIVE),
    ]);
    prop_oneof![6 => upper, 2 => unit, 2 => scaled, 1 => grazing, 1 => special]
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
    #![proptest_config(ProptestConfig::with_cases(1500))]

    /// Batches of 0..40 pairs (so every tail length and every lane position
    /// of an edge case occur) for every configuration.
    #[test]
    fn eval_batch_matches_eval(
        pairs in prop::collection::vec(pair(), 0..40),
        log_alpha in -4.0f32..0.0,
        n in prop::sample::select(vec![0.0f32, 1.0, 30.0, 1e4, 1e7]),
    ) {
        let alpha = 10f32.powf(log_alpha).clamp(1e-4, 1.0);
        compare_all(alpha, n, &pairs)?;
    }
}

/// Deterministic sweep (SplitMix64, 200 000 pairs in batches of 1000, eight
/// roughnesses including both ends of the range, Phong exponents 0 to 10⁷):
/// reports the worst ulp distance of the exact kernels, which their design
/// makes 0, and the worst Phong error in units of `(1 + |y|)·2⁻²⁴`.
#[test]
fn eval_batch_worst_error_sweep() {
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
    let (mut worst, mut worst_phong) = (0.0f64, 0.0f64);
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
            let (w, p) = compare_all(alpha, n, &pairs).unwrap();
            worst = worst.max(w);
            worst_phong = worst_phong.max(p);
        }
    }
    eprintln!(
        "eval_batch vs eval over 200000 pairs x 9 BRDFs ({nonzero} non-zero GGX values): \
         exact kernels worst {worst} ulp; Phong worst {worst_phong:.3} x (1+|y|) 2^-24 relative"
    );
    assert!(nonzero > 100_000, "{nonzero}");
    assert!(worst <= MAX_ULP as f64);
}
