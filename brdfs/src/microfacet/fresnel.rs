//! Fresnel reflectance terms, chosen by type.

use super::prepared::DielectricCells;
use crate::error::{BrdfError, check_range};
#[cfg(feature = "simd")]
use crate::simd::Vf;
#[cfg(feature = "simd")]
use crate::simd::{LANES, store};
#[cfg(feature = "simd")]
use crate::vec4::sqrt4;
use radiometry::Spectrum;
#[cfg(feature = "simd")]
use radiometry::glam::Vec4;
use radiometry::math::safe_sqrt;

/// Smallest accepted (real part of the) relative index of refraction `η`.
pub const MIN_ETA: f32 = 1e-3;
/// Largest accepted (real part of the) relative index of refraction `η`.
pub const MAX_ETA: f32 = 1e3;
/// Largest accepted extinction coefficient `k` of a [`Conductor`].
pub const MAX_K: f32 = 1e3;

/// The Fresnel factor `F(cos θd)` of a microfacet BRDF, where `θd` is the
/// angle between `ωi` and the microfacet normal `h`.
///
/// `cos_theta_d` is clamped to `[0, 1]` (NaN → 0, i.e. grazing); every
/// implementor returns values in `[0, 1]` per channel, `F → 1` at grazing.
///
/// ```
/// use radiometry_brdfs::microfacet::{Fresnel, NoFresnel, Schlick};
/// assert_eq!(NoFresnel.eval(0.3), 1.0);
/// assert!((Schlick::new(0.04f32).unwrap().eval(1.0) - 0.04).abs() < 1e-7);
/// ```
pub trait Fresnel {
    /// The spectrum type of the reflectance.
    type Spectrum: Spectrum;
    /// `F(cos θd)` per channel.
    fn eval(&self, cos_theta_d: f32) -> Self::Spectrum;

    /// Whether `F` is smooth (analytic) in `cos θd ∈ (0, 1]` (no total
    /// internal reflection kink); see `radiometry::Brdf::is_smooth`.
    /// Default `false`.
    fn is_smooth(&self) -> bool {
        false
    }

    /// The smallest and largest value of `F(cos θd)` per channel over
    /// `cos θd ∈ [0, 1]`, `(min, max)` — what bounds the Fresnel factor of a
    /// microfacet albedo ([`Microfacet`](super::Microfacet)'s
    /// `directional_albedo`).
    ///
    /// The default evaluates `F` on the 33 nodes `cos θd = j/32` and refines
    /// each channel's smallest node value by 24 golden-section steps in the
    /// two cells around it (about 33 + 24·channels evaluations; exact for a
    /// function with one interior minimum, as every Fresnel term of this
    /// crate has); the maximum is the largest node value (`F(0) = 1` for
    /// every physical term). [`NoFresnel`] and [`Schlick`] override it with
    /// their closed forms.
    fn bounds(&self) -> (Self::Spectrum, Self::Spectrum) {
        numeric_bounds(|c| self.eval(c))
    }

    /// How the albedo of a GGX lobe (height-correlated `G2`) with this
    /// Fresnel term is read from the global energy tables
    /// ([`fresnel_table`](super::fresnel_table)): a real dielectric index, or
    /// the coefficients of a term linear in `(1 − c)⁵` and `c (1 − c)⁶`.
    /// Default [`FresnelForm::Other`] (the albedo is estimated from the
    /// lobe's own samples).
    fn form(&self) -> FresnelForm<Self::Spectrum> {
        FresnelForm::Other
    }

    /// Hidden hook (not a stable API): this term carrying the albedo cells
    /// of a GGX (height-correlated) lobe of roughness `alpha`, for
    /// [`Microfacet`](super::Microfacet)'s
    /// [`with_prepared_albedo`](radiometry::Brdf::with_prepared_albedo),
    /// which calls it only for a [`FresnelForm::Dielectric`] term. The
    /// default returns the term unchanged; [`Dielectric`] keeps the cells
    /// ([`Achromatic`](super::Achromatic) forwards).
    #[doc(hidden)]
    fn with_albedo_cells(self, alpha: f32) -> Self
    where
        Self: Sized,
    {
        let _ = alpha;
        self
    }

