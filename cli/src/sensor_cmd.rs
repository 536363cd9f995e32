//! `radiometry sensor ...`: simulate EMVA 1288 pixel readings under a
//! standard light, and render a slanted-edge target through the five colour
//! architectures (Bayer + bilinear, Bayer + Malvar–He–Cutler, 3-chip prism,
//! filter wheel, stacked layers; see [`crate::sensor_edge`]).

use clap::{Args, Subcommand, ValueEnum};
use radiometry::sensor::color::{BayerPattern, false_colour_energy};
use radiometry::sensor::{
    Emva1288, FillFactor, IrradianceField, Monochromatic, Pcg32, Pixel, Sampling, SensorError,
    UniformSpectral,
};
use radiometry::spectral::photometry::{K_M, illuminance_lux};
use radiometry::spectral::{self, FnCurve, IlluminantA, Scaled, SpectralCurve};
use std::path::PathBuf;
use std::process::ExitCode;

use crate::sensor_edge::{EDGE_SLOPE, WHEEL_MOTION_PX_PER_SLOT, render, write_png, write_svg};
use crate::{Format, json_num};

/// Largest `--repeats`.
const MAX_REPEATS: u64 = 10_000_000;
/// At most this many individual readings are listed in the JSON output.
const MAX_LISTED_READINGS: usize = 1000;

/// `radiometry sensor` subcommands.
#[derive(Subcommand, Debug)]
pub enum SensorCommand {
    /// Simulate readings of one EMVA 1288 linear-camera pixel (shot noise, dark noise, gain, ADC) under a
    /// light scaled to a given illuminance; compare the sample mean/variance of the readings with the photon
    /// transfer prediction σ²_y = K²(σ²_d + μ_e) + 1/12 DN².
    #[command(after_help = READ_HELP)]
    Read(ReadArgs),
    /// Render a black/white slanted-edge target through the colour architectures side by side into one
    /// picture, each panel labelled: (a) Bayer + bilinear, (b) Bayer + Malvar–He–Cutler, (c) 3-chip prism,
    /// (d) filter wheel (R, G, B one after another while the edge moves 1 px per filter slot) and (e) stacked
    /// layers (Foveon-like); print the false-colour energy Σ Σ_c (c − mean)² of each (zero for a perfect
    /// achromatic reproduction).
    Edge(EdgeArgs),
}

const READ_HELP: &str = "\
Model (EMVA 1288 Release 4.0, §2): photons μ_p = A·t·∫E(λ)·λ/(hc) dλ on the photosensitive area A·fill,
electrons μ_e = η·μ_p (η = --qe at every wavelength), mean μ_y = K·μ_e (clipped to [0, 2^bits − 1] and
the full well), one reading y = round(K·(Poisson(μ_e) + N(0, σ_d²))) clipped to [0, 2^bits − 1].
Lights: d65 (CIE D65), a (CIE illuminant A), mono:<nm> (a line at <nm>); each is scaled so that its
illuminance K_m ∫E V dλ (K_m = 683 lm/W) equals --lux.
JSON keys: light, lux, irradiance_w_m2, mean_electrons, mean_dn, repeats, readings (the first 1000),
sample_mean_dn, sample_variance_dn (null for repeats < 2), predicted_variance_dn, saturated.
Exit codes: 0 success, 2 invalid input (e.g. negative lux, NaN, bits outside 1..=32).";

/// Arguments of `radiometry sensor read`.
#[derive(Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct ReadArgs {
    /// Light: `d65`, `a` (CIE illuminant A) or `mono:<nm>` (monochromatic line).
    #[arg(long, default_value = "d65")]
    light: String,
    /// Illuminance on the pixel, lux (finite, ≥ 0).
    #[arg(long)]
    lux: f64,
    /// Exposure time, s (finite, ≥ 0).
    #[arg(long, default_value_t = 0.001)]
    exposure: f64,
    /// Quantum efficiency η, electrons per photon, in [0, 1], the same at every wavelength.
    #[arg(long, default_value_t = 0.5)]
    qe: f64,
    /// System gain K, DN per electron (> 0).
    #[arg(long, default_value_t = 0.1)]
    gain: f64,
    /// ADC bit depth, 1..=32.
    #[arg(long, default_value_t = 12)]
    bits: i64,
    /// Temporal dark noise σ_d, electrons (≥ 0).
    #[arg(long = "dark-noise", default_value_t = 0.0)]
    dark_noise: f64,
    /// Saturation capacity (full well), electrons (> 0).
    #[arg(long = "full-well", default_value_t = 40_000.0)]
    full_well: f64,
    /// Pixel area, m² (> 0); default a 5 µm × 5 µm pixel.
    #[arg(long = "pixel-area", default_value_t = 25e-12)]
    pixel_area: f64,
    /// Fill factor, in (0, 1].
    #[arg(long = "fill-factor", default_value_t = 1.0)]
    fill_factor: f64,
    /// Seed of the noise generator (PCG32).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Number of simulated readings (1..=10000000).
    #[arg(long, default_value_t = 1)]
    repeats: u64,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

