//! Colour material balls: the preview scene of [`super`] with a coloured sun
//! and sky, rendered in linear RGB ([`render_rgb`]) or spectrally with hero
//! wavelengths ([`render_spectral`]), written as 8-bit sRGB ([`RgbImage`]).
//!
//! **Light.** The sun and the sky keep their scalar radiances
//! ([`Options::sun_irradiance`], [`Options::sky_radiance`]); [`LightColours`]
//! tints them (linear sRGB, white = `(1, 1, 1)`) and may add a ground below
//! the horizontal plane (a multiple of the sky radiance per channel; a
//! horizon line gives metals something to reflect). The estimator is the grey
//! one ([`Lighting::shade_spectrum`]): the same directions, densities and MIS
//! weights, per channel — so a grey BRDF under white light gives the grey
//! render's numbers in every channel, bit for bit (tested). In spectral
//! mode a colour `c` is the light spectrum `m ρ(λ) D65(λ)`
//! ([`RgbIlluminant`], the uplift of `c/m`, `m = max c`): white is D65.
//!
//! **Spectral** (hero wavelengths: Wilkie et al. 2014, "Hero wavelength
//! spectral sampling", Computer Graphics Forum 33(4)): each camera sample
//! carries `N` wavelengths `λ_j = 360 + 420 nm · frac(ξ + j/N)`, the BRDF is
//! built at those wavelengths ([`SpectralMaterial`]), and the sample's
//! radiance `L(λ_j)` becomes linear sRGB through the CIE 1931 observer under
//! D65 ([`SrgbObserver`]): `RGB ≈ (420 nm / N) Σ_j L(λ_j) v(λ_j)`, unbiased
//! for the observer's integral over 360–780 nm. `ξ` is stratified over the
//! pixel's samples (`(s + ξ₀)/samples`, `ξ₀` per pixel from its own stream,
//! so the directions of the grey render are unchanged).
//!
//! **Materials.** Any `Brdf<Spectrum = Vec3>` renders in RGB; a monochrome
//! BRDF (the spec grammar's `AnyBrdf` today) through [`AsRgb`] (each value
//! splatted, [`ToLinearRgb`]) and, spectrally, through [`Splat`]. The
//! [`Preset`]s build typed coloured materials — gold and copper from their
//! measured `η, k` ([`Metal`]), a red plastic — in RGB and at any
//! wavelengths.
//!
//! **Hooking an RGB run-time BRDF in.** A run-time BRDF whose `Spectrum` is
//! `Vec3` goes straight into [`render_rgb`]; one whose spectrum is another
//! type implements [`ToLinearRgb`] for it and goes through [`AsRgb`]. For
//! [`render_spectral`] it implements [`SpectralMaterial`] (build the
//! material at `N` wavelengths, e.g. by uplifting its RGB parameters with
//! [`uplift_reflectance`] once and evaluating the spectra per sample).

use super::envmap::EnvMap;
use super::image::tone_map;
use super::{
    Env, Environment, Lighting, MapEnv, Options, PreviewError, camera_ray_with, check_options, half_fov_tan,
    hit_ball,
};
use crate::tradeoff::Progress;
use radiometry::glam::Vec3;
use radiometry::rng::Pcg32;
use radiometry::spectral::SpectralCurve;
use radiometry::spectral::uplift::{
    RgbIlluminant, SigmoidSpectrum, SrgbObserver, UpliftError, uplift_reflectance,
};
use radiometry::{Albedo, Brdf, BrdfSample, SampledSpectrum, Spectrum};
use radiometry_brdfs::metals::Metal;
use radiometry_brdfs::microfacet::Conductor;
use radiometry_brdfs::openpbr::{OpenPbr, OpenPbrParams};
use radiometry_brdfs::{BrdfError, Ggx, HeightCorrelated, Microfacet};
use std::fmt;
use std::sync::Mutex;

/// Shortest wavelength of hero sampling, nm.
pub const LAMBDA_MIN_NM: f32 = 360.0;
/// Longest wavelength of hero sampling, nm.
pub const LAMBDA_MAX_NM: f32 = 780.0;
/// Largest number of hero wavelengths per sample.
pub const MAX_HERO: usize = 32;

