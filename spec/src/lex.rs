//! The tokenizer of the spec grammar: names, numbers, punctuation, each with its byte span.

use crate::SpecError;

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Tok {
    Ident(String),
    Num(f64),
    /// A double-quoted string (no escapes; it runs to the next `"`).
    Str(String),
    LParen,
    RParen,
    Comma,
    Eq,
    Plus,
    End,
}

#[derive(Clone, Debug)]
pub(crate) struct Token {
    pub(crate) tok: Tok,
    pub(crate) start: usize,
    pub(crate) end: usize,
}

pub(crate) fn describe(t: &Tok) -> String {
    match t {
        Tok::Ident(s) => format!("name `{s}`"),
        Tok::Num(_) => "a number".into(),
        Tok::Str(_) => "a string".into(),
        Tok::LParen => "`(`".into(),
        Tok::RParen => "`)`".into(),
        Tok::Comma => "`,`".into(),
        Tok::Eq => "`=`".into(),
        Tok::Plus => "`+`".into(),
        Tok::End => "end of input".into(),
    }
}

pub(crate) fn lex(spec: &str) -> Result<Vec<Token>, SpecError> {
    let err = |start: usize, end: usize, message: String| SpecError {
        spec: spec.to_string(),
        start,
        end,
        message,
    };
    let b = spec.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let start = i;
        let simple = match c {
            b'(' => Some(Tok::LParen),
            b')' => Some(Tok::RParen),
            b',' => Some(Tok::Comma),
            b'=' => Some(Tok::Eq),
            _ => None,
        };
        if let Some(t) = simple {
            out.push(Token {
                tok: t,
                start,
                end: i + 1,
            });
            i += 1;
            continue;
        }
        if c == b'"' {
            let Some(len) = spec[i + 1..].find('"') else {
                return Err(err(
                    start,
                    spec.len(),
                    "unterminated string (a `\"` opens it)".into(),
                ));
            };
            let end = i + 1 + len + 1;
            out.push(Token {
                tok: Tok::Str(spec[i + 1..end - 1].to_string()),
                start,
                end,
            });
            i = end;
            continue;
        }
        if c.is_ascii_alphabetic() || c == b'_' {
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'-') {
                i += 1;
            }
            out.push(Token {
                tok: Tok::Ident(spec[start..i].to_string()),
                start,
                end: i,
            });
            continue;
        }
        let sign_then_digit = (c == b'+' || c == b'-')
            && i + 1 < b.len()
            && (b[i + 1].is_ascii_digit() || b[i + 1] == b'.')
            && !matches!(
                out.last().map(|t| &t.tok),
                Some(Tok::RParen | Tok::Ident(_) | Tok::Num(_))
            );
        if c.is_ascii_digit() || c == b'.' || sign_then_digit {
            if c == b'+' || c == b'-' {
                i += 1;
            }
            let mut digits = 0;
            while i < b.len() && b[i].is_ascii_digit() {
                i += 1;
                digits += 1;
            }
            if i < b.len() && b[i] == b'.' {
                i += 1;
                while i < b.len() && b[i].is_ascii_digit() {
                    i += 1;
                    digits += 1;
                }
            }
            if digits > 0 && i < b.len() && (b[i] == b'e' || b[i] == b'E') {
                let mut j = i + 1;
                if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
                    j += 1;
                }
                let exp_start = j;
                while j < b.len() && b[j].is_ascii_digit() {
                    j += 1;
                }
                if j > exp_start {
                    i = j;
                } else {
                    return Err(err(start, j, "malformed exponent in number".into()));
                }
            }
            // A number glued to letters (`1x`) is one bad token.
            if i < b.len() && (b[i].is_ascii_alphabetic() || b[i] == b'_') {
                let mut j = i;
                while j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] == b'_' || b[j] == b'.') {
                    j += 1;
                }
                return Err(err(start, j, format!("malformed number `{}`", &spec[start..j])));
            }
            if digits == 0 {
                return Err(err(start, i, format!("malformed number `{}`", &spec[start..i])));
            }
            let text = &spec[start..i];
            let v: f64 = text
                .parse()
                .map_err(|_| err(start, i, format!("malformed number `{text}`")))?;
            if !v.is_finite() {
                return Err(err(start, i, format!("number `{text}` is out of range")));
            }
            out.push(Token {
                tok: Tok::Num(v),
                start,
                end: i,
            });
            continue;
        }
        if c == b'+' {
            out.push(Token {
                tok: Tok::Plus,
                start,
                end: i + 1,
            });
            i += 1;
            continue;
        }
        // Unknown character (possibly multi-byte): underline the whole char.
        let ch = spec[start..].chars().next().unwrap_or('?');
        return Err(err(
            start,
            start + ch.len_utf8(),
            format!("unexpected character `{}`", ch.escape_debug()),
        ));
    }
    out.push(Token {
        tok: Tok::End,
        start: spec.len(),
        end: spec.len(),
    });
    Ok(out)
}
