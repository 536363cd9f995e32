//! The fast path of the Beckmann visible-slope sampler (`Beckmann::sample_visible`,
//! Heitz & d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the
//! Distribution of Visible Normals", CGF 33(4), §4.2): the slope `x̃` of the
//! standard (`α = 1`) surface seen at angle θ solves
//!
//! ```text
//! 2C(x̃) = 2u C(b),   2C(x) = c erfc(−x) + s e^{−x²}/√π,   b = min(cot θ, 9)
//! ```
//!
//! (`c = cos θ`, `s = sin θ`), for `u ∈ [U_LO, U_HI] = [2⁻²⁰, 1 − 2⁻¹⁰]` in
//! `f32` without `f64` and without a data-dependent branch:
//!
//! 1. **Start**: bilinear interpolation in a table of the exact quantile
//!    (`beckmann_slope_table.rs`, 33 × 41 nodes, written by
//!    `brdfs/tools/beckmann_slope_table.py`) over `β = c/(c + s) ∈ [0, 1]`
//!    and the logit `t = log2(u/(1 − u)) ∈ [−20, 10]`, in which the quantile
//!    is smooth (Gaussian at β = 1, `−√(−ln u)` at β = 0, `∓√|t|`-like
//!    tails). `log2` is the exponent bits plus a degree-5 polynomial
//!    (1.7·10⁻⁵). Worst start error `|C(x₀)/C(b) − u|` = 2.0·10⁻³.
//! 2. **One Halley step** on `r(x) = 2C(x) − 2uC(b)`, evaluated without
//!    cancellation on both sides of 0 with `erfcx(|x|)`:
//!    `r = K + e^{−x²}(s/√π ± c erfcx(|x|))` with `K = −2uC(b)` (`x ≤ 0`,
//!    `+`) or `K = 2(1 − u)C(b) − E` (`x > 0`, `−`), `E = 2C(b) − 2c`; with
//!    `r' = 2(c − xs)e^{−x²}/√π`, `r'' = −2e^{−x²}(s + 2x(c − xs))/√π` the step
//!    `x − r/r' / (1 − r r''/(2r'²))` over a common denominator is
//!    `x − 2r√π d / (4d²e^{−x²} + r√π(s + 2xd))`, `d = c − xs` (one division).
//!
//! Everything is homogeneous of degree 0 in `(c, s)`, so the sampler takes
//! the unnormalised `(|ω_z|, α|ω_xy|)` of the stretched direction.
//! `2C(b) = 2c + E` with `E = 2s·aΛ(a)`, `a = cot θ`, the fitted `f32`
//! rational of `beckmann_f32` (the projected area of the standard surface;
//! `E = 0` beyond `a = 3.5`, where it is below `2⁻²⁶ c`).
//!
//! Accuracy of the scheme in exact arithmetic (`beckmann_slope_table.py
//! --sweep`, 2·10⁵ (θ, u) including grazing, near-normal and both ends of the
//! range): `|C(x̃)/C(b) − u| ≤ 1.6·10⁻⁸`, and relative to the tail mass
//! `min(u, 1 − u)` ≤ 1.2·10⁻⁶ (the two-Halley-step tail scheme: 6.3·10⁻⁹
//! and 1.7·10⁻⁴ over its wider range; both absolute figures are far below
//! the `f32` spacing of `u`, 6·10⁻⁸ near 1). In `f32`
//! the unit tests measure it against the `f64` CDF (`fast_slope_matches_f64`).
//! Outside `[U_LO, U_HI]` the caller uses the tail scheme
//! (`Beckmann::sample_slope_x`).

use super::beckmann_f32::{AREA_CUT, F32Arith, a_lambda_rational, exp_neg};
use super::beckmann_slope_table::{LOG2_POLY, NB, NT, T_HI, T_LO, TABLE};
use super::special::{ERFCX_P, ERFCX_Q, FRAC_1_SQRT_PI, MAX_SLOPE, SQRT_PI};

/// Lowest `u` of the fast path, `2⁻²⁰` (logit `t ≥ −20`).
pub(crate) const U_LO: f32 = 9.536_743e-7;
/// Highest `u` of the fast path, `1 − 2⁻¹⁰` (logit `t < 10`).
pub(crate) const U_HI: f32 = 0.999_023_44;