/// Seed perturbation of the per-pixel wavelength offsets (kept apart from
/// the direction streams).
const LAMBDA_STREAM_KEY: u64 = 0x6a09_e667_f3bc_c909;

/// A spectrum with a linear sRGB reading: what [`AsRgb`] needs of a BRDF's
/// values. `f32` (grey) is splatted, `Vec3` is itself.
pub trait ToLinearRgb: Spectrum {
    /// The value as linear sRGB.
    fn to_linear_rgb(self) -> Vec3;
}

impl ToLinearRgb for f32 {
    #[inline]
    fn to_linear_rgb(self) -> Vec3 {
        Vec3::splat(self)
    }
}

impl ToLinearRgb for Vec3 {
    #[inline]
    fn to_linear_rgb(self) -> Vec3 {
        self
    }
}

/// A BRDF seen in linear RGB: its values through [`ToLinearRgb`]; pdfs and
/// directions unchanged.
#[derive(Clone, Copy, Debug)]
pub struct AsRgb<'a, B: ?Sized>(pub &'a B);

impl<B: Brdf + ?Sized> Brdf for AsRgb<'_, B>
where
    B::Spectrum: ToLinearRgb,
{
    type Spectrum = Vec3;
    fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
        self.0.eval(wi, wo).to_linear_rgb()
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<Vec3>> {
        self.0.sample(wo, u).map(|s| BrdfSample {
            wi: s.wi,
            pdf: s.pdf,
            weight: s.weight.to_linear_rgb(),
        })
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
    fn is_smooth(&self) -> bool {
        self.0.is_smooth()
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<Vec3> {
        let a = self.0.directional_albedo(wo);
        Albedo {
            value: a.value.to_linear_rgb(),
            error: a.error,
            is_bound: a.is_bound,
        }
    }
}

/// A monochrome BRDF as any spectrum: every channel (wavelength) the same
/// value.
#[derive(Clone, Copy, Debug)]
pub struct Splat<'a, B: ?Sized, S>(pub &'a B, pub std::marker::PhantomData<S>);

impl<'a, B: ?Sized, S> Splat<'a, B, S> {
    /// Wraps `brdf`.
    pub fn new(brdf: &'a B) -> Self {
        Splat(brdf, std::marker::PhantomData)
    }
}

impl<B: Brdf<Spectrum = f32> + ?Sized, S: Spectrum> Brdf for Splat<'_, B, S> {
    type Spectrum = S;
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        S::splat(self.0.eval(wi, wo))
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        self.0.sample(wo, u).map(|s| BrdfSample {
            wi: s.wi,
            pdf: s.pdf,
            weight: S::splat(s.weight),
        })
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        self.0.pdf(wi, wo)
    }
    fn is_smooth(&self) -> bool {
        self.0.is_smooth()
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        let a = self.0.directional_albedo(wo);
        Albedo {
            value: S::splat(a.value),
            error: a.error,
            is_bound: a.is_bound,
        }
    }
}

/// The colours of the sun, the sky and the ground (linear sRGB multipliers
/// of the sun's and the sky's radiances; finite, ≥ 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightColours {
    /// The sun's colour.
    pub sun: [f32; 3],
    /// The sky's colour.
    pub sky: [f32; 3],
    /// The ground's radiance as a multiple of the sky radiance, per channel;
    /// `None`: no ground (the sky all around, as in the grey scene).
    pub ground: Option<[f32; 3]>,
}

impl Default for LightColours {
    /// White sun and sky, no ground: the grey preview's light.
    fn default() -> Self {
        LightColours {
            sun: [1.0; 3],
            sky: [1.0; 3],
            ground: None,
        }
    }
}

impl LightColours {
    /// A daylight look: a white (D65) sun, a pale blue sky `(0.75, 0.85, 1.0)`
    /// and a darker grey-brown ground `(0.2, 0.17, 0.15)` (the docs' balls).
    pub const DAYLIGHT: LightColours = LightColours {
        sun: [1.0, 1.0, 1.0],
        sky: [0.75, 0.85, 1.0],
        ground: Some([0.2, 0.17, 0.15]),
    };

