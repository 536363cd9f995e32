//! `radiometry tradeoff`: what accuracy costs in time.
//!
//! For a standard suite of directional albedos (Lambertian; modified Phong
//! n ∈ {1, 10, 100, 1000}; GGX and Beckmann α ∈ {0.001, 0.01, 0.05, 0.3, 1},
//! all with F = 1 and the height-correlated Smith G2; θo ∈ {0°, 60°, 85°,
//! 89.5°, 89.9°}; GGX with the Fresnel of gold; the [`materials`]: two
//! layers and every plugin and combinator the crates ship)
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
    /// Rows measured outside this crate (user integrators run by the Python
    /// harness), merged into the tables, CSVs and summary by case name.
    pub external: Vec<ExternalRow>,
    /// Runs of the random-material honesty check (`--honesty N`, module
    /// [`honesty`]; 0: none). With `--cases honesty` only that check runs.
    pub honesty: usize,
}

/// A row measured outside this crate: a user integrator (Python
/// `radiometry.tradeoff(integrators=...)`) run on a case of the suites. The
/// harness counts `evaluations` itself; the report adds the reference and the
/// true error. `budget` is set for a fixed-budget row (the budget ladder),
/// `tol` for a to-tolerance row (the absolute tolerance the integrator was
/// asked for); exactly one of them.
#[derive(Clone, Debug, PartialEq)]
pub struct ExternalRow {
    /// Case name, as in [`suite`] or [`product::suite`].
    pub case: String,
    /// Integrator name (must not clash with a built-in one).
    pub integrator: String,
    /// Deterministic quadrature (else Monte Carlo).
    pub deterministic: bool,
    /// The budget given (fixed-budget rows).
    pub budget: Option<u32>,
    /// The absolute tolerance asked for (to-tolerance rows).
    pub tol: Option<f64>,
    /// Integrand evaluations the harness counted (all runs).
    pub evaluations: u64,
    /// The integrator's value.
    pub estimate: f64,
    /// The integrator's claimed error.
    pub error_estimate: f64,
    /// Whether the integrator stands behind its error (default true).
    pub resolved: bool,
    /// Why not (free text, no commas); empty when resolved.
    pub status_reason: String,
    /// To-tolerance rows: `tolerance reached`, `max budget reached`, … as
    /// the integrator reports it (empty for fixed-budget rows).
    pub stopped: String,
    /// Wall time in seconds (harness-measured).
    pub seconds: f64,
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

/// A material of the `materials` families.
#[derive(Clone, Debug)]
pub struct Material {
    /// Name (the case names' middle part; no commas).
    pub name: &'static str,
    /// BRDF spec given to the plugins.
    pub spec: String,
    /// The independent f64 model.
    pub model: RefModel,
    /// θo of its albedo cases, in degrees.
    pub thetas: &'static [f64],
    /// Its product cases: `(light elevation in degrees, view)` under both
    /// the sun and the lamp; view `mirror` (the mirror direction of the
    /// light's centre) or `off` (10° off it in azimuth).
    pub products: &'static [(f64, &'static str)],
    /// The budgets of its cases ([`Budgets::FULL`] or
    /// [`Budgets::COMPOSITE`]).
    pub budgets: Budgets,
}

/// The largest budgets of a case: of its fixed-budget ladder, and of the
/// last run of its to-tolerance runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budgets {
    /// Largest budget of the fixed-budget ladder (the ladder stops there).
    pub ladder: u32,
    /// Most evaluations in the last run of a to-tolerance run.
    pub tolerance: u32,
}

