//! The generic call grammar: `name(key=value, ...)` and `+`-sums of calls, parsed into [`Call`]s.

use crate::SpecError;
use crate::lex::{Tok, Token, describe, lex};

/// A parsed `name(key=value, ...)` call.
#[derive(Clone, Debug, PartialEq)]
pub struct Call {
    /// The name.
    pub name: String,
    /// Span of the name.
    pub name_span: (usize, usize),
    /// Span of the whole call.
    pub span: (usize, usize),
    /// Arguments in order.
    pub args: Vec<Arg>,
}

/// One `key=value` argument.
#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    /// The key.
    pub key: String,
    /// Span of the key.
    pub key_span: (usize, usize),
    /// The value.
    pub value: Value,
}

/// An argument value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// A number and its span.
    Num(f64, (usize, usize)),
    /// A nested call (or a bare name).
    Call(Call),
    /// `rgb(R, G, B)`: a colour's three numbers, with the span of the whole value.
    Rgb([f64; 3], (usize, usize)),
    /// `"text"`: a string (a file name), with the span of the quoted value.
    Str(String, (usize, usize)),
}

impl Value {
    pub(crate) fn span(&self) -> (usize, usize) {
        match self {
            Value::Num(_, s) => *s,
            Value::Call(c) => c.span,
            Value::Rgb(_, s) => *s,
            Value::Str(_, s) => *s,
        }
    }
}

pub(crate) struct Parser<'a> {
    spec: &'a str,
    toks: Vec<Token>,
    pos: usize,
}

impl<'a> Parser<'a> {
    pub(crate) fn new(spec: &'a str) -> Result<Self, SpecError> {
        Ok(Parser {
            spec,
            toks: lex(spec)?,
            pos: 0,
        })
    }

    pub(crate) fn peek(&self) -> &Token {
        &self.toks[self.pos.min(self.toks.len() - 1)]
    }

    pub(crate) fn bump(&mut self) -> Token {
        let t = self.peek().clone();
        if self.pos < self.toks.len() - 1 {
            self.pos += 1;
        }
        t
    }

    pub(crate) fn err_at(&self, t: &Token, message: String) -> SpecError {
        SpecError {
            spec: self.spec.to_string(),
            start: t.start,
            end: t.end,
            message,
        }
    }

    pub(crate) fn expected(&self, what: &str) -> SpecError {
        let t = self.peek().clone();
        self.err_at(&t, format!("expected {what}, found {}", describe(&t.tok)))
    }

    pub(crate) fn call(&mut self, depth: usize) -> Result<Call, SpecError> {
        if depth > 8 {
            return Err(self.expected("a shallower nesting of calls"));
        }
        let t = self.peek().clone();
        let Tok::Ident(name) = t.tok.clone() else {
            return Err(self.expected("a name"));
        };
        self.bump();
        let mut call = Call {
            name,
            name_span: (t.start, t.end),
            span: (t.start, t.end),
            args: Vec::new(),
        };
        if self.peek().tok != Tok::LParen {
            return Ok(call);
        }
        self.bump();
        loop {
            if self.peek().tok == Tok::RParen {
                break;
            }
            let kt = self.peek().clone();
            let Tok::Ident(key) = kt.tok.clone() else {
                return Err(self.expected("a parameter name or `)`"));
            };
            self.bump();
            if self.peek().tok != Tok::Eq {
                return Err(self.expected(&format!("`=` after `{key}`")));
            }
            self.bump();
            let vt = self.peek().clone();
            let value = match vt.tok {
                Tok::Num(v) => {
                    self.bump();
                    Value::Num(v, (vt.start, vt.end))
                }
                Tok::Ident(ref n) if n == "rgb" => self.rgb()?,
                Tok::Str(ref text) => {
                    self.bump();
                    Value::Str(text.clone(), (vt.start, vt.end))
                }
                Tok::Ident(_) => Value::Call(self.call(depth + 1)?),
                _ => return Err(self.expected(&format!("a value for `{key}`"))),
            };
            call.args.push(Arg {
                key,
                key_span: (kt.start, kt.end),
                value,
            });
            match self.peek().tok {
                Tok::Comma => {
                    self.bump();
                }
                Tok::RParen => break,
                _ => return Err(self.expected("`,` or `)`")),
            }
        }
        let close = self.bump();
        call.span.1 = close.end;
        Ok(call)
    }

    /// `rgb(R, G, B)`, three numbers (positional), at the current token.
    fn rgb(&mut self) -> Result<Value, SpecError> {
        let start = self.bump().start;
        if self.peek().tok != Tok::LParen {
            return Err(self.expected("`(` after `rgb`"));
        }
        self.bump();
        let mut c = [0.0; 3];
        for (i, v) in c.iter_mut().enumerate() {
            let t = self.peek().clone();
            let Tok::Num(x) = t.tok else {
                return Err(self.expected("a number (rgb takes three: rgb(R, G, B))"));
            };
            self.bump();
            *v = x;
            let (sep, what) = if i < 2 {
                (Tok::Comma, "`,` (rgb takes three numbers)")
            } else {
                (Tok::RParen, "`)` (rgb takes three numbers)")
            };
            if self.peek().tok != sep {
                return Err(self.expected(what));
            }
            if i < 2 {
                self.bump();
            }
        }
        let close = self.bump();
        Ok(Value::Rgb(c, (start, close.end)))
    }

    pub(crate) fn finish(&mut self) -> Result<(), SpecError> {
        if self.peek().tok == Tok::End {
            Ok(())
        } else {
            Err(self.expected("end of input"))
        }
    }
}

/// Parses a single call (a BRDF spec).
pub fn parse_call(spec: &str) -> Result<Call, SpecError> {
    let mut p = Parser::new(spec)?;
    let c = p.call(0)?;
    p.finish()?;
    Ok(c)
}

/// Parses a `+`-separated sum of calls (a light spec).
pub fn parse_sum(spec: &str) -> Result<Vec<Call>, SpecError> {
    let mut p = Parser::new(spec)?;
    let mut out = vec![p.call(0)?];
    while p.peek().tok == Tok::Plus {
        p.bump();
        out.push(p.call(0)?);
    }
    p.finish()?;
    Ok(out)
}
