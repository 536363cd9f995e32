//! A material-ball renderer: a unit sphere with one BRDF, seen by a pinhole
//! camera, lit by a sun (a uniform spherical cap, [`Cap`]) and a uniform sky
//! ([`UniformSky`]) — what `radiometry preview SPEC --out ball.png` draws.
//!
//! | piece | what it is |
//! |---|---|
//! | [`render`] | the image: per pixel, [`Options::samples`] camera rays, each shaded with one light sample and one BRDF sample combined by multiple importance sampling; parallel over rows with `std::thread::scope` |
//! | [`Lighting`] | the sun and the sky, and [`Lighting::shade`], the one-sample-per-technique estimator of the reflected radiance at one shading point |
//! | [`Image`] | the linear radiance and the sphere coverage of every pixel; [`tone_map`] to 8 bits; PNG and SVG output with the `plot` feature ([`image`] module) |
//! | [`colour`] | the same scene in colour: coloured sun, sky and ground ([`Env`]), RGB ([`colour::render_rgb`]) and hero-wavelength spectral ([`colour::render_spectral`]) renders, typed colour materials, 8-bit RGB output |
//! | [`envmap`] | equirectangular environment maps (Radiance `.hdr` with the `hdr` feature) and their importance sampling, lighting [`colour::render_rgb_env`] |
//! | [`camera`] | the pixel equation end to end: the ball through a simulated camera (Bayer, prism, stacked; EMVA 1288 noise; demosaicing; colour matrix; response curve) beside the CIE 1931 observer |
//!
//! **Scene.** World axes: `+Y` up, the camera on `+Z` at distance
//! [`CAMERA_DISTANCE`] looking at the sphere (radius 1, at the origin) with a
//! vertical field of view [`FIELD_OF_VIEW_DEG`] (the ball fills ~86 % of the
//! frame). The sun direction has an elevation above the horizontal plane and
//! an azimuth measured from the camera's side (`0°`: behind the camera,
//! positive: toward the viewer's right). The sky surrounds the scene on every
//! side with the same radiance (also below the horizon: there is no ground), so
//! every shading point sees the sky over its whole hemisphere — a white
//! furnace when the sun is off. The background pixels show what a camera ray
//! that misses the ball sees: the sky, plus the sun where the ray lies in the
//! sun's cap. A convex ball does not shadow itself, so there are no visibility
//! tests.
//!
//! **Estimator** (Veach & Guibas 1995, "Optimally combining sampling
//! techniques for Monte Carlo rendering", the multi-sample model, §3, with the
//! power heuristic β = 2, §4.2). At a shading point with local frame
//! [`Frame::from_normal`]`(n)` and view `ωo`, the incident radiance is
//! `L(ω) = L_sky + L_sun 1_cap(ω)`. Two techniques, one sample each:
//! - *light*: with probability `q` a direction uniform in the sun's cone
//!   (density `1/(2π(1 − cos σ))`), otherwise a cosine-weighted direction for
//!   the sky (density `cos θ/π`); `q = E_sun/(E_sun + E_sky)`, the sun's share of
//!   the irradiance at the point in closed form ([`Cap::irradiance`] of the cap
//!   in the local frame, horizon-clipped; `E_sky = π L_sky`). The light density
//!   `p_L` is that mixture;
//! - *BRDF*: the BRDF's own [`Brdf::sample`], density `p_B` (its `pdf`).
//!
//! Each sample `ω_k` from technique `k` contributes
//! `f(ω_k, ωo) L(ω_k) cos θ_k / p_k(ω_k) · w_k(ω_k)` with
//! `w_k = p_k² / (p_L² + p_B²)`. The sum is unbiased for any `q` that is
//! positive where the sun is visible; it is exact (zero variance) for a
//! Lambertian BRDF under the sky alone, where both densities are `cos θ/π`.
//! Camera rays are jittered uniformly inside the pixel (a box filter), so a
//! pixel on the silhouette averages ball and background.
//!
//! **Determinism.** Pixel `(x, y)` draws from its own
//! [`Pcg32::with_stream`]`(seed, y · size + x)`: the image depends on the
//! options only, not on the number of threads or their scheduling.
//!
//! ```
//! use radiometry_tools::preview::{Options, render};
//! use radiometry_tools::spec::{model::build_brdf, parse_brdf};
//!
//! let spec = "lambertian(albedo=1)";
//! let brdf = build_brdf(spec, &parse_brdf(spec)?)?;
//! // A white furnace: a white Lambertian ball under the sky alone vanishes.
//! let opt = Options { size: 8, samples: 4, sun_irradiance: 0.0, progress: false, ..Options::default() };
//! let img = render(&brdf, &opt)?;
//! assert!(img.radiance().iter().all(|&l| (l - opt.sky_radiance).abs() < 1e-4 * opt.sky_radiance));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod camera;
pub mod colour;
pub mod envmap;
pub mod image;

