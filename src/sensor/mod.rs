//! Sensor models: from spectral irradiance on a pixel to a reading, and
//! back.
//!
//! A pixel reads `I = R(∫_t ∫_λ ∫_x ∫_y E(x,y,λ,t) s(x,y) q(λ))`
//! (CSE 252A radiometry lecture on radiometry and reflectance). Here
//!
//! * `E` is an [`IrradianceField`] that *declares* how it varies: over the
//!   pixel area ([`IrradianceField::VARIES_IN_SPACE`]), over time
//!   ([`IrradianceField::VARIES_IN_TIME`]) and over wavelength
//!   ([`IrradianceField::spectral`]: a band or a single wavelength).
//!   [`Pixel::mean_electrons`] integrates only the dimensions that vary.
//! * `s(x,y)` is an [`Aperture`] ([`FillFactor`] or [`FnAperture`]),
//! * `q(λ)` is the quantum efficiency η(λ), any
//!   [`SpectralCurve`],
//! * `R` is a [`response::Response`] curve (linear, gamma, sRGB,
//!   tabulated), each with its inverse; [`calibration`] recovers it,
//! * noise, gain, full well and ADC follow the EMVA 1288 linear model
//!   ([`emva`]), every effect opt-in by type,
//! * colour architectures (Bayer CFA + demosaicing, 3-chip prism, filter
//!   wheel, stacked layers) live in [`color`].
//!
//! Everything is `no_std`, allocation-free, `f32` at the API; image-level
//! functions write into caller buffers.
//!
//! ```
//! use radiometry::sensor::{FillFactor, Monochromatic, Pixel, Sampling};
//! use radiometry::spectral::FnCurve;
//! // A 5 µm pixel, 60 % fill factor, QE 0.5, 10 ms, under 1 mW/m² of 550 nm light.
//! let px = Pixel::new(FillFactor::new(0.6).unwrap(), FnCurve::new(300.0, 1100.0, |_| 0.5),
//!                     25e-12, 0.01, Sampling::default()).unwrap();
//! let e = px.mean_electrons(&Monochromatic::new(550.0, 1e-3)).unwrap();
//! // photons = E A t λ/(hc) = 1e-3·25e-12·0.01·550e-9/(6.626e-34·2.998e8) ≈ 692; × 0.6 × 0.5
//! assert!((e - 207.7).abs() < 0.5);
//! ```

use crate::spectral::SpectralCurve;
use core::fmt;

pub mod als;
pub mod calibration;
pub mod color;
pub mod emva;
pub mod noise;
pub mod response;

pub use emva::Emva1288;
pub use noise::Pcg32;
pub use response::Response;

/// Why a sensor computation was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SensorError {
    /// A parameter or input value was NaN or infinite.
    NotFinite,
    /// A parameter is outside its domain (named).
    BadParameter(&'static str),
    /// A response table is not strictly increasing, so it has no inverse.
    NotMonotonic,
    /// A caller buffer has the wrong length, or image dimensions are too
    /// small.
    BadBuffer,
    /// A least-squares system was singular (not enough distinct data).
    Singular,
}

impl fmt::Display for SensorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite => write!(f, "non-finite input"),
            Self::BadParameter(p) => write!(f, "parameter out of domain: {p}"),
            Self::NotMonotonic => write!(f, "response table is not strictly increasing"),
            Self::BadBuffer => write!(f, "buffer length does not match the image dimensions"),
            Self::Singular => write!(f, "least-squares system is singular"),
        }
    }
}

impl core::error::Error for SensorError {}

/// How an [`IrradianceField`] is distributed over wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpectralSupport {
    /// All power at one wavelength (nm): [`IrradianceField::irradiance`]
    /// returns irradiance in W·m⁻² and is evaluated at this wavelength only.
    Monochromatic(f32),
    /// Spread over `[lo, hi]` nm: [`IrradianceField::irradiance`] returns
    /// spectral irradiance in W·m⁻²·nm⁻¹.
    Band {
        /// Lower end, nm.
        lo: f32,
        /// Upper end, nm.
        hi: f32,
    },
}

