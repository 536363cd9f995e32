//! The LTC sheen `LtcSheen<S>` of Zeltner, Burley & Chiang 2022: evaluation, exact importance
//! sampling, and the closed-form albedo.

use super::ltc_table::{LtcCoeffs, cell};
use crate::error::{BrdfError, check_range};
use crate::microfacet::{is_unit, unitize};
use core::f32::consts::FRAC_1_PI;
use radiometry::glam::Vec3;
use radiometry::warp::square_to_cosine_hemisphere;
use radiometry::{Albedo, Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// Relative error stated by [`LtcSheen::directional_albedo`]: the albedo `C R` is exact for the
/// lobe as defined; what separates it from `∫ eval cos θi` is the `f32` rounding of `eval` (a few
/// ulps per point; the test `brdfs/tests/ltc_sheen.rs` measures the difference against an `f64`
/// quadrature of `eval`).
pub(crate) const ALBEDO_REL_ERROR: f32 = 1e-5;

/// The sheen of Tizian Zeltner, Brent Burley & Matt Jen-Yuan Chiang, "Practical Multiple-Scattering
/// Sheen Using Linearly Transformed Cosines" (SIGGRAPH 2022 Talks) — OpenPBR Surface 1.1's
/// recommended fuzz lobe:
///
/// ```text
/// f_r(ωi, ωo) cos θi = C · R(μo, r) · D(ω),     ω = Rz(−φo) ωi   (ωi in the frame of ωo's azimuth)
/// D(ω) = D₀(M⁻¹ω/|M⁻¹ω|) · a²/|M⁻¹ω|³ = a² cos θ / (π |M⁻¹ω|⁴),     D₀(ω) = max(cos θ, 0)/π,
/// so   f_r(ωi, ωo) = C · R · a² / (π |M⁻¹ω|⁴),     |M⁻¹ω|² = (a x + b z)² + a² y² + z²,
/// ```
///
/// a linearly transformed cosine (Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light
/// Shading with Linearly Transformed Cosines", eq. 2 and §3) with `M⁻¹ = [[a, 0, b], [0, a, 0],
/// [0, 0, 1]]` and reflectance `R`, where `(a, b, R)` are the authors' fit to a volumetric layer of
/// SGGX fibres (single-scattering albedo 1, unit density and thickness: multiple scattering
/// included), tabulated on a 32 × 32 grid of `μo = cos θo = j/31` × `r = k/31` and interpolated
/// bilinearly ([`LtcCoeffs::at`](super::LtcCoeffs::at); the data: `ltc_data.rs`).
///
/// # Parameters and domain
/// * `color` `C`: every channel in `[0, 1]`; it scales the lobe (the paper's sheen colour).
/// * `roughness` `r ∈ [0, 1]`: the table's vertical axis (the paper's `α = √σ`, `σ` the SGGX
///   fibre cross-section; OpenPBR's `fuzz_roughness`). **At the ends:** `r = 1` is the table's last
///   row (a broad lobe, `R` from `0.34` at normal to `0.75` at grazing view); `r = 0` is the first
///   row, which has a lobe only at grazing view (`μo < 1/31`, `R ≤ 10⁻⁵`): the fuzz is
///   effectively black. Rows 1–3 (`r < 4/31`) likewise hold no lobe towards normal view
///   (`R = 0` there): thin fibres reflect towards grazing only.
/// * Directions: any finite vectors (normalised; zero below the horizon and for degenerate
///   input). `f_r` has no `1/cos θi` singularity: it stays bounded at the horizon.
///
/// # Albedo (closed form)
/// `E(ωo) = ∫_H f_r cos θi dωi = C R ∫_{z>0} D(ω) dω`. Substituting `ω' = M⁻¹ω/|M⁻¹ω|` (the
/// LTC's change of variables, Jacobian `a²/|M⁻¹ω|³`), this is the mass of the clamped cosine `D₀`
/// over the image of the upper hemisphere, `{ω' : (M ω')_z > 0} = {ω' : n·ω' > 0}` with `n` the
/// third row of `M`. The cosine lobe's mass on the positive side of a plane through the origin
/// with normal `n` is `(1 + n_z/|n|)/2` (the view factor of a tilted plane; 1 for `n = +Z`, ½ for a
/// vertical plane). Here `M = [[1/a, 0, −b/a], [0, 1/a, 0], [0, 0, 1]]`: `n = +Z`, the fraction is
/// exactly 1, and
///
/// ```text
/// E(ωo) = C · R(μo, r),
/// ```
///
/// O(1), with the stated error `10⁻⁵ · max(C) R` for the `f32` rounding of `eval` (a bound:
/// measured against an `f64` quadrature of `eval`). `R ≤ 0.75` in the table, so `E < 1`.
/// [`LtcSheen::albedo_untinted`] is `R` alone (OpenPBR's `E_F`, by which the base under the fuzz is
/// attenuated).
///
/// # Sampling
/// Exact: `ω'` cosine-weighted ([`square_to_cosine_hemisphere`]), `ω = M ω'/|M ω'|`
/// (computed as `(x' − b z', y', a z')` normalised: the factor `1/a` cancels), rotated back by
/// `φo`; `pdf = D(ω)` (solid angle), `weight = C R`. Every sample lies above the horizon (`M`
/// keeps `z`), so the pdf integrates to 1 over the hemisphere wherever the lobe exists; `None`
/// where it does not (`a = 0`) and on the horizon (`u` on the disk's rim). `pdf` recomputes `D`
/// from `ωi`, and `sample` returns exactly `pdf(ωi, ωo)`.
///
/// # Symmetry
/// **Not reciprocal**: `f_r(ωi, ωo) ≠ f_r(ωo, ωi)` in general — the fit describes light leaving
/// towards `ωo` (as in the paper, Adobe's OpenPBR BSDF and Blender Cycles). Isotropic: `f_r`
/// depends on `(θi, θo, φo − φi)` only, except at `ωo = +Z` exactly, where the azimuth of `ωo` is
/// undefined and `+X` is used (the table's `|b| ≤ 0.004` at `μo = 1` tilts the lobe that little).
/// [`Brdf::is_smooth`] is `true`: for a fixed `ωo`, `f_r cos θi` is a rational function of `ωi`
/// (the table enters through `ωo` only).
///
/// ```
/// use radiometry::{Brdf, glam::Vec3};
/// use radiometry_brdfs::LtcSheen;
/// let fuzz = LtcSheen::new(Vec3::new(0.9, 0.6, 0.3), 0.5)?;
/// let wo = Vec3::new(0.6, 0.0, 0.8);
/// let s = fuzz.sample(wo, [0.3, 0.7]).unwrap();
/// assert_eq!(s.pdf, fuzz.pdf(s.wi, wo)); // bit for bit
/// let f = fuzz.eval(s.wi, wo);
/// assert!(((f * s.wi.z / s.pdf) - s.weight).abs().max_element() < 1e-5);
/// // The albedo is C·R, and R is what OpenPBR attenuates the base by.
/// let e = fuzz.directional_albedo(wo);
/// let r = fuzz.albedo_untinted(wo.z);
/// assert_eq!(e.value, Vec3::new(0.9, 0.6, 0.3) * r);
/// assert!(e.is_bound && r > 0.0 && r < 1.0);
/// assert!(LtcSheen::new(1.0f32, 1.5).is_err() && LtcSheen::new(-0.1f32, 0.5).is_err());
/// # Ok::<(), radiometry_brdfs::BrdfError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LtcSheen<S: Spectrum = f32> {
    color: S,
    roughness: f32,
    /// The table row cell `⌊31 r⌋` and the weight of the row above it.
    row: usize,
    row_weight: f32,
}

