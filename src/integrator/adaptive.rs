//! Globally adaptive cubature on the unit square with the embedded
//! Genz–Malik degree-7/degree-5 rule ([`Adaptive`]).

use super::acc::{self, F32_FLOOR, WideSum, nonzero};
use super::chunk::{self, BatchFn, head, head_mut};
use super::confirm;
use super::tolerance::{by_doubling, check_tolerance_args};
use super::{
    Estimate, Integrand, IntegrateError, Integrator, Status, StopReason, ToleranceOutcome, Unresolved,
    WideOf, probe,
};
use crate::spectrum::WideSpectrum;

/// Most live regions kept on the stack. When the table is full, the
/// worst region is no longer split but re-evaluated with the composite
/// rule on an `n × n` grid of cells, `n` doubling each time (no region is
/// ever discarded or frozen).
pub const MAX_REGIONS: usize = 512;

/// The region table of a run whose budget cannot fill it: every split
/// spends at least `2 × 17` evaluations and adds one region to the 4 it
/// starts with, so a budget of at most [`SMALL_REGIONS_BUDGET`] keeps fewer
/// than `SMALL_REGIONS` live and the run is the same, bit for bit, as with
/// [`MAX_REGIONS`]: the stack follows the budget (≈ 4 KiB of regions for
/// `f32` instead of ≈ 37 KiB; firmware-sized at a budget of 1,024).
pub const SMALL_REGIONS: usize = 48;

/// Largest budget run with the [`SMALL_REGIONS`] table.
pub const SMALL_REGIONS_BUDGET: u32 = (SMALL_REGIONS as u32 - 5) * 2 * GM_POINTS as u32;

/// The region table of the smallest budgets (up to [`TINY_REGIONS_BUDGET`],
/// 1,053: the firmware configuration of a budget of 1,024), ≈ 2.6 KiB of
/// regions for `f32`. The run starts with 4 regions after `4 × 17`
/// evaluations and splits only while `2 × 17` more fit the budget, so `k`
/// splits need a budget of at least `34 (k + 2)`: below `34 (N − 2)` the
/// table of `N` regions never fills, and the run is the same, bit for bit,
/// as with [`MAX_REGIONS`].
pub const TINY_REGIONS: usize = 33;

/// Largest budget run with the [`TINY_REGIONS`] table: `34 (N − 2) − 1`.
pub const TINY_REGIONS_BUDGET: u32 = (TINY_REGIONS as u32 - 2) * 2 * GM_POINTS as u32 - 1;

/// Most unit squares of one run: the components of a mixture sampling map
/// that the warped rule integrates each on its own square (see
/// [`Integrand::sampling_components`]); a map with more components with a
/// positive weight is integrated whole.
pub const MAX_SQUARES: usize = chunk::MAX_COMPONENTS;

/// Most evaluations an [`Adaptive`] run spends (`2²⁰`).
pub const MAX_ADAPTIVE_EVALUATIONS: u32 = 1 << 20;

/// Every this many splits, the largest live region is split instead of
/// the one with the largest error estimate.
const FORCED_EVERY: u64 = 4;

/// Azimuth offset (in turns) of the plain hemisphere parameterisation:
/// `φ = 2π (b + PHI_OFFSET mod 1)`, the golden-ratio conjugate `(√5 − 1)/2`.
const PHI_OFFSET: f64 = 0.618_033_988_749_894_9;

/// Position of the first cut of `[0,1]` on both axes (`(√5 − 1)/2`).
const FIRST_CUT: f64 = 0.618_033_988_749_894_9;

/// [`FIRST_CUT`] of the shifted rule ([`Adaptive::shifted`]): `√2 − 1`.
const SHIFTED_CUT: f64 = 0.414_213_562_373_095_03;

/// The bend `κ` of the shifted rule's pieces (see `PlainMap`).
const SHIFTED_BEND: f64 = 0.5;

/// [`PHI_OFFSET`] of the shifted rule: `(3 − √5)/2`.
const SHIFTED_PHI_OFFSET: f64 = 0.381_966_011_250_105_1;

/// Staged mode: the first checkpoint is taken when `Σ errors ≤ STAGE_K ·
/// tol` — the regions' `|I₇ − I₅|` estimates the error of the embedded
/// degree-5 rule, which once the rule converges is many times the
/// degree-7 value's — and the confirming refinement must move the value by
/// `≤ tol` (see [`Adaptive::run`]).
const STAGE_K: f64 = 8.0;

/// An estimate and, in the staged mode, the difference to the checkpoint
/// that confirmed it.
type Staged<W> = (Estimate<W>, Option<W>);

/// Most draws of the mean check that confirms a staged candidate.
const CONFIRM_MAX_DRAWS: u32 = 65_536;

/// Points of the 2-D Genz–Malik rule.
const GM_POINTS: usize = 17;

// Genz & Malik (1980), "An adaptive algorithm for numerical integration over
// an N-dimensional rectangular region", J. Comput. Appl. Math. 6(4),
// Eqs. (3.2)–(3.4), with n = 2 dimensions. Generators on [-1,1]^2:
// λ₂² = 9/70, λ₃² = λ₄² = 9/10, λ₅² = 9/19.
// Degree-7 weights (normalised so that Σ = 1 over the 17 points):
//   w₁ = (12824 − 9120n + 400n²)/19683, w₂ = 980/6561,
//   w₃ = (1820 − 400n)/19683, w₄ = 200/19683, w₅ = 6859/19683/2ⁿ.
// Embedded degree-5 weights:
//   w₁' = (729 − 950n + 50n²)/729, w₂' = 245/486,
//   w₃' = (265 − 100n)/1458, w₄' = 25/729.
const N: f64 = 2.0;
const W7: [f64; 5] = [
    (12824.0 - 9120.0 * N + 400.0 * N * N) / 19683.0,
    980.0 / 6561.0,
    (1820.0 - 400.0 * N) / 19683.0,
    200.0 / 19683.0,
    6859.0 / 19683.0 / 4.0,
];
const W5: [f64; 4] = [
    (729.0 - 950.0 * N + 50.0 * N * N) / 729.0,
    245.0 / 486.0,
    (265.0 - 100.0 * N) / 1458.0,
    25.0 / 729.0,
];

/// The generators `(t₀, t₁, class)` of the 17 points on `[-1,1]²`.
fn gm_points() -> [(f64, f64, usize); GM_POINTS] {
    let l2 = libm::sqrt(9.0 / 70.0);
    let l3 = libm::sqrt(9.0 / 10.0);
    let l4 = l3;
    let l5 = libm::sqrt(9.0 / 19.0);
    [
        (0.0, 0.0, 0),
        (l2, 0.0, 1),
        (-l2, 0.0, 1),
        (0.0, l2, 1),
        (0.0, -l2, 1),
        (l3, 0.0, 2),
        (-l3, 0.0, 2),
        (0.0, l3, 2),
        (0.0, -l3, 2),
        (l4, l4, 3),
        (l4, -l4, 3),
        (-l4, l4, 3),
        (-l4, -l4, 3),
        (l5, l5, 4),
        (l5, -l5, 4),
        (-l5, l5, 4),
        (-l5, -l5, 4),
    ]
}

#[derive(Clone, Copy, Debug)]
struct Region<W> {
    c: [f64; 2],
    h: [f64; 2],
    value: W,
    error: W,
    /// Channel-wise Σ|w f| (for the f32 rounding floor).
    abs: W,
    /// Scalar priority: largest channel of `error + 2⁻²³ abs`.
    key: f64,
    /// Largest `max_channel |f|` at the region's nodes (for the peak probe).
    peak: f64,
    /// Axis with the larger fourth difference (split here).
    axis: u8,
    /// The region's rule is the composite rule on an `n × n` grid of
    /// equal cells (`n > 1` only once the table is full).
    n: u32,
}

impl<W> Region<W> {
    /// Area of one cell of the region's (composite) rule.
    fn cell_area(&self) -> f64 {
        let n = self.n as f64;
        self.h[0] * self.h[1] / (n * n)
    }
}

/// Most regions whose points go to the integrand in one batch
/// (`2 × 17 = 34` points: two regions of the initial 2 × 2 grid, the two
/// halves of a split, or two cells of a composite rule). Each region's
/// rule reads only its own points: the results do not depend on it.
const BATCH_REGIONS: usize = 2;

/// Applies the rule to the rectangles `c[r] ± h[r]`, `r < min(c.len(),
/// h.len())`, evaluating the points of [`BATCH_REGIONS`] of them in one
/// batch, and passes the regions to `each` in order.
fn rules<W: WideSpectrum>(
    c: &[[f64; 2]],
    h: &[[f64; 2]],
    f: &mut impl BatchFn<W>,
    mut each: impl FnMut(Region<W>),
) -> Result<(), IntegrateError> {
    let mut pts = [[0.0f64; 2]; BATCH_REGIONS * GM_POINTS];
    let mut vals = [W::splat(0.0); BATCH_REGIONS * GM_POINTS];
    for (c, h) in c.chunks(BATCH_REGIONS).zip(h.chunks(BATCH_REGIONS)) {
        let m = c.len().min(h.len());
        for ((&c, &h), p) in c.iter().zip(h).zip(pts.chunks_exact_mut(GM_POINTS)) {
            rule_points(c, h, p);
        }
        f(head(&pts, m * GM_POINTS), head_mut(&mut vals, m * GM_POINTS))?;
        for ((&c, &h), v) in c.iter().zip(h).zip(vals.chunks_exact(GM_POINTS)) {
            each(rule(c, h, v));
        }
    }
    Ok(())
}

/// The Genz–Malik rule compounded over an `n × n` grid of equal cells of
/// the rectangle `c ± h` (value, error and Σ|w f| are sums over the cells
/// in row-major order; the points of [`BATCH_REGIONS`] cells are evaluated
/// at a time).
fn composite<W: WideSpectrum>(
    c: [f64; 2],
    h: [f64; 2],
    n: u32,
    axis: u8,
    f: &mut impl BatchFn<W>,
) -> Result<Region<W>, IntegrateError> {
    let hc = [h[0] / n as f64, h[1] / n as f64];
    let (mut v, mut e, mut a) = (WideSum::<W>::new(), WideSum::<W>::new(), WideSum::<W>::new());
    let mut peak = 0.0f64;
    let cells = n as u64 * n as u64;
    let mut centres = [[0.0f64; 2]; BATCH_REGIONS];
    let mut start = 0u64;
    while start < cells {
        let m = (cells - start).min(BATCH_REGIONS as u64) as usize;
        for (k, cc) in centres.iter_mut().take(m).enumerate() {
            let (i, j) = ((start + k as u64) / n as u64, (start + k as u64) % n as u64);
            *cc = [
                c[0] - h[0] + (2 * i + 1) as f64 * hc[0],
                c[1] - h[1] + (2 * j + 1) as f64 * hc[1],
            ];
        }
        rules(head(&centres, m), &[hc; BATCH_REGIONS], f, |r| {
            v.add(r.value);
            e.add(r.error);
            a.add(r.abs);
            peak = peak.max(r.peak);
        })?;
        start += m as u64;
    }
    let (value, error, abs) = (v.value(), e.value(), a.value());
    Ok(Region {
        c,
        h,
        value,
        error,
        abs,
        key: acc::max_abs(acc::add(error, abs.map(|x| x * F32_FLOOR))),
        peak,
        axis,
        n,
    })
}

