//! The pixel equation end to end: the material ball as a simulated camera
//! records it, beside the same ball as an ideal CIE observer sees it —
//! what `radiometry preview … --camera bayer|prism|stacked` draws.
//!
//! `I_c = R(∫∫∫∫ E(x, y, λ, t) s(x, y) q_c(λ))` (the [`radiometry::sensor`]
//! module), here:
//!
//! 1. **Scene radiance** `L(λ)`: the preview scene ([`super`]) rendered
//!    spectrally with `N` hero wavelengths per camera sample
//!    ([`colour::render_spectral`]'s estimator), the sun and the sky both of
//!    the [`Illuminant`]'s spectrum (D65 daylight or CIE A, a tungsten lamp),
//!    scaled so that their luminance is the preview's scalar radiance.
//! 2. **Per pixel and channel**, the photo-electron signal
//!    `∝ ∫ L(λ) q_c(λ) λ dλ` (photons: energy × λ/(hc); the pixel's box
//!    filter is the `s(x, y)` of the jittered camera rays), estimated with the
//!    same hero wavelengths, and the observer's linear sRGB
//!    `∫ L(λ) v_c(λ) dλ` ([`SrgbObserver`]).
//! 3. **Exposure**: one number, [`CameraOptions::exposure`], the fraction of
//!    the full well that the brightest channel of a white diffuser facing the
//!    sun collects (the product of exposure time, aperture and scene level
//!    that a photographer sets); every signal is scaled by the same factor.
//! 4. **Sensor** ([`Emva1288`]): Poisson shot noise, Gaussian dark noise,
//!    gain `K = (2^bits − 1 − offset)/full well`, dark offset, ADC
//!    rounding and clipping — per photosite. A Bayer sensor has one channel
//!    per photosite (RGGB mosaic); the 3-chip prism and the stacked sensor
//!    read three per pixel.
//! 5. **Development**: black level removed and normalised to the full well,
//!    bilinear demosaicing (Bayer, [`demosaic_bilinear`]), then the colour
//!    correction matrix `M` — the least-squares fit of the camera's
//!    illuminant-weighted sensitivities to the observer's,
//!    `min Σ_λ |M E(λ) q(λ) λ − E(λ) v(λ)|²` over 360–780 nm — and a white
//!    balance `D` (diagonal) that makes the white diffuser neutral at
//!    [`WHITE_LEVEL`].
//! 6. **Response curve** `R`: the sRGB transfer function
//!    ([`response::Srgb`]) on the clipped linear value, 8 bits.
//!
//! The observer picture takes step 2's observer values, the same von Kries
//! white balance in linear sRGB (the identity up to scale under D65) and
//! the same `R`. [`CameraReport`] states the difference: the mean CIE 1976
//! ΔE*ab over the ball of the camera against the observer, with and without
//! noise (the noiseless figure is the colour error of the sensitivities and
//! the demosaicing alone), the per-channel ratio camera/observer, and the
//! noise measured against the EMVA 1288 prediction.
//!
//! **Sensitivities** ([`CameraKind::sensitivities`]), each times an IR-cut
//! filter (a logistic edge at 650 nm, 8 nm wide) and, for the Bayer and
//! prism sensors, the quantum efficiency of a 3 µm silicon photodiode behind a
//! 20 %-reflecting surface, `0.8 (1 − exp(−α(λ) · 3 µm))` (α of
//! [`silicon_absorption`], Green & Keevers 1995; zero below 400 nm where the
//! table stops):
//! - *Bayer*: a parametric colour filter array in the shape of measured
//!   camera sensitivities (Jiang, Liu, Gu & Süsstrunk 2013, "What is the
//!   space of spectral sensitivity functions for digital color cameras?",
//!   WACV): blue a Gaussian at 455 nm (σ 28 nm), green at 535 nm (σ 38 nm),
//!   red a long-pass edge at 585 nm (12 nm wide), each over a 2 % floor — a
//!   model, not a measured camera;
//! - *prism*: the crate's [`DichroicPrism`] (cuts at 490 and 590 nm, 5 nm
//!   edges);
//! - *stacked*: the three layers of [`StackedLayers::foveon`] (Beer–Lambert
//!   in silicon; broad, overlapping responses that need a strong matrix).

