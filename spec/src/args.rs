//! Argument checking of one call: names, types, duplicates, ranges.

use crate::SpecError;
use crate::call::{Arg, Call, Value};
use crate::error::err_span;

/// A string argument and its span.
pub(crate) type Spanned<'a> = (&'a str, (usize, usize));

/// Reads the arguments of one call, checking names, types, duplicates and
/// ranges, and remembering spans for later errors.
pub(crate) struct Args<'a> {
    spec: &'a str,
    call: &'a Call,
    used: Vec<bool>,
}

impl<'a> Args<'a> {
    pub(crate) fn new(spec: &'a str, call: &'a Call, allowed: &[&str]) -> Result<Self, SpecError> {
        for (i, a) in call.args.iter().enumerate() {
            if !allowed.contains(&a.key.as_str()) {
                let list = if allowed.is_empty() {
                    "it takes no parameters".to_string()
                } else {
                    format!("expected one of: {}", allowed.join(", "))
                };
                return Err(err_span(
                    spec,
                    a.key_span,
                    format!("unknown parameter `{}` for `{}` ({list})", a.key, call.name),
                ));
            }
            if call.args[..i].iter().any(|b| b.key == a.key) {
                return Err(err_span(
                    spec,
                    a.key_span,
                    format!("parameter `{}` given twice", a.key),
                ));
            }
        }
        Ok(Args {
            spec,
            call,
            used: vec![false; call.args.len()],
        })
    }

    pub(crate) fn find(&mut self, key: &str) -> Option<&'a Arg> {
        let i = self.call.args.iter().position(|a| a.key == key)?;
        self.used[i] = true;
        Some(&self.call.args[i])
    }

    /// A number in `[min, max]` (`open_min`: excludes `min`), or `default`
    /// (`None`: required).
    pub(crate) fn num(
        &mut self,
        key: &str,
        default: Option<f64>,
        min: f64,
        max: f64,
        open_min: bool,
    ) -> Result<f64, SpecError> {
        let Some(a) = self.find(key) else {
            return default.ok_or_else(|| {
                err_span(
                    self.spec,
                    self.call.name_span,
                    format!("`{}` needs parameter `{key}`", self.call.name),
                )
            });
        };
        match &a.value {
            Value::Num(v, span) => {
                let bad_low = if open_min { *v <= min } else { *v < min };
                if bad_low || *v > max {
                    let lb = if open_min { "(" } else { "[" };
                    Err(err_span(
                        self.spec,
                        *span,
                        format!("`{key}` = {v} is outside {lb}{min}, {max}]"),
                    ))
                } else {
                    Ok(*v)
                }
            }
            Value::Call(c) => Err(err_span(self.spec, c.span, format!("`{key}` must be a number"))),
            Value::Rgb(_, span) => Err(err_span(
                self.spec,
                *span,
                format!("`{key}` must be one number, not a colour"),
            )),
            Value::Str(_, span) => Err(err_span(
                self.spec,
                *span,
                format!("`{key}` must be a number, not a string"),
            )),
        }
    }

    /// A colour in `[0, 1]` per channel: one number (grey) or `rgb(R, G, B)`;
    /// `default` when absent (`None`: required).
    pub(crate) fn colour(&mut self, key: &str, default: Option<f64>) -> Result<[f64; 3], SpecError> {
        let Some(a) = self.find(key) else {
            return default.map(|v| [v; 3]).ok_or_else(|| {
                err_span(
                    self.spec,
                    self.call.name_span,
                    format!("`{}` needs parameter `{key}`", self.call.name),
                )
            });
        };
        let (c, span) = match &a.value {
            Value::Num(v, span) => ([*v; 3], *span),
            Value::Rgb(c, span) => (*c, *span),
            Value::Str(_, span) => {
                return Err(err_span(
                    self.spec,
                    *span,
                    format!("`{key}` must be a number or rgb(R, G, B), not a string"),
                ));
            }
            Value::Call(c) => {
                return Err(err_span(
                    self.spec,
                    c.span,
                    format!("`{key}` must be a number or rgb(R, G, B)"),
                ));
            }
        };
        if let Some(v) = c.iter().find(|v| !(0.0..=1.0).contains(*v)) {
            return Err(err_span(
                self.spec,
                span,
                format!("`{key}` = {v} is outside [0, 1] (a colour channel)"),
            ));
        }
        Ok(c)
    }

    /// Whether the call has argument `key` (without marking it used).
    pub(crate) fn has(&self, key: &str) -> bool {
        self.call.args.iter().any(|a| a.key == key)
    }

    /// A string `"..."` and its span, or `None` when absent.
    pub(crate) fn string(&mut self, key: &str) -> Result<Option<Spanned<'a>>, SpecError> {
        let Some(a) = self.find(key) else {
            return Ok(None);
        };
        match &a.value {
            Value::Str(s, span) => Ok(Some((s.as_str(), *span))),
            v => Err(err_span(
                self.spec,
                v.span(),
                format!("`{key}` must be a string in double quotes"),
            )),
        }
    }

    /// A nested call (or bare name) value.
    pub(crate) fn call_value(&mut self, key: &str) -> Result<Option<&'a Call>, SpecError> {
        let Some(a) = self.find(key) else {
            return Ok(None);
        };
        match &a.value {
            Value::Call(c) => Ok(Some(c)),
            Value::Num(_, span) | Value::Rgb(_, span) | Value::Str(_, span) => Err(err_span(
                self.spec,
                *span,
                format!("`{key}` must be a name, not a number"),
            )),
        }
    }
}
