//! Global energy tables of GGX (height-correlated Smith `G2`) with a Fresnel
//! factor: the directional albedo of a dielectric interface `E(μ, α, η)` on
//! both sides of `η = 1`, its hemispherical average `Ē(α, η)`, and the two
//! moments that make the albedo of every Fresnel term linear in its
//! parameters (Schlick, F82-tint) exact per channel.
//!
//! # What the tables hold
//!
//! With `E₁(μ, α)` the albedo with `F = 1` ([`AlbedoTable`])
//! and `c = ωo·h`,
//!
//! ```text
//! E_F(μo, α) = ∫_H F(c) D(h) G2(ωi, ωo) / (4 μo) dωi        (single scattering)
//! R_F(μo, α) = E_F / E₁                                       (the lobe's mean Fresnel factor)
//! ```
//!
//! * **Dielectric** (`F` the exact unpolarised Fresnel reflectance of a real
//!   relative index `η`): [`dielectric_albedo`] `= E₁ · R`, with `R` read
//!   from `u16` nodes, `33 × 32 × 32` for `η > 1` and `65 × 32 × 16` for
//!   `η < 1` (67.6 KB and 66.6 KB): `x = √μ` for `η > 1`; for `η < 1` the `μ`
//!   axis is split at the critical cosine `μc = √(1 − η²)`, `x = ½ ∓ ½
//!   s(|μ − μc|)` with `s(d) = 0.3 √(d/span) + 0.7 asinh(d/w)/asinh(span/w)`,
//!   `w = max(α η, 10⁻⁴)`: total internal
//!   reflection starts on a node line for every `η`, the nodes near it are
//!   as fine as the roughness rounds it (each roughness row read in its own
//!   units of `w`), and far from it `√`-spaced, where the Fresnel factor goes
//!   like `√(μ − μc)`.
//!   Roughness nodes `√α_k = 0.01 + 0.99 k/31`; index nodes `z_l = l/31`,
//!   `z = F0^¼`, `F0 = ((η − 1)/(η + 1))²` (as Cycles and Adobe's OpenPBR
//!   BSDF parameterise theirs). Trilinear interpolation, except that for
//!   `η > 1` the first roughness row (`α₀ = 10⁻⁴`, a smooth interface to
//!   `O(α₀²)`) is read as the exact Fresnel factor `F(μ)` rather than
//!   interpolated: below the second node the ratio is `(1 − f_α) F(μ) +
//!   f_α R_{k=1}` (linear in `z`, `F0 ∝ z⁴`, misses `F` at a smooth coat's
//!   normal incidence by up to 0.7 %).
//! * **Average** [`dielectric_average`] `Ē(α, η) = 2∫₀¹ E_F(μ) μ dμ`:
//!   `32 × 32` (`η > 1`) and `16 × 32` (`η < 1`) `f32`, bilinear.
//! * **Moments** `R5 = M5/E₁`, `R6 = M6/E₁` of `F = (1 − c)⁵` and
//!   `F = c (1 − c)⁶` on `33 × 32` `f32` nodes: for `F = f0 + (1 − f0)(1 −
//!   c)⁵ − a c (1 − c)⁶` (Schlick with `a = 0`, F82-tint), `R_F = f0 + (1 −
//!   f0) R5 − a R6` exactly ([`linear_fresnel_ratio`]).
//!
//! The values were computed by `tools/examples/energy_tables.rs` (product
//! Gauss–Legendre quadrature in `f64` on the square of the visible-normal
//! map; its header states the convergence of every table), written out as
//! `fresnel_table_data.rs`. The tests in `brdfs/tests/fresnel_tables.rs`
//! regenerate a sample of nodes and measure the interpolation error at cell
//! midpoints and random points against an independent adaptive quadrature
//! over the hemisphere; the errors they find are stated on each function.

use super::albedo_table::{AlbedoReader, AlbedoTable, EnergyTable};
use super::fresnel_table_data as data;
use super::{Ggx, HeightCorrelated, MAX_ETA};

/// The error this crate states for the tabulated albedo `E₁ · R` of a GGX
/// lobe with a Fresnel term linear in the moments (Schlick, F82-tint):
/// `2·10⁻³` (the moments converge to 3.7·10⁻⁴ and are smooth; `E₁`'s own
/// bound is 10⁻³).
pub const FRESNEL_TABLE_ERROR: f32 = 2e-3;

/// The error this crate states for [`dielectric_albedo`], from the
/// measurements of `tools/examples/energy_tables_check.rs` (10⁴ random
/// points against the generator's `f64` quadrature, 200 against the
/// hemisphere references): `η > 1`: `5·10⁻³` (worst seen 4.3·10⁻³, at
/// `α = 0.003` and 89°; 99 % of points below 8.7·10⁻⁴); `η < 1`: `10⁻²` for
/// `α ≥ 0.01`, `5·10⁻²` below (worst seen 5.0·10⁻², at `α = 0.0013` a
/// hair from the critical angle, where total internal reflection sets in
/// over a width `αη` far below a cell; 99 % of points below 3.9·10⁻³).
pub fn dielectric_error(alpha: f32, eta: f32) -> f32 {
    if eta >= 1.0 {
        5e-3
    } else if alpha >= 0.01 {
        1e-2
    } else {
        5e-2
    }
}

/// `μ` nodes per row.
pub const FT_NX: usize = 33;
/// Roughness nodes.
pub const FT_NA: usize = 32;
/// Index nodes (`z = F0^¼`).
pub const FT_NZ: usize = 32;
/// `μ` nodes per row of the `η < 1` table.
pub const FT_NX_IN: usize = 65;
/// Index nodes of the `η < 1` table.
pub const FT_NZ_IN: usize = 16;

/// Cell and fraction of `s ∈ [0, n − 1]` (clamped; NaN → 0).
#[inline(always)]
fn cell_of(s: f32, n: usize) -> (usize, f32) {
    let s = if s > 0.0 {
        s.min(n.saturating_sub(1) as f32)
    } else {
        0.0
    };
    // `s ∈ [0, n − 1]`: through `u32` the conversion is one instruction.
    let i = ((s as u32) as usize).min(n.saturating_sub(2));
    (i, (s - i as f32).clamp(0.0, 1.0))
}

/// The roughness coordinate: `(√α − 0.01)/0.99 · 31`.
#[inline(always)]
fn alpha_coord(alpha: f32) -> (usize, f32) {
    let t = radiometry::math::sqrtf(alpha.clamp(1e-4, 1.0));
    cell_of((t - 0.01) / 0.99 * (FT_NA - 1) as f32, FT_NA)
}

/// The roughness node `α_k = (0.01 + 0.99 k/31)²`.
#[inline(always)]
fn alpha_node_f32(k: usize) -> f32 {
    let t = 0.01 + 0.99 * k as f32 / (FT_NA - 1) as f32;
    t * t
}