pub use image::{Format, Image, WHITE_POINT, tone_map};

use crate::tradeoff::Progress;
use radiometry::glam::Vec3;
use radiometry::light::{Cap, LightError, UniformSky};
use radiometry::math::ONE_MINUS_EPSILON;
use radiometry::rng::Pcg32;
use radiometry::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};
use radiometry::{Brdf, Frame, Spectrum};
use radiometry_brdfs::openpbr::{Layering, OpenPbr, OpenPbrParams};
use std::f32::consts::{PI, TAU};
use std::fmt;
use std::sync::Mutex;

/// Default image size (pixels, square).
pub const DEFAULT_SIZE: u32 = 256;
/// Default camera samples per pixel (each one light and one BRDF sample).
pub const DEFAULT_SAMPLES: u32 = 256;
/// Largest image size accepted.
pub const MAX_SIZE: u32 = 8192;
/// Largest number of samples per pixel accepted.
pub const MAX_SAMPLES: u32 = 1 << 20;
/// Distance of the pinhole from the centre of the unit ball.
pub const CAMERA_DISTANCE: f32 = 4.0;
/// Vertical (and horizontal) field of view of the camera, degrees.
pub const FIELD_OF_VIEW_DEG: f32 = 33.4;
/// Views more grazing than this (`cos θo`) are lifted to it at the
/// silhouette, where rounding could put `ωo` below the horizon.
pub const MIN_COS_VIEW: f32 = 1e-4;

/// What to render and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Image width and height in pixels, in `[1, MAX_SIZE]`.
    pub size: u32,
    /// Camera samples per pixel, in `[1, MAX_SAMPLES]`.
    pub samples: u32,
    /// Sun elevation above the horizontal plane, degrees in `[-90, 90]`.
    pub sun_elevation: f32,
    /// Sun azimuth, degrees: `0` behind the camera, positive toward the
    /// viewer's right.
    pub sun_azimuth: f32,
    /// Angular radius (half-angle) of the sun's cap, degrees in `(0, 90]`
    /// (the real sun: 0.27°).
    pub sun_radius: f32,
    /// The sun's irradiance at normal incidence `E⊥ = π L sin²σ`; `0` turns
    /// the sun off.
    pub sun_irradiance: f32,
    /// The sky's radiance (uniform, all around).
    pub sky_radiance: f32,
    /// Seed of the per-pixel generators.
    pub seed: u64,
    /// Worker threads (`0`: [`std::thread::available_parallelism`]).
    pub threads: usize,
    /// A progress bar on stderr (with the `progress-bar` feature; plain lines
    /// otherwise).
    pub progress: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            size: DEFAULT_SIZE,
            samples: DEFAULT_SAMPLES,
            sun_elevation: 40.0,
            sun_azimuth: -45.0,
            sun_radius: 2.0,
            sun_irradiance: 5.0,
            sky_radiance: 0.15,
            seed: 1,
            threads: 0,
            progress: true,
        }
    }
}

