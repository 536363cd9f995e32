//! `radiometry tradeoff`: what accuracy costs in time.
//!
//! For a standard suite of directional albedos (Lambertian; modified Phong
//! n ∈ {1, 10, 100, 1000}; GGX and Beckmann α ∈ {0.001, 0.01, 0.05, 0.3, 1},
//! all with F = 1 and the height-correlated Smith G2; θo ∈ {0°, 60°, 85°,
//! 89.5°, 89.9°})
//! every integrator runs over a ladder of budgets. Each estimate is compared
//! with an independent f64 reference ([`crate::reference`]) that carries
//! its own error bound; wall time is the median of a few repeats for small
//! budgets. Outputs: a summary table (stdout and `summary.md`), the raw
//! `tradeoff.csv`, `references.csv`, and log-log SVG plots.

use crate::model::{AnyBrdf, AnyIntegrator, all_integrators, build_brdf};
use crate::reference::{self, RefModel, Reference};
use crate::spec::parse_brdf;
use radiometry::glam::Vec3;
use radiometry::integrator::{DirectionalAlbedo, IntegrateError, Integrator, Status};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Options of a run.
#[derive(Clone, Debug)]
pub struct Options {
    /// CI-sized run.
    pub quick: bool,
    /// Output folder.
    pub out: PathBuf,
    /// Worker threads.
    pub threads: usize,
    /// Monte Carlo seed.
    pub seed: u64,
    /// Show a progress bar on stderr.
    pub progress: bool,
    /// Keep only cases whose name contains one of these (all when empty).
    pub cases: Vec<String>,
    /// Keep only integrators whose name contains one of these (all when empty).
    pub integrators: Vec<String>,
}

/// Whether `name` passes a substring filter (an empty filter passes all).
fn selected(filter: &[String], name: &str) -> bool {
    filter.is_empty() || filter.iter().any(|f| name.contains(f.as_str()))
}

/// The exact CSV header (a contract).
/// The first ten columns are those of earlier versions, in the same order;
/// `status` (`resolved` / `unresolved`) and `status_reason` (empty, or
/// e.g. `no-support-seen`) follow.
pub const CSV_HEADER: &str = "case,integrator,budget,evaluations,estimate,reference,abs_error,rel_error,error_estimate,seconds,status,status_reason";

/// Relative-error targets of the summary.
pub const TARGETS: [f64; 3] = [1e-2, 1e-4, 1e-6];

/// Budget ladder of the full run: 16·4^k up to 4^10 = 1,048,576.
pub const FULL_BUDGETS: [u32; 9] = [16, 64, 256, 1024, 4096, 16384, 65536, 262_144, 1_048_576];
/// Budget ladder of `--quick`.
pub const QUICK_BUDGETS: [u32; 5] = [16, 64, 256, 1024, 4096];

/// Real part of the complex refractive index of gold at 632.8 nm.
pub const GOLD_ETA: f64 = 0.18104;
/// Imaginary part (extinction coefficient) of gold at 632.8 nm.
pub const GOLD_K: f64 = 3.068099;

/// One case of the suite.
#[derive(Clone, Debug)]
pub struct Case {
    /// Name used in the CSV (no commas).
    pub name: String,
    /// Family: lambertian, phong, ggx, beckmann, ggx-gold.
    pub family: &'static str,
    /// BRDF spec given to the plugins.
    pub spec: String,
    /// The independent f64 model.
    pub model: RefModel,
    /// θo in degrees.
    pub theta_o: f64,
}

fn fmt_num(x: f64) -> String {
    let s = format!("{x}");
    s.trim_end_matches(".0").to_string()
}

