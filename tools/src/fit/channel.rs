//! The per-channel least-squares problem of [`super::fit`] at a fixed
//! roughness, and the small Levenberg–Marquardt solver that minimises it.

use super::{FresnelModel, Prepared};
use radiometry_brdfs::{Conductor, Fresnel};
use std::f64::consts::FRAC_1_PI;

/// Largest number of parameters of one channel (`ln η, k, kd`).
pub(super) const MAX_PARAMS: usize = 3;

/// Intervals of the conductor Fresnel table in `cos θd ∈ [0, 1]`.
pub(super) const TABLE_INTERVALS: usize = 1024;

/// Largest normal-incidence reflectance of the conductor parametrisation:
/// keeps `η ∈ [2.5·10⁻³, 399]` and `k ≤ 20`, inside the plugin's
/// `[10⁻³, 10³]` domain.
const R_MAX: f64 = 0.99;

/// Finite-difference step of the conductor parameters `(r, t)`: large
/// enough that the `f32` rounding of the plugin's Fresnel (≈ 6·10⁻⁸) stays a
/// `10⁻⁴` relative perturbation of the derivative.
const FD_STEP: f64 = 1e-3;

/// The conductor index `(η, k)` of the parameters `(r, t) ∈ [0, R_MAX] × [0, 1]`:
/// `r` is the normal-incidence reflectance `F0 = ((η−1)² + k²)/((η+1)² + k²)`
/// (Born & Wolf § 14.2) and `t` places `η` between the two indices with
/// `k = 0` and that `F0`, `η_lo = (1 − √r)/(1 + √r)` and `η_hi = 1/η_lo`, on a
/// log scale: `η = η_lo^(1−t) η_hi^t`; then `k² = (r(η+1)² − (η−1)²)/(1 − r)`
/// (solving the `F0` equation for `k`). Every `(η, k ≥ 0)` with reflectance
/// `r` has exactly one `t`, so `(r, t)` covers all conductors with
/// `F0 ≤ R_MAX`, and it separates the well-determined `F0` from the
/// weakly-determined shape of the curve — far better conditioned for the
/// solver than `(η, k)` (the idea of Gulbrandsen 2014, "Artist friendly
/// metallic Fresnel", JCGT 3(4), with a mapping that spans every `η`).
pub(super) fn conductor_eta_k(r: f64, t: f64) -> (f64, f64) {
    let r = r.clamp(0.0, R_MAX);
    let t = t.clamp(0.0, 1.0);
    let sr = r.sqrt();
    let ln_lo = ((1.0 - sr) / (1.0 + sr)).ln();
    let eta = (ln_lo * (1.0 - 2.0 * t)).exp();
    let k2 = (r * (eta + 1.0).powi(2) - (eta - 1.0).powi(2)) / (1.0 - r);
    (eta, k2.max(0.0).sqrt())
}

/// One channel's model at a fixed roughness: with `S_j = D G2/(4 μi μo)` of
/// sample `j` (the plugin with `F = 1`),
/// `f_j(p) = kd/π + S_j F(cos θd_j; q)` and the residual
/// `r_j = √w_j (y_j − ln(1 + μi_j f_j))`, `y_j = ln(1 + μi_j f_table)`.
///
/// Parameters `p = (q, kd)`: Schlick `q = (F0)`, `F = F0 + (1 − F0)(1 − cos θd)⁵`
/// (Schlick 1994, eq. 15); conductor `q = (r, t)` of [`conductor_eta_k`], `F` the plugin's exact
/// conductor Fresnel, read from a [`TABLE_INTERVALS`]-interval table in
/// `cos θd` by linear interpolation (F is smooth in `cos θd`; the table error
/// is below 10⁻⁵, far under any fit residual of measured data).
pub(super) struct ChannelProblem<'a> {
    pub(super) data: &'a Prepared,
    pub(super) channel: usize,
    /// `S_j` at the current roughness.
    pub(super) s: &'a [f64],
    pub(super) fresnel: FresnelModel,
    pub(super) diffuse: bool,
}

/// `Σ r²`, `JᵀJ` and `Jᵀr` at one parameter point.
pub(super) struct Normal {
    pub(super) cost: f64,
    pub(super) jtj: [[f64; MAX_PARAMS]; MAX_PARAMS],
    pub(super) jtr: [f64; MAX_PARAMS],
}

