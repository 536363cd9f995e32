//! The Rusinkiewicz half/difference grid on which [`Tabulated`](super::Tabulated)
//! stores an isotropic BRDF.
//!
//! # Coordinates (Rusinkiewicz 1998)
//!
//! S. Rusinkiewicz, "A New Change of Variables for Efficient BRDF
//! Representation", Eurographics Rendering Workshop 1998, §3: with the half
//! vector `h = (ωi + ωo)/‖ωi + ωo‖ = (sin θh cos φh, sin θh sin φh, cos θh)`,
//! the *difference vector* is `ωi` seen from a frame in which `h` is the pole,
//!
//! ```text
//! d = R_y(−θh) · R_z(−φh) · ωi = (sin θd cos φd, sin θd sin φd, cos θd),
//! ```
//!
//! so `cos θd = ωi·h`. An isotropic BRDF does not depend on `φh`, leaving
//! `(θh, θd, φd)`. Exchanging `ωi` and `ωo` keeps `h` and maps `d` to its
//! mirror image about `h`, `(−dx, −dy, dz)`, i.e. `φd → φd + π`: by
//! reciprocity `f` has period π in `φd`, and the grid stores `φd ∈ [0, π)`
//! ("folding": `φd < 0 → φd + π`).
//!
//! # The MERL layout and other resolutions
//!
//! Matusik, Pfister, Brand & McMillan, "A Data-Driven Reflectance Model",
//! SIGGRAPH 2003, store `90 × 90 × 180` values with node `i` of each axis at
//!
//! ```text
//! θh(i) = (i/Nh)² · π/2      (square-root mapping: index = √(θh/(π/2)) · Nh)
//! θd(j) = j/Nd · π/2         (index = θd/(π/2) · Nd)
//! φd(k) = k/Nφ · π           (index = φd/π · Nφ, periodic with period Nφ)
//! flat  = k + Nφ·(j + Nd·i)
//! ```
//!
//! [`RusinkiewiczGrid::MERL`] is that grid; [`RusinkiewiczGrid::new`]
//! accepts any resolution with the same mappings. The square-root mapping
//! puts most θh nodes near the specular peak (node 1 of MERL at 0.011°,
//! node 45 at 22.5°).
//!
//! # Accuracy of the coordinate conversion
//!
//! The three angles are computed as `atan2` of sine and cosine components
//! (accurate near the poles, where `acos` of a rounded cosine is not), with
//! the degree-9 arctangent polynomial of Abramowitz & Stegun 4.4.47 on
//! `[0, 1]` (absolute error ≤ 1.2·10⁻⁵ rad, relative ≤ 1.4·10⁻⁴, checked in
//! the tests against `f64::atan2`; 7·10⁻⁴ of a MERL θd cell) and octant
//! reduction; the half vector is never normalised and no angle needs a
//! division besides the one inside `atan2`. The round trip
//! node → directions → coordinates is exact to 1.5·10⁻⁵ rad.
//!
//! # Example
//!
//! ```
//! use radiometry_brdfs::tabulated::RusinkiewiczGrid;
//! let g = RusinkiewiczGrid::MERL;
//! assert_eq!(g.len(), 90 * 90 * 180);
//! assert_eq!(g.index(1, 2, 3), 3 + 180 * (2 + 90 * 1));
//! let (wi, wo) = g.node_directions(30, 20, 45);
//! let (th, td, pd) = RusinkiewiczGrid::half_diff(wi, wo);
//! assert!((th - g.theta_h(30)).abs() < 2e-5);
//! assert!((td - g.theta_d(20)).abs() < 2e-5);
//! assert!((pd - g.phi_d(45)).abs() < 2e-5);
//! ```

use super::TabulatedError;
use core::f32::consts::{FRAC_2_PI, FRAC_PI_2, PI};
use radiometry::glam::Vec3;

/// Largest number of nodes on one axis accepted by [`RusinkiewiczGrid::new`].
pub const MAX_AXIS: usize = 1 << 12;
/// Largest number of nodes in total (per channel) accepted by
/// [`RusinkiewiczGrid::new`] (keeps every flat index below 2³¹ on 32-bit
/// targets).
pub const MAX_LEN: usize = 1 << 28;

