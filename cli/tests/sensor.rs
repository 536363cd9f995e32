//! End-to-end tests of `radiometry sensor read` and `radiometry sensor edge`.

use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_radiometry"))
        .args(args)
        .output()
        .expect("run radiometry")
}

fn json(o: &Output) -> serde_json::Value {
    assert!(
        o.status.success(),
        "exit {:?}, stderr: {}",
        o.status,
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("stdout is one JSON object")
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("key {key} missing or not a number in {v}"))
}

/// Mean DN of a monochromatic pixel, by hand in f64 (EMVA 1288 §2.1):
/// E = lux / (683 lm/W · V(λ)), photons = E·A·fill·t·λ/(hc), electrons = η·photons, DN = K·electrons.
#[allow(clippy::too_many_arguments)] // one argument per factor of the formula
fn hand_mean_dn(
    lux: f64,
    v_lambda: f64,
    lambda_nm: f64,
    area: f64,
    fill: f64,
    t: f64,
    qe: f64,
    k: f64,
) -> f64 {
    const H: f64 = 6.626_070_15e-34;
    const C: f64 = 299_792_458.0;
    let e = lux / (683.0 * v_lambda);
    let photons = e * area * fill * t * lambda_nm * 1e-9 / (H * C);
    k * qe * photons
}

#[test]
fn read_json_shape_and_mono_555_matches_hand_computation() {
    // V(555 nm) = 1.0000 in the CIE 1924 photopic table (CIE 015:2018 Table T.2 lists 1.000000 at 555 nm).
    let cases = [
        // lux, exposure, qe, gain, area, fill
        (100.0, 0.01, 0.5, 0.1, 25e-12, 1.0),
        (2.5, 0.1, 0.8, 0.25, 9e-12, 0.6),
        (1000.0, 0.001, 0.3, 1.0, 1.44e-12, 0.5),
    ];
    for (lux, t, qe, k, area, fill) in cases {
        let o = run(&[
            "sensor",
            "read",
            "--light",
            "mono:555",
            "--lux",
            &lux.to_string(),
            "--exposure",
            &t.to_string(),
            "--qe",
            &qe.to_string(),
            "--gain",
            &k.to_string(),
            "--pixel-area",
            &area.to_string(),
            "--fill-factor",
            &fill.to_string(),
            "--bits",
            "16",
            "--full-well",
            "1e6",
            "--format",
            "json",
        ]);
        let j = json(&o);
        for key in [
            "mean_electrons",
            "mean_dn",
            "predicted_variance_dn",
            "irradiance_w_m2",
            "sample_mean_dn",
        ] {
            assert!(j[key].is_number(), "{key} in {j}");
        }
        assert!(j["readings"].is_array());
        assert_eq!(j["readings"].as_array().unwrap().len(), 1);
        assert!(
            j["sample_variance_dn"].is_null(),
            "one reading has no sample variance"
        );
        let want = hand_mean_dn(lux, 1.0, 555.0, area, fill, t, qe, k);
        let got = num(&j, "mean_dn");
        assert!(
            (got - want).abs() <= 1e-5 * want,
            "mean_dn {got} vs hand {want} (lux {lux})"
        );
        let e = num(&j, "mean_electrons");
        assert!((e * k - want).abs() <= 1e-5 * want, "mean_electrons {e}");
        let irr = num(&j, "irradiance_w_m2");
        assert!((irr - lux / 683.0).abs() <= 1e-6 * lux / 683.0);
        // σ²_y = K²(σ²_d + μ_e) + 1/12 with σ_d = 0.
        let pv = num(&j, "predicted_variance_dn");
        let want_v = k * k * e + 1.0 / 12.0;
        assert!(
            (pv - want_v).abs() <= 1e-5 * want_v,
            "predicted variance {pv} vs {want_v}"
        );
    }
}

#[test]
fn read_repeats_follow_photon_transfer() {
    // 20 000 readings: the sample variance of DN has relative standard error ≈ √(2/(n−1)) ≈ 1 %
    // (plus a little excess kurtosis from the Poisson part), so 5 % is a > 4σ bound; the sample mean
    // has standard error σ/√n.
    let o = run(&[
        "sensor",
        "read",
        "--light",
        "d65",
        "--lux",
        "50",
        "--exposure",
        "0.0001",
        "--gain",
        "0.5",
        "--dark-noise",
        "6",
        "--repeats",
        "20000",
        "--seed",
        "7",
        "--format",
        "json",
    ]);
    let j = json(&o);
    let mu = num(&j, "mean_dn");
    let e = num(&j, "mean_electrons");
    assert!(
        e > 100.0 && mu > 50.0,
        "enough signal to avoid clipping at 0: {j}"
    );
    assert!(!j["saturated"].as_bool().unwrap());
    let pv = num(&j, "predicted_variance_dn");
    assert!((pv - (0.25 * (36.0 + e) + 1.0 / 12.0)).abs() < 1e-4 * pv);
    let sv = num(&j, "sample_variance_dn");
    let sm = num(&j, "sample_mean_dn");
    assert!(
        (sv / pv - 1.0).abs() < 0.05,
        "sample variance {sv} vs predicted {pv}"
    );
    assert!(
        (sm - mu).abs() < 5.0 * (pv / 20000.0).sqrt(),
        "sample mean {sm} vs {mu}"
    );
    assert_eq!(j["readings"].as_array().unwrap().len(), 1000);
}

