//! The local shading frame: normal on `+Z`, directions pointing away from
//! the surface.
//!
//! Spherical coordinates follow the usual convention (Pharr, Jakob &
//! Humphreys, *Physically Based Rendering* 4th ed., §3.8): θ is measured
//! from `+Z`, φ from `+X` toward `+Y`, and
//! `ω = (sin θ cos φ, sin θ sin φ, cos θ)`. The solid-angle element is
//! `dω = sin θ dθ dφ`.
//!
//! Every helper here is total: for any finite input, including non-unit
//! vectors and the zero vector, it returns finite values.

use crate::math::{safe_sqrt, sqr};
use glam::Vec3;

/// `cos θ = ω·n = ω.z` in the local frame.
#[inline]
pub fn cos_theta(w: Vec3) -> f32 {
    w.z
}

/// Whether `w` is unit length to within `4ε`, `|‖w‖² − 1| ≤ 4ε`, and
/// strictly above the horizon (`cos θ > 0`): the input the straight-line
/// formulas of the crate's lobes take as it is (the tolerance within which
/// `radiometry-brdfs` leaves a direction unnormalised). False for NaN and
/// infinite components.
///
/// ```
/// use radiometry::frame::is_checked;
/// use radiometry::glam::Vec3;
/// assert!(is_checked(Vec3::new(0.6, 0.0, 0.8)));
/// assert!(!is_checked(Vec3::new(0.6, 0.0, -0.8))); // below the horizon
/// assert!(!is_checked(Vec3::new(0.0, 0.0, 2.0))); // not unit
/// assert!(!is_checked(Vec3::new(f32::NAN, 0.0, 1.0)));
/// ```
#[inline(always)]
pub fn is_checked(w: Vec3) -> bool {
    (w.length_squared() - 1.0).abs() <= 4.0 * f32::EPSILON && w.z > 0.0
}

/// `cos² θ`.
#[inline]
pub fn cos2_theta(w: Vec3) -> f32 {
    w.z * w.z
}

/// `sin² θ = max(0, 1 − cos² θ)`.
#[inline]
pub fn sin2_theta(w: Vec3) -> f32 {
    (1.0 - cos2_theta(w)).max(0.0)
}

/// `sin θ = sqrt(max(0, 1 − cos² θ))`.
#[inline]
pub fn sin_theta(w: Vec3) -> f32 {
    safe_sqrt(1.0 - cos2_theta(w))
}

/// `tan² θ = sin² θ / cos² θ`.
///
/// Returns `f32::INFINITY` when `cos θ = 0` (a grazing direction); callers in
/// this crate and in `radiometry-brdfs` treat an infinite `tan² θ` as the
/// limit it is (for instance Smith `Λ → ∞`, `G1 → 0`).
#[inline]
pub fn tan2_theta(w: Vec3) -> f32 {
    let c2 = cos2_theta(w);
    if c2 == 0.0 {
        f32::INFINITY
    } else {
        sin2_theta(w) / c2
    }
}

/// `tan θ`, with the same grazing convention as [`tan2_theta`].
#[inline]
pub fn tan_theta(w: Vec3) -> f32 {
    let c = cos_theta(w);
    if c == 0.0 { f32::INFINITY } else { sin_theta(w) / c }
}

/// `cos φ = x / sin θ`, and `1` when `sin θ = 0` (φ is then arbitrary).
#[inline]
pub fn cos_phi(w: Vec3) -> f32 {
    let s = sin_theta(w);
    if s == 0.0 { 1.0 } else { (w.x / s).clamp(-1.0, 1.0) }
}

/// `sin φ = y / sin θ`, and `0` when `sin θ = 0`.
#[inline]
pub fn sin_phi(w: Vec3) -> f32 {
    let s = sin_theta(w);
    if s == 0.0 { 0.0 } else { (w.y / s).clamp(-1.0, 1.0) }
}

/// Whether `w` lies in the upper hemisphere (`cos θ > 0`).
#[inline]
pub fn is_upper(w: Vec3) -> bool {
    w.z > 0.0
}

/// Whether `a` and `b` are on the same side of the surface.
#[inline]
pub fn same_hemisphere(a: Vec3, b: Vec3) -> bool {
    a.z * b.z > 0.0
}

/// Unit direction from spherical angles (radians):
/// `ω = (sin θ cos φ, sin θ sin φ, cos θ)`.
#[inline]
pub fn spherical_direction(theta: f32, phi: f32) -> Vec3 {
    let (st, ct) = crate::math::sincos(theta);
    let (sp, cp) = crate::math::sincos(phi);
    Vec3::new(st * cp, st * sp, ct)
}

