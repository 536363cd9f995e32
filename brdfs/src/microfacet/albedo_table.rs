//! The tabulated directional albedo `E(μ, α)` of a single-scattering
//! microfacet BRDF with `F = 1`, the input of the Kulla–Conty
//! multiple-scattering lobe ([`KullaConty`](super::KullaConty)).

use super::{Beckmann, Ggx, HeightCorrelated, Separable, albedo_data};
use crate::vec4::sqrt4;
use radiometry::glam::Vec4;

/// Number of `μ = cos θo` nodes per row: node coordinate `μ_ref,j = (j/63)²`,
/// `j = 0..64` (uniform in `√μ_ref`, see [`node_scale`]).
pub const N_MU: usize = 64;

/// Number of roughness nodes: `α_k = α_min + (1 − α_min)(k/31)³`, `k = 0..32`,
/// `α_min = 10⁻⁴` (uniform in the cube root, dense where `E` changes fastest).
pub const N_ALPHA: usize = 32;

/// The directional albedo of a microfacet BRDF with `F = 1`,
///
/// ```text
/// E(μo, α) = ∫_H f_r(ωi, ωo) cos θi dωi,   μo = cos θo
/// ```
///
/// (Kulla & Conty 2017, "Revisiting Physically Based Shading at
/// Imageworks", SIGGRAPH course, slide "Energy compensation"), tabulated on
/// the grid `α_k = α_min + (1 − α_min)(k/31)³` (`k = 0..32`, `α_min = 10⁻⁴ =`
/// [`MIN_ALPHA`](super::MIN_ALPHA)) × `μ_ref,j = (j/63)²` (`j = 0..64`).
///
/// Column `j` of row `k` holds `E` at the `μ` whose node coordinate
/// ([`node_scale`]) is `μ_ref = (j/63)²` — the plain `μ_j` for `α_k ≥ 0.2`,
/// nodes crowded towards grazing below; column 0 holds `E` at
/// `μ_ref = 10⁻⁶`, the grazing limit (`f_r` itself is 0 at `μ = 0` exactly). Every other entry was computed by this project's
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
/// Interpolation: see [`albedo`](Self::albedo) (linear in `√μ` within a
/// row, Catmull–Rom in `∛(α − α_min)` across rows at fixed `α tan θ`).
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

/// The tabulated albedos of one distribution, one per Smith variant (what
/// [`MicrofacetDistribution::energy_tables`](super::MicrofacetDistribution::energy_tables)
/// returns and [`ShadowingMasking::select_table`](super::ShadowingMasking::select_table)
/// picks from).
#[derive(Clone, Copy, Debug)]
pub struct EnergyTables {
    /// `E(μ, α)` with the height-correlated `G2`.
    pub height_correlated: &'static AlbedoTable,
    /// `E(μ, α)` with the separable `G2`.
    pub separable: &'static AlbedoTable,
}

/// The error this crate states for [`AlbedoTable::albedo`] against the
/// exact `E(μ, α)`: `10⁻³` for every `α ∈ [10⁻⁴, 1]`, `μ ∈ (0, 1]`. The
/// measured errors are smaller: `3.6·10⁻⁴` for `α ∈ [0.05, 1]`,
/// `θo ≤ 89°` (see [`AlbedoTable`]), `E − E_tab ≤ 4.4·10⁻⁴` everywhere
/// ([`LOSS_MARGIN`](super::LOSS_MARGIN)), and the test
/// `brdfs/tests/microfacet_albedo.rs` finds at most `7.3·10⁻⁵` against its
/// independent `f64` quadrature (4 variants × `α ∈ {0.02, 0.1, 0.3, 0.6, 1}`
/// × `θo ∈ {0°, 40°, 65°, 80°, 88°}`).
pub const ALBEDO_TABLE_ERROR: f32 = 1e-3;

/// Which tabulated albedo belongs to a distribution `D` (the implementor)
/// with shadowing–masking `G`. Implemented for [`Ggx`] and [`Beckmann`] with
/// [`HeightCorrelated`] and [`Separable`].
pub trait EnergyTable<G> {
    /// The table of `E(μ, α)` for this `(D, G)`.
    const TABLE: &'static AlbedoTable;
}

impl Ggx {
    /// Both tables of GGX.
    pub(crate) const TABLES: EnergyTables = EnergyTables {
        height_correlated: &albedo_data::GGX_HEIGHT_CORRELATED,
        separable: &albedo_data::GGX_SEPARABLE,
    };
}

