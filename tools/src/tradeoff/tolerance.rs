//! The to-tolerance section of `radiometry tradeoff`: every case × every
//! integrator × the relative tolerances [`TOL_TARGETS`], each run through
//! [`integrate_to_tolerance`] as `radiometry albedo --tol` runs it (start
//! budget 64, at most [`DEFAULT_MAX_BUDGET`] evaluations in the last run),
//! compared with the case's f64 reference.
//!
//! The absolute tolerance handed to the driver is `rel_tol × |reference|`
//! ([`tolerance_for`]); an outside harness (the Python
//! `radiometry.tradeoff(integrators=…)`) computes the same tolerances from
//! [`case_reference`].
//!
//! Honesty: a run that stops with "tolerance reached", resolved, is
//! dishonest when its true error exceeds `10 × max(claimed error, tol)`.

use super::product::{self, ProductCase};
use super::{Case, ExternalRow, Options};
use crate::model::{AnyBrdf, AnyIntegrator};
use crate::reference::Reference;
use radiometry::glam::Vec3;
use radiometry::integrator::{
    DEFAULT_MAX_BUDGET, DirectionalAlbedo, IntegrateError, ToleranceOutcome, integrate_to_tolerance,
};
use std::fmt::Write as _;
use std::time::Instant;

/// Relative tolerances of the section. `10⁻⁸` is left out: it is below the
/// `f32` evaluation floor of the integrands (`2⁻²³ ≈ 1.2·10⁻⁷` relative per
/// value; the report's best rows level off at 2–5·10⁻⁸).
pub const TOL_TARGETS: [f64; 3] = [1e-2, 1e-4, 1e-6];

/// The exact CSV header of `tolerance.csv` (a contract).
pub const TOL_CSV_HEADER: &str = "case,integrator,tol,rel_tol,evaluations,final_budget,estimate,reference,abs_error,rel_error,error_estimate,stopped,status,status_reason,seconds";

/// A run is dishonest when it claims the tolerance, resolved, and its true
/// error exceeds this many times `max(claimed error, tol)`.
pub const HONESTY_FACTOR: f64 = 10.0;

/// The absolute tolerance of a to-tolerance row: `rel_tol × |reference|`
/// (the section's tolerances are relative to the case's f64 reference, as
/// the report's other sections measure relative errors).
pub fn tolerance_for(reference: f64, rel_tol: f64) -> f64 {
    rel_tol * reference.abs().max(f64::MIN_POSITIVE)
}

/// The f64 reference of the case called `name` (either suite, full
/// selection) — what an outside harness needs for [`tolerance_for`].
pub fn case_reference(name: &str) -> Result<Reference, String> {
    if let Some(c) = super::suite(false).into_iter().find(|c| c.name == name) {
        return Ok(crate::reference::albedo(&c.model, c.theta_o.to_radians()));
    }
    if let Some(c) = product::suite(false).into_iter().find(|c| c.name == name) {
        return Ok(product::reference(&c));
    }
    Err(format!("unknown case `{name}`"))
}

/// Whether `name` is a case of either suite (full selection).
pub fn case_exists(name: &str) -> bool {
    super::suite(false).iter().any(|c| c.name == name) || product::suite(false).iter().any(|c| c.name == name)
}

/// One to-tolerance run.
#[derive(Clone, Debug)]
pub struct TolRow {
    /// Case name.
    pub case: String,
    /// Integrator name.
    pub integrator: String,
    /// Deterministic quadrature (else Monte Carlo).
    pub deterministic: bool,
    /// Whether the integrator is one of the crate's own.
    pub builtin: bool,
    /// Relative tolerance (one of [`TOL_TARGETS`]).
    pub rel_tol: f64,
    /// Absolute tolerance handed to the driver.
    pub tol: f64,
    /// Evaluations over all runs.
    pub evaluations: u64,
    /// Budget of the last run.
    pub final_budget: u32,
    /// The value returned.
    pub estimate: f64,
    /// Its claimed error.
    pub error_estimate: f64,
    /// Why it stopped (`tolerance reached`, …; `error: …` if refused).
    pub stopped: String,
    /// `resolved` / `unresolved`.
    pub status: String,
    /// Status reason (empty when resolved).
    pub status_reason: String,
    /// Wall time of the whole refinement, seconds.
    pub seconds: f64,
    /// The case's f64 reference.
    pub reference: f64,
}

impl TolRow {
    /// `|estimate − reference|`.
    pub fn abs_error(&self) -> f64 {
        (self.estimate - self.reference).abs()
    }

    /// Whether the row claims the tolerance, resolved.
    pub fn claims(&self) -> bool {
        self.stopped == "tolerance reached" && self.status == "resolved"
    }

