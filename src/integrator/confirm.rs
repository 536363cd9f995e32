//! Confirmation of a to-tolerance candidate by an unrelated rule on another
//! parameterisation ([`cross_confirm`]).
//!
//! A candidate that confirms itself — a nested grid whose coarser levels
//! agree, a staged adaptive run whose later stage agrees with an earlier one,
//! a run from scratch on the same square — can be fooled alike by every one
//! of its stages where the integrand is not what the rule's error estimate
//! assumes: a kink (the Oren–Nayar family at `μi = μo` and `cos Δφ = 0`, a
//! dielectric's critical angle, a table's cells), a lobe cut by the horizon,
//! or the seam of a mixture sampling map (a composite picks its lobe by
//! `u₀ < p`, so the warped integrand steps at `u₀ = p`). The stages converge
//! to the same wrong value and agree with each other.
//!
//! The evidence accepted here comes from a second method whose errors do not
//! follow the first one's: staged [`Adaptive`] Genz–Malik runs from scratch
//! on the *plain* `(μ, φ)` square (no seams: the plain square does not go
//! through the sampling map; split at the integrand's
//! [kinks](super::Integrand::kinks), where the Oren–Nayar family switches
//! terms), on the *warped* square (a smooth map for a single lobe), and on a
//! shifted twin of each (other first cuts, bent coordinates: no node in
//! common). A candidate stands when a run of an independent rule differs
//! from it by at most `tol` (every channel); where the integrand is not
//! declared smooth the two must come from different squares, or three rules
//! of the plain square must agree (one of them not split at the kinks). A
//! wrong candidate stands only if unrelated rules make the same error to
//! within `tol`.

use super::acc;
use super::adaptive::{Adaptive, MAX_ADAPTIVE_EVALUATIONS};
use super::{Estimate, Integrand, IntegrateError, StopReason, ToleranceOutcome, WideOf, probe};
use crate::spectrum::WideSpectrum;

/// The parameterisation (and rule) a candidate came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Family {
    /// The nested Clenshaw–Curtis × trapezoid grid on the plain square.
    Grid,
    /// A grid on a chart centred on the lobe's peak.
    Chart,
    /// The staged Genz–Malik rule on the plain `(μ, φ)` square.
    Plain,
    /// The same on the plain square with other cuts and azimuth offset
    /// ([`Adaptive::shifted`]).
    Shifted,
    /// The shifted plain rule without the split at the kinks
    /// ([`Adaptive::unsplit`]).
    Unsplit,
    /// The staged Genz–Malik rule on the sampling map's square.
    Warped,
    /// The same on the sampling map's square with other cuts and bent
    /// coordinates ([`Adaptive::shifted`]).
    WarpedShifted,
}

impl Family {
    /// Whether a candidate of `self` may be confirmed by one of `other`:
    /// different rules or parameterisations, which share no nodes (the
    /// plain grid and the plain adaptive rule share the square but not the
    /// rule: the grid's estimate assumes global smoothness, the adaptive
    /// rule refines locally; the plain and the shifted adaptive rules split
    /// at the same kink lines but place every node elsewhere).
    ///
    /// Where the integrand is not smooth (`smooth = false`), two rules on
    /// the same square are not enough: the warped rule and its shifted twin
    /// share the sampling map and its seams, and the rules of the plain
    /// square (the grid, the plain and the shifted rule) can miss the same
    /// part of a lobe squeezed against the horizon (a coat past its critical
    /// angle at θo = 89.7°: the plain and the shifted rule agreed to
    /// `4·10⁻⁷` and were both `9·10⁻⁴` low). A candidate of one square is
    /// then confirmed only by one of the other. For a smooth integrand any
    /// two families confirm each other (GGX `α = 10⁻³`, which no rule of the
    /// plain square resolves, confirms on its own map).
    ///
    /// A smooth integrand with a sampling map still needs one rule off the
    /// plain square: two rules of the plain square can miss the same lobe
    /// squeezed against the horizon however smooth it is (GGX `α = 0.01`
    /// at θo = 89.9°: the plain and the shifted rule agreed to `1.6·10⁻⁶`
    /// on 0.96180 at `tol = 10⁻⁴`, the truth is 0.96557; the warped rules
    /// and the charts see the lobe). Without a sampling map the plain rules
    /// are all there is and confirm each other.
    ///
    /// `broad`: the caller's pilot found the lobe broad (peakiness at most
    /// [`NARROW_PEAKINESS`](super::auto::NARROW_PEAKINESS)), so that the
    /// rules of the plain square resolve it: for a smooth integrand their
    /// pairs then confirm each other again (the nested grid and the plain
    /// rule on a GGX α = 0.3 lobe at 0°, at a fifth of the cost of a warped
    /// partner).
    fn independent_of(self, other: Family, smooth: bool, has_map: bool, broad: bool) -> bool {
        if !has_map {
            return self != other;
        }
        if !smooth {
            return self.is_warped() != other.is_warped();
        }
        self != other && (broad || !(self.is_plain_square() && other.is_plain_square()))
    }
}