impl Beckmann {
    /// Both tables of Beckmann.
    pub(crate) const TABLES: EnergyTables = EnergyTables {
        height_correlated: &albedo_data::BECKMANN_HEIGHT_CORRELATED,
        separable: &albedo_data::BECKMANN_SEPARABLE,
    };
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

/// The node coordinate `μ_ref,j = (j/63)²` of column `j` (see [`node_scale`];
/// the generator evaluates column 0 at `μ_ref = 10⁻⁶`).
pub const fn mu_node(j: usize) -> f32 {
    let x = j as f32 / (N_MU - 1) as f32;
    x * x
}

/// Smallest tabulated roughness (row 0), [`MIN_ALPHA`](super::MIN_ALPHA).
const ALPHA_MIN: f32 = super::MIN_ALPHA;

/// `α_k = α_min + (1 − α_min)(k/31)³` of row `k`.
pub const fn alpha_node(k: usize) -> f32 {
    let s = k as f32 / (N_ALPHA - 1) as f32;
    ALPHA_MIN + (1.0 - ALPHA_MIN) * (s * s * s)
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
    // `s ∈ [0, n − 1]` here, so the conversion never saturates; through
    // `u32` it is one instruction (to `usize` it handles `2⁶³` and above).
    let i = (s.min(last) as u32).min(n as u32 - 2);
    // `i ≤ n − 2`, so `i + 1` is a valid index.
    (i as usize, s - i as f32)
}

impl AlbedoTable {
    /// `E(μ, α)` for `μ = cos θo ∈ [0, 1]` (clamped, NaN → 0) and
    /// `α ∈ [α_min, 1]`.
    ///
    /// Interpolation in `α` at fixed Smith variable `a = cot θ / α` (not at
    /// fixed `μ`): the albedo of a rough surface depends on `ωo` mostly
    /// through `α tan θo` (Smith's `Λ` is a function of `a` alone; Heitz 2014,
    /// eq. 72), so the steep grazing dip of `E`, which sits at `μ ∼ α`, moves
    /// with `α`, and interpolating at fixed `μ` would smear it. Row `r` is
    /// therefore read at `μ'` with `tan θ' = (α/α_r) tan θ`, linear in `√μ'`
    /// between its nodes, and the four nearest rows are combined by a
    /// Catmull–Rom spline in `∛(α − α_min)` (the outermost rows continued
    /// linearly). `α` is clamped to `[α_min, 1]` (NaN → `α_min`).
    pub fn albedo(&self, mu: f32, alpha: f32) -> f32 {
        // One code path for the plain and the prepared read: the reader's
        // construction is the roughness half of the work.
        AlbedoReader::new(alpha).albedo(self, mu)
    }
}

/// [`AlbedoTable::albedo`] at one roughness, with the roughness work done
/// once: the four rows of the Catmull–Rom spline in `∛(α − α_min)`, each
/// row's tangent scaling `k_r = (α ρ(α_r)/α_r)²`, and the spline's basis
/// weights (the outermost rows' linear continuation folded in):
///
/// ```text
/// E(μ, α) = Σ_r w_r · row_r(μ'_r),   μ'_r = μ / √(μ² + k_r sin²θ),
/// w = ½ (−t + 2t² − t³,  2 − 5t² + 3t³,  t + 4t² − 3t³,  −t² + t³)
/// ```
///
/// A material that reads `E(·, α)` at every call at one `α` builds this at
/// construction (one cube root and four scalings) and skips them per call.
/// Equal to [`AlbedoTable::albedo`] up to rounding (the spline summed by
/// weights rather than by Horner's rule; tested within `2·10⁻⁶`).
///
/// ```
/// use radiometry_brdfs::microfacet::{AlbedoReader, AlbedoTable, EnergyTable, Ggx, HeightCorrelated};
/// let t: &AlbedoTable = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
/// let r = AlbedoReader::new(0.3);
/// assert!((r.albedo(t, 0.5) - t.albedo(0.5, 0.3)).abs() < 2e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AlbedoReader {
    /// The first of the four consecutive rows `row..row + 4` the spline
    /// reads (at the table's edges the outermost row's weight is 0).
    row: u8,
    /// Whether the four rows share one tangent scaling (`k2` all the same
    /// bits: every row below [`ALPHA_REF`]), so that one coordinate serves
    /// them all.
    shared: bool,
    /// The table's roughness coordinate [`alpha_axis`]`(α)`, kept for the
    /// other global tables on the same axis (`Ē₁`, the metal's sampler rows).
    axis: f32,
    k2: [f32; 4],
    w: [f32; 4],
}

