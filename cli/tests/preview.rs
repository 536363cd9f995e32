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

/// IHDR colour type of a PNG file (0 grey, 2 RGB) and its width.
fn png_kind(bytes: &[u8]) -> (u8, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    (
        bytes[25],
        u32::from_be_bytes([bytes[16], bytes[17], bytes[18], bytes[19]]),
    )
}

#[test]
fn preview_writes_colour_materials_spectra_and_the_camera() {
    let out = tmp("colour.png");
    let o = out.to_str().unwrap();
    let common = ["--size", "8", "--samples", "2", "--no-progress", "--out", o];
    // A grey spec stays an 8-bit grey PNG; with a sky colour it becomes RGB.
    let r = run(&[&["preview", "lambertian"], &common[..]].concat());
    assert_eq!(r.status.code(), Some(0));
    assert_eq!(png_kind(&std::fs::read(&out).unwrap()), (0, 8));
    for extra in [
        &["lambertian", "--sky-colour", "0.5,0.7,1"][..],
        &["--material", "gold"],
        &["--material", "red-plastic", "--daylight"],
        &["--material", "copper", "--spectral", "4"],
        &["eon(rho=0.5, sigma=0.5)", "--spectral", "1", "--rgb"],
    ] {
        let r = run(&[&["preview"], extra, &common[..]].concat());
        assert_eq!(
            r.status.code(),
            Some(0),
            "{extra:?}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        assert_eq!(png_kind(&std::fs::read(&out).unwrap()), (2, 8), "{extra:?}");
    }
    // The camera: camera | gap | observer under a 14-pixel label band, and the report.
    let r = run(&[
        &[
            "preview",
            "--material",
            "gold",
            "--camera",
            "bayer",
            "--light",
            "a",
        ],
        &common[..],
    ]
    .concat());
    assert_eq!(r.status.code(), Some(0), "{}", String::from_utf8_lossy(&r.stderr));
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(png_kind(&bytes), (2, 8 + 8 + 8));
    assert_eq!(
        u32::from_be_bytes([bytes[20], bytes[21], bytes[22], bytes[23]]),
        8 + 14
    );
    let text = String::from_utf8_lossy(&r.stdout);
    assert!(text.contains("dE*ab") && text.contains("EMVA SNR"), "{text}");
    let _ = std::fs::remove_file(&out);
}

#[test]
fn preview_rejects_bad_colour_input() {
    let out = tmp("bad-colour.png");
    let o = out.to_str().unwrap();
    for args in [
        &["preview", "--out", o][..],
        &["preview", "lambertian", "--material", "gold", "--out", o],
        &["preview", "--material", "silver", "--out", o],
        &["preview", "lambertian", "--sky-colour", "1,2", "--out", o],
        &["preview", "lambertian", "--sky-colour", "1,-2,0", "--out", o],
        &["preview", "lambertian", "--spectral", "3", "--out", o],
        &[
            "preview",
            "--material",
            "gold",
            "--camera",
            "bayer",
            "--spectral",
            "4",
            "--out",
            o,
        ],
        &[
            "preview",
            "--material",
            "gold",
            "--camera",
            "prism",
            "--camera-exposure",
            "0",
            "--out",
            o,
        ],
        &["preview", "openpbr", "--textured", "--rgb", "--out", o],
        &[
            "preview",
            "lambertian",
            "--env",
            "/nonexistent/sky.hdr",
            "--out",
            o,
        ],
        &[
            "preview",
            "lambertian",
            "--env",
            "/nonexistent/sky.hdr",
            "--spectral",
            "4",
            "--out",
            o,
        ],
    ] {
        let r = run(args);
        assert_eq!(
            r.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
    }
    assert!(!out.exists());
}

#[test]
fn preview_lights_by_an_hdr_environment_map() {
    // A constant 8 × 4 Radiance file (RGBE, written by hand: header, then flat scanlines of
    // 4 bytes per texel; 0.5 = mantissa 128, exponent 128) lights a white Lambertian as a
    // uniform sky of 0.5: the furnace ball vanishes into the background.
    let path = tmp("grey.hdr");
    let mut bytes = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n".to_vec();
    for _ in 0..32 {
        bytes.extend_from_slice(&[128, 128, 128, 128]);
    }
    std::fs::write(&path, bytes).unwrap();
    let out = tmp("env.png");
    let r = run(&[
        "preview",
        "lambertian",
        "--env",
        path.to_str().unwrap(),
        "--sun-irradiance",
        "0",
        "--size",
        "8",
        "--samples",
        "2",
        "--no-progress",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(r.status.code(), Some(0), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(String::from_utf8_lossy(&r.stdout).contains("environment 8×4 texels"));
    let png = std::fs::read(&out).unwrap();
    assert_eq!(png_kind(&png), (2, 8));
    let _ = std::fs::remove_file(out);
    let _ = std::fs::remove_file(path);
}

/// The 8-bit samples of a PNG file.
fn png_samples(path: &std::path::Path) -> Vec<u8> {
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

#[test]
fn a_grey_spec_gives_the_same_bytes_in_rgb() {
    let (grey, rgb) = (tmp("same-grey.png"), tmp("same-rgb.png"));
    let spec = "coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))";
    for (out, extra) in [(&grey, None), (&rgb, Some("--rgb"))] {
        let mut args = vec!["preview", spec, "--size", "12", "--samples", "4", "--no-progress"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let r = run(&args);
        assert_eq!(r.status.code(), Some(0), "{}", String::from_utf8_lossy(&r.stderr));
    }
    let (g, c) = (png_samples(&grey), png_samples(&rgb));
    assert_eq!(c.len(), 3 * g.len());
    assert!(g.iter().zip(c.chunks(3)).all(|(g, c)| c == [*g; 3]));
    let _ = std::fs::remove_file(grey);
    let _ = std::fs::remove_file(rgb);
}

/// `--mtlx FILE [--material NAME]`: an OpenPBR material from a MaterialX
/// document renders in colour; skipped inputs are named in warnings; a
/// texture, an unknown material and an ambiguous document are refused; a
/// colour spec renders in RGB and its red ball is red.
#[test]
fn preview_reads_materialx_documents_and_colour_specs() {
    let doc = tmp("two.mtlx");
    std::fs::write(
        &doc,
        r#"<?xml version="1.0"?><materialx version="1.39">
          <surfacematerial name="Red" type="material">
            <input name="surfaceshader" type="surfaceshader" nodename="red_s" />
          </surfacematerial>
          <surfacematerial name="Tex" type="material">
            <input name="surfaceshader" type="surfaceshader" nodename="tex_s" />
          </surfacematerial>
          <open_pbr_surface name="red_s" type="surfaceshader">
            <input name="base_color" type="color3" value="0.8, 0.05, 0.05" />
            <input name="transmission_weight" type="float" value="0.5" />
          </open_pbr_surface>
          <open_pbr_surface name="tex_s" type="surfaceshader">
            <input name="base_color" type="color3" nodename="image1" />
          </open_pbr_surface>
        </materialx>"#,
    )
    .unwrap();
    let d = doc.to_str().unwrap();
    let out = tmp("mtlx.png");
    let o = run(&[
        "preview",
        "--mtlx",
        d,
        "--material",
        "Red",
        "--size",
        "16",
        "--samples",
        "8",
        "--no-progress",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning") && err.contains("transmission_weight"),
        "{err}"
    );
    let px = png_samples(&out);
    assert_eq!(png_kind(&std::fs::read(&out).unwrap()).0, 2, "an RGB picture");
    // The centre pixel of the red ball: red above green and blue.
    let c = (8 * 16 + 8) * 3;
    assert!(px[c] > px[c + 1] && px[c] > px[c + 2], "{:?}", &px[c..c + 3]);
    for (args, needle) in [
        (vec!["--material", "Tex"], "connected"),
        (vec!["--material", "Blue"], "no material `Blue`"),
        (vec![], "choose a material"),
    ] {
        let mut all = vec!["preview", "--mtlx", d, "--out", out.to_str().unwrap()];
        all.extend(args);
        let o = run(&all);
        assert_eq!(o.status.code(), Some(2));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(needle), "{needle}: {err}");
    }
    let o = run(&[
        "preview",
        "lambertian",
        "--mtlx",
        d,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_file(out);
    let _ = std::fs::remove_file(doc);
}

/// A MaterialX document with constant inputs renders the same ball as the
/// equivalent `openpbr(...)` spec, pixel for pixel.
#[test]
fn a_materialx_ball_is_its_openpbr_spec_ball() {
    let doc = tmp("same.mtlx");
    std::fs::write(
        &doc,
        r#"<?xml version="1.0"?><materialx version="1.39" colorspace="lin_rec709">
          <open_pbr_surface name="paint" type="surfaceshader">
            <input name="base_color" type="color3" value="0.8, 0.05, 0.05" />
            <input name="specular_roughness" type="float" value="0.2" />
            <input name="coat_weight" type="float" value="0.5" />
          </open_pbr_surface>
        </materialx>"#,
    )
    .unwrap();
    let (a, b) = (tmp("same-mtlx.png"), tmp("same-spec.png"));
    let common = ["--size", "16", "--samples", "8", "--no-progress", "--daylight"];
    let mut args = vec![
        "preview",
        "--mtlx",
        doc.to_str().unwrap(),
        "--out",
        a.to_str().unwrap(),
    ];
    args.extend(common);
    assert_eq!(run(&args).status.code(), Some(0));
    let mut args = vec![
        "preview",
        "openpbr(base_color=rgb(0.8, 0.05, 0.05), specular_roughness=0.2, coat_weight=0.5)",
        "--out",
        b.to_str().unwrap(),
    ];
    args.extend(common);
    assert_eq!(run(&args).status.code(), Some(0));
    let (pa, pb) = (png_samples(&a), png_samples(&b));
    assert_eq!(pa.len(), 16 * 16 * 3);
    assert_eq!(pa, pb);
    for f in [a, b, doc] {
        let _ = std::fs::remove_file(f);
    }
}
