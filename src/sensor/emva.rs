//! The EMVA 1288 linear camera model, every effect opt-in by type.
//!
//! EMVA Standard 1288 Release 4.0 Linear (2021), §2 "Sensitivity,
//! linearity and noise": photons `μ_p = A E t λ/(hc)` become electrons
//! `μ_e = η μ_p` with Poisson shot noise `σ_e² = μ_e`; dark noise
//! `σ_d` (electrons) is added; the system gain `K` (DN/e⁻) and an
//! ADC give `μ_y = μ_y.dark + K μ_e` with quantisation noise
//! `σ_q² = 1/12 DN²`, so that the **photon transfer** relation holds:
//!
//! `σ_y² = K² σ_d² + σ_q² + K (μ_y − μ_y.dark)`.
//!
//! (Equation numbers are not cited: they differ between releases 3.1
//! and 4.0; the relations are those of §2 in both.)
//! Saturation: electrons are clipped at the saturation capacity, the
//! output at `2^bits − 1`. Optional DSNU (offset) and PRNU (gain)
//! non-uniformity are per-pixel, deterministic in the pixel index.
//!
//! Effects are chosen by type: [`NoShotNoise`] / [`PoissonShotNoise`],
//! [`NoDarkNoise`] / [`GaussianDarkNoise`], [`NoFixedPattern`] /
//! [`FixedPatternNoise`]. The "off" types are zero-sized and cost nothing.
//!
//! ```
//! use radiometry::sensor::{Emva1288, FillFactor, Pcg32, Pixel, Sampling};
//! use radiometry::spectral::FnCurve;
//! let px = Pixel::new(FillFactor::new(1.0).unwrap(), FnCurve::new(300.0, 1100.0, |_| 0.5),
//!                     25e-12, 0.01, Sampling::default()).unwrap();
//! let cam = Emva1288::ideal(px, 0.5, 8_000.0, 12).unwrap()
//!     .with_shot_noise()
//!     .with_dark_noise(3.0).unwrap()
//!     .with_dark_offset(10.0).unwrap();
//! let mut rng = Pcg32::new(1);
//! let dn = cam.digitize(1000.0, 0, &mut rng);
//! assert!(dn > 400.0 && dn < 620.0);
//! // Beyond full well: 8000 e⁻ → 4000 DN + offset, plus dark noise (σ = 1.5 DN).
//! assert!((cam.digitize(1e9, 0, &mut rng) - 4010.0).abs() < 10.0);
//! ```

use super::noise::{Pcg32, poisson, standard_normal};
use super::{Aperture, IrradianceField, Pixel, Sensor, SensorError};
use crate::math::clamp_to;
use crate::spectral::SpectralCurve;
use rand_core::Rng;

/// Shot noise on the photo-electron count.
pub trait ShotNoise {
    /// A realisation of the electron count with mean `mu_e ≥ 0`.
    fn electrons<G: Rng + ?Sized>(&self, mu_e: f32, rng: &mut G) -> f32;
}

/// No shot noise: the count is its mean.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoShotNoise;

impl ShotNoise for NoShotNoise {
    #[inline]
    fn electrons<G: Rng + ?Sized>(&self, mu_e: f32, _rng: &mut G) -> f32 {
        mu_e.max(0.0)
    }
}

/// Poisson shot noise (photon counting statistics), sampled by
/// [`poisson`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PoissonShotNoise;

impl ShotNoise for PoissonShotNoise {
    #[inline]
    fn electrons<G: Rng + ?Sized>(&self, mu_e: f32, rng: &mut G) -> f32 {
        poisson(rng, mu_e)
    }
}

/// Temporal dark noise, in electrons, added before the gain.
pub trait DarkNoise {
    /// One realisation (zero mean).
    fn sample<G: Rng + ?Sized>(&self, rng: &mut G) -> f32;
}

/// No dark noise.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoDarkNoise;

impl DarkNoise for NoDarkNoise {
    #[inline]
    fn sample<G: Rng + ?Sized>(&self, _rng: &mut G) -> f32 {
        0.0
    }
}

/// Gaussian dark noise with standard deviation `sigma_e` electrons.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussianDarkNoise {
    /// σ_d, electrons.
    pub sigma_e: f32,
}

impl DarkNoise for GaussianDarkNoise {
    #[inline]
    fn sample<G: Rng + ?Sized>(&self, rng: &mut G) -> f32 {
        self.sigma_e * standard_normal(rng)
    }
}