    /// The ground's colour (the sky's when there is no ground).
    pub fn ground(&self) -> [f32; 3] {
        self.ground.unwrap_or(self.sky)
    }

    fn check(&self) -> Result<(), PreviewError> {
        for (name, c) in [
            ("sun colour", self.sun),
            ("sky colour", self.sky),
            ("ground colour", self.ground()),
        ] {
            for v in c {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(PreviewError::Colour(name, v));
                }
            }
        }
        Ok(())
    }
}

/// A rendered colour picture: linear sRGB and ball coverage per pixel,
/// row-major from the top-left corner, `width × height`.
#[derive(Clone, Debug, PartialEq)]
pub struct RgbImage {
    width: u32,
    height: u32,
    rgb: Vec<[f32; 3]>,
    coverage: Vec<f32>,
}

impl RgbImage {
    /// An image from its pixels (`width · height` of each), or `None` when
    /// the lengths do not match.
    pub fn new(width: u32, height: u32, rgb: Vec<[f32; 3]>, coverage: Vec<f32>) -> Option<Self> {
        let n = (width as usize).checked_mul(height as usize)?;
        (rgb.len() == n && coverage.len() == n).then_some(RgbImage {
            width,
            height,
            rgb,
            coverage,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Linear sRGB of every pixel (row-major).
    pub fn rgb(&self) -> &[[f32; 3]] {
        &self.rgb
    }

    /// The fraction of each pixel's samples that hit the ball.
    pub fn coverage(&self) -> &[f32] {
        &self.coverage
    }

    /// The 8-bit pixels, `R G B` row-major: each channel through the grey
    /// preview's tone curve ([`tone_map`]: extended Reinhard, then the sRGB
    /// transfer function), so a grey picture has the grey bytes.
    pub fn to_rgb8(&self, exposure: f32) -> Vec<u8> {
        self.rgb
            .iter()
            .flat_map(|p| p.map(|v| tone_map(v, exposure)))
            .collect()
    }

    /// Two images of equal height side by side, `gap` pixels of `gap_rgb`
    /// between them (linear values).
    pub fn beside(&self, other: &RgbImage, gap: u32, gap_rgb: [f32; 3]) -> RgbImage {
        let h = self.height.max(other.height);
        let w = self.width + gap + other.width;
        let mut rgb = vec![gap_rgb; (w * h) as usize];
        let mut cov = vec![0.0; (w * h) as usize];
        for (img, x0) in [(self, 0), (other, self.width + gap)] {
            for y in 0..img.height {
                for x in 0..img.width {
                    let s = (y * img.width + x) as usize;
                    let d = (y * w + x0 + x) as usize;
                    rgb[d] = img.rgb[s];
                    cov[d] = img.coverage[s];
                }
            }
        }
        RgbImage {
            width: w,
            height: h,
            rgb,
            coverage: cov,
        }
    }

    /// The picture as a PNG file's bytes (8-bit RGB), with `description` in a
    /// `Description` text chunk when it is not empty.
    #[cfg(feature = "plot")]
    pub fn encode_png(&self, exposure: f32, description: &str) -> std::io::Result<Vec<u8>> {
        super::image::encode_png8(
            self.width,
            self.height,
            png::ColorType::Rgb,
            &self.to_rgb8(exposure),
            description,
        )
    }

    /// Writes the picture to `path` as PNG or SVG (the PNG in an `<image>`).
    #[cfg(feature = "plot")]
    pub fn write(
        &self,
        path: &std::path::Path,
        format: super::Format,
        exposure: f32,
        description: &str,
    ) -> std::io::Result<()> {
        let png = self.encode_png(exposure, description)?;
        match format {
            super::Format::Png => std::fs::write(path, png),
            super::Format::Svg => std::fs::write(
                path,
                super::image::svg_wrap(&png, self.width, self.height, description),
            ),
        }
    }
}

/// The ball rendered row by row on `opt.threads` threads, `C` channels per
/// pixel: `shade(p, d, u, ξ)` is a camera sample hitting the ball at `p`
/// (ray direction `d`, 5 uniforms `u`, wavelength offset `ξ`),
/// `background(d, ξ)` one that misses. The direction random numbers are
/// drawn exactly as the grey render draws them.
pub(crate) fn render_channels<const C: usize>(
    opt: &Options,
    shade: impl Fn(Vec3, Vec3, [f32; 5], f32) -> [f32; C] + Sync,
    background: impl Fn(Vec3, f32) -> [f32; C] + Sync,
) -> (Vec<[f32; C]>, Vec<f32>) {
    let n = opt.size as usize;
    let mut pixels = vec![[0.0f32; C]; n * n];
    let mut coverage = vec![0.0f32; n * n];
    let threads = if opt.threads == 0 {
        std::thread::available_parallelism().map_or(1, |t| t.get())
    } else {
        opt.threads
    }
    .clamp(1, n);
    let progress = Progress::new(opt.progress, n);
    let rows = Mutex::new(pixels.chunks_mut(n).zip(coverage.chunks_mut(n)).enumerate());
    let t = half_fov_tan();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let next = rows.lock().map(|mut r| r.next()).unwrap_or(None);
                    let Some((y, (prow, crow))) = next else { break };
                    for (x, (px_out, c_out)) in prow.iter_mut().zip(crow.iter_mut()).enumerate() {
                        let index = (y * n + x) as u64;
                        let mut rng = Pcg32::with_stream(opt.seed, index);
                        let xi0 = Pcg32::with_stream(opt.seed ^ LAMBDA_STREAM_KEY, index).next_f32();
                        let mut sum = [0.0f64; C];
                        let mut hits = 0u32;
                        for s in 0..opt.samples {
                            let (px, py) = (x as f32 + rng.next_f32(), y as f32 + rng.next_f32());
                            let (o, d) = camera_ray_with(t, px, py, opt.size);
                            let u = [
                                rng.next_f32(),
                                rng.next_f32(),
                                rng.next_f32(),
                                rng.next_f32(),
                                rng.next_f32(),
                            ];
                            let xi = ((s as f32 + xi0) / opt.samples as f32)
                                .min(radiometry::math::ONE_MINUS_EPSILON);
                            let v = match hit_ball(o, d) {
                                Some(p) => {
                                    hits += 1;
                                    shade(p, d, u, xi)
                                }
                                None => background(d, xi),
                            };
                            for (a, b) in sum.iter_mut().zip(v) {
                                *a += b as f64;
                            }
                        }
                        *px_out = sum.map(|v| (v / opt.samples as f64) as f32);
                        *c_out = hits as f32 / opt.samples as f32;
                    }
                    progress.tick(&format!("row {}", y + 1));
                }
            });
        }
    });
    progress.finish();
    (pixels, coverage)
}