/// The roughness coordinate of the global GGX tables, `x = ∛((α −
/// α_min)/(1 − α_min)) ∈ [0, 1]` with `α` clamped to `[α_min, 1]` (NaN →
/// `α_min`, so `x = 0`): the `E₁` rows sit at `x = r/31`, as do `Ē₁` and
/// the metal's sampler rows. One cube root per roughness serves them all.
#[inline]
pub(crate) fn alpha_axis(alpha: f32) -> f32 {
    let alpha = if alpha > ALPHA_MIN {
        alpha.min(1.0)
    } else {
        ALPHA_MIN
    };
    libm::cbrtf((alpha - ALPHA_MIN) / (1.0 - ALPHA_MIN))
}

/// `ρ(α_r)/α_r` per row `r` (see [`node_scale`]): row `r` is read at the
/// tangent scaling `q = α ρ(α_r)/α_r`, so a reader's construction needs no
/// division. Below [`ALPHA_REF`] the quotient is `1/ALPHA_REF` exactly
/// (`ρ(α_r) = α_r/ALPHA_REF`), stored as that one constant: computed as
/// `(α_r/ALPHA_REF)/α_r` it rounds one ulp low on rows 6 and 12, and every
/// reader whose four rows include one of them (`α ∈ [0.0043, 0.0117)` and
/// `[0.034, 0.092)`) would miss the shared coordinate.
const ROW_SCALE: [f32; N_ALPHA] = {
    let mut t = [0.0f32; N_ALPHA];
    let mut r = 0;
    while r < N_ALPHA {
        let ar = alpha_node(r);
        t[r] = if ar < ALPHA_REF { 1.0 / ALPHA_REF } else { 1.0 / ar };
        r += 1;
    }
    t
};

impl AlbedoReader {
    /// The roughness coordinate [`alpha_axis`] of this reader's `α`.
    #[inline]
    pub(crate) fn axis(&self) -> f32 {
        self.axis
    }

    /// The reader of `E(·, α)`; `α` is clamped to `[α_min, 1]` (NaN →
    /// `α_min`) as [`AlbedoTable::albedo`] clamps it.
    #[inline(always)]
    pub fn new(alpha: f32) -> Self {
        let axis = alpha_axis(alpha);
        let alpha = if alpha > ALPHA_MIN {
            alpha.min(1.0)
        } else {
            ALPHA_MIN
        };
        let (k, t) = cell(axis, N_ALPHA);
        let (t2, t3) = (t * t, t * t * t);
        let mut w = [
            0.5 * (-t + 2.0 * t2 - t3),
            0.5 * (2.0 - 5.0 * t2 + 3.0 * t3),
            0.5 * (t + 4.0 * t2 - 3.0 * t3),
            0.5 * (t3 - t2),
        ];
        // Four consecutive rows `first..first + 4`: at the table's edges the
        // spline's outer row is continued linearly from the two inner ones
        // (p₀ = 2p₁ − p₂ at the first cell, p₃ = 2p₂ − p₁ at the last) and
        // the row left over gets weight 0.
        let first = if k == 0 {
            // p₀ = 2p₁ − p₂: rows 0, 1, 2 (and 3, weight 0).
            w = [w[1] + 2.0 * w[0], w[2] - w[0], w[3], 0.0];
            0
        } else if k + 2 >= N_ALPHA {
            // p₃ = 2p₂ − p₁: rows k − 1, k, k + 1 (and k − 2, weight 0).
            w = [0.0, w[0], w[1] - w[3], w[2] + 2.0 * w[3]];
            k - 2
        } else {
            k - 1
        };
        let mut k2 = [0.0f32; 4];
        for (i, k2) in k2.iter_mut().enumerate() {
            let r = (first + i).min(N_ALPHA - 1);
            let q = alpha * ROW_SCALE.get(r).copied().unwrap_or(1.0);
            *k2 = q * q;
        }
        // Rows below ALPHA_REF share the scaling (α/ALPHA_REF)² (their
        // `ρ(α_r)/α_r` is the one constant 1/ALPHA_REF): where the four are
        // the same bits, one coordinate serves them all, and the read is bit
        // for bit the four-lane one.
        let shared = k2.iter().all(|&k| k.to_bits() == k2[0].to_bits());
        Self {
            row: first as u8,
            shared,
            axis,
            k2,
            w,
        }
    }

