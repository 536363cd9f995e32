//! The tabulated directional albedo `E(μo, r)` of the sheen lobe with
//! `color = 1`, computed by this project's integrator.

use super::MIN_SHEEN_ROUGHNESS;
use super::albedo_data;

/// Number of `μ = cos θo` nodes per row, uniform in the node coordinate
/// [`sheen_mu_coord`] (logarithmic above `μ₀ = 10⁻⁴`, linear below).
pub const N_MU: usize = 96;

/// `μ₀` of [`sheen_mu_coord`].
pub const MU_0: f32 = 1e-4;

/// Number of roughness nodes: `r_k = r_min + (1 − r_min)(k/31)²`,
/// `k = 0..32`, `r_min =` [`MIN_SHEEN_ROUGHNESS`] (dense at small `r`,
/// where `E` changes fastest).
pub const N_R: usize = 32;

/// The node coordinate of `μ ∈ [0, 1]`:
/// `x(μ) = ln(1 + μ/μ₀) / ln(1 + 1/μ₀)`, `μ₀ =` [`MU_0`] — linear in `μ`
/// below `μ₀` and logarithmic above, because `E(μ)` has its structure on a
/// logarithmic scale: the kink where the grazing continuation of `Λ`
/// starts ([`Charlie::mu_star`](super::Charlie::mu_star), `4·10⁻⁵…9·10⁻⁵`)
/// and the maximum near `μ ≈ 5·10⁻³`. (On nodes uniform in `μ^¼` the
/// interpolation error near the kink was `10⁻³`.)
#[inline]
pub fn sheen_mu_coord(mu: f32) -> f32 {
    libm::log1pf(mu / MU_0) / LN_1P_INV_MU0
}

/// `ln(1 + 1/μ₀)`.
const LN_1P_INV_MU0: f32 = 9.210_441;

/// The node `μ_j = μ₀ ((1 + 1/μ₀)^(j/95) − 1)` of column `j` (the inverse
/// of [`sheen_mu_coord`] at `j/95`; exactly 0 and 1 at the ends).
pub fn sheen_mu_node(j: usize) -> f32 {
    if j + 1 >= N_MU {
        return 1.0;
    }
    let x = j as f32 / (N_MU - 1) as f32;
    MU_0 * libm::expm1f(x * LN_1P_INV_MU0)
}

/// The node `r_k = r_min + (1 − r_min)(k/31)²` of row `k`.
pub const fn sheen_r_node(k: usize) -> f32 {
    let t = k as f32 / (N_R - 1) as f32;
    MIN_SHEEN_ROUGHNESS + (1.0 - MIN_SHEEN_ROUGHNESS) * (t * t)
}

/// The stated error of [`Sheen::directional_albedo`](super::Sheen) for
/// `color = 1`: integration error of the entries plus the largest
/// interpolation error the generator measured between the nodes, rounded
/// up (the figures are in the header of `albedo_data.rs`).
pub(crate) const TABLE_ERROR: f32 = albedo_data::STATED_ERROR;

/// The table behind [`Sheen::directional_albedo`](super::Sheen).
pub(crate) static SHEEN_ALBEDO: &SheenAlbedoTable = &albedo_data::SHEEN;

/// The directional albedo of the sheen lobe ([`Sheen`](super::Sheen)) with
/// `color = 1`,
///
/// ```text
/// E(μo, r) = ∫_H f_r(ωi, ωo) cos θi dωi
///          = ∫_H D(h) G(ωi, ωo) / (4 cos θo) dωi,     μo = cos θo,
/// ```
///
/// on the grid `μ_j` uniform in [`sheen_mu_coord`] ([`sheen_mu_node`]) × `r_k = r_min + (1 −
/// r_min)(k/31)²` ([`sheen_r_node`]), every entry computed by this
/// project's integrator ([`radiometry::integrator::Adaptive`], warped onto
/// the lobe's own sampling map) with the generator
/// `brdfs/examples/sheen_tables.rs`. The header of the generated data states
/// the integration error (the difference of two budgets) and the largest
/// interpolation error measured at the centres of all cells against the
/// same integrator; [`Sheen::directional_albedo`](super::Sheen) states
/// their sum, rounded up, as its bound. The test
/// `brdfs/tests/sheen.rs` recomputes a sample of entries and off-node
/// points with an independent `f64` quadrature of its own copy of the
/// formulas.
///
/// Interpolation: a separable Catmull–Rom spline (Catmull & Rom 1974) in
/// [`sheen_mu_coord`] along a row and in `√((r − r_min)/(1 − r_min))` across rows (both
/// uniform node coordinates), the outermost nodes continued linearly;
/// clamped to `[0, 1]`.
///
/// ```
/// use radiometry_brdfs::sheen::SheenAlbedoTable;
/// let t = SheenAlbedoTable::get();
/// let e = t.albedo(0.5, 0.5);
/// assert!(e > 0.2 && e < 0.4);
/// ```
#[derive(Debug, PartialEq)]
pub struct SheenAlbedoTable {
    /// `values[k][j] = E(μ_j, r_k)`.
    pub values: [[f32; N_MU]; N_R],
}

