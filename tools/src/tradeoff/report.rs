//! The summary of `radiometry tradeoff` (tables of evaluations and time
//! to each target, the honesty of the error estimates, the notes) and its
//! CSV files: everything written from the measured rows of a [`Report`].

use super::{CSV_HEADER, Case, MethodInfo, Options, Row, TARGETS};
use crate::reference::Reference;
use std::fmt::Write as _;

/// Which suite a [`Report`] holds (selects the texts of its summary).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SuiteKind {
    /// Directional albedos.
    Albedo,
    /// Reflected radiance under a cap light ([`product`](super::product)).
    Product,
}

/// Everything measured, for tables and plots.
pub struct Report<'a> {
    /// The cases.
    pub cases: &'a [Case],
    /// Their references.
    pub refs: &'a [Reference],
    /// The integrators (names and kinds).
    pub integs: &'a [MethodInfo],
    /// The rows, sorted by (case, integrator, budget).
    pub rows: &'a [Row],
    /// The budget ladder.
    pub budgets: &'a [u32],
    /// Time spent on the references, in seconds of one thread (summed over
    /// the references, which run alongside the sweep).
    pub ref_seconds: f64,
    /// Which suite.
    pub kind: SuiteKind,
    /// Per case, the relative change of the `f64` reference when the
    /// case's inputs are rounded to `f32` (product cases: `ωo`, light axis,
    /// σ); `None` where not computed.
    pub input_shift: Option<&'a [f64]>,
}