/// `z = F0^¼ = √|(η − 1)/(η + 1)|` on its table's nodes, and whether
/// `η < 1`.
#[inline(always)]
fn index_coord(eta: f32) -> (usize, f32, bool) {
    let z = index_z(eta);
    let inside = eta < 1.0;
    let nz = if inside { FT_NZ_IN } else { FT_NZ };
    let (l, f) = cell_of(z * (nz - 1) as f32, nz);
    (l, f, inside)
}

/// `z = √|(η − 1)/(η + 1)|`, capped at 1 (1 where not finite).
#[inline(always)]
fn index_z(eta: f32) -> f32 {
    let r = ((eta - 1.0) / (eta + 1.0)).abs();
    radiometry::math::sqrtf(if r.is_finite() { r.min(1.0) } else { 1.0 })
}

/// The cells of `(α, η)` on the `η > 1` table's grid whichever side of 1
/// `η` lies (`η < 1` at the node of `1/η`, the same `z`): the index cell
/// `(l, f_z)` and the roughness cell `(k, f_a)` — the rows of the diffuse
/// sampler ([`TransmissionSampler`](super::transmission_sampler)), which
/// sit at that table's nodes. For `η ≥ 1` they are [`RatioCells::new`]'s.
#[inline(always)]
pub(crate) fn outside_cells(alpha: f32, eta: f32) -> ((usize, f32), (usize, f32)) {
    (
        cell_of(index_z(eta) * (FT_NZ - 1) as f32, FT_NZ),
        alpha_coord(alpha),
    )
}

/// The ratio table's cells of one `(α, η)`: the index cell `(l, f_z, η <
/// 1)` ([`index_coord`]: `z = √|(η − 1)/(η + 1)|`) and the roughness cell
/// `(k, f_a)` ([`alpha_coord`]: `(√α − 0.01)/0.99 · 31`). Computed once,
/// they serve every table on the same grid: the dielectric readers, the
/// average `Ē`, and the diffuse sampler's rows
/// ([`TransmissionSampler`](super::transmission_sampler)), which sit at the
/// `η > 1` table's nodes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RatioCells {
    pub(crate) index: (usize, f32, bool),
    pub(crate) alpha: (usize, f32),
}

impl RatioCells {
    /// The cells of `(α, η)` (clamped as [`dielectric_ratio`] clamps them).
    #[inline(always)]
    pub(crate) fn new(alpha: f32, eta: f32) -> Self {
        Self {
            index: index_coord(eta),
            alpha: alpha_coord(alpha),
        }
    }

    /// [`dielectric_average`]`(α', η)` at another roughness `α'` and this
    /// index, bit for bit (the index cell reused).
    #[inline(always)]
    pub(crate) fn average_at(&self, alpha: f32) -> f32 {
        average_in(self.index, alpha_coord(alpha))
    }
}

/// The `μ` coordinate `x ∈ [0, 1]` of a table (see the module docs).
#[cfg(test)]
#[inline(always)]
fn mu_coord(mu: f32, inside: bool, eta: f32, alpha: f32) -> f32 {
    let mu = mu.clamp(0.0, 1.0);
    if !inside {
        return radiometry::math::sqrtf(mu);
    }
    let mc = radiometry::math::sqrtf((1.0 - eta * eta).max(0.0));
    let w = (alpha * eta).max(1e-4);
    let side = |d: f32, span: f32| {
        if span <= 0.0 {
            return 0.0;
        }
        let d = d.max(0.0).min(span); // (no `clamp`: its bound assertion is a panic path)
        0.3 * radiometry::math::sqrtf(d / span) + 0.7 * libm::asinhf(d / w) / libm::asinhf(span / w)
    };
    if mu <= mc {
        0.5 - 0.5 * side(mc - mu, mc)
    } else {
        0.5 + 0.5 * side(mu - mc, 1.0 - mc)
    }
}

/// `R = E_F / E₁` of a GGX dielectric interface of relative index `η` at
/// `μ = cos θo` and roughness `α`, trilinear in the table's coordinates
/// (for `η > 1` below the second roughness node, the first node's row is the
/// exact Fresnel factor: see the module docs). In `[0, 1]`; `η = 1` gives 0.
pub fn dielectric_ratio(mu: f32, alpha: f32, eta: f32) -> f32 {
    DielectricRatioReader::new(alpha, eta).ratio(mu)
}

/// The directional albedo `E_F(μ, α, η) = E₁(μ, α) · R` of a GGX
/// (height-correlated) dielectric interface: one read of the `F = 1` table
/// and one of [`dielectric_ratio`].
pub fn dielectric_albedo(e1: &AlbedoTable, mu: f32, alpha: f32, eta: f32) -> f32 {
    (e1.albedo(mu, alpha) * dielectric_ratio(mu, alpha, eta)).clamp(0.0, 1.0)
}

/// [`dielectric_albedo`] at one `(α, η)`, with everything that does not
/// depend on `μ` done once: the `F = 1` table's rows ([`AlbedoReader`]),
/// the ratio table's four `(z, α)` corners and their bilinear weights, and
/// for `η < 1` each roughness row's critical-angle coordinate constants
/// (`μc`, `w_k = max(α_k η, 10⁻⁴)`, `1/asinh(span/w_k)`). Per call: one
/// `√μ` (or two `asinh` for `η < 1`) and the row reads,
///
/// ```text
/// E_F(μ) = E₁(μ) · Σ_c w_c · lerp(R_c[j], R_c[j+1], f_x(μ))
/// ```
///
/// Equal to [`dielectric_albedo`] up to rounding (tested within `2·10⁻⁶`).
/// A material built at every hit stores one per dielectric lobe.
///
/// ```
/// use radiometry_brdfs::microfacet::fresnel_table::{DielectricAlbedoReader, dielectric_albedo};
/// use radiometry_brdfs::microfacet::{AlbedoTable, EnergyTable, Ggx, HeightCorrelated};
/// let e1: &AlbedoTable = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
/// let r = DielectricAlbedoReader::new(0.2, 1.5);
/// assert!((r.albedo(0.7) - dielectric_albedo(e1, 0.7, 0.2, 1.5)).abs() < 2e-6);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricAlbedoReader {
    e1: AlbedoReader,
    ratio: DielectricRatioReader,
    /// Whether one `μ` coordinate serves the four rows of `E₁` and the ratio
    /// is read from the `η > 1` table alone (no exact smooth row): the
    /// straight-line read.
    fast: bool,
}

/// [`dielectric_ratio`] at one `(α, η)`: the ratio table's four `(z, α)`
/// corners and their bilinear weights, and for `η < 1` each roughness row's
/// critical-angle constants, computed once ([`dielectric_ratio`] is this
/// reader built and read once).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricRatioReader {
    /// Offset of column 0 of the corner `(l, k)`; the corners `(l, k+1)`,
    /// `(l+1, k)`, `(l+1, k+1)` follow at [`corner_offsets`] from it.
    base: u32,
    /// Their bilinear weights.
    w: [f32; 4],
    inside: bool,
    /// `η < 1`: the critical cosine `μc`.
    mc: f32,
    /// `η < 1`, per roughness row `k`, `k + 1`: `1/w_k`.
    inv_w: [f32; 2],
    /// `η < 1`, per roughness row: `1/asinh(μc/w_k)`, `1/asinh((1 − μc)/w_k)`
    /// (0 where the span is empty).
    norm: [[f32; 2]; 2],
    /// `η > 1` below the second roughness node: the weight of the first
    /// roughness row, read as the exact Fresnel factor of `η`, and that factor.
    exact: f32,
    /// `η² − 1` and `η²` of that factor ([`smooth_fresnel`]).
    eta2m1: f32,
    eta2: f32,
}

