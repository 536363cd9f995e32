//! Shared internals of the integrators: channel-wise compensated sums,
//! shifted-data moment accumulators, the hemisphere direction of a point
//! `(μ, φ)` and the rounding of unit-square coordinates to `f32` (the
//! chunked evaluation of integrand values is in [`super::chunk`]).

use super::{MIN_EFFECTIVE_SAMPLES, MIN_HITS, Status, Unresolved};
use crate::spectrum::WideSpectrum;
use glam::Vec3;

/// Channel-wise Neumaier compensated sum of wide spectra
/// (Neumaier 1974, ZAMM 54; same scheme as [`crate::math::CompensatedSum`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WideSum<W> {
    sum: W,
    c: W,
}

impl<W: WideSpectrum> WideSum<W> {
    #[inline]
    pub(crate) fn new() -> Self {
        Self {
            sum: W::splat(0.0),
            c: W::splat(0.0),
        }
    }

    #[inline]
    pub(crate) fn add(&mut self, x: W) {
        let s = self.sum;
        let t = s.zip(x, |a, b| a + b);
        let c = W::from_fn(|i| {
            let (a, b, ti) = (s.channel(i), x.channel(i), t.channel(i));
            let d = if a.abs() >= b.abs() {
                (a - ti) + b
            } else {
                (b - ti) + a
            };
            self.c.channel(i) + d
        });
        self.sum = t;
        self.c = c;
    }

    #[inline]
    pub(crate) fn value(&self) -> W {
        self.sum.zip(self.c, |a, b| a + b)
    }
}

/// Sample moments with the shifted-data algorithm: with a fixed shift `K`
/// (the first observation), `mean = K + Σd/n` and
/// `s² = (Σd² − (Σd)²/n)/(n − 1)` where `d = x − K` (Chan, Golub & LeVeque
/// 1983, "Algorithms for computing the sample variance", Am. Stat. 37(3)).
/// Both sums are compensated.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Moments<W> {
    shift: W,
    d: WideSum<W>,
    d2: WideSum<W>,
    n: u64,
    /// What the status of a Monte Carlo estimate is judged from.
    pub(crate) diag: SampleDiagnostics<W>,
}

/// Support and tail diagnostics of a set of Monte Carlo samples `xₖ`: the
/// number of non-zero samples ("hits") and, per channel, `Σ|x|` and `Σx²`,
/// from which the effective sample size `(Σ|x|)²/Σx²` follows (Kong 1992;
/// Owen 2013, §9.3: the number of equally weighted samples carrying the
/// same information; it collapses when a few samples dominate the sum).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SampleDiagnostics<W> {
    hits: u64,
    abs: WideSum<W>,
    sq: WideSum<W>,
}

impl<W: WideSpectrum> SampleDiagnostics<W> {
    #[inline]
    pub(crate) fn new() -> Self {
        Self {
            hits: 0,
            abs: WideSum::new(),
            sq: WideSum::new(),
        }
    }

    #[inline]
    pub(crate) fn push(&mut self, x: W) {
        if x.map(f64::abs).max_channel() > 0.0 {
            self.hits += 1;
        }
        self.abs.add(x.map(f64::abs));
        self.sq.add(x.map(|v| v * v));
    }

    /// Adds `hits` non-zero samples whose `Σ|x|` and `Σx²` are `abs`, `sq`
    /// (the plain sums of a chunk, see [`Moments::push_chunk`]).
    #[inline]
    fn add_sums(&mut self, hits: u64, abs: W, sq: W) {
        self.hits += hits;
        self.abs.add(abs);
        self.sq.add(sq);
    }

    /// The `f32` rounding floor of a mean of `n` samples, per channel:
    /// `2⁻²³ Σ|x| / n`. Every sample is an `f32` integrand value carrying up
    /// to about one ulp of systematic rounding, which no variance estimate
    /// sees; the quadrature rules add the same floor (`2⁻²³ Σ|w g|`).
    pub(crate) fn rounding_floor(&self, n: u64) -> W {
        let n = n.max(1) as f64;
        self.abs.value().map(|a| a / n * F32_FLOOR)
    }

