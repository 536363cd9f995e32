//! Adaptive `f64` quadrature with an a-posteriori error estimate, on intervals and on the upper
//! hemisphere.
//!
//! The 1-D rule is Gauss–Legendre with 8 nodes (exact for polynomials of degree 15; nodes found by
//! Newton's method on the Legendre polynomial `P_n`, evaluated by the three-term recurrence
//! `(k+1) P_{k+1} = (2k+1) x P_k − k P_{k−1}`, weights `2 / ((1 − x²) P_n'(x)²)`; Abramowitz & Stegun
//! 25.4.29). Adaptivity: an interval is accepted when the sum of the rule over its two halves differs from
//! the rule over the whole by at most the local tolerance; the reported error is the sum of those
//! differences over all accepted intervals. Because the halves are far more accurate than the whole, that
//! difference over-estimates the error of the accepted value (the standard, conservative a-posteriori
//! estimate). When the depth limit stops the refinement, the last difference is still added to the error,
//! so a hard integrand shows up as a large error. Like every a-posteriori estimate it can be fooled by a
//! feature narrower than the node spacing of the first rule (both levels miss it): callers therefore put
//! breakpoints at lobe centres and widths ([`lobe_breaks`]) and at the horizon kink.
//!
//! Spherical integrals are written in a frame whose pole `r` is chosen by the caller (for a BRDF lobe,
//! the mirror direction): `ω = cos θ' r + sin θ' (cos φ' s + sin φ' t)`, `dω = sin θ' dθ' dφ'`, with `s`
//! in the plane of `r` and the normal, so that the horizon `ω_z = 0` is `A + B cos φ' = 0` and the part of
//! each ring above the horizon is found in closed form (no discontinuity inside an integration interval).

use radiometry::glam::DVec3;
use std::f64::consts::{PI, TAU};

/// A Gauss–Legendre rule on `[-1, 1]`.
#[derive(Clone, Debug)]
pub struct GaussLegendre {
    /// Nodes.
    pub x: Vec<f64>,
    /// Weights.
    pub w: Vec<f64>,
}

impl GaussLegendre {
    /// The `n`-point rule.
    pub fn new(n: usize) -> Self {
        let mut x = vec![0.0; n];
        let mut w = vec![0.0; n];
        for i in 0..n {
            // Initial guess (A&S 22.16.6 asymptotics), then Newton.
            let mut z = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0f64, z);
                for k in 1..n {
                    let p2 = ((2 * k + 1) as f64 * z * p1 - k as f64 * p0) / (k + 1) as f64;
                    p0 = p1;
                    p1 = p2;
                }
                // p1 = P_n(z), p0 = P_{n-1}(z); P_n' = n (z P_n − P_{n−1}) / (z² − 1).
                dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
                let dz = p1 / dp;
                z -= dz;
                if dz.abs() < 1e-16 {
                    break;
                }
            }
            x[i] = z;
            w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        }
        GaussLegendre { x, w }
    }

    /// `∫_a^b f` by this rule; `f` returns (value, auxiliary), both integrated with the same weights.
    pub fn apply(&self, a: f64, b: f64, f: &mut impl FnMut(f64) -> (f64, f64)) -> (f64, f64) {
        let c = 0.5 * (a + b);
        let h = 0.5 * (b - a);
        let (mut v, mut e) = (0.0, 0.0);
        for (x, w) in self.x.iter().zip(&self.w) {
            let (fv, fe) = f(c + h * x);
            v += w * fv;
            e += w * fe;
        }
        (v * h, e * h)
    }
}

/// A value with its error estimate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Integral {
    /// The estimate.
    pub value: f64,
    /// Estimated absolute error (≥ 0).
    pub err: f64,
    /// Integrand evaluations spent.
    pub evals: u64,
}

impl Integral {
    /// Asserts that this reference converged — finite, with an error estimate of at most `bound` — and
    /// returns it. A comparison that uses `err` as slack (`|value − exact| ≤ err + …`) calls this first:
    /// an unconverged reference (say `err = 0.3`) would otherwise widen the tolerance until the
    /// comparison cannot fail. `bound` is fixed by the test, well below the effect it must detect.
    #[track_caller]
    pub fn converged(self, bound: f64, what: impl core::fmt::Display) -> Self {
        assert!(
            self.value.is_finite() && self.err.is_finite() && self.err <= bound,
            "reference did not converge ({what}): {self:?}, required error <= {bound:e}"
        );
        self
    }
}

impl core::ops::Add for Integral {
    type Output = Integral;
    fn add(self, o: Integral) -> Integral {
        Integral {
            value: self.value + o.value,
            err: self.err + o.err,
            evals: self.evals + o.evals,
        }
    }
}