impl Family {
    /// Whether the rule runs on the sampling map's square.
    fn is_warped(self) -> bool {
        matches!(self, Family::Warped | Family::WarpedShifted)
    }

    /// Whether the rule runs on the plain `(μ, φ)` square.
    fn is_plain_square(self) -> bool {
        matches!(
            self,
            Family::Grid | Family::Plain | Family::Shifted | Family::Unsplit
        )
    }
}

/// With `e` (of the plain-square family `family`), three candidates of
/// three different plain-square families ([`Family::Grid`],
/// [`Family::Plain`], [`Family::Shifted`], [`Family::Unsplit`]) within
/// `tol` of each other: the largest difference (per channel) of `e` to the
/// other two.
fn plain_trio<W: WideSpectrum>(
    cands: &[Option<Candidate<W>>],
    e: &Estimate<W>,
    family: Family,
    tol: f64,
) -> Option<W> {
    let near = |a: W, b: W| acc::max_abs(acc::abs_diff(a, b)) <= tol;
    let plain_square = [Family::Grid, Family::Plain, Family::Shifted, Family::Unsplit];
    let others = || {
        cands
            .iter()
            .flatten()
            .filter(move |c| c.family != family && plain_square.contains(&c.family))
            .filter(move |c| near(c.estimate.value, e.value))
    };
    for a in others() {
        for b in others() {
            if a.family != b.family && near(a.estimate.value, b.estimate.value) {
                let (da, db) = (
                    acc::abs_diff(a.estimate.value, e.value),
                    acc::abs_diff(b.estimate.value, e.value),
                );
                return Some(da.zip(db, f64::max));
            }
        }
    }
    None
}

/// Most candidates kept.
const MAX_CANDIDATES: usize = 16;

/// Most staged runs of [`cross_confirm`].
const MAX_ATTEMPTS: u32 = 48;

/// How much tighter a method's next staged run refines after one that
/// produced a value (a candidate or not).
const ROUND_FACTOR: f64 = 4.0;

/// The evaluations the first attempt may spend at least (else four times
/// the first candidate's).
const FIRST_CAP: u64 = 4096;

/// A candidate: a resolved estimate with error `≤ tol`, confirmed by its
/// own method.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Candidate<W> {
    pub(crate) estimate: Estimate<W>,
    pub(crate) family: Family,
}

/// Bookkeeping of a to-tolerance run: evaluations and runs so far.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Spent {
    pub(crate) evaluations: u64,
    pub(crate) runs: u32,
}

