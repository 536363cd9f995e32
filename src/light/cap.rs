//! Uniform spherical caps (sun, spherical lamp) and the integrand of the reflection equation over a cap.

use super::{
    Light, LightError, MAX_RADIANCE, WideEstimate, check_radiance, exact, visible_wo, zero_estimate,
};
use crate::brdf::Brdf;
use crate::frame::try_normalize;
use crate::integrator::chunk::brdf_eval_where;
use crate::integrator::{CHUNK, Integrand, IntegrandSample, IntegrateError, Integrator};
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
        let (sn, cs) = libm::sincosf(half_angle);
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
        let s = libm::sinf(half_angle);
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

    fn irradiance_estimate<I: Integrator>(&self, _: &I, _: u32) -> Result<WideEstimate<S>, IntegrateError> {
        Ok(exact(self.irradiance(), 0))
    }

    /// Integrates `f_r L cos θi` over the visible part of the cap only
    /// ([`CapIntegrand`]). A cap entirely below the horizon, or black,
    /// costs nothing.
    fn reflected_radiance<B, I>(
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
/// Construction (a change of variables, PBR 4th ed. §2.4.1): with cap
/// coordinates `(α, β)` — α the angle from the axis, β the azimuth about
/// it — and `v = 1 − cos α = 2 sin²(α/2)`, the solid angle is
/// `dω = dv dβ`. For each β the visible α form an interval
/// `[α_lo(β), α_hi(β)] ⊆ [0, σ]` (the horizon `ω_z = 0` is
/// `cos θa cos α − sin θa cos β sin α = 0`, solved for α with `atan2`).
/// A hemisphere direction `ω' = (sin θ' cos φ', sin θ' sin φ', cos θ')`
/// maps to `β = φ'` (unclipped cap; see below for the clipped case) and
/// `v = v_lo + (1 − cos θ')(v_hi − v_lo)`, so
/// `dω = J dω'` with `J(β) = v_hi(β) − v_lo(β)` and
///
/// `∫_H g'(ω') dω' = ∫_{cap ∩ H} f_r L cos θ dω`, `g'(ω') = J f_r(ω(ω'), ωo) L cos θ(ω')`.
///
/// `g'` is smooth in `cos θ'`. In φ' it is smooth and periodic when the
/// cap is entirely above the horizon (`β = φ'`). When the horizon clips
/// the cap, `J(β)` has kinks at `β = ±β*`, `cos β* = cot σ cos θa / sin θa`
/// (where the horizon starts to cut the radial segments), and for an axis
/// at or below the horizon `J = 0` on `|β| < β*`. Then φ' is mapped
/// piecewise onto the visible β-pieces, each a quarter (or half) of φ' —
/// `[−β*, 0]`, `[0, β*]`, `[β*, π]`, `[π, 2π − β*]`; for an axis at or
/// below the horizon `[β*, π]`, `[π, 2π − β*]` — each through Sidi's
/// sin²-transform (Sidi 1993), whose Jacobian vanishes to second order at
/// the piece ends, so the kinks no longer slow quadrature down and no node
/// is spent on the invisible part. The cuts at `β = 0, π` lie in the
/// vertical plane through the axis, the plane of symmetry of the clipped
/// cap: there, for a glossy BRDF seen near its grazing mirror direction,
/// the reflected lobe is a thin ridge (narrow in azimuth about the normal,
/// wide in elevation), and Sidi's crowding of nodes at piece ends
/// resolves it (GGX α = 0.01 under a 5° lamp 2° above the horizon, seen at
/// the mirror direction: `cap-adaptive` reaches 4.5·10⁻⁷ at 65,536
/// evaluations, 1.6·10⁻⁶ with the ridge mid-piece). The Jacobian `dβ/dφ'`
/// multiplies `g'`. Its sampling map is uniform on the hemisphere
/// (density `1/2π`). Using `v`
/// instead of `cos α` keeps full precision for tiny caps (the sun).
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
    /// Cap axis and its orthonormal complement (local frame).
    a: Vec3,
    e1: Vec3,
    e2: Vec3,
    /// cos θa, sin θa of the axis.
    c: f32,
    s: f32,
    sigma: f32,
    sin_sigma: f32,
    v_sigma: f32,
    azimuth: Azimuth,
}

