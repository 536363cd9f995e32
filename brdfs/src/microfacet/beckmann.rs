//! The Beckmann normal distribution.

use super::special::{LAMBDA_ZERO_A, erfinv_2p_minus_1, exp_neg64, lambda_from_exp};
use super::{
    MAX_ALPHA, MIN_ALPHA, MicrofacetDistribution, beckmann_slope, clamp01, tan2_theta_robust, unitize,
};
use crate::error::{BrdfError, check_range};
use radiometry::glam::Vec3;

/// The isotropic Beckmann microfacet distribution.
///
/// Beckmann & Spizzichino 1963, *The Scattering of Electromagnetic Waves
/// from Rough Surfaces*; Walter et al. 2007, eq. 25–27:
///
/// ```text
/// D(m) = exp(−tan²θm / α²) / (π α² cos⁴θm)
/// Λ(ω) = (erf(a) − 1)/2 + exp(−a²) / (2 a √π),   a = 1/(α tan θ)
/// ```
///
/// `Λ` is the exact erf form (Heitz 2014, eq. 80), evaluated to `f32`
/// accuracy (a few ulp) by a fitted rational in `a` times one exponential —
/// not the cruder rational approximation of Walter et al. eq. 27. Domain:
/// `α ∈ [MIN_ALPHA, MAX_ALPHA] = [1e-4, 1]`.
///
/// The BRDF's hot path ([`d_cos2`](MicrofacetDistribution::d_cos2) and
/// [`projected_area`](MicrofacetDistribution::projected_area), behind
/// `eval`, `pdf` and the sample weights) runs in `f32` without `f64`: the
/// projected area `A = cos θ (1 + Λ)` through one fitted rational
/// (exponential included; ≤ 3 ulp of the exact `A`) and `D` with one `f32`
/// exponential (≤ `4 + 3x` ulp, `x = tan²θm/α²`).
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Beckmann, MicrofacetDistribution};
/// let d = Beckmann::new(0.3).unwrap();
/// assert!((d.d(Vec3::Z) - 1.0 / (core::f32::consts::PI * 0.09)).abs() < 1e-4);
/// assert_eq!(d.lambda(Vec3::Z), 0.0);
/// assert_eq!(d.g1(Vec3::new(1.0, 0.0, 0.0)), 0.0);
/// assert!(Beckmann::new(f32::NAN).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beckmann {
    alpha: f32,
    /// `(1/α², 1/(πα²))` for `D` (`beckmann_f32::d_consts`).
    d_consts: (f32, f32),
}

impl Beckmann {
    /// A Beckmann distribution with roughness `α ∈ [1e-4, 1]`; NaN,
    /// infinities and values outside the range are rejected with [`BrdfError`].
    pub fn new(alpha: f32) -> Result<Self, BrdfError> {
        let alpha = check_range("alpha", alpha, MIN_ALPHA, MAX_ALPHA)?;
        Ok(Beckmann {
            alpha,
            d_consts: super::beckmann_f32::d_consts(alpha),
        })
    }
}

/// `1/(2√π)`.
const FRAC_1_2SQRT_PI: f64 = 0.282_094_791_773_878_14;

/// Below `a = 2⁻²⁰`, `Λ = 1/(2√π a) − 1/2` to within a relative `a²`.
#[cfg(test)]
const TINY_A: f32 = 9.536_743e-7;