use super::colour::{self, RgbImage, SpectralMaterial, render_channels};
use super::{Env, Lighting, Options, PreviewError, check_options};
use radiometry::SampledSpectrum;
use radiometry::rng::Pcg32;
use radiometry::sensor::color::{
    BayerPattern, DichroicPrism, StackedLayers, demosaic_bilinear, silicon_absorption,
};
use radiometry::sensor::emva::{GaussianDarkNoise, PoissonShotNoise};
use radiometry::sensor::response::{self, Response};
use radiometry::sensor::{Emva1288, FillFactor, Pixel, Sampling, SensorError};
use radiometry::spectral::uplift::{COLORCHECKER_SRGB8, SrgbObserver, srgb8_to_linear, uplift_reflectance};
use radiometry::spectral::{Blackbody, FnCurve, IlluminantA, SpectralCurve};

/// The linear value the white diffuser facing the sun develops to, in both
/// pictures (below 1, so that it is not clipped).
pub const WHITE_LEVEL: f32 = 0.9;

/// Number of wavelengths of the camera's spectral grid (360, 370, …, 780 nm).
pub const GRID_LEN: usize = 43;
/// Step of the camera's spectral grid, nm.
pub const GRID_STEP_NM: f32 = 10.0;
const LO: f32 = colour::LAMBDA_MIN_NM;
const HI: f32 = colour::LAMBDA_MAX_NM;

/// The camera's wavelengths, nm.
pub fn grid() -> [f32; GRID_LEN] {
    std::array::from_fn(|i| LO + GRID_STEP_NM * i as f32)
}

/// The camera's colour architecture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CameraKind {
    /// A Bayer colour filter array (RGGB) + bilinear demosaicing.
    Bayer,
    /// A 3-chip dichroic prism.
    Prism,
    /// Stacked photodiodes (Foveon-like).
    Stacked,
}

impl CameraKind {
    /// Every kind.
    pub const ALL: [CameraKind; 3] = [CameraKind::Bayer, CameraKind::Prism, CameraKind::Stacked];

    /// The kind of a CLI name.
    pub fn from_name(name: &str) -> Option<CameraKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The CLI name.
    pub fn name(self) -> &'static str {
        match self {
            CameraKind::Bayer => "bayer",
            CameraKind::Prism => "prism",
            CameraKind::Stacked => "stacked",
        }
    }

    /// `q_c(λ)`, `[R, G, B]`, electrons per photon (module docs).
    pub fn sensitivities(self, lambda_nm: f32) -> [f32; 3] {
        if !lambda_nm.is_finite() {
            return [0.0; 3];
        }
        let ir_cut = 1.0 / (1.0 + ((lambda_nm - 650.0) / 8.0).clamp(-80.0, 80.0).exp());
        let qe = || 0.8 * (1.0 - (-silicon_absorption().value(lambda_nm) * 3.0).exp());
        let gauss = |mu: f32, sigma: f32| (-0.5 * ((lambda_nm - mu) / sigma).powi(2)).exp();
        match self {
            CameraKind::Bayer => {
                let red = 1.0 / (1.0 + (-(lambda_nm - 585.0) / 12.0).clamp(-80.0, 80.0).exp());
                let t = [red, gauss(535.0, 38.0), gauss(455.0, 28.0)];
                let q = qe() * ir_cut;
                t.map(|v| (0.02 + 0.98 * v) * q)
            }
            CameraKind::Prism => {
                // Valid constants: the constructor cannot fail.
                let p = DichroicPrism::new(490.0, 590.0, 5.0).map(|p| p.transmittances(lambda_nm));
                let q = qe() * ir_cut;
                p.map_or([0.0; 3], |t| t.map(|v| v * q))
            }
            CameraKind::Stacked => {
                let f = StackedLayers::foveon().fractions(lambda_nm);
                [f[2] * ir_cut, f[1] * ir_cut, f[0] * ir_cut]
            }
        }
    }
}

/// The spectrum of the sun and the sky.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Illuminant {
    /// CIE D65 (daylight; the sRGB white).
    D65,
    /// CIE illuminant A (a 2856 K tungsten lamp).
    A,
    /// A black body at this temperature, kelvin, in `[1000, 40000]`
    /// (Planck's law, [`Blackbody`]).
    Planck(f32),
}

impl Illuminant {
    /// The CLI name (`d65`, `a`, `planck:T`).
    pub fn name(self) -> String {
        match self {
            Illuminant::D65 => String::from("d65"),
            Illuminant::A => String::from("a"),
            Illuminant::Planck(t) => format!("planck:{t}"),
        }
    }