    /// Hidden hook (not a stable API): the cells
    /// [`with_albedo_cells`](Self::with_albedo_cells) built, if they were
    /// built for roughness `alpha`. Default `None`.
    #[doc(hidden)]
    #[inline(always)]
    fn albedo_cells(&self, alpha: f32) -> Option<&DielectricCells> {
        let _ = alpha;
        None
    }

    /// Hidden hook of the `simd` feature (not a stable API): the last factor
    /// of the microfacet BRDF for one vector of lanes,
    /// `out[k] = F(cos θd[k]) · scale[k]`, and exactly `0` where
    /// `scale[k] = 0` — what `Microfacet::eval` computes from the same two
    /// numbers, bit for bit. `scale[k] ≥ 0` is finite; `cos θd[k] ∈ [0, 1]`
    /// where `scale[k] > 0` (other lanes may hold anything).
    ///
    /// The default calls [`eval`](Self::eval) per lane; [`NoFresnel`],
    /// [`Schlick`], [`Dielectric`] and [`Conductor`] override it with vector
    /// code that performs the scalar operations in the scalar order (0 ulp).
    #[cfg(feature = "simd")]
    #[doc(hidden)]
    #[inline]
    fn eval_scaled_lanes(&self, cos_theta_d: Vf, scale: Vf, out: &mut [Self::Spectrum; LANES]) {
        let (c, s) = (cos_theta_d.to_array(), scale.to_array());
        for (k, o) in out.iter_mut().enumerate() {
            *o = if s[k] == 0.0 {
                Self::Spectrum::zero()
            } else {
                self.eval(c[k]) * s[k]
            };
        }
    }
}

/// What a Fresnel term is, as far as the global energy tables can read its
/// albedo ([`Fresnel::form`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FresnelForm<S> {
    /// `F = 1`.
    One,
    /// The exact unpolarised reflectance of a real relative index `η`.
    Dielectric(f32),
    /// `F(c) = f0 + (1 − f0)(1 − c)⁵ − a c (1 − c)⁶` per channel, never
    /// clamped (Schlick: `a = 0`; F82-tint where it stays in `[0, 1]`).
    Linear {
        /// Reflectance at normal incidence.
        f0: S,
        /// The coefficient of `c (1 − c)⁶`.
        a: S,
    },
    /// Anything else.
    Other,
}

/// [`Fresnel::bounds`] of a function of `cos θd ∈ [0, 1]`: node minimum on
/// 33 nodes, refined per channel by golden-section search in the two cells
/// around it; node maximum.
pub(crate) fn numeric_bounds<S: Spectrum>(f: impl Fn(f32) -> S) -> (S, S) {
    const NODES: usize = 33;
    let h = 1.0 / (NODES - 1) as f32;
    let mut lo = f(0.0);
    let mut hi = lo;
    // Node of each channel's minimum (channels past 64 keep node 0 and are
    // refined around it: their node minimum still bounds them).
    let mut arg = [0usize; 64];
    for j in 1..NODES {
        let v = f(j as f32 * h);
        for (c, a) in arg.iter_mut().enumerate().take(S::CHANNELS) {
            if v.channel(c) < lo.channel(c) {
                *a = j;
            }
        }
        lo = S::from_fn(|c| lo.channel(c).min(v.channel(c)));
        hi = S::from_fn(|c| hi.channel(c).max(v.channel(c)));
    }
    // Golden-section refinement per channel on [x_{j−1}, x_{j+1}].
    const INV_PHI: f32 = 0.618_034;
    let refined = S::from_fn(|c| {
        let j = if c < 64 { arg[c] } else { 0 };
        let (mut a, mut b) = ((j as f32 - 1.0).max(0.0) * h, ((j + 1) as f32 * h).min(1.0));
        let g = |x: f32| f(x).channel(c);
        let mut x1 = b - INV_PHI * (b - a);
        let mut x2 = a + INV_PHI * (b - a);
        let (mut f1, mut f2) = (g(x1), g(x2));
        let mut best = lo.channel(c).min(f1).min(f2);
        for _ in 0..24 {
            if f1 <= f2 {
                b = x2;
                x2 = x1;
                f2 = f1;
                x1 = b - INV_PHI * (b - a);
                f1 = g(x1);
                best = best.min(f1);
            } else {
                a = x1;
                x1 = x2;
                f1 = f2;
                x2 = a + INV_PHI * (b - a);
                f2 = g(x2);
                best = best.min(f2);
            }
        }
        best
    });
    (refined, hi)
}

