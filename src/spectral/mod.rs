//! Spectral data tables and photometry (in progress).
