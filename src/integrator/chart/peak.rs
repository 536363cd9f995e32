//! The peak-centred chart of the hemisphere that [`Auto`](super::Auto) uses
//! for narrow lobes: polar coordinates about the lobe's peak direction, with
//! a radial warp matched to the lobe's width and the radial range clipped
//! at the horizon along every azimuth.
//!
//! Let `p` be the pole (the peak, `p_z > 0`), `e₁` the unit vector
//! orthogonal to `p` in the vertical plane through `p` pointing down
//! (`e₁_z = −√(1 − p_z²)`; any horizontal vector when `p = ẑ`), and
//! `e₂ = p × e₁` (horizontal). A direction at angle `θ'` from the pole and
//! azimuth `φ'` about it is
//!
//! `ω = cos θ' p + sin θ' (cos φ' e₁ + sin φ' e₂)`, `dω = sin θ' dθ' dφ'`.
//!
//! **Radius.** With the stereographic radius `s = tan(θ'/2)` and `y = s²`,
//! `dω = 2 dy / (1 + y)² dφ'`. A lobe of width `w` about its peak falls off
//! like `(w² + y)⁻²` (GGX's `D` has exactly this form in `tan θ_h`). The
//! radial coordinate is logarithmic in `w² + y` and quadratic at the pole:
//!
//! `y = w² expm1(L x²)`, `L = ln(1 + y_h/w²)`, `dy/dx = 2 L x (w² + y)`,
//!
//! * under which such a lobe times the area element is
//!   `∝ x/(w² + y) ∝ x e^{−L x²}`, analytic in `x`, whose scale does not
//!   depend on how well `w` was guessed (a wrong `w` shifts the lobe along
//!   `x`);
//! * the rest of the hemisphere (cosine factors, shadowing, the horizon),
//!   which varies on the scale `y ~ 1`, keeps a fixed share of the
//!   coordinate (a radial map that is the lobe's own CDF `y/(w² + y)` makes
//!   `g J` constant on the lobe but squeezes the far field into a band of
//!   width `~w²` at `x = 1`, a boundary layer Clenshaw–Curtis cannot
//!   resolve);
//! * the radius `√y ∝ x` near the pole, so a smooth integrand is analytic in
//!   `x` on every azimuth even though `L` depends on the azimuth (with
//!   `y ∝ x` the rows carry a `√x` term that the azimuth sum no longer
//!   cancels, and the `x` rule converges algebraically).
//!
//! **Horizon.** Along azimuth `φ'` the great circle leaves the upper
//! hemisphere where `p_z cos θ' + t_z sin θ' = 0`, `t_z = e₁_z cos φ'`:
//! at `θ'_h = atan2(p_z, −t_z) ∈ (0, π)`, i.e. `y_h = tan²(θ'_h / 2)`.
//! The radial coordinate is scaled to it, `x = F(y) / F(y_h) ∈ [0, 1]`, so
//! the integrand never meets the horizon's discontinuity inside the square:
//! the horizon is the edge `x = 1`, a smooth (periodic) function of `φ'`.
//!
//! **Aspect.** A lobe seen near the horizon is an ellipse, narrow across
//! the plane of incidence (GGX at `θo = 85°`: about 11 : 1). The chart works
//! in coordinates `X = (Z₁, Z₂ / k)` where `Z = s (cos ψ, sin ψ)` is the
//! stereographic point of the direction at azimuth `ψ` about the pole and
//! `k = w₂ / w₁` the lobe's width across (`e₂`) over its width along
//! (`e₁`): in `X` the lobe is round, of width `w = w₁`. Stereographic
//! projection is conformal with `dω = 4 dZ / (1 + |Z|²)²`, and `dZ = k dX`.
//!
//! **Map.** `(x, t) ∈ [0, 1]² ↦ ω`: `φ' = 2π t` is the polar angle of `X`,
//! `ρ = |X|² = w² expm1(L x²)` its squared radius, with `L = ln(1 + ρ_h/w²)`
//! and `ρ_h = y_h(ψ) / m`, `m = cos² φ' + k² sin² φ'`, `tan ψ = k tan φ'`;
//! then `y = |Z|² = m ρ`. Jacobian
//!
//! `J = dω / (dx dt) = 2π · 4 k L x (w² + ρ) / (1 + y)²`.
//!
//! `∫∫ J dx dt = 2π` (the hemisphere's solid angle) for every pole and
//! width, which the tests check.