/// Spatial (fixed-pattern) non-uniformity.
pub trait FixedPattern {
    /// `(gain factor 1 + PRNU_i, offset DSNU_i in DN)` of pixel `index`.
    fn pattern(&self, index: u32) -> (f32, f32);
}

/// A perfectly uniform sensor.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoFixedPattern;

impl FixedPattern for NoFixedPattern {
    #[inline]
    fn pattern(&self, _index: u32) -> (f32, f32) {
        (1.0, 0.0)
    }
}

/// Gaussian DSNU (σ in DN) and PRNU (relative σ of the gain), drawn once
/// per pixel from a PCG32 stream keyed by `(seed, index)` — so a pixel
/// keeps its pattern from frame to frame (EMVA 1288 §4 "spatial
/// nonuniformity"). The gain factor is floored at 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedPatternNoise {
    /// DSNU standard deviation, DN.
    pub dsnu_dn: f32,
    /// PRNU standard deviation, as a fraction of the signal.
    pub prnu: f32,
    /// Pattern seed.
    pub seed: u64,
}

impl FixedPattern for FixedPatternNoise {
    fn pattern(&self, index: u32) -> (f32, f32) {
        let mut r = Pcg32::with_stream(self.seed, index as u64);
        let g = (1.0 + self.prnu * standard_normal(&mut r)).max(0.0);
        (g, self.dsnu_dn * standard_normal(&mut r))
    }
}

/// An EMVA 1288 linear camera: a [`Pixel`] plus gain, offset, full well,
/// ADC and the chosen noise effects. See the module docs.
#[derive(Clone, Copy, Debug)]
pub struct Emva1288<A, Q, S = NoShotNoise, D = NoDarkNoise, P = NoFixedPattern> {
    /// The pixel (aperture, QE, area, exposure).
    pub pixel: Pixel<A, Q>,
    gain_k: f32,
    dark_offset_dn: f32,
    saturation_e: f32,
    max_dn: f32,
    shot: S,
    dark: D,
    pattern: P,
}

impl<A: Aperture, Q: SpectralCurve> Emva1288<A, Q> {
    /// A noiseless camera: gain `K > 0` DN/e⁻, saturation capacity
    /// `> 0` electrons, ADC with `1..=32` bits, no offset.
    pub fn ideal(
        pixel: Pixel<A, Q>,
        gain_k: f32,
        saturation_e: f32,
        adc_bits: u8,
    ) -> Result<Self, SensorError> {
        if !(gain_k.is_finite() && saturation_e.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if gain_k <= 0.0 || saturation_e <= 0.0 {
            return Err(SensorError::BadParameter(
                "gain and saturation capacity must be > 0",
            ));
        }
        if !(1..=32).contains(&adc_bits) {
            return Err(SensorError::BadParameter("ADC bits must be in 1..=32"));
        }
        let max_dn = ((1u64 << adc_bits) - 1) as f32;
        Ok(Self {
            pixel,
            gain_k,
            dark_offset_dn: 0.0,
            saturation_e,
            max_dn,
            shot: NoShotNoise,
            dark: NoDarkNoise,
            pattern: NoFixedPattern,
        })
    }
}

impl<A: Aperture, Q: SpectralCurve, S: ShotNoise, D: DarkNoise, P: FixedPattern> Emva1288<A, Q, S, D, P> {
    /// Turns Poisson shot noise on.
    pub fn with_shot_noise(self) -> Emva1288<A, Q, PoissonShotNoise, D, P> {
        let Self {
            pixel,
            gain_k,
            dark_offset_dn,
            saturation_e,
            max_dn,
            dark,
            pattern,
            ..
        } = self;
        Emva1288 {
            pixel,
            gain_k,
            dark_offset_dn,
            saturation_e,
            max_dn,
            shot: PoissonShotNoise,
            dark,
            pattern,
        }
    }

    /// Adds Gaussian dark noise σ_d ≥ 0 electrons.
    pub fn with_dark_noise(
        self,
        sigma_e: f32,
    ) -> Result<Emva1288<A, Q, S, GaussianDarkNoise, P>, SensorError> {
        if !sigma_e.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if sigma_e < 0.0 {
            return Err(SensorError::BadParameter("dark noise must be ≥ 0"));
        }
        let Self {
            pixel,
            gain_k,
            dark_offset_dn,
            saturation_e,
            max_dn,
            shot,
            pattern,
            ..
        } = self;
        Ok(Emva1288 {
            pixel,
            gain_k,
            dark_offset_dn,
            saturation_e,
            max_dn,
            shot,
            dark: GaussianDarkNoise { sigma_e },
            pattern,
        })
    }

