//! Uniform spherical caps (sun, spherical lamp) and the integrand of the reflection equation over a cap.

use super::{
    Light, LightError, LightPart, MAX_RADIANCE, PartVisitor, WideEstimate, check_radiance, visible_wo,
    zero_estimate,
};
use crate::brdf::Brdf;
use crate::frame::try_normalize;
use crate::integrator::chunk::{head, head_mut};
use crate::integrator::{Integrand, IntegrandSample, IntegrateError, Integrator};
use crate::math::safe_sqrt;
use crate::radiometric;
use crate::spectrum::Spectrum;
use crate::warp::square_to_uniform_hemisphere;
use core::f32::consts::{FRAC_1_PI, FRAC_PI_2, TAU};
use glam::Vec3;

/// A uniform spherical cap light: radiance `L` from every direction within
/// half-angle `σ` of a unit axis `ωa` (a distant sphere such as the sun,
/// `σ ≈ 4.65·10⁻³ rad`, or a spherical lamp of radius `r` at distance `d`,
/// `sin σ = r/d`). Irradiance in closed form including a cap partly below
/// the horizon ([`radiometric::cap_irradiance`]; Snyder 1996, MSR-TR-96-11;
/// Lagarde & de Rousiers 2014 §4.7.2). Reflected radiance integrates over
/// the visible part of the cap only ([`CapIntegrand`]).
///
/// ```
/// use radiometry::light::Cap;
/// use radiometry::glam::Vec3;
/// // A cap whose axis lies on the horizon: half of it is visible.
/// let cap = Cap::new(Vec3::X, 0.3, 1.0f32).unwrap();
/// let e = cap.irradiance();
/// assert!((e - (0.3 - libm::sinf(0.3) * libm::cosf(0.3))).abs() < 1e-6);
/// assert!(Cap::new(Vec3::Z, 0.0, 1.0f32).is_err());
/// assert!(Cap::new(Vec3::Z, 1.6, 1.0f32).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cap<S> {
    axis: Vec3,
    half_angle: f32,
    /// `sin²σ` and `cos²σ` (clamped ≥ 0), cached for [`Cap::contains`].
    sin2: f32,
    cos2: f32,
    radiance: S,
}

impl<S: Spectrum> Cap<S> {
    /// A cap around `axis` (normalised here; finite, non-zero; may point
    /// below the horizon) of half-angle `half_angle ∈ (0, π/2]` radians
    /// (`π/2` as the `f32` constant [`core::f32::consts::FRAC_PI_2`] is
    /// accepted) and radiance `radiance` (each channel finite, in
    /// `[0, MAX_RADIANCE]`).
    pub fn new(axis: Vec3, half_angle: f32, radiance: S) -> Result<Self, LightError> {
        let axis = try_normalize(axis).ok_or(LightError::InvalidDirection)?;
        if half_angle.is_nan() || half_angle <= 0.0 || half_angle > FRAC_PI_2 {
            return Err(LightError::HalfAngleOutOfRange(half_angle));
        }
        let (sn, cs) = crate::math::sincos(half_angle);
        let cs = cs.max(0.0);
        Ok(Self {
            axis,
            half_angle,
            sin2: sn * sn,
            cos2: cs * cs,
            radiance: check_radiance(radiance)?,
        })
    }

    /// A cap given by its irradiance at normal incidence `E⊥ = π L sin²σ`
    /// ([`radiometric::cap_normal_irradiance`]), i.e. radiance
    /// `L = E⊥ / (π sin²σ)`: the extended counterpart of
    /// [`Directional::new`](super::Directional::new)`(axis, E⊥)`. Fails with
    /// [`LightError::RadianceTooLarge`] if `L` would exceed
    /// [`MAX_RADIANCE`].
    pub fn from_normal_irradiance(axis: Vec3, half_angle: f32, e_perp: S) -> Result<Self, LightError> {
        let e_perp = check_radiance(e_perp)?;
        if half_angle.is_nan() || half_angle <= 0.0 || half_angle > FRAC_PI_2 {
            return Err(LightError::HalfAngleOutOfRange(half_angle));
        }
        let s = crate::math::sin(half_angle);
        // s > 0, but s² underflows to 0 for σ ≲ 1e-19, making k infinite.
        let k = FRAC_1_PI / (s * s);
        if !k.is_finite() {
            return Err(LightError::RadianceTooLarge);
        }
        // Compute per channel in f64 to detect overflow before rounding.
        let mut ok = true;
        let l = S::from_fn(|i| {
            let v = e_perp.channel(i) as f64 * k as f64;
            if v > MAX_RADIANCE as f64 {
                ok = false;
            }
            v as f32
        });
        if !ok {
            return Err(LightError::RadianceTooLarge);
        }
        Self::new(axis, half_angle, l)
    }

