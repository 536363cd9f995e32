//! The chunk driver of the vector sampling kernels
//! ([`Brdf::sample_batch`](radiometry::Brdf::sample_batch)).

use super::{Dirs, LANES, Vf};
use radiometry::glam::Vec3;

/// A sampling kernel over [`LANES`] `(ωo, u)` pairs with its scalar
/// counterpart.
pub(crate) trait SampleKernel {
    /// The value per pair (`Option<BrdfSample<S>>`).
    type Out;
    /// Writes the [`LANES`] values of one chunk (`u = (u0, u1)` per lane)
    /// and returns a bit mask of the lanes it did not handle (bit `k` for
    /// lane `k`): the driver recomputes those with [`one`](Self::one).
    fn lanes(&self, wo: Dirs, u0: Vf, u1: Vf, out: &mut [Self::Out; LANES]) -> u32;
    /// The scalar value of one pair (the tail, the lanes handed back; what
    /// `lanes` must equal).
    fn one(&self, wo: Vec3, u: [f32; 2]) -> Self::Out;
}

/// Recomputes the lanes of `cold` with the scalar method.
#[cold]
#[inline(never)]
fn fix_cold<K: SampleKernel>(
    k: &K,
    cold: u32,
    out: &mut [K::Out; LANES],
    wo: &[Vec3; LANES],
    u: &[[f32; 2]; LANES],
) {
    for (j, o) in out.iter_mut().enumerate() {
        if cold & (1 << j) != 0 {
            *o = k.one(wo[j], u[j]);
        }
    }
}

/// `out[k] = sample(wo[k], u[k])` for `k < min(len)`: whole chunks of
/// [`LANES`] through `k.lanes`, the tail through `k.one`; elements past the
/// shortest input are set to `None` (the batch length rule,
/// [`radiometry::batch::zero_tail`]).
#[inline(always)]
pub(crate) fn run_samples<K: SampleKernel>(k: &K, wo: &[Vec3], u: &[[f32; 2]], out: &mut [K::Out])
where
    K::Out: Default,
{
    let n = wo.len().min(u.len()).min(out.len());
    radiometry::batch::zero_tail(out, n);
    let (wo, u, out) = (&wo[..n], &u[..n], &mut out[..n]);
    let (cw, tw) = wo.as_chunks::<LANES>();
    let (cu, tu) = u.as_chunks::<LANES>();
    let (co, to) = out.as_chunks_mut::<LANES>();
    for ((w, uc), o) in cw.iter().zip(cu).zip(co) {
        let u0 = Vf::new(core::array::from_fn(|j| uc[j][0]));
        let u1 = Vf::new(core::array::from_fn(|j| uc[j][1]));
        let cold = k.lanes(Dirs::from_aos(w), u0, u1, o);
        if cold != 0 {
            fix_cold(k, cold, o, w, uc);
        }
    }
    for ((o, &w), &v) in to.iter_mut().zip(tw).zip(tu) {
        *o = k.one(w, v);
    }
}
