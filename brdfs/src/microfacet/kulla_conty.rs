//! Kulla–Conty multiple-scattering energy compensation of a microfacet BRDF.

use super::albedo_table::{EnergyTable, N_MU, cosine_average, lerp_row, mu_node, node_scale, rescale_mu};
use super::{
    Fresnel, HeightCorrelated, Microfacet, MicrofacetDistribution, NoFresnel, ShadowingMasking, clamp01,
    is_unit, unitize,
};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::math::sincos_turn;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// Below this cosine-weighted average loss `1 − E_avg` the compensation lobe
/// is switched off (it would be `0/0`): at `α ≲ 10⁻³` the single-scattering
/// lobe loses less than this fraction of the light.
const MIN_AVERAGE_LOSS: f32 = 1e-6;

/// Margin subtracted from the tabulated loss `1 − E(μ)` so that the table's
/// interpolation error can never create energy: the compensated albedo is
/// `E(μo) + max(1 − E_tab(μo) − δ, 0) ≤ 1` whenever `E − E_tab ≤ δ`. The
/// largest excess `E − E_tab` measured before the margin (adaptive cubature
/// at 10⁵ evaluations against the interpolated table, 40 × 60 (α, μ)
/// points per variant plus a grazing sweep down to `μ = 10⁻⁸`) is
/// `4.4·10⁻⁴`, for GGX `α = 1` at `μ ≈ 4·10⁻⁵` (θo = 89.998°); elsewhere it
/// stays below `1.6·10⁻⁴`. With the margin, `brdfs/examples/kulla_conty_excess.rs`
/// finds the exact albedo at or below what the lobe assumes kept at every
/// point of all four variants (largest excess `−2·10⁻¹⁰`, i.e. where both are 1).
pub const LOSS_MARGIN: f32 = 6e-4;

/// The largest `f32` below 1 (remapped sample coordinates stay in `[0, 1)`).
const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;