/// Renders the ball in linear RGB: any `Brdf<Spectrum = Vec3>` (a grey one
/// through [`AsRgb`]) under the coloured sun and sky.
pub fn render_rgb<B: Brdf<Spectrum = Vec3> + Sync + ?Sized>(
    brdf: &B,
    opt: &Options,
    colours: &LightColours,
) -> Result<RgbImage, PreviewError> {
    check_options(opt)?;
    colours.check()?;
    let lighting = Lighting::new(opt)?;
    let env = Env {
        sky: Vec3::from_array(colours.sky) * lighting.sky().sky_radiance(),
        ground: Vec3::from_array(colours.ground()) * lighting.sky().sky_radiance(),
        sun: Vec3::from_array(colours.sun) * lighting.sun().cap_radiance(),
    };
    let (rgb, coverage) = render_channels::<3>(
        opt,
        |p, d, u, _| lighting.shade_spectrum(brdf, p, -d, u, &env).to_array(),
        |d, _| lighting.radiance_env(d, &env).to_array(),
    );
    Ok(RgbImage {
        width: opt.size,
        height: opt.size,
        rgb,
        coverage,
    })
}

/// Renders the ball in linear RGB under an environment map
/// ([`super::envmap`]): the map times `scale` all around (the background
/// shows it), plus the preview's sun cap tinted by `sun_colour` (set
/// [`Options::sun_irradiance`] to 0 to light by the map alone).
/// [`Options::sky_radiance`] only steers the choice between the sun's cone and
/// the cosine-weighted technique; the map's mean luminance times `scale` is
/// a good value.
pub fn render_rgb_env<B: Brdf<Spectrum = Vec3> + Sync + ?Sized>(
    brdf: &B,
    opt: &Options,
    map: &EnvMap,
    scale: f32,
    sun_colour: [f32; 3],
) -> Result<RgbImage, PreviewError> {
    check_options(opt)?;
    LightColours {
        sun: sun_colour,
        ..LightColours::default()
    }
    .check()?;
    if !(scale.is_finite() && scale >= 0.0) {
        return Err(PreviewError::EnvMap(format!(
            "scale {scale} must be finite and ≥ 0"
        )));
    }
    let lighting = Lighting::new(opt)?;
    let sampler = super::envmap::EnvSampler::new(map);
    let env = MapEnv {
        map,
        scale,
        sun: Vec3::from_array(sun_colour) * lighting.sun().cap_radiance(),
        sampler: sampler.as_ref(),
    };
    let (rgb, coverage) = render_channels::<3>(
        opt,
        |p, d, u, _| lighting.shade_spectrum(brdf, p, -d, u, &env).to_array(),
        |d, _| env.radiance(&lighting, d).to_array(),
    );
    Ok(RgbImage {
        width: opt.size,
        height: opt.size,
        rgb,
        coverage,
    })
}

