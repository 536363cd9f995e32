//! A global sampler for the Kulla–Conty multiple-scattering lobe of GGX with
//! the height-correlated `G2`, for materials built in O(1) (OpenPBR's metal).
//!
//! The lobe `f_ms ∝ (1 − E(μi))(1 − E(μo))` is drawn in `μi` from its own
//! cosine-weighted profile `(1 − E(μi)) μi` (bounded per cell, as
//! [`KullaConty`](super::KullaConty) does per instance), here once per
//! roughness node `α_k` of the albedo table ([`alpha_node`], 32 rows) and
//! stored as global data (`ms_sampler_data.rs`, 24 KiB): a material uses the
//! row nearest its roughness in the table's `∛(α − α_min)` coordinate. Row
//! `k` has the table's 64 nodes of that roughness `μ_j(α_k)` (see
//! [`node_scale`]) and, on cell `j`, the height
//! `v_j = max(ℓ_j, ℓ_{j+1}) + 10⁻³ max v` (`ℓ` the loss less
//! [`LOSS_MARGIN`](super::LOSS_MARGIN)); it draws cell `j` with probability
//! `v_j (μ_{j+1}² − μ_j²) / T`, `μ²` uniform in the cell and `φ` uniform, so
//! its solid-angle density is `μ v_j / (π T)`.
//!
//! Against a cosine lobe, whose weight grows like `1 − E(μi)` (a narrow band
//! at the horizon for smooth metals), the weight of this sampler stays within
//! a bounded factor of a constant, also at the neighbouring roughness.
//!
//! Dimensions: `[MsRow; N_ALPHA]`, each row `mu_sq: [f32; N_MU]` (`μ_j²`),
//! `cdf: [f32; N_MU]` (cell `j` spans `cdf[j]..cdf[j+1]`), `dens:
//! [f32; N_MU − 1]` (`v_j / (π T)`). The unit test
//! `rows_are_the_kulla_conty_samplers_of_the_table` recomputes every row from
//! the albedo table bit for bit (and with `RADIOMETRY_REGENERATE=1` writes the
//! file).

use super::albedo_table::{N_ALPHA, N_MU};
use radiometry::glam::Vec3;
use radiometry::math::sincos_turn;

/// One roughness row of the sampler (see the module docs).
#[derive(Debug, PartialEq)]
pub(crate) struct MsRow {
    pub(crate) mu_sq: [f32; N_MU],
    pub(crate) cdf: [f32; N_MU],
    pub(crate) dens: [f32; N_MU - 1],
}

#[rustfmt::skip]
mod data;
pub(crate) use data::GGX_HC_MS_ROWS;

/// The index of the row nearest `α` in the table's coordinate
/// `∛((α − α_min)/(1 − α_min))` (`α` clamped to `[α_min, 1]`, NaN → 0).
#[cfg(test)]
pub(crate) fn row_index(alpha: f32) -> u8 {
    row_index_at(super::albedo_table::alpha_axis(alpha))
}

/// [`row_index`] at the coordinate `x =`
/// [`alpha_axis`](super::albedo_table::alpha_axis)`(α)`.
#[inline]
pub(crate) fn row_index_at(x: f32) -> u8 {
    (libm::roundf(x * (N_ALPHA - 1) as f32) as usize).min(N_ALPHA - 1) as u8
}

/// Row `k` (the last row for `k` out of range).
pub(crate) fn row(k: u8) -> &'static MsRow {
    match GGX_HC_MS_ROWS.get(k as usize) {
        Some(r) => r,
        None => &GGX_HC_MS_ROWS[N_ALPHA - 1],
    }
}

/// The row nearest `α` ([`row_index`]).
#[cfg(test)]
pub(crate) fn row_for(alpha: f32) -> &'static MsRow {
    row(row_index(alpha))
}