/// How the hemisphere azimuth φ' maps to the cap azimuth β.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Azimuth {
    /// Cap fully above the horizon: `β = φ'`.
    Full,
    /// Axis above the horizon, cap partly below: `|β| < β*` is clipped from
    /// above, `|β| > β*` is whole; each half of φ' covers one piece.
    Split(f32),
    /// Axis at or below the horizon: only `|β| > β*` is visible (clipped
    /// from below); all of φ' covers it.
    Lower(f32),
}

/// Sidi's sin²-transform `S(t) = t − sin(2πt)/(2π)` on `[0, 1]` and its
/// derivative `S'(t) = 2 sin²(πt)` (Sidi 1993, "A new variable
/// transformation for numerical integration", Int. Ser. Numer. Math. 112):
/// it flattens the integrand at both ends of a piece, so a kink at a piece
/// boundary becomes a jump in a high derivative only.
///
/// Returned as `(S(τ), S'(t), from_end)` with `τ = min(t, 1 − t)` (exact in
/// `f32`) and `from_end = t > ½`; since `S(1 − τ) = 1 − S(τ)`, the mapped
/// point is `lo + w·S(τ)` from the start of a piece `[lo, lo + w]`, or
/// `hi − w·S(τ)` from its end. `S(τ) = (x − sin x)/(2π)`, `x = 2πτ ∈ [0, π]`,
/// comes from the Taylor series of `x − sin x = x³ Σₖ (−z)ᵏ/(2k + 3)!`,
/// `z = x²` (10 terms: truncation < 10⁻¹² relative on `[0, π]`; the terms
/// alternate with a largest term below `S(τ)`, so the `f32` sum keeps a
/// relative error of a few ulp): the plain `t − sin(2πt)/(2π)` cancels
/// near the ends, where `S ≈ (2πτ)³/(12π)` is far below `t` — a relative
/// error of 10⁻⁴ at `τ = 0.01` and of 1 at `τ = 5·10⁻⁴` — so the mapped
/// points drifted away from the Jacobian `S'`, which is exact there, and
/// the quadrature's error levelled off at 10⁻⁶ (GGX α = 0.01 under the
/// sun at the horizon, seen at the grazing mirror direction, where the
/// lobe is a ridge at a piece end).
#[inline]
fn sidi(t: f32) -> (f32, f32, bool) {
    let t = t.clamp(0.0, 1.0);
    let from_end = t > 0.5;
    let tau = if from_end { 1.0 - t } else { t };
    let x = TAU * tau;
    let z = x * x;
    // 1/(2k + 3)! for k = 0 … 9.
    const C: [f32; 10] = [
        1.0 / 6.0,
        1.0 / 120.0,
        1.0 / 5040.0,
        1.0 / 362_880.0,
        1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
        1.0 / 1_307_674_368_000.0,
        1.0 / 355_687_428_096_000.0,
        1.0 / 121_645_100_408_832_000.0,
        1.0 / 51_090_942_171_709_440_000.0,
    ];
    let mut acc = C[9];
    for &c in C[..9].iter().rev() {
        acc = c - z * acc;
    }
    let s_tau = (x * z * acc / TAU).clamp(0.0, 0.5);
    let s1 = libm::sinf(core::f32::consts::PI * tau);
    (s_tau, 2.0 * s1 * s1, from_end)
}

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

