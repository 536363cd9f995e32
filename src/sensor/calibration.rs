//! Radiometric calibration: recover the inverse response `g = R⁻¹` from
//! readings of a static scene at several known exposures.
//!
//! Two methods: [`mitsunaga_nayar`] (parametric, a polynomial — small,
//! smooth, for normalised readings) and [`debevec_malik`] (non-parametric,
//! one value per reading level with a smoothness prior — for integer
//! levels; its cost grows as `(levels + pixels)²`).
//!
//! Method 1: Mitsunaga & Nayar 1999, "Radiometric self calibration",
//! CVPR, §3 (eqs. 3–8) with *known* exposure ratios. The inverse response
//! is a polynomial `g(M) = Σ_{n<N} c_n Mⁿ` of normalised readings
//! `M ∈ [0, 1]`, normalised by `g(1) = 1`. For a static scene, pixel `p`
//! read at exposures `t_q` and `t_{q+1}` satisfies
//! `g(M_{p,q}) = (t_q / t_{q+1}) g(M_{p,q+1})`; the coefficients minimise
//!
//! `ε = Σ_p Σ_q [g(M_{p,q}) − R_q g(M_{p,q+1})]²`,  `R_q = t_q/t_{q+1}`,
//!
//! subject to `g(1) = Σ c_n = 1` (eliminating `c_{N−1}`) and `g(0) = c_0 = 0`
//! (readings must be black-level corrected: zero exposure reads zero), a
//! linear least-squares problem of `N−2` unknowns solved by normal equations with Gaussian
//! elimination and partial pivoting in fixed-size arrays (no allocation).
//! The accumulation and the solve use `f64` (documented: the monomial
//! normal equations are ill-conditioned in `f32` for `N ≥ 5`); the fitted
//! curve is evaluated in `f32`.
//!
//! Pairs where either reading lies outside `[lo, hi]` (under-exposed or
//! clipped) are skipped, as Mitsunaga & Nayar recommend.
//!
//! Use exposure ratios that are not all equal: with a single repeated
//! ratio the data cannot distinguish `g` from a "fractal" family of
//! alternatives (Grossberg & Nayar 2003, "Determining the camera response
//! from images: what is knowable?", PAMI 25(11)).
//!
//! ```
//! use radiometry::sensor::calibration::mitsunaga_nayar;
//! use radiometry::sensor::response::{Gamma, Response};
//! let r = Gamma::new(2.2).unwrap();
//! let exposures = [0.05f32, 0.08, 0.2, 0.35, 1.0];
//! let mut readings = [0.0f32; 60 * 5];
//! for p in 0..60 {
//!     let e = libm::powf(10.0, -3.0 + 3.0 * p as f32 / 59.0);
//!     for (q, t) in exposures.iter().enumerate() {
//!         readings[p * 5 + q] = r.apply(e * t);
//!     }
//! }
//! let g = mitsunaga_nayar::<6>(&readings, &exposures, 0.02, 0.98).unwrap();
//! assert!((g.inverse(0.5) - r.inverse(0.5)).abs() < 5e-3);
//! ```

use super::SensorError;
use super::response::Response;
use crate::math::clamp_to;

/// A polynomial inverse response `g(M) = Σ c_n Mⁿ` (`N` coefficients) on
/// the calibrated range `[m_lo, 1]`, where it is strictly increasing and
/// positive (checked on construction); below `m_lo` — where the data did
/// not constrain the fit — it is continued linearly through the origin,
/// `g(M) = g(m_lo) M / m_lo`.
/// As a [`Response`]: `inverse(y) = g(y)`, and `apply(x)` solves
/// `g(M) = x` by bisection (exact to f32 resolution).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PolynomialInverseResponse<const N: usize> {
    coeffs: [f32; N],
    m_lo: f32,
}

impl<const N: usize> PolynomialInverseResponse<N> {
    /// Wraps coefficients `c_0..c_{N−1}` valid on `[m_lo, 1]`,
    /// `0 ≤ m_lo < 1`. Errors: non-finite input
    /// ([`SensorError::NotFinite`]); `m_lo` out of range
    /// ([`SensorError::BadParameter`]); the polynomial not strictly
    /// increasing at 1025 points of `[m_lo, 1]`, or `g(m_lo) ≤ 0` when
    /// `m_lo > 0` ([`SensorError::NotMonotonic`]).
    pub fn new(coeffs: [f32; N], m_lo: f32) -> Result<Self, SensorError> {
        if N == 0 || coeffs.iter().any(|c| !c.is_finite()) || !m_lo.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if !(0.0..1.0).contains(&m_lo) {
            return Err(SensorError::BadParameter("m_lo must be in [0, 1)"));
        }
        let g = Self { coeffs, m_lo };
        let mut prev = g.poly(m_lo);
        if !prev.is_finite() {
            return Err(SensorError::NotFinite);
        }
        if m_lo > 0.0 && prev <= 0.0 {
            return Err(SensorError::NotMonotonic);
        }
        for i in 1..=1024 {
            let v = g.poly(m_lo + (1.0 - m_lo) * i as f32 / 1024.0);
            if !v.is_finite() {
                return Err(SensorError::NotFinite);
            }
            if v <= prev {
                return Err(SensorError::NotMonotonic);
            }
            prev = v;
        }
        Ok(g)
    }

