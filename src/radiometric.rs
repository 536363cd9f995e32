//! Radiometric closed forms (in progress).