impl DielectricAlbedoReader {
    /// The reader of `E_F(·, α, η)` (the arguments clamped as
    /// [`dielectric_albedo`] clamps them).
    pub fn new(alpha: f32, eta: f32) -> Self {
        Self::with_average(alpha, eta).0
    }

    /// The reader and [`dielectric_average`]`(α, η)`, bit for bit, from one
    /// computation of the index and roughness cells (a prepared lobe keeps
    /// both: [`DielectricCells`](super::prepared::DielectricCells)).
    #[inline(always)]
    pub(crate) fn with_average(alpha: f32, eta: f32) -> (Self, f32) {
        Self::with_average_in(RatioCells::new(alpha, eta), alpha, eta)
    }

    /// [`with_average`](Self::with_average) from the ratio table's cells of
    /// `(α, η)` computed once ([`RatioCells::new`]), for a material whose
    /// other tables read the same cells.
    #[inline(always)]
    pub(crate) fn with_average_in(cells: RatioCells, alpha: f32, eta: f32) -> (Self, f32) {
        let (ratio, average) = DielectricRatioReader::with_average_in(cells, eta);
        let e1 = AlbedoReader::new(alpha);
        let reader = Self {
            e1,
            ratio,
            fast: e1.is_shared() && !ratio.inside && ratio.exact == 0.0,
        };
        (reader, average)
    }

    /// `R(μ) = E_F/E₁` (see [`dielectric_ratio`]), in `[0, 1]`.
    #[inline]
    pub fn ratio(&self, mu: f32) -> f32 {
        self.ratio.ratio(mu)
    }

    /// `E_F(μ, α, η) = E₁(μ, α) · R(μ)` (see [`dielectric_albedo`]), in `[0, 1]`.
    #[inline(always)]
    pub fn albedo(&self, mu: f32) -> f32 {
        let e1 = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        if !self.fast {
            return self.albedo_general(mu);
        }
        let mu = if mu > 0.0 { mu.min(1.0) } else { 0.0 };
        (self.e1.albedo_shared(e1, mu) * self.ratio.ratio_outside(mu)).clamp(0.0, 1.0)
    }

    /// [`albedo`](Self::albedo) and `E₁(μ)` from the one read of `E₁` it
    /// makes: `(E_F(μ), E₁(μ))`, the second bit for bit
    /// [`AlbedoReader::albedo`] of the GGX table at this roughness (the
    /// reader inside, [`e1_reader`](Self::e1_reader)). For a material with a
    /// second lobe of the same roughness that needs `E₁` (OpenPBR's metal
    /// under its specular layer).
    #[inline(always)]
    pub(crate) fn albedo_and_e1(&self, mu: f32) -> (f32, f32) {
        let table = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        if !self.fast {
            let e1 = self.e1.albedo(table, mu);
            return ((e1 * self.ratio.ratio(mu)).clamp(0.0, 1.0), e1);
        }
        let mu = if mu > 0.0 { mu.min(1.0) } else { 0.0 };
        let e1 = self.e1.albedo_shared(table, mu);
        ((e1 * self.ratio.ratio_outside(mu)).clamp(0.0, 1.0), e1)
    }

    /// [`albedo_and_e1`](Self::albedo_and_e1) at `μ = 1` (normal
    /// incidence), bit for bit, without the coordinates' roots and division
    /// ([`AlbedoReader::albedo_at_normal`], [`DielectricRatioReader::ratio_at_normal`]).
    #[inline]
    pub(crate) fn albedo_and_e1_at_normal(&self) -> (f32, f32) {
        let e1 = self
            .e1
            .albedo_at_normal(<Ggx as EnergyTable<HeightCorrelated>>::TABLE);
        ((e1 * self.ratio.ratio_at_normal()).clamp(0.0, 1.0), e1)
    }

    /// [`albedo`](Self::albedo) at `μ = 1`, bit for bit (see
    /// [`albedo_and_e1_at_normal`](Self::albedo_and_e1_at_normal)).
    #[inline]
    pub(crate) fn albedo_at_normal(&self) -> f32 {
        self.albedo_and_e1_at_normal().0
    }

    /// The reader of `E₁(·, α)` inside this one.
    #[inline]
    pub(crate) fn e1_reader(&self) -> &AlbedoReader {
        &self.e1
    }

    /// [`albedo`](Self::albedo) through the general readers.
    #[inline(never)]
    fn albedo_general(&self, mu: f32) -> f32 {
        let e1 = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        (self.e1.albedo(e1, mu) * self.ratio.ratio(mu)).clamp(0.0, 1.0)
    }
}

/// [`DielectricAlbedoReader::albedo`] in vector lanes (feature `simd`).
#[cfg(feature = "simd")]
impl DielectricAlbedoReader {
    /// Whether [`rows`](Self::rows) serves this reader: `η > 1` with no exact
    /// smooth-interface row (every reader outside the first roughness cell).
    #[inline(always)]
    pub(crate) fn has_lanes(&self) -> bool {
        !self.ratio.inside && self.ratio.exact == 0.0
    }

    /// The combined rows of a reader with [`has_lanes`](Self::has_lanes),
    /// for a batch of reads in vector lanes ([`DielectricAlbedoRows`]);
    /// `None` otherwise.
    #[inline]
    pub(crate) fn rows(&self) -> Option<DielectricAlbedoRows> {
        if !self.has_lanes() {
            return None;
        }
        let shared = self.e1.is_shared();
        Some(DielectricAlbedoRows {
            e1: self.e1,
            e1_row: if shared {
                Some(
                    self.e1
                        .combined_row(<Ggx as EnergyTable<HeightCorrelated>>::TABLE),
                )
            } else {
                None
            },
            ratio_row: self.ratio.outside_row(),
        })
    }
}

/// A [`DielectricAlbedoReader`] (`η > 1`, no exact smooth row) with its
/// table entries summed once per column for a batch of reads (feature
/// `simd`): the ratio table's four `(z, α)` corners into one row of 33, and
/// `E₁`'s four roughness rows into one row of 64 where they share one
/// coordinate. A read then takes two entries per table rather than eight —
/// the same sums the scalar read forms at the cell's two nodes, so the same
/// bits. Built per batch call (about 400 bytes, one multiply–add per entry
/// and row), never kept in a material.
#[cfg(feature = "simd")]
#[derive(Clone, Copy, Debug)]
pub(crate) struct DielectricAlbedoRows {
    e1: AlbedoReader,
    /// `E₁`'s rows summed per node ([`AlbedoReader::combined_row`]) when
    /// they share one coordinate.
    e1_row: Option<[f32; super::albedo_table::N_MU]>,
    /// The ratio table's corners summed per column
    /// ([`DielectricRatioReader::outside_row`]).
    ratio_row: [f32; FT_NX],
}

