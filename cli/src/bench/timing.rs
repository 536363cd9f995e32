//! The inputs and the timing loop of `radiometry bench`, and the timed
//! passes (one `#[inline(never)]` function per path).

use radiometry::batch::Vec3Soa;
use radiometry::frame::spherical_direction;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample};
use std::time::{Duration, Instant};

/// A repetition lasts about `min_time / REP_SLICES` (at least one pass):
/// short repetitions give the best-of more chances to miss the machine's
/// other load.
pub(super) const REP_SLICES: u32 = 10;
/// Repetitions per measurement, at least (slow passes at n = 2²⁰ are one
/// pass per repetition).
pub(super) const MIN_REPS: u32 = 3;

/// Deterministic inputs of the largest size; every run uses a prefix.
///
/// The arrays of one layout share one allocation with staggered starts (AoS
/// `wi`, `wo` 192 B apart modulo 4 KiB; the six SoA components 64 B apart),
/// so that the input streams of a loop do not alias modulo 4 KiB (the same
/// L1 set, false store-to-load dependences), as they would if each sat at the
/// start of its own page-aligned allocation.
pub(super) struct Inputs {
    pub(super) n: usize,
    /// `wi` at `[0, n)`, `wo` at `[n + AOS_PAD, 2n + AOS_PAD)`.
    pub(super) aos: Vec<Vec3>,
    /// Component `j` (`wi.x, wi.y, wi.z, wo.x, wo.y, wo.z`) at
    /// `[j (n + SOA_PAD), j (n + SOA_PAD) + n)`.
    pub(super) soa: Vec<f32>,
    pub(super) u: Vec<[f32; 2]>,
    /// `u₀` at `[0, n)`, `u₁` at `[n + SOA_PAD, 2n + SOA_PAD)`.
    pub(super) u_soa: Vec<f32>,
}

const AOS_PAD: usize = 16;
const SOA_PAD: usize = 16;

/// How the direction pairs of an [`Inputs`] are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum InputSet {
    /// Golden-ratio (R2) sequences: consecutive pairs are close to the
    /// previous ones' neighbours, so data-dependent branches see long
    /// regular runs.
    Golden,
    /// Independent uniform draws of a fixed-seed [`radiometry::rng::Pcg32`]
    /// (the same distribution as [`Golden`](Self::Golden), in no order):
    /// what a renderer's directions look like to the branch predictor.
    Random,
}

impl InputSet {
    /// Both sets, in the order the bench runs them.
    pub(super) const ALL: [InputSet; 2] = [InputSet::Golden, InputSet::Random];

    /// The name printed in the `inputs` column.
    pub(super) fn name(self) -> &'static str {
        match self {
            InputSet::Golden => "golden",
            InputSet::Random => "random",
        }
    }
}

/// The seed of [`InputSet::Random`].
const RANDOM_SEED: u64 = 0x5EED_0028;

impl Inputs {
    /// Direction pairs spread over the upper hemisphere (θ uniform in
    /// [0, 1.55) rad, φ in [0, 2π)) and `u` in [0,1)²: from golden-ratio
    /// (R2) sequences in f64, which stay well spread for 2²⁰ points, or
    /// from a fixed-seed random generator ([`InputSet`]).
    pub(super) fn new(n: usize, set: InputSet) -> Self {
        let frac = |k: usize, g: f64| (k as f64 * g).fract();
        // Largest f32 below 1: a fraction just below 1 must not round up to 1.
        let below_one = |x: f64| (x as f32).min(1.0 - f32::EPSILON / 2.0);
        let mut rng = radiometry::rng::Pcg32::new(RANDOM_SEED);
        let mut wi = Vec::with_capacity(n);
        let mut wo = Vec::with_capacity(n);
        let mut u = Vec::with_capacity(n);
        for k in 0..n {
            let [a, b, c, d] = match set {
                InputSet::Golden => [
                    frac(k, 0.618_033_988_749_894_9),
                    frac(k, 0.381_966_011_250_105_1),
                    frac(k, 0.754_877_666_246_692_7),
                    frac(k, 0.569_840_290_998_053_2),
                ],
                InputSet::Random => std::array::from_fn(|_| rng.next_f64()),
            };
            let tau = std::f64::consts::TAU;
            wi.push(spherical_direction((a * 1.55) as f32, (b * tau) as f32));
            wo.push(spherical_direction((c * 1.55) as f32, (d * tau) as f32));
            // u from wi's numbers: sampling uses wo and u only, so the two are independent.
            u.push([below_one(a), below_one(b)]);
        }
        let mut aos = wi.clone();
        aos.extend(std::iter::repeat_n(Vec3::Z, AOS_PAD));
        aos.extend_from_slice(&wo);
        let mut soa = Vec::with_capacity(6 * (n + SOA_PAD));
        for w in [&wi, &wo] {
            for j in 0..3 {
                soa.extend(w.iter().map(|v| v[j]));
                soa.extend(std::iter::repeat_n(0.0, SOA_PAD));
            }
        }
        let mut u_soa = Vec::with_capacity(2 * (n + SOA_PAD));
        for j in 0..2 {
            u_soa.extend(u.iter().map(|v| v[j]));
            u_soa.extend(std::iter::repeat_n(0.0, SOA_PAD));
        }
        Inputs {
            n,
            aos,
            soa,
            u,
            u_soa,
        }
    }