/// Unit direction from `sin θ`, `cos θ` and φ (avoids a trigonometric call
/// when the cosine is already known, and keeps precision near the pole).
#[inline]
pub fn spherical_direction_sc(sin_theta: f32, cos_theta: f32, phi: f32) -> Vec3 {
    let (sp, cp) = crate::math::sincos(phi);
    Vec3::new(
        sin_theta.clamp(-1.0, 1.0) * cp,
        sin_theta.clamp(-1.0, 1.0) * sp,
        cos_theta.clamp(-1.0, 1.0),
    )
}

/// θ of a direction, in `[0, π]`. Uses `atan2(|xy|, z)`, which is accurate
/// at the pole and at the horizon (unlike `acos(z)`).
#[inline]
pub fn spherical_theta(w: Vec3) -> f32 {
    libm::atan2f(libm::hypotf(w.x, w.y), w.z)
}

/// φ of a direction, in `[0, 2π)`; `0` at the poles.
#[inline]
pub fn spherical_phi(w: Vec3) -> f32 {
    let p = libm::atan2f(w.y, w.x);
    if p < 0.0 { p + core::f32::consts::TAU } else { p }
}

/// Mirror reflection of `w` about the normal `n`: `2(w·n)n − w`.
///
/// Both point away from the surface (PBR 4th ed., eq. 9.1).
#[inline]
pub fn reflect(w: Vec3, n: Vec3) -> Vec3 {
    2.0 * w.dot(n) * n - w
}

/// Mirror reflection about the local normal `+Z`: `(−x, −y, z)`.
#[inline]
pub fn reflect_z(w: Vec3) -> Vec3 {
    Vec3::new(-w.x, -w.y, w.z)
}

/// The reflection half vector `h = (ωi + ωo)/|ωi + ωo|`, oriented into the
/// upper hemisphere, or `None` when it is undefined.
///
/// It is undefined when `ωi + ωo` is (nearly) the zero vector, i.e.
/// `ωi = −ωo`, or when either input is not finite. Such configurations
/// contribute nothing to a reflection BRDF (they are a set of measure zero
/// for which `D(h)` has no meaning), so BRDFs return 0 there.
///
/// The direction is that of [`half_vector_sum`]: corrected for the lengths
/// of the `f32` inputs where `ωi + ωo` cancels.
#[inline]
pub fn half_vector(wi: Vec3, wo: Vec3) -> Option<Vec3> {
    let (h, sum2) = half_vector_sum(wi, wo);
    let len2 = h.length_squared();
    // 1e-14 ≈ (1e-7)²: below this the direction of h is dominated by
    // rounding in the inputs.
    if !(sum2 > 1e-14 && len2 > 1e-14 && len2.is_finite()) {
        return None;
    }
    let h = h / crate::math::sqrtf(len2);
    Some(if h.z < 0.0 { -h } else { h })
}

/// `|ωi + ωo|²` below which [`half_vector_sum`] corrects for the input
/// lengths (`θd > 60°` for unit inputs).
pub const HALF_VECTOR_CORRECTION_BELOW: f32 = 1.0;

/// The unnormalised half vector of two directions that are unit to within
/// a few ulp, and `|ωi + ωo|²`: `h` points along `ωi/‖ωi‖ + ωo/‖ωo‖`.
///
/// With `s = ωi + ωo`, `d = ωi − ωo` and `δ = ‖ω‖² − 1`, that sum is, up to
/// a common factor `1 + O(δ)` and terms of order `δ²`,
/// `h = s − ¼ (δi − δo) d`, and `δi − δo = ‖ωi‖² − ‖ωo‖² = d·s` exactly — so
/// the correction needs no extra precision: where `s` cancels, its
/// components are exact (Sterbenz's lemma) and `d·s` is accurate relative
/// to `|s|`. It matters where `ωi + ωo` cancels (`θd` near 90°: both
/// directions grazing, near the mirror configuration): there a length
/// error of one `f32` ulp — every `f32` direction near `(±1, 0, small)` has
/// one — turns `s` by `~ε/|s|` radians, a large fraction of a narrow lobe
/// (GGX α = 0.01 with both directions at 89.9°: pointwise errors up to 10%).
///
/// Applied where `|s|² <` [`HALF_VECTOR_CORRECTION_BELOW`] only: elsewhere
/// the correction turns `h` by at most `¼ |δi − δo| tan θd ≤ 0.43 |δi − δo|`
/// radians (`≤ 2·10⁻⁷` for `|δ| ≤ 4ε`, `~4·10⁻⁸` for rounded unit vectors),
/// the size of the direction rounding of `f32` inputs themselves. Swapping
/// `ωi` and `ωo` negates `d` and `d·s` exactly, so the result is symmetric
/// bit for bit.
///
/// ```
/// use radiometry::frame::half_vector_sum;
/// use radiometry::glam::Vec3;
/// // Both directions at 89.9° from the normal, mirror configuration.
/// let (s, c) = (89.9f64.to_radians().sin(), 89.9f64.to_radians().cos());
/// let wo = Vec3::new(s as f32, 0.0, c as f32);
/// let wi = Vec3::new(-s as f32, 1e-5, c as f32);
/// let (h, sum2) = half_vector_sum(wi, wo);
/// assert!(sum2 < 1e-4 && h.z > 0.0);
/// ```
#[inline]
pub fn half_vector_sum(wi: Vec3, wo: Vec3) -> (Vec3, f32) {
    let s = wi + wo;
    let sum2 = s.length_squared();
    let h = if sum2 < HALF_VECTOR_CORRECTION_BELOW {
        let d = wi - wo;
        // `(d/4)·s = ¼ d·s` (`d/4` is exact) without a dependent multiply.
        s - (0.25 * d).dot(s) * d
    } else {
        s
    };
    (h, sum2)
}

