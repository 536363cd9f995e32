//! Integration tests of `radiometry bench`: output shapes and the internal
//! consistency of the ratio columns (the rates themselves are machine
//! dependent). `--min-time-ms` (hidden) keeps the runs short.

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

const PLUGINS: [&str; 19] = [
    "lambertian",
    "modified-phong-n100",
    "blinn-phong-n100",
    "ggx-hc-a0.3",
    "ggx-sep-a0.3",
    "ggx-hc-schlick-rgb-a0.3",
    "ggx-hc-conductor-rgb-a0.3",
    "beckmann-hc-a0.3",
    "tabulated-merl-ggx-a0.3",
    "tabulated-merl-rgb-ggx-a0.3",
    "eon-s0.5",
    "ggx-hc-dielectric-a0.1",
    "plastic-ggx0.1-eon",
    "openpbr-defaults",
    "openpbr-all-layers",
    "openpbr-defaults-reciprocal",
    "openpbr-all-layers-reciprocal",
    "openpbr-defaults-rgb",
    "spec-openpbr-red-rgb",
];
/// The materials' extra paths (construction at every hit, a whole hit, the same through one prepared view).
const MATERIAL_PATHS: [(&str, &[&str]); 5] = [
    (
        "plastic-ggx0.1-eon",
        &[
            "construct",
            "hit",
            "hit-prepared",
            "albedo-read",
            "albedo-full",
            "albedo-prepared",
            "albedo-batch",
            "eval-parts",
            "eval-batch-parts",
            "sample-batch-parts",
        ],
    ),
    (
        "openpbr-defaults",
        &[
            "construct",
            "hit",
            "hit-prepared",
            "eval-batch-parts",
            "sample-batch-parts",
            "eval-parts",
            "sample-parts",
        ],
    ),
    ("openpbr-all-layers", &["construct", "hit", "hit-prepared"]),
    (
        "openpbr-defaults-reciprocal",
        &["construct", "hit", "hit-prepared"],
    ),
    (
        "openpbr-all-layers-reciprocal",
        &["construct", "hit", "hit-prepared"],
    ),
];

/// Extra paths of plugin `p`.
fn extra_paths(p: &str) -> usize {
    MATERIAL_PATHS.iter().find(|m| m.0 == p).map_or(0, |m| m.1.len())
}
const PATHS: [&str; 7] = [
    "eval",
    "eval_batch",
    "eval_batch_soa",
    "pdf",
    "pdf_batch",
    "sample",
    "sample_batch",
];
const BATCH_PATHS: [&str; 4] = ["eval_batch", "eval_batch_soa", "pdf_batch", "sample_batch"];
/// The input sets, each timed at every n.
const INPUTS: [&str; 2] = ["golden", "random"];

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs())
}

