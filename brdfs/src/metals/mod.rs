//! Named metals: measured complex refractive indices `η(λ) + i k(λ)`,
//! evaluated at a renderer's wavelengths, and their reductions to RGB (and
//! monochrome) for renderers that do not trace spectra.
//!
//! | [`Metal`] | source | rows | range (nm) |
//! |---|---|---|---|
//! | `Au`, `Ag`, `Cu` | Johnson & Christy 1972, Phys. Rev. B 6, 4370, doi:10.1103/PhysRevB.6.4370 | 25 | 292.4–984.0 |
//! | `Al` | Rakić 1995, Appl. Opt. 34, 4755, doi:10.1364/AO.34.004755 | 19 | 247.97–911.66 |
//! | `Cr`, `Fe`, `Ni`, `Ti` | Johnson & Christy 1974, Phys. Rev. B 9, 5056, doi:10.1103/PhysRevB.9.5056 | 25 | 292.0–984.0 |
//! | `Pt` | Rakić et al. 1998, Appl. Opt. 37, 5271, doi:10.1364/AO.37.005271 (Lorentz–Drude fit to measured data) | 72 | 299.25–902.85 |
//! | `Brass` (Cu 70 %, Zn 30 %) | Querry 1985, CRDC-CR-85034 (DTIC ADA158623) | 61 | 300–900 |
//!
//! The rows are the publications' (through the public-domain
//! refractiveindex.info database; the file `data.rs` says which file each
//! came from and how it was cropped). Between rows `η` and `k` are
//! interpolated linearly in `λ`; outside its range a table is an error
//! ([`Metal::eta_k`]) or, where asked for, clamped to its end rows
//! ([`Metal::eta_k_clamped`]).
//!
//! **Reduction to colour.** A reflectance spectrum `R(λ)` — the Fresnel
//! reflectance `F(μ, λ)` of the metal at one angle — is reduced to linear
//! sRGB by the CIE 1931 2° colour-matching functions under illuminant D65
//! (the white point of sRGB), `XYZ = Σ R(λ) D65(λ) x̄ȳz̄(λ) / Σ D65(λ) ȳ(λ)`
//! over `λ = 360, 365, …, 780 nm` (the range of the crate's D65 table; the
//! CIE functions beyond 780 nm add < 10⁻⁴ of Y), then
//! [`XYZ_TO_SRGB`] (IEC
//! 61966-2-1), each channel clamped to `[0, 1]`. A perfect reflector gives
//! white to `10⁻³`. Monochrome is the `Y` of the same sum (luminance).
//! Those reductions give [`Metal::reflectance_rgb`] (the colour at normal
//! incidence), [`F82Tint::metal`] (OpenPBR's two colours, `f0` and the tint
//! at 82°) and [`Conductor::metal`] (per channel the `η`, `k` whose exact
//! Fresnel curve passes through the reduced reflectances at both angles).
//!
//! ```
//! use radiometry::SampledSpectrum;
//! use radiometry_brdfs::metals::Metal;
//! use radiometry_brdfs::microfacet::{Conductor, Fresnel};
//! # fn main() -> Result<(), radiometry_brdfs::BrdfError> {
//! // Hero-wavelength rendering: four wavelengths per path.
//! let lambdas = [450.0, 530.0, 610.0, 690.0];
//! let gold = Conductor::metal_sampled(Metal::Au, &lambdas)?;
//! let f0: SampledSpectrum<4> = gold.eval(1.0);
//! assert!(f0.0[0] < 0.5 && f0.0[3] > 0.9); // blue absorbed, red reflected
//! // RGB renderers: the colour of gold at normal incidence.
//! let rgb = Metal::Au.reflectance_rgb();
//! assert!(rgb.x > rgb.y && rgb.y > rgb.z);
//! assert!(Metal::Au.eta_k(200.0).is_err()); // outside the measured range
//! assert_eq!(Metal::from_name("au"), Some(Metal::Au));
//! # Ok(())
//! # }
//! ```

mod data;