impl Report<'_> {
    /// Relative error of a row.
    pub fn rel_error(&self, r: &Row) -> f64 {
        let reference = self.refs[r.case].value;
        (r.estimate - reference).abs() / reference.abs().max(f64::MIN_POSITIVE)
    }

    fn rows_of(&self, case: usize, integ: usize) -> Vec<&Row> {
        self.rows
            .iter()
            .filter(|r| r.case == case && r.integ == integ)
            .collect()
    }

    /// The first row from which on every larger budget meets `target`.
    fn reach(&self, case: usize, integ: usize, target: f64) -> Option<&Row> {
        let rows = self.rows_of(case, integ);
        let mut found = None;
        for r in rows.iter().rev() {
            if self.rel_error(r) <= target {
                found = Some(*r);
            } else {
                break;
            }
        }
        found
    }

    pub(super) fn summary(&self, opt: &Options, elapsed: f64, refused: &[String]) -> (String, String) {
        let mut families: Vec<&str> = Vec::new();
        for c in self.cases {
            if !families.contains(&c.family) {
                families.push(c.family);
            }
        }
        let mut text = String::new();
        let mut md = String::new();
        let run_kind = if opt.quick { "quick" } else { "full" };
        let (suite_title, suite_text) = match self.kind {
            SuiteKind::Albedo => (
                "Accuracy vs. time",
                "Directional albedo with F = 1 (family `ggx-gold`: the exact conductor Fresnel of gold at 632.8 nm, \
                 η = 0.18104, k = 3.068099) and the height-correlated Smith G2 for microfacets; θo ∈ {0°, 60°, 85°, \
                 89.5°, 89.9°}. Family `materials`: `coated(TOP, BASE)` layers, a plastic (a GGX α = 0.1 coat with the \
                 exact Fresnel of η = 1.5 over EON ρ = 0.8, σ = 0.5) and gold under a clear GGX α = 0.05 coat, at θo ∈ \
                 {0°, 60°, 85°}; their references tabulate the coat's true albedo at the layer's nodes. Then the \
                 plugins and combinators: `eon(rho=0.9, sigma=1)`, `fon(rho=0.8, sigma=0.7)`, \
                 `oren-nayar(rho=0.8, sigma_rad=0.35)` (references: their closed-form albedos) and \
                 `sheen(color=1, roughness=0.3)` at θo ∈ {0°, 60°, 85°}; a sum (GGX α = 0.2 with the Fresnel of \
                 η = 1.5 + EON ρ = 0.5, σ = 1), a mix (0.3 gold GGX α = 0.05 + 0.7 Oren–Nayar ρ = 0.9, σ = 0.5 rad; \
                 references: the weighted sums of the lobes' references), OpenPBR's defaults and OpenPBR with every \
                 layer (metalness 0.5, coat 1 of roughness 0.2, fuzz 1) at θo ∈ {20°, 80°}. The sheen's and the \
                 OpenPBRs' references are f64 quadratures of the plugin's own values (no closed form; independent \
                 of its sampling maps). These composites' ladders stop at 262,144 evaluations, the mix's and the \
                 OpenPBRs' at 65,536 (their sampling maps cost 0.6–2.4 µs per evaluation), and each case is judged \
                 over its own ladder.",
            ),
            SuiteKind::Product => (
                "Product integrals: glossy lobes under a cap light",
                "Reflected radiance L_r(ωo) = ∫_cap f_r L cos θi dωi (L = 1) of GGX α ∈ {0.01, 0.1, 0.5} (F = 1, \
                 height-correlated G2) under the sun (σ = 0.27°) and a lamp (σ = 5°) at elevations 10°, 45°, 80° and \
                 partly below the horizon (sun 0.1°, lamp 2°), viewed at the mirror direction of the light's centre \
                 and 10° off it in azimuth; families `materials-sun` and `materials-lamp`: the two layered materials \
                 of the albedo suite under the same lights at elevations 45° and 10°, and EON, the sheen, the sum, \
                 the mix and both OpenPBRs at elevation 45°, mirror view, and the sheen at 10°, 10° off (it vanishes \
                 at the mirror direction); ladders up to 262,144 (mix, OpenPBRs: 65,536). Methods: `cap-*` quadrature over the visible cap; `light-sampling` \
                 (uniform in the cone), `brdf-sampling` (the BRDF's visible-normal sampling) and `mis-light-brdf` \
                 (one-sample balance-heuristic MIS of both), each with PRNG and Sobol points.",
            ),
        };
        let _ = writeln!(text, "\n== {suite_title} ==\n");
        let _ = writeln!(
            md,
            "### {suite_title} ({run_kind} run: {} cases × {} integrators × budgets {}–{}, {:.0} s on {} thread(s) for the whole report)\n",
            self.cases.len(),
            self.integs.len(),
            self.budgets[0],
            self.budgets[self.budgets.len() - 1],
            elapsed,
            opt.threads
        );
        let _ = writeln!(
            md,
            "Each cell: the worst case of the family — evaluations / wall time needed for the relative error to \
             stay ≤ the target at that budget and every larger one of the ladder; `not reached (k/N)`: only k of \
             the family's N cases got there within {} evaluations. {suite_text} Wall time: median of \
             up to 5 runs, fewer once the runs so far took 2 ms (so one run from about 2 ms on; `--quick`: one \
             run).\n",
            self.budgets[self.budgets.len() - 1]
        );
        let _ = writeln!(
            md,
            "| family | integrator | rel. err 1e-2 | rel. err 1e-4 | rel. err 1e-6 |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|");
        let _ = writeln!(
            text,
            "Evaluations / wall time for the worst case of each family to reach (and keep, at every larger \
             budget) the relative error:\n"
        );
        let _ = writeln!(
            text,
            "{:<11} {:<26} {:>22} {:>22} {:>22}",
            "family", "integrator", "rel.err 1e-2", "rel.err 1e-4", "rel.err 1e-6"
        );
        for fam in &families {
            let idx: Vec<usize> = (0..self.cases.len())
                .filter(|&i| self.cases[i].family == *fam)
                .collect();
            for (ii, integ) in self.integs.iter().enumerate() {
                let mut cells = Vec::new();
                for &t in &TARGETS {
                    let hits: Vec<&Row> = idx.iter().filter_map(|&ci| self.reach(ci, ii, t)).collect();
                    if hits.len() == idx.len() {
                        let ev = hits.iter().map(|r| r.evaluations).max().unwrap_or(0);
                        let s = hits.iter().map(|r| r.seconds).fold(0.0, f64::max);
                        cells.push(format!("{ev} / {}", fmt_time(s)));
                    } else {
                        cells.push(format!("not reached ({}/{})", hits.len(), idx.len()));
                    }
                }
                let _ = writeln!(
                    text,
                    "{:<11} {:<26} {:>22} {:>22} {:>22}",
                    fam,
                    integ.name(),
                    cells[0],
                    cells[1],
                    cells[2]
                );
                let _ = writeln!(
                    md,
                    "| {fam} | {} | {} | {} | {} |",
                    integ.name(),
                    cells[0],
                    cells[1],
                    cells[2]
                );
            }
        }

        // Goal check: best deterministic integrator per case.
        let _ = writeln!(
            md,
            "\n#### Best deterministic integrator per case (goal: rel. err ≤ 1e-4 with ≤ 4,096 and ≤ 1e-6 with ≤ 65,536 evaluations)\n"
        );
        if self.input_shift.is_some() {
            let _ = writeln!(
                md,
                "`f32 input shift`: how far the exact value moves when the case's inputs (ωo, light axis, σ) are \
                 rounded to f32, the precision every integrator here receives them in (relative; both values \
                 from the f64 reference). Where it exceeds a target, no f32 integrator can be expected to meet \
                 it.\n"
            );
            let _ = writeln!(
                md,
                "| case | reference ρ | reference bound | f32 input shift | best for 1e-4 (evals) | best for 1e-6 (evals) | goal |"
            );
            let _ = writeln!(md, "|---|---|---|---|---|---|---|");
        } else {
            let _ = writeln!(
                md,
                "| case | reference ρ | reference bound | best for 1e-4 (evals) | best for 1e-6 (evals) | goal |"
            );
            let _ = writeln!(md, "|---|---|---|---|---|---|");
        }
        let mut met = 0;
        let mut fails = Vec::new();
        for (ci, c) in self.cases.iter().enumerate() {
            let best = |t: f64| {
                (0..self.integs.len())
                    .filter(|&ii| self.integs[ii].is_deterministic())
                    .filter_map(|ii| {
                        self.reach(ci, ii, t)
                            .map(|r| (r.evaluations, self.integs[ii].name()))
                    })
                    .min()
            };
            let (b4, b6) = (best(1e-4), best(1e-6));
            let ok = b4.is_some_and(|b| b.0 <= 4096) && b6.is_some_and(|b| b.0 <= 65536);
            if ok {
                met += 1;
            } else {
                fails.push(match self.input_shift {
                    Some(s) => format!("{} (f32 input shift {:.1e})", c.name, s[ci]),
                    None => c.name.clone(),
                });
            }
            let show =
                |b: Option<(u64, &str)>| b.map_or("not reached".to_string(), |(e, n)| format!("{n} ({e})"));
            let shift = self
                .input_shift
                .map_or(String::new(), |s| format!(" {:.1e} |", s[ci]));
            let _ = writeln!(
                md,
                "| {} | {:.12} | {:.1e} |{shift} {} | {} | {} |",
                c.name,
                self.refs[ci].value,
                self.refs[ci].bound,
                show(b4),
                show(b6),
                if ok { "met" } else { "missed" }
            );
        }
        let goal = format!(
            "Goal (best deterministic integrator: ≤ 1e-4 within 4,096 and ≤ 1e-6 within 65,536 evaluations): met for {met} of {} cases{}",
            self.cases.len(),
            if fails.is_empty() {
                String::new()
            } else {
                format!("; missed: {}", fails.join(", "))
            }
        );
        let _ = writeln!(md, "\n{goal}.\n");
        let _ = writeln!(text, "\n{goal}.");
        if let Some(line) = self.composites_goal() {
            let _ = writeln!(md, "{line}.\n");
            let _ = writeln!(text, "{line}.");
        }

        // Honesty of the error estimates.
        let _ = writeln!(md, "#### Honesty of the error estimates\n");
        let _ = writeln!(
            md,
            "Quadrature: share of rows with true error ≤ estimate, and the worst understatement (true / \
             estimate); Monte Carlo: share of rows with true error ≤ 3σ. Rows whose true error is below 10× the \
             reference bound are not counted. `unresolved`: rows whose estimate carries an unresolved status \
             (the integrator says it cannot stand behind its error; reasons in the CSV's `status_reason`); the \
             last two columns count only resolved rows.\n"
        );
        let _ = writeln!(
            md,
            "| integrator | rows | covered (1× quadrature, 3σ MC) | true ≤ 10× estimate | worst true/estimate | unresolved | resolved: covered | resolved: worst true/estimate |"
        );
        let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
        let mut offenders: Vec<(f64, &Row)> = Vec::new();
        let max_ref_bound = |ci: usize| self.refs[ci].bound;
        let mut ref_worst = 0.0f64;
        for r in self.refs.iter() {
            ref_worst = ref_worst.max(r.bound / r.value.abs().max(f64::MIN_POSITIVE));
        }
        // Targets of the issue: deterministic rows with budget ≥ 64 have an
        // estimate ≥ true/10 or are flagged; MC rows with ≥ 256 evaluations
        // have true ≤ 3σ.
        let (mut det_n, mut det_ok, mut det_worst) = (0usize, 0usize, 0.0f64);
        let (mut mc_n, mut mc_ok, mut mc_res_n, mut mc_res_ok) = (0usize, 0usize, 0usize, 0usize);
        let mut mc_flag_ok = 0usize;
        let fmt_ratio = |worst: f64| {
            if worst >= 1e300 {
                "∞ (estimate 0)".to_string()
            } else if worst >= 1e3 {
                format!("{worst:.1e}")
            } else {
                format!("{worst:.2}")
            }
        };
        for (ii, integ) in self.integs.iter().enumerate() {
            let (mut n, mut cov, mut cov10, mut worst) = (0usize, 0usize, 0usize, 0.0f64);
            let (mut unres, mut res_n, mut res_cov, mut res_worst) = (0usize, 0usize, 0usize, 0.0f64);
            let k = if integ.is_deterministic() { 1.0 } else { 3.0 };
            for r in self.rows.iter().filter(|r| r.integ == ii) {
                let abs = (r.estimate - self.refs[r.case].value).abs();
                if abs <= 10.0 * max_ref_bound(r.case) {
                    continue;
                }
                n += 1;
                let resolved = r.status.is_resolved();
                if abs <= k * r.error_estimate {
                    cov += 1;
                }
                if abs <= 10.0 * r.error_estimate {
                    cov10 += 1;
                }
                let ratio = if r.error_estimate > 0.0 {
                    abs / r.error_estimate
                } else {
                    f64::INFINITY
                };
                worst = worst.max(ratio);
                if resolved {
                    res_n += 1;
                    if abs <= k * r.error_estimate {
                        res_cov += 1;
                    }
                    res_worst = res_worst.max(ratio);
                } else {
                    unres += 1;
                }
                if integ.external {
                    // Listed in the table, not counted in the crate's targets.
                } else if integ.is_deterministic() {
                    if r.budget >= 64 {
                        det_n += 1;
                        det_ok += usize::from(!resolved || ratio <= 10.0);
                        if resolved {
                            det_worst = det_worst.max(ratio);
                        }
                    }
                    if resolved && ratio > 10.0 {
                        offenders.push((ratio, r));
                    }
                } else if r.evaluations >= 256 {
                    mc_n += 1;
                    mc_ok += usize::from(abs <= 3.0 * r.error_estimate);
                    mc_flag_ok += usize::from(!resolved || abs <= 3.0 * r.error_estimate);
                    if resolved {
                        mc_res_n += 1;
                        mc_res_ok += usize::from(abs <= 3.0 * r.error_estimate);
                    }
                }
            }
            let pct = |a: usize, b: usize| if b > 0 { a as f64 / b as f64 * 100.0 } else { 100.0 };
            let _ = writeln!(
                md,
                "| {} | {n} | {:.1} % | {:.1} % | {} | {unres} | {:.1} % | {} |",
                integ.name(),
                pct(cov, n),
                pct(cov10, n),
                fmt_ratio(worst),
                pct(res_cov, res_n),
                fmt_ratio(res_worst)
            );
        }
        let pct = |a: usize, b: usize| if b > 0 { a as f64 / b as f64 * 100.0 } else { 100.0 };
        let honesty = format!(
            "Honesty: deterministic rows with budget ≥ 64 whose error estimate is ≥ true error / 10 or that are flagged \
             unresolved: {det_ok} of {det_n} ({:.1} %; target 100 %; worst true/estimate of a resolved row {}). Monte Carlo rows \
             with ≥ 256 evaluations and true error ≤ 3σ: {mc_ok} of {mc_n} ({:.1} %; target ≥ 99 %); resolved ones only: \
             {mc_res_ok} of {mc_res_n} ({:.1} %); within 3σ or flagged unresolved (the deterministic criterion): \
             {mc_flag_ok} of {mc_n} ({:.1} %)",
            pct(det_ok, det_n),
            if det_worst > 0.0 {
                fmt_ratio(det_worst)
            } else {
                "none".into()
            },
            pct(mc_ok, mc_n),
            pct(mc_res_ok, mc_res_n),
            pct(mc_flag_ok, mc_n)
        );
        let _ = writeln!(md, "\n{honesty}.");
        let _ = writeln!(text, "{honesty}.");
        let (fa_md, fa_text) = self.false_alarms();
        md.push_str(&fa_md);
        text.push_str(&fa_text);
        if !offenders.is_empty() {
            // Worst 4 per integrator, then by ratio.
            offenders.sort_by(|a, b| a.1.integ.cmp(&b.1.integ).then(b.0.total_cmp(&a.0)));
            let mut kept: Vec<(f64, &Row)> = Vec::new();
            for o in &offenders {
                if kept.iter().filter(|k| k.1.integ == o.1.integ).count() < 4 {
                    kept.push(*o);
                }
            }
            let _ = writeln!(
                md,
                "\nResolved quadrature rows whose error estimate understates the true error by more than 10× \
                 ({} rows; the worst 4 of each integrator):\n",
                offenders.len()
            );
            let _ = writeln!(
                md,
                "| case | integrator | budget | rel. error | estimate / ρ | true / estimate |"
            );
            let _ = writeln!(md, "|---|---|---|---|---|---|");
            for (ratio, r) in &kept {
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {:.1e} | {:.1e} | {:.1e} |",
                    self.cases[r.case].name,
                    self.integs[r.integ].name(),
                    r.budget,
                    self.rel_error(r),
                    r.error_estimate / self.refs[r.case].value,
                    ratio
                );
            }
        }
        let refs_line = format!(
            "References: nested adaptive Gauss–Kronrod (7,15) in f64, independent of the integrators and plugins \
             (the sheen's and the OpenPBRs': of the plugin's own values, independent of its sampling maps; EON, FON \
             and Oren–Nayar: closed forms); worst relative reference bound {ref_worst:.1e}; {:.1} s (one thread's time, summed) for all \
             references.",
            self.ref_seconds
        );
        let _ = writeln!(md, "\n{refs_line}");
        let _ = writeln!(text, "{refs_line}");
        if !refused.is_empty() {
            let _ = writeln!(md, "\nBudgets refused (no row written):\n");
            for r in refused {
                let _ = writeln!(md, "- {r}");
            }
        }
        let _ = writeln!(
            md,
            "\nRegenerate with `cargo run --release -p radiometry-cli -- tradeoff{}` (output in `{}`).",
            if opt.quick { " --quick" } else { "" },
            opt.out.display()
        );
        (text, md)
    }
}