/// Tolerances and limits of the adaptive rule.
#[derive(Clone, Copy, Debug)]
pub struct Tol {
    /// Absolute tolerance of the whole integral.
    pub abs: f64,
    /// Relative tolerance per interval (relative to the interval's own integral of |f|): stops chasing
    /// the rounding noise of `f32` evaluations. The error estimate is reported either way.
    pub rel: f64,
    /// Maximum bisection depth.
    pub depth: u32,
}

/// An adaptive 1-D integrator (8-point Gauss–Legendre).
#[derive(Clone, Debug)]
pub struct Adaptive {
    gl: GaussLegendre,
}

impl Default for Adaptive {
    fn default() -> Self {
        Adaptive {
            gl: GaussLegendre::new(8),
        }
    }
}

impl Adaptive {
    /// `∫_a^b f` where `f(x)` returns `(value, error of value)`; the second component (e.g. the error of
    /// an inner integral) is integrated alongside and added to the reported error.
    pub fn integrate(&self, a: f64, b: f64, tol: Tol, f: &mut impl FnMut(f64) -> (f64, f64)) -> Integral {
        if b <= a {
            return Integral::default();
        }
        let whole = self.gl.apply(a, b, f);
        let mut evals = self.gl.x.len() as u64;
        let (v, e) = self.rec(a, b, whole, tol.abs, tol.rel, tol.depth, f, &mut evals);
        Integral {
            value: v,
            err: e,
            evals,
        }
    }

    /// Sum of [`Adaptive::integrate`] over consecutive segments `breaks[k]..breaks[k+1]`, the absolute
    /// tolerance shared in proportion to the segment lengths.
    pub fn integrate_breaks(
        &self,
        breaks: &[f64],
        tol: Tol,
        f: &mut impl FnMut(f64) -> (f64, f64),
    ) -> Integral {
        let total = breaks.last().unwrap() - breaks[0];
        let mut acc = Integral::default();
        for s in breaks.windows(2) {
            let t = Tol {
                abs: tol.abs * (s[1] - s[0]) / total,
                ..tol
            };
            acc = acc + self.integrate(s[0], s[1], t, f);
        }
        acc
    }

    #[allow(clippy::too_many_arguments)]
    fn rec(
        &self,
        a: f64,
        b: f64,
        whole: (f64, f64),
        abs: f64,
        rel: f64,
        depth: u32,
        f: &mut impl FnMut(f64) -> (f64, f64),
        evals: &mut u64,
    ) -> (f64, f64) {
        let m = 0.5 * (a + b);
        let l = self.gl.apply(a, m, f);
        let r = self.gl.apply(m, b, f);
        *evals += 2 * self.gl.x.len() as u64;
        let v = l.0 + r.0;
        let diff = (v - whole.0).abs();
        if diff <= abs.max(rel * v.abs()) || depth == 0 || m <= a || m >= b {
            return (v, diff + l.1.abs() + r.1.abs());
        }
        let (v1, e1) = self.rec(a, m, l, 0.5 * abs, rel, depth - 1, f, evals);
        let (v2, e2) = self.rec(m, b, r, 0.5 * abs, rel, depth - 1, f, evals);
        (v1 + v2, e1 + e2)
    }
}

/// An orthonormal frame `(s, t, r)` with pole `r`; `s` lies in the plane of `r` and `+Z` with `s_z ≥ 0`,
/// so `t_z = 0`.
#[derive(Clone, Copy, Debug)]
pub struct PoleFrame {
    /// Pole.
    pub r: DVec3,
    /// First tangent (toward `+Z`).
    pub s: DVec3,
    /// Second tangent (horizontal).
    pub t: DVec3,
}

impl PoleFrame {
    /// Frame around the (normalised) pole `r`.
    pub fn new(r: DVec3) -> Self {
        let r = r.normalize();
        let zp = DVec3::Z - r.z * r;
        let s = if zp.length() > 1e-12 {
            zp.normalize()
        } else {
            DVec3::X
        };
        let t = r.cross(s).normalize();
        PoleFrame { r, s, t }
    }

    /// Pole angle `|π/2 − θ_pole|` at which rings around the pole start to cross the horizon.
    pub fn horizon_kink(&self) -> f64 {
        (0.5 * PI - self.r.z.clamp(-1.0, 1.0).acos()).abs()
    }

    /// Largest pole angle that still reaches the upper hemisphere: `π/2 + θ_pole` (at most π).
    pub fn theta_max(&self) -> f64 {
        (0.5 * PI + self.r.z.clamp(-1.0, 1.0).acos()).min(PI)
    }

