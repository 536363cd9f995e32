//! Radiometric calibration.