#[cfg(feature = "simd")]
impl DielectricAlbedoRows {
    /// `E_F(μ, α, η)` at each lane's `μ` (clamped to `[0, 1]`, NaN → 0):
    /// lane for lane [`DielectricAlbedoReader::albedo`].
    #[inline(always)]
    pub(crate) fn albedo_lanes(&self, mu: crate::simd::Vf) -> crate::simd::Vf {
        use crate::simd::Vf;
        let mu = mu.simd_gt(Vf::ZERO).select(mu.min(Vf::ONE), Vf::ZERO);
        let e = match &self.e1_row {
            Some(row) => self.e1.albedo_combined_lanes(row, mu),
            None => self
                .e1
                .albedo_lanes(<Ggx as EnergyTable<HeightCorrelated>>::TABLE, mu),
        };
        let r = DielectricRatioReader::ratio_row_lanes(&self.ratio_row, mu);
        (e * r).max(Vf::ZERO).min(Vf::ONE)
    }
}

/// The ratio's combined row read in vector lanes.
#[cfg(feature = "simd")]
impl DielectricRatioReader {
    /// `R(μ)` for `η > 1` at each lane's `μ ∈ [0, 1]` from a combined row:
    /// the cell of `x = √μ` in vector form, the row's two entries per lane,
    /// the chord in vector form (the scalar read's operations).
    #[inline(always)]
    fn ratio_row_lanes(row: &[f32; FT_NX], mu: crate::simd::Vf) -> crate::simd::Vf {
        use crate::simd::Vf;
        // `cell_of(√μ (n − 1), n)`.
        let s = mu.sqrt() * Vf::splat((FT_NX - 1) as f32);
        let s = s
            .simd_gt(Vf::ZERO)
            .select(s.min(Vf::splat(FT_NX.saturating_sub(1) as f32)), Vf::ZERO);
        // `min(trunc(s), n − 2)` = `trunc(min(s, n − 2))` for `s ≥ 0`.
        let (cells, i_f) = crate::simd::cells_of(s.min(Vf::splat(FT_NX.saturating_sub(2) as f32)));
        let fx = (s - i_f).max(Vf::ZERO).min(Vf::ONE);
        let (a, b) = super::albedo_table::row_nodes_lanes(row, &cells);
        ((a + fx * (b - a)) * Vf::splat(1.0 / 65535.0))
            .max(Vf::ZERO)
            .min(Vf::ONE)
    }
}

/// The offsets of the ratio table's four `(z, α)` corners `(l, k)`, `(l,
/// k+1)`, `(l+1, k)`, `(l+1, k+1)` from the first, in a table of `nx`
/// columns per row.
const fn corner_offsets(nx: usize) -> [usize; 4] {
    [0, nx, FT_NA * nx, FT_NA * nx + nx]
}

impl DielectricRatioReader {
    /// The reader of `R(·, α, η)` (the arguments clamped as
    /// [`dielectric_ratio`] clamps them).
    pub fn new(alpha: f32, eta: f32) -> Self {
        Self::with_average(alpha, eta).0
    }

    /// The reader and [`dielectric_average`]`(α, η)`, bit for bit, from one
    /// computation of the index and roughness cells.
    #[inline(always)]
    pub(crate) fn with_average(alpha: f32, eta: f32) -> (Self, f32) {
        Self::with_average_in(RatioCells::new(alpha, eta), eta)
    }

    /// [`with_average`](Self::with_average) from the cells of `(α, η)`
    /// ([`RatioCells::new`]).
    #[inline(always)]
    pub(crate) fn with_average_in(cells: RatioCells, eta: f32) -> (Self, f32) {
        let (l, fz, inside) = cells.index;
        let (k, fa) = cells.alpha;
        let average = average_in((l, fz, inside), (k, fa));
        let nx = if inside { FT_NX_IN } else { FT_NX };
        let off = |l: usize, k: usize| l.wrapping_mul(FT_NA).wrapping_add(k).wrapping_mul(nx);
        let base = off(l, k) as u32;
        let w = [(1.0 - fz) * (1.0 - fa), (1.0 - fz) * fa, fz * (1.0 - fa), fz * fa];
        let mut r = Self {
            base,
            w,
            inside,
            mc: 0.0,
            inv_w: [0.0; 2],
            norm: [[0.0; 2]; 2],
            exact: 0.0,
            eta2m1: 0.0,
            eta2: 1.0,
        };
        if !inside && k == 0 {
            // The first roughness row (α₀ = 10⁻⁴) is the smooth interface: its
            // ratio is the Fresnel factor F(μ) itself (to O(α₀²)), read exactly
            // instead of interpolated in z = F0^¼ and √μ.
            let e = if eta.is_finite() {
                eta.clamp(1.0, MAX_ETA)
            } else {
                MAX_ETA
            };
            r.exact = 1.0 - fa;
            r.eta2m1 = (e - 1.0) * (e + 1.0);
            r.eta2 = e * e;
            r.w[0] = 0.0;
            r.w[2] = 0.0;
        }
        if inside {
            let mc = radiometry::math::sqrtf((1.0 - eta * eta).max(0.0));
            r.mc = mc;
            for (i, kk) in [k, k + 1].into_iter().enumerate() {
                let wk = (alpha_node_f32(kk) * eta).max(1e-4);
                let n = |span: f32| {
                    if span > 0.0 {
                        1.0 / libm::asinhf(span / wk)
                    } else {
                        0.0
                    }
                };
                if let (Some(iw), Some(nm)) = (r.inv_w.get_mut(i), r.norm.get_mut(i)) {
                    *iw = 1.0 / wk;
                    *nm = [n(mc), n(1.0 - mc)];
                }
            }
        }
        (r, average)
    }

    /// `x ∈ [0, 1]` of the `η < 1` table for both roughness rows (`k`,
    /// `k + 1`): [`mu_coord`] with this reader's constants; the distance to
    /// the critical cosine and its square-root term are the rows' common part.
    #[inline(always)]
    fn x_inside(&self, mu: f32) -> [f32; 2] {
        let mc = self.mc;
        let (below, d, span) = if mu <= mc {
            (true, mc - mu, mc)
        } else {
            (false, mu - mc, 1.0 - mc)
        };
        if span <= 0.0 {
            return [0.5; 2];
        }
        let d = d.max(0.0).min(span);
        let root = 0.3 * radiometry::math::sqrtf(d / span);
        let x = |i: usize| {
            let (inv_w, [n_lo, n_hi]) = (self.inv_w[i & 1], self.norm[i & 1]);
            let side = root + 0.7 * libm::asinhf(d * inv_w) * if below { n_lo } else { n_hi };
            if below { 0.5 - 0.5 * side } else { 0.5 + 0.5 * side }
        };
        [x(0), x(1)]
    }