use crate::error::BrdfError;
use crate::microfacet::{Conductor, F82Tint, Fresnel, MU_BAR};
use radiometry::SampledSpectrum;
use radiometry::glam::Vec3;
use radiometry::spectral::SpectralCurve;
use radiometry::spectral::photometry::XYZ_TO_SRGB;
use radiometry::spectral::{d65, x_bar, y_bar, z_bar};

/// One metal's table: `η(λ_i)`, `k(λ_i)` at increasing wavelengths.
#[derive(Debug, PartialEq)]
pub struct MetalTable {
    /// The publication the rows come from.
    pub source: &'static str,
    /// Its DOI (or report number).
    pub doi: &'static str,
    /// Wavelengths, nm, strictly increasing.
    pub lambda_nm: &'static [f32],
    /// Real part of the refractive index at each wavelength.
    pub eta: &'static [f32],
    /// Extinction coefficient at each wavelength.
    pub k: &'static [f32],
}

/// A metal with a tabulated complex refractive index (see the [module
/// docs](self) for the sources).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Metal {
    /// Gold (Johnson & Christy 1972).
    Au,
    /// Silver (Johnson & Christy 1972).
    Ag,
    /// Copper (Johnson & Christy 1972).
    Cu,
    /// Aluminium (Rakić 1995).
    Al,
    /// Chromium (Johnson & Christy 1974).
    Cr,
    /// Iron (Johnson & Christy 1974).
    Fe,
    /// Nickel (Johnson & Christy 1974).
    Ni,
    /// Titanium (Johnson & Christy 1974).
    Ti,
    /// Platinum (Rakić et al. 1998).
    Pt,
    /// Brass, Cu 70 % Zn 30 % (Querry 1985).
    Brass,
}

/// Wavelengths of the colour reduction: 360, 365, …, 780 nm.
const N_CIE: usize = 85;
const CIE_START: f32 = 360.0;
const CIE_STEP: f32 = 5.0;

impl Metal {
    /// Every named metal.
    pub const ALL: [Metal; 10] = [
        Metal::Au,
        Metal::Ag,
        Metal::Cu,
        Metal::Al,
        Metal::Cr,
        Metal::Fe,
        Metal::Ni,
        Metal::Ti,
        Metal::Pt,
        Metal::Brass,
    ];