/// The irradiance reaching one pixel, with a declaration of the
/// dimensions in which it varies. The sensor samples only those.
///
/// Coordinates: `x, y ∈ [0,1]` across the pixel, `t ∈ [0, exposure]`
/// seconds, `λ` in nm.
///
/// ```
/// use radiometry::sensor::{IrradianceField, SpectralSupport};
/// /// A light switched on half-way through the exposure, uniform, at 630 nm.
/// struct Flash;
/// impl IrradianceField for Flash {
///     const VARIES_IN_SPACE: bool = false;
///     const VARIES_IN_TIME: bool = true;
///     fn spectral(&self) -> SpectralSupport { SpectralSupport::Monochromatic(630.0) }
///     fn irradiance(&self, _x: f32, _y: f32, _l: f32, t: f32) -> f32 { if t > 0.005 { 2.0 } else { 0.0 } }
/// }
/// assert!(!Flash::VARIES_IN_SPACE);
/// ```
pub trait IrradianceField {
    /// Whether `irradiance` depends on `(x, y)`. If `false` it is
    /// evaluated at the pixel centre only.
    const VARIES_IN_SPACE: bool;
    /// Whether `irradiance` depends on `t`. If `false` it is evaluated at
    /// `t = 0` and multiplied by the exposure time.
    const VARIES_IN_TIME: bool;
    /// The spectral distribution; see [`SpectralSupport`] for units.
    fn spectral(&self) -> SpectralSupport;
    /// (Spectral) irradiance at `(x, y, λ, t)`.
    fn irradiance(&self, x: f32, y: f32, lambda_nm: f32, t: f32) -> f32;
}

/// A static, spatially uniform field with spectral irradiance `curve(λ)`
/// (W·m⁻²·nm⁻¹) — the common case of a pixel under a steady lamp.
///
/// ```
/// use radiometry::sensor::{IrradianceField, UniformSpectral};
/// use radiometry::spectral::{self, Scaled};
/// let f = UniformSpectral(Scaled::new(spectral::d65(), 1e-3));
/// assert!((f.irradiance(0.3, 0.2, 560.0, 1.0) - 0.1).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct UniformSpectral<C>(pub C);

impl<C: SpectralCurve> IrradianceField for UniformSpectral<C> {
    const VARIES_IN_SPACE: bool = false;
    const VARIES_IN_TIME: bool = false;
    fn spectral(&self) -> SpectralSupport {
        let (lo, hi) = self.0.support();
        SpectralSupport::Band { lo, hi }
    }
    fn irradiance(&self, _x: f32, _y: f32, lambda_nm: f32, _t: f32) -> f32 {
        self.0.value(lambda_nm)
    }
}

/// A static, uniform, monochromatic field: `irradiance` W·m⁻² at
/// `lambda_nm` (a laser, an LED approximated as a line).
///
/// ```
/// use radiometry::sensor::{IrradianceField, Monochromatic, SpectralSupport};
/// let m = Monochromatic::new(532.0, 0.1);
/// assert_eq!(m.spectral(), SpectralSupport::Monochromatic(532.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Monochromatic {
    /// Wavelength, nm.
    pub lambda_nm: f32,
    /// Irradiance, W·m⁻².
    pub irradiance: f32,
}

impl Monochromatic {
    /// A line at `lambda_nm` with `irradiance_w_m2`.
    pub fn new(lambda_nm: f32, irradiance_w_m2: f32) -> Self {
        Self {
            lambda_nm,
            irradiance: irradiance_w_m2,
        }
    }
}

impl IrradianceField for Monochromatic {
    const VARIES_IN_SPACE: bool = false;
    const VARIES_IN_TIME: bool = false;
    fn spectral(&self) -> SpectralSupport {
        SpectralSupport::Monochromatic(self.lambda_nm)
    }
    fn irradiance(&self, _x: f32, _y: f32, _l: f32, _t: f32) -> f32 {
        self.irradiance
    }
}