    /// `E(μ, α)` from `table` for `μ = cos θo ∈ [0, 1]` (clamped, NaN → 0),
    /// in `[0, 1]`. The four rows' coordinates go through one four-lane
    /// pass (two lane square roots and a division; the lane root is one vector
    /// instruction with the `simd` feature), lane for lane the operations of
    /// [`AlbedoTable::albedo`]'s `rescale_mu` and `lerp_row`.
    #[inline]
    pub fn albedo(&self, table: &AlbedoTable, mu: f32) -> f32 {
        let mu = if mu > 0.0 { mu.min(1.0) } else { 0.0 };
        let s2 = (1.0 - mu) * (1.0 + mu);
        let first = usize::from(self.row);
        let Some(rows) = table.values.get(first..first + 4) else {
            return 0.0;
        };
        let acc = if self.shared {
            self.shared_sum(rows, mu, s2)
        } else {
            // μ'_r = min(μ/√(μ² + k_r s²), 1), 0 where the root's argument is 0.
            let d = Vec4::splat(mu * mu) + Vec4::from_array(self.k2) * s2;
            let q = (Vec4::splat(mu) / sqrt4(d)).min(Vec4::ONE);
            let q = Vec4::select(d.cmpgt(Vec4::ZERO), q, Vec4::ZERO);
            // x_r = √μ'_r, the row coordinate.
            let x = sqrt4(q).to_array();
            let mut acc = 0.0f32;
            for ((row, &x), &w) in rows.iter().zip(&x).zip(&self.w) {
                let (j, t) = cell(x, N_MU);
                let t = if j == 0 { t * t } else { t };
                let (a, b) = (row[j], row[j + 1]);
                acc += w * (a + t * (b - a));
            }
            acc
        };
        acc.clamp(0.0, 1.0)
    }

    /// [`albedo`](Self::albedo) at `μ = 1` (normal incidence), bit for bit:
    /// there `s² = 0`, every row's `μ' = 1/√1 = 1` and `x = √1 = 1` exactly
    /// (the tangent scalings `k_r` are finite), so the cell is the last one,
    /// `(j, t) = (N_μ − 2, 1)`, whatever the reader — the roots and the
    /// division the general read makes on the way are left out.
    #[inline]
    pub(crate) fn albedo_at_normal(&self, table: &AlbedoTable) -> f32 {
        let first = usize::from(self.row);
        let Some(rows) = table.values.get(first..first + 4) else {
            return 0.0;
        };
        let (j, t) = (N_MU - 2, 1.0f32);
        let acc = if self.shared {
            self.shared_sum_in(rows, j, t)
        } else {
            let mut acc = 0.0f32;
            for (row, &w) in rows.iter().zip(&self.w) {
                let (a, b) = (row[j], row[j + 1]);
                acc += w * (a + t * (b - a));
            }
            acc
        };
        acc.clamp(0.0, 1.0)
    }

    /// Whether the four rows share one coordinate (see the field `shared`).
    #[inline]
    pub(crate) fn is_shared(&self) -> bool {
        self.shared
    }

    /// [`albedo`](Self::albedo) of a reader whose rows share one coordinate
    /// ([`is_shared`](Self::is_shared)), `μ ∈ [0, 1]`.
    #[inline(always)]
    pub(crate) fn albedo_shared(&self, table: &AlbedoTable, mu: f32) -> f32 {
        let first = usize::from(self.row);
        match table.values.get(first..first + 4) {
            Some(rows) => self.shared_sum(rows, mu, (1.0 - mu) * (1.0 + mu)).clamp(0.0, 1.0),
            None => 0.0,
        }
    }

    /// The weighted sum of the four rows at the one coordinate `√μ'`,
    /// `μ' = min(μ/√(μ² + k s²), 1)` (0 where the root's argument is 0):
    /// the rows' spline at the cell's two nodes, then the chord between them,
    ///
    /// ```text
    /// E = a + t (b − a),   a = Σ_r w_r row_r[j],   b = Σ_r w_r row_r[j+1]
    /// ```
    ///
    /// (the same sums a combined row holds, so a read of that row is this
    /// read bit for bit).
    #[inline(always)]
    fn shared_sum(&self, rows: &[[f32; N_MU]], mu: f32, s2: f32) -> f32 {
        let (j, t) = self.shared_cell(mu, s2);
        self.shared_sum_in(rows, j, t)
    }