    /// `R(μ) = E_F/E₁` (see [`dielectric_ratio`]), in `[0, 1]`.
    #[inline]
    pub fn ratio(&self, mu: f32) -> f32 {
        let mu = mu.clamp(0.0, 1.0);
        if self.inside {
            return self.ratio_inside(mu);
        }
        self.outside_ratio(self.outside_sum(mu), mu)
    }

    /// [`ratio`](Self::ratio) at `μ = 1` (normal incidence), bit for bit:
    /// for `η > 1` the `μ` cell of `x = √1 = 1` is the last one, `(j, f_x) =
    /// (N_x − 2, 1)`, so the root is left out (`η < 1` reads the general way).
    #[inline]
    pub(crate) fn ratio_at_normal(&self) -> f32 {
        if self.inside {
            return self.ratio_inside(1.0);
        }
        self.outside_ratio(self.outside_sum_in(FT_NX - 2, 1.0), 1.0)
    }

    /// `η > 1`: the ratio from the corners' sum `acc` (table units) at `μ`,
    /// plus the exact smooth-interface row's share where there is one.
    #[inline(always)]
    fn outside_ratio(&self, acc: f32, mu: f32) -> f32 {
        let smooth = if self.exact > 0.0 {
            self.exact * smooth_fresnel(mu, self.eta2m1, self.eta2)
        } else {
            0.0
        };
        (acc * (1.0 / 65535.0) + smooth).clamp(0.0, 1.0)
    }

    /// `η > 1`: the corners' bilinear sum (table units) at `μ ∈ [0, 1]`,
    /// every corner at the same `x = √μ`: the corners summed at the cell's
    /// two nodes, then the chord between them,
    ///
    /// ```text
    /// a + f_x (b − a),   a = Σ_c w_c R_c[j],   b = Σ_c w_c R_c[j+1]
    /// ```
    ///
    /// (the sums a [`DielectricAlbedoRows`] holds, so a read of that row is
    /// this read bit for bit).
    #[inline(always)]
    fn outside_sum(&self, mu: f32) -> f32 {
        let (j, fx) = cell_of(radiometry::math::sqrtf(mu) * (FT_NX - 1) as f32, FT_NX);
        self.outside_sum_in(j, fx)
    }

    /// [`outside_sum`](Self::outside_sum) in the `μ` cell `(j, f_x)`.
    #[inline(always)]
    fn outside_sum_in(&self, j: usize, fx: f32) -> f32 {
        let i = (self.base as usize).wrapping_add(j);
        // The corners (l, k), (l, k + 1), (l + 1, k), (l + 1, k + 1) sit
        // at offsets 0, NX, NA·NX and NA·NX + NX from the first; each is
        // read at the cell's two nodes.
        const SPAN: usize = FT_NA * FT_NX + FT_NX + 2;
        match data::DIELECTRIC_OUT.get(i..i.wrapping_add(SPAN)) {
            Some(t) => {
                // (`get`: `t` has SPAN entries and every offset is below it,
                // which the optimiser sees; no panic path either way.)
                let at = |i: usize| f32::from(t.get(i).copied().unwrap_or(0));
                let [w0, w1, w2, w3] = self.w;
                let node = |j: usize| {
                    (((0.0 + w0 * at(j)) + w1 * at(j + FT_NX)) + w2 * at(j + FT_NA * FT_NX))
                        + w3 * at(j + FT_NA * FT_NX + FT_NX)
                };
                let (a, b) = (node(0), node(1));
                a + fx * (b - a)
            }
            None => 0.0,
        }
    }

    /// `η > 1`: the four corners summed once per column, `c_j = Σ_c w_c
    /// R_c[j]` (table units), what [`DielectricAlbedoRows`] reads.
    #[cfg(feature = "simd")]
    #[inline]
    fn outside_row(&self) -> [f32; FT_NX] {
        let mut out = [0.0f32; FT_NX];
        let corner = |o: usize| {
            let i = (self.base as usize).wrapping_add(o);
            data::DIELECTRIC_OUT
                .get(i..i.wrapping_add(FT_NX))
                .and_then(|c| <&[u16; FT_NX]>::try_from(c).ok())
        };
        let [o0, o1, o2, o3] = corner_offsets(FT_NX);
        if let (Some(c0), Some(c1), Some(c2), Some(c3)) = (corner(o0), corner(o1), corner(o2), corner(o3)) {
            let [w0, w1, w2, w3] = self.w;
            // `outside_sum`'s node sum, column by column (in vector form).
            for (j, o) in out.iter_mut().enumerate() {
                let at = |c: &[u16; FT_NX]| f32::from(c[j]);
                *o = (((0.0 + w0 * at(c0)) + w1 * at(c1)) + w2 * at(c2)) + w3 * at(c3);
            }
        }
        out
    }

    /// [`ratio`](Self::ratio) for `η > 1` without the exact smooth row
    /// (`exact = 0`), `μ ∈ [0, 1]`.
    #[inline(always)]
    fn ratio_outside(&self, mu: f32) -> f32 {
        (self.outside_sum(mu) * (1.0 / 65535.0)).clamp(0.0, 1.0)
    }

    /// [`ratio`](Self::ratio) for `η < 1` (`μ ∈ [0, 1]`): each roughness row
    /// at its own `x`.
    #[inline]
    fn ratio_inside(&self, mu: f32) -> f32 {
        let table: &[u16] = &data::DIELECTRIC_IN;
        let nx = FT_NX_IN;
        let cell_at = |x: f32| cell_of(x * (nx - 1) as f32, nx);
        let [x0, x1] = self.x_inside(mu);
        let cells = [cell_at(x0), cell_at(x1)];
        let mut acc = 0.0f32;
        for (c, (&o, &w)) in corner_offsets(nx).iter().zip(&self.w).enumerate() {
            // Corners 0 and 2 sit on roughness row k, 1 and 3 on k + 1.
            let (j, fx) = cells[c & 1];
            let i = (self.base as usize).wrapping_add(o).wrapping_add(j);
            let a = table.get(i).copied().unwrap_or(0) as f32;
            let bb = table.get(i.wrapping_add(1)).copied().unwrap_or(0) as f32;
            acc += w * (a + fx * (bb - a));
        }
        (acc * (1.0 / 65535.0)).clamp(0.0, 1.0)
    }
}