/// A material that can be built at any `N` wavelengths (nm) — what
/// [`render_spectral`] builds at every camera sample.
pub trait SpectralMaterial<const N: usize>: Sync {
    /// The BRDF at those wavelengths.
    type Brdf: Brdf<Spectrum = SampledSpectrum<N>> + Sync;
    /// Builds it (`None` skips the sample: it counts as black).
    fn at(&self, lambdas_nm: &[f32; N]) -> Option<Self::Brdf>;
}

/// A monochrome BRDF is the same at every wavelength.
impl<'a, B: Brdf<Spectrum = f32> + Sync + ?Sized, const N: usize> SpectralMaterial<N> for AsGrey<'a, B> {
    type Brdf = Splat<'a, B, SampledSpectrum<N>>;
    fn at(&self, _lambdas_nm: &[f32; N]) -> Option<Self::Brdf> {
        Some(Splat::new(self.0))
    }
}

/// A monochrome BRDF used as a [`SpectralMaterial`] (every wavelength the
/// same value).
#[derive(Clone, Copy, Debug)]
pub struct AsGrey<'a, B: ?Sized>(pub &'a B);

/// The hero wavelengths of offset `xi ∈ [0, 1)`: `λ_j = 360 + 420 frac(ξ + j/N)`.
pub fn hero_wavelengths<const N: usize>(xi: f32) -> [f32; N] {
    let span = LAMBDA_MAX_NM - LAMBDA_MIN_NM;
    core::array::from_fn(|j| {
        let t = xi + j as f32 / N as f32;
        let t = t - t.floor();
        (LAMBDA_MIN_NM + span * t).min(LAMBDA_MAX_NM)
    })
}

/// The light spectra of `colours` ([`RgbIlluminant`]).
pub(crate) fn light_spectra(
    colours: &LightColours,
) -> Result<(RgbIlluminant, RgbIlluminant, RgbIlluminant), PreviewError> {
    colours.check()?;
    let sun = RgbIlluminant::new(colours.sun).map_err(PreviewError::Uplift)?;
    let sky = RgbIlluminant::new(colours.sky).map_err(PreviewError::Uplift)?;
    let ground = RgbIlluminant::new(colours.ground()).map_err(PreviewError::Uplift)?;
    Ok((sun, sky, ground))
}