/// The standard suite (or the `--quick` subset).
pub fn suite(quick: bool) -> Vec<Case> {
    let thetas = [0.0, 60.0, 85.0, 89.5, 89.9];
    let mut v = Vec::new();
    let mut push = |family: &'static str, param: String, spec: String, model: RefModel, t: f64| {
        v.push(Case {
            name: format!("{family}{param}-to{}", fmt_num(t)),
            family,
            spec,
            model,
            theta_o: t,
        });
    };
    for &t in &thetas {
        push(
            "lambertian",
            String::new(),
            "lambertian(albedo=1)".into(),
            RefModel::Lambertian { albedo: 1.0 },
            t,
        );
    }
    for n in [1.0, 10.0, 100.0, 1000.0] {
        for &t in &thetas {
            push(
                "phong",
                format!("-n{}", fmt_num(n)),
                format!("phong(exponent={n}, ks=1, kd=0)"),
                RefModel::Phong { n, ks: 1.0, kd: 0.0 },
                t,
            );
        }
    }
    for (family, ggx) in [("ggx", true), ("beckmann", false)] {
        for a in [0.001, 0.01, 0.05, 0.3, 1.0] {
            for &t in &thetas {
                // Beckmann α = 10⁻³ at θo ≥ 89.5°: the f64 reference (nested
                // adaptive Gauss–Kronrod to 10⁻¹²) takes ~50 s there and
                // still bounds its own error only to 7·10⁻⁸ (89.5°) and
                // 7·10⁻³ (89.9°), too loose to judge an integrator by, so
                // those two cases are left out.
                if !ggx && a < 0.005 && t >= 89.5 {
                    continue;
                }
                push(
                    family,
                    format!("-a{}", fmt_num(a)),
                    format!("{family}(alpha={a}, g=height-correlated, fresnel=none)"),
                    RefModel::Microfacet {
                        ggx,
                        alpha: a,
                        height_correlated: true,
                        conductor: None,
                    },
                    t,
                );
            }
        }
    }
    // A coloured conductor: GGX with the exact Fresnel of gold at 632.8 nm
    // (η = 0.18104, k = 3.068099; Sopra material library, via the
    // Filmetrics refractive-index database).
    for a in [0.05, 0.3] {
        for t in [0.0, 85.0] {
            push(
                "ggx-gold",
                format!("-a{}", fmt_num(a)),
                format!("ggx(alpha={a}, g=height-correlated, fresnel=conductor(eta={GOLD_ETA}, k={GOLD_K}))"),
                RefModel::Microfacet {
                    ggx: true,
                    alpha: a,
                    height_correlated: true,
                    conductor: Some((GOLD_ETA, GOLD_K)),
                },
                t,
            );
        }
    }
    if quick {
        let keep = [
            "lambertian-to60",
            "phong-n100-to60",
            "ggx-a0.3-to60",
            "ggx-a0.01-to89.5",
            "beckmann-a0.05-to85",
        ];
        v.retain(|c| keep.contains(&c.name.as_str()));
    }
    v
}

/// One measured row of the CSV.
#[derive(Clone, Debug)]
pub struct Row {
    /// Case index.
    pub case: usize,
    /// Integrator index.
    pub integ: usize,
    /// Budget given.
    pub budget: u32,
    /// Evaluations spent.
    pub evaluations: u64,
    /// The estimate.
    pub estimate: f64,
    /// The integrator's error estimate.
    pub error_estimate: f64,
    /// Median wall time in seconds.
    pub seconds: f64,
    /// The estimate's status.
    pub status: Status,
}

/// Most timing runs per budget (`--quick`: one).
fn max_repeats(quick: bool) -> usize {
    if quick { 1 } else { 5 }
}

/// Repeats stop once the runs so far took this long: a run of a millisecond
/// or more is timed well enough once, and the repeats are for the
/// microsecond-scale runs, where one scheduler tick would dominate.
pub const REPEAT_UNTIL_SECONDS: f64 = 2e-3;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// `(budget, evaluations, estimate, error estimate, median seconds, status)`.
pub type Measured = (u32, u64, f64, f64, f64, Status);

fn measure(
    brdf: &AnyBrdf,
    theta_o: f64,
    integ: &AnyIntegrator,
    budgets: &[u32],
    quick: bool,
) -> (Vec<Measured>, Vec<String>) {
    let t = theta_o.to_radians();
    let g = DirectionalAlbedo {
        brdf,
        wo: Vec3::new(t.sin() as f32, 0.0, t.cos() as f32),
    };
    ladder(budgets, quick, integ.name(), |b| integ.integrate(&g, b))
}

