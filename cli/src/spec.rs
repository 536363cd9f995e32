//! Parser for BRDF and light specifications given on the command line.
//!
//! Grammar (whitespace is ignored between tokens):
//!
//! ```text
//! brdf  := call
//! light := call ('+' call)*
//! call  := NAME [ '(' [ arg (',' arg)* [','] ] ')' ]
//! arg   := KEY '=' value
//! value := NUMBER | call
//! ```
//!
//! `NAME`/`KEY` are `[A-Za-z_][A-Za-z0-9_-]*`; numbers are decimal with an
//! optional sign, fraction and exponent. Angles are in **degrees**. Every
//! error carries the byte span of the offending token so that
//! [`SpecError`]'s `Display` can underline it with carets.

use std::fmt;

/// A parse or validation error with the span of the offending token.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecError {
    /// The full spec text.
    pub spec: String,
    /// Byte offset where the offending token starts.
    pub start: usize,
    /// Byte offset one past its end (`start == end` for "end of input").
    pub end: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let start = floor_char_boundary(&self.spec, self.start.min(self.spec.len()));
        let end = floor_char_boundary(&self.spec, self.end.min(self.spec.len())).max(start);
        let col = self.spec[..start].chars().count();
        let width = self.spec[start..end].chars().count().max(1);
        // Control characters would break the alignment; show them as spaces.
        let shown: String = self
            .spec
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        writeln!(f, "invalid spec: {}", self.message)?;
        writeln!(f, "  {shown}")?;
        write!(f, "  {}{}", " ".repeat(col), "^".repeat(width))
    }
}

impl std::error::Error for SpecError {}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Num(f64),
    LParen,
    RParen,
    Comma,
    Eq,
    Plus,
    End,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    start: usize,
    end: usize,
}

fn describe(t: &Tok) -> String {
    match t {
        Tok::Ident(s) => format!("name `{s}`"),
        Tok::Num(_) => "a number".into(),
        Tok::LParen => "`(`".into(),
        Tok::RParen => "`)`".into(),
        Tok::Comma => "`,`".into(),
        Tok::Eq => "`=`".into(),
        Tok::Plus => "`+`".into(),
        Tok::End => "end of input".into(),
    }
}

fn lex(spec: &str) -> Result<Vec<Token>, SpecError> {
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
}

impl Value {
    fn span(&self) -> (usize, usize) {
        match self {
            Value::Num(_, s) => *s,
            Value::Call(c) => c.span,
        }
    }
}

struct Parser<'a> {
    spec: &'a str,
    toks: Vec<Token>,
    pos: usize,
}

impl<'a> Parser<'a> {
    fn new(spec: &'a str) -> Result<Self, SpecError> {
        Ok(Parser {
            spec,
            toks: lex(spec)?,
            pos: 0,
        })
    }

    fn peek(&self) -> &Token {
        &self.toks[self.pos.min(self.toks.len() - 1)]
    }

    fn bump(&mut self) -> Token {
        let t = self.peek().clone();
        if self.pos < self.toks.len() - 1 {
            self.pos += 1;
        }
        t
    }

    fn err_at(&self, t: &Token, message: String) -> SpecError {
        SpecError {
            spec: self.spec.to_string(),
            start: t.start,
            end: t.end,
            message,
        }
    }

    fn expected(&self, what: &str) -> SpecError {
        let t = self.peek().clone();
        self.err_at(&t, format!("expected {what}, found {}", describe(&t.tok)))
    }

    fn call(&mut self, depth: usize) -> Result<Call, SpecError> {
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

    fn finish(&mut self) -> Result<(), SpecError> {
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

/// Reads the arguments of one call, checking names, types, duplicates and
/// ranges, and remembering spans for later errors.
struct Args<'a> {
    spec: &'a str,
    call: &'a Call,
    used: Vec<bool>,
}

impl<'a> Args<'a> {
    fn new(spec: &'a str, call: &'a Call, allowed: &[&str]) -> Result<Self, SpecError> {
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

    fn find(&mut self, key: &str) -> Option<&'a Arg> {
        let i = self.call.args.iter().position(|a| a.key == key)?;
        self.used[i] = true;
        Some(&self.call.args[i])
    }

    /// A number in `[min, max]` (`open_min`: excludes `min`), or `default`
    /// (`None`: required).
    fn num(
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
        }
    }

    /// A nested call (or bare name) value.
    fn call_value(&mut self, key: &str) -> Result<Option<&'a Call>, SpecError> {
        let Some(a) = self.find(key) else {
            return Ok(None);
        };
        match &a.value {
            Value::Call(c) => Ok(Some(c)),
            Value::Num(_, span) => Err(err_span(
                self.spec,
                *span,
                format!("`{key}` must be a name, not a number"),
            )),
        }
    }
}