    fn check(self) -> Result<(), PreviewError> {
        match self {
            Illuminant::Planck(t) if !(t.is_finite() && (1000.0..=40_000.0).contains(&t)) => {
                Err(PreviewError::Camera(SensorError::BadParameter(
                    "black-body temperature must be in [1000, 40000] K",
                )))
            }
            _ => Ok(()),
        }
    }

    fn raw(self, lambda_nm: f32) -> f32 {
        match self {
            Illuminant::D65 => radiometry::spectral::d65().value(lambda_nm),
            Illuminant::A => IlluminantA.value(lambda_nm),
            Illuminant::Planck(t) => Blackbody::new(t).map_or(0.0, |b| b.value(lambda_nm)),
        }
    }
}

/// The response curve `R` that encodes both pictures (a curve of
/// [`radiometry::sensor::response`], applied to the clipped linear value).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ResponseCurve {
    /// The sRGB transfer function ([`response::Srgb`]): what a display expects.
    Srgb,
    /// A power law `y = x^(1/γ)` ([`response::Gamma`], `γ ∈ [0.05, 20]`).
    Gamma(f32),
    /// Linear ([`response::Linear`]): the raw picture, dark on a display.
    Linear,
}

impl ResponseCurve {
    /// The curve at `x` (clipped to `[0, 1]`, NaN → 0); a `Gamma` out of its
    /// range is the caller's error, caught by [`render_camera`].
    pub fn apply(&self, x: f32) -> f32 {
        match self {
            ResponseCurve::Srgb => response::Srgb.apply(x),
            ResponseCurve::Linear => response::Linear.apply(x),
            ResponseCurve::Gamma(g) => response::Gamma::new(*g).map_or(0.0, |c| c.apply(x)),
        }
    }

    fn check(&self) -> Result<(), PreviewError> {
        if let ResponseCurve::Gamma(g) = self {
            response::Gamma::new(*g).map_err(PreviewError::Camera)?;
        }
        Ok(())
    }
}

/// The camera of [`render_camera`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraOptions {
    /// Colour architecture.
    pub kind: CameraKind,
    /// Spectrum of the sun and the sky.
    pub illuminant: Illuminant,
    /// Fraction of the full well collected by the white diffuser's brightest
    /// channel, in `(0, 16]` (above 1 the white clips).
    pub exposure: f32,
    /// Saturation capacity, electrons (> 0).
    pub full_well_e: f32,
    /// Temporal dark noise σ_d, electrons (≥ 0).
    pub dark_noise_e: f32,
    /// ADC bits, 8..=16.
    pub bits: u8,
    /// Dark offset, DN (≥ 0, below the ADC's range).
    pub dark_offset_dn: f32,
    /// Shot and dark noise on (`false`: the noiseless mean response).
    pub noise: bool,
    /// Seed of the sensor noise.
    pub seed: u64,
    /// The response curve of both pictures.
    pub response: ResponseCurve,
}

impl Default for CameraOptions {
    fn default() -> Self {
        CameraOptions {
            kind: CameraKind::Bayer,
            illuminant: Illuminant::D65,
            exposure: 0.25,
            full_well_e: 10_000.0,
            dark_noise_e: 6.0,
            bits: 12,
            dark_offset_dn: 64.0,
            noise: true,
            seed: 1,
            response: ResponseCurve::Srgb,
        }
    }
}

type Curve = FnCurve<fn(f32) -> f32>;

/// The EMVA 1288 sensor of a [`CameraOptions`].
#[derive(Clone, Copy, Debug)]
pub struct SensorModel {
    noisy: Emva1288<FillFactor, Curve, PoissonShotNoise, GaussianDarkNoise>,
    noise: bool,
    full_well_e: f32,
    seed: u64,
}

impl SensorModel {
    /// The sensor: gain `K = (2^bits − 1 − offset)/full well`.
    pub fn new(c: &CameraOptions) -> Result<Self, PreviewError> {
        let e = PreviewError::Camera;
        if !(8..=16).contains(&c.bits) {
            return Err(e(SensorError::BadParameter("ADC bits must be in 8..=16")));
        }
        if !(c.full_well_e.is_finite() && c.dark_noise_e.is_finite() && c.dark_offset_dn.is_finite()) {
            return Err(e(SensorError::NotFinite));
        }
        let max = ((1u32 << c.bits) - 1) as f32;
        if !(c.full_well_e > 0.0 && c.dark_offset_dn >= 0.0 && c.dark_offset_dn < 0.5 * max) {
            return Err(e(SensorError::BadParameter(
                "full well must be > 0 and the dark offset in [0, half the ADC range)",
            )));
        }
        let gain = (max - c.dark_offset_dn) / c.full_well_e;
        let qe: Curve = FnCurve::new(LO, HI, |_| 1.0);
        let px = Pixel::new(
            FillFactor::new(1.0).map_err(e)?,
            qe,
            1e-12,
            0.0,
            Sampling::default(),
        )
        .map_err(e)?;
        let noisy = Emva1288::ideal(px, gain, c.full_well_e, c.bits)
            .map_err(e)?
            .with_shot_noise()
            .with_dark_noise(c.dark_noise_e)
            .map_err(e)?
            .with_dark_offset(c.dark_offset_dn)
            .map_err(e)?;
        Ok(SensorModel {
            noisy,
            noise: c.noise,
            full_well_e: c.full_well_e,
            seed: c.seed,
        })
    }

