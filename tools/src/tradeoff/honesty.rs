//! The random-material honesty check of `radiometry tradeoff --honesty N`:
//! random specs of the grammar (random plugins and parameters, sums, mixes
//! and coats nested up to depth 3), random `θo` (a third of them grazing,
//! 75°–89.9°), absolute tolerances log-uniform in `10⁻⁶ … 10⁻³`, a random
//! integrator of [`all_integrators`] (half of the runs `auto`, the default
//! of `radiometry albedo`), each run through [`integrate_to_tolerance`] as
//! `radiometry albedo --tol` runs it (start budget 64), with at most
//! [`HONESTY_MAX_BUDGET`] evaluations in the last run. The reference is an `f64` quadrature
//! of the same BRDF's values written independently of the integrators
//! ([`reference::albedo_of`]: nested adaptive Gauss–Kronrod split at the
//! kinks and the mirror direction); a case whose reference bound exceeds its
//! tolerance is not judged (counted as such).
//!
//! A run *lies* when it stops with "tolerance reached", resolved, and its
//! true error, less the reference's bound, exceeds
//! [`HONESTY_FACTOR`]` × max(claimed error, tol)`.

use super::tolerance::HONESTY_FACTOR;
use crate::model::{AnyIntegrator, all_integrators, build_brdf};
use crate::reference;
use crate::spec::parse_brdf;
use radiometry::Brdf as _;
use radiometry::Integrator as _;
use radiometry::glam::Vec3;
use radiometry::integrator::{DEFAULT_MAX_BUDGET, DirectionalAlbedo, integrate_to_tolerance};
use std::fmt::Write as _;
use std::time::Instant;

/// The largest budget of a run's last refinement in the check (`2¹⁸`, a
/// sixteenth of `radiometry albedo --tol`'s [`DEFAULT_MAX_BUDGET`]): the
/// warped Gauss–Legendre rule on a deep composite spends up to 50 µs per
/// evaluation (the composites' samplers), and one run to the default
/// maximum would take minutes. Claims are made at every budget; a run that
/// would need more stops with "max budget reached" and claims nothing.
pub const HONESTY_MAX_BUDGET: u32 = DEFAULT_MAX_BUDGET / 16;

/// The exact CSV header of `honesty.csv`.
pub const HONESTY_CSV_HEADER: &str = "spec,theta_o,integrator,tol,reference,reference_bound,estimate,error_estimate,abs_error,stopped,status,evaluations,seconds,verdict";

/// SplitMix64 (Steele, Lea & Flood 2014): the case generator's own small
/// random source, so a seed names the same cases everywhere.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[a, b)`.
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }

    /// Log-uniform in `[a, b)`.
    pub fn log_range(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.unit()).exp()
    }

    /// Uniform index below `n`.
    pub fn below(&mut self, n: usize) -> usize {
        ((self.unit() * n as f64) as usize).min(n.saturating_sub(1))
    }
}

/// A random Fresnel argument of `ggx`/`beckmann`.
fn fresnel(r: &mut Rng) -> String {
    match r.below(4) {
        0 => "none".into(),
        1 => format!("schlick(f0={:.3})", r.range(0.02, 1.0)),
        2 => format!("dielectric(eta={:.3})", r.range(0.6, 2.5)),
        _ => format!(
            "conductor(eta={:.3}, k={:.3})",
            r.range(0.1, 2.0),
            r.range(0.5, 5.0)
        ),
    }
}