    /// `(u₀, u₁)` as two slices.
    pub(super) fn u_soa(&self, n: usize) -> (&[f32], &[f32]) {
        let s = self.n + SOA_PAD;
        (&self.u_soa[..n], &self.u_soa[s..s + n])
    }

    pub(super) fn wi(&self, n: usize) -> &[Vec3] {
        &self.aos[..n]
    }

    pub(super) fn wo(&self, n: usize) -> &[Vec3] {
        let s = self.n + AOS_PAD;
        &self.aos[s..s + n]
    }

    pub(super) fn soa(&self, first: usize, n: usize) -> Vec3Soa<'_> {
        let c = |j: usize| {
            let s = (first + j) * (self.n + SOA_PAD);
            &self.soa[s..s + n]
        };
        Vec3Soa::new(c(0), c(1), c(2))
    }

    pub(super) fn wi_soa(&self, n: usize) -> Vec3Soa<'_> {
        self.soa(0, n)
    }

    pub(super) fn wo_soa(&self, n: usize) -> Vec3Soa<'_> {
        self.soa(3, n)
    }
}

/// Times `pass` (one pass over `n` elements): warm-up of at least a quarter
/// of `min_time` and at least one pass (page faults, caches, clocks), then
/// repetitions of `iters` passes, `iters ≥ 1` chosen so that a repetition
/// takes about `min_time / REP_SLICES`, until `min_time` has been spent and
/// at least [`MIN_REPS`] were run. Returns the best (smallest) seconds per
/// element over the repetitions.
pub(super) fn measure(n: usize, min_time: Duration, mut pass: impl FnMut()) -> f64 {
    let t0 = Instant::now();
    let mut passes = 0u64;
    loop {
        pass();
        passes += 1;
        if t0.elapsed() >= min_time / 4 {
            break;
        }
    }
    let per_pass = t0.elapsed().as_secs_f64() / passes as f64;
    let target = min_time.as_secs_f64() / REP_SLICES as f64;
    let iters = ((target / per_pass).ceil() as u64).max(1);
    let mut best = f64::INFINITY;
    let mut total = 0.0;
    let mut reps = 0;
    while reps < MIN_REPS || total < min_time.as_secs_f64() {
        let t = Instant::now();
        for _ in 0..iters {
            pass();
        }
        let dt = t.elapsed().as_secs_f64();
        total += dt;
        reps += 1;
        if dt > 0.0 {
            best = best.min(dt / iters as f64);
        }
    }
    best / n as f64
}

// --- The timed passes. `#[inline(never)]` keeps each loop a standalone
// kernel; callers pass every argument through `black_box`.

#[inline(never)]
#[allow(clippy::needless_range_loop)] // the indexed loop is the point: it is what a renderer writes
pub(super) fn pass_eval<B: Brdf>(brdf: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    for k in 0..n {
        out[k] = brdf.eval(wi[k], wo[k]);
    }
}

#[inline(never)]
pub(super) fn pass_eval_batch<B: Brdf>(brdf: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [B::Spectrum]) {
    brdf.eval_batch(wi, wo, out);
}

#[inline(never)]
pub(super) fn pass_eval_batch_soa<B: Brdf>(
    brdf: &B,
    wi: Vec3Soa<'_>,
    wo: Vec3Soa<'_>,
    out: &mut [B::Spectrum],
) {
    brdf.eval_batch_soa(wi, wo, out);
}

#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub(super) fn pass_pdf<B: Brdf>(brdf: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    let n = out.len();
    let (wi, wo) = (&wi[..n], &wo[..n]);
    for k in 0..n {
        out[k] = brdf.pdf(wi[k], wo[k]);
    }
}

#[inline(never)]
pub(super) fn pass_pdf_batch<B: Brdf>(brdf: &B, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
    brdf.pdf_batch(wi, wo, out);
}

#[inline(never)]
pub(super) fn pass_sample_batch<B: Brdf>(
    brdf: &B,
    wo: &[Vec3],
    u: &[[f32; 2]],
    out: &mut [Option<BrdfSample<B::Spectrum>>],
) {
    brdf.sample_batch(wo, u, out);
}

#[inline(never)]
#[allow(clippy::needless_range_loop)]
pub(super) fn pass_sample<B: Brdf>(
    brdf: &B,
    wo: &[Vec3],
    u: &[[f32; 2]],
    out: &mut [Option<BrdfSample<B::Spectrum>>],
) {
    let n = out.len();
    let (wo, u) = (&wo[..n], &u[..n]);
    for k in 0..n {
        out[k] = brdf.sample(wo[k], u[k]);
    }
}
