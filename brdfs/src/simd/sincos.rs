//! [`radiometry::math::sincos_turn`] lane-wise, bit for bit: the sine and
//! cosine of `t` full turns (`φ = 2π u` of the samplers, the concentric
//! map's angles `θ/2π`).

use super::{Vf, Vi, from_bits, to_bits};
use radiometry::math::{COS_TAYLOR, SIN_TAYLOR, TURN_SHIFTER};

/// `(sin 2πt, cos 2πt)` lane-wise, **bit for bit**
/// [`radiometry::math::sincos_turn`] (the same `f32` operations in the same
/// order, no FMA; the quadrant's swap and signs as selects and sign-bit
/// flips):
///
/// ```text
/// x = 4t,  q = round(x),  k = q mod 4,  r = (π/2)(x − q)
/// sin r ≈ r + r³ P(r²),  cos r ≈ 1 + r² Q(r²)   (Taylor, to r⁹ and r¹⁰)
/// (sin, cos)(2πt) = (s, c), (c, −s), (−s, −c), (−c, s)  for k = 0, 1, 2, 3
/// ```
///
/// Domain `|t| < 2²⁰` (the callers pass `t ∈ [−1, 1]`), within `10⁻⁷` of
/// the exact values. Unit test `sincos_turn_is_the_scalar_bit_for_bit`:
/// every 7th `f32` of `[−1, 1]`.
#[inline(always)]
pub(crate) fn sincos_turn(t: Vf) -> (Vf, Vf) {
    let x = Vf::splat(4.0) * t;
    let shifted = x + Vf::splat(TURN_SHIFTER);
    let q = shifted - Vf::splat(TURN_SHIFTER);
    let k = to_bits(shifted) & Vi::splat(3);
    let r = (x - q) * Vf::splat(core::f32::consts::FRAC_PI_2);
    let z = r * r;
    let s = SIN_TAYLOR.map(Vf::splat);
    let c = COS_TAYLOR.map(Vf::splat);
    let ps = s[0] + z * (s[1] + z * (s[2] + z * s[3]));
    let pc = c[0] + z * (c[1] + z * (c[2] + z * (c[3] + z * c[4])));
    let (sn, cs) = (r + (r * z) * ps, Vf::ONE + z * pc);
    let odd: Vf = wide::bytemuck::cast((k & Vi::splat(1)).simd_eq(Vi::splat(1)));
    let s1 = odd.select(cs, sn);
    let c1 = odd.select(sn, cs);
    (
        from_bits(to_bits(s1) ^ ((k & Vi::splat(2)) << 30_u32)),
        from_bits(to_bits(c1) ^ (((k + Vi::splat(1)) & Vi::splat(2)) << 30_u32)),
    )
}

#[cfg(test)]
mod tests {
    use super::super::LANES;
    use super::*;

    /// Every 7th `f32` of `[−1, 1]` (about 305 million values), the
    /// multiples of an eighth of a turn and their neighbours, and edge
    /// values: the bits of the scalar function in every lane.
    #[test]
    fn sincos_turn_is_the_scalar_bit_for_bit() {
        let check = |ts: &[f32; LANES]| {
            let (s, c) = sincos_turn(Vf::new(*ts));
            let (s, c) = (s.to_array(), c.to_array());
            for k in 0..LANES {
                let (ws, wc) = radiometry::math::sincos_turn(ts[k]);
                assert!(
                    ws.to_bits() == s[k].to_bits() && wc.to_bits() == c[k].to_bits(),
                    "sincos_turn({:e} = {:#x}): scalar ({ws:e}, {wc:e}), vector ({:e}, {:e})",
                    ts[k],
                    ts[k].to_bits(),
                    s[k],
                    c[k]
                );
            }
        };
        let mut specials = std::vec![-0.0f32, 0.0, 1e-45, f32::MIN_POSITIVE, 1.0, -1.0];
        for j in -8..=8 {
            let mut t = j as f32 / 8.0;
            for _ in 0..4 {
                t = t.next_down();
            }
            for _ in 0..9 {
                specials.push(t);
                t = t.next_up();
            }
        }
        crate::simd::check_values(&check, &specials);
        crate::simd::sweep(&check, &[(0, 1.0), (0x8000_0000, 1.0)]);
    }

    extern crate std;
}
