//! Unit tests of the microfacet module (references are independent f64 quadratures and closed forms).