/// Confirms `first` (if any) or finds and confirms a candidate with staged
/// [`Adaptive`] runs from scratch: on the plain square split at the
/// integrand's kinks ([`Family::Plain`]), its shifted twin
/// ([`Family::Shifted`]) and — with a sampling map — the warped square and
/// its shifted twin ([`Family::Warped`], [`Family::WarpedShifted`]). Each
/// attempt runs the method that has spent the fewest evaluations so far
/// (ties: the shifted warped rule first after a warped candidate, the
/// warped rules first after a chart's candidate or without one, the plain
/// rules first otherwise), staged to
/// its own tolerance `t` (`tol` at first, divided by 4 after each run that
/// produced a value) with at most `cap` evaluations (`max(4 × first's,
/// 4,096)`, quadrupled whenever an attempt ran out of it before meeting
/// `t`; at most [`MAX_ATTEMPTS`] attempts). A resolved run confirmed by its
/// own stages with error `≤ tol` is a candidate; the outcome is
/// [`StopReason::ToleranceReached`] as soon as two candidates of
/// [independent](Family::independent_of) families (or, for a non-smooth
/// integrand, three of the plain square: `plain_trio`) differ by `≤ tol`
/// (every channel) and — with a sampling map —
/// an importance-sampled mean check through the map does not contradict the
/// later one (see `probe::MeanCheck`). The later candidate is returned, its
/// error the larger of its own and the difference, `confirmation` the
/// difference. The runs spend at most `max_budget` evaluations in all (each
/// at most [`MAX_ADAPTIVE_EVALUATIONS`]); without two agreeing candidates
/// the stop is [`StopReason::MaxBudget`] (or [`StopReason::IntegratorCap`]
/// when a run was held below the budget left by the rule's own cap) with
/// the best estimate (resolved first, then the smallest error).
pub(crate) fn cross_confirm<I: Integrand>(
    g: &I,
    tol: f64,
    max_budget: u32,
    first: Option<Candidate<WideOf<I>>>,
    last: Option<Estimate<WideOf<I>>>,
    mut spent: Spent,
    broad: bool,
) -> Result<ToleranceOutcome<WideOf<I>>, IntegrateError> {
    let plain = Adaptive::new(0.0, 0.0)?;
    let warped = g.has_sampling_map().then(|| plain.warped());
    // Without a map there is no second square: the plain rules confirm
    // each other.
    let smooth = g.is_smooth() || warped.is_none();
    let has_map = warped.is_some();
    let mut cands: [Option<Candidate<WideOf<I>>>; MAX_CANDIDATES] = [None; MAX_CANDIDATES];
    let mut n = 0usize;
    if let Some(c) = first {
        if let Some(slot) = cands.first_mut() {
            *slot = Some(c);
        }
        n = 1;
    }
    // The methods, in the order they are tried when they have spent
    // alike: after a warped candidate its shifted twin (a narrow lobe the
    // plain square meets late), after a chart's candidate or without one
    // (narrow lobes) the warped rules, otherwise the plain rules first.
    let w = warped.map(|w| (w, Family::Warped));
    let ws = warped.map(|w| (w.shifted(), Family::WarpedShifted));
    let p = Some((plain, Family::Plain));
    let q = Some((plain.shifted(), Family::Shifted));
    // The third rule of the plain square, for non-smooth integrands only
    // (see `plain_trio`).
    let u = (!smooth).then(|| (plain.unsplit(), Family::Unsplit));
    let methods: [Option<(Adaptive, Family)>; 5] = match first.map(|c| c.family) {
        Some(Family::Warped) => [ws, p, q, u, w],
        Some(Family::Chart) | None => [w, ws, p, q, u],
        _ => [p, q, u, w, ws],
    };
    let mut last = last;
    let mut capped = false;
    // The randomised check (see `randomised_check`), once taken.
    let mut randomised: Option<Option<probe::MeanCheck<WideOf<I>>>> = None;
    // Per method: its next tolerance, the evaluations it spent, whether it
    // can do no better.
    let mut t = [tol; 5];
    let mut used = [0u64; 5];
    let mut exhausted = [false; 5];
    // Each attempt spends at most `cap` evaluations (quadrupled whenever an
    // attempt ran out of it): a method that stalls (a warped rule on a
    // seam) does not take the budget from one that converges.
    let mut cap = first.map_or(0, |c| 4 * c.estimate.evaluations).max(FIRST_CAP);
    for _attempt in 0..MAX_ATTEMPTS {
        // The method that spent least so far (ties: `methods` order).
        let Some(k) = (0..5)
            .filter(|&k| methods.get(k).is_some_and(Option::is_some) && exhausted.get(k) == Some(&false))
            .min_by_key(|&k| used.get(k).copied().unwrap_or(u64::MAX))
        else {
            break;
        };
        let (Some(&Some((rule, family))), Some(&tk)) = (methods.get(k), t.get(k)) else {
            break;
        };
        let left = (max_budget as u64).saturating_sub(spent.evaluations);
        if left < rule.min_budget() as u64 {
            break;
        }
        let limit = left.min(MAX_ADAPTIVE_EVALUATIONS as u64);
        capped |= limit < left;
        let budget = limit.min(cap).max(rule.min_budget() as u64) as u32;
        let (e, confirmed) = rule.staged(g, budget, tk)?;
        spent.evaluations += e.evaluations;
        spent.runs += 1;
        if let Some(u) = used.get_mut(k) {
            *u += e.evaluations;
        }
        // Without a confirmation the outcome reports the best estimate seen
        // (resolved first, then the smallest error), not the last attempt.
        let better = last.is_none_or(|l| {
            (e.is_resolved(), -acc::max_abs(e.error)) > (l.is_resolved(), -acc::max_abs(l.error))
        });
        if better {
            last = Some(e);
        }
        let own = confirmed.is_some() && e.is_resolved() && acc::max_abs(e.error) <= tol;
        if !own {
            if confirmed.is_none() {
                // Out of evaluations before meeting `t`: with a larger cap,
                // or, at the limit, never.
                if budget as u64 >= limit {
                    if let Some(x) = exhausted.get_mut(k) {
                        *x = true;
                    }
                } else {
                    cap = cap.saturating_mul(4);
                }
            } else {
                if let Some(x) = t.get_mut(k) {
                    *x = next_tolerance(tk, &e);
                }
            }
            continue;
        }
        if let Some(x) = t.get_mut(k) {
            *x = next_tolerance(tk, &e);
        }
        // A non-smooth integrand's plain-square candidate also stands when
        // three rules of the plain square (of the grid, the plain, the
        // shifted and the unsplit rule) agree within `tol`: three rules
        // with unrelated nodes, one of them not split at the kinks.
        let trio = (!smooth && !family.is_warped())
            .then(|| plain_trio(cands.get(..n).unwrap_or_default(), &e, family, tol))
            .flatten();
        let pairs = cands.iter().take(n).flatten().filter_map(|c| {
            if !c.family.independent_of(family, smooth, has_map, broad) {
                return None;
            }
            let d = acc::abs_diff(e.value, c.estimate.value);
            (acc::max_abs(d) <= tol).then_some(d)
        });
        for d in trio.into_iter().chain(pairs) {
            if !mean_check_agrees(g, &e, tol, &mut spent)? {
                continue;
            }
            return Ok(reached(e, d, d, spent, max_budget));
        }
        // A non-smooth integrand's pair of one square (two warped rules that
        // share the map's seams, or two plain rules that can miss the same
        // narrow lobe) stands on randomised evidence: an importance-sampled
        // estimate through the map with enough draws that its own 4σ bound
        // is at most half the tolerance, and within the other half of `e`.
        if !smooth {
            let near_same_square = cands.iter().take(n).flatten().find(|c| {
                c.family != family
                    && !c.family.independent_of(family, smooth, has_map, broad)
                    && acc::max_abs(acc::abs_diff(e.value, c.estimate.value)) <= tol
            });
            if near_same_square.is_some() && randomised.is_none() {
                randomised = Some(randomised_check(g, tol, max_budget, &mut spent)?);
            }
            if let Some(c) = near_same_square
                && let Some(Some(m)) = &randomised
                && let Some(d) = randomised_agrees(m, &e, tol)
            {
                let pair = acc::abs_diff(e.value, c.estimate.value);
                return Ok(reached(e, pair.zip(d, f64::max), d, spent, max_budget));
            }
        }
        let cand = Candidate { estimate: e, family };
        if let Some(slot) = cands.get_mut(n) {
            *slot = Some(cand);
            n += 1;
        } else if let Some(slot) = cands.get_mut(MAX_CANDIDATES - 1) {
            *slot = Some(cand);
        }
    }
    let zero = WideOf::<I>::splat(0.0);
    let e = last.unwrap_or(Estimate {
        value: zero,
        error: zero,
        evaluations: 0,
        status: super::Status::Unresolved(super::Unresolved::NoSupportSeen),
    });
    Ok(ToleranceOutcome {
        estimate: e,
        budget: max_budget,
        stop: if capped {
            StopReason::IntegratorCap
        } else {
            StopReason::MaxBudget
        },
        total_evaluations: spent.evaluations,
        confirmation: None,
        runs: spent.runs,
    })
}

