//! [`SpecError`]: a parse or validation error that underlines the offending token with carets.

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

/// A [`SpecError`] over `span` of `spec`.
pub(crate) fn err_span(spec: &str, span: (usize, usize), message: String) -> SpecError {
    SpecError {
        spec: spec.to_string(),
        start: span.0,
        end: span.1,
        message,
    }
}