/// A single-scattering microfacet BRDF plus the Kulla–Conty
/// multiple-scattering lobe (Kulla & Conty 2017, "Revisiting Physically
/// Based Shading at Imageworks", SIGGRAPH course notes, §"Multiple
/// scattering"; after Jakob et al. 2014 and Turquin 2019):
///
/// ```text
/// f(ωi, ωo) = f_ss(ωi, ωo) + F_ms · (1 − E(μi)) (1 − E(μo)) / (π (1 − E_avg))
/// E_avg = 2 ∫₀¹ E(μ) μ dμ,   F_avg = 2 ∫₀¹ F(μ) μ dμ,
/// F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg))          (per channel)
/// ```
///
/// where `f_ss` is [`Microfacet<D, G, F>`], `E(μ)` its albedo with `F = 1`
/// (the tabulated [`AlbedoTable`](super::AlbedoTable) of `(D, G)`, see
/// [`EnergyTable`]) and `μ = cos θ`. With `F = 1`, `F_ms = 1` and the lobe
/// adds the lost energy `1 − E(μo)` less a margin
/// [`LOSS_MARGIN`]` = 6·10⁻⁴` (so that interpolation error never creates
/// energy): the white-furnace albedo is `1 − 6·10⁻⁴` up to the
/// interpolation error of the table, `|albedo − 1| ≤ 2·10⁻³` for
/// `α ∈ [0.05, 1]`, `θo ≤ 89°` (the measured figure is in
/// `brdfs/tests/kulla_conty.rs`; `E_avg` is computed from the same
/// interpolant that `eval` uses, so no further error enters). `F_ms`
/// is the coloured-conductor term: light that scatters `k` times is tinted
/// by `F_avg^k` (Kulla & Conty's geometric series).
///
/// The added lobe is symmetric in `(ωi, ωo)` (bit for bit: one product of
/// two factors), so the BRDF stays reciprocal; it is zero when either
/// direction is at or below the horizon.
///
/// Opt-in by type: the compensated BRDF is this separate type, the plain
/// [`Microfacet`] is untouched and pays nothing.
///
/// Sampling: a mixture of the single-scattering lobe and a sampler of the
/// added lobe's own profile `(1 − E(μi)) cos θi` (`∝ L(μi²) cos θi` with
/// `L` the losses at the table's nodes, linear in `μ²` between them: a
/// continuous density), chosen with probability
/// `w(μo) = 1 − E(μo)` (the fraction of energy the lobe carries when
/// `F = 1`); the density is exactly
/// `pdf = (1 − w) pdf_ss(ωi, ωo) + w μi L(μi²) / (π T)`. (A cosine lobe in its
/// place has the same support but, on smooth surfaces, weights up to 74×
/// their mean in the band `μi ≲ α` where the added lobe lives.)
///
/// ```
/// use radiometry::{Brdf, glam::Vec3};
/// use radiometry_brdfs::microfacet::{Ggx, KullaConty, NoFresnel};
/// # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
/// let b: KullaConty<Ggx> = KullaConty::new(Ggx::new(1.0)?, NoFresnel);
/// let wo = Vec3::Z;
/// // Single scattering keeps E(1) = 1 − ln 2 at normal incidence; the lobe adds the rest.
/// let e = b.albedo(1.0) - radiometry_brdfs::microfacet::LOSS_MARGIN;
/// assert!((e - (1.0 - core::f32::consts::LN_2)).abs() < 1e-4);
/// assert!(b.average_albedo() > 0.3 && b.average_albedo() < 0.6);
/// let s = b.sample(wo, [0.3, 0.7]).unwrap();
/// assert!((s.pdf - b.pdf(s.wi, wo)).abs() <= 1e-6 * s.pdf);
/// assert!(b.eval(Vec3::new(0.6, 0.0, 0.8), wo) > b.single().eval(Vec3::new(0.6, 0.0, 0.8), wo));
/// # Ok(())
/// # }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KullaConty<D, G = HeightCorrelated, F = NoFresnel>
where
    F: Fresnel,
{
    single: Microfacet<D, G, F>,
    /// `1 − E(μ)` at this `α` on the nodes `μ_j` of this instance (the
    /// table's `√μ` nodes after the tangent scaling by `1/r`).
    loss: [f32; N_MU],
    /// `r² = min(α/0.2, 1)²` ([`node_scale`]): a direction's node coordinate is
    /// `μ_ref = μ / √(μ² + r² sin²θ)` (`tan θ_ref = r tan θ`).
    r2: f32,
    /// `E_avg` of the interpolated row.
    e_avg: f32,
    /// `μ_j²` of the nodes (cell `j` of the lobe sampler is
    /// `μ² ∈ [mu_sq[j], mu_sq[j + 1]]`).
    mu_sq: [f32; N_MU],
    /// Cumulative masses `Σ_{k<j} M_k / T` of the lobe sampler's cells
    /// (`cdf[0] = 0`, `cdf[N_MU − 1] = 1`).
    cdf: [f32; N_MU],
    /// `h_j / (π T)` at the nodes: the lobe sampler's density is `μ` times
    /// these, interpolated linearly in `μ²` ([`lobe_sampler`]).
    dens: [f32; N_MU],
    /// `F_ms / (π (1 − E_avg))` per channel (0 when the lobe is off).
    scale: F::Spectrum,
}

/// `F_avg = 2 ∫₀¹ F(μ) μ dμ` per channel (Kulla & Conty 2017), by a 3-point
/// Gauss–Legendre rule on each of 16 equal cells of `μ` (error below `10⁻⁶`
/// for the smooth `F` of conductors and dielectrics with `η > 1`; a total
/// internal reflection kink (`η < 1`) costs up to ~`10⁻⁴`).
fn fresnel_average<F: Fresnel>(f: &F) -> F::Spectrum {
    const G: [(f32, f32); 3] = [
        (0.112_701_66, 5.0 / 18.0),
        (0.5, 8.0 / 18.0),
        (0.887_298_35, 5.0 / 18.0),
    ];
    const CELLS: usize = 16;
    let h = 1.0 / CELLS as f32;
    let mut sum = F::Spectrum::zero();
    for c in 0..CELLS {
        for &(t, w) in &G {
            let mu = (c as f32 + t) * h;
            sum += f.eval(mu) * (w * mu);
        }
    }
    (sum * (2.0 * h)).map(|v| v.clamp(0.0, 1.0))
}

