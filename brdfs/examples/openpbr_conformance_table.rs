//! The tables of `docs/materials.md` § "Conformance": this crate's OpenPBR
//! against Adobe's OpenPBR BSDF on the committed combinations
//! (`tests/data/openpbr_adobe.json`), in both layering modes — the
//! channel-average directional albedo at θo ∈ {0°, 45°, 75°, 85°} (ours by
//! plain adaptive cubature of `eval` at 2¹⁸ evaluations, or for a
//! near-delta coat the mean of 2²⁰ stratified sample weights) and the
//! per-sample variance of the sample weight `f cos θi / pdf` (channel
//! average, 2²⁰ iid uniform samples of a fixed seed, a failed sample counting
//! 0) against Adobe's on the same footing.
//!
//! Run: `cargo run --release -p radiometry-brdfs --features examples --example openpbr_conformance_table`
//! (append `-- variance` for the sampling table alone)

use radiometry::Brdf;
use radiometry::glam::Vec3;
use radiometry::integrator::{Adaptive, DirectionalAlbedo, Integrator};
use radiometry_brdfs::openpbr::{Layering, OpenPbr};
use serde_json::Value;

#[path = "../tests/openpbr_adobe_params.rs"]
mod adobe_params;
use adobe_params::{Average, avg3, params, weight_variance};

fn wo(theta: f64) -> Vec3 {
    let t = theta.to_radians();
    Vec3::new(t.sin() as f32, 0.0, t.cos() as f32)
}

fn albedo(m: &OpenPbr<Vec3>, theta: f64, near_delta: bool) -> f64 {
    let b = Average(m);
    if near_delta {
        let n = 1024;
        let mut s = 0.0;
        for i in 0..n {
            for j in 0..n {
                let u = [(i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32];
                s += b.sample(wo(theta), u).map_or(0.0, |x| f64::from(x.weight));
            }
        }
        return s / (n * n) as f64;
    }
    let g = DirectionalAlbedo {
        brdf: &b,
        wo: wo(theta),
    };
    Adaptive::new(0.0, 0.0)
        .unwrap()
        .integrate(&g, 1 << 18)
        .unwrap()
        .value
}

fn main() {
    let d: Value = serde_json::from_str(include_str!("../tests/data/openpbr_adobe.json")).unwrap();
    let thetas: Vec<f64> = d["theta_o"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let show = [0.0, 45.0, 75.0, 85.0];
    // `variance`: the sampling table alone.
    let modes: &[(Layering, &str)] = if std::env::args().nth(1).as_deref() == Some("variance") {
        &[]
    } else {
        &[
            (Layering::EnergyConserving, "energy"),
            (Layering::Reciprocal, "reciprocal"),
        ]
    };
    for &(mode, key) in modes {
        println!("\n### {key}: albedo at θo = 0° / 45° / 75° / 85°, Adobe → radiometry\n");
        println!("| combination | Adobe | radiometry | largest difference |");
        println!("|---|---|---|---|");
        for case in d["cases"].as_array().unwrap() {
            let p = params(&case["params"]);
            let m = OpenPbr::with_layering(p, mode).unwrap();
            let near = p.coat_weight > 0.0 && p.coat_roughness < 0.05;
            let mut a = Vec::new();
            let mut o = Vec::new();
            let mut worst = 0.0f64;
            for (k, &t) in thetas.iter().enumerate() {
                if !show.contains(&t) {
                    continue;
                }
                let theirs = avg3(&case[key]["albedo"][k]);
                let ours = albedo(&m, t, near);
                worst = worst.max((ours - theirs).abs());
                a.push(format!("{theirs:.4}"));
                o.push(format!("{ours:.4}"));
            }
            println!(
                "| `{}` | {} | {} | {:.1e} |",
                case["name"].as_str().unwrap(),
                a.join(" / "),
                o.join(" / "),
                worst
            );
        }
    }
    println!(
        "\n### sampling: per-sample variance of the weight, radiometry ÷ Adobe, θo = 0° / 45° / 75° (energy mode)\n"
    );
    println!("| combination | Adobe variance | ratio |");
    println!("|---|---|---|");
    let mut worst = (0.0f64, String::new());
    for case in d["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let m = OpenPbr::new(params(&case["params"])).unwrap();
        let theirs: Vec<f64> = case["energy"]["variance"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let mut r = Vec::new();
        for (k, &t) in [0.0, 45.0, 75.0].iter().enumerate() {
            let v = weight_variance(&m, wo(t), 1 << 20);
            let ratio = v / theirs[k].max(1e-12);
            if ratio > worst.0 {
                worst = (ratio, format!("{name} θo {t}"));
            }
            r.push(format!("{ratio:.2}"));
        }
        let tv: Vec<String> = theirs.iter().map(|v| format!("{v:.2e}")).collect();
        println!("| `{name}` | {} | {} |", tv.join(" / "), r.join(" / "));
    }
    println!("\nlargest ratio {:.2} ({})", worst.0, worst.1);
}
