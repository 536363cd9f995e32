//! Response curves `R`: normalised exposure `x ∈ [0, 1]` (1 = saturation)
//! → normalised output `y ∈ [0, 1]`, each with its inverse.
//!
//! Policy (all curves): inputs are clamped to `[0, 1]` — a sensor cannot
//! output less than black or more than white — and NaN reads as 0. So
//! `inverse(apply(x)) = x` for `x ∈ [0, 1]` (up to rounding), and
//! `apply(inverse(y)) = y` for `y ∈ [0, 1]`.
//!
//! ```
//! use radiometry::sensor::response::{Gamma, Response, Srgb};
//! let g = Gamma::new(2.2).unwrap();
//! assert!((g.inverse(g.apply(0.3)) - 0.3).abs() < 1e-6);
//! assert!((Srgb.apply(0.0031308) - 0.04045).abs() < 1e-5);
//! ```

use super::SensorError;

/// A monotonic map from normalised exposure to normalised output.
pub trait Response {
    /// `y = R(x)`, `x` clamped to `[0, 1]`, NaN → 0.
    fn apply(&self, x: f32) -> f32;
    /// `x = R⁻¹(y)`, `y` clamped to `[0, 1]`, NaN → 0.
    fn inverse(&self, y: f32) -> f32;
}

#[inline]
fn unit(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

/// The identity response `y = x` (a linear sensor).
///
/// ```
/// use radiometry::sensor::response::{Linear, Response};
/// assert_eq!(Linear.apply(0.25), 0.25);
/// assert_eq!(Linear.apply(2.0), 1.0); // saturates
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Linear;

impl Response for Linear {
    fn apply(&self, x: f32) -> f32 {
        unit(x)
    }
    fn inverse(&self, y: f32) -> f32 {
        unit(y)
    }
}

/// A power-law (gamma) encoding `y = x^(1/γ)`, inverse `x = y^γ`
/// (e.g. ITU-R BT.1886 display γ = 2.4 inverted; Poynton, *Digital Video
/// and HD*, 2nd ed., ch. 27).
///
/// ```
/// use radiometry::sensor::response::{Gamma, Response};
/// assert!((Gamma::new(2.0).unwrap().apply(0.25) - 0.5).abs() < 1e-6);
/// assert!(Gamma::new(0.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gamma {
    gamma: f32,
}

impl Gamma {
    /// `γ ∈ [0.05, 20]` (finite, positive; outside that range the curve is
    /// numerically a step in `f32`).
    pub fn new(gamma: f32) -> Result<Self, SensorError> {
        if !gamma.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if !(0.05..=20.0).contains(&gamma) {
            return Err(SensorError::BadParameter("gamma must be in [0.05, 20]"));
        }
        Ok(Self { gamma })
    }
}

impl Response for Gamma {
    fn apply(&self, x: f32) -> f32 {
        libm::powf(unit(x), 1.0 / self.gamma)
    }
    fn inverse(&self, y: f32) -> f32 {
        libm::powf(unit(y), self.gamma)
    }
}

/// The sRGB transfer function (IEC 61966-2-1:1999 §5.2 encoding, §5.1
/// decoding):
/// `y = 12.92 x` for `x ≤ 0.0031308`, else `1.055 x^(1/2.4) − 0.055`;
/// inverse `x = y/12.92` for `y ≤ 0.04045`, else `((y + 0.055)/1.055)^2.4`.
///
/// ```
/// use radiometry::sensor::response::{Response, Srgb};
/// assert!((Srgb.apply(1.0) - 1.0).abs() < 1e-6);
/// assert!((Srgb.inverse(0.5) - 0.21404).abs() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Srgb;

impl Response for Srgb {
    fn apply(&self, x: f32) -> f32 {
        let x = unit(x);
        if x <= 0.003_130_8 {
            12.92 * x
        } else {
            1.055 * libm::powf(x, 1.0 / 2.4) - 0.055
        }
    }
    fn inverse(&self, y: f32) -> f32 {
        let y = unit(y);
        if y <= 0.040_45 {
            y / 12.92
        } else {
            libm::powf((y + 0.055) / 1.055, 2.4)
        }
    }
}

/// A tabulated response: `y_i` at `x_i = i/(n−1)`, linearly interpolated;
/// strictly increasing (checked), so the inverse is the piecewise-linear
/// inverse found by binary search.
///
/// ```
/// use radiometry::sensor::response::{Response, TabulatedResponse};
/// let r = TabulatedResponse::new(&[0.0, 0.6, 0.9, 1.0]).unwrap();
/// assert!((r.apply(1.0 / 6.0) - 0.3).abs() < 1e-6);
/// assert!((r.inverse(0.3) - 1.0 / 6.0).abs() < 1e-6);
/// assert!(TabulatedResponse::new(&[0.0, 0.5, 0.4, 1.0]).is_err()); // not monotonic
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TabulatedResponse<'a> {
    y: &'a [f32],
}

impl<'a> TabulatedResponse<'a> {
    /// At least two finite, strictly increasing values; error
    /// [`SensorError::NotMonotonic`] otherwise (a flat or decreasing table
    /// has no inverse).
    pub fn new(y: &'a [f32]) -> Result<Self, SensorError> {
        if y.len() < 2 {
            return Err(SensorError::BadBuffer);
        }
        if y.iter().any(|v| !v.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if y.windows(2).any(|w| w[1] <= w[0]) {
            return Err(SensorError::NotMonotonic);
        }
        Ok(Self { y })
    }
}

impl Response for TabulatedResponse<'_> {
    /// Linear interpolation of the table at `x ∈ [0, 1]` (output in the
    /// table's own range, which need not be `[0, 1]`).
    fn apply(&self, x: f32) -> f32 {
        let n = self.y.len();
        let t = unit(x) * (n - 1) as f32;
        let i = (t as usize).min(n - 2);
        let f = t - i as f32;
        // `i + 1 < n` (`n ≥ 2` from `new`); checked reads keep no panic path.
        match (self.y.get(i), self.y.get(i + 1)) {
            (Some(&a), Some(&b)) => a + (b - a) * f,
            _ => 0.0,
        }
    }
    /// Inverse: `y` is clamped to the table's range `[y_0, y_{n−1}]`.
    fn inverse(&self, y: f32) -> f32 {
        let n = self.y.len();
        // `n ≥ 2` and the table increases (from `new`). The clamps are written
        // out and the reads checked: no panic path (`clamp` asserts
        // `min ≤ max`), the same values.
        let (first, last) = (
            self.y.first().copied().unwrap_or(0.0),
            self.y.last().copied().unwrap_or(0.0),
        );
        let y = if y.is_nan() || y < first {
            first
        } else if y > last {
            last
        } else {
            y
        };
        let hi = self.y.partition_point(|&v| v <= y).max(1).min(n - 1);
        let (Some(&a), Some(&b)) = (self.y.get(hi.wrapping_sub(1)), self.y.get(hi)) else {
            return 0.0;
        };
        let f = ((y - a) / (b - a)).clamp(0.0, 1.0);
        ((hi - 1) as f32 + f) / (n - 1) as f32
    }
}