#[inline]
pub(crate) fn clamp_cos(c: f32) -> f32 {
    if c > 0.0 { c.min(1.0) } else { 0.0 }
}

/// [`clamp_cos`] lane-wise (NaN → 0).
#[cfg(feature = "simd")]
#[inline(always)]
fn clamp_cos_v(c: Vf) -> Vf {
    c.simd_gt(Vf::ZERO).select(c.min(Vf::ONE), Vf::ZERO)
}

/// No Fresnel effect: `F = 1` (zero-sized; costs nothing).
///
/// ```
/// use radiometry_brdfs::microfacet::{Fresnel, NoFresnel};
/// assert_eq!(NoFresnel.eval(0.0), 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct NoFresnel;

impl Fresnel for NoFresnel {
    fn form(&self) -> FresnelForm<f32> {
        FresnelForm::One
    }

    type Spectrum = f32;
    fn is_smooth(&self) -> bool {
        true
    }
    /// `(1, 1)`.
    fn bounds(&self) -> (f32, f32) {
        (1.0, 1.0)
    }
    #[inline(always)]
    fn eval(&self, _cos_theta_d: f32) -> f32 {
        1.0
    }

    /// `1 · s = s` exactly: one vector store.
    #[cfg(feature = "simd")]
    #[inline(always)]
    fn eval_scaled_lanes(&self, _cos_theta_d: Vf, scale: Vf, out: &mut [f32; LANES]) {
        *out = scale.to_array();
    }
}

/// Schlick's approximation `F = f0 + (1 − f0)(1 − cos θd)⁵` (Schlick 1994,
/// "An Inexpensive BRDF Model for Physically-based Rendering", CGF 13(3),
/// eq. 15). Domain: every channel of `f0` in `[0, 1]`.
///
/// ```
/// use radiometry::glam::Vec3;
/// use radiometry_brdfs::microfacet::{Fresnel, Schlick};
/// let f = Schlick::new(Vec3::new(0.9, 0.6, 0.3)).unwrap();
/// assert_eq!(f.eval(0.0), Vec3::ONE);
/// assert!(Schlick::new(1.5f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schlick<S = f32> {
    f0: S,
}

impl<S: Spectrum> Schlick<S> {
    /// Validates `f0 ∈ [0, 1]` per channel.
    pub fn new(f0: S) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("f0", f0.channel(i), 0.0, 1.0)?;
        }
        Ok(Schlick { f0 })
    }

    /// The normal-incidence reflectance `f0`.
    pub fn f0(&self) -> S {
        self.f0
    }
}

impl<S: Spectrum> Fresnel for Schlick<S> {
    fn form(&self) -> FresnelForm<S> {
        FresnelForm::Linear {
            f0: self.f0,
            a: S::zero(),
        }
    }

    type Spectrum = S;
    fn is_smooth(&self) -> bool {
        true
    }
    /// `(f0, 1)`: `F` falls monotonically from 1 at grazing to `f0`.
    fn bounds(&self) -> (S, S) {
        (self.f0, S::splat(1.0))
    }
    #[inline]
    fn eval(&self, cos_theta_d: f32) -> S {
        let m = 1.0 - clamp_cos(cos_theta_d);
        let m2 = m * m;
        let w = m2 * m2 * m;
        self.f0 + (S::splat(1.0) - self.f0) * w
    }

    /// Per channel `(f0 + (1 − f0) w) · s`, the scalar operations in order.
    #[cfg(feature = "simd")]
    #[inline(always)]
    fn eval_scaled_lanes(&self, cos_theta_d: Vf, scale: Vf, out: &mut [S; LANES]) {
        let m = Vf::ONE - clamp_cos_v(cos_theta_d);
        let m2 = m * m;
        let w = m2 * m2 * m;
        let one_minus = S::splat(1.0) - self.f0;
        store(out, |c| {
            (Vf::splat(self.f0.channel(c)) + Vf::splat(one_minus.channel(c)) * w) * scale
        });
    }
}