impl Report<'_> {
    /// The goal of the composites (the albedo cases of family `materials`):
    /// the best deterministic integrator reaches (and keeps) a relative
    /// error of 1e-6 within 65,536 evaluations, and `auto` within 4× the
    /// best's evaluations; `None` without such cases or without `auto`.
    pub fn composites_goal(&self) -> Option<String> {
        if self.kind != SuiteKind::Albedo {
            return None;
        }
        let cases: Vec<usize> = (0..self.cases.len())
            .filter(|&ci| self.cases[ci].family == "materials")
            .collect();
        let auto = self
            .integs
            .iter()
            .position(|i| i.name() == "auto" && !i.external)?;
        if cases.is_empty() {
            return None;
        }
        let (mut best_ok, mut auto_ok) = (0usize, 0usize);
        let (mut best_missed, mut auto_missed) = (Vec::new(), Vec::new());
        for &ci in &cases {
            let best = (0..self.integs.len())
                .filter(|&ii| self.integs[ii].is_deterministic() && !self.integs[ii].external)
                .filter_map(|ii| {
                    self.reach(ci, ii, 1e-6)
                        .map(|r| (r.evaluations, self.integs[ii].name()))
                })
                .min();
            let name = &self.cases[ci].name;
            match best {
                Some((e, _)) if e <= 65536 => best_ok += 1,
                Some((e, n)) => best_missed.push(format!("{name} ({n}: {e})")),
                None => best_missed.push(format!("{name} (not reached)")),
            }
            let a = self.reach(ci, auto, 1e-6).map(|r| r.evaluations);
            match (a, best) {
                (Some(a), Some((b, _))) if a as f64 <= 4.0 * b as f64 => auto_ok += 1,
                (Some(a), Some((b, n))) => auto_missed.push(format!("{name} (auto {a}, {n} {b})")),
                (None, _) => auto_missed.push(format!("{name} (auto: not reached)")),
                (Some(a), None) => auto_missed.push(format!("{name} (auto {a}, no best)")),
            }
        }
        let n = cases.len();
        let list = |v: &[String]| {
            if v.is_empty() {
                String::new()
            } else {
                format!("; missed: {}", v.join(", "))
            }
        };
        Some(format!(
            "Goal on the composites (family `materials`): the best deterministic integrator keeps rel. err ≤ 1e-6 \
             within 65,536 evaluations on {best_ok} of {n} cases{}; `auto` within 4× the best's evaluations on \
             {auto_ok} of {n}{}",
            list(&best_missed),
            list(&auto_missed)
        ))
    }

    /// False alarms of the unresolved flags, per reason: deterministic rows
    /// (budget ≥ 64) flagged unresolved whose true error is within 3× their
    /// claimed error anyway, and Monte Carlo rows (≥ 256 evaluations)
    /// flagged whose true error is within 3σ. Rows whose true error is below
    /// 10× the reference bound are not counted (as in the honesty table).
    fn false_alarms(&self) -> (String, String) {
        // reason -> (deterministic flagged, fine, MC flagged, fine)
        let mut by: Vec<(&'static str, [usize; 4])> = Vec::new();
        for r in self.rows {
            if r.status.is_resolved() {
                continue;
            }
            let Some(integ) = self.integs.get(r.integ).filter(|i| !i.external) else {
                continue;
            };
            let abs = (r.estimate - self.refs[r.case].value).abs();
            if abs <= 10.0 * self.refs[r.case].bound {
                continue;
            }
            let det = integ.is_deterministic();
            if (det && r.budget < 64) || (!det && r.evaluations < 256) {
                continue;
            }
            let fine = abs <= 3.0 * r.error_estimate;
            let reason = r.status.reason();
            let slot = match by.iter().position(|(n, _)| *n == reason) {
                Some(i) => i,
                None => {
                    by.push((reason, [0; 4]));
                    by.len() - 1
                }
            };
            let c = &mut by[slot].1;
            let k = if det { 0 } else { 2 };
            c[k] += 1;
            c[k + 1] += usize::from(fine);
        }
        let pct = |a: usize, b: usize| if b > 0 { a as f64 / b as f64 * 100.0 } else { 0.0 };
        let mut md = String::from(
            "\n#### False alarms of the unresolved flags\n\nA flag is a false alarm when the flagged row's true error \
             is within 3× its claimed error anyway (Monte Carlo: within 3σ). Deterministic rows with budget ≥ 64, \
             Monte Carlo rows with ≥ 256 evaluations.\n\n| reason | deterministic flagged | false alarms | Monte Carlo \
             flagged | false alarms |\n|---|---|---|---|---|\n",
        );
        let mut tot = [0usize; 4];
        for (reason, c) in &by {
            let _ = writeln!(
                md,
                "| `{reason}` | {} | {} ({:.0} %) | {} | {} ({:.0} %) |",
                c[0],
                c[1],
                pct(c[1], c[0]),
                c[2],
                c[3],
                pct(c[3], c[2])
            );
            for (t, x) in tot.iter_mut().zip(c) {
                *t += x;
            }
        }
        let line = format!(
            "False alarms: deterministic {} of {} flagged rows ({:.0} %; target ≤ 40 %), Monte Carlo {} of {} ({:.0} %)",
            tot[1],
            tot[0],
            pct(tot[1], tot[0]),
            tot[3],
            tot[2],
            pct(tot[3], tot[2])
        );
        let _ = writeln!(
            md,
            "| all | {} | {} ({:.0} %) | {} | {} ({:.0} %) |\n\n{line}.",
            tot[0],
            tot[1],
            pct(tot[1], tot[0]),
            tot[2],
            tot[3],
            pct(tot[3], tot[2])
        );
        (md, format!("{line}.\n"))
    }
}

