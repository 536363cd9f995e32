//! Small numerical helpers shared by the crate and by plugins.
//!
//! All functions are total on finite input: they return finite values and
//! never panic. `f32` functions use `libm`, so they are identical with and
//! without `std`.

/// `√x` with IEEE 754 rounding: bit for bit `libm::sqrtf` (NaN for `x < 0`,
/// `±0`, `+∞` and NaN pass through), compiled to the target's own
/// square-root instruction in the target's own encoding.
///
/// On x86 `libm::sqrtf` is inline assembly of the legacy-SSE `sqrtss`. In a
/// build with AVX enabled (`-C target-cpu=native`, `x86-64-v3`) the compiler
/// encodes everything else as VEX, and on Intel cores each legacy-SSE
/// instruction that runs while the upper halves of the vector registers are
/// dirty pays an SSE/AVX transition: OpenPBR's `sample`, whose draw takes
/// three roots after vector code, ran 3× slower in such a build on an Intel
/// Xeon than in the portable one (`docs/performance.md`). Here x86 goes through
/// `_mm_sqrt_ss` (via `safe_arch`) where AVX is on, which the compiler encodes
/// as `vsqrtss`; without AVX (the portable x86-64 build, where every
/// instruction is legacy SSE) and on other targets it calls `libm::sqrtf`.
///
/// ```
/// use radiometry::math::sqrtf;
/// assert_eq!(sqrtf(2.25), 1.5);
/// assert_eq!(sqrtf(2.0).to_bits(), libm::sqrtf(2.0).to_bits());
/// assert!(sqrtf(-1.0).is_nan());
/// ```
#[inline(always)]
pub fn sqrtf(x: f32) -> f32 {
    #[cfg(all(any(target_arch = "x86", target_arch = "x86_64"), target_feature = "avx"))]
    {
        safe_arch::get_f32_from_m128_s(safe_arch::sqrt_m128_s(safe_arch::set_m128_s(x)))
    }
    #[cfg(not(all(any(target_arch = "x86", target_arch = "x86_64"), target_feature = "avx")))]
    {
        libm::sqrtf(x)
    }
}

/// `sqrt(max(x, 0))`: a square root that returns 0 instead of NaN for
/// slightly negative arguments produced by rounding.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    sqrtf(x.max(0.0))
}

/// `acos` with its argument clamped to `[-1, 1]`.
#[inline]
pub fn safe_acos(x: f32) -> f32 {
    libm::acosf(x.clamp(-1.0, 1.0))
}

/// `asin` with its argument clamped to `[-1, 1]`.
#[inline]
pub fn safe_asin(x: f32) -> f32 {
    libm::asinf(x.clamp(-1.0, 1.0))
}

/// Clamps a sample coordinate into `[0, 1]`, mapping NaN to `0`.
///
/// Used by every warp and sampler so that any `u`, including NaN and values
/// outside the unit interval, maps to a point of the closed domain.
///
/// ```
/// use radiometry::math::clamp01;
/// assert_eq!(clamp01(f32::NAN), 0.0);
/// assert_eq!(clamp01(1.5), 1.0);
/// assert_eq!(clamp01(0.25), 0.25);
/// ```
#[inline]
pub fn clamp01(u: f32) -> f32 {
    if u > 0.0 { u.min(1.0) } else { 0.0 }
}

/// `x.clamp(lo, hi)` without its `lo ≤ hi` assertion: the same two comparisons, so the same result
/// (NaN stays NaN, a signed zero is kept) whenever `lo ≤ hi`, and no panic path when the bounds are
/// run-time values. For `lo > hi` it returns `hi` or `x` (never panics).
#[inline]
pub(crate) fn clamp_to(x: f32, lo: f32, hi: f32) -> f32 {
    let mut x = x;
    if x < lo {
        x = lo;
    }
    if x > hi {
        x = hi;
    }
    x
}

/// `x²`.
#[inline]
pub(crate) fn sqr(x: f32) -> f32 {
    x * x
}

