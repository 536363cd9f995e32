//! The GGX / Trowbridge–Reitz normal distribution.

use super::{
    MAX_ALPHA, MIN_ALPHA, MicrofacetDistribution, clamp01, finite_nonneg, tan2_theta_robust, unitize,
};
use crate::error::{BrdfError, check_range};
use core::f32::consts::PI;
use radiometry::glam::Vec3;
use radiometry::math::safe_sqrt;

/// The isotropic GGX (Trowbridge–Reitz) microfacet distribution.
///
/// Trowbridge & Reitz 1975, "Average irregularity representation of a rough
/// surface for ray reflection", JOSA 65(5); Walter et al. 2007, eq. 33:
///
/// ```text
/// D(m) = α² / (π cos⁴θm (α² + tan²θm)²) = α² / (π (α² cos²θm + sin²θm)²)
/// ```
///
/// and (Walter et al. 2007, eq. 34 rewritten in Λ form; Heitz 2014, eq. 86)
/// `Λ(ω) = (−1 + sqrt(1 + α² tan²θ)) / 2`.
///
/// Domain: `α ∈ [MIN_ALPHA, MAX_ALPHA] = [1e-4, 1]`.
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Ggx, MicrofacetDistribution};
/// let d = Ggx::new(0.5).unwrap();
/// // Peak value 1/(π α²) at m = +Z.
/// assert!((d.d(Vec3::Z) - 1.0 / (core::f32::consts::PI * 0.25)).abs() < 1e-5);
/// assert_eq!(d.g1(Vec3::X), 0.0); // grazing
/// assert!(Ggx::new(0.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    alpha: f32,
}

impl Ggx {
    /// A GGX distribution with roughness `α ∈ [1e-4, 1]`; NaN, infinities and
    /// values outside the range are rejected with [`BrdfError`].
    pub fn new(alpha: f32) -> Result<Self, BrdfError> {
        Ok(Ggx {
            alpha: check_range("alpha", alpha, MIN_ALPHA, MAX_ALPHA)?,
        })
    }

    /// The distribution of an `α` the caller has checked (in `[1e-4, 1]`):
    /// a material built at every hit from parameters it validated.
    #[inline(always)]
    pub(crate) fn from_valid(alpha: f32) -> Self {
        Ggx { alpha }
    }
}

impl MicrofacetDistribution for Ggx {
    #[inline]
    fn alpha(&self) -> f32 {
        self.alpha
    }

    fn energy_tables(&self) -> Option<super::EnergyTables> {
        Some(Self::TABLES)
    }

    /// `D(m) = α² / (π (α² cos²θm + sin²θm)²)` (Walter et al. 2007, eq. 33,
    /// multiplied through by `cos⁴θm`) of `m` normalised robustly; see
    /// [`d_cos2`](MicrofacetDistribution::d_cos2).
    #[inline]
    fn d(&self, m: Vec3) -> f32 {
        match unitize(m) {
            Some(m) if m.z > 0.0 => self.d_cos2(m.z * m.z, m.x * m.x + m.y * m.y),
            _ => 0.0,
        }
    }

    /// `D = α² / (π (α² cos²θm + sin²θm)²)`. For a unit normal the bracket
    /// is `≥ α² ≥ 10⁻⁸`, so the result is finite for every `α` in range; the
    /// form has no `1 − cos²` cancellation near the peak.
    #[inline(always)]
    fn d_cos2(&self, cos2: f32, sin2: f32) -> f32 {
        let a2 = self.alpha * self.alpha;
        let t = a2 * cos2 + sin2;
        finite_nonneg(a2 / (PI * t * t))
    }

    /// `D = α² L² / (π (α² h_z² + h_x² + h_y²)²)`, `L = h_z² + h_x² + h_y²`
    /// ([`d_cos2`](MicrofacetDistribution::d_cos2) multiplied through by
    /// `L²`), returned as the quotient `(α² L², π t²)`,
    /// `t = α² h_z² + h_x² + h_y²`. Within the contract (`L ∈ [2⁻³², 2³²]`)
    /// `t ≥ α² L ≥ 2.3·10⁻¹⁸`, so both parts are normal, finite `f32`.
    #[inline(always)]
    fn d_ratio(&self, hz2: f32, hxy2: f32) -> (f32, f32) {
        let a2 = self.alpha * self.alpha;
        let l = hz2 + hxy2;
        let t = a2 * hz2 + hxy2;
        ((a2 * l) * l, (PI * t) * t)
    }