/// The tolerance of a method's next staged run after one that produced `e`
/// at tolerance `t`: `min(t, ε)/4`, `ε` the run's own error estimate (every
/// channel's largest), so that the next run refines past the point where
/// this one stopped instead of repeating it (a run that met `t` with a
/// far smaller error would otherwise stop at the same node set).
fn next_tolerance<W: WideSpectrum>(t: f64, e: &Estimate<W>) -> f64 {
    let own = acc::max_abs(e.error);
    let t = if own.is_finite() && own > 0.0 {
        t.min(own)
    } else {
        t
    };
    t / ROUND_FACTOR
}

/// Draws of the pilot that sizes a randomised confirmation.
const RANDOMISED_PILOT: u32 = 4096;

/// Most draws of a randomised confirmation.
const RANDOMISED_MAX_DRAWS: u64 = 1 << 22;

/// The randomised check of [`cross_confirm`] (with a sampling map): a pilot
/// of [`RANDOMISED_PILOT`] lattice draws through the map estimates the
/// weight's variance `v` (the largest channel's); when `n = 80 v / tol²`
/// draws (so that `4σ ≈ 0.45 tol`) fit in the budget left and in
/// [`RANDOMISED_MAX_DRAWS`], they are taken. `None` when the check cannot be
/// afforded (a tight tolerance: the draws grow as `tol⁻²`) or is not usable
/// (too few non-zero draws). Taken at most once per driver run.
fn randomised_check<I: Integrand>(
    g: &I,
    tol: f64,
    max_budget: u32,
    spent: &mut Spent,
) -> Result<Option<probe::MeanCheck<WideOf<I>>>, IntegrateError> {
    if !g.has_sampling_map() {
        return Ok(None);
    }
    let left = (max_budget as u64).saturating_sub(spent.evaluations);
    if left < RANDOMISED_PILOT as u64 {
        return Ok(None);
    }
    let pilot = probe::MeanCheck::take(g, RANDOMISED_PILOT)?;
    spent.evaluations += RANDOMISED_PILOT as u64;
    if !pilot.usable {
        return Ok(None);
    }
    // The variance of one draw from the pilot's standard error.
    let s = acc::max_abs(pilot.sigma);
    let var = s * s * RANDOMISED_PILOT as f64;
    let need = libm::ceil(80.0 * var / (tol * tol)).max(RANDOMISED_PILOT as f64);
    let left = (max_budget as u64).saturating_sub(spent.evaluations);
    if need.is_nan() || need > RANDOMISED_MAX_DRAWS.min(left) as f64 {
        return Ok(None);
    }
    let n = need as u32;
    let m = probe::MeanCheck::take(g, n)?;
    spent.evaluations += n as u64;
    Ok(m.usable.then_some(m))
}