/// Exact unpolarised Fresnel reflectance of a dielectric interface with
/// relative index of refraction `η = η_t/η_i` (PBR 4th ed., §9.3, eq. 9.4–9.5;
/// Born & Wolf, *Principles of Optics*, §1.5):
///
/// ```text
/// cos θt = sqrt(1 − sin²θi/η²),
/// r∥ = (η cos θi − cos θt)/(η cos θi + cos θt),  r⊥ = (cos θi − η cos θt)/(cos θi + η cos θt),
/// F = (r∥² + r⊥²)/2,
/// ```
///
/// and `F = 1` under total internal reflection (`sin²θi/η² ≥ 1`, only for
/// `η < 1`). Domain: `η ∈ [MIN_ETA, MAX_ETA]`.
///
/// ```
/// use radiometry_brdfs::microfacet::{Dielectric, Fresnel};
/// let glass = Dielectric::new(1.5).unwrap();
/// assert!((glass.eval(1.0) - 0.04).abs() < 1e-6);
/// assert_eq!(Dielectric::new(1.0 / 1.5).unwrap().eval(0.3), 1.0); // TIR
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Dielectric {
    eta: f32,
    /// The albedo cells of the GGX lobe this term was prepared in
    /// ([`Brdf::with_prepared_albedo`](radiometry::Brdf::with_prepared_albedo)
    /// of a [`Microfacet`](super::Microfacet)).
    cells: Option<DielectricCells>,
}

/// Two terms are equal when their indices are (a term prepared in a lobe is
/// the same Fresnel factor).
impl PartialEq for Dielectric {
    fn eq(&self, other: &Self) -> bool {
        self.eta == other.eta
    }
}

impl Dielectric {
    /// Validates `η ∈ [1e-3, 1e3]`.
    pub fn new(eta: f32) -> Result<Self, BrdfError> {
        Ok(Dielectric {
            eta: check_range("eta", eta, MIN_ETA, MAX_ETA)?,
            cells: None,
        })
    }

    /// The term of an `η` the caller has checked (in `[1e-3, 1e3]`).
    #[inline(always)]
    pub(crate) fn from_valid(eta: f32) -> Self {
        Dielectric { eta, cells: None }
    }

    /// The relative index of refraction `η`.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// This term with `cells` as its prepared albedo cells: what
    /// [`Fresnel::with_albedo_cells`] builds, for a caller that computed the
    /// ratio table's cells once for several tables
    /// ([`DielectricCells::new_in`]).
    #[inline(always)]
    pub(crate) fn with_cells(self, cells: DielectricCells) -> Self {
        Self {
            cells: Some(cells),
            ..self
        }
    }
}

impl Fresnel for Dielectric {
    fn form(&self) -> FresnelForm<f32> {
        FresnelForm::Dielectric(self.eta)
    }

    fn with_albedo_cells(self, alpha: f32) -> Self {
        Self {
            cells: Some(DielectricCells::new(alpha, self.eta)),
            ..self
        }
    }

    #[inline(always)]
    fn albedo_cells(&self, alpha: f32) -> Option<&DielectricCells> {
        self.cells.as_ref().and_then(|c| c.for_alpha(alpha))
    }

    type Spectrum = f32;
    fn is_smooth(&self) -> bool {
        // Total internal reflection (η < 1) has a kink at the critical angle.
        self.eta >= 1.0
    }
    #[inline]
    fn eval(&self, cos_theta_d: f32) -> f32 {
        let ci = clamp_cos(cos_theta_d);
        let eta = self.eta;
        let sin2_t = (1.0 - ci * ci) / (eta * eta);
        if sin2_t >= 1.0 {
            return 1.0;
        }
        let ct = safe_sqrt(1.0 - sin2_t);
        let (np, dp) = (eta * ci - ct, eta * ci + ct);
        let (ns, ds) = (ci - eta * ct, ci + eta * ct);
        if dp <= 0.0 || ds <= 0.0 {
            // η = 1 at exact grazing: the 0/0 limit is taken as 1.
            return 1.0;
        }
        let (rp, rs) = (np / dp, ns / ds);
        (0.5 * (rp * rp + rs * rs)).clamp(0.0, 1.0)
    }

