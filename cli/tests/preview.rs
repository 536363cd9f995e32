//! `radiometry preview`: the command writes a picture of the requested size and
//! format, and rejects bad input with exit code 2.

use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_radiometry"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("radiometry-preview-test-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d.join(name)
}

#[test]
fn preview_writes_a_png_of_the_requested_size() {
    let out = tmp("ball.png");
    let o = run(&[
        "preview",
        "lambertian",
        "--size",
        "16",
        "--samples",
        "8",
        "--no-progress",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("16×16"));
    let bytes = std::fs::read(&out).expect("png written");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: width and height, big-endian, at bytes 16..24; 8-bit greyscale.
    assert_eq!(&bytes[16..24], &[0, 0, 0, 16, 0, 0, 0, 16]);
    assert_eq!((bytes[24], bytes[25]), (8, 0));
    let _ = std::fs::remove_file(out);
}

#[test]
fn preview_writes_svg_by_extension_or_flag() {
    let out = tmp("ball.svg");
    let o = run(&[
        "preview",
        "ggx(alpha=0.3)",
        "--size",
        "8",
        "--samples",
        "2",
        "--no-progress",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(&out).expect("svg written");
    assert!(
        svg.starts_with("<svg") && svg.contains("data:image/png;base64,"),
        "{svg}"
    );
    let out2 = tmp("ball.picture");
    let o = run(&[
        "preview",
        "lambertian",
        "--size",
        "4",
        "--samples",
        "1",
        "--format",
        "svg",
        "--no-progress",
        "--out",
        out2.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    assert!(std::fs::read_to_string(&out2).unwrap().starts_with("<svg"));
    let _ = std::fs::remove_file(out);
    let _ = std::fs::remove_file(out2);
}

#[test]
fn preview_rejects_bad_input() {
    let out = tmp("bad.png");
    let o = run(&[
        "preview",
        "ggx(alpha=2)",
        "--size",
        "4",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&[
        "preview",
        "lambertian",
        "--size",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("size"));
    let o = run(&[
        "preview",
        "lambertian",
        "--sun-elevation",
        "-95",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
    let o = run(&["preview", "--help"]);
    let help = String::from_utf8_lossy(&o.stdout);
    for s in [
        "--samples",
        "--sun-elevation",
        "--format",
        "power heuristic",
        "coated(",
    ] {
        assert!(help.contains(s), "{s} missing from:\n{help}");
    }
}
