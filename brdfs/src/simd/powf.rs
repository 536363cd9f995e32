//! `powf` lane-wise for a lane-constant exponent, bit for bit with
//! `libm::powf`.

use super::Vf;
use super::bits::*;

/// `libm::powf(x, y)` lane-wise, **bit for bit**, for a lane-constant
/// exponent `y` (a port of libm's algorithm, FreeBSD `e_powf.c`, restricted
/// to `x ≥ 0` — negative `x` lanes are unspecified):
///
/// * the scalar special cases of `y` first (`y = 0`: 1; `y = ±1`: `x`,
///   `1/x`; `y = 2`: `x·x`; `y = 1/2`: `√x`), and `x ∈ {0, 1, +∞}`, NaN;
/// * otherwise `log2 x = n + log2(1 + f)` from the bits of `x` (subnormal `x`
///   prescaled by `2²⁴`), `1 + f` reduced around 1 or 1.5, the odd series in
///   `s = (x − bp)/(x + bp)`, carried as a head with 12 trailing zero bits
///   and a tail; `y log2 x` likewise as `p_h + p_l`; overflow to `+∞` and
///   underflow to 0 by libm's tests; `2^{p_h + p_l}` from an integer part
///   (integer operations on the bits) and the Remez polynomial of
///   `exp`, scaled by `2^n` (`scalbnf` where the result is subnormal).
///
/// Exponents that are not finite or exceed `2²⁷` in magnitude (libm's
/// `|1 − x|`-series branch) go through `libm::powf` per lane. The unit test
/// `powf_is_libm_bit_for_bit` compares with `libm::powf` on every 7th `f32`
/// of `(0, 1]` for several `y` and on a sparser grid up to `f32::MAX`.
#[inline(always)]
pub(crate) fn powf(x: Vf, y: f32) -> Vf {
    const DP_H1: f32 = f32::from_bits(0x3f15_c000); // 5.84960938e-01
    const DP_L1: f32 = f32::from_bits(0x35d1_cfdc); // 1.56322085e-06
    const L1: f32 = f32::from_bits(0x3f19_999a);
    const L2: f32 = f32::from_bits(0x3edb_6db7);
    const L3: f32 = f32::from_bits(0x3eaa_aaab);
    const L4: f32 = f32::from_bits(0x3e8b_a305);
    const L5: f32 = f32::from_bits(0x3e6c_3255);
    const L6: f32 = f32::from_bits(0x3e53_f142);
    const P1: f32 = f32::from_bits(0x3e2a_aaab);
    const P2: f32 = f32::from_bits(0xbb36_0b61);
    const P3: f32 = f32::from_bits(0x388a_b355);
    const P4: f32 = f32::from_bits(0xb5dd_ea0e);
    const P5: f32 = f32::from_bits(0x3331_bb4c);
    const LG2: f32 = f32::from_bits(0x3f31_7218);
    const LG2_H: f32 = f32::from_bits(0x3f31_7200);
    const LG2_L: f32 = f32::from_bits(0x35bf_be8c);
    const OVT: f32 = 4.299_566_6e-8; // −(128 − log2(ovfl + ½ulp))
    const CP: f32 = f32::from_bits(0x3f76_384f); // 2/(3 ln 2)
    const CP_H: f32 = f32::from_bits(0x3f76_4000);
    const CP_L: f32 = f32::from_bits(0xb8f6_23c6);
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let si = |v: i32| Vi::splat(v);
    // The scalar branches on y, in libm's order (x = 1 gives 1 in each).
    if y == 0.0 {
        return one;
    }
    if y.is_nan() || y.abs() > 134_217_728.0 {
        let xs = x.to_array();
        return Vf::new(core::array::from_fn(|k| libm::powf(xs[k], y)));
    }
    if y == 1.0 {
        return x;
    }
    if y == -1.0 {
        return one / x;
    }
    if y == 2.0 {
        return x * x;
    }
    if y == 0.5 {
        return x.sqrt();
    }
    // log2 x = n + log2(ax), ax ∈ [√2/2·…, …) around bp ∈ {1, 1.5}.
    let ix0 = to_bits(x);
    let sub = ix0.simd_lt(si(0x0080_0000));
    let ix1 = to_bits(fmask(sub).select(x * Vf::splat(16_777_216.0), x));
    let jm = ix1 & si(0x007f_ffff);
    let k1 = jm.simd_gt(si(0x001c_c471)) & jm.simd_lt(si(0x005d_b3d7));
    let k_up = !jm.simd_lt(si(0x005d_b3d7));
    let n = sub.select(si(-24), si(0)) + ((ix1 >> 23_u32) - si(0x7f)) + k_up.select(si(1), si(0));
    let ix = (jm | si(0x3f80_0000)) - k_up.select(si(0x0080_0000), si(0));
    let ax = from_bits(ix);
    let k1f = fmask(k1);
    let bp = k1f.select(Vf::splat(1.5), one);
    let dp_h = k1f.select(Vf::splat(DP_H1), zero);
    let dp_l = k1f.select(Vf::splat(DP_L1), zero);
    let u = ax - bp;
    let v = one / (ax + bp);
    let s = u * v;
    let s_h = clear_low(s, 0xffff_f000);
    let t_h = from_bits(
        (((ix >> 1_u32) & si(0xffff_f000_u32 as i32)) | si(0x2000_0000))
            + si(0x0040_0000)
            + k1.select(si(1 << 21), si(0)),
    );
    let t_l = ax - (t_h - bp);
    let s_l = v * ((u - s_h * t_h) - s_h * t_l);
    let s2 = s * s;
    let sp = |c: f32| Vf::splat(c);
    let r = s2 * s2 * (sp(L1) + s2 * (sp(L2) + s2 * (sp(L3) + s2 * (sp(L4) + s2 * (sp(L5) + s2 * sp(L6))))));
    let r = r + s_l * (s_h + s);
    let s2 = s_h * s_h;
    let three = sp(3.0);
    let t_h = clear_low(three + s2 + r, 0xffff_f000);
    let t_l = r - ((t_h - three) - s2);
    let u = s_h * t_h;
    let v = s_l * t_h + t_l * s;
    let p_h = clear_low(u + v, 0xffff_f000);
    let p_l = v - (p_h - u);
    let z_h = sp(CP_H) * p_h;
    let z_l = sp(CP_L) * p_h + p_l * sp(CP) + dp_l;
    let t = int_to_float(n);
    let t1 = clear_low(((z_h + z_l) + dp_h) + t, 0xffff_f000);
    let t2 = z_l - (((t1 - t) - dp_h) - z_h);
    // y log2 x = p_h + p_l with y split as y1 (12 trailing zero bits) + rest.
    let y1 = f32::from_bits(y.to_bits() & 0xffff_f000);
    let p_l = sp(y - y1) * t1 + sp(y) * t2;
    let p_h = sp(y1) * t1;
    let z = p_l + p_h;
    let j = to_bits(z);
    let at_max = j.simd_eq(si(0x4300_0000));
    let over = fmask(j.simd_gt(si(0x4300_0000))) | (fmask(at_max) & (p_l + sp(OVT)).simd_gt(z - p_h));
    let under = fmask(j.simd_lt(si(0)) & (j & si(0x7fff_ffff)).simd_gt(si(0x4316_0000)))
        | (fmask(j.simd_eq(si(0xc316_0000_u32 as i32))) & p_l.simd_le(z - p_h));
    // 2^z: integer part n (nearest) from the bits of z, fraction by the
    // Remez polynomial.
    let i = j & si(0x7fff_ffff);
    let k = (i >> 23_u32) - si(0x7f);
    let big = i.simd_gt(si(0x3f00_0000));
    let nn = j + shr_var(si(0x0080_0000), k + si(1));
    let k = ((nn & si(0x7fff_ffff)) >> 23_u32) - si(0x7f);
    let tt = from_bits(nn & !shr_var(si(0x007f_ffff), k));
    let nn = shr_var((nn & si(0x007f_ffff)) | si(0x0080_0000), si(23) - k);
    let nn = j.simd_lt(si(0)).select(si(0) - nn, nn);
    let n = big.select(nn, si(0));
    let p_h = fmask(big).select(p_h - tt, p_h);
    let t = clear_low(p_l + p_h, 0xffff_8000);
    let u = t * sp(LG2_H);
    let v = (p_l - (t - p_h)) * sp(LG2) + t * sp(LG2_L);
    let z = u + v;
    let w = v - (z - u);
    let t = z * z;
    let t1 = z - t * (sp(P1) + t * (sp(P2) + t * (sp(P3) + t * (sp(P4) + t * sp(P5)))));
    let r = (z * t1) / (t1 - sp(2.0)) - (w + z * w);
    let z = one - (r - z);
    let jz = to_bits(z) + (n << 23_u32);
    let normal = fmask((jz >> 23_u32).simd_gt(si(0)));
    let v = normal.select(from_bits(jz), scalbnf(z, int_to_float(n)));
    let v = over.select(sp(f32::INFINITY), under.select(zero, v));
    // x ∈ {0, 1, +∞} (libm returns |x| for y > 0, 1/|x| for y < 0), NaN.
    let v = x.simd_eq(one).select(one, v);
    let edge = x.simd_eq(zero) | x.simd_eq(sp(f32::INFINITY));
    let v = edge.select(if y > 0.0 { x } else { one / x }, v);
    x.is_nan().select(x, v)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::simd::{LANES, sweep, sweep_stride};

    /// `powf` equals `libm::powf` bit for bit: every 7th `f32` of `(0, 1]`
    /// for `y = 30`, every 61st for 0.3 and 10⁷, every 997th one of
    /// `(0, f32::MAX]` for more exponents (including subnormal and overflowing
    /// results and libm's special exponents), and the special values of `x`.
    #[test]
    fn powf_is_libm_bit_for_bit() {
        let check_y = |y: f32| {
            move |xs: &[f32; LANES]| {
                let got = powf(Vf::new(*xs), y).to_array();
                for (x, g) in xs.iter().zip(got) {
                    let want = libm::powf(*x, y);
                    assert!(
                        want.to_bits() == g.to_bits() || (want.is_nan() && g.is_nan()),
                        "powf({x:e} = {:#x}, {y:e}): libm {want:e}, vector {g:e}",
                        x.to_bits()
                    );
                }
            }
        };
        sweep(&check_y(30.0), &[(0, 1.0)]);
        for y in [0.3f32, 1e7] {
            sweep_stride(&check_y(y), &[(0, 1.0)], 61);
        }
        let ys = [
            0.0f32,
            1e-30,
            0.001,
            0.5,
            1.0,
            1.5,
            2.0,
            2.5,
            7.25,
            100.0,
            1000.0,
            1e5,
            1.3e8,
            2e8,
            -0.5,
            -1.0,
            -2.0,
            -3.7,
            f32::INFINITY,
        ];
        let xs_special = [
            0.0f32,
            f32::MIN_POSITIVE,
            1e-45,
            1.0,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
            0.5,
            2.0,
        ];
        for y in ys {
            let check = check_y(y);
            let mut xs = [0.75f32; LANES];
            xs[..xs_special.len().min(LANES)].copy_from_slice(&xs_special[..xs_special.len().min(LANES)]);
            check(&xs);
            let mut n = 0;
            let mut bits = 1u32;
            while bits < 0x7f80_0000 {
                xs[n] = f32::from_bits(bits);
                n += 1;
                if n == LANES {
                    check(&xs);
                    n = 0;
                }
                bits += 997;
            }
        }
    }
}