/// Runs `run(budget)` over the ladder: per budget the first estimate and
/// the median wall time of up to [`max_repeats`] runs (fewer once they
/// took [`REPEAT_UNTIL_SECONDS`]); a refused budget (an error)
/// is recorded as `"{name} at budget {b}: {error}"` and written no row.
pub(crate) fn ladder(
    budgets: &[u32],
    quick: bool,
    name: &str,
    mut run: impl FnMut(u32) -> Result<radiometry::integrator::Estimate<f64>, IntegrateError>,
) -> (Vec<Measured>, Vec<String>) {
    let mut out = Vec::new();
    let mut refused = Vec::new();
    for &b in budgets {
        let mut times = Vec::new();
        let mut first = None;
        let mut spent = 0.0;
        for _ in 0..max_repeats(quick) {
            if spent >= REPEAT_UNTIL_SECONDS {
                break;
            }
            let t0 = Instant::now();
            let r = run(b);
            let dt = t0.elapsed().as_secs_f64();
            spent += dt;
            times.push(dt);
            match r {
                Ok(e) => {
                    if first.is_none() {
                        first = Some(e);
                    }
                }
                Err(e) => {
                    refused.push(format!("{name} at budget {b}: {e}"));
                    break;
                }
            }
        }
        if let Some(e) = first {
            out.push((b, e.evaluations, e.value, e.error, median(times), e.status));
        }
    }
    (out, refused)
}

/// A method's name and kind, for the tables.
#[derive(Clone, Debug)]
pub struct MethodInfo {
    /// Report name.
    pub name: String,
    /// Deterministic quadrature (else Monte Carlo).
    pub deterministic: bool,
}

impl MethodInfo {
    /// Report name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Deterministic quadrature (else Monte Carlo).
    pub fn is_deterministic(&self) -> bool {
        self.deterministic
    }
}

/// Runs `job(j)` for every `j < n` on `threads` workers, each taking the next
/// index as it becomes free (so a long job does not hold up the others).
fn parallel_for(threads: usize, n: usize, job: impl Fn(usize) + Sync) {
    let next = AtomicUsize::new(0);
    std::thread::scope(|s| {
        for _ in 0..threads.max(1) {
            s.spawn(|| {
                loop {
                    let j = next.fetch_add(1, Ordering::Relaxed);
                    if j >= n {
                        break;
                    }
                    job(j);
                }
            });
        }
    });
}

/// Result slots of the jobs of one suite.
struct Slots {
    refs: Vec<Mutex<Option<Reference>>>,
    rows: Mutex<Vec<Row>>,
    refused: Mutex<Vec<String>>,
}

impl Slots {
    fn new(n_refs: usize) -> Slots {
        Slots {
            refs: (0..n_refs).map(|_| Mutex::new(None)).collect(),
            rows: Mutex::new(Vec::new()),
            refused: Mutex::new(Vec::new()),
        }
    }

    /// Records the ladder of `(case, method)`; refusals are kept for case 0.
    fn record(&self, ci: usize, ii: usize, (m, r): (Vec<Measured>, Vec<String>)) {
        let mut rows = self.rows.lock().expect("no poison");
        for (budget, evaluations, estimate, error_estimate, seconds, status) in m {
            rows.push(Row {
                case: ci,
                integ: ii,
                budget,
                evaluations,
                estimate,
                error_estimate,
                seconds,
                status,
            });
        }
        if ci == 0 {
            self.refused.lock().expect("no poison").extend(r);
        }
    }

    /// The references in case order, and the rows sorted by (case, method,
    /// budget) with the refusals.
    fn finish(self) -> (Vec<Reference>, Vec<Row>, Vec<String>) {
        let refs = self
            .refs
            .into_iter()
            .map(|m| m.into_inner().expect("no poison").expect("computed"))
            .collect();
        let mut rows = self.rows.into_inner().expect("no poison");
        rows.sort_by_key(|r| (r.case, r.integ, r.budget));
        (refs, rows, self.refused.into_inner().expect("no poison"))
    }
}

