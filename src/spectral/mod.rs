//! Spectral data tables, spectral curves and photometry.
//!
//! * [`SpectralCurve`]: any function of wavelength (nm) with a declared
//!   support — tabulated data ([`Tabulated`] on a uniform grid,
//!   [`Irregular`] on an increasing grid), closures ([`FnCurve`]), Planck's
//!   law ([`Blackbody`]) and CIE illuminant A ([`IlluminantA`]).
//! * CIE data ([`tables`]): the CIE 1931 2° colour-matching functions, the
//!   photopic luminous efficiency V(λ) and illuminant D65, exposed as curves
//!   by [`x_bar`], [`y_bar`], [`z_bar`], [`photopic_v`] and [`d65`].
//! * Photometry and colorimetry ([`photometry`]): illuminance in lux from
//!   spectral irradiance (683 lm/W), tristimulus values, chromaticity, and
//!   XYZ → linear sRGB.
//!
//! **Out-of-range policy.** [`SpectralCurve::value`] is total: it returns
//! `0.0` outside the curve's support and for a non-finite wavelength (a
//! tabulated spectrum is taken to be zero where it was not measured).
//! Callers who must know that they left the table use
//! [`Tabulated::try_value`], which returns a typed [`SpectralError`].
//!
//! ```
//! use radiometry::spectral::{self, SpectralCurve};
//! let v = spectral::photopic_v();
//! assert_eq!(v.value(555.0), 1.0); // peak of V(λ)
//! assert_eq!(v.value(900.0), 0.0); // outside the table: zero
//! assert_eq!(v.value(f32::NAN), 0.0);
//! assert!(v.try_value(900.0).is_err());
//! ```

use core::fmt;

pub mod photometry;
pub mod tables;
pub mod uplift;

pub use photometry::{
    K_M, chromaticity, illuminance_lux, illuminance_monochromatic, xyz, xyz_to_linear_srgb,
};

/// Why a spectral table or a wavelength was rejected.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SpectralError {
    /// A wavelength or table entry was NaN or infinite.
    NotFinite,
    /// The wavelength lies outside the table's range `[min, max]` (nm).
    OutOfRange {
        /// The requested wavelength, nm.
        lambda: f32,
        /// Smallest tabulated wavelength, nm.
        min: f32,
        /// Largest tabulated wavelength, nm.
        max: f32,
    },
    /// The table has fewer than two entries, or the wavelength and value
    /// slices differ in length.
    BadLength,
    /// The wavelength step is not positive, or the wavelengths of an
    /// [`Irregular`] table are not strictly increasing.
    NotIncreasing,
    /// A physical parameter is out of its domain (e.g. a temperature ≤ 0).
    BadParameter,
}

impl fmt::Display for SpectralError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite => write!(f, "non-finite wavelength or table value"),
            Self::OutOfRange { lambda, min, max } => {
                write!(
                    f,
                    "wavelength {lambda} nm outside the table range [{min}, {max}] nm"
                )
            }
            Self::BadLength => write!(f, "spectral table needs at least two entries of equal length"),
            Self::NotIncreasing => write!(f, "wavelengths must be strictly increasing"),
            Self::BadParameter => write!(f, "parameter outside its physical domain"),
        }
    }
}

impl core::error::Error for SpectralError {}

/// A function of wavelength λ (nanometres) with a bounded support.
///
/// Contract: [`value`](Self::value) is finite for every input, `0.0` outside
/// [`support`](Self::support) and for NaN/∞ wavelengths.
///
/// ```
/// use radiometry::spectral::{FnCurve, SpectralCurve};
/// let flat = FnCurve::new(400.0, 700.0, |_| 2.0);
/// assert_eq!(flat.value(500.0), 2.0);
/// assert_eq!(flat.value(800.0), 0.0);
/// assert_eq!(flat.support(), (400.0, 700.0));
/// ```
pub trait SpectralCurve {
    /// The curve at `lambda_nm`.
    fn value(&self, lambda_nm: f32) -> f32;
    /// The closed interval `[lo, hi]` (nm) outside which the curve is zero.
    fn support(&self) -> (f32, f32);
}

impl<C: SpectralCurve + ?Sized> SpectralCurve for &C {
    #[inline]
    fn value(&self, lambda_nm: f32) -> f32 {
        (**self).value(lambda_nm)
    }
    #[inline]
    fn support(&self) -> (f32, f32) {
        (**self).support()
    }
}