    /// Start of the calibrated range.
    pub fn m_lo(&self) -> f32 {
        self.m_lo
    }

    #[inline]
    fn poly(&self, m: f32) -> f32 {
        self.coeffs.iter().rev().fold(0.0, |acc, &c| acc * m + c)
    }

    /// The coefficients `c_n`.
    pub fn coeffs(&self) -> [f32; N] {
        self.coeffs
    }

    /// `g(M)`: Horner's rule on `[m_lo, ∞)`, the linear continuation
    /// below `m_lo` (no clamping).
    #[inline]
    pub fn eval(&self, m: f32) -> f32 {
        if m < self.m_lo {
            self.poly(self.m_lo) * (m / self.m_lo)
        } else {
            self.poly(m)
        }
    }
}

impl<const N: usize> Response for PolynomialInverseResponse<N> {
    /// `R(x) = g⁻¹(x)`: bisection on `[0, 1]`; `x` is clamped to
    /// `[g(0), g(1)]`, NaN → `g(0)`.
    fn apply(&self, x: f32) -> f32 {
        let (g0, g1) = (self.eval(0.0), self.eval(1.0));
        // `g0 < g1` (checked by `new`); `clamp_to` is `clamp` without its assertion.
        let x = if x.is_nan() { g0 } else { clamp_to(x, g0, g1) };
        let (mut lo, mut hi) = (0.0f32, 1.0f32);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if self.eval(mid) < x {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
    /// `g(y)`, `y` clamped to `[0, 1]`, NaN → 0.
    fn inverse(&self, y: f32) -> f32 {
        let y = if y.is_nan() { 0.0 } else { y.clamp(0.0, 1.0) };
        self.eval(y)
    }
}

/// Largest number of polynomial coefficients [`mitsunaga_nayar`] accepts.
pub const MAX_COEFFS: usize = 12;

/// Fits the inverse response (see the module docs).
///
/// * `readings[p · Q + q]`: normalised reading of pixel `p` at exposure
///   `q`, `Q = exposures.len() ≥ 2`; `readings.len()` must be a multiple
///   of `Q`.
/// * `exposures`: strictly positive, finite exposure times (any order —
///   ratios are taken between consecutive entries).
/// * `[lo, hi]`: readings used (e.g. `[0.02, 0.98]`); the result is a
///   polynomial on `[lo, 1]`, continued linearly below `lo`.
/// * `N`: number of coefficients, `2 ≤ N ≤` [`MAX_COEFFS`].
///
/// Errors: [`SensorError::BadBuffer`] for inconsistent lengths,
/// [`SensorError::NotFinite`] / [`SensorError::BadParameter`] for invalid
/// exposures or range, [`SensorError::Singular`] when too few usable
/// pairs, and [`SensorError::NotMonotonic`] when the fitted `g` is not
/// increasing (the data do not determine a response).
pub fn mitsunaga_nayar<const N: usize>(
    readings: &[f32],
    exposures: &[f32],
    lo: f32,
    hi: f32,
) -> Result<PolynomialInverseResponse<N>, SensorError> {
    if !(2..=MAX_COEFFS).contains(&N) {
        return Err(SensorError::BadParameter(
            "number of coefficients must be in 2..=12",
        ));
    }
    let q = exposures.len();
    if q < 2 || readings.is_empty() || !readings.len().is_multiple_of(q) {
        return Err(SensorError::BadBuffer);
    }
    if exposures.iter().any(|t| !t.is_finite()) || !(lo.is_finite() && hi.is_finite()) {
        return Err(SensorError::NotFinite);
    }
    if exposures.iter().any(|&t| t <= 0.0) || !(0.0..hi).contains(&lo) || hi > 1.0 {
        return Err(SensorError::BadParameter(
            "exposures must be > 0 and 0 ≤ lo < hi ≤ 1",
        ));
    }
    let k = N - 1; // unknowns c_1..c_{N−2} (stored at 0..k−1 shifted by one); c_0 = 0
    let mut ata = [[0.0f64; MAX_COEFFS]; MAX_COEFFS];
    let mut atb = [0.0f64; MAX_COEFFS];
    let mut pairs = 0usize;
    // Consecutive exposures `(j, j + 1)` as pairs of windows (no indexing: no panic path).
    for px in readings.chunks_exact(q) {
        for (m, t) in px.windows(2).zip(exposures.windows(2)) {
            let (&[m0, m1], &[t0, t1]) = (m, t) else {
                continue;
            };
            if !(m0 >= lo && m0 <= hi && m1 >= lo && m1 <= hi) {
                continue;
            }
            let r = t0 as f64 / t1 as f64;
            // a_n = M0ⁿ − r M1ⁿ; residual = Σ_{n<k} c_n (a_n − a_k) + a_k.
            let mut a = [0.0f64; MAX_COEFFS];
            let (mut p0, mut p1) = (1.0f64, 1.0f64);
            for an in a.iter_mut().take(N) {
                *an = p0 - r * p1;
                p0 *= m0 as f64;
                p1 *= m1 as f64;
            }
            // Unknown `i − 1` is the coefficient of `Mⁱ`, `1 ≤ i < k`.
            let ak = a.get(k).copied().unwrap_or(0.0);
            let unknowns = a.get(1..k).unwrap_or(&[]);
            for ((row, b), &ai) in ata.iter_mut().zip(atb.iter_mut()).zip(unknowns) {
                let di = ai - ak;
                for (cell, &aj) in row.iter_mut().zip(unknowns) {
                    *cell += di * (aj - ak);
                }
                *b -= di * ak;
            }
            pairs += 1;
        }
    }
    if pairs < k {
        return Err(SensorError::Singular);
    }
    let c = if k > 1 {
        solve::<MAX_COEFFS>(&mut ata, &mut atb, k - 1)?
    } else {
        [0.0; MAX_COEFFS]
    };
    // `c_0 = 0`, `c_1..c_{k−1}` solved, `c_k = 1 − Σ` (`k = N − 1`, the last).
    let mut coeffs = [0.0f32; N];
    let mut sum = 0.0f64;
    for (ci, &v) in coeffs.iter_mut().skip(1).take(k - 1).zip(&c) {
        *ci = v as f32;
        sum += v;
    }
    if let Some(last) = coeffs.last_mut() {
        *last = (1.0 - sum) as f32;
    }
    PolynomialInverseResponse::new(coeffs, lo)
}

/// Solves the leading `n × n` block of `a x = b` by Gaussian elimination
/// with partial pivoting (Golub & Van Loan, *Matrix Computations*, 4th
/// ed., Alg. 3.4.1), in place, without allocation. Relative pivot
/// threshold 1e-14 → [`SensorError::Singular`].
pub fn solve<const M: usize>(
    a: &mut [[f64; M]; M],
    b: &mut [f64; M],
    n: usize,
) -> Result<[f64; M], SensorError> {
    // Rows and columns through iterators, `get` and `split_*_mut`: no panic path for any `n`.
    let n = n.min(M);
    let scale = a
        .iter()
        .take(n)
        .flat_map(|row| row.iter().take(n))
        .fold(0.0f64, |m, v| m.max(v.abs()));
    if !(scale.is_finite() && scale > 0.0) {
        return Err(SensorError::Singular);
    }
    let at = |row: &[f64; M], c: usize| row.get(c).copied().unwrap_or(0.0);
    for col in 0..n {
        let (Some(rows), Some(rhs)) = (a.get_mut(col..n), b.get_mut(col..n)) else {
            break;
        };
        // The last row of largest |a[r][col]| (as `max_by`), as an offset from `col`.
        let piv = rows
            .iter()
            .enumerate()
            .max_by(|(_, x), (_, y)| at(x, col).abs().total_cmp(&at(y, col).abs()))
            .map_or(0, |(i, _)| i);
        if rows.get(piv).map_or(0.0, |r| at(r, col)).abs() <= 1e-14 * scale {
            return Err(SensorError::Singular);
        }
        swap_first(rows, piv);
        swap_first(rhs, piv);
        let (Some((prow, below)), Some((&mut pb, rhs_below))) =
            (rows.split_first_mut(), rhs.split_first_mut())
        else {
            break;
        };
        let p = at(prow, col);
        for (row, br) in below.iter_mut().zip(rhs_below) {
            let f = at(row, col) / p;
            for (v, &pv) in row.iter_mut().zip(prow.iter()).take(n).skip(col) {
                *v -= f * pv;
            }
            *br -= f * pb;
        }
    }
    let mut x = [0.0f64; M];
    for r in (0..n).rev() {
        let (Some(row), Some(&br)) = (a.get(r), b.get(r)) else {
            continue;
        };
        let Some((done, after)) = x.split_at_mut_checked(r + 1) else {
            continue;
        };
        let mut s = br;
        for (&arc, &xc) in row.iter().skip(r + 1).take(n - r - 1).zip(after.iter()) {
            s -= arc * xc;
        }
        if let Some(xr) = done.last_mut() {
            *xr = s / at(row, r);
        }
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Err(SensorError::Singular);
    }
    Ok(x)
}

/// Swaps `s[0]` and `s[j]` (nothing when `j` is 0 or out of range).
fn swap_first<T>(s: &mut [T], j: usize) {
    if let Some((first, rest)) = s.split_first_mut()
        && let Some(other) = rest.get_mut(j.wrapping_sub(1))
    {
        core::mem::swap(first, other);
    }
}

/// A tabulated inverse response from [`debevec_malik`]: `g(z) = ln X(z)`
/// at the `Z` reading levels `z = 0..Z−1` (reading `y = z/(Z−1)`),
/// normalised so that the top level has `X = 1`. As a [`Response`],
/// `inverse(y)` interpolates `X` linearly between levels and `apply`
/// inverts that by binary search.
///
/// ```
/// use radiometry::sensor::calibration::debevec_malik;
/// use radiometry::sensor::response::{Gamma, Response};
/// let r = Gamma::new(2.0).unwrap();
/// let t = [0.05f32, 0.08, 0.2, 0.35, 1.0];
/// let mut levels = [0u16; 30 * 5];
/// for p in 0..30 {
///     let e = libm::powf(10.0, -2.0 + 2.0 * p as f32 / 29.0);
///     for q in 0..5 {
///         levels[p * 5 + q] = libm::roundf(r.apply(e * t[q]) * 15.0) as u16;
///     }
/// }
/// let g = debevec_malik::<16, 48>(&levels, &t, 2.0).unwrap();
/// // Level 8 of 15 ≈ exposure (8/15)² = 0.284, within the quantisation bin.
/// assert!((g.exposures()[8] - 0.284).abs() < 0.04);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogExposureTable<const Z: usize> {
    x: [f32; Z],
}

impl<const Z: usize> LogExposureTable<Z> {
    /// Relative exposure `X(z)` at every level.
    pub fn exposures(&self) -> [f32; Z] {
        self.x
    }
}

impl<const Z: usize> Response for LogExposureTable<Z> {
    fn apply(&self, x: f32) -> f32 {
        // `Z ≥ 3` and `x` strictly increasing (from `debevec_malik`, the only constructor); checked
        // reads and `clamp_to` (`clamp` without its assertion) keep no panic path.
        let (Some(&first), Some(&last)) = (self.x.first(), self.x.last()) else {
            return 0.0;
        };
        let x = if x.is_nan() {
            first
        } else {
            clamp_to(x, first, last)
        };
        let hi = self
            .x
            .partition_point(|&v| v <= x)
            .min(Z.saturating_sub(1))
            .max(1);
        let (Some(&a), Some(&b)) = (self.x.get(hi - 1), self.x.get(hi)) else {
            return 0.0;
        };
        let f = ((x - a) / (b - a)).clamp(0.0, 1.0);
        ((hi - 1) as f32 + f) / (Z - 1) as f32
    }
    fn inverse(&self, y: f32) -> f32 {
        let y = if y.is_nan() { 0.0 } else { y.clamp(0.0, 1.0) };
        let t = y * Z.saturating_sub(1) as f32;
        let i = (t as usize).min(Z.saturating_sub(2));
        let f = t - i as f32;
        match (self.x.get(i), self.x.get(i + 1)) {
            (Some(&a), Some(&b)) => a + (b - a) * f,
            _ => 0.0,
        }
    }
}

/// Debevec & Malik 1997 ("Recovering high dynamic range radiance maps
/// from photographs", SIGGRAPH, §2.1 eq. 3 and the appendix): least
/// squares for `g(z) = ln X(z)` and the log irradiances `ln E_p`,
///
/// `min Σ_p Σ_q [w(Z_pq)(g(Z_pq) − ln E_p − ln t_q)]² + λ Σ_z [w(z) g''(z)]²`,
///
/// with the hat weight `w(z) = min(z, Z−1−z)`, `g''(z) = g(z−1) − 2g(z) +
/// g(z+1)`, and `g(⌊Z/2⌋) = 0` fixing the scale. Solved through the normal
/// equations in fixed-size `U × U` `f64` arrays (`U ≥ Z + P` unknowns; the
/// matrix lives on the stack: `8·U²` bytes), Gaussian elimination with
/// partial pivoting.
///
/// * `levels[p · Q + q]`: integer reading level `< Z` of pixel `p` at
///   exposure `q`; `Q = exposures.len() ≥ 2`.
/// * `smoothness`: λ ≥ 0 (finite).
///
/// Errors: [`SensorError::BadBuffer`] (lengths, a level ≥ Z, `Z < 3`,
/// `Z + P > U`), [`SensorError::NotFinite`] / [`SensorError::BadParameter`]
/// (exposures, λ), [`SensorError::Singular`], and
/// [`SensorError::NotMonotonic`] when the recovered `g` is not strictly
/// increasing (the data or λ do not determine a response).
pub fn debevec_malik<const Z: usize, const U: usize>(
    levels: &[u16],
    exposures: &[f32],
    smoothness: f32,
) -> Result<LogExposureTable<Z>, SensorError> {
    let q = exposures.len();
    if Z < 3 || q < 2 || levels.is_empty() || !levels.len().is_multiple_of(q) {
        return Err(SensorError::BadBuffer);
    }
    let p_count = levels.len() / q;
    if Z + p_count > U || levels.iter().any(|&z| z as usize >= Z) {
        return Err(SensorError::BadBuffer);
    }
    if exposures.iter().any(|t| !t.is_finite()) || !smoothness.is_finite() {
        return Err(SensorError::NotFinite);
    }
    if exposures.iter().any(|&t| t <= 0.0) || smoothness < 0.0 {
        return Err(SensorError::BadParameter(
            "exposures must be > 0 and smoothness ≥ 0",
        ));
    }
    let w = |z: usize| z.min((Z - 1).saturating_sub(z)) as f64;
    let mut ata = [[0.0f64; U]; U];
    let mut atb = [0.0f64; U];
    // Indices are below `Z + p_count ≤ U` (checked above); checked writes keep no panic path.
    let add = |m: &mut [[f64; U]; U], i: usize, j: usize, v: f64| {
        if let Some(c) = m.get_mut(i).and_then(|r| r.get_mut(j)) {
            *c += v;
        }
    };
    // Data rows: w (g[z] − lnE[p]) = w ln t.
    for (p, px) in levels.chunks_exact(q).enumerate() {
        for (&z, &t) in px.iter().zip(exposures) {
            let z = z as usize;
            let wz2 = w(z) * w(z);
            if wz2 == 0.0 {
                continue;
            }
            let (i, j) = (z, Z + p);
            let lt = libm::log(t as f64);
            add(&mut ata, i, i, wz2);
            add(&mut ata, j, j, wz2);
            add(&mut ata, i, j, -wz2);
            add(&mut ata, j, i, -wz2);
            if let Some(b) = atb.get_mut(i) {
                *b += wz2 * lt;
            }
            if let Some(b) = atb.get_mut(j) {
                *b -= wz2 * lt;
            }
        }
    }
    // Scale fixing: g(Z/2) = 0.
    add(&mut ata, Z / 2, Z / 2, 1.0);
    // Smoothness rows: λ w(z) (g[z−1] − 2 g[z] + g[z+1]) = 0.
    let lam = smoothness as f64;
    for z in 1..Z - 1 {
        let c = lam * w(z);
        let idx = [z - 1, z, z + 1];
        let coef = [c, -2.0 * c, c];
        for (&ia, &ca) in idx.iter().zip(&coef) {
            for (&ib, &cb) in idx.iter().zip(&coef) {
                add(&mut ata, ia, ib, ca * cb);
            }
        }
    }
    // Pixels that never produced a weighted sample would leave a zero row: pin them.
    for (j, row) in ata.iter_mut().enumerate().take(Z + p_count).skip(Z) {
        if let Some(d) = row.get_mut(j)
            && *d == 0.0
        {
            *d = 1.0;
        }
    }
    let sol = solve::<U>(&mut ata, &mut atb, Z + p_count)?;
    let top = sol.get(Z - 1).copied().unwrap_or(0.0);
    let mut x = [0.0f32; Z];
    for (xz, &g) in x.iter_mut().zip(&sol) {
        *xz = libm::exp(g - top) as f32;
    }
    if x.iter().zip(x.iter().skip(1)).any(|(a, b)| b <= a) || x.iter().any(|v| !v.is_finite()) {
        return Err(SensorError::NotMonotonic);
    }
    Ok(LogExposureTable { x })
}
