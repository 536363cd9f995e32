//! Bit-level helpers of the vector `libm` ports (`expf`, `log1pf`, `powf`,
//! `expm1f`, `logf`, `acosf`, `sincos_turn`): the integer vectors of the width of
//! [`Vf`], conversions between lanes and their bits, and `scalbnf`.

use super::Vf;

/// The integer vectors of the same width as [`Vf`] (bit manipulation in
/// the `libm` ports below).
#[cfg(target_feature = "avx512f")]
pub(super) type Vi = wide::i32x16;
#[cfg(not(target_feature = "avx512f"))]
pub(super) type Vi = wide::i32x8;
#[cfg(target_feature = "avx512f")]
pub(super) type Vu = wide::u32x16;
#[cfg(not(target_feature = "avx512f"))]
pub(super) type Vu = wide::u32x8;
// The widths are chosen by separate `cfg`s: the build fails if they disagree.
const _: () = assert!(core::mem::size_of::<Vi>() == core::mem::size_of::<Vf>());
const _: () = assert!(core::mem::size_of::<Vu>() == core::mem::size_of::<Vf>());

/// `i32` lanes to `f32` (exact for `|k| < 2²⁴`).
#[inline(always)]
pub(super) fn int_to_float(k: Vi) -> Vf {
    k.round_float()
}

/// The bits of each lane (`f32::to_bits`).
#[inline(always)]
pub(super) fn to_bits(x: Vf) -> Vi {
    wide::bytemuck::cast(x)
}

/// Lanes from bits (`f32::from_bits`).
#[inline(always)]
pub(super) fn from_bits(i: Vi) -> Vf {
    wide::bytemuck::cast(i)
}

/// An integer mask (all ones / all zeros per lane) as a float mask.
#[inline(always)]
pub(super) fn fmask(m: Vi) -> Vf {
    wide::bytemuck::cast(m)
}

/// `a >> b` per lane (arithmetic; `b ∈ [0, 31]`).
#[inline(always)]
pub(super) fn shr_var(a: Vi, b: Vi) -> Vi {
    a >> wide::bytemuck::cast::<Vi, Vu>(b)
}

/// `x` with the low bits cleared: `f32::from_bits(x.to_bits() & mask)`.
#[inline(always)]
pub(super) fn clear_low(x: Vf, mask: u32) -> Vf {
    from_bits(to_bits(x) & Vi::splat(mask as i32))
}

/// `scalbnf(y, k)` of libm (`y · 2^k` with one rounding) for integer-valued
/// `k ∈ [−228, 254]` and `y` normal: a prescale by `2^-102` below `−126`
/// or by `2^127` above `127` (exact), then one multiply by `2^{k₂}`,
/// `k₂ ∈ [−126, 127]`, as libm's `scalbn`.
#[inline(always)]
pub(super) fn scalbnf(y: Vf, k: Vf) -> Vf {
    let one = Vf::ONE;
    let low = k.simd_lt(Vf::splat(-126.0));
    let high = k.simd_gt(Vf::splat(127.0));
    let pre = low.select(
        Vf::splat(f32::from_bits(0x0c80_0000)),
        high.select(Vf::splat(f32::from_bits(0x7f00_0000)), one),
    );
    let k2 = low.select(k + Vf::splat(102.0), high.select(k - Vf::splat(127.0), k));
    let k2 = k2.max(Vf::splat(-126.0)).min(Vf::splat(127.0));
    let pow2 = from_bits((k2 + Vf::splat(127.0)).trunc_int() << 23_u32);
    (y * pre) * pow2
}
