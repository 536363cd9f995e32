//! Errors of the lobe combinators' constructors.

use core::fmt;

/// A combinator parameter outside its domain (rejected, never clamped).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ComposeError {
    /// A [`Mix`](super::Mix) weight outside `[0, 1]` (or not finite).
    Weight(f32),
    /// A [`Scaled`](super::Scaled) factor or a coat colour with a channel
    /// that is negative or not finite (the offending channel value).
    Scale(f32),
    /// A coat colour channel above 1 (transmittance cannot exceed 1).
    CoatColor(f32),
    /// A coat index of refraction below 1 or not finite.
    CoatIor(f32),
    /// A [`Coated`](super::Coated) top tint channel outside `[0, 1]` or not
    /// finite.
    TopTint(f32),
    /// A value of an albedo table outside `[0, 1]` or not finite, or a
    /// negative or non-finite table error (the offending value). No
    /// constructor of this crate returns it (`Coated` reads its
    /// top's albedo per call); kept for callers that match on it.
    AlbedoTable(f32),
}

impl fmt::Display for ComposeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Weight(w) => write!(f, "mix weight {w} is outside [0, 1]"),
            Self::Scale(s) => write!(f, "scale factor {s} is negative or not finite"),
            Self::CoatColor(c) => write!(f, "coat colour {c} is outside [0, 1]"),
            Self::CoatIor(e) => write!(f, "coat index of refraction {e} is below 1 or not finite"),
            Self::TopTint(t) => write!(f, "top tint {t} is outside [0, 1]"),
            Self::AlbedoTable(v) => write!(f, "albedo table value {v} is outside [0, 1] or not finite"),
        }
    }
}

impl core::error::Error for ComposeError {}
