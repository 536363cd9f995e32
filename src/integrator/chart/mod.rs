//! Charts of the hemisphere for the nested grid of [`Auto`](super::Auto):
//! maps `(x, t) ∈ [0, 1]² ↦ (ω, J = dω/(dx dt))` that make a peaked lobe
//! smooth, so that Clenshaw–Curtis in `x` times the trapezoid rule in the
//! periodic `t` converge exponentially on it.
//!
//! | file | chart | for |
//! |---|---|---|
//! | [`peak`] | polar coordinates about the lobe's peak, logarithmic radius clipped at the horizon, stretched by the lobe's aspect | lobes whose peak is well above the horizon |
//! | [`product`] | the plain `(μ, φ)` hemisphere with a sinh warp of `μ` and a periodised sinh warp of `φ` about the peak | lobes squeezed against the horizon (grazing views) |
//!
//! In both, the grid's last `μ` row (`μ_i = 1`) is a single direction —
//! the peak chart's pole, the product chart's zenith — which the grid
//! evaluates once and weights by each node's Jacobian.

pub(crate) mod peak;
pub(crate) mod product;

pub(crate) use peak::PeakChart;
pub(crate) use product::ProductChart;

use glam::Vec3;

/// A chart the grid can use instead of the plain hemisphere.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Chart {
    /// See [`PeakChart`].
    Peak(PeakChart),
    /// See [`ProductChart`].
    Product(ProductChart),
}

impl Chart {
    /// `(ω, J)` at the grid's node `(μ_i, t)`: `μ_i = 1` is the row the grid
    /// evaluates once ([`Chart::pole`]).
    pub(crate) fn map(&self, mu: f64, t: f64) -> (Vec3, f64) {
        match self {
            // The peak chart's radius `x = 1 − μ_i`: the pole at `μ_i = 1`.
            Chart::Peak(c) => c.map(1.0 - mu, t),
            Chart::Product(c) => c.map(mu, t),
        }
    }

    /// The direction of the row `μ_i = 1` (the same for every `t`).
    pub(crate) fn pole(&self) -> Vec3 {
        match self {
            Chart::Peak(c) => c.pole(),
            Chart::Product(_) => Vec3::Z,
        }
    }

    /// The typical relative change of the integrand when a node's direction
    /// is rounded to `f32` (see each chart).
    pub(crate) fn rounding(&self) -> f64 {
        match self {
            Chart::Peak(c) => c.rounding(),
            Chart::Product(c) => c.rounding(),
        }
    }

    /// The chart's twin: the same peak with its widths scaled by
    /// [`TWIN_WIDTH`], so that no node of a grid on it lies where a node of
    /// the same grid on `self` does. A value of a smooth integrand that
    /// the two grids agree on is confirmed by two parameterisations.
    pub(crate) fn twin(&self) -> Option<Chart> {
        match self {
            Chart::Peak(c) => c.scaled(TWIN_WIDTH).map(Chart::Peak),
            Chart::Product(c) => c.scaled(TWIN_WIDTH).map(Chart::Product),
        }
    }
}

/// The width ratio of a chart's [twin](Chart::twin): irrational, far from
/// 1 and from the grids' refinement ratio 2.
pub(crate) const TWIN_WIDTH: f64 = 0.618_033_988_749_894_9;

/// `∫∫ f(ω) J dx dt` for a chart `map(x, t) = (ω, J)` (tests): composite
/// Simpson in `x` (the Jacobians are smooth) times the trapezoid rule in the
/// periodic `t`; `nx` even.
#[cfg(test)]
pub(crate) fn simpson_trapezoid(
    map: impl Fn(f64, f64) -> (Vec3, f64),
    f: impl Fn(Vec3) -> f64,
    nx: usize,
    nt: usize,
) -> f64 {
    let mut s = 0.0;
    for i in 0..=nx {
        let x = i as f64 / nx as f64;
        let wx = if i == 0 || i == nx {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        for k in 0..nt {
            let (w, j) = map(x, k as f64 / nt as f64);
            s += wx * f(w) * j;
        }
    }
    s / (3.0 * nx as f64 * nt as f64)
}
