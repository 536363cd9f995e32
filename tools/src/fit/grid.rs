//! Samples for [`fit`](super::fit()) from an RGB table on a Rusinkiewicz
//! `(θh, θd, φd)` grid — a MERL file read by [`crate::merl`].
//!
//! # Weights
//! A node stands for the cell of grid space around it, and its weight is
//! the cell's measure in `(ωi, ωo)` space. The change of variables of
//! Rusinkiewicz (1998) has the Jacobian `dωi dωo = 4 cos θd dωh dωd`: for
//! fixed `ωi`, `ωo = 2(ωi·h)h − ωi` gives `dωo = 4 (ωi·h) dωh` (Walter et al.
//! 2007, eq. 14), and `ωi ↦ ωd` is a rotation for fixed `h`. With
//! `dωh = sin θh dθh dφh`, `dωd = sin θd dθd dφd` and isotropy (`φh` integrates
//! to a constant), the weight of node `(i, j, k)` is, up to a constant factor,
//!
//! `w = [cos θh]_{b_h}^{a_h} · [sin² θd]_{a_d}^{b_d} · Δφd`
//!
//! the exact integrals of `sin θh dθh` and `2 sin θd cos θd dθd` over the
//! cell: index intervals `[i − s/2, i + s/2]` (clamped to the axis, `s` the
//! subsampling step) mapped through the grid's node functions (`θh` the
//! square-root mapping). Hence `Σ w μi μo ≈ π/8` over a full grid (tested),
//! and the fit metric does not depend on the resolution or the subsampling.
//!
//! # Subsampling
//! [`Subsample::DEFAULT`] keeps every θh node (they resolve the specular
//! peak), every 2nd θd and every 4th φd node: 90 × 45 × 45 = 182 250 nodes
//! of the MERL grid, of which 139 757 lie above the horizon. A fit then
//! takes 0.35–0.8 s of CPU time with Schlick Fresnel and 1.7–4.2 s with the
//! conductor Fresnel (release build, AMD EPYC, one thread; `time radiometry
//! fit …`), and still sees the peak at full resolution.

use super::{FitError, Sample};
use radiometry::glam::Vec3;
use radiometry_brdfs::tabulated::RusinkiewiczGrid;
use std::f64::consts::{FRAC_PI_2, PI};

/// Node steps along the three axes (`1` = every node).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Subsample {
    theta_h: usize,
    theta_d: usize,
    phi_d: usize,
}

impl Subsample {
    /// Every θh, every 2nd θd, every 4th φd node (module doc).
    pub const DEFAULT: Subsample = Subsample {
        theta_h: 1,
        theta_d: 2,
        phi_d: 4,
    };
    /// Every node.
    pub const ALL: Subsample = Subsample {
        theta_h: 1,
        theta_d: 1,
        phi_d: 1,
    };

    /// Steps along θh, θd, φd; `None` when one is 0.
    pub fn new(theta_h: usize, theta_d: usize, phi_d: usize) -> Option<Subsample> {
        (theta_h > 0 && theta_d > 0 && phi_d > 0).then_some(Subsample {
            theta_h,
            theta_d,
            phi_d,
        })
    }

    /// `[θh, θd, φd]` steps.
    pub fn steps(&self) -> [usize; 3] {
        [self.theta_h, self.theta_d, self.phi_d]
    }
}

/// The index interval `[x − s/2, x + s/2]` clamped to `[0, n]`.
fn cell(x: usize, s: usize, n: usize) -> (f64, f64) {
    let (x, h, n) = (x as f64, s as f64 / 2.0, n as f64);
    ((x - h).max(0.0), (x + h).min(n))
}

/// Weight of node `(i, j, ·)` (module doc; the same for every φd node).
pub fn node_weight(grid: &RusinkiewiczGrid, sub: Subsample, i: usize, j: usize) -> f64 {
    let [nh, nd, np] = grid.dims();
    let (a, b) = cell(i, sub.theta_h, nh);
    let th = |x: f64| (x / nh as f64).powi(2) * FRAC_PI_2;
    let wh = th(a).cos() - th(b).cos();
    let (a, b) = cell(j, sub.theta_d, nd);
    let td = |x: f64| x / nd as f64 * FRAC_PI_2;
    let wd = td(b).sin().powi(2) - td(a).sin().powi(2);
    wh * wd * sub.phi_d as f64 * PI / np as f64
}