/// A curve tabulated on a uniform wavelength grid
/// `λ_i = start + i·step`, linearly interpolated between nodes and zero
/// outside `[start, start + (n−1)·step]`.
///
/// Linear interpolation is the method CIE 015:2018 §7.2.1 allows for
/// data given at 5 nm when finer steps are needed.
///
/// ```
/// use radiometry::spectral::{SpectralCurve, Tabulated};
/// const Q: [f32; 3] = [0.2, 0.6, 0.4];
/// let q = Tabulated::new(400.0, 100.0, &Q).unwrap();
/// assert!((q.value(450.0) - 0.4).abs() < 1e-6);
/// assert_eq!(q.value(399.0), 0.0);
/// assert!(Tabulated::new(400.0, -1.0, &Q).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tabulated<'a> {
    start: f32,
    step: f32,
    values: &'a [f32],
}

impl<'a> Tabulated<'a> {
    /// Validates and wraps a table: `start` finite, `step > 0` finite,
    /// at least two values, all finite.
    pub const fn new(start_nm: f32, step_nm: f32, values: &'a [f32]) -> Result<Self, SpectralError> {
        if !start_nm.is_finite() || !step_nm.is_finite() {
            return Err(SpectralError::NotFinite);
        }
        if step_nm <= 0.0 {
            return Err(SpectralError::NotIncreasing);
        }
        if values.len() < 2 {
            return Err(SpectralError::BadLength);
        }
        let mut i = 0;
        while i < values.len() {
            if !values[i].is_finite() {
                return Err(SpectralError::NotFinite);
            }
            i += 1;
        }
        Ok(Self {
            start: start_nm,
            step: step_nm,
            values,
        })
    }

    /// The tabulated values.
    pub const fn values(&self) -> &'a [f32] {
        self.values
    }

    /// The first tabulated wavelength, nm.
    pub const fn start(&self) -> f32 {
        self.start
    }

    /// The grid step, nm.
    pub const fn step(&self) -> f32 {
        self.step
    }

    /// The last tabulated wavelength, nm.
    pub fn end(&self) -> f32 {
        self.start + (self.values.len() - 1) as f32 * self.step
    }

    /// Like [`SpectralCurve::value`], but a wavelength outside the table or
    /// a non-finite one is an error instead of `0.0`.
    pub fn try_value(&self, lambda_nm: f32) -> Result<f32, SpectralError> {
        if !lambda_nm.is_finite() {
            return Err(SpectralError::NotFinite);
        }
        let (min, max) = (self.start, self.end());
        if lambda_nm < min || lambda_nm > max {
            return Err(SpectralError::OutOfRange {
                lambda: lambda_nm,
                min,
                max,
            });
        }
        Ok(self.interp(lambda_nm))
    }

    #[inline]
    fn interp(&self, lambda_nm: f32) -> f32 {
        let n = self.values.len();
        let t = (lambda_nm - self.start) / self.step;
        let i = (t as usize).min(n.saturating_sub(2));
        let f = (t - i as f32).clamp(0.0, 1.0);
        // `new` guarantees n ≥ 2, so both nodes exist; `get` (not indexing)
        // lets no panic path survive where the optimiser cannot see that.
        match (self.values.get(i), self.values.get(i + 1)) {
            (Some(&a), Some(&b)) => a + (b - a) * f,
            _ => 0.0,
        }
    }
}

impl SpectralCurve for Tabulated<'_> {
    #[inline]
    fn value(&self, lambda_nm: f32) -> f32 {
        // NaN fails both comparisons, so test the accepted range positively.
        if lambda_nm >= self.start && lambda_nm <= self.end() {
            self.interp(lambda_nm)
        } else {
            0.0
        }
    }
    fn support(&self) -> (f32, f32) {
        (self.start, self.end())
    }
}

/// A curve tabulated at strictly increasing wavelengths (e.g. a quantum
/// efficiency read off a datasheet), linearly interpolated, zero outside
/// `[λ_0, λ_{n−1}]`.
///
/// ```
/// use radiometry::spectral::{Irregular, SpectralCurve};
/// let qe = Irregular::new(&[400.0, 550.0, 1000.0], &[0.3, 0.6, 0.1]).unwrap();
/// assert!((qe.value(475.0) - 0.45).abs() < 1e-6);
/// assert!(Irregular::new(&[400.0, 400.0], &[1.0, 1.0]).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Irregular<'a> {
    lambdas: &'a [f32],
    values: &'a [f32],
}