impl<D, G, F> KullaConty<D, G, F>
where
    D: MicrofacetDistribution + EnergyTable<G>,
    G: ShadowingMasking,
    F: Fresnel,
{
    /// Compensates `Microfacet::<D, G, F>::new(distribution, fresnel)`.
    /// Infallible: both arguments were validated by their constructors.
    pub fn new(distribution: D, fresnel: F) -> Self {
        Self::from_single(Microfacet::new(distribution, fresnel))
    }

    /// Compensates an existing single-scattering BRDF: tabulates
    /// `1 − E(μ_j)` once at its `α` ([`AlbedoTable::albedo`](super::AlbedoTable::albedo))
    /// on 64 nodes, then computes `E_avg`, `F_avg` and `F_ms`.
    ///
    /// The nodes are the table's `μ_ref,j = (j/63)²` mapped by
    /// `tan θ = tan θ_ref / r`, `r = min(α/0.2, 1)`: for `α ≥ 0.2` they are the
    /// table's own, for smoother surfaces they crowd towards grazing with
    /// `α`, where the albedo's dip (at `μ ∼ α`) lies. `eval` interpolates
    /// linearly in `√μ_ref`, and `E_avg` is integrated (4-point
    /// Gauss–Legendre per cell) over that same interpolant, so the lobe's
    /// cosine-weighted integral is exactly what the normalisation assumes.
    pub fn from_single(single: Microfacet<D, G, F>) -> Self {
        let alpha = single.distribution.alpha();
        let r = node_scale(alpha);
        let r2 = r * r;
        let inv_r2 = 1.0 / r2;
        let nodes: [f32; N_MU] = core::array::from_fn(|j| {
            let m = mu_node(j);
            rescale_mu(m, (1.0 - m) * (1.0 + m), inv_r2)
        });
        let loss: [f32; N_MU] = core::array::from_fn(|j| 1.0 - D::TABLE.albedo(nodes[j], alpha));
        // The margin's kink max(l − δ, 0) inside a cell splits it: where the
        // interpolated loss crosses δ (linear in t, with t = t_x² in cell 0).
        let split = |j: usize| {
            let (a, b) = (loss[j], loss[j + 1]);
            let t = (LOSS_MARGIN - a) / (b - a);
            if !(t > 0.0 && t < 1.0) {
                return None;
            }
            let tx = if j == 0 { radiometry::math::sqrtf(t) } else { t };
            let x = (j as f32 + tx) / (N_MU - 1) as f32;
            let m = x * x;
            Some(rescale_mu(m, (1.0 - m) * (1.0 + m), inv_r2))
        };
        let avg_loss = cosine_average(&nodes, split, |mu| {
            margined(lerp_row(&loss, rescale_mu(mu, (1.0 - mu) * (1.0 + mu), r2)))
        });
        let e_avg = 1.0 - avg_loss;
        let f_avg = fresnel_average(&single.fresnel);
        let scale = if avg_loss > MIN_AVERAGE_LOSS {
            f_avg.map(|fa| {
                let den = 1.0 - fa * avg_loss;
                if den > 0.0 {
                    (fa * fa * e_avg / den) * (FRAC_1_PI / avg_loss)
                } else {
                    0.0
                }
            })
        } else {
            F::Spectrum::zero()
        };
        let (mu_sq, cdf, dens) = lobe_sampler(&nodes, &loss);
        KullaConty {
            single,
            loss,
            r2,
            mu_sq,
            cdf,
            dens,
            e_avg,
            scale,
        }
    }
}