/// `v(α) = 1 − cos α = 2 sin²(α/2)` without cancellation.
#[inline]
fn versine(alpha: f32) -> f32 {
    let h = libm::sinf(0.5 * alpha);
    2.0 * h * h
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
        let (ss, cs) = libm::sincosf(cap.half_angle);
        let (ss, cs) = (ss.clamp(0.0, 1.0), cs.clamp(0.0, 1.0));
        let azimuth = if c >= ss || s <= 0.0 {
            Azimuth::Full
        } else {
            // The azimuth where clipping starts: cos β* = −y, with
            // y = −cot σ · cos θa / sin θa (see radiometric::cap_projected_solid_angle).
            let y = (-(c / ss) * (cs / s)).clamp(-1.0, 1.0);
            let beta_star = libm::acosf(-y);
            if c > 0.0 {
                Azimuth::Split(beta_star)
            } else {
                Azimuth::Lower(beta_star)
            }
        };
        Self {
            brdf,
            wo,
            radiance: cap.radiance,
            a,
            e1,
            e2,
            c,
            s,
            sigma: cap.half_angle,
            sin_sigma: libm::sinf(cap.half_angle),
            v_sigma: versine(cap.half_angle),
            azimuth,
        }
    }

    /// The visible `[v_lo, v_hi]` at azimuth with cosine `cos_b`, or `None`.
    #[inline]
    fn v_range(&self, cos_b: f32) -> Option<(f32, f32)> {
        let c = self.c;
        if c >= self.sin_sigma {
            return Some((0.0, self.v_sigma));
        }
        // Visible ⇔ c cos α − k sin α ≥ 0, α ∈ [0, σ].
        let k = self.s * cos_b;
        if k > 0.0 {
            if c <= 0.0 {
                return None;
            }
            let hi = libm::atan2f(c, k);
            if hi >= self.sigma {
                Some((0.0, self.v_sigma))
            } else {
                Some((0.0, versine(hi)))
            }
        } else if c >= 0.0 {
            Some((0.0, self.v_sigma))
        } else if k == 0.0 {
            None
        } else {
            let lo = libm::atan2f(-c, -k);
            if lo >= self.sigma {
                None
            } else {
                Some((versine(lo), self.v_sigma))
            }
        }
    }

    /// Cap azimuth β and `dβ/dφ'` for the hemisphere azimuth `φ' ∈ [0, 2π]`.
    #[inline]
    fn beta(&self, phi: f32) -> (f32, f32) {
        let pi = core::f32::consts::PI;
        match self.azimuth {
            Azimuth::Full => (phi, 1.0),
            Azimuth::Lower(bs) => {
                // Two pieces, [β*, π] and [π, 2π − β*].
                let half = pi - bs;
                let (lo, t) = if phi < pi {
                    (bs, phi / pi)
                } else {
                    (pi, (phi - pi) / pi)
                };
                let (b, db) = sidi_piece(lo, half, t);
                (b, db / pi)
            }
            Azimuth::Split(bs) => {
                // Four pieces: [−β*, 0], [0, β*] on φ' < π; [β*, π], [π, 2π − β*] on φ' ≥ π.
                let h = 0.5 * pi;
                let q = (phi / h).clamp(0.0, 3.999_999_8);
                let k = libm::floorf(q);
                let (lo, width) = match k as u32 {
                    0 => (-bs, bs),
                    1 => (0.0, bs),
                    2 => (bs, pi - bs),
                    _ => (pi, pi - bs),
                };
                let (b, db) = sidi_piece(lo, width, q - k);
                (b, db / h)
            }
        }
    }

    /// Where `g'` at `u0 = 1 − cos θ' ∈ [0,1]` and hemisphere azimuth `φ'`
    /// needs the BRDF.
    #[inline]
    fn point_at(&self, u0: f32, phi: f32) -> CapPoint {
        let (beta, dbeta) = self.beta(phi);
        if dbeta <= 0.0 {
            return CapPoint { w: None, dbeta: None };
        }
        let (sb, cb) = libm::sincosf(beta);
        CapPoint {
            w: self.point_param(u0, cb, sb),
            dbeta: Some(dbeta),
        }
    }

    /// The direction `ω` and the factor `cos θ · J` of `g'` (without the
    /// azimuth Jacobian) at `u0 = 1 − cos θ' ∈ [0,1]` and cap azimuth
    /// `(cos β, sin β)`; `None` where `g'` is zero.
    #[inline]
    fn point_param(&self, u0: f32, cos_b: f32, sin_b: f32) -> Option<(Vec3, f32)> {
        let (v_lo, v_hi) = self.v_range(cos_b)?;
        let jac = v_hi - v_lo;
        if jac.is_nan() || jac <= 0.0 {
            return None;
        }
        let v = (v_lo + u0.clamp(0.0, 1.0) * jac).min(v_hi);
        let sin_a = safe_sqrt(v * (2.0 - v));
        let cos_a = 1.0 - v;
        let w = cos_a * self.a + sin_a * (cos_b * self.e1 + sin_b * self.e2);
        let cz = w.z;
        if cz.is_nan() || cz <= 0.0 {
            return None;
        }
        Some((w, cz * jac))
    }

    /// Where [`Integrand::eval`] at the hemisphere direction `w` needs the BRDF.
    #[inline]
    fn point(&self, w: Vec3) -> CapPoint {
        let u0 = 1.0 - w.z.clamp(0.0, 1.0);
        if self.azimuth == Azimuth::Full {
            // β = φ': no trigonometry needed.
            let r = libm::hypotf(w.x, w.y);
            let (cb, sb) = if r > 0.0 && r.is_finite() {
                (w.x / r, w.y / r)
            } else {
                (1.0, 0.0)
            };
            return CapPoint {
                w: self.point_param(u0, cb, sb),
                dbeta: None,
            };
        }
        self.point_at(u0, crate::frame::spherical_phi(w))
    }

    /// `g' = ((f_r L) · cos θ J) · dβ/dφ'` from `f = f_r(ω, ωo)` at `p`.
    #[inline]
    fn finish(&self, f: B::Spectrum, p: &CapPoint) -> B::Spectrum {
        let base = match p.w {
            Some((_, s)) => f * self.radiance * s,
            None => B::Spectrum::zero(),
        };
        match p.dbeta {
            Some(d) => base * d,
            None => base,
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

    /// `out[k] = g'(p[k])` with one [`Brdf::eval_batch`] over the points
    /// that need the BRDF (`p.len() ≤ CHUNK`).
    fn values(&self, p: &[CapPoint], out: &mut [B::Spectrum]) {
        let mut wi = [None; CHUNK];
        let n = p.len().min(out.len()).min(CHUNK);
        for (d, p) in wi[..n].iter_mut().zip(p) {
            *d = p.w.map(|(w, _)| w);
        }
        brdf_eval_where(&self.brdf, self.wo, &wi[..n], &mut out[..n]);
        for (o, p) in out[..n].iter_mut().zip(p) {
            *o = self.finish(*o, p);
        }
    }
}

/// Where the cap integrand needs the BRDF: the direction with the factor
/// `cos θ · J` (`None`: zero), and the azimuth Jacobian to apply (`None`:
/// none).
#[derive(Clone, Copy, Debug)]
struct CapPoint {
    w: Option<(Vec3, f32)>,
    dbeta: Option<f32>,
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

    /// As [`Integrand::eval`], with one [`Brdf::eval_batch`] per chunk over
    /// the points inside the visible cap.
    fn eval_batch(&self, w: &[Vec3], out: &mut [B::Spectrum]) {
        let mut p = [CapPoint { w: None, dbeta: None }; CHUNK];
        for (w, out) in w.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = w.len().min(out.len());
            for (p, &w) in p[..n].iter_mut().zip(w) {
                *p = self.point(w);
            }
            self.values(&p[..n], &mut out[..n]);
        }
    }

    /// As [`Integrand::sample`], with one [`Brdf::eval_batch`] per chunk.
    fn sample_batch(&self, u: &[[f32; 2]], out: &mut [Option<IntegrandSample<B::Spectrum>>]) {
        let mut p = [CapPoint { w: None, dbeta: None }; CHUNK];
        let mut v = [B::Spectrum::zero(); CHUNK];
        for (u, out) in u.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let n = u.len().min(out.len());
            for (p, u) in p[..n].iter_mut().zip(u) {
                *p = self.point_at(u[0].clamp(0.0, 1.0), TAU * u[1].clamp(0.0, 1.0));
            }
            self.values(&p[..n], &mut v[..n]);
            for ((o, u), &value) in out[..n].iter_mut().zip(u).zip(&v[..n]) {
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
        // S(τ) in f64: the formula where its cancellation costs < 10⁻¹¹, the
        // series (x³/6)(1 − x²/20)/(2π) below (truncation < 2·10⁻¹²).
        let exact = |tau: f64| {
            let x = core::f64::consts::TAU * tau;
            if tau >= 1e-3 {
                tau - x.sin() / core::f64::consts::TAU
            } else {
                x * x * x / 6.0 * (1.0 - x * x / 20.0) / core::f64::consts::TAU
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
            let want_j = width as f64 * 2.0 * (core::f64::consts::PI * t64).sin().powi(2);
            if want_j > 1e-30 {
                worst_j = worst_j.max((j as f64 - want_j).abs() / want_j);
            }
        }
        // Measured: 2.5e-7 (point, beyond one ulp of the result, relative to
        // the distance from the nearer end; the plain t − sin(2πt)/(2π)
        // gives 1: every digit of the displacement lost) and 2.9e-7
        // (Jacobian).
        assert!(worst_x <= 1e-6, "point {worst_x:e}");
        assert!(worst_j <= 1e-6, "Jacobian {worst_j:e}");
        assert_eq!(sidi_piece(lo, width, 0.0).0, lo);
        assert_eq!(sidi_piece(lo, width, 1.0).0, lo + width);
    }
}