    /// The unit axis.
    pub fn axis(&self) -> Vec3 {
        self.axis
    }

    /// The half-angle σ (radians).
    pub fn half_angle(&self) -> f32 {
        self.half_angle
    }

    /// The radiance `L`.
    pub fn cap_radiance(&self) -> S {
        self.radiance
    }

    /// Solid angle of the whole cap, `2π(1 − cos σ)`
    /// ([`radiometric::cap_solid_angle`]).
    pub fn solid_angle(&self) -> f32 {
        radiometric::cap_solid_angle(self.half_angle)
    }

    /// Irradiance on the surface, horizon-clipped closed form
    /// ([`radiometric::cap_irradiance`]).
    pub fn irradiance(&self) -> S {
        radiometric::cap_irradiance(self.radiance, self.axis.z, self.half_angle)
    }

    /// Whether direction `w` (any finite vector) lies in the cap:
    /// angle(w, axis) ≤ σ, tested as `|w × a|² cos²σ ≤ (w·a)² sin²σ`
    /// with `w·a ≥ 0`, which stays exact for tiny caps (no `1 − cos`).
    pub fn contains(&self, w: Vec3) -> bool {
        let d = w.dot(self.axis);
        if d.is_nan() || d < 0.0 {
            return false;
        }
        let cross2 = w.cross(self.axis).length_squared();
        let w2 = w.length_squared();
        if w2.is_nan() || w2 <= 0.0 || !w2.is_finite() {
            return false;
        }
        cross2 * self.cos2 <= d * d * self.sin2
    }
}

impl<S: Spectrum> Light for Cap<S> {
    type Spectrum = S;

    fn radiance(&self, w: Vec3) -> S {
        if self.contains(w) {
            self.radiance
        } else {
            S::zero()
        }
    }

    fn closed_form_irradiance(&self) -> Option<S> {
        Some(self.irradiance())
    }

    fn for_each_part(&self, f: &mut PartVisitor<'_, S>) -> Result<(), IntegrateError> {
        f(LightPart::Cap(self))
    }
}

impl<S: Spectrum> Cap<S> {
    /// Integrates `f_r L cos θi` over the visible part of the cap only
    /// ([`CapIntegrand`]). A cap entirely below the horizon, or black,
    /// costs nothing.
    pub(crate) fn reflect<B, I>(
        &self,
        brdf: &B,
        wo: Vec3,
        integrator: &I,
        budget: u32,
    ) -> Result<WideEstimate<S>, IntegrateError>
    where
        B: Brdf<Spectrum = S>,
        I: Integrator,
    {
        let Some(wo) = visible_wo(wo) else {
            return Ok(zero_estimate::<S>());
        };
        if self.radiance.is_black()
            || radiometric::cap_projected_solid_angle(self.axis.z, self.half_angle) <= 0.0
        {
            return Ok(zero_estimate::<S>());
        }
        integrator.integrate(&CapIntegrand::new(brdf, wo, self), budget)
    }
}