    /// Pole angles where the part of a ring above the horizon changes character: the kink
    /// `|π/2 − θ_pole|` and the end `π/2 + θ_pole`, plus graded points at distances `λσ`
    /// (`λ = 1/4 … 64`) from them, `σ = |cos θ_pole sin θ_pole|`. Near these points the arc length
    /// above the horizon behaves like a square root over a scale `σ` (`dk/dθ' = 1/σ` there, with
    /// `k = −cot θ' cot θ_pole`), a feature narrower than the nodes of a first rule when the pole is
    /// grazing or nearly normal; the graded breakpoints make the adaptive rule (and its error estimate)
    /// see it.
    pub fn horizon_breaks(&self) -> Vec<f64> {
        let tp = self.r.z.clamp(-1.0, 1.0).acos();
        let sigma = (tp.cos() * tp.sin()).abs();
        let kink = self.horizon_kink();
        let tmax = self.theta_max();
        let mut v = vec![kink];
        if sigma > 0.0 {
            for lam in [0.25, 1.0, 4.0, 16.0, 64.0] {
                v.push(kink - lam * sigma);
                v.push(kink + lam * sigma);
                v.push(tmax - lam * sigma);
            }
        }
        v.retain(|&t| t > 0.0 && t < tmax);
        v
    }

    /// Direction with pole angle cosine `ct`, sine `st` and azimuth `phi`.
    pub fn dir(&self, ct: f64, st: f64, phi: f64) -> DVec3 {
        ct * self.r + st * (phi.cos() * self.s + phi.sin() * self.t)
    }

    /// `(cos θ', φ' ∈ [0, 2π))` of a unit direction.
    pub fn coords(&self, w: DVec3) -> (f64, f64) {
        let c = w.dot(self.r).clamp(-1.0, 1.0);
        let mut p = w.dot(self.t).atan2(w.dot(self.s));
        if p < 0.0 {
            p += TAU;
        }
        if p >= TAU {
            p = 0.0;
        }
        (c, p)
    }

    /// The parts of `[lo, hi] ⊂ [0, 2π]` where the ring `(ct, st)` lies strictly above the horizon:
    /// `ω_z = ct r_z + st s_z cos φ' > 0`. At most two intervals.
    pub fn upper_phi(&self, ct: f64, st: f64, lo: f64, hi: f64) -> Vec<(f64, f64)> {
        let a = ct * self.r.z;
        let b = st * self.s.z;
        let mut out = Vec::with_capacity(2);
        if b <= 1e-300 {
            if a > 0.0 {
                out.push((lo, hi));
            }
            return out;
        }
        let k = -a / b;
        if k >= 1.0 {
            return out;
        }
        if k <= -1.0 {
            out.push((lo, hi));
            return out;
        }
        let half = k.acos();
        for (x, y) in [(0.0, half), (TAU - half, TAU)] {
            let (p, q) = (lo.max(x), hi.min(y));
            if q > p {
                out.push((p, q));
            }
        }
        out
    }
}

/// `∫_{H+} g(ω) dω` over the upper hemisphere, in the frame of `pole`, with the pole-angle integral split
/// at `theta_breaks` (increasing, from 0; the last one is clipped to the largest pole angle that still
/// reaches the hemisphere). `tol.abs` is the absolute tolerance of the total.
pub fn integrate_hemisphere(
    q: &Adaptive,
    pole: DVec3,
    theta_breaks: &[f64],
    tol: Tol,
    g: &mut impl FnMut(DVec3) -> f64,
) -> Integral {
    let fr = PoleFrame::new(pole);
    // Largest angle between the pole and an upper direction: π/2 + θ_pole.
    let theta_max = fr.theta_max();
    let mut breaks: Vec<f64> = theta_breaks
        .iter()
        .copied()
        .filter(|&t| t > 0.0 && t < theta_max)
        .collect();
    breaks.extend(fr.horizon_breaks());
    breaks.push(0.0);
    breaks.push(theta_max);
    breaks.sort_by(|a, b| a.partial_cmp(b).unwrap());
    breaks.dedup();
    let inner_tol = Tol {
        abs: tol.abs / (4.0 * PI),
        ..tol
    };
    let mut evals = 0u64;
    let mut outer = |theta: f64| -> (f64, f64) {
        let (st, ct) = theta.sin_cos();
        let mut acc = Integral::default();
        for (lo, hi) in fr.upper_phi(ct, st, 0.0, TAU) {
            acc = acc + q.integrate(lo, hi, inner_tol, &mut |phi| (g(fr.dir(ct, st, phi)), 0.0));
        }
        evals += acc.evals;
        (st * acc.value, st * acc.err)
    };
    let mut r = q.integrate_breaks(&breaks, tol, &mut outer);
    r.evals = evals;
    r
}

/// Geometric pole-angle breakpoints for a lobe of angular width `w`: `w/8, w/4, …` doubling up to π.
pub fn lobe_breaks(w: f64) -> Vec<f64> {
    let mut v = Vec::new();
    let mut t = (w / 8.0).max(1e-7);
    while t < PI {
        v.push(t);
        t *= 2.0;
    }
    v
}