impl<'a> Irregular<'a> {
    /// Validates: equal lengths ≥ 2, all finite, wavelengths strictly
    /// increasing.
    pub fn new(lambdas_nm: &'a [f32], values: &'a [f32]) -> Result<Self, SpectralError> {
        if lambdas_nm.len() != values.len() || values.len() < 2 {
            return Err(SpectralError::BadLength);
        }
        if lambdas_nm.iter().chain(values).any(|v| !v.is_finite()) {
            return Err(SpectralError::NotFinite);
        }
        if lambdas_nm.windows(2).any(|w| w[1] <= w[0]) {
            return Err(SpectralError::NotIncreasing);
        }
        Ok(Self {
            lambdas: lambdas_nm,
            values,
        })
    }

    /// For crate-internal constant tables already known to satisfy the
    /// invariants of [`Irregular::new`] (checked by this crate's tests).
    pub(crate) const fn from_valid_table(lambdas_nm: &'a [f32], values: &'a [f32]) -> Self {
        Self {
            lambdas: lambdas_nm,
            values,
        }
    }
}

impl SpectralCurve for Irregular<'_> {
    fn value(&self, lambda_nm: f32) -> f32 {
        let n = self.lambdas.len();
        let (lo, hi) = self.support();
        if !(lambda_nm >= lo && lambda_nm <= hi) {
            return 0.0;
        }
        // First node strictly above λ (binary search), clamped to a valid
        // interval (`n ≥ 2` from `new`; checked reads: no panic path).
        let hi = self
            .lambdas
            .partition_point(|&l| l <= lambda_nm)
            .max(1)
            .min(n - 1);
        let lo = hi.wrapping_sub(1);
        let (Some(&l0), Some(&l1), Some(&v0), Some(&v1)) = (
            self.lambdas.get(lo),
            self.lambdas.get(hi),
            self.values.get(lo),
            self.values.get(hi),
        ) else {
            return 0.0;
        };
        let f = ((lambda_nm - l0) / (l1 - l0)).clamp(0.0, 1.0);
        v0 + (v1 - v0) * f
    }
    fn support(&self) -> (f32, f32) {
        match (self.lambdas.first(), self.lambdas.last()) {
            (Some(&lo), Some(&hi)) => (lo, hi),
            _ => (0.0, 0.0),
        }
    }
}

/// A closure `f(λ)` restricted to `[lo, hi]`; non-finite results read as 0.
///
/// ```
/// use radiometry::spectral::{FnCurve, SpectralCurve};
/// let c = FnCurve::new(380.0, 780.0, |l| l / 1000.0);
/// assert!((c.value(500.0) - 0.5).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FnCurve<F> {
    lo: f32,
    hi: f32,
    f: F,
}

impl<F: Fn(f32) -> f32> FnCurve<F> {
    /// Wraps `f` on the support `[lo, hi]` (swapped if given in reverse;
    /// a non-finite bound gives an empty support at 0).
    pub fn new(lo_nm: f32, hi_nm: f32, f: F) -> Self {
        let (lo, hi) = if lo_nm.is_finite() && hi_nm.is_finite() {
            (lo_nm.min(hi_nm), lo_nm.max(hi_nm))
        } else {
            (0.0, 0.0)
        };
        Self { lo, hi, f }
    }
}

impl<F: Fn(f32) -> f32> SpectralCurve for FnCurve<F> {
    fn value(&self, lambda_nm: f32) -> f32 {
        if lambda_nm >= self.lo && lambda_nm <= self.hi {
            let v = (self.f)(lambda_nm);
            if v.is_finite() { v } else { 0.0 }
        } else {
            0.0
        }
    }
    fn support(&self) -> (f32, f32) {
        (self.lo, self.hi)
    }
}

/// A curve multiplied by a constant: `k · c(λ)` (e.g. a relative SPD
/// scaled to absolute spectral irradiance).
///
/// ```
/// use radiometry::spectral::{self, Scaled, SpectralCurve};
/// let e = Scaled::new(spectral::d65(), 0.01);
/// assert!((e.value(560.0) - 1.0).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Scaled<C> {
    /// The curve.
    pub curve: C,
    /// The factor (non-finite factors read as 0).
    pub factor: f32,
}

impl<C: SpectralCurve> Scaled<C> {
    /// `factor · curve`.
    pub fn new(curve: C, factor: f32) -> Self {
        Self {
            curve,
            factor: if factor.is_finite() { factor } else { 0.0 },
        }
    }
}

impl<C: SpectralCurve> SpectralCurve for Scaled<C> {
    fn value(&self, lambda_nm: f32) -> f32 {
        let v = self.curve.value(lambda_nm) * self.factor;
        if v.is_finite() { v } else { 0.0 }
    }
    fn support(&self) -> (f32, f32) {
        self.curve.support()
    }
}

