//! The Beckmann normal distribution.

use super::special::{FRAC_1_SQRT_PI, MAX_SLOPE, erfinv_2p_minus_1, erfinv_2p_minus_1_guess};
use super::{
    MAX_ALPHA, MIN_ALPHA, MicrofacetDistribution, clamp01, finite_nonneg, tan2_theta_robust, unitize,
};
use crate::error::{BrdfError, check_range};
use core::f32::consts::PI;
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
/// `Λ` is the exact erf form (Heitz 2014, eq. 80), not a rational
/// approximation. Domain: `α ∈ [MIN_ALPHA, MAX_ALPHA] = [1e-4, 1]`.
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
}

impl Beckmann {
    /// A Beckmann distribution with roughness `α ∈ [1e-4, 1]`; NaN,
    /// infinities and values outside the range are rejected with [`BrdfError`].
    pub fn new(alpha: f32) -> Result<Self, BrdfError> {
        Ok(Beckmann {
            alpha: check_range("alpha", alpha, MIN_ALPHA, MAX_ALPHA)?,
        })
    }
}

/// `Λ(a)` for `a = 1/(α tan θ) ≥ 0`.
///
/// * `a < 2`: `Λ = (e^{−a²}/(a√π) − erfc(a)) / 2` (the erf form with
///   `erf − 1 = −erfc`; the cancellation costs at most a factor `2a² ≤ 8` in
///   relative error).
/// * `a ≥ 2`: with the continued fraction
///   `erfc(a) = e^{−a²}/√π · K`, `K = 1/(a + (1/2)/(a + 1/(a + (3/2)/(a + …))))`
///   (Abramowitz & Stegun 7.1.14), the difference becomes
///   `Λ = e^{−a²}/(2√π) · k/(a (a + k))` with `k = (1/2)/(a + 1/(a + …))`,
///   free of cancellation. 16 levels evaluated backward give a truncation
///   error below 1.4·10⁻⁷ relative for `a ≥ 2`.
/// * `a = 0` (grazing) gives `+∞`; `a = +∞` (normal incidence) gives 0.
fn lambda_of_a(a: f32) -> f32 {
    if a.is_nan() || a <= 0.0 {
        return f32::INFINITY;
    }
    if a == f32::INFINITY {
        return 0.0;
    }
    if a >= 2.0 {
        let mut k = 0.0f32;
        let mut n = 16.0f32;
        while n >= 1.0 {
            k = (0.5 * n) / (a + k);
            n -= 1.0;
        }
        return libm::expf(-a * a) * (0.5 * FRAC_1_SQRT_PI) * k / (a * (a + k));
    }
    let l = 0.5 * (libm::expf(-a * a) * FRAC_1_SQRT_PI / a - libm::erfcf(a));
    if l.is_nan() { f32::INFINITY } else { l.max(0.0) }
}

impl Beckmann {
    /// The CDF (unnormalised) of the visible slope `x̃` of the standard
    /// (`α = 1`) Beckmann surface seen at angle θ (Heitz & d'Eon 2014,
    /// §4.2): `C(x) = ∫_{−∞}^x (cos θ − t sin θ) e^{−t²}/√π dt
    ///            = cos θ erfc(−x)/2 + sin θ e^{−x²}/(2√π)`.
    #[inline]
    fn slope_cdf(cos_t: f32, sin_t: f32, x: f32) -> f32 {
        0.5 * cos_t * libm::erfcf(-x) + 0.5 * sin_t * FRAC_1_SQRT_PI * libm::expf(-x * x)
    }

