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
//! The three angles are computed from `h = ωi + ωo` and `e = ωi − ωo` only
//! (never normalised; exactly reciprocal, see `coords_above` in the
//! source), each as an `atan2` of two non-negative components given by
//! their squares — one division, one square root and a degree-15
//! arctangent polynomial of this project's fit (constant `ATAN_R`) —
//! rather than an `acos` of a rounded cosine, which loses accuracy near the
//! poles. Measured against `f64` in the unit tests: the arctangent to
//! 2.8·10⁻⁷ rad (relative 3.3·10⁻⁷, i.e. 1.6·10⁻⁵ of a MERL θd cell; the
//! previous A&S 4.4.47 polynomial had 1.2·10⁻⁵ rad, 7·10⁻⁴ of a cell); the
//! continuous grid indices of 200 000 random unit pairs to 3.8·10⁻⁵ cells
//! (θh), 1.6·10⁻⁵ (θd) and 2.9·10⁻⁴ (φd, where θh, θd ≥ 0.01; φd is
//! undefined at either pole), the rest being the `f32` rounding of
//! `ωi ± ωo` (the spacing of `f32` at index 90 is alone 7.6·10⁻⁶). The
//! round trip node → directions → coordinates is exact to 1.5·10⁻⁵ rad.
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
use super::coords::{coords_opposite, half_diff_pair};
use core::f32::consts::{FRAC_1_PI, FRAC_2_PI, FRAC_PI_2, PI};
use radiometry::glam::{Vec3, Vec4};

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
    /// symmetric in `ωi ↔ ωo` bit for bit (computed from `ωi + ωo` and
    /// `±(ωi − ωo)` only, see `coords_above` in the source), and for two
    /// directions above the horizon it is exactly the coordinates
    /// [`Tabulated::eval`](super::Tabulated) interpolates at.
    ///
    /// Degenerate input has a documented finite fallback: a zero or
    /// non-finite direction gives `(0, 0, 0)`; `ωi = −ωo` (no half vector)
    /// uses `h = +Z`. [`try_half_diff`](Self::try_half_diff) reports both
    /// cases as `None` instead.
    pub fn half_diff(wi: Vec3, wo: Vec3) -> (f32, f32, f32) {
        match (unit(wi), unit(wo)) {
            (Some(a), Some(b)) => half_diff_pair(a, b).unwrap_or_else(|| coords_opposite(a)),
            _ => (0.0, 0.0, 0.0),
        }
    }

    /// [`half_diff`](Self::half_diff), or `None` when a direction is zero or
    /// not finite, or `ωi + ωo` vanishes (no half vector).
    pub fn try_half_diff(wi: Vec3, wo: Vec3) -> Option<(f32, f32, f32)> {
        half_diff_pair(unit(wi)?, unit(wo)?)
    }

    /// [`CellMap::cells`] of this grid (tests; the BRDF keeps its `CellMap`).
    #[cfg(test)]
    #[inline(always)]
    pub(crate) fn cells(&self, theta_h: f32, theta_d: f32, phi_d: f32) -> Cells {
        CellMap::new(*self).cells(theta_h, theta_d, phi_d)
    }
}

/// The constants of [`cells`](Self::cells) for one grid, computed
/// once (by [`Tabulated::new`](super::Tabulated::new)) instead of on every
/// lookup: the index scales, the clamps, the last node of each axis and the
/// strides of the flat index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CellMap {
    /// `(Nh √(2/π), Nd · 2/π, Nφ/π, 0)`.
    scale: Vec4,
    /// `(Nh − 1, Nd − 1, Nφ⁻, 0)`.
    lim: Vec4,
    /// `Nh − 1`, `Nd − 1`, `Nφ`.
    last_h: u32,
    last_d: u32,
    n_phi: u32,
    /// Strides of the flat index: `Nφ·Nd` (θh) and `Nφ` (θd).
    pub(crate) plane: usize,
    pub(crate) row: usize,
}

impl CellMap {
    /// The constants of `grid`.
    pub(crate) fn new(grid: RusinkiewiczGrid) -> Self {
        let (nh, nd, np) = (grid.n_theta_h, grid.n_theta_d, grid.n_phi_d);
        let np_f = np as f32;
        CellMap {
            scale: Vec4::new(
                nh as f32 * SQRT_2_OVER_PI,
                nd as f32 * FRAC_2_PI,
                np_f * FRAC_1_PI,
                0.0,
            ),
            lim: Vec4::new(
                nh.saturating_sub(1) as f32,
                nd.saturating_sub(1) as f32,
                f32::from_bits(np_f.to_bits() - 1),
                0.0,
            ),
            last_h: nh.saturating_sub(1),
            last_d: nd.saturating_sub(1),
            n_phi: np,
            plane: grid.n_phi_d() * grid.n_theta_d(),
            row: grid.n_phi_d(),
        }
    }