/// The reflection integrand of a [`Cap`] light, reparametrised so that its
/// integral over the *hemisphere* equals the integral of
/// `f_r(ωi, ωo) L cos θi` over the *visible part of the cap only*; any
/// hemisphere [`Integrator`] then spends all its nodes on the cap.
///
/// Construction (a change of variables, PBR 4th ed. §2.4.1). Cap frame: the
/// axis `a`, `e1` in the vertical plane through `a` pointing down (toward
/// the horizon) and the horizontal `e2 = a × e1`. Cylindrical coordinates
/// about the great circle through `a` and `e1`:
///
/// ```text
/// ω = √(1 − y²) (cos ψ a + sin ψ e1) + y e2,     dω = dψ dy   (Archimedes)
/// ```
///
/// with `y ∈ [−1, 1]` the height along `e2` and `ψ` the angle in the
/// `(a, e1)` plane. In these coordinates both boundaries are simple: the
/// cap `ω·a ≥ cos σ` is `|ψ| ≤ ψ_max(y) = atan2(√(sin²σ − y²), cos σ)`
/// for `|y| ≤ sin σ`, and the horizon `ω_z ≥ 0` is `ψ ≤ ε_a`, the
/// elevation of the axis (`ω_z = √(1 − y²) sin(ε_a − ψ)`), the same for
/// every `y`. A hemisphere direction `ω' = (sin θ' cos φ', sin θ' sin φ',
/// cos θ')` maps `1 − cos θ' ∈ [0, 1]` linearly onto the visible
/// `ψ ∈ [−ψ_max(y), min(ψ_max(y), ε_a)]` and `φ'` onto the visible `y`
/// through `y = sin σ sin χ` (so the chord `√(sin²σ − y²) = sin σ cos χ`
/// has no square-root end at the rim): a cap entirely above the horizon
/// maps `φ'` linearly onto `χ ∈ [−π/2, π/2]`, one smooth piece; a clipped
/// cap splits χ at the break points `−X, (−χ*), 0, (χ*), X` — `X` the
/// largest visible `|χ|`, `χ*` where the horizon meets the rim
/// (`ψ_max(y*) = ε_a`, a kink of the ψ-range) — and maps equal parts of `φ'`
/// onto the pieces through Sidi's sin⁴-transform (Sidi 1993), whose Jacobian
/// vanishes to fourth order at the piece ends. So
///
/// `∫_H g'(ω') dω' = ∫_{cap ∩ H} f_r L cos θ dω`,
/// `g'(ω') = f_r(ω, ωo) L cos θ · (ψ_hi − ψ_lo) · dy/dφ'`.
///
/// Why these coordinates: for a clipped cap the piece ends crowd nodes at
/// `y = 0`, the vertical plane through the axis, where a glossy lobe seen
/// near its grazing mirror direction is a thin ridge (narrow in azimuth
/// about the normal, `|Δy| ≲ α ω_z` for GGX, long in elevation); the ridge
/// runs along ψ, where the integrand is smooth. Polar coordinates about the
/// axis (an earlier version) put their pole on that ridge, which slowed
/// every rule to algebraic convergence (GGX α = 0.01 under the sun at the
/// horizon, seen at the mirror direction: relative error 2.6·10⁻³ at 4,096
/// evaluations). All the quantities stay accurate for tiny caps (the sun):
/// `y`, `ψ` and `ε_a − ψ` are small numbers carried as such, and `ω_z`
/// comes from `sin(ε_a − ψ)`. Its sampling map is uniform on the
/// hemisphere (density `1/2π`).
///
/// ```
/// use radiometry::light::{Cap, CapIntegrand};
/// use radiometry::integrator::{GaussLegendre, Integrator};
/// use radiometry::{Brdf, glam::Vec3};
/// struct One;
/// impl Brdf for One {
///     type Spectrum = f32;
///     fn eval(&self, _: Vec3, _: Vec3) -> f32 { 1.0 }
/// }
/// // With f_r = 1 the integral is the cap irradiance.
/// let cap = Cap::new(Vec3::new(1.0, 0.0, 0.1), 0.4, 1.0f32).unwrap();
/// let e = GaussLegendre::new().integrate(&CapIntegrand::new(One, Vec3::Z, &cap), 5000).unwrap();
/// assert!((e.value - cap.irradiance() as f64).abs() < 1e-5);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct CapIntegrand<B: Brdf> {
    brdf: B,
    wo: Vec3,
    radiance: B::Spectrum,
    /// Cap axis and its frame (local frame): `e1` down in the vertical
    /// plane through the axis, `e2` horizontal.
    a: Vec3,
    e1: Vec3,
    e2: Vec3,
    /// Elevation `ε_a ∈ [−π/2, π/2]` of the axis.
    elevation: f32,
    /// `sin σ`, `cos σ`.
    sin_sigma: f32,
    cos_sigma: f32,
    /// Break points of the visible `y` (`pieces + 1` of them, increasing;
    /// unused entries repeat the last), and the number of pieces (0: the cap
    /// is entirely below the horizon).
    breaks: [f32; 5],
    pieces: u32,
}