    /// `Λ(ω)` of `ω` normalised robustly; see
    /// [`lambda_tan2`](MicrofacetDistribution::lambda_tan2).
    #[inline]
    fn lambda(&self, w: Vec3) -> f32 {
        self.lambda_tan2(tan2_theta_robust(w))
    }

    /// `G1(ω)`; see [`g1_tan2`](MicrofacetDistribution::g1_tan2).
    #[inline]
    fn g1(&self, w: Vec3) -> f32 {
        self.g1_tan2(tan2_theta_robust(w))
    }

    /// `Λ = (−1 + sqrt(1 + α² tan²θ))/2` (Heitz 2014, eq. 86), evaluated as
    /// `x / (2 (1 + sqrt(1 + x)))` with `x = α² tan²θ` (no cancellation for
    /// small `x`); `+∞` at grazing (`tan²θ = +∞` or NaN).
    #[inline(always)]
    fn lambda_tan2(&self, tan2: f32) -> f32 {
        let x = self.alpha * self.alpha * tan2;
        if x < f32::INFINITY {
            x / (2.0 * (1.0 + radiometry::math::sqrtf(1.0 + x)))
        } else {
            f32::INFINITY
        }
    }

    /// `A(ω) = cos θ (1 + Λ) = (cos θ + sqrt(cos²θ + α² sin²θ))/2` (the GGX
    /// `Λ` above multiplied through by `cos θ`): no division, and `α sin θ/2`
    /// at grazing.
    #[inline(always)]
    fn projected_area(&self, cos_theta: f32, sin2: f32) -> f32 {
        let a2 = self.alpha * self.alpha;
        0.5 * (cos_theta + radiometry::math::sqrtf(cos_theta * cos_theta + a2 * sin2))
    }

    /// `G1 = 1/(1 + Λ) = 2 / (1 + sqrt(1 + α² tan²θ))` (Walter et al. 2007,
    /// eq. 34); `0` at grazing.
    #[inline(always)]
    fn g1_tan2(&self, tan2: f32) -> f32 {
        let x = self.alpha * self.alpha * tan2;
        if x < f32::INFINITY {
            2.0 / (1.0 + radiometry::math::sqrtf(1.0 + x))
        } else {
            0.0
        }
    }

    #[cfg(feature = "simd")]
    #[inline]
    fn batch_kind(&self) -> super::DistributionKind {
        super::DistributionKind::Ggx { alpha: self.alpha }
    }

    /// Visible-normal sampling by spherical caps (Dupuy & Benyoub 2023,
    /// "Sampling Visible GGX Normals with Spherical Caps", CGF 42(8), §3;
    /// stretch/unstretch as in Heitz 2018, "Sampling the GGX Distribution of
    /// Visible Normals", JCGT 7(4)).
    ///
    /// 1. Stretch: `v = normalize(α x, α y, z)` of `ωo` (mirrored to `z ≥ 0`).
    /// 2. Sample `c` uniformly on the spherical cap `z_c ∈ [−v_z, 1]`:
    ///    `φ = 2π u₀`, `z_c = (1 − u₁)(1 + v_z) − v_z`.
    /// 3. `h = c + v` is a visible normal of the α = 1 configuration;
    ///    unstretch: `m = normalize(α h_x, α h_y, h_z)`.
    ///
    /// `1 − z_c = u₁(1 + v_z)`, `1 + z_c = (1 − u₁)(1 + v_z) + (1 − v_z)` and
    /// `h_z = (1 − u₁)(1 + v_z)` are evaluated in these cancellation-free
    /// forms.
    #[inline]
    fn sample_visible(&self, wo: Vec3, u: [f32; 2]) -> Vec3 {
        let a = self.alpha;
        let wo = unitize(wo).unwrap_or(Vec3::Z);
        let v = unitize(Vec3::new(a * wo.x, a * wo.y, wo.z.abs())).unwrap_or(Vec3::Z);
        let (u0, u1) = (clamp01(u[0]), clamp01(u[1]));
        let one_plus_vz = 1.0 + v.z;
        let one_minus_zc = u1 * one_plus_vz;
        let hz = (1.0 - u1) * one_plus_vz;
        let one_plus_zc = hz + (1.0 - v.z);
        let sin_c = safe_sqrt(one_minus_zc * one_plus_zc);
        let (sp, cp) = radiometry::math::sincos_turn(u0);
        let h = Vec3::new(sin_c * cp + v.x, sin_c * sp + v.y, hz);
        unitize(Vec3::new(a * h.x, a * h.y, h.z.max(0.0))).unwrap_or(Vec3::Z)
    }
}