    /// System gain K, DN/e⁻.
    pub fn gain(&self) -> f32 {
        self.noisy.gain()
    }

    /// The EMVA 1288 photon-transfer variance of a reading with mean
    /// `mu_e` electrons (below saturation): `σ_y² = K²(μ_e + σ_d²) + 1/12` DN².
    pub fn predicted_variance_dn(&self, mu_e: f32, dark_noise_e: f32) -> f32 {
        let k = self.gain();
        k * k * (mu_e + dark_noise_e * dark_noise_e) + 1.0 / 12.0
    }

    /// One reading (DN) of photosite `index` with mean `mu_e` electrons;
    /// without noise the rounded mean response.
    pub fn read(&self, mu_e: f32, index: u32) -> f32 {
        if self.noise {
            let mut rng = Pcg32::with_stream(self.seed, index as u64);
            self.noisy.digitize(mu_e, index, &mut rng)
        } else {
            self.noisy.mean_dn(mu_e).round()
        }
    }

    /// A reading back to the fraction of the full well (black level removed).
    pub fn normalise(&self, dn: f32) -> f32 {
        (dn - self.noisy.mean_dn(0.0)) / (self.gain() * self.full_well_e)
    }
}

/// What the camera picture shows against the observer's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraReport {
    /// Pixels compared: wholly on the ball, neither picture clipped.
    pub pixels: usize,
    /// Mean CIE 1976 ΔE*ab, camera (with noise) against observer.
    pub mean_delta_e: f32,
    /// The same without sensor noise: the sensitivities' and the
    /// demosaicing's colour error.
    pub mean_delta_e_noiseless: f32,
    /// Mean ΔE*ab of the 24 ColorChecker patches (the chart the matrix is
    /// fitted on), lit as the white diffuser, noiseless: the classic
    /// camera-profile figure.
    pub chart_delta_e: f32,
    /// The largest of those 24.
    pub chart_delta_e_max: f32,
    /// Per channel, mean noiseless camera / mean observer (linear, over the
    /// pixels): the systematic colour error.
    pub channel_ratio: [f32; 3],
    /// RMS of (noisy − noiseless) over the compared pixels, per channel, as a
    /// fraction of the white level (linear, developed; zero without noise).
    pub noise: [f32; 3],
    /// The EMVA 1288 prediction of [`CameraReport::noise`]: per pixel the
    /// photon-transfer variance of each raw channel, `(μ_e + σ_d²)/FW² +
    /// 1/(12 K² FW²)` — for the Bayer sensor, of the bilinear average of the
    /// 2 or 4 neighbouring photosites where the pixel does not read the
    /// channel itself — through the colour matrix and white balance
    /// (`Σ_j (D M)²_cj σ_j²`), RMS over the pixels.
    pub noise_predicted: [f32; 3],
    /// The white diffuser's brightest channel: mean electrons.
    pub white_electrons: f32,
    /// The EMVA 1288 signal-to-noise ratio there,
    /// `μ_e / √(μ_e + σ_d² + 1/(12 K²))`.
    pub white_snr: f32,
    /// The colour correction matrix with the white balance, `D M`, acting on
    /// raw values divided by the white diffuser's (rows R, G, B of linear
    /// sRGB relative to the white; each row sums to 1). Large off-diagonal
    /// entries amplify noise.
    pub ccm: [[f32; 3]; 3],
}

/// The two pictures and the report.
#[derive(Clone, Debug)]
pub struct CameraRender {
    /// The camera's picture (developed linear sRGB).
    pub camera: RgbImage,
    /// The observer's picture (linear sRGB, white balanced).
    pub observer: RgbImage,
    /// The observer's linear sRGB before white balance.
    pub observer_raw: RgbImage,
    /// The comparison.
    pub report: CameraReport,
}