/// A validated Rusinkiewicz `(θh, θd, φd)` grid: `n_theta_h × n_theta_d ×
/// n_phi_d` nodes with the mappings of the [module documentation](self).
///
/// ```
/// use radiometry_brdfs::tabulated::RusinkiewiczGrid;
/// let g = RusinkiewiczGrid::new(32, 16, 8)?;
/// assert_eq!(g.len(), 32 * 16 * 8);
/// assert!(RusinkiewiczGrid::new(0, 16, 8).is_err());
/// # Ok::<(), radiometry_brdfs::tabulated::TabulatedError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RusinkiewiczGrid {
    n_theta_h: u32,
    n_theta_d: u32,
    n_phi_d: u32,
}

/// One axis lookup: the two neighbouring nodes and the weight of the upper one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AxisCell {
    pub(crate) i0: usize,
    pub(crate) i1: usize,
    pub(crate) t: f32,
}

impl RusinkiewiczGrid {
    /// The MERL layout: 90 θh nodes (square-root mapping), 90 θd nodes, 180
    /// φd nodes over `[0, π)`.
    pub const MERL: RusinkiewiczGrid = RusinkiewiczGrid {
        n_theta_h: 90,
        n_theta_d: 90,
        n_phi_d: 180,
    };

    /// A grid with the given numbers of nodes per axis.
    ///
    /// # Errors
    /// [`TabulatedError::BadDims`] when an axis has 0 or more than
    /// [`MAX_AXIS`] nodes, or the product exceeds [`MAX_LEN`].
    pub fn new(n_theta_h: usize, n_theta_d: usize, n_phi_d: usize) -> Result<Self, TabulatedError> {
        let bad = TabulatedError::BadDims {
            dims: [n_theta_h, n_theta_d, n_phi_d],
        };
        let axis_ok = |n: usize| (1..=MAX_AXIS).contains(&n);
        if !(axis_ok(n_theta_h) && axis_ok(n_theta_d) && axis_ok(n_phi_d)) {
            return Err(bad);
        }
        // No overflow: each factor ≤ 2¹².
        if n_theta_h * n_theta_d * n_phi_d > MAX_LEN {
            return Err(bad);
        }
        Ok(Self {
            n_theta_h: n_theta_h as u32,
            n_theta_d: n_theta_d as u32,
            n_phi_d: n_phi_d as u32,
        })
    }

    /// Nodes on the θh axis.
    #[inline]
    pub fn n_theta_h(&self) -> usize {
        self.n_theta_h as usize
    }

    /// Nodes on the θd axis.
    #[inline]
    pub fn n_theta_d(&self) -> usize {
        self.n_theta_d as usize
    }

    /// Nodes on the φd axis.
    #[inline]
    pub fn n_phi_d(&self) -> usize {
        self.n_phi_d as usize
    }

    /// `[n_theta_h, n_theta_d, n_phi_d]`.
    #[inline]
    pub fn dims(&self) -> [usize; 3] {
        [self.n_theta_h(), self.n_theta_d(), self.n_phi_d()]
    }

    /// Values per channel: `n_theta_h · n_theta_d · n_phi_d`.
    #[inline]
    pub fn len(&self) -> usize {
        self.n_theta_h() * self.n_theta_d() * self.n_phi_d()
    }

    /// Always `false` (every axis has at least one node); present for the
    /// `len`/`is_empty` convention.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Flat index `i_phi_d + n_phi_d·(i_theta_d + n_theta_d·i_theta_h)`
    /// (the MERL order: φd fastest, θh slowest). Indices past the end of an
    /// axis are clamped to its last node, so the result is always
    /// `< self.len()`.
    #[inline]
    pub fn index(&self, i_theta_h: usize, i_theta_d: usize, i_phi_d: usize) -> usize {
        let ih = i_theta_h.min(self.n_theta_h() - 1);
        let id = i_theta_d.min(self.n_theta_d() - 1);
        let ip = i_phi_d.min(self.n_phi_d() - 1);
        ip + self.n_phi_d() * (id + self.n_theta_d() * ih)
    }

