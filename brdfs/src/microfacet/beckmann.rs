//! The Beckmann normal distribution.

use super::special::{FRAC_1_SQRT_PI, MAX_SLOPE, erfinv_2p_minus_1};
use super::{MAX_ALPHA, MIN_ALPHA, MicrofacetDistribution, clamp01, finite_nonneg, unitize};
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
/// * `a < 5`: `Λ = (e^{−a²}/(a√π) − erfc(a)) / 2` (the erf form with
///   `erf − 1 = −erfc`; cancellation costs at most ≈ 2a² ulp ≈ 3·10⁻⁶ relative).
/// * `a ≥ 5`: the asymptotic expansion of `erfc` (Abramowitz & Stegun 7.1.23)
///   turns the difference into
///   `Λ = e^{−a²}/(2a√π) · Σ_{n≥1} (−1)^{n+1} (2n−1)!! / (2a²)ⁿ`, summed to
///   `n = 6` (truncation error < 10⁻⁵ relative at `a = 5`).
/// * `a = 0` (grazing) gives `+∞`.
fn lambda_of_a(a: f32) -> f32 {
    if a.is_nan() || a <= 0.0 {
        return f32::INFINITY;
    }
    if a >= 5.0 {
        let t = 1.0 / (2.0 * a * a);
        // Σ (−1)^{n+1} (2n−1)!! tⁿ, Horner form.
        let s = t * (1.0 - 3.0 * t * (1.0 - 5.0 * t * (1.0 - 7.0 * t * (1.0 - 9.0 * t * (1.0 - 11.0 * t)))));
        return libm::expf(-a * a) * FRAC_1_SQRT_PI / (2.0 * a) * s;
    }
    let l = 0.5 * (libm::expf(-a * a) * FRAC_1_SQRT_PI / a - libm::erfcf(a));
    if l.is_nan() { f32::INFINITY } else { l.max(0.0) }
}

impl Beckmann {
    /// `a = cos θ / (α sin θ)` of `w`; `+∞` at the pole, `0` at grazing and
    /// for degenerate `w`.
    #[inline]
    fn a_of(&self, w: Vec3) -> f32 {
        let Some(w) = unitize(w) else {
            return 0.0;
        };
        let s = libm::hypotf(w.x, w.y);
        if s == 0.0 {
            return f32::INFINITY;
        }
        w.z.abs() / (self.alpha * s)
    }

    /// The CDF (unnormalised) of the visible slope `x̃` of the standard
    /// (`α = 1`) Beckmann surface seen at angle θ (Heitz & d'Eon 2014,
    /// §4.2): `C(x) = ∫_{−∞}^x (cos θ − t sin θ) e^{−t²}/√π dt
    ///            = cos θ erfc(−x)/2 + sin θ e^{−x²}/(2√π)`.
    #[inline]
    fn slope_cdf(cos_t: f32, sin_t: f32, x: f32) -> f32 {
        0.5 * cos_t * libm::erfcf(-x) + 0.5 * sin_t * FRAC_1_SQRT_PI * libm::expf(-x * x)
    }

    /// Samples the slope `x̃ ∈ [−MAX_SLOPE, b]` with density ∝
    /// `(cos θ − x̃ sin θ) e^{−x̃²}` (Heitz & d'Eon 2014, eq. 11–12 for
    /// Beckmann), `b = min(cot θ, MAX_SLOPE)`, by inverting `C` with Newton's
    /// method safeguarded by bisection (at most 40 steps; stops at an
    /// interval or step below 2⁻²¹ relative).
    fn sample_slope_x(cos_t: f32, sin_t: f32, u: f32) -> f32 {
        let b = if sin_t * MAX_SLOPE <= cos_t {
            MAX_SLOPE
        } else {
            cos_t / sin_t
        };
        let (mut lo, mut hi) = (-MAX_SLOPE, b);
        let target = u * Self::slope_cdf(cos_t, sin_t, b);
        if target <= Self::slope_cdf(cos_t, sin_t, lo) {
            return lo;
        }
        // Start from the normal-incidence quantile, which is exact for θ = 0.
        let mut x = erfinv_2p_minus_1(u).clamp(lo, hi);
        for _ in 0..40 {
            let c = Self::slope_cdf(cos_t, sin_t, x) - target;
            if c > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            let dc = (cos_t - x * sin_t) * FRAC_1_SQRT_PI * libm::expf(-x * x);
            let mut next = x - c / dc;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            let tol = 5e-7 * (1.0 + x.abs());
            if (next - x).abs() <= tol || hi - lo <= tol {
                x = next;
                break;
            }
            x = next;
        }
        x.clamp(-MAX_SLOPE, b)
    }
}

impl MicrofacetDistribution for Beckmann {
    #[inline]
    fn alpha(&self) -> f32 {
        self.alpha
    }

    /// `D(m) = exp(−tan²θm/α²) / (π α² cos⁴θm)` (Walter et al. 2007, eq. 25).
    /// For `cos²θm < 10⁻⁸` it is evaluated as
    /// `exp(−tan²θm/α² − 2 ln cos²θm)/(π α²)` so that the vanishing
    /// exponential and the exploding `1/cos⁴` never meet as `0·∞`.
    #[inline]
    fn d(&self, m: Vec3) -> f32 {
        let Some(m) = unitize(m) else {
            return 0.0;
        };
        if m.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let c2 = m.z * m.z;
        let e = (m.x * m.x + m.y * m.y) / (c2 * a2);
        let v = if c2 >= 1e-8 {
            libm::expf(-e) / (c2 * c2)
        } else {
            libm::expf(-e - 2.0 * libm::logf(c2))
        };
        finite_nonneg(v / (PI * a2))
    }

    /// The exact Smith `Λ` (Walter et al. 2007, eq. 27 in Λ form); `+∞` at
    /// grazing, `0` at normal incidence.
    #[inline]
    fn lambda(&self, w: Vec3) -> f32 {
        lambda_of_a(self.a_of(w))
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
        let sin_t = libm::hypotf(v.x, v.y).min(1.0);
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