impl Budgets {
    /// The whole ladder ([`FULL_BUDGETS`]) and the driver's
    /// [`DEFAULT_MAX_BUDGET`](radiometry::integrator::DEFAULT_MAX_BUDGET), as
    /// `radiometry albedo --tol`.
    pub const FULL: Budgets = Budgets {
        ladder: u32::MAX,
        tolerance: radiometry::integrator::DEFAULT_MAX_BUDGET,
    };
    /// The plugins and combinators added with EON … OpenPBR: the ladder up
    /// to 2¹⁸ = 262,144 and at most 2¹⁸ evaluations in the last
    /// to-tolerance run (the random-material check's
    /// [`honesty::HONESTY_MAX_BUDGET`]); 4× the goal's 65,536. The full
    /// ladder and 2²² would take the report past ten minutes.
    pub const COMPOSITE: Budgets = Budgets {
        ladder: 262_144,
        tolerance: 262_144,
    };
    /// The costliest composites (the mix with a gold lobe and the
    /// OpenPBRs, whose sampling maps cost 0.6–2.4 µs per evaluation): the
    /// ladder up to the goal's 65,536, and at most 2¹⁸ evaluations in the
    /// last to-tolerance run, as [`Budgets::COMPOSITE`] (with 65,536 the
    /// adaptive rules stopped there at θo = 80°, resolved within 10⁻⁶ but
    /// before their confirmation).
    pub const HEAVY: Budgets = Budgets {
        ladder: 65_536,
        tolerance: 262_144,
    };
}