    /// [`shared_sum`](Self::shared_sum) in the cell `(j, t)`.
    #[inline(always)]
    fn shared_sum_in(&self, rows: &[[f32; N_MU]], j: usize, t: f32) -> f32 {
        let node = |j: usize| {
            let mut acc = 0.0f32;
            for (row, &w) in rows.iter().zip(&self.w) {
                acc += w * row.get(j).copied().unwrap_or(0.0);
            }
            acc
        };
        let (a, b) = (node(j), node(j + 1));
        a + t * (b - a)
    }

    /// The cell `(j, t)` of the rows' shared coordinate `x = √μ'`, `μ' =
    /// min(μ/√(μ² + k s²), 1)` (0 where the root's argument is 0), `t`
    /// squared in the first cell.
    #[inline(always)]
    fn shared_cell(&self, mu: f32, s2: f32) -> (usize, f32) {
        let d = mu * mu + self.k2[0] * s2;
        let q = if d > 0.0 {
            (mu / radiometry::math::sqrtf(d)).min(1.0)
        } else {
            0.0
        };
        let (j, t) = cell(radiometry::math::sqrtf(q), N_MU);
        (j, if j == 0 { t * t } else { t })
    }

    /// The four rows of a reader whose rows share one coordinate
    /// ([`is_shared`](Self::is_shared)) summed once per node, `c_j = Σ_r
    /// w_r row_r[j]`: what [`albedo_combined_lanes`](Self::albedo_combined_lanes)
    /// reads (feature `simd`).
    #[cfg(feature = "simd")]
    #[inline]
    pub(crate) fn combined_row(&self, table: &AlbedoTable) -> [f32; N_MU] {
        let first = usize::from(self.row);
        let mut out = [0.0f32; N_MU];
        if let Some([r0, r1, r2, r3]) = table.values.get(first..first + 4) {
            let [w0, w1, w2, w3] = self.w;
            // `shared_sum`'s node sum, node by node (in vector form).
            for (j, o) in out.iter_mut().enumerate() {
                *o = (((0.0 + w0 * r0[j]) + w1 * r1[j]) + w2 * r2[j]) + w3 * r3[j];
            }
        }
        out
    }
}

/// [`AlbedoReader::albedo`] in vector lanes (feature `simd`): the
/// same operations lane for lane, so the same bits.
#[cfg(feature = "simd")]
impl AlbedoReader {
    /// `E(μ, α)` at each lane's `μ ∈ [0, 1]`: [`albedo`](Self::albedo) lane
    /// for lane (the rows' shared coordinate, or each row's own).
    #[inline(always)]
    pub(crate) fn albedo_lanes(&self, table: &AlbedoTable, mu: crate::simd::Vf) -> crate::simd::Vf {
        use crate::simd::Vf;
        let first = usize::from(self.row);
        let Some(rows) = table.values.get(first..first + 4) else {
            return Vf::ZERO;
        };
        let s2 = (Vf::ONE - mu) * (Vf::ONE + mu);
        let mut acc = Vf::ZERO;
        if self.shared {
            // One coordinate for the four rows: the spline at the cell's two
            // nodes, then the chord (the scalar `shared_sum`'s order).
            let (cells, t) = cell_lanes(mu, s2, self.k2[0]);
            let (mut a, mut b) = (Vf::ZERO, Vf::ZERO);
            for (row, &w) in rows.iter().zip(&self.w) {
                let (ra, rb) = row_nodes_lanes(row, &cells);
                a += Vf::splat(w) * ra;
                b += Vf::splat(w) * rb;
            }
            acc = a + t * (b - a);
        } else {
            for ((row, &w), &k2) in rows.iter().zip(&self.w).zip(&self.k2) {
                let (cells, t) = cell_lanes(mu, s2, k2);
                acc += Vf::splat(w) * row_lerp_lanes(row, &cells, t);
            }
        }
        acc.max(Vf::ZERO).min(Vf::ONE)
    }
}

