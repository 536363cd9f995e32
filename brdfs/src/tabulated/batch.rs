//! The vector kernel of [`Tabulated`](super::Tabulated)'s `eval_batch` and
//! `eval_batch_soa` (feature `simd`): the Rusinkiewicz coordinates of
//! [`LANES`] pairs in vector form — the same operations as the scalar
//! `half_diff_unit` (sums, products, `√`, one division per `atan2`, the
//! A&S 4.4.47 polynomial, selects), so each lane is bit-identical to
//! [`Brdf::eval`] — then the trilinear table reads per lane. Lanes with a
//! non-unit direction go back to the scalar method (its cold path
//! normalises).

use super::Tabulated;
use crate::simd::{Dirs, Kernel, LANES, Vf, cold_lanes};
use core::f32::consts::{FRAC_PI_2, PI};
use radiometry::glam::Vec3;
use radiometry::{Brdf, Spectrum};

/// `eval` over [`LANES`] pairs.
pub(super) struct Eval<'t, 'a, S: Spectrum>(pub(super) &'t Tabulated<'a, S>);

/// `atan(x)`, `x ∈ [0, 1]`: the scalar `atan_unit` (A&S 4.4.47, Estrin
/// form) operation for operation.
#[inline(always)]
fn atan_unit(x: Vf) -> Vf {
    let [a1, a3, a5, a7, a9] = super::grid::ATAN.map(Vf::splat);
    let z = x * x;
    let z2 = z * z;
    let lo = a1 + a3 * z;
    let mid = a5 + a7 * z;
    x * (lo + z2 * (mid + z2 * a9))
}

/// The scalar `atan2(|y|, x)` lane-wise.
#[inline(always)]
fn atan2(y: Vf, x: Vf) -> Vf {
    let ax = x.abs();
    let ay = y.abs();
    let num = ax.min(ay);
    let den = ax.max(ay).max(Vf::splat(f32::MIN_POSITIVE));
    let r = atan_unit(num / den);
    let r = ay.simd_gt(ax).select(Vf::splat(FRAC_PI_2) - r, r);
    x.simd_lt(Vf::ZERO).select(Vf::splat(PI) - r, r)
}

impl<S: Spectrum> Kernel for Eval<'_, '_, S> {
    type Out = S;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [S; LANES]) -> u32 {
        let zero = Vf::ZERO;
        let h = wi.add(wo);
        let len2 = h.length_squared();
        let valid = wi.z.simd_gt(zero) & wo.z.simd_gt(zero) & len2.simd_gt(Vf::splat(1e-30));
        let pick_i = wi.z.simd_le(wo.z);
        let a = Dirs {
            x: pick_i.select(wi.x, wo.x),
            y: pick_i.select(wi.y, wo.y),
            z: pick_i.select(wi.z, wo.z),
        };
        let sh2 = h.x * h.x + h.y * h.y;
        let sh = sh2.sqrt();
        let theta_h = atan2(sh, h.z);
        let x1s = h.x * a.x + h.y * a.y;
        let y1s = h.x * a.y - h.y * a.x;
        let len = len2.sqrt();
        let off_pole = sh2.simd_gt(Vf::splat(1e-24) * h.z * h.z);
        let dx = off_pole.select(h.z * x1s - sh2 * a.z, a.x);
        let dy = off_pole.select(len * y1s, a.y);
        let dz = off_pole.select(sh * x1s + h.z * sh * a.z, a.z);
        let sd = (dx * dx + dy * dy).sqrt();
        let theta_d = atan2(sd, dz);
        let flip = dy.simd_lt(zero) | (dy.simd_eq(zero) & dx.simd_lt(zero));
        let sign = flip.select(Vf::splat(-1.0), Vf::ONE);
        let phi_d = atan2(dy * sign, dx * sign);
        let (th, td, pd) = (theta_h.to_array(), theta_d.to_array(), phi_d.to_array());
        let ok = valid.to_bitmask();
        for (k, o) in out.iter_mut().enumerate() {
            *o = if ok & (1 << k) != 0 {
                self.0.lookup(th[k], td[k], pd[k])
            } else {
                S::zero()
            };
        }
        cold_lanes(wi, wo)
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> S {
        self.0.eval(wi, wo)
    }
}