    /// A claimed, resolved row whose true error exceeds
    /// [`HONESTY_FACTOR`]` × max(claim, tol)`.
    pub fn dishonest(&self) -> bool {
        self.claims() && self.abs_error() > HONESTY_FACTOR * self.error_estimate.max(self.tol)
    }

    fn from_outcome(r: Result<ToleranceOutcome<f64>, IntegrateError>, seconds: f64, base: TolRow) -> TolRow {
        match r {
            Ok(o) => TolRow {
                evaluations: o.total_evaluations,
                final_budget: o.budget,
                estimate: o.estimate.value,
                error_estimate: o.estimate.error,
                stopped: o.stop.as_str().into(),
                status: o.estimate.status.as_str().into(),
                status_reason: o.estimate.status.reason().into(),
                seconds,
                ..base
            },
            Err(e) => TolRow {
                stopped: format!("error: {e}").replace(',', ";"),
                status: "unresolved".into(),
                status_reason: "refused".into(),
                estimate: f64::NAN,
                error_estimate: f64::NAN,
                seconds,
                ..base
            },
        }
    }
}

fn blank(
    case: &str,
    integrator: &str,
    deterministic: bool,
    rel_tol: f64,
    tol: f64,
    reference: f64,
) -> TolRow {
    TolRow {
        case: case.into(),
        integrator: integrator.into(),
        deterministic,
        builtin: true,
        rel_tol,
        tol,
        evaluations: 0,
        final_budget: 0,
        estimate: 0.0,
        error_estimate: 0.0,
        stopped: String::new(),
        status: String::new(),
        status_reason: String::new(),
        seconds: 0.0,
        reference,
    }
}

/// Runs `integ` to every tolerance on an albedo case.
pub fn albedo_rows(brdf: &AnyBrdf, case: &Case, reference: f64, integ: &AnyIntegrator) -> Vec<TolRow> {
    let t = case.theta_o.to_radians();
    let g = DirectionalAlbedo {
        brdf,
        wo: Vec3::new(t.sin() as f32, 0.0, t.cos() as f32),
    };
    use radiometry::Integrator as _;
    TOL_TARGETS
        .iter()
        .map(|&rel| {
            let tol = tolerance_for(reference, rel);
            let t0 = Instant::now();
            let r = integrate_to_tolerance(integ, &g, tol, 64, case.budgets.tolerance);
            let base = blank(
                &case.name,
                integ.name(),
                integ.is_deterministic(),
                rel,
                tol,
                reference,
            );
            TolRow::from_outcome(r, t0.elapsed().as_secs_f64(), base)
        })
        .collect()
}

/// Runs a product method to every tolerance on a product case.
pub fn product_rows(brdf: &AnyBrdf, case: &ProductCase, reference: f64, m: &product::Method) -> Vec<TolRow> {
    TOL_TARGETS
        .iter()
        .map(|&rel| {
            let tol = tolerance_for(reference, rel);
            let t0 = Instant::now();
            let r = m.to_tolerance(brdf, case, tol);
            let base = blank(&case.name, &m.name(), m.is_deterministic(), rel, tol, reference);
            TolRow::from_outcome(r, t0.elapsed().as_secs_f64(), base)
        })
        .collect()
}

/// The to-tolerance rows of the outside integrators (`opt.external` rows
/// with a `tol`), with the reference of their case; rows naming an unknown
/// case are reported as an error.
pub fn external_rows(opt: &Options, refs: &[(String, Reference)]) -> Result<Vec<TolRow>, String> {
    let mut v = Vec::new();
    for e in opt.external.iter().filter(|e| e.tol.is_some()) {
        let Some((_, r)) = refs.iter().find(|(n, _)| *n == e.case) else {
            if case_exists(&e.case) {
                continue; // a case the --cases filter left out
            }
            return Err(format!(
                "external row of `{}` names the unknown case `{}`",
                e.integrator, e.case
            ));
        };
        v.push(from_external(e, r.value));
    }
    Ok(v)
}

fn from_external(e: &ExternalRow, reference: f64) -> TolRow {
    let tol = e.tol.unwrap_or(f64::NAN);
    TolRow {
        case: e.case.clone(),
        integrator: e.integrator.clone(),
        deterministic: e.deterministic,
        builtin: false,
        rel_tol: f64::NAN,
        tol,
        evaluations: e.evaluations,
        final_budget: 0,
        estimate: e.estimate,
        error_estimate: e.error_estimate,
        stopped: e.stopped.replace(',', ";"),
        status: if e.resolved { "resolved" } else { "unresolved" }.into(),
        status_reason: e.status_reason.replace(',', ";"),
        seconds: e.seconds,
        reference,
    }
}