/// `Λ(a)` for `a = 1/(α tan θ) ≥ 0`, without iteration.
///
/// With `erf − 1 = −erfc` and `erfcx(a) = e^{a²} erfc(a)`,
/// `Λ(a) = (e^{−a²}/(a√π) − erfc(a))/2 = e^{−a²} T(a) / (2√π a)` where
/// `T(a) = 1 − √π a erfcx(a)` falls smoothly from 1 to `~1/(2a²)`: the erf
/// form's cancellation for large `a` is inside `T`, which is fitted directly
/// (rational of degree 4/6, relative error 4.2·10⁻⁹, see `special.rs`), so
/// nothing cancels at run time. `e^{−a²}` is one exponential of the exact
/// `a²` ([`exp_neg64`](super::special::exp_neg64), a division-free
/// Cody–Waite + polynomial kernel, 1.9·10⁻⁹); the rational and the products
/// are evaluated in `f64` and rounded once.
///
/// * `a ≥ 9.7656` (including `+∞`): `0` (the exact value is below half the
///   smallest subnormal);
/// * `a < 2⁻²⁰`: `1/(2√π a) − 1/2`, which overflows to `+∞` for
///   `a < 8.3·10⁻⁴⁰` (subnormal `a`) — consistent with the limit;
/// * `a ≤ 0` or NaN (grazing or degenerate): `+∞`.
///
/// Never NaN, never negative. Max error 1 ulp (measured 0.60) of the exact
/// `Λ(a)` at the given `f32` `a` for results `≥ f32::MIN_POSITIVE` (unit test
/// `lambda_of_a_matches_f64`, dense grid, against libm's `f64` `erfc`);
/// subnormal results (`a > 9.0`) to within one subnormal ulp.
///
/// The BRDF's hot path uses the `f32` projected area of
/// [`beckmann_f32`](super::beckmann_f32) instead; [`beckmann_lambda_tan2`]
/// serves `lambda`/`g1`, and this form is the tests' check of the fit.
#[cfg(test)]
pub(crate) fn lambda_of_a(a: f32) -> f32 {
    if a.is_nan() || a <= 0.0 {
        return f32::INFINITY;
    }
    if a >= LAMBDA_ZERO_A {
        return 0.0;
    }
    if a < TINY_A {
        return (FRAC_1_2SQRT_PI / a as f64 - 0.5) as f32;
    }
    let a = a as f64;
    lambda_from_exp(a, exp_neg64(a * a))
}

/// `Λ` of Beckmann straight from `tan²θ` and `α`: `a² = 1/(α² tan²θ)`,
/// `Λ = e^{−a²} T(a)/(2√π a)`, with `a²` formed in `f64` (so its rounding
/// is not amplified by `Λ ∝ e^{−a²}`), one exponential and one `f64` square
/// root for `a` (the odd powers of `a` in `Λ` make a square root
/// unavoidable).
///
/// `tan2 = 0` (normal incidence) gives 0, `tan2 = +∞` (grazing) `+∞`; NaN
/// and negative `tan2` give `+∞` (degenerate directions are treated as
/// grazing, so `G1 = 0`). Never NaN, never negative. Max error 1 ulp
/// (measured 0.58) of the exact `Λ` of the given `α`, `tan²θ` (unit test
/// `lambda_tan2_matches_f64`).
#[inline]
pub(crate) fn beckmann_lambda_tan2(alpha: f32, tan2: f32) -> f32 {
    if tan2.is_nan() || tan2 <= 0.0 {
        // 0 and −0: normal incidence; NaN, negative: degenerate.
        return if tan2 == 0.0 { 0.0 } else { f32::INFINITY };
    }
    let x = (alpha as f64) * (alpha as f64) * (tan2 as f64); // 1/a², exact to 2⁻⁵³
    // a < 2⁻²⁰ ⇔ 1/a² > 2⁴⁰ (includes tan2 = +∞).
    if x > 1_099_511_627_776.0 {
        return (FRAC_1_2SQRT_PI * libm::sqrt(x) - 0.5) as f32;
    }
    let a2 = 1.0 / x; // +∞ for tan2 = 0
    if a2 >= LAMBDA_ZERO_A as f64 * LAMBDA_ZERO_A as f64 {
        return 0.0;
    }
    lambda_from_exp(libm::sqrt(a2), exp_neg64(a2))
}

/// The vector forms of [`Beckmann::d_ratio`] and [`Beckmann::projected_area`]
/// (feature `simd`), lane for lane the scalar operations (bit-identical):
/// `expf` is the bit-exact vector port, and the `f64` parts of `Λ` run on
/// `f64` vectors.
#[cfg(feature = "simd")]
pub(super) mod lanes {
    use crate::simd::Vf;

    /// `Beckmann::d_ratio` lane-wise, bit for bit: `D` (the quotient's
    /// denominator is 1).
    #[inline(always)]
    pub(in super::super) fn d(consts: (f32, f32), hz2: Vf, hxy2: Vf) -> Vf {
        super::super::beckmann_f32::d_v(consts, hz2, hxy2)
    }

