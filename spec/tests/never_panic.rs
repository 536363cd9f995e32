//! Property: no input string makes a parser panic, and every error's span lies inside the spec.

use radiometry_spec::{parse_angles, parse_brdf, parse_lights};

proptest::proptest! {
    #[test]
    fn random_strings_never_panic(s in "\\PC{0,40}") {
        let _ = parse_brdf(&s).map_err(|e| e.to_string());
        let _ = parse_lights(&s).map_err(|e| e.to_string());
        let _ = parse_angles(&s).map_err(|e| e.to_string());
    }

    #[test]
    fn spec_like_strings_never_panic(s in "[a-z(),=+.0-9e -]{0,40}") {
        if let Err(e) = parse_brdf(&s) {
            let shown = e.to_string();
            proptest::prop_assert!(e.start <= e.end && e.end <= s.len());
            proptest::prop_assert!(shown.contains('^'));
        }
        let _ = parse_lights(&s).map_err(|e| e.to_string());
    }
}

proptest::proptest! {
    /// Every coloured plugin spec that parses builds in both spectra (the parser rejects what a plugin would); its
    /// RGB BRDF gives finite, non-negative values per channel, and a grey spec the monochrome value on every
    /// channel.
    #[test]
    fn parsed_specs_build_in_mono_and_rgb(
        name in proptest::sample::select(vec!["lambertian", "eon", "fon", "sheen", "ltc-sheen", "oren-nayar"]),
        r in 0.0f64..=1.0, g in 0.0f64..=1.0, b in 0.0f64..=1.0, s in 0.07f64..=1.0,
        ti in 0.0f32..89.0, to in 0.0f32..89.0, phi in 0.0f32..std::f32::consts::TAU, grey in proptest::bool::ANY,
    ) {
        let (g, b) = if grey { (r, r) } else { (g, b) };
        use radiometry::Brdf;
        use radiometry::glam::Vec3;
        use radiometry_spec::model::{build_brdf, build_brdf_rgb};
        let key = match name {
            "lambertian" => "albedo",
            "sheen" | "ltc-sheen" => "color",
            _ => "rho",
        };
        let second = match name {
            "lambertian" => String::new(),
            "sheen" | "ltc-sheen" => format!(", roughness={s}"),
            "oren-nayar" => format!(", sigma_rad={}", s * 0.3),
            _ => format!(", sigma={s}"),
        };
        let text = format!("{name}({key}=rgb({r}, {g}, {b}){second})");
        // The classic Oren–Nayar's energy bound is checked per channel by the parser.
        let spec = match parse_brdf(&text) {
            Ok(spec) => spec,
            Err(e) => {
                proptest::prop_assert!(name == "oren-nayar" && e.message.contains("energy gain"), "{}", e);
                return Ok(());
            }
        };
        let (m, c) = (build_brdf(&text, &spec), build_brdf_rgb(&text, &spec));
        proptest::prop_assert!(m.is_ok() && c.is_ok(), "{}", text);
        if let (Ok(m), Ok(c)) = (m, c) {
            let d = |t: f32, p: f32| {
                let t = t.to_radians();
                Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
            };
            let (wi, wo) = (d(ti, phi), d(to, 0.0));
            let f = c.eval(wi, wo);
            proptest::prop_assert!(f.is_finite() && f.min_element() >= 0.0, "{} {}", text, f);
            proptest::prop_assert_eq!(spec.is_grey(), grey || (r == g && g == b));
            if spec.is_grey() {
                proptest::prop_assert_eq!(f, Vec3::splat(m.eval(wi, wo)), "{}", text);
            }
        }
    }
}