/// The conductor Fresnel `F(c_i)` of the plugin at `c_i = i/TABLE_INTERVALS`.
/// `η` and `k` are clamped into the plugin's domain first (a non-finite
/// value, which [`conductor_eta_k`] never produces, becomes `η = 1`, `k = 0`).
pub(super) fn conductor_table(eta: f64, k: f64) -> Vec<f64> {
    let eta = if eta.is_finite() {
        eta.clamp(1e-3, 1e3)
    } else {
        1.0
    };
    let k = if k.is_finite() { k.clamp(0.0, 1e3) } else { 0.0 };
    let Ok(f) = Conductor::new(eta as f32, k as f32) else {
        unreachable!("η ∈ [1e-3, 1e3] and k ∈ [0, 1e3] are the plugin's domain")
    };
    (0..=TABLE_INTERVALS)
        .map(|i| f.eval(i as f32 / TABLE_INTERVALS as f32) as f64)
        .collect()
}

impl ChannelProblem<'_> {
    /// Number of parameters.
    pub(super) fn dim(&self) -> usize {
        self.fresnel_dim() + usize::from(self.diffuse)
    }

    fn fresnel_dim(&self) -> usize {
        match self.fresnel {
            FresnelModel::Schlick => 1,
            FresnelModel::Conductor => 2,
        }
    }

    /// The starting point: Schlick `F0 = 0.5`; conductor `r = 0.5, t = 0.3`
    /// (`η = 0.41, k = 1.8`); `kd = 0.05`.
    pub(super) fn start(&self) -> Vec<f64> {
        let mut p = match self.fresnel {
            FresnelModel::Schlick => vec![0.5],
            FresnelModel::Conductor => vec![0.5, 0.3],
        };
        if self.diffuse {
            p.push(0.05);
        }
        p
    }

    /// The parameter box: `F0, t, kd ∈ [0, 1]`, `r ∈ [0, R_MAX]`.
    pub(super) fn bounds(&self) -> [(f64, f64); MAX_PARAMS] {
        let mut b = [(0.0, 1.0); MAX_PARAMS];
        if self.fresnel == FresnelModel::Conductor {
            b[0] = (0.0, R_MAX);
        }
        b
    }

    /// Clamps `p` into the box ([`bounds`](Self::bounds)).
    pub(super) fn project(&self, p: &mut [f64]) {
        for (x, (lo, hi)) in p.iter_mut().zip(self.bounds()) {
            *x = x.clamp(lo, hi);
        }
    }

    /// `Σ r_j²`, `JᵀJ`, `Jᵀr` at `p` (analytic derivatives in `F0` and `kd`,
    /// one-sided differences of the table in `r` and `t`, towards the inside
    /// of the box).
    pub(super) fn normal(&self, p: &[f64]) -> Normal {
        let nq = self.fresnel_dim();
        let kd = if self.diffuse { p[nq] } else { 0.0 };
        let mut steps = [FD_STEP; 2];
        let tables: Vec<Vec<f64>> = match self.fresnel {
            FresnelModel::Schlick => Vec::new(),
            FresnelModel::Conductor => {
                let b = self.bounds();
                steps = [0, 1].map(|i| {
                    if p[i] + FD_STEP <= b[i].1 {
                        FD_STEP
                    } else {
                        -FD_STEP
                    }
                });
                let table = |r: f64, t: f64| {
                    let (eta, k) = conductor_eta_k(r, t);
                    conductor_table(eta, k)
                };
                vec![
                    table(p[0], p[1]),
                    table(p[0] + steps[0], p[1]),
                    table(p[0], p[1] + steps[1]),
                ]
            }
        };
        let d = self.data;
        let (y, w) = (&d.y[self.channel], &d.w[self.channel]);
        let mut out = Normal {
            cost: 0.0,
            jtj: [[0.0; MAX_PARAMS]; MAX_PARAMS],
            jtr: [0.0; MAX_PARAMS],
        };
        let m = self.dim();
        for j in 0..d.len() {
            if w[j] == 0.0 {
                continue;
            }
            let s = self.s[j];
            let mut dfq = [0.0; MAX_PARAMS];
            let fr = match self.fresnel {
                FresnelModel::Schlick => {
                    dfq[0] = 1.0 - d.s5[j];
                    p[0] + (1.0 - p[0]) * d.s5[j]
                }
                FresnelModel::Conductor => {
                    let (i, t) = d.cell[j];
                    let lerp = |tab: &[f64]| tab[i] + (tab[i + 1] - tab[i]) * t;
                    let f = lerp(&tables[0]);
                    dfq[0] = (lerp(&tables[1]) - f) / steps[0];
                    dfq[1] = (lerp(&tables[2]) - f) / steps[1];
                    f
                }
            };
            let f = kd * FRAC_1_PI + s * fr;
            let mu = d.mu_i[j];
            let sw = w[j].sqrt();
            let r = sw * (y[j] - (mu * f).ln_1p());
            out.cost += r * r;
            // ∂r/∂f = −√w μi/(1 + μi f)
            let drdf = -sw * mu / (1.0 + mu * f);
            let mut jrow = [0.0; MAX_PARAMS];
            for (a, dq) in jrow.iter_mut().zip(&dfq).take(nq) {
                *a = drdf * s * dq;
            }
            if self.diffuse {
                jrow[nq] = drdf * FRAC_1_PI;
            }
            for a in 0..m {
                out.jtr[a] += jrow[a] * r;
                for b in 0..=a {
                    out.jtj[a][b] += jrow[a] * jrow[b];
                }
            }
        }
        for a in 0..m {
            for b in 0..a {
                out.jtj[b][a] = out.jtj[a][b];
            }
        }
        out
    }
}

