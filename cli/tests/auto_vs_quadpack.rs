//! `auto` to a tolerance of `10⁻⁶` on the report's 25 GGX albedo cases, as a
//! user runs it: honest against the independent `f64` references of
//! `cli/results/references.csv` (nested Gauss–Kronrod in `f64`, written
//! apart from the integrators and plugins), and cheaper than QUADPACK —
//! SciPy's `integrate.nquad` on the plain `(μ, φ)` square, whose runs on the
//! same integrand are recorded in `cli/results/peers-scipy-nquad.csv` (see
//! `tools/scripts/`). The peer's figure is its cheapest run whose true error
//! is at most `max(auto's true error, 10⁻⁶ × reference)`, as in the report.

use radiometry::glam::Vec3;
use radiometry::integrator::{Auto, DirectionalAlbedo, integrate_to_tolerance};
use radiometry_spec::model::build_brdf;
use radiometry_spec::parse_brdf;

/// The fields of one CSV line (double quotes protect commas).
fn fields(line: &str) -> Vec<String> {
    let (mut out, mut cur, mut quoted) = (Vec::new(), String::new(), false);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    out.push(cur);
    out
}

fn results(file: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("results")
        .join(file);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn auto_beats_quadpack_on_every_ggx_albedo_case_honestly() {
    let refs = results("references.csv");
    let peers = results("peers-scipy-nquad.csv");
    // case → (evaluations, estimate) of every nquad run.
    let mut nquad: std::collections::HashMap<String, Vec<(u64, f64)>> = Default::default();
    for line in peers.lines().skip(1) {
        let f = fields(line);
        if f[1] == "scipy-nquad" {
            nquad
                .entry(f[0].clone())
                .or_default()
                .push((f[5].parse().unwrap(), f[6].parse().unwrap()));
        }
    }
    let mut worst = (0.0f64, String::new());
    let mut cases = 0;
    for line in refs.lines().skip(1) {
        let f = fields(line);
        let (case, theta, spec, reference) = (&f[0], &f[1], &f[2], f[3].parse::<f64>().unwrap());
        if !case.starts_with("ggx-a") {
            continue;
        }
        cases += 1;
        let brdf = build_brdf(spec, &parse_brdf(spec).unwrap()).unwrap();
        // ωo as the report builds it (sines and cosines in f64).
        let t = theta.parse::<f64>().unwrap().to_radians();
        let g = DirectionalAlbedo {
            brdf: &brdf,
            wo: Vec3::new(t.sin() as f32, 0.0, t.cos() as f32),
        };
        let tol = 1e-6 * reference;
        let out = integrate_to_tolerance(&Auto::new(), &g, tol, 64, 1 << 22).unwrap();
        let err = (out.estimate.value - reference).abs();
        assert!(out.reached() && out.estimate.is_resolved(), "{case}: {out:?}");
        assert!(
            err <= 10.0 * out.estimate.error.max(tol),
            "{case}: {} ± {:.1e} vs {reference} (true error {err:.1e})",
            out.estimate.value,
            out.estimate.error
        );
        let target = err.max(tol);
        let peer = nquad
            .get(case)
            .into_iter()
            .flatten()
            .filter(|(_, v)| (v - reference).abs() <= target)
            .map(|&(n, _)| n)
            .min();
        if let Some(n) = peer {
            let ratio = out.total_evaluations as f64 / n as f64;
            eprintln!(
                "{case}: auto {} evaluations, nquad {n}: {ratio:.2}",
                out.total_evaluations
            );
            if ratio > worst.0 {
                worst = (ratio, case.clone());
            }
        } else {
            eprintln!(
                "{case}: auto {} evaluations, nquad never as accurate",
                out.total_evaluations
            );
        }
    }
    assert_eq!(cases, 25);
    assert!(
        worst.0 < 1.0,
        "auto needs more evaluations than nquad on {}: {:.2}",
        worst.1,
        worst.0
    );
}