fn fmt_time(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.0} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

pub(super) fn write_csv(opt: &Options, reps: &[&Report<'_>]) -> Result<(), String> {
    let mut s = String::with_capacity(reps.iter().map(|r| r.rows.len()).sum::<usize>() * 160);
    s.push_str(CSV_HEADER);
    s.push('\n');
    for rep in reps {
        for r in rep.rows {
            let reference = rep.refs[r.case].value;
            let abs = (r.estimate - reference).abs();
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{:e},{:e},{:e},{:e},{},{}",
                rep.cases[r.case].name,
                rep.integs[r.integ].name(),
                r.budget,
                r.evaluations,
                r.estimate,
                reference,
                abs,
                rep.rel_error(r),
                r.error_estimate,
                r.seconds,
                r.status.as_str(),
                r.status.reason()
            );
        }
    }
    std::fs::write(opt.out.join("tradeoff.csv"), s).map_err(|e| format!("cannot write tradeoff.csv: {e}"))?;
    // `theta_o`: the polar angle of ωo in degrees (product cases: of the
    // viewing direction; their light is in the case name).
    let mut s = String::from("case,theta_o,spec,reference,bound,reference_evaluations\n");
    for rep in reps {
        for (c, r) in rep.cases.iter().zip(rep.refs) {
            let _ = writeln!(
                s,
                "{},{},\"{}\",{},{},{}",
                c.name, c.theta_o, c.spec, r.value, r.bound, r.evaluations
            );
        }
    }
    std::fs::write(opt.out.join("references.csv"), s).map_err(|e| format!("cannot write references.csv: {e}"))
}

