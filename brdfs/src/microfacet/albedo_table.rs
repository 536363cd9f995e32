//! The tabulated directional albedo `E(μ, α)` of a single-scattering
//! microfacet BRDF with `F = 1`, the input of the Kulla–Conty
//! multiple-scattering lobe ([`KullaConty`](super::KullaConty)).

use super::{Beckmann, Ggx, HeightCorrelated, Separable, albedo_data};

/// Number of `μ = cos θo` nodes per row: `μ_j = (j/63)²`, `j = 0..64`
/// (uniform in `√μ`, which resolves the steep fall of `E` towards grazing).
pub const N_MU: usize = 64;

/// Number of roughness nodes: `α_k = (k/31)²`, `k = 0..32` (uniform in `√α`).
pub const N_ALPHA: usize = 32;

/// The directional albedo of a microfacet BRDF with `F = 1`,
///
/// ```text
/// E(μo, α) = ∫_H f_r(ωi, ωo) cos θi dωi,   μo = cos θo
/// ```
///
/// (Kulla & Conty 2017, "Revisiting Physically Based Shading at
/// Imageworks", SIGGRAPH course, slide "Energy compensation"), tabulated on
/// the grid `α_k = (k/31)²` (`k = 0..32`) × `μ_j = (j/63)²` (`j = 0..64`).
///
/// Row `k = 0` is the `α → 0` limit, `E ≡ 1` (a mirror loses no energy);
/// column `j = 0` holds `E` at `μ = 10⁻⁶`, the grazing limit (`f_r` itself is
/// 0 at `μ = 0` exactly). Every other entry was computed by this project's
/// integrator ([`radiometry::integrator::Adaptive`], warped onto the BRDF's
/// own sampling map) with the generator `brdfs/examples/kulla_conty_tables.rs`;
/// its header states the integration error, and the test
/// `brdfs/tests/kulla_conty_tables.rs` recomputes a sample of entries with an
/// independent `f64` quadrature.
///
/// Entry error: the generator states `|I(B) − I(4B)| ≤ 7.6·10⁻⁵` over all
/// entries (the written value is `I(4B)`, `B = 40 000`); the independent
/// `f64` quadrature of the test agrees to `3.7·10⁻⁵` on 288 sampled entries.
///
/// Interpolation (what [`row`](Self::row) and [`albedo`](Self::albedo) do):
/// Catmull–Rom in `√α` between rows, then linear in `√μ` between columns.
/// Its total error against the exact `E` is at most `3.6·10⁻⁴` for
/// `α ∈ [0.05, 1]`, `μ ∈ [cos 89°, 1]` (the largest white-furnace deviation
/// of [`KullaConty`](super::KullaConty) measured by
/// `brdfs/tests/kulla_conty.rs` on 19 off-node roughnesses × 22 angles ×
/// 4 variants, at Beckmann, `α = 0.05`, `θo = 87°`); it grows below
/// `α = 0.05`, where the table's first rows are far apart.
///
/// ```
/// use radiometry_brdfs::microfacet::{AlbedoTable, EnergyTable, Ggx, HeightCorrelated};
/// let t: &AlbedoTable = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
/// // GGX, α = 1, normal incidence: E = 1 − ln 2 (closed form).
/// let e = t.albedo(1.0, 1.0);
/// assert!((e - (1.0 - core::f32::consts::LN_2)).abs() < 1e-4);
/// ```
#[derive(Debug, PartialEq)]
pub struct AlbedoTable {
    /// `values[k][j] = E(μ_j, α_k)`.
    pub values: [[f32; N_MU]; N_ALPHA],
}

/// Which tabulated albedo belongs to a distribution `D` (the implementor)
/// with shadowing–masking `G`. Implemented for [`Ggx`] and [`Beckmann`] with
/// [`HeightCorrelated`] and [`Separable`].
pub trait EnergyTable<G> {
    /// The table of `E(μ, α)` for this `(D, G)`.
    const TABLE: &'static AlbedoTable;
}

impl EnergyTable<HeightCorrelated> for Ggx {
    const TABLE: &'static AlbedoTable = &albedo_data::GGX_HEIGHT_CORRELATED;
}
impl EnergyTable<Separable> for Ggx {
    const TABLE: &'static AlbedoTable = &albedo_data::GGX_SEPARABLE;
}
impl EnergyTable<HeightCorrelated> for Beckmann {
    const TABLE: &'static AlbedoTable = &albedo_data::BECKMANN_HEIGHT_CORRELATED;
}
impl EnergyTable<Separable> for Beckmann {
    const TABLE: &'static AlbedoTable = &albedo_data::BECKMANN_SEPARABLE;
}

/// `μ_j = (j/63)²` of column `j` (the generator evaluates column 0 at `10⁻⁶`).
pub const fn mu_node(j: usize) -> f32 {
    let x = j as f32 / (N_MU - 1) as f32;
    x * x
}

/// `α_k = (k/31)²` of row `k`.
pub const fn alpha_node(k: usize) -> f32 {
    let s = k as f32 / (N_ALPHA - 1) as f32;
    s * s
}

/// The Catmull–Rom spline through `p0..p3` at `t ∈ [0, 1]` between `p1` and
/// `p2` (Catmull & Rom 1974; uniform parametrisation):
/// `½ (2p1 + (p2 − p0)t + (2p0 − 5p1 + 4p2 − p3)t² + (3p1 − p0 − 3p2 + p3)t³)`.
#[inline]
fn catmull_rom(p: [f32; 4], t: f32) -> f32 {
    let [p0, p1, p2, p3] = p;
    let a = 2.0 * p1;
    let b = p2 - p0;
    let c = 2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3;
    let d = 3.0 * p1 - p0 - 3.0 * p2 + p3;
    0.5 * (a + t * (b + t * (c + t * d)))
}