    /// `Beckmann::projected_area` lane-wise (bit for bit).
    #[inline(always)]
    pub(in super::super) fn projected_area(alpha: f32, cos_theta: Vf, sin2: Vf) -> Vf {
        super::super::beckmann_f32::area_v(alpha, cos_theta, sin2)
    }
}

impl MicrofacetDistribution for Beckmann {
    #[inline]
    fn alpha(&self) -> f32 {
        self.alpha
    }

    fn energy_tables(&self) -> Option<super::EnergyTables> {
        Some(Self::TABLES)
    }

    /// `D(m) = exp(−tan²θm/α²) / (π α² cos⁴θm)` (Walter et al. 2007, eq. 25)
    /// of `m` normalised robustly; see
    /// [`d_cos2`](MicrofacetDistribution::d_cos2).
    #[inline]
    fn d(&self, m: Vec3) -> f32 {
        match unitize(m) {
            Some(m) if m.z > 0.0 => self.d_cos2(m.z * m.z, m.x * m.x + m.y * m.y),
            _ => 0.0,
        }
    }

    /// `D = exp(−tan²θm/α²) / (π α² cos⁴θm)` in `f32` with one division
    /// and one `f32` exponential (`beckmann_f32::d`):
    /// `u = 1/cos²θm`, `x = sin²θm u/α²`, `D = e^{−x} u²/(πα²)`; `0` where
    /// `x > 87` (`e^{−x} < 1.7·10⁻³⁸`) and at `cos²θm = 0`.
    #[inline(always)]
    fn d_cos2(&self, cos2: f32, sin2: f32) -> f32 {
        super::beckmann_f32::d(self.d_consts, cos2, sin2)
    }

    /// [`d_cos2`](MicrofacetDistribution::d_cos2) in the squares of a
    /// vector of any length along `m` (`beckmann_f32::d`):
    /// `τ = tan²θm = h_xy²/h_z²`, `u = 1 + τ`, `x = τ/α²`,
    /// `D = e^{−x} u²/(πα²)`, returned as `(D, 1)`; one division.
    #[inline(always)]
    fn d_ratio(&self, hz2: f32, hxy2: f32) -> (f32, f32) {
        (super::beckmann_f32::d(self.d_consts, hz2, hxy2), 1.0)
    }

    /// The exact Smith `Λ` (Walter et al. 2007, eq. 27 in Λ form) of `ω`
    /// normalised robustly; `+∞` at grazing, `0` at normal incidence.
    #[inline]
    fn lambda(&self, w: Vec3) -> f32 {
        self.lambda_tan2(tan2_theta_robust(w))
    }

    /// `A(ω) = cos θ (1 + Λ) = cos θ + α sin θ · aΛ(a)` with
    /// `a = cos θ/(α sin θ)`, `aΛ(a)` (exponential included) one fitted
    /// `f32` rational (module `beckmann_f32`): finite at
    /// grazing (`A → α sin θ/(2√π)`), no division by `a`, ≤ 3 ulp.
    #[inline(always)]
    fn projected_area(&self, cos_theta: f32, sin2: f32) -> f32 {
        super::beckmann_f32::area(self.alpha, cos_theta, sin2)
    }

    #[cfg(feature = "simd")]
    #[inline]
    fn batch_kind(&self) -> super::DistributionKind {
        super::DistributionKind::Beckmann { alpha: self.alpha }
    }

    /// `Λ` straight from `tan²θ` (one `expf`, a fitted rational, no iteration): `0` for
    /// `tan²θ = 0`, `+∞` for `tan²θ = +∞` or NaN.
    #[inline(always)]
    fn lambda_tan2(&self, tan2: f32) -> f32 {
        beckmann_lambda_tan2(self.alpha, tan2)
    }