/// A general field from a closure `f(x, y, λ, t)` (spectral irradiance,
/// W·m⁻²·nm⁻¹) on the band `[lo, hi]`; declares that it varies in every
/// dimension, so the sensor integrates all of them.
///
/// ```
/// use radiometry::sensor::{FnField, IrradianceField};
/// let f = FnField::new(400.0, 700.0, |x, _y, _l, _t| x);
/// assert_eq!(f.irradiance(0.25, 0.0, 500.0, 0.0), 0.25);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FnField<F> {
    lo: f32,
    hi: f32,
    f: F,
}

impl<F: Fn(f32, f32, f32, f32) -> f32> FnField<F> {
    /// `f` on the band `[lo, hi]` nm.
    pub fn new(lo_nm: f32, hi_nm: f32, f: F) -> Self {
        Self {
            lo: lo_nm,
            hi: hi_nm,
            f,
        }
    }
}

impl<F: Fn(f32, f32, f32, f32) -> f32> IrradianceField for FnField<F> {
    const VARIES_IN_SPACE: bool = true;
    const VARIES_IN_TIME: bool = true;
    fn spectral(&self) -> SpectralSupport {
        SpectralSupport::Band {
            lo: self.lo,
            hi: self.hi,
        }
    }
    fn irradiance(&self, x: f32, y: f32, l: f32, t: f32) -> f32 {
        (self.f)(x, y, l, t)
    }
}

/// Wraps any field and declares it varying in every dimension; a
/// monochromatic line becomes a box of width `line_width_nm` with the same
/// power. Used to check that each shortcut equals the full integration.
///
/// ```
/// use radiometry::sensor::{Full, IrradianceField, Monochromatic};
/// let f = Full::new(Monochromatic::new(500.0, 1.0), 0.5);
/// assert!(<Full<Monochromatic> as IrradianceField>::VARIES_IN_TIME);
/// assert_eq!(f.irradiance(0.5, 0.5, 500.1, 0.0), 2.0); // 1 W/m² over 0.5 nm
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Full<F> {
    /// The wrapped field.
    pub field: F,
    /// Width (nm) of the box replacing a monochromatic line.
    pub line_width_nm: f32,
}

impl<F: IrradianceField> Full<F> {
    /// Wraps `field`.
    pub fn new(field: F, line_width_nm: f32) -> Self {
        Self { field, line_width_nm }
    }
}

impl<F: IrradianceField> IrradianceField for Full<F> {
    const VARIES_IN_SPACE: bool = true;
    const VARIES_IN_TIME: bool = true;
    fn spectral(&self) -> SpectralSupport {
        match self.field.spectral() {
            SpectralSupport::Monochromatic(l) => {
                let h = 0.5 * self.line_width_nm;
                SpectralSupport::Band { lo: l - h, hi: l + h }
            }
            b => b,
        }
    }
    fn irradiance(&self, x: f32, y: f32, lambda_nm: f32, t: f32) -> f32 {
        match self.field.spectral() {
            SpectralSupport::Monochromatic(l) => {
                let h = 0.5 * self.line_width_nm;
                // The width as f32 sees it, so that power is conserved exactly.
                let w = (l + h) - (l - h);
                if w > 0.0 && (l - h..=l + h).contains(&lambda_nm) {
                    self.field.irradiance(x, y, l, t) / w
                } else {
                    0.0
                }
            }
            SpectralSupport::Band { .. } => self.field.irradiance(x, y, lambda_nm, t),
        }
    }
}