    /// The short name: the chemical symbol, or `Brass`.
    pub const fn name(self) -> &'static str {
        match self {
            Metal::Au => "Au",
            Metal::Ag => "Ag",
            Metal::Cu => "Cu",
            Metal::Al => "Al",
            Metal::Cr => "Cr",
            Metal::Fe => "Fe",
            Metal::Ni => "Ni",
            Metal::Ti => "Ti",
            Metal::Pt => "Pt",
            Metal::Brass => "Brass",
        }
    }

    /// The metal of a [`name`](Self::name), ASCII case-insensitive (`"au"`,
    /// `"AU"`, `"brass"`); `CuZn` is accepted for brass. `None` otherwise.
    pub fn from_name(name: &str) -> Option<Metal> {
        if name.eq_ignore_ascii_case("CuZn") {
            return Some(Metal::Brass);
        }
        Metal::ALL
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(name))
    }

    /// The measured table.
    pub fn table(self) -> &'static MetalTable {
        match self {
            Metal::Au => &data::AU,
            Metal::Ag => &data::AG,
            Metal::Cu => &data::CU,
            Metal::Al => &data::AL,
            Metal::Cr => &data::CR,
            Metal::Fe => &data::FE,
            Metal::Ni => &data::NI,
            Metal::Ti => &data::TI,
            Metal::Pt => &data::PT,
            Metal::Brass => &data::BRASS,
        }
    }

    /// The tabulated wavelength range `(min, max)`, nm.
    pub fn range_nm(self) -> (f32, f32) {
        let l = self.table().lambda_nm;
        (
            l.first().copied().unwrap_or(0.0),
            l.last().copied().unwrap_or(0.0),
        )
    }

    /// `(η, k)` at `lambda_nm`, linear in `λ` between the table's rows
    /// (exactly the row's values at a row's wavelength).
    ///
    /// Errors: [`BrdfError::NotFinite`] (parameter `lambda`) for NaN or ±∞,
    /// [`BrdfError::WavelengthOutOfRange`] outside [`range_nm`](Self::range_nm).
    pub fn eta_k(self, lambda_nm: f32) -> Result<(f32, f32), BrdfError> {
        if !lambda_nm.is_finite() {
            return Err(BrdfError::NotFinite { name: "lambda" });
        }
        let (lo, hi) = self.range_nm();
        if !(lo..=hi).contains(&lambda_nm) {
            return Err(BrdfError::WavelengthOutOfRange {
                lambda_nm,
                min_nm: lo,
                max_nm: hi,
            });
        }
        Ok(self.eta_k_clamped(lambda_nm))
    }

    /// `(η, k)` at `lambda_nm` with the wavelength clamped to
    /// [`range_nm`](Self::range_nm) (the end rows continue as constants; NaN
    /// reads as the first row). Total: never fails, always finite.
    pub fn eta_k_clamped(self, lambda_nm: f32) -> (f32, f32) {
        let t = self.table();
        // Slices and `get` throughout: no index can panic (the tables have
        // equal lengths ≥ 2, tested; the code does not rely on it).
        let n = t.lambda_nm.len().min(t.eta.len()).min(t.k.len());
        let (l, eta, k) = (&t.lambda_nm[..n], &t.eta[..n], &t.k[..n]);
        let row = |i: usize| {
            (
                eta.get(i).copied().unwrap_or(1.0),
                k.get(i).copied().unwrap_or(0.0),
            )
        };
        let (Some(&first), Some(&last)) = (l.first(), l.last()) else {
            return (1.0, 0.0);
        };
        let x = if lambda_nm > first {
            lambda_nm.min(last)
        } else {
            first
        };
        // First row strictly above x, kept inside 1..n − 1.
        let j = l.partition_point(|&v| v <= x).min(n - 1).max(1);
        let (Some(&l0), Some(&l1)) = (l.get(j - 1), l.get(j)) else {
            return row(0);
        };
        let s = ((x - l0) / (l1 - l0)).clamp(0.0, 1.0);
        let (a, b) = (row(j - 1), row(j));
        if s == 0.0 {
            a
        } else if s == 1.0 {
            b
        } else {
            (a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1))
        }
    }

    /// `(η, k)` at each of `N` wavelengths (hero-wavelength rendering), as
    /// two [`SampledSpectrum`]s; the first wavelength outside the range is
    /// the error ([`eta_k`](Self::eta_k)).
    pub fn eta_k_sampled<const N: usize>(
        self,
        lambdas_nm: &[f32; N],
    ) -> Result<(SampledSpectrum<N>, SampledSpectrum<N>), BrdfError> {
        let mut eta = [0.0; N];
        let mut k = [0.0; N];
        for i in 0..N {
            (eta[i], k[i]) = self.eta_k(lambdas_nm[i])?;
        }
        Ok((SampledSpectrum(eta), SampledSpectrum(k)))
    }

    /// The reflectance at normal incidence
    /// `R(λ) = ((η − 1)² + k²)/((η + 1)² + k²)` (Born & Wolf §14.2), with the
    /// errors of [`eta_k`](Self::eta_k).
    pub fn reflectance(self, lambda_nm: f32) -> Result<f32, BrdfError> {
        let (n, k) = self.eta_k(lambda_nm)?;
        Ok(((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k))
    }

    /// The exact conductor Fresnel reflectance at `cos θ = mu` on the 85
    /// wavelengths of the colour reduction.
    fn fresnel_on_cie_grid(self, mu: f32) -> SampledSpectrum<N_CIE> {
        let mut eta = [0.0; N_CIE];
        let mut k = [0.0; N_CIE];
        for i in 0..N_CIE {
            (eta[i], k[i]) = self.eta_k_clamped(CIE_START + CIE_STEP * i as f32);
        }
        // Every table's η, k lie inside the conductor's domain (tested).
        Conductor::from_valid(SampledSpectrum(eta), SampledSpectrum(k)).eval(mu)
    }

    /// The Fresnel reflectance at `cos θ = mu` reduced to linear sRGB (see
    /// the [module docs](self)), each channel in `[0, 1]`.
    pub fn fresnel_rgb(self, mu: f32) -> Vec3 {
        let xyz = reduce_xyz(&self.fresnel_on_cie_grid(mu));
        let m = &XYZ_TO_SRGB;
        Vec3::from_array(core::array::from_fn(|r| {
            (m[r][0] * xyz[0] + m[r][1] * xyz[1] + m[r][2] * xyz[2]).clamp(0.0, 1.0)
        }))
    }

    /// The Fresnel reflectance at `cos θ = mu` reduced to its luminance `Y`
    /// (relative to a perfect reflector under D65), in `[0, 1]`.
    pub fn fresnel_luminance(self, mu: f32) -> f32 {
        reduce_xyz(&self.fresnel_on_cie_grid(mu))[1].clamp(0.0, 1.0)
    }

    /// The colour at normal incidence, [`fresnel_rgb`](Self::fresnel_rgb)`(1)`
    /// (OpenPBR's `base_color` of this metal).
    pub fn reflectance_rgb(self) -> Vec3 {
        self.fresnel_rgb(1.0)
    }
}