/// Sidi's sin⁴-transform `S(t) = t − (2/(3π)) sin 2πt + (1/(12π)) sin 4πt`
/// on `[0, 1]` and its derivative `S'(t) = (8/3) sin⁴(πt)` (Sidi 1993, "A
/// new variable transformation for numerical integration", Int. Ser.
/// Numer. Math. 112, the transform ψ₂): it flattens the integrand at both
/// ends of a piece to fourth order, so pieces of different widths (whose
/// Jacobians differ by a factor at a shared end) still join with four
/// continuous derivatives. The sin²-transform (`S' = 2 sin²πt`) joined them
/// with a jump in the second derivative, and Gauss–Legendre across the
/// join converged as `n⁻³` only (a cap clipped by the horizon: relative
/// error 1.6·10⁻⁵ at 3,930 evaluations).
///
/// Returned as `(S(τ), S'(t), from_end)` with `τ = min(t, 1 − t)` (exact in
/// `f32`) and `from_end = t > ½`; since `S(1 − τ) = 1 − S(τ)`, the mapped
/// point is `lo + w·S(τ)` from the start of a piece `[lo, lo + w]`, or
/// `hi − w·S(τ)` from its end. `S(τ) ∝ τ⁵` near 0, far below `τ`: the
/// closed form cancels there (all digits lost at `τ ≈ 10⁻²`), and points
/// computed so drift away from the Jacobian, which is exact — the error
/// of the quadrature then levels off (at 10⁻⁶ for GGX α = 0.01 under the
/// sun at the horizon, seen at the grazing mirror direction, with the
/// earlier sin² form). So `S(τ)` comes from its Taylor series for
/// `τ ≤ ⅜` ([`SIDI4_SERIES`]) and from the reflected form
/// `½ − (x + (4/3) sin x + (1/6) sin 2x)/(2π)`, `x = 2π(½ − τ)`, a sum of
/// positive terms, above.
#[inline]
fn sidi(t: f32) -> (f32, f32, bool) {
    let t = t.clamp(0.0, 1.0);
    let from_end = t > 0.5;
    let tau = if from_end { 1.0 - t } else { t };
    let s_tau = if tau <= 0.375 {
        // x⁵ Σₖ cₖ x^{2(k−2)}, x = 2πτ ≤ 3π/4 (truncation < 10⁻⁹ relative;
        // the terms alternate, at most 2× the sum).
        let x = TAU * tau;
        let z = x * x;
        let mut acc = SIDI4_SERIES[9];
        for &c in SIDI4_SERIES[..9].iter().rev() {
            acc = c + z * acc;
        }
        // x⁵/(2π) = (2π)⁴ τ⁵ with τ exact: the rounding of x enters only
        // the slowly varying sum.
        let t2 = tau * tau;
        TAU_POW4 * (t2 * t2 * tau) * acc
    } else {
        // S(½ − u) = ½ − (x + (4/3) sin x + (1/6) sin 2x)/(2π), x = 2πu ≤ π/4:
        // a sum of positive terms, at most 2.5× the result.
        let x = TAU * (0.5 - tau);
        let (sx, cx) = crate::math::sincos(x);
        0.5 - (x + (4.0 / 3.0) * sx + (1.0 / 3.0) * sx * cx) / TAU
    };
    let s1 = crate::math::sin(core::f32::consts::PI * tau);
    let s2 = s1 * s1;
    (s_tau.clamp(0.0, 0.5), (8.0 / 3.0) * s2 * s2, from_end)
}

