//! MERL `.binary` files and the `Tabulated` plugin built from them: file round trip,
//! malformed files, and the directional albedo of a table of GGX α = 0.3 (F = 1, height-correlated)
//! on the MERL grid against the independent f64 reference of `radiometry_cli::reference` (GGX
//! re-implemented in f64 from Walter et al. 2007 / Heitz 2014, nested Gauss–Kronrod), plus the
//! interpolation error of the table against the analytic plugin.

use radiometry::Brdf;
use radiometry::glam::Vec3;
use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
use radiometry_brdfs::{Ggx, HeightCorrelated, Lambertian, Microfacet, NoFresnel};
use radiometry_cli::merl::{self, MerlError, MerlTable};
use radiometry_cli::reference::{self, RefModel};
use std::f64::consts::PI;

fn ggx(alpha: f32) -> Microfacet<Ggx, HeightCorrelated, NoFresnel> {
    Microfacet::new(Ggx::new(alpha).unwrap(), NoFresnel)
}

/// Lambertian + GGX (a diffuse base under a specular lobe), RGB.
struct DiffuseGgx {
    diffuse: Lambertian<Vec3>,
    spec: Microfacet<Ggx, HeightCorrelated, NoFresnel>,
    ks: f32,
}

impl Brdf for DiffuseGgx {
    type Spectrum = Vec3;
    fn eval(&self, wi: Vec3, wo: Vec3) -> Vec3 {
        self.diffuse.eval(wi, wo) + Vec3::splat(self.ks * self.spec.eval(wi, wo))
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("radiometry-merl-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Write from GGX and from Lambertian + GGX on the MERL grid, read back: identical values (the f64
/// detour through `/ scale`, `* scale` is exact after rounding to f32), header as written, file size
/// 12 + 24 · 1 458 000 bytes; the values at nodes equal the analytic BRDF there.
#[test]
fn round_trip_on_the_merl_grid() {
    let grid = RusinkiewiczGrid::MERL;
    let g = ggx(0.3);
    let table = merl::tabulate(&g, grid).unwrap();
    let path = tmp("ggx.binary");
    merl::write(&path, &table).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes.len(), 12 + 24 * 90 * 90 * 180);
    assert_eq!(&bytes[..12], &[90, 0, 0, 0, 90, 0, 0, 0, 180, 0, 0, 0]);
    // The first red value is stored divided by 1/1500.
    let first = f64::from_le_bytes(bytes[12..20].try_into().unwrap());
    assert!((first - table.values[0].x as f64 * 1500.0).abs() <= 1e-9 * first.abs());
    let back = merl::read(&path).unwrap();
    assert_eq!(back.grid, grid);
    assert_eq!(back.missing, 0);
    assert!(back.values == table.values);
    // Node values are the analytic BRDF at the node directions.
    for &(i, j, k) in &[
        (10usize, 20usize, 30usize),
        (45, 45, 90),
        (0, 0, 0),
        (89, 80, 179),
    ] {
        let (wi, wo) = grid.node_directions(i, j, k);
        assert_eq!(back.values[grid.index(i, j, k)], Vec3::splat(g.eval(wi, wo)));
    }

    let d = DiffuseGgx {
        diffuse: Lambertian::new(Vec3::new(0.5, 0.3, 0.1)).unwrap(),
        spec: ggx(0.1),
        ks: 0.4,
    };
    let table = merl::tabulate(&d, grid).unwrap();
    let path = tmp("diffuse_ggx.binary");
    merl::write(&path, &table).unwrap();
    let back = merl::read(&path).unwrap();
    assert!(back.values == table.values);
    let (wi, wo) = grid.node_directions(5, 30, 0);
    let want = Vec3::new(0.5, 0.3, 0.1) / std::f32::consts::PI + Vec3::splat(0.4 * d.spec.eval(wi, wo));
    assert!((back.values[grid.index(5, 30, 0)] - want).abs().max_element() <= 1e-6 * want.max_element());
    for f in ["ggx.binary", "diffuse_ggx.binary"] {
        let _ = std::fs::remove_file(tmp(f));
    }
}

/// Truncated, bad dims, NaN, missing file: typed errors with clear messages (never a panic).
#[test]
fn malformed_files() {
    let grid = RusinkiewiczGrid::new(4, 4, 4).unwrap();
    let table = merl::tabulate(&ggx(0.5), grid).unwrap();
    let bytes = merl::to_bytes(&table);
    for cut in [0, 5, 12, 13, bytes.len() / 2, bytes.len() - 1] {
        let e = merl::from_bytes(&bytes[..cut]).unwrap_err();
        assert!(matches!(e, MerlError::Length { .. }), "{cut}: {e}");
        assert!(e.to_string().contains("bytes"), "{e}");
    }
    let mut bad = bytes.clone();
    bad[4..8].copy_from_slice(&(-4i32).to_le_bytes());
    let e = merl::from_bytes(&bad).unwrap_err();
    assert_eq!(e.to_string(), "MERL header dimensions 4 x -4 x 4 are invalid");
    let mut bad = bytes.clone();
    bad[8..12].copy_from_slice(&5i32.to_le_bytes());
    assert!(matches!(merl::from_bytes(&bad), Err(MerlError::Length { .. })));
    let mut bad = bytes.clone();
    let at = 12 + 8 * (64 + 7);
    bad[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    let e = merl::from_bytes(&bad).unwrap_err();
    assert!(matches!(e, MerlError::NotFinite { channel: 1, index: 7 }), "{e}");
    assert_eq!(e.to_string(), "MERL value 7 of channel 1 is not finite");
    // A writer call with a table that does not match its grid.
    let wrong = MerlTable {
        grid,
        values: vec![Vec3::ZERO; 3],
        missing: 0,
    };
    assert!(matches!(
        merl::write(&tmp("wrong.binary"), &wrong),
        Err(MerlError::Length { .. })
    ));
}

/// Directional albedo of `b` at θo by nested adaptive Gauss–Kronrod in (μ = cos θi, φ) — the
/// reference module's 1D rule, applied here to the plugin under test — with break points at the
/// mirror direction (μ = cos θo, φ = π).
fn albedo_of(b: &dyn Fn(Vec3, Vec3) -> f32, theta_o: f64) -> f64 {
    let wo = Vec3::new(theta_o.sin() as f32, 0.0, theta_o.cos() as f32);
    let mu0 = theta_o.cos();
    let mu_breaks: Vec<f64> = [-0.2, -0.05, -0.01, 0.0, 0.01, 0.05, 0.2]
        .iter()
        .map(|d| mu0 + d)
        .collect();
    let phi_breaks: Vec<f64> = [0.05, 0.2, 0.6].iter().map(|d| PI - d).collect();
    let (v, _) = reference::adaptive(
        |mu| {
            let s = (1.0 - mu * mu).max(0.0).sqrt();
            let (v, _) = reference::adaptive(
                |phi| {
                    let wi = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, mu as f32);
                    b(wi, wo) as f64 * mu
                },
                0.0,
                PI,
                &phi_breaks,
                1e-9,
                1e-7,
                2000,
            );
            2.0 * v
        },
        0.0,
        1.0,
        &mu_breaks,
        1e-8,
        1e-6,
        2000,
    );
    v
}

/// The target: the table of GGX α = 0.3 on the MERL grid reproduces the analytic albedo
/// within 1 % for θo ≤ 80°. Prints the figures (relative albedo error of the table against the
/// reference; of the analytic plugin against the reference, for scale; pointwise interpolation error).
#[test]
fn ggx_table_albedo_within_one_percent() {
    let grid = RusinkiewiczGrid::MERL;
    let g = ggx(0.3);
    let table = merl::tabulate(&g, grid).unwrap();
    let mono: Vec<f32> = table.values.iter().map(|v| v.x).collect();
    let t = Tabulated::new(grid, &mono).unwrap();
    let model = RefModel::Microfacet {
        ggx: true,
        alpha: 0.3,
        height_correlated: true,
        conductor: None,
    };
    let mut worst = 0.0f64;
    for deg in [0.0f64, 20.0, 40.0, 60.0, 70.0, 80.0] {
        let to = deg.to_radians();
        let r = reference::albedo(&model, to);
        let a_tab = albedo_of(&|wi, wo| t.eval(wi, wo), to);
        let a_ggx = albedo_of(&|wi, wo| g.eval(wi, wo), to);
        let rel = (a_tab - r.value) / r.value;
        eprintln!(
            "θo={deg:>4}°: reference {:.6} (±{:.1e}), table {a_tab:.6} ({:+.3} %), analytic plugin {a_ggx:.6} ({:+.4} %)",
            r.value,
            r.bound,
            100.0 * rel,
            100.0 * (a_ggx - r.value) / r.value
        );
        worst = worst.max(rel.abs());
        assert!(
            rel.abs() < 0.01,
            "θo = {deg}°: table albedo {a_tab} vs reference {}",
            r.value
        );
    }
    eprintln!(
        "worst relative albedo error of the MERL-grid table, θo ≤ 80°: {:.3} %",
        100.0 * worst
    );

    // Pointwise interpolation error, f cos θi-weighted, over a deterministic point set (θi, θo ≤ 80°).
    let (mut num, mut den, mut max_rel_peak) = (0.0f64, 0.0f64, 0.0f64);
    let n = 200;
    for a in 0..n {
        for b in 0..n {
            let ti = (a as f64 + 0.5) / n as f64 * 80f64.to_radians();
            let to = (b as f64 * 0.618_034).fract() * 80f64.to_radians();
            let ph = (b as f64 + 0.5) / n as f64 * 2.0 * PI;
            let wi = Vec3::new(ti.sin() as f32, 0.0, ti.cos() as f32);
            let wo = Vec3::new(
                (to.sin() * ph.cos()) as f32,
                (to.sin() * ph.sin()) as f32,
                to.cos() as f32,
            );
            let (ft, fg) = (t.eval(wi, wo) as f64, g.eval(wi, wo) as f64);
            num += (ft - fg).abs() * ti.cos();
            den += fg * ti.cos();
            if fg > 0.5 {
                max_rel_peak = max_rel_peak.max((ft - fg).abs() / fg);
            }
        }
    }
    eprintln!(
        "interpolation error: cos-weighted mean |f_table − f_ggx| / mean f_ggx = {:.3} %; max relative where f_ggx > 0.5: {:.2} %",
        100.0 * num / den,
        100.0 * max_rel_peak
    );
    assert!(num / den < 0.01);
}

fn run(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_radiometry"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// `radiometry tabulate` writes a file that `tabulated(file=…)` reads back: `eval` at a node direction
/// equals the analytic spec's value; `albedo` (adaptive) matches the f64 reference of GGX α = 0.3 within
/// 1 %; a missing or truncated file is a spec error (exit 2) that names the file and underlines the path.
#[test]
fn cli_tabulate_then_albedo_and_eval() {
    let path = tmp("cli_ggx.binary");
    let p = path.to_str().unwrap();
    let o = run(&["tabulate", "ggx(alpha=0.3)", "--out", p]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::metadata(&path).unwrap().len(), 12 + 24 * 1_458_000);
    let spec = format!("tabulated(file={p})");
    // wi = (30°, 0°), wo = (30°, 180°): the mirror pair, θh = 0 (a node), θd = 30° (node 30).
    // A MERL file has three channels: `eval` prints R G B (here all the grey GGX), `--mono` their luminance.
    let eval = |args: &[&str]| -> Vec<f64> {
        let o = run(&[&["eval"], args, &["--wi", "30,0", "--wo", "30,180"]].concat());
        assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout)
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect()
    };
    let fg = eval(&["ggx(alpha=0.3)"]);
    assert_eq!(fg.len(), 1);
    let (rgb, mono) = (eval(&[&spec]), eval(&[&spec, "--mono"]));
    assert_eq!((rgb.len(), mono.len()), (3, 1));
    for ft in rgb.into_iter().chain(mono) {
        assert!((ft - fg[0]).abs() <= 1e-5 * fg[0], "{ft} vs {fg:?}");
    }
    let o = run(&[
        "albedo",
        &spec,
        "--theta-o",
        "40",
        "--integrator",
        "adaptive",
        "--budget",
        "65536",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let channels = j["value"].as_array().expect("an albedo per channel");
    assert_eq!(channels.len(), 3);
    let a = channels[1].as_f64().expect("albedo value");
    for c in channels {
        assert!((c.as_f64().unwrap() - a).abs() <= 1e-5 * a, "{j}");
    }
    let model = RefModel::Microfacet {
        ggx: true,
        alpha: 0.3,
        height_correlated: true,
        conductor: None,
    };
    let r = reference::albedo(&model, 40f64.to_radians()).value;
    assert!((a - r).abs() < 0.01 * r, "{a} vs {r}");

    let missing = tmp("missing.binary");
    let spec = format!("tabulated(file={})", missing.display());
    let o = run(&["albedo", &spec, "--theta-o", "10"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("cannot read MERL file") && err.contains("missing.binary") && err.contains('^'),
        "{err}"
    );
    let trunc = tmp("trunc.binary");
    std::fs::write(&trunc, &std::fs::read(&path).unwrap()[..1000]).unwrap();
    let spec = format!("tabulated(file={})", trunc.display());
    let o = run(&["eval", &spec, "--wi", "0,0", "--wo", "0,0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("1000 bytes"));
    let o = run(&["albedo", "tabulated(file=)", "--theta-o", "10"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("empty path"));
    for f in [&path, &trunc] {
        let _ = std::fs::remove_file(f);
    }
}

/// `radiometry tabulate` of a colour spec writes its channels: gold's table read back gives gold's three values
/// at a node direction (θh = 0, θd = 30°), within the f64 → f32 rounding of the file.
#[test]
fn cli_tabulate_keeps_colour() {
    let path = tmp("cli_gold.binary");
    let p = path.to_str().unwrap();
    let gold = "ggx(alpha=0.3, fresnel=conductor(metal=Au))";
    let o = run(&["tabulate", gold, "--out", p]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let eval = |s: &str| -> Vec<f64> {
        let o = run(&["eval", s, "--wi", "30,0", "--wo", "30,180"]);
        assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout)
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect()
    };
    let (table, direct) = (eval(&format!("tabulated(file={p})")), eval(gold));
    assert_eq!((table.len(), direct.len()), (3, 3));
    for c in 0..3 {
        assert!(
            (table[c] - direct[c]).abs() <= 1e-5 * direct[c],
            "{table:?} vs {direct:?}"
        );
    }
    assert!(table[0] > 2.0 * table[2], "gold: {table:?}");
    std::fs::remove_file(&path).ok();
}
