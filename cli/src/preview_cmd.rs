//! `radiometry preview SPEC --out ball.png`: a material ball rendered by
//! `radiometry_tools::preview` (argument parsing and printing only).

use crate::{model, spec};
use clap::ValueEnum;
use radiometry_tools::preview::camera::{self, CameraKind, CameraOptions, Illuminant, ResponseCurve};
use radiometry_tools::preview::colour::{self, AsGrey, AsRgb, LightColours, Preset, PresetKind, RgbImage};
use radiometry_tools::preview::envmap::EnvMap;
use radiometry_tools::preview::{self, Format, Options};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Image file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ImageFormat {
    /// 8-bit greyscale PNG.
    Png,
    /// SVG holding the PNG as a base64 `<image>`.
    Svg,
}

/// A typed colour material (`--material`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum MaterialArg {
    /// Gold: GGX α = 0.2, the exact Fresnel of Au's measured η, k (Johnson & Christy 1972).
    Gold,
    /// Copper: as gold with Cu.
    Copper,
    /// A red plastic: OpenPBR, base_color (0.6, 0.04, 0.03) linear sRGB, specular_roughness 0.25.
    RedPlastic,
}

impl MaterialArg {
    fn kind(self) -> PresetKind {
        match self {
            MaterialArg::Gold => PresetKind::Gold,
            MaterialArg::Copper => PresetKind::Copper,
            MaterialArg::RedPlastic => PresetKind::RedPlastic,
        }
    }
}

/// Colour architecture of `--camera`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CameraArg {
    /// Bayer colour filter array (RGGB) + bilinear demosaicing.
    Bayer,
    /// 3-chip dichroic prism.
    Prism,
    /// Stacked photodiodes (Foveon-like).
    Stacked,
}

/// `d65`, `a` or `planck:T` (kelvin, in [1000, 40000]).
fn parse_light(s: &str) -> Result<Illuminant, String> {
    match s {
        "d65" => Ok(Illuminant::D65),
        "a" => Ok(Illuminant::A),
        _ => {
            let t = s
                .strip_prefix("planck:")
                .ok_or_else(|| format!("'{s}': expected d65, a or planck:T"))?;
            let t: f32 = t.parse().map_err(|_| format!("'{t}' is not a number"))?;
            if !(t.is_finite() && (1000.0..=40_000.0).contains(&t)) {
                return Err(format!("black-body temperature {t} K must be in [1000, 40000]"));
            }
            Ok(Illuminant::Planck(t))
        }
    }
}

/// `R,G,B` with finite components ≥ 0.
fn parse_rgb(s: &str) -> Result<[f32; 3], String> {
    let v: Vec<&str> = s.split(',').map(str::trim).collect();
    if v.len() != 3 {
        return Err(format!("'{s}': expected R,G,B (three numbers)"));
    }
    let mut out = [0.0f32; 3];
    for (o, t) in out.iter_mut().zip(v) {
        let x: f32 = t.parse().map_err(|_| format!("'{t}' is not a number"))?;
        if !(x.is_finite() && x >= 0.0) {
            return Err(format!("'{t}' must be finite and >= 0"));
        }
        *o = x;
    }
    Ok(out)
}

/// `srgb`, `linear` or `gamma:G`.
fn parse_response(s: &str) -> Result<ResponseCurve, String> {
    match s {
        "srgb" => Ok(ResponseCurve::Srgb),
        "linear" => Ok(ResponseCurve::Linear),
        _ => {
            let g = s
                .strip_prefix("gamma:")
                .ok_or_else(|| format!("'{s}': expected srgb, linear or gamma:G"))?;
            let g: f32 = g.parse().map_err(|_| format!("'{g}' is not a number"))?;
            if !(g.is_finite() && (0.05..=20.0).contains(&g)) {
                return Err(format!("gamma {g} must be in [0.05, 20]"));
            }
            Ok(ResponseCurve::Gamma(g))
        }
    }
}

