//! `radiometry` command-line tool: the accuracy-vs-time report of the
//! hemisphere integrators (`tradeoff`), directional albedo, irradiance and
//! BRDF queries, material-ball previews.
//!
//! Exit codes: 0 success, 1 runtime failure (e.g. an integrator error or an
//! unwritable output folder), 2 invalid command line or spec.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod bench;
mod fit_cmd;
mod furnace;
mod preview_cmd;
mod sensor_cmd;
mod sensor_edge;
mod tabulate_cmd;

/// `model`, `reference`, `tradeoff` and the spec grammar live in the library half of this package (`src/lib.rs`,
/// shared with the Python module); `crate::model` etc. keep their paths for the modules here.
use radiometry_cli::{model, spec, tradeoff};

use clap::{Parser, Subcommand, ValueEnum};
use radiometry::glam::Vec3;
use radiometry::integrator::{DEFAULT_MAX_BUDGET, DirectionalAlbedo, Integrator, integrate_to_tolerance};
use radiometry::{Brdf, Spectrum, WideSpectrum};
use std::process::ExitCode;
use std::time::Instant;

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Format {
    /// Human-readable text.
    Text,
    /// One JSON object.
    Json,
}

#[derive(Parser, Debug)]
#[command(
    name = "radiometry",
    version,
    about = "Radiometry and BRDF tool: what integration accuracy costs in time, albedo, irradiance, f_r",
    long_about = "Radiometry and BRDF tool.\n\nStart with `radiometry tradeoff` (accuracy-vs-time report of every \
hemisphere integrator against independent references). Angles are in degrees everywhere on the command line. \
Exit codes: 0 success, 1 runtime failure, 2 invalid command line or spec."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Accuracy-vs-time report: every integrator over a ladder of budgets on a standard suite of directional
    /// albedos, against independent f64 references (summary table on stdout; CSV, SVG plots and summary.md in
    /// the output folder).
    Tradeoff {
        /// CI-sized run: a few cases, budgets ≤ 4096, one timing repeat.
        #[arg(long)]
        quick: bool,
        /// Output folder (created if missing).
        #[arg(long, default_value = "target/tradeoff")]
        out: std::path::PathBuf,
        /// Worker threads (default: available parallelism).
        #[arg(long)]
        threads: Option<usize>,
        /// Seed of the Monte Carlo integrators.
        #[arg(long, default_value_t = model::DEFAULT_SEED)]
        seed: u64,
        /// Hide the progress bar on stderr.
        #[arg(long)]
        no_progress: bool,
        /// Only the cases whose name contains one of these comma-separated substrings (e.g. `ggx-a0.01,to89.9`).
        #[arg(long, value_delimiter = ',')]
        cases: Vec<String>,
        /// Only the integrators whose name contains one of these comma-separated substrings (e.g. `gauss,adaptive`).
        #[arg(long, value_delimiter = ',')]
        integrators: Vec<String>,
        /// Rows of outside integrators (a CSV with the header of `radiometry::tradeoff::external`, as the Python
        /// `radiometry.tradeoff(integrators=..., peers_csv=...)` writes it) to merge into the tables, the CSVs and the
        /// summary (e.g. SciPy's nquad for the to-tolerance comparison).
        #[arg(long)]
        peers: Option<std::path::PathBuf>,
        /// Also run the random-material honesty check: N random specs of the grammar (sums, mixes and coats nested
        /// up to depth 3), random θo (a third grazing), tolerances 1e-6..1e-3, a random integrator (half `auto`),
        /// each to its tolerance, judged against an independent f64 quadrature; writes honesty.csv and the count of
        /// claims and lies to summary.md. `--cases honesty` runs only this check.
        #[arg(long, default_value_t = 0)]
        honesty: usize,
    },
    /// Directional albedo ρ(θo) = ∫ f_r(ωi, ωo) cos θi dωi of a BRDF.
    #[command(after_help = spec::BRDF_SPEC_HELP)]
    Albedo {
        /// BRDF spec, e.g. `ggx(alpha=0.1, g=separable, fresnel=schlick(f0=0.04))` (see below).
        spec: String,
        /// Outgoing polar angle θo in degrees, in [0, 90].
        #[arg(long = "theta-o", allow_negative_numbers = true)]
        theta_o: f64,
        /// Integrator name (list: `radiometry integrators`). The default, `auto`, picks the parameterisation from
        /// the integrand (a nested Clenshaw–Curtis × trapezoid grid for broad lobes, the warped adaptive rule for
        /// narrow ones; with a fixed `--budget`, the plain adaptive rule first for a kinked lobe with a mixture
        /// sampling map: the composites and the Oren–Nayar family) and needs the fewest evaluations of the report's integrators to a tolerance (`radiometry
        /// tradeoff`, summary.md, section "To a tolerance").
        #[arg(long, default_value = "auto")]
        integrator: String,
        /// Evaluation budget of a single run (default 4096).
        #[arg(long, conflicts_with = "tol")]
        budget: Option<u32>,
        /// Absolute error tolerance. Refines until the estimate is resolved, its error estimate is ≤ X and it is
        /// confirmed beyond one run: the budget is doubled from 64 until two successive runs agree within X (the
        /// adaptive rules and `auto` instead refine their own work, and `auto` and `adaptive-warped` then need a
        /// run of a rule with other nodes to agree: the plain (μ, φ) square split at μi = μo and cos Δφ = 0, the
        /// sampling map's square, or the shifted twin of either), with at
        /// most 4194304 (2^22) evaluations in the last run. The output says what happened ("stopped": "tolerance
        /// reached" | "max budget reached" | "integrator cap reached" | "out of reach": Monte Carlo whose N^-1/2
        /// projection needs more than 4 × the maximum budget), and "confirmation": how far the answer moved from
        /// the run that confirmed it.
        #[arg(long)]
        tol: Option<f64>,
        /// Seed of Monte Carlo integrators.
        #[arg(long, default_value_t = model::DEFAULT_SEED)]
        seed: u64,
        /// Output format (json keys: value, error, evaluations, seconds, integrator, budget, stopped, status,
        /// status_reason; for a colour spec value, error and confirmation are [R, G, B] arrays and "channels" is
        /// "linear-srgb").
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// One value (the Rec. 709 luminance path) even for a colour spec. Without it a spec with an rgb() colour,
        /// a named metal or a MERL file gives one value per channel (R G B, linear sRGB); a grey spec always
        /// gives one value.
        #[arg(long)]
        mono: bool,
    },
    /// Evaluate f_r(ωi → ωo) [1/sr] of a BRDF.
    #[command(after_help = spec::BRDF_SPEC_HELP)]
    Eval {
        /// BRDF spec (see below).
        spec: String,
        /// Incident direction THETA,PHI in degrees.
        #[arg(long, allow_hyphen_values = true)]
        wi: String,
        /// Outgoing direction THETA,PHI in degrees.
        #[arg(long, allow_hyphen_values = true)]
        wo: String,
        /// Output format (json keys: value, wi, wo; for a colour spec value is an [R, G, B] array and "channels"
        /// is "linear-srgb").
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// One value (the Rec. 709 luminance path) even for a colour spec. Without it a spec with an rgb() colour,
        /// a named metal or a MERL file prints one value per channel (R G B, linear sRGB); a grey spec always
        /// prints one value.
        #[arg(long)]
        mono: bool,
    },
    /// Irradiance E on a surface with normal +Z from a light spec (sum of lights), in closed form.
    #[command(after_help = spec::LIGHT_SPEC_HELP)]
    Irradiance {
        /// Light spec, e.g. `cap(axis_theta=95, half_angle=10, radiance=1) + sky(radiance=0.1)`.
        light: String,
        /// Output format (json keys: value, lights).
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// List the integrator names.
    Integrators,
    /// Sensor simulation: EMVA 1288 pixel readings under a light (`read`), demosaicing false colour on a
    /// slanted edge (`edge`).
    #[command(subcommand)]
    Sensor(sensor_cmd::SensorCommand),
    /// Single-thread throughput of every BRDF plugin's eval / eval_batch / eval_batch_soa / pdf / pdf_batch /
    /// sample / sample_batch, also as fractions of this CPU's limits timed in the same run (a reference GGX kernel, scalar
    /// and auto-vectorised, and the memory-stream bound).
    #[command(after_help = bench::AFTER_HELP)]
    Bench(bench::BenchArgs),
    /// White-furnace test of a microfacet BRDF: albedo over θo with single scattering and with the
    /// Kulla–Conty multiple-scattering compensation (table on stdout, SVG plot).
    #[command(after_help = spec::BRDF_SPEC_HELP)]
    Furnace(furnace::FurnaceArgs),
    /// Fit a microfacet model (GGX or Beckmann, Schlick or conductor Fresnel, optional diffuse term) to a
    /// tabulated BRDF in a MERL `.binary` file: prints the parameters as spec strings (R, G, B) that `albedo` and
    /// `eval` accept, and the fit error.
    #[command(after_help = fit_cmd::AFTER_HELP)]
    Fit(fit_cmd::FitArgs),
    /// Write a MERL .binary file of a BRDF spec (plus an optional Lambertian base), e.g. to test
    /// `tabulated(file=…)`.
    #[command(after_help = spec::BRDF_SPEC_HELP)]
    Tabulate(tabulate_cmd::TabulateArgs),
    /// Render a material ball: a sphere with the BRDF under a sun and a sky, by BRDF sampling, light sampling and
    /// multiple importance sampling, to a PNG or SVG.
    #[command(after_help = format!("{}{}", preview_cmd::AFTER_HELP, spec::BRDF_SPEC_HELP))]
    Preview(preview_cmd::PreviewArgs),
}