/// Whether `u` (already in `[0, 1]`) takes the fast path.
#[inline(always)]
pub(crate) fn in_fast_range(u: f32) -> bool {
    (U_LO..=U_HI).contains(&u)
}

/// `erfcx(y) = e^{y²} erfc(y)` for `0 ≤ y ≤ 10` in `f32`: the degree-4/5
/// rational of `special::ERFCX_P/ERFCX_Q` (own fit, 5.7·10⁻⁹ relative)
/// with its coefficients rounded to `f32`, Estrin in `f32`. ≤ 6 ulp (measured 4.8; unit
/// test `erfcx32_matches_f64`).
#[inline(always)]
pub(crate) fn erfcx32<T: F32Arith>(y: T) -> T {
    let k = |c: f64| T::splat(c as f32);
    let (p, q) = (&ERFCX_P, &ERFCX_Q);
    // Estrin's scheme (shorter dependency chain than Horner).
    let y2 = y * y;
    let y4 = y2 * y2;
    let num = (k(p[0]) + k(p[1]) * y) + y2 * (k(p[2]) + k(p[3]) * y) + y4 * k(p[4]);
    let den = (k(q[0]) + k(q[1]) * y) + y2 * (k(q[2]) + k(q[3]) * y) + y4 * (k(q[4]) + k(q[5]) * y);
    num / den
}

/// `e + f·P(f)` with `P` the `log2(1 + f)/f` polynomial (`LOG2_POLY`,
/// 1.7·10⁻⁵ absolute): `log2` of `2^e (1 + f)`.
#[inline(always)]
pub(crate) fn log2_poly<T: F32Arith>(e: T, f: T) -> T {
    let k = |i: usize| T::splat(LOG2_POLY[i]);
    let p = (((k(4) * f + k(3)) * f + k(2)) * f + k(1)) * f + k(0);
    e + f * p
}

/// `2⁻²³·(1.5·2²³ + n)`-style exact conversion constant: `from_bits(0x4b00_0000 | n) − 2²³ = n`.
pub(crate) const TWO_23: f32 = 8_388_608.0;

/// `log2 q` (to 1.7·10⁻⁵) for a positive normal `f32` `q`: the exponent
/// from the bits (converted exactly through `2²³`), the mantissa by
/// [`log2_poly`]. Other input gives an unspecified finite or NaN value.
#[inline(always)]
fn log2_pos(q: f32) -> f32 {
    let bits = q.to_bits();
    let e = f32::from_bits(0x4b00_0000 | (bits >> 23)) - (TWO_23 + 127.0);
    let f = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000) - 1.0;
    log2_poly(e, f)
}

/// `(fi, fj)`: the fractional table coordinates of `β = c/(c + s)` and
/// `t = clamp(log2(u/(1 − u)), T_LO, T_HI)` (generic arithmetic part).
#[inline(always)]
fn coords<T: F32Arith>(beta: T, t: T) -> (T, T) {
    (
        beta * T::splat((NB - 1) as f32),
        (t - T::splat(T_LO)) * T::splat((NT - 1) as f32 / (T_HI - T_LO)),
    )
}

/// The index of the table cell and its four corners for fractional
/// coordinates `(fi, fj)` (clamped to the table; NaN counts as 0).
#[inline(always)]
fn corners(fi: f32, fj: f32) -> (f32, f32, [f32; 4]) {
    let i = (fi as usize).min(NB - 2);
    let j = (fj as usize).min(NT - 2);
    let k = i * NT + j;
    let t = &TABLE;
    (i as f32, j as f32, [t[k], t[k + 1], t[k + NT], t[k + NT + 1]])
}

/// Bilinear interpolation of the corners `[x00, x01, x10, x11]` with
/// weights `a` (along β) and `w` (along t).
#[inline(always)]
fn bilinear<T: F32Arith>(a: T, w: T, c: [T; 4]) -> T {
    let lo = c[0] + w * (c[1] - c[0]);
    let hi = c[2] + w * (c[3] - c[2]);
    lo + a * (hi - lo)
}

/// `(E, 2C(b))` for the unnormalised `(c, s)`: `E = 2s·aΛ(a)`, `a = c/s`,
/// `0` for `a ≥ AREA_CUT` (also `s = 0`).
#[inline(always)]
fn totals(c: f32, s: f32) -> (f32, f32, f32) {
    let a = c / s;
    // Branch-free (θ decides, unpredictably): the rational of a clamped `a`.
    let r = a_lambda_rational(a.min(AREA_CUT));
    let e = if a < AREA_CUT { 2.0 * s * r } else { 0.0 };
    (a, e, 2.0 * c + e)
}