/// A row's cell at each lane's `μ` (`s2 = 1 − μ²`) for the tangent scaling
/// `k2`, as [`AlbedoReader::albedo`] finds it: the coordinate `x = √μ'`,
/// `μ' = min(μ/√(μ² + k2 s2), 1)` (0 where the root's argument is 0), then
/// `cell(x, N_MU)` — `s = min(x (n − 1), n − 1)` (0 for `x ≤ 0`), the cell
/// `i = min(s, n − 2)` truncated, `t = s − i` (squared in the first cell).
#[cfg(feature = "simd")]
#[inline(always)]
fn cell_lanes(
    mu: crate::simd::Vf,
    s2: crate::simd::Vf,
    k2: f32,
) -> ([usize; crate::simd::LANES], crate::simd::Vf) {
    use crate::simd::Vf;
    let d = mu * mu + Vf::splat(k2) * s2;
    let q = d.simd_gt(Vf::ZERO).select((mu / d.sqrt()).min(Vf::ONE), Vf::ZERO);
    let x = q.sqrt();
    let s = x.simd_gt(Vf::ZERO).select(
        (x * Vf::splat((N_MU - 1) as f32)).min(Vf::splat(N_MU as f32 - 1.0)),
        Vf::ZERO,
    );
    let (cells, i_f) = crate::simd::cells_of(s.min(Vf::splat((N_MU - 2) as f32)));
    let t = s - i_f;
    (cells, i_f.simd_eq(Vf::ZERO).select(t * t, t))
}

/// `a + t (b − a)` of one row at each lane's cell (`a`, `b` the entries at
/// the cell and the next one, read per lane).
#[cfg(feature = "simd")]
#[inline(always)]
fn row_lerp_lanes(
    row: &[f32; N_MU],
    cells: &[usize; crate::simd::LANES],
    t: crate::simd::Vf,
) -> crate::simd::Vf {
    let (a, b) = row_nodes_lanes(row, cells);
    a + t * (b - a)
}

/// The entries of one row at each lane's cell and the next node, read per
/// lane (0 past the row's end).
#[cfg(feature = "simd")]
#[inline(always)]
pub(crate) fn row_nodes_lanes(
    row: &[f32],
    cells: &[usize; crate::simd::LANES],
) -> (crate::simd::Vf, crate::simd::Vf) {
    use crate::simd::{LANES, Vf};
    let (mut a, mut b) = ([0.0f32; LANES], [0.0f32; LANES]);
    for ((a, b), &j) in a.iter_mut().zip(&mut b).zip(cells) {
        (*a, *b) = (
            row.get(j).copied().unwrap_or(0.0),
            row.get(j + 1).copied().unwrap_or(0.0),
        );
    }
    (Vf::from(a), Vf::from(b))
}

#[cfg(feature = "simd")]
impl AlbedoReader {
    /// [`albedo`](Self::albedo) of a reader with a shared coordinate from its
    /// [`combined_row`](Self::combined_row), at each lane's `μ ∈ [0, 1]`:
    /// the coordinate's cell per lane, two entries of the row per lane, the
    /// chord in vector form — bit for bit the scalar read of the four rows.
    #[inline(always)]
    pub(crate) fn albedo_combined_lanes(&self, row: &[f32; N_MU], mu: crate::simd::Vf) -> crate::simd::Vf {
        use crate::simd::Vf;
        let s2 = (Vf::ONE - mu) * (Vf::ONE + mu);
        let (cells, t) = cell_lanes(mu, s2, self.k2[0]);
        let (a, b) = row_nodes_lanes(row, &cells);
        (a + t * (b - a)).max(Vf::ZERO).min(Vf::ONE)
    }
}

/// Roughness from which a row's nodes are the plain `μ_j = (j/63)²`; below
/// it they crowd towards grazing with `α` (see [`node_scale`]).
pub const ALPHA_REF: f32 = 0.2;

/// `ρ(α) = min(α/ALPHA_REF, 1)`: the nodes of a row (and of a
/// [`KullaConty`](super::KullaConty) instance) at roughness `α` are
/// `tan θ_j = tan θ_ref,j / ρ(α)` with `cos θ_ref,j = (j/63)²`, so that for
/// `α < 0.2` they follow the albedo's grazing dip, which sits at `μ ∼ α`.
/// A direction's node coordinate is `μ_ref = μ / √(μ² + ρ² sin²θ)`.
#[inline]
pub fn node_scale(alpha: f32) -> f32 {
    if alpha > 0.0 {
        (alpha / ALPHA_REF).min(1.0)
    } else {
        0.0
    }
}

/// `μ' = cos θ'` with `tan θ' = √k2 · tan θ`, from `μ = cos θ ≥ 0` and
/// `s2 = sin²θ`: `μ' = μ / √(μ² + k2 s2)`, in `[0, 1]` (0 when both vanish).
#[inline(always)]
pub(crate) fn rescale_mu(mu: f32, s2: f32, k2: f32) -> f32 {
    let d = mu * mu + k2 * s2;
    if d > 0.0 {
        (mu / radiometry::math::sqrtf(d)).min(1.0)
    } else {
        0.0
    }
}