/// `XYZ = Σ R D65 (x̄, ȳ, z̄) / Σ D65 ȳ` on the reduction grid.
fn reduce_xyz(r: &SampledSpectrum<N_CIE>) -> [f32; 3] {
    let (x, y, z, d) = (x_bar(), y_bar(), z_bar(), d65());
    let mut acc = [0.0f32; 3];
    let mut white = 0.0f32;
    for i in 0..N_CIE {
        let l = CIE_START + CIE_STEP * i as f32;
        let w = d.value(l);
        let yb = y.value(l);
        acc[0] += r.0[i] * w * x.value(l);
        acc[1] += r.0[i] * w * yb;
        acc[2] += r.0[i] * w * z.value(l);
        white += w * yb;
    }
    acc.map(|v| v / white)
}

/// Per channel, the conductor index `η + ik` whose exact Fresnel
/// reflectance is `r` at normal incidence and `h` at `μ̄ = 1/7`
/// (82°), found on the one-parameter family of Gulbrandsen 2014 ("Artist
/// Friendly Metallic Fresnel", JCGT 3(4), eq. 3–4),
/// `η(g) = g (1 − r)/(1 + r) + (1 − g)(1 + √r)/(1 − √r)`,
/// `k² = (r(η + 1)² − (η − 1)²)/(1 − r)`, whose members all have
/// `F(1) = r`: `F(μ̄)` rises with the edge tint `g ∈ [0, 1]`, and `g` is
/// found by 40 bisection steps (a target outside the family's range takes
/// the nearer end). `r` is limited to `[10⁻⁴, 0.996]`, which keeps every
/// member inside the conductor's domain (`η ∈ [2·10⁻³, 998]`, `k < 10³`).
fn fit_eta_k(r: f32, h: f32) -> (f32, f32) {
    let r = r.clamp(1e-4, 0.996);
    let sr = radiometry::math::sqrtf(r);
    let at = |g: f32| {
        let n = g * (1.0 - r) / (1.0 + r) + (1.0 - g) * (1.0 + sr) / (1.0 - sr);
        let k2 = (r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r);
        (n, radiometry::math::sqrtf(k2.max(0.0)))
    };
    let f_bar = |g: f32| {
        let (n, k) = at(g);
        Conductor::from_valid(n, k).eval(MU_BAR)
    };
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    if h <= f_bar(0.0) {
        return at(0.0);
    }
    if h >= f_bar(1.0) {
        return at(1.0);
    }
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if f_bar(mid) < h {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    at(0.5 * (lo + hi))
}

/// The F82-tint parameters `(f0, t)` of one channel's reduced reflectances
/// `F(1)` and `F(μ̄)`: `t = F(μ̄)/F_S(μ̄)`, clamped to `[0, 1]`.
fn f82_params(f0: f32, f_bar: f32) -> (f32, f32) {
    let f0 = f0.clamp(0.0, 1.0);
    let schlick = f0 + (1.0 - f0) * crate::microfacet::f82::W_BAR;
    (f0, (f_bar / schlick).clamp(0.0, 1.0))
}

impl Conductor<Vec3> {
    /// The RGB conductor of a named metal: per channel the `η`, `k` whose
    /// exact Fresnel reflectance equals the metal's sRGB-reduced reflectance
    /// ([`Metal::fresnel_rgb`]) at normal incidence and at 82°
    /// (`μ̄ = 1/7`), on Gulbrandsen's (2014) family of indices. (A direct
    /// reduction of `η` and `k` themselves has no physical meaning and
    /// gives the wrong colour.) Costs a few hundred Fresnel evaluations: build
    /// it once per material.
    pub fn metal(metal: Metal) -> Self {
        let (f0, fb) = (metal.fresnel_rgb(1.0), metal.fresnel_rgb(MU_BAR));
        let fit: [(f32, f32); 3] = core::array::from_fn(|c| fit_eta_k(f0[c], fb[c]));
        let eta = Vec3::from_array(fit.map(|p| p.0));
        let k = Vec3::from_array(fit.map(|p| p.1));
        // The fit keeps η ∈ [10⁻³, 10³) and k ∈ [0, 10³): inside the domain.
        Conductor::from_valid(eta, k)
    }
}

impl Conductor<f32> {
    /// The monochrome conductor of a named metal: as
    /// [`Conductor::metal`], fitted to the luminance `Y` of the reflectance
    /// ([`Metal::fresnel_luminance`]) at normal incidence and at 82°. What
    /// the spec grammar's `conductor(metal=…)` builds.
    pub fn metal_luminance(metal: Metal) -> Self {
        let (n, k) = fit_eta_k(metal.fresnel_luminance(1.0), metal.fresnel_luminance(MU_BAR));
        Conductor::from_valid(n, k)
    }
}

impl<const N: usize> Conductor<SampledSpectrum<N>> {
    /// The spectral conductor of a named metal at `N` wavelengths (nm) — the
    /// hero wavelengths of one path — with the table's `η`, `k`
    /// ([`Metal::eta_k_sampled`]); a wavelength outside the table's range
    /// is an error.
    pub fn metal_sampled(metal: Metal, lambdas_nm: &[f32; N]) -> Result<Self, BrdfError> {
        let (eta, k) = metal.eta_k_sampled(lambdas_nm)?;
        Conductor::new(eta, k)
    }
}

impl F82Tint<Vec3> {
    /// OpenPBR's two metal colours for a named metal: `f0` the sRGB
    /// reflectance at normal incidence and the tint `t = F(μ̄)/F_S(μ̄)` from
    /// the sRGB reflectance at 82° (each reduced from the measured spectrum,
    /// [`Metal::fresnel_rgb`]), clamped to `[0, 1]`.
    pub fn metal(metal: Metal) -> Self {
        let (f0, fb) = (metal.fresnel_rgb(1.0), metal.fresnel_rgb(MU_BAR));
        let p: [(f32, f32); 3] = core::array::from_fn(|c| f82_params(f0[c], fb[c]));
        F82Tint::from_valid(Vec3::from_array(p.map(|x| x.0)), Vec3::from_array(p.map(|x| x.1)))
    }
}

impl F82Tint<f32> {
    /// As [`F82Tint::metal`] from the luminance of the reflectances.
    pub fn metal_luminance(metal: Metal) -> Self {
        let (f0, t) = f82_params(metal.fresnel_luminance(1.0), metal.fresnel_luminance(MU_BAR));
        F82Tint::from_valid(f0, t)
    }
}

#[cfg(test)]
mod tests;