impl<D, G, F: Fresnel> KullaConty<D, G, F> {
    /// The single-scattering BRDF being compensated.
    pub fn single(&self) -> &Microfacet<D, G, F> {
        &self.single
    }

    /// `E_avg = 2 ∫₀¹ E(μ) μ dμ` of the interpolated albedo at this `α`.
    pub fn average_albedo(&self) -> f32 {
        self.e_avg
    }

    /// The tabulated single-scattering albedo `E(μ)` (`F = 1`) at this `α`
    /// plus [`LOSS_MARGIN`] (what the lobe treats as kept; at most 1),
    /// `μ = cos θ` clamped to `[0, 1]`: linear in `√μ_ref` between the nodes.
    pub fn albedo(&self, mu: f32) -> f32 {
        let mu = clamp01(mu);
        1.0 - self.loss_at(mu, (1.0 - mu) * (1.0 + mu))
    }

    /// `max(1 − E(μ) − δ, 0)` ([`LOSS_MARGIN`]) of a direction with
    /// `cos θ = mu ≥ 0`, `sin²θ = s2`.
    #[inline(always)]
    fn loss_at(&self, mu: f32, s2: f32) -> f32 {
        margined(lerp_row(&self.loss, rescale_mu(mu, s2, self.r2)))
    }

    /// `F_ms / (π (1 − E_avg))` per channel, the constant factor of the
    /// added lobe.
    pub fn lobe_scale(&self) -> F::Spectrum {
        self.scale
    }

    /// The added lobe `scale · (1 − E(μi)) (1 − E(μo))` of unit directions
    /// above the horizon (the product of two factors commutes exactly, so
    /// the lobe is symmetric bit for bit).
    #[inline(always)]
    fn lobe(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        let a = self.loss_at(wi.z, wi.x * wi.x + wi.y * wi.y);
        let b = self.loss_at(wo.z, wo.x * wo.x + wo.y * wo.y);
        self.scale * (a * b)
    }