/// `(cos φo, sin φo)` of a direction's azimuth, `(1, 0)` on the normal.
#[inline(always)]
fn azimuth(w: Vec3) -> (f32, f32) {
    let r2 = w.x * w.x + w.y * w.y;
    if r2 >= 1e-30 {
        let inv = 1.0 / radiometry::math::sqrtf(r2);
        (w.x * inv, w.y * inv)
    } else {
        azimuth_cold(w)
    }
}

/// [`azimuth`] of a direction within `10⁻¹⁵` of the normal: rescaled first, so that the azimuth
/// of `(10⁻²⁰, 10⁻²⁰, 1)` is 45° and not lost to underflow.
#[cold]
#[inline(never)]
fn azimuth_cold(w: Vec3) -> (f32, f32) {
    let m = w.x.abs().max(w.y.abs());
    if !(m > 0.0 && m.is_finite()) {
        return (1.0, 0.0);
    }
    let (x, y) = (w.x / m, w.y / m);
    let inv = 1.0 / radiometry::math::sqrtf(x * x + y * y);
    (x * inv, y * inv)
}

impl<S: Spectrum> LtcSheen<S> {
    /// The LTC sheen of colour `color` and roughness `roughness`. O(1): validates and finds the
    /// table rows.
    ///
    /// # Errors
    /// [`BrdfError::NotFinite`] for a NaN/∞ parameter, [`BrdfError::OutOfRange`] for a `color`
    /// channel or the `roughness` outside `[0, 1]`.
    pub fn new(color: S, roughness: f32) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("color", color.channel(i), 0.0, 1.0)?;
        }
        let roughness = check_range("roughness", roughness, 0.0, 1.0)?;
        Ok(Self::from_valid(color, roughness))
    }

    /// The lobe of a colour and roughness the caller has checked (each in
    /// `[0, 1]`): a material built at every hit from parameters it validated.
    #[inline(always)]
    pub(crate) fn from_valid(color: S, roughness: f32) -> Self {
        let (row, row_weight) = cell(roughness);
        Self {
            color,
            roughness,
            row,
            row_weight,
        }
    }

    /// The colour `C`.
    #[inline]
    pub fn color(&self) -> S {
        self.color
    }

    /// The roughness `r`.
    #[inline]
    pub fn roughness(&self) -> f32 {
        self.roughness
    }

    /// The LTC `(a, b, R)` at `cos θo = mu_o` (clamped to `[0, 1]`, NaN → 0) for this roughness.
    #[inline]
    pub fn coefficients(&self, mu_o: f32) -> LtcCoeffs {
        LtcCoeffs::in_rows(self.row, self.row_weight, mu_o)
    }

    /// The albedo of the lobe with colour 1 at `μo = cos θo`: `R(μo, r)`, one bilinear table
    /// lookup (see the type's "Albedo"). `0` for `mu_o ≤ 0` or NaN (at or below the horizon, as
    /// [`Brdf::directional_albedo`]); `mu_o > 1` is read as 1. In `[0, 0.75]`.
    ///
    /// OpenPBR attenuates the layers under the fuzz by `1 − w_F E_F(ωo)`, `E_F` this value.
    ///
    /// ```
    /// use radiometry_brdfs::LtcSheen;
    /// let fuzz = LtcSheen::new(1.0f32, 0.5)?;
    /// assert!(fuzz.albedo_untinted(0.1) > fuzz.albedo_untinted(1.0)); // more sheen at grazing view
    /// assert_eq!(fuzz.albedo_untinted(0.0), 0.0);
    /// # Ok::<(), radiometry_brdfs::BrdfError>(())
    /// ```
    #[inline]
    pub fn albedo_untinted(&self, mu_o: f32) -> f32 {
        if mu_o > 0.0 {
            self.coefficients(mu_o).r
        } else {
            0.0
        }
    }

    /// `(R, D(ωi)/cos θi)` for unit `wi`, `wo`: `R` and `a²/(π |M⁻¹ω|⁴)` in the frame of `ωo`'s
    /// azimuth, `(0, 0)` when either is at or below the horizon or the lobe is absent.
    #[inline(always)]
    fn unit_terms(&self, wi: Vec3, wo: Vec3) -> (f32, f32) {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            return (0.0, 0.0);
        }
        let c = self.coefficients(wo.z);
        if c.a == 0.0 {
            return (0.0, 0.0);
        }
        terms_in(c, azimuth(wo), wi)
    }

    /// The lobe's state at one unit `ωo`: its coefficients at `μo` and
    /// `ωo`'s azimuth, for a material that evaluates several `ωi` at one
    /// view ([`eval_pdf_at`](Self::eval_pdf_at)).
    #[inline]
    pub(crate) fn at(&self, wo: Vec3) -> LtcAt {
        let above = wo.z > 0.0 && is_unit(wo);
        LtcAt {
            wo,
            above,
            c: if above {
                self.coefficients(wo.z)
            } else {
                LtcCoeffs::ZERO
            },
            azimuth: if above { azimuth(wo) } else { (1.0, 0.0) },
        }
    }

    /// [`eval_pdf`](Self::eval_pdf) at `(wi, at.wo)`, bit for bit, from the
    /// view's state (the table read and the azimuth done once per view).
    #[inline]
    pub(crate) fn eval_pdf_at(&self, at: &LtcAt, wi: Vec3) -> (S, f32) {
        if !(at.above && is_unit(wi)) {
            return self.eval_pdf(wi, at.wo);
        }
        let (r, d) = if wi.z > 0.0 && at.c.a != 0.0 {
            terms_in(at.c, at.azimuth, wi)
        } else {
            (0.0, 0.0)
        };
        (self.color * (r * d), d * wi.z)
    }
}