/// `(2π)⁴`.
const TAU_POW4: f32 = 1_558.545_4;

/// `cₖ = (−1)ᵏ (2^{2k+1}/6 − 4/3)/(2k + 1)!`, `k = 2 … 11`: the Taylor
/// coefficients of `x − (4/3) sin x + (1/6) sin 2x = Σₖ cₖ x^{2k+1}` (the
/// terms `k = 0, 1` vanish).
const SIDI4_SERIES: [f32; 10] = [
    1.0 / 30.0,
    -1.0 / 252.0,
    2.314_814_8e-4,
    -8.517_717e-6,
    2.190_453_6e-7,
    -4.175_351_4e-9,
    6.141_347e-11,
    -7.183_191e-13,
    6.841_213e-15,
    -5.408_089e-17,
];

/// The point of a piece `[lo, lo + width]` at Sidi parameter `t` (see
/// [`sidi`]): `lo + width·S(t)`, measured from the nearer end, and the
/// Jacobian `width·S'(t)`.
#[inline]
fn sidi_piece(lo: f32, width: f32, t: f32) -> (f32, f32) {
    let (s_tau, ds, from_end) = sidi(t);
    let x = if from_end {
        (lo + width) - width * s_tau
    } else {
        lo + width * s_tau
    };
    (x, width * ds)
}

impl<B: Brdf> CapIntegrand<B> {
    /// The integrand for `brdf`, outgoing direction `wo` (as given) and the
    /// cap `cap`.
    pub fn new(brdf: B, wo: Vec3, cap: &Cap<B::Spectrum>) -> Self {
        let a = cap.axis;
        let c = a.z.clamp(-1.0, 1.0);
        let s = libm::hypotf(a.x, a.y).min(1.0);
        let (cp, sp) = if s > 0.0 { (a.x / s, a.y / s) } else { (1.0, 0.0) };
        let e1 = Vec3::new(c * cp, c * sp, -s);
        let e2 = Vec3::new(-sp, cp, 0.0);
        let elevation = libm::atan2f(c, s);
        let (ss, cs) = crate::math::sincos(cap.half_angle);
        let (ss, cs) = (ss.clamp(0.0, 1.0), cs.clamp(0.0, 1.0));
        // ψ_max(y) = ε_a ⇔ sin²σ − y² = cos²σ tan²ε_a: the horizon meets the
        // rim at |y| = y*, i.e. at χ* = asin(y*/sin σ).
        let t = libm::tanf(elevation.abs().min(FRAC_PI_2)) * cs;
        let y_rim = safe_sqrt((ss - t) * (ss + t));
        let chi_rim = if ss > 0.0 {
            libm::asinf((y_rim / ss).clamp(0.0, 1.0))
        } else {
            0.0
        };
        let h = FRAC_PI_2;
        let (breaks, pieces) = if elevation >= cap.half_angle {
            // Entirely above the horizon.
            ([-h, h, h, h, h], 1)
        } else if elevation >= 0.0 {
            // The centre is visible; the horizon cuts the rim at ±χ*.
            if chi_rim > 0.0 && chi_rim < h {
                ([-h, -chi_rim, 0.0, chi_rim, h], 4)
            } else {
                ([-h, 0.0, h, h, h], 2)
            }
        } else if t < ss && chi_rim > 0.0 {
            // The centre is hidden: only |χ| < χ* reaches above the horizon.
            ([-chi_rim, 0.0, chi_rim, chi_rim, chi_rim], 2)
        } else {
            ([0.0; 5], 0)
        };
        Self {
            brdf,
            wo,
            radiance: cap.radiance,
            a,
            e1,
            e2,
            elevation,
            sin_sigma: ss,
            cos_sigma: cs,
            breaks,
            pieces,
        }
    }