#[cfg(test)]
mod tests {
    use super::super::{MethodInfo, QUICK_BUDGETS, Row, suite};
    use super::*;
    use crate::model::all_integrators;
    use radiometry::integrator::{Integrator, Status};

    #[test]
    fn reach_requires_all_larger_budgets() {
        let cases = suite(true)[..1].to_vec();
        let refs = vec![Reference {
            value: 1.0,
            bound: 1e-15,
            evaluations: 0,
        }];
        let integs: Vec<MethodInfo> = all_integrators(1, 0.0)[..1]
            .iter()
            .map(|i| MethodInfo {
                name: i.name().to_string(),
                deterministic: i.is_deterministic(),
                external: false,
            })
            .collect();
        let mk = |budget, est| Row {
            case: 0,
            integ: 0,
            budget,
            evaluations: budget as u64,
            estimate: est,
            error_estimate: 0.0,
            seconds: 0.0,
            status: Status::Resolved,
        };
        let rows = vec![
            mk(16, 1.0),
            mk(64, 1.1),
            mk(256, 1.0 + 1e-5),
            mk(1024, 1.0 + 1e-7),
        ];
        let rep = Report {
            cases: &cases,
            refs: &refs,
            integs: &integs,
            rows: &rows,
            budgets: &QUICK_BUDGETS,
            ref_seconds: 0.0,
            kind: SuiteKind::Albedo,
            input_shift: None,
        };
        assert_eq!(rep.reach(0, 0, 1e-2).map(|r| r.budget), Some(256));
        assert_eq!(rep.reach(0, 0, 1e-6).map(|r| r.budget), Some(1024));
        assert_eq!(rep.reach(0, 0, 1e-8).map(|r| r.budget), None);
    }
}