/// Why a preview could not be rendered.
#[derive(Debug)]
#[non_exhaustive]
pub enum PreviewError {
    /// `size` is 0 or above [`MAX_SIZE`].
    Size(u32),
    /// `samples` is 0 or above [`MAX_SAMPLES`].
    Samples(u32),
    /// An angle is out of its range or not finite (name, value).
    Angle(&'static str, f32),
    /// The sun or the sky was rejected.
    Light(LightError),
    /// Writing the image failed.
    Io(std::io::Error),
    /// The textured ball's base parameters (or a colour preset) were
    /// rejected by their BRDF.
    Material(radiometry_brdfs::BrdfError),
    /// A light colour is negative or not finite (name, value).
    Colour(&'static str, f32),
    /// A colour could not be uplifted to a spectrum.
    Uplift(radiometry::spectral::uplift::UpliftError),
    /// The number of hero wavelengths is 0 or above `colour::MAX_HERO`.
    Wavelengths(usize),
    /// The simulated camera was rejected (a sensor parameter out of range).
    Camera(radiometry::sensor::SensorError),
    /// An environment map was rejected or could not be read.
    EnvMap(String),
}

impl fmt::Display for PreviewError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PreviewError::Size(s) => write!(f, "image size {s} is outside [1, {MAX_SIZE}]"),
            PreviewError::Samples(s) => write!(f, "samples per pixel {s} is outside [1, {MAX_SAMPLES}]"),
            PreviewError::Angle(name, v) => write!(f, "{name} {v} is out of range"),
            PreviewError::Light(e) => write!(f, "{e}"),
            PreviewError::Io(e) => write!(f, "{e}"),
            PreviewError::Material(e) => write!(f, "material: {e}"),
            PreviewError::Colour(name, v) => write!(f, "{name} component {v} must be finite and >= 0"),
            PreviewError::Uplift(e) => write!(f, "{e}"),
            PreviewError::Wavelengths(n) => {
                write!(f, "{n} hero wavelengths: must be in [1, {}]", colour::MAX_HERO)
            }
            PreviewError::Camera(e) => write!(f, "camera: {e}"),
            PreviewError::EnvMap(e) => write!(f, "environment map: {e}"),
        }
    }
}

impl std::error::Error for PreviewError {}

impl From<LightError> for PreviewError {
    fn from(e: LightError) -> Self {
        PreviewError::Light(e)
    }
}

impl From<std::io::Error> for PreviewError {
    fn from(e: std::io::Error) -> Self {
        PreviewError::Io(e)
    }
}

/// The sun and the sky of the preview, in world space.
#[derive(Clone, Copy, Debug)]
pub struct Lighting {
    sun: Cap<f32>,
    sky: UniformSky<f32>,
    /// Tangents of the sun's axis (for cone sampling).
    e1: Vec3,
    e2: Vec3,
    /// `1 − cos σ` without cancellation, and the cone density `1/(2π(1 − cos σ))`.
    v_sigma: f32,
    cone_pdf: f32,
    /// `sin σ` and `E⊥ = π L sin²σ`.
    sin_sigma: f32,
    e_perp: f32,
}

impl Lighting {
    /// The lighting of `opt` (angles in degrees; see [`Options`]).
    pub fn new(opt: &Options) -> Result<Self, PreviewError> {
        let finite_in = |name, v: f32, lo: f32, hi: f32| {
            if v.is_finite() && v >= lo && v <= hi {
                Ok(v)
            } else {
                Err(PreviewError::Angle(name, v))
            }
        };
        let el = finite_in("sun elevation", opt.sun_elevation, -90.0, 90.0)?.to_radians();
        let az = finite_in("sun azimuth", opt.sun_azimuth, -360.0, 360.0)?.to_radians();
        let radius = finite_in("sun radius", opt.sun_radius, 0.0, 90.0)?;
        if radius <= 0.0 {
            return Err(PreviewError::Angle("sun radius", radius));
        }
        let sigma = radius.to_radians().min(std::f32::consts::FRAC_PI_2);
        let axis = Vec3::new(az.sin() * el.cos(), el.sin(), az.cos() * el.cos());
        let sun = Cap::from_normal_irradiance(axis, sigma, opt.sun_irradiance)?;
        let sky = UniformSky::new(opt.sky_radiance)?;
        let f = Frame::from_normal(sun.axis()).ok_or(LightError::InvalidDirection)?;
        let h = (0.5 * sigma).sin();
        let v_sigma = 2.0 * h * h;
        let cone_pdf = 1.0 / (TAU * v_sigma);
        Ok(Lighting {
            sun,
            sky,
            e1: f.s,
            e2: f.t,
            v_sigma,
            cone_pdf: if cone_pdf.is_finite() { cone_pdf } else { 0.0 },
            sin_sigma: sigma.sin(),
            e_perp: sun.cap_radiance() * PI * sigma.sin() * sigma.sin(),
        })
    }

    /// The sun (world space).
    pub fn sun(&self) -> &Cap<f32> {
        &self.sun
    }