fn spec_error(e: spec::SpecError) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(2)
}

fn usage_error(msg: &str) -> ExitCode {
    eprintln!("error: {msg}");
    ExitCode::from(2)
}

fn dir(theta_deg: f64, phi_deg: f64) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(
        (t.sin() * p.cos()) as f32,
        (t.sin() * p.sin()) as f32,
        t.cos() as f32,
    )
}

fn json_num(x: f64) -> serde_json::Value {
    serde_json::Number::from_f64(x).map_or(serde_json::Value::Null, serde_json::Value::Number)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Eval {
            spec,
            wi,
            wo,
            format,
            mono,
        } => {
            let parsed = match spec::parse_brdf(&spec) {
                Ok(p) => p,
                Err(e) => return spec_error(e),
            };
            let (ti, pi) = match spec::parse_angles(&wi) {
                Ok(a) => a,
                Err(e) => return spec_error(e),
            };
            let (to, po) = match spec::parse_angles(&wo) {
                Ok(a) => a,
                Err(e) => return spec_error(e),
            };
            let (wi, wo) = (dir(ti, pi), dir(to, po));
            if colour(&parsed, mono) {
                let brdf = match model::build_brdf_rgb(&spec, &parsed) {
                    Ok(b) => b,
                    Err(e) => return spec_error(e),
                };
                let f = brdf.eval(wi, wo);
                match format {
                    Format::Text => println!("{} {} {}", f.x, f.y, f.z),
                    Format::Json => println!(
                        "{}",
                        serde_json::json!({
                            "value": f.to_array().map(|v| json_num(v as f64)),
                            "channels": CHANNELS,
                            "wi": [ti, pi],
                            "wo": [to, po],
                        })
                    ),
                }
                return ExitCode::SUCCESS;
            }
            let brdf = match model::build_brdf(&spec, &parsed) {
                Ok(b) => b,
                Err(e) => return spec_error(e),
            };
            let f = brdf.eval(wi, wo);
            match format {
                Format::Text => println!("{f}"),
                Format::Json => println!(
                    "{}",
                    serde_json::json!({"value": json_num(f as f64), "wi": [ti, pi], "wo": [to, po]})
                ),
            }
            ExitCode::SUCCESS
        }
        Command::Albedo {
            spec,
            theta_o,
            integrator,
            budget,
            tol,
            seed,
            format,
            mono,
        } => {
            let parsed = match spec::parse_brdf(&spec) {
                Ok(p) => p,
                Err(e) => return spec_error(e),
            };
            let a = AlbedoArgs {
                theta_o,
                integrator,
                budget,
                tol,
                seed,
                format,
            };
            if colour(&parsed, mono) {
                match model::build_brdf_rgb(&spec, &parsed) {
                    Ok(b) => albedo(&b, a),
                    Err(e) => spec_error(e),
                }
            } else {
                match model::build_brdf(&spec, &parsed) {
                    Ok(b) => albedo(&b, a),
                    Err(e) => spec_error(e),
                }
            }
        }
        Command::Irradiance { light, format } => {
            let lights = match spec::parse_lights(&light) {
                Ok(l) => l,
                Err(e) => return spec_error(e),
            };
            let mut total = 0.0f64;
            let mut parts = Vec::new();
            for l in &lights {
                let (kind, e) = model::irradiance_of(l);
                total += e as f64;
                parts.push(serde_json::json!({"kind": kind, "irradiance": json_num(e as f64)}));
            }
            match format {
                Format::Text => println!("{total}"),
                Format::Json => println!(
                    "{}",
                    serde_json::json!({"value": json_num(total), "lights": parts})
                ),
            }
            ExitCode::SUCCESS
        }
        Command::Sensor(cmd) => sensor_cmd::run(cmd),
        Command::Bench(args) => bench::run(args),
        Command::Furnace(args) => furnace::run(args),
        Command::Fit(args) => fit_cmd::run(args),
        Command::Tabulate(args) => tabulate_cmd::run(args),
        Command::Preview(args) => preview_cmd::run(args),
        Command::Integrators => {
            for i in model::all_integrators(model::DEFAULT_SEED, 0.0) {
                println!("{}", i.name());
            }
            ExitCode::SUCCESS
        }
        Command::Tradeoff {
            quick,
            out,
            threads,
            seed,
            no_progress,
            cases,
            integrators,
            peers,
            honesty,
        } => {
            let external = match peers {
                None => Vec::new(),
                Some(p) => match std::fs::read_to_string(&p)
                    .map_err(|e| format!("cannot read {}: {e}", p.display()))
                    .and_then(|t| {
                        tradeoff::external::from_csv(&t).map_err(|e| format!("{}: {e}", p.display()))
                    }) {
                    Ok(r) => r,
                    Err(e) => return usage_error(&e),
                },
            };
            let threads = threads
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
                .max(1);
            match tradeoff::run(&tradeoff::Options {
                quick,
                out,
                threads,
                seed,
                progress: !no_progress,
                cases,
                integrators,
                external,
                honesty,
            }) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(1)
                }
            }
        }
    }
}