/// A [`LtcSheen`] at one `ωo` ([`LtcSheen::at`]): `ωo`, whether it is a
/// unit direction above the horizon, and there the coefficients at `μo`
/// and its azimuth `(cos φo, sin φo)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LtcAt {
    wo: Vec3,
    above: bool,
    c: LtcCoeffs,
    azimuth: (f32, f32),
}

impl LtcAt {
    /// Whether `ωo` is a unit direction above the horizon (else the state
    /// holds no lobe and callers take the lobe's own paths).
    #[inline]
    pub(crate) fn is_above(&self) -> bool {
        self.above
    }

    /// The direction [`Brdf::sample`] of the lobe draws at `u` from this
    /// `ωo` (bit for bit its `wi`; the caller evaluates the density), or
    /// `None` where there is no lobe or on the horizon.
    #[inline]
    pub(crate) fn direction(&self, u: [f32; 2]) -> Option<Vec3> {
        if !self.above {
            return None;
        }
        direction(self.c, self.azimuth, u)
    }

    /// `R(μo)`, the lobe's untinted albedo at `ωo` (0 unless `ωo` is a unit
    /// direction above the horizon): [`LtcSheen::albedo_untinted`] of `μo`.
    #[inline]
    pub(crate) fn albedo_untinted(&self) -> f32 {
        self.c.r
    }
}