    /// The sky.
    pub fn sky(&self) -> &UniformSky<f32> {
        &self.sky
    }

    /// Incident radiance from world direction `w`: the sky, plus the sun in
    /// its cap.
    pub fn radiance(&self, w: Vec3) -> f32 {
        let sun = if self.sun.contains(w) {
            self.sun.cap_radiance()
        } else {
            0.0
        };
        self.sky.sky_radiance() + sun
    }

    /// Uniform direction in the sun's cone (world space).
    fn cone_sample(&self, u: [f32; 2]) -> Vec3 {
        let v = u[0] * self.v_sigma;
        let sin_a = (v * (2.0 - v)).max(0.0).sqrt();
        let (sb, cb) = (TAU * u[1]).sin_cos();
        (1.0 - v) * self.sun.axis() + sin_a * (cb * self.e1 + sb * self.e2)
    }

    /// The probability `q` of drawing the light sample from the sun at a
    /// point with frame `frame`: the sun's share of the irradiance.
    fn sun_share(&self, frame: &Frame) -> f32 {
        if self.cone_pdf == 0.0 {
            return 0.0;
        }
        // The closed form of a cap wholly above the horizon, π L sin²σ cos θa,
        // without the clipped formula's trigonometry; clipped caps call it.
        let c = frame.n.dot(self.sun.axis());
        let e_sun = if c >= self.sin_sigma {
            self.e_perp * c
        } else if c <= -self.sin_sigma {
            0.0
        } else {
            radiometry::radiometric::cap_irradiance(self.sun.cap_radiance(), c, self.sun.half_angle())
        };
        let e_sky = PI * self.sky.sky_radiance();
        let total = e_sun + e_sky;
        if total > 0.0 && total.is_finite() {
            e_sun / total
        } else {
            0.0
        }
    }

    /// The light technique's density at world direction `w` (local `wl`).
    fn light_pdf(&self, q: f32, w: Vec3, wl: Vec3) -> f32 {
        let cone = if self.sun.contains(w) { self.cone_pdf } else { 0.0 };
        q * cone + (1.0 - q) * cosine_hemisphere_pdf(wl)
    }

    /// [`Lighting::light_pdf`] with the non-sun branch drawn from `sampler`
    /// when there is one.
    fn light_pdf_env(&self, q: f32, w: Vec3, wl: Vec3, sampler: Option<&envmap::EnvSampler>) -> f32 {
        match sampler {
            None => self.light_pdf(q, w, wl),
            Some(s) => {
                let cone = if self.sun.contains(w) { self.cone_pdf } else { 0.0 };
                q * cone + (1.0 - q) * s.pdf(w)
            }
        }
    }

    /// One estimate of the reflected radiance `L_r(ωo)` at a point with
    /// (unit) world normal `n`, seen from (unit) world direction `wo` (toward
    /// the viewer): one light sample and one BRDF sample, combined with the
    /// power heuristic (module docs). `u` holds the 5 uniform numbers it
    /// uses: `u[0]` picks sun or sky, `u[1..3]` place the light sample,
    /// `u[3..5]` the BRDF sample. Non-finite contributions (none from a
    /// correct plugin) count as zero.
    pub fn shade<B: Brdf<Spectrum = f32> + ?Sized>(&self, brdf: &B, n: Vec3, wo: Vec3, u: [f32; 5]) -> f32 {
        let Some(frame) = Frame::from_normal(n) else {
            return 0.0;
        };
        let mut wo_l = frame.to_local(wo);
        if wo_l.z < MIN_COS_VIEW {
            wo_l.z = MIN_COS_VIEW;
            wo_l = wo_l.normalize_or_zero();
            if wo_l == Vec3::ZERO {
                return 0.0;
            }
        }
        let q = self.sun_share(&frame);
        let light = self.light_draw(brdf, &frame, wo_l, q, [u[0], u[1], u[2]]);
        let bsdf = self.brdf_draw(brdf, &frame, wo_l, q, [u[3], u[4]]);
        let v = (light + bsdf) as f32;
        if v.is_finite() { v } else { 0.0 }
    }