/// The pixel's spatial response `s(x, y)` over `[0,1]²`.
pub trait Aperture {
    /// Whether `s` is constant over the pixel (then a spatially varying
    /// field is integrated against a constant, and a uniform field needs
    /// only `mean()`).
    const UNIFORM: bool;
    /// `s(x, y)`.
    fn weight(&self, x: f32, y: f32) -> f32;
    /// `∫∫ s(x,y) dx dy` over the unit square, computed with `n × n`
    /// midpoint samples when the aperture is not uniform (`n` clamped to
    /// `1..=`[`MAX_SPACE_SAMPLES`]).
    fn mean(&self, n: u32) -> f32 {
        let n = n.clamp(1, MAX_SPACE_SAMPLES);
        let mut acc = 0.0f32;
        for j in 0..n {
            for i in 0..n {
                acc += self.weight((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            }
        }
        acc / (n * n) as f32
    }
}

/// A uniform aperture: `s(x, y) = fill factor`, the fraction of the pixel
/// area that is photosensitive.
///
/// ```
/// use radiometry::sensor::{Aperture, FillFactor};
/// assert_eq!(FillFactor::new(0.5).unwrap().mean(1), 0.5);
/// assert!(FillFactor::new(1.5).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FillFactor(f32);

impl FillFactor {
    /// Fill factor in `(0, 1]`.
    pub fn new(fill: f32) -> Result<Self, SensorError> {
        if !fill.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if !(fill > 0.0 && fill <= 1.0) {
            return Err(SensorError::BadParameter("fill factor must be in (0, 1]"));
        }
        Ok(Self(fill))
    }
}

impl Aperture for FillFactor {
    const UNIFORM: bool = true;
    fn weight(&self, _x: f32, _y: f32) -> f32 {
        self.0
    }
    fn mean(&self, _n: u32) -> f32 {
        self.0
    }
}

/// A user aperture `s(x, y)` (e.g. a photodiode occupying a corner, or a
/// microlens profile). Non-finite values read as 0.
///
/// ```
/// use radiometry::sensor::{Aperture, FnAperture};
/// let corner = FnAperture(|x: f32, y: f32| if x < 0.5 && y < 0.5 { 1.0 } else { 0.0 });
/// assert!((corner.mean(64) - 0.25).abs() < 1e-6);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FnAperture<F>(pub F);

impl<F: Fn(f32, f32) -> f32> Aperture for FnAperture<F> {
    const UNIFORM: bool = false;
    fn weight(&self, x: f32, y: f32) -> f32 {
        let v = (self.0)(x, y);
        if v.is_finite() { v } else { 0.0 }
    }
}

/// Largest [`Sampling::space`] accepted (4096 × 4096 samples).
pub const MAX_SPACE_SAMPLES: u32 = 4096;
/// Largest [`Sampling::time`] accepted.
pub const MAX_TIME_SAMPLES: u32 = 1 << 20;

/// Sample counts for the dimensions a field declares varying.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// `n × n` midpoint samples over the pixel (≥ 1).
    pub space: u32,
    /// Midpoint samples over the exposure (≥ 1).
    pub time: u32,
    /// Trapezoid step over wavelength, nm (> 0).
    pub wavelength_step_nm: f32,
}

impl Default for Sampling {
    /// 16 × 16 spatial, 64 temporal, 1 nm spectral.
    fn default() -> Self {
        Self {
            space: 16,
            time: 64,
            wavelength_step_nm: 1.0,
        }
    }
}

/// Planck constant × speed of light, J·m (SI 2019 exact values).
pub const HC: f32 = 6.626_07e-34 * 299_792_458.0;

/// A pixel: aperture `s`, quantum efficiency `η(λ)` (electrons per
/// photon), area and exposure time; it turns a field into a mean number
/// of photo-electrons.
///
/// ```
/// use radiometry::sensor::{FillFactor, Pixel, Sampling, UniformSpectral};
/// use radiometry::spectral::{self, FnCurve, Scaled};
/// let px = Pixel::new(FillFactor::new(1.0).unwrap(), FnCurve::new(380.0, 780.0, |_| 0.6),
///                     (4e-6f32).powi(2), 1e-3, Sampling::default()).unwrap();
/// let e = px.mean_electrons(&UniformSpectral(Scaled::new(spectral::d65(), 1e-4))).unwrap();
/// assert!(e > 0.0);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Pixel<A, Q> {
    /// Spatial response `s(x, y)`.
    pub aperture: A,
    /// Quantum efficiency `η(λ)` ∈ [0, 1].
    pub qe: Q,
    area_m2: f32,
    exposure_s: f32,
    sampling: Sampling,
}