/// Renders the ball through the camera and the observer (module docs) on
/// the fixed spectral grid [`grid`] (the material is built once there). The pictures hold linear values
/// in which the white diffuser is [`WHITE_LEVEL`]; write them with
/// [`RgbImage::write_encoded`] (clipping and [`CameraOptions::response`]),
/// not the preview's tone curve.
pub fn render_camera<M: SpectralMaterial<GRID_LEN>>(
    material: &M,
    opt: &Options,
    cam: &CameraOptions,
) -> Result<CameraRender, PreviewError> {
    check_options(opt)?;
    if !(cam.exposure.is_finite() && cam.exposure > 0.0 && cam.exposure <= 16.0) {
        return Err(PreviewError::Camera(SensorError::BadParameter(
            "exposure must be in (0, 16]",
        )));
    }
    let sensor = SensorModel::new(cam)?;
    cam.response.check()?;
    cam.illuminant.check()?;
    let lighting = Lighting::new(opt)?;
    let observer = SrgbObserver::new();
    let illum = cam.illuminant;
    let kind = cam.kind;
    let grid = grid();
    // Trapezoid weights of the grid, times the observer's and the camera's
    // (photon-counting) sensitivities.
    let trap = |i: usize| {
        if i == 0 || i == GRID_LEN - 1 {
            0.5 * GRID_STEP_NM
        } else {
            GRID_STEP_NM
        }
    };
    let w_obs: [[f32; 3]; GRID_LEN] = std::array::from_fn(|i| observer.weights(grid[i]).map(|v| v * trap(i)));
    let w_cam: [[f32; 3]; GRID_LEN] =
        std::array::from_fn(|i| kind.sensitivities(grid[i]).map(|v| v * grid[i] * trap(i)));
    // The illuminant, normalised to unit luminance under the observer.
    let raw: [f32; GRID_LEN] = grid.map(|l| illum.raw(l));
    let y: f32 = (0..GRID_LEN)
        .map(|i| raw[i] * (0.2126 * w_obs[i][0] + 0.7152 * w_obs[i][1] + 0.0722 * w_obs[i][2]))
        .sum();
    if !(y.is_finite() && y > 0.0) {
        return Err(PreviewError::Camera(SensorError::NotFinite));
    }
    let e: [f32; GRID_LEN] = raw.map(|v| v / y);
    let (sky_l, sun_l) = (lighting.sky().sky_radiance(), lighting.sun().cap_radiance());
    let env = Env {
        sky: SampledSpectrum(e.map(|v| v * sky_l)),
        ground: SampledSpectrum(e.map(|v| v * sky_l)),
        sun: SampledSpectrum(e.map(|v| v * sun_l)),
    };
    let brdf = material
        .at(&grid)
        .ok_or(PreviewError::Camera(SensorError::BadParameter(
            "the material cannot be built on the camera's wavelengths",
        )))?;
    // Per sample: observer RGB (0..3) and camera photon signal (3..6).
    let channels = |v: SampledSpectrum<GRID_LEN>| {
        let mut out = [0.0f32; 6];
        for (i, value) in v.0.iter().enumerate() {
            for c in 0..3 {
                out[c] += value * w_obs[i][c];
                out[3 + c] += value * w_cam[i][c];
            }
        }
        out
    };
    let (pixels, coverage) = render_channels::<6>(
        opt,
        |p, d, u, _| channels(lighting.shade_spectrum(&brdf, p, -d, u, &env)),
        |d, _| channels(lighting.radiance_env(d, &env)),
    );

    // The white diffuser facing the sun: L = (E⊥ + π L_sky) E(λ)/π.
    let white_l = (lighting.e_perp + std::f32::consts::PI * sky_l) / std::f32::consts::PI;
    let response = |rho: &dyn Fn(f32) -> f32| {
        let (mut q, mut v) = ([0.0f64; 3], [0.0f64; 3]);
        for i in 0..GRID_LEN {
            let r = rho(grid[i]) as f64 * e[i] as f64;
            for c in 0..3 {
                q[c] += r * w_cam[i][c] as f64;
                v[c] += r * w_obs[i][c] as f64;
            }
        }
        (q, v)
    };
    let (white_q, white_v) = response(&|_| 1.0);
    let cam_ref = white_q.map(|v| v * white_l as f64);
    let obs_ref = white_v.map(|v| v * white_l as f64);
    // The colour matrix: least squares over the 24 ColorChecker patches (their
    // uplifted spectra) under the illuminant, camera → observer — a chart
    // calibration, as cameras are profiled.
    let mut qq = [[0.0f64; 3]; 3];
    let mut vq = [[0.0f64; 3]; 3];
    let mut chart = [([0.0f64; 3], [0.0f64; 3]); 24];
    for (patch, slot) in COLORCHECKER_SRGB8.iter().zip(chart.iter_mut()) {
        let rho = uplift_reflectance(patch.map(srgb8_to_linear)).map_err(PreviewError::Uplift)?;
        let (q, v) = response(&|l| rho.eval(l));
        *slot = (q, v);
        for a in 0..3 {
            for b in 0..3 {
                qq[a][b] += q[a] * q[b];
                vq[a][b] += v[a] * q[b];
            }
        }
    }
    let qq_inv = invert3(qq).ok_or(PreviewError::Camera(SensorError::Singular))?;
    let ccm: [[f64; 3]; 3] =
        std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| vq[r][k] * qq_inv[k][c]).sum()));

    // Exposure: the white's brightest channel at `exposure` × full well.
    let cam_max = cam_ref.iter().fold(0.0f64, |m, &v| m.max(v));
    if cam_max.is_nan() || cam_max <= 0.0 {
        return Err(PreviewError::Camera(SensorError::Singular));
    }
    let to_e = cam.exposure as f64 * cam.full_well_e as f64 / cam_max;
    let white_frac = cam_ref.map(|v| v * to_e / cam.full_well_e as f64);
    // White balance: D · M · white = WHITE_LEVEL in every channel.
    let m_white: [f64; 3] = std::array::from_fn(|r| (0..3).map(|k| ccm[r][k] * white_frac[k]).sum());
    let not_positive = |v: &f64| v.is_nan() || *v <= 0.0;
    if m_white.iter().any(not_positive) || obs_ref.iter().any(not_positive) {
        return Err(PreviewError::Camera(SensorError::Singular));
    }
    let d_cam = m_white.map(|v| WHITE_LEVEL as f64 / v);
    let d_obs = obs_ref.map(|v| WHITE_LEVEL as f64 / v);

    let n = opt.size as usize;
    let observer_raw: Vec<[f32; 3]> = pixels.iter().map(|p| [p[0], p[1], p[2]]).collect();
    let observer_wb: Vec<[f32; 3]> = observer_raw
        .iter()
        .map(|p| std::array::from_fn(|c| (p[c] as f64 * d_obs[c]) as f32))
        .collect();
    let develop = |noise: bool| -> Result<Vec<[f32; 3]>, PreviewError> {
        let s = SensorModel { noise, ..sensor };
        let mut planes = vec![[0.0f32; 3]; n * n];
        match kind {
            CameraKind::Bayer => {
                let pattern = BayerPattern::Rggb;
                let mut raw = vec![0.0f32; n * n];
                for (i, (r, p)) in raw.iter_mut().zip(&pixels).enumerate() {
                    let c = pattern.channel_at(i % n, i / n);
                    let mu = (p[3 + c] as f64 * to_e) as f32;
                    *r = s.normalise(s.read(mu, i as u32));
                }
                demosaic_bilinear(&raw, n, n, pattern, &mut planes).map_err(PreviewError::Camera)?;
            }
            CameraKind::Prism | CameraKind::Stacked => {
                for (i, (o, p)) in planes.iter_mut().zip(&pixels).enumerate() {
                    for c in 0..3 {
                        let mu = (p[3 + c] as f64 * to_e) as f32;
                        o[c] = s.normalise(s.read(mu, (3 * i + c) as u32));
                    }
                }
            }
        }
        Ok(planes
            .iter()
            .map(|r| {
                std::array::from_fn(|row| {
                    let v: f64 = (0..3).map(|k| ccm[row][k] * r[k] as f64).sum();
                    (v * d_cam[row]) as f32
                })
            })
            .collect())
    };
    let camera = develop(cam.noise)?;
    let clean = develop(false)?;

    // The comparison over pixels wholly on the ball where nothing clips.
    // The white-balanced matrix on white-normalised raw values: rows sum to 1.
    let balanced: [[f32; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|c| (d_cam[r] * ccm[r][c] * white_frac[c] / WHITE_LEVEL as f64) as f32)
    });
    let mut report = CameraReport {
        ccm: balanced,
        ..CameraReport::default()
    };
    let (mut de, mut de0) = (0.0f64, 0.0f64);
    let mut sums = [[0.0f64; 3]; 2]; // clean camera, observer
    let mut sq = [0.0f64; 3];
    let mut predicted = [0.0f64; 3];
    let k_dn = sensor.gain() as f64;
    let fw = cam.full_well_e as f64;
    // EMVA 1288 variance of a normalised raw value with mean μ electrons.
    let raw_var =
        |mu: f64| (mu + (cam.dark_noise_e as f64).powi(2)) / (fw * fw) + 1.0 / (12.0 * k_dn * k_dn * fw * fw);
    let dm: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|c| d_cam[r] * ccm[r][c]));
    for i in 0..n * n {
        let (a, b, c) = (camera[i], observer_wb[i], clean[i]);
        if coverage[i] < 1.0 || [a, b, c].iter().flatten().any(|&v| v >= 1.0) {
            continue;
        }
        report.pixels += 1;
        de += delta_e(a, b) as f64;
        de0 += delta_e(c, b) as f64;
        let var: [f64; 3] = std::array::from_fn(|k| match kind {
            CameraKind::Bayer => bayer_variance(i % n, i / n, n, k, &|x, y| {
                let c = BayerPattern::Rggb.channel_at(x, y);
                raw_var(pixels[y * n + x][3 + c] as f64 * to_e)
            }),
            _ => raw_var(pixels[i][3 + k] as f64 * to_e),
        });
        for k in 0..3 {
            sums[0][k] += c[k] as f64;
            sums[1][k] += b[k] as f64;
            sq[k] += ((a[k] - c[k]) as f64).powi(2);
            predicted[k] += (0..3).map(|j| dm[k][j] * dm[k][j] * var[j]).sum::<f64>();
        }
    }
    if report.pixels > 0 {
        let np = report.pixels as f64;
        report.mean_delta_e = (de / np) as f32;
        report.mean_delta_e_noiseless = (de0 / np) as f32;
        report.channel_ratio = std::array::from_fn(|k| (sums[0][k] / sums[1][k]) as f32);
        if cam.noise {
            report.noise = std::array::from_fn(|k| ((sq[k] / np).sqrt() / WHITE_LEVEL as f64) as f32);
            report.noise_predicted =
                std::array::from_fn(|k| ((predicted[k] / np).sqrt() / WHITE_LEVEL as f64) as f32);
        }
    }
    // The chart itself, lit as the white diffuser, noiseless: the fit's residual.
    let mut chart_de = [0.0f32; 24];
    for (d, (q, v)) in chart_de.iter_mut().zip(&chart) {
        let raw = q.map(|x| x * white_l as f64 * to_e / fw);
        let a: [f32; 3] = std::array::from_fn(|r| (0..3).map(|j| dm[r][j] * raw[j]).sum::<f64>() as f32);
        let b: [f32; 3] = std::array::from_fn(|r| (v[r] * white_l as f64 * d_obs[r]) as f32);
        *d = delta_e(a, b);
    }
    report.chart_delta_e = chart_de.iter().sum::<f32>() / 24.0;
    report.chart_delta_e_max = chart_de.iter().fold(0.0f32, |m, &v| m.max(v));
    let mu = cam.exposure * cam.full_well_e;
    let k = sensor.gain();
    report.white_electrons = mu;
    report.white_snr = mu / (mu + cam.dark_noise_e * cam.dark_noise_e + 1.0 / (12.0 * k * k)).sqrt();

    let img = |rgb: Vec<[f32; 3]>| RgbImage::new(opt.size, opt.size, rgb, coverage.clone());
    let bad = || PreviewError::Camera(SensorError::BadBuffer);
    Ok(CameraRender {
        camera: img(camera).ok_or_else(bad)?,
        observer: img(observer_wb).ok_or_else(bad)?,
        observer_raw: img(observer_raw).ok_or_else(bad)?,
        report,
    })
}

