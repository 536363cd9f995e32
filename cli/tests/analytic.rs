//! An independent `f64` writer of the analytic BRDFs that `fit.rs` and `fit_cli.rs` tabulate and fit,
//! written here from the published formulas — not with `radiometry-brdfs` or the CLI's model code — so
//! the fit is not checked against tables made by the code it fits (a shared mistake in `D`, `Λ`, `G2`,
//! `F` or the diffuse term would otherwise cancel out).
//!
//! `f(ωi, ωo) = kd/π + F(ωi·h) D(h) G2(ωi, ωo) / (4 cos θi cos θo)`, `h = (ωi + ωo)/‖ωi + ωo‖`
//! (Walter et al. 2007, "Microfacet models for refraction through rough surfaces", eq. 20), with
//! * `D`, GGX: `α² / (π cos⁴θh (α² + tan²θh)²)` (Walter et al. 2007, eq. 33); Beckmann:
//!   `exp(−tan²θh/α²) / (π α² cos⁴θh)` (eq. 25);
//! * the Smith `G1 = 1/(1 + Λ)`, from Walter et al.'s `G1`: GGX `2/(1 + √(1 + α² tan²θ))` (eq. 34), so
//!   `Λ = (√(1 + α² tan²θ) − 1)/2`; Beckmann `G1 = 2/(1 + erf a + e^{−a²}/(a√π))`, `a = 1/(α tan θ)`
//!   (eq. 27, the exact form), so `Λ = (erf a − 1)/2 + e^{−a²}/(2a√π)`;
//! * `G2`, height-correlated: `1/(1 + Λ(ωi) + Λ(ωo))`; separable: `G1(ωi) G1(ωo)` (Heitz 2014,
//!   "Understanding the masking-shadowing function", eqs. 99 and 98);
//! * `F`, Schlick: `F0 + (1 − F0)(1 − cos θd)⁵` (Schlick 1994, eq. 15); conductor: the exact
//!   unpolarised reflectance of a complex index `η + ik` in real arithmetic (Born & Wolf, §14.2; as
//!   written out in Lagarde 2013, "Memo on Fresnel equations"): with `s² = sin²θ`,
//!   `a² + b² = √((η² − k² − s²)² + 4η²k²)`, `a = √((a² + b² + η² − k² − s²)/2)`,
//!   `Rs = (a² + b² − 2a cos θ + cos²θ)/(a² + b² + 2a cos θ + cos²θ)`,
//!   `Rp = Rs (cos²θ (a² + b²) − 2a cos θ s² + s⁴)/(cos²θ (a² + b²) + 2a cos θ s² + s⁴)`,
//!   `F = (Rs + Rp)/2` — a different formula from the crate's complex-arithmetic `FrComplex`.
//!
//! Only the grid's node directions ([`RusinkiewiczGrid::node_directions`], the MERL layout, tested
//! against MERL's conventions in `merl.rs`) come from the crate: they are where the fit reads the table.

use radiometry::glam::DVec3;
use radiometry_brdfs::tabulated::RusinkiewiczGrid;
use std::f64::consts::PI;

/// Microfacet normal distribution.
#[derive(Clone, Copy, Debug)]
pub enum Ndf {
    Ggx,
    Beckmann,
}

/// Fresnel term.
#[derive(Clone, Copy, Debug)]
pub enum Fres {
    Schlick { f0: f64 },
    Conductor { eta: f64, k: f64 },
}

/// `kd/π` plus an optional microfacet lobe (one channel).
#[derive(Clone, Copy, Debug)]
pub struct Analytic {
    /// `(D, α, separable G2?, F)`, or `None` for a purely diffuse BRDF.
    pub lobe: Option<(Ndf, f64, bool, Fres)>,
    /// Diffuse albedo.
    pub kd: f64,
}

impl Analytic {
    /// GGX, height-correlated, Schlick `F0`, no diffuse term.
    pub fn ggx(alpha: f64, f0: f64) -> Self {
        Analytic {
            lobe: Some((Ndf::Ggx, alpha, false, Fres::Schlick { f0 })),
            kd: 0.0,
        }
    }
    /// Beckmann, height-correlated, Schlick `F0`, no diffuse term.
    pub fn beckmann(alpha: f64, f0: f64) -> Self {
        Analytic {
            lobe: Some((Ndf::Beckmann, alpha, false, Fres::Schlick { f0 })),
            kd: 0.0,
        }
    }
    /// A Lambertian BRDF of albedo `kd`.
    pub fn lambertian(kd: f64) -> Self {
        Analytic { lobe: None, kd }
    }
    /// With the diffuse term `kd/π`.
    pub fn kd(self, kd: f64) -> Self {
        Analytic { kd, ..self }
    }
    /// With the separable Smith `G2`.
    pub fn separable(mut self) -> Self {
        if let Some(l) = &mut self.lobe {
            l.2 = true;
        }
        self
    }
    /// With the conductor Fresnel term of `η + ik`.
    pub fn conductor(mut self, eta: f64, k: f64) -> Self {
        if let Some(l) = &mut self.lobe {
            l.3 = Fres::Conductor { eta, k };
        }
        self
    }