/// A random leaf lobe of the grammar.
fn leaf(r: &mut Rng) -> String {
    match r.below(12) {
        0 => format!("lambertian(albedo={:.3})", r.range(0.05, 1.0)),
        11 => format!(
            "ltc-sheen(color={:.3}, roughness={:.3})",
            r.range(0.05, 1.0),
            r.unit()
        ),
        1 | 2 => {
            let ms = if r.below(4) == 0 { ", ms=kulla-conty" } else { "" };
            let g = if r.below(3) == 0 { ", g=separable" } else { "" };
            format!(
                "ggx(alpha={:.4}, fresnel={}{g}{ms})",
                r.log_range(0.03, 1.0),
                fresnel(r)
            )
        }
        3 => format!(
            "beckmann(alpha={:.4}, fresnel={})",
            r.log_range(0.03, 1.0),
            fresnel(r)
        ),
        4 => format!("eon(rho={:.3}, sigma={:.3})", r.range(0.05, 1.0), r.unit()),
        5 => format!("fon(rho={:.3}, sigma={:.3})", r.range(0.05, 1.0), r.unit()),
        // ρ ≤ 0.9: the classic Oren–Nayar gains energy at grazing views
        // above a σ-dependent bound near 1, which the grammar refuses.
        6 => format!(
            "oren-nayar(rho={:.3}, sigma_rad={:.3})",
            r.range(0.05, 0.9),
            r.range(0.0, 1.2)
        ),
        7 => format!(
            "sheen(color={:.3}, roughness={:.3})",
            r.range(0.05, 1.0),
            r.range(0.1, 1.0)
        ),
        8 => format!(
            "phong(exponent={:.1}, ks={:.3}, kd={:.3})",
            r.log_range(2.0, 300.0),
            r.range(0.0, 0.6),
            r.range(0.0, 0.4)
        ),
        9 => format!(
            "blinn-phong(exponent={:.1}, ks={:.3}, kd={:.3})",
            r.log_range(2.0, 300.0),
            r.range(0.0, 0.6),
            r.range(0.0, 0.4)
        ),
        _ => {
            let mut s = String::from("openpbr(");
            let _ = write!(
                s,
                "base_color={:.3}, base_metalness={:.3}, base_diffuse_roughness={:.3}, specular_roughness={:.3}",
                r.range(0.05, 1.0),
                if r.below(2) == 0 { 0.0 } else { r.unit() },
                r.unit(),
                r.range(0.05, 1.0)
            );
            if r.below(2) == 0 {
                let _ = write!(
                    s,
                    ", coat_weight={:.3}, coat_roughness={:.3}",
                    r.unit(),
                    r.range(0.05, 1.0)
                );
            }
            if r.below(3) == 0 {
                let _ = write!(
                    s,
                    ", fuzz_weight={:.3}, fuzz_roughness={:.3}",
                    r.unit(),
                    r.range(0.1, 1.0)
                );
            }
            if r.below(4) == 0 {
                s.push_str(", reciprocal=1");
            }
            s.push(')');
            s
        }
    }
}

/// A random spec: a leaf, or (below depth 3) a sum, mix or coat of two
/// random specs; a coat's top is a dielectric GGX or Beckmann, as a coat is.
pub fn random_spec(r: &mut Rng, depth: u32) -> String {
    if depth >= 3 || r.below(2) == 0 {
        return leaf(r);
    }
    match r.below(3) {
        0 => format!("{} + {}", random_spec(r, depth + 1), random_spec(r, depth + 1)),
        1 => format!(
            "mix({:.3}, {}, {})",
            r.unit(),
            random_spec(r, depth + 1),
            random_spec(r, depth + 1)
        ),
        _ => {
            let top = match r.below(3) {
                0 => format!(
                    "ggx(alpha={:.4}, fresnel=dielectric(eta={:.3}))",
                    r.log_range(0.03, 1.0),
                    r.range(0.6, 2.5)
                ),
                1 => format!(
                    "beckmann(alpha={:.4}, fresnel=dielectric(eta={:.3}))",
                    r.log_range(0.03, 1.0),
                    r.range(0.6, 2.5)
                ),
                _ => random_spec(r, depth + 1),
            };
            let reciprocal = if r.below(4) == 0 { ", reciprocal=1" } else { "" };
            format!("coated({top}, {}{reciprocal})", random_spec(r, depth + 1))
        }
    }
}