/// The largest `f32` strictly below 1 (`1 − 2⁻²⁴ = 0.99999994`).
///
/// Sample coordinates `u` live in `[0, ONE_MINUS_EPSILON]`.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// `(sin 2πt, cos 2πt)`: the sine and cosine of `t` full turns, the
/// azimuth `φ = 2π u` of every sampler, without forming `2π u` (whose
/// rounding, up to `2.4·10⁻⁷` rad near `2π`, the reduction would keep).
///
/// Branch-free (the quadrant of a random `u` is unpredictable, and the
/// samplers' vector kernels run the same operations lane for lane):
///
/// ```text
/// x = 4t,  q = round(x) (the 1.5·2²³ shifter),  k = q mod 4,  r = (π/2)(x − q) ∈ [−π/4, π/4]
/// sin r ≈ r (1 − r²/3! + r⁴/5! − r⁶/7! + r⁸/9!)                  (remainder < 2·10⁻⁹)
/// cos r ≈ 1 − r²/2! + r⁴/4! − r⁶/6! + r⁸/8! − r¹⁰/10!            (remainder < 2·10⁻¹⁰)
/// (sin, cos)(2πt) = (s, c), (c, −s), (−s, −c), (−c, s)  for k = 0, 1, 2, 3
/// ```
///
/// `x − q` is exact, so the only rounding before the polynomials is that
/// of `r`. Domain: `|t| < 2²⁰` (the samplers pass `t ∈ [−1, 1]`); NaN and
/// infinite `t` give NaN. Accuracy: within `10⁻⁷` (measured 0.91·10⁻⁷) of the exact values
/// (unit test `sincos_turn_matches_f64`), and exactly `(0, 1)` at `t = 0`
/// and `t = 1`.
///
/// ```
/// use radiometry::math::sincos_turn;
/// assert_eq!(sincos_turn(0.0), (0.0, 1.0));
/// assert_eq!(sincos_turn(0.25), (1.0, 0.0));
/// assert_eq!(sincos_turn(1.0), (0.0, 1.0));
/// let (s, c) = sincos_turn(0.1);
/// assert!((s - 0.587_785_25).abs() < 1e-7 && (c - 0.809_017).abs() < 1e-7);
/// ```
#[inline]
pub fn sincos_turn(t: f32) -> (f32, f32) {
    let x = 4.0 * t;
    let shifted = x + TURN_SHIFTER;
    let q = shifted - TURN_SHIFTER;
    let k = shifted.to_bits() & 3;
    let r = (x - q) * core::f32::consts::FRAC_PI_2;
    let (s, c) = sincos_turn_kernels(r);
    quadrant(s, c, k)
}

/// `(sin x, cos x)` of an angle `x` in radians, in `f32` arithmetic only (no `f64`, so no soft-float helper on an
/// FPU without double precision, where `libm::sincosf` runs its kernels in `f64`).
///
/// Cody–Waite reduction with the three-part `π/2` of Cephes' `sinf` (Moshier 1989: `P1 + P2 + P3`, with 8 and
/// 11 significant bits in `P1`, `P2`, so `q·P1` and `q·P2` are exact for `|q| < 2¹³`), then the polynomials and
/// the branch-free quadrant selection of [`sincos_turn`]:
///
/// ```text
/// q = round(2x/π),  r = ((x − q·P1) − q·P2) − q·P3 ∈ [−π/4, π/4] (+ rounding),  k = q mod 4
/// ```
///
/// Accuracy (unit test `sincos_matches_f64`, against `f64` `sin`, `cos` of the same `f32` `x`): on
/// `|x| ≤ 8192`, an absolute error ≤ `1.2·10⁻⁷` (measured `8.5·10⁻⁸`) and ≤ 2 ulp of the exact value wherever
/// `|sin x|`, `|cos x| ≥ 2⁻¹²` (measured: 1.44 ulp on `[−2π, 2π]`, 1.47 ulp beyond; `libm::sincosf` is within
/// 1 ulp); where the exact value is
/// smaller, the rounding of `r` dominates and the ulp count grows, the absolute bound holds. Exactly `(0, 1)`
/// at `x = 0`. Beyond `|x| > 8192` (a cold path) the angle is reduced in turns, `x/2π − round(x/2π)` in
/// `f32`, which keeps an absolute error ≤ `|x|·2⁻²³`: finite, in `[−1, 1]`. NaN and `±∞` give NaN.
///
/// ```
/// use radiometry::math::sincos;
/// assert_eq!(sincos(0.0), (0.0, 1.0));
/// let (s, c) = sincos(1.0);
/// assert!((s - 0.841_470_96).abs() <= 6e-8 && (c - 0.540_302_3).abs() <= 6e-8);
/// let (s, c) = sincos(1.0e30); // finite for every finite angle
/// assert!(s.abs() <= 1.0 && c.abs() <= 1.0);
/// ```
#[inline]
pub fn sincos(x: f32) -> (f32, f32) {
    // NaN fails the comparison and takes the cold path too.
    if x.abs() > SINCOS_REDUCTION_MAX || x.is_nan() {
        return sincos_large(x);
    }
    let y = x * core::f32::consts::FRAC_2_PI;
    let shifted = y + TURN_SHIFTER;
    let q = shifted - TURN_SHIFTER;
    let k = shifted.to_bits() & 3;
    let r = ((x - q * PIO2_1) - q * PIO2_2) - q * PIO2_3;
    let (s, c) = sincos_turn_kernels(r);
    quadrant(s, c, k)
}