/// The direction `ω = M ω'/|M ω'|` the LTC of coefficients `c` at `ωo`'s
/// azimuth draws at `u` (`ω'` cosine-weighted), or `None` where there is
/// no lobe (`a = 0`) or on the horizon.
#[inline(always)]
fn direction(c: LtcCoeffs, (cos_o, sin_o): (f32, f32), u: [f32; 2]) -> Option<Vec3> {
    if c.a == 0.0 {
        return None;
    }
    let o = square_to_cosine_hemisphere(u);
    // M ω' up to the factor 1/a (normalised away).
    let x = o.x - c.b * o.z;
    let y = o.y;
    let z = c.a * o.z;
    let v = Vec3::new(cos_o * x - sin_o * y, sin_o * x + cos_o * y, z);
    // |v|² ≥ (a z')² + … ≥ 10⁻²⁴ unless z' = 0 (then z = 0: rejected below).
    let l2 = v.length_squared();
    if l2.is_nan() || l2 <= 0.0 {
        return None;
    }
    let wi = v * (1.0 / radiometry::math::sqrtf(l2));
    if wi.z.is_nan() || wi.z <= 0.0 {
        return None;
    }
    Some(wi)
}

/// `(R, D(ωi)/cos θi)` from the coefficients `c` (`a > 0`) at `μo` and
/// `ωo`'s azimuth, for unit `wi` above the horizon.
#[inline(always)]
fn terms_in(c: LtcCoeffs, (cos_o, sin_o): (f32, f32), wi: Vec3) -> (f32, f32) {
    let x = cos_o * wi.x + sin_o * wi.y;
    let y = cos_o * wi.y - sin_o * wi.x;
    let u = c.a * x + c.b * wi.z;
    let v = c.a * y;
    // ≥ a²/(1 + a² + b²) ≥ 10⁻²³ (smallest singular value of M⁻¹): q ≤ 1.1/a ≤ 1.1·10¹¹.
    let l2 = u * u + v * v + wi.z * wi.z;
    let q = c.a / l2;
    (c.r, q * q * FRAC_1_PI)
}

impl<S: Spectrum> LtcSheen<S> {
    /// `(f_r, pdf)` at once: [`Brdf::eval`] and [`Brdf::pdf`] bit for bit,
    /// the table read and the frame shared (a material that needs both at
    /// one direction, as a mixture's `sample` does).
    #[inline]
    pub(crate) fn eval_pdf(&self, wi: Vec3, wo: Vec3) -> (S, f32) {
        let (r, d, z) = self.terms(wi, wo);
        (self.color * (r * d), d * z)
    }

