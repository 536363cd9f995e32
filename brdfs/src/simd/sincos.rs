//! `libm::sincosf` lane-wise, bit for bit, for the arguments the samplers
//! pass (`2π u`, `u ∈ [0, 1]`).

use super::{Vd, Vf, narrow, widen};

/// `π/2` rounded to `f64`, and its multiples (exact in `f64`), as the
/// scalar routine uses them.
const PIO2: f64 = 0.5 * core::f64::consts::PI;

/// The minimax polynomial of `sin` on `[−π/4, π/4]` that `libm`'s `k_sinf`
/// evaluates (FreeBSD `k_sinf.c`; `|sin x/x − P| < 2⁻³⁷·⁵`): coefficients of
/// `x³, x⁵, x⁷, x⁹`.
const S: [f64; 4] = [
    f64::from_bits(0xbfc5_5555_54cb_ac77), // -0.166666666416265235595
    f64::from_bits(0x3f81_1110_896e_fbb2), // 0.0083333293858894631756
    f64::from_bits(0xbf2a_00f9_e2ca_e774), // -0.000198393348360966317347
    f64::from_bits(0x3ec6_cd87_8c3b_46a7), // 0.0000027183114939898219064
];

/// The polynomial of `cos` on `[−π/4, π/4]` of `libm`'s `k_cosf` (FreeBSD
/// `k_cosf.c`; `|cos x − c(x)| < 2⁻³⁴·¹`): coefficients of `x², x⁴, x⁶, x⁸`.
const C: [f64; 4] = [
    f64::from_bits(0xbfdf_ffff_fd0c_5e81), // -0.499999997251031003120
    f64::from_bits(0x3fa5_5553_e105_3a42), // 0.0416666233237390631894
    f64::from_bits(0xbf56_c087_e80f_1e27), // -0.00138867637746099294692
    f64::from_bits(0x3ef9_9342_e0ee_5069), // 0.0000243904487962774090654
];

/// `k_sinf` in `f64` (before its rounding to `f32`), the scalar order:
/// `(x + s (S₁ + z S₂)) + s w (S₃ + z S₄)`, `z = x²`, `w = z²`, `s = z x`.
#[inline(always)]
fn k_sin(x: Vd) -> Vd {
    let z = x * x;
    let w = z * z;
    let r = Vd::splat(S[2]) + z * Vd::splat(S[3]);
    let s = z * x;
    (x + s * (Vd::splat(S[0]) + z * Vd::splat(S[1]))) + s * w * r
}

/// `k_cosf` in `f64`: `((1 + z C₀) + w C₁) + (w z)(C₂ + z C₃)`.
#[inline(always)]
fn k_cos(x: Vd) -> Vd {
    let z = x * x;
    let w = z * z;
    let r = Vd::splat(C[2]) + z * Vd::splat(C[3]);
    ((Vd::ONE + z * Vd::splat(C[0])) + w * Vd::splat(C[1])) + (w * z) * r
}