/// Fills the relative tolerance of outside rows (`tol / |reference|`,
/// snapped to the nearest of [`TOL_TARGETS`] within 1 %).
pub fn snap_rel_tol(rows: &mut [TolRow]) {
    for r in rows.iter_mut().filter(|r| !r.builtin) {
        let rel = r.tol / r.reference.abs().max(f64::MIN_POSITIVE);
        r.rel_tol = TOL_TARGETS
            .iter()
            .copied()
            .find(|t| (rel / t - 1.0).abs() <= 0.01)
            .unwrap_or(rel);
    }
}

/// `tolerance.csv`.
pub fn csv(rows: &[TolRow]) -> String {
    let mut s = String::from(TOL_CSV_HEADER);
    s.push('\n');
    for r in rows {
        let ae = r.abs_error();
        let _ = writeln!(
            s,
            "{},{},{:e},{:e},{},{},{},{},{:e},{:e},{:e},{},{},{},{}",
            r.case,
            r.integrator,
            r.tol,
            r.rel_tol,
            r.evaluations,
            r.final_budget,
            r.estimate,
            r.reference,
            ae,
            ae / r.reference.abs().max(f64::MIN_POSITIVE),
            r.error_estimate,
            r.stopped,
            r.status,
            r.status_reason,
            r.seconds
        );
    }
    s
}

/// The summary section (markdown) and its plain-text lines for stdout.
pub fn summary(rows: &[TolRow], families: &[(String, String)]) -> (String, String) {
    let mut md = String::new();
    let mut text = String::new();
    let _ = writeln!(text, "\n== To a tolerance ==\n");
    let _ = writeln!(
        md,
        "### To a tolerance (`integrate_to_tolerance`, as `radiometry albedo --tol`)\n"
    );
    let _ = writeln!(
        md,
        "Every case of both suites × every integrator × relative tolerance 1e-2, 1e-4, 1e-6 (absolute tolerance \
         handed to the driver: that × the case's f64 reference), start budget 64, at most {DEFAULT_MAX_BUDGET} \
         evaluations in the last run ({} for the composites' cases from EON to OpenPBR, whose fixed-budget ladders \
         stop at {} or, for the mix and the OpenPBRs, {}: their sampling maps cost 0.6–2.4 µs per evaluation). \
         A row *claims* when it stops with `tolerance reached` and a resolved status; \
         it is *dishonest* when its true error then exceeds {HONESTY_FACTOR}× max(claimed error, tol). `10⁻⁸` is not \
         run: it is below the `f32` evaluation floor. Raw rows: `tolerance.csv`.\n",
        super::Budgets::COMPOSITE.tolerance,
        super::Budgets::COMPOSITE.ladder,
        super::Budgets::HEAVY.ladder
    );
    let builtin: Vec<&TolRow> = rows.iter().filter(|r| r.builtin).collect();
    let claimed = builtin.iter().filter(|r| r.claims()).count();
    let bad: Vec<&TolRow> = rows.iter().filter(|r| r.dishonest()).collect();
    let line = format!(
        "Honesty: {claimed} of {} runs of the crate's integrators claim the tolerance (resolved); {} of them have a \
         true error above {}× max(claim, tol) (target 0).",
        builtin.len(),
        bad.iter().filter(|r| r.builtin).count(),
        HONESTY_FACTOR
    );
    let _ = writeln!(md, "{line}\n");
    let _ = writeln!(text, "{line}");
    let outside: Vec<&TolRow> = rows.iter().filter(|r| !r.builtin).collect();
    if !outside.is_empty() {
        let line = format!(
            "Outside integrators (measured elsewhere, merged by case): {} of {} runs claim the tolerance; {} of them \
             have a true error above {}× max(claim, tol).",
            outside.iter().filter(|r| r.claims()).count(),
            outside.len(),
            bad.iter().filter(|r| !r.builtin).count(),
            HONESTY_FACTOR
        );
        let _ = writeln!(md, "{line}\n");
        let _ = writeln!(text, "{line}");
    }
    for r in bad
        .iter()
        .filter(|r| r.builtin)
        .chain(bad.iter().filter(|r| !r.builtin).take(10))
        .take(30)
    {
        let l = format!(
            "  dishonest: {} {} rel_tol {:e}: {} ± {:.2e} vs {} (true error {:.2e})",
            r.case,
            r.integrator,
            r.rel_tol,
            r.estimate,
            r.error_estimate,
            r.reference,
            r.abs_error()
        );
        let _ = writeln!(md, "- `{}`", l.trim());
        let _ = writeln!(text, "{l}");
    }
    // Per integrator and tolerance: claimed runs, and the evaluations
    // (median and worst over the claimed runs).
    let mut integs: Vec<(&str, bool)> = Vec::new();
    for r in rows {
        if !integs.iter().any(|(n, _)| *n == r.integrator) {
            integs.push((&r.integrator, r.builtin));
        }
    }
    let _ = writeln!(
        md,
        "\nPer integrator: runs that claimed the tolerance / runs, and the evaluations they spent (median, worst) \
         — all runs of the refinement counted.\n"
    );
    let _ = writeln!(md, "| integrator | 1e-2 | 1e-4 | 1e-6 |");
    let _ = writeln!(md, "|---|---|---|---|");
    for (name, builtin) in &integs {
        let mut cells = Vec::new();
        for &t in &TOL_TARGETS {
            let of: Vec<&TolRow> = rows
                .iter()
                .filter(|r| r.integrator == *name && (r.rel_tol / t - 1.0).abs() < 1e-6)
                .collect();
            let mut ev: Vec<u64> = of.iter().filter(|r| r.claims()).map(|r| r.evaluations).collect();
            ev.sort_unstable();
            let cell = if ev.is_empty() {
                format!("0/{}", of.len())
            } else {
                format!(
                    "{}/{}: {} ({})",
                    ev.len(),
                    of.len(),
                    ev[ev.len() / 2],
                    ev[ev.len() - 1]
                )
            };
            cells.push(cell);
        }
        let label = if *builtin {
            format!("`{name}`")
        } else {
            format!("`{name}` (outside)")
        };
        let _ = writeln!(md, "| {label} | {} | {} | {} |", cells[0], cells[1], cells[2]);
    }
    let (t, m) = versus_outside(rows, families);
    text.push_str(&t);
    md.push_str(&m);
    (text, md)
}