    /// Visible-normal sampling of Heitz & d'Eon 2014 ("Importance Sampling
    /// Microfacet-Based BSDFs using the Distribution of Visible Normals",
    /// CGF 33(4), §4): stretch `ωo` to the `α = 1` configuration
    /// `v = normalize(α x, α y, z)`, sample the visible slopes `(x̃, ỹ)` of the
    /// standard surface for incidence `θ_v` (azimuth 0) — `x̃` by inverting
    /// its marginal CDF, `ỹ = erfinv(2u₁ − 1)` (the slope density factorises,
    /// and the visibility factor depends on `x̃` only) — rotate by `φ_v`,
    /// unstretch the slopes by `α`, and return `m = normalize(−x̃, −ỹ, 1)`.
    ///
    /// `x̃` for `u₀ ∈ [2⁻²⁰, 1 − 2⁻¹⁰]` (99.9 % of uniform samples) comes
    /// from the `f32` fast path of `beckmann_slope` (a bilinear start from a
    /// table of the exact quantile and one Halley step, no `f64`, no
    /// data-dependent branch; `|C(x̃)/C(b) − u| ≤ 1.6·10⁻⁸` in exact
    /// arithmetic); the tails from the bounded start and two safeguarded
    /// Halley steps of `Beckmann::sample_slope_x`. Either way
    /// the returned `pdf` of `Microfacet::sample` is computed from the
    /// returned direction.
    #[inline]
    fn sample_visible(&self, wo: Vec3, u: [f32; 2]) -> Vec3 {
        let a = self.alpha;
        let wo = unitize(wo).unwrap_or(Vec3::Z);
        let (u0, u1) = (clamp01(u[0]), clamp01(u[1]));
        // The azimuth of the stretched direction is that of ωo.
        let rxy = radiometry::math::sqrtf(wo.x * wo.x + wo.y * wo.y);
        let (cos_p, sin_p) = if rxy > 0.0 {
            let inv = 1.0 / rxy;
            (wo.x * inv, wo.y * inv)
        } else {
            (1.0, 0.0)
        };
        let sx = Self::slope_x(a, wo, rxy, u0);
        let sy = erfinv_2p_minus_1(u1);
        let tx = cos_p * sx - sin_p * sy;
        let ty = sin_p * sx + cos_p * sy;
        unitize(Vec3::new(-a * tx, -a * ty, 1.0)).unwrap_or(Vec3::Z)
    }
}

impl Beckmann {
    /// The visible slope `x̃` of `sample_visible` for unit `wo` (`rxy =
    /// |wo_xy|`, `u ∈ [0, 1]`): the fast path of `beckmann_slope` on
    /// `(|ω_z|, α|ω_xy|)` inside its range, else [`slope_x_tail`](Self::slope_x_tail).
    #[inline(always)]
    fn slope_x(a: f32, wo: Vec3, rxy: f32, u: f32) -> f32 {
        if beckmann_slope::in_fast_range(u) {
            beckmann_slope::slope_x(wo.z.abs(), a * rxy, u)
        } else {
            Self::slope_x_tail(a, wo, u)
        }
    }

    /// The slope `x̃` for `u` outside the fast range of `beckmann_slope`
    /// (`u < 2⁻²⁰` or `u > 1 − 2⁻¹⁰`, 0.1 % of uniform samples): the
    /// bounded start and two safeguarded Halley steps of
    /// [`sample_slope_x`](Self::sample_slope_x) on the normalised stretched
    /// direction `v = normalize(α ω_x, α ω_y, |ω_z|)`.
    #[cold]
    #[inline(never)]
    fn slope_x_tail(a: f32, wo: Vec3, u: f32) -> f32 {
        let v = unitize(Vec3::new(a * wo.x, a * wo.y, wo.z.abs())).unwrap_or(Vec3::Z);
        let sin_t = radiometry::math::sqrtf(v.x * v.x + v.y * v.y).min(1.0);
        Self::sample_slope_x(v.z, sin_t, u)
    }
}

#[cfg(test)]
mod tests {
    use super::super::special::MAX_SLOPE;
    use super::*;

