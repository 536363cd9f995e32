//! Lights and illumination (in progress).