/// The variance of channel `k` at pixel `(x, y)` of an `n × n` RGGB mosaic
/// after [`demosaic_bilinear`]: the photosite's own variance where it reads
/// `k`, otherwise `Σ_j (w_j/Σw)² σ_j²` over the photosites of colour `k` in
/// the 3 × 3 neighbourhood with weights `[1 2 1]ᵀ[1 2 1]` (mirrored at the
/// borders as the demosaicing mirrors them; photosites are independent).
fn bayer_variance(x: usize, y: usize, n: usize, k: usize, var_at: &dyn Fn(usize, usize) -> f64) -> f64 {
    let pattern = BayerPattern::Rggb;
    if pattern.channel_at(x, y) == k {
        return var_at(x, y);
    }
    let reflect = |i: isize| -> usize {
        let p = 2 * (n as isize - 1);
        let m = i.rem_euclid(p.max(1));
        (if m >= n as isize { p - m } else { m }) as usize
    };
    const K: [f64; 3] = [1.0, 2.0, 1.0];
    let mut sites: Vec<((usize, usize), f64)> = Vec::with_capacity(9);
    let mut den = 0.0;
    for (j, ky) in K.iter().enumerate() {
        let yy = reflect(y as isize + j as isize - 1);
        for (i, kx) in K.iter().enumerate() {
            let xx = reflect(x as isize + i as isize - 1);
            if pattern.channel_at(xx, yy) == k {
                den += ky * kx;
                match sites.iter_mut().find(|(p, _)| *p == (xx, yy)) {
                    Some((_, w)) => *w += ky * kx,
                    None => sites.push(((xx, yy), ky * kx)),
                }
            }
        }
    }
    if den <= 0.0 {
        return 0.0;
    }
    sites
        .iter()
        .map(|&((xx, yy), w)| (w / den) * (w / den) * var_at(xx, yy))
        .sum()
}

