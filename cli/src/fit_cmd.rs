//! `radiometry fit FILE --model ggx|beckmann [--fresnel schlick|conductor]
//! [--diffuse]`: fits an analytic microfacet model to a MERL `.binary` table
//! and prints its parameters as spec strings (one per RGB channel, since the
//! spec grammar is monochrome) that `radiometry albedo` / `eval` accept, and
//! the fit error. The model, metric and optimiser are documented in
//! `radiometry_cli::fit`; the table → samples step (node weights,
//! subsampling, missing entries) in `radiometry_cli::fit::grid`.

use crate::Format;
use clap::ValueEnum;
use radiometry_cli::fit::grid::{Subsample, missing_mask, samples};
use radiometry_cli::fit::{ChannelFresnel, Fit, FitOptions, FresnelModel, fit, metric};
use radiometry_cli::merl;
use radiometry_cli::model::build_brdf;
use radiometry_cli::spec::{Distribution, G2Kind, parse_brdf};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Microfacet distribution of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ModelArg {
    /// GGX / Trowbridge–Reitz.
    Ggx,
    /// Beckmann.
    Beckmann,
}

/// Fresnel model of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FresnelArg {
    /// Schlick, F0 per channel.
    Schlick,
    /// Exact conductor, η and k per channel.
    Conductor,
}

/// Smith shadowing–masking of the fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum GArg {
    /// `G2 = 1/(1 + Λ(ωi) + Λ(ωo))`.
    HeightCorrelated,
    /// `G2 = G1(ωi) G1(ωo)`.
    Separable,
}

/// Arguments of `radiometry fit`.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// MERL `.binary` file (header of three i32 dims, then f64 values; any Rusinkiewicz grid resolution).
    file: PathBuf,
    /// Microfacet distribution.
    #[arg(long, value_enum)]
    model: ModelArg,
    /// Fresnel term: Schlick (F0 per channel) or exact conductor (η, k per channel).
    #[arg(long, value_enum, default_value_t = FresnelArg::Schlick)]
    fresnel: FresnelArg,
    /// Add a Lambertian term kd/π per channel (printed as the spec's `kd=`).
    #[arg(long)]
    diffuse: bool,
    /// Smith shadowing–masking variant.
    #[arg(long, value_enum, default_value_t = GArg::HeightCorrelated)]
    g: GArg,
    /// Node steps along θh,θd,φd: every node of θh, every 2nd θd and every 4th φd by default (182 250 of the
    /// MERL grid's 1 458 000 nodes); `1,1,1` reads every node.
    #[arg(long, default_value = "1,2,4")]
    subsample: String,
    /// Output format (json keys: file, grid, missing, model, g, fresnel, diffuse, subsample, samples, alpha, f0,
    /// eta, k, kd, metric, rms_log_error, channel_metric, metric_of_specs, specs, alpha_evaluations, solver_iterations, seconds).
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

/// Help shown after the options.
pub const AFTER_HELP: &str = "Metric: E = Σ w μi μo (ln(1 + μi f_table) − ln(1 + μi f_fit))² / Σ w μi μo over the \
table's nodes above the horizon (μ = cos θ, w = the node's cell measure in (ωi, ωo)), summed over R, G, B; the fit \
error printed is E and the RMS log error √E. Missing (negative) entries are skipped. One roughness for all channels; \
F0 (or η, k) and kd per channel. The three printed specs (R, G, B) are accepted by `radiometry albedo` and `eval`.";

fn parse_subsample(s: &str) -> Option<Subsample> {
    let v: Vec<usize> = s
        .split(',')
        .map(|x| x.trim().parse().ok())
        .collect::<Option<_>>()?;
    match v[..] {
        [h, d, p] => Subsample::new(h, d, p),
        _ => None,
    }
}

fn fail(msg: impl std::fmt::Display, code: u8) -> ExitCode {
    eprintln!("error: {msg}");
    ExitCode::from(code)
}

/// Runs `radiometry fit`.
pub fn run(a: FitArgs) -> ExitCode {
    let Some(sub) = parse_subsample(&a.subsample) else {
        return fail(
            format!(
                "--subsample {:?}: expected three positive integers H,D,P",
                a.subsample
            ),
            2,
        );
    };
    let t0 = Instant::now();
    let bytes = match std::fs::read(&a.file) {
        Ok(b) => b,
        Err(e) => return fail(format!("{}: {e}", a.file.display()), 1),
    };
    let table = match merl::from_bytes(&bytes) {
        Ok(t) => t,
        Err(e) => return fail(format!("{}: {e}", a.file.display()), 1),
    };
    let mask = missing_mask(&bytes, &table.grid);
    let s = match samples(&table.grid, &table.values, Some(&mask), sub) {
        Ok(s) => s,
        Err(e) => return fail(e, 1),
    };
    let options = FitOptions {
        distribution: match a.model {
            ModelArg::Ggx => Distribution::Ggx,
            ModelArg::Beckmann => Distribution::Beckmann,
        },
        g: match a.g {
            GArg::HeightCorrelated => G2Kind::HeightCorrelated,
            GArg::Separable => G2Kind::Separable,
        },
        fresnel: match a.fresnel {
            FresnelArg::Schlick => FresnelModel::Schlick,
            FresnelArg::Conductor => FresnelModel::Conductor,
        },
        diffuse: a.diffuse,
    };
    let f = match fit(&s, &options) {
        Ok(f) => f,
        Err(e) => return fail(format!("{}: {e}", a.file.display()), 1),
    };
    let specs = f.specs();
    // The metric recomputed from the printed text through the spec parser
    // and the plugins: shows that the specs reproduce the fit.
    let of_specs = specs
        .iter()
        .map(|t| parse_brdf(t).and_then(|p| build_brdf(t, &p)))
        .collect::<Result<Vec<_>, _>>()
        .ok()
        .and_then(|b| metric(&s, [&b[0], &b[1], &b[2]]).ok());
    let seconds = t0.elapsed().as_secs_f64();
    match a.format {
        Format::Text => print_text(&a, &table.grid.dims(), table.missing, sub, &f, of_specs, seconds),
        Format::Json => print_json(&a, &table.grid.dims(), table.missing, sub, &f, of_specs, seconds),
    }
    ExitCode::SUCCESS
}

