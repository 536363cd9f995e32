//! The coefficients `(a, b, R)` of the LTC sheen at `(cos θo, roughness)`: bilinear interpolation
//! in the fitted 32 × 32 table of Zeltner, Burley & Chiang 2022.

use super::ltc_data::LTC_SHEEN_VOLUME;

/// Number of nodes of the LTC sheen table along each axis: `cos θo = j/31` and roughness `k/31`,
/// `j, k = 0..32` ([`ltc_sheen_node`]).
pub const LTC_N: usize = 32;

/// The node `i/31` of either axis of the LTC sheen table (`cos θo` along a row, roughness across
/// rows); `1` for `i ≥ 31`.
#[inline]
pub fn ltc_sheen_node(i: usize) -> f32 {
    if i + 1 >= LTC_N {
        1.0
    } else {
        i as f32 / (LTC_N - 1) as f32
    }
}

/// Smallest interpolated `a` for which the lobe is kept. Below it — only within `10⁻¹⁰` above
/// the roughness nodes `0, 1/31, 2/31, 3/31`, where the rows below are all zero — `(a, b, R)` is
/// set to `(0, 0, 0)`: the density `a²/(π |M⁻¹ω|⁴)` would exceed the `f32` range there, and the
/// `R` dropped is below `3·10⁻¹⁰` (`R/a` of the table's nonzero entries is at most `20.2`).
pub const LTC_MIN_A: f32 = 1e-11;

/// `1 − 2⁻²⁴`: the largest `f32` below 1. Coordinates are clamped to it so that the cell index
/// stays below 31 (as in the reference implementation's lookup).
const BELOW_ONE: f32 = 1.0 - 1.0 / 16_777_216.0;

/// The linearly transformed cosine of the LTC sheen at one `(cos θo, roughness)` (Zeltner, Burley
/// & Chiang 2022): the inverse matrix
///
/// ```text
///        ⎡ a  0  b ⎤
/// M⁻¹ =  ⎢ 0  a  0 ⎥,      in the frame where ωo = (sin θo, 0, cos θo),
///        ⎣ 0  0  1 ⎦
/// ```
///
/// and the reflectance `R` (the albedo of the lobe with colour 1).
///
/// Domain: `a ≥ 0` (0 only where the table has no lobe, with `R = 0`), `|b| < 0.2`,
/// `R ∈ [0, 0.75]`.
///
/// ```
/// use radiometry_brdfs::sheen::LtcCoeffs;
/// let c = LtcCoeffs::at(0.5, 0.5);
/// assert!(c.a > 0.0 && c.r > 0.0 && c.r < 1.0);
/// assert_eq!(LtcCoeffs::at(0.5, 0.0), LtcCoeffs::ZERO); // roughness 0: no lobe away from grazing
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LtcCoeffs {
    /// `a`: the diagonal of `M⁻¹`'s tangential block (the table's `a_inv`).
    pub a: f32,
    /// `b`: the coupling of `x` to `z` in `M⁻¹` (the table's `b_inv`).
    pub b: f32,
    /// `R`: the reflectance, the albedo of the lobe with colour 1.
    pub r: f32,
}

impl LtcCoeffs {
    /// No lobe.
    pub const ZERO: LtcCoeffs = LtcCoeffs {
        a: 0.0,
        b: 0.0,
        r: 0.0,
    };

    /// `(a, b, R)` at `cos θo = mu` and roughness `roughness`, bilinear in the table on the nodes
    /// `j/31 × k/31` ([`ltc_sheen_node`]): both coordinates clamped to `[0, 1 − 2⁻²⁴]` (NaN → 0),
    /// cell `⌊31 x⌋`, weights `31 x − ⌊31 x⌋`, as the authors' lookup (`SheenLTC::fetchCoeffs`)
    /// does. [`LtcCoeffs::ZERO`] where the interpolated `a` is below [`LTC_MIN_A`].
    #[inline]
    pub fn at(mu: f32, roughness: f32) -> LtcCoeffs {
        let (k, rf) = cell(roughness);
        Self::in_rows(k, rf, mu)
    }

    /// [`LtcCoeffs::at`] with the row cell `k` and its weight `rf` already found (a lobe of fixed
    /// roughness finds them once).
    #[inline]
    pub(crate) fn in_rows(k: usize, rf: f32, mu: f32) -> LtcCoeffs {
        let (j, cf) = cell(mu);
        // `k ≤ 30` from `cell`; the `min` lets the compiler drop the bounds checks.
        let k = k.min(LTC_N - 2);
        let lo = &LTC_SHEEN_VOLUME[k];
        let hi = &LTC_SHEEN_VOLUME[k + 1];
        let lerp = |x: f32, y: f32, t: f32| x * (1.0 - t) + y * t;
        let v = |i: usize| {
            lerp(
                lerp(lo[j][i], lo[j + 1][i], cf),
                lerp(hi[j][i], hi[j + 1][i], cf),
                rf,
            )
        };
        let a = v(0);
        if a.is_nan() || a < LTC_MIN_A {
            return LtcCoeffs::ZERO;
        }
        LtcCoeffs { a, b: v(1), r: v(2) }
    }
}