    /// `(y, √(sin²σ − y²), dy/dφ')` for the hemisphere azimuth
    /// `φ' ∈ [0, 2π]` (through `y = sin σ sin χ`), or `None` when nothing is
    /// visible.
    #[inline]
    fn y_of(&self, phi: f32) -> Option<(f32, f32, f32)> {
        let n = self.pieces;
        if n == 0 {
            return None;
        }
        let part = TAU / n as f32;
        let q = (phi / part).clamp(0.0, n as f32 * (1.0 - f32::EPSILON));
        let k = libm::floorf(q);
        let i = (k as usize).min(n as usize - 1);
        let lo = self.breaks.get(i).copied().unwrap_or(0.0);
        let hi = self.breaks.get(i + 1).copied().unwrap_or(lo);
        let (chi, dchi) = if n == 1 {
            (lo + (hi - lo) * (q - k), hi - lo)
        } else {
            sidi_piece(lo, hi - lo, q - k)
        };
        let (sc, cc) = crate::math::sincos(chi);
        let ss = self.sin_sigma;
        let chord = ss * cc.max(0.0);
        Some((ss * sc, chord, chord * dchi / part))
    }

    /// The direction `ω` and the factor `cos θ · (ψ_hi − ψ_lo)` of `g'`
    /// (without `dy/dφ'`) at `u0 = 1 − cos θ' ∈ [0,1]`, height `y` and
    /// `chord = √(sin²σ − y²)`; `None` where `g'` is zero.
    #[inline]
    fn point_param(&self, u0: f32, y: f32, chord: f32) -> Option<(Vec3, f32)> {
        let psi_max = libm::atan2f(chord, self.cos_sigma);
        let lo = -psi_max;
        let hi = psi_max.min(self.elevation);
        let width = hi - lo;
        if width.is_nan() || width <= 0.0 {
            return None;
        }
        let psi = (lo + u0.clamp(0.0, 1.0) * width).min(hi);
        let r = safe_sqrt((1.0 - y) * (1.0 + y));
        let (sp, cp) = crate::math::sincos(psi);
        let mut w = r * (cp * self.a + sp * self.e1) + y * self.e2;
        // ω_z = √(1 − y²) sin(ε_a − ψ), without the cancellation of the sum.
        w.z = r * crate::math::sin(self.elevation - psi);
        let cz = w.z;
        if cz.is_nan() || cz <= 0.0 {
            return None;
        }
        Some((w, cz * width))
    }

    /// Where `g'` at `u0 = 1 − cos θ' ∈ [0,1]` and hemisphere azimuth `φ'`
    /// needs the BRDF.
    #[inline]
    fn point_at(&self, u0: f32, phi: f32) -> CapPoint {
        match self.y_of(phi) {
            Some((y, chord, dy)) if dy > 0.0 => CapPoint {
                w: self.point_param(u0, y, chord),
                dy,
            },
            _ => CapPoint { w: None, dy: 0.0 },
        }
    }

    /// Where [`Integrand::eval`] at the hemisphere direction `w` needs the BRDF.
    #[inline]
    fn point(&self, w: Vec3) -> CapPoint {
        let u0 = 1.0 - w.z.clamp(0.0, 1.0);
        self.point_at(u0, crate::frame::spherical_phi(w))
    }

    /// `g' = ((f_r L) · cos θ (ψ_hi − ψ_lo)) · dy/dφ'` from
    /// `f = f_r(ω, ωo)` at `p`.
    #[inline]
    fn finish(&self, f: B::Spectrum, p: &CapPoint) -> B::Spectrum {
        match p.w {
            Some((_, s)) => f * self.radiance * s * p.dy,
            None => B::Spectrum::zero(),
        }
    }

    /// `g'` at `p` (one BRDF evaluation where needed).
    #[inline]
    fn value(&self, p: &CapPoint) -> B::Spectrum {
        let f = match p.w {
            Some((w, _)) => self.brdf.eval(w, self.wo),
            None => B::Spectrum::zero(),
        };
        self.finish(f, p)
    }

