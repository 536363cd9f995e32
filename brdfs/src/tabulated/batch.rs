//! The vector kernel of [`Tabulated`](super::Tabulated)'s `eval_batch` and
//! `eval_batch_soa` (feature `simd`): the Rusinkiewicz coordinates of
//! [`LANES`] pairs in vector form — the same operations per pair as the
//! scalar hot path `coords_above` of the grid module (sums, products, the
//! squares, one division and one `√` per angle, the arctangent polynomial
//! `ATAN_R`, comparison selects; the scalar code holds the three angles of
//! one pair in the lanes of a `glam::Vec4`, the kernel holds one angle of
//! [`LANES`] pairs in a vector), so each lane is bit-identical to
//! [`Brdf::eval`] — then the trilinear table reads per lane
//! ([`Tabulated::lookup`](super::Tabulated::lookup), as the scalar path).
//! Lanes the scalar path sends to its cold path (a non-unit direction, or
//! `‖ωi + ωo‖² < H_MIN` above the horizon) go back to the scalar method.

use super::Tabulated;
use super::coords::{ATAN_R, H_MIN};
use crate::simd::{Dirs, Kernel, LANES, Vf, cold_lanes};
use core::f32::consts::{FRAC_PI_2, PI};
use radiometry::glam::Vec3;
use radiometry::{Brdf, Spectrum};

/// `pdf` over [`LANES`] pairs: `HalfVectorDistribution::pdf_lanes` with
/// sampling enabled, else the cosine density `cos θi/π` above the horizon;
/// lanes with a non-unit direction go back to the scalar method (which
/// normalises first).
pub(super) struct Pdf<'t, 'a, S: Spectrum>(pub(super) &'t Tabulated<'a, S>);

impl<S: Spectrum> Kernel for Pdf<'_, '_, S> {
    type Out = f32;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [f32; LANES]) -> u32 {
        let zero = Vf::ZERO;
        let p = match self.0.sampling() {
            Some(d) => d.pdf_lanes(wi, wo),
            None => (wi.z.simd_gt(zero) & wo.z.simd_gt(zero))
                .select(wi.z * Vf::splat(core::f32::consts::FRAC_1_PI), zero),
        };
        *out = p.to_array();
        cold_lanes(wi, wo)
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
}

/// `eval` over [`LANES`] pairs.
pub(super) struct Eval<'t, 'a, S: Spectrum>(pub(super) &'t Tabulated<'a, S>);

/// The scalar `atan2_squares` lane-wise: `atan2(√y², √x²)` by
/// `r² = min/max`, `√r² · A(r²)`, `π/2 −` that when `y² > x²`.
#[inline(always)]
fn atan2_squares(y2: Vf, x2: Vf) -> Vf {
    let swap = y2.simd_gt(x2);
    let num = swap.select(x2, y2);
    let den = swap.select(y2, x2);
    let min = Vf::splat(f32::MIN_POSITIVE);
    let den = den.simd_gt(min).select(den, min);
    let r2 = num / den;
    let [c0, c1, c2, c3, c4, c5, c6, c7] = ATAN_R.map(Vf::splat);
    let z2 = r2 * r2;
    let z4 = z2 * z2;
    let p01 = c0 + c1 * r2;
    let p23 = c2 + c3 * r2;
    let p45 = c4 + c5 * r2;
    let p67 = c6 + c7 * r2;
    let q0 = p01 + z2 * p23;
    let q1 = p45 + z2 * p67;
    let a = r2.sqrt() * (q0 + z4 * q1);
    swap.select(Vf::splat(FRAC_PI_2) - a, a)
}

impl<S: Spectrum> Kernel for Eval<'_, '_, S> {
    type Out = S;

    #[inline(always)]
    fn lanes(&self, wi: Dirs, wo: Dirs, out: &mut [S; LANES]) -> u32 {
        let zero = Vf::ZERO;
        let h = wi.add(wo);
        let e = Dirs {
            x: wi.x - wo.x,
            y: wi.y - wo.y,
            z: wi.z - wo.z,
        };
        let s = h.x * h.x + h.y * h.y;
        let hz2 = h.z * h.z;
        let hh = s + hz2;
        let above = wi.z.simd_gt(zero) & wo.z.simd_gt(zero);
        let near_opposite = above & !hh.simd_ge(Vf::splat(H_MIN));
        let ee = e.x * e.x + e.y * e.y + e.z * e.z;
        // φd: the scalar `phi_d_squares`.
        let pole = s.simd_le(Vf::splat(1e-24) * hz2);
        let p = pole.select(e.y, h.x * e.y - h.y * e.x);
        let q = pole.select(e.x, h.z * (h.x * e.x + h.y * e.y) - s * e.z);
        let w = pole.select(Vf::ONE, hh);
        let y2 = p * p * w;
        let x2 = q * q;
        let neg = (p * q).simd_lt(zero);
        let theta_h = atan2_squares(s, hz2);
        let theta_d = atan2_squares(ee, hh);
        let a = atan2_squares(y2, x2);
        let phi_d = neg.select(Vf::splat(PI) - a, a);
        // √θh of the index map for all lanes at once (one vector root where
        // `lookup` takes one scalar root per lane).
        let (rh, td, pd) = (theta_h.sqrt().to_array(), theta_d.to_array(), phi_d.to_array());
        let ok = above.to_bitmask();
        for (k, o) in out.iter_mut().enumerate() {
            *o = if ok & (1 << k) != 0 {
                self.0.lookup_root(rh[k], td[k], pd[k])
            } else {
                S::zero()
            };
        }
        cold_lanes(wi, wo) | near_opposite.to_bitmask()
    }

    #[inline(always)]
    fn one(&self, wi: Vec3, wo: Vec3) -> S {
        self.0.eval(wi, wo)
    }
}