/// Picture format of `radiometry sensor edge`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ImageFormat {
    /// Scalable vector graphics (one rectangle per pixel, with text labels).
    Svg,
    /// 8-bit RGB PNG (encoded by the `png` crate; labels in the `font8x8` glyphs).
    Png,
}

/// Bayer phase on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Pattern {
    /// R G / G B.
    Rggb,
    /// B G / G R.
    Bggr,
    /// G R / B G.
    Grbg,
    /// G B / R G.
    Gbrg,
}

impl From<Pattern> for BayerPattern {
    fn from(p: Pattern) -> Self {
        match p {
            Pattern::Rggb => BayerPattern::Rggb,
            Pattern::Bggr => BayerPattern::Bggr,
            Pattern::Grbg => BayerPattern::Grbg,
            Pattern::Gbrg => BayerPattern::Gbrg,
        }
    }
}

/// Arguments of `radiometry sensor edge`.
#[derive(Args, Debug)]
pub struct EdgeArgs {
    /// Output folder (created if missing); the picture is `edge.svg` or `edge.png` in it.
    #[arg(long, default_value = "target/sensor")]
    out: PathBuf,
    /// Side of the square target, pixels (8..=512).
    #[arg(long, default_value_t = 64)]
    size: usize,
    /// Bayer phase.
    #[arg(long, value_enum, default_value_t = Pattern::Rggb)]
    pattern: Pattern,
    /// Picture format.
    #[arg(long, value_enum, default_value_t = ImageFormat::Svg)]
    format: ImageFormat,
    /// Print the report as one JSON object (keys: file, size, pattern, slope, wheel_motion_px_per_slot,
    /// false_colour_energy {bilinear, malvar, three_chip, filter_wheel, stacked}).
    #[arg(long)]
    json: bool,
}

/// Runs a `sensor` subcommand.
pub fn run(cmd: SensorCommand) -> ExitCode {
    let r = match cmd {
        SensorCommand::Read(a) => read(&a),
        SensorCommand::Edge(a) => edge(&a),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(m)) => {
            eprintln!("error: {m}");
            ExitCode::from(2)
        }
        Err(Failure::Runtime(m)) => {
            eprintln!("error: {m}");
            ExitCode::from(1)
        }
    }
}

enum Failure {
    /// Invalid input (exit 2).
    Usage(String),
    /// Runtime failure, e.g. an unwritable folder (exit 1).
    Runtime(String),
}

fn usage(msg: impl Into<String>) -> Failure {
    Failure::Usage(msg.into())
}

fn sensor_err(what: &str, e: SensorError) -> Failure {
    Failure::Usage(format!("{what}: {e}"))
}

/// `x` as a finite f32 in the range described by `ok`, or a usage error naming `--flag`.
fn check(flag: &str, x: f64, ok: impl Fn(f32) -> bool, domain: &str) -> Result<f32, Failure> {
    let v = x as f32;
    if !x.is_finite() || !v.is_finite() {
        return Err(usage(format!("--{flag} {x} is not a finite number (f32)")));
    }
    if !ok(v) {
        return Err(usage(format!("--{flag} {x} is outside its domain: {domain}")));
    }
    Ok(v)
}

/// A parsed `--light`.
#[derive(Clone, Copy, Debug)]
enum Light {
    D65,
    A,
    Mono(f32),
}

fn parse_light(s: &str) -> Result<Light, Failure> {
    let t = s.trim().to_ascii_lowercase();
    match t.as_str() {
        "d65" => Ok(Light::D65),
        "a" => Ok(Light::A),
        _ => {
            let Some(nm) = t.strip_prefix("mono:") else {
                return Err(usage(format!(
                    "unknown light `{s}`; expected d65, a or mono:<nm>"
                )));
            };
            let l: f64 = nm
                .trim()
                .parse()
                .map_err(|_| usage(format!("mono:<nm>: `{nm}` is not a number")))?;
            let l = check("light mono", l, |v| v > 0.0, "wavelength > 0 nm")?;
            Ok(Light::Mono(l))
        }
    }
}

/// The camera, the light and the derived numbers of one `read` run.
struct ReadOutcome {
    irradiance_w_m2: f32,
    mean_electrons: f32,
    mean_dn: f32,
    predicted_variance_dn: f32,
    saturated: bool,
    readings: Vec<f32>,
}