/// The inverse of a 3 × 3 matrix by cofactors; `None` when singular.
fn invert3(m: [[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let c = |r0: usize, r1: usize, c0: usize, c1: usize| m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0];
    let cof = [
        [c(1, 2, 1, 2), -c(1, 2, 0, 2), c(1, 2, 0, 1)],
        [-c(0, 2, 1, 2), c(0, 2, 0, 2), -c(0, 2, 0, 1)],
        [c(0, 1, 1, 2), -c(0, 1, 0, 2), c(0, 1, 0, 1)],
    ];
    let det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    if det.is_nan() || det.abs() <= 1e-12 * scale * scale * scale {
        return None;
    }
    // inverse = adjugate / det, adjugate = cofactorᵀ.
    Some(std::array::from_fn(|r| {
        std::array::from_fn(|col| cof[col][r] / det)
    }))
}

/// The sRGB → XYZ matrix of IEC 61966-2-1 (D65).
const SRGB_TO_XYZ: [[f32; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

/// CIE 1976 L*a*b* of linear sRGB `rgb`, white = linear sRGB
/// `(WHITE_LEVEL, WHITE_LEVEL, WHITE_LEVEL)` (CIE 015:2018 §8.2.1).
fn lab(rgb: [f32; 3]) -> [f32; 3] {
    let xyz = |p: [f32; 3]| -> [f32; 3] {
        std::array::from_fn(|r| {
            SRGB_TO_XYZ[r][0] * p[0] + SRGB_TO_XYZ[r][1] * p[1] + SRGB_TO_XYZ[r][2] * p[2]
        })
    };
    let w = xyz([WHITE_LEVEL; 3]);
    let v = xyz(rgb);
    let f = |t: f32| {
        let d = 6.0f32 / 29.0;
        if t > d * d * d {
            t.cbrt()
        } else {
            t / (3.0 * d * d) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(v[0] / w[0]), f(v[1] / w[1]), f(v[2] / w[2]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// ΔE*ab (CIE 1976) between two linear sRGB colours.
pub fn delta_e(a: [f32; 3], b: [f32; 3]) -> f32 {
    let (p, q) = (lab(a), lab(b));
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

impl RgbImage {
    /// The 8-bit pixels for a camera-style picture: each linear value clipped
    /// to `[0, 1]` and encoded by the response curve `r`, `R G B` row-major.
    pub fn to_encoded8(&self, r: ResponseCurve) -> Vec<u8> {
        self.rgb()
            .iter()
            .flat_map(|p| p.map(|v| (r.apply(v) * 255.0 + 0.5).clamp(0.0, 255.0) as u8))
            .collect()
    }

    /// Writes the picture through [`RgbImage::to_encoded8`] to `path` as PNG
    /// or SVG (the PNG in an `<image>`).
    #[cfg(feature = "plot")]
    pub fn write_encoded(
        &self,
        path: &std::path::Path,
        format: super::Format,
        r: ResponseCurve,
        description: &str,
    ) -> std::io::Result<()> {
        let png = super::image::encode_png8(
            self.width(),
            self.height(),
            png::ColorType::Rgb,
            &self.to_encoded8(r),
            description,
        )?;
        match format {
            super::Format::Png => std::fs::write(path, png),
            super::Format::Svg => std::fs::write(
                path,
                super::image::svg_wrap(&png, self.width(), self.height(), description),
            ),
        }
    }
}

#[cfg(test)]
mod tests;