    /// The resolution floor of a mean of `n` samples, per channel:
    /// `Σ|x| / n² = mean|x| / n`. A part of the integrand that `n` draws hit
    /// with probability `p ≲ 1/n` is likely never drawn (`P = (1 − p)ⁿ`), and
    /// then no variance estimate sees it: when its estimator values are of
    /// the size of the others (the typical case: a sliver of the sampling
    /// square where an importance-sampling map leaves the support, while
    /// every other weight is ≈ 1), it moves the mean by about `p · mean`.
    /// Adding `mean/n` covers such unseen events up to `p ≈ 3/n` at 3σ; a
    /// rare event with a *large* estimator value (a peak the sampling
    /// misses) is not bounded by it and is what the peak probe flags.
    pub(crate) fn resolution_floor(&self, n: u64) -> W {
        let n = n.max(1) as f64;
        self.abs.value().map(|a| a / (n * n))
    }

    /// [`rounding_floor`](Self::rounding_floor) +
    /// [`resolution_floor`](Self::resolution_floor): what a Monte Carlo
    /// estimate adds to its standard error.
    pub(crate) fn floors(&self, n: u64) -> W {
        add(self.rounding_floor(n), self.resolution_floor(n))
    }

    /// Adds another set's diagnostics.
    pub(crate) fn merge(&mut self, o: &Self) {
        self.hits += o.hits;
        self.abs.add(o.abs.value());
        self.sq.add(o.sq.value());
    }

    /// The status: no hit → `NoSupportSeen`; fewer than [`MIN_HITS`] →
    /// `FewHits`; an effective sample size below
    /// [`MIN_EFFECTIVE_SAMPLES`] in any channel with a non-zero sum →
    /// `HeavyTail`; else resolved.
    pub(crate) fn status(&self) -> Status {
        if self.hits == 0 {
            return Status::Unresolved(Unresolved::NoSupportSeen);
        }
        if self.hits < MIN_HITS {
            return Status::Unresolved(Unresolved::FewHits);
        }
        let (a, q) = (self.abs.value(), self.sq.value());
        for i in 0..W::CHANNELS {
            let (a, q) = (a.channel(i), q.channel(i));
            if q > 0.0 && a * a / q < MIN_EFFECTIVE_SAMPLES {
                return Status::Unresolved(Unresolved::HeavyTail);
            }
        }
        Status::Resolved
    }
}

impl<W: WideSpectrum> Moments<W> {
    #[inline]
    pub(crate) fn new() -> Self {
        Self {
            shift: W::splat(0.0),
            d: WideSum::new(),
            d2: WideSum::new(),
            n: 0,
            diag: SampleDiagnostics::new(),
        }
    }

    #[inline]
    pub(crate) fn push(&mut self, x: W) {
        if self.n == 0 {
            self.shift = x;
        }
        let d = x.zip(self.shift, |a, k| a - k);
        self.d.add(d);
        self.d2.add(d.map(|v| v * v));
        self.n += 1;
        self.diag.push(x);
    }

    /// [`push`](Self::push) for each of `xs` in order, with the sums of the
    /// chunk formed plainly in `f64` and then added to the compensated
    /// totals once: for chunks of at most [`CHUNK`](super::chunk::CHUNK) = 64
    /// samples the plain sums carry a relative error `≤ 64 ε₆₄ ≈ 1.4·10⁻¹⁴`
    /// of `Σ|term|` (Higham 2002, *Accuracy and Stability of Numerical
    /// Algorithms*, §4.2), nine orders below the `f32` resolution of the
    /// samples, at a quarter of the cost of four compensated additions per
    /// sample.
    #[inline]
    pub(crate) fn push_chunk(&mut self, xs: &[W]) {
        let Some(&first) = xs.first() else {
            return;
        };
        if self.n == 0 {
            self.shift = first;
        }
        let k = self.shift;
        let zero = W::splat(0.0);
        let (mut d, mut d2, mut abs, mut sq, mut hits) = (zero, zero, zero, zero, 0u64);
        for &x in xs {
            let dx = x.zip(k, |a, b| a - b);
            d = d.zip(dx, |s, v| s + v);
            d2 = d2.zip(dx, |s, v| s + v * v);
            let ax = x.map(f64::abs);
            hits += u64::from(ax.max_channel() > 0.0);
            abs = abs.zip(ax, |s, v| s + v);
            sq = sq.zip(x, |s, v| s + v * v);
        }
        self.d.add(d);
        self.d2.add(d2);
        self.n += xs.len() as u64;
        self.diag.add_sums(hits, abs, sq);
    }

    #[inline]
    pub(crate) fn count(&self) -> u64 {
        self.n
    }