/// The Catmull–Rom spline through `p0..p3` at `t ∈ [0, 1]` between `p1`
/// and `p2`: `½(2p1 + (p2 − p0)t + (2p0 − 5p1 + 4p2 − p3)t² + (3p1 − p0 −
/// 3p2 + p3)t³)`.
#[inline(always)]
fn catmull_rom([p0, p1, p2, p3]: [f32; 4], t: f32) -> f32 {
    let a = 2.0 * p1;
    let b = p2 - p0;
    let c = 2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3;
    let d = 3.0 * p1 - p0 - 3.0 * p2 + p3;
    0.5 * (a + t * (b + t * (c + t * d)))
}

/// Cell index `i ≤ n − 2` and fraction of `x ∈ [0, 1]` on `n` uniform
/// nodes (clamped; NaN → 0).
#[inline(always)]
fn cell(x: f32, n: usize) -> (usize, f32) {
    let s = if x > 0.0 {
        (x * (n - 1) as f32).min((n - 1) as f32)
    } else {
        0.0
    };
    let i = (s as usize).min(n - 2);
    (i, (s - i as f32).clamp(0.0, 1.0))
}

/// The spline through `get(i−1..=i+2)` at fraction `t` of cell `i` of `n`
/// nodes, ghost nodes continued linearly.
#[inline(always)]
fn spline(get: impl Fn(usize) -> f32, i: usize, t: f32, n: usize) -> f32 {
    let p1 = get(i);
    let p2 = get(i + 1);
    let p0 = if i >= 1 { get(i - 1) } else { 2.0 * p1 - p2 };
    let p3 = if i + 2 < n { get(i + 2) } else { 2.0 * p2 - p1 };
    catmull_rom([p0, p1, p2, p3], t)
}

impl SheenAlbedoTable {
    /// The crate's table (the one [`Sheen`](super::Sheen) uses).
    pub fn get() -> &'static SheenAlbedoTable {
        SHEEN_ALBEDO
    }

    /// `E(μ, r)` for `μ = cos θo ∈ [0, 1]` and `r ∈ [r_min, 1]` (both
    /// clamped, NaN to the lower end). Column 0 (`μ = 0`) holds the
    /// limit `μ → 0⁺` (the lobe itself is 0 on the horizon).
    pub fn albedo(&self, mu: f32, r: f32) -> f32 {
        let mu = if mu > 0.0 { mu.min(1.0) } else { 0.0 };
        let r = if r > MIN_SHEEN_ROUGHNESS {
            r.min(1.0)
        } else {
            MIN_SHEEN_ROUGHNESS
        };
        let s = sheen_mu_coord(mu);
        let tr = radiometry::math::sqrtf((r - MIN_SHEEN_ROUGHNESS) / (1.0 - MIN_SHEEN_ROUGHNESS));
        let (j, u) = cell(s, N_MU);
        let (k, v) = cell(tr, N_R);
        let row = |k: usize| {
            let vals = &self.values[k.min(N_R - 1)];
            spline(|j| vals[j.min(N_MU - 1)], j, u, N_MU)
        };
        spline(row, k, v, N_R).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_stays_in_range() {
        for x in [f32::NAN, -1.0, 0.0, 0.5, 1.0, 2.0, f32::INFINITY] {
            let (i, t) = cell(x, N_MU);
            assert!(i + 1 < N_MU && (0.0..=1.0).contains(&t), "{x}: {i} {t}");
        }
    }

    #[test]
    fn albedo_hits_nodes() {
        let t = SheenAlbedoTable::get();
        for k in [0usize, 1, 7, 30, 31] {
            for j in [1usize, 5, 40, 63] {
                let e = t.albedo(sheen_mu_node(j), sheen_r_node(k));
                assert!(
                    (e - t.values[k][j]).abs() < 2e-6,
                    "{k} {j}: {e} vs {}",
                    t.values[k][j]
                );
            }
        }
    }

    #[test]
    fn catmull_rom_reproduces_cubics_on_uniform_nodes() {
        let f = |x: f32| 0.3 + x * (0.2 - 0.1 * x);
        let p = [f(-1.0), f(0.0), f(1.0), f(2.0)];
        for t in [0.0f32, 0.25, 0.5, 1.0] {
            assert!((catmull_rom(p, t) - f(t)).abs() < 1e-6);
        }
    }
}