fn names(a: &FitArgs) -> (&'static str, &'static str, &'static str) {
    (
        match a.model {
            ModelArg::Ggx => "ggx",
            ModelArg::Beckmann => "beckmann",
        },
        match a.g {
            GArg::HeightCorrelated => "height-correlated",
            GArg::Separable => "separable",
        },
        match a.fresnel {
            FresnelArg::Schlick => "schlick",
            FresnelArg::Conductor => "conductor",
        },
    )
}

fn conductor(f: &Fit) -> Option<([f64; 3], [f64; 3])> {
    let mut eta = [0.0; 3];
    let mut k = [0.0; 3];
    for c in 0..3 {
        match f.fresnel[c] {
            ChannelFresnel::Conductor { eta: e, k: kk } => {
                eta[c] = e;
                k[c] = kk;
            }
            ChannelFresnel::Schlick { .. } => return None,
        }
    }
    Some((eta, k))
}

fn print_text(
    a: &FitArgs,
    dims: &[usize; 3],
    missing: usize,
    sub: Subsample,
    f: &Fit,
    of_specs: Option<f64>,
    seconds: f64,
) {
    let (model, g, fresnel) = names(a);
    let [sh, sd, sp] = sub.steps();
    println!(
        "fit: {} ({}x{}x{} grid, {missing} missing entries)",
        a.file.display(),
        dims[0],
        dims[1],
        dims[2]
    );
    println!(
        "model: {model}, g={g}, fresnel={fresnel}, diffuse {}",
        if a.diffuse { "yes" } else { "no" }
    );
    println!(
        "samples: {} above the horizon (every {sh} theta_h, {sd} theta_d, {sp} phi_d node); {} roughness values, {} solver iterations, {seconds:.2} s",
        f.samples, f.alpha_evaluations, f.solver_iterations
    );
    let row = |v: [f64; 3]| format!("{:.6}  {:.6}  {:.6}", v[0], v[1], v[2]);
    println!("alpha         {:.6}", f.alpha);
    println!("F0 (R G B)    {}", row(f.f0()));
    if let Some((eta, k)) = conductor(f) {
        println!("eta (R G B)   {}", row(eta));
        println!("k (R G B)     {}", row(k));
    }
    if a.diffuse {
        println!("kd (R G B)    {}", row(f.kd));
    }
    println!("metric: E = sum w mu_i mu_o (ln(1 + mu_i f_table) - ln(1 + mu_i f_fit))^2 / sum w mu_i mu_o");
    println!(
        "E = {:.4e}, RMS log error sqrt(E) = {:.4e} (R {:.3e}, G {:.3e}, B {:.3e})",
        f.metric,
        f.rms_log_error(),
        f.channel_metric[0].sqrt(),
        f.channel_metric[1].sqrt(),
        f.channel_metric[2].sqrt()
    );
    if let Some(m) = of_specs {
        println!("E of the printed specs (6 digits) = {m:.4e}");
    }
    for (name, s) in ["R", "G", "B"].iter().zip(f.specs()) {
        println!("spec {name}: {s}");
    }
}

fn print_json(
    a: &FitArgs,
    dims: &[usize; 3],
    missing: usize,
    sub: Subsample,
    f: &Fit,
    of_specs: Option<f64>,
    seconds: f64,
) {
    let (model, g, fresnel) = names(a);
    let (eta, k) = match conductor(f) {
        Some((e, k)) => (serde_json::json!(e), serde_json::json!(k)),
        None => (serde_json::Value::Null, serde_json::Value::Null),
    };
    let j = serde_json::json!({
        "file": a.file.display().to_string(),
        "grid": dims,
        "missing": missing,
        "model": model,
        "g": g,
        "fresnel": fresnel,
        "diffuse": a.diffuse,
        "subsample": sub.steps(),
        "samples": f.samples,
        "alpha": f.alpha,
        "f0": f.f0(),
        "eta": eta,
        "k": k,
        "kd": f.kd,
        "metric": f.metric,
        "rms_log_error": f.rms_log_error(),
        "channel_metric": f.channel_metric,
        "metric_of_specs": of_specs,
        "specs": f.specs(),
        "alpha_evaluations": f.alpha_evaluations,
        "solver_iterations": f.solver_iterations,
        "seconds": seconds,
    });
    println!("{j}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subsample_flag() {
        assert_eq!(parse_subsample("1,2,4"), Some(Subsample::DEFAULT));
        assert_eq!(parse_subsample(" 1, 1 ,1"), Some(Subsample::ALL));
        for bad in ["", "1,2", "1,2,3,4", "0,1,1", "a,b,c", "-1,2,3"] {
            assert_eq!(parse_subsample(bad), None, "{bad}");
        }
    }
}