/// The 17 points of the rule on the rectangle `c ± h`, into `out[..17]`.
fn rule_points(c: [f64; 2], h: [f64; 2], out: &mut [[f64; 2]]) {
    for (o, &(t0, t1, _)) in out.iter_mut().zip(gm_points().iter()) {
        *o = [c[0] + h[0] * t0, c[1] + h[1] * t1];
    }
}

/// The rule on the rectangle `c ± h` from the values `vals[..17]` at its
/// [`rule_points`].
fn rule<W: WideSpectrum>(c: [f64; 2], h: [f64; 2], vals: &[W]) -> Region<W> {
    // A fixed-size copy: constant indices below, no panic path.
    let vals: [W; GM_POINTS] = core::array::from_fn(|k| vals.get(k).copied().unwrap_or(W::splat(0.0)));
    let pts = gm_points();
    let vol = 4.0 * h[0] * h[1];
    let mut i7 = WideSum::<W>::new();
    let mut i5 = WideSum::<W>::new();
    let mut ab = WideSum::<W>::new();
    let mut peak = 0.0f64;
    for (&(_, _, cls), &v) in pts.iter().zip(&vals) {
        peak = peak.max(acc::max_abs(v));
        let w7 = W7.get(cls).copied().unwrap_or(0.0);
        i7.add(v.map(|x| x * w7 * vol));
        ab.add(v.map(|x| (x * w7 * vol).abs()));
        if let Some(&w5) = W5.get(cls) {
            i5.add(v.map(|x| x * w5 * vol));
        }
    }
    let (i7, i5) = (i7.value(), i5.value());
    // Fourth divided differences along each axis (Genz & Malik 1980, §4):
    // D_i = |f(λ₂eᵢ)+f(−λ₂eᵢ)−2f₀ − (λ₂²/λ₃²)(f(λ₃eᵢ)+f(−λ₃eᵢ)−2f₀)|.
    let ratio = (9.0 / 70.0) / (9.0 / 10.0);
    let fourth = |a: usize, b: usize, p: usize, q: usize| -> f64 {
        (0..W::CHANNELS)
            .map(|i| {
                // Indices below GM_POINTS (checked reads: no panic path if not inlined).
                let v = |k: usize| vals.get(k).map_or(0.0, |v| v.channel(i));
                let f0 = v(0);
                let d2 = v(a) + v(b) - 2.0 * f0;
                let d3 = v(p) + v(q) - 2.0 * f0;
                (d2 - ratio * d3).abs()
            })
            .sum()
    };
    let dx = fourth(1, 2, 5, 6);
    let dy = fourth(3, 4, 7, 8);
    let error = acc::abs_diff(i7, i5);
    let abs = ab.value();
    // Priority includes the region's f32 rounding floor (∝ its Σ|w f|), so
    // among regions whose 17 values agree (|I₇ − I₅| ≈ 0) the larger ones
    // are split first and the small ones frozen first.
    let key = acc::max_abs(acc::add(error, abs.map(|a| a * F32_FLOOR)));
    Region {
        c,
        h,
        value: i7,
        error,
        abs,
        key,
        peak,
        // Ties (e.g. both 0 where the integrand is constant) split the
        // longer side, so blank regions do not become thin slabs.
        axis: if dy > dx || (dy == dx && h[1] > h[0]) {
            1
        } else {
            0
        },
        n: 1,
    }
}

/// Bisection steps locating a step found in an edge gap (see [`edge_gaps`]).
const EDGE_BISECTIONS: u64 = 6;

/// Most evaluations of one region's [`edge_gaps`] check: a region touches
/// at most two sides of the square (the first cut is not at an edge), two
/// points per side plus the bisection.
const EDGE_POINTS: u64 = 2 * (2 + EDGE_BISECTIONS);

/// Tolerance of "on the boundary" (region sides are sums of halvings).
const EDGE_EPS: f64 = 1e-12;

