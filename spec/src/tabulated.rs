//! `tabulated(file=PATH)`: a BRDF read from a MERL `.binary` file.
//!
//! A path is not a token of the general grammar (it may hold `/`, `.`,
//! `-`, spaces, commas), so this form is recognised before the call
//! parser: the spec is `tabulated`, `(`, `file`, `=`, the path, `)`, with
//! optional whitespace between tokens. The path runs to the **last** `)`
//! of the spec, with surrounding whitespace trimmed; a path wrapped in
//! double quotes (`file="my dir/x.binary"`) is taken verbatim between the
//! quotes. [`BrdfSpec::Tabulated`](crate::BrdfSpec::Tabulated) stores the
//! byte span of the path in the spec text (so the spec stays `Copy`);
//! [`BrdfSpec::file`](crate::BrdfSpec::file) returns it. Reading the file
//! is [`merl::load_tabulated`](crate::merl::load_tabulated)'s job.

use crate::{BrdfSpec, SpecError};

/// `Some(result)` when `spec` is a `tabulated(...)` call, `None` otherwise
/// (the general parser then handles it).
pub(crate) fn parse(spec: &str) -> Option<Result<BrdfSpec, SpecError>> {
    let lead = spec.len() - spec.trim_start().len();
    let rest = &spec[lead..];
    let name = "tabulated";
    let after_name = rest.strip_prefix(name)?;
    // `tabulated_x` or `tabulatedfoo` is another name.
    if after_name
        .bytes()
        .next()
        .is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'-')
    {
        return None;
    }
    let err = |start: usize, end: usize, message: &str| {
        Some(Err(SpecError {
            spec: spec.to_string(),
            start,
            end,
            message: message.to_string(),
        }))
    };
    let name_span = (lead, lead + name.len());
    let mut i = name_span.1;
    let skip_ws = |mut i: usize| {
        while spec.as_bytes().get(i).is_some_and(|b| b.is_ascii_whitespace()) {
            i += 1;
        }
        i
    };
    i = skip_ws(i);
    if spec.as_bytes().get(i) != Some(&b'(') {
        return err(
            name_span.0,
            name_span.1,
            "tabulated needs a file: tabulated(file=PATH)",
        );
    }
    i = skip_ws(i + 1);
    let key = "file";
    if !spec[i..].starts_with(key) {
        let end = spec[i..]
            .find(|c: char| c == '=' || c == ')' || c.is_whitespace())
            .map_or(spec.len(), |k| i + k);
        return err(
            i,
            end.max(i),
            "expected `file=PATH` (the only parameter of tabulated)",
        );
    }
    let key_end = i + key.len();
    i = skip_ws(key_end);
    if spec.as_bytes().get(i) != Some(&b'=') {
        return err(i, (i + 1).min(spec.len()), "expected `=` after `file`");
    }
    i = skip_ws(i + 1);
    let Some(close) = spec.rfind(')').filter(|&c| c >= i) else {
        return err(spec.len(), spec.len(), "expected `)` after the path");
    };
    let tail = close + 1;
    if !spec[tail..].trim().is_empty() {
        let t = skip_ws(tail);
        return err(t, spec.len(), "unexpected text after `)`");
    }
    let raw = &spec[i..close];
    let trimmed_start = i + (raw.len() - raw.trim_start().len());
    let trimmed_end = i + raw.trim_end().len();
    let (start, end) = if spec[trimmed_start..trimmed_end].starts_with('"') {
        let inner = trimmed_start + 1;
        match spec[inner..trimmed_end].find('"') {
            Some(q) if inner + q + 1 == trimmed_end => (inner, inner + q),
            _ => {
                return err(
                    trimmed_start,
                    trimmed_end.max(trimmed_start + 1),
                    "unterminated or misplaced `\"` in the path",
                );
            }
        }
    } else {
        (trimmed_start, trimmed_end)
    };
    if start >= end {
        return err(start, start, "empty path: tabulated(file=PATH)");
    }
    Some(Ok(BrdfSpec::Tabulated { file: (start, end) }))
}

#[cfg(test)]
mod tests {
    use crate::{BrdfSpec, parse_brdf};

    fn path(spec: &str) -> String {
        let s = parse_brdf(spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
        s.file(spec).expect("a tabulated spec").to_string()
    }

    #[test]
    fn paths() {
        assert_eq!(path("tabulated(file=x.binary)"), "x.binary");
        assert_eq!(
            path("  tabulated ( file = /tmp/a b/c-1.binary )  "),
            "/tmp/a b/c-1.binary"
        );
        assert_eq!(path("tabulated(file=dir(1)/x,y.binary)"), "dir(1)/x,y.binary");
        assert_eq!(path(r#"tabulated(file=" spaced .binary")"#), " spaced .binary");
        assert_eq!(
            parse_brdf("tabulated(file=x)").unwrap(),
            BrdfSpec::Tabulated { file: (15, 16) }
        );
        assert_eq!(BrdfSpec::Lambertian { albedo: [1.0; 3] }.file("x"), None);
    }

    #[test]
    fn errors_point_at_the_problem() {
        for (spec, under, msg) in [
            ("tabulated", "tabulated", "needs a file"),
            ("tabulated(fil=x)", "fil", "expected `file=PATH`"),
            ("tabulated(file x)", "x", "expected `=`"),
            ("tabulated(file=)", "", "empty path"),
            ("tabulated(file=x", "", "expected `)`"),
            ("tabulated(file=x) y", "y", "unexpected text"),
            (r#"tabulated(file="x)"#, "\"x", "unterminated"),
        ] {
            let e = parse_brdf(spec).unwrap_err();
            assert_eq!(&e.spec[e.start..e.end], under, "{spec}: {e}");
            assert!(e.message.contains(msg), "{spec}: {e}");
            // Display never panics and underlines.
            assert!(e.to_string().contains('^'), "{e}");
        }
        // Other names are untouched.
        assert!(
            parse_brdf("tabulatedx(file=1)")
                .unwrap_err()
                .message
                .contains("unknown BRDF")
        );
    }
}