fn simulate<F: IrradianceField>(
    a: &ReadArgs,
    v: &Validated,
    field: &F,
    irradiance_w_m2: f32,
) -> Result<ReadOutcome, Failure> {
    // Constant QE over every wavelength any light here can have.
    let qe_val = v.qe;
    let qe = FnCurve::new(1.0, 1.0e5, move |_| qe_val);
    let px = Pixel::new(
        FillFactor::new(v.fill).map_err(|e| sensor_err("--fill-factor", e))?,
        qe,
        v.area,
        v.exposure,
        Sampling::default(),
    )
    .map_err(|e| sensor_err("pixel", e))?;
    let cam = Emva1288::ideal(px, v.gain, v.full_well, v.bits)
        .map_err(|e| sensor_err("camera", e))?
        .with_shot_noise()
        .with_dark_noise(v.dark)
        .map_err(|e| sensor_err("--dark-noise", e))?;
    let mu_e = cam.pixel.mean_electrons(field).map_err(|e| {
        usage(format!(
            "the light collects a non-finite number of electrons ({e}); lower --lux, --exposure or --pixel-area"
        ))
    })?;
    let mean_dn = cam.mean_dn(mu_e);
    // Photon transfer (EMVA 1288 Release 4.0 eq. 6/7): σ²_y = K²(σ²_d + μ_e) + σ²_q, σ²_q = 1/12 DN².
    let k = v.gain as f64;
    let predicted = k * k * ((v.dark as f64).powi(2) + mu_e as f64) + 1.0 / 12.0;
    let saturated = mu_e >= v.full_well || k * mu_e as f64 >= cam.max_dn() as f64;
    let mut rng = Pcg32::new(a.seed);
    let readings = (0..a.repeats).map(|_| cam.digitize(mu_e, 0, &mut rng)).collect();
    Ok(ReadOutcome {
        irradiance_w_m2,
        mean_electrons: mu_e,
        mean_dn,
        predicted_variance_dn: predicted as f32,
        saturated,
        readings,
    })
}

struct Validated {
    lux: f32,
    exposure: f32,
    qe: f32,
    gain: f32,
    bits: u8,
    dark: f32,
    full_well: f32,
    area: f32,
    fill: f32,
}

fn validate(a: &ReadArgs) -> Result<Validated, Failure> {
    let bits = if (1..=32).contains(&a.bits) {
        a.bits as u8
    } else {
        return Err(usage(format!("--bits {} is outside 1..=32", a.bits)));
    };
    if !(1..=MAX_REPEATS).contains(&a.repeats) {
        return Err(usage(format!(
            "--repeats {} is outside 1..={MAX_REPEATS}",
            a.repeats
        )));
    }
    Ok(Validated {
        lux: check("lux", a.lux, |v| v >= 0.0, "≥ 0 lx")?,
        exposure: check("exposure", a.exposure, |v| v >= 0.0, "≥ 0 s")?,
        qe: check("qe", a.qe, |v| (0.0..=1.0).contains(&v), "[0, 1]")?,
        gain: check("gain", a.gain, |v| v > 0.0, "> 0 DN/e⁻")?,
        bits,
        dark: check("dark-noise", a.dark_noise, |v| v >= 0.0, "≥ 0 e⁻")?,
        full_well: check("full-well", a.full_well, |v| v > 0.0, "> 0 e⁻")?,
        area: check("pixel-area", a.pixel_area, |v| v > 0.0, "> 0 m²")?,
        fill: check("fill-factor", a.fill_factor, |v| v > 0.0 && v <= 1.0, "(0, 1]")?,
    })
}