/// The unpolarised Fresnel reflectance of a smooth interface of index `η ≥
/// 1` at `cos θ = μ ∈ [0, 1]`, from `η² − 1` and `η²`, without the
/// cancellation of the textbook form near `η = 1`: with `μt = √((η² − 1 +
/// μ²)/η²)`,
///
/// ```text
/// r_p = (η μ − μt)/(η μ + μt) = (η² − 1)((η² + 1) μ² − 1) / (η² (η μ + μt)²)
/// r_s = (μ − η μt)/(μ + η μt) = −(η² − 1) / (μ + η μt)²
/// F   = (r_p² + r_s²)/2
/// ```
#[inline]
fn smooth_fresnel(mu: f32, eta2m1: f32, eta2: f32) -> f32 {
    if eta2m1 <= 0.0 {
        return 0.0;
    }
    let mu = mu.clamp(0.0, 1.0);
    let eta = radiometry::math::sqrtf(eta2);
    // μt² = (η² − 1 + μ²)/η², free of the cancellation of 1 − (1 − μ²)/η².
    let mt = radiometry::math::sqrtf(((eta2m1 + mu * mu) / eta2).max(0.0));
    let dp = eta * mu + mt;
    let ds = mu + eta * mt;
    if dp <= 0.0 || ds <= 0.0 {
        return 1.0;
    }
    let rp = eta2m1 * ((eta2 + 1.0) * mu * mu - 1.0) / (eta2 * dp * dp);
    let rs = eta2m1 / (ds * ds);
    (0.5 * (rp * rp + rs * rs)).clamp(0.0, 1.0)
}

/// The hemispherical average `Ē(α, η) = 2∫₀¹ E_F(μ) μ dμ` of a GGX
/// dielectric interface, bilinear in `(√α, F0^¼)`.
pub fn dielectric_average(alpha: f32, eta: f32) -> f32 {
    dielectric_average_inline(alpha, eta)
}

/// [`dielectric_average`], always inlined: at a constant `α` the
/// roughness cell is computed at compile time.
#[inline(always)]
pub(crate) fn dielectric_average_inline(alpha: f32, eta: f32) -> f32 {
    average_in(index_coord(eta), alpha_coord(alpha))
}

/// [`dielectric_average`] at the cells `(l, f_z, η < 1)` of the index
/// ([`index_coord`]) and `(k, f_a)` of the roughness ([`alpha_coord`]).
#[inline(always)]
fn average_in((l, fz, inside): (usize, f32, bool), (k, fa): (usize, f32)) -> f32 {
    let table: &[f32] = if inside {
        &data::AVERAGE_IN
    } else {
        &data::AVERAGE_OUT
    };
    let at = |l: usize, k: usize| {
        table
            .get(l.wrapping_mul(FT_NA).wrapping_add(k))
            .copied()
            .unwrap_or(0.0)
    };
    let row = |l: usize| {
        let a = at(l, k);
        a + fa * (at(l, k.wrapping_add(1)) - a)
    };
    let a = row(l);
    (a + fz * (row(l.wrapping_add(1)) - a)).clamp(0.0, 1.0)
}

/// The moments `(R5, R6) = (M5/E₁, M6/E₁)` at `μ`, `α` (bilinear in `(√μ,
/// √α)`): the lobe's means of `(1 − c)⁵` and `c (1 − c)⁶`.
pub fn fresnel_moments(mu: f32, alpha: f32) -> (f32, f32) {
    MomentCell::new(alpha).moments(mu)
}

/// The roughness cell `(k, f_a)` of the moment tables at one `α`, for a lobe
/// that reads [`fresnel_moments`] at many `μ` (the root and division of
/// the roughness coordinate made once).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MomentCell {
    k: u8,
    fa: f32,
}

impl MomentCell {
    /// The cell of `α` (clamped as [`fresnel_moments`] clamps it).
    #[inline]
    pub(crate) fn new(alpha: f32) -> Self {
        Self::at(alpha_coord(alpha))
    }

    /// The cell `(k, f_a)` of [`alpha_coord`] (the ratio table's roughness
    /// cell, [`RatioCells::alpha`], on the same grid): [`new`](Self::new)
    /// where a reader of the same `α` computed it.
    #[inline(always)]
    pub(crate) fn at((k, fa): (usize, f32)) -> Self {
        // `k ≤ FT_NA − 2 = 30`.
        Self { k: k as u8, fa }
    }

    /// [`fresnel_moments`] at `μ` for this cell's `α`, bit for bit.
    #[inline]
    pub(crate) fn moments(&self, mu: f32) -> (f32, f32) {
        let (j, fx) = cell_of(
            radiometry::math::sqrtf(mu.clamp(0.0, 1.0)) * (FT_NX - 1) as f32,
            FT_NX,
        );
        self.moments_in(j, fx)
    }

    /// [`fresnel_moments`] at `μ = 1` (normal incidence), bit for bit: the
    /// `μ` cell of `√1 = 1` is the last, `(N_x − 2, 1)`.
    #[inline]
    pub(crate) fn moments_at_normal(&self) -> (f32, f32) {
        self.moments_in(FT_NX - 2, 1.0)
    }

    /// The moments in the `μ` cell `(j, f_x)`: bilinear in `(√μ, √α)`.
    #[inline(always)]
    fn moments_in(&self, j: usize, fx: f32) -> (f32, f32) {
        let (k, fa) = (usize::from(self.k), self.fa);
        let read = |t: &[f32]| {
            let at = |k: usize| {
                let i = k.wrapping_mul(FT_NX).wrapping_add(j);
                let a = t.get(i).copied().unwrap_or(0.0);
                let b = t.get(i.wrapping_add(1)).copied().unwrap_or(0.0);
                a + fx * (b - a)
            };
            let a = at(k);
            a + fa * (at(k.wrapping_add(1)) - a)
        };
        (read(&data::MOMENT5), read(&data::MOMENT6))
    }
}

/// The lobe's mean Fresnel factor `R_F = f0 + (1 − f0) R5 − a R6` of `F(c)
/// = f0 + (1 − f0)(1 − c)⁵ − a c (1 − c)⁶` (Schlick: `a = 0`; F82-tint:
/// Hoffman 2019's `a`), from [`fresnel_moments`]: exact up to the moments'
/// interpolation, clamped to `[0, 1]`.
#[inline]
pub fn linear_fresnel_ratio(f0: f32, a: f32, moments: (f32, f32)) -> f32 {
    (f0 + (1.0 - f0) * moments.0 - a * moments.1).clamp(0.0, 1.0)
}

/// The hemispherical average `Ē₁(α) = 2∫E₁(μ, α) μ dμ` of the `F = 1`
/// albedo of GGX (height-correlated `G2`) as [`AlbedoTable::albedo`] reads
/// it: a 32-node table at the albedo table's roughness nodes, linear in
/// `∛(α − α_min)` between them (`e1_average_data.rs`, generated by
/// `tools/examples/e1_average.rs`). The normalisation of a Kulla–Conty
/// multiple-scattering lobe built without integration.
pub fn e1_average(alpha: f32) -> f32 {
    e1_average_at(super::albedo_table::alpha_axis(alpha))
}

