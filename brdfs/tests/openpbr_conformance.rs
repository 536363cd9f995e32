//! OpenPBR conformance against Adobe's OpenPBR BSDF (`adobe/openpbr-bsdf`, the
//! BSDF of Adobe's Eclair renderer), measured outside this repository with
//! `tools/scripts/adobe_openpbr_measure.cpp` and committed as numbers in
//! `tests/data/openpbr_adobe.json` (its `source` and `command` fields say
//! which commit and how): directional albedos at θo ∈ {0°, …, 85°} and
//! values `f_r` at eight direction triples, per channel, for 25 parameter
//! combinations, in Adobe's default (energy-conserving) build and its
//! reciprocal-coat build.
//!
//! * **Energy-conserving mode** (both implement OpenPBR's albedo scaling):
//!   the channel-average albedo within `5·10⁻³` at θo ≤ 75° and every value
//!   within 2 % (θi, θo ≤ 75°) on every combination, apart from the
//!   differences `docs/materials.md` names, each asserted here with its own
//!   measured bound.
//! * **Reciprocal mode**: the two builds make different choices (Adobe keeps
//!   its fuzz one-sided and normalises its coat by `1 − Ē`; this crate caps
//!   the Kelemen form under the specular lobes and uses the reciprocal
//!   Charlie sheen). Combinations without coat and fuzz are the same model
//!   and must agree as above; white combinations must stay at least as close
//!   to 1 as Adobe's reciprocal build (within `10⁻³`) and below `1 + 2·10⁻³`.
//!
//! Our albedos integrate `eval` by plain adaptive cubature at 2¹⁵ and 2¹⁶
//! evaluations (the two must agree to `5·10⁻⁴`: the reference has
//! converged far below the tolerance it is used for); the smooth-coat
//! combination (coat roughness 0, a near-delta lobe) by the mean of our own
//! sample weights on a 512 × 512 stratified grid.

use radiometry::glam::Vec3;
use radiometry::integrator::{Adaptive, DirectionalAlbedo, Integrator};
use radiometry::{Brdf, Spectrum};
use radiometry_brdfs::openpbr::{Layering, OpenPbr};
use serde_json::Value;

#[path = "openpbr_adobe_params.rs"]
mod adobe_params;
use adobe_params::{Average, avg3, params, weight_variance};

fn data() -> Value {
    let text = include_str!("data/openpbr_adobe.json");
    serde_json::from_str(text).expect("valid JSON")
}

fn dir(theta_deg: f64, phi_deg: f64) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(
        (t.sin() * p.cos()) as f32,
        (t.sin() * p.sin()) as f32,
        t.cos() as f32,
    )
}

/// Our channel-average albedo at θo (see the module docs for the method).
fn our_albedo(m: &OpenPbr<Vec3>, theta_deg: f64, near_delta: bool) -> f64 {
    let wo = dir(theta_deg, 0.0);
    let b = Average(m);
    if near_delta {
        let n = 512;
        let mut s = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let u = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                if let Some(x) = b.sample(wo, u) {
                    s += f64::from(x.weight);
                }
            }
        }
        return s / (n * n) as f64;
    }
    let a = Adaptive::new(0.0, 0.0).unwrap();
    let g = DirectionalAlbedo { brdf: &b, wo };
    let coarse = a.integrate(&g, 1 << 15).unwrap().value;
    let fine = a.integrate(&g, 1 << 16).unwrap().value;
    assert!((coarse - fine).abs() < 5e-4, "θo {theta_deg}: {coarse} vs {fine}");
    fine
}