/// `(sin x, cos x)` lane-wise, **bit for bit** `libm::sincosf` (FreeBSD
/// `s_sincosf.c`, the same `f64` operations in the same order; no FMA) for
/// `x ∈ [−π/4, 9π/4]`: the argument is reduced by the nearest of
/// `0, π/2, π, 3π/2, 2π` (as `π/2 − x` or `x − kπ/2`, chosen by the same
/// thresholds on the bits of `|x|`), the two kernels
///
/// ```text
/// sin r ≈ r + r³(S₁ + r²S₂) + r⁷(S₃ + r²S₄),   cos r ≈ 1 + r²C₀ + r⁴C₁ + r⁶(C₂ + r²C₃)
/// ```
///
/// run in `f64` and the quadrant picks, swaps and negates them; for
/// `|x| < 2⁻¹²` the result is `(x, 1)` (on `[−π/4, 0]`, libm's first branch,
/// the kernels run on `x` itself). Other lanes (below `−π/4`, larger, NaN)
/// are outside the contract (finite garbage, never a panic); the callers
/// pass `2π u` with `u ∈ [0, 1]` (`2π` rounded to `f32`, `≤ 9π/4`) and the
/// concentric map's angles `π/4 · q`, `π/2 − π/4 · q` with `q ∈ [−1, 1]`.
/// Unit test `sincosf_is_libm_bit_for_bit`: every `f32` in `[−π/4, 2π]`
/// with a stride of 7.
#[inline(always)]
pub(crate) fn sincosf(x: Vf) -> (Vf, Vf) {
    let thr = |bits: u32| Vd::splat(f32::from_bits(bits) as f64);
    let halves = widen(x.abs());
    let xs = widen(x);
    let one = |h: usize| {
        let (ax, xd) = (halves[h], xs[h]);
        // The scalar branches: |x| ≤ π/4, ≤ 3π/4, ≤ 5π/4, ≤ 7π/4, else.
        let b0 = ax.simd_le(thr(0x3f49_0fda));
        let b1 = !b0 & ax.simd_le(thr(0x4016_cbe3));
        let b2 = ax.simd_gt(thr(0x4016_cbe3)) & ax.simd_le(thr(0x407b_53d1));
        let b3 = ax.simd_gt(thr(0x407b_53d1)) & ax.simd_le(thr(0x40af_eddf));
        let tiny = ax.simd_lt(thr(0x3980_0000));
        let k = b0.select(
            Vd::ZERO,
            b2.select(
                Vd::splat(2.0 * PIO2),
                b3.select(Vd::splat(3.0 * PIO2), Vd::splat(4.0 * PIO2)),
            ),
        );
        let r = b1.select(Vd::splat(PIO2) - xd, xd - k);
        let (ks, kc) = (k_sin(r), k_cos(r));
        // b1: (cos, sin); b2: (−sin, −cos); b3: (−cos, sin); b0, b4: (sin, cos).
        let swap = b1 | b3;
        let s = swap.select(kc, ks);
        let c = swap.select(ks, kc);
        let s = (b2 | b3).select(-s, s);
        let c = b2.select(-c, c);
        (tiny.select(xd, s), tiny.select(Vd::ONE, c))
    };
    let (s0, c0) = one(0);
    let (s1, c1) = one(1);
    (narrow([s0, s1]), narrow([c0, c1]))
}

#[cfg(test)]
mod tests {
    use super::super::LANES;
    use super::*;

    /// Every 7th `f32` of `[0, 2π]` and of `[−π/4, −0]` (about 154 + 151
    /// million values), `2π` as `f32` and its neighbours, and the branch
    /// thresholds ± 2 ulp (`−π/4` and `−2⁻¹²` too).
    #[test]
    fn sincosf_is_libm_bit_for_bit() {
        let check = |xs: &[f32; LANES]| {
            let (s, c) = sincosf(Vf::new(*xs));
            let (s, c) = (s.to_array(), c.to_array());
            for k in 0..LANES {
                let (ws, wc) = libm::sincosf(xs[k]);
                assert!(
                    ws.to_bits() == s[k].to_bits() && wc.to_bits() == c[k].to_bits(),
                    "sincosf({:e} = {:#x}): libm ({ws:e}, {wc:e}), vector ({:e}, {:e})",
                    xs[k],
                    xs[k].to_bits(),
                    s[k],
                    c[k]
                );
            }
        };
        let mut specials = std::vec![-0.0f32, 0.0, core::f32::consts::TAU, 1e-45, f32::MIN_POSITIVE];
        for bits in [0xb980_0000u32, 0xbf49_0fda] {
            for d in -2i32..=0 {
                specials.push(f32::from_bits(bits.wrapping_add_signed(d)));
            }
        }
        for bits in [
            0x3980_0000u32,
            0x3f49_0fda,
            0x4016_cbe3,
            0x407b_53d1,
            0x40af_eddf,
            0x40c9_0fdb,
        ] {
            for d in -2i32..=2 {
                specials.push(f32::from_bits(bits.wrapping_add_signed(d)));
            }
        }
        crate::simd::check_values(&check, &specials);
        // [0, 2π] and [−π/4, −0] (sign bit set; −π/4 rounded down in
        // magnitude, libm's threshold `0x3f490fda`).
        crate::simd::sweep(
            &check,
            &[
                (0, core::f32::consts::TAU),
                (0x8000_0000, f32::from_bits(0x3f49_0fda)),
            ],
        );
    }

    extern crate std;
}
