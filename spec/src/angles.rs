//! `THETA,PHI` direction arguments (degrees).

use crate::SpecError;
use crate::call::Parser;
use crate::error::err_span;
use crate::lex::Tok;

/// Parses `THETA,PHI` (degrees) as given to `--wi`/`--wo`.
pub fn parse_angles(text: &str) -> Result<(f64, f64), SpecError> {
    let mut p = Parser::new(text)?;
    let mut nums = Vec::new();
    loop {
        let t = p.peek().clone();
        match t.tok {
            Tok::Num(v) => {
                p.bump();
                nums.push((v, (t.start, t.end)));
            }
            _ => return Err(p.expected("an angle in degrees")),
        }
        if nums.len() == 2 {
            break;
        }
        if p.peek().tok != Tok::Comma {
            return Err(p.expected("`,` between THETA and PHI"));
        }
        p.bump();
    }
    p.finish()?;
    let (theta, ts) = nums[0];
    if !(0.0..=180.0).contains(&theta) {
        return Err(err_span(
            text,
            ts,
            format!("THETA = {theta} is outside [0, 180] degrees"),
        ));
    }
    Ok((theta, nums[1].0))
}
#[cfg(test)]
mod tests {
    use super::*;

    fn caret_of(e: &SpecError) -> &str {
        &e.spec[e.start..e.end]
    }

    #[test]
    fn angles() {
        assert_eq!(parse_angles("30,45").unwrap(), (30.0, 45.0));
        assert_eq!(parse_angles(" 0 , -90.5 ").unwrap(), (0.0, -90.5));
        for (t, bad) in [
            ("30", ""),
            ("30,", ""),
            ("a,1", "a"),
            ("190,0", "190"),
            ("1,2,3", ","),
        ] {
            let e = parse_angles(t).expect_err(t);
            assert_eq!(caret_of(&e), bad, "{t}: {e}");
        }
    }
}