/// Whether the randomised check `m` confirms `e` to `tol`: in every channel
/// `4σ + |m|/n ≤ tol/2` and `|e − m| ≤ tol/2`. Then `|e − I| ≤ |e − m| +
/// |m − I| ≤ tol` unless the check's mean is more than 4σ off (a 4σ event
/// of the central limit theorem; the lattice draws are at least as accurate
/// as independent ones for weights of bounded variation). Returns
/// `|e − m| + 4σ + |m|/n` per channel, the bound claimed.
fn randomised_agrees<W: WideSpectrum>(m: &probe::MeanCheck<W>, e: &Estimate<W>, tol: f64) -> Option<W> {
    let nf = m.n as f64;
    let stands = (0..W::CHANNELS).all(|i| {
        let d = (e.value.channel(i) - m.mean.channel(i)).abs();
        4.0 * m.sigma.channel(i) + m.mean.channel(i).abs() / nf <= 0.5 * tol && d <= 0.5 * tol
    });
    let bound = acc::abs_diff(e.value, m.mean)
        .zip(m.sigma, |d, s| d + 4.0 * s)
        .zip(m.mean, |b, mm| b + mm.abs() / nf);
    stands.then_some(bound)
}

/// The outcome of a confirmed candidate `e`: [`StopReason::ToleranceReached`],
/// its error raised to `bound` where that is larger (per channel), the
/// confirmation `d`, every evaluation and run of `spent` counted.
pub(crate) fn reached<W: WideSpectrum>(
    mut e: Estimate<W>,
    bound: W,
    d: W,
    spent: Spent,
    max_budget: u32,
) -> ToleranceOutcome<W> {
    e.error = e.error.zip(bound, f64::max);
    e.evaluations = spent.evaluations;
    ToleranceOutcome {
        estimate: e,
        budget: max_budget,
        stop: StopReason::ToleranceReached,
        total_evaluations: spent.evaluations,
        confirmation: Some(d),
        runs: spent.runs,
    }
}

/// Most draws of the mean check of an agreeing pair.
const CONFIRM_MAX_DRAWS: u32 = 65_536;

/// With a sampling map: an importance-sampled estimate through the map (a
/// quarter of the evaluations spent, between 64 and 65,536 lattice draws)
/// does not contradict `e` by more than `tol + 4σ + |P|/n` (see
/// [`probe::MeanCheck::judge`]). Without a map: `true`.
pub(crate) fn mean_check_agrees<I: Integrand>(
    g: &I,
    e: &Estimate<WideOf<I>>,
    tol: f64,
    spent: &mut Spent,
) -> Result<bool, IntegrateError> {
    if !g.has_sampling_map() {
        return Ok(true);
    }
    let n = u32::try_from(spent.evaluations / 4)
        .unwrap_or(u32::MAX)
        .clamp(probe::MEAN_CHECK_MIN_POINTS, CONFIRM_MAX_DRAWS);
    let m = probe::MeanCheck::take(g, n)?;
    spent.evaluations += n as u64;
    Ok(m.judge(super::Status::Resolved, e.value, WideOf::<I>::splat(tol))
        .is_resolved())
}