/// One random case: spec, `θo` in degrees, absolute tolerance, integrator
/// index into [`all_integrators`].
#[derive(Clone, Debug)]
pub struct HonestyCase {
    /// The BRDF spec.
    pub spec: String,
    /// `θo`, degrees.
    pub theta_o: f64,
    /// Absolute tolerance.
    pub tol: f64,
    /// The integrator's name.
    pub integrator: String,
}

/// The `n` cases of `seed` (the same list for the same arguments).
pub fn cases(n: usize, seed: u64) -> Vec<HonestyCase> {
    let names: Vec<String> = all_integrators(1, 0.0)
        .iter()
        .map(|i| i.name().to_string())
        .collect();
    let mut r = Rng::new(seed);
    (0..n)
        .map(|_| {
            let spec = random_spec(&mut r, 0);
            let theta_o = if r.below(3) == 0 {
                r.range(75.0, 89.9)
            } else {
                r.range(0.0, 89.9)
            };
            let tol = r.log_range(1e-6, 1e-3);
            let integrator = if r.below(2) == 0 {
                "auto".to_string()
            } else {
                names[r.below(names.len())].clone()
            };
            HonestyCase {
                spec,
                theta_o: (theta_o * 10.0).round() / 10.0,
                tol,
                integrator,
            }
        })
        .collect()
}

/// One judged run.
#[derive(Clone, Debug)]
pub struct HonestyRow {
    /// The case.
    pub case: HonestyCase,
    /// The reference and its bound (NaN when the spec did not build).
    pub reference: f64,
    /// The reference's bound.
    pub bound: f64,
    /// The returned value, its claimed error, evaluations, stop, status.
    pub estimate: f64,
    /// Claimed error.
    pub error: f64,
    /// Evaluations over all runs.
    pub evaluations: u64,
    /// Why it stopped.
    pub stopped: String,
    /// `resolved` / `unresolved`.
    pub status: String,
    /// Wall time of the run (not of the reference).
    pub seconds: f64,
}

impl HonestyRow {
    /// Whether the row claims the tolerance, resolved.
    pub fn claims(&self) -> bool {
        self.stopped == "tolerance reached" && self.status == "resolved"
    }

    /// Whether the reference can judge the row: finite, bound `≤ tol` (the
    /// bound is subtracted from the true error before it is judged).
    pub fn judged(&self) -> bool {
        self.reference.is_finite() && self.bound <= self.case.tol
    }

    /// `(|estimate − reference| − bound) / max(claim, tol)`.
    pub fn ratio(&self) -> f64 {
        ((self.estimate - self.reference).abs() - self.bound).max(0.0) / self.error.max(self.case.tol)
    }

    /// A judged claim off by more than [`HONESTY_FACTOR`]` × max(claim, tol)`.
    pub fn lies(&self) -> bool {
        self.claims() && self.judged() && self.ratio() > HONESTY_FACTOR
    }
}

/// Runs one case (the reference and the integrator, at most
/// [`HONESTY_MAX_BUDGET`] evaluations in the last run).
pub fn run_case(c: &HonestyCase) -> HonestyRow {
    run_case_with(c, HONESTY_MAX_BUDGET)
}