    /// A direction from the lobe sampler ([`lobe_sampler`]): the cell of
    /// `u₀` in `cdf`, `μ²` in the cell from its linear density (the root of
    /// the quadratic cdf), `φ = 2π u₁`.
    #[inline]
    fn sample_lobe(&self, u0: f32, u1: f32) -> Vec3 {
        let j = self.cdf[1..].partition_point(|&c| c <= u0).min(N_MU - 2);
        let (c0, c1) = (self.cdf[j], self.cdf[j + 1]);
        let r = if c1 > c0 {
            ((u0 - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.5
        };
        // The density in the cell is `∝ h₀ (1 − t) + h₁ t` in `t ∈ [0, 1]`;
        // its cdf `(h₀ t + (h₁ − h₀) t²/2) / ((h₀ + h₁)/2) = r` solved in the
        // cancellation-free form `t = r (h₀ + h₁) / (h₀ + √((1 − r) h₀² + r h₁²))`.
        let (h0, h1) = (self.dens[j], self.dens[j + 1]);
        let den = h0 + radiometry::math::sqrtf(((1.0 - r) * h0 * h0 + r * h1 * h1).max(0.0));
        let t = if den > 0.0 {
            (r * (h0 + h1) / den).clamp(0.0, 1.0)
        } else {
            r
        };
        let (a, b) = (self.mu_sq[j], self.mu_sq[j + 1]);
        let m2 = (a + t * (b - a)).clamp(0.0, 1.0);
        let sin_t = radiometry::math::sqrtf(1.0 - m2);
        let (s, c) = sincos_turn(u1);
        Vec3::new(sin_t * c, sin_t * s, radiometry::math::sqrtf(m2))
    }

    /// The lobe sampler's solid-angle density `μ L(μ²) / (π T)` at
    /// `μ = cos θ` (`L` linear in `μ²` on the cell of `μ²`: continuous).
    #[inline]
    fn lobe_pdf(&self, mu: f32) -> f32 {
        let m2 = mu * mu;
        let j = self.mu_sq[1..].partition_point(|&m| m <= m2).min(N_MU - 2);
        let (a, b) = (self.mu_sq[j], self.mu_sq[j + 1]);
        let t = if b > a {
            ((m2 - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (h0, h1) = (self.dens[j], self.dens[j + 1]);
        mu * (h0 + t * (h1 - h0))
    }

    /// The probability `w(μo) = 1 − E(μo) ∈ [0, 1]` of drawing from the
    /// lobe sampler.
    #[inline(always)]
    fn cosine_weight(&self, wo: Vec3) -> f32 {
        self.loss_at(wo.z, wo.x * wo.x + wo.y * wo.y).clamp(0.0, 1.0)
    }
}

/// Relative floor `ε` of the lobe sampler's node heights (`ℓ_j + ε·max ℓ`):
/// every cell above the horizon keeps a positive density, so the mixture
/// density covers every direction where the BRDF is non-zero.
const SAMPLER_FLOOR: f32 = 1e-3;

/// The lobe sampler's tables from the nodes `μ_j` and the losses `1 − E(μ_j)`.
///
/// The lobe's cosine-weighted profile `(1 − E(μ)) μ` is followed by
/// `L(μ²) μ`, `L` the heights `h_j = ℓ_j + ε max_k ℓ_k` at the nodes (`ℓ`
/// margined) interpolated linearly in `s = μ²` — a continuous density, so
/// that the weights `f cos θi / pdf` have no step at the cells' edges (a
/// piecewise-constant `L` made every warped rule's integrand step along 63
/// lines, and the warped adaptive rule stalled at `10⁻⁵` on Beckmann
/// `α = 0.05` at θo = 85°). The sampler draws `s` from the density
/// `L(s) / T` — cell `j` with probability `M_j / T`,
/// `M_j = (h_j + h_{j+1}) (s_{j+1} − s_j) / 2`, `T = Σ M_k`, then `s` from
/// the cell's linear density — and `φ` uniform, so its solid-angle density
/// is `μ L(μ²) / (π T)` (`dω = ds dφ / (2μ)`). The interpolated loss is
/// monotone between two nodes, like `L`, so the weight of the lobe alone,
/// `F_ms (1 − E(μo)) T (1 − E(μi)) / ((1 − E_avg) L(μi²))`, stays within the
/// ratio of adjacent heights of a constant, where a cosine lobe's
/// weight grows like `(1 − E(μi))`, which for smooth surfaces is a narrow
/// band at the horizon (Beckmann `α = 0.05`: weights up to 74 against a mean
/// of 1).
fn lobe_sampler(nodes: &[f32; N_MU], loss: &[f32; N_MU]) -> ([f32; N_MU], [f32; N_MU], [f32; N_MU]) {
    let mu_sq: [f32; N_MU] = core::array::from_fn(|j| nodes[j] * nodes[j]);
    let mut v: [f32; N_MU] = core::array::from_fn(|j| margined(loss[j]));
    let top = v.iter().fold(0.0f32, |m, &x| m.max(x));
    let floor = if top > 0.0 { SAMPLER_FLOOR * top } else { 1.0 };
    for x in &mut v {
        *x += floor;
    }
    // f32 throughout (63 positive terms: relative rounding ≲ 63 ε), so
    // firmware without a double-precision FPU pulls in no f64 helpers.
    let mass: [f32; N_MU - 1] =
        core::array::from_fn(|j| 0.5 * (v[j] + v[j + 1]) * (mu_sq[j + 1] - mu_sq[j]).max(0.0));
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
    let norm = if total > 0.0 { FRAC_1_PI / total } else { 0.0 };
    let dens: [f32; N_MU] = core::array::from_fn(|j| v[j] * norm);
    (mu_sq, cdf, dens)
}

/// `max(loss − δ, 0)`, the loss the lobe restores ([`LOSS_MARGIN`]); applied
/// after interpolation, so the guarantee holds at every `μ`, not only at
/// the nodes.
#[inline(always)]
fn margined(loss: f32) -> f32 {
    (loss - LOSS_MARGIN).max(0.0)
}

/// Both directions as unit vectors (unchanged when already unit to within
/// `4ε`), or `None` for degenerate input.
#[inline(always)]
fn unit_pair(wi: Vec3, wo: Vec3) -> Option<(Vec3, Vec3)> {
    if is_unit(wi) && is_unit(wo) {
        Some((wi, wo))
    } else {
        Some((unitize(wi)?, unitize(wo)?))
    }
}

impl<D, G, F> Brdf for KullaConty<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
    type Spectrum = F::Spectrum;

    /// `f_ss(ωi, ωo) + F_ms (1 − E(μi))(1 − E(μo)) / (π (1 − E_avg))`
    /// (Kulla & Conty 2017); zero when either direction is at or below the
    /// horizon.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> F::Spectrum {
        let ss = self.single.eval(wi, wo);
        match unit_pair(wi, wo) {
            Some((wi, wo)) if wi.z > 0.0 && wo.z > 0.0 => ss + self.lobe(wi, wo),
            _ => ss,
        }
    }

    /// With probability `w = 1 − E(μo)` a direction of the added lobe's sampler (`u₀`
    /// rescaled to `u₀/w`), otherwise the single-scattering sampler (`u₀`
    /// rescaled to `(u₀ − w)/(1 − w)`); the returned pdf is
    /// [`pdf`](Brdf::pdf) of the pair and the weight `f cos θi / pdf`.
    #[inline]
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<F::Spectrum>> {
        let wo_unit = if is_unit(wo) { wo } else { unitize(wo)? };
        if wo_unit.z <= 0.0 {
            return None;
        }
        let w = self.cosine_weight(wo_unit);
        let (u0, u1) = (clamp01(u[0]), clamp01(u[1]));
        let wi = if u0 < w {
            self.sample_lobe((u0 / w).min(ONE_MINUS_EPS), u1)
        } else {
            let r = if w > 0.0 {
                ((u0 - w) / (1.0 - w)).clamp(0.0, ONE_MINUS_EPS)
            } else {
                u0
            };
            self.single.sample(wo, [r, u1])?.wi
        };
        let wi = if is_unit(wi) { wi } else { unitize(wi)? };
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wi, wo);
        if !(pdf > 0.0 && pdf < f32::INFINITY) {
            return None;
        }
        let f = self.eval(wi, wo);
        let weight = (f * (wi.z / pdf)).map(|v| if v.is_finite() { v } else { 0.0 });
        Some(BrdfSample { wi, pdf, weight })
    }

    /// Two components, in the order of [`sample`](Brdf::sample)'s pick
    /// (`u₀ < w`): the added lobe's sampler (0, weight `w = 1 − E(μo)`) and
    /// the single-scattering sampler (1, weight `1 − w`).
    fn sampling_components(&self) -> usize {
        2
    }

    /// `w = 1 − E(μo)` for the added lobe's component 0, `1 − w` for the
    /// single-scattering component 1 (the weights [`pdf`](Brdf::pdf) mixes
    /// with); at a degenerate `wo` the single-scattering component alone.
    fn component_weight(&self, wo: Vec3, k: usize) -> f32 {
        let w = match if is_unit(wo) { Some(wo) } else { unitize(wo) } {
            Some(wo) if wo.z > 0.0 => self.cosine_weight(wo),
            _ => 0.0,
        };
        match k {
            0 => w,
            1 => 1.0 - w,
            _ => 0.0,
        }
    }

    /// The added lobe's sampler's direction (0) or the single-scattering
    /// one (1) at `u`, as [`sample`](Brdf::sample) draws them from its rescaled
    /// `u₀`; `None` at or below the horizon.
    fn sample_component(&self, wo: Vec3, k: usize, u: [f32; 2]) -> Option<Vec3> {
        let wo_unit = if is_unit(wo) { wo } else { unitize(wo)? };
        if wo_unit.z <= 0.0 {
            return None;
        }
        let (u0, u1) = (clamp01(u[0]).min(ONE_MINUS_EPS), clamp01(u[1]));
        let wi = match k {
            0 => self.sample_lobe(u0, u1),
            1 => self.single.sample(wo, [u0, u1])?.wi,
            _ => return None,
        };
        let wi = if is_unit(wi) { wi } else { unitize(wi)? };
        (wi.z > 0.0).then_some(wi)
    }

    /// `(1 − w) pdf_ss(ωi, ωo) + w μi L(μi²) / (π T)` (the added lobe's sampler: `L` the
    /// heights at the table's nodes, linear in `μ²`, `T` the total mass) with `w = 1 − E(μo)`; 0 when
    /// either direction is at or below the horizon.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let Some((wi_u, wo_u)) = unit_pair(wi, wo) else {
            return 0.0;
        };
        if !(wi_u.z > 0.0 && wo_u.z > 0.0) {
            return 0.0;
        }
        let w = self.cosine_weight(wo_u);
        let p = (1.0 - w) * self.single.pdf(wi, wo) + w * self.lobe_pdf(wi_u.z);
        if p > 0.0 { p.min(f32::MAX) } else { 0.0 }
    }

