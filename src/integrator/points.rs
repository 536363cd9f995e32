//! Point sets on the unit square for Monte Carlo and randomized quasi-Monte
//! Carlo: jittered (stratified) grids (the seeded PRNG is
//! [`crate::rng::Pcg32`]),
//! Owen-scrambled Sobol points (computed here, see [`sobol_value`]), and the Fibonacci
//! lattice behind spherical Fibonacci point sets.
//!
//! Everything is deterministic for a given seed and allocation-free.
//!
//! ```
//! use radiometry::integrator::points::fibonacci_point;
//! let p = fibonacci_point(3, 8, [0.0, 0.0]);
//! assert!((p[0] - 3.5 / 8.0).abs() < 1e-6);
//! ```

pub use super::sobol::{SOBOL_DIMENSIONS, SOBOL_MAX_POINTS, sobol_point, sobol_point_pairs, sobol_value};
use crate::math::ONE_MINUS_EPSILON;
pub(crate) use crate::rng::Pcg32;
use glam::Vec3;

/// Which point set a Monte Carlo integrator draws its unit-square points
/// from.
///
/// ```
/// use radiometry::integrator::points::PointSet;
/// assert_eq!(PointSet::Sobol.name(), "sobol");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PointSet {
    /// Independent uniform points from [`Pcg32`]; error = sample standard error.
    Prng,
    /// A jittered `nx × ny` grid (one uniform point per cell; Cook 1986,
    /// "Stochastic sampling in computer graphics", ACM TOG 5(1)).
    Stratified,
    /// Owen-scrambled Sobol points (Burley 2020, "Practical Hash-based Owen
    /// Scrambling", JCGT 9(4)), see [`sobol_value`].
    Sobol,
    /// The Fibonacci lattice `((i + ½)/n, {i/Φ})` with a random toroidal
    /// shift (Cranley & Patterson 1976); mapped through the uniform or polar
    /// cosine hemisphere map it is the spherical Fibonacci point set of
    /// Marques et al. 2013, "Spherical Fibonacci Point Sets for Illumination
    /// Integrals", CGF 32(8).
    Fibonacci,
}

impl PointSet {
    /// All point sets, in a fixed order.
    pub const ALL: [PointSet; 4] = [
        PointSet::Prng,
        PointSet::Stratified,
        PointSet::Sobol,
        PointSet::Fibonacci,
    ];

    /// Short stable name: `"prng"`, `"stratified"`, `"sobol"`, `"fibonacci"`.
    pub fn name(self) -> &'static str {
        match self {
            PointSet::Prng => "prng",
            PointSet::Stratified => "stratified",
            PointSet::Sobol => "sobol",
            PointSet::Fibonacci => "fibonacci",
        }
    }
}

/// `1/Φ = (√5 − 1)/2`, the golden-ratio conjugate.
const INV_PHI: f64 = 0.618_033_988_749_894_8;

/// Point `i` of the `n`-point Fibonacci lattice on the unit square,
/// toroidally shifted by `shift`:
/// `u = ({(i + ½)/n + s₀}, {i/Φ + s₁})` with `{·}` the fractional part
/// (Marques et al. 2013, Eq. 2 in the unit-square form; Cranley & Patterson
/// 1976 for the random shift). Domain: `i < n`, `n ≥ 1`; any `shift`.
/// Output lies in `[0, 1 − 2⁻²⁴]²`.
///
/// ```
/// use radiometry::integrator::points::fibonacci_point;
/// let p = fibonacci_point(1, 4, [0.0, 0.0]);
/// assert!((p[0] - 0.375).abs() < 1e-7 && (p[1] - 0.618034).abs() < 1e-6);
/// ```
pub fn fibonacci_point(i: u32, n: u32, shift: [f64; 2]) -> [f32; 2] {
    let n = n.max(1) as f64;
    let a = (i as f64 + 0.5) / n + shift[0];
    let b = i as f64 * INV_PHI + shift[1];
    [unit_f32(frac(a)), unit_f32(frac(b))]
}

/// Point `cell` of a jittered `nx × ny` grid: cell `(cell mod nx,
/// cell div nx)` plus the jitter `j ∈ [0,1)²`. Output in `[0, 1 − 2⁻²⁴]²`.
/// (`jittered_point(5, 4, 2, [0.5, 0.5]) = [0.375, 0.75]`, a unit test.)
pub(crate) fn jittered_point(cell: u32, nx: u32, ny: u32, j: [f32; 2]) -> [f32; 2] {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let cx = (cell % nx) as f64;
    let cy = ((cell / nx) % ny) as f64;
    [
        unit_f32((cx + j[0] as f64) / nx as f64),
        unit_f32((cy + j[1] as f64) / ny as f64),
    ]
}

/// The grid `nx × ny` used for `n` jittered points: `nx = ⌊√n⌋`,
/// `ny = ⌊n/nx⌋` (so `nx·ny ≤ n`, and `nx·ny > n − 2√n`).
pub(crate) fn jitter_grid(n: u32) -> (u32, u32) {
    let n = n.max(1);
    let mut nx = libm::sqrt(n as f64) as u32;
    while (nx as u64 + 1) * (nx as u64 + 1) <= n as u64 {
        nx += 1;
    }
    while nx > 1 && nx as u64 * nx as u64 > n as u64 {
        nx -= 1;
    }
    let nx = nx.max(1);
    (nx, n / nx)
}