/// The materials of the `materials` families, with the θo of their albedo
/// cases and their product cases.
///
/// * `plastic`: a clear dielectric coat (GGX α = 0.1, height-correlated G2,
///   the exact Fresnel of η = 1.5) over EON (ρ = 0.8, σ = 0.5);
/// * `coated-gold`: a clear dielectric coat (GGX α = 0.05, η = 1.5) over
///   GGX α = 0.3 with the exact conductor Fresnel of gold at 632.8 nm
///   ([`GOLD_ETA`], [`GOLD_K`]);
/// * the rough diffuse plugins `eon` (ρ = 0.9, σ = 1), `fon` (ρ = 0.8,
///   σ = 0.7) and `oren-nayar` (ρ = 0.8, σ = 0.35 rad), whose albedos have
///   closed forms ([`crate::reference::materials::Lobe::closed_albedo`]);
/// * `sheen` (colour 1, roughness 0.3), `openpbr` (OpenPBR Surface's
///   defaults) and `openpbr-all-layers` (metalness 0.5, coat 1 with
///   roughness 0.2, fuzz 1, as the bench's row of that name): f64 quadrature
///   of the plugin's own values ([`RefModel::PluginEval`]), independent of
///   its sampling maps;
/// * `sum`: GGX α = 0.2 with the exact Fresnel of η = 1.5 plus EON (ρ = 0.5,
///   σ = 1); `mix`: 0.3 × gold GGX α = 0.05 + 0.7 × Oren–Nayar (ρ = 0.9,
///   σ = 0.5 rad) — the weighted sums of the lobes' references.
///
/// The layered references tabulate the coat's true directional albedo at
/// the layer's nodes ([`crate::reference::materials`]).
pub fn materials() -> Vec<Material> {
    use crate::reference::materials::{Fresnel, Layer, Lobe};
    let glass = Fresnel::Dielectric { eta: 1.5 };
    let gold = Fresnel::Conductor {
        eta: GOLD_ETA,
        k: GOLD_K,
    };
    let one = |lobe: Lobe| RefModel::Lobes([(1.0, lobe), (0.0, Lobe::Black)]);
    const LAYERED: &[f64] = &[0.0, 60.0, 85.0];
    const BOTH: &[(f64, &str)] = &[(45.0, "mirror"), (45.0, "off"), (10.0, "mirror"), (10.0, "off")];
    // The rough diffuse lobes and the sheen are cheap to evaluate and
    // sample: three θo, the last grazing. The sum, the mix and the OpenPBRs
    // cost 0.5–2.4 µs per sample: two θo, one grazing. Under the lights
    // (sun and lamp, elevation 45°, mirror view): every material but FON and
    // Oren–Nayar (whose cap integrands are EON's kind).
    const CHEAP: &[f64] = &[0.0, 60.0, 85.0];
    const HEAVY: &[f64] = &[20.0, 80.0];
    const LIT: &[(f64, &str)] = &[(45.0, "mirror")];
    // The sheen vanishes at the mirror direction (`D ∝ sin θh^(1/r)`, `h`
    // on the normal there): it is lit at 10° elevation, seen 10° off.
    const SHEEN_LIT: &[(f64, &str)] = &[(10.0, "off")];
    const UNLIT: &[(f64, &str)] = &[];
    vec![
        Material {
            name: "plastic",
            spec: "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), eon(rho=0.8, sigma=0.5))".into(),
            model: RefModel::Coated(Layer {
                top: Lobe::Ggx {
                    alpha: 0.1,
                    fresnel: glass,
                },
                base: Lobe::Eon { rho: 0.8, sigma: 0.5 },
            }),
            thetas: LAYERED,
            products: BOTH,
            budgets: Budgets::FULL,
        },
        Material {
            name: "coated-gold",
            spec: format!(
                "coated(ggx(alpha=0.05, fresnel=dielectric(eta=1.5)), \
                 ggx(alpha=0.3, fresnel=conductor(eta={GOLD_ETA}, k={GOLD_K})))"
            ),
            model: RefModel::Coated(Layer {
                top: Lobe::Ggx {
                    alpha: 0.05,
                    fresnel: glass,
                },
                base: Lobe::Ggx {
                    alpha: 0.3,
                    fresnel: gold,
                },
            }),
            thetas: LAYERED,
            products: BOTH,
            budgets: Budgets::FULL,
        },
        Material {
            name: "eon",
            spec: "eon(rho=0.9, sigma=1)".into(),
            model: one(Lobe::Eon { rho: 0.9, sigma: 1.0 }),
            thetas: CHEAP,
            products: LIT,
            budgets: Budgets::COMPOSITE,
        },
        Material {
            name: "fon",
            spec: "fon(rho=0.8, sigma=0.7)".into(),
            model: one(Lobe::Fon { rho: 0.8, sigma: 0.7 }),
            thetas: CHEAP,
            products: UNLIT,
            budgets: Budgets::COMPOSITE,
        },
        Material {
            name: "oren-nayar",
            spec: "oren-nayar(rho=0.8, sigma_rad=0.35)".into(),
            model: one(Lobe::OrenNayar {
                rho: 0.8,
                sigma_rad: 0.35,
            }),
            thetas: CHEAP,
            products: UNLIT,
            budgets: Budgets::COMPOSITE,
        },
        Material {
            name: "sheen",
            spec: SHEEN.into(),
            model: RefModel::PluginEval {
                spec: SHEEN,
                peak: Some(0.05),
                mu_break: Some(0.5),
            },
            thetas: CHEAP,
            products: SHEEN_LIT,
            budgets: Budgets::COMPOSITE,
        },
        Material {
            name: "sum",
            spec: "ggx(alpha=0.2, fresnel=dielectric(eta=1.5)) + eon(rho=0.5, sigma=1)".into(),
            model: RefModel::Lobes([
                (
                    1.0,
                    Lobe::Ggx {
                        alpha: 0.2,
                        fresnel: glass,
                    },
                ),
                (1.0, Lobe::Eon { rho: 0.5, sigma: 1.0 }),
            ]),
            thetas: HEAVY,
            products: LIT,
            budgets: Budgets::COMPOSITE,
        },
        Material {
            name: "mix",
            spec: format!(
                "mix(0.3, ggx(alpha=0.05, fresnel=conductor(eta={GOLD_ETA}, k={GOLD_K})), \
                 oren-nayar(rho=0.9, sigma_rad=0.5))"
            ),
            model: RefModel::Lobes([
                (
                    0.3,
                    Lobe::Ggx {
                        alpha: 0.05,
                        fresnel: gold,
                    },
                ),
                (
                    0.7,
                    Lobe::OrenNayar {
                        rho: 0.9,
                        sigma_rad: 0.5,
                    },
                ),
            ]),
            thetas: HEAVY,
            products: LIT,
            budgets: Budgets::HEAVY,
        },
        Material {
            name: "openpbr",
            spec: OPENPBR_DEFAULTS.into(),
            model: RefModel::PluginEval {
                spec: OPENPBR_DEFAULTS,
                peak: Some(2.0 * 0.09),
                mu_break: None,
            },
            thetas: HEAVY,
            products: LIT,
            budgets: Budgets::HEAVY,
        },
        Material {
            name: "openpbr-all-layers",
            spec: OPENPBR_ALL_LAYERS.into(),
            model: RefModel::PluginEval {
                spec: OPENPBR_ALL_LAYERS,
                peak: Some(2.0 * 0.04),
                mu_break: None,
            },
            thetas: HEAVY,
            products: LIT,
            budgets: Budgets::HEAVY,
        },
    ]
}

