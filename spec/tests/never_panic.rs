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
