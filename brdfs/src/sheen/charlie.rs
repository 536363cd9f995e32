//! The "Charlie" sheen distribution and its fitted Smith `Λ`
//! (Estevez & Kulla 2017).

use crate::error::{BrdfError, check_range};
use core::f32::consts::PI;

/// Smallest accepted sheen roughness `r`. Below it the distribution's
/// exponent `1/r` exceeds 10³ and the lobe hugs the horizon ever more
/// narrowly; the albedo table ([`SheenAlbedoTable`](super::SheenAlbedoTable))
/// starts here.
pub const MIN_SHEEN_ROUGHNESS: f32 = 0.07;

/// Largest accepted sheen roughness `r` (the paper's domain is `(0, 1]`).
pub const MAX_SHEEN_ROUGHNESS: f32 = 1.0;

/// The paper's fit of `L(x) = a/(1 + b x^c) + d x + e` at `r = 0`
/// (Estevez & Kulla 2017, Table 1, first row): `[a, b, c, d, e]`.
const FIT_R0: [f32; 5] = [25.3245, 3.32435, 0.16801, -1.27393, -4.85967];

/// The same fit at `r = 1` (Table 1, second row).
const FIT_R1: [f32; 5] = [21.5473, 3.82987, 0.19823, -1.97760, -4.32054];

/// The microfacet normal distribution of Estevez & Kulla 2017, "Production
/// Friendly Microfacet Sheen BRDF" (Sony Pictures Imageworks, SIGGRAPH
/// 2017 talk), eq. 2, nicknamed "Charlie":
///
/// ```text
/// D(m) = (2 + 1/r) sin(θm)^(1/r) / (2π),     r ∈ (0, 1]
/// ```
///
/// normalised so that `∫_H D(m) cos θm dm = 1` (with `s = sin θm`:
/// `2π ∫₀¹ s^(1/r) s ds · (2 + 1/r)/(2π) = 1`). Unlike GGX or Beckmann it
/// peaks at *grazing* normals (`θm = 90°`): the fibres of a cloth standing
/// up from the surface. `r = 1` gives `D = 3 sin θm / (2π)`; `r → 0`
/// concentrates `D` on the horizon.
///
/// Its Smith masking `Λ` has no closed form; the paper fits
/// `L(x) = a/(1 + b x^c) + d x + e` and sets
///
/// ```text
/// Λ(μ) = exp(L(μ))                     for μ = cos θ < 1/2,
/// Λ(μ) = exp(2 L(1/2) − L(1 − μ))      for μ ≥ 1/2,
/// ```
///
/// with each of `a, b, c, d, e` interpolated between the fits at `r = 0`
/// and `r = 1` (Table 1) as `p = (1 − r)² p₀ + (1 − (1 − r)²) p₁` (the
/// same interpolation appears in the Khronos `KHR_materials_sheen`
/// reference and Dassault Systèmes' Enterprise PBR specification).
/// The two branches join with a continuous first derivative at `μ = 1/2`.
///
/// Domain: `r ∈ [`[`MIN_SHEEN_ROUGHNESS`]`, 1]`; directions as cosines or
/// sines squared in `[0, 1]` (values outside are clamped, NaN → 0).
///
/// ```
/// use radiometry_brdfs::sheen::Charlie;
/// let c = Charlie::new(1.0)?;
/// // r = 1: D(θm = 90°) = 3/(2π).
/// assert!((c.d_sin2(1.0) - 3.0 / (2.0 * core::f32::consts::PI)).abs() < 1e-6);
/// assert_eq!(c.d_sin2(0.0), 0.0); // normal along +Z: no fibre faces up
/// // Λ is large at grazing, small at normal incidence.
/// assert!(c.lambda(0.01) > 10.0 && c.lambda(1.0) < 0.1);
/// assert!(Charlie::new(0.0).is_err());
/// # Ok::<(), radiometry_brdfs::BrdfError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Charlie {
    r: f32,
    /// `1/(2r)`: the exponent of `sin²θm`.
    half_inv_r: f32,
    /// `(2 + 1/r)/(2π)`.
    norm: f32,
    /// `[a, b, c, d, e]` at this `r`.
    fit: [f32; 5],
    /// `2 L(1/2)`.
    two_l_half: f32,
    /// `μ*`, the grazing continuation point (see [`Charlie::lambda`]).
    mu_star: f32,
    /// `μ* Λ_fit(μ*)`.
    mu_lambda_star: f32,
}