/// Runs the report: the directional-albedo suite, then the product
/// integrals (a GGX lobe under the sun and a lamp, [`product`]).
pub fn run(opt: &Options) -> Result<(), String> {
    let wall = Instant::now();
    std::fs::create_dir_all(&opt.out).map_err(|e| format!("cannot create {}: {e}", opt.out.display()))?;
    let budgets: &[u32] = if opt.quick { &QUICK_BUDGETS } else { &FULL_BUDGETS };
    // Albedo suite.
    let mut cases = suite(opt.quick);
    cases.retain(|c| selected(&opt.cases, &c.name));
    let mut integs = all_integrators(opt.seed, 0.0);
    integs.retain(|i| selected(&opt.integrators, i.name()));
    if integs.is_empty() {
        cases.clear();
    }
    // Product suite.
    let mut pcases = product::suite(opt.quick);
    pcases.retain(|c| selected(&opt.cases, &c.name));
    let mut pmethods = product::methods(opt.seed);
    pmethods.retain(|m| selected(&opt.integrators, &m.name()));
    if pmethods.is_empty() {
        pcases.clear();
    }
    if cases.is_empty() && pcases.is_empty() {
        return Err("the --cases / --integrators filters leave nothing to run".into());
    }
    let build = |spec: &str| -> Result<_, String> {
        let parsed = parse_brdf(spec).map_err(|e| e.to_string())?;
        build_brdf(spec, &parsed).map_err(|e| e.to_string())
    };
    let brdfs = cases
        .iter()
        .map(|c| build(&c.spec))
        .collect::<Result<Vec<_>, _>>()?;
    let pbrdfs = pcases
        .iter()
        .map(|c| build(&c.spec))
        .collect::<Result<Vec<_>, _>>()?;
    let total = cases.len() * (1 + integs.len()) + pcases.len() * (2 + pmethods.len());
    let progress = Progress::new(opt.progress, total);

    // One queue of jobs on `threads` workers: first the references
    // (independent of the integrators; the f32-input references of the
    // product cases after the others), then every (case, method) over the
    // budget ladder. A worker done with its references goes on with the
    // sweep while the other finishes a long reference, so no core idles;
    // `ref_seconds` adds up the references' own times (one thread each).
    let albedo = Slots::new(cases.len());
    let product = Slots::new(pcases.len());
    let product_f32: Vec<Mutex<Option<Reference>>> = (0..pcases.len()).map(|_| Mutex::new(None)).collect();
    let ref_nanos = std::sync::atomic::AtomicU64::new(0);
    let (nr, np) = (cases.len(), pcases.len());
    let (ns, nps) = (nr * integs.len(), np * pmethods.len());
    let timed = |f: &dyn Fn() -> Reference| {
        let t = Instant::now();
        let r = f();
        ref_nanos.fetch_add(t.elapsed().as_nanos() as u64, Ordering::Relaxed);
        r
    };
    parallel_for(opt.threads, nr + 2 * np + ns + nps, |j| {
        if j < nr {
            let r = timed(&|| reference::albedo(&cases[j].model, cases[j].theta_o.to_radians()));
            *albedo.refs[j].lock().expect("no poison") = Some(r);
            progress.tick(&format!("reference {}", cases[j].name));
        } else if j < nr + np {
            let i = j - nr;
            *product.refs[i].lock().expect("no poison") = Some(timed(&|| product::reference(&pcases[i])));
            progress.tick(&format!("reference {}", pcases[i].name));
        } else if j < nr + 2 * np {
            let i = j - nr - np;
            *product_f32[i].lock().expect("no poison") =
                Some(timed(&|| product::reference_at_f32_input(&pcases[i])));
            progress.tick(&format!("reference at f32 input {}", pcases[i].name));
        } else if j < nr + 2 * np + ns {
            let k = j - nr - 2 * np;
            let (ci, ii) = (k / integs.len(), k % integs.len());
            albedo.record(
                ci,
                ii,
                measure(&brdfs[ci], cases[ci].theta_o, &integs[ii], budgets, opt.quick),
            );
            progress.tick(&format!("{} {}", cases[ci].name, integs[ii].name()));
        } else {
            let k = j - nr - 2 * np - ns;
            let (ci, ii) = (k / pmethods.len(), k % pmethods.len());
            product.record(
                ci,
                ii,
                product::measure(&pbrdfs[ci], &pcases[ci], &pmethods[ii], budgets, opt.quick),
            );
            progress.tick(&format!("{} {}", pcases[ci].name, pmethods[ii].name()));
        }
    });
    progress.finish();
    let ref_seconds = ref_nanos.into_inner() as f64 * 1e-9;
    let (refs, rows, refused) = albedo.finish();
    let (prefs, prows, prefused) = product.finish();
    let prefs_f32: Vec<Reference> = product_f32
        .into_iter()
        .map(|m| m.into_inner().expect("no poison").expect("computed"))
        .collect();
    // The relative shift of the exact value when the inputs are rounded to
    // f32: the conditioning of each product case.
    let input_shift: Vec<f64> = prefs
        .iter()
        .zip(&prefs_f32)
        .map(|(a, b)| (b.value - a.value).abs() / a.value.abs().max(f64::MIN_POSITIVE))
        .collect();

    let infos: Vec<MethodInfo> = integs
        .iter()
        .map(|i| MethodInfo {
            name: i.name().to_string(),
            deterministic: i.is_deterministic(),
        })
        .collect();
    let report = Report {
        cases: &cases,
        refs: &refs,
        integs: &infos,
        rows: &rows,
        budgets,
        ref_seconds,
        kind: SuiteKind::Albedo,
        input_shift: None,
    };
    let pcases_as: Vec<Case> = pcases
        .iter()
        .map(|c| Case {
            name: c.name.clone(),
            family: c.family,
            spec: c.spec.clone(),
            model: c.model,
            theta_o: c.wo[2].clamp(-1.0, 1.0).acos().to_degrees(),
        })
        .collect();
    let pinfos = product::method_infos(&pmethods);
    let preport = Report {
        cases: &pcases_as,
        refs: &prefs,
        integs: &pinfos,
        rows: &prows,
        budgets,
        ref_seconds,
        kind: SuiteKind::Product,
        input_shift: Some(&input_shift),
    };
    write_csv(opt, &[&report, &preport])?;
    crate::tradeoff::plot::write_plots(&opt.out, &report)?;
    crate::tradeoff::plot::write_plots(&opt.out, &preport)?;
    let elapsed = wall.elapsed().as_secs_f64();
    let mut text = String::new();
    let mut md = String::new();
    for (rep, refused) in [(&report, &refused), (&preport, &prefused)] {
        if rep.cases.is_empty() {
            continue;
        }
        let (t, m) = rep.summary(opt, elapsed, refused);
        text.push_str(&t);
        md.push_str(&m);
        md.push('\n');
    }
    print!("{text}");
    std::fs::write(opt.out.join("summary.md"), md).map_err(|e| format!("cannot write summary.md: {e}"))?;
    println!(
        "\nWrote {}/tradeoff.csv, references.csv, summary.md and SVG plots ({:.1} s).",
        opt.out.display(),
        elapsed
    );
    Ok(())
}

