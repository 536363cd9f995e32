//! A global sampler for a diffuse base under a GGX dielectric layer: the
//! direction `ωi` drawn in proportion to the light the layer lets through,
//! `(1 − E_F(μi, α, η)) μi` (the layer's transmission times the cosine),
//! for materials built in O(1) (OpenPBR's diffuse lobe under its specular
//! layer).
//!
//! A diffuse body under a dielectric layer carries the layer's factor
//! `1 − E_F(μi)` in its value (Kelemen and Szirmay-Kalos 2001; OpenPBR's
//! albedo-scaling layer). Drawn from a cosine, the sample weight varies as
//! that factor: a relative variance of `7·10⁻⁴` for the coat over white
//! plastic of the conformance set, `10⁻²` for a smooth `η = 1.5` layer.
//! Drawn from this sampler the weight is nearly constant (the unit test
//! `follows_the_transmission` states the reduction).
//!
//! # The density
//!
//! One row per node `(z_l, α_k)` of the `η > 1` ratio table
//! ([`fresnel_table`](super::fresnel_table): `z = F0^¼ = l/31`, `√α = 0.01 +
//! 0.99 k/31`) holds the heights `h_j ∝ max(1 − E_F(μ_j), 10⁻³ max)` at the
//! 17 nodes `μ_j = (j/16)²` (`s_j = μ_j² = j⁴/65536`: cells as fine near the
//! horizon, where the factor falls, as the table's own `√μ` nodes). A
//! material blends the four rows around its `(α, η)` with the table's
//! bilinear weights ([`TransmissionSampler::new`], O(1)), and the density
//! is piecewise linear in `s = μ²` between the nodes:
//!
//! ```text
//! p(ωi) = μi · lerp(h_j, h_{j+1}, (s − s_j)/(s_{j+1} − s_j)) · norm,     norm = 1/(π T),
//! T = Σ_j (h_j + h_{j+1})/2 · (s_{j+1} − s_j)
//! ```
//!
//! with `φ` uniform (`dω = dφ ds/(2μ)`, so a height constant in `s` is the
//! cosine lobe `μ/π`). Continuous in `μ`, so the weight `f cos/p` has no
//! step at a cell edge. Sampling picks the cell by its mass and inverts the
//! linear density in closed form.
//!
//! Dimensions: `[TransmissionRow; 32 × 32]`, index `32 l + k`; each row
//! `h: [u16; 17]`, `65535 ×` the height over the row's largest (34 KiB);
//! beside them, derived from them at compile time, each row's cumulative
//! cell masses (`ROWS_F32`, `[[f32; 17]; 32 × 32]`, 68 KiB).
//! The unit test `rows_are_the_transmission_of_the_table` recomputes every
//! row from the albedo tables bit for bit (and with
//! `RADIOMETRY_REGENERATE=1` writes `transmission_sampler/data.rs`).

use super::fresnel_table::{RatioCells, outside_cells};
use radiometry::glam::Vec3;
use radiometry::math::sincos_turn;

/// Cells per row.
pub(crate) const CELLS: usize = 16;
/// Roughness nodes (the ratio table's).
const N_A: usize = 32;
/// Index nodes (the `η > 1` ratio table's).
const N_Z: usize = 32;

/// One node's heights (see the module docs).
#[derive(Debug, PartialEq)]
pub(crate) struct TransmissionRow {
    pub(crate) h: [u16; CELLS + 1],
}

#[rustfmt::skip]
mod data;
pub(crate) use data::TRANSMISSION_ROWS;

/// `s_j = (j/16)⁴ = j⁴/65536`, exact in `f32`.
const S_EDGE: [f32; CELLS + 1] = {
    let mut e = [0.0f32; CELLS + 1];
    let mut j = 0;
    while j <= CELLS {
        let q = (j * j * j * j) as f32;
        e[j] = q / 65536.0;
        j += 1;
    }
    e
};

/// `1/(s_{j+1} − s_j)` per cell (the widths are exact; the reciprocals
/// rounded once).
const INV_WIDTH: [f32; CELLS] = {
    let mut e = [0.0f32; CELLS];
    let mut j = 0;
    while j < CELLS {
        e[j] = 1.0 / (S_EDGE[j + 1] - S_EDGE[j]);
        j += 1;
    }
    e
};