    fn light_draw<B: Brdf<Spectrum = f32> + ?Sized>(
        &self,
        brdf: &B,
        frame: &Frame,
        wo: Vec3,
        q: f32,
        u: [f32; 3],
    ) -> f64 {
        // u0 picks the sun (u0 < q) or the sky; u1, u2 place the direction.
        let (w, wl) = if u[0] < q {
            let w = self.cone_sample([u[1], u[2]]);
            (w, frame.to_local(w))
        } else {
            let wl = square_to_cosine_hemisphere([u[1], u[2]]);
            (frame.to_world(wl), wl)
        };
        if wl.z <= 0.0 {
            return 0.0;
        }
        let p_l = self.light_pdf(q, w, wl) as f64;
        if p_l <= 0.0 || p_l.is_nan() {
            return 0.0;
        }
        let f = brdf.eval(wl, wo) as f64;
        if f == 0.0 {
            return 0.0;
        }
        let p_b = brdf.pdf(wl, wo) as f64;
        let l = self.radiance(w) as f64;
        // f L cos / p_L · p_L² / (p_L² + p_B²)
        f * l * wl.z as f64 * p_l / (p_l * p_l + p_b * p_b)
    }

    fn brdf_draw<B: Brdf<Spectrum = f32> + ?Sized>(
        &self,
        brdf: &B,
        frame: &Frame,
        wo: Vec3,
        q: f32,
        u: [f32; 2],
    ) -> f64 {
        let u = [u[0].min(ONE_MINUS_EPSILON), u[1].min(ONE_MINUS_EPSILON)];
        let Some(s) = brdf.sample(wo, u) else {
            return 0.0;
        };
        if s.wi.z <= 0.0 || s.weight == 0.0 {
            return 0.0;
        }
        let w = frame.to_world(s.wi);
        let p_b = s.pdf as f64;
        let p_l = self.light_pdf(q, w, s.wi) as f64;
        let mis = p_b * p_b / (p_b * p_b + p_l * p_l);
        s.weight as f64 * self.radiance(w) as f64 * mis
    }
}

/// The radiances of the sun, the sky and the ground in one spectrum type,
/// colour included (what [`Lighting::shade_spectrum`] lights with).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Env<S> {
    /// Radiance of the sky (every direction above the horizontal plane).
    pub sky: S,
    /// Radiance of the ground (below it; equal to `sky` for the grey scene).
    pub ground: S,
    /// Radiance inside the sun's cap, added to the sky's.
    pub sun: S,
}

/// What lights the colour preview: the incident radiance from every world
/// direction, in spectrum `S` ([`Env`]: a uniform sky, a ground and the sun;
/// [`envmap::EnvMap`] through [`MapEnv`]).
pub trait Environment<S> {
    /// Incident radiance from (unit, world) direction `w`.
    fn radiance(&self, lighting: &Lighting, w: Vec3) -> S;

    /// A distribution of world directions for the light technique's
    /// non-sun branch; `None` (the default): cosine-weighted about the
    /// normal, as for a uniform sky.
    fn sampler(&self) -> Option<&envmap::EnvSampler> {
        None
    }
}

impl<S: Spectrum> Environment<S> for Env<S> {
    fn radiance(&self, lighting: &Lighting, w: Vec3) -> S {
        lighting.radiance_env(w, self)
    }
}

/// An environment map times `scale`, plus the preview's sun cap of radiance
/// `sun` (linear RGB).
#[derive(Clone, Copy, Debug)]
pub struct MapEnv<'a> {
    /// The map.
    pub map: &'a envmap::EnvMap,
    /// Its radiance scale.
    pub scale: f32,
    /// The sun's radiance inside its cap.
    pub sun: Vec3,
    /// Importance sampling of the map (`None`: cosine-weighted).
    pub sampler: Option<&'a envmap::EnvSampler>,
}

impl Environment<Vec3> for MapEnv<'_> {
    fn radiance(&self, lighting: &Lighting, w: Vec3) -> Vec3 {
        let sun = if lighting.sun.contains(w) {
            self.sun
        } else {
            Vec3::ZERO
        };
        Vec3::from_array(self.map.radiance(w)) * self.scale + sun
    }

    fn sampler(&self) -> Option<&envmap::EnvSampler> {
        self.sampler
    }
}