fn err_span(spec: &str, span: (usize, usize), message: String) -> SpecError {
    SpecError {
        spec: spec.to_string(),
        start: span.0,
        end: span.1,
        message,
    }
}

/// Microfacet normal distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// GGX / Trowbridge–Reitz.
    Ggx,
    /// Beckmann.
    Beckmann,
}

/// Smith shadowing–masking variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum G2Kind {
    /// `G2 = 1/(1+Λ(ωi)+Λ(ωo))`.
    HeightCorrelated,
    /// `G2 = G1(ωi) G1(ωo)`.
    Separable,
}

/// Fresnel term of a microfacet BRDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FresnelSpec {
    /// `F = 1`.
    None,
    /// Schlick's approximation with normal-incidence reflectance `f0`.
    Schlick {
        /// Reflectance at normal incidence.
        f0: f64,
    },
    /// Exact dielectric Fresnel with relative index `eta`.
    Dielectric {
        /// Relative index of refraction.
        eta: f64,
    },
    /// Exact conductor Fresnel with complex index `eta + i k`.
    Conductor {
        /// Real part of the index.
        eta: f64,
        /// Extinction coefficient.
        k: f64,
    },
}

/// A validated BRDF description (parameters as given; angles none).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BrdfSpec {
    /// `lambertian(albedo=1)`.
    Lambertian {
        /// Albedo ρ ∈ [0, 1].
        albedo: f64,
    },
    /// `phong(exponent=N, ks=1, kd=0)`: modified Phong (Lafortune & Willems 1994).
    Phong {
        /// Exponent n.
        exponent: f64,
        /// Specular coefficient.
        ks: f64,
        /// Diffuse coefficient.
        kd: f64,
    },
    /// `blinn-phong(exponent=N, ks=1, kd=0)`: normalised Blinn–Phong.
    BlinnPhong {
        /// Exponent n.
        exponent: f64,
        /// Specular coefficient.
        ks: f64,
        /// Diffuse coefficient.
        kd: f64,
    },
    /// `ggx(...)` / `beckmann(...)`.
    Microfacet {
        /// Distribution.
        distribution: Distribution,
        /// Roughness α.
        alpha: f64,
        /// Shadowing–masking variant.
        g: G2Kind,
        /// Fresnel term.
        fresnel: FresnelSpec,
    },
}

/// Largest accepted Phong / Blinn–Phong exponent (the plugins' `MAX_EXPONENT`).
pub const MAX_EXPONENT: f64 = 1e7;
/// Smallest accepted microfacet roughness (the plugins' `MIN_ALPHA`).
pub const MIN_ALPHA: f64 = 1e-4;
/// Largest accepted microfacet roughness (the plugins' `MAX_ALPHA`).
pub const MAX_ALPHA: f64 = 1.0;

/// Help text describing the BRDF spec language (used by `--help`).
pub const BRDF_SPEC_HELP: &str = "BRDF spec, e.g. `lambertian(albedo=0.5)`, `phong(exponent=100, ks=1, kd=0)`, \
`blinn-phong(exponent=100, ks=1, kd=0)`, `ggx(alpha=0.1, g=height-correlated|separable, \
fresnel=none|schlick(f0=0.04)|dielectric(eta=1.5)|conductor(eta=0.2,k=3.9))`, `beckmann(...)` \
(same parameters as ggx). Defaults: albedo=1, ks=1, kd=0, g=height-correlated, fresnel=none; \
exponent ∈ [0, 1e7] and alpha ∈ [1e-4, 1] are required; kd + ks ≤ 1.";