/// Planck's law for the spectral radiance of a black body at temperature
/// `T`, in W·m⁻²·sr⁻¹·nm⁻¹ (Planck 1901; CODATA constants):
/// `L(λ,T) = 2hc² / λ⁵ / (exp(hc/(λkT)) − 1)`.
///
/// Domain: `T > 0` (checked at construction); support 1 nm – 100 µm.
///
/// ```
/// use radiometry::spectral::{Blackbody, SpectralCurve};
/// let sun = Blackbody::new(5778.0).unwrap();
/// // Wien's displacement law: peak near b/T = 2.8978e6 nm·K / 5778 K ≈ 501.5 nm.
/// assert!(sun.value(501.5) > sun.value(480.0) && sun.value(501.5) > sun.value(520.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blackbody {
    temperature_k: f32,
}

impl Blackbody {
    /// A black body at `temperature_k` kelvin; error unless finite and > 0.
    pub fn new(temperature_k: f32) -> Result<Self, SpectralError> {
        if !temperature_k.is_finite() {
            return Err(SpectralError::NotFinite);
        }
        if temperature_k <= 0.0 {
            return Err(SpectralError::BadParameter);
        }
        Ok(Self { temperature_k })
    }
}

impl SpectralCurve for Blackbody {
    fn value(&self, lambda_nm: f32) -> f32 {
        const H: f32 = 6.626_07e-34; // J·s (exact, SI 2019)
        const C: f32 = 299_792_458.0; // m/s (exact)
        const KB: f32 = 1.380_649e-23; // J/K (exact)
        if !(1.0..=1.0e5).contains(&lambda_nm) {
            return 0.0;
        }
        let l = lambda_nm * 1e-9;
        let x = H * C / (l * KB * self.temperature_k);
        if x > 80.0 {
            return 0.0; // exp(80) ~ 5e34: the radiance is below f32 resolution of anything visible
        }
        // 2hc²/λ⁵ per metre of wavelength, ×1e-9 per nm. λ⁵ = λ_µm⁴·1e-24·λ_m keeps
        // every intermediate inside the f32 range.
        let um = lambda_nm * 1e-3;
        let l5 = um * um * um * um * l;
        let pref = 2.0 * H * C * C / l5 * 1e15;
        let v = pref / libm::expm1f(x);
        if v.is_finite() { v } else { 0.0 }
    }
    fn support(&self) -> (f32, f32) {
        (1.0, 1.0e5)
    }
}

/// CIE standard illuminant A: the relative spectral power distribution of
/// a Planckian radiator at about 2856 K, normalised to 100 at 560 nm, in
/// the exact form that defines it (CIE 015:2018 §4.1 eq. 4.1; ISO 11664-2):
///
/// `S_A(λ) = 100 (560/λ)⁵ · (exp(1.435e7/(2848·560)) − 1) / (exp(1.435e7/(2848·λ)) − 1)`,
/// λ in nm. (The constants 1.435e7 nm·K and 2848 K are the historical c₂
/// and temperature; with today's c₂ = 1.4388e7 nm·K the same curve is a
/// Planckian at 2856 K. Using 1.4388e7/2856 instead shifts the table by
/// up to 0.13 % at 300 nm.)
///
/// The formula is defined for all λ; the support is 300–830 nm (the CIE
/// tabulation range). Evaluated in `f64` internally only to keep the
/// ratio of two exponentials exact to f32 precision.
///
/// ```
/// use radiometry::spectral::{IlluminantA, SpectralCurve};
/// assert!((IlluminantA.value(560.0) - 100.0).abs() < 1e-4);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IlluminantA;

impl SpectralCurve for IlluminantA {
    fn value(&self, lambda_nm: f32) -> f32 {
        if !(300.0..=830.0).contains(&lambda_nm) {
            return 0.0;
        }
        let l = lambda_nm as f64;
        const C2_OVER_T: f64 = 1.435e7 / 2848.0; // nm
        let num = libm::expm1(C2_OVER_T / 560.0);
        let den = libm::expm1(C2_OVER_T / l);
        let r = 560.0 / l;
        (100.0 * r * r * r * r * r * num / den) as f32
    }
    fn support(&self) -> (f32, f32) {
        (300.0, 830.0)
    }
}

/// CIE 1931 2° colour-matching function x̄(λ) (360–830 nm, CIE 015:2018 Table T.4).
pub const fn x_bar() -> Tabulated<'static> {
    Tabulated {
        start: tables::CMF_START_NM,
        step: tables::CMF_STEP_NM,
        values: &tables::CIE1931_X_BAR,
    }
}