/// The sheen material of [`materials`].
pub const SHEEN: &str = "sheen(color=1, roughness=0.3)";
/// OpenPBR Surface with its default parameters (a dielectric specular
/// layer of roughness 0.3, α = 0.09, over a diffuse base of colour 0.8).
pub const OPENPBR_DEFAULTS: &str = "openpbr";
/// OpenPBR with every layer on: metalness 0.5, a coat of weight 1 and
/// roughness 0.2 (α = 0.04), fuzz of weight 1 (the bench's
/// `openpbr-all-layers`).
pub const OPENPBR_ALL_LAYERS: &str =
    "openpbr(base_metalness=0.5, coat_weight=1, coat_roughness=0.2, fuzz_weight=1)";

/// One case of the suite.
#[derive(Clone, Debug)]
pub struct Case {
    /// Name used in the CSV (no commas).
    pub name: String,
    /// Family: lambertian, phong, ggx, beckmann, ggx-gold, materials.
    pub family: &'static str,
    /// BRDF spec given to the plugins.
    pub spec: String,
    /// The independent f64 model.
    pub model: RefModel,
    /// θo in degrees.
    pub theta_o: f64,
    /// Its largest budgets.
    pub budgets: Budgets,
}

fn fmt_num(x: f64) -> String {
    let s = format!("{x}");
    s.trim_end_matches(".0").to_string()
}