/// [`e1_average`] at the roughness coordinate `x =`
/// [`alpha_axis`](super::albedo_table::alpha_axis)`(α)` (an
/// [`AlbedoReader`]'s, so that a material reads both from one cube root).
#[inline]
pub(crate) fn e1_average_at(x: f32) -> f32 {
    use super::albedo_table::N_ALPHA;
    let (k, f) = cell_of(x * (N_ALPHA - 1) as f32, N_ALPHA);
    let at = |k: usize| {
        super::e1_average_data::GGX_HC_E1_AVERAGE
            .get(k)
            .copied()
            .unwrap_or(1.0)
    };
    let a = at(k);
    (a + f * (at(k.wrapping_add(1)) - a)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::test_stream::uniforms;

    /// The trilinear read as the module docs state it, corner by corner from
    /// `μ`'s coordinate per roughness row (the readers' reference).
    fn trilinear_ratio(mu: f32, alpha: f32, eta: f32) -> f32 {
        let (l, fz, inside) = index_coord(eta);
        let (k, fa) = alpha_coord(alpha);
        let table: &[u16] = if inside {
            &data::DIELECTRIC_IN
        } else {
            &data::DIELECTRIC_OUT
        };
        // Each `z` slice at its own x: the inside table's x depends on η only
        // through μc, which is the η of the query for both slices (nodes on a
        // line of constant x share the critical point).
        // The inside table's x depends on α (the width of the rounded kink):
        // each roughness row is read at its own node α, so that rows align in
        // units of that width.
        let at = |l: usize, k: usize| -> f32 {
            let a_k = if inside { alpha_node_f32(k) } else { alpha };
            let x = mu_coord(mu, inside, eta, a_k);
            let (j, fx) = if inside {
                cell_of(x * (FT_NX_IN - 1) as f32, FT_NX_IN)
            } else {
                cell_of(x * (FT_NX - 1) as f32, FT_NX)
            };
            let nx = if inside { FT_NX_IN } else { FT_NX };
            // Wrapping index arithmetic: an index past the table reads 0 through
            // `get` (no overflow check can panic; the cells keep it in range).
            let base = l
                .wrapping_mul(FT_NA)
                .wrapping_add(k)
                .wrapping_mul(nx)
                .wrapping_add(j);
            let a = table.get(base).copied().unwrap_or(0) as f32;
            let b = table.get(base.wrapping_add(1)).copied().unwrap_or(0) as f32;
            a + fx * (b - a)
        };
        if !inside && k == 0 {
            // The first roughness row is the smooth interface's Fresnel factor.
            let second = at(l, 1) + fz * (at(l.wrapping_add(1), 1) - at(l, 1));
            let v = (1.0 - fa) * smooth_fresnel(mu, eta) + fa * second * (1.0 / 65535.0);
            return v.clamp(0.0, 1.0);
        }
        let row = |l: usize| {
            let a = at(l, k);
            a + fa * (at(l, k.wrapping_add(1)) - a)
        };
        let a = row(l);
        let v = a + fz * (row(l.wrapping_add(1)) - a);
        (v * (1.0 / 65535.0)).clamp(0.0, 1.0)
    }

    /// The unpolarised Fresnel reflectance of a smooth interface of index
    /// `η ≥ 1` at `cos θ = μ`, in `f64` (Born and Wolf: the mean of
    /// `((η μ − μt)/(η μ + μt))²` and `((μ − η μt)/(μ + η μt))²`, `μt² = 1 − (1 − μ²)/η²`).
    fn smooth_fresnel(mu: f32, eta: f32) -> f32 {
        let (m, e) = (f64::from(mu.clamp(0.0, 1.0)), f64::from(eta));
        let mt = (1.0 - (1.0 - m * m) / (e * e)).max(0.0).sqrt();
        let rp = (e * m - mt) / (e * m + mt);
        let rs = (m - e * mt) / (m + e * mt);
        (0.5 * (rp * rp + rs * rs)) as f32
    }

    /// The prepared readers equal the plain reads up to rounding, on random
    /// `(μ, α, η)` on both sides of `η = 1` (roughness spread in `√α`, from
    /// near-delta to 1; `μ` spread in `√μ` so grazing is covered), with the
    /// edges of every domain (μ = 0, 1, α at both ends, η near 1).
    #[test]
    fn readers_equal_the_plain_reads() {
        let e1: &AlbedoTable = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        let mut u = uniforms(0x9e37_79b9_7f4a_7c15);
        let mut worst = (0.0f32, 0.0f32);
        for n in 0..20_000 {
            let alpha = match n % 50 {
                0 => 1e-4,
                1 => 1.0,
                _ => {
                    let s = u();
                    (s * s).max(1e-4)
                }
            };
            let eta = match n % 7 {
                0 => 1.0 + 1e-3,
                1 => 1.0 - 1e-3,
                2..=4 => 1.0 + 2.0 * u(),
                _ => 0.3 + 0.7 * u(),
            };
            let mu = match n % 13 {
                0 => 0.0,
                1 => 1.0,
                _ => {
                    let s = u();
                    s * s
                }
            };
            let a = AlbedoReader::new(alpha).albedo(e1, mu);
            let b = e1.albedo(mu, alpha);
            worst.0 = worst.0.max((a - b).abs());
            let r = DielectricAlbedoReader::new(alpha, eta);
            let (c, d) = (
                r.albedo(mu),
                (e1.albedo(mu, alpha) * trilinear_ratio(mu, alpha, eta)).clamp(0.0, 1.0),
            );
            worst.1 = worst.1.max((c - d).abs());
            assert!(
                (a - b).abs() <= 2e-6 && (c - d).abs() <= 2e-6,
                "μ {mu} α {alpha} η {eta}: E₁ {a} vs {b}, E_F {c} vs {d}"
            );
        }
        std::eprintln!("worst |Δ|: E₁ {:.2e}, E_F {:.2e}", worst.0, worst.1);
    }

    /// `albedo_and_e1` returns the reader's `albedo` and the plain `E₁`
    /// read at its roughness bit for bit, on random `(α, η)` on both sides of
    /// the shared coordinate and of `η = 1`, and `μ` at the ends, outside
    /// `[0, 1]` and NaN.
    #[test]
    fn albedo_and_e1_are_the_two_reads() {
        let table = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        let mut u = uniforms(0x6a09_e667_f3bc_c909);
        let (mut fast, mut general) = (0, 0);
        for n in 0..4_000 {
            let alpha = match n % 40 {
                0 => 1e-4,
                1 => 1.0,
                _ => (u() * u()).max(1e-4),
            };
            let eta = match n % 9 {
                0 => 1.0,
                1 => 0.3 + 0.69 * u(),
                _ => 1.0 + 2.5 * u(),
            };
            let r = DielectricAlbedoReader::new(alpha, eta);
            if r.fast {
                fast += 1;
            } else {
                general += 1;
            }
            let mu = match n % 7 {
                0 => 0.0,
                1 => 1.0,
                2 => -0.25,
                3 => 1.5,
                4 => f32::NAN,
                _ => u(),
            };
            let (e_f, e1) = r.albedo_and_e1(mu);
            assert_eq!(
                e_f.to_bits(),
                r.albedo(mu).to_bits(),
                "α {alpha} η {eta} μ {mu}: E_F"
            );
            let plain = AlbedoReader::new(alpha).albedo(table, mu);
            assert_eq!(e1.to_bits(), plain.to_bits(), "α {alpha} η {eta} μ {mu}: E₁");
            assert_eq!(r.e1_reader(), &AlbedoReader::new(alpha));
        }
        assert!(
            fast > 1_000 && general > 1_000,
            "{fast} fast, {general} general readers"
        );
    }

    /// `Ē₁` and the metal sampler's row read from a reader's roughness
    /// coordinate ([`AlbedoReader::axis`]) are bit for bit the reads from
    /// `α` written out with their own cube roots: random `α`, the ends of
    /// `[10⁻⁴, 1]`, outside it, and NaN.
    #[test]
    fn shared_axis_reads_the_same_bits() {
        use super::super::ms_sampler::{row_index, row_index_at};
        let direct = |alpha: f32| libm::cbrtf(((alpha - 1e-4) / (1.0 - 1e-4)).clamp(0.0, 1.0));
        let mut u = uniforms(0x9e37_79b9_7f4a_7c15);
        for n in 0..4_000 {
            let alpha = match n % 10 {
                0 => 1e-4,
                1 => 1.0,
                2 => 1.5,
                3 => -0.25,
                4 => f32::NAN,
                5 => 0.0,
                _ => (u() * u()).max(1e-5),
            };
            let x = AlbedoReader::new(alpha).axis();
            let t = if alpha.is_nan() { 0.0 } else { direct(alpha) };
            assert_eq!(x.to_bits(), t.to_bits(), "α {alpha}");
            assert_eq!(
                e1_average_at(x).to_bits(),
                e1_average(alpha).to_bits(),
                "α {alpha}"
            );
            assert_eq!(row_index_at(x), row_index(alpha), "α {alpha}");
            let old_row = (libm::roundf(t * 31.0) as usize).min(31) as u8;
            assert_eq!(row_index_at(x), old_row, "α {alpha}");
        }
    }

    /// The reads at normal incidence without the coordinates' roots
    /// (`*_at_normal`) are the general reads at `μ = 1` bit for bit, and the
    /// average read with a reader's cells is [`dielectric_average`]: random
    /// `α` on both sides of `α = 0.2` (rows sharing one coordinate or not)
    /// and in the exact smooth row, the ends of `[10⁻⁴, 1]`, outside it and
    /// NaN; random `η` above and below 1, `η = 1` and the index's ends.
    #[test]
    fn normal_incidence_reads_are_the_general_reads() {
        let table = <Ggx as EnergyTable<HeightCorrelated>>::TABLE;
        let mut u = uniforms(0x2545_f491_4f6c_dd1d);
        let (mut shared, mut inside, mut exact) = (0, 0, 0);
        for n in 0..6_000 {
            let alpha = match n % 12 {
                0 => 1e-4,
                1 => 1.0,
                2 => 0.2,
                3 => 1.5,
                4 => -0.25,
                5 => f32::NAN,
                6 => 2e-4 * u(),
                _ => (u() * u()).max(1e-5),
            };
            let eta = match n % 7 {
                0 => 1.0,
                1 => MAX_ETA,
                2 => 0.3 + 0.7 * u(),
                _ => 1.0 + 3.0 * u(),
            };
            let r = DielectricAlbedoReader::new(alpha, eta);
            let what = std::format!("α {alpha} η {eta}");
            let (a, b) = (r.albedo_and_e1_at_normal(), r.albedo_and_e1(1.0));
            assert_eq!(
                (a.0.to_bits(), a.1.to_bits()),
                (b.0.to_bits(), b.1.to_bits()),
                "{what}"
            );
            assert_eq!(r.albedo_at_normal().to_bits(), r.albedo(1.0).to_bits(), "{what}");
            let e1 = AlbedoReader::new(alpha);
            assert_eq!(
                e1.albedo_at_normal(table).to_bits(),
                e1.albedo(table, 1.0).to_bits(),
                "{what}"
            );
            let ratio = DielectricRatioReader::new(alpha, eta);
            assert_eq!(
                ratio.ratio_at_normal().to_bits(),
                ratio.ratio(1.0).to_bits(),
                "{what}"
            );
            let (m, f) = (
                MomentCell::new(alpha).moments_at_normal(),
                fresnel_moments(1.0, alpha),
            );
            assert_eq!(
                (m.0.to_bits(), m.1.to_bits()),
                (f.0.to_bits(), f.1.to_bits()),
                "{what}"
            );
            // The average read with the reader's cells is the plain read.
            let (with, average) = DielectricAlbedoReader::with_average(alpha, eta);
            assert_eq!(
                average.to_bits(),
                dielectric_average(alpha, eta).to_bits(),
                "{what}"
            );
            assert_eq!(with, r, "{what}");
            shared += usize::from(e1.is_shared());
            inside += usize::from(ratio.inside);
            exact += usize::from(ratio.exact > 0.0);
        }
        // Every branch of the reads was taken.
        assert!(
            shared > 100 && inside > 100 && exact > 100,
            "{shared} {inside} {exact}"
        );
        assert!(shared < 5_000, "{shared}");
    }

    /// A batch's combined rows read in lanes return the scalar reader's bits
    /// at every lane: random `(α, η > 1)` on both sides of `α = 0.2` (rows
    /// sharing one coordinate or not), `μ` at the table's ends, outside
    /// `[0, 1]`, NaN, and random; readers without rows (`η < 1`, the exact
    /// smooth row) have none.
    #[cfg(feature = "simd")]
    #[test]
    fn combined_rows_read_the_scalar_bits() {
        use crate::simd::{LANES, Vf};
        let mut u = uniforms(0x51_7cc1_b727_220a);
        let (mut with_rows, mut shared) = (0, 0);
        for n in 0..4_000 {
            let alpha = match n % 40 {
                0 => 1e-4,
                1 => 1.0,
                2 => 0.2,
                _ => (u() * u()).max(1e-4),
            };
            let eta = match n % 9 {
                0 => 1.0 + 1e-3,
                1 => 0.3 + 0.69 * u(),
                _ => 1.0 + 2.5 * u(),
            };
            let r = DielectricAlbedoReader::new(alpha, eta);
            let Some(rows) = r.rows() else {
                assert!(eta < 1.0 || r.ratio.exact > 0.0, "α {alpha} η {eta}: no rows");
                continue;
            };
            with_rows += 1;
            shared += usize::from(rows.e1_row.is_some());
            let mu: [f32; LANES] = core::array::from_fn(|k| match (n + k) % 11 {
                0 => 0.0,
                1 => 1.0,
                2 => -0.25,
                3 => 1.5,
                4 => f32::NAN,
                5 => 1e-6,
                _ => u(),
            });
            let lanes = rows.albedo_lanes(Vf::from(mu)).to_array();
            for (&m, &l) in mu.iter().zip(&lanes) {
                let s = r.albedo(m);
                assert_eq!(
                    l.to_bits(),
                    s.to_bits(),
                    "α {alpha} η {eta} μ {m}: lanes {l}, scalar {s}"
                );
            }
        }
        assert!(
            with_rows > 2_000 && shared > 500,
            "{with_rows} readers with rows, {shared} shared"
        );
    }
}