    /// The slope sampler as `sample_visible` runs it (fast path inside
    /// `[U_LO, U_HI]`, tail scheme outside), over the whole `u` range and
    /// across both switch points: finite, in `[−MAX_SLOPE, b]`, monotone in
    /// `u` (to within `2·10⁻⁶(1 + |x|)`, as the tail scheme's test, plus the
    /// `x` width of 4 resolution units of `u` where the density vanishes), and
    /// `|C(x)/C(b) − u|` within 4 resolution units (see
    /// `slope_inversion_reproduces_u`); edge `u` (0, subnormal, the switch
    /// points and their neighbours, `1 − ε`, 1) finite and in range.
    #[test]
    fn dispatched_slope_sampler_is_monotone_and_accurate() {
        use super::beckmann_slope::{U_HI, U_LO};
        let mut us: std::vec::Vec<f32> = (0..=20_000).map(|i| i as f32 / 20_000.0).collect();
        for v in [U_LO, U_HI] {
            let mut w = v;
            for _ in 0..64 {
                w = w.next_down();
            }
            for _ in 0..128 {
                us.push(w);
                w = w.next_up();
            }
        }
        let mut t = 1e-45f32;
        while t < 0.01 {
            us.push(t);
            us.push(1.0 - t);
            t *= 3.0;
        }
        // Every 8th f32 in [0.98, 1): where the upper tail is steep in `x`
        // (near grazing, dx/du ~ 1/(2|x|)).
        let mut w = 0.98f32;
        while w < 1.0 {
            us.push(w);
            for _ in 0..8 {
                w = w.next_up();
            }
        }
        us.extend([radiometry::math::ONE_MINUS_EPSILON, 1.0, 0.0]);
        us.retain(|u| (0.0..=1.0).contains(u));
        us.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let mut worst = 0.0f64;
        for &alpha in &[1e-4f32, 0.3, 1.0] {
            let near_grazing = [1.55, 1.565, 1.57, core::f64::consts::FRAC_PI_2 - 1e-4];
            let thetas = (0..=24).map(|k| k as f64 / 24.0 * core::f64::consts::FRAC_PI_2);
            for theta in thetas.chain(near_grazing) {
                let wo = Vec3::new(libm::sin(theta) as f32, 0.0, libm::cos(theta) as f32);
                let rxy = radiometry::math::sqrtf(wo.x * wo.x + wo.y * wo.y);
                // The stretched direction, normalised, in f64 for the reference.
                let (sx64, cz64) = (alpha as f64 * wo.x as f64, wo.z as f64);
                let n = (sx64 * sx64 + cz64 * cz64).sqrt();
                let (c64, s64) = (cz64 / n, sx64 / n);
                let b = if s64 * 9.0 <= c64 { 9.0 } else { c64 / s64 };
                let total = cdf64(c64, s64, b);
                let (mut prev, mut prev_tol) = (-MAX_SLOPE, 0.0f64);
                for &u in &us {
                    let x = Beckmann::slope_x(alpha, wo, rxy, u);
                    assert!(
                        x.is_finite() && x >= -MAX_SLOPE && x as f64 <= b + 1e-6,
                        "α={alpha} θ={theta} u={u}: {x}"
                    );
                    let got = cdf64(c64, s64, x as f64) / total;
                    let dens = (c64 - x as f64 * s64).max(0.0) * libm::exp(-(x as f64).powi(2))
                        / core::f64::consts::PI.sqrt()
                        / total;
                    let eps = f32::EPSILON as f64;
                    let unit = dens * (x.abs().max(1e-3) as f64) * eps * 4.0 + 4.0 * eps;
                    // Monotone up to the accuracy asserted below: a step back
                    // of at most 2·10⁻⁶(1 + |x|) plus 4 resolution units of
                    // `u` at either end, converted to `x` by the density.
                    let tol = 2e-6 * (1.0 + x.abs() as f64) + 4.0 * unit / dens.max(1e-30);
                    assert!(
                        x as f64 >= prev as f64 - tol.max(prev_tol),
                        "α={alpha} θ={theta} u={u}: {x} < {prev}"
                    );
                    (prev, prev_tol) = (x, tol);
                    // Below −MAX_SLOPE's mass the clamp decides, by design.
                    if x > -MAX_SLOPE {
                        let err = (got - u as f64).abs() / unit;
                        worst = worst.max(err);
                        assert!(err < 4.0, "α={alpha} θ={theta} u={u}: x={x} ({err} units)");
                    }
                }
            }
        }
        std::println!("dispatched Beckmann slope sampler: worst {worst:.2} resolution units");
    }