/// One committed row in `f32`: its heights `h_j = q_j/65535` and cumulative
/// masses `M_j = Σ_{i<j} (h_i + h_{i+1}) (s_{i+1} − s_i)` (`M_0 = 0`, `M_16`
/// twice the row's total), summed in that order.
struct RowF32 {
    h: [f32; CELLS + 1],
    m: [f32; CELLS + 1],
}

/// [`TRANSMISSION_ROWS`] in `f32` with their cumulative masses, derived at
/// compile time: dimensions `[RowF32; 32 × 32]` (136 KiB), index `32 l + k`
/// as the rows. A sampler blends its four corners' heights and masses with
/// the same weights ([`TransmissionSampler::new`]): the masses are linear
/// in the heights, so no running sum is left for construction.
static ROWS_F32: [RowF32; N_Z * N_A] = {
    let mut out = [const {
        RowF32 {
            h: [0.0; CELLS + 1],
            m: [0.0; CELLS + 1],
        }
    }; N_Z * N_A];
    let mut r = 0;
    while r < N_Z * N_A {
        let q = &TRANSMISSION_ROWS[r].h;
        let mut j = 0;
        while j <= CELLS {
            out[r].h[j] = q[j] as f32 * (1.0 / 65535.0);
            j += 1;
        }
        let mut acc = 0.0f32;
        j = 0;
        while j < CELLS {
            acc += (out[r].h[j] + out[r].h[j + 1]) * (S_EDGE[j + 1] - S_EDGE[j]);
            out[r].m[j + 1] = acc;
            j += 1;
        }
        r += 1;
    }
    out
};

/// The sampler of one `(α, η)`: the heights of the four surrounding rows,
/// blended with the ratio table's bilinear weights in `(√α, F0^¼)`
/// (`√α` clamped to `[0.01, 1]`; `z = √|(η − 1)/(η + 1)|`, so `η < 1` uses
/// the rows of `1/η`, a valid density of the same Fresnel strength), and
/// the cells' cumulative masses for the draw and the normalisation `1/(π
/// T)`, blended the same way from the corners' [`ROWS_F32`]. Built in
/// O(1) with no chain of dependent sums: 68 multiply-adds for the heights,
/// 68 for the masses (a running sum of the blended heights would be 16
/// additions, each waiting for the last).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TransmissionSampler {
    h: [f32; CELLS + 1],
    /// `M_j = Σ_{i<j} m_i`, `m_i = (h_i + h_{i+1})(s_{i+1} − s_i)`: `M_0 = 0`,
    /// `M_16 = 2T` — the corners' [`ROWS_F32`] blended.
    cum: [f32; CELLS + 1],
    norm: f32,
}

impl TransmissionSampler {
    /// The sampler of `(1 − E_F(μ, α, η)) μ` (see the module docs).
    pub(crate) fn new(alpha: f32, eta: f32) -> Self {
        let (index, roughness) = outside_cells(alpha, eta);
        Self::at_cells(index, roughness)
    }

    /// [`new`](Self::new) from the ratio table's cells of `(α, η)` where a
    /// dielectric reader computed them ([`RatioCells`]), bit for bit: for
    /// `η ≥ 1` they are this sampler's cells (the rows sit at the `η > 1`
    /// table's nodes); `η < 1` computes its own (the rows of `1/η`).
    #[inline(always)]
    pub(crate) fn from_cells(cells: &RatioCells, alpha: f32, eta: f32) -> Self {
        let (l, fz, inside) = cells.index;
        if inside {
            return Self::new(alpha, eta);
        }
        Self::at_cells((l, fz), cells.alpha)
    }

    /// The sampler of the index cell `(l, f_z)` and roughness cell `(k,
    /// f_a)`.
    #[inline(always)]
    fn at_cells((l, fz): (usize, f32), (k, fa): (usize, f32)) -> Self {
        let w = [(1.0 - fz) * (1.0 - fa), (1.0 - fz) * fa, fz * (1.0 - fa), fz * fa];
        let sampler = Self::blend(l * N_A + k, w);
        if sampler.norm > 0.0 {
            sampler
        } else {
            // Unreachable for the committed rows (every height ≥ 10⁻³ of its
            // row's top, so every total is positive); the first row (η = 1:
            // the cosine lobe) as a fallback.
            Self::blend(0, [1.0, 0.0, 0.0, 0.0])
        }
    }