    /// The cells of `(θh, θd, φd)` on the three axes at once (four-lane
    /// `glam::Vec4` arithmetic): continuous indices
    ///
    /// ```text
    /// u_h = √θh · Nh √(2/π),   u_d = θd · Nd (2/π),   u_φ = φd · Nφ/π,
    /// ```
    ///
    /// clamped to `[0, Nh − 1]`, `[0, Nd − 1]` (θ axes constant beyond
    /// their last node) and `[0, Nφ⁻]` (`Nφ⁻` the float below `Nφ`; φd is
    /// periodic: node `Nφ` is node 0); NaN and negative input give 0. The
    /// floor is `i = round(u − ½)` by the `1.5·2²³` rounding trick (`(u − ½) +
    /// 1.5·2²³` rounds to an integer, read from the bits): exact for
    /// `0 ≤ u < 2²²`; at an integer `u = k` it may give `i = k − 1, t = 1`
    /// instead of `i = k, t = 0`, which interpolates to the same value bit
    /// for bit (`a·0 + b·1 = b = b·1 + c·0` for finite values).
    #[inline(always)]
    pub(crate) fn cells(&self, theta_h: f32, theta_d: f32, phi_d: f32) -> Cells {
        self.cells_root(radiometry::math::sqrtf(theta_h), theta_d, phi_d)
    }

    /// [`cells`](Self::cells) from `√θh` instead of `θh` (the vector
    /// kernel takes the roots of all its lanes in one instruction: the same
    /// correctly rounded value as `sqrtf`).
    #[inline(always)]
    pub(crate) fn cells_root(&self, root_theta_h: f32, theta_d: f32, phi_d: f32) -> Cells {
        let u = Vec4::new(root_theta_h, theta_d, phi_d, 0.0) * self.scale;
        // NaN → 0, then ≤ lim: `max(u, 0)` returns its second operand for a
        // NaN `u` (SSE `maxps`; glam's scalar fallback ignores the NaN).
        let u = u.max(Vec4::ZERO).min(self.lim);
        let v = (u - Vec4::splat(0.5)) + Vec4::splat(MAGIC);
        let t = u - (v - Vec4::splat(MAGIC));
        let [vh, vd, vp, _] = v.to_array();
        let index = |v: f32| v.to_bits().wrapping_sub(MAGIC.to_bits());
        let (ih, id, ip) = (index(vh), index(vd), index(vp));
        let [th, td, tp, _] = t.to_array();
        Cells {
            h: [ih as usize, (ih + 1).min(self.last_h) as usize],
            d: [id as usize, (id + 1).min(self.last_d) as usize],
            p: [ip as usize, if ip + 1 < self.n_phi { ip + 1 } else { 0 } as usize],
            t: [th, td, tp],
        }
    }
}

/// `1.5 · 2²³`: for `x ∈ [−2²², 2²²]`, `x + MAGIC ∈ [2²³, 2²⁴)`, where the
/// spacing of `f32` is 1, so the sum rounds `x` to the nearest integer (ties
/// to even), held in the low mantissa bits.
const MAGIC: f32 = 12_582_912.0;

/// `√(2/π)`.
const SQRT_2_OVER_PI: f32 = 0.797_884_6;

/// The lookup cells of [`RusinkiewiczGrid::cells`]: the two nodes of each
/// axis (`[i0, i1]`) and the weights `t` of the upper nodes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cells {
    pub(crate) h: [usize; 2],
    pub(crate) d: [usize; 2],
    pub(crate) p: [usize; 2],
    pub(crate) t: [f32; 3],
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

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

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
        let c = m.cells(FRAC_PI_2 * 0.25, FRAC_PI_2 * 0.5 + 1e-3, PI * 0.999_999);
        // θh node 45 exactly: (45, t = 0) or, by the rounding floor, (44, t = 1).
        // (√θh · 90 √(2/π) rounds to 45 + 4·10⁻⁶.)
        assert!(
            c.h == [45, 46] && c.t[0] < 1e-5 || c.h == [44, 45] && c.t[0] > 1.0 - 1e-5,
            "{c:?}"
        );
        assert_eq!(c.d[0], 45);
        assert_eq!(c.p, [179, 0]);
        let c = m.cells(2.0, 0.0, PI);
        // Beyond the last node (89, odd): (89, t = 0) or (88, t = 1).
        assert!(
            c.h == [89, 89] && c.t[0] == 0.0 || c.h == [88, 89] && c.t[0] == 1.0,
            "{c:?}"
        );
        assert_eq!(c.d, [0, 1]);
        // φd = π: the periodic end, weight 1 on node 0.
        assert_eq!(c.p, [179, 0]);
        assert!(c.t[2] > 0.9999, "{c:?}");
        let c = m.cells(f32::NAN, -1.0, f32::NAN);
        assert_eq!((c.h, c.d, c.p, c.t), ([0, 1], [0, 1], [0, 1], [0.0; 3]));
        // One-node axes.
        let g = RusinkiewiczGrid::new(1, 1, 1).unwrap();
        let c = g.cells(1.0, 1.0, 1.0);
        assert_eq!((c.h, c.d, c.p), ([0, 0], [0, 0], [0, 0]));
    }

    /// The rounding floor of `cells` against the exact floor over a dense
    /// sweep of every axis of a large grid (incl. every integer).
    #[test]
    fn cells_floor_is_exact() {
        let g = RusinkiewiczGrid::new(4096, 4096, 16).unwrap();
        for k in 0..=(4096 * 64) {
            let u = k as f32 / 64.0;
            let theta_d = u / (4096.0 * FRAC_2_PI);
            let c = g.cells(0.0, theta_d, 0.0);
            // The continuous index the cell sees (same rounding as `cells`).
            let uu = (theta_d * (4096.0 * FRAC_2_PI)).min(4095.0);
            let (i, t) = (c.d[0] as f32, c.t[1]);
            assert!((0.0..=1.0).contains(&t), "{u}: {c:?}");
            assert_eq!(i + t, uu, "{u}: {c:?}");
            assert!(uu.floor() == i || uu == i + 1.0 && t == 1.0, "{u}: {c:?}");
        }
    }
}