/// Renders the ball spectrally with `N` hero wavelengths per camera sample
/// (module docs), `1 ≤ N ≤` [`MAX_HERO`]; the picture is linear sRGB.
pub fn render_spectral<const N: usize, M: SpectralMaterial<N>>(
    material: &M,
    opt: &Options,
    colours: &LightColours,
) -> Result<RgbImage, PreviewError> {
    if N == 0 || N > MAX_HERO {
        return Err(PreviewError::Wavelengths(N));
    }
    check_options(opt)?;
    let lighting = Lighting::new(opt)?;
    let (sun_spd, sky_spd, ground_spd) = light_spectra(colours)?;
    let observer = SrgbObserver::new();
    let (sky_l, sun_l) = (lighting.sky().sky_radiance(), lighting.sun().cap_radiance());
    let per_sample = (LAMBDA_MAX_NM - LAMBDA_MIN_NM) / N as f32;
    let lights = |l: &[f32; N]| Env {
        sky: SampledSpectrum(l.map(|x| sky_l * sky_spd.value(x))),
        ground: SampledSpectrum(l.map(|x| sky_l * ground_spd.value(x))),
        sun: SampledSpectrum(l.map(|x| sun_l * sun_spd.value(x))),
    };
    let to_rgb = |l: &[f32; N], v: SampledSpectrum<N>| {
        let mut rgb = [0.0f32; 3];
        for (lambda, value) in l.iter().zip(v.0) {
            let w = observer.weights(*lambda);
            for (o, wc) in rgb.iter_mut().zip(w) {
                *o += value * wc * per_sample;
            }
        }
        rgb
    };
    let (rgb, coverage) = render_channels::<3>(
        opt,
        |p, d, u, xi| {
            let l = hero_wavelengths::<N>(xi);
            let Some(brdf) = material.at(&l) else {
                return [0.0; 3];
            };
            to_rgb(&l, lighting.shade_spectrum(&brdf, p, -d, u, &lights(&l)))
        },
        |d, xi| {
            let l = hero_wavelengths::<N>(xi);
            to_rgb(&l, lighting.radiance_env(d, &lights(&l)))
        },
    );
    Ok(RgbImage {
        width: opt.size,
        height: opt.size,
        rgb,
        coverage,
    })
}

/// The hero-wavelength counts [`render_spectral_n`] dispatches to.
pub const HERO_COUNTS: [usize; 4] = [1, 4, 8, 16];

/// [`render_spectral`] with the number of hero wavelengths chosen at run
/// time, one of [`HERO_COUNTS`] (another count is
/// [`PreviewError::Wavelengths`]).
pub fn render_spectral_n<M>(
    n: usize,
    material: &M,
    opt: &Options,
    colours: &LightColours,
) -> Result<RgbImage, PreviewError>
where
    M: SpectralMaterial<1> + SpectralMaterial<4> + SpectralMaterial<8> + SpectralMaterial<16>,
{
    match n {
        1 => render_spectral::<1, M>(material, opt, colours),
        4 => render_spectral::<4, M>(material, opt, colours),
        8 => render_spectral::<8, M>(material, opt, colours),
        16 => render_spectral::<16, M>(material, opt, colours),
        _ => Err(PreviewError::Wavelengths(n)),
    }
}

/// The typed colour materials of `radiometry preview --material`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PresetKind {
    /// Gold: GGX α = 0.2 (height-correlated Smith, single scattering), the
    /// exact conductor Fresnel of Au (Johnson & Christy 1972).
    Gold,
    /// Copper: as gold with Cu's `η, k`.
    Copper,
    /// A red plastic: OpenPBR with `base_color = (0.6, 0.04, 0.03)`,
    /// `specular_roughness = 0.25`, IOR 1.5.
    RedPlastic,
}

impl PresetKind {
    /// Every preset.
    pub const ALL: [PresetKind; 3] = [PresetKind::Gold, PresetKind::Copper, PresetKind::RedPlastic];

    /// The CLI name: `gold`, `copper`, `red-plastic`.
    pub fn name(self) -> &'static str {
        match self {
            PresetKind::Gold => "gold",
            PresetKind::Copper => "copper",
            PresetKind::RedPlastic => "red-plastic",
        }
    }

    /// The preset of a CLI name.
    pub fn from_name(name: &str) -> Option<PresetKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// GGX α of the metal presets.
pub const METAL_ALPHA: f32 = 0.2;
/// Linear sRGB base colour of the red plastic preset.
pub const RED_PLASTIC_RGB: [f32; 3] = [0.6, 0.04, 0.03];
/// `specular_roughness` of the red plastic preset.
pub const RED_PLASTIC_ROUGHNESS: f32 = 0.25;