fn read(a: &ReadArgs) -> Result<(), Failure> {
    let light = parse_light(&a.light)?;
    let v = validate(a)?;
    let out = match light {
        Light::D65 => {
            let unit = illuminance_lux(&spectral::d65());
            let f = Scaled::new(spectral::d65(), v.lux / unit);
            let e = radiometry::spectral::integrate_fn(f.support().0, f.support().1, 1.0, |l| f.value(l));
            simulate(a, &v, &UniformSpectral(f), e)?
        }
        Light::A => {
            let unit = illuminance_lux(&IlluminantA);
            let f = Scaled::new(IlluminantA, v.lux / unit);
            let e = radiometry::spectral::integrate_fn(f.support().0, f.support().1, 1.0, |l| f.value(l));
            simulate(a, &v, &UniformSpectral(f), e)?
        }
        Light::Mono(l) => {
            let vl = spectral::photopic_v().value(l);
            if vl <= 0.0 {
                return Err(usage(format!(
                    "mono:{l}: V(λ) = 0 there (outside 360–830 nm), so no irradiance gives {} lx",
                    v.lux
                )));
            }
            let e = v.lux / (K_M * vl);
            if !e.is_finite() {
                return Err(usage(format!(
                    "mono:{l}: irradiance for {} lx overflows f32",
                    v.lux
                )));
            }
            simulate(a, &v, &Monochromatic::new(l, e), e)?
        }
    };
    let n = out.readings.len() as f64;
    let mean = out.readings.iter().map(|&r| r as f64).sum::<f64>() / n;
    let var = (out.readings.len() >= 2).then(|| {
        out.readings
            .iter()
            .map(|&r| (r as f64 - mean) * (r as f64 - mean))
            .sum::<f64>()
            / (n - 1.0)
    });
    match a.format {
        Format::Text => {
            println!("light {} at {} lx = {} W/m²", a.light, v.lux, out.irradiance_w_m2);
            println!("mean electrons μ_e      = {}", out.mean_electrons);
            println!("mean DN μ_y (model)     = {}", out.mean_dn);
            println!("predicted variance (DN²) = {}", out.predicted_variance_dn);
            if out.readings.len() == 1 {
                println!("reading (DN)            = {}", out.readings[0]);
            } else {
                println!("sample mean DN ({} readings) = {mean}", out.readings.len());
                if let Some(s) = var {
                    println!("sample variance (DN²)   = {s}");
                }
            }
            if out.saturated {
                println!(
                    "note: the pixel saturates (full well or ADC range); the variance prediction does not apply"
                );
            }
        }
        Format::Json => {
            let listed: Vec<_> = out
                .readings
                .iter()
                .take(MAX_LISTED_READINGS)
                .map(|&r| json_num(r as f64))
                .collect();
            let j = serde_json::json!({
                "light": a.light,
                "lux": json_num(v.lux as f64),
                "irradiance_w_m2": json_num(out.irradiance_w_m2 as f64),
                "mean_electrons": json_num(out.mean_electrons as f64),
                "mean_dn": json_num(out.mean_dn as f64),
                "repeats": a.repeats,
                "readings": listed,
                "sample_mean_dn": json_num(mean),
                "sample_variance_dn": var.map_or(serde_json::Value::Null, json_num),
                "predicted_variance_dn": json_num(out.predicted_variance_dn as f64),
                "saturated": out.saturated,
            });
            println!("{j}");
        }
    }
    Ok(())
}

fn edge(a: &EdgeArgs) -> Result<(), Failure> {
    if !(8..=512).contains(&a.size) {
        return Err(usage(format!("--size {} is outside 8..=512", a.size)));
    }
    let n = a.size;
    let pattern = BayerPattern::from(a.pattern);
    let panels = render(n, pattern).map_err(|e| Failure::Runtime(format!("edge target: {e}")))?;
    let energies: Vec<f32> = panels.iter().map(|p| false_colour_energy(&p.rgb)).collect();
    std::fs::create_dir_all(&a.out)
        .map_err(|e| Failure::Runtime(format!("cannot create {}: {e}", a.out.display())))?;
    let (path, written) = match a.format {
        ImageFormat::Svg => {
            let p = a.out.join("edge.svg");
            let r = write_svg(&p, n, &panels);
            (p, r)
        }
        ImageFormat::Png => {
            let p = a.out.join("edge.png");
            let r = write_png(&p, n, &panels);
            (p, r)
        }
    };
    written.map_err(|e| Failure::Runtime(format!("cannot write {}: {e}", path.display())))?;
    if a.json {
        let energy: serde_json::Map<String, serde_json::Value> = panels
            .iter()
            .zip(&energies)
            .map(|(p, &e)| (p.key.to_string(), json_num(e as f64)))
            .collect();
        println!(
            "{}",
            serde_json::json!({
                "file": path.display().to_string(),
                "size": n,
                "pattern": format!("{:?}", pattern).to_ascii_lowercase(),
                "slope": json_num(EDGE_SLOPE as f64),
                "wheel_motion_px_per_slot": json_num(WHEEL_MOTION_PX_PER_SLOT as f64),
                "false_colour_energy": energy,
            })
        );
    } else {
        println!(
            "slanted edge {n}×{n}, slope {EDGE_SLOPE}, Bayer {:?}: false-colour energy Σ Σ_c (c − mean)²",
            pattern
        );
        for (p, e) in panels.iter().zip(&energies) {
            println!("  {:<27}{e}", p.label);
        }
        println!("wrote {}", path.display());
    }
    Ok(())
}