impl Lighting {
    /// Incident radiance from world direction `w` in any spectrum: the sky
    /// (the ground below the horizontal plane, `w.y < 0`), plus the sun in
    /// its cap (radiances per channel, colour included).
    pub fn radiance_env<S: Spectrum>(&self, w: Vec3, env: &Env<S>) -> S {
        let sun = if self.sun.contains(w) { env.sun } else { S::zero() };
        let base = if w.y < 0.0 { env.ground } else { env.sky };
        base + sun
    }

    /// [`Lighting::shade`] in any spectrum: the same estimator (the same
    /// directions, pdfs and MIS weights, which depend on the scalar sun and
    /// sky only), with the incident radiance of `env` per channel
    /// ([`Lighting::radiance_env`]; the ground, when it differs from the sky,
    /// is reached by the cosine-weighted sky technique and the BRDF's). For a
    /// BRDF whose channels are equal under white light without a ground it
    /// gives the bits of `shade` in every channel.
    pub fn shade_spectrum<S: Spectrum, B: Brdf<Spectrum = S> + ?Sized, E: Environment<S> + ?Sized>(
        &self,
        brdf: &B,
        n: Vec3,
        wo: Vec3,
        u: [f32; 5],
        env: &E,
    ) -> S {
        let Some(frame) = Frame::from_normal(n) else {
            return S::zero();
        };
        let mut wo_l = frame.to_local(wo);
        if wo_l.z < MIN_COS_VIEW {
            wo_l.z = MIN_COS_VIEW;
            wo_l = wo_l.normalize_or_zero();
            if wo_l == Vec3::ZERO {
                return S::zero();
            }
        }
        let q = self.sun_share(&frame);
        let mut light = [0.0f64; MAX_CHANNELS];
        let mut bsdf = [0.0f64; MAX_CHANNELS];
        self.light_draw_s(brdf, &frame, wo_l, q, [u[0], u[1], u[2]], env, &mut light);
        self.brdf_draw_s(brdf, &frame, wo_l, q, [u[3], u[4]], env, &mut bsdf);
        S::from_fn(|c| {
            let v = (light.get(c).copied().unwrap_or(0.0) + bsdf.get(c).copied().unwrap_or(0.0)) as f32;
            if v.is_finite() { v } else { 0.0 }
        })
    }