/// The differences `docs/materials.md` names, by combination: what differs,
/// and the largest albedo difference (θo ≤ 75°) and relative value
/// difference measured on the committed combination (rounded up), which
/// replace the 5·10⁻³ and 2 % targets there.
const NAMED: [(&str, &str, f64, f64); 7] = [
    (
        "white-metal-r0.3",
        "metal lobe: Adobe's separable Smith G and multiple-scattering lobe",
        5e-3,
        0.05,
    ),
    (
        "white-metal-r0.8",
        "metal lobe: Adobe's separable Smith G and multiple-scattering lobe",
        5e-3,
        0.05,
    ),
    (
        "gold",
        "metal lobe: Adobe's separable Smith G and multiple-scattering lobe",
        5e-3,
        0.05,
    ),
    (
        "all-layers-white",
        "coat roughening: the specification's 2 r_c⁴ against Adobe's (1 − 1/η_c) r_c⁴, and Adobe's fuzz roughening the coat",
        5e-3,
        0.12,
    ),
    (
        "coat-1.3-over-1.8",
        "coat roughening: the specification's 2 r_c⁴ against Adobe's (1 − 1/η_c) r_c⁴",
        1e-2,
        0.05,
    ),
    (
        "tinted-coat-half",
        "partial absorbing coat: the specification mixes coated and bare surface, Adobe applies the coverage per passage",
        7e-2,
        0.35,
    ),
    (
        "coat-2.0-over-1.5",
        "coat darkening: K_s = F(μo) per the specification against Adobe's hemispherical average",
        2e-2,
        0.04,
    ),
];

/// The albedo and value tolerances of a combination.
fn tolerances(name: &str) -> (f64, f64) {
    NAMED
        .iter()
        .find(|n| n.0 == name)
        .map_or((5e-3, 0.02), |n| (n.2, n.3))
}