    /// The scalar formula lane-wise; the two early returns (`F = 1` under
    /// total internal reflection and at the `η = 1` grazing limit) become
    /// selects.
    #[cfg(feature = "simd")]
    #[inline(always)]
    fn eval_scaled_lanes(&self, cos_theta_d: Vf, scale: Vf, out: &mut [f32; LANES]) {
        let (zero, one) = (Vf::ZERO, Vf::ONE);
        let ci = clamp_cos_v(cos_theta_d);
        let eta = Vf::splat(self.eta);
        let sin2_t = (one - ci * ci) / Vf::splat(self.eta * self.eta);
        let ct = (one - sin2_t).max(zero).sqrt();
        let (np, dp) = (eta * ci - ct, eta * ci + ct);
        let (ns, ds) = (ci - eta * ct, ci + eta * ct);
        let (rp, rs) = (np / dp, ns / ds);
        let f = (Vf::splat(0.5) * (rp * rp + rs * rs)).max(zero).min(one);
        let limit = sin2_t.simd_ge(one) | dp.simd_le(zero) | ds.simd_le(zero);
        *out = (limit.select(one, f) * scale).to_array();
    }
}

/// Exact unpolarised Fresnel reflectance of a conductor with complex
/// relative index of refraction `η + i k` (PBR 4th ed., §9.4, `FrComplex`;
/// Born & Wolf §14.2): the dielectric formula evaluated in complex
/// arithmetic, `F = (|r∥|² + |r⊥|²)/2`. Domain: each channel of `η` in
/// `[MIN_ETA, MAX_ETA]`, of `k` in `[0, MAX_K]`.
///
/// ```
/// use radiometry_brdfs::microfacet::{Conductor, Fresnel};
/// let gold_ish = Conductor::new(0.2f32, 3.0).unwrap();
/// let f0 = (0.8f32 * 0.8 + 9.0) / (1.2 * 1.2 + 9.0);
/// assert!((gold_ish.eval(1.0) - f0).abs() < 1e-5);
/// assert!(Conductor::new(1.0f32, -1.0).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor<S = f32> {
    eta: S,
    k: S,
    /// `1/(η + ik)²` per channel (real and imaginary parts), formed once
    /// here as `fr_complex` would form it per call.
    inv_eta2_re: S,
    inv_eta2_im: S,
}

impl<S: Spectrum> Conductor<S> {
    /// Validates `η ∈ [1e-3, 1e3]` and `k ∈ [0, 1e3]` per channel.
    pub fn new(eta: S, k: S) -> Result<Self, BrdfError> {
        for i in 0..S::CHANNELS {
            check_range("eta", eta.channel(i), MIN_ETA, MAX_ETA)?;
            check_range("k", k.channel(i), 0.0, MAX_K)?;
        }
        Ok(Self::from_valid(eta, k))
    }

    /// [`new`](Self::new) without the checks, for parameters known to be in
    /// the domain (the named metals).
    pub(crate) fn from_valid(eta: S, k: S) -> Self {
        let inv = |i: usize| inv_eta2(eta.channel(i), k.channel(i));
        Conductor {
            eta,
            k,
            inv_eta2_re: S::from_fn(|i| inv(i).re),
            inv_eta2_im: S::from_fn(|i| inv(i).im),
        }
    }

    /// The real part `η` of the index.
    pub fn eta(&self) -> S {
        self.eta
    }

    /// The extinction coefficient `k`.
    pub fn k(&self) -> S {
        self.k
    }

    /// `fr_complex4` on groups of four channels.
    #[cfg(feature = "simd")]
    #[inline]
    fn eval_grouped(&self, ci: f32) -> S {
        // Lanes past the last channel evaluate a harmless η = 1, k = 0.
        let lanes = |v: &S, g: usize, pad: f32| {
            Vec4::from_array(core::array::from_fn(|j| {
                let i = 4 * g + j;
                if i < S::CHANNELS { v.channel(i) } else { pad }
            }))
        };
        let mut group = (usize::MAX, Vec4::ZERO);
        S::from_fn(|i| {
            let g = i / 4;
            if group.0 != g {
                let f = fr_complex4(
                    ci,
                    lanes(&self.eta, g, 1.0),
                    lanes(&self.k, g, 0.0),
                    lanes(&self.inv_eta2_re, g, 1.0),
                    lanes(&self.inv_eta2_im, g, 0.0),
                );
                group = (g, f);
            }
            group.1[i % 4]
        })
    }