/// [`run_case`] with at most `max_budget` evaluations in the last run.
pub fn run_case_with(c: &HonestyCase, max_budget: u32) -> HonestyRow {
    let mut row = HonestyRow {
        case: c.clone(),
        reference: f64::NAN,
        bound: f64::NAN,
        estimate: f64::NAN,
        error: f64::NAN,
        evaluations: 0,
        stopped: String::new(),
        status: String::new(),
        seconds: 0.0,
    };
    let brdf = match parse_brdf(&c.spec).and_then(|s| build_brdf(&c.spec, &s)) {
        Ok(b) => b,
        Err(e) => {
            row.stopped = format!("error: {}", e.message).replace(',', ";");
            return row;
        }
    };
    let t = c.theta_o.to_radians();
    let wo = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
    let f = |wi: [f64; 3]| {
        let w = Vec3::new(wi[0] as f32, wi[1] as f32, wi[2] as f32);
        if w.z <= 0.0 {
            return 0.0;
        }
        brdf.eval(w.normalize(), wo) as f64
    };
    let r = reference::albedo_of(&f, t);
    row.reference = r.value;
    row.bound = r.bound;
    let Some(integ): Option<AnyIntegrator> = all_integrators(crate::model::DEFAULT_SEED, 0.0)
        .into_iter()
        .find(|i| i.name() == c.integrator)
    else {
        row.stopped = "error: unknown integrator".into();
        return row;
    };
    let g = DirectionalAlbedo { brdf: &brdf, wo };
    let t0 = Instant::now();
    match integrate_to_tolerance(&integ, &g, c.tol, 64, max_budget) {
        Ok(o) => {
            row.estimate = o.estimate.value;
            row.error = o.estimate.error;
            row.evaluations = o.total_evaluations;
            row.stopped = o.stop.as_str().into();
            row.status = o.estimate.status.as_str().into();
        }
        Err(e) => {
            row.stopped = format!("error: {e}").replace(',', ";");
            row.status = "unresolved".into();
        }
    }
    row.seconds = t0.elapsed().as_secs_f64();
    row
}

/// `honesty.csv`.
pub fn csv(rows: &[HonestyRow]) -> String {
    let mut s = String::from(HONESTY_CSV_HEADER);
    s.push('\n');
    for r in rows {
        let verdict = if !r.claims() {
            "no claim"
        } else if !r.judged() {
            "not judged"
        } else if r.lies() {
            "LIE"
        } else {
            "honest"
        };
        let _ = writeln!(
            s,
            "\"{}\",{},{},{:e},{},{:e},{},{:e},{:e},{},{},{},{:.6},{verdict}",
            r.case.spec,
            r.case.theta_o,
            r.case.integrator,
            r.case.tol,
            r.reference,
            r.bound,
            r.estimate,
            r.error,
            (r.estimate - r.reference).abs(),
            r.stopped,
            r.status,
            r.evaluations,
            r.seconds
        );
    }
    s
}

/// Counts of a run: runs, judged runs, claims, judged claims, lies, the
/// worst ratio of a judged claim and its row.
#[derive(Clone, Debug, Default)]
pub struct HonestyCounts {
    /// Runs.
    pub runs: usize,
    /// Runs with a reference good enough to judge them.
    pub judged: usize,
    /// Runs that claim the tolerance, resolved.
    pub claims: usize,
    /// Judged claims.
    pub judged_claims: usize,
    /// Judged claims off by more than 10 × max(claim, tol).
    pub lies: usize,
    /// The worst ratio `(|error| − bound)/max(claim, tol)` of a judged claim.
    pub worst: f64,
    /// Index of that row.
    pub worst_row: Option<usize>,
    /// Runs whose spec or integrator was refused.
    pub errors: usize,
}

/// The counts of `rows`.
pub fn counts(rows: &[HonestyRow]) -> HonestyCounts {
    let mut c = HonestyCounts {
        runs: rows.len(),
        ..Default::default()
    };
    for (k, r) in rows.iter().enumerate() {
        c.errors += usize::from(r.stopped.starts_with("error"));
        c.judged += usize::from(r.judged());
        c.claims += usize::from(r.claims());
        if r.claims() && r.judged() {
            c.judged_claims += 1;
            c.lies += usize::from(r.lies());
            if r.ratio() > c.worst {
                c.worst = r.ratio();
                c.worst_row = Some(k);
            }
        }
    }
    c
}