/// The row value at `μ` (clamped to `[0, 1]`, NaN → 0): linear in `√μ`
/// between nodes, except in the first cell `μ < μ_1 = 63⁻²`, where it is
/// linear in `μ` (towards grazing `1 − E` vanishes like `μ` for the
/// height-correlated G2 — measured: `1.4·10⁻⁵` at `μ = 10⁻⁶`, `1.1·10⁻³` at
/// `10⁻⁴` for GGX `α = 1` — and a chord in `√μ` would overstate it).
#[inline(always)]
pub(crate) fn lerp_row(row: &[f32; N_MU], mu: f32) -> f32 {
    let x = if mu > 0.0 {
        radiometry::math::sqrtf(mu.min(1.0))
    } else {
        0.0
    };
    let (j, t) = cell(x, N_MU);
    let t = if j == 0 { t * t } else { t };
    let (a, b) = (row[j], row[j + 1]);
    a + t * (b - a)
}

/// `2 ∫₀¹ r(μ) μ dμ` of a function `r` given on cells `[nodes[j], nodes[j+1]]`
/// that cover `[0, 1]`, each cell optionally split at `split(j)` (a kink of
/// `r` inside it): a 4-point Gauss–Legendre rule per piece (exact for
/// polynomials of degree 7 in `μ`; the functions integrated here are linear
/// in a smooth monotone map of `μ` on each piece).
pub(crate) fn cosine_average(
    nodes: &[f32; N_MU],
    split: impl Fn(usize) -> Option<f32>,
    r: impl Fn(f32) -> f32,
) -> f32 {
    // Gauss–Legendre, 4 points on [0, 1] (A&S 25.4.29 nodes ±0.8611363, ±0.3399810).
    const G: [(f32, f32); 4] = [
        (0.069_431_84, 0.173_927_42),
        (0.330_009_5, 0.326_072_58),
        (0.669_990_5, 0.326_072_58),
        (0.930_568_15, 0.173_927_42),
    ];
    let piece = |a: f32, b: f32| {
        let h = b - a;
        let mut s = 0.0f32;
        for &(t, w) in &G {
            let mu = a + t * h;
            s += w * r(mu) * mu;
        }
        s * h
    };
    let mut sum = 0.0f32;
    for j in 0..N_MU - 1 {
        let (a, b) = (nodes[j], nodes[j + 1]);
        sum += match split(j) {
            Some(m) if m > a && m < b => piece(a, m) + piece(m, b),
            _ => piece(a, b),
        };
    }
    (2.0 * sum).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spline as [`AlbedoTable`]'s docs state it, summed by Horner's
    /// rule from the four rows' values (the form the reader's basis weights
    /// replace), written out here as the reader's reference.
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

    /// `E(μ, α)` by rows and Catmull–Rom (see [`AlbedoTable::albedo`]).
    fn horner_albedo(tab: &AlbedoTable, mu: f32, alpha: f32) -> f32 {
        let mu = if mu > 0.0 { mu.min(1.0) } else { 0.0 };
        let alpha = if alpha > ALPHA_MIN {
            alpha.min(1.0)
        } else {
            ALPHA_MIN
        };
        let s2 = (1.0 - mu) * (1.0 + mu);
        let (k, t) = cell(libm::cbrtf((alpha - ALPHA_MIN) / (1.0 - ALPHA_MIN)), N_ALPHA);
        let at = |r: usize| {
            let r = r.min(N_ALPHA - 1);
            let ar = alpha_node(r);
            // a-invariant μ' at α_r (tan θ' = (α/α_r) tan θ), then row r's node
            // coordinate (tan θ_ref = ρ(α_r) tan θ'): one tangent scaling.
            let q = node_scale(ar) * (alpha / ar);
            lerp_row(&tab.values[r], rescale_mu(mu, s2, q * q))
        };
        let p1 = at(k);
        let p2 = at(k + 1);
        let p0 = if k >= 1 { at(k - 1) } else { 2.0 * p1 - p2 };
        let p3 = if k + 2 < N_ALPHA { at(k + 2) } else { 2.0 * p2 - p1 };
        catmull_rom([p0, p1, p2, p3], t).clamp(0.0, 1.0)
    }
    /// Every reader whose four spline rows (weighted or not) all lie below
    /// `ALPHA_REF` reads them at one shared coordinate, and no other does:
    /// checked at every `α` between nodes and at the nodes themselves.
    #[test]
    fn rows_below_alpha_ref_share_one_coordinate() {
        extern crate std;
        let mut alphas: std::vec::Vec<f32> = (0..N_ALPHA).map(alpha_node).collect();
        for k in 0..N_ALPHA - 1 {
            let (a, b) = (alpha_node(k), alpha_node(k + 1));
            alphas.extend((1..16).map(|i| a + (b - a) * i as f32 / 16.0));
        }
        for alpha in alphas {
            let r = AlbedoReader::new(alpha);
            let first = usize::from(r.row);
            let below = (first..first + 4).all(|k| alpha_node(k.min(N_ALPHA - 1)) < ALPHA_REF);
            assert_eq!(r.is_shared(), below, "alpha {alpha}: rows {first}..{}", first + 4);
        }
    }

    /// The reader (the basis weights, the four-lane pass) equals the spline
    /// summed by Horner's rule to rounding, on random `(μ, α)` and the
    /// domain's edges (the outermost rows' continuation included).
    #[test]
    fn reader_equals_the_horner_spline() {
        let table = &albedo_data::GGX_HEIGHT_CORRELATED;
        let mut u = crate::test_stream::uniforms(0x2545_f491_4f6c_dd1d);
        for n in 0..20_000 {
            let alpha = match n % 40 {
                0 => ALPHA_MIN,
                1 => 1.0,
                2 => alpha_node(1 + n % 30),
                _ => u() * u() * u(),
            };
            let mu = match n % 11 {
                0 => 0.0,
                1 => 1.0,
                _ => u() * u(),
            };
            let (a, b) = (table.albedo(mu, alpha), horner_albedo(table, mu, alpha));
            assert!((a - b).abs() <= 2e-6, "μ {mu} α {alpha}: {a} vs {b}");
        }
    }

    #[test]
    fn cosine_average_is_exact_for_polynomials() {
        let nodes: [f32; N_MU] = core::array::from_fn(mu_node);
        assert!((cosine_average(&nodes, |_| None, |_| 1.0) - 1.0).abs() < 1e-6);
        // 2∫ μ³ μ dμ = 2/5.
        assert!((cosine_average(&nodes, |_| None, |m| m * m * m) - 0.4).abs() < 1e-6);
        let half: [f32; N_MU] = core::array::from_fn(mu_node);
        // A kink at μ = 0.3 inside a cell: 2∫₀^0.3 μ dμ = 0.09 exactly with the split.
        let j = (0..N_MU - 1)
            .find(|&j| half[j] < 0.3 && half[j + 1] > 0.3)
            .unwrap();
        let split = |k: usize| (k == j).then_some(0.3f32);
        let v = cosine_average(&half, split, |m| if m < 0.3 { 1.0 } else { 0.0 });
        assert!((v - 0.09).abs() < 1e-6, "{v}");
    }

    #[test]
    fn cell_stays_in_range() {
        for x in [f32::NAN, -1.0, 0.0, 0.5, 1.0, 2.0, f32::INFINITY] {
            let (i, t) = cell(x, N_MU);
            assert!(i + 1 < N_MU && (0.0..=1.0).contains(&t), "{x}: {i} {t}");
        }
    }

    #[test]
    fn albedo_hits_nodes() {
        let t = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        for k in [0usize, 1, 7, 31] {
            for j in [1usize, 5, 63] {
                let (m, a) = (mu_node(j), alpha_node(k));
                let rho = node_scale(a);
                let mu = rescale_mu(m, (1.0 - m) * (1.0 + m), 1.0 / (rho * rho));
                let e = t.albedo(mu, a);
                assert!(
                    (e - t.values[k][j]).abs() < 2e-6,
                    "{k} {j}: {e} vs {}",
                    t.values[k][j]
                );
            }
        }
    }

    #[test]
    fn rescale_mu_is_the_tangent_scaling() {
        // tan θ = 0.75 → tan θ' = 1.5 (k2 = 4): μ' = 1/√(1 + 2.25).
        let m = rescale_mu(0.8, 0.36, 4.0);
        assert!((m - 1.0 / 3.25f32.sqrt()).abs() < 1e-6);
        assert_eq!(rescale_mu(0.0, 0.0, 1.0), 0.0);
        assert_eq!(rescale_mu(1.0, 0.0, 1e6), 1.0);
    }
}