    #[allow(clippy::too_many_arguments)]
    fn light_draw_s<S: Spectrum, B: Brdf<Spectrum = S> + ?Sized, E: Environment<S> + ?Sized>(
        &self,
        brdf: &B,
        frame: &Frame,
        wo: Vec3,
        q: f32,
        u: [f32; 3],
        env: &E,
        out: &mut [f64],
    ) {
        let sampler = env.sampler();
        let (w, wl) = if u[0] < q {
            let w = self.cone_sample([u[1], u[2]]);
            (w, frame.to_local(w))
        } else if let Some(s) = sampler {
            let w = s.sample([u[1], u[2]]);
            (w, frame.to_local(w))
        } else {
            let wl = square_to_cosine_hemisphere([u[1], u[2]]);
            (frame.to_world(wl), wl)
        };
        if wl.z <= 0.0 {
            return;
        }
        let p_l = self.light_pdf_env(q, w, wl, sampler) as f64;
        if p_l <= 0.0 || p_l.is_nan() {
            return;
        }
        let f = brdf.eval(wl, wo);
        if f.is_black() {
            return;
        }
        let p_b = brdf.pdf(wl, wo) as f64;
        let l = env.radiance(self, w);
        for (c, o) in out.iter_mut().enumerate().take(S::CHANNELS) {
            // The expression order of `light_draw`, channel by channel.
            *o = f.channel(c) as f64 * l.channel(c) as f64 * wl.z as f64 * p_l / (p_l * p_l + p_b * p_b);
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn brdf_draw_s<S: Spectrum, B: Brdf<Spectrum = S> + ?Sized, E: Environment<S> + ?Sized>(
        &self,
        brdf: &B,
        frame: &Frame,
        wo: Vec3,
        q: f32,
        u: [f32; 2],
        env: &E,
        out: &mut [f64],
    ) {
        let u = [u[0].min(ONE_MINUS_EPSILON), u[1].min(ONE_MINUS_EPSILON)];
        let Some(s) = brdf.sample(wo, u) else {
            return;
        };
        if s.wi.z <= 0.0 || s.weight.is_black() {
            return;
        }
        let w = frame.to_world(s.wi);
        let p_b = s.pdf as f64;
        let p_l = self.light_pdf_env(q, w, s.wi, env.sampler()) as f64;
        let mis = p_b * p_b / (p_b * p_b + p_l * p_l);
        let l = env.radiance(self, w);
        for (c, o) in out.iter_mut().enumerate().take(S::CHANNELS) {
            *o = s.weight.channel(c) as f64 * l.channel(c) as f64 * mis;
        }
    }
}

/// Channels [`Lighting::shade_spectrum`] carries (more are dropped as black).
pub const MAX_CHANNELS: usize = 64;

/// `tan(FIELD_OF_VIEW_DEG / 2)`.
pub(crate) fn half_fov_tan() -> f32 {
    (0.5 * FIELD_OF_VIEW_DEG).to_radians().tan()
}

/// The pinhole camera ray through image point `(px, py)` (pixels, `y` down)
/// of a `size × size` image: origin and unit direction.
pub fn camera_ray(px: f32, py: f32, size: u32) -> (Vec3, Vec3) {
    camera_ray_with(half_fov_tan(), px, py, size)
}

pub(crate) fn camera_ray_with(t: f32, px: f32, py: f32, size: u32) -> (Vec3, Vec3) {
    let s = size as f32;
    let x = (2.0 * px / s - 1.0) * t;
    let y = (1.0 - 2.0 * py / s) * t;
    (
        Vec3::new(0.0, 0.0, CAMERA_DISTANCE),
        Vec3::new(x, y, -1.0).normalize(),
    )
}

/// The first hit of the ray `o + t d` (unit `d`) with the unit ball at the
/// origin: the point (which is also the outward normal), or `None`.
pub fn hit_ball(o: Vec3, d: Vec3) -> Option<Vec3> {
    let b = o.dot(d);
    let c = o.length_squared() - 1.0;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    if t <= 0.0 {
        return None;
    }
    (o + t * d).try_normalize()
}

/// Renders the ball with `brdf` (module docs): `opt.size²` pixels of linear
/// radiance, each the mean of `opt.samples` jittered camera rays.
pub fn render<B: Brdf<Spectrum = f32> + Sync + ?Sized>(
    brdf: &B,
    opt: &Options,
) -> Result<Image, PreviewError> {
    check_options(opt)?;
    let lighting = Lighting::new(opt)?;
    Ok(render_with(&lighting, opt, |p, d, u| {
        lighting.shade(brdf, p, -d, u)
    }))
}

/// The image size and samples per pixel within their limits.
pub(crate) fn check_options(opt: &Options) -> Result<(), PreviewError> {
    if opt.size == 0 || opt.size > MAX_SIZE {
        return Err(PreviewError::Size(opt.size));
    }
    if opt.samples == 0 || opt.samples > MAX_SAMPLES {
        return Err(PreviewError::Samples(opt.samples));
    }
    Ok(())
}

/// The ball rendered row by row on `opt.threads` threads: `shade(p, d, u)`
/// is the radiance toward the camera from the hit point `p` of a camera ray
/// of direction `d`, with 5 uniform numbers `u`; a ray that misses sees the
/// sky. Deterministic for a given seed, whatever the number of threads.
fn render_with(
    lighting: &Lighting,
    opt: &Options,
    shade: impl Fn(Vec3, Vec3, [f32; 5]) -> f32 + Sync,
) -> Image {
    let n = opt.size as usize;
    let mut radiance = vec![0.0f32; n * n];
    let mut coverage = vec![0.0f32; n * n];
    let threads = if opt.threads == 0 {
        std::thread::available_parallelism().map_or(1, |t| t.get())
    } else {
        opt.threads
    }
    .clamp(1, n);
    let progress = Progress::new(opt.progress, n);
    let rows = Mutex::new(radiance.chunks_mut(n).zip(coverage.chunks_mut(n)).enumerate());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    // Take the next row; the lock is held only for that.
                    let next = rows.lock().map(|mut r| r.next()).unwrap_or(None);
                    let Some((y, (lrow, crow))) = next else { break };
                    render_row(lighting, opt, y, lrow, crow, &shade);
                    progress.tick(&format!("row {}", y + 1));
                }
            });
        }
    });
    progress.finish();
    Image::new(opt.size, radiance, coverage)
}