    /// The four corners from `row` (`(l, k)`, `(l, k + 1)`, `(l + 1, k)`,
    /// `(l + 1, k + 1)`) blended with weights `w`: heights and cumulative
    /// masses (`norm` 0 where the total is not positive and finite).
    #[inline(always)]
    fn blend(row: usize, w: [f32; 4]) -> Self {
        let mut h = [0.0f32; CELLS + 1];
        let mut cum = [0.0f32; CELLS + 1];
        for (i, &wc) in [row, row + 1, row + N_A, row + N_A + 1].iter().zip(&w) {
            if let Some(r) = ROWS_F32.get(*i) {
                for (x, &q) in h.iter_mut().zip(&r.h) {
                    *x += wc * q;
                }
                for (x, &q) in cum.iter_mut().zip(&r.m) {
                    *x += wc * q;
                }
            }
        }
        // `M_16 = 2T`.
        let total = cum[CELLS];
        let norm = if total > 0.0 && total.is_finite() {
            2.0 * core::f32::consts::FRAC_1_PI / total
        } else {
            0.0
        };
        Self { h, cum, norm }
    }

    #[inline(always)]
    fn height_in(h: &[f32; CELLS + 1], j: usize) -> f32 {
        h.get(j).copied().unwrap_or(0.0)
    }

    #[inline(always)]
    fn height(&self, j: usize) -> f32 {
        Self::height_in(&self.h, j)
    }

    /// A direction drawn from the density with `u0, u1 ∈ [0, 1)`: the last
    /// cell `j ≤ 15` with `M_j ≤ u0 M_16`, then `s = s_j + t (s_{j+1} − s_j)`
    /// from the cell's linear density, `t = q/(h_j + √(h_j² + d q))` (`d =
    /// h_{j+1} − h_j`, `q = (u0 M_16 − M_j)/(s_{j+1} − s_j)`, twice the mass
    /// left in the cell per unit `t`), and `φ = 2π u1`. Always inlined: the
    /// draw sits between the picks and the pass over the lobes on a sample's
    /// critical path.
    #[inline(always)]
    pub(crate) fn sample(&self, u0: f32, u1: f32) -> Vec3 {
        Self::direction(self.polar(u0), u1)
    }

    /// The direction of the polar part `(sin θ, cos θ)` that
    /// [`polar`](Self::polar) drew and the azimuth `φ = 2π u1`:
    /// [`sample`](Self::sample)'s last step.
    #[inline(always)]
    pub(crate) fn direction((sin_t, cos_t): (f32, f32), u1: f32) -> Vec3 {
        let (sn, cs) = sincos_turn(u1);
        Vec3::new(sin_t * cs, sin_t * sn, cos_t)
    }

    /// The polar part `(sin θ, cos θ)` of [`sample`](Self::sample) at `u0`
    /// (the azimuth comes from `u1` alone).
    #[inline(always)]
    pub(crate) fn polar(&self, u0: f32) -> (f32, f32) {
        let cum = &self.cum;
        let target = u0.clamp(0.0, 1.0) * cum[CELLS];
        // The last j ≤ 15 with M_j ≤ target: M is non-decreasing, so it is the
        // number of M_1..M_15 at or below it (16 independent comparisons, no
        // chain of dependent steps: the draw sits on `sample`'s critical path).
        let j: usize = cum[1..CELLS].iter().map(|&m| usize::from(m <= target)).sum();
        let left = (target - cum.get(j).copied().unwrap_or(0.0)).max(0.0);
        let (h0, h1) = (self.height(j), self.height(j + 1));
        let (s0, s1) = (edge(j), edge(j + 1));
        let width = s1 - s0;
        // ∫₀ᵗ (h0 + d τ) dτ = c: the cell's mass per unit t is (h0 + h1)/2 and
        // `left` counts it as (h0 + h1) · width, so 2c = left/width (`q`, from
        // the stored reciprocal: one division fewer on the critical path).
        let q = left * INV_WIDTH.get(j).copied().unwrap_or(0.0);
        let d = h1 - h0;
        let den = h0 + radiometry::math::sqrtf((h0 * h0 + d * q).max(0.0));
        let t = if den > 0.0 { (q / den).clamp(0.0, 1.0) } else { 0.5 };
        let s = (s0 + t * width).clamp(0.0, 1.0);
        (
            radiometry::math::sqrtf((1.0 - s).max(0.0)),
            radiometry::math::sqrtf(s),
        )
    }