/// `sin x` in `f32` arithmetic only: [`sincos`]`(x).0` (same accuracy).
#[inline]
pub fn sin(x: f32) -> f32 {
    sincos(x).0
}

/// `cos x` in `f32` arithmetic only: [`sincos`]`(x).1` (same accuracy).
#[inline]
pub fn cos(x: f32) -> f32 {
    sincos(x).1
}

/// Largest `|x|` reduced by the three-part `π/2` of [`sincos`] (`|q| < 2¹³`).
const SINCOS_REDUCTION_MAX: f32 = 8192.0;
/// `π/2 = PIO2_1 + PIO2_2 + PIO2_3 + O(2·10⁻¹⁵)` (Cephes `sinf`'s `DP1..3`, doubled).
const PIO2_1: f32 = 1.570_312_5;
const PIO2_2: f32 = f32::from_bits(0x39FD_A000); // 4.837_512_969_970_703e-4, 11 significant bits
const PIO2_3: f32 = f32::from_bits(0x33A22169); // 7.549_79e-8

/// [`sincos`] beyond `|x| > 8192`, and NaN / `±∞`: reduced in turns.
#[cold]
#[inline(never)]
fn sincos_large(x: f32) -> (f32, f32) {
    let t = x * (0.5 * core::f32::consts::FRAC_1_PI);
    sincos_turn(t - libm::roundf(t))
}

/// The quadrant `k` of [`sincos_turn`] and [`sincos`]: `(s, c)`, `(c, −s)`, `(−s, −c)`, `(−c, s)`.
#[inline(always)]
fn quadrant(s: f32, c: f32, k: u32) -> (f32, f32) {
    // Swap for odd k, then the signs, by bit masks.
    let odd = 0u32.wrapping_sub(k & 1);
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let s1 = (cb & odd) | (sb & !odd);
    let c1 = (sb & odd) | (cb & !odd);
    (
        f32::from_bits(s1 ^ ((k & 2) << 30)),
        f32::from_bits(c1 ^ (((k + 1) & 2) << 30)),
    )
}

/// `1.5·2²³`: `x + TURN_SHIFTER` rounds `|x| < 2²²` to an integer held in
/// the low mantissa bits ([`sincos_turn`]).
#[doc(hidden)]
pub const TURN_SHIFTER: f32 = 12_582_912.0;

/// Taylor coefficients of [`sincos_turn`]: `sin r = r (1 + r² P(r²))`,
/// `P = [−1/3!, 1/5!, −1/7!, 1/9!]`, Horner from the last.
#[doc(hidden)]
pub const SIN_TAYLOR: [f32; 4] = [-1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362_880.0];