/// The parameters of the textured ball at the point `p` of the unit ball
/// (`radiometry preview … --textured`): from the base parameters `base`,
/// `specular_roughness` ramps from 0.05 at the bottom to 0.8 at the top,
/// `base_metalness` from 0 on the left to 1 on the right, and a checker of
/// 8 × 4 squares in longitude and latitude toggles a clear coat
/// (`coat_weight` 1, `coat_roughness` 0.05) on and off.
pub fn textured_params(base: OpenPbrParams<f32>, p: Vec3) -> OpenPbrParams<f32> {
    let up = (0.5 * (p.y + 1.0)).clamp(0.0, 1.0);
    let right = (0.5 * (p.x + 1.0)).clamp(0.0, 1.0);
    let lon = p.x.atan2(p.z);
    let lat = p.y.clamp(-1.0, 1.0).asin();
    let cell = ((lon / PI * 4.0).floor() as i32) + ((lat / PI * 4.0).floor() as i32);
    let coat = cell.rem_euclid(2) == 0;
    OpenPbrParams {
        specular_roughness: 0.05 + 0.75 * up,
        base_metalness: right,
        coat_weight: if coat { 1.0 } else { 0.0 },
        coat_roughness: if coat { 0.05 } else { base.coat_roughness },
        ..base
    }
}

/// What [`render_textured`] measured: hits shaded and the time spent in
/// `OpenPbr::new` (one construction per hit).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TexturedStats {
    /// Camera samples that hit the ball (each built its own material).
    pub hits: u64,
    /// Seconds spent constructing materials, summed over the threads.
    pub construct_secs: f64,
}

/// Renders the textured ball: an `OpenPbr` built at every hit from
/// [`textured_params`] (a renderer with textured parameters), in the given
/// layering; otherwise as [`render`].
pub fn render_textured(
    base: OpenPbrParams<f32>,
    layering: Layering,
    opt: &Options,
) -> Result<(Image, TexturedStats), PreviewError> {
    use std::sync::atomic::{AtomicU64, Ordering};
    check_options(opt)?;
    OpenPbr::with_layering(textured_params(base, Vec3::Z), layering).map_err(PreviewError::Material)?;
    let lighting = Lighting::new(opt)?;
    let (hits, nanos) = (AtomicU64::new(0), AtomicU64::new(0));
    let img = render_with(&lighting, opt, |p, d, u| {
        let t0 = std::time::Instant::now();
        let m = OpenPbr::with_layering(textured_params(base, p), layering);
        let dt = u64::try_from(t0.elapsed().as_nanos()).unwrap_or(u64::MAX);
        nanos.fetch_add(dt, Ordering::Relaxed);
        hits.fetch_add(1, Ordering::Relaxed);
        m.map_or(0.0, |m| lighting.shade(&m, p, -d, u))
    });
    let stats = TexturedStats {
        hits: hits.load(Ordering::Relaxed),
        construct_secs: nanos.load(Ordering::Relaxed) as f64 * 1e-9,
    };
    Ok((img, stats))
}

fn render_row(
    lighting: &Lighting,
    opt: &Options,
    y: usize,
    lrow: &mut [f32],
    crow: &mut [f32],
    shade: &impl Fn(Vec3, Vec3, [f32; 5]) -> f32,
) {
    let n = opt.size as usize;
    let t = half_fov_tan();
    for (x, (l, c)) in lrow.iter_mut().zip(crow.iter_mut()).enumerate() {
        let mut rng = Pcg32::with_stream(opt.seed, (y * n + x) as u64);
        let (mut sum, mut hits) = (0.0f64, 0u32);
        for _ in 0..opt.samples {
            let (px, py) = (x as f32 + rng.next_f32(), y as f32 + rng.next_f32());
            let (o, d) = camera_ray_with(t, px, py, opt.size);
            let u = [
                rng.next_f32(),
                rng.next_f32(),
                rng.next_f32(),
                rng.next_f32(),
                rng.next_f32(),
            ];
            sum += match hit_ball(o, d) {
                Some(p) => {
                    hits += 1;
                    shade(p, d, u) as f64
                }
                None => lighting.radiance(d) as f64,
            };
        }
        *l = (sum / opt.samples as f64) as f32;
        *c = hits as f32 / opt.samples as f32;
    }
}

#[cfg(test)]
mod tests;