/// The cell `⌊31 x⌋ ≤ 30` and the weight of its upper node, for `x` clamped to `[0, 1 − 2⁻²⁴]`
/// (NaN → 0).
#[inline(always)]
pub(crate) fn cell(x: f32) -> (usize, f32) {
    let x = if x > 0.0 { x.min(BELOW_ONE) } else { 0.0 };
    let s = x * (LTC_N - 1) as f32;
    // `s ∈ [0, 31)`: truncation is `⌊s⌋`, exact, one instruction each way
    // (`libm::floorf` is a call).
    let i = (s as u32) as f32;
    // `s < 31`, so `i ≤ 30`; the `min` only documents it.
    ((i as usize).min(LTC_N - 2), s - i)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn cell_stays_in_range() {
        for x in [
            f32::NAN,
            -1.0,
            0.0,
            1e-30,
            0.5,
            BELOW_ONE,
            1.0,
            2.0,
            f32::INFINITY,
        ] {
            let (i, t) = cell(x);
            assert!(i + 1 < LTC_N && (0.0..1.0).contains(&t), "{x}: {i} {t}");
        }
    }

    /// The truncation in `cell` is `floorf` on its whole domain: every
    /// `f32` step near the nodes, the ends, and a sweep of `[0, 1]`.
    #[test]
    fn cell_is_floor() {
        let floor_cell = |x: f32| {
            let x = if x > 0.0 { x.min(BELOW_ONE) } else { 0.0 };
            let s = x * (LTC_N - 1) as f32;
            let i = libm::floorf(s);
            ((i as usize).min(LTC_N - 2), s - i)
        };
        let mut xs = std::vec![
            f32::NAN,
            -0.0,
            0.0,
            BELOW_ONE,
            1.0,
            f32::INFINITY,
            f32::MIN_POSITIVE
        ];
        for j in 0..=LTC_N {
            let node = j as f32 / (LTC_N - 1) as f32;
            let mut x = node;
            for _ in 0..8 {
                xs.push(x);
                x = f32::from_bits(x.to_bits().wrapping_sub(1));
            }
            xs.push(f32::from_bits(node.to_bits() + 1));
        }
        xs.extend((0..100_000).map(|i| i as f32 / 100_000.0));
        for x in xs {
            let (a, b) = (cell(x), floor_cell(x));
            assert_eq!((a.0, a.1.to_bits()), (b.0, b.1.to_bits()), "x {x}");
        }
    }

    #[test]
    fn hits_the_nodes() {
        for k in [4usize, 10, 17, 30] {
            for j in [0usize, 1, 15, 30] {
                let c = LtcCoeffs::at(ltc_sheen_node(j), ltc_sheen_node(k));
                let e = LTC_SHEEN_VOLUME[k][j];
                assert!((c.a - e[0]).abs() < 1e-6 && (c.b - e[1]).abs() < 1e-6 && (c.r - e[2]).abs() < 1e-6);
            }
        }
        // The last node of each axis is reached through the clamp to 1 − 2⁻²⁴.
        let c = LtcCoeffs::at(1.0, 1.0);
        assert!((c.r - LTC_SHEEN_VOLUME[31][31][2]).abs() < 1e-6);
    }

    #[test]
    fn zero_entries_have_zero_reflectance_and_small_a_is_dropped() {
        let mut worst = 0.0f32;
        for row in LTC_SHEEN_VOLUME.iter() {
            for e in row {
                assert!(e[0] >= 0.0 && e[1].abs() < 0.2 && (0.0..0.75).contains(&e[2]));
                assert_eq!(e[0] == 0.0, e == &[0.0; 3]);
                if e[0] > 0.0 {
                    worst = worst.max(e[2] / e[0]);
                }
            }
        }
        assert!(worst < 20.2, "R/a up to {worst}");
        // Just above roughness 0, away from grazing: the row-1 weight is 10⁻³⁰.
        assert_eq!(LtcCoeffs::at(0.1, 1e-30 / 31.0), LtcCoeffs::ZERO);
        let c = LtcCoeffs::at(0.1, 1e-5);
        assert!(c.a > LTC_MIN_A && c.r < 1e-4, "{c:?}");
    }
}