    /// `f(ωi, ωo)` [1/sr]; 0 when a direction is at or below the horizon.
    pub fn eval(&self, wi: DVec3, wo: DVec3) -> f64 {
        let (wi, wo) = (wi.normalize(), wo.normalize());
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        let diffuse = self.kd / PI;
        let Some((ndf, alpha, separable, fres)) = self.lobe else {
            return diffuse;
        };
        let h = (wi + wo).normalize();
        let a2 = alpha * alpha;
        let c2 = h.z * h.z;
        let tan2 = (1.0 - c2) / c2;
        let d = match ndf {
            Ndf::Ggx => a2 / (PI * c2 * c2 * (a2 + tan2) * (a2 + tan2)),
            Ndf::Beckmann => (-tan2 / a2).exp() / (PI * a2 * c2 * c2),
        };
        let lambda = |w: DVec3| -> f64 {
            let tan2 = (1.0 - w.z * w.z) / (w.z * w.z);
            if tan2 <= 0.0 {
                return 0.0;
            }
            match ndf {
                Ndf::Ggx => 0.5 * ((1.0 + a2 * tan2).sqrt() - 1.0),
                Ndf::Beckmann => {
                    let a = 1.0 / (alpha * tan2.sqrt());
                    0.5 * (libm::erf(a) - 1.0) + (-a * a).exp() / (2.0 * a * PI.sqrt())
                }
            }
        };
        let (li, lo) = (lambda(wi), lambda(wo));
        let g2 = if separable {
            1.0 / ((1.0 + li) * (1.0 + lo))
        } else {
            1.0 / (1.0 + li + lo)
        };
        let cd = wi.dot(h).clamp(0.0, 1.0);
        let f = match fres {
            Fres::Schlick { f0 } => f0 + (1.0 - f0) * (1.0 - cd).powi(5),
            Fres::Conductor { eta, k } => conductor_fresnel(cd, eta, k),
        };
        diffuse + f * d * g2 / (4.0 * wi.z * wo.z)
    }
}

/// Exact unpolarised reflectance of a conductor `η + ik` at `cos θ` (module doc; real arithmetic).
pub fn conductor_fresnel(cos: f64, eta: f64, k: f64) -> f64 {
    let c2 = cos * cos;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let rs = (a2b2 - 2.0 * a * cos + c2) / (a2b2 + 2.0 * a * cos + c2);
    let rp = rs * (c2 * a2b2 - 2.0 * a * cos * s2 + s2 * s2) / (c2 * a2b2 + 2.0 * a * cos * s2 + s2 * s2);
    0.5 * (rs + rp)
}

/// `f` of each channel at node `(i, j, k)` of `grid`, in `f64`.
pub fn node_value(rgb: &[Analytic; 3], grid: &RusinkiewiczGrid, i: usize, j: usize, k: usize) -> [f64; 3] {
    let (wi, wo) = grid.node_directions(i, j, k);
    let (wi, wo) = (wi.as_dvec3(), wo.as_dvec3());
    rgb.map(|b| b.eval(wi, wo))
}

/// MERL's per-channel scales: a file stores `f / scale` (`BRDFRead.cpp` of the MERL database:
/// `RED_SCALE = 1/1500`, `GREEN_SCALE = 1.15/1500`, `BLUE_SCALE = 1.66/1500`).
pub const MERL_SCALES: [f64; 3] = [1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0];

/// The bytes of a MERL `.binary` file of `rgb` on `grid`, written here (not with the CLI's writer):
/// three little-endian `i32` dimensions `(Nθh, Nθd, Nφd)`, then per channel (R, G, B) one `f64` per
/// node in the grid's flat order, `f / scale`; nodes with a direction below the horizon are stored as
/// `−1` (missing, as in MERL data).
pub fn merl_bytes(rgb: &[Analytic; 3], grid: &RusinkiewiczGrid) -> Vec<u8> {
    let [nh, nd, np] = grid.dims();
    let mut out = Vec::with_capacity(12 + 24 * grid.len());
    for d in [nh, nd, np] {
        out.extend_from_slice(&(d as i32).to_le_bytes());
    }
    let mut block = vec![vec![0.0f64; grid.len()]; 3];
    for i in 0..nh {
        for j in 0..nd {
            for k in 0..np {
                let (wi, wo) = grid.node_directions(i, j, k);
                let index = grid.index(i, j, k);
                let v = node_value(rgb, grid, i, j, k);
                for c in 0..3 {
                    block[c][index] = if wi.z <= 0.0 || wo.z <= 0.0 {
                        -1.0
                    } else {
                        v[c] / MERL_SCALES[c]
                    };
                }
            }
        }
    }
    for b in block {
        for x in b {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    out
}