impl MsRow {
    /// A direction drawn from the row's density with `u0, u1 ∈ [0, 1)`:
    /// cell `j` with `cdf[j] ≤ u0 < cdf[j+1]`, `μ² = lerp(μ_j², μ_{j+1}², t)`,
    /// `φ = 2π u1`.
    pub(crate) fn sample(&self, u0: f32, u1: f32) -> Vec3 {
        let j = self
            .cdf
            .get(1..)
            .map_or(0, |c| c.partition_point(|&c| c <= u0))
            .min(N_MU - 2);
        let (c0, c1) = (self.at_cdf(j), self.at_cdf(j + 1));
        let t = if c1 > c0 {
            ((u0 - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let (a, b) = (self.at_mu_sq(j), self.at_mu_sq(j + 1));
        let m2 = (a + t * (b - a)).clamp(0.0, 1.0);
        let sin_t = radiometry::math::sqrtf(1.0 - m2);
        let (s, c) = sincos_turn(u1);
        Vec3::new(sin_t * c, sin_t * s, radiometry::math::sqrtf(m2))
    }

    /// The solid-angle density `μ v_j / (π T)` of [`sample`](Self::sample)
    /// at `μ = cos θ > 0` (`j` the cell of `μ²`); 0 for `μ ≤ 0`.
    pub(crate) fn pdf(&self, mu: f32) -> f32 {
        if mu.is_nan() || mu <= 0.0 {
            return 0.0;
        }
        let m2 = mu * mu;
        let j = self
            .mu_sq
            .get(1..)
            .map_or(0, |m| m.partition_point(|&m| m <= m2))
            .min(N_MU - 2);
        mu * self.dens.get(j).copied().unwrap_or(0.0)
    }

    fn at_cdf(&self, j: usize) -> f32 {
        self.cdf.get(j).copied().unwrap_or(1.0)
    }

    fn at_mu_sq(&self, j: usize) -> f32 {
        self.mu_sq.get(j).copied().unwrap_or(1.0)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::albedo_table::{EnergyTable, alpha_node, mu_node, node_scale, rescale_mu};
    use super::super::{Ggx, HeightCorrelated};
    use super::*;
    use std::fmt::Write as _;
    use std::string::String;

    /// `max(ℓ − δ, 0)`, the loss the Kulla–Conty lobe restores.
    fn margined_loss(loss: f32) -> f32 {
        (loss - super::super::LOSS_MARGIN).max(0.0)
    }

    /// The piecewise-constant cell sampler of the rows (cell heights
    /// `v_j = max(ℓ_j, ℓ_{j+1}) + 10⁻³ max v`), as `KullaConty` built it per
    /// instance when these rows were generated.
    fn lobe_sampler(nodes: &[f32; N_MU], loss: &[f32; N_MU]) -> ([f32; N_MU], [f32; N_MU], [f32; N_MU - 1]) {
        let mu_sq: [f32; N_MU] = core::array::from_fn(|j| nodes[j] * nodes[j]);
        let mut v: [f32; N_MU - 1] =
            core::array::from_fn(|j| margined_loss(loss[j]).max(margined_loss(loss[j + 1])));
        let top = v.iter().fold(0.0f32, |m, &x| m.max(x));
        let floor = if top > 0.0 { 1e-3f32 * top } else { 1.0 };
        for x in &mut v {
            *x += floor;
        }
        // f32 throughout (63 positive terms: relative rounding ≲ 63 ε), so
        // firmware without a double-precision FPU pulls in no f64 helpers.
        let mass: [f32; N_MU - 1] = core::array::from_fn(|j| v[j] * (mu_sq[j + 1] - mu_sq[j]).max(0.0));
        let total: f32 = mass.iter().sum();
        let mut cdf = [0.0f32; N_MU];
        let mut acc = 0.0f32;
        for j in 0..N_MU - 1 {
            acc += mass[j];
            cdf[j + 1] = if total > 0.0 {
                (acc / total).min(1.0)
            } else {
                (j + 1) as f32 / (N_MU - 1) as f32
            };
        }
        cdf[N_MU - 1] = 1.0;
        let norm = if total > 0.0 {
            core::f32::consts::FRAC_1_PI / total
        } else {
            0.0
        };
        let dens: [f32; N_MU - 1] = core::array::from_fn(|j| v[j] * norm);
        (mu_sq, cdf, dens)
    }

    /// Row `k` from the table, as [`KullaConty`](super::super::KullaConty)
    /// builds its sampler at `α = α_k`.
    fn row(k: usize) -> MsRow {
        let alpha = alpha_node(k);
        let r = node_scale(alpha);
        let inv_r2 = 1.0 / (r * r);
        let nodes: [f32; N_MU] = core::array::from_fn(|j| {
            let m = mu_node(j);
            rescale_mu(m, (1.0 - m) * (1.0 + m), inv_r2)
        });
        let table = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        let loss: [f32; N_MU] = core::array::from_fn(|j| 1.0 - table.albedo(nodes[j], alpha));
        let (mu_sq, cdf, dens) = lobe_sampler(&nodes, &loss);
        MsRow { mu_sq, cdf, dens }
    }

    fn write_rows(rows: &[MsRow]) -> String {
        let mut s = String::new();
        s.push_str("//! Generated by `RADIOMETRY_REGENERATE=1 cargo test -p radiometry-brdfs --lib ms_sampler` (do not\n");
        s.push_str("//! edit): the Kulla–Conty lobe samplers of the GGX height-correlated albedo table, one per roughness\n");
        s.push_str("//! node (see `ms_sampler.rs`).\n");
        s.push_str("#![allow(clippy::excessive_precision, clippy::approx_constant)]\n");
        s.push_str("use super::MsRow;\n\n");
        s.push_str("/// The rows, `α_k` ascending (see the module docs of `ms_sampler`).\n");
        s.push_str("pub(crate) static GGX_HC_MS_ROWS: [MsRow; 32] = [\n");
        for r in rows {
            let list = |v: &[f32]| {
                v.iter()
                    .map(|x| std::format!("{x:?}"))
                    .collect::<std::vec::Vec<_>>()
                    .join(", ")
            };
            let _ = writeln!(
                s,
                "MsRow {{ mu_sq: [{}], cdf: [{}], dens: [{}] }},",
                list(&r.mu_sq),
                list(&r.cdf),
                list(&r.dens)
            );
        }
        s.push_str("];\n");
        s
    }

    #[test]
    fn rows_are_the_kulla_conty_samplers_of_the_table() {
        let rows: std::vec::Vec<MsRow> = (0..N_ALPHA).map(row).collect();
        if std::env::var_os("RADIOMETRY_REGENERATE").is_some() {
            let path =
                std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/microfacet/ms_sampler/data.rs");
            std::fs::write(&path, write_rows(&rows)).unwrap();
        }
        for (k, r) in rows.iter().enumerate() {
            assert_eq!(r, &GGX_HC_MS_ROWS[k], "row {k}");
        }
    }

    /// The density integrates to 1 over the hemisphere and `sample` follows
    /// it: the fraction of draws in `μ² < 1/2` equals `∫ pdf` there (by a
    /// fine midpoint rule in `μ`).
    #[test]
    fn density_is_normalised_and_sampled() {
        for k in [0, 5, 12, 20, 31] {
            let r = &GGX_HC_MS_ROWS[k];
            let n = 200_000;
            let (mut total, mut below) = (0.0f64, 0.0f64);
            for i in 0..n {
                let mu = (i as f64 + 0.5) / n as f64;
                let p = f64::from(r.pdf(mu as f32)) * core::f64::consts::TAU / n as f64;
                total += p;
                if mu * mu < 0.5 {
                    below += p;
                }
            }
            assert!((total - 1.0).abs() < 2e-3, "row {k}: ∫pdf = {total}");
            let m = 1 << 16;
            let hits = (0..m)
                .filter(|&i| {
                    let w = r.sample((i as f32 + 0.5) / m as f32, 0.3);
                    w.z * w.z < 0.5
                })
                .count();
            let frac = hits as f64 / m as f64;
            assert!((frac - below).abs() < 2e-3, "row {k}: {frac} vs {below}");
        }
    }

    #[test]
    fn rows_follow_the_roughness() {
        assert!(core::ptr::eq(row_for(1.0), &GGX_HC_MS_ROWS[31]));
        assert!(core::ptr::eq(row_for(0.0), &GGX_HC_MS_ROWS[0]));
        assert!(core::ptr::eq(row_for(f32::NAN), &GGX_HC_MS_ROWS[0]));
        assert!(core::ptr::eq(row_for(alpha_node(17)), &GGX_HC_MS_ROWS[17]));
        assert_eq!(row_for(2.0).pdf(f32::NAN), 0.0);
    }
}