    /// `1/(η + ik)²` of channel `i`.
    #[inline(always)]
    fn inv_eta2(&self, i: usize) -> Cx {
        Cx {
            re: self.inv_eta2_re.channel(i),
            im: self.inv_eta2_im.channel(i),
        }
    }
}

/// A minimal complex number for [`Conductor`].
#[derive(Clone, Copy, Debug)]
struct Cx {
    re: f32,
    im: f32,
}

impl Cx {
    #[inline]
    fn add(self, o: Cx) -> Cx {
        Cx {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
    #[inline]
    fn sub(self, o: Cx) -> Cx {
        Cx {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
    #[inline]
    fn mul(self, o: Cx) -> Cx {
        Cx {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
    #[inline]
    fn scale(self, s: f32) -> Cx {
        Cx {
            re: self.re * s,
            im: self.im * s,
        }
    }
    #[inline]
    fn norm2(self) -> f32 {
        self.re * self.re + self.im * self.im
    }
    /// Principal square root (Re ≥ 0), in the cancellation-free form
    /// (Kahan 1987, "Branch cuts for complex elementary functions"), with
    /// `|z| = √(re² + im²)` in `f32`: the one argument, `1 − sin²θt`, has
    /// `|re|, |im| ≤ 1 + 10⁶` for every `η`, `k` the constructor accepts
    /// (`|sin²θt| ≤ 1/|η + ik|² ≤ 10⁶`), so the squares cannot overflow;
    /// where they underflow `|z| < 10⁻¹⁹`, `cos θt ≈ 0` and `F` is 1 to far
    /// below `f32` resolution either way. (`libm::hypotf` rounds an `f64`
    /// sum: a little more accurate, but a scalar call per lane in the
    /// vector kernel, which made the conductor 8× slower than Schlick.)
    #[inline]
    fn sqrt(self) -> Cx {
        let r = radiometry::math::sqrtf(self.norm2());
        if r == 0.0 {
            return Cx { re: 0.0, im: 0.0 };
        }
        if self.re >= 0.0 {
            let t = radiometry::math::sqrtf(0.5 * (r + self.re));
            Cx {
                re: t,
                im: self.im / (2.0 * t),
            }
        } else {
            let t = radiometry::math::sqrtf(0.5 * (r - self.re));
            Cx {
                re: self.im.abs() / (2.0 * t),
                im: libm::copysignf(t, self.im),
            }
        }
    }
}

/// `|a/b|²` with the convention `1` when `b = 0` (grazing limit).
#[inline]
fn ratio_norm2(a: Cx, b: Cx) -> f32 {
    let nb = b.norm2();
    if nb.is_nan() || nb <= 0.0 {
        return 1.0;
    }
    (a.norm2() / nb).clamp(0.0, 1.0)
}

/// `1/(η + ik)² = conj(e²)/|e²|²`, `e = η + ik`.
fn inv_eta2(eta: f32, k: f32) -> Cx {
    let e = Cx { re: eta, im: k };
    let e2 = e.mul(e);
    Cx {
        re: e2.re,
        im: -e2.im,
    }
    .scale(1.0 / e2.norm2())
}

/// `FrComplex(cos θi, η + ik)` for one channel, given `inv_e2 = 1/(η + ik)²`
/// ([`inv_eta2`]).
#[inline]
fn fr_complex(ci: f32, eta: f32, k: f32, inv_e2: Cx) -> f32 {
    let e = Cx { re: eta, im: k };
    let sin2_i = (1.0 - ci * ci).max(0.0);
    // sin²θt = sin²θi / η² = sin²θi · conj(η²)/|η²|²
    let sin2_t = inv_e2.scale(sin2_i);
    let ct = Cx {
        re: 1.0 - sin2_t.re,
        im: -sin2_t.im,
    }
    .sqrt();
    let c = Cx { re: ci, im: 0.0 };
    let ec = e.scale(ci);
    let ect = e.mul(ct);
    let rp = ratio_norm2(ec.sub(ct), ec.add(ct));
    let rs = ratio_norm2(c.sub(ect), c.add(ect));
    (0.5 * (rp + rs)).clamp(0.0, 1.0)
}

/// [`fr_complex`] on four channels at once, one per lane of a
/// `glam::Vec4`: per lane the same operations in the same order (both
/// branches of [`Cx::sqrt`] and of [`ratio_norm2`] as selects), so every
/// lane is bit-identical to `fr_complex` of its channel, while the
/// channels of an RGB conductor share one vector square root or division
/// where `fr_complex` would take three (used with the `simd` feature, whose
/// [`sqrt4`] is one instruction; glam's four scalar roots would cost more
/// than the per-channel form saves).
#[cfg(feature = "simd")]
#[inline]
fn fr_complex4(ci: f32, eta: Vec4, k: Vec4, inv_re: Vec4, inv_im: Vec4) -> Vec4 {
    let (zero, one, half, two) = (Vec4::ZERO, Vec4::ONE, Vec4::splat(0.5), Vec4::splat(2.0));
    let sin2_i = (1.0 - ci * ci).max(0.0);
    // ct = √(1 − sin²θt), sin²θt = sin²θi/η² (`Cx::sqrt`).
    let (z_re, z_im) = (one - inv_re * sin2_i, -(inv_im * sin2_i));
    let r = sqrt4(z_re * z_re + z_im * z_im);
    let tp = sqrt4(half * (r + z_re));
    let tn = sqrt4(half * (r - z_re));
    let pos = z_re.cmpge(zero);
    let at_zero = r.cmpeq(zero);
    let ct_re = Vec4::select(at_zero, zero, Vec4::select(pos, tp, z_im.abs() / (two * tn)));
    let ct_im = Vec4::select(
        at_zero,
        zero,
        Vec4::select(pos, z_im / (two * tp), tn.copysign(z_im)),
    );
    // ec = η ci, ect = η ct; rp = |ec − ct|²/|ec + ct|², rs = |ci − ect|²/|ci + ect|².
    let c = Vec4::splat(ci);
    let (ec_re, ec_im) = (eta * ci, k * ci);
    let (ect_re, ect_im) = (eta * ct_re - k * ct_im, eta * ct_im + k * ct_re);
    let rp = ratio_norm2_4((ec_re - ct_re, ec_im - ct_im), (ec_re + ct_re, ec_im + ct_im));
    let rs = ratio_norm2_4((c - ect_re, zero - ect_im), (c + ect_re, zero + ect_im));
    clamp01_4(half * (rp + rs))
}

/// [`ratio_norm2`] on four lanes (`(re, im)` pairs).
#[cfg(feature = "simd")]
#[inline(always)]
fn ratio_norm2_4(a: (Vec4, Vec4), b: (Vec4, Vec4)) -> Vec4 {
    let nb = b.0 * b.0 + b.1 * b.1;
    let na = a.0 * a.0 + a.1 * a.1;
    // `!(nb > 0)`: NaN or ≤ 0 gives 1, as the scalar test.
    Vec4::select(nb.cmpgt(Vec4::ZERO), clamp01_4(na / nb), Vec4::ONE)
}

/// `f32::clamp(x, 0, 1)` per lane (NaN stays NaN).
#[cfg(feature = "simd")]
#[inline(always)]
fn clamp01_4(x: Vec4) -> Vec4 {
    let x = Vec4::select(x.cmplt(Vec4::ZERO), Vec4::ZERO, x);
    Vec4::select(x.cmpgt(Vec4::ONE), Vec4::ONE, x)
}

impl<S: Spectrum> Fresnel for Conductor<S> {
    type Spectrum = S;
    fn is_smooth(&self) -> bool {
        true
    }
    /// The complex Fresnel formula per channel; with the `simd` feature and
    /// more than one channel, four channels at a time in vector lanes (the
    /// same bits).
    #[inline]
    fn eval(&self, cos_theta_d: f32) -> S {
        let ci = clamp_cos(cos_theta_d);
        #[cfg(feature = "simd")]
        if S::CHANNELS > 1 {
            return self.eval_grouped(ci);
        }
        S::from_fn(|i| fr_complex(ci, self.eta.channel(i), self.k.channel(i), self.inv_eta2(i)))
    }

    /// [`fr_complex`] lane-wise per channel (`fr_complex_v`), times `s`.
    #[cfg(feature = "simd")]
    #[inline(always)]
    fn eval_scaled_lanes(&self, cos_theta_d: Vf, scale: Vf, out: &mut [S; LANES]) {
        let ci = clamp_cos_v(cos_theta_d);
        store(out, |c| {
            fr_complex_v(ci, self.eta.channel(c), self.k.channel(c), self.inv_eta2(c)) * scale
        });
    }
}

/// A vector of complex numbers (`re`, `im` lanes) for [`fr_complex_v`].
#[cfg(feature = "simd")]
#[derive(Clone, Copy)]
struct CxV {
    re: Vf,
    im: Vf,
}

#[cfg(feature = "simd")]
impl CxV {
    #[inline(always)]
    fn add(self, o: CxV) -> CxV {
        CxV {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
    #[inline(always)]
    fn sub(self, o: CxV) -> CxV {
        CxV {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
    /// `Cx::mul` of the lane-constant `e` and `self` (same products, same
    /// order).
    #[inline(always)]
    fn const_mul(e: Cx, o: CxV) -> CxV {
        let (er, ei) = (Vf::splat(e.re), Vf::splat(e.im));
        CxV {
            re: er * o.re - ei * o.im,
            im: er * o.im + ei * o.re,
        }
    }
    #[inline(always)]
    fn norm2(self) -> Vf {
        self.re * self.re + self.im * self.im
    }
    /// [`Cx::sqrt`] lane-wise: both branches, then a select (the same
    /// operations, so bit-identical).
    #[inline(always)]
    fn sqrt(self) -> CxV {
        let r = self.norm2().sqrt();
        let half = Vf::splat(0.5);
        let two = Vf::splat(2.0);
        let pos = self.re.simd_ge(Vf::ZERO);
        // re ≥ 0: t = √((r + re)/2), (t, im/(2t)).
        let tp = (half * (r + self.re)).sqrt();
        // re < 0: t = √((r − re)/2), (|im|/(2t), copysign(t, im)).
        let tn = (half * (r - self.re)).sqrt();
        let tn_signed = self.im.is_sign_negative().select(-tn, tn);
        let zero = r.simd_eq(Vf::ZERO);
        CxV {
            re: zero.select(Vf::ZERO, pos.select(tp, self.im.abs() / (two * tn))),
            im: zero.select(Vf::ZERO, pos.select(self.im / (two * tp), tn_signed)),
        }
    }
}

/// [`ratio_norm2`] lane-wise.
#[cfg(feature = "simd")]
#[inline(always)]
fn ratio_norm2_v(a: CxV, b: CxV) -> Vf {
    let nb = b.norm2();
    let r = (a.norm2() / nb).max(Vf::ZERO).min(Vf::ONE);
    nb.simd_gt(Vf::ZERO).select(r, Vf::ONE)
}

/// [`fr_complex`] of a vector of cosines `ci ∈ [0, 1]` and one channel `η + ik`
/// (with the conductor's stored `1/η²`): every per-lane operation is the
/// scalar one.
#[cfg(feature = "simd")]
#[inline(always)]
fn fr_complex_v(ci: Vf, eta: f32, k: f32, inv_e2: Cx) -> Vf {
    let e = Cx { re: eta, im: k };
    let (zero, one) = (Vf::ZERO, Vf::ONE);
    let sin2_i = (one - ci * ci).max(zero);
    // sin²θt = inv_e2 · sin²θi; ct = √(1 − sin²θt).
    let ct = CxV {
        re: one - Vf::splat(inv_e2.re) * sin2_i,
        im: -(Vf::splat(inv_e2.im) * sin2_i),
    }
    .sqrt();
    let c = CxV { re: ci, im: zero };
    let ec = CxV {
        re: Vf::splat(eta) * ci,
        im: Vf::splat(k) * ci,
    };
    let ect = CxV::const_mul(e, ct);
    let rp = ratio_norm2_v(ec.sub(ct), ec.add(ct));
    let rs = ratio_norm2_v(c.sub(ect), c.add(ect));
    (Vf::splat(0.5) * (rp + rs)).max(zero).min(one)
}