/// The standard suite (or the `--quick` subset).
pub fn suite(quick: bool) -> Vec<Case> {
    let thetas = [0.0, 60.0, 85.0, 89.5, 89.9];
    let mut v = Vec::new();
    let mut push_with =
        |family: &'static str, param: String, spec: String, model: RefModel, t: f64, budgets| {
            v.push(Case {
                name: format!("{family}{param}-to{}", fmt_num(t)),
                family,
                spec,
                model,
                theta_o: t,
                budgets,
            });
        };
    let mut push = |family: &'static str, param: String, spec: String, model: RefModel, t: f64| {
        push_with(family, param, spec, model, t, Budgets::FULL)
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
    // Layered materials (see [`materials`]).
    for m in materials() {
        for &t in m.thetas {
            push_with(
                "materials",
                format!("-{}", m.name),
                m.spec.clone(),
                m.model,
                t,
                m.budgets,
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
    case: &Case,
    integ: &AnyIntegrator,
    budgets: &[u32],
    quick: bool,
) -> (Vec<Measured>, Vec<String>) {
    let budgets: Vec<u32> = budgets
        .iter()
        .copied()
        .filter(|&b| b <= case.budgets.ladder)
        .collect();
    let budgets = &budgets[..];
    let t = case.theta_o.to_radians();
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
    /// Measured outside this crate (a user integrator): listed in the
    /// tables, left out of the honesty targets of the crate's integrators.
    pub external: bool,
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

/// The run-time BRDF of a spec (errors as text).
pub(crate) fn build(spec: &str) -> Result<AnyBrdf, String> {
    let parsed = parse_brdf(spec).map_err(|e| e.to_string())?;
    build_brdf(spec, &parsed).map_err(|e| e.to_string())
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
        if opt.honesty > 0 {
            let (text, md) = honesty_section(opt)?;
            print!("{text}");
            std::fs::write(opt.out.join("summary.md"), md)
                .map_err(|e| format!("cannot write summary.md: {e}"))?;
            println!("\nWrote {}/honesty.csv, summary.md.", opt.out.display());
            return Ok(());
        }
        return Err("the --cases / --integrators filters leave nothing to run".into());
    }
    let brdfs = cases
        .iter()
        .map(|c| build(&c.spec))
        .collect::<Result<Vec<_>, _>>()?;
    let pbrdfs = pcases
        .iter()
        .map(|c| build(&c.spec))
        .collect::<Result<Vec<_>, _>>()?;
    let total = cases.len() * (1 + 2 * integs.len()) + pcases.len() * (2 + 2 * pmethods.len());
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
                measure(&brdfs[ci], &cases[ci], &integs[ii], budgets, opt.quick),
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
    let ref_seconds = ref_nanos.into_inner() as f64 * 1e-9;
    let (refs, mut rows, refused) = albedo.finish();
    let (prefs, mut prows, prefused) = product.finish();

    // The to-tolerance section: every (case, integrator) refined to each of
    // TOL_TARGETS, once the references are known.
    let tol_rows: Mutex<Vec<tolerance::TolRow>> = Mutex::new(Vec::new());
    let (nt, npt) = (cases.len() * integs.len(), pcases.len() * pmethods.len());
    parallel_for(opt.threads, nt + npt, |k| {
        let r = if k < nt {
            let (ci, ii) = (k / integs.len(), k % integs.len());
            progress.tick(&format!("to tolerance {} {}", cases[ci].name, integs[ii].name()));
            tolerance::albedo_rows(&brdfs[ci], &cases[ci], refs[ci].value, &integs[ii])
        } else {
            let k = k - nt;
            let (ci, ii) = (k / pmethods.len(), k % pmethods.len());
            progress.tick(&format!(
                "to tolerance {} {}",
                pcases[ci].name,
                pmethods[ii].name()
            ));
            tolerance::product_rows(&pbrdfs[ci], &pcases[ci], prefs[ci].value, &pmethods[ii])
        };
        tol_rows.lock().expect("no poison").extend(r);
    });
    progress.finish();
    let mut tol_rows = tol_rows.into_inner().expect("no poison");
    // Outside integrators' rows, merged by case name.
    let named_refs: Vec<(String, Reference)> = cases
        .iter()
        .map(|c| c.name.clone())
        .zip(refs.iter().cloned())
        .chain(pcases.iter().map(|c| c.name.clone()).zip(prefs.iter().cloned()))
        .collect();
    let mut ext_tol = tolerance::external_rows(opt, &named_refs)?;
    tolerance::snap_rel_tol(&mut ext_tol);
    tol_rows.extend(ext_tol);
    let order = |n: &str| named_refs.iter().position(|(c, _)| c == n).unwrap_or(usize::MAX);
    tol_rows.sort_by(|a, b| {
        (
            order(&a.case),
            !a.builtin,
            a.integrator.as_str(),
            a.rel_tol.to_bits(),
        )
            .cmp(&(
                order(&b.case),
                !b.builtin,
                b.integrator.as_str(),
                b.rel_tol.to_bits(),
            ))
    });
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

    let mut infos: Vec<MethodInfo> = integs
        .iter()
        .map(|i| MethodInfo {
            name: i.name().to_string(),
            deterministic: i.is_deterministic(),
            external: false,
        })
        .collect();
    let mut pinfos = product::method_infos(&pmethods);
    // Outside integrators' fixed-budget rows.
    for e in opt.external.iter() {
        let Some(budget) = e.budget else { continue };
        let (ci, infos, rows) = if let Some(ci) = cases.iter().position(|c| c.name == e.case) {
            (ci, &mut infos, &mut rows)
        } else if let Some(ci) = pcases.iter().position(|c| c.name == e.case) {
            (ci, &mut pinfos, &mut prows)
        } else if tolerance::case_exists(&e.case) {
            continue; // a case the --cases filter left out
        } else {
            return Err(format!(
                "external row of `{}` names the unknown case `{}`",
                e.integrator, e.case
            ));
        };
        let ii = match infos.iter().position(|m| m.name == e.integrator) {
            Some(i) => i,
            None => {
                infos.push(MethodInfo {
                    name: e.integrator.clone(),
                    deterministic: e.deterministic,
                    external: true,
                });
                infos.len() - 1
            }
        };
        rows.push(Row {
            case: ci,
            integ: ii,
            budget,
            evaluations: e.evaluations,
            estimate: e.estimate,
            error_estimate: e.error_estimate,
            seconds: e.seconds,
            status: if e.resolved {
                Status::Resolved
            } else {
                Status::Unresolved(radiometry::integrator::Unresolved::External)
            },
        });
    }
    rows.sort_by_key(|r| (r.case, r.integ, r.budget));
    prows.sort_by_key(|r| (r.case, r.integ, r.budget));
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
            budgets: c.budgets,
        })
        .collect();
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
    #[cfg(feature = "plot")]
    {
        crate::tradeoff::plot::write_plots(&opt.out, &report)?;
        crate::tradeoff::plot::write_plots(&opt.out, &preport)?;
    }
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
    std::fs::write(opt.out.join("tolerance.csv"), tolerance::csv(&tol_rows))
        .map_err(|e| format!("cannot write tolerance.csv: {e}"))?;
    if !tol_rows.is_empty() {
        let families: Vec<(String, String)> = cases
            .iter()
            .map(|c| (c.name.clone(), c.family.to_string()))
            .chain(pcases.iter().map(|c| (c.name.clone(), c.family.to_string())))
            .collect();
        let (t, m) = tolerance::summary(&tol_rows, &families);
        text.push_str(&t);
        md.push_str(&m);
    }
    if opt.honesty > 0 {
        let (t, m) = honesty_section(opt)?;
        text.push_str(&t);
        md.push_str(&m);
    }
    print!("{text}");
    std::fs::write(opt.out.join("summary.md"), md).map_err(|e| format!("cannot write summary.md: {e}"))?;
    println!(
        "\nWrote {}/tradeoff.csv, tolerance.csv, references.csv, summary.md{} ({:.1} s).",
        opt.out.display(),
        if cfg!(feature = "plot") {
            " and SVG plots"
        } else {
            ""
        },
        elapsed
    );
    Ok(())
}