    fn lambda64(a: f64) -> f64 {
        // The erf form in f64 with libm's f64 erfc; its cancellation costs
        // ≤ 2a² f64 ulps (≤ 2·10⁻¹⁴ relative for a ≤ 9.8), far below f32 ulps.
        0.5 * (libm::exp(-a * a) / (a * core::f64::consts::PI.sqrt()) - libm::erfc(a))
    }

    /// `f32` ulps between `v` and the reference `r` (ulp at `r`; subnormal
    /// ulps below the normal range).
    fn ulps(v: f32, r: f64) -> f64 {
        let ar = r.abs().max(f32::MIN_POSITIVE as f64);
        let ulp = libm::exp2(libm::floor(libm::log2(ar)) - 23.0);
        (v as f64 - r).abs() / ulp
    }

    extern crate std;

    /// Test points for functions of `a`: `n` evenly spaced over `(0, 9.8]`,
    /// then a geometric sweep (ratio 1.37) from the smallest subnormal to 10.
    fn a_grid(n: usize) -> std::vec::Vec<f32> {
        let mut pts: std::vec::Vec<f32> = (1..=n).map(|i| i as f32 * (9.8 / n as f32)).collect();
        let mut t = 1e-45f32;
        while t < 10.0 {
            pts.push(t);
            t = (t * 1.37).max(t.next_up());
        }
        pts
    }

    /// `lambda_of_a` against the f64 erf form at the same (f32) `a`: a dense
    /// grid over `(0, 9.77]`, a geometric sweep down to subnormal `a`, and
    /// the edge values.
    #[test]
    fn lambda_of_a_matches_f64() {
        extern crate std;
        let mut pts = a_grid(400_000);
        pts.extend([
            TINY_A,
            TINY_A.next_down(),
            TINY_A.next_up(),
            LAMBDA_ZERO_A.next_down(),
            2.0,
            9.0,
        ]);
        let mut worst = 0.0f64;
        let mut worst_sub = 0.0f64;
        for a in pts {
            let v = lambda_of_a(a);
            assert!(v >= 0.0 && !v.is_nan(), "Λ({a}) = {v}");
            let r = lambda64(a as f64);
            if r > f32::MAX as f64 {
                assert_eq!(v, f32::INFINITY, "Λ({a})");
                continue;
            }
            let e = ulps(v, r);
            if r >= f32::MIN_POSITIVE as f64 {
                worst = worst.max(e);
                assert!(e <= 1.0, "Λ({a}) = {v} vs {r}: {e} ulp");
            } else {
                worst_sub = worst_sub.max(e);
                assert!(e <= 1.0, "Λ({a}) = {v} vs {r}: {e} subnormal ulp");
            }
        }
        // Edges: a ≤ 0 / NaN → +∞, +∞ → 0, tiny → huge or +∞, monotone.
        assert_eq!(lambda_of_a(0.0), f32::INFINITY);
        assert_eq!(lambda_of_a(-0.0), f32::INFINITY);
        assert_eq!(lambda_of_a(-1.0), f32::INFINITY);
        assert_eq!(lambda_of_a(f32::NAN), f32::INFINITY);
        assert_eq!(lambda_of_a(f32::INFINITY), 0.0);
        assert_eq!(lambda_of_a(f32::MAX), 0.0);
        assert_eq!(lambda_of_a(LAMBDA_ZERO_A), 0.0);
        assert_eq!(lambda_of_a(1e-45), f32::INFINITY);
        assert_eq!(lambda_of_a(1e-40), f32::INFINITY);
        assert!(lambda_of_a(1e-38).is_finite() && lambda_of_a(1e-38) > 1e37);
        let mut prev = f32::INFINITY;
        let mut a = 1e-45f32;
        while a < 12.0 {
            let v = lambda_of_a(a);
            assert!(v <= prev, "Λ not monotone at a = {a}");
            prev = v;
            a = (a * 1.01).max(a.next_up());
        }
        std::println!("lambda_of_a: worst {worst:.2} ulp (normal results), {worst_sub:.2} subnormal ulp");
    }