    /// [`Self::unit_terms`] of any input.
    #[inline(always)]
    fn terms(&self, wi: Vec3, wo: Vec3) -> (f32, f32, f32) {
        if is_unit(wi) && is_unit(wo) {
            let (r, d) = self.unit_terms(wi, wo);
            (r, d, wi.z)
        } else {
            self.terms_cold(wi, wo)
        }
    }

    /// The cold path of [`Self::terms`]: non-unit, degenerate or non-finite input.
    #[cold]
    #[inline(never)]
    fn terms_cold(&self, wi: Vec3, wo: Vec3) -> (f32, f32, f32) {
        match (unitize(wi), unitize(wo)) {
            (Some(wi), Some(wo)) => {
                let (r, d) = self.unit_terms(wi, wo);
                (r, d, wi.z)
            }
            _ => (0.0, 0.0, 0.0),
        }
    }
}

impl<S: Spectrum> Brdf for LtcSheen<S> {
    type Spectrum = S;

    /// `true`: for fixed `ωo`, `f_r cos θi = C R a² cos θ/(π |M⁻¹ω|⁴)` is rational in `ωi`.
    fn is_smooth(&self) -> bool {
        true
    }

    /// `C · R · a²/(π |M⁻¹ω|⁴)` (Zeltner, Burley & Chiang 2022, with the LTC density of Heitz et
    /// al. 2016). Hot path: one squared-length test per direction.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        let (r, d, _) = self.terms(wi, wo);
        self.color * (r * d)
    }

    /// Exact LTC sampling (see the type's "Sampling"); `weight = C R`. `None` when `wo` is at or
    /// below the horizon or degenerate, where the table has no lobe, or on the horizon.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo_unit = if is_unit(wo) { wo } else { unitize(wo)? };
        if wo_unit.z.is_nan() || wo_unit.z <= 0.0 {
            return None;
        }
        let c = self.coefficients(wo_unit.z);
        let wi = direction(c, azimuth(wo_unit), u)?;
        let pdf = self.pdf(wi, wo);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        Some(BrdfSample {
            wi,
            pdf,
            weight: self.color * c.r,
        })
    }

    /// `D(ωi) = a² cos θ/(π |M⁻¹ω|⁴)` when both directions (normalised) are above the horizon
    /// and the lobe exists, else 0.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        let (_, d, z) = self.terms(wi, wo);
        d * z
    }

    /// `C · R(μo, r)`, exact (see the type's "Albedo"), stated error `10⁻⁵ · max(C) R` (`f32`
    /// rounding of `eval`); exactly zero at or below the horizon.
    fn directional_albedo(&self, wo: Vec3) -> Albedo<S> {
        let wo = if is_unit(wo) { Some(wo) } else { unitize(wo) };
        match wo {
            Some(w) if w.z > 0.0 => {
                let r = self.albedo_untinted(w.z);
                Albedo::bounded(self.color * r, self.color.max_channel() * r * ALBEDO_REL_ERROR)
            }
            _ => Albedo::zero(),
        }
    }
}

impl<S: Spectrum> IsotropicBrdf for LtcSheen<S> {}

#[cfg(test)]
mod tests {
    use super::*;
    use radiometry::math::ONE_MINUS_EPSILON;