    /// Adds DSNU (σ, DN) and PRNU (relative σ), both finite and ≥ 0.
    pub fn with_fixed_pattern(
        self,
        dsnu_dn: f32,
        prnu: f32,
        seed: u64,
    ) -> Result<Emva1288<A, Q, S, D, FixedPatternNoise>, SensorError> {
        if !(dsnu_dn.is_finite() && prnu.is_finite()) {
            return Err(SensorError::NotFinite);
        }
        if dsnu_dn < 0.0 || prnu < 0.0 {
            return Err(SensorError::BadParameter("DSNU and PRNU must be ≥ 0"));
        }
        let Self {
            pixel,
            gain_k,
            dark_offset_dn,
            saturation_e,
            max_dn,
            shot,
            dark,
            ..
        } = self;
        Ok(Emva1288 {
            pixel,
            gain_k,
            dark_offset_dn,
            saturation_e,
            max_dn,
            shot,
            dark,
            pattern: FixedPatternNoise { dsnu_dn, prnu, seed },
        })
    }

    /// Sets the dark offset `μ_y.dark` (DN, finite, ≥ 0). An offset keeps
    /// dark noise from being clipped at 0 DN, as in real cameras.
    pub fn with_dark_offset(mut self, offset_dn: f32) -> Result<Self, SensorError> {
        if !offset_dn.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if offset_dn < 0.0 {
            return Err(SensorError::BadParameter("dark offset must be ≥ 0"));
        }
        self.dark_offset_dn = offset_dn;
        Ok(self)
    }

    /// System gain K, DN/e⁻.
    pub fn gain(&self) -> f32 {
        self.gain_k
    }

    /// Saturation capacity, electrons.
    pub fn saturation(&self) -> f32 {
        self.saturation_e
    }

    /// Largest output, `2^bits − 1` DN.
    pub fn max_dn(&self) -> f32 {
        self.max_dn
    }

    /// The noiseless, unquantised mean response `μ_y = μ_y.dark + K min(μ_e, μ_e.sat)`
    /// (EMVA 1288 §2.2), clipped to `[0, 2^bits − 1]`.
    pub fn mean_dn(&self, mu_e: f32) -> f32 {
        let e = if mu_e.is_nan() {
            0.0
        } else {
            clamp_to(mu_e, 0.0, self.saturation_e)
        };
        clamp_to(self.dark_offset_dn + self.gain_k * e, 0.0, self.max_dn)
    }

    /// One digital value for a mean of `mu_e` photo-electrons at pixel
    /// `pixel_index` (for DSNU/PRNU):
    ///
    /// `y = clip(round(μ_y.dark + DSNU_i + K (min(n_e, μ_e.sat) + n_d)), 0, 2^bits − 1)`,
    /// `n_e ~ shot(μ_e (1 + PRNU_i))`, `n_d ~ dark`.
    ///
    /// Negative or NaN `mu_e` reads as 0 electrons (no light); the result
    /// is always a finite integer in `[0, 2^bits − 1]`.
    pub fn digitize<G: Rng + ?Sized>(&self, mu_e: f32, pixel_index: u32, rng: &mut G) -> f32 {
        let (g, off) = self.pattern.pattern(pixel_index);
        let mu = if mu_e.is_nan() {
            0.0
        } else {
            (mu_e * g).clamp(0.0, 1e12)
        };
        let ne = self.shot.electrons(mu, rng).min(self.saturation_e);
        let nd = self.dark.sample(rng);
        let y = self.dark_offset_dn + off + self.gain_k * (ne + nd);
        clamp_to(libm::roundf(y), 0.0, self.max_dn)
    }

    /// One reading of `field` at pixel `pixel_index`: [`Pixel::mean_electrons`]
    /// then [`Self::digitize`].
    pub fn read_pixel<F: IrradianceField, G: Rng + ?Sized>(
        &self,
        field: &F,
        pixel_index: u32,
        rng: &mut G,
    ) -> Result<f32, SensorError> {
        let mu = self.pixel.mean_electrons(field)?;
        Ok(self.digitize(mu, pixel_index, rng))
    }
}

impl<A: Aperture, Q: SpectralCurve, S: ShotNoise, D: DarkNoise, P: FixedPattern> Sensor
    for Emva1288<A, Q, S, D, P>
{
    type Reading = f32;
    /// [`Emva1288::read_pixel`] at pixel 0.
    fn read<F: IrradianceField, G: Rng + ?Sized>(&self, field: &F, rng: &mut G) -> Result<f32, SensorError> {
        self.read_pixel(field, 0, rng)
    }
}