/// `cos r = 1 + r² Q(r²)`, `Q = [−1/2!, 1/4!, −1/6!, 1/8!, −1/10!]`.
#[doc(hidden)]
pub const COS_TAYLOR: [f32; 5] = [-0.5, 1.0 / 24.0, -1.0 / 720.0, 1.0 / 40_320.0, -1.0 / 3_628_800.0];

/// `(sin r, cos r)` for `|r| ≤ π/4` by [`SIN_TAYLOR`], [`COS_TAYLOR`].
#[inline(always)]
fn sincos_turn_kernels(r: f32) -> (f32, f32) {
    let z = r * r;
    let [s0, s1, s2, s3] = SIN_TAYLOR;
    let [c0, c1, c2, c3, c4] = COS_TAYLOR;
    let ps = s0 + z * (s1 + z * (s2 + z * s3));
    let pc = c0 + z * (c1 + z * (c2 + z * (c3 + z * c4)));
    (r + (r * z) * ps, 1.0 + z * pc)
}

/// Kahan–Babuška (Neumaier) compensated sum in `f64`.
///
/// Neumaier, A. (1974), "Rundungsfehleranalyse einiger Verfahren zur
/// Summation endlicher Summen", ZAMM 54. The running error term `c`
/// captures the low-order bits lost in `sum + x`.
///
/// ```
/// use radiometry::math::CompensatedSum;
/// let mut s = CompensatedSum::default();
/// s.add(1e16); s.add(1.0); s.add(-1e16);
/// assert_eq!(s.value(), 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CompensatedSum {
    sum: f64,
    c: f64,
}