    /// `out[k] = g'(p[k])` for `k < min(p.len(), out.len(), SUB)`, with
    /// one [`Brdf::eval_batch`] over the points that need the BRDF
    /// (compacted; the others are zero). Never inlined: its buffers
    /// (`SUB` points) stay out of the integrator's frame.
    #[inline(never)]
    fn values(&self, p: &[CapPoint], out: &mut [B::Spectrum]) {
        let wos = [self.wo; SUB];
        let mut dense = [Vec3::ZERO; SUB];
        let mut index = [0u8; SUB];
        let mut vals = [B::Spectrum::zero(); SUB];
        let n = p.len().min(out.len()).min(SUB);
        // Checked writes: `m ≤ k < SUB` by construction, and the code keeps
        // no panic path for it.
        let mut m = 0;
        for (k, p) in head(p, n).iter().enumerate() {
            if let (Some((w, _)), Some(d), Some(i)) = (p.w, dense.get_mut(m), index.get_mut(m)) {
                *d = w;
                *i = k as u8;
                m += 1;
            }
        }
        let m = m.min(SUB);
        self.brdf
            .eval_batch(head(&dense, m), head(&wos, m), head_mut(&mut vals, m));
        for (&k, &v) in head(&index, m).iter().zip(head(&vals, m)) {
            if let Some(o) = out.get_mut(k as usize) {
                *o = v;
            }
        }
        for (o, p) in head_mut(out, n).iter_mut().zip(head(p, n)) {
            *o = self.finish(*o, p);
        }
    }
}

/// Points per call of the cap integrand's BRDF batch: each chunk of the
/// integrators ([`CHUNK`](crate::integrator::CHUNK) points) is evaluated
/// `SUB` points at a time, so the integrand's own buffers (points,
/// compacted directions, values) stay small (≈ 0.5 KB for `f32`) on top of
/// the integrator's. Batch kernels are bit-identical to [`Brdf::eval`], so
/// the values do not depend on it.
const SUB: usize = 8;

/// Where the cap integrand needs the BRDF: the direction with the factor
/// `cos θ · (ψ_hi − ψ_lo)` (`None`: zero), and `dy/dφ'`.
#[derive(Clone, Copy, Debug)]
struct CapPoint {
    w: Option<(Vec3, f32)>,
    dy: f32,
}

impl<B: Brdf> Integrand for CapIntegrand<B> {
    type Spectrum = B::Spectrum;

    #[inline]
    fn eval(&self, w: Vec3) -> B::Spectrum {
        self.value(&self.point(w))
    }

    fn has_sampling_map(&self) -> bool {
        true
    }