/// The summary line of the section.
pub fn summary_line(rows: &[HonestyRow], seconds: f64) -> String {
    let c = counts(rows);
    let worst = c
        .worst_row
        .map(|k| {
            let r = &rows[k];
            format!(
                " (`{}` at θo = {}°, `{}`, tol {:.1e})",
                r.case.spec, r.case.theta_o, r.case.integrator, r.case.tol
            )
        })
        .unwrap_or_default();
    format!(
        "Random materials: {} runs ({} judged by a reference bound within the tolerance, {} refused), {} claims \
         of \"tolerance reached\" (resolved), {} judged; **{} lies** (true error above 10 × max(claim, tol)); worst \
         ratio {:.2}{worst}; {:.0} s.",
        c.runs, c.judged, c.errors, c.claims, c.judged_claims, c.lies, c.worst, seconds
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The generator makes specs the grammar accepts, nested as documented.
    #[test]
    fn random_specs_parse_and_nest() {
        let cs = cases(200, 7);
        let mut composite = 0;
        for c in &cs {
            let s = parse_brdf(&c.spec).unwrap_or_else(|e| panic!("{}: {e}", c.spec));
            assert!(build_brdf(&c.spec, &s).is_ok(), "{}", c.spec);
            assert!((0.0..90.0).contains(&c.theta_o), "{c:?}");
            assert!((1e-6..1e-3).contains(&c.tol), "{c:?}");
            composite += usize::from(
                c.spec.contains(" + ") || c.spec.starts_with("mix") || c.spec.starts_with("coated"),
            );
        }
        assert!(composite > 40, "{composite} composites in 200");
        assert!(cs.iter().filter(|c| c.theta_o >= 75.0).count() > 50);
    }

    /// The reference of the check against closed forms: Lambertian `ρ`, and
    /// GGX `α = 1` at normal incidence `1 − ln 2` (within the `f32` values'
    /// rounding), with bounds that cover the difference.
    #[test]
    fn the_split_reference_meets_closed_forms() {
        for (spec, theta, exact) in [
            ("lambertian(albedo=0.5)", 60.0f64, 0.5),
            ("ggx(alpha=1)", 0.0, 1.0 - core::f64::consts::LN_2),
        ] {
            let b = build_brdf(spec, &parse_brdf(spec).unwrap()).unwrap();
            let t = theta.to_radians();
            let wo = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
            let f = |wi: [f64; 3]| {
                let w = Vec3::new(wi[0] as f32, wi[1] as f32, wi[2] as f32);
                if w.z <= 0.0 {
                    0.0
                } else {
                    b.eval(w.normalize(), wo) as f64
                }
            };
            let r = reference::albedo_of(&f, t);
            assert!(r.bound < 1e-6, "{spec}: {r:?}");
            assert!((r.value - exact).abs() < 1e-6, "{spec}: {r:?} vs {exact}");
        }
    }

    /// A small fixed sample of the random-material check (the report's
    /// `--honesty N` runs the large one): no run that claims the tolerance,
    /// resolved, is off by more than 10 × max(claim, tol), and the sample
    /// does make claims (so the assertion can fail).
    #[test]
    fn random_materials_are_honest() {
        // The drivers that confirm their own work (`auto`, the adaptive
        // rules), at most 2¹⁶ evaluations in the last run (seconds at the
        // test profile's opt-level 1).
        let names = ["auto", "adaptive-warped", "adaptive", "auto"];
        let rows: Vec<HonestyRow> = cases(24, 0x5EED_0039)
            .into_iter()
            .enumerate()
            .map(|(k, mut c)| {
                c.integrator = names[k % names.len()].into();
                run_case_with(&c, 1 << 16)
            })
            .collect();
        let c = counts(&rows);
        let lies: Vec<String> = rows
            .iter()
            .filter(|r| r.lies())
            .map(|r| {
                format!(
                    "{} at {}° by {} (tol {:e}): {} ± {:e} vs {} ± {:e}",
                    r.case.spec,
                    r.case.theta_o,
                    r.case.integrator,
                    r.case.tol,
                    r.estimate,
                    r.error,
                    r.reference,
                    r.bound
                )
            })
            .collect();
        assert!(lies.is_empty(), "{lies:#?}");
        assert!(c.judged_claims >= 12, "{c:?}");
        assert_eq!(c.errors, 0, "{c:?}");
    }
}