/// The Halley step `x − 2r√π d/(4d²e^{−x²} + r√π(s + 2xd))`,
/// `r = k + e^{−x²} h`, `d = c − xs` (see the module documentation).
#[inline(always)]
fn halley<T: F32Arith>(c: T, s: T, x: T, e: T, k: T, h: T) -> T {
    let two = T::splat(2.0);
    let r = k + e * h;
    let d = c - x * s;
    let rp = r * T::splat(SQRT_PI);
    let den = T::splat(4.0) * d * d * e + rp * (s + two * x * d);
    x - two * rp * d / den
}

/// The visible slope `x̃` for `u ∈ [U_LO, U_HI]` (see the module
/// documentation) from the unnormalised `c = |ω_z| ≥ 0`, `s = α|ω_xy| ≥ 0`,
/// `c + s > 0`; in `[−MAX_SLOPE, min(c/s, MAX_SLOPE)]`, never NaN.
#[inline(always)]
pub(crate) fn slope_x(c: f32, s: f32, u: f32) -> f32 {
    let (a, e_b, total2) = totals(c, s);
    let b = a.min(MAX_SLOPE);
    let beta = c / (c + s);
    // max/min rather than clamp: panic-free, NaN → T_LO (as the lanes).
    #[allow(clippy::manual_clamp)]
    let t = log2_pos(u / (1.0 - u)).max(T_LO).min(T_HI);
    let (fi, fj) = coords(beta, t);
    let (i, j, cs) = corners(fi, fj);
    let x = bilinear(fi - i, fj - j, cs);
    let lower = x <= 0.0;
    let e = exp_neg(x * x);
    let cx = c * erfcx32(x.abs());
    let sf = s * FRAC_1_SQRT_PI;
    let (k, h) = if lower {
        (-u * total2, sf + cx)
    } else {
        ((1.0 - u) * total2 - e_b, sf - cx)
    };
    let x1 = halley(c, s, x, e, k, h);
    // max/min absorb NaN (`f32::max` returns the other operand); `+ 0`
    // makes a zero `+0` (as the tail scheme).
    #[allow(clippy::manual_clamp)]
    let x1 = x1.max(-MAX_SLOPE).min(b);
    x1 + 0.0
}

/// The vector form of [`slope_x`] (feature `simd`), lane for lane the same
/// operations (bit-identical): the table corners are gathered per lane.
#[cfg(feature = "simd")]
pub(crate) mod lanes {
    use super::*;
    use crate::simd::{LANES, Vf};

    /// The `i32` vector of the width of `Vf`.
    #[cfg(target_feature = "avx512f")]
    type Vi = wide::i32x16;
    #[cfg(not(target_feature = "avx512f"))]
    type Vi = wide::i32x8;
    // The two widths are chosen by separate `cfg`s: the build fails if they disagree.
    const _: () = assert!(core::mem::size_of::<Vi>() == core::mem::size_of::<Vf>());

    /// [`log2_pos`] lane-wise.
    #[inline(always)]
    fn log2_pos_v(q: Vf) -> Vf {
        let bits: Vi = wide::bytemuck::cast(q);
        let ebits: Vf = wide::bytemuck::cast((bits >> 23_i32) | Vi::splat(0x4b00_0000));
        let e = ebits - Vf::splat(TWO_23 + 127.0);
        let m: Vf = wide::bytemuck::cast((bits & Vi::splat(0x007f_ffff)) | Vi::splat(0x3f80_0000));
        log2_poly(e, m - Vf::ONE)
    }