use glam::{DVec3, Vec3};

/// The chart: pole, frame and squared width `w²`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PeakChart {
    p: DVec3,
    e1: DVec3,
    e2: DVec3,
    w2: f64,
    /// Aspect `k = w₂/w₁`.
    k: f64,
}

/// Range of the aspect `k` the chart accepts (clamped).
pub(crate) const ASPECT_RANGE: (f64, f64) = (1.0 / 256.0, 256.0);

/// Smallest pole height `p_z` the chart accepts: below it the horizon edge
/// turns too fast in `φ'` for the trapezoid rule to gain anything.
pub(crate) const MIN_POLE_Z: f64 = 1e-4;

impl PeakChart {
    /// The chart about `pole` (normalised here) with squared width `w2`
    /// along `e₁` and aspect `k` (clamped to [`ASPECT_RANGE`], `1` if not
    /// finite); `None` for a pole below [`MIN_POLE_Z`], a non-finite pole or
    /// a width outside `(0, ∞)`.
    pub(crate) fn new(pole: Vec3, w2: f64, k: f64) -> Option<Self> {
        let k = if k.is_finite() && k > 0.0 {
            k.clamp(ASPECT_RANGE.0, ASPECT_RANGE.1)
        } else {
            1.0
        };
        let p = pole.as_dvec3();
        let n = p.length();
        if !(n.is_finite() && n > 0.0 && w2.is_finite() && w2 > 0.0) {
            return None;
        }
        let p = p / n;
        if p.z.is_nan() || p.z < MIN_POLE_Z {
            return None;
        }
        let h = libm::sqrt((1.0 - p.z * p.z).max(0.0));
        let e1 = if h > 1e-9 {
            // −ẑ minus its component along p, normalised: (p_z p − ẑ)/h.
            DVec3::new(p.z * p.x / h, p.z * p.y / h, (p.z * p.z - 1.0) / h)
        } else {
            DVec3::X
        };
        let e2 = p.cross(e1);
        Some(PeakChart { p, e1, e2, w2, k })
    }

    /// The typical relative change of a lobe of this chart's widths when a
    /// direction moves by the rounding of an `f32` unit vector (`≈ 2⁻²⁴`
    /// rad per component): that angle over the lobe's narrowest angular
    /// width `2 w min(k, 1)` (the stereographic radius is half the angle).
    pub(crate) fn rounding(&self) -> f64 {
        let eps = libm::ldexp(1.0, -24);
        (eps / (2.0 * libm::sqrt(self.w2) * self.k.min(1.0))).min(1.0)
    }

    /// The chart with both widths scaled by `s` (`w² → s² w²`).
    pub(crate) fn scaled(&self, s: f64) -> Option<Self> {
        let w2 = self.w2 * s * s;
        (w2.is_finite() && w2 > 0.0).then_some(PeakChart { w2, ..*self })
    }

    /// The frame `(e₁, e₂)` of the chart's tangent plane.
    pub(crate) fn frame(&self) -> (DVec3, DVec3) {
        (self.e1, self.e2)
    }

    /// The pole direction (`x = 0` for every `t`).
    pub(crate) fn pole(&self) -> Vec3 {
        self.p.as_vec3()
    }