    /// `beckmann_lambda_tan2` against the f64 erf form at the `a` implied by
    /// its (exact `f32`) arguments, in ulps.
    #[test]
    fn lambda_tan2_matches_f64() {
        extern crate std;
        let mut worst = 0.0f64;
        for &alpha in &[1e-4f32, 0.01, 0.3, 1.0] {
            let mut t2 = 1e-30f32;
            while t2 < 1e30 {
                let v = beckmann_lambda_tan2(alpha, t2);
                assert!(v >= 0.0 && !v.is_nan());
                let a = 1.0 / ((alpha as f64) * (t2 as f64).sqrt());
                let r = lambda64(a);
                if r >= f32::MIN_POSITIVE as f64 && r <= f32::MAX as f64 {
                    let e = ulps(v, r);
                    worst = worst.max(e);
                    assert!(e <= 1.0, "α={alpha} tan²={t2}: {v} vs {r} ({e} ulp)");
                    // Agrees with lambda_of_a at the f32 a.
                    let va = lambda_of_a(a as f32);
                    assert!(ulps(va, r) <= 4.0 * (1.0 + 2.0 * a * a));
                }
                t2 *= 1.013;
            }
            assert_eq!(beckmann_lambda_tan2(alpha, 0.0), 0.0);
            assert_eq!(beckmann_lambda_tan2(alpha, -0.0), 0.0);
            assert_eq!(beckmann_lambda_tan2(alpha, 1e-45), 0.0);
            assert_eq!(beckmann_lambda_tan2(alpha, f32::INFINITY), f32::INFINITY);
            let big = beckmann_lambda_tan2(alpha, f32::MAX);
            assert!(big.is_finite() && big > 1e14, "{big}");
            assert_eq!(beckmann_lambda_tan2(alpha, f32::NAN), f32::INFINITY);
            assert_eq!(beckmann_lambda_tan2(alpha, -1.0), f32::INFINITY);
        }
        std::println!("beckmann_lambda_tan2: worst {worst:.2} ulp");
    }

    /// `2C(x)/2` in `f64`: the slope CDF from its closed form (libm's `erfc`).
    fn cdf64(c: f64, s: f64, x: f64) -> f64 {
        0.5 * c * libm::erfc(-x) + 0.5 * s * libm::exp(-x * x) / core::f64::consts::PI.sqrt()
    }

    /// Regression test of the tail scheme at the largest `u` below 1 near
    /// grazing, where the slope density vanishes at the end point
    /// `b = cot θ`: the complement `G(x) = 2C(b) − 2C(x)` is formed with
    /// cancellation in `f32`, and before `TAIL_RESOLUTION` the safeguarded
    /// Halley steps fell back to bisection there: `|C(x̃)/C(b) − u|` reached
    /// 9·10⁻⁵ (α = 0.3, θ = 1.565, u = 1 − 2⁻²³), 2.9·10⁻⁵ (α = 1,
    /// θ = 1.55), 1.7·10⁻⁵ (α = 0.05, θ = 1.57). Now within 4 resolution
    /// units (`4 · 4ε`) for every `u ≥ 1 − 2⁻¹²`.
    #[test]
    fn tail_scheme_top_of_range_near_grazing() {
        for (alpha, theta) in [(0.3f32, 1.565f64), (1.0, 1.55), (0.05, 1.57)] {
            let wo = Vec3::new(libm::sin(theta) as f32, 0.0, libm::cos(theta) as f32);
            let v = unitize(Vec3::new(alpha * wo.x, 0.0, wo.z)).unwrap();
            let (c, s) = (v.z as f64, v.x as f64);
            let total = cdf64(c, s, c / s);
            let mut u = 1.0 - 2f32.powi(-12);
            while u < 1.0 {
                let x = Beckmann::slope_x_tail(alpha, wo, u);
                let err = (cdf64(c, s, x as f64) / total - u as f64).abs();
                assert!(
                    err < 4.0 * 4.0 * f32::EPSILON as f64,
                    "α={alpha} θ={theta} u={u}: |F − u| = {err:.2e}"
                );
                u = u.next_up();
            }
        }
    }
}