    /// `eval_pdf` is `(eval, pdf)` bit for bit, unit and non-unit directions,
    /// below the horizon included.
    /// The lobe's state at one `ωo` evaluates and draws bit for bit as the
    /// lobe's own calls: random unit and non-unit pairs, below the horizon,
    /// grazing and zero directions, at four roughnesses.
    #[test]
    fn state_at_wo_is_the_lobes_calls() {
        let mut u = crate::test_stream::uniforms(0x2545_f491_4f6c_dd1d);
        let (mut drawn, mut prepared) = (0, 0);
        for r in [0.0f32, 0.07, 0.5, 1.0] {
            let s = LtcSheen::new(radiometry::glam::Vec3::new(0.9, 0.5, 0.2), r).unwrap();
            for n in 0..3000 {
                let mut dir = || {
                    let v = Vec3::new(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
                    match n % 7 {
                        0 => v * 3.0,
                        1 => Vec3::new(v.x, v.y, 1e-7).normalize_or(Vec3::Z),
                        2 => Vec3::ZERO,
                        _ => v.normalize_or(Vec3::Z),
                    }
                };
                let (wi, wo) = (dir(), dir());
                let at = s.at(wo);
                prepared += usize::from(at.is_above());
                let (v, p) = s.eval_pdf_at(&at, wi);
                let (e, q) = s.eval_pdf(wi, wo);
                assert!(
                    v.to_array().map(f32::to_bits) == e.to_array().map(f32::to_bits),
                    "{wi} {wo}"
                );
                assert_eq!(p.to_bits(), q.to_bits(), "{wi} {wo}");
                if at.is_above() {
                    let uu = [u(), u()];
                    assert_eq!(
                        at.direction(uu).map(|w| w.to_array().map(f32::to_bits)),
                        s.sample(wo, uu).map(|x| x.wi.to_array().map(f32::to_bits)),
                        "{wo} {uu:?}"
                    );
                    drawn += 1;
                    assert_eq!(at.albedo_untinted().to_bits(), s.albedo_untinted(wo.z).to_bits());
                }
            }
        }
        assert!(prepared > 3000 && drawn > 3000, "{prepared} {drawn}");
    }

    #[test]
    fn eval_pdf_is_eval_and_pdf() {
        let mut u = crate::test_stream::uniforms(0x51ed_2701_a3c4_9b1d);
        for r in [0.0f32, 0.07, 0.5, 1.0] {
            let s = LtcSheen::new(radiometry::glam::Vec3::new(0.9, 0.5, 0.2), r).unwrap();
            for n in 0..2000 {
                let mut dir = || {
                    let v = Vec3::new(2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0);
                    if n % 3 == 0 {
                        v * 3.0
                    } else {
                        v.normalize_or(Vec3::Z)
                    }
                };
                let (wi, wo) = (dir(), dir());
                let (v, p) = s.eval_pdf(wi, wo);
                let (e, q) = (s.eval(wi, wo), s.pdf(wi, wo));
                assert!(
                    v.to_array().map(f32::to_bits) == e.to_array().map(f32::to_bits),
                    "{wi} {wo}"
                );
                assert_eq!(p.to_bits(), q.to_bits(), "{wi} {wo}");
            }
        }
    }

    #[test]
    fn parameters_at_the_ends_and_errors() {
        assert!(LtcSheen::new(1.0f32, 0.0).is_ok() && LtcSheen::new(1.0f32, 1.0).is_ok());
        assert!(LtcSheen::new(0.0f32, 0.5).is_ok());
        assert!(matches!(
            LtcSheen::new(1.0f32, -1e-7),
            Err(BrdfError::OutOfRange {
                name: "roughness",
                ..
            })
        ));
        assert!(matches!(
            LtcSheen::new(1.0f32, f32::NAN),
            Err(BrdfError::NotFinite { name: "roughness" })
        ));
        assert!(matches!(
            LtcSheen::new(Vec3::new(0.5, 1.01, 0.5), 0.5),
            Err(BrdfError::OutOfRange { name: "color", .. })
        ));
        // r = 0: a lobe only at grazing view, with R ≤ 10⁻⁵.
        let s = LtcSheen::new(1.0f32, 0.0).unwrap();
        assert_eq!(s.albedo_untinted(0.5), 0.0);
        assert!(s.albedo_untinted(0.01) > 0.0 && s.albedo_untinted(0.01) <= 1e-5);
        assert!(s.sample(Vec3::new(0.6, 0.0, 0.8), [0.5, 0.5]).is_none());
        // r = 1: the last row.
        let s = LtcSheen::new(1.0f32, 1.0).unwrap();
        assert!((s.albedo_untinted(1.0) - 0.34187).abs() < 1e-6);
    }

    #[test]
    fn weight_is_f_cos_over_pdf() {
        let s = LtcSheen::new(0.7f32, 0.4).unwrap();
        for mu in [0.02f32, 0.3, 0.9, 1.0] {
            let wo = Vec3::new((1.0 - mu * mu).sqrt() * 0.6, (1.0 - mu * mu).sqrt() * -0.8, mu);
            for u in [[0.1f32, 0.2], [0.5, 0.5], [0.9, ONE_MINUS_EPSILON], [0.0, 0.0]] {
                if let Some(smp) = s.sample(wo, u) {
                    let f = s.eval(smp.wi, wo);
                    assert_eq!(smp.pdf, s.pdf(smp.wi, wo));
                    let w = f * smp.wi.z / smp.pdf;
                    assert!((w - smp.weight).abs() <= 1e-5 * smp.weight, "{w} {}", smp.weight);
                }
            }
        }
    }
}