    /// `(ω, J)` at `(x, t)`, `x ∈ [0, 1]`, `t` in turns.
    pub(crate) fn map(&self, x: f64, t: f64) -> (Vec3, f64) {
        let x = x.clamp(0.0, 1.0);
        let (sf, cf) = libm::sincos(core::f64::consts::TAU * t);
        // The physical azimuth ψ of the ray φ' in X: (cos ψ, sin ψ) ∝ (cos φ', k sin φ').
        let k = self.k;
        let m = cf * cf + k * k * sf * sf;
        let sm = libm::sqrt(m);
        let (cp, sp) = (cf / sm, k * sf / sm);
        let tz = self.e1.z * cp;
        let pz = self.p.z;
        let r = libm::hypot(pz, tz);
        // s_h = tan(θ'_h/2) = sin θ'_h / (1 + cos θ'_h) with
        // (cos, sin) θ'_h = (−t_z, p_z)/r; for t_z > 0 the equivalent
        // (r + t_z)/p_z avoids the cancellation in r − t_z.
        let sh = if tz <= 0.0 { pz / (r - tz) } else { (r + tz) / pz };
        let w2 = self.w2;
        let rho_h = sh * sh / m;
        let l = libm::log1p(rho_h / w2);
        // `clamp(0, ρ_h)` written out: `f64::clamp` asserts `min ≤ max` (a
        // panic path for a NaN `ρ_h`); the same value otherwise.
        let mut rho = w2 * libm::expm1(l * x * x);
        if rho < 0.0 {
            rho = 0.0;
        }
        if rho > rho_h {
            rho = rho_h;
        }
        let y = rho * m;
        let d = 1.0 + y;
        let (ct, st) = ((1.0 - y) / d, 2.0 * libm::sqrt(y) / d);
        let dir = self.p * ct + (self.e1 * cp + self.e2 * sp) * st;
        let jac = core::f64::consts::TAU * 4.0 * k * l * x * (w2 + rho) / (d * d);
        // Round to f32 and keep the direction on the closed upper
        // hemisphere (x = 1 is the horizon itself).
        let v = dir.as_vec3();
        (Vec3::new(v.x, v.y, v.z.max(0.0)), jac)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::chart::simpson_trapezoid;

    /// `∫∫ f(ω) J dx dt` on this chart.
    fn integrate(c: &PeakChart, f: impl Fn(Vec3) -> f64, nx: usize, nt: usize) -> f64 {
        simpson_trapezoid(|x, t| c.map(x, t), f, nx, nt)
    }

    #[test]
    fn the_chart_covers_the_hemisphere_once() {
        // ∫ dω = 2π and ∫ cos θ dω = π over the upper hemisphere, for poles
        // from the zenith down to 85° (auto uses it to 78°), widths from narrow to broad and
        // aspects from 1 : 11 to 3 : 1 (the elongated chart needs the fine
        // azimuth rule).
        for &(pz, w2, k) in &[
            (1.0f32, 0.01, 1.0),
            (0.5, 0.0025, 0.3),
            (0.087, 0.01, 0.09),
            (0.2, 1.0, 1.0),
            (0.9, 4.0, 3.0),
            (0.05, 0.01, 0.5),
        ] {
            let pole = Vec3::new((1.0 - pz * pz).sqrt(), 0.0, pz);
            let c = PeakChart::new(pole, w2, k).unwrap();
            let area = integrate(&c, |_| 1.0, 400, 2048);
            let proj = integrate(&c, |w| w.z as f64, 400, 2048);
            assert!(
                (area - core::f64::consts::TAU).abs() < 1e-6,
                "{pz} {w2} {k}: {area}"
            );
            assert!(
                (proj - core::f64::consts::PI).abs() < 1e-6,
                "{pz} {w2} {k}: {proj}"
            );
        }
    }

    #[test]
    fn the_chart_stays_on_the_upper_hemisphere_and_is_finite() {
        let c = PeakChart::new(Vec3::new(0.999, 0.0, 0.01), 1e-6, 0.01).unwrap();
        for i in 0..=64 {
            for k in 0..64 {
                let (w, j) = c.map(i as f64 / 64.0, k as f64 / 64.0);
                assert!(
                    w.z >= 0.0 && w.is_finite() && j.is_finite() && j >= 0.0,
                    "{i} {k}: {w} {j}"
                );
                assert!((w.length() - 1.0).abs() < 1e-5, "{w}");
            }
        }
        assert!(PeakChart::new(Vec3::new(1.0, 0.0, 0.0), 0.1, 1.0).is_none());
        assert!(PeakChart::new(Vec3::Z, 0.0, 1.0).is_none());
        assert!(PeakChart::new(Vec3::new(f32::NAN, 0.0, 1.0), 0.1, 1.0).is_none());
    }
}