impl Charlie {
    /// The distribution with roughness `r`.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] for NaN/∞, [`BrdfError::OutOfRange`] for
    /// `r` outside `[`[`MIN_SHEEN_ROUGHNESS`]`, 1]` (named `roughness`).
    pub fn new(r: f32) -> Result<Self, BrdfError> {
        let r = check_range("roughness", r, MIN_SHEEN_ROUGHNESS, MAX_SHEEN_ROUGHNESS)?;
        let t = (1.0 - r) * (1.0 - r);
        let fit: [f32; 5] = core::array::from_fn(|k| t * FIT_R0[k] + (1.0 - t) * FIT_R1[k]);
        let mut c = Charlie {
            r,
            half_inv_r: 0.5 / r,
            norm: (2.0 + 1.0 / r) / (2.0 * PI),
            fit,
            two_l_half: 0.0,
            mu_star: 0.0,
            mu_lambda_star: 0.0,
        };
        c.two_l_half = 2.0 * c.l(0.5);
        // μ* solves a c y/(1 + y)² = 1 with y = b μ^c (the smaller root):
        // there d(μ e^{L(μ)})/dμ = 0 up to the term d μ* (|d μ*| < 3·10⁻⁴).
        let [a, b, cc, _, _] = c.fit;
        let k = a * cc - 2.0; // ≥ 2.25 for every r ∈ [0, 1]
        let y = 0.5 * (k - radiometry::math::sqrtf(k * k - 4.0));
        c.mu_star = libm::powf(y / b, 1.0 / cc);
        c.mu_lambda_star = c.mu_star * libm::expf(c.l(c.mu_star));
        Ok(c)
    }

    /// The grazing continuation point `μ*`.
    #[inline]
    pub fn mu_star(&self) -> f32 {
        self.mu_star
    }

    /// The roughness `r`.
    #[inline]
    pub fn roughness(&self) -> f32 {
        self.r
    }

    /// The interpolated fit coefficients `[a, b, c, d, e]` of `L` at this
    /// `r` (Estevez & Kulla 2017, Table 1).
    #[inline]
    pub fn fit(&self) -> [f32; 5] {
        self.fit
    }

    /// `D(m)` from `sin²θm ∈ [0, 1]`: `(2 + 1/r)/(2π) · (sin²θm)^(1/(2r))`
    /// [sr⁻¹]; finite, `≥ 0`, `0` at `sin²θm = 0` (and for NaN).
    #[inline]
    pub fn d_sin2(&self, sin2: f32) -> f32 {
        let s2 = if sin2 > 0.0 { sin2.min(1.0) } else { return 0.0 };
        self.norm * libm::powf(s2, self.half_inv_r)
    }

    /// `L(x) = a/(1 + b x^c) + d x + e` for `x ∈ [0, 1]`.
    #[inline(always)]
    fn l(&self, x: f32) -> f32 {
        let [a, b, c, d, e] = self.fit;
        let xc = if x > 0.0 { libm::powf(x, c) } else { 0.0 };
        a / (1.0 + b * xc) + d * x + e
    }

    /// The fitted Smith `Λ(μ)` of a direction with `μ = cos θ ∈ [0, 1]`
    /// (clamped; NaN is treated as grazing): finite, positive, at most
    /// `exp(a + e) ≈ 7.6·10⁸` (the fit's grazing value at `r = 0`).
    #[inline]
    pub fn lambda(&self, mu: f32) -> f32 {
        let mu = if mu > 0.0 { mu.min(1.0) } else { 0.0 };
        if mu < self.mu_star {
            return self.mu_lambda_star / mu;
        }
        let l = if mu < 0.5 {
            self.l(mu)
        } else {
            self.two_l_half - self.l(1.0 - mu)
        };
        libm::expf(l)
    }
}