impl<A: Aperture, Q: SpectralCurve> Pixel<A, Q> {
    /// A pixel of area `area_m2 > 0` exposed for `exposure_s ≥ 0` seconds
    /// (zero exposure is allowed and collects nothing).
    pub fn new(
        aperture: A,
        qe: Q,
        area_m2: f32,
        exposure_s: f32,
        sampling: Sampling,
    ) -> Result<Self, SensorError> {
        if !(area_m2.is_finite() && exposure_s.is_finite() && sampling.wavelength_step_nm.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if area_m2 <= 0.0 {
            return Err(SensorError::BadParameter("pixel area must be > 0"));
        }
        if exposure_s < 0.0 {
            return Err(SensorError::BadParameter("exposure must be ≥ 0"));
        }
        if sampling.space == 0 || sampling.time == 0 || sampling.wavelength_step_nm <= 0.0 {
            return Err(SensorError::BadParameter("sample counts and step must be > 0"));
        }
        if sampling.space > MAX_SPACE_SAMPLES || sampling.time > MAX_TIME_SAMPLES {
            return Err(SensorError::BadParameter(
                "at most 4096 × 4096 spatial and 2²⁰ temporal samples",
            ));
        }
        Ok(Self {
            aperture,
            qe,
            area_m2,
            exposure_s,
            sampling,
        })
    }

    /// Exposure time, s.
    pub fn exposure(&self) -> f32 {
        self.exposure_s
    }

    /// A copy with another exposure time (validated as in [`Pixel::new`]).
    pub fn with_exposure(self, exposure_s: f32) -> Result<Self, SensorError>
    where
        A: Copy,
        Q: Copy,
    {
        Self::new(self.aperture, self.qe, self.area_m2, exposure_s, self.sampling)
    }

    /// Mean photo-electrons collected:
    ///
    /// `μ_e = A ∫_0^T ∫_λ ∫∫ E(x,y,λ,t) s(x,y) η(λ) λ/(hc) dx dy dλ dt`,
    ///
    /// the spectral form of EMVA 1288 Release 4.0 §2.1 (`μ_p = A E t λ/(hc)`,
    /// `μ_e = η μ_p`). Only declared dimensions are sampled: a static field
    /// is evaluated at `t = 0` and multiplied by `T`; a spatially uniform
    /// one at the pixel centre times `∫∫ s`; a monochromatic one at its
    /// wavelength. Rules: midpoint in space and time, trapezoid in λ at
    /// [`Sampling::wavelength_step_nm`] over the band ∩ the QE support.
    ///
    /// Zero exposure gives 0. Negative irradiance is integrated as given
    /// (a physical field is ≥ 0); NaN or infinite field values, or a
    /// non-finite monochromatic wavelength, are an error
    /// ([`SensorError::NotFinite`]), as is a non-finite result. Light
    /// outside the QE support collects 0.
    pub fn mean_electrons<F: IrradianceField>(&self, field: &F) -> Result<f32, SensorError> {
        if self.exposure_s == 0.0 {
            return Ok(0.0);
        }
        let mut bad = false;
        // Spectral integral of E·η·λ/(hc) at fixed (x, y, t), photons/(m²·s) → electrons.
        let spectral = |x: f32, y: f32, t: f32, bad: &mut bool| -> f32 {
            match field.spectral() {
                SpectralSupport::Monochromatic(l) => {
                    let e = field.irradiance(x, y, l, t);
                    if !(e.is_finite() && l.is_finite()) {
                        *bad = true;
                        return 0.0;
                    }
                    e * self.qe.value(l) * (l * 1e-9 / HC)
                }
                SpectralSupport::Band { lo, hi } => {
                    let (q0, q1) = self.qe.support();
                    let (lo, hi) = (lo.max(q0), hi.min(q1));
                    if !(lo.is_finite() && hi.is_finite()) || hi <= lo {
                        return 0.0;
                    }
                    let n = libm::ceilf((hi - lo) / self.sampling.wavelength_step_nm).clamp(1.0, 100_000.0)
                        as u32;
                    let h = (hi - lo) / n as f32;
                    let mut acc = crate::spectral::CompensatedF32::default();
                    for i in 0..=n {
                        let l = lo + i as f32 * h;
                        let e = field.irradiance(x, y, l, t);
                        if !e.is_finite() {
                            *bad = true;
                            return 0.0;
                        }
                        let w = if i == 0 || i == n { 0.5 } else { 1.0 };
                        acc.add(w * e * self.qe.value(l) * l);
                    }
                    // λ in nm → ×1e-9 m; /hc. Scale separately to stay in f32 range.
                    acc.value() * h * (1e-9 / HC)
                }
            }
        };
        // Spatial integral ∫∫ E s at fixed t.
        let spatial = |t: f32, bad: &mut bool| -> f32 {
            if F::VARIES_IN_SPACE {
                let n = self.sampling.space;
                let mut acc = 0.0f32;
                for j in 0..n {
                    for i in 0..n {
                        let (x, y) = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                        let s = if A::UNIFORM {
                            1.0
                        } else {
                            self.aperture.weight(x, y)
                        };
                        if s != 0.0 {
                            acc += s * spectral(x, y, t, bad);
                        }
                    }
                }
                let m = acc / (n * n) as f32;
                if A::UNIFORM {
                    m * self.aperture.weight(0.5, 0.5)
                } else {
                    m
                }
            } else {
                spectral(0.5, 0.5, t, bad) * self.aperture.mean(self.sampling.space)
            }
        };
        let temporal = if F::VARIES_IN_TIME {
            let n = self.sampling.time;
            let mut acc = 0.0f32;
            for k in 0..n {
                acc += spatial((k as f32 + 0.5) / n as f32 * self.exposure_s, &mut bad);
            }
            acc / n as f32 * self.exposure_s
        } else {
            spatial(0.0, &mut bad) * self.exposure_s
        };
        let mu = temporal * self.area_m2;
        if bad || !mu.is_finite() {
            Err(SensorError::NotFinite)
        } else {
            Ok(mu)
        }
    }
}

/// A sensor: turns the irradiance field on a pixel into a reading.
///
/// `rng` drives the noise effects; noiseless sensors ignore it. The
/// reading type is the sensor's output unit (DN for a camera, counts for
/// an ambient-light sensor).
///
/// ```
/// use radiometry::sensor::{Emva1288, FillFactor, Monochromatic, Pcg32, Pixel, Sampling, Sensor};
/// use radiometry::spectral::FnCurve;
/// let px = Pixel::new(FillFactor::new(1.0).unwrap(), FnCurve::new(300.0, 1100.0, |_| 0.5),
///                     25e-12, 0.01, Sampling::default()).unwrap();
/// let cam = Emva1288::ideal(px, 0.1, 10_000.0, 12).unwrap(); // noiseless
/// let dn = cam.read(&Monochromatic::new(550.0, 1e-3), &mut Pcg32::new(1)).unwrap();
/// assert_eq!(dn, 35.0); // round(0.1 DN/e⁻ × 346 e⁻)
/// ```
pub trait Sensor {
    /// The reading's type.
    type Reading;
    /// One reading of `field`.
    fn read<F: IrradianceField, G: rand_core::Rng + ?Sized>(
        &self,
        field: &F,
        rng: &mut G,
    ) -> Result<Self::Reading, SensorError>;
}