/// The options of `radiometry albedo` after the spec.
struct AlbedoArgs {
    theta_o: f64,
    integrator: String,
    budget: Option<u32>,
    tol: Option<f64>,
    seed: u64,
    format: Format,
}

/// What the channels of a colour result are (the JSON key "channels").
const CHANNELS: &str = "linear-srgb";

/// Whether a spec is printed per channel: it has a colour (an rgb() colour, a named metal or a MERL file) and
/// `--mono` was not given.
fn colour(parsed: &spec::BrdfSpec, mono: bool) -> bool {
    !mono && !parsed.is_grey()
}

/// A result as text: the number (one channel) or the channels separated by spaces.
fn wide_text<W: WideSpectrum>(w: &W, channels: usize, f: impl Fn(f64) -> String) -> String {
    (0..channels)
        .map(|c| f(w.channel(c)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A result as JSON: the number (one channel) or the array of the channels.
fn wide_json<W: WideSpectrum>(w: &W, channels: usize) -> serde_json::Value {
    if channels == 1 {
        json_num(w.channel(0))
    } else {
        serde_json::Value::Array((0..channels).map(|c| json_num(w.channel(c))).collect())
    }
}

/// `radiometry albedo` with the run-time BRDF built (monochrome or RGB).
fn albedo<S: Spectrum>(brdf: &model::AnyBrdf<S>, a: AlbedoArgs) -> ExitCode {
    let AlbedoArgs {
        theta_o,
        integrator,
        budget,
        tol,
        seed,
        format,
    } = a;
    if !(0.0..=90.0).contains(&theta_o) {
        return usage_error(&format!("--theta-o {theta_o} is outside [0, 90] degrees"));
    }
    if let Some(t) = tol
        && !(t.is_finite() && t > 0.0)
    {
        return usage_error(&format!("--tol {t} must be a positive finite number"));
    }
    let Some(integ) = model::integrator_by_name(&integrator, seed, tol.unwrap_or(0.0)) else {
        let names: Vec<_> = model::all_integrators(seed, 0.0)
            .iter()
            .map(|i| i.name())
            .collect();
        return usage_error(&format!(
            "unknown integrator `{integrator}`; expected one of: {}",
            names.join(", ")
        ));
    };
    let g = DirectionalAlbedo {
        brdf: &brdf,
        wo: dir(theta_o, 0.0),
    };
    let t0 = Instant::now();
    let (est, used_budget, stopped, total) = if let Some(t) = tol {
        match integrate_to_tolerance(&integ, &g, t, 64, DEFAULT_MAX_BUDGET) {
            Ok(o) => (o.estimate, o.budget, Some(o), o.total_evaluations),
            Err(e) => {
                eprintln!("error: {}: {e}", integ.name());
                return ExitCode::from(1);
            }
        }
    } else {
        let b = budget.unwrap_or(4096);
        match integ.integrate(&g, b) {
            Ok(e) => (e, b, None, e.evaluations),
            Err(e) => {
                eprintln!("error: {}: {e}", integ.name());
                return ExitCode::from(1);
            }
        }
    };
    let secs = t0.elapsed().as_secs_f64();
    match format {
        Format::Text => {
            print!(
                "albedo = {} ± {}  ({} evaluations, {:.6} s, {}, budget {})",
                wide_text(&est.value, S::CHANNELS, |v| format!("{v}")),
                wide_text(&est.error, S::CHANNELS, |v| format!("{v}")),
                total,
                secs,
                integ.name(),
                used_budget
            );
            if let Some(o) = stopped {
                print!(", stopped: {}", o.stop.as_str());
                if let Some(c) = o.confirmation {
                    let c = wide_text(&c, S::CHANNELS, |v| format!("{v:.3e}"));
                    print!(" (confirmed: moved {c} from the previous run)");
                }
            }
            if !est.status.is_resolved() {
                print!(", {}", est.status);
            }
            println!();
        }
        Format::Json => {
            let mut j = serde_json::json!({
                "value": wide_json(&est.value, S::CHANNELS),
                "error": wide_json(&est.error, S::CHANNELS),
                "evaluations": total,
                "seconds": json_num(secs),
                "integrator": integ.name(),
                "budget": used_budget,
                "final_run_evaluations": est.evaluations,
                "status": est.status.as_str(),
                "status_reason": est.status.reason(),
            });
            if let Some(o) = stopped {
                j["stopped"] = serde_json::Value::String(o.stop.as_str().into());
                j["runs"] = serde_json::Value::from(o.runs);
                if let Some(c) = o.confirmation {
                    j["confirmation"] = wide_json(&c, S::CHANNELS);
                }
                j["tol"] = json_num(tol.unwrap_or(0.0));
                j["max_budget"] = serde_json::Value::from(DEFAULT_MAX_BUDGET);
            }
            if S::CHANNELS > 1 {
                j["channels"] = serde_json::Value::from(CHANNELS);
            }
            println!("{j}");
        }
    }
    ExitCode::SUCCESS
}