/// Normalises `w`, returning `None` for the zero vector and non-finite input.
#[inline]
pub fn try_normalize(w: Vec3) -> Option<Vec3> {
    let l2 = w.length_squared();
    if l2 > 0.0 && l2.is_finite() {
        Some(w / crate::math::sqrtf(l2))
    } else {
        None
    }
}

/// An orthonormal basis `(s, t, n)`: converts between world space and the
/// local shading frame in which `n` is `+Z`.
///
/// Built with the branchless construction of Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited" (JCGT 6(1)), which is continuous except at
/// `n.z = −1` and exact to rounding everywhere.
///
/// ```
/// use radiometry::{Frame, glam::Vec3};
/// let n = Vec3::new(1.0, 2.0, 3.0).normalize();
/// let f = Frame::from_normal(n).unwrap();
/// let local = f.to_local(n);
/// assert!((local - Vec3::Z).length() < 1e-6);
/// let w = Vec3::new(0.3, -0.2, 0.9).normalize();
/// assert!((f.to_world(f.to_local(w)) - w).length() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent (local `+X`).
    pub s: Vec3,
    /// Second tangent (local `+Y`).
    pub t: Vec3,
    /// Normal (local `+Z`).
    pub n: Vec3,
}

impl Frame {
    /// The identity frame: local == world.
    pub const IDENTITY: Frame = Frame {
        s: Vec3::X,
        t: Vec3::Y,
        n: Vec3::Z,
    };

