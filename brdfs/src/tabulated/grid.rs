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
        let (nh, nd, np) = (self.n_theta_h, self.n_theta_d, self.n_phi_d);
        let scale = Vec4::new(
            nh as f32 * SQRT_2_OVER_PI,
            nd as f32 * FRAC_2_PI,
            np as f32 * FRAC_1_PI,
            0.0,
        );
        let np_f = np as f32;
        let lim = Vec4::new(
            nh.saturating_sub(1) as f32,
            nd.saturating_sub(1) as f32,
            f32::from_bits(np_f.to_bits() - 1),
            0.0,
        );
        let u = Vec4::new(libm::sqrtf(theta_h), theta_d, phi_d, 0.0) * scale;
        // NaN → 0, then ≤ lim: `max(u, 0)` returns its second operand for a
        // NaN `u` (SSE `maxps`; glam's scalar fallback ignores the NaN).
        let u = u.max(Vec4::ZERO).min(lim);
        let v = (u - Vec4::splat(0.5)) + Vec4::splat(MAGIC);
        let t = u - (v - Vec4::splat(MAGIC));
        let [vh, vd, vp, _] = v.to_array();
        let index = |v: f32| v.to_bits().wrapping_sub(MAGIC.to_bits());
        let (ih, id, ip) = (index(vh), index(vd), index(vp));
        let [th, td, tp, _] = t.to_array();
        Cells {
            h: [ih as usize, (ih + 1).min(nh.saturating_sub(1)) as usize],
            d: [id as usize, (id + 1).min(nd.saturating_sub(1)) as usize],
            p: [ip as usize, if ip + 1 < np { ip + 1 } else { 0 } as usize],
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

/// Smallest `‖ωi + ωo‖²` of the fast path [`coords_above`] (`‖h‖ ≥ 10⁻⁴`,
/// `θd ≤ 89.997°`): above it the squares the path forms (`~‖h‖⁴‖e‖²`)
/// stay far from `f32` underflow. Smaller values (unit directions nearly
/// opposite, both grazing) go through [`coords_unit`], which rescales `h`
/// first.
pub(crate) const H_MIN: f32 = 1e-8;

/// `(θh, θd, φd)` of unit directions `ωi`, `ωo` above the horizon from
/// `h = ωi + ωo` (never normalised), `hh = ‖h‖² ≥` [`H_MIN`] and
/// `e = ωi − ωo`; the hot path of [`Tabulated::eval`](super::Tabulated).
///
/// Each angle is an `atan2(y, x)` with `x, y ≥ 0` given by its squares:
///
/// ```text
/// θh:  y² = hx² + hy²,      x² = hz²                    (tan θh = sin θh / cos θh)
/// θd:  y² = ‖e‖²,            x² = ‖h‖²                   (‖e‖ = 2 sin θd, ‖h‖ = 2 cos θd)
/// φd:  y² = P² ‖h‖²,         x² = Q²                     P = hx ey − hy ex,
///                                                        Q = hz (hx ex + hy ey) − (hx² + hy²) ez
/// ```
///
/// computed as `r² = min(y², x²)/max(y², x²)`, `a = √r² · A(r²)` with the
/// arctangent polynomial `atan r = r·A(r²)` of [`ATAN_R`], and `π/2 − a`
/// when `y > x`: one division and one square root per angle, both
/// independent of the polynomial, and no square root before the division
/// (the ratio of squares needs none). The three angles share four-lane
/// `glam::Vec4` operations.
///
/// **φd.** `e = 2 sin θd (cos φd u + sin φd v)` in the frame `(u, v, ĥ)` of
/// the [module documentation](self) (`u = R_z(φh) R_y(θh) x̂`,
/// `v = R_z(φh) ŷ`), where `e·u = Q/(‖h‖ √(hx²+hy²))` and
/// `e·v = P/√(hx²+hy²)`, so `φd = atan2(e·v, e·u) = atan2(P‖h‖, Q)`;
/// folded into `[0, π)` (period π, reciprocity) it is `atan2(|P|‖h‖, |Q|)`,
/// or `π −` that when `P·Q < 0`. With `h` on the normal
/// (`hx² + hy² ≤ 10⁻²⁴ hz²`, `θh < 10⁻¹²`) φh is taken as 0 and
/// `(e·u, e·v) = (ex, ey)`.
///
/// **Exact reciprocity.** `h` is the same for `(ωi, ωo)` and `(ωo, ωi)`
/// (IEEE addition commutes) and `e` changes sign exactly, so `P`, `Q` change
/// sign exactly and every square, `P·Q`, hence every angle is bit-identical.
///
/// Needs `hz > 0`, `hh ≥` [`H_MIN`] and unit directions to within `4ε`.
#[inline(always)]
pub(crate) fn coords_above(h: Vec3, hh: f32, e: Vec3) -> (f32, f32, f32) {
    let s = h.x * h.x + h.y * h.y;
    let ee = e.x * e.x + e.y * e.y + e.z * e.z;
    let (y2, x2, neg) = phi_d_squares(h, s, hh, e);
    let a = atan2_squares(Vec4::new(s, ee, y2, 0.0), Vec4::new(h.z * h.z, hh, x2, 1.0));
    let phi_d = if neg { PI - a.z } else { a.z };
    (a.x, a.y, phi_d)
}

/// `(P²‖h‖², Q², P·Q < 0)` of [`coords_above`] (`s = hx² + hy²`,
/// `hh = ‖h‖²`; at the pole `(ey², ex², ey·ex < 0)`).
#[inline(always)]
fn phi_d_squares(h: Vec3, s: f32, hh: f32, e: Vec3) -> (f32, f32, bool) {
    let pole = s <= 1e-24 * (h.z * h.z);
    let p = if pole { e.y } else { h.x * e.y - h.y * e.x };
    let q = if pole {
        e.x
    } else {
        h.z * (h.x * e.x + h.y * e.y) - s * e.z
    };
    let w = if pole { 1.0 } else { hh };
    (p * p * w, q * q, p * q < 0.0)
}

/// `atan2(√y², √x²) ∈ [0, π/2]` lane-wise for `x², y² ≥ 0` (`(0, 0)` → 0):
/// `r² = min/max`, `a = √r² · A(r²)` ([`ATAN_R`]), `π/2 − a` when
/// `y² > x²` (comparison selects; NaN lanes give NaN).
#[inline(always)]
fn atan2_squares(y2: Vec4, x2: Vec4) -> Vec4 {
    let swap = y2.cmpgt(x2);
    let num = Vec4::select(swap, x2, y2);
    let den = Vec4::select(swap, y2, x2);
    let min = Vec4::splat(f32::MIN_POSITIVE);
    let den = Vec4::select(den.cmpgt(min), den, min);
    let r2 = num / den;
    let a = r2.sqrt() * atan_poly4(r2);
    Vec4::select(swap, Vec4::splat(FRAC_PI_2) - a, a)
}

/// `A(z) = Σₖ cₖ zᵏ` of [`ATAN_R`] on four lanes (Estrin form).
#[inline(always)]
fn atan_poly4(z: Vec4) -> Vec4 {
    let [c0, c1, c2, c3, c4, c5, c6, c7] = ATAN_R.map(Vec4::splat);
    let z2 = z * z;
    let z4 = z2 * z2;
    let p01 = c0 + c1 * z;
    let p23 = c2 + c3 * z;
    let p45 = c4 + c5 * z;
    let p67 = c6 + c7 * z;
    let q0 = p01 + z2 * p23;
    let q1 = p45 + z2 * p67;
    q0 + z4 * q1
}

/// `atan2(y, x) ∈ [0, π]` for `y ≥ 0` (`(0, 0)` → 0) from the squares,
/// `π −` the first quadrant's angle when `x < 0` (scalar form of
/// [`atan2_squares`], for the cold paths).
fn atan2_r(y: f32, x: f32) -> f32 {
    let a = atan2_squares(Vec4::splat(y * y), Vec4::splat(x * x)).x;
    if x < 0.0 { PI - a } else { a }
}

/// `(θh, θd, φd)` of unit directions whose sum `h` has `hz > 0`: exactly
/// [`coords_above`] when `‖h‖² ≥` [`H_MIN`]; below, θh and φd (scale-free
/// ratios of `h`'s components) from `g = h / max|hᵢ|` (a function of the
/// symmetric `h`, so still exactly reciprocal) and θd from the unscaled
/// `‖h‖²`.
#[inline]
pub(crate) fn coords_unit(a: Vec3, b: Vec3) -> (f32, f32, f32) {
    let h = a + b;
    let hh = h.length_squared();
    let e = a - b;
    if hh >= H_MIN {
        return coords_above(h, hh, e);
    }
    // hz > 0, so m > 0; g has components in [−1, 1], the largest ±1.
    let m = h.abs().max_element();
    let g = h / m;
    let (th, _, pd) = coords_above(g, g.length_squared(), e);
    let ee = e.x * e.x + e.y * e.y + e.z * e.z;
    let td = atan2_squares(Vec4::splat(ee), Vec4::splat(hh)).x;
    (th, td, pd)
}

/// `(θh, θd, φd)` of unit directions whose sum `h` has `hz ≤ 0` (the
/// public [`RusinkiewiczGrid::half_diff`] at or below the horizon), or
/// `None` when `h = 0`: `θh = atan2(√(hx² + hy²), hz) ∈ [π/2, π]`, θd and φd
/// as in [`coords_above`], with `g = h / max|hᵢ|`.
fn coords_below(a: Vec3, b: Vec3) -> Option<(f32, f32, f32)> {
    let h = a + b;
    let m = h.abs().max_element();
    if m.is_nan() || m <= 0.0 {
        return None;
    }
    let g = h / m;
    let e = a - b;
    let s = g.x * g.x + g.y * g.y;
    let theta_h = atan2_r(libm::sqrtf(s), g.z);
    let (_, _, phi_d) = coords_above(g, g.length_squared(), e);
    let ee = e.x * e.x + e.y * e.y + e.z * e.z;
    let theta_d = atan2_squares(Vec4::splat(ee), Vec4::splat(h.length_squared())).x;
    Some((theta_h, theta_d, phi_d))
}

/// `(θh, θd, φd)` of unit `a` and `b = −a` (no half vector) with `h = +Z`:
/// `θd` the polar angle of `a`, `φd` its folded azimuth, `θh = 0`.
fn coords_opposite(a: Vec3) -> (f32, f32, f32) {
    let theta_d = atan2_r(libm::sqrtf(a.x * a.x + a.y * a.y), a.z);
    let (_, _, phi_d) = coords_above(Vec3::Z, 1.0, a);
    (0.0, theta_d, phi_d)
}

/// `(θh, θd, φd)` of unit directions, `None` when `ωi + ωo = 0`.
fn half_diff_pair(a: Vec3, b: Vec3) -> Option<(f32, f32, f32)> {
    if a.z + b.z > 0.0 {
        Some(coords_unit(a, b))
    } else {
        coords_below(a, b)
    }
}

/// Coefficients `c₀ … c₇` of the arctangent polynomial
/// `atan r ≈ r · A(r²)`, `A(z) = Σₖ cₖ zᵏ` (degree 15 in `r`), for
/// `r ∈ [0, 1]`: a fit of this project minimising the largest *relative*
/// error of `atan` on `[0, 1]` (Lawson's iteratively reweighted least
/// squares on 4 000 Chebyshev nodes in `f64`, then rounded to `f32`).
/// Relative accuracy matters at small θh, whose grid index is `√θh`.
/// Measured error of the whole `f32` evaluation ([`atan2_squares`], unit
/// test `atan2_squares_error_is_small`): see the module documentation.
pub(crate) const ATAN_R: [f32; 8] = [
    0.999_999_9,
    -0.333_319_9,
    0.199_697_27,
    -0.140_194_95,
    0.099_143_27,
    -0.059_486_844,
    0.024_252_7,
    -0.004_693_354,
];

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
    extern crate std;
    use super::*;

    /// `atan2_squares` (the hot path's arctangent: squares, one division,
    /// `√`, the degree-15 polynomial) against `f64::atan2` of the same `f32`
    /// components, over a dense sweep of `[0, π/2]` at several scales, plus
    /// the endpoints (0, π/2, (0, 0)), subnormal and grazing components.
    #[test]
    fn atan2_squares_error_is_small() {
        let (mut abs, mut rel) = (0.0f64, 0.0f64);
        let mut check = |y: f32, x: f32| {
            let got = atan2_squares(Vec4::splat(y * y), Vec4::splat(x * x)).x as f64;
            let want = (y as f64).atan2(x as f64);
            abs = abs.max((got - want).abs());
            if want > 0.0 {
                rel = rel.max((got - want).abs() / want);
            }
        };
        for i in 0..=200_000 {
            let t = i as f64 / 200_000.0 * core::f64::consts::FRAC_PI_2;
            for r in [1e-9f64, 1e-3, 1.0, 2.0, 1e3] {
                check((t.sin() * r) as f32, (t.cos() * r) as f32);
            }
        }
        // Grazing and near-pole ratios: y/x down to 10⁻⁷ and up to 10⁷.
        for k in 0..=140 {
            let q = 10f64.powf(-7.0 + k as f64 * 0.05) as f32;
            check(q, 1.0);
            check(1.0, q);
        }
        // Measured: absolute 2.76e-7 rad, relative 3.33e-7.
        assert!(abs <= 3e-7, "absolute {abs:e}");
        assert!(rel <= 5e-7, "relative {rel:e}");
        // Endpoints exactly.
        let at = |y: f32, x: f32| atan2_squares(Vec4::splat(y), Vec4::splat(x)).x;
        assert_eq!(at(0.0, 0.0), 0.0);
        assert_eq!(at(0.0, 1.0), 0.0);
        assert!((at(1.0, 0.0) - FRAC_PI_2).abs() <= 2e-7);
        assert_eq!(at(f32::from_bits(1), 1.0), f32::from_bits(1).sqrt() * ATAN_R[0]);
        assert!((at(1.0, f32::from_bits(1)) - FRAC_PI_2).abs() <= 2e-7);
    }

    /// The independent `f64` reference of the coordinates: `h` normalised,
    /// `θh = atan2(√(hx²+hy²), hz)`, `d = R_y(−θh) R_z(−φh) ωi` built
    /// explicitly, `θd = atan2(√(dx²+dy²), dz)`, `φd = atan2(dy, dx)` folded
    /// into `[0, π)` (the module documentation's definition).
    fn reference(wi: Vec3, wo: Vec3) -> (f64, f64, f64) {
        let a = [wi.x as f64, wi.y as f64, wi.z as f64];
        let b = [wo.x as f64, wo.y as f64, wo.z as f64];
        let n = |v: [f64; 3]| {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [v[0] / l, v[1] / l, v[2] / l]
        };
        let (a, b) = (n(a), n(b));
        let h = n([a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
        let th = h[0].hypot(h[1]).atan2(h[2]);
        let ph = h[1].atan2(h[0]);
        let (c, s) = (ph.cos(), ph.sin());
        let x1 = c * a[0] + s * a[1];
        let y1 = -s * a[0] + c * a[1];
        let (ct, st) = (th.cos(), th.sin());
        let d = [ct * x1 - st * a[2], y1, st * x1 + ct * a[2]];
        let td = d[0].hypot(d[1]).atan2(d[2]);
        let mut pd = d[1].atan2(d[0]);
        if pd < 0.0 {
            pd += core::f64::consts::PI;
        }
        (th, td, pd)
    }

    /// Error of the hot path's coordinates in MERL cell units, against the
    /// `f64` reference, over 200 000 random unit pairs above the horizon:
    /// the continuous indices `u_h = 90√(2θh/π)`, `u_d = 180θd/π` and (where
    /// φd is well defined, θh, θd ≥ 0.01) `u_φ = 180φd/π`. The bounds are
    /// the measured worst cases rounded up; the `f32` spacing of `u` alone is
    /// 7.6·10⁻⁶ at 90.
    #[test]
    fn coordinates_error_in_cells() {
        let mut rng = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        let dir = |next: &mut dyn FnMut() -> f64| {
            let z = next().max(1e-6);
            let p = next() * core::f64::consts::TAU;
            let r = (1.0 - z * z).sqrt();
            Vec3::new((r * p.cos()) as f32, (r * p.sin()) as f32, z as f32)
        };
        let mut worst = [0.0f64; 3];
        for _ in 0..200_000 {
            let wi = dir(&mut next);
            let wo = dir(&mut next);
            if !(crate::microfacet::is_unit(wi) && crate::microfacet::is_unit(wo)) {
                continue;
            }
            let h = wi + wo;
            let hh = h.length_squared();
            if hh < H_MIN {
                continue;
            }
            let (th, td, pd) = coords_above(h, hh, wi - wo);
            let (rh, rd, rp) = reference(wi, wo);
            let uh = |t: f64| 90.0 * (t / core::f64::consts::FRAC_PI_2).sqrt();
            let cell = 180.0 / core::f64::consts::PI;
            worst[0] = worst[0].max((uh(th as f64) - uh(rh)).abs());
            worst[1] = worst[1].max((td as f64 - rd).abs() * cell);
            if rh >= 0.01 && rd >= 0.01 {
                let mut dp = (pd as f64 - rp).abs();
                dp = dp.min(core::f64::consts::PI - dp);
                worst[2] = worst[2].max(dp * cell);
            }
        }
        // Measured: θh 3.8e-5, θd 1.6e-5, φd 2.9e-4 (dominated by the rounding
        // of h = ωi + ωo in f32, relative ε/θ near the poles of each angle; the
        // arctangent itself contributes ≤ 2.8e-7 rad = 1.6e-5 of a θd cell).
        assert!(worst[0] <= 5e-5, "θh {:e} cells", worst[0]);
        assert!(worst[1] <= 2e-5, "θd {:e} cells", worst[1]);
        assert!(worst[2] <= 4e-4, "φd {:e} cells", worst[2]);
    }

    /// Exact reciprocity of the coordinates, bit for bit, including pairs
    /// with equal `cos θ` (rotated copies), mirror pairs (θh = 0, the pole
    /// branch), retro-reflection (θd = 0) and nearly opposite grazing pairs
    /// (the rescaled path).
    #[test]
    fn coordinates_are_exactly_symmetric() {
        let mut pairs = std::vec::Vec::new();
        for i in 0..2000 {
            let t = 0.0007 * i as f32;
            let (a, b) = ((t * 1.3).sin(), (t * 0.7).cos());
            let wi = Vec3::new(a * b, a * (1.0 - b * b).sqrt(), (1.0 - a * a).sqrt());
            let rot = |w: Vec3, f: f32| {
                Vec3::new(w.x * f.cos() - w.y * f.sin(), w.x * f.sin() + w.y * f.cos(), w.z)
            };
            pairs.push((wi, rot(wi, 0.3 + t)));
            pairs.push((wi, Vec3::new(-wi.x, -wi.y, wi.z)));
            pairs.push((wi, wi));
            pairs.push((wi, Vec3::new(-wi.x, -wi.y, 1e-6 * (1.0 + t))));
            pairs.push((Vec3::new(wi.x, wi.y, 1e-9), Vec3::new(-wi.x, -wi.y, 2e-9)));
        }
        for (wi, wo) in pairs {
            let a = RusinkiewiczGrid::half_diff(wi, wo);
            let b = RusinkiewiczGrid::half_diff(wo, wi);
            let bits = |v: (f32, f32, f32)| (v.0.to_bits(), v.1.to_bits(), v.2.to_bits());
            assert_eq!(bits(a), bits(b), "{wi:?} {wo:?}");
            assert!(
                a.0.is_finite() && a.1.is_finite() && a.2.is_finite(),
                "{wi:?} {wo:?}"
            );
            assert!((0.0..=PI).contains(&a.2), "{wi:?} {wo:?}: {a:?}");
        }
    }

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
