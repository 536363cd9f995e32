//! Small numerical helpers shared by the crate and by plugins.
//!
//! All functions are total on finite input: they return finite values and
//! never panic. `f32` functions use `libm`, so they are identical with and
//! without `std`.

/// `sqrt(max(x, 0))`: a square root that returns 0 instead of NaN for
/// slightly negative arguments produced by rounding.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    libm::sqrtf(x.max(0.0))
}

/// `f64` version of [`safe_sqrt`].
#[inline]
pub fn safe_sqrt_f64(x: f64) -> f64 {
    libm::sqrt(x.max(0.0))
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

/// `x²`.
#[inline]
pub fn sqr(x: f32) -> f32 {
    x * x
}

/// The largest `f32` strictly below 1 (`1 − 2⁻²⁴ = 0.99999994`).
///
/// Sample coordinates `u` live in `[0, ONE_MINUS_EPSILON]`.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// Returns `x` if it is finite, otherwise `fallback`.
#[inline]
pub fn finite_or(x: f32, fallback: f32) -> f32 {
    if x.is_finite() { x } else { fallback }
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

    #[test]
    fn one_minus_epsilon_is_largest_below_one() {
        const { assert!(ONE_MINUS_EPSILON < 1.0) };
        assert_eq!(f32::from_bits(ONE_MINUS_EPSILON.to_bits() + 1), 1.0);
    }

    #[test]
    fn safe_functions_never_nan() {
        assert_eq!(safe_sqrt(-1e-9), 0.0);
        assert_eq!(safe_acos(1.0000001), 0.0);
        assert!(safe_asin(-2.0).is_finite());
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