    /// The solid-angle density of [`sample`](Self::sample) at `μ = cos θ`:
    /// `μ · lerp(h_j, h_{j+1}, (s − s_j)/(s_{j+1} − s_j)) · norm`, `s = μ²`;
    /// 0 for `μ ≤ 0` or NaN.
    #[inline]
    pub(crate) fn pdf(&self, mu: f32) -> f32 {
        if mu.is_nan() || mu <= 0.0 {
            return 0.0;
        }
        let mu = mu.min(1.0);
        let s = mu * mu;
        // The cell of `s`: the number of inner edges `s_1..s_15` at or below
        // it (independent comparisons against constants, no root, no branch).
        let j: usize = S_EDGE[1..CELLS].iter().map(|&e| usize::from(e <= s)).sum();
        let t = ((s - edge(j)) * INV_WIDTH.get(j).copied().unwrap_or(0.0)).clamp(0.0, 1.0);
        let (h0, h1) = (self.height(j), self.height(j + 1));
        mu * (h0 + t * (h1 - h0)) * self.norm
    }
}

#[inline(always)]
fn edge(j: usize) -> f32 {
    S_EDGE.get(j).copied().unwrap_or(1.0)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::super::fresnel_table::DielectricAlbedoReader;
    use super::*;
    use std::fmt::Write as _;
    use std::string::String;
    use std::vec::Vec;

    /// The node `(α_k, η_l)` of the ratio table (`η_l = (1 + z²)/(1 − z²)`,
    /// `z = l/31`; the last index node is the limit `η → ∞`, capped).
    fn node(l: usize, k: usize) -> (f32, f32) {
        let t = 0.01 + 0.99 * k as f32 / (N_A - 1) as f32;
        let z = l as f32 / (N_Z - 1) as f32;
        let z2 = z * z;
        let eta = if z2 < 1.0 {
            ((1.0 + z2) / (1.0 - z2)).min(1e6)
        } else {
            1e6
        };
        (t * t, eta)
    }

    /// Row `(l, k)` from the tables: heights at `μ_j = (j/16)²`.
    fn compute_row(l: usize, k: usize) -> TransmissionRow {
        let (alpha, eta) = node(l, k);
        let r = DielectricAlbedoReader::new(alpha, eta);
        let g: [f64; CELLS + 1] = core::array::from_fn(|j| {
            let x = j as f32 / CELLS as f32;
            f64::from(1.0 - r.albedo(x * x)).max(0.0)
        });
        let top = g.iter().fold(0.0f64, |m, &x| m.max(x));
        let h: [u16; CELLS + 1] = if top > 0.0 {
            core::array::from_fn(|j| (g[j].max(1e-3 * top) / top * 65535.0).round() as u16)
        } else {
            [65535; CELLS + 1]
        };
        TransmissionRow { h }
    }

    fn all_rows() -> Vec<TransmissionRow> {
        (0..N_Z)
            .flat_map(|l| (0..N_A).map(move |k| (l, k)))
            .map(|(l, k)| compute_row(l, k))
            .collect()
    }

    fn write_rows(rows: &[TransmissionRow]) -> String {
        let mut s = String::new();
        s.push_str("//! Generated by `RADIOMETRY_REGENERATE=1 cargo test -p radiometry-brdfs --lib transmission_sampler`\n");
        s.push_str("//! (do not edit): the samplers of `(1 − E_F(μ, α, η)) μ` at the nodes of the `η > 1` ratio table\n");
        s.push_str("//! (see `transmission_sampler.rs`).\n");
        s.push_str(
            "#![allow(clippy::excessive_precision, clippy::approx_constant, clippy::unreadable_literal)]\n",
        );
        s.push_str("use super::TransmissionRow;\n\n");
        s.push_str("/// The rows, index `32 l + k` (`z_l = l/31`, `√α_k = 0.01 + 0.99 k/31`).\n");
        let _ = writeln!(
            s,
            "pub(crate) static TRANSMISSION_ROWS: [TransmissionRow; {}] = [",
            rows.len()
        );
        for r in rows {
            let h: Vec<String> = r.h.iter().map(|x| std::format!("{x}")).collect();
            let _ = writeln!(s, "TransmissionRow {{ h: [{}] }},", h.join(", "));
        }
        s.push_str("];\n");
        s
    }

    #[test]
    fn rows_are_the_transmission_of_the_table() {
        let rows = all_rows();
        if std::env::var_os("RADIOMETRY_REGENERATE").is_some() {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("src/microfacet/transmission_sampler/data.rs");
            std::fs::write(&path, write_rows(&rows)).unwrap();
        }
        assert_eq!(rows.len(), TRANSMISSION_ROWS.len());
        for (i, r) in rows.iter().enumerate() {
            assert_eq!(r, &TRANSMISSION_ROWS[i], "row {i}");
        }
    }

    /// A sampler built from a dielectric reader's cells
    /// ([`TransmissionSampler::from_cells`], as `OpenPbr` builds its diffuse
    /// sampler) is the sampler [`TransmissionSampler::new`] builds, field
    /// for field: at random `(α, η)` on both sides of 1, at the table's
    /// nodes and ends, and at `η = 1`.
    #[test]
    fn sampler_from_shared_cells_is_new() {
        let mut u = crate::test_stream::uniforms(0x7A11_CE11_5EED_0001);
        for n in 0..4_000 {
            let alpha = match n % 10 {
                0 => 1e-4,
                1 => 1.0,
                2 => {
                    let t = 0.01 + 0.99 * (n % 32) as f32 / 31.0;
                    t * t
                }
                _ => (u() * u()).max(1e-4),
            };
            let eta = match n % 7 {
                0 => 1.0,
                1 => 0.2 + 0.79 * u(),
                2 => 1e3,
                _ => 1.0 + 3.0 * u(),
            };
            let cells = RatioCells::new(alpha, eta);
            assert_eq!(
                TransmissionSampler::from_cells(&cells, alpha, eta),
                TransmissionSampler::new(alpha, eta),
                "α {alpha} η {eta}"
            );
        }
    }

    /// The density integrates to 1 over the hemisphere (a fine midpoint rule
    /// in `s`), and `sample` follows it: the share of draws below each cell
    /// edge and at mid-cell points equals `∫ pdf` there.
    #[test]
    fn density_is_normalised_and_sampled() {
        for (i, (alpha, eta)) in [
            (1e-4, 1.0),
            (0.003, 1.5),
            (0.05, 1.07),
            (0.3, 2.0),
            (1.0, 4.0),
            (0.0081, 3.0),
        ]
        .into_iter()
        .enumerate()
        {
            let r = TransmissionSampler::new(alpha, eta);
            let n = 400_000;
            // ∫ p dω = ∫ p(μ) 2π μ⁻¹ … in s: dω = π ds/μ after φ.
            let cut = [1e-4f64, 0.01, 0.1, 0.3, 0.55, 0.8];
            let mut below = [0.0f64; 6];
            let mut total = 0.0f64;
            for q in 0..n {
                let s = (q as f64 + 0.5) / n as f64;
                let mu = s.sqrt();
                let p = f64::from(r.pdf(mu as f32)) * core::f64::consts::PI / mu / n as f64;
                total += p;
                for (b, &c) in below.iter_mut().zip(&cut) {
                    if s < c {
                        *b += p;
                    }
                }
            }
            assert!((total - 1.0).abs() < 1e-4, "row {i}: ∫pdf = {total}");
            let m = 1 << 18;
            let mut hits = [0usize; 6];
            for q in 0..m {
                let w = r.sample((q as f32 + 0.5) / m as f32, 0.3);
                assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= 0.0, "row {i}: {w}");
                let s = f64::from(w.z) * f64::from(w.z);
                for (h, &c) in hits.iter_mut().zip(&cut) {
                    if s < c {
                        *h += 1;
                    }
                }
            }
            for (c, (&h, &b)) in cut.iter().zip(hits.iter().zip(&below)) {
                let frac = h as f64 / m as f64;
                assert!(
                    (frac - b).abs() < 1e-4 + 1e-3 * b,
                    "row {i}, s < {c}: {frac} vs {b}"
                );
            }
        }
    }

    /// Against a cosine lobe, the weight `(1 − E_F(μ)) μ/(π p)` of this
    /// sampler varies far less: its relative variance (by quadrature in
    /// `s`) is at least 10× smaller wherever the cosine's exceeds 10⁻⁴,
    /// at random `(α, η)` between the nodes, and the weight stays within a
    /// factor 50 of its mean.
    #[test]
    fn follows_the_transmission() {
        let mut rnd = crate::test_stream::uniforms(0x9E37_79B9_7F4A_7C15);
        let rel_var = |g: &dyn Fn(f64) -> f64, p: &dyn Fn(f64) -> f64| {
            // Density in s ∝ p(μ)/μ; weight g μ/p.
            let n = 20_000;
            let (mut z, mut m1, mut m2, mut wmax) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            for q in 0..n {
                let s = (q as f64 + 0.5) / n as f64;
                let mu = s.sqrt();
                let d = p(mu) / mu;
                let w = g(mu) / d;
                z += d;
                m1 += d * w;
                m2 += d * w * w;
                wmax = wmax.max(w);
            }
            let (m1, m2) = (m1 / z, m2 / z);
            (m2 / (m1 * m1) - 1.0, wmax / m1)
        };
        let mut checked = 0;
        for _ in 0..300 {
            let alpha = 1e-4 + rnd() * rnd();
            let eta = 1.0 + 2.5 * rnd() * rnd();
            let reader = DielectricAlbedoReader::new(alpha, eta);
            let g = |mu: f64| f64::from(1.0 - reader.albedo(mu as f32)).max(0.0);
            let (cosine, _) = rel_var(&g, &|mu| mu);
            let r = TransmissionSampler::new(alpha, eta);
            let (shaped, peak) = rel_var(&g, &|mu| f64::from(r.pdf(mu as f32)));
            assert!(peak < 50.0, "α {alpha}, η {eta}: weight up to {peak}× its mean");
            if cosine > 1e-4 {
                checked += 1;
                assert!(
                    shaped * 10.0 < cosine,
                    "α {alpha}, η {eta}: relative variance {shaped:.3e} vs cosine {cosine:.3e}"
                );
            }
        }
        assert!(checked > 100, "{checked}");
    }

    /// At a node the sampler is that node's row; `η < 1` is the sampler of
    /// `1/η`; NaN and out-of-range input give a normalised density.
    #[test]
    fn blends_the_rows() {
        for (l, k) in [(3, 7), (20, 0), (30, 30), (0, 15)] {
            let (a, e) = node(l, k);
            let s = TransmissionSampler::new(a, e);
            let row = &TRANSMISSION_ROWS[l * N_A + k];
            for (x, &q) in s.h.iter().zip(&row.h) {
                assert!((x - q as f32 / 65535.0).abs() < 1e-5, "({l}, {k}): {x} vs {q}");
            }
        }
        let (inv, out) = (
            TransmissionSampler::new(0.2, 1.0 / 1.5),
            TransmissionSampler::new(0.2, 1.5),
        );
        for (a, b) in inv.h.iter().zip(&out.h) {
            assert!((a - b).abs() < 1e-6, "{inv:?} vs {out:?}");
        }
        for (a, e) in [
            (f32::NAN, f32::NAN),
            (-1.0, 0.0),
            (f32::INFINITY, f32::INFINITY),
            (0.0, 1e30),
        ] {
            let s = TransmissionSampler::new(a, e);
            assert!(s.norm.is_finite() && s.norm > 0.0, "({a}, {e}): {s:?}");
            let w = s.sample(0.5, 0.5);
            assert!(w.is_finite() && w.z > 0.0 && s.pdf(w.z) > 0.0, "({a}, {e}): {w}");
        }
    }
}