/// Which suite a [`Report`] holds (selects the texts of its summary).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SuiteKind {
    /// Directional albedos.
    Albedo,
    /// Reflected radiance under a cap light ([`product`]).
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

    fn summary(&self, opt: &Options, elapsed: f64, refused: &[String]) -> (String, String) {
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
                 89.5°, 89.9°}.",
            ),
            SuiteKind::Product => (
                "Product integrals: a GGX lobe under a cap light",
                "Reflected radiance L_r(ωo) = ∫_cap f_r L cos θi dωi (L = 1) of GGX α ∈ {0.01, 0.1, 0.5} (F = 1, \
                 height-correlated G2) under the sun (σ = 0.27°) and a lamp (σ = 5°) at elevations 10°, 45°, 80° and \
                 partly below the horizon (sun 0.1°, lamp 2°), viewed at the mirror direction of the light's centre \
                 and 10° off it in azimuth. Methods: `cap-*` quadrature over the visible cap; `light-sampling` \
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
                if integ.is_deterministic() {
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
            "References: nested adaptive Gauss–Kronrod (7,15) in f64, independent of the integrators and plugins; \
             worst relative reference bound {ref_worst:.1e}; {:.1} s (one thread's time, summed) for all \
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

fn fmt_time(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.0} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.1} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

fn write_csv(opt: &Options, reps: &[&Report<'_>]) -> Result<(), String> {
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

pub mod plot;
pub mod product;
mod progress;
pub(crate) use progress::Progress;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suite_has_the_issue_cases() {
        let s = suite(false);
        // θo ∈ {0, 60, 85, 89.5, 89.9}; Phong n ∈ {1, 10, 100, 1000};
        // microfacet α ∈ {0.001, 0.01, 0.05, 0.3, 1}.
        assert_eq!(s.len(), 5 + 20 + 25 + 23 + 4);
        assert!(s.iter().any(|c| c.name == "ggx-a0.001-to89.9"));
        assert!(s.iter().all(|c| !c.name.contains(',')));
        let mut names: Vec<_> = s.iter().map(|c| c.name.clone()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), s.len());
        assert_eq!(suite(true).len(), 5);
        for c in &s {
            assert!(parse_brdf(&c.spec).is_ok(), "{}", c.spec);
        }
    }

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