    /// Samples the slope `x̃ ∈ [−MAX_SLOPE, b]` with density ∝
    /// `(cos θ − x̃ sin θ) e^{−x̃²}` (Heitz & d'Eon 2014, §4.2 and eq. 11–12 for
    /// Beckmann), `b = min(cot θ, MAX_SLOPE)`, by solving
    /// `C(x̃) = u C(b)` with Newton's method safeguarded by bisection, started
    /// from the normal-incidence quantile `erfinv(2u − 1)` (exact for θ = 0).
    /// It stops when the residual reaches the `f32` rounding level of `C`
    /// (`4ε C(b)`), the step falls below `2⁻²¹(1 + |x̃|)`, or after 24 steps.
    fn sample_slope_x(cos_t: f32, sin_t: f32, u: f32) -> f32 {
        let b = if sin_t * MAX_SLOPE <= cos_t {
            MAX_SLOPE
        } else {
            cos_t / sin_t
        };
        if u <= 0.0 {
            return -MAX_SLOPE;
        }
        let total = Self::slope_cdf(cos_t, sin_t, b);
        let target = u * total;
        let noise = 4.0 * f32::EPSILON * total;
        let (mut lo, mut hi) = (-MAX_SLOPE, b);
        let mut x = erfinv_2p_minus_1_guess(u).max(lo).min(hi);
        for _ in 0..24 {
            let e = libm::expf(-x * x) * FRAC_1_SQRT_PI;
            let c = 0.5 * cos_t * libm::erfcf(-x) + 0.5 * sin_t * e - target;
            if c.abs() <= noise {
                break;
            }
            if c > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            let dc = (cos_t - x * sin_t) * e;
            let mut next = x - c / dc;
            if next.is_nan() || next <= lo || next >= hi {
                next = 0.5 * (lo + hi);
            }
            let done = (next - x).abs() <= 4.8e-7 * (1.0 + x.abs());
            x = next;
            if done {
                break;
            }
        }
        x.max(-MAX_SLOPE).min(b)
    }
}