/// Cell index and fraction of `x ∈ [0, 1]` on `n` uniform nodes (`x` is
/// clamped; NaN → 0).
#[inline(always)]
pub(crate) fn cell(x: f32, n: usize) -> (usize, f32) {
    let last = (n - 2) as f32;
    let s = if x > 0.0 {
        (x * (n - 1) as f32).min(n as f32 - 1.0)
    } else {
        0.0
    };
    let i = s.min(last) as usize;
    // `i ≤ n − 2`, so `i + 1` is a valid index.
    (i.min(n - 2), s - i as f32)
}

impl AlbedoTable {
    /// The row `E(μ_j, α)` for `j = 0..64` at roughness `α` (clamped to
    /// `[0, 1]`, NaN → 0): Catmull–Rom in `√α` through the four nearest
    /// rows (the outermost rows are continued linearly), clamped to `[0, 1]`.
    pub fn row(&self, alpha: f32) -> [f32; N_MU] {
        let s = if alpha > 0.0 {
            libm::sqrtf(alpha.min(1.0))
        } else {
            0.0
        };
        let (k, t) = cell(s, N_ALPHA);
        let v = &self.values;
        let mut out = [0.0f32; N_MU];
        for (j, o) in out.iter_mut().enumerate() {
            let p1 = v[k][j];
            let p2 = v[k + 1][j];
            let p0 = if k > 0 { v[k - 1][j] } else { 2.0 * p1 - p2 };
            let p3 = if k + 2 < N_ALPHA {
                v[k + 2][j]
            } else {
                2.0 * p2 - p1
            };
            *o = catmull_rom([p0, p1, p2, p3], t).clamp(0.0, 1.0);
        }
        out
    }

    /// `E(μ, α)`: [`row`](Self::row) at `α`, then linear in `√μ` (`μ`
    /// clamped to `[0, 1]`). Builds the whole row; for many lookups at one
    /// `α` keep the row (as [`KullaConty`](super::KullaConty) does).
    pub fn albedo(&self, mu: f32, alpha: f32) -> f32 {
        lerp_row(&self.row(alpha), mu)
    }
}

/// The row value at `μ`, linear in `√μ` between nodes (`μ` clamped to
/// `[0, 1]`, NaN → 0).
#[inline(always)]
pub(crate) fn lerp_row(row: &[f32; N_MU], mu: f32) -> f32 {
    let x = if mu > 0.0 { libm::sqrtf(mu.min(1.0)) } else { 0.0 };
    let (j, t) = cell(x, N_MU);
    let (a, b) = (row[j], row[j + 1]);
    a + t * (b - a)
}

/// `2 ∫₀¹ r(μ) μ dμ = 4 ∫₀¹ r(x) x³ dx` (`x = √μ`) of the function that is
/// linear in `x` between the nodes of `row` — exact up to rounding: a
/// 3-point Gauss–Legendre rule per cell is exact for the degree-4
/// integrand.
pub(crate) fn cosine_average(row: &[f32; N_MU]) -> f32 {
    // Gauss–Legendre, 3 points on [0, 1]: nodes ½ ∓ √(3/5)/2, ½; weights 5/18, 8/18, 5/18.
    const G: [(f32, f32); 3] = [
        (0.112_701_66, 5.0 / 18.0),
        (0.5, 8.0 / 18.0),
        (0.887_298_35, 5.0 / 18.0),
    ];
    let h = 1.0 / (N_MU - 1) as f32;
    let mut sum = 0.0f32;
    for j in 0..N_MU - 1 {
        let (a, b) = (row[j], row[j + 1]);
        let mut cell_sum = 0.0f32;
        for &(t, w) in &G {
            let x = (j as f32 + t) * h;
            cell_sum += w * (a + t * (b - a)) * (x * x * x);
        }
        sum += cell_sum;
    }
    (4.0 * h * sum).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cosine_average_is_exact_for_polynomials() {
        // r(μ) = 1 → 1; r(μ) = √μ (linear in x, so exact) → 2∫ μ^{3/2} dμ = 4/5.
        let ones = [1.0f32; N_MU];
        assert!((cosine_average(&ones) - 1.0).abs() < 1e-6);
        let sq: [f32; N_MU] = core::array::from_fn(|j| libm::sqrtf(mu_node(j)));
        assert!((cosine_average(&sq) - 0.8).abs() < 1e-6);
    }

    #[test]
    fn cell_stays_in_range() {
        for x in [f32::NAN, -1.0, 0.0, 0.5, 1.0, 2.0, f32::INFINITY] {
            let (i, t) = cell(x, N_MU);
            assert!(i + 1 < N_MU && (0.0..=1.0).contains(&t), "{x}: {i} {t}");
        }
    }

    #[test]
    fn rows_hit_nodes() {
        let t = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        for k in [1usize, 7, 31] {
            let r = t.row(alpha_node(k));
            for j in [0usize, 5, 63] {
                assert!((r[j] - t.values[k][j]).abs() < 2e-6, "{k} {j}");
            }
        }
        assert!(t.row(0.0).iter().all(|&e| e == 1.0));
    }
}