/// Help text describing the light spec language.
pub const LIGHT_SPEC_HELP: &str = "Light spec (angles in degrees; `+` sums lights), e.g. \
`cap(axis_theta=95, axis_phi=0, half_angle=10, radiance=1)`, `sky(radiance=1)`, \
`directional(theta=30, phi=0, irradiance=1)`, `sky(radiance=0.2) + directional(theta=30, irradiance=3)`. \
Defaults: phi/axis_phi=0, radiance/irradiance=1; theta/axis_theta ∈ [0, 180] and half_angle ∈ (0, 90] are required.";

/// Parses and validates a BRDF spec.
pub fn parse_brdf(spec: &str) -> Result<BrdfSpec, SpecError> {
    let call = parse_call(spec)?;
    let name = call.name.as_str();
    match name {
        "lambertian" | "lambert" => {
            let mut a = Args::new(spec, &call, &["albedo"])?;
            let albedo = a.num("albedo", Some(1.0), 0.0, 1.0, false)?;
            Ok(BrdfSpec::Lambertian { albedo })
        }
        "phong" | "blinn-phong" => {
            let mut a = Args::new(spec, &call, &["exponent", "ks", "kd"])?;
            let exponent = a.num("exponent", None, 0.0, MAX_EXPONENT, false)?;
            let ks = a.num("ks", Some(1.0), 0.0, 1.0, false)?;
            let kd = a.num("kd", Some(0.0), 0.0, 1.0, false)?;
            if kd + ks > 1.0 + 1e-12 {
                let span = call
                    .args
                    .iter()
                    .find(|x| x.key == "ks")
                    .or_else(|| call.args.iter().find(|x| x.key == "kd"))
                    .map_or(call.span, |x| (x.key_span.0, x.value.span().1));
                return Err(err_span(spec, span, format!("kd + ks = {} must be ≤ 1", kd + ks)));
            }
            Ok(if name == "phong" {
                BrdfSpec::Phong { exponent, ks, kd }
            } else {
                BrdfSpec::BlinnPhong { exponent, ks, kd }
            })
        }
        "ggx" | "beckmann" => {
            let mut a = Args::new(spec, &call, &["alpha", "g", "fresnel"])?;
            let alpha = a.num("alpha", None, MIN_ALPHA, MAX_ALPHA, false)?;
            let g = match a.call_value("g")? {
                None => G2Kind::HeightCorrelated,
                Some(c) => {
                    Args::new(spec, c, &[])?;
                    match c.name.as_str() {
                        "height-correlated" => G2Kind::HeightCorrelated,
                        "separable" | "uncorrelated" => G2Kind::Separable,
                        other => {
                            return Err(err_span(
                                spec,
                                c.name_span,
                                format!(
                                    "unknown shadowing-masking `{other}` (expected height-correlated or separable)"
                                ),
                            ));
                        }
                    }
                }
            };
            let fresnel = match a.call_value("fresnel")? {
                None => FresnelSpec::None,
                Some(c) => parse_fresnel(spec, c)?,
            };
            let distribution = if name == "ggx" {
                Distribution::Ggx
            } else {
                Distribution::Beckmann
            };
            Ok(BrdfSpec::Microfacet {
                distribution,
                alpha,
                g,
                fresnel,
            })
        }
        other => Err(err_span(
            spec,
            call.name_span,
            format!("unknown BRDF `{other}` (expected lambertian, phong, blinn-phong, ggx or beckmann)"),
        )),
    }
}

fn parse_fresnel(spec: &str, c: &Call) -> Result<FresnelSpec, SpecError> {
    match c.name.as_str() {
        "none" => {
            Args::new(spec, c, &[])?;
            Ok(FresnelSpec::None)
        }
        "schlick" => {
            let mut a = Args::new(spec, c, &["f0"])?;
            Ok(FresnelSpec::Schlick {
                f0: a.num("f0", Some(0.04), 0.0, 1.0, false)?,
            })
        }
        "dielectric" => {
            let mut a = Args::new(spec, c, &["eta"])?;
            Ok(FresnelSpec::Dielectric {
                eta: a.num("eta", Some(1.5), 0.0, 1e3, true)?,
            })
        }
        "conductor" => {
            let mut a = Args::new(spec, c, &["eta", "k"])?;
            Ok(FresnelSpec::Conductor {
                eta: a.num("eta", None, 0.0, 1e3, true)?,
                k: a.num("k", None, 0.0, 1e3, false)?,
            })
        }
        other => Err(err_span(
            spec,
            c.name_span,
            format!("unknown fresnel `{other}` (expected none, schlick, dielectric or conductor)"),
        )),
    }
}

