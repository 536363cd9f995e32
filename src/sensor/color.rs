//! Colour architectures.