/// Solves the `m × m` system `a x = b` by Gaussian elimination with partial
/// pivoting; `None` when a pivot vanishes.
fn solve(
    mut a: [[f64; MAX_PARAMS]; MAX_PARAMS],
    mut b: [f64; MAX_PARAMS],
    m: usize,
) -> Option<[f64; MAX_PARAMS]> {
    for col in 0..m {
        let piv = (col..m).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
        if a[piv][col].abs() <= 0.0 || a[piv][col].is_nan() {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        let pivot_row = a[col];
        for row in col + 1..m {
            let f = a[row][col] / pivot_row[col];
            for (x, p) in a[row].iter_mut().zip(&pivot_row).take(m).skip(col) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; MAX_PARAMS];
    for row in (0..m).rev() {
        let mut s = b[row];
        for c in row + 1..m {
            s -= a[row][c] * x[c];
        }
        x[row] = s / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Relative parameter change below which the solver stops: the parameters
/// are `O(1)`, and `10⁻⁹` is below the `f32` resolution of the model.
const STEP_TOL: f64 = 1e-9;

/// Projected Levenberg–Marquardt (Levenberg 1944; Marquardt 1963, with
/// Marquardt's scaling `λ diag(JᵀJ)`): the step solves
/// `(JᵀJ + λ diag(JᵀJ)) δ = −Jᵀr` over the free parameters — a parameter on
/// a bound of the box whose descent direction `−(Jᵀr)_i` points out of the
/// box is held fixed (the active set of projected Newton methods, Bertsekas
/// 1982) — and the trial point is clamped into the box. A trial is accepted
/// when the cost drops (then `λ ← λ/3`), rejected otherwise (`λ ← 4λ`).
/// Stops when an accepted step lowers the cost by less than `GAIN_TOL` of
/// itself, when the step moves no parameter by more than
/// `STEP_TOL (1 + |p|)`, when `λ > 10¹⁰`, or after [`MAX_ITERATIONS`].
/// `λ` starts at `lambda` (clamped to `[10⁻⁶, 10³]`; a warm start passes the
/// final `λ` of a neighbouring problem, which saves the rejected trials that
/// would raise it again). Returns the parameters, their cost `Σ r²`, the
/// iterations used and the final `λ`.
pub(super) fn minimize(prob: &ChannelProblem<'_>, start: &[f64], lambda: f64) -> (Vec<f64>, f64, usize, f64) {
    let m = prob.dim();
    let bounds = prob.bounds();
    let mut p = start.to_vec();
    prob.project(&mut p);
    let mut cur = prob.normal(&p);
    let mut lambda = if lambda.is_finite() {
        lambda.clamp(1e-6, 1e3)
    } else {
        LAMBDA_START
    };
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let mut a = cur.jtj;
        let mut rhs = cur.jtr.map(|v| -v);
        let scale = (0..m).map(|i| a[i][i]).fold(0.0f64, f64::max).max(1e-300);
        for i in 0..m {
            let (lo, hi) = bounds[i];
            let fixed = (p[i] <= lo && rhs[i] < 0.0) || (p[i] >= hi && rhs[i] > 0.0);
            if fixed {
                a[i] = [0.0; MAX_PARAMS];
                for row in a.iter_mut() {
                    row[i] = 0.0;
                }
                a[i][i] = 1.0;
                rhs[i] = 0.0;
            } else {
                a[i][i] += lambda * a[i][i] + 1e-12 * scale;
            }
        }
        let Some(delta) = solve(a, rhs, m) else {
            lambda *= 4.0;
            if lambda > 1e10 {
                break;
            }
            continue;
        };
        let mut trial: Vec<f64> = p.iter().zip(&delta).map(|(x, d)| x + d).collect();
        prob.project(&mut trial);
        if trial
            .iter()
            .zip(&p)
            .all(|(t, x)| (t - x).abs() <= STEP_TOL * (1.0 + x.abs()))
        {
            break;
        }
        let next = prob.normal(&trial);
        if next.cost < cur.cost {
            let gain = cur.cost - next.cost;
            p = trial;
            let done = gain <= GAIN_TOL * cur.cost;
            cur = next;
            lambda = (lambda / 3.0).max(1e-12);
            if done {
                break;
            }
        } else if next.cost - cur.cost <= GAIN_TOL * cur.cost {
            // At the noise floor of the f32 model: no trial can do better.
            break;
        } else {
            lambda *= 4.0;
            if lambda > 1e10 {
                break;
            }
        }
    }
    (p, cur.cost, iterations, lambda)
}

/// Marquardt's `λ` of a cold start.
pub(super) const LAMBDA_START: f64 = 1e-3;

/// Relative cost decrease of an accepted step below which [`minimize`]
/// stops (the outer roughness search compares costs that differ by far more).
const GAIN_TOL: f64 = 1e-8;

/// Iteration cap of [`minimize`] (warm-started problems take a handful).
pub(super) const MAX_ITERATIONS: usize = 100;

#[cfg(test)]
mod tests {
    use super::*;

    /// The solver against a system with a known solution.
    #[test]
    fn solve_3x3() {
        let a = [[4.0, 1.0, 2.0], [1.0, 5.0, 3.0], [2.0, 3.0, 6.0]];
        let x = [1.0, -2.0, 0.5];
        let b = [0, 1, 2].map(|i| (0..3).map(|j| a[i][j] * x[j]).sum::<f64>());
        let got = solve(a, b, 3).unwrap();
        for i in 0..3 {
            assert!((got[i] - x[i]).abs() < 1e-12, "{got:?}");
        }
        assert!(solve([[0.0; 3]; 3], [1.0; 3], 2).is_none());
    }

    /// `(r, t)` maps to an index with reflectance `r` at normal incidence,
    /// `t = 0` and `1` to the two `k = 0` indices, and a known conductor
    /// (gold at 632.8 nm, `η = 0.18104`, `k = 3.068099`) is reached.
    #[test]
    fn conductor_parametrisation() {
        let f0 = |e: f64, k: f64| ((e - 1.0).powi(2) + k * k) / ((e + 1.0).powi(2) + k * k);
        for r in [0.0, 0.04, 0.5, 0.9, R_MAX] {
            for t in [0.0, 0.2, 0.5, 0.8, 1.0] {
                let (e, k) = conductor_eta_k(r, t);
                assert!((f0(e, k) - r).abs() < 1e-12, "r={r} t={t}: η={e} k={k}");
                assert!((1e-3..=1e3).contains(&e) && (0.0..=1e3).contains(&k), "{e} {k}");
            }
            let (lo, hi) = (conductor_eta_k(r, 0.0), conductor_eta_k(r, 1.0));
            // k = √(difference of two O(max(1, η)²) terms): rounding leaves
            // k ≲ 10⁻⁷ max(1, η) instead of 0.
            assert!(lo.1 < 1e-6 && hi.1 < 1e-6 * hi.0, "{lo:?} {hi:?}");
            assert!((lo.0 * hi.0 - 1.0).abs() < 1e-12, "{lo:?} {hi:?}");
        }
        let (eta, k) = (0.18104f64, 3.068099f64);
        let r = f0(eta, k);
        let sr = r.sqrt();
        let ln_lo = ((1.0 - sr) / (1.0 + sr)).ln();
        let t = 0.5 * (1.0 - eta.ln() / ln_lo);
        let (e2, k2) = conductor_eta_k(r, t);
        assert!((e2 - eta).abs() < 1e-9 && (k2 - k).abs() < 1e-9, "{e2} {k2}");
    }

    /// The table reproduces the plugin's conductor Fresnel between nodes to
    /// 10⁻⁵ (gold-like and aluminium-like indices).
    #[test]
    fn conductor_table_interpolation_error() {
        for (eta, k) in [(0.18, 3.07), (1.2, 7.0), (0.05, 0.5), (3.0, 0.0)] {
            let t = conductor_table(eta, k);
            let f = Conductor::new(eta as f32, k as f32).unwrap();
            let mut worst = 0.0f64;
            for i in 0..10_000 {
                let c = (i as f64 + 0.37) / 10_000.0;
                let pos = c * TABLE_INTERVALS as f64;
                let n = (pos as usize).min(TABLE_INTERVALS - 1);
                let fr = pos - n as f64;
                let lerp = t[n] + (t[n + 1] - t[n]) * fr;
                worst = worst.max((lerp - f.eval(c as f32) as f64).abs());
            }
            assert!(worst < 1e-5, "η={eta} k={k}: {worst:e}");
        }
    }
}