    /// The single-scattering part as [`Microfacet`]'s albedo (this
    /// instance's tabulated `E(μo)` times the lobe's Fresnel average, with the error over the
    /// range of `F` plus the table's [`ALBEDO_TABLE_ERROR`](super::ALBEDO_TABLE_ERROR)),
    /// plus the added lobe's albedo in closed form: `∫ scale (1 − E(μi))(1 − E(μo)) cos θi dωi
    /// = F_ms (1 − E(μo))` (margined losses), since `scale = F_ms/(π (1 − E_avg))`
    /// and `E_avg` was integrated over the same interpolant; the lobe's term
    /// in the error is `10⁻⁴ F_ms (1 − E(μo))` for that Gauss–Legendre
    /// integration. With `F = 1` the value is `1 − LOSS_MARGIN` up to the
    /// margin's clamp. Zero at or below the horizon.
    fn directional_albedo(&self, wo: Vec3) -> Albedo<F::Spectrum> {
        let Some(w) = unitize(wo) else {
            return Albedo::zero();
        };
        if w.z <= 0.0 {
            return Albedo::zero();
        }
        let s2 = w.x * w.x + w.y * w.y;
        let raw_loss = lerp_row(&self.loss, rescale_mu(w.z, s2, self.r2));
        let e1 = 1.0 - raw_loss;
        let table = self
            .single
            .distribution
            .energy_tables()
            .and_then(|t| G::select_table(&t));
        let single = match table.and_then(|t| self.single.tabulated_fresnel_ratio(t, w.z)) {
            Some((ratio, error)) => Albedo {
                value: (ratio * e1).map(|v| v.clamp(0.0, 1.0)),
                error,
                is_bound: false,
            },
            None => super::fresnel_albedo(e1, self.single.fresnel_spread(w)),
        };
        // F_ms = scale · π (1 − E_avg) per channel.
        let f_ms = self.scale * (core::f32::consts::PI * (1.0 - self.e_avg));
        let lobe = f_ms * self.loss_at(w.z, s2);
        let lobe_err = 1e-4 * lobe.max_channel();
        Albedo {
            value: single.value + lobe,
            error: single.error + lobe_err,
            is_bound: single.is_bound,
        }
    }
}

impl<D, G, F> IsotropicBrdf for KullaConty<D, G, F>
where
    D: MicrofacetDistribution,
    G: ShadowingMasking,
    F: Fresnel,
{
}