/// Polar (Malley) cosine-weighted hemisphere map:
/// `r = √u₀`, `φ = 2π u₁`, `ω = (r cos φ, r sin φ, √(1 − r²))`, density
/// `cos θ / π` (PBRT 4th ed. §A.5.3 with the polar disk map). This is the
/// map under which the Fibonacci lattice becomes the cosine-weighted
/// spherical Fibonacci set (Marques et al. 2013, §4). Domain `u ∈ [0,1]²`.
#[inline]
pub(crate) fn square_to_cosine_hemisphere_polar(u: [f32; 2]) -> Vec3 {
    let u0 = u[0].clamp(0.0, 1.0);
    let r = crate::math::sqrtf(u0);
    let (s, c) = crate::math::sincos_turn(u[1].clamp(0.0, 1.0));
    let z = crate::math::sqrtf((1.0 - u0).max(0.0));
    Vec3::new(r * c, r * s, z)
}

#[inline]
fn frac(x: f64) -> f64 {
    // For 0 ≤ x < 2⁵³ truncation is the floor and exact, and needs no
    // libm call (`floor` is a software routine without SSE4.1).
    if (0.0..9.0e15).contains(&x) {
        return x - (x as i64) as f64;
    }
    let f = x - libm::floor(x);
    if f.is_finite() { f } else { 0.0 }
}

#[inline]
fn unit_f32(x: f64) -> f32 {
    (x.clamp(0.0, 1.0) as f32).min(ONE_MINUS_EPSILON)
}

/// A 32-bit mix of a seed and an index (SplitMix64 finaliser, Steele,
/// Lea & Flood 2014, "Fast splittable pseudorandom number generators",
/// OOPSLA), used to derive per-replicate seeds.
#[inline]
pub(crate) fn mix_seed(seed: u64, index: u64) -> u64 {
    let mut z = seed
        ^ index
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The truncation shortcut of `frac` is `x − floor(x)` bit for bit on
    /// `[0, 9·10¹⁵)`, and the libm path takes over beyond.
    #[test]
    fn frac_is_x_minus_floor() {
        let mut rng = Pcg32::with_stream(3, 5);
        for k in 0..200_000 {
            let scale = [1.0, 7.0, 1e3, 1e9, 4.5e15, 8.999e15, 2e16][k % 7];
            let x = rng.next_f64() * scale;
            assert_eq!(frac(x).to_bits(), (x - libm::floor(x)).to_bits(), "x = {x}");
        }
        for x in [0.0, 0.5, 1.0, 1.0 - f64::EPSILON / 2.0, 9.0e15, 1e300, -0.25] {
            let want = x - libm::floor(x);
            assert_eq!(frac(x).to_bits(), want.to_bits(), "x = {x}");
        }
        assert_eq!(frac(f64::INFINITY), 0.0);
        assert_eq!(frac(f64::NAN), 0.0);
    }

    #[test]
    fn sobol_point_pairs_are_the_two_first_pairs_bit_for_bit() {
        for seed in [0u32, 1, 0xdead_beef] {
            for i in (0..SOBOL_MAX_POINTS)
                .step_by(97)
                .chain([SOBOL_MAX_POINTS - 1, SOBOL_MAX_POINTS + 5])
            {
                let [a, b] = sobol_point_pairs(i, seed);
                let (ea, eb) = (sobol_point(i, 0, seed), sobol_point(i, 1, seed));
                assert_eq!(a.map(f32::to_bits), ea.map(f32::to_bits), "i={i} seed={seed}");
                assert_eq!(b.map(f32::to_bits), eb.map(f32::to_bits), "i={i} seed={seed}");
            }
        }
    }

    #[test]
    fn jittered_cells_and_the_polar_map() {
        assert_eq!(jittered_point(5, 4, 2, [0.5, 0.5]), [0.375, 0.75]);
        assert_eq!(square_to_cosine_hemisphere_polar([0.0, 0.3]).z, 1.0);
    }

    #[test]
    fn unit_ranges() {
        let mut r = Pcg32::with_stream(1, 1);
        for _ in 0..10_000 {
            let (a, b) = (r.next_f32(), r.next_f64());
            assert!((0.0..1.0).contains(&a) && (0.0..1.0).contains(&b));
        }
        for n in [1u32, 2, 3, 15, 16, 17, 1000, u32::MAX] {
            let (nx, ny) = jitter_grid(n);
            assert!(nx >= 1 && ny >= 1 && nx as u64 * ny as u64 <= n as u64, "{n}");
        }
        let p = fibonacci_point(7, 8, [0.9, 0.99]);
        assert!(p[0] < 1.0 && p[1] < 1.0);
    }

    #[test]
    fn fibonacci_lattice_equidistributes() {
        // Discrepancy check: count of points in [0, 1/2) x [0, 1/3) ≈ n/6.
        let n = 987u32;
        let c = (0..n)
            .map(|i| fibonacci_point(i, n, [0.0, 0.0]))
            .filter(|p| p[0] < 0.5 && p[1] < 1.0 / 3.0)
            .count() as f64;
        assert!((c - n as f64 / 6.0).abs() < 5.0, "{c}");
    }
}