    /// The sample mean (zero when empty).
    pub(crate) fn mean(&self) -> W {
        if self.n == 0 {
            return W::splat(0.0);
        }
        let n = self.n as f64;
        self.shift.zip(self.d.value(), |k, d| k + d / n)
    }

    /// The standard error of the mean, `s/√n` (zero for `n < 2`).
    pub(crate) fn standard_error(&self) -> W {
        if self.n < 2 {
            return W::splat(0.0);
        }
        let n = self.n as f64;
        let sd = self.d.value();
        let sd2 = self.d2.value();
        W::from_fn(|i| {
            let a = sd.channel(i);
            let var = ((sd2.channel(i) - a * a / n) / (n - 1.0)).max(0.0);
            libm::sqrt(var / n)
        })
    }
}

/// Direction for `cos θ = mu`, azimuth `phi` (PBRT 4th ed. §3.8.3):
/// `(sin θ cos φ, sin θ sin φ, cos θ)` with `sin θ = √(1 − μ²)`.
#[inline]
pub(crate) fn direction(mu: f64, phi: f64) -> Vec3 {
    let mu = mu.clamp(0.0, 1.0);
    let s = libm::sqrt((1.0 - mu * mu).max(0.0));
    let (sp, cp) = libm::sincos(phi);
    Vec3::new((s * cp) as f32, (s * sp) as f32, mu as f32)
}

/// Rounds `x ∈ [0, 1]` to an `f32` in `[0, 1)` (at most `1 − 2⁻²⁴`).
#[inline]
pub(crate) fn to_unit_f32(x: f64) -> f32 {
    let v = x.clamp(0.0, 1.0) as f32;
    v.min(crate::math::ONE_MINUS_EPSILON)
}

/// Channel-wise `|a − b|`.
#[inline]
pub(crate) fn abs_diff<W: WideSpectrum>(a: W, b: W) -> W {
    a.zip(b, |x, y| (x - y).abs())
}

/// Channel-wise sum.
#[inline]
pub(crate) fn add<W: WideSpectrum>(a: W, b: W) -> W {
    a.zip(b, |x, y| x + y)
}

/// Largest channel of `|w|`.
#[inline]
pub(crate) fn max_abs<W: WideSpectrum>(w: W) -> f64 {
    (0..W::CHANNELS).fold(0.0f64, |m, i| m.max(w.channel(i).abs()))
}

/// Whether a value is non-zero in some channel (the integrand's support).
#[inline]
pub(crate) fn nonzero<W: WideSpectrum>(v: &W) -> bool {
    max_abs(*v) > 0.0
}

/// Relative accuracy of the `f32` integrand values and directions: the
/// integrand is evaluated in single precision, so a quadrature sum
/// `Σ wₖ g(ωₖ)` cannot be trusted below about `2⁻²³ Σ |wₖ g(ωₖ)|`
/// (unit roundoff of the value plus that of the rounded node direction).
pub(crate) const F32_FLOOR: f64 = f32::EPSILON as f64;

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::rng::Pcg32;

    /// `push_chunk` over chunks of 64 gives the moments and diagnostics of
    /// `push` one by one, to the plain-sum error it documents (here a
    /// sample with heavy tails, zeros and a large offset: the hard case of
    /// the shifted-data sums).
    #[test]
    fn push_chunk_matches_push() {
        let mut rng = Pcg32::with_stream(7, 11);
        let xs: std::vec::Vec<f64> = (0..10_000)
            .map(|k| {
                let u = rng.next_f64();
                if k % 5 == 0 { 0.0 } else { 1e3 + 1.0 / (u + 1e-3) }
            })
            .collect();
        let (mut one, mut chunked) = (Moments::<f64>::new(), Moments::<f64>::new());
        for &x in &xs {
            one.push(x);
        }
        for c in xs.chunks(64) {
            chunked.push_chunk(c);
        }
        chunked.push_chunk(&[]);
        assert_eq!(one.count(), chunked.count());
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * a.abs().max(b.abs());
        assert!(
            close(one.mean(), chunked.mean()),
            "{} vs {}",
            one.mean(),
            chunked.mean()
        );
        assert!(close(one.standard_error(), chunked.standard_error()));
        let n = one.count();
        assert!(close(one.diag.floors(n), chunked.diag.floors(n)));
        assert_eq!(one.diag.hits, chunked.diag.hits);
        assert_eq!(one.diag.status(), chunked.diag.status());
    }
}
