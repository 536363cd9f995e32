//! `radiometry preview SPEC --out ball.png`: a material ball rendered by
//! `radiometry_tools::preview` (argument parsing and printing only).

use crate::{model, spec};
use clap::ValueEnum;
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

/// The help text after the options: the scene, the estimator, examples.
pub const AFTER_HELP: &str = "\
Scene: a unit ball seen by a pinhole camera (33.4° field of view, 4 radii away), lit by a sun (a uniform cap of
angular radius --sun-radius with irradiance --sun-irradiance at normal incidence) and a uniform sky of radiance
--sky-radiance all around (there is no ground); the background shows the sky. Each camera sample shades with one
light sample (sun cone or cosine-weighted sky, by the sun's share of the irradiance) and one sample of the BRDF's
own importance sampling, combined by the power heuristic. Deterministic for a given seed, whatever the number of
threads. Tone curve: extended Reinhard with white point 4 (times --exposure), then the sRGB transfer function,
8 bits; the BRDF is monochrome, so the picture is grey.

Examples:
  radiometry preview 'coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))' --out plastic.png
  radiometry preview 'ggx(alpha=0.3, fresnel=conductor(eta=0.2, k=3))' --size 160 --format svg --out metal.svg

";

/// Arguments of `radiometry preview`.
#[derive(clap::Args, Debug)]
pub struct PreviewArgs {
    /// BRDF spec of the ball, e.g. `ggx(alpha=0.1, fresnel=dielectric(eta=1.5)) + lambertian(albedo=0.5)` (see
    /// below).
    spec: String,
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
}

/// Runs `radiometry preview`.
pub fn run(a: PreviewArgs) -> ExitCode {
    let parsed = match spec::parse_brdf(&a.spec) {
        Ok(p) => p,
        Err(e) => return crate::spec_error(e),
    };
    let brdf = match model::build_brdf(&a.spec, &parsed) {
        Ok(b) => b,
        Err(e) => return crate::spec_error(e),
    };
    if !(a.exposure.is_finite() && a.exposure > 0.0) {
        return crate::usage_error(&format!(
            "--exposure {} must be a positive finite number",
            a.exposure
        ));
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
        a.spec,
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