#[test]
fn quick_json_has_every_plugin_and_path_with_consistent_ratios() {
    let o = run(&["bench", "--quick", "--format", "json", "--min-time-ms", "1"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value =
        serde_json::from_str(stdout(&o).trim()).unwrap_or_else(|e| panic!("not JSON ({e}): {}", stdout(&o)));

    let h = &j["header"];
    assert!(!h["cpu"].as_str().expect("cpu").is_empty(), "{h}");
    assert!(h["target_features"].is_object(), "{h}");
    assert!(h["simd_feature"].is_boolean(), "{h}");
    assert!(h["profile"].is_string() && h["opt_level"].is_string(), "{h}");
    assert!(h["timing"].as_str().expect("timing").contains("best of"), "{h}");

    let all_rows = j["rows"].as_array().expect("rows");
    let extra: usize = MATERIAL_PATHS.iter().map(|m| m.1.len()).sum();
    assert_eq!(
        all_rows.len(),
        INPUTS.len() * (8 + PLUGINS.len() * PATHS.len() + extra)
    );
    for set in INPUTS {
        let rows: Vec<&serde_json::Value> = all_rows.iter().filter(|r| r["inputs"] == set).collect();
        let get = |plugin: &str, path: &str| {
            let v: Vec<_> = rows
                .iter()
                .filter(|r| r["plugin"] == plugin && r["path"] == path)
                .collect();
            assert_eq!(v.len(), 1, "{set} {plugin} {path}: {} rows", v.len());
            *v[0]
        };
        let rate = |r: &serde_json::Value| r["m_per_s"].as_f64().expect("m_per_s");
        let stream = rate(get("stream", "stream"));
        let ref_scalar = rate(get("reference-ggx-scalar", "eval"));
        let ref_soa = rate(get("reference-ggx-soa", "eval_batch_soa"));
        let ref_sample = rate(get("reference-ggx-sample-scalar", "sample"));
        let ref_sample_soa = rate(get("reference-ggx-sample-soa", "sample_batch"));
        let ref_beckmann = rate(get("reference-beckmann-scalar", "eval"));
        let ref_tabulated = rate(get("reference-tabulated-scalar", "eval"));
        let ref_eon = rate(get("reference-eon-scalar", "eval"));
        assert_eq!(rows.len(), 8 + PLUGINS.len() * PATHS.len() + extra);
        for &r in &rows {
            assert_eq!(r["n"], 4096, "--quick is n = 4096 only: {r}");
            let m = rate(r);
            assert!(m.is_finite() && m > 0.0, "{r}");
            let ns = r["ns_per_elem"].as_f64().expect("ns_per_elem");
            assert!(close(ns, 1e3 / m), "{r}");
            assert!(
                close(r["vs_stream"].as_f64().expect("vs_stream"), m / stream),
                "{r}"
            );
            if r["plugin"] == "stream" {
                assert!(r["vs_ref"].is_null() && r["ref"].is_null(), "{r}");
                continue;
            }
            let batch = BATCH_PATHS.iter().any(|p| r["path"] == *p);
            let (name, denom) = if r["path"] == "sample" {
                ("reference-ggx-sample-scalar", ref_sample)
            } else if r["path"] == "sample_batch" {
                ("reference-ggx-sample-soa", ref_sample_soa)
            } else if batch {
                ("reference-ggx-soa", ref_soa)
            } else {
                ("reference-ggx-scalar", ref_scalar)
            };
            assert_eq!(r["ref"], name, "{r}");
            assert!(close(r["vs_ref"].as_f64().expect("vs_ref"), m / denom), "{r}");
            // The plain loop of the plugin's own formula, where the bench has one.
            let own = match (
                r["plugin"].as_str().expect("plugin"),
                r["path"].as_str().expect("path"),
            ) {
                ("ggx-hc-a0.3", "eval") => Some(("reference-ggx-scalar", ref_scalar)),
                ("ggx-hc-a0.3", "eval_batch" | "eval_batch_soa") => Some(("reference-ggx-soa", ref_soa)),
                ("ggx-hc-a0.3", "sample") => Some(("reference-ggx-sample-scalar", ref_sample)),
                ("ggx-hc-a0.3", "sample_batch") => Some(("reference-ggx-sample-soa", ref_sample_soa)),
                ("beckmann-hc-a0.3", "eval") => Some(("reference-beckmann-scalar", ref_beckmann)),
                ("tabulated-merl-ggx-a0.3", "eval") => Some(("reference-tabulated-scalar", ref_tabulated)),
                ("eon-s0.5", "eval") => Some(("reference-eon-scalar", ref_eon)),
                _ => None,
            };
            match own {
                Some((name, denom)) => {
                    assert_eq!(r["own_ref"], name, "{r}");
                    assert!(
                        close(r["vs_own_ref"].as_f64().expect("vs_own_ref"), m / denom),
                        "{r}"
                    );
                }
                None => assert!(r["own_ref"].is_null() && r["vs_own_ref"].is_null(), "{r}"),
            }
        }
        for p in PLUGINS {
            for path in PATHS {
                get(p, path);
            }
        }
    }
    // A warning for every batch row below 0.95x its scalar row, and no other.
    let warnings = j["warnings"].as_array().expect("warnings");
    let mut expected = 0;
    for r in all_rows {
        let scalar_path = match r["path"].as_str().expect("path") {
            "eval_batch" | "eval_batch_soa" => "eval",
            "pdf_batch" => "pdf",
            "sample_batch" => "sample",
            _ => continue,
        };
        let Some(s) = all_rows
            .iter()
            .find(|s| s["plugin"] == r["plugin"] && s["inputs"] == r["inputs"] && s["path"] == scalar_path)
        else {
            continue;
        };
        let ratio = r["m_per_s"].as_f64().unwrap() / s["m_per_s"].as_f64().unwrap();
        let w = warnings
            .iter()
            .find(|w| w["plugin"] == r["plugin"] && w["path"] == r["path"] && w["inputs"] == r["inputs"]);
        if ratio < 0.95 {
            let w = w.unwrap_or_else(|| panic!("no warning for {r}"));
            assert_eq!(w["scalar_path"], scalar_path);
            assert!(close(w["vs_scalar"].as_f64().unwrap(), ratio), "{w}");
            expected += 1;
        } else {
            assert!(w.is_none(), "{w:?} for {r}");
        }
    }
    assert_eq!(warnings.len(), expected);
}

#[test]
fn only_times_the_selected_plugins() {
    let o = run(&[
        "bench",
        "--quick",
        "--format",
        "json",
        "--min-time-ms",
        "1",
        "--only",
        "tabulated-merl-ggx",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_str(stdout(&o).trim()).expect("JSON");
    let rows = j["rows"].as_array().expect("rows");
    // Per input set: the eight references and the seven paths of the one plugin.
    assert_eq!(rows.len(), INPUTS.len() * (8 + PATHS.len()), "{rows:?}");
    for r in rows {
        let p = r["plugin"].as_str().expect("plugin");
        assert!(
            p == "tabulated-merl-ggx-a0.3" || p == "stream" || p.starts_with("reference-"),
            "{r}"
        );
    }
}

#[test]
fn quick_table_has_the_header_and_ratio_columns() {
    let o = run(&["bench", "--quick", "--min-time-ms", "1"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let s = stdout(&o);
    for key in ["cpu:", "features:", "simd feature", "profile", "best of"] {
        assert!(s.contains(key), "missing `{key}`:\n{s}");
    }
    let head = s
        .lines()
        .find(|l| l.starts_with("plugin"))
        .unwrap_or_else(|| panic!("no column header:\n{s}"));
    let cols: Vec<&str> = head.split_whitespace().collect();
    assert_eq!(
        cols,
        [
            "plugin",
            "path",
            "n",
            "m_per_s",
            "ns_per_elem",
            "vs_ref",
            "vs_stream",
            "vs_own_ref",
            "inputs"
        ]
    );
    for p in PLUGINS {
        let lines = s
            .lines()
            .filter(|l| l.split_whitespace().next() == Some(p))
            .count();
        assert_eq!(lines, INPUTS.len() * (PATHS.len() + extra_paths(p)), "{p}:\n{s}");
    }
}

#[test]
fn help_documents_method_and_native_build() {
    let o = run(&["bench", "--help"]);
    assert!(o.status.success());
    let s = stdout(&o);
    for key in [
        "target-cpu=native",
        "--features simd",
        "BEST",
        "vs_ref",
        "vs_stream",
        "vs_own_ref",
        "--quick",
        "golden",
        "random",
        "warning",
        "--only",
    ] {
        assert!(s.contains(key), "missing `{key}`:\n{s}");
    }
    assert!(!s.contains("min-time-ms"), "the test flag stays hidden:\n{s}");
    let o = run(&["bench", "--min-time-ms", "0"]);
    assert_eq!(o.status.code(), Some(2));
}