    /// Builds a frame around `n` (normalised here). Returns `None` if `n` is
    /// zero or not finite.
    pub fn from_normal(n: Vec3) -> Option<Frame> {
        let n = try_normalize(n)?;
        let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * sqr(n.x) * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + sqr(n.y) * a, -n.y);
        Some(Frame { s, t, n })
    }

    /// Builds the frame of a renderer's shading normal `n` and tangent `t`
    /// (both normalised here): `s` is `t` made orthogonal to `n`
    /// (Gram–Schmidt: `s = (t − (t·n) n)/|…|`) and the second tangent is
    /// `n × s`, so the frame is right-handed (`s × t = n`). Returns `None` if
    /// either vector is zero or not finite, or if `t` is parallel to `n`
    /// (no tangent direction left).
    ///
    /// ```
    /// use radiometry::{Frame, glam::Vec3};
    /// let f = Frame::from_normal_tangent(Vec3::Z, Vec3::new(1.0, 0.0, 0.2)).unwrap();
    /// assert!((f.s - Vec3::X).length() < 1e-6 && (f.t - Vec3::Y).length() < 1e-6);
    /// assert!(Frame::from_normal_tangent(Vec3::Z, Vec3::Z * 2.0).is_none());
    /// ```
    pub fn from_normal_tangent(n: Vec3, t: Vec3) -> Option<Frame> {
        let n = try_normalize(n)?;
        let t = try_normalize(t)?;
        let s = try_normalize(t - t.dot(n) * n)?;
        // Parallel input leaves only rounding noise: demand a real tangent.
        if (t - t.dot(n) * n).length_squared() < 1e-12 {
            return None;
        }
        Some(Frame { s, t: n.cross(s), n })
    }

    /// World → local: `(w·s, w·t, w·n)`.
    #[inline]
    pub fn to_local(&self, w: Vec3) -> Vec3 {
        Vec3::new(w.dot(self.s), w.dot(self.t), w.dot(self.n))
    }

    /// Local → world: `x s + y t + z n`.
    #[inline]
    pub fn to_world(&self, w: Vec3) -> Vec3 {
        w.x * self.s + w.y * self.t + w.z * self.n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spherical_round_trip() {
        for &(t, p) in &[(0.3f32, 1.0f32), (1.5, 5.0), (0.01, 3.0), (1.2, 0.0)] {
            let w = spherical_direction(t, p);
            assert!((w.length() - 1.0).abs() < 1e-6);
            assert!((spherical_theta(w) - t).abs() < 1e-5);
            assert!((spherical_phi(w) - p).abs() < 1e-5);
        }
    }

    #[test]
    fn trig_helpers_are_total_at_grazing_and_pole() {
        let graze = Vec3::new(1.0, 0.0, 0.0);
        assert_eq!(tan2_theta(graze), f32::INFINITY);
        assert_eq!(cos_phi(Vec3::Z), 1.0);
        assert_eq!(sin_phi(Vec3::Z), 0.0);
        let w = Vec3::new(0.0, 1.0, 1e-7);
        assert!(tan2_theta(w).is_finite());
        assert!(sin_theta(Vec3::new(0.0, 0.0, 1.0000001)) == 0.0);
    }

    #[test]
    fn half_vector_degenerate() {
        let w = Vec3::new(0.6, 0.0, 0.8);
        assert!(half_vector(w, -w).is_none());
        assert!(half_vector(w, Vec3::new(f32::NAN, 0.0, 1.0)).is_none());
        let h = half_vector(w, reflect_z(w)).unwrap();
        assert!((h - Vec3::Z).length() < 1e-6);
        // Grazing pair below the horizon still gives an upper-hemisphere h.
        let h = half_vector(Vec3::new(1.0, 0.0, -0.1), Vec3::new(0.0, 1.0, -0.1)).unwrap();
        assert!(h.z > 0.0);
    }

    #[test]
    fn frame_from_normal_and_tangent() {
        let ns = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.3, -0.8, 0.2),
            Vec3::new(1e-8, 0.0, 1.0),
        ];
        let ts = [Vec3::X, Vec3::new(0.2, 0.9, -0.4), Vec3::new(-5.0, 1.0, 1.0)];
        for n in ns {
            for t in ts {
                let f = Frame::from_normal_tangent(n, t).unwrap();
                let nn = n.normalize();
                assert!((f.n - nn).length() < 1e-6);
                for v in [f.s, f.t, f.n] {
                    assert!((v.length() - 1.0).abs() < 1e-5);
                }
                assert!(f.s.dot(f.t).abs() < 1e-5 && f.s.dot(f.n).abs() < 1e-5 && f.t.dot(f.n).abs() < 1e-5);
                assert!((f.s.cross(f.t) - f.n).length() < 1e-5, "right-handed");
                // s lies in the plane of n and t, on t's side.
                assert!(f.s.dot(t) > 0.0 && f.s.dot(nn.cross(t)).abs() < 1e-5);
                let w = Vec3::new(0.3, -0.2, 0.9).normalize();
                assert!((f.to_world(f.to_local(w)) - w).length() < 1e-5);
            }
        }
        for (n, t) in [
            (Vec3::Z, Vec3::Z),
            (Vec3::Z, -3.0 * Vec3::Z),
            (Vec3::ZERO, Vec3::X),
            (Vec3::Z, Vec3::ZERO),
            (Vec3::new(f32::NAN, 0.0, 1.0), Vec3::X),
            (Vec3::Z, Vec3::new(f32::INFINITY, 0.0, 0.0)),
        ] {
            assert!(Frame::from_normal_tangent(n, t).is_none(), "{n:?} {t:?}");
        }
    }

    #[test]
    fn frame_orthonormal_everywhere() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.0, 1e-8, -1.0),
            Vec3::new(1.0, 1.0, 1.0),
        ] {
            let f = Frame::from_normal(n).unwrap();
            assert!((f.s.length() - 1.0).abs() < 1e-5);
            assert!((f.t.length() - 1.0).abs() < 1e-5);
            assert!(f.s.dot(f.t).abs() < 1e-5);
            assert!(f.s.dot(f.n).abs() < 1e-5);
            assert!((f.s.cross(f.t) - f.n).length() < 1e-5, "right-handed for {n:?}");
        }
        assert!(Frame::from_normal(Vec3::ZERO).is_none());
        assert!(Frame::from_normal(Vec3::splat(f32::NAN)).is_none());
    }

    #[test]
    fn reflect_matches_reflect_z() {
        let w = Vec3::new(0.3, -0.4, 0.866).normalize();
        assert!((reflect(w, Vec3::Z) - reflect_z(w)).length() < 1e-6);
    }
}