    /// θh of node `i` (rad): `(i/Nh)² · π/2` (clamped to the last node).
    #[inline]
    pub fn theta_h(&self, i: usize) -> f32 {
        let x = i.min(self.n_theta_h() - 1) as f32 / self.n_theta_h as f32;
        x * x * FRAC_PI_2
    }

    /// θd of node `j` (rad): `j/Nd · π/2` (clamped to the last node).
    #[inline]
    pub fn theta_d(&self, j: usize) -> f32 {
        j.min(self.n_theta_d() - 1) as f32 / self.n_theta_d as f32 * FRAC_PI_2
    }

    /// φd of node `k` (rad): `k/Nφ · π` (clamped to the last node).
    #[inline]
    pub fn phi_d(&self, k: usize) -> f32 {
        k.min(self.n_phi_d() - 1) as f32 / self.n_phi_d as f32 * PI
    }

    /// The unit directions `(ωi, ωo)` (local frame, normal `+Z`) of node
    /// `(i, j, k)` with `φh = 0`: the inverse of the module's change of
    /// variables, `ωi = R_y(θh)·d`, `ωo = R_y(θh)·(−dx, −dy, dz)` with
    /// `d = (sin θd cos φd, sin θd sin φd, cos θd)`. Indices are clamped as
    /// in [`index`](Self::index). Either direction may lie below the horizon
    /// (e.g. `θh + θd > π/2` at `φd = 0`); a BRDF is zero there.
    pub fn node_directions(&self, i_theta_h: usize, i_theta_d: usize, i_phi_d: usize) -> (Vec3, Vec3) {
        directions(
            self.theta_h(i_theta_h),
            self.theta_d(i_theta_d),
            self.phi_d(i_phi_d),
        )
    }

    /// Rusinkiewicz coordinates `(θh, θd, φd)` of a pair of directions, with
    /// `θh, θd ∈ [0, π]` and `φd` folded into `[0, π)` (module
    /// documentation). The inputs are normalised first; the result is
    /// symmetric in `ωi ↔ ωo` bit for bit unless `cos θi = cos θo` (the
    /// difference vector is taken from the direction with the smaller
    /// `cos θ`, which only changes rounding since the folded φd is
    /// symmetric).
    ///
    /// Degenerate input has a documented finite fallback: a zero or
    /// non-finite direction gives `(0, 0, 0)`; `ωi = −ωo` (no half vector)
    /// uses `h = +Z`. [`try_half_diff`](Self::try_half_diff) reports both
    /// cases as `None` instead.
    pub fn half_diff(wi: Vec3, wo: Vec3) -> (f32, f32, f32) {
        match (unit(wi), unit(wo)) {
            (Some(a), Some(b)) => half_diff_unit(a, b).unwrap_or_else(|| half_diff_about(a, Vec3::Z)),
            _ => (0.0, 0.0, 0.0),
        }
    }

    /// [`half_diff`](Self::half_diff), or `None` when a direction is zero or
    /// not finite, or `ωi + ωo` vanishes (no half vector).
    pub fn try_half_diff(wi: Vec3, wo: Vec3) -> Option<(f32, f32, f32)> {
        half_diff_unit(unit(wi)?, unit(wo)?)
    }

    /// The θh axis cell of `θh` (continuous index `√(θh/(π/2))·Nh`,
    /// constant beyond the last node).
    #[inline(always)]
    pub(crate) fn cell_theta_h(&self, theta_h: f32) -> AxisCell {
        let u = libm::sqrtf((theta_h * FRAC_2_PI).max(0.0)) * self.n_theta_h as f32;
        clamped_cell(u, self.n_theta_h)
    }

    /// The θd axis cell of `θd` (continuous index `θd/(π/2)·Nd`).
    #[inline(always)]
    pub(crate) fn cell_theta_d(&self, theta_d: f32) -> AxisCell {
        clamped_cell(theta_d * FRAC_2_PI * self.n_theta_d as f32, self.n_theta_d)
    }

