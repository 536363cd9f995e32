//! The validated samples of a fit, in the form the per-channel problems read.

use super::channel::TABLE_INTERVALS;
use super::{FitError, Sample};
use radiometry::glam::Vec3;

/// The usable samples in the form the per-channel problems read.
pub(crate) struct Prepared {
    pub(super) wi: Vec<Vec3>,
    pub(super) wo: Vec<Vec3>,
    /// `cos θi`.
    pub(super) mu_i: Vec<f64>,
    /// `(1 − cos θd)⁵` (Schlick's basis).
    pub(super) s5: Vec<f64>,
    /// Cell of `cos θd` in the conductor table: `(interval, fraction)`.
    pub(super) cell: Vec<(usize, f64)>,
    /// `ln(1 + μi f_table)` per channel.
    pub(super) y: [Vec<f64>; 3],
    /// `w μi μo` per channel, 0 where the value is missing.
    pub(super) w: [Vec<f64>; 3],
}

impl Prepared {
    pub(super) fn len(&self) -> usize {
        self.wi.len()
    }

    /// Every `k`-th sample (`k ≥ 1`), for the coarse roughness scan.
    pub(super) fn every(&self, k: usize) -> Prepared {
        fn pick<T: Copy>(v: &[T], k: usize) -> Vec<T> {
            v.iter().step_by(k.max(1)).copied().collect()
        }
        Prepared {
            wi: pick(&self.wi, k),
            wo: pick(&self.wo, k),
            mu_i: pick(&self.mu_i, k),
            s5: pick(&self.s5, k),
            cell: pick(&self.cell, k),
            y: [0, 1, 2].map(|c| pick(&self.y[c], k)),
            w: [0, 1, 2].map(|c| pick(&self.w[c], k)),
        }
    }

    /// Validates and converts the samples (see [`FitError`]).
    pub(super) fn new(samples: &[Sample]) -> Result<Prepared, FitError> {
        if samples.is_empty() {
            return Err(FitError::Empty);
        }
        let mut p = Prepared {
            wi: Vec::new(),
            wo: Vec::new(),
            mu_i: Vec::new(),
            s5: Vec::new(),
            cell: Vec::new(),
            y: Default::default(),
            w: Default::default(),
        };
        for (index, s) in samples.iter().enumerate() {
            if !(s.weight.is_finite() && s.weight >= 0.0) {
                return Err(FitError::InvalidSample {
                    index,
                    reason: "weight is negative or not finite",
                });
            }
            let (Some(wi), Some(wo)) = (s.wi.as_dvec3().try_normalize(), s.wo.as_dvec3().try_normalize())
            else {
                return Err(FitError::InvalidSample {
                    index,
                    reason: "a direction is zero or not finite",
                });
            };
            let present = s.value.map(|v| v.is_finite() && v >= 0.0);
            if wi.z <= 0.0 || wo.z <= 0.0 || s.weight == 0.0 || !present.iter().any(|&x| x) {
                continue;
            }
            let Some(h) = (wi + wo).try_normalize() else {
                continue;
            };
            let cd = wi.dot(h).clamp(0.0, 1.0);
            let pos = cd * TABLE_INTERVALS as f64;
            let n = (pos as usize).min(TABLE_INTERVALS - 1);
            p.wi.push(wi.as_vec3());
            p.wo.push(wo.as_vec3());
            p.mu_i.push(wi.z);
            p.s5.push((1.0 - cd).powi(5));
            p.cell.push((n, pos - n as f64));
            let cw = s.weight * wi.z * wo.z;
            for (c, &here) in present.iter().enumerate() {
                let (y, w) = if here {
                    ((wi.z * s.value[c]).ln_1p(), cw)
                } else {
                    (0.0, 0.0)
                };
                p.y[c].push(y);
                p.w[c].push(w);
            }
        }
        if p.len() == 0 {
            return Err(FitError::NoValidSamples { total: samples.len() });
        }
        if let Some(channel) = (0..3).find(|&c| p.w[c].iter().all(|&w| w == 0.0)) {
            return Err(FitError::EmptyChannel { channel });
        }
        Ok(p)
    }
}