impl MicrofacetDistribution for Beckmann {
    #[inline]
    fn alpha(&self) -> f32 {
        self.alpha
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

    /// `D = exp(−tan²θm/α²) / (π α² cos⁴θm)` with `tan²θm = sin²/cos²`.
    /// For `cos²θm < 10⁻⁸` it is evaluated as
    /// `exp(−tan²θm/α² − 2 ln cos²θm)/(π α²)` so that the vanishing
    /// exponential and the exploding `1/cos⁴` never meet as `0·∞`.
    #[inline(always)]
    fn d_cos2(&self, cos2: f32, sin2: f32) -> f32 {
        let a2 = self.alpha * self.alpha;
        let e = sin2 / (cos2 * a2);
        let v = if cos2 >= 1e-8 {
            libm::expf(-e) / (cos2 * cos2)
        } else {
            libm::expf(-e - 2.0 * libm::logf(cos2))
        };
        finite_nonneg(v / (PI * a2))
    }

    /// The exact Smith `Λ` (Walter et al. 2007, eq. 27 in Λ form) of `ω`
    /// normalised robustly; `+∞` at grazing, `0` at normal incidence.
    #[inline]
    fn lambda(&self, w: Vec3) -> f32 {
        self.lambda_tan2(tan2_theta_robust(w))
    }

    /// `A(ω) = cos θ (1 + Λ) = cos θ + α sin θ · aΛ(a)` with
    /// `a = cos θ/(α sin θ)`: `cos θ · Λ` written through `a Λ(a)`, which is
    /// finite at grazing (`a → 0`: `aΛ → 1/(2√π)`, so `A → α sin θ/(2√π)`).
    #[inline(always)]
    fn projected_area(&self, cos_theta: f32, sin2: f32) -> f32 {
        let s = libm::sqrtf(sin2);
        let alpha_s = self.alpha * s;
        if alpha_s <= 0.0 {
            // Normal incidence: Λ = 0.
            return cos_theta;
        }
        let a = cos_theta / alpha_s;
        if a == f32::INFINITY {
            return cos_theta;
        }
        // For a < 1e-20, aΛ(a) = 1/(2√π) − a/2 + O(a²) is 1/(2√π) in f32.
        let a_lambda = if a < 1e-20 {
            0.5 * FRAC_1_SQRT_PI
        } else {
            a * lambda_of_a(a)
        };
        cos_theta + alpha_s * a_lambda
    }

    #[cfg(feature = "simd")]
    #[inline]
    fn batch_kind(&self) -> super::DistributionKind {
        super::DistributionKind::Beckmann { alpha: self.alpha }
    }

    /// `Λ(a)` with `a = 1/(α tan θ)` (the erf form above): `0` for
    /// `tan²θ = 0`, `+∞` for `tan²θ = +∞` or NaN.
    #[inline(always)]
    fn lambda_tan2(&self, tan2: f32) -> f32 {
        if tan2.is_nan() || tan2 == f32::INFINITY {
            return f32::INFINITY;
        }
        lambda_of_a(1.0 / (self.alpha * libm::sqrtf(tan2)))
    }

    /// Visible-normal sampling of Heitz & d'Eon 2014 ("Importance Sampling
    /// Microfacet-Based BSDFs using the Distribution of Visible Normals",
    /// CGF 33(4), §4): stretch `ωo` to the `α = 1` configuration
    /// `v = normalize(α x, α y, z)`, sample the visible slopes `(x̃, ỹ)` of the
    /// standard surface for incidence `θ_v` (azimuth 0) — `x̃` by inverting
    /// its marginal CDF, `ỹ = erfinv(2u₁ − 1)` (the slope density factorises,
    /// and the visibility factor depends on `x̃` only) — rotate by `φ_v`,
    /// unstretch the slopes by `α`, and return `m = normalize(−x̃, −ỹ, 1)`.
    fn sample_visible(&self, wo: Vec3, u: [f32; 2]) -> Vec3 {
        let a = self.alpha;
        let wo = unitize(wo).unwrap_or(Vec3::Z);
        let v = unitize(Vec3::new(a * wo.x, a * wo.y, wo.z.abs())).unwrap_or(Vec3::Z);
        let sin_t = libm::sqrtf(v.x * v.x + v.y * v.y).min(1.0);
        let cos_t = v.z;
        let (cos_p, sin_p) = if sin_t > 0.0 {
            (v.x / sin_t, v.y / sin_t)
        } else {
            (1.0, 0.0)
        };
        let sx = Self::sample_slope_x(cos_t, sin_t, clamp01(u[0]));
        let sy = erfinv_2p_minus_1(clamp01(u[1]));
        let tx = cos_p * sx - sin_p * sy;
        let ty = sin_p * sx + cos_p * sy;
        unitize(Vec3::new(-a * tx, -a * ty, 1.0)).unwrap_or(Vec3::Z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f64 reference of the slope CDF written from its integral definition
    /// `C(x) = ∫_{−∞}^x (cos θ − t sin θ) e^{−t²}/√π dt` (closed form in f64).
    fn cdf64(c: f64, s: f64, x: f64) -> f64 {
        0.5 * c * libm::erfc(-x) + 0.5 * s * libm::exp(-x * x) / core::f64::consts::PI.sqrt()
    }

    /// The inverted CDF reproduces `u`: `|C(x(u))/C(b) − u|` is measured in
    /// units of the resolution the `f32` slope allows (`C'(x)·ulp(x)`, plus
    /// the `f32` rounding of `C` itself).
    #[test]
    fn slope_inversion_reproduces_u() {
        let mut worst = 0.0f64;
        for k in 0..=12 {
            let theta = (k as f64 / 12.0) * core::f64::consts::FRAC_PI_2;
            let (s, c) = (libm::sin(theta) as f32, libm::cos(theta) as f32);
            let (s64, c64) = (s as f64, c as f64);
            let b = if s * MAX_SLOPE <= c {
                MAX_SLOPE as f64
            } else {
                (c / s) as f64
            };
            let total = cdf64(c64, s64, b);
            for i in 0..=2000 {
                let u = match i {
                    0 => 0.0f32,
                    2000 => radiometry::math::ONE_MINUS_EPSILON,
                    _ => i as f32 / 2000.0,
                };
                let x = Beckmann::sample_slope_x(c, s, u);
                assert!(x.is_finite() && x >= -MAX_SLOPE && x as f64 <= b + 1e-6);
                let got = cdf64(c64, s64, x as f64) / total;
                let dens = (c64 - x as f64 * s64).max(0.0) * libm::exp(-(x as f64).powi(2))
                    / core::f64::consts::PI.sqrt()
                    / total;
                let unit =
                    dens * (x.abs().max(1e-3) as f64) * f32::EPSILON as f64 * 4.0 + 4.0 * f32::EPSILON as f64;
                let err = (got - u as f64).abs() / unit;
                worst = worst.max(err);
                assert!(err < 4.0, "θ={theta} u={u}: x={x}, C/C(b)={got} ({err} units)");
            }
        }
        extern crate std;
        std::println!("Beckmann slope inversion: worst |C(x)/C(b) − u| = {worst:.1} resolution units");
    }
}