    /// The φd axis cell of a folded `φd ∈ [0, π]` (continuous index
    /// `φd/π·Nφ`, periodic).
    #[inline(always)]
    pub(crate) fn cell_phi_d(&self, phi_d: f32) -> AxisCell {
        let n = self.n_phi_d;
        let mut u = (phi_d * (1.0 / PI) * n as f32).max(0.0);
        let nf = n as f32;
        if u >= nf {
            u -= nf;
        }
        // u ≥ 0: truncation is the floor (NaN converts to 0).
        let i0 = (u as usize).min(n as usize - 1);
        let i1 = if i0 + 1 >= n as usize { 0 } else { i0 + 1 };
        AxisCell {
            i0,
            i1,
            t: (u - i0 as f32).clamp(0.0, 1.0),
        }
    }
}

/// Cell of a clamped (non-periodic) axis with `n` nodes at continuous index `u`.
#[inline(always)]
fn clamped_cell(u: f32, n: u32) -> AxisCell {
    let last = n as usize - 1;
    let u = u.max(0.0);
    // u ≥ 0: truncation is the floor (NaN converts to 0).
    let i0 = (u as usize).min(last);
    let i1 = (i0 + 1).min(last);
    AxisCell {
        i0,
        i1,
        t: if i1 == i0 {
            0.0
        } else {
            (u - i0 as f32).clamp(0.0, 1.0)
        },
    }
}

/// `(ωi, ωo)` of the coordinates `(θh, θd, φd)` with `φh = 0`.
pub(crate) fn directions(theta_h: f32, theta_d: f32, phi_d: f32) -> (Vec3, Vec3) {
    let (sh, ch) = libm::sincosf(theta_h);
    let (sd, cd) = libm::sincosf(theta_d);
    let (sp, cp) = libm::sincosf(phi_d);
    let d = Vec3::new(sd * cp, sd * sp, cd);
    // R_y(θ)·(x, y, z) = (cos θ x + sin θ z, y, −sin θ x + cos θ z).
    let rot = |v: Vec3| Vec3::new(ch * v.x + sh * v.z, v.y, -sh * v.x + ch * v.z);
    (rot(d), rot(Vec3::new(-d.x, -d.y, d.z)))
}

/// Normalised `w`, or `None` for zero or non-finite input.
#[inline]
fn unit(w: Vec3) -> Option<Vec3> {
    crate::microfacet::unitize(w)
}

/// `(θh, θd, φd)` of unit directions; `None` when `ωi + ωo` vanishes.
/// The hot path of [`Tabulated::eval`](super::Tabulated).
#[inline(always)]
pub(crate) fn half_diff_unit(wi: Vec3, wo: Vec3) -> Option<(f32, f32, f32)> {
    let h = wi + wo;
    let len2 = h.length_squared();
    if len2.is_nan() || len2 <= 1e-30 {
        return None;
    }
    // Difference vector from the direction with the smaller z (a select, not
    // a branch): the same operations for (ωi, ωo) and (ωo, ωi) unless the two
    // z are equal, where the two orders differ by rounding only (the folded
    // φd is symmetric).
    let a = if wi.z <= wo.z { wi } else { wo };
    Some(half_diff_about(a, h))
}

/// `(θh, θd, φd)` of the unit direction `a` about the half vector `h`
/// (any positive length: every angle below is an `atan2` of components that
/// scale together, so `h` is never normalised).
#[inline(always)]
fn half_diff_about(a: Vec3, h: Vec3) -> (f32, f32, f32) {
    let sh2 = h.x * h.x + h.y * h.y;
    let sh = libm::sqrtf(sh2);
    let theta_h = atan2(sh, h.z);
    // d = R_y(−θh) R_z(−φh) a, with cos φh = hx/sh, sin φh = hy/sh,
    // cos θh = hz/|h|, sin θh = sh/|h|, computed as d·sh·|h| (no division):
    //   x1 = cos φh ax + sin φh ay,  y1 = −sin φh ax + cos φh ay,
    //   d = (cos θh x1 − sin θh az, y1, sin θh x1 + cos θh az).
    let x1s = h.x * a.x + h.y * a.y; // sh · x1
    let y1s = h.x * a.y - h.y * a.x; // sh · y1
    let len = libm::sqrtf(h.length_squared());
    let (dx, dy, dz) = if sh2 > 1e-24 * h.z * h.z {
        (h.z * x1s - sh2 * a.z, len * y1s, sh * x1s + h.z * sh * a.z)
    } else {
        // h on the normal (θh < 10⁻¹² rad): φh is arbitrary (0) and d = a.
        (a.x, a.y, a.z)
    };
    let sd = libm::sqrtf(dx * dx + dy * dy);
    let theta_d = atan2(sd, dz);
    // Fold by reciprocity: (dx, dy) ~ (−dx, −dy); pick dy ≥ 0 (and dx > 0 on
    // dy = 0), so that φd ∈ [0, π). A sign select, not a branch (the sign
    // is unpredictable in a renderer's loop).
    let flip = dy < 0.0 || (dy == 0.0 && dx < 0.0);
    let sign = if flip { -1.0 } else { 1.0 };
    let phi_d = atan2(dy * sign, dx * sign);
    (theta_h, theta_d, phi_d)
}