#[test]
fn read_d65_and_a_scale_to_the_requested_illuminance() {
    // Doubling the lux doubles the electrons (linearity) for both broadband lights, and A, being
    // redder, gives more photons per lux than D65 for a flat QE (more energy outside V's peak,
    // and more photons per joule at long wavelengths).
    let get = |light: &str, lux: &str| {
        let j = json(&run(&[
            "sensor", "read", "--light", light, "--lux", lux, "--format", "json",
        ]));
        num(&j, "mean_electrons")
    };
    for light in ["d65", "a"] {
        let (e1, e2) = (get(light, "10"), get(light, "20"));
        assert!((e2 / e1 - 2.0).abs() < 1e-5, "{light}: {e1} {e2}");
    }
    assert!(get("a", "10") > get("d65", "10"));
}

#[test]
fn read_bad_inputs_exit_2_without_panic() {
    let bad: &[&[&str]] = &[
        &["--lux", "-5"],
        &["--lux", "NaN"],
        &["--lux", "inf"],
        &["--lux", "1e300"],
        &["--lux", "10", "--bits", "33"],
        &["--lux", "10", "--bits", "0"],
        &["--lux", "10", "--qe", "1.5"],
        &["--lux", "10", "--gain", "0"],
        &["--lux", "10", "--exposure", "-1"],
        &["--lux", "10", "--dark-noise", "-1"],
        &["--lux", "10", "--pixel-area", "0"],
        &["--lux", "10", "--fill-factor", "0"],
        &["--lux", "10", "--repeats", "0"],
        &["--lux", "10", "--light", "mono:900"],
        &["--lux", "10", "--light", "mono:abc"],
        &["--lux", "10", "--light", "mono:nan"],
        &["--lux", "10", "--light", "laser"],
        &["--lux", "1e30", "--exposure", "1e30"],
    ];
    for args in bad {
        let mut all = vec!["sensor", "read"];
        all.extend_from_slice(args);
        let o = run(&all);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: stderr {err}");
        assert!(err.contains("error"), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn read_zero_light_reads_zero() {
    let j = json(&run(&[
        "sensor",
        "read",
        "--lux",
        "0",
        "--repeats",
        "10",
        "--format",
        "json",
    ]));
    assert_eq!(num(&j, "mean_electrons"), 0.0);
    assert_eq!(num(&j, "sample_mean_dn"), 0.0);
}

fn tmp_dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("radiometry-sensor-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn edge_writes_picture_and_orders_false_colour() {
    for (pattern, format) in [("rggb", "svg"), ("bggr", "png"), ("grbg", "svg"), ("gbrg", "png")] {
        let dir = tmp_dir(pattern);
        let o = run(&[
            "sensor",
            "edge",
            "--out",
            dir.to_str().unwrap(),
            "--size",
            "32",
            "--pattern",
            pattern,
            "--format",
            format,
            "--json",
        ]);
        let j = json(&o);
        let file = std::path::PathBuf::from(j["file"].as_str().unwrap());
        assert_eq!(file, dir.join(format!("edge.{format}")));
        let bytes = std::fs::read(&file).expect("picture written");
        let e = &j["false_colour_energy"];
        let (bil, mal, three, wheel, stacked) = (
            e["bilinear"].as_f64().unwrap(),
            e["malvar"].as_f64().unwrap(),
            e["three_chip"].as_f64().unwrap(),
            e["filter_wheel"].as_f64().unwrap(),
            e["stacked"].as_f64().unwrap(),
        );
        println!("{pattern}: bilinear {bil}, malvar {mal}, 3-chip {three}, wheel {wheel}, stacked {stacked}");
        assert!(bil > mal, "{pattern}: bilinear {bil} ≤ malvar {mal}");
        assert!(mal > three, "{pattern}: malvar {mal} ≤ 3-chip {three}");
        assert!(three < 1e-9, "{pattern}: 3-chip false colour {three}");
        assert!(stacked < 1e-9, "{pattern}: stacked false colour {stacked}");
        // The edge moves during the wheel's R, G, B slots: colour fringes.
        assert!(wheel > mal, "{pattern}: filter wheel {wheel} ≤ malvar {mal}");
        if format == "svg" {
            let s = String::from_utf8(bytes).unwrap();
            assert!(s.starts_with("<svg") && s.trim_end().ends_with("</svg>"));
            // 5 panels of 32×32 pixel rects, plus the background.
            assert_eq!(s.matches("<rect").count(), 5 * 32 * 32 + 1);
            for label in [
                "bilinear",
                "Malvar-He-Cutler",
                "3-chip",
                "Filter wheel",
                "Stacked (Foveon)",
            ] {
                assert!(s.contains(label), "label {label}");
            }
        } else {
            check_png(&bytes);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// PNG check: signature and chunk CRCs (CRC-32 computed here), IHDR (8-bit RGB, five panels wide), then
/// the image decoded (the `png` crate's decoder) to the IHDR size with white, black and coloured pixels.
fn check_png(b: &[u8]) {
    fn crc(data: &[u8]) -> u32 {
        // Table-driven CRC-32 (ISO 3309, reflected 0xEDB88320), built here.
        let table: Vec<u32> = (0..256u32)
            .map(|n| {
                (0..8).fold(n, |c, _| {
                    if c & 1 == 1 {
                        0xEDB8_8320 ^ (c >> 1)
                    } else {
                        c >> 1
                    }
                })
            })
            .collect();
        !data
            .iter()
            .fold(!0u32, |c, &x| table[((c ^ x as u32) & 0xFF) as usize] ^ (c >> 8))
    }
    assert_eq!(&b[..8], &[0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A]);
    let mut i = 8;
    let (mut w, mut h) = (0usize, 0usize);
    let mut kinds = Vec::new();
    while i < b.len() {
        let len = u32::from_be_bytes(b[i..i + 4].try_into().unwrap()) as usize;
        let kind = &b[i + 4..i + 8];
        let data = &b[i + 8..i + 8 + len];
        let c = u32::from_be_bytes(b[i + 8 + len..i + 12 + len].try_into().unwrap());
        assert_eq!(
            c,
            crc(&b[i + 4..i + 8 + len]),
            "CRC of {}",
            String::from_utf8_lossy(kind)
        );
        if kind == b"IHDR" {
            w = u32::from_be_bytes(data[0..4].try_into().unwrap()) as usize;
            h = u32::from_be_bytes(data[4..8].try_into().unwrap()) as usize;
            assert_eq!(&data[8..13], &[8, 2, 0, 0, 0], "8-bit RGB");
        }
        kinds.push(String::from_utf8_lossy(kind).into_owned());
        i += 12 + len;
    }
    assert_eq!(kinds.first().map(String::as_str), Some("IHDR"));
    assert_eq!(kinds.last().map(String::as_str), Some("IEND"));
    assert!(kinds.iter().any(|k| k == "IDAT"));
    assert!(w > 5 * 32 && h > 32);
    let mut reader = png::Decoder::new(std::io::Cursor::new(b))
        .read_info()
        .expect("decodable PNG");
    let mut raw = vec![0u8; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut raw).expect("one frame");
    assert_eq!((info.width as usize, info.height as usize), (w, h));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let px: Vec<&[u8]> = raw[..3 * w * h].chunks(3).collect();
    // Some pixels are pure white and pure black (the edge target), some are coloured (bilinear).
    assert!(px.iter().any(|p| *p == [255, 255, 255]));
    assert!(px.iter().any(|p| *p == [0, 0, 0]));
    assert!(px.iter().any(|p| p[0] != p[1] || p[1] != p[2]));
}

#[test]
fn edge_bad_size_exits_2() {
    for size in ["0", "4", "100000"] {
        let o = run(&[
            "sensor",
            "edge",
            "--size",
            size,
            "--out",
            "/nonexistent-should-not-be-created",
        ]);
        assert_eq!(o.status.code(), Some(2), "size {size}");
    }
}

#[test]
fn help_documents_the_sensor_commands() {
    let o = run(&["sensor", "--help"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains("read") && s.contains("edge"), "{s}");
    let o = run(&["sensor", "read", "--help"]);
    let s = String::from_utf8_lossy(&o.stdout);
    for key in [
        "--lux",
        "--light",
        "mono:<nm>",
        "predicted_variance_dn",
        "--repeats",
    ] {
        assert!(s.contains(key), "{key} missing from help: {s}");
    }
}