/// Which channel entries of a MERL file are missing (stored negative): the
/// reader replaces them by 0 and only counts them, so the fit reads the
/// signs from the bytes. `bytes` must be a file [`crate::merl::from_bytes`]
/// accepted for `grid` (otherwise every entry counts as present).
pub fn missing_mask(bytes: &[u8], grid: &RusinkiewiczGrid) -> Vec<[bool; 3]> {
    let n = grid.len();
    let mut mask = vec![[false; 3]; n];
    let Some(body) = bytes.get(crate::merl::HEADER_BYTES..) else {
        return mask;
    };
    if body.len() != 24 * n {
        return mask;
    }
    for (channel, block) in body.chunks_exact(8 * n).enumerate() {
        for (m, c) in mask.iter_mut().zip(block.chunks_exact(8)) {
            let raw = f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]);
            m[channel] = raw < 0.0;
        }
    }
    mask
}

/// The fit samples of a table: every [`Subsample`]d node with both
/// directions above the horizon ([`RusinkiewiczGrid::node_directions`]),
/// with its value (a channel marked in `missing` becomes `−1`, i.e.
/// missing) and its [`node_weight`].
///
/// # Errors
/// [`FitError::TableSize`] when `values` (or `missing`) does not have one
/// entry per grid node.
pub fn samples(
    grid: &RusinkiewiczGrid,
    values: &[Vec3],
    missing: Option<&[[bool; 3]]>,
    sub: Subsample,
) -> Result<Vec<Sample>, FitError> {
    let n = grid.len();
    for found in [Some(values.len()), missing.map(<[_]>::len)]
        .into_iter()
        .flatten()
    {
        if found != n {
            return Err(FitError::TableSize { expected: n, found });
        }
    }
    let [nh, nd, np] = grid.dims();
    let mut out = Vec::new();
    for i in (0..nh).step_by(sub.theta_h) {
        for j in (0..nd).step_by(sub.theta_d) {
            for k in (0..np).step_by(sub.phi_d) {
                let (wi, wo) = grid.node_directions(i, j, k);
                if wi.z <= 0.0 || wo.z <= 0.0 {
                    continue;
                }
                let index = grid.index(i, j, k);
                let v = values[index];
                let gone = missing.map_or([false; 3], |m| m[index]);
                let value = [0, 1, 2].map(|c| if gone[c] { -1.0 } else { v[c] as f64 });
                out.push(Sample {
                    wi,
                    wo,
                    value,
                    weight: node_weight(grid, sub, i, j),
                });
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Σ w μi μo` over the nodes above the horizon approximates
    /// `∫∫ μi μo dωi dωo / (8π) = π²/(8π) = π/8` (the constant of the
    /// module doc: `4 · 2π (φh) · 2 (φd folding) / 2 (the sin² integral)`),
    /// and the error shrinks with the resolution (the cells straddling the
    /// horizon are the first-order error).
    #[test]
    fn weights_integrate_the_cosine_product() {
        let err = |g: RusinkiewiczGrid, sub: Subsample| {
            let ones = vec![Vec3::ONE; g.len()];
            let s = samples(&g, &ones, None, sub).unwrap();
            let sum: f64 = s.iter().map(|x| x.weight * x.wi.z as f64 * x.wo.z as f64).sum();
            (sum / (PI / 8.0) - 1.0).abs()
        };
        let coarse = err(RusinkiewiczGrid::new(45, 45, 90).unwrap(), Subsample::ALL);
        let merl = err(RusinkiewiczGrid::MERL, Subsample::ALL);
        let merl_sub = err(RusinkiewiczGrid::MERL, Subsample::DEFAULT);
        eprintln!(
            "relative error of Σ w μi μo: 45x45x90 {coarse:.2e}, MERL {merl:.2e}, MERL subsampled {merl_sub:.2e}"
        );
        assert!(merl < 5e-4, "{merl}");
        assert!(merl < 0.5 * coarse, "{merl} vs {coarse}");
        assert!(merl_sub < 5e-4, "{merl_sub}");
    }

    #[test]
    fn size_mismatch_and_masks() {
        let g = RusinkiewiczGrid::new(8, 8, 8).unwrap();
        assert_eq!(
            samples(&g, &[Vec3::ONE; 10], None, Subsample::ALL),
            Err(FitError::TableSize {
                expected: 512,
                found: 10
            })
        );
        let mut m = vec![[false; 3]; 512];
        m[g.index(1, 1, 0)] = [true, false, true];
        let s = samples(&g, &vec![Vec3::splat(0.5); 512], Some(&m), Subsample::ALL).unwrap();
        let (wi, wo) = g.node_directions(1, 1, 0);
        let hit = s.iter().find(|x| x.wi == wi && x.wo == wo).unwrap();
        assert_eq!(hit.value, [-1.0, 0.5, -1.0]);
        assert!(s.iter().all(|x| x.wi.z > 0.0 && x.wo.z > 0.0 && x.weight >= 0.0));
        assert_eq!(Subsample::new(1, 0, 1), None);
    }
}