/// A typed colour material (module docs), ready to build in RGB or at any
/// wavelengths.
#[derive(Clone, Copy, Debug)]
pub struct Preset {
    kind: PresetKind,
    base: SigmoidSpectrum,
}

/// The BRDF of a [`Preset`] in spectrum `S`.
#[derive(Clone, Debug)]
pub enum PresetBrdf<S: Spectrum> {
    /// A GGX conductor.
    Metal(Microfacet<Ggx, HeightCorrelated, Conductor<S>>),
    /// An OpenPBR dielectric.
    Plastic(Box<OpenPbr<S>>),
}

impl<S: Spectrum> Brdf for PresetBrdf<S> {
    type Spectrum = S;
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        match self {
            PresetBrdf::Metal(b) => b.eval(wi, wo),
            PresetBrdf::Plastic(b) => b.eval(wi, wo),
        }
    }
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        match self {
            PresetBrdf::Metal(b) => b.sample(wo, u),
            PresetBrdf::Plastic(b) => b.sample(wo, u),
        }
    }
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        match self {
            PresetBrdf::Metal(b) => b.pdf(wi, wo),
            PresetBrdf::Plastic(b) => b.pdf(wi, wo),
        }
    }
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        match self {
            PresetBrdf::Metal(b) => b.directional_albedo(wo),
            PresetBrdf::Plastic(b) => b.directional_albedo(wo),
        }
    }
}

impl Preset {
    /// The preset (its base colour uplifted once).
    pub fn new(kind: PresetKind) -> Result<Self, PreviewError> {
        let base = uplift_reflectance(RED_PLASTIC_RGB).map_err(PreviewError::Uplift)?;
        Ok(Preset { kind, base })
    }

    /// Which preset.
    pub fn kind(&self) -> PresetKind {
        self.kind
    }

    fn metal(&self) -> Option<Metal> {
        match self.kind {
            PresetKind::Gold => Some(Metal::Au),
            PresetKind::Copper => Some(Metal::Cu),
            PresetKind::RedPlastic => None,
        }
    }

    fn plastic<S: Spectrum>(base_color: S) -> Result<PresetBrdf<S>, BrdfError> {
        let p = OpenPbrParams {
            base_color,
            specular_roughness: RED_PLASTIC_ROUGHNESS,
            specular_ior: 1.5,
            ..OpenPbrParams::default()
        };
        Ok(PresetBrdf::Plastic(Box::new(OpenPbr::new(p)?)))
    }

    /// The RGB material: metals by [`Conductor::metal`] (per channel the
    /// `η, k` matching the sRGB-reduced reflectance at 0° and 82°).
    pub fn rgb(&self) -> Result<PresetBrdf<Vec3>, PreviewError> {
        match self.metal() {
            Some(m) => Ok(PresetBrdf::Metal(Microfacet::new(
                Ggx::new(METAL_ALPHA).map_err(PreviewError::Material)?,
                Conductor::metal(m),
            ))),
            None => Self::plastic(Vec3::from_array(RED_PLASTIC_RGB)).map_err(PreviewError::Material),
        }
    }
}

impl<const N: usize> SpectralMaterial<N> for Preset {
    type Brdf = PresetBrdf<SampledSpectrum<N>>;
    /// Metals with the measured `η(λ), k(λ)`; the plastic's base colour is
    /// the uplifted spectrum at the wavelengths.
    fn at(&self, lambdas_nm: &[f32; N]) -> Option<Self::Brdf> {
        match self.metal() {
            Some(m) => Some(PresetBrdf::Metal(Microfacet::new(
                Ggx::new(METAL_ALPHA).ok()?,
                Conductor::metal_sampled(m, lambdas_nm).ok()?,
            ))),
            None => Self::plastic(SampledSpectrum(lambdas_nm.map(|l| self.base.eval(l)))).ok(),
        }
    }
}

impl fmt::Display for PresetKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Uplift errors as preview errors.
impl From<UpliftError> for PreviewError {
    fn from(e: UpliftError) -> Self {
        PreviewError::Uplift(e)
    }
}

#[cfg(test)]
mod tests;