    /// Uniform on the hemisphere (`cos θ' = 1 − u₀`, `φ' = 2π u₁`), density
    /// `1/2π`; the value is computed from `u` directly.
    #[inline]
    fn sample(&self, u: [f32; 2]) -> Option<IntegrandSample<B::Spectrum>> {
        let u0 = u[0].clamp(0.0, 1.0);
        let w = square_to_uniform_hemisphere([1.0 - u0, u[1]]);
        Some(IntegrandSample {
            w,
            pdf: 0.5 * FRAC_1_PI,
            value: self.value(&self.point_at(u0, TAU * u[1].clamp(0.0, 1.0))),
        })
    }

    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if w.z >= 0.0 { 0.5 * FRAC_1_PI } else { 0.0 }
    }

    /// As [`Integrand::eval`], with one [`Brdf::eval_batch`] per `SUB`
    /// points over those inside the visible cap.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        crate::batch::zero_tail(out, w.len());
        let mut p = [CapPoint { w: None, dy: 0.0 }; SUB];
        for (w, out) in w.chunks(SUB).zip(out.chunks_mut(SUB)) {
            let n = w.len().min(out.len()).min(SUB);
            for (p, &w) in head_mut(&mut p, n).iter_mut().zip(w) {
                *p = self.point(w);
            }
            self.values(head(&p, n), out);
        }
    }

    /// As [`Integrand::sample`], with one [`Brdf::eval_batch`] per `SUB`
    /// points.
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<B::Spectrum>>]) {
        crate::batch::zero_tail(out, u.len());
        let mut p = [CapPoint { w: None, dy: 0.0 }; SUB];
        let mut v = [B::Spectrum::zero(); SUB];
        for (u, out) in u.chunks(SUB).zip(out.chunks_mut(SUB)) {
            let n = u.len().min(out.len()).min(SUB);
            for (p, u) in head_mut(&mut p, n).iter_mut().zip(u) {
                *p = self.point_at(u[0].clamp(0.0, 1.0), TAU * u[1].clamp(0.0, 1.0));
            }
            self.values(head(&p, n), &mut v);
            for ((o, u), &value) in out.iter_mut().zip(u).zip(head(&v, n)) {
                let u0 = u[0].clamp(0.0, 1.0);
                *o = Some(IntegrandSample {
                    w: square_to_uniform_hemisphere([1.0 - u0, u[1]]),
                    pdf: 0.5 * FRAC_1_PI,
                    value,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The Sidi map against `f64` on a grid dense near both piece ends:
    /// the mapped point is accurate *relative to its distance from the
    /// nearer end* (where the plain `t − sin(2πt)/(2π)` lost every digit),
    /// the Jacobian relative to itself, and the two ends are hit exactly.
    #[test]
    fn sidi_piece_is_accurate_near_both_ends() {
        // S(τ) in f64: the closed form where its cancellation costs < 10⁻¹⁰,
        // the first four terms of the series below (written out from
        // x − (4/3) sin x + (1/6) sin 2x; truncation < 10⁻¹² relative).
        let exact = |tau: f64| {
            let x = core::f64::consts::TAU * tau;
            if tau >= 0.02 {
                tau - (2.0 / (3.0 * core::f64::consts::PI)) * x.sin()
                    + (1.0 / (12.0 * core::f64::consts::PI)) * (2.0 * x).sin()
            } else {
                let z = x * x;
                let c = [
                    1.0 / 30.0,
                    -20.0 / 5040.0,
                    84.0 / 362_880.0,
                    -340.0 / 39_916_800.0,
                ];
                x.powi(5) * (c[0] + z * (c[1] + z * (c[2] + z * c[3]))) / core::f64::consts::TAU
            }
        };
        let mut ts: std::vec::Vec<f32> = (0..=4000).map(|i| i as f32 / 4000.0).collect();
        for k in 1..=60 {
            let tau = 10f32.powf(-(k as f32) / 10.0);
            ts.push(tau);
            ts.push(1.0 - tau);
        }
        let (lo, width) = (-1.3f32, 1.3f32); // the piece [−β*, 0]
        let (mut worst_x, mut worst_j) = (0.0f64, 0.0f64);
        for &t in &ts {
            let (x, j) = sidi_piece(lo, width, t);
            let t64 = t as f64;
            let tau = t64.min(1.0 - t64);
            let want = if t64 > 0.5 {
                (lo + width) as f64 - width as f64 * exact(tau)
            } else {
                lo as f64 + width as f64 * exact(tau)
            };
            // Beyond the rounding of the result itself (one ulp of x), the
            // error relative to the distance from the nearer end (computed
            // without cancellation).
            let dist = width as f64 * exact(tau);
            let ulp = (x.abs() as f64 * f32::EPSILON as f64).max(f32::from_bits(1) as f64);
            if dist > 0.0 {
                let e = ((x as f64 - want).abs() - ulp).max(0.0) / dist;
                worst_x = worst_x.max(e);
            }
            let want_j = width as f64 * (8.0 / 3.0) * (core::f64::consts::PI * t64).sin().powi(4);
            if want_j > 1e-30 {
                worst_j = worst_j.max((j as f64 - want_j).abs() / want_j);
            }
        }
        // Measured: 1.6e-7 (point, beyond one ulp of the result, relative to
        // the distance from the nearer end; the closed form in f32 gives 1:
        // every digit of the displacement lost) and 6.6e-7 (Jacobian).
        assert!(worst_x <= 1e-6, "point {worst_x:e}");
        assert!(worst_j <= 1e-6, "Jacobian {worst_j:e}");
        assert_eq!(sidi_piece(lo, width, 0.0).0, lo);
        assert_eq!(sidi_piece(lo, width, 1.0).0, lo + width);
    }
}