/// The support step on the line through `p` along `axis`, between `x`
/// (on the side whose support flag is `!flag_e`) and `e` (flag `flag_e`):
/// [`EDGE_BISECTIONS`] bisections, returning the bound `s₋` nearer `x` (the
/// last point found with `x`'s flag, or `x`).
fn locate_step<W: WideSpectrum>(
    mut p: [f64; 2],
    axis: usize,
    x: f64,
    e: f64,
    flag_e: bool,
    f: &mut impl BatchFn<W>,
) -> Result<f64, IntegrateError> {
    let (mut lo, mut hi) = (x, e);
    let mut v = [W::splat(0.0)];
    for _ in 0..EDGE_BISECTIONS {
        let mid = 0.5 * (lo + hi);
        p[axis & 1] = mid;
        f(&[p], &mut v)?;
        if nonzero(&v[0]) == flag_e {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(lo)
}

/// The kink lines of the plain square (see `PlainMap`): `x = c` where the
/// integrand states a kink `μ = μk`, and `b ∈ {0, c, 1}` where it states
/// kinks `cos(φ − φk) = 0` (`c` the rule's first cut). On them a lobe may
/// end (a clamped lobe such as Phong's `max(0, ω·r)` is zero on one side of
/// a great circle that runs beside the lines `cos Δφ = 0`), so the
/// edge-gap check runs on region sides there.
#[derive(Clone, Copy, Debug)]
struct KinkLines {
    cut: f64,
    mu: bool,
    phi: bool,
}

impl KinkLines {
    /// The line a region side at `edge` (normal axis `ax`) lies on.
    fn line(&self, ax: usize, edge: f64) -> Option<f64> {
        let on = |l: f64| (edge - l).abs() <= EDGE_EPS;
        if ax == 0 {
            (self.mu && on(self.cut)).then_some(self.cut)
        } else if self.phi {
            [0.0, self.cut, 1.0].into_iter().find(|&l| on(l))
        } else {
            None
        }
    }
}

/// Smallest budget from which the plain [`Adaptive`] rule runs the edge-gap
/// checks on its kink lines ([`Integrand::kinks`]; fixed budgets only: the
/// tolerance driver's staged runs, which other rules confirm, skip them, and
/// `auto` to a tolerance kept its cost, 0.92× SciPy's `nquad` on GGX
/// `α = 0.3` at normal view where the checks made it 1.07×): a run with them still ends
/// with at least 8 leaf regions (4 splits of `2 × 17` evaluations and up to
/// `2 × 16` for the checks each, after the 4 initial regions and theirs: 396),
/// so that the few-nodes check of `status_of` applies. (From 132 on, a run
/// of 256 ended with 7 regions and GGX `α = 0.01` at `θo = 85°` answered
/// 447 ± 42 for an albedo of 0.99, resolved: its lobe on one node.)
pub const KINK_CHECK_MIN_BUDGET: u32 = 512;

/// Edge-gap check of the region `r` (warped square; on the plain square,
/// the sides on its kink lines, see [`KinkLines`]). The rule's nodes
/// stay `(1 − λ₃) h/n` (`λ₃ = √0.9`, `n × n` cells) away from the region's
/// sides, so a step of the warped integrand in that margin — typically
/// where the sampling map stops producing directions in a sliver at the
/// square's edge, e.g. GGX's visible-normal map at `u₁ → 1` — is never
/// seen, at any refinement, by a region on the square's boundary. For each
/// side of `r` on the boundary, the integrand is evaluated at the side's
/// midpoint `e` and at the nearest node position `x` (the outer node of the
/// adjacent cell on the same line). Where exactly one of `g(e)`, `g(x)` is
/// zero, the step `s` lies between them; [`EDGE_BISECTIONS`] bisections
/// locate it to `[s₋, s₊]` (`s₋` nearer `x`), and the region's error grows
/// by `max(|g(e)|, |g(x)|) · |e − s₋| · side length` (channel-wise): the
/// strip beyond the step, which the rule's smooth continuation of its
/// nodes may count as support (or miss). Refinement then shrinks the strip.
/// (The adaptive analogue of the edge-gap bound of the plain warped
/// Gauss–Legendre rule.) Returns the evaluations spent
/// (≤ [`EDGE_POINTS`]).
fn edge_gaps<W: WideSpectrum>(
    r: &mut Region<W>,
    squares: usize,
    lines: Option<KinkLines>,
    f: &mut impl BatchFn<W>,
) -> Result<u64, IntegrateError> {
    let l3 = libm::sqrt(0.9);
    let n = r.n as f64;
    // Sides on the boundary: the normal axis of each.
    let mut pts = [[0.0f64; 2]; 4];
    let mut axes = [0usize; 2];
    let mut m = 0;
    for ax in 0..2 {
        for sign in [-1.0, 1.0] {
            // The domain is `[0, squares] × [0, 1]`, one unit square per
            // component of the sampling map: its sides are at integers.
            let edge = r.c[ax] + sign * r.h[ax];
            if let Some(k) = lines {
                // The plain square: sides on a kink line, the line itself.
                if let Some(at) = k.line(ax, edge)
                    && m < 2
                {
                    let mut e = r.c;
                    e[ax] = at;
                    let mut x = r.c;
                    x[ax] = r.c[ax] + sign * (r.h[ax] - (1.0 - l3) * r.h[ax] / n);
                    pts[2 * m] = e;
                    pts[2 * m + 1] = x;
                    axes[m] = ax;
                    m += 1;
                }
                continue;
            }
            let near = libm::round(edge);
            if m < 2 && (edge - near).abs() <= EDGE_EPS {
                let top = if ax == 0 { squares as f64 } else { 1.0 };
                let mut e = r.c;
                // `+ 0.0`: a left side at `−0.0` is the point `0.0`. A right
                // side inside the domain (the seam between two components'
                // squares) is taken just below the integer, in the square
                // of the region (see `square_of`).
                e[ax] = if sign < 0.0 {
                    near + 0.0
                } else if near < top {
                    f64::from_bits(near.to_bits().saturating_sub(1))
                } else {
                    near
                };
                let mut x = r.c;
                x[ax] = r.c[ax] + sign * (r.h[ax] - (1.0 - l3) * r.h[ax] / n);
                pts[2 * m] = e;
                pts[2 * m + 1] = x;
                axes[m] = ax;
                m += 1;
            }
        }
    }
    // `m ≤ 2` (see the guard above; `min` lets the optimiser drop the
    // slicing's panic path).
    let m = m.min(2);
    if m == 0 {
        return Ok(0);
    }
    let mut vals = [W::splat(0.0); 4];
    f(&pts[..2 * m], &mut vals[..2 * m])?;
    let mut evals = 2 * m as u64;
    let mut grew = false;
    for k in 0..m {
        // `ax ∈ {0, 1}`; masking states it for the optimiser.
        let ax = axes.get(k).copied().unwrap_or(0) & 1;
        let (Some(&ve), Some(&vx), Some(&pe), Some(&px)) = (
            vals.get(2 * k),
            vals.get(2 * k + 1),
            pts.get(2 * k),
            pts.get(2 * k + 1),
        ) else {
            continue;
        };
        let flag_e = nonzero(&ve);
        if flag_e == nonzero(&vx) {
            continue;
        }
        let (e, x) = (pe[ax], px[ax]);
        let lo = locate_step(pe, ax, x, e, flag_e, f)?;
        evals += EDGE_BISECTIONS;
        let strip = (e - lo).abs();
        let side = 2.0 * r.h[ax ^ 1];
        r.error = acc::add(r.error, ve.zip(vx, |a, b| a.abs().max(b.abs()) * strip * side));
        // Split across the strip next (see `cut_gaps`).
        r.axis = ax as u8;
        grew = true;
    }
    if grew {
        r.key = acc::max_abs(acc::add(r.error, r.abs.map(|x| x * F32_FLOOR)));
    }
    Ok(evals)
}

/// Most evaluations of one [`cut_gaps`] check: three points on the line
/// across the cut and the bisection of a step on each side.
const CUT_POINTS: u64 = 3 + 2 * EDGE_BISECTIONS;

/// Cut-gap check after splitting a region into `a` (below the cut) and `b`
/// (above it) along `axis` (warped square only), run when one child's
/// nodes saw support and the other's did not: the support boundary then
/// crosses the region near the cut, and may lie in the margin between the
/// cut and either child's nearest nodes, where neither rule sees it — e.g.
/// the horizon pre-image of GGX's visible-normal map at `α = 1` is the line
/// `u₁ ≈ 2/3`, which a dyadic cut `u₁ = 0.6659` leaves 0.0008 inside the
/// zero child's 0.0012-wide margin: that child reports `0 ± 0` for the
/// sliver of support it holds, at every budget (the relative bias
/// `4·10⁻⁶` at `θo = 60°` that an estimate of `10⁻⁷` did not cover).
/// On the line across the cut's midpoint, the integrand is evaluated at
/// the cut `e` and at the nearest node position of each child (`x_a`,
/// `x_b`); where the support flag changes between `x` and `e`, the step is
/// located by [`EDGE_BISECTIONS`] bisections and that child's error grows
/// by the strip beyond it, `max(|g(x)|, |g(e)|) · |e − s₋| · side`, as in
/// [`edge_gaps`], and its next split is across the cut's axis (halving it
/// along the cut would leave the step in both grandchildren's margins,
/// with no error left to refine them). Refinement of the child then brings
/// the boundary into view. Returns the evaluations spent (≤ [`CUT_POINTS`]).
fn cut_gaps<W: WideSpectrum>(
    a: &mut Region<W>,
    b: &mut Region<W>,
    axis: usize,
    f: &mut impl BatchFn<W>,
) -> Result<u64, IntegrateError> {
    // `axis ∈ {0, 1}`; masking states it (no panic path in the indexing below).
    let axis = axis & 1;
    let l3 = libm::sqrt(0.9);
    let cut = a.c[axis] + a.h[axis];
    let mut e = a.c;
    e[axis] = cut;
    let mut xa = e;
    xa[axis] = cut - (1.0 - l3) * a.h[axis] / a.n as f64;
    let mut xb = e;
    xb[axis] = cut + (1.0 - l3) * b.h[axis] / b.n as f64;
    let pts = [xa, e, xb];
    let mut vals = [W::splat(0.0); 3];
    f(&pts, &mut vals)?;
    let mut evals = 3u64;
    let side = 2.0 * a.h[axis ^ 1];
    let flag_e = nonzero(&vals[1]);
    for (r, x, vx) in [(a, xa, vals[0]), (b, xb, vals[2])] {
        if nonzero(&vx) == flag_e {
            continue;
        }
        let lo = locate_step(e, axis, x[axis], cut, flag_e, f)?;
        evals += EDGE_BISECTIONS;
        let strip = (cut - lo).abs();
        let ve = vals[1];
        r.error = acc::add(r.error, ve.zip(vx, |p, q| p.abs().max(q.abs()) * strip * side));
        r.key = acc::max_abs(acc::add(r.error, r.abs.map(|x| x * F32_FLOOR)));
        // Split across the strip next: halving along it would leave the step
        // in both children's margins, and the error with it.
        r.axis = axis as u8;
    }
    Ok(evals)
}

/// Two-level check after splitting `p` into `a` and `b`: the difference
/// `d = |I(p) − (I(a) + I(b))|` is an estimate of the error of `p`'s rule
/// that does not depend on the 17 nodes seeing the feature. Where it
/// exceeds `p`'s own estimate `e(p)` (channel-wise), the rule was fooled
/// (typically a kink or step between the outer nodes and the region edge),
/// and the excess `(d − e(p))/2` is added to each child's error.
fn two_level<W: WideSpectrum>(p: &Region<W>, a: &mut Region<W>, b: &mut Region<W>) {
    let sum = acc::add(a.value, b.value);
    let d = acc::abs_diff(p.value, sum);
    let excess = d.zip(p.error, |d, e| 0.5 * (d - e).max(0.0));
    if acc::max_abs(excess) > 0.0 {
        for c in [a, b] {
            c.error = acc::add(c.error, excess);
            c.key = acc::max_abs(acc::add(c.error, c.abs.map(|x| x * F32_FLOOR)));
        }
    }
}

/// Globally adaptive Genz–Malik cubature over `[0,1]²` — by default the
/// hemisphere in `(μ = cos θ, φ/2π)` (so `∫_H g dω = 2π ∫∫ g da db`), or,
/// with `warped`, the unit square of the integrand's sampling map
/// (`∫ g/p du`, see [`super::WarpedGaussLegendre`]).
///
/// Each region gets the 17-point degree-7 Genz–Malik rule with its
/// embedded degree-5 rule; the region error is `|I₇ − I₅|` (Genz & Malik
/// 1980, J. Comput. Appl. Math. 6(4); the scheme of van Dooren & de
/// Ridder 1976 and of HCubature/`cubature`). The region with the largest
/// error is halved along the axis with the larger fourth difference, until
///
/// `Σ errors ≤ max(abs_tol, rel_tol · |Σ values|)` (largest channel), or
/// the budget cannot pay for another split (34 evaluations). With both
/// tolerances 0 the whole budget is spent; regions whose estimated error is
/// exactly 0 (all 17 values equal, as for a warped integrand that is
/// piecewise constant) are then split largest-first, so a feature hidden
/// between their nodes can still be found.
///
/// Safeguards against kinks and steps the rule cannot see. The 17 nodes
/// stay `≥ 2.6 %` of the width away from the region's edges, so a kink
/// (clamped lobe `max(0, cos α)`) or a step (sampling map leaving the
/// hemisphere) lying in that margin is integrated as its smooth
/// continuation with `I₇ ≈ I₅`: a silent bias that no local error estimate
/// built on those nodes can detect (it made earlier versions level off at
/// relative error ~5·10⁻⁵ while claiming ~10⁻⁷ on Phong/GGX at θo = 89.5°,
/// because the symmetry lines φ = π/2, π, 3π/2 of a BRDF lobe sat just
/// beside the dyadic cuts b = ¼, ½, ¾). Therefore:
/// 1. the first cut of both axes is at `(√5 − 1)/2` (not ½), and the plain
///    hemisphere is rotated by that fraction of a turn
///    (`φ = 2π (b + 0.618… mod 1)`, exact for the periodic azimuth), so
///    region edges do not line up with the symmetry lines of typical
///    integrands;
/// 2. every 4th split refines the live region with the largest cells
///    whatever its estimate (also whenever the worst region's estimate is
///    already below its `f32` floor, or its next refinement does not fit
///    the budget), so no region stays coarse (and blind) forever (the failure
///    mode of automatic quadrature discussed by Lyness 1983, "When not to
///    use an automatic quadrature routine", SIAM Rev. 25(1));
/// 3. a two-level check: after a split, `d = |I(parent) − I(children)|`
///    estimates the parent's true error independently of where its nodes
///    were; where `d` exceeds the parent's estimate, the excess is added
///    (half each) to the children's errors (after the two-level error
///    estimate of Sakiotis et al. 2021, "PAGANI: a parallel adaptive GPU
///    algorithm for numerical integration", SC'21).
///
/// 4. on the warped square, every new region with a side on the square's
///    boundary gets an edge-gap check (`edge_gaps`: the integrand at the
///    side and at the nearest node position; a support step between them is
///    located by 6 bisections and the strip beyond it added to the region's
///    error), because the sampling map often stops producing directions in
///    a sliver at the edge that no node ever enters; likewise, a split
///    whose children disagree on support (one child's nodes all zero, the
///    other's not) gets a cut-gap check across the cut (`cut_gaps`), since
///    the support boundary may sit in the margin beside the cut; a region
///    whose error grew by either check is next split across that strip;
/// 5. on the plain hemisphere, with a sampling map and a budget ≥ 84, a
///    peak probe ([`probe`], 16 draws from the budget): a
///    probe value above twice the largest node value of the leaf region
///    holding it marks the estimate [`Unresolved::UnseenPeak`]; at budgets
///    ≥ 4,096 the probe's mean check (one evaluation in 64, at most 1,024:
///    an importance-sampled estimate through the map) marks an estimate that
///    misses it by more than both errors [`Unresolved::ProbeDisagrees`]
///    (part of a lobe left in region margins: Beckmann `α = 10⁻³` at
///    `θo = 60°` converged 1.4 % low with an estimate of `1.5·10⁻⁴`), and its
///    draws are peak probes too, located in the leaf regions as the probe's
///    16 are (no extra evaluation): a lobe thinner than the regions' node
///    spacing that the 16 draws and the mean (whose `4σ` is about `10⁻²` of
///    a grazing lobe) both miss — Beckmann `α = 0.05` at `θo = 89.9°`, a
///    sliver about `10⁻²` rad wide in `φ`, converged `3·10⁻⁴` low with an
///    estimate of `5.6·10⁻⁷` at 2¹⁶–2²⁰ evaluations — is
///    [`Unresolved::UnseenPeak`] (the plain rule draws one point per 16
///    evaluations of its budget for this, [`PEAK_DRAW_SHARE`], at most
///    1,024);
/// 6. on the plain hemisphere, with a fixed budget (not in the staged runs
///    of the tolerance driver), from a budget of 512
///    ([`KINK_CHECK_MIN_BUDGET`]), the edge-gap check of 4. on every region side that lies on
///    one of the integrand's [kink lines](Integrand::kinks) (`μ = μk`,
///    `cos(φ − φk) = 0`), and the cut-gap check on the plain square too: a
///    lobe that ends beside such a line is a support step in the margin no
///    node enters (Phong `n = 1` at `θo = 89.5°`: `max(0, ω·r)` vanishes
///    beyond a great circle that runs within `0.0087 cot θ` rad of the lines
///    `cos Δφ = 0`; the rule was 4·10⁻⁶ low with estimates 10–36× smaller
///    at 1,024–65,536 evaluations);
/// 7. on the plain hemisphere split at a kink `μk`, with a fixed budget (not
///    in the staged runs, which other rules confirm), the piece from `μk` to
///    the pole is `μ = 1 − (1 − μk)(1 − u)²` (`sin θ` linear in `u`), so a
///    lobe that is not symmetric about the normal has no square-root
///    singularity at the zenith (the same Phong lobe passes `0.5°` from the
///    zenith and left `2.7·10⁻⁶` of its albedo in `μ > 0.9999` unseen at
///    every budget on the linear map, `2.2·10⁻⁶` off with an estimate of
///    `1.2·10⁻⁷` at 16,384);
/// 8. on the plain hemisphere, with a sampling map and a fixed budget
///    ≥ [`CROSS_CHECK_MIN_BUDGET`] (4,096), a cross-check on the map's
///    square: the warped rule gets `1/`[`CROSS_CHECK_SHARE`] of the budget,
///    and where the two values differ by more than both estimates together
///    the plain estimate's error grows to their difference (channel-wise;
///    the value stays the plain rule's). This is evidence from another
///    parameterisation, independent of the run's own nested estimate: the
///    retro-reflection wedge of Beckmann `α = 0.3` at `θo = 89.9°`
///    (`1.2·10⁻⁵` of the albedo within `Δφ ≈ 10⁻³` of the mirror azimuth
///    below `μ = 0.002`, which no plain node reaches) left the rule
///    `9·10⁻⁶` low with an estimate of `8.5·10⁻⁷` at 65,536.
///
/// These make blind regions rare and short-lived but cannot exclude them:
/// the estimate is a heuristic, not a bound. An integrand that is nonzero
/// only in a region smaller than the node spacing (e.g. a Beckmann lobe
/// with α = 0.01 seen by the plain rule) can yield `0 ± 0`; use the
/// `warped` variant for narrow lobes.
///
/// Start: a 2 × 2 grid of regions (68 evaluations = minimum budget).
/// Reported error = `Σ region errors + 2⁻²³ Σ|w g|` (the `f32` rounding
/// floor), channel-wise. Memory: at most [`MAX_REGIONS`] live regions on
/// the stack; once the table is full, the chosen region (worst, or every
/// 4th time the one with the largest cells) is instead re-evaluated with
/// the composite Genz–Malik rule on a grid twice as fine per axis
/// (`17 n²` evaluations for `n × n` cells), with the same two-level check
/// against its previous value; this stops when the budget cannot pay for
/// the next refinement. At most
/// [`MAX_ADAPTIVE_EVALUATIONS`] are spent. NaN/∞ → `NonFiniteIntegrand`.
/// Stack use: the region table takes `MAX_REGIONS × (48 + 24·CHANNELS)`
/// bytes (≈ 37 KiB for `f32`, ≈ 61 KiB for RGB; for a sampled spectrum
/// with many channels mind small thread stacks), or [`SMALL_REGIONS`] ×
/// the same at budgets up to [`SMALL_REGIONS_BUDGET`] (1,462), and
/// [`TINY_REGIONS`] × the same up to [`TINY_REGIONS_BUDGET`] (1,053), which
/// cannot fill more (same result).
/// `warped` without a sampling map → `NoSamplingMap`.
///
/// ```
/// use radiometry::integrator::{Adaptive, Integrand, Integrator};
/// use radiometry::glam::Vec3;
/// struct Cos8;
/// impl Integrand for Cos8 {
///     type Spectrum = f32;
///     fn eval(&self, w: Vec3) -> f32 { w.z.powi(8) }
/// }
/// let a = Adaptive::new(1e-6, 0.0).unwrap();
/// let e = a.integrate(&Cos8, 100_000).unwrap();
/// let exact = 2.0 * core::f64::consts::PI / 9.0;
/// assert!((e.value - exact).abs() <= e.error);
/// assert!(e.error <= 1e-6 * exact * 1.01);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    rel_tol: f64,
    abs_tol: f64,
    warped: bool,
    /// The shifted twin of the confirmation runs (see
    /// [`Adaptive::shifted`]).
    shifted: bool,
    /// The plain square without the split at the integrand's kinks (see
    /// [`Adaptive::unsplit`]).
    unsplit: bool,
}

impl Adaptive {
    /// Smallest accepted budget of the plain rule (4 regions × 17 points).
    pub const MIN_BUDGET: u32 = 4 * GM_POINTS as u32;

    /// Smallest accepted budget of the warped rule: the plain minimum plus
    /// the edge-gap checks of the four initial regions (a run without them
    /// cannot see a support step in the margins at the square's edges, and
    /// would report a lobe's tail it never saw as resolved).
    pub const MIN_BUDGET_WARPED: u32 = Self::MIN_BUDGET + 4 * EDGE_POINTS as u32;

    /// Smallest budget this configuration accepts ([`Self::MIN_BUDGET`] or
    /// [`Self::MIN_BUDGET_WARPED`]).
    pub const fn min_budget(&self) -> u32 {
        if self.warped {
            Self::MIN_BUDGET_WARPED
        } else {
            Self::MIN_BUDGET
        }
    }

    /// Adaptive cubature over the hemisphere stopping at relative
    /// tolerance `rel_tol` or absolute tolerance `abs_tol`, whichever is
    /// looser. Both must be finite and `≥ 0`
    /// (else [`IntegrateError::InvalidConfig`]); `0, 0` refines until the
    /// budget is spent.
    pub fn new(rel_tol: f64, abs_tol: f64) -> Result<Self, IntegrateError> {
        if !(rel_tol.is_finite() && rel_tol >= 0.0) {
            return Err(IntegrateError::InvalidConfig("rel_tol must be finite and >= 0"));
        }
        if !(abs_tol.is_finite() && abs_tol >= 0.0) {
            return Err(IntegrateError::InvalidConfig("abs_tol must be finite and >= 0"));
        }
        Ok(Self {
            rel_tol,
            abs_tol,
            warped: false,
            shifted: false,
            unsplit: false,
        })
    }

    /// The same rule applied on the integrand's sampling-map square.
    pub const fn warped(mut self) -> Self {
        self.warped = true;
        self
    }

    /// The same rule with other cuts and nodes: the first cut of both axes
    /// at `√2 − 1` instead of `(√5 − 1)/2`, and every piece of the square
    /// bent by `s(u) = u + κ u (1 − u)` (`κ =` [`SHIFTED_BEND`]; on the plain
    /// square the azimuth offset is `(3 − √5)/2` turns instead of
    /// `(√5 − 1)/2` where the integrand states no kinks), so that no region
    /// boundary and no node of the two rules coincide. Used by the
    /// tolerance driver as an independent confirmation (crate-internal: the
    /// report's `adaptive` and `adaptive-warped` are the unshifted rules).
    pub(crate) const fn shifted(mut self) -> Self {
        self.shifted = true;
        self
    }

    /// The shifted plain rule without the split at the integrand's kinks
    /// (the square mapped linearly, first cuts at `√2 − 1`, azimuth offset
    /// `(3 − √5)/2` turns): a third rule of the plain square for the
    /// tolerance driver (crate-internal).
    pub(crate) const fn unsplit(mut self) -> Self {
        self.shifted = true;
        self.unsplit = true;
        self
    }

    /// Whether this runs on the sampling-map square.
    pub const fn is_warped(&self) -> bool {
        self.warped
    }

    /// `(rel_tol, abs_tol)`.
    pub const fn tolerances(&self) -> (f64, f64) {
        (self.rel_tol, self.abs_tol)
    }

    /// The adaptive loop on `[0,1]²` with values `f`. `probe`: points of the
    /// square with the integrand value there (on the scale of `f`), drawn
    /// through the integrand's sampling map; the estimate is
    /// [`Unresolved::UnseenPeak`] when the leaf region holding one of them
    /// saw no value within [`probe::PEAK_RATIO`] of it at its nodes.
    ///
    /// `confirm = Some(tol)`: the staged mode of
    /// [`Integrator::to_tolerance`] — the configured tolerances are ignored;
    /// refinement goes on until `Σ errors ≤ tol`, the value there is kept as
    /// a checkpoint, and refinement continues until the evaluations have
    /// doubled; the run stops when the new value is within `tol` of the
    /// checkpoint (every channel), `Σ errors ≤ tol` still holds and the
    /// status is resolved, and returns that difference; otherwise the new
    /// value becomes the checkpoint and refinement continues (up to the
    /// budget). The regions are refined once, never recomputed.
    ///
    /// `squares`: the domain is `[0, squares] × [0, 1]`, `squares` unit
    /// squares side by side (one per component of a mixture sampling map,
    /// see [`Integrand::sampling_components`]), each started as the single
    /// square is (4 regions cut at the first cut); `1` is the unit square.
    fn run<W: WideSpectrum>(
        &self,
        budget: u32,
        probe: &[([f64; 2], f64)],
        squares: usize,
        lines: Option<KinkLines>,
        f: impl BatchFn<W>,
        confirm: Option<f64>,
    ) -> Result<Staged<W>, IntegrateError> {
        // `K` squares start with `4 K` regions instead of 4: the table of
        // `N` regions cannot fill below `34 (N − 2 K)`, which is the single
        // square's bound at a budget larger by `68 (K − 1)`.
        let squares = squares.clamp(1, MAX_SQUARES);
        let sized = budget.saturating_add(2 * GM_POINTS as u32 * 2 * (squares as u32 - 1));
        if sized <= TINY_REGIONS_BUDGET {
            self.run_with::<W, TINY_REGIONS>(budget, probe, squares, lines, f, confirm)
        } else if sized <= SMALL_REGIONS_BUDGET {
            self.run_with::<W, SMALL_REGIONS>(budget, probe, squares, lines, f, confirm)
        } else {
            self.run_with::<W, MAX_REGIONS>(budget, probe, squares, lines, f, confirm)
        }
    }

    /// [`Adaptive::run`] with a table of `N` regions. Never inlined: each
    /// table size keeps its own stack frame.
    #[inline(never)]
    fn run_with<W: WideSpectrum, const N: usize>(
        &self,
        budget: u32,
        probe: &[([f64; 2], f64)],
        squares: usize,
        lines: Option<KinkLines>,
        mut f: impl BatchFn<W>,
        confirm: Option<f64>,
    ) -> Result<Staged<W>, IntegrateError> {
        let squares = squares.clamp(1, MAX_SQUARES);
        // Edge-gap checks on the warped square (see `edge_gaps`), on every
        // new region on the boundary, from the initial regions on: the
        // warped rule's minimum budget pays for them.
        // On the plain square, on the sides on its kink lines, from
        // `KINK_CHECK_MIN_BUDGET` on, with a fixed budget (the staged runs of
        // the tolerance driver are confirmed by other rules instead).
        let lines = if self.warped || confirm.is_some() {
            None
        } else {
            lines.filter(|_| budget >= KINK_CHECK_MIN_BUDGET)
        };
        let edge = self.warped || lines.is_some();
        let edge_cost = if edge { EDGE_POINTS } else { 0 };
        let minimum = self.min_budget().saturating_mul(squares as u32);
        if budget < minimum {
            return Err(IntegrateError::BudgetTooSmall { minimum });
        }
        let budget = budget.min(MAX_ADAPTIVE_EVALUATIONS) as u64;
        let zero = W::splat(0.0);
        let empty = Region {
            c: [0.0; 2],
            h: [0.0; 2],
            value: zero,
            error: zero,
            abs: zero,
            key: 0.0,
            peak: 0.0,
            axis: 0,
            n: 1,
        };
        let mut regions = [empty; N];
        let mut live = 0usize;
        // Initial cut at `FIRST_CUT` (not ½) on both axes, so later
        // midpoint cuts do not fall on the symmetry lines ¼, ½, ¾ of
        // typical integrands (see the type's docs).
        let cut = if self.shifted { SHIFTED_CUT } else { FIRST_CUT };
        let span = |i: usize| if i == 0 { (0.0, cut) } else { (cut, 1.0) };
        // Square `s` is `[s, s + 1] × [0, 1]`; its regions are those of the
        // unit square shifted by `s` (exactly the unit square's for `s = 0`).
        // Checked writes and `take(live)` below: `live ≤ N` holds
        // by construction, and the code keeps no panic path for it.
        for s in 0..squares {
            let x = s as f64;
            let (mut c0, mut h0) = ([[0.0; 2]; 4], [[0.0; 2]; 4]);
            for ((c, h), (i, j)) in c0
                .iter_mut()
                .zip(h0.iter_mut())
                .zip([(0, 0), (0, 1), (1, 0), (1, 1)])
            {
                let ((x0, x1), (y0, y1)) = (span(i), span(j));
                *c = [x + 0.5 * (x0 + x1), 0.5 * (y0 + y1)];
                *h = [0.5 * (x1 - x0), 0.5 * (y1 - y0)];
            }
            rules(&c0, &h0, &mut f, |r| {
                if let Some(slot) = regions.get_mut(live) {
                    *slot = r;
                    live += 1;
                }
            })?;
        }
        let initial = 4 * squares;
        let mut evals = (initial * GM_POINTS) as u64;
        if edge {
            for r in regions.iter_mut().take(live) {
                evals += edge_gaps(r, squares, lines, &mut f)?;
            }
        }
        let mut splits = 0u64;
        // Staged mode: the checkpoint `(value, evaluations)` and, once
        // confirmed, the difference to it.
        let mut checkpoint: Option<(W, u64)> = None;
        let mut confirmed: Option<W> = None;
        loop {
            // Totals and the worst region.
            let mut worst = 0usize;
            let mut largest = 0usize;
            // The worst region's error and area, the largest region's area
            // and key (−1: none yet, so region 0 is taken first).
            let (mut we, mut wa) = (-1.0f64, -1.0f64);
            let (mut la, mut lk) = (-1.0f64, -1.0f64);
            let mut err_sum = 0.0f64;
            let mut val = WideSum::<W>::new();
            for (k, r) in regions.iter().take(live).enumerate() {
                err_sum += r.key;
                val.add(r.value);
                // Largest error first; among equal errors (e.g. all zero on a
                // piecewise-constant integrand) the largest region.
                // (By the estimate alone: the f32 floor term of the key does
                // not shrink under refinement.)
                let (re, ra) = (acc::max_abs(r.error), r.cell_area());
                if re > we || (re == we && ra > wa) {
                    (worst, we, wa) = (k, re, ra);
                }
                if ra > la || (ra == la && r.key > lk) {
                    (largest, la, lk) = (k, ra, r.key);
                }
            }
            let converged = if let Some(tol) = confirm {
                let v = val.value();
                match checkpoint {
                    None if err_sum <= STAGE_K * tol => {
                        checkpoint = Some((v, evals));
                        false
                    }
                    Some((v0, e0)) if evals >= 2 * e0 => {
                        let d = acc::abs_diff(v, v0);
                        let agree = acc::max_abs(d) <= tol
                            && err_sum <= STAGE_K * tol
                            && status_of(regions.get(..live).unwrap_or_default(), probe).is_resolved();
                        if agree {
                            confirmed = Some(d);
                        } else {
                            checkpoint = Some((v, evals));
                        }
                        agree
                    }
                    _ => false,
                }
            } else {
                let target = self.abs_tol.max(self.rel_tol * acc::max_abs(val.value()));
                target > 0.0 && err_sum <= target
            };
            if converged || evals + 2 * (GM_POINTS as u64 + edge_cost) > budget {
                break;
            }
            // Every `FORCED_EVERY`-th split refines the largest region
            // regardless of its estimate (see the type's docs).
            // So does the worst region once its estimate is below its f32
            // floor (refining it cannot help).
            let Some(&w) = regions.get(worst) else {
                break;
            };
            let mut forced = splits % FORCED_EVERY == FORCED_EVERY - 1
                || acc::max_abs(w.error) <= F32_FLOOR * acc::max_abs(w.abs);
            if live == N && !forced {
                let n = w.n.saturating_mul(2) as u64;
                forced = evals + n * n * GM_POINTS as u64 + edge_cost > budget;
            }
            if forced {
                worst = largest;
            }
            let Some(&r) = regions.get(worst) else {
                break;
            };
            if live == N {
                // Table full: re-evaluate the region with the composite
                // rule on a grid twice as fine per axis (the table never
                // discards a region, so none is left blind for good).
                let n = r.n.saturating_mul(2);
                let cost = (n as u64) * (n as u64) * GM_POINTS as u64;
                if evals + cost + edge_cost > budget {
                    break;
                }
                let mut q = composite(r.c, r.h, n, r.axis, &mut f)?;
                evals += cost;
                if edge {
                    evals += edge_gaps(&mut q, squares, lines, &mut f)?;
                }
                splits += 1;
                // Two-level check against the coarser rule.
                let d = acc::abs_diff(r.value, q.value);
                let excess = d.zip(r.error, |d, e| (d - e).max(0.0));
                q.error = acc::add(q.error, excess);
                q.key = acc::max_abs(acc::add(q.error, q.abs.map(|x| x * F32_FLOOR)));
                if let Some(slot) = regions.get_mut(worst) {
                    *slot = q;
                }
                continue;
            }
            let ax = r.axis as usize & 1;
            let mut h = r.h;
            h[ax] *= 0.5;
            let mut c1 = r.c;
            let mut c2 = r.c;
            c1[ax] -= h[ax];
            c2[ax] += h[ax];
            let mut ab = [empty; 2];
            let mut k = 0;
            rules(&[c1, c2], &[h, h], &mut f, |q| {
                if let Some(slot) = ab.get_mut(k) {
                    *slot = q;
                }
                k += 1;
            })?;
            let [mut a, mut b] = ab;
            evals += 2 * GM_POINTS as u64;
            if edge {
                evals +=
                    edge_gaps(&mut a, squares, lines, &mut f)? + edge_gaps(&mut b, squares, lines, &mut f)?;
                if nonzero(&a.abs) != nonzero(&b.abs) && evals + CUT_POINTS <= budget {
                    evals += cut_gaps(&mut a, &mut b, ax, &mut f)?;
                }
            }
            splits += 1;
            two_level(&r, &mut a, &mut b);
            if let Some(slot) = regions.get_mut(worst) {
                *slot = a;
            }
            if let Some(slot) = regions.get_mut(live) {
                *slot = b;
                live += 1;
            }
        }
        let (mut val, mut err, mut abs) = (WideSum::<W>::new(), WideSum::<W>::new(), WideSum::<W>::new());
        for r in regions.iter().take(live) {
            val.add(r.value);
            err.add(r.error);
            abs.add(r.abs);
        }
        let abs = abs.value();
        let status = status_of(regions.get(..live).unwrap_or_default(), probe);
        // Confirmed in the staged mode: the rule's own estimate (of the
        // embedded degree-5 rule's error) deflated by STAGE_K, or the
        // observed change under doubling, whichever is larger.
        let err = match confirmed {
            Some(d) => err.value().zip(d, |e, d| (e / STAGE_K).max(d)),
            None => err.value(),
        };
        Ok((
            Estimate {
                value: val.value(),
                error: acc::add(err, abs.map(|a| a * F32_FLOOR)),
                evaluations: evals,
                status,
            },
            confirmed,
        ))
    }

    /// The staged mode of [`Adaptive::run`] to `tol` with at most `budget`
    /// evaluations: the estimate and, when a refinement that doubled the
    /// evaluations moved the value by `≤ tol`, that difference.
    pub(crate) fn staged<I: Integrand>(
        &self,
        g: &I,
        budget: u32,
        tol: f64,
    ) -> Result<Staged<WideOf<I>>, IntegrateError> {
        self.integrate_impl(g, budget, Some(tol))
    }

    /// [`Integrator::integrate`], and in the staged mode (`confirm`) the
    /// difference to the confirming checkpoint (see [`Adaptive::run`]).
    fn integrate_impl<I: Integrand>(
        &self,
        g: &I,
        budget: u32,
        confirm: Option<f64>,
    ) -> Result<Staged<WideOf<I>>, IntegrateError> {
        if self.warped {
            if !g.has_sampling_map() {
                return Err(IntegrateError::NoSamplingMap);
            }
            // A mixture map: each component on its own square (no seam), when
            // the budget pays for the squares' initial regions.
            let comps = chunk::Components::of(g);
            let k = comps.len();
            if k > 1 && budget >= self.min_budget().saturating_mul(k as u32) {
                let bend = if self.shifted { SHIFTED_BEND } else { 0.0 };
                return self.run(
                    budget,
                    &[],
                    k,
                    None,
                    |p: &[[f64; 2]], out: &mut [WideOf<I>]| {
                        chunk::component_warped_values(g, &comps, bend, p, out)
                    },
                    confirm,
                );
            }
            if self.shifted {
                return self.run(
                    budget,
                    &[],
                    1,
                    None,
                    |p: &[[f64; 2]], out: &mut [WideOf<I>]| {
                        chunk::bent_warped_values(g, p, SHIFTED_BEND, out)
                    },
                    confirm,
                );
            }
            self.run(
                budget,
                &[],
                1,
                None,
                |p: &[[f64; 2]], out: &mut [WideOf<I>]| chunk::warped_values(g, p, out),
                confirm,
            )
        } else {
            self.integrate_hemisphere(g, budget, confirm)
        }
    }

    /// The plain (unwarped) path of [`Adaptive::integrate_impl`]. Never
    /// inlined: its probe table stays out of the warped path's frame.
    #[inline(never)]
    fn integrate_hemisphere<I: Integrand>(
        &self,
        g: &I,
        budget: u32,
        confirm: Option<f64>,
    ) -> Result<Staged<WideOf<I>>, IntegrateError> {
        let offset = if self.shifted {
            SHIFTED_PHI_OFFSET
        } else {
            PHI_OFFSET
        };
        let cut = if self.shifted { SHIFTED_CUT } else { FIRST_CUT };
        let map = if self.unsplit {
            PlainMap::new(None, cut, offset, 0.0)
        } else {
            let bend = if self.shifted { SHIFTED_BEND } else { 0.0 };
            // The pole piece with a fixed budget only (check 7): the staged
            // runs of the tolerance driver are confirmed by other rules, and
            // on the linear map `auto` confirmed GGX `α = 1` at 85° to 10⁻⁶
            // with 1,041 evaluations where the pole piece took 1,381.
            PlainMap::new(g.kinks(), cut, offset, bend).with_pole(confirm.is_none())
        };
        // In the staged mode the rule's size is not known in advance:
        // the mean check is sized by the evaluations the rule spent.
        let check = if confirm.is_some() {
            0
        } else {
            peak_draws(g, budget)
        };
        let (rule_budget, probing) = probe::split_budget(g, budget - check, Self::MIN_BUDGET);
        let (mut e, confirmed) = if check > 0 {
            // The mean check's draws are peak probes too (see the type's
            // docs): a table for all of them, in its own frame.
            self.hemisphere_probed::<I, { probe::PROBE_POINTS + probe::MEAN_CHECK_MAX_POINTS as usize }>(
                g,
                &map,
                rule_budget,
                probing,
                check,
                confirm,
            )?
        } else {
            self.hemisphere_probed::<I, { probe::PROBE_POINTS }>(g, &map, rule_budget, probing, 0, confirm)?
        };
        if confirm.is_some() {
            let check = probe::mean_check_points(g, u32::try_from(e.evaluations).unwrap_or(u32::MAX));
            if check > 0 {
                let m = probe::MeanCheck::take(g, check)?;
                e.status = m.judge(e.status, e.value, e.error);
                e.evaluations += check as u64;
            }
        }
        Ok((e, confirmed))
    }

    /// The plain rule with the peak probe (`probing`) and, when `check > 0`,
    /// the mean check of `check` draws, whose draws are located in the leaf
    /// regions as the probe's are (`P` ≥ the probe's points plus `check`).
    /// Never inlined: the table of `P` points stays out of the frames of
    /// the budgets without a mean check.
    #[inline(never)]
    fn hemisphere_probed<I: Integrand, const P: usize>(
        &self,
        g: &I,
        map: &PlainMap,
        rule_budget: u32,
        probing: bool,
        check: u32,
        confirm: Option<f64>,
    ) -> Result<Staged<WideOf<I>>, IntegrateError> {
        // The probes' points in the square's coordinates `(μ, b)` with
        // `φ = 2π turn(b)`, values on the scale of `2π g`.
        let mut pts = [([0.0f64; 2], 0.0f64); P];
        let (n, mean) = probe_points(g, map, probing, check, &mut pts)?;
        let (mut e, confirmed) = self.run(
            rule_budget,
            pts.get(..n).unwrap_or_default(),
            1,
            map.lines(),
            |p: &[[f64; 2]], out: &mut [WideOf<I>]| {
                chunk::mapped_hemisphere_values(g, p, |x, b| map.forward(x, b), out)
            },
            confirm,
        )?;
        if probing {
            e.evaluations += probe::PROBE_POINTS as u64;
        }
        if let Some(m) = mean {
            e.status = m.judge(e.status, e.value, e.error);
            e.evaluations += check as u64;
        }
        Ok((e, confirmed))
    }
}

/// How many probe points [`probe_points`] wrote, and the mean check.
type ProbePoints<W> = (usize, Option<probe::MeanCheck<W>>);

/// Fills `pts` with the peak probe's points (`probing`) and the mean
/// check's `check` draws (only where `P > PROBE_POINTS`, known at compile
/// time) in the plain square's coordinates; returns how many it wrote and
/// the mean check. Never inlined: the probe's own table and the draws'
/// buffers stay out of the frame that runs the rule (the firmware's stack
/// target: 8,000 B at a budget of 1,024 on the Cortex-M4F).
#[inline(never)]
fn probe_points<I: Integrand, const P: usize>(
    g: &I,
    map: &PlainMap,
    probing: bool,
    check: u32,
    pts: &mut [([f64; 2], f64); P],
) -> Result<ProbePoints<WideOf<I>>, IntegrateError> {
    let mut n = 0;
    let mut push = |w: glam::Vec3, v: f64| {
        let (x, b, j) = map.inverse(w);
        if let Some(p) = pts.get_mut(n) {
            *p = ([x, b], v * j);
            n += 1;
        }
    };
    if probing {
        for &(w, v) in probe::Probe::take(g)?.points() {
            push(w, v);
        }
    }
    let mean = if P > probe::PROBE_POINTS && check > 0 {
        Some(probe::MeanCheck::take_each(g, check, &mut push)?)
    } else {
        None
    };
    Ok((n, mean))
}

/// One draw of the plain rule's mean check, whose draws are also peak
/// probes (see [`Adaptive`]), per this many evaluations of the budget (the
/// crate's other blind rules draw one per
/// [`MEAN_CHECK_SHARE`](probe::MEAN_CHECK_SHARE) = 64): at 16,384
/// evaluations 256 draws missed the sliver of Beckmann `α = 0.05` at
/// `θo = 89.9°` that 1,024 find.
pub const PEAK_DRAW_SHARE: u32 = 16;

/// Draws of the plain rule's mean check at `budget`: one per
/// [`PEAK_DRAW_SHARE`] evaluations, at most
/// [`MEAN_CHECK_MAX_POINTS`](probe::MEAN_CHECK_MAX_POINTS), where
/// [`probe::mean_check_points`] makes one (budgets ≥ 4,096 with a sampling
/// map); else 0.
fn peak_draws<I: Integrand>(g: &I, budget: u32) -> u32 {
    if probe::mean_check_points(g, budget) > 0 {
        (budget / PEAK_DRAW_SHARE).min(probe::MEAN_CHECK_MAX_POINTS)
    } else {
        0
    }
}

/// The plain square `(x, b) ∈ [0,1]²` of [`Adaptive`] mapped to the
/// hemisphere `(μ, φ)`, piecewise linearly so that the integrand's kink
/// lines ([`Integrand::kinks`]) fall on the first cuts `x = c`, `b = c` of
/// the rule (`c` the rule's first cut):
/// * `μ`: `[0, c] → [0, μk]` and `[c, 1] → [μk, 1]` (with a kink
///   `0 < μk < 1`), else `μ = x`;
/// * `φ` (in turns): `[0, c] → φk + [¼, ¾]` (the half turn about the
///   mirror azimuth `φk + ½`) and `[c, 1] → φk + [¾, 5/4]`, so that
///   `cos(φ − φk) = 0` at `b = 0` and `b = c`; else `φ = b + offset`.
///
/// Within each piece, the fraction `u ∈ [0, 1]` is bent to
/// `s(u) = u + κ u (1 − u)` (`κ = 0` for the plain rule,
/// [`SHIFTED_BEND`] for the shifted one), so that the two rules' nodes
/// differ inside the pieces as well (a linear map would send both rules'
/// regions, and nodes, to the same directions).
///
/// The value is `g` times the Jacobian `2π (dμ/dx)(dφ/db)` (φ in turns).
#[derive(Clone, Copy, Debug)]
struct PlainMap {
    cut: f64,
    bend: f64,
    /// `μk`, when strictly inside `(0, 1)`.
    mu: Option<f64>,
    /// `φk` in turns, or `None` (then `offset`).
    phi: Option<f64>,
    offset: f64,
    /// Whether the piece above `μk` is the [`pole`] piece (else linear).
    pole: bool,
}

impl PlainMap {
    /// Kinks closer than this to `μ = 0` or `1` are not split at (no
    /// region could hold the sliver).
    const MU_MARGIN: f64 = 1e-9;

    fn new(k: Option<super::Kinks>, cut: f64, offset: f64, bend: f64) -> Self {
        let mu = k
            .map(|k| k.mu)
            .filter(|&m| m.is_finite() && m > Self::MU_MARGIN && m < 1.0 - Self::MU_MARGIN);
        let phi = k
            .map(|k| k.phi / core::f64::consts::TAU)
            .filter(|p| p.is_finite())
            .map(|p| p - libm::floor(p));
        PlainMap {
            cut,
            bend,
            mu,
            phi,
            offset,
            pole: false,
        }
    }

    /// The same map with the [`pole`] piece above `μk` (`on`), or linear.
    fn with_pole(mut self, on: bool) -> Self {
        self.pole = on;
        self
    }

    /// Its kink lines, if the integrand states any.
    fn lines(&self) -> Option<KinkLines> {
        (self.mu.is_some() || self.phi.is_some()).then_some(KinkLines {
            cut: self.cut,
            mu: self.mu.is_some(),
            phi: self.phi.is_some(),
        })
    }

    /// `(s(u), s'(u))` of the bend.
    fn bent(&self, u: f64) -> (f64, f64) {
        let k = self.bend;
        (u + k * u * (1.0 - u), 1.0 + k * (1.0 - 2.0 * u))
    }

    /// `(u, s'(u))` with `s(u) = s`.
    fn unbent(&self, s: f64) -> (f64, f64) {
        let k = self.bend;
        if k == 0.0 {
            return (s, 1.0);
        }
        let d = ((1.0 + k) * (1.0 + k) - 4.0 * k * s).max(0.0);
        let u = (((1.0 + k) - libm::sqrt(d)) / (2.0 * k)).clamp(0.0, 1.0);
        (u, 1.0 + k * (1.0 - 2.0 * u))
    }

    /// `(μ, φ [radians], Jacobian)` at `(x, b)`.
    fn forward(&self, x: f64, b: f64) -> (f64, f64, f64) {
        let c = self.cut;
        let (mu, jm) = match self.mu {
            Some(m) if x < c => {
                let (u, d) = self.bent(x / c);
                (m * u, d * m / c)
            }
            Some(m) => {
                let (u, d) = self.bent((x - c) / (1.0 - c));
                let (mu, j) = if self.pole {
                    pole(m, u)
                } else {
                    (m + (1.0 - m) * u, 1.0 - m)
                };
                (mu, d * j / (1.0 - c))
            }
            None => (x, 1.0),
        };
        let (t, jt) = match self.phi {
            Some(p) if b < c => {
                let (u, d) = self.bent(b / c);
                (p + 0.25 + 0.5 * u, d * 0.5 / c)
            }
            Some(p) => {
                let (u, d) = self.bent((b - c) / (1.0 - c));
                (p + 0.75 + 0.5 * u, d * 0.5 / (1.0 - c))
            }
            None => (b + self.offset, 1.0),
        };
        let t = t - libm::floor(t);
        let tau = core::f64::consts::TAU;
        (mu.clamp(0.0, 1.0), tau * t, tau * jm * jt)
    }

    /// `(x, b, Jacobian)` of the direction `w` (the inverse of
    /// [`PlainMap::forward`]).
    fn inverse(&self, w: glam::Vec3) -> (f64, f64, f64) {
        let c = self.cut;
        let mu = (w.z as f64).clamp(0.0, 1.0);
        let (x, jm) = match self.mu {
            // `μ = μk` itself (a probe drawn on the kink line) belongs to
            // the lower piece, just below the cut: a point on the cut would
            // be judged against either side's nodes, whose Jacobians differ
            // (2(1 − μk)/(1 − c) above, μk/c below).
            Some(m) if mu <= m => {
                let (u, d) = self.unbent(mu / m);
                let below = f64::from_bits(c.to_bits().saturating_sub(1));
                ((c * u).min(below), d * m / c)
            }
            Some(m) => {
                // `1 − μ = sin²θ/(1 + μ)` from the horizontal components:
                // accurate near the pole, where `1 − μ` of an `f32` `μ` is not.
                let (wx, wy) = (w.x as f64, w.y as f64);
                let (u, j) = if self.pole {
                    pole_inverse(m, (wx * wx + wy * wy) / (1.0 + mu))
                } else {
                    ((mu - m) / (1.0 - m), 1.0 - m)
                };
                let (u, d) = self.unbent(u);
                (c + (1.0 - c) * u, d * j / (1.0 - c))
            }
            None => (mu, 1.0),
        };
        let t = libm::atan2(w.y as f64, w.x as f64) / core::f64::consts::TAU;
        let (b, jt) = match self.phi {
            Some(p) => {
                let s = t - p - 0.25;
                let s = s - libm::floor(s);
                if s < 0.5 {
                    let (u, d) = self.unbent(s / 0.5);
                    (c * u, d * 0.5 / c)
                } else {
                    let (u, d) = self.unbent((s - 0.5) / 0.5);
                    (c + (1.0 - c) * u, d * 0.5 / (1.0 - c))
                }
            }
            None => {
                let b = t - self.offset;
                (b - libm::floor(b), 1.0)
            }
        };
        (
            x.clamp(0.0, 1.0),
            b.clamp(0.0, 1.0),
            core::f64::consts::TAU * jm * jt,
        )
    }
}

/// The piece of the plain square that ends at the pole, `u ∈ [0, 1] ↦
/// μ ∈ [m, 1]`: `μ = 1 − (1 − m)(1 − u)²`, so that `√(1 − μ)` (and with
/// it `sin θ`, the scale of `ωi`'s horizontal components) is linear in
/// `u`. A lobe that is not rotationally symmetric about the normal is then
/// a smooth function of `u` up to the pole, where in `μ` it has the
/// square-root singularity of `sin θ = √(1 − μ²)`: Phong `n = 1` at
/// `θo = 89.5°`, whose support ends on the great circle `ωi · r = 0`
/// `0.5°` from the zenith, left `2.7·10⁻⁶` of its albedo (in
/// `μ > 0.9999`) unseen at every budget on the linear map. (Without a
/// kink line, `μ = x` throughout: an isotropic lobe states its kinks except
/// at normal view, where it is rotationally symmetric.) Returns
/// `(μ, dμ/du)`.
fn pole(m: f64, u: f64) -> (f64, f64) {
    let v = 1.0 - u;
    (1.0 - (1.0 - m) * v * v, 2.0 * (1.0 - m) * v)
}

/// `(u, dμ/du)` of [`pole`] at `1 − μ = one_minus`.
fn pole_inverse(m: f64, one_minus: f64) -> (f64, f64) {
    let v = libm::sqrt((one_minus / (1.0 - m)).max(0.0));
    ((1.0 - v).clamp(0.0, 1.0), 2.0 * (1.0 - m) * v)
}

/// The status of an estimate made of the leaf regions `regions`, with the
/// peak probe `probe` (see [`Adaptive::run`]):
/// * no node of any region saw the support: `0 ± 0` says nothing;
/// * the support seen by a handful of regions only (effective region
///   count `(Σ|Q_r|)²/Σ|Q_r|²` below 4, with ≥ 8 regions): a lobe met by the
///   tails of a few regions' rules, not resolved by refinement;
/// * a probe value in a leaf region whose nodes saw nothing near it: a peak
///   (or part of a lobe) between the nodes that refinement never reached
///   (see [`probe`]).
fn status_of<W: WideSpectrum>(regions: &[Region<W>], probe: &[([f64; 2], f64)]) -> Status {
    let (mut abs, mut sq) = (WideSum::<W>::new(), WideSum::<W>::new());
    for r in regions {
        abs.add(r.abs);
        sq.add(r.abs.map(|a| a * a));
    }
    let abs = abs.value();
    let unseen = probe.iter().any(|&(p, v)| {
        regions
            .iter()
            .find(|r| (p[0] - r.c[0]).abs() <= r.h[0] && (p[1] - r.c[1]).abs() <= r.h[1])
            .is_some_and(|r| v > probe::PEAK_RATIO * r.peak)
    });
    if acc::max_abs(abs) <= 0.0 {
        Status::Unresolved(Unresolved::NoSupportSeen)
    } else if regions.len() >= 8 && super::gauss_legendre::effective_nodes(abs, sq.value()) < 4.0 {
        Status::Unresolved(Unresolved::FewNodes)
    } else if unseen {
        Status::Unresolved(Unresolved::UnseenPeak)
    } else {
        Status::Resolved
    }
}

/// Smallest fixed budget from which the plain [`Adaptive`] rule spends a
/// [`CROSS_CHECK_SHARE`] of it on the warped rule, as a second
/// parameterisation that checks its error estimate (integrands with a
/// sampling map; see item 8 of [`Adaptive`]'s checks).
pub const CROSS_CHECK_MIN_BUDGET: u32 = 4096;

/// The plain rule's cross-check gets `1/CROSS_CHECK_SHARE` of the budget.
pub const CROSS_CHECK_SHARE: u32 = 8;

impl Adaptive {
    /// The plain rule with a fixed budget, cross-checked on the sampling
    /// map's square: `budget − budget/8` for the plain rule, the rest for
    /// the warped one. Where the two values differ by more than both error
    /// estimates together, channel-wise, the plain estimate's error grows to
    /// their difference: the warped square resolves what the plain square
    /// leaves in slivers its nodes never reach (the retro-reflection wedge
    /// of a rough lobe at the horizon, Beckmann `α = 0.3` at `θo = 89.9°`:
    /// `1.2·10⁻⁵` of the albedo within `Δφ ≈ 10⁻³` of the mirror azimuth
    /// below `μ = 0.002`) or where a lobe's support ends on a curve beside
    /// the kink lines (Phong `n = 1` at `θo = 89.5°`). The value stays the
    /// plain rule's.
    fn cross_checked<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        let side = budget / CROSS_CHECK_SHARE;
        let mut e = self.integrate_unchecked(g, budget - side)?;
        let w = self.warped().integrate_unchecked(g, side)?;
        if w.value.is_finite() && w.error.is_finite() && e.value.is_finite() && e.error.is_finite() {
            e.error = WideOf::<I>::from_fn(|i| {
                let d = (e.value.channel(i) - w.value.channel(i)).abs();
                let own = e.error.channel(i);
                if d > own + w.error.channel(i) {
                    d.max(own)
                } else {
                    own
                }
            });
        }
        e.evaluations += w.evaluations;
        Ok(e)
    }

    /// [`Integrator::integrate`] without the cross-check on the map's
    /// square (for [`Auto`](super::Auto), which falls back to the warped
    /// rule itself when the plain one is unresolved).
    pub(crate) fn integrate_unchecked<I: Integrand>(
        &self,
        g: &I,
        budget: u32,
    ) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        self.integrate_impl(g, budget, None).map(|(e, _)| e)
    }
}