/// The random-material honesty check ([`honesty`]): `opt.honesty` cases of
/// seed `opt.seed` on `opt.threads` workers; writes `honesty.csv` and returns
/// the section's text and markdown.
fn honesty_section(opt: &Options) -> Result<(String, String), String> {
    let t0 = Instant::now();
    let cases = honesty::cases(opt.honesty, opt.seed);
    let slots: Vec<std::sync::Mutex<Option<honesty::HonestyRow>>> =
        cases.iter().map(|_| std::sync::Mutex::new(None)).collect();
    let progress = Progress::new(opt.progress, cases.len());
    parallel_for(opt.threads, cases.len(), |k| {
        let row = honesty::run_case(&cases[k]);
        *slots[k].lock().expect("no poison") = Some(row);
        progress.tick("honesty");
    });
    progress.finish();
    let rows: Vec<honesty::HonestyRow> = slots
        .into_iter()
        .map(|m| m.into_inner().expect("no poison").expect("computed"))
        .collect();
    std::fs::write(opt.out.join("honesty.csv"), honesty::csv(&rows))
        .map_err(|e| format!("cannot write honesty.csv: {e}"))?;
    let line = honesty::summary_line(&rows, t0.elapsed().as_secs_f64());
    Ok((
        format!("\n{line}\n"),
        format!(
            "\n### Honesty on random materials (`--honesty {}`)\n\n{line}\n",
            opt.honesty
        ),
    ))
}

pub mod external;
pub mod honesty;
#[cfg(feature = "plot")]
pub mod plot;
pub mod product;
mod progress;
pub mod tolerance;
pub(crate) use progress::Progress;
pub use tolerance::{TOL_CSV_HEADER, TOL_TARGETS, case_reference, tolerance_for};
mod report;
use report::write_csv;
pub use report::{Report, SuiteKind};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suite_has_the_issue_cases() {
        let s = suite(false);
        // θo ∈ {0, 60, 85, 89.5, 89.9}; Phong n ∈ {1, 10, 100, 1000};
        // microfacet α ∈ {0.001, 0.01, 0.05, 0.3, 1}.
        // Materials: two layers at 3 θo, four cheap plugins at 3, four
        // heavy composites at 2.
        assert_eq!(s.len(), 5 + 20 + 25 + 23 + 4 + 6 + 4 * 3 + 4 * 2);
        for name in [
            "eon",
            "fon",
            "oren-nayar",
            "sheen",
            "sum",
            "mix",
            "openpbr",
            "openpbr-all-layers",
        ] {
            let of: Vec<&Case> = s
                .iter()
                .filter(|c| c.name.starts_with(&format!("materials-{name}-to")))
                .collect();
            assert!(of.len() >= 2, "{name}");
            // Each is seen at a grazing angle too, and its spec is the plugin.
            assert!(of.iter().any(|c| c.theta_o >= 75.0), "{name}");
            assert!(of.iter().all(|c| c.budgets != Budgets::FULL), "{name}");
        }
        let openpbr = s
            .iter()
            .find(|c| c.name == "materials-openpbr-to20")
            .expect("case");
        assert_eq!(openpbr.spec, "openpbr");
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
}
