//! End to end: `radiometry fit` on MERL `.binary` files written from analytic
//! BRDFs (by the independent `f64` writer of [`crate::analytic`]; the bad-file
//! cases use `radiometry_cli::merl`'s writer), and the printed specs fed back
//! to `radiometry albedo` / `eval`.

use crate::analytic::Analytic;
use radiometry_brdfs::tabulated::RusinkiewiczGrid;
use radiometry_cli::merl;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_radiometry"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn tmp(name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join(name)
}

/// The MERL-layout bytes of GGX α = 0.3 with Schlick F0 = (0.9, 0.6, 0.3),
/// written by the independent [`crate::analytic`] (not by the crate's model
/// code or the CLI's MERL writer), with the nodes below the horizon stored as
/// missing (−1, as in MERL data) and every 50th node above it missing in the
/// green channel.
fn ggx_bytes() -> (Vec<u8>, usize) {
    let g = RusinkiewiczGrid::MERL;
    let rgb = [0.9, 0.6, 0.3].map(|f0| Analytic::ggx(0.3, f0));
    let mut bytes = crate::analytic::merl_bytes(&rgb, &g);
    let n = g.len();
    let mut missing = 0;
    for i in 0..90 {
        for j in 0..90 {
            for k in 0..180 {
                let (wi, wo) = g.node_directions(i, j, k);
                let index = g.index(i, j, k);
                if wi.z <= 0.0 || wo.z <= 0.0 {
                    missing += 3;
                } else if index.is_multiple_of(50) {
                    let at = merl::HEADER_BYTES + 8 * (n + index);
                    bytes[at..at + 8].copy_from_slice(&(-1.0f64).to_le_bytes());
                    missing += 1;
                }
            }
        }
    }
    (bytes, missing)
}

fn json(o: &Output) -> serde_json::Value {
    assert_eq!(o.status.code(), Some(0), "{}", stderr(o));
    serde_json::from_str(stdout(o).trim()).unwrap_or_else(|e| panic!("not JSON ({e}): {}", stdout(o)))
}

#[test]
fn fit_a_merl_file_and_use_the_specs() {
    let (bytes, missing) = ggx_bytes();
    let path = tmp("fit_ggx_a0.3.binary");
    std::fs::write(&path, &bytes).unwrap();
    let file = path.to_str().unwrap();
    let sub = ["--subsample", "3,4,8"];

    // Default subsampling: 139 757 samples above the horizon (a green entry
    // missing leaves the node's red and blue); the roughness scan runs on a
    // subset of them.
    let j = json(&run(&["fit", file, "--model", "ggx", "--format", "json"]));
    assert_eq!(j["samples"].as_u64(), Some(139_757), "{j}");
    eprintln!("{j}");
    assert_eq!(j["missing"].as_u64(), Some(missing as u64));
    assert_eq!(j["grid"], serde_json::json!([90, 90, 180]));
    let alpha = j["alpha"].as_f64().unwrap();
    assert!((alpha / 0.3 - 1.0).abs() < 0.01, "{alpha}");
    for (c, want) in [0.9, 0.6, 0.3].into_iter().enumerate() {
        let f0 = j["f0"][c].as_f64().unwrap();
        assert!((f0 / want - 1.0).abs() < 0.02, "F0[{c}] = {f0}");
    }
    let e = j["metric"].as_f64().unwrap();
    let e_specs = j["metric_of_specs"].as_f64().unwrap();
    assert!(e < 1e-10 && e_specs < 1e-10, "{e} {e_specs}");

    // The printed specs work in `albedo` and `eval`.
    let specs: Vec<String> = j["specs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap().to_string())
        .collect();
    assert_eq!(specs[0], "ggx(alpha=0.3, fresnel=schlick(f0=0.9))");
    for s in &specs {
        let a = run(&["albedo", s, "--theta-o", "30"]);
        assert_eq!(a.status.code(), Some(0), "{s}: {}", stderr(&a));
        let e = run(&["eval", s, "--wi", "20,0", "--wo", "30,180"]);
        assert_eq!(e.status.code(), Some(0), "{s}: {}", stderr(&e));
        let v: f64 = stdout(&e).trim().parse().unwrap();
        assert!(v > 0.0 && v.is_finite(), "{v}");
    }

    // The wrong distribution fits worse; text output names the metric.
    let b = json(&run(&[
        &["fit", file, "--model", "beckmann", "--format", "json"],
        &sub[..],
    ]
    .concat()));
    assert!(b["metric"].as_f64().unwrap() > 1e4 * e.max(1e-12), "{b}");
    let t = run(&[&["fit", file, "--model", "ggx", "--diffuse"], &sub[..]].concat());
    assert_eq!(t.status.code(), Some(0), "{}", stderr(&t));
    let text = stdout(&t);
    assert!(
        text.contains("RMS log error") && text.contains("spec B: ggx(alpha=0.3"),
        "{text}"
    );
    assert!(text.contains("kd (R G B)"), "{text}");
    std::fs::remove_file(&path).ok();
}

#[test]
fn bad_files_and_arguments() {
    let g = RusinkiewiczGrid::new(8, 8, 8).unwrap();
    let lambert = radiometry_brdfs::Lambertian::new(0.5f32).unwrap();
    let good = merl::to_bytes(&merl::tabulate(&lambert, g).unwrap());

    let missing = tmp("fit_does_not_exist.binary");
    let o = run(&["fit", missing.to_str().unwrap(), "--model", "ggx"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).starts_with("error: "), "{}", stderr(&o));

    let truncated = tmp("fit_truncated.binary");
    std::fs::write(&truncated, &good[..good.len() - 5]).unwrap();
    let o = run(&["fit", truncated.to_str().unwrap(), "--model", "ggx"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).starts_with("error: "), "{}", stderr(&o));

    let mut all_missing = good.clone();
    for x in all_missing[merl::HEADER_BYTES..].chunks_exact_mut(8) {
        x.copy_from_slice(&(-1.0f64).to_le_bytes());
    }
    let empty = tmp("fit_all_missing.binary");
    std::fs::write(&empty, &all_missing).unwrap();
    let o = run(&["fit", empty.to_str().unwrap(), "--model", "ggx"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("none of the"), "{}", stderr(&o));

    let ok = tmp("fit_lambert.binary");
    std::fs::write(&ok, &good).unwrap();
    let p = ok.to_str().unwrap();
    for args in [
        vec!["fit", p, "--model", "phong"],
        vec!["fit", p],
        vec!["fit", p, "--model", "ggx", "--subsample", "1,0,1"],
        vec!["fit", p, "--model", "ggx", "--fresnel", "dielectric"],
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
    for f in [truncated, empty, ok] {
        std::fs::remove_file(f).ok();
    }
}
