//! The Rusinkiewicz coordinates `(θh, θd, φd)` of a pair of directions:
//! the hot path of [`Tabulated::eval`](super::Tabulated) (`coords_above`),
//! its robust variants, and the arctangents they use. The change of
//! variables, the grid and the accuracy figures are in the
//! [`grid`](super::grid) module's documentation.

#[cfg(doc)]
use super::RusinkiewiczGrid;
use crate::vec4::sqrt4;
use core::f32::consts::{FRAC_PI_2, PI};
use radiometry::glam::{Vec3, Vec4};

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
/// the [`grid`](super::grid) module documentation (`u = R_z(φh) R_y(θh) x̂`,
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
    let (y2, x2, pq) = phi_d_squares(h, s, hh, e);
    let a = atan2_squares(Vec4::new(s, ee, y2, 0.0), Vec4::new(h.z * h.z, hh, x2, 1.0));
    let phi_d = if pq < 0.0 { PI - a.z } else { a.z };
    (a.x, a.y, phi_d)
}

/// `(P²‖h‖², Q², P·Q)` of [`coords_above`] (`s = hx² + hy²`,
/// `hh = ‖h‖²`; at the pole `(ey², ex², ey·ex)`).
#[inline(always)]
fn phi_d_squares(h: Vec3, s: f32, hh: f32, e: Vec3) -> (f32, f32, f32) {
    let pole = s <= 1e-24 * (h.z * h.z);
    let p = if pole { e.y } else { h.x * e.y - h.y * e.x };
    let q = if pole {
        e.x
    } else {
        h.z * (h.x * e.x + h.y * e.y) - s * e.z
    };
    let w = if pole { 1.0 } else { hh };
    (p * p * w, q * q, p * q)
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
    let a = sqrt4(r2) * atan_poly4(r2);
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
    let theta_h = atan2_r(radiometry::math::sqrtf(s), g.z);
    let (_, _, phi_d) = coords_above(g, g.length_squared(), e);
    let ee = e.x * e.x + e.y * e.y + e.z * e.z;
    let theta_d = atan2_squares(Vec4::splat(ee), Vec4::splat(h.length_squared())).x;
    Some((theta_h, theta_d, phi_d))
}

/// `(θh, θd, φd)` of unit `a` and `b = −a` (no half vector) with `h = +Z`:
/// `θd` the polar angle of `a`, `φd` its folded azimuth, `θh = 0`.
pub(crate) fn coords_opposite(a: Vec3) -> (f32, f32, f32) {
    let theta_d = atan2_r(radiometry::math::sqrtf(a.x * a.x + a.y * a.y), a.z);
    let (_, _, phi_d) = coords_above(Vec3::Z, 1.0, a);
    (0.0, theta_d, phi_d)
}

/// `(θh, θd, φd)` of unit directions, `None` when `ωi + ωo = 0`.
pub(crate) fn half_diff_pair(a: Vec3, b: Vec3) -> Option<(f32, f32, f32)> {
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

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::tabulated::RusinkiewiczGrid;

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
}