/// The coefficients `a₁, a₃, a₅, a₇, a₉` of [`atan_unit`] (A&S 4.4.47).
pub(crate) const ATAN: [f32; 5] = [0.999_866, -0.330_299_5, 0.180_141, -0.085_133, 0.020_835_1];

/// `atan(x)` for `x ∈ [0, 1]`: Abramowitz & Stegun 4.4.47,
/// `atan x = a₁x + a₃x³ + a₅x⁵ + a₇x⁷ + a₉x⁹ + ε`, `|ε| ≤ 10⁻⁵` (we measure
/// 1.15·10⁻⁵ rad absolute and 1.34·10⁻⁴ relative in f64; 7·10⁻⁴ of a MERL
/// θd cell). Evaluated in Estrin form (shorter dependency chain than Horner).
#[inline(always)]
fn atan_unit(x: f32) -> f32 {
    let [a1, a3, a5, a7, a9] = ATAN;
    let z = x * x;
    let z2 = z * z;
    let lo = a1 + a3 * z;
    let mid = a5 + a7 * z;
    x * (lo + z2 * (mid + z2 * a9))
}

/// `atan2(|y|, x) ∈ [0, π]` (any sign of `x`; `(0, 0)` → 0), by octant
/// reduction to [`atan_unit`] with selects rather than branches (the
/// octant is unpredictable in a renderer's loop). Non-finite input gives a
/// value in `[0, π]` or NaN, which callers clamp.
#[inline(always)]
pub(crate) fn atan2(y: f32, x: f32) -> f32 {
    let ax = x.abs();
    let ay = y.abs();
    let num = ax.min(ay);
    let den = ax.max(ay).max(f32::MIN_POSITIVE);
    let r = atan_unit(num / den);
    let r = if ay > ax { FRAC_PI_2 - r } else { r };
    if x < 0.0 { PI - r } else { r }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A&S 4.4.47 in f32 against f64 `atan2` over the upper half plane.
    #[test]
    fn atan2_error_is_small() {
        let mut worst = 0.0f64;
        for i in 0..=20_000 {
            let t = i as f64 / 20_000.0 * core::f64::consts::PI;
            for r in [1e-20f64, 1e-3, 1.0, 1e3] {
                let (y, x) = ((t.sin() * r) as f32, (t.cos() * r) as f32);
                let want = (y as f64).atan2(x as f64);
                worst = worst.max((atan2(y, x) as f64 - want).abs());
            }
        }
        assert!(worst < 1.2e-5, "{worst}");
        assert_eq!(atan2(0.0, 0.0), 0.0);
        assert_eq!(atan2(0.0, -1.0), PI);
    }

    /// Round trip node → directions → coordinates on every MERL node of a
    /// sparse sub-grid, against the node values (f64 reference of the
    /// forward map: the directions are built in f64 here, not by the code
    /// under test).
    #[test]
    fn half_diff_inverts_node_directions() {
        let g = RusinkiewiczGrid::MERL;
        let mut worst = 0.0f64;
        for i in (0..90).step_by(7) {
            for j in (0..90).step_by(5) {
                for k in (0..180).step_by(11) {
                    let (th, td, pd) = (g.theta_h(i) as f64, g.theta_d(j) as f64, g.phi_d(k) as f64);
                    let d = [td.sin() * pd.cos(), td.sin() * pd.sin(), td.cos()];
                    let rot = |v: [f64; 3]| {
                        Vec3::new(
                            (th.cos() * v[0] + th.sin() * v[2]) as f32,
                            v[1] as f32,
                            (-th.sin() * v[0] + th.cos() * v[2]) as f32,
                        )
                    };
                    let wi = rot(d);
                    let wo = rot([-d[0], -d[1], d[2]]);
                    let (a, b, c) = RusinkiewiczGrid::half_diff(wi, wo);
                    let (a2, b2, c2) = RusinkiewiczGrid::half_diff(wo, wi);
                    assert_eq!((a, b, c), (a2, b2, c2));
                    let mut dphi = (c as f64 - pd).abs();
                    if j == 0 || dphi > 3.0 {
                        // φd is undefined at θd = 0; near π it wraps to 0.
                        dphi = if j == 0 {
                            0.0
                        } else {
                            (dphi - core::f64::consts::PI).abs()
                        };
                    }
                    let e = (a as f64 - th).abs().max((b as f64 - td).abs()).max(dphi);
                    worst = worst.max(e);
                    let (ni, no) = g.node_directions(i, j, k);
                    assert!((ni - wi).length() < 1e-6 && (no - wo).length() < 1e-6);
                }
            }
        }
        assert!(worst < 1.5e-5, "{worst}");
    }

    /// Known configurations: the mirror pair (θh = 0, θd = θo) and the
    /// retro-reflection (θd = 0, θh = θo).
    #[test]
    fn special_configurations() {
        let t = 0.7f32;
        let wo = Vec3::new(t.sin(), 0.0, t.cos());
        let mirror = Vec3::new(-wo.x, 0.0, wo.z);
        let (th, td, _) = RusinkiewiczGrid::half_diff(mirror, wo);
        // Tolerance: the A&S 4.4.47 bound 1.2e-5 rad plus f32 rounding.
        assert!(th.abs() < 1e-7 && (td - t).abs() < 2e-5, "{th} {td}");
        let (th, td, _) = RusinkiewiczGrid::half_diff(wo, wo);
        assert!((th - t).abs() < 2e-5 && td.abs() < 1e-6, "{th} {td}");
        // Fallbacks.
        assert_eq!(RusinkiewiczGrid::half_diff(Vec3::ZERO, wo), (0.0, 0.0, 0.0));
        assert!(RusinkiewiczGrid::try_half_diff(wo, -wo).is_none());
        let (th, td, pd) = RusinkiewiczGrid::half_diff(wo, -wo);
        assert!(th == 0.0 && td.is_finite() && pd.is_finite());
        assert!(RusinkiewiczGrid::half_diff(Vec3::splat(f32::NAN), wo) == (0.0, 0.0, 0.0));
    }

    #[test]
    fn dims_validation_and_index() {
        assert!(RusinkiewiczGrid::new(0, 1, 1).is_err());
        assert!(RusinkiewiczGrid::new(1, MAX_AXIS + 1, 1).is_err());
        assert!(RusinkiewiczGrid::new(MAX_AXIS, MAX_AXIS, MAX_AXIS).is_err());
        let g = RusinkiewiczGrid::new(3, 4, 5).unwrap();
        assert_eq!(g.index(2, 3, 4), g.len() - 1);
        assert_eq!(g.index(99, 99, 99), g.len() - 1);
        assert_eq!(
            RusinkiewiczGrid::new(90, 90, 180).unwrap(),
            RusinkiewiczGrid::MERL
        );
        // MERL index formulas at a few angles.
        let m = RusinkiewiczGrid::MERL;
        let c = m.cell_theta_h(FRAC_PI_2 * 0.25);
        assert_eq!((c.i0, c.t), (45, 0.0));
        let c = m.cell_theta_d(FRAC_PI_2 * 0.5 + 1e-3);
        assert_eq!(c.i0, 45);
        let c = m.cell_phi_d(PI * 0.999_999);
        assert_eq!((c.i0, c.i1), (179, 0));
        let c = m.cell_phi_d(PI);
        assert_eq!(c.i0, 0);
        let c = m.cell_theta_h(2.0);
        assert_eq!((c.i0, c.i1, c.t), (89, 89, 0.0));
    }
}