/// One light of a light spec (angles in degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSpec {
    /// Uniform spherical cap of radiance `radiance` around the axis (θ, φ).
    Cap {
        /// Polar angle of the axis from +Z, degrees.
        axis_theta: f64,
        /// Azimuth of the axis, degrees.
        axis_phi: f64,
        /// Half opening angle, degrees.
        half_angle: f64,
        /// Radiance.
        radiance: f64,
    },
    /// Uniform sky (whole upper hemisphere) of radiance `radiance`.
    Sky {
        /// Radiance.
        radiance: f64,
    },
    /// Directional (delta) light of normal irradiance `irradiance` from (θ, φ).
    Directional {
        /// Polar angle, degrees.
        theta: f64,
        /// Azimuth, degrees.
        phi: f64,
        /// Irradiance on a surface facing the light.
        irradiance: f64,
    },
}

/// Parses and validates a light spec (a `+`-sum of lights).
pub fn parse_lights(spec: &str) -> Result<Vec<LightSpec>, SpecError> {
    let calls = parse_sum(spec)?;
    let mut out = Vec::new();
    for c in &calls {
        out.push(match c.name.as_str() {
            "cap" | "cone" | "sun" => {
                let mut a = Args::new(spec, c, &["axis_theta", "axis_phi", "half_angle", "radiance"])?;
                LightSpec::Cap {
                    axis_theta: a.num("axis_theta", None, 0.0, 180.0, false)?,
                    axis_phi: a.num("axis_phi", Some(0.0), -360.0, 360.0, false)?,
                    half_angle: a.num("half_angle", None, 0.0, 90.0, true)?,
                    radiance: a.num("radiance", Some(1.0), 0.0, 1e30, false)?,
                }
            }
            "sky" => {
                let mut a = Args::new(spec, c, &["radiance"])?;
                LightSpec::Sky {
                    radiance: a.num("radiance", Some(1.0), 0.0, 1e30, false)?,
                }
            }
            "directional" => {
                let mut a = Args::new(spec, c, &["theta", "phi", "irradiance"])?;
                LightSpec::Directional {
                    theta: a.num("theta", None, 0.0, 180.0, false)?,
                    phi: a.num("phi", Some(0.0), -360.0, 360.0, false)?,
                    irradiance: a.num("irradiance", Some(1.0), 0.0, 1e30, false)?,
                }
            }
            other => {
                return Err(err_span(
                    spec,
                    c.name_span,
                    format!("unknown light `{other}` (expected cap, sky or directional)"),
                ));
            }
        });
    }
    Ok(out)
}

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
    fn brdf_examples_from_the_issue() {
        assert_eq!(
            parse_brdf("lambertian(albedo=0.5)").unwrap(),
            BrdfSpec::Lambertian { albedo: 0.5 }
        );
        assert_eq!(
            parse_brdf("phong(exponent=100, ks=1, kd=0)").unwrap(),
            BrdfSpec::Phong {
                exponent: 100.0,
                ks: 1.0,
                kd: 0.0
            }
        );
        assert_eq!(
            parse_brdf("blinn-phong(exponent=20,ks=0.5,kd=0.5)").unwrap(),
            BrdfSpec::BlinnPhong {
                exponent: 20.0,
                ks: 0.5,
                kd: 0.5
            }
        );
        assert_eq!(
            parse_brdf("ggx(alpha=0.1, g=separable, fresnel=conductor(eta=0.2,k=3.9))").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 0.1,
                g: G2Kind::Separable,
                fresnel: FresnelSpec::Conductor { eta: 0.2, k: 3.9 }
            }
        );
        assert_eq!(
            parse_brdf("beckmann(alpha=1e-2, g=height-correlated, fresnel=schlick(f0=0.04))").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Beckmann,
                alpha: 0.01,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::Schlick { f0: 0.04 }
            }
        );
        assert_eq!(
            parse_brdf("  ggx ( alpha = .3 , fresnel = dielectric ( eta = 1.5 ) , ) ").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 0.3,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::Dielectric { eta: 1.5 }
            }
        );
        assert_eq!(
            parse_brdf("lambertian").unwrap(),
            BrdfSpec::Lambertian { albedo: 1.0 }
        );
        assert_eq!(
            parse_brdf("ggx(alpha=1, fresnel=none)").unwrap(),
            BrdfSpec::Microfacet {
                distribution: Distribution::Ggx,
                alpha: 1.0,
                g: G2Kind::HeightCorrelated,
                fresnel: FresnelSpec::None
            }
        );
    }

    #[test]
    fn errors_point_at_the_offending_token() {
        let cases: &[(&str, &str)] = &[
            ("lambertain(albedo=0.5)", "lambertain"),
            ("lambertian(albdo=0.5)", "albdo"),
            ("lambertian(albedo=1.5)", "1.5"),
            ("lambertian(albedo=-0.1)", "-0.1"),
            ("lambertian(albedo=0.5", ""),
            ("lambertian(albedo=0.5))", ")"),
            ("lambertian(albedo 0.5)", "0.5"),
            ("lambertian(albedo=)", ")"),
            ("lambertian(albedo=0.5, albedo=0.2)", "albedo"),
            ("phong(ks=1)", "phong"),
            ("phong(exponent=1e8)", "1e8"),
            ("ggx(alpha=0.1, g=sep)", "sep"),
            ("ggx(alpha=0.1, g=1)", "1"),
            ("ggx(alpha=0.1, fresnel=schlik(f0=0.04))", "schlik"),
            ("ggx(alpha=0.1, fresnel=schlick(f=0.04))", "f"),
            ("ggx(alpha=0.1, fresnel=conductor(eta=0.2))", "conductor"),
            ("ggx(alpha=0)", "0"),
            ("ggx(alpha=1x)", "1x"),
            ("ggx(alpha=0.1) junk", "junk"),
            ("ggx(alpha=0.1; g=separable)", ";"),
            ("ggx(alpha=nan)", "nan"),
            ("ggx(alpha=1e999)", "1e999"),
            ("ggx(alpha=0.1, g=separable(x=1))", "x"),
            ("", ""),
            ("(", "("),
            ("ggx(alpha=0.1é)", "é"),
        ];
        for (spec, bad) in cases {
            let e = parse_brdf(spec).expect_err(spec);
            assert_eq!(caret_of(&e), *bad, "spec {spec:?}: {e}");
            let shown = e.to_string();
            assert!(shown.contains('^'), "{shown}");
            assert!(shown.contains(spec.trim_end()) || spec.is_empty(), "{shown}");
        }
    }

    #[test]
    fn caret_is_aligned_under_the_token() {
        let e = parse_brdf("ggx(alpha=0.1, g=sep)").unwrap_err();
        let s = e.to_string();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines.len(), 3);
        let col = lines[2].find('^').unwrap();
        assert_eq!(&lines[1][col..col + 3], "sep");
        assert_eq!(lines[2].trim(), "^^^");
    }

    #[test]
    fn kd_plus_ks_constraint() {
        let e = parse_brdf("phong(exponent=10, ks=0.7, kd=0.5)").unwrap_err();
        assert!(e.message.contains("kd + ks"), "{e}");
        assert!(parse_brdf("phong(exponent=10, ks=0.5, kd=0.5)").is_ok());
    }

    #[test]
    fn lights() {
        let l = parse_lights("cap(axis_theta=95, half_angle=10, radiance=1)").unwrap();
        assert_eq!(
            l,
            vec![LightSpec::Cap {
                axis_theta: 95.0,
                axis_phi: 0.0,
                half_angle: 10.0,
                radiance: 1.0
            }]
        );
        let l = parse_lights("sky(radiance=2) + directional(theta=30, irradiance=1)+sky").unwrap();
        assert_eq!(l.len(), 3);
        assert_eq!(l[0], LightSpec::Sky { radiance: 2.0 });
        assert_eq!(
            l[1],
            LightSpec::Directional {
                theta: 30.0,
                phi: 0.0,
                irradiance: 1.0
            }
        );
        for (spec, bad) in [
            ("cap(axis_theta=95, radiance=1)", "cap"),
            ("sky(radiance=1) +", ""),
            ("sky(radiance=1) + lamp", "lamp"),
            ("directional(theta=200)", "200"),
            ("sky(radiance=1) sky", "sky"),
        ] {
            let e = parse_lights(spec).expect_err(spec);
            assert_eq!(caret_of(&e), bad, "{spec}: {e}");
        }
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
}