/// CIE 1931 2° colour-matching function ȳ(λ) (= photopic V(λ)).
pub const fn y_bar() -> Tabulated<'static> {
    Tabulated {
        start: tables::CMF_START_NM,
        step: tables::CMF_STEP_NM,
        values: &tables::CIE1931_Y_BAR,
    }
}

/// CIE 1931 2° colour-matching function z̄(λ).
pub const fn z_bar() -> Tabulated<'static> {
    Tabulated {
        start: tables::CMF_START_NM,
        step: tables::CMF_STEP_NM,
        values: &tables::CIE1931_Z_BAR,
    }
}

/// CIE photopic luminous efficiency function V(λ), peak 1 at 555 nm
/// (CIE S 010/ISO 23539:2005), 360–830 nm.
pub const fn photopic_v() -> Tabulated<'static> {
    Tabulated {
        start: tables::CMF_START_NM,
        step: tables::CMF_STEP_NM,
        values: &tables::CIE_PHOTOPIC_V,
    }
}

/// CIE standard illuminant D65 (relative SPD, 100 at 560 nm), 300–780 nm
/// (CIE 015:2018 Table T.1).
pub const fn d65() -> Tabulated<'static> {
    Tabulated {
        start: tables::D65_START_NM,
        step: tables::D65_STEP_NM,
        values: &tables::CIE_D65,
    }
}

/// `∫ a(λ) b(λ) dλ` over the intersection of the two supports by the
/// composite trapezoid rule with the given step (nm; a non-positive or
/// non-finite step means 1 nm, and at most 100 000 intervals are used).
/// The sum is compensated (Neumaier 1974) in `f32`.
///
/// Exact for products of piecewise-linear curves whose nodes lie on the
/// integration grid up to the O(h²) trapezoid error of each product
/// segment.
///
/// Curves are zero outside their supports, and the integral runs over the
/// intersection of the supports. Declare supports tightly: a curve whose
/// support is wider than where it is non-zero (e.g. a tabulated spectrum
/// wrapped in a wider [`FnCurve`]) has a jump to zero inside the interval,
/// which the trapezoid rule integrates with an O(h) error (half a step of
/// the jump height).
///
/// ```
/// use radiometry::spectral::{FnCurve, integrate_product};
/// let one = FnCurve::new(400.0, 500.0, |_| 1.0);
/// let ramp = FnCurve::new(0.0, 1000.0, |l| l);
/// // ∫_400^500 λ dλ = 45 000
/// assert!((integrate_product(&one, &ramp, 1.0) - 45_000.0).abs() < 1.0);
/// ```
pub fn integrate_product(a: &impl SpectralCurve, b: &impl SpectralCurve, step_nm: f32) -> f32 {
    let (a0, a1) = a.support();
    let (b0, b1) = b.support();
    integrate_fn(a0.max(b0), a1.min(b1), step_nm, |l| a.value(l) * b.value(l))
}

/// `∫_lo^hi f(λ) dλ` by the composite trapezoid rule (see
/// [`integrate_product`] for the step policy). Empty or non-finite
/// intervals (including `hi − lo` overflowing `f32`) give 0; non-finite
/// integrand values count as 0; a sum that overflows `f32` gives 0.
pub fn integrate_fn(lo: f32, hi: f32, step_nm: f32, f: impl Fn(f32) -> f32) -> f32 {
    if !(lo.is_finite() && hi.is_finite() && (hi - lo).is_finite()) || hi <= lo {
        return 0.0;
    }
    let step = if step_nm.is_finite() && step_nm > 0.0 {
        step_nm
    } else {
        1.0
    };
    let n = libm::ceilf((hi - lo) / step).clamp(1.0, 100_000.0) as u32;
    let h = (hi - lo) / n as f32;
    let g = |l: f32| {
        let v = f(l);
        if v.is_finite() { v } else { 0.0 }
    };
    let mut s = CompensatedF32::default();
    s.add(0.5 * g(lo));
    s.add(0.5 * g(hi));
    for i in 1..n {
        s.add(g(lo + i as f32 * h));
    }
    let v = s.value() * h;
    if v.is_finite() { v } else { 0.0 }
}

/// Neumaier compensated sum in `f32`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CompensatedF32 {
    sum: f32,
    c: f32,
}

impl CompensatedF32 {
    #[inline]
    pub(crate) fn add(&mut self, x: f32) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.c += (self.sum - t) + x;
        } else {
            self.c += (x - t) + self.sum;
        }
        self.sum = t;
    }
    #[inline]
    pub(crate) fn value(&self) -> f32 {
        self.sum + self.c
    }
}