impl CompensatedSum {
    /// Adds `x` to the sum.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.c += (self.sum - t) + x;
        } else {
            self.c += (x - t) + self.sum;
        }
        self.sum = t;
    }

    /// The compensated total.
    #[inline]
    pub fn value(&self) -> f64 {
        self.sum + self.c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;

    #[test]
    fn one_minus_epsilon_is_largest_below_one() {
        const { assert!(ONE_MINUS_EPSILON < 1.0) };
        assert_eq!(f32::from_bits(ONE_MINUS_EPSILON.to_bits() + 1), 1.0);
    }

    /// `sqrtf` is `libm::sqrtf` bit for bit on every 61st `f32` bit
    /// pattern (both signs, zeros, subnormals, infinities, NaNs) and on the
    /// specials themselves.
    #[test]
    fn sqrtf_is_libms_bits() {
        let specials = [
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            1.0,
            2.0,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -1.0,
        ];
        let sweep = (0..=u32::MAX / 61).map(|k| f32::from_bits(k.wrapping_mul(61)));
        for x in specials.into_iter().chain(sweep) {
            assert_eq!(
                sqrtf(x).to_bits(),
                libm::sqrtf(x).to_bits(),
                "x = {x:e} ({:#x})",
                x.to_bits()
            );
        }
    }

    #[test]
    fn safe_functions_never_nan() {
        assert_eq!(safe_sqrt(-1e-9), 0.0);
        assert_eq!(safe_acos(1.0000001), 0.0);
        assert!(safe_asin(-2.0).is_finite());
    }

    /// `sincos_turn` against `f64` `sin`, `cos` of `2πt` (at the `f32` `t`)
    /// over `[−1, 1]` in steps of 2⁻²¹ and near the quadrant boundaries;
    /// also `sin² + cos²` and the exact values at multiples of a quarter turn.
    #[test]
    fn sincos_turn_matches_f64() {
        let mut worst = 0.0f64;
        let mut check = |t: f32| {
            let (s, c) = sincos_turn(t);
            let x = core::f64::consts::TAU * t as f64;
            let e = (s as f64 - libm::sin(x))
                .abs()
                .max((c as f64 - libm::cos(x)).abs());
            worst = worst.max(e);
            assert!(e <= 1.0e-7, "t = {t}: ({s}, {c}), error {e:e}");
        };
        let n = 1 << 21;
        for i in -n..=n {
            check(i as f32 / n as f32);
        }
        for k in -8..=8 {
            let mut t = k as f32 / 8.0;
            for _ in 0..64 {
                check(t);
                t = t.next_up();
            }
        }
        for (t, want) in [
            (0.0f32, (0.0f32, 1.0f32)),
            (0.25, (1.0, 0.0)),
            (0.5, (0.0, -1.0)),
            (0.75, (-1.0, 0.0)),
            (1.0, (0.0, 1.0)),
            (-0.25, (-1.0, 0.0)),
        ] {
            let (s, c) = sincos_turn(t);
            assert!(s == want.0 && c == want.1, "t = {t}: ({s}, {c})");
        }
        assert!(sincos_turn(f32::NAN).0.is_nan());
        assert!(worst > 0.0);
    }

    /// `sincos` against `f64` `sin`, `cos` of the same `f32` `x`: every 97th `f32` in `[−2π, 2π]`, a grid to
    /// `±8192`, the neighbourhoods of multiples of `π/2`, and large and non-finite angles. Reports the
    /// absolute error and the ulps of the exact value where it is at least `2⁻¹²`.
    #[test]
    fn sincos_matches_f64() {
        let ulp = |v: f64| {
            let f = (v as f32).abs();
            (f.next_up() - f) as f64
        };
        let mut worst = (0.0f64, 0.0f64, 0.0f64); // (abs, ulps on [−2π, 2π], ulps beyond)
        let mut check = |x: f32| {
            let (s, c) = sincos(x);
            let (es, ec) = (libm::sin(x as f64), libm::cos(x as f64));
            let abs = (s as f64 - es).abs().max((c as f64 - ec).abs());
            assert!(abs <= 1.2e-7, "x = {x}: ({s}, {c}), abs error {abs:e}");
            worst.0 = worst.0.max(abs);
            for (got, want) in [(s, es), (c, ec)] {
                if want.abs() >= 1.0 / 4096.0 {
                    let u = (got as f64 - want).abs() / ulp(want);
                    let slot = if x.abs() <= core::f32::consts::TAU {
                        &mut worst.1
                    } else {
                        &mut worst.2
                    };
                    *slot = slot.max(u);
                    assert!(u <= 2.0, "x = {x}: {got} vs {want}, {u} ulp");
                }
            }
        };
        let mut b = (-core::f32::consts::TAU).to_bits();
        while f32::from_bits(b) < 0.0 {
            check(f32::from_bits(b));
            b = b.wrapping_sub(97);
        }
        let mut x = 0.0f32;
        while x <= core::f32::consts::TAU {
            check(x);
            x = f32::from_bits(x.to_bits() + 97).max(1e-30);
        }
        for i in -200_000..=200_000 {
            check(i as f32 * (8192.0 / 200_000.0));
        }
        for q in -5215..=5215 {
            let mut x = (q as f64 * core::f64::consts::FRAC_PI_2) as f32;
            for _ in 0..4 {
                x = x.next_down();
            }
            for _ in 0..9 {
                check(x);
                x = x.next_up();
            }
        }
        assert_eq!(sincos(0.0), (0.0, 1.0));
        for x in [1.0e4f32, -3.3e5, 1.0e30, f32::MAX, -f32::MAX] {
            let (s, c) = sincos(x);
            assert!(s.abs() <= 1.0 && c.abs() <= 1.0, "x = {x}: ({s}, {c})");
            let bound = x.abs() as f64 * 2f64.powi(-23) + 1e-7;
            assert!(
                (s as f64 - libm::sin(x as f64)).abs() <= bound.max(2.0),
                "x = {x}"
            );
        }
        assert!(sincos(f32::NAN).0.is_nan() && sincos(f32::INFINITY).1.is_nan());
        std::eprintln!(
            "sincos: abs error {:.3e}, {:.2} ulp on [-2pi, 2pi], {:.2} ulp to 8192",
            worst.0,
            worst.1,
            worst.2
        );
    }

    #[test]
    fn compensated_sum_beats_naive() {
        let mut s = CompensatedSum::default();
        let mut naive = 0.0f64;
        for _ in 0..1_000_000 {
            s.add(0.1);
            naive += 0.1;
        }
        assert!((s.value() - 100_000.0).abs() < 1e-9);
        assert!((naive - 100_000.0).abs() > (s.value() - 100_000.0).abs());
    }
}