    /// [`slope_x`] lane-wise (every lane computed; the caller selects the
    /// lanes with `u ∈ [U_LO, U_HI]`).
    #[inline(always)]
    pub(crate) fn slope_x_v(c: Vf, s: Vf, u: Vf) -> Vf {
        let zero = Vf::ZERO;
        let a = c / s;
        let inside = a.simd_lt(Vf::splat(AREA_CUT));
        let r = a_lambda_rational(a.min(Vf::splat(AREA_CUT)));
        let e_b = inside.select(Vf::splat(2.0) * s * r, zero);
        let total2 = Vf::splat(2.0) * c + e_b;
        let b = a.min(Vf::splat(MAX_SLOPE));
        let beta = c / (c + s);
        let t = log2_pos_v(u / (Vf::ONE - u))
            .max(Vf::splat(T_LO))
            .min(Vf::splat(T_HI));
        let (fi, fj) = coords(beta, t);
        let (fia, fja) = (fi.to_array(), fj.to_array());
        let mut ii = [0.0f32; LANES];
        let mut jj = [0.0f32; LANES];
        let mut cs = [[0.0f32; LANES]; 4];
        for l in 0..LANES {
            let (i, j, c4) = corners(fia[l], fja[l]);
            ii[l] = i;
            jj[l] = j;
            for q in 0..4 {
                cs[q][l] = c4[q];
            }
        }
        let x = bilinear(
            fi - Vf::new(ii),
            fj - Vf::new(jj),
            [Vf::new(cs[0]), Vf::new(cs[1]), Vf::new(cs[2]), Vf::new(cs[3])],
        );
        let lower = x.simd_le(zero);
        let e = exp_neg(x * x);
        let cx = c * erfcx32(x.abs());
        let sf = s * Vf::splat(FRAC_1_SQRT_PI);
        let k = lower.select(-u * total2, (Vf::ONE - u) * total2 - e_b);
        let h = lower.select(sf + cx, sf - cx);
        let x1 = halley(c, s, x, e, k, h);
        // `f32::max(NaN, m) = m`: NaN lanes become −MAX_SLOPE as in the scalar.
        let x1 = x1
            .is_nan()
            .select(Vf::splat(-MAX_SLOPE), x1.max(Vf::splat(-MAX_SLOPE)));
        x1.min(b) + zero
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// `2C(x)` in `f64` from libm's `erfc` (the closed form of the CDF,
    /// independent of the code under test).
    fn cdf2(c: f64, s: f64, x: f64) -> f64 {
        c * libm::erfc(-x) + s * libm::exp(-x * x) / core::f64::consts::PI.sqrt()
    }

    fn ulps(v: f32, r: f64) -> f64 {
        let e = libm::floor(libm::log2(r.abs().max(f32::MIN_POSITIVE as f64)));
        (v as f64 - r).abs() / libm::exp2(e - 23.0)
    }

    #[test]
    fn erfcx32_matches_f64() {
        let mut worst = 0.0f64;
        for i in 0..=200_000 {
            let y = i as f32 * (10.0 / 200_000.0);
            let y64 = y as f64;
            // e^{y²} erfc(y) in f64 (fine for y ≤ 10: erfc(10) ≈ 2·10⁻⁴⁵ is
            // a normal f64 with full relative accuracy).
            let r = libm::exp(y64 * y64) * libm::erfc(y64);
            let e = ulps(erfcx32(y), r);
            worst = worst.max(e);
            assert!(e <= 6.0, "erfcx32({y}) = {} vs {r} ({e:.2} ulp)", erfcx32(y));
        }
        std::println!("erfcx32: worst {worst:.2} ulp");
    }

    #[test]
    fn log2_pos_matches_libm() {
        let mut q = 1e-7f32;
        while q < 2e3 {
            let r = libm::log2(q as f64);
            assert!(
                (log2_pos(q) as f64 - r).abs() < 2e-5,
                "log2({q}) = {} vs {r}",
                log2_pos(q)
            );
            q *= 1.0007;
        }
    }

    /// The fast path against the `f64` CDF over θ (uniform, and geometric
    /// towards both ends) and `u` over the whole fast range (uniform and
    /// geometric towards both ends): `|C(x̃)/C(b) − u|` within 4 of the
    /// resolution units of `slope_inversion_reproduces_u` (`C'(x)·ulp(x)`
    /// plus `4ε`), in range, never NaN; and relative to the tail mass
    /// within `10⁻⁵` where the tail mass is `≥ 10⁻⁴`-resolved.
    #[test]
    fn fast_slope_matches_f64() {
        let mut thetas: std::vec::Vec<f64> = (0..=96)
            .map(|k| k as f64 / 96.0 * core::f64::consts::FRAC_PI_2)
            .collect();
        let mut t = 1e-7f64;
        while t < 0.3 {
            thetas.push(t);
            thetas.push(core::f64::consts::FRAC_PI_2 - t);
            t *= 3.0;
        }
        let mut us: std::vec::Vec<f32> = (1..2000).map(|i| i as f32 / 2000.0).collect();
        let mut v = U_LO;
        while v < 0.5 {
            us.push(v);
            us.push(1.0 - v);
            v *= 1.5;
        }
        us.extend([U_LO, U_HI, U_LO.next_up(), U_HI.next_down()]);
        us.retain(|&u| in_fast_range(u));
        let (mut worst, mut worst_rel) = (0.0f64, 0.0f64);
        for &theta in &thetas {
            for &alpha in &[1.0f32, 0.3] {
                // The unnormalised inputs the sampler gets: (|ω_z|, α|ω_xy|).
                let (c, s) = (libm::cos(theta) as f32, alpha * libm::sin(theta) as f32);
                let (c64, s64) = (c as f64, s as f64);
                let n = (c64 * c64 + s64 * s64).sqrt();
                let (cn, sn) = (c64 / n, s64 / n);
                let b = if s64 * 9.0 <= c64 { 9.0 } else { c64 / s64 };
                let total = cdf2(cn, sn, b);
                for &u in &us {
                    let x = slope_x(c, s, u);
                    assert!(
                        x.is_finite() && x >= -MAX_SLOPE && x as f64 <= b + 1e-6,
                        "θ={theta} u={u}: {x}"
                    );
                    let got = cdf2(cn, sn, x as f64) / total;
                    let dens = 2.0 * (cn - x as f64 * sn).max(0.0) * libm::exp(-(x as f64).powi(2))
                        / core::f64::consts::PI.sqrt()
                        / total;
                    let eps = f32::EPSILON as f64;
                    let unit = dens * (x.abs().max(1e-3) as f64) * eps * 4.0 + 4.0 * eps;
                    let err = (got - u as f64).abs();
                    worst = worst.max(err / unit);
                    assert!(
                        err < 4.0 * unit,
                        "θ={theta} α={alpha} u={u}: x={x}, C/C(b)={got} ({} units)",
                        err / unit
                    );
                    let tail = (u as f64).min(1.0 - u as f64);
                    // Relative to the tail mass where f32 resolves it to 10⁻⁵
                    // (the lower tail; 1 − u carries u's absolute rounding).
                    if u < 0.5 {
                        let rel = err / tail;
                        worst_rel = worst_rel.max(rel);
                        assert!(
                            rel < 1e-5 + 8.0 * unit / tail,
                            "θ={theta} u={u}: tail-relative {rel}"
                        );
                    }
                }
            }
        }
        std::println!(
            "fast Beckmann slope: worst {worst:.2} resolution units, lower-tail relative {worst_rel:.2e}"
        );
    }

    /// The vector form is the scalar one bit for bit.
    #[cfg(feature = "simd")]
    #[test]
    fn lanes_are_scalar_bit_for_bit() {
        use crate::simd::{LANES, Vf};
        let mut pts = std::vec::Vec::new();
        for k in 0..=64 {
            let theta = k as f64 / 64.0 * core::f64::consts::FRAC_PI_2;
            for &alpha in &[1e-4f32, 0.3, 1.0] {
                let (c, s) = (libm::cos(theta) as f32, alpha * libm::sin(theta) as f32);
                for i in 0..=300 {
                    let u = U_LO + (U_HI - U_LO) * (i as f32 / 300.0);
                    pts.push((c, s, u));
                }
                pts.push((c, s, U_LO));
                pts.push((c, s, U_HI));
            }
        }
        pts.push((0.0, 1.0, 0.5));
        pts.push((1.0, 0.0, 0.5));
        for chunk in pts.chunks(LANES) {
            let mut c = [1.0f32; LANES];
            let mut s = [0.0f32; LANES];
            let mut u = [0.5f32; LANES];
            for (k, &(ck, sk, uk)) in chunk.iter().enumerate() {
                c[k] = ck;
                s[k] = sk;
                u[k] = uk;
            }
            let v = lanes::slope_x_v(Vf::new(c), Vf::new(s), Vf::new(u)).to_array();
            for k in 0..LANES {
                assert_eq!(
                    v[k].to_bits(),
                    slope_x(c[k], s[k], u[k]).to_bits(),
                    "{} {} {}",
                    c[k],
                    s[k],
                    u[k]
                );
            }
        }
    }
}