/// `auto` against each outside integrator on the GGX albedo cases at
/// relative tolerance 10⁻⁶: `auto`'s evaluations (all runs) and true error
/// `e`, and the fewest evaluations of any of the outside integrator's rows
/// on that case (any tolerance) whose true error is `≤ max(e, 10⁻⁶ |ref|)`
/// — "for the same true error", its cheapest adequate run.
fn versus_outside(rows: &[TolRow], families: &[(String, String)]) -> (String, String) {
    let (mut md, mut text) = (String::new(), String::new());
    let mut outside: Vec<&str> = Vec::new();
    for r in rows.iter().filter(|r| !r.builtin) {
        if !outside.contains(&r.integrator.as_str()) {
            outside.push(&r.integrator);
        }
    }
    let ggx = |case: &str| families.iter().any(|(c, f)| c == case && f == "ggx");
    for peer in outside {
        let _ = writeln!(
            md,
            "\n#### `auto` vs `{peer}` on the GGX albedo cases, relative tolerance 1e-6\n\n`{peer}`: the fewest \
             evaluations of its runs on the case (any tolerance) whose true error is ≤ max(auto's true error, 1e-6 × \
             reference) — its cheapest run as accurate as auto's answer. Ratio < 1: auto needs fewer.\n\n| case | \
             auto evaluations | auto true error | `{peer}` evaluations | ratio |\n|---|---|---|---|---|"
        );
        let (mut n, mut wins, mut worst) = (0usize, 0usize, (0.0f64, String::new()));
        for a in rows.iter().filter(|r| {
            r.builtin && r.integrator == "auto" && ggx(&r.case) && (r.rel_tol / 1e-6 - 1.0).abs() < 1e-6
        }) {
            let target = a.abs_error().max(1e-6 * a.reference.abs());
            let best = rows
                .iter()
                .filter(|r| r.integrator == peer && r.case == a.case && r.abs_error() <= target)
                .map(|r| r.evaluations)
                .min();
            let (cell, ratio) = match best {
                Some(q) => (q.to_string(), a.evaluations as f64 / q.max(1) as f64),
                None => ("not reached".to_string(), 0.0),
            };
            let ok = a.claims() && ratio < 1.0;
            n += 1;
            wins += usize::from(ok);
            if ratio > worst.0 || (!a.claims() && worst.1.is_empty()) {
                worst = (ratio, a.case.clone());
            }
            let _ = writeln!(
                md,
                "| {} | {}{} | {:.1e} | {cell} | {} |",
                a.case,
                a.evaluations,
                if a.claims() { "" } else { " (not reached)" },
                a.abs_error(),
                if best.is_some() {
                    format!("{ratio:.2}")
                } else {
                    "0 (peer never as accurate)".into()
                }
            );
        }
        let line = format!(
            "auto vs {peer} (GGX albedo, 1e-6): auto reached the tolerance with fewer evaluations on {wins} of {n} \
             cases; worst ratio auto/{peer} {:.2} ({})",
            worst.0, worst.1
        );
        let _ = writeln!(md, "\n{line}.");
        let _ = writeln!(text, "{line}.");
    }
    (text, md)
}
