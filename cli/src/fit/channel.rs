//! The per-channel least-squares problem of [`super::fit`] at a fixed
//! roughness, and the small Levenberg–Marquardt solver that minimises it.

use super::{FresnelModel, Prepared};
use radiometry_brdfs::{Conductor, Fresnel};
use std::f64::consts::FRAC_1_PI;

/// Largest number of parameters of one channel (`ln η, k, kd`).
pub(super) const MAX_PARAMS: usize = 3;

/// Intervals of the conductor Fresnel table in `cos θd ∈ [0, 1]`.
pub(super) const TABLE_INTERVALS: usize = 1024;

/// Bounds of the conductor parameters: `η ∈ [ETA_MIN, ETA_MAX]`,
/// `k ∈ [0, K_MAX]` (inside the plugin's `[1e-3, 1e3]` domain).
const ETA_MIN: f64 = 1e-2;
const ETA_MAX: f64 = 50.0;
const K_MAX: f64 = 50.0;

/// Finite-difference step of the conductor parameters `(ln η, k)`: large
/// enough that the `f32` rounding of the plugin's Fresnel (≈ 6·10⁻⁸) stays a
/// `10⁻⁴` relative perturbation of the derivative.
const FD_STEP: f64 = 1e-3;

/// One channel's model at a fixed roughness: with `S_j = D G2/(4 μi μo)` of
/// sample `j` (the plugin with `F = 1`),
/// `f_j(p) = kd/π + S_j F(cos θd_j; q)` and the residual
/// `r_j = √w_j (y_j − ln(1 + μi_j f_j))`, `y_j = ln(1 + μi_j f_table)`.
///
/// Parameters `p = (q, kd)`: Schlick `q = (F0)`, `F = F0 + (1 − F0)(1 − cos θd)⁵`
/// (Schlick 1994, eq. 15); conductor `q = (ln η, k)`, `F` the plugin's exact
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
/// `η` and `k` are clamped into the parameter box first (a non-finite value,
/// which the solver never produces, becomes the box's lower end).
pub(super) fn conductor_table(eta: f64, k: f64) -> Vec<f64> {
    let eta = if eta.is_finite() {
        eta.clamp(ETA_MIN, ETA_MAX)
    } else {
        ETA_MIN
    };
    let k = if k.is_finite() { k.clamp(0.0, K_MAX) } else { 0.0 };
    let Ok(f) = Conductor::new(eta as f32, k as f32) else {
        unreachable!("η ∈ [1e-2, 50] and k ∈ [0, 50] are inside the plugin's domain")
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

    /// The starting point: Schlick `F0 = 0.5`; conductor `η = 1, k = 1`
    /// (`F0 = 0.2`); `kd = 0.05`.
    pub(super) fn start(&self) -> Vec<f64> {
        let mut p = match self.fresnel {
            FresnelModel::Schlick => vec![0.5],
            FresnelModel::Conductor => vec![0.0, 1.0],
        };
        if self.diffuse {
            p.push(0.05);
        }
        p
    }

    /// Clamps `p` into the box: `F0, kd ∈ [0, 1]`, `η ∈ [10⁻², 50]`, `k ∈ [0, 50]`.
    pub(super) fn project(&self, p: &mut [f64]) {
        match self.fresnel {
            FresnelModel::Schlick => p[0] = p[0].clamp(0.0, 1.0),
            FresnelModel::Conductor => {
                p[0] = p[0].clamp(ETA_MIN.ln(), ETA_MAX.ln());
                p[1] = p[1].clamp(0.0, K_MAX);
            }
        }
        if self.diffuse {
            let i = self.fresnel_dim();
            p[i] = p[i].clamp(0.0, 1.0);
        }
    }

    /// `Σ r_j²`, `JᵀJ`, `Jᵀr` at `p` (analytic derivatives in `F0` and `kd`,
    /// forward differences of the table in `ln η` and `k`).
    pub(super) fn normal(&self, p: &[f64]) -> Normal {
        let nq = self.fresnel_dim();
        let kd = if self.diffuse { p[nq] } else { 0.0 };
        let tables: Vec<Vec<f64>> = match self.fresnel {
            FresnelModel::Schlick => Vec::new(),
            FresnelModel::Conductor => {
                let (eta, k) = (p[0].exp(), p[1]);
                vec![
                    conductor_table(eta, k),
                    conductor_table((p[0] + FD_STEP).exp(), k),
                    conductor_table(eta, k + FD_STEP),
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
                    dfq[0] = (lerp(&tables[1]) - f) / FD_STEP;
                    dfq[1] = (lerp(&tables[2]) - f) / FD_STEP;
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
/// are `O(1)`, and `10⁻¹⁰` is far below the `f32` resolution of the model.
const STEP_TOL: f64 = 1e-10;

/// Projected Levenberg–Marquardt (Levenberg 1944; Marquardt 1963, with
/// Marquardt's scaling `λ diag(JᵀJ)`): the step solves
/// `(JᵀJ + λ diag(JᵀJ)) δ = −Jᵀr`, the trial point is clamped into the
/// parameter box, accepted when the cost drops (then `λ ← λ/3`), rejected
/// otherwise (`λ ← 4λ`). Stops when an accepted step lowers the cost by less
/// than `10⁻¹²` of itself, when the (projected) step moves no parameter by
/// more than `STEP_TOL (1 + |p|)`, when `λ > 10¹⁰`, or after 200 iterations.
/// Returns the parameters and their cost `Σ r²`.
pub(super) fn minimize(prob: &ChannelProblem<'_>, start: &[f64]) -> (Vec<f64>, f64) {
    let m = prob.dim();
    let mut p = start.to_vec();
    prob.project(&mut p);
    let mut cur = prob.normal(&p);
    let mut lambda = 1e-3;
    for _ in 0..200 {
        let mut a = cur.jtj;
        let scale = (0..m).map(|i| a[i][i]).fold(0.0f64, f64::max).max(1e-300);
        for (i, row) in a.iter_mut().enumerate().take(m) {
            row[i] += lambda * row[i] + 1e-12 * scale;
        }
        let rhs = cur.jtr.map(|v| -v);
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
            let done = gain <= 1e-12 * cur.cost;
            cur = next;
            lambda = (lambda / 3.0).max(1e-12);
            if done {
                break;
            }
        } else {
            lambda *= 4.0;
            if lambda > 1e10 {
                break;
            }
        }
    }
    (p, cur.cost)
}

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