#[test]
fn energy_conserving_mode_matches_adobes_default_build() {
    let d = data();
    let thetas: Vec<f64> = d["theta_o"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let triples = d["value_triples"].as_array().unwrap();
    let mut worst_albedo = (0.0f64, String::new());
    let mut worst_value = (0.0f64, String::new());
    let mut failures = Vec::new();
    for case in d["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let p = params(&case["params"]);
        let m = OpenPbr::new(p).unwrap();
        let near_delta = p.coat_weight > 0.0 && p.coat_roughness < 0.05;
        let adobe = &case["energy"];
        let (tol_albedo, tol_value) = tolerances(name);
        for (k, &t) in thetas.iter().enumerate() {
            if t > 75.0 {
                continue;
            }
            let theirs = avg3(&adobe["albedo"][k]);
            let ours = our_albedo(&m, t, near_delta);
            let diff = (ours - theirs).abs();
            if diff > worst_albedo.0 && tol_albedo == 5e-3 {
                worst_albedo = (diff, format!("{name} θo {t}: ours {ours:.5}, Adobe {theirs:.5}"));
            }
            if diff > tol_albedo {
                failures.push(format!(
                    "albedo {name} θo = {t}°: ours {ours:.5}, Adobe {theirs:.5}"
                ));
            }
        }
        let Some(values) = adobe["values"].as_array() else {
            continue;
        };
        for (tr, v) in triples.iter().zip(values) {
            let tr: Vec<f64> = tr
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            let (wi, wo) = (dir(tr[0], tr[2]), dir(tr[1], 0.0));
            let f = m.eval(wi, wo);
            for c in 0..3 {
                let theirs = v[c].as_f64().unwrap();
                let ours = f64::from(f.channel(c));
                let rel = (ours - theirs).abs() / theirs.abs().max(1e-3);
                if rel > worst_value.0 && tol_value == 0.02 {
                    worst_value = (
                        rel,
                        format!("{name} {tr:?} channel {c}: ours {ours:.5}, Adobe {theirs:.5}"),
                    );
                }
                if rel > tol_value {
                    failures.push(format!(
                        "value {name} {tr:?} channel {c}: ours {ours:.5}, Adobe {theirs:.5} ({:.1}%)",
                        100.0 * rel
                    ));
                }
            }
        }
    }
    println!(
        "outside the named differences: worst albedo difference {:.2e} ({})",
        worst_albedo.0, worst_albedo.1
    );
    println!(
        "outside the named differences: worst value difference {:.2}% ({})",
        100.0 * worst_value.0,
        worst_value.1
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The reciprocal mode against Adobe's reciprocal-coat build (see the module
/// docs): the same model where neither coat nor fuzz is on; on white
/// combinations at least as close to 1 as Adobe (within 10⁻³) and never
/// above `1 + 2·10⁻³`. Prints every combination's largest difference.
#[test]
fn reciprocal_mode_against_adobes_reciprocal_build() {
    let d = data();
    let thetas: Vec<f64> = d["theta_o"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let mut failures = Vec::new();
    for case in d["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let p = params(&case["params"]);
        let m = OpenPbr::with_layering(p, Layering::Reciprocal).unwrap();
        let near_delta = p.coat_weight > 0.0 && p.coat_roughness < 0.05;
        let layered = p.coat_weight > 0.0 || p.fuzz_weight > 0.0;
        let white = [p.base_color, p.specular_color, p.coat_color, p.fuzz_color]
            .iter()
            .all(|c| c.min_element() == 1.0)
            && p.base_weight == 1.0
            && p.specular_weight == 1.0;
        let adobe = &case["reciprocal"];
        let mut worst = 0.0f64;
        for (k, &t) in thetas.iter().enumerate() {
            if t > 75.0 {
                continue;
            }
            let theirs = avg3(&adobe["albedo"][k]);
            let ours = our_albedo(&m, t, near_delta);
            worst = worst.max((ours - theirs).abs());
            if !layered && (ours - theirs).abs() > tolerances(name).0 {
                failures.push(format!("{name} θo = {t}°: ours {ours:.5}, Adobe {theirs:.5}"));
            }
            if white && ((ours - 1.0).abs() > (theirs - 1.0).abs() + 1e-3 || ours > 1.0 + 2e-3) {
                failures.push(format!(
                    "white {name} θo = {t}°: ours {ours:.5}, Adobe {theirs:.5}"
                ));
            }
        }
        println!("{name}: largest albedo difference to Adobe's reciprocal build {worst:.4}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Sampling efficiency against Adobe's sampler (energy mode): the
/// per-sample variance of the weight within 1.2× Adobe's (measured with
/// 2²⁰ iid samples, `energy.variance`) at θo = 0°, 45°, 75° on every
/// combination, apart from the two `docs/materials.md` names, each asserted
/// with its own bound:
///
/// * `all-layers-white` follows the specification's coat roughening of the
///   base, `(r_s⁴ + 2 r_c⁴)^¼`, where Adobe's BSDF uses `(r_s⁴ + (1 − 1/η_c)
///   r_c⁴)^¼`: a rougher white metal, measured 1.20–1.23×. With the base
///   roughness that gives Adobe's roughened value, within 1.0×.
/// * `coat-r0-over-grey-diffuse`: Adobe's coat of roughness 0 is an ideal
///   mirror whose weight is constant; this crate's is GGX at `α = 10⁻⁴`,
///   whose weights vary by `F(ωo·h) G2/G1` over the distribution's heavy
///   tail: a variance below `3·10⁻⁷` (a relative standard deviation of
///   0.1 %) where Adobe's is `10⁻¹¹`.
#[test]
fn sampling_variance_against_adobes_sampler() {
    let d = data();
    let n = 1 << 18;
    let mut failures = Vec::new();
    for case in d["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let p = params(&case["params"]);
        let m = OpenPbr::new(p).unwrap();
        let theirs: Vec<f64> = case["energy"]["variance"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let mut ratios = Vec::new();
        for (k, t) in [0.0, 45.0, 75.0].into_iter().enumerate() {
            let ours = weight_variance(&m, dir(t, 0.0), n).max(0.0);
            let ratio = ours / theirs[k];
            ratios.push(format!("{ratio:.2}"));
            let ok = match name {
                "all-layers-white" => {
                    // The base roughness whose roughened value is Adobe's.
                    let (rs, rc, nc) = (p.specular_roughness, p.coat_roughness, p.coat_ior);
                    let target = rs.powi(4) + (1.0 - 1.0 / nc) * rc.powi(4);
                    let mut q = p;
                    q.specular_roughness = (target - 2.0 * rc.powi(4)).max(0.0).powf(0.25);
                    let adobe_rough =
                        weight_variance(&OpenPbr::new(q).unwrap(), dir(t, 0.0), n).max(0.0) / theirs[k];
                    println!("  {name} θo = {t}°: with Adobe's roughening {adobe_rough:.2}×");
                    ratio <= 1.3 && adobe_rough <= 1.0
                }
                "coat-r0-over-grey-diffuse" => ours <= 3e-7,
                _ => ratio <= 1.2,
            };
            if !ok {
                failures.push(format!(
                    "{name} θo = {t}°: variance {ours:.3e}, Adobe {:.3e} ({ratio:.2}×)",
                    theirs[k]
                ));
            }
        }
        println!("{name}: variance ÷ Adobe's at 0°/45°/75°: {}", ratios.join(" / "));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