/// The help text after the options: the scene, the estimator, examples.
pub const AFTER_HELP: &str = "\
Scene: a unit ball seen by a pinhole camera (33.4° field of view, 4 radii away), lit by a sun (a uniform cap of
angular radius --sun-radius with irradiance --sun-irradiance at normal incidence) and a uniform sky of radiance
--sky-radiance all around (there is no ground); the background shows the sky. Each camera sample shades with one
light sample (sun cone or cosine-weighted sky, by the sun's share of the irradiance) and one sample of the BRDF's
own importance sampling, combined by the power heuristic. Deterministic for a given seed, whatever the number of
threads. Tone curve: extended Reinhard with white point 4 (times --exposure), then the sRGB transfer function,
8 bits; the spec grammar's BRDFs are monochrome, so a spec under white light gives a grey picture.

Colour: --material gold|copper|red-plastic renders a typed colour material (instead of SPEC); --sun-colour and
--sky-colour tint the lights (linear sRGB), --ground-colour adds a ground below the horizon (--daylight: a white
sun, a pale blue sky, a grey-brown ground), --env FILE.hdr lights by an equirectangular Radiance map instead;
--rgb forces an RGB picture. Any of these writes 8-bit RGB (each
channel through the same tone curve: a grey spec gives the grey picture's bytes). --spectral N renders with N
hero wavelengths per sample (1, 4, 8 or 16; 360-780 nm), lights as spectra (white = D65), colour by the CIE 1931
observer. --camera bayer|prism|stacked renders the pixel equation: the ball on 43 wavelengths under --light
d65|a|planck:T, through the camera's spectral sensitivities, exposure (--camera-exposure: the fraction of the full
well a white diffuser facing the sun fills), EMVA 1288 shot and dark noise (10,000 e- full well, --dark-noise e-,
12-bit ADC), bilinear demosaicing (Bayer), a colour matrix fitted on the 24 ColorChecker patches and a white balance,
the response curve (--response srgb|linear|gamma:G); beside it (right) the same ball as the CIE 1931 observer
sees it; prints the colour error (mean CIE 1976 dE*ab) and the noise against the EMVA prediction.

Examples:
  radiometry preview 'coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))' --out plastic.png
  radiometry preview 'ggx(alpha=0.3, fresnel=conductor(eta=0.2, k=3))' --size 160 --format svg --out metal.svg
  radiometry preview --material gold --sky-colour 0.45,0.6,1 --out gold.png
  radiometry preview --material copper --spectral 4 --out copper.png
  radiometry preview --material red-plastic --camera bayer --light a --out camera.png

";

/// Arguments of `radiometry preview`.
#[derive(clap::Args, Debug)]
pub struct PreviewArgs {
    /// BRDF spec of the ball, e.g. `ggx(alpha=0.1, fresnel=dielectric(eta=1.5)) + lambertian(albedo=0.5)` (see
    /// below); omit it with --material.
    spec: Option<String>,
    /// Output file.
    #[arg(long, default_value = "ball.png")]
    out: PathBuf,
    /// File format (default: from the extension of --out, `.svg` → svg, anything else → png).
    #[arg(long, value_enum)]
    format: Option<ImageFormat>,
    /// Image width and height in pixels.
    #[arg(long, default_value_t = preview::DEFAULT_SIZE)]
    size: u32,
    /// Camera samples per pixel (each one light sample and one BRDF sample).
    #[arg(long, default_value_t = preview::DEFAULT_SAMPLES)]
    samples: u32,
    /// Sun elevation above the horizontal plane, degrees in [-90, 90].
    #[arg(long, default_value_t = Options::default().sun_elevation, allow_negative_numbers = true)]
    sun_elevation: f32,
    /// Sun azimuth in degrees: 0 behind the camera, positive toward the viewer's right.
    #[arg(long, default_value_t = Options::default().sun_azimuth, allow_negative_numbers = true)]
    sun_azimuth: f32,
    /// Angular radius of the sun in degrees, in (0, 90] (the real sun: 0.27).
    #[arg(long, default_value_t = Options::default().sun_radius)]
    sun_radius: f32,
    /// Irradiance of the sun at normal incidence (0 turns it off).
    #[arg(long, default_value_t = Options::default().sun_irradiance)]
    sun_irradiance: f32,
    /// Radiance of the uniform sky.
    #[arg(long, default_value_t = Options::default().sky_radiance)]
    sky_radiance: f32,
    /// Exposure: radiance multiplier before the tone curve.
    #[arg(long, default_value_t = 1.0)]
    exposure: f32,
    /// Seed of the per-pixel random number generators.
    #[arg(long, default_value_t = Options::default().seed)]
    seed: u64,
    /// Worker threads (default: available parallelism).
    #[arg(long)]
    threads: Option<usize>,
    /// Hide the progress bar on stderr.
    #[arg(long)]
    no_progress: bool,
    /// A spatially varying material built at every hit: SPEC must be `openpbr(...)`, whose parameters are the base;
    /// `specular_roughness` ramps from 0.05 (bottom) to 0.8 (top), `base_metalness` from 0 (left) to 1 (right), and a
    /// checker toggles a clear coat. Prints the time per hit spent constructing the material.
    #[arg(long)]
    textured: bool,
    /// A typed colour material instead of SPEC (an RGB picture): gold, copper or red-plastic; with --mtlx, the name
    /// of the document's material (a surfacematerial or an open_pbr_surface node).
    #[arg(long, value_name = "NAME")]
    material: Option<String>,
    /// An OpenPBR material from a MaterialX document (`.mtlx`): the constant reflection inputs of its
    /// open_pbr_surface node (--material picks one when the document has several); inputs outside a
    /// reflection-only BRDF are named in warnings, textures and node graphs refused.
    #[arg(long, value_name = "FILE")]
    mtlx: Option<PathBuf>,
    /// Colour of the sun, linear sRGB `R,G,B` (an RGB picture).
    #[arg(long, alias = "sun-color", value_parser = parse_rgb)]
    sun_colour: Option<[f32; 3]>,
    /// Colour of the sky, linear sRGB `R,G,B` (an RGB picture).
    #[arg(long, alias = "sky-color", value_parser = parse_rgb)]
    sky_colour: Option<[f32; 3]>,
    /// Radiance of the ground below the horizontal plane, per channel as a multiple of --sky-radiance, `R,G,B`
    /// (default: no ground, the sky all around; an RGB picture).
    #[arg(long, alias = "ground-color", value_parser = parse_rgb)]
    ground_colour: Option<[f32; 3]>,
    /// The docs' daylight: --sun-colour 1,1,1 --sky-colour 0.75,0.85,1 --ground-colour 0.2,0.17,0.15 (the
    /// explicit flags win).
    #[arg(long)]
    daylight: bool,
    /// An equirectangular environment map (Radiance `.hdr`) instead of the uniform sky and ground: its texels times
    /// --env-scale are the radiance all around (the image centre straight ahead of the camera, behind the ball); the
    /// sun (--sun-…) is added. An RGB picture; --sky-radiance is replaced by the map's mean luminance.
    #[arg(long, value_name = "FILE")]
    env: Option<PathBuf>,
    /// Radiance scale of --env.
    #[arg(long, default_value_t = 1.0)]
    env_scale: f32,
    /// Write an RGB picture even when everything is grey.
    #[arg(long)]
    rgb: bool,
    /// Hero-wavelength spectral rendering with N wavelengths per sample (1, 4, 8 or 16).
    #[arg(long, value_name = "N")]
    spectral: Option<usize>,
    /// Render the pixel equation: the ball through a simulated camera, beside the CIE observer's ball.
    #[arg(long, value_enum)]
    camera: Option<CameraArg>,
    /// Light spectrum of the sun and the sky for --camera: `d65`, `a` (CIE illuminant A, tungsten) or `planck:T` (a
    /// black body at T kelvin).
    #[arg(long, default_value = "d65", value_parser = parse_light)]
    light: Illuminant,
    /// --camera: fraction of the full well that a white diffuser facing the sun fills, in (0, 16].
    #[arg(long, default_value_t = CameraOptions::default().exposure)]
    camera_exposure: f32,
    /// --camera: temporal dark noise, electrons.
    #[arg(long, default_value_t = CameraOptions::default().dark_noise_e)]
    dark_noise: f32,
    /// --camera: no shot or dark noise (the mean response).
    #[arg(long)]
    no_noise: bool,
    /// --camera: the response curve encoding both pictures: `srgb`, `linear` or `gamma:G` (y = x^(1/G)).
    #[arg(long, default_value = "srgb", value_parser = parse_response)]
    response: ResponseCurve,
}

/// The ball's material: a grey spec (monochrome run-time BRDF), a colour
/// spec (the RGB run-time BRDF) or a typed preset.
enum Ball {
    Spec(spec::BrdfSpec, model::AnyBrdf),
    SpecRgb(model::AnyBrdfRgb),
    Preset(Preset),
}

/// A spec's ball: grey specs in the monochrome run-time BRDF, colour specs
/// in RGB.
fn spec_ball(s: &str) -> Result<Ball, ExitCode> {
    let parsed = spec::parse_brdf(s).map_err(crate::spec_error)?;
    if parsed.is_grey() {
        model::build_brdf(s, &parsed)
            .map(|b| Ball::Spec(parsed, b))
            .map_err(crate::spec_error)
    } else {
        model::build_brdf_rgb(s, &parsed)
            .map(Ball::SpecRgb)
            .map_err(crate::spec_error)
    }
}

/// The spec of `--mtlx FILE [--material NAME]`, `openpbr(file="FILE",
/// material="NAME")`, after printing the document's warnings.
fn mtlx_spec(path: &std::path::Path, material: Option<&str>) -> Result<String, ExitCode> {
    let text = path.display().to_string();
    if text.contains('"') {
        return Err(crate::usage_error("--mtlx: the file name must not contain `\"`"));
    }
    let xml = std::fs::read_to_string(path)
        .map_err(|e| crate::usage_error(&format!("--mtlx: cannot read {text}: {e}")))?;
    let m = spec::mtlx::read_openpbr(&xml, material)
        .map_err(|e| crate::usage_error(&format!("--mtlx {text}: {e}")))?;
    for w in &m.warnings {
        eprintln!("warning: {text}, material `{}`: {w}", m.name);
    }
    if m.name.contains('"') {
        return Err(crate::usage_error(
            "--mtlx: the material's name must not contain `\"`",
        ));
    }
    Ok(format!(r#"openpbr(file="{text}", material="{}")"#, m.name))
}

/// Runs `radiometry preview`.
pub fn run(a: PreviewArgs) -> ExitCode {
    let mut a = a;
    if let Some(path) = a.mtlx.clone() {
        if a.spec.is_some() {
            return crate::usage_error("give either SPEC or --mtlx, not both");
        }
        match mtlx_spec(&path, a.material.as_deref()) {
            Ok(s) => a.spec = Some(s),
            Err(code) => return code,
        }
        a.material = None;
    }
    let preset = match a.material.as_deref().map(|m| MaterialArg::from_str(m, true)) {
        None => None,
        Some(Ok(m)) => Some(m),
        Some(Err(_)) => {
            return crate::usage_error(&format!(
                "--material {}: one of gold, copper, red-plastic (or a material of --mtlx FILE)",
                a.material.as_deref().unwrap_or("")
            ));
        }
    };
    let ball = match (&a.spec, preset) {
        (Some(_), Some(_)) => return crate::usage_error("give either SPEC or --material, not both"),
        (None, None) => {
            return crate::usage_error("give a BRDF SPEC, --mtlx FILE or --material gold|copper|red-plastic");
        }
        (None, Some(m)) => match Preset::new(m.kind()) {
            Ok(p) => Ball::Preset(p),
            Err(e) => return crate::usage_error(&e.to_string()),
        },
        (Some(s), None) => match spec_ball(s) {
            Ok(b) => b,
            Err(code) => return code,
        },
    };
    let a = a;
    if !(a.exposure.is_finite() && a.exposure > 0.0) {
        return crate::usage_error(&format!(
            "--exposure {} must be a positive finite number",
            a.exposure
        ));
    }
    let colours = LightColours {
        sun: a.sun_colour.unwrap_or([1.0; 3]),
        sky: a.sky_colour.unwrap_or([1.0; 3]),
        ground: a.ground_colour,
    };
    let colours = if a.daylight {
        let d = LightColours::DAYLIGHT;
        LightColours {
            sun: a.sun_colour.unwrap_or(d.sun),
            sky: a.sky_colour.unwrap_or(d.sky),
            ground: a.ground_colour.or(d.ground),
        }
    } else {
        colours
    };
    let colour_out = a.rgb
        || a.material.is_some()
        || matches!(ball, Ball::SpecRgb(_))
        || a.sun_colour.is_some()
        || a.sky_colour.is_some()
        || a.ground_colour.is_some()
        || a.daylight
        || a.env.is_some()
        || a.spectral.is_some()
        || a.camera.is_some();
    if a.textured && colour_out {
        return crate::usage_error("--textured renders the grey ball only (no colour flags)");
    }
    if a.camera.is_some()
        && (a.spectral.is_some()
            || a.sun_colour.is_some()
            || a.sky_colour.is_some()
            || a.ground_colour.is_some()
            || a.daylight)
    {
        return crate::usage_error(
            "--camera renders on its own 43 wavelengths under --light; drop --spectral and the light colours",
        );
    }
    if a.env.is_some()
        && (a.spectral.is_some()
            || a.camera.is_some()
            || a.sky_colour.is_some()
            || a.ground_colour.is_some()
            || a.daylight)
    {
        return crate::usage_error(
            "--env lights in RGB by the map itself; drop --spectral, --camera, --sky-colour, --ground-colour, --daylight",
        );
    }
    if let Some(n) = a.spectral
        && !colour::HERO_COUNTS.contains(&n)
    {
        return crate::usage_error(&format!("--spectral {n}: N must be one of 1, 4, 8, 16"));
    }
    let opt = Options {
        size: a.size,
        samples: a.samples,
        sun_elevation: a.sun_elevation,
        sun_azimuth: a.sun_azimuth,
        sun_radius: a.sun_radius,
        sun_irradiance: a.sun_irradiance,
        sky_radiance: a.sky_radiance,
        seed: a.seed,
        threads: a.threads.unwrap_or(0),
        progress: !a.no_progress,
    };
    let format = match a.format {
        Some(ImageFormat::Png) => Format::Png,
        Some(ImageFormat::Svg) => Format::Svg,
        None => Format::from_path(&a.out),
    };
    let threads = match opt.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        t => t,
    };
    let t0 = Instant::now();
    if colour_out {
        return run_colour(&a, &ball, &opt, &colours, format, threads, t0);
    }
    let Ball::Spec(parsed, brdf) = ball else {
        return crate::usage_error("--material renders in colour");
    };
    let spec_text = a.spec.clone().unwrap_or_default();
    let (img, stats) = if a.textured {
        let spec::BrdfSpec::OpenPbr(p) = parsed else {
            return crate::usage_error("--textured needs an openpbr(...) spec (its parameters are the base)");
        };
        let (base, layering) = model::openpbr_params(&p);
        match preview::render_textured(base, layering, &opt) {
            Ok((i, s)) => (i, Some(s)),
            Err(e) => return crate::usage_error(&e.to_string()),
        }
    } else {
        match preview::render(&brdf, &opt) {
            Ok(i) => (i, None),
            Err(e) => return crate::usage_error(&e.to_string()),
        }
    };
    let secs = t0.elapsed().as_secs_f64();
    let description = format!(
        "radiometry preview '{}'{} --size {} --samples {} --sun-elevation {} --sun-azimuth {} --sun-radius {} \
--sun-irradiance {} --sky-radiance {} --exposure {} --seed {}",
        spec_text,
        if a.textured { " --textured" } else { "" },
        opt.size,
        opt.samples,
        opt.sun_elevation,
        opt.sun_azimuth,
        opt.sun_radius,
        opt.sun_irradiance,
        opt.sky_radiance,
        a.exposure,
        opt.seed
    );
    if let Err(e) = img.write(&a.out, format, a.exposure, &description) {
        eprintln!("error: cannot write {}: {e}", a.out.display());
        return ExitCode::from(1);
    }
    println!(
        "wrote {} ({}×{} px, {} samples/pixel, {:.2} s on {} thread{})",
        a.out.display(),
        opt.size,
        opt.size,
        opt.samples,
        secs,
        threads.min(opt.size as usize),
        if threads.min(opt.size as usize) == 1 {
            ""
        } else {
            "s"
        }
    );
    if let Some(s) = stats {
        println!(
            "textured: {} hits, each building its material: {:.0} ns per construction ({:.1} % of the render's thread time)",
            s.hits,
            1e9 * s.construct_secs / (s.hits.max(1) as f64),
            100.0 * s.construct_secs / (secs * threads.min(opt.size as usize) as f64)
        );
    }
    ExitCode::SUCCESS
}

/// The common part of the command line, for the PNG's description.
fn describe(a: &PreviewArgs, opt: &Options) -> String {
    let what = match (&a.spec, &a.material) {
        (Some(s), _) => format!("'{s}'"),
        (None, Some(m)) => format!("--material {m}"),
        (None, None) => String::new(),
    };
    format!(
        "radiometry preview {what} --size {} --samples {} --sun-elevation {} --sun-azimuth {} --sun-radius {} \
--sun-irradiance {} --sky-radiance {} --seed {}",
        opt.size,
        opt.samples,
        opt.sun_elevation,
        opt.sun_azimuth,
        opt.sun_radius,
        opt.sun_irradiance,
        opt.sky_radiance,
        opt.seed
    )
}

/// `--material`, the light colours, `--rgb`, `--spectral`, `--camera`.
fn run_colour(
    a: &PreviewArgs,
    ball: &Ball,
    opt: &Options,
    colours: &LightColours,
    format: Format,
    threads: usize,
    t0: Instant,
) -> ExitCode {
    let used = threads.min(opt.size as usize);
    let mut description = describe(a, opt);
    if let Some(kind) = a.camera {
        let cam = CameraOptions {
            kind: match kind {
                CameraArg::Bayer => CameraKind::Bayer,
                CameraArg::Prism => CameraKind::Prism,
                CameraArg::Stacked => CameraKind::Stacked,
            },
            illuminant: a.light,
            exposure: a.camera_exposure,
            dark_noise_e: a.dark_noise,
            noise: !a.no_noise,
            seed: a.seed,
            response: a.response,
            ..CameraOptions::default()
        };
        let r = match ball {
            Ball::Spec(_, b) => camera::render_camera(&AsGrey(b), opt, &cam),
            Ball::SpecRgb(_) => {
                return crate::usage_error(
                    "--camera renders grey specs and --material presets (a colour spec is not uplifted to spectra yet)",
                );
            }
            Ball::Preset(p) => camera::render_camera(p, opt, &cam),
        };
        let r = match r {
            Ok(r) => r,
            Err(e) => return crate::usage_error(&e.to_string()),
        };
        let secs = t0.elapsed().as_secs_f64();
        description.push_str(&format!(
            " --camera {} --light {} --camera-exposure {} --dark-noise {}{} --response {} (left: camera, right: CIE 1931 \
observer)",
            cam.kind.name(),
            cam.illuminant.name(),
            cam.exposure,
            cam.dark_noise_e,
            if cam.noise { "" } else { " --no-noise" },
            match cam.response {
                ResponseCurve::Srgb => String::from("srgb"),
                ResponseCurve::Linear => String::from("linear"),
                ResponseCurve::Gamma(g) => format!("gamma:{g}"),
                _ => String::from("?"),
            }
        ));
        let pair = r.camera.beside(&r.observer, 8, [0.0; 3]);
        let labels = [
            format!("camera: {}, {}", cam.kind.name(), cam.illuminant.name()),
            String::from("CIE 1931 observer"),
        ];
        let x1 = (r.camera.width() + 8) as usize;
        if let Err(e) = write_labelled(
            &a.out,
            format,
            &pair,
            cam.response,
            &labels,
            [0, x1],
            &description,
        ) {
            eprintln!("error: cannot write {}: {e}", a.out.display());
            return ExitCode::from(1);
        }
        let rep = r.report;
        println!(
            "wrote {} ({}×{} px: camera | observer, {} samples/pixel, 43 wavelengths, {:.2} s on {} thread{})",
            a.out.display(),
            pair.width(),
            pair.height() + LABEL_BAND,
            opt.samples,
            secs,
            used,
            if used == 1 { "" } else { "s" }
        );
        println!(
            "camera {} under {}: mean dE*ab {:.2} (noiseless {:.2}) over {} ball pixels; camera/observer per channel \
R {:.3} G {:.3} B {:.3}",
            cam.kind.name(),
            cam.illuminant.name(),
            rep.mean_delta_e,
            rep.mean_delta_e_noiseless,
            rep.pixels,
            rep.channel_ratio[0],
            rep.channel_ratio[1],
            rep.channel_ratio[2]
        );
        println!(
            "noise: white diffuser {:.0} e- (EMVA SNR {:.1}); rms noise over the ball as a fraction of white: R {:.4} \
G {:.4} B {:.4}; EMVA prediction through the matrix R {:.4} G {:.4} B {:.4}",
            rep.white_electrons,
            rep.white_snr,
            rep.noise[0],
            rep.noise[1],
            rep.noise[2],
            rep.noise_predicted[0],
            rep.noise_predicted[1],
            rep.noise_predicted[2]
        );
        println!(
            "ColorChecker (the matrix's chart, noiseless): mean dE*ab {:.2}, largest {:.2}",
            rep.chart_delta_e, rep.chart_delta_e_max
        );
        let m = rep.ccm;
        println!(
            "colour matrix (white-balanced, on white-normalised raw): [{:.3} {:.3} {:.3}; {:.3} {:.3} {:.3}; {:.3} {:.3} {:.3}]",
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]
        );
        return ExitCode::SUCCESS;
    }
    if let Some(path) = &a.env {
        let map = match EnvMap::read_hdr(path) {
            Ok(m) => m,
            Err(e) => return crate::usage_error(&e.to_string()),
        };
        let m = map.mean();
        let lum = (0.2126 * m[0] + 0.7152 * m[1] + 0.0722 * m[2]) * a.env_scale;
        let opt = Options {
            sky_radiance: if lum.is_finite() { lum.max(0.0) } else { 0.0 },
            ..opt.clone()
        };
        let img = match ball {
            Ball::Spec(_, b) => colour::render_rgb_env(&AsRgb(b), &opt, &map, a.env_scale, colours.sun),
            Ball::SpecRgb(b) => colour::render_rgb_env(b, &opt, &map, a.env_scale, colours.sun),
            Ball::Preset(p) => match p.rgb() {
                Ok(m) => colour::render_rgb_env(&m, &opt, &map, a.env_scale, colours.sun),
                Err(e) => Err(e),
            },
        };
        let img = match img {
            Ok(i) => i,
            Err(e) => return crate::usage_error(&e.to_string()),
        };
        let secs = t0.elapsed().as_secs_f64();
        description.push_str(&format!(
            " --env {} --env-scale {} --sun-colour {},{},{} --exposure {}",
            path.display(),
            a.env_scale,
            colours.sun[0],
            colours.sun[1],
            colours.sun[2],
            a.exposure
        ));
        if let Err(e) = img.write(&a.out, format, a.exposure, &description) {
            eprintln!("error: cannot write {}: {e}", a.out.display());
            return ExitCode::from(1);
        }
        println!(
            "wrote {} ({}×{} px, RGB, environment {}×{} texels, {} samples/pixel, {:.2} s on {} thread{})",
            a.out.display(),
            opt.size,
            opt.size,
            map.width(),
            map.height(),
            opt.samples,
            secs,
            used,
            if used == 1 { "" } else { "s" }
        );
        return ExitCode::SUCCESS;
    }
    let img: Result<RgbImage, _> = match (ball, a.spectral) {
        (Ball::Spec(_, b), None) => colour::render_rgb(&AsRgb(b), opt, colours),
        (Ball::SpecRgb(b), None) => colour::render_rgb(b, opt, colours),
        (Ball::SpecRgb(_), Some(_)) => {
            return crate::usage_error(
                "--spectral renders grey specs and --material presets (a colour spec is not uplifted to spectra yet)",
            );
        }
        (Ball::Preset(p), None) => match p.rgb() {
            Ok(m) => colour::render_rgb(&m, opt, colours),
            Err(e) => Err(e),
        },
        (Ball::Spec(_, b), Some(n)) => colour::render_spectral_n(n, &AsGrey(b), opt, colours),
        (Ball::Preset(p), Some(n)) => colour::render_spectral_n(n, p, opt, colours),
    };
    let img = match img {
        Ok(i) => i,
        Err(e) => return crate::usage_error(&e.to_string()),
    };
    let secs = t0.elapsed().as_secs_f64();
    let c = |v: [f32; 3]| format!("{},{},{}", v[0], v[1], v[2]);
    description.push_str(&format!(
        " --sun-colour {} --sky-colour {}{} --exposure {}{}",
        c(colours.sun),
        c(colours.sky),
        colours
            .ground
            .map_or(String::new(), |g| format!(" --ground-colour {}", c(g))),
        a.exposure,
        a.spectral
            .map_or(String::from(" --rgb"), |n| format!(" --spectral {n}"))
    ));
    if let Err(e) = img.write(&a.out, format, a.exposure, &description) {
        eprintln!("error: cannot write {}: {e}", a.out.display());
        return ExitCode::from(1);
    }
    println!(
        "wrote {} ({}×{} px, RGB{}, {} samples/pixel, {:.2} s on {} thread{})",
        a.out.display(),
        opt.size,
        opt.size,
        a.spectral
            .map_or(String::new(), |n| format!(", {n} hero wavelengths")),
        opt.samples,
        secs,
        used,
        if used == 1 { "" } else { "s" }
    );
    ExitCode::SUCCESS
}

/// Height of the label band above the camera picture, pixels.
const LABEL_BAND: u32 = 14;

/// The camera | observer picture encoded by the response curve, under a black
/// band with a label over each half (8 × 8 glyphs of `font8x8`, white, at
/// the given x offsets), as PNG or SVG.
fn write_labelled(
    path: &std::path::Path,
    format: Format,
    img: &RgbImage,
    response: ResponseCurve,
    labels: &[String; 2],
    x0: [usize; 2],
    description: &str,
) -> std::io::Result<()> {
    use font8x8::UnicodeFonts as _;
    let (w, h) = (img.width() as usize, img.height() as usize);
    let band = LABEL_BAND as usize;
    let mut px = vec![0u8; 3 * w * band];
    px.extend(img.to_encoded8(response));
    for (label, &x) in labels.iter().zip(&x0) {
        for (i, ch) in label.chars().enumerate() {
            let glyph = font8x8::BASIC_FONTS.get(ch).unwrap_or([0; 8]);
            for (row, bits) in glyph.iter().enumerate() {
                for col in 0..8 {
                    // font8x8: bit 0 is the leftmost column.
                    let (gx, gy) = (x + 3 + i * 8 + col, 3 + row);
                    if bits & (1 << col) != 0 && gx < w {
                        px[3 * (gy * w + gx)..3 * (gy * w + gx) + 3].copy_from_slice(&[255, 255, 255]);
                    }
                }
            }
        }
    }
    let height = (h + band) as u32;
    let png = radiometry_tools::preview::image::encode_png8(
        img.width(),
        height,
        png::ColorType::Rgb,
        &px,
        description,
    )?;
    match format {
        Format::Png => std::fs::write(path, png),
        Format::Svg => std::fs::write(
            path,
            radiometry_tools::preview::image::svg_wrap(&png, img.width(), height, description),
        ),
    }
}