impl Integrator for Adaptive {
    fn integrate<I: Integrand>(&self, g: &I, budget: u32) -> Result<Estimate<WideOf<I>>, IntegrateError> {
        if !self.warped && g.has_sampling_map() && budget >= CROSS_CHECK_MIN_BUDGET {
            return self.cross_checked(g, budget);
        }
        self.integrate_unchecked(g, budget)
    }

    /// One staged run with the budget
    /// `min(max_budget, MAX_ADAPTIVE_EVALUATIONS)`: the rule refines until its
    /// error estimate is `≤ 8 tol` (its `|I₇ − I₅|` overstates the degree-7
    /// value's error), then goes on until the evaluations have doubled and
    /// proposes the value if it moved by `≤ tol`. On the plain square the
    /// candidate stands only if a run from scratch at twice its evaluations
    /// agrees within `tol` and an importance-sampled mean check does not
    /// contradict it; otherwise budget doubling from scratch takes over. On
    /// the warped square (whose stages and fresh runs share the map's seams
    /// and kinks, and whose fresh run refines the same regions) it stands
    /// only if a staged run with other nodes agrees within `tol`, with the
    /// mean check: the warped rule's shifted twin (other cuts, bent
    /// coordinates; see `Adaptive::shifted`), the plain square split at the
    /// integrand's [kinks](Integrand::kinks), or its shifted twin (for an
    /// integrand not declared [smooth](Integrand::is_smooth), a rule of the
    /// plain square). The
    /// driver alternates such runs, each staged to a tolerance four times
    /// tighter than the method's last, until two of different rules agree or
    /// `max_budget`
    /// evaluations are spent in all. `start_budget` is
    /// not used (the staged run starts at the rule's minimum); the
    /// configured tolerances are ignored.
    fn to_tolerance<I: Integrand>(
        &self,
        g: &I,
        tol: f64,
        start_budget: u32,
        max_budget: u32,
    ) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
        check_tolerance_args(tol, start_budget, max_budget)?;
        let budget = max_budget.min(MAX_ADAPTIVE_EVALUATIONS);
        let (e, confirmed) = self.integrate_impl(g, budget, Some(tol))?;
        let cap_stop = if budget < max_budget {
            StopReason::IntegratorCap
        } else {
            StopReason::MaxBudget
        };
        let fresh = Adaptive {
            rel_tol: 0.0,
            abs_tol: 0.0,
            warped: self.warped,
            shifted: self.shifted,
            unsplit: self.unsplit,
        };
        if confirmed.is_none() || !e.is_resolved() {
            return Ok(ToleranceOutcome {
                estimate: e,
                budget,
                stop: cap_stop,
                total_evaluations: e.evaluations,
                confirmation: None,
                runs: 1,
            });
        }
        // On the warped square, the candidate's stages and a run from
        // scratch share the sampling map, and with it the map's seams (a
        // mixture map steps at `u₀ = p`) and kinks: they can converge to the
        // same wrong value. The confirmation comes from the plain square
        // (see `confirm::cross_confirm`).
        // On the plain square with a sampling map, two rules of that square
        // can miss the same lobe squeezed against the horizon (GGX α = 0.01
        // at θo = 89.9°: a run from scratch agreed with the candidate to
        // 1.6·10⁻⁶ on 0.96180, the truth is 0.96557, and the mean check's
        // 4σ covered the difference): the confirmation comes from the
        // sampling map's square too.
        if self.warped || g.has_sampling_map() {
            let first = confirm::Candidate {
                estimate: e,
                family: if self.warped {
                    confirm::Family::Warped
                } else {
                    confirm::Family::Plain
                },
            };
            let spent = confirm::Spent {
                evaluations: e.evaluations,
                runs: 1,
            };
            let mut out = confirm::cross_confirm(g, tol, max_budget, Some(first), Some(e), spent, false)?;
            if out.stop == StopReason::MaxBudget {
                out.stop = cap_stop;
            }
            return Ok(out);
        }
        // The staged run's confirmation compares it with its own earlier
        // stage, whose regions it shares: a feature neither stage's nodes
        // reached fools both alike (the Kulla–Conty mixture map at θo = 85°:
        // 0.9891 ± 2.5·10⁻⁴ claimed for 10⁻³, the albedo ≈ 0.9999). So the
        // candidate is also compared with a run from scratch at twice its
        // evaluations, which refines in another order (its budget decides
        // when the region table fills), and with an importance-sampled
        // estimate through the integrand's map (a mean check of a quarter of
        // the evaluations spent, between 64 and 65,536 draws of a rank-1
        // lattice, independent of every node), which contradicts a candidate
        // off by more than `tol + 4σ + |P|/n`.
        let b2 = u32::try_from(2 * e.evaluations).unwrap_or(u32::MAX).min(budget);
        let e2 = fresh.integrate(g, b2)?;
        let d = acc::abs_diff(e.value, e2.value);
        let mut spent = e.evaluations + e2.evaluations;
        let mut agrees = e2.is_resolved() && acc::max_abs(d) <= tol;
        if agrees && g.has_sampling_map() {
            let n = u32::try_from(spent / 4)
                .unwrap_or(u32::MAX)
                .clamp(probe::MEAN_CHECK_MIN_POINTS, CONFIRM_MAX_DRAWS);
            let m = probe::MeanCheck::take(g, n)?;
            spent += n as u64;
            agrees = m
                .judge(Status::Resolved, e.value, WideOf::<I>::splat(tol))
                .is_resolved();
        }
        if agrees {
            return Ok(ToleranceOutcome {
                estimate: e,
                budget,
                stop: StopReason::ToleranceReached,
                total_evaluations: spent,
                confirmation: Some(d),
                runs: 2,
            });
        }
        // Not confirmed: budget doubling from scratch (every run refined to
        // its whole budget, confirmed against the previous one).
        let start = u32::try_from(2 * e2.evaluations).unwrap_or(u32::MAX).min(budget);
        let mut out = by_doubling(&fresh, g, tol, start.max(self.min_budget()), budget)?;
        out.total_evaluations += spent;
        out.runs += 2;
        if out.stop == StopReason::MaxBudget {
            out.stop = cap_stop;
        }
        Ok(out)
    }

    fn name(&self) -> &'static str {
        if self.warped {
            "adaptive-warped"
        } else {
            "adaptive"
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The region tables sized by the budget give the same results, bit for
    /// bit, as the largest table, up to the largest budget of each
    /// (plain and warped runs that never converge: they split to the end).
    #[test]
    fn region_tables_sized_by_the_budget_give_the_same_bits() {
        let f = |p: &[[f64; 2]], out: &mut [f64]| {
            for (o, &[x, y]) in out.iter_mut().zip(p) {
                *o = 1.0 / (1e-3 + (x - 0.3) * (x - 0.3) + (y - 0.7) * (y - 0.7))
                    + if x > 0.9 { 0.0 } else { 1.0 };
            }
            Ok(())
        };
        for a in [
            Adaptive::new(1e-12, 0.0).unwrap(),
            Adaptive::new(1e-12, 0.0).unwrap().warped(),
        ] {
            for budget in [a.min_budget(), 500, 1000, 1024, TINY_REGIONS_BUDGET] {
                let max = a
                    .run_with::<f64, MAX_REGIONS>(budget, &[], 1, None, f, None)
                    .unwrap();
                assert_eq!(
                    a.run_with::<f64, TINY_REGIONS>(budget, &[], 1, None, f, None)
                        .unwrap(),
                    max,
                    "{budget}"
                );
                assert_eq!(
                    a.run_with::<f64, SMALL_REGIONS>(budget, &[], 1, None, f, None)
                        .unwrap(),
                    max,
                    "{budget}"
                );
            }
            for budget in [TINY_REGIONS_BUDGET + 1, 1300, SMALL_REGIONS_BUDGET] {
                let max = a
                    .run_with::<f64, MAX_REGIONS>(budget, &[], 1, None, f, None)
                    .unwrap();
                assert_eq!(
                    a.run_with::<f64, SMALL_REGIONS>(budget, &[], 1, None, f, None)
                        .unwrap(),
                    max,
                    "{budget}"
                );
            }
        }
    }

    #[test]
    fn genz_malik_degrees() {
        // Degree-7 rule exact for x^a y^b, a+b ≤ 7; degree-5 for a+b ≤ 5.
        let pts = gm_points();
        for a in 0..8i32 {
            for b in 0..(8 - a) {
                let exact = |k: i32| if k % 2 == 1 { 0.0 } else { 2.0 / (k as f64 + 1.0) };
                let ex = exact(a) * exact(b);
                let q7: f64 = pts
                    .iter()
                    .map(|&(x, y, c)| 4.0 * W7[c] * libm::pow(x, a as f64) * libm::pow(y, b as f64))
                    .sum();
                assert!((q7 - ex).abs() < 1e-14, "deg7 {a} {b}: {q7} vs {ex}");
                if a + b <= 5 {
                    let q5: f64 = pts
                        .iter()
                        .filter(|p| p.2 < 4)
                        .map(|&(x, y, c)| 4.0 * W5[c] * libm::pow(x, a as f64) * libm::pow(y, b as f64))
                        .sum();
                    assert!((q5 - ex).abs() < 1e-14, "deg5 {a} {b}: {q5} vs {ex}");
                }
            }
        }
    }

    /// The piecewise map of the plain square: the inverse undoes the
    /// forward map, the Jacobian integrates to the area `2π` of the
    /// `(μ, φ)` domain, and the kink lines fall on the first cuts.
    #[test]
    fn plain_map_puts_kinks_on_the_cuts() {
        let k = Some(super::super::Kinks { mu: 0.3, phi: 1.0 });
        for (cut, bend) in [(FIRST_CUT, 0.0), (SHIFTED_CUT, SHIFTED_BEND)] {
            for pole in [true, false] {
                let m = PlainMap::new(k, cut, PHI_OFFSET, bend).with_pole(pole);
                let (mu, phi, _) = m.forward(cut, 0.0);
                assert!((mu - 0.3).abs() < 1e-12, "{mu}");
                assert!((libm::cos(phi - 1.0)).abs() < 1e-12, "{phi}");
                let (_, phi, _) = m.forward(0.2, cut);
                assert!((libm::cos(phi - 1.0)).abs() < 1e-12, "{phi}");
                // Two-point Gauss sums in `x`, midpoint sums in `b`, on each
                // piece: the Jacobian is a product of a cubic in `x` (the bend
                // times the pole piece's `2(1 − μk)(1 − u)`) and a factor linear
                // in `b` within a piece, so they are exact there.
                let n = 100;
                let g2 = 0.5 / libm::sqrt(3.0);
                let mut area = 0.0;
                let pieces = [(0.0, cut), (cut, 1.0)];
                for &(x0, x1) in &pieces {
                    for &(b0, b1) in &pieces {
                        for i in 0..n {
                            for (j, gx) in (0..2 * n).map(|j| (j / 2, if j % 2 == 0 { -g2 } else { g2 })) {
                                let x = x0 + (x1 - x0) * (i as f64 + 0.5 + gx) / n as f64;
                                let b = b0 + (b1 - b0) * (j as f64 + 0.5) / n as f64;
                                let (mu, phi, jac) = m.forward(x, b);
                                area += 0.5 * jac * (x1 - x0) * (b1 - b0) / (n * n) as f64;
                                let w = glam::Vec3::new(
                                    (libm::sqrt(1.0 - mu * mu) * libm::cos(phi)) as f32,
                                    (libm::sqrt(1.0 - mu * mu) * libm::sin(phi)) as f32,
                                    mu as f32,
                                );
                                let (x2, b2, j2) = m.inverse(w);
                                assert!(
                                    (x2 - x).abs() < 1e-5 && (b2 - b).abs() < 1e-5,
                                    "{x} {b} → {x2} {b2}"
                                );
                                assert!((j2 - jac).abs() < 1e-4 * jac, "{jac} vs {j2}");
                            }
                        }
                    }
                }
                assert!((area - core::f64::consts::TAU).abs() < 1e-9, "{area}");
            }
        }
    }

    /// `g = |μ − m|` with its kink a sliver from the horizon (`m = 0.003`,
    /// as the Oren–Nayar family's `μi = μo` at θo ≈ 89.8°): closed form
    /// `2π (m² + (1 − m)²)/2`. Told where the kink is, the plain rule meets
    /// `10⁻⁷` and `Auto` reaches `10⁻⁴` and `10⁻⁶` within 10 × the
    /// tolerance. (Untold, every rule on the plain square extrapolates the
    /// linear part over the sliver `[0, m]`, whose nodes none of them
    /// places: `Auto` then claims `3.1227431 ± 5.6·10⁻⁷` at `10⁻⁶` against
    /// `3.1227996` — the limit of a kink the integrand does not state.)
    #[test]
    fn a_kink_near_the_horizon_is_split_at() {
        struct Kinked(bool);
        impl Integrand for Kinked {
            type Spectrum = f32;
            fn eval(&self, w: glam::Vec3) -> f32 {
                (w.z - 0.003).abs()
            }
            fn kinks(&self) -> Option<super::super::Kinks> {
                self.0.then_some(super::super::Kinks { mu: 0.003, phi: 0.0 })
            }
        }
        let m = 0.003f64;
        let exact = core::f64::consts::PI * (m * m + (1.0 - m) * (1.0 - m));
        let a = Adaptive::new(0.0, 0.0).unwrap();
        let e = a.integrate(&Kinked(true), 4096).unwrap();
        assert!((e.value - exact).abs() < 1e-6, "{e:?} vs {exact}");
        assert!((e.value - exact).abs() <= e.error.max(1e-7), "{e:?} vs {exact}");
        for tol in [1e-4, 1e-6] {
            let out = super::super::integrate_to_tolerance(
                &super::super::Auto::new(),
                &Kinked(true),
                tol,
                64,
                1 << 22,
            )
            .unwrap();
            let err = (out.estimate.value - exact).abs();
            assert!(out.reached(), "{tol}: {out:?}");
            assert!(
                err <= 10.0 * out.estimate.error.max(tol),
                "{tol}: {out:?} vs {exact}"
            );
        }
    }

    #[test]
    fn rejects_bad_config() {
        assert!(Adaptive::new(f64::NAN, 0.0).is_err());
        assert!(Adaptive::new(0.0, -1.0).is_err());
        assert!(Adaptive::new(0.0, 0.0).is_ok());
    }
}
