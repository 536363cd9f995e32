//! The [`Tabulated`] BRDF plugin.

use super::coords::{H_MIN, coords_above, coords_unit};
use super::grid::{CellMap, Cells};
use super::sampling::DEFAULT_COSINE_WEIGHT;
use super::{HalfVectorDistribution, MAX_VALUE, RusinkiewiczGrid, TabulatedError};
use crate::microfacet::{is_unit, unitize};
use core::fmt;
#[cfg(feature = "simd")]
use radiometry::batch::Vec3Soa;
use radiometry::glam::Vec3;
use radiometry::{Brdf, BrdfSample, IsotropicBrdf, Spectrum};

/// An isotropic BRDF tabulated on a [`RusinkiewiczGrid`], interpolated
/// trilinearly; see the [module documentation](super).
///
/// # Formula
///
/// With the continuous grid indices `u_h = √(θh/(π/2))·Nh`,
/// `u_d = θd/(π/2)·Nd`, `u_φ = φd/π·Nφ` of `(ωi, ωo)` (Rusinkiewicz 1998;
/// φd folded into `[0, π)`), cell corners `i = ⌊u⌋`, weights `t = u − ⌊u⌋`,
///
/// ```text
/// f_r(ωi, ωo) = Σ_{a,b,c ∈ {0,1}} (1−t_h)^{1−a} t_h^a (1−t_d)^{1−b} t_d^b (1−t_φ)^{1−c} t_φ^c
///               · F[i_h + a, i_d + b, i_φ + c]
/// ```
///
/// for `cos θi > 0` and `cos θo > 0`, else 0. The θ axes are constant past
/// their last node (MERL's last θd node is 89°, the last θh node 87.0°);
/// the φd axis is periodic (node `Nφ` is node 0, by reciprocity). The
/// result is a convex combination of table values: finite, `≥ 0`, and
/// exactly reciprocal (the coordinates are computed symmetrically).
///
/// # Storage: `&'a [S]`, one spectrum per node
///
/// Values are borrowed, interleaved by node (`&[Vec3]` for RGB, `&[f32]`
/// for one channel): the 8 corner lookups of one evaluation touch 8
/// contiguous spectra instead of 24 scattered floats for per-channel
/// planes, and a monochrome table costs one channel only. The caller owns
/// the memory (a MERL table is 1 458 000 `Vec3`, 17.5 MB) and applies any
/// scaling before construction; missing values must be replaced (e.g. by
/// 0) since the constructor rejects negative entries.
///
/// # Speed
///
/// `radiometry bench` (Intel Xeon, Cascade Lake, 2 shared cores, `-C
/// target-cpu=native`, n = 4096 pairs over the hemisphere, table of 5.8 MB),
/// scalar `eval`: 17.3 M/s (0.10 × the in-run fewest-division GGX
/// reference); with feature `simd`, `eval_batch` 31.1 M/s and
/// `eval_batch_soa` 34.3 M/s (16 lanes; the coordinates in vector form, the
/// table reads per lane). The scalar path is latency-bound: one dependent
/// chain (the sums, one division and square root, the arctangent
/// polynomial, the θh square-root mapping, the index arithmetic, a table
/// read that usually misses L1, the trilinear sum) of which the
/// out-of-order core overlaps little more than one evaluation with the
/// next.
///
/// # Sampling
///
/// [`Tabulated::new`] keeps the default cosine sampling of
/// [`Brdf::sample`]. [`Tabulated::with_sampling`] builds the half-vector
/// distribution of [`HalfVectorDistribution`] into a caller buffer of
/// [`Tabulated::sampling_buffer_len`] floats: exact pdf, with χ² and
/// variance figures in the [`sampling`](super::sampling) module.
///
/// # Example
///
/// ```
/// use radiometry::{Brdf, glam::Vec3};
/// use radiometry_brdfs::tabulated::{RusinkiewiczGrid, Tabulated};
///
/// // A constant table: f = 0.25 everywhere above the horizon.
/// let grid = RusinkiewiczGrid::new(16, 16, 8)?;
/// let values = vec![0.25f32; grid.len()];
/// let mut buf = vec![0.0f32; Tabulated::<f32>::sampling_buffer_len(&grid)];
/// let brdf = Tabulated::new(grid, &values)?.with_sampling(&mut buf)?;
/// let wo = Vec3::new(0.6, 0.0, 0.8);
/// assert!((brdf.eval(Vec3::Z, wo) - 0.25).abs() < 1e-6);
/// let s = brdf.sample(wo, [0.1, 0.5]).unwrap();
/// assert_eq!(s.pdf, brdf.pdf(s.wi, wo));
/// # Ok::<(), radiometry_brdfs::tabulated::TabulatedError>(())
/// ```
#[derive(Clone, Copy, PartialEq)]
pub struct Tabulated<'a, S: Spectrum = Vec3> {
    grid: RusinkiewiczGrid,
    /// The lookup constants of `grid`, computed once.
    map: CellMap,
    values: &'a [S],
    sampling: Option<HalfVectorDistribution<'a>>,
}

impl<S: Spectrum> fmt::Debug for Tabulated<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Tabulated")
            .field("grid", &self.grid)
            .field("values", &self.values.len())
            .field("sampling", &self.sampling.map(|d| d.cosine_weight()))
            .finish()
    }
}

impl<'a, S: Spectrum> Tabulated<'a, S> {
    /// A BRDF over `values` (one spectrum per node of `grid`, in the flat
    /// order of [`RusinkiewiczGrid::index`]) with cosine sampling.
    ///
    /// # Errors
    /// [`TabulatedError::Length`] when `values.len() != grid.len()`,
    /// [`TabulatedError::NotFinite`] for a NaN or infinite channel,
    /// [`TabulatedError::OutOfRange`] for a channel outside
    /// `[0, MAX_VALUE]` (the first offending value is reported).
    pub fn new(grid: RusinkiewiczGrid, values: &'a [S]) -> Result<Self, TabulatedError> {
        if values.len() != grid.len() {
            return Err(TabulatedError::Length {
                expected: grid.len(),
                found: values.len(),
            });
        }
        for (index, v) in values.iter().enumerate() {
            for channel in 0..S::CHANNELS {
                let value = v.channel(channel);
                if !value.is_finite() {
                    return Err(TabulatedError::NotFinite { index, channel });
                }
                if !(0.0..=MAX_VALUE).contains(&value) {
                    return Err(TabulatedError::OutOfRange {
                        index,
                        channel,
                        value,
                    });
                }
            }
        }
        Ok(Self {
            grid,
            map: CellMap::new(grid),
            values,
            sampling: None,
        })
    }

    /// Floats needed by [`with_sampling`](Self::with_sampling) for `grid`:
    /// `3 (n_theta_h + 1)` and a guide table (2,001 in all for MERL).
    pub fn sampling_buffer_len(grid: &RusinkiewiczGrid) -> usize {
        HalfVectorDistribution::buffer_len(grid)
    }

    /// Enables importance sampling with the half-vector distribution built
    /// into `buffer`, cosine weight
    /// [`DEFAULT_COSINE_WEIGHT`](super::sampling::DEFAULT_COSINE_WEIGHT).
    ///
    /// # Errors
    /// [`TabulatedError::Buffer`] when `buffer` is too short.
    pub fn with_sampling(self, buffer: &'a mut [f32]) -> Result<Self, TabulatedError> {
        self.with_sampling_weight(buffer, DEFAULT_COSINE_WEIGHT)
    }

    /// [`with_sampling`](Self::with_sampling) with cosine weight
    /// `c ∈ (0, 1]`.
    ///
    /// # Errors
    /// [`TabulatedError::Buffer`] when `buffer` is too short,
    /// [`TabulatedError::CosineWeight`] for `c ∉ (0, 1]`.
    pub fn with_sampling_weight(
        self,
        buffer: &'a mut [f32],
        cosine_weight: f32,
    ) -> Result<Self, TabulatedError> {
        let d = HalfVectorDistribution::build(&self.grid, self.values, buffer, cosine_weight)?;
        Ok(Self {
            sampling: Some(d),
            ..self
        })
    }

    /// The grid.
    pub fn grid(&self) -> RusinkiewiczGrid {
        self.grid
    }

    /// The borrowed values.
    pub fn values(&self) -> &'a [S] {
        self.values
    }

    /// The sampling distribution, if enabled.
    pub fn sampling(&self) -> Option<&HalfVectorDistribution<'a>> {
        self.sampling.as_ref()
    }

    /// The trilinear interpolation of the [formula](Self) at
    /// `(θh, θd, φd)` with `φd` folded into `[0, π]` (no horizon test).
    #[inline(always)]
    pub fn lookup(&self, theta_h: f32, theta_d: f32, phi_d: f32) -> S {
        self.lookup_cells(self.map.cells(theta_h, theta_d, phi_d))
    }

    /// [`lookup`](Self::lookup) from `√θh` (the vector kernel's per-lane
    /// reads; the same bits).
    #[cfg(feature = "simd")]
    #[inline(always)]
    pub(crate) fn lookup_root(&self, root_theta_h: f32, theta_d: f32, phi_d: f32) -> S {
        self.lookup_cells(self.map.cells_root(root_theta_h, theta_d, phi_d))
    }

    /// The trilinear interpolation over the cells `c`.
    #[inline(always)]
    fn lookup_cells(&self, c: Cells) -> S {
        let (np, plane) = (self.map.row, self.map.plane);
        // Two independent products (not `np·(id + nd·ih)`): shorter latency.
        let row = |ih: usize, id: usize| plane * ih + np * id;
        let [th, td, tp] = c.t;
        let at = |row: usize| -> S {
            let a = self.values.get(row + c.p[0]).copied().unwrap_or_default();
            let b = self.values.get(row + c.p[1]).copied().unwrap_or_default();
            a * (1.0 - tp) + b * tp
        };
        let lo = at(row(c.h[0], c.d[0])) * (1.0 - td) + at(row(c.h[0], c.d[1])) * td;
        let hi = at(row(c.h[1], c.d[0])) * (1.0 - td) + at(row(c.h[1], c.d[1])) * td;
        lo * (1.0 - th) + hi * th
    }

    /// `eval` for unit directions.
    #[inline(always)]
    fn eval_unit(&self, wi: Vec3, wo: Vec3) -> S {
        if wi.z > 0.0 && wo.z > 0.0 {
            let (th, td, pd) = coords_unit(wi, wo);
            self.lookup(th, td, pd)
        } else {
            S::zero()
        }
    }

    /// The cold path of `eval`: non-unit, degenerate or non-finite input,
    /// and unit pairs with `‖ωi + ωo‖² <` `H_MIN` (nearly opposite, both
    /// grazing).
    #[cold]
    #[inline(never)]
    fn eval_cold(&self, wi: Vec3, wo: Vec3) -> S {
        match (unitize(wi), unitize(wo)) {
            (Some(a), Some(b)) => self.eval_unit(a, b),
            _ => S::zero(),
        }
    }
    /// `pdf` for unit directions.
    #[inline]
    fn pdf_unit(&self, wi: Vec3, wo: Vec3) -> f32 {
        match &self.sampling {
            Some(d) => d.pdf(wi, wo),
            None if wi.z > 0.0 && wo.z > 0.0 => wi.z * core::f32::consts::FRAC_1_PI,
            None => 0.0,
        }
    }
}

impl<S: Spectrum> Brdf for Tabulated<'_, S> {
    type Spectrum = S;

    /// The trilinear interpolation of the [formula](Tabulated). Hot path:
    /// one horizon test, then one test that both directions are unit (to
    /// `4ε`) and `‖ωi + ωo‖² ≥ 10⁻²⁰`, then straight-line arithmetic (the
    /// coordinates of `coords_above` in the grid module's source: three
    /// polynomial arctangents, four square roots, three divisions) and the
    /// 8 table reads; anything else takes a cold normalising path.
    #[inline]
    fn eval(&self, wi: Vec3, wo: Vec3) -> S {
        if !(wi.z > 0.0 && wo.z > 0.0) {
            // Normalising keeps the sign of z, and NaN fails the test.
            return S::zero();
        }
        let h = wi + wo;
        let hh = h.length_squared();
        if is_unit(wi) & is_unit(wo) & (hh >= H_MIN) {
            let (th, td, pd) = coords_above(h, hh, wi - wo);
            self.lookup(th, td, pd)
        } else {
            self.eval_cold(wi, wo)
        }
    }

    /// With the `simd` feature: the coordinates of [`LANES`](crate::simd::LANES)
    /// pairs in vector form, then the table reads per lane
    /// (`tabulated::batch`); bit-identical to [`eval`](Brdf::eval).
    #[cfg(feature = "simd")]
    fn eval_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [S]) {
        crate::simd::Batch::Aos(wi, wo, out).run(&super::batch::Eval(self))
    }

    /// With the `simd` feature a vector kernel (`tabulated::batch`);
    /// bit-identical to [`pdf`](Brdf::pdf).
    #[cfg(feature = "simd")]
    fn pdf_batch(&self, wi: &[Vec3], wo: &[Vec3], out: &mut [f32]) {
        crate::simd::Batch::Aos(wi, wo, out).run(&super::batch::Pdf(self))
    }

    /// The structure-of-arrays form of [`eval_batch`](Brdf::eval_batch)
    /// (the same vector kernel with plain loads); bit-identical to
    /// [`eval`](Brdf::eval).
    #[cfg(feature = "simd")]
    fn eval_batch_soa(&self, wi: Vec3Soa<'_>, wo: Vec3Soa<'_>, out: &mut [S]) {
        crate::simd::Batch::Soa(wi, wo, out).run(&super::batch::Eval(self))
    }

    /// The mixture of [`HalfVectorDistribution::sample`] when sampling is
    /// enabled, else cosine sampling; the returned pdf is
    /// [`pdf`](Brdf::pdf)`(wi, wo)` bit for bit.
    fn sample(&self, wo: Vec3, u: [f32; 2]) -> Option<BrdfSample<S>> {
        let wo = if is_unit(wo) { wo } else { unitize(wo)? };
        if wo.z <= 0.0 {
            return None;
        }
        let wi = match &self.sampling {
            Some(d) => d.sample(wo, u)?,
            None => radiometry::warp::square_to_cosine_hemisphere(u),
        };
        let wi = if is_unit(wi) { wi } else { unitize(wi)? };
        let pdf = self.pdf_unit(wi, wo);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let w = self.eval_unit(wi, wo) * (wi.z / pdf);
        w.is_finite().then_some(BrdfSample { wi, pdf, weight: w })
    }

    /// The density of [`sample`](Brdf::sample) (see
    /// [`HalfVectorDistribution::pdf`]); 0 when either direction is at or
    /// below the horizon or degenerate.
    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        if is_unit(wi) && is_unit(wo) {
            self.pdf_unit(wi, wo)
        } else {
            match (unitize(wi), unitize(wo)) {
                (Some(a), Some(b)) => self.pdf_unit(a, b),
                _ => 0.0,
            }
        }
    }
}

impl<S: Spectrum> IsotropicBrdf for Tabulated<'_, S> {}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use radiometry::batch::Vec3Soa;
    use std::vec;
    use std::vec::Vec;

    /// A table linear in the three continuous indices is reproduced exactly
    /// (trilinear interpolation is exact on multilinear data) inside the
    /// grid; checked at f64-built directions.
    #[test]
    fn trilinear_is_exact_on_multilinear_data() {
        let grid = RusinkiewiczGrid::new(10, 12, 8).unwrap();
        let f = |a: f64, b: f64, c: f64| 1.0 + 0.5 * a + 0.25 * b + 0.125 * c.min(7.0);
        let mut values = vec![0.0f32; grid.len()];
        for i in 0..10 {
            for j in 0..12 {
                for k in 0..8 {
                    values[grid.index(i, j, k)] = f(i as f64, j as f64, k as f64) as f32;
                }
            }
        }
        let t = Tabulated::new(grid, &values).unwrap();
        for &(th, td, pd) in &[(0.3f64, 0.4f64, 1.0f64), (0.05, 1.2, 0.2), (0.9, 0.1, 2.5)] {
            let (ua, ub, uc) = (
                (th / core::f64::consts::FRAC_PI_2).sqrt() * 10.0,
                td / core::f64::consts::FRAC_PI_2 * 12.0,
                pd / core::f64::consts::PI * 8.0,
            );
            let got = t.lookup(th as f32, td as f32, pd as f32) as f64;
            assert!((got - f(ua, ub, uc)).abs() < 1e-5, "{th} {td} {pd}: {got}");
        }
        // Periodic φd: between node 7 and node 0.
        let got = t.lookup(0.3, 0.4, (7.5 / 8.0 * core::f64::consts::PI) as f32) as f64;
        let (ua, ub) = (
            (0.3f64 / core::f64::consts::FRAC_PI_2).sqrt() * 10.0,
            0.4 / core::f64::consts::FRAC_PI_2 * 12.0,
        );
        let want = 0.5 * (f(ua, ub, 7.0) + f(ua, ub, 0.0));
        assert!((got - want).abs() < 1e-5, "{got} {want}");
    }

    /// `eval_batch` and `eval_batch_soa` (the vector kernel with feature
    /// `simd`, else the default loops) equal `eval` bit for bit, including hard inputs and a length that is not a multiple of
    /// the chunk; extra outputs are zeroed (the batch length rule).
    #[test]
    fn batch_equals_scalar() {
        let grid = RusinkiewiczGrid::new(9, 7, 5).unwrap();
        let values: Vec<Vec3> = (0..grid.len())
            .map(|i| Vec3::new((i % 11) as f32, (i % 5) as f32 * 0.5, 0.1))
            .collect();
        let t = Tabulated::new(grid, &values).unwrap();
        let n = 517;
        let dir = |k: usize, s: f32| {
            let a = k as f32 * s;
            match k % 9 {
                0 => Vec3::ZERO,
                1 => Vec3::new(a.cos(), a.sin(), -0.2),
                2 => Vec3::new(a.cos(), a.sin(), 0.3) * 4.0,
                _ => Vec3::new(a.cos() * 0.6, a.sin() * 0.6, 0.8),
            }
        };
        let wi: Vec<Vec3> = (0..n).map(|k| dir(k, 0.7)).collect();
        let wo: Vec<Vec3> = (0..n).map(|k| dir(k + 3, 1.3)).collect();
        let mut out = vec![Vec3::splat(-1.0); n + 2];
        t.eval_batch(&wi, &wo, &mut out);
        let xs = |w: &[Vec3], c: usize| w.iter().map(|v| v[c]).collect::<Vec<f32>>();
        let (ix, iy, iz, ox, oy, oz) = (
            xs(&wi, 0),
            xs(&wi, 1),
            xs(&wi, 2),
            xs(&wo, 0),
            xs(&wo, 1),
            xs(&wo, 2),
        );
        let mut out2 = vec![Vec3::splat(-1.0); n];
        t.eval_batch_soa(
            Vec3Soa::new(&ix, &iy, &iz),
            Vec3Soa::new(&ox, &oy, &oz),
            &mut out2,
        );
        for k in 0..n {
            let e = t.eval(wi[k], wo[k]);
            assert_eq!(
                out[k].to_array().map(f32::to_bits),
                e.to_array().map(f32::to_bits),
                "{k}"
            );
            assert_eq!(
                out2[k].to_array().map(f32::to_bits),
                e.to_array().map(f32::to_bits),
                "{k}"
            );
        }
        // The batch length rule: outputs past the inputs are zeroed.
        assert_eq!(out[n], Vec3::ZERO);
    }

    /// `eval_batch` / `eval_batch_soa` equal `eval` bit for bit over a
    /// sweep of 40 000 pairs on a MERL-shaped grid, mixing every path of
    /// the scalar code in every lane position: generic pairs, mirror pairs
    /// (θh = 0, the pole branch), `ωi = ωo` (θd = 0), nearly opposite
    /// grazing pairs (`‖ωi + ωo‖² <` `H_MIN`, the cold path), below the
    /// horizon, non-unit and NaN.
    #[test]
    fn batch_equals_scalar_sweep() {
        let grid = RusinkiewiczGrid::new(90, 90, 180).unwrap();
        let values: Vec<f32> = (0..grid.len())
            .map(|i| ((i * 7919) % 1000) as f32 * 1e-3)
            .collect();
        let t = Tabulated::new(grid, &values).unwrap();
        let n = 40_000;
        let mut wi = Vec::with_capacity(n);
        let mut wo = Vec::with_capacity(n);
        for k in 0..n {
            let a = (k as f32 * 0.618_034).fract() * 1.56;
            let b = (k as f32 * 0.381_966).fract() * core::f32::consts::TAU;
            let c = (k as f32 * 0.754_878).fract() * 1.56;
            let d = (k as f32 * 0.569_840).fract() * core::f32::consts::TAU;
            let i = Vec3::new(a.sin() * b.cos(), a.sin() * b.sin(), a.cos());
            let o = Vec3::new(c.sin() * d.cos(), c.sin() * d.sin(), c.cos());
            let (i, o) = match k % 11 {
                1 => (i, Vec3::new(-i.x, -i.y, i.z)),
                2 => (i, i),
                3 => (Vec3::new(i.x, i.y, 1e-7), Vec3::new(-i.x, -i.y, 3e-7)),
                4 => (i, Vec3::new(o.x, o.y, -o.z)),
                5 => (i * 1.5, o),
                6 => (i, Vec3::NAN),
                _ => (i, o),
            };
            wi.push(i);
            wo.push(o);
        }
        let mut out = vec![-1.0f32; n];
        t.eval_batch(&wi, &wo, &mut out);
        let xs = |w: &[Vec3], c: usize| w.iter().map(|v| v[c]).collect::<Vec<f32>>();
        let (ix, iy, iz, ox, oy, oz) = (
            xs(&wi, 0),
            xs(&wi, 1),
            xs(&wi, 2),
            xs(&wo, 0),
            xs(&wo, 1),
            xs(&wo, 2),
        );
        let mut out2 = vec![-1.0f32; n];
        t.eval_batch_soa(
            Vec3Soa::new(&ix, &iy, &iz),
            Vec3Soa::new(&ox, &oy, &oz),
            &mut out2,
        );
        for k in 0..n {
            let e = t.eval(wi[k], wo[k]);
            assert_eq!(out[k].to_bits(), e.to_bits(), "{k}: {:?} {:?}", wi[k], wo[k]);
            assert_eq!(out2[k].to_bits(), e.to_bits(), "{k}");
            // Exactly reciprocal, and exactly the lookup at `half_diff`.
            assert_eq!(t.eval(wo[k], wi[k]).to_bits(), e.to_bits(), "{k}");
            if wi[k].z > 0.0 && wo[k].z > 0.0 {
                let (a, b, c) = RusinkiewiczGrid::half_diff(wi[k], wo[k]);
                assert_eq!(t.lookup(a, b, c).to_bits(), e.to_bits(), "{k}");
            }
        }
    }

    /// `pdf_batch` (the vector kernel with feature `simd`, else the default
    /// loop) equals `pdf` bit for bit, with and without sampling, over the
    /// pairs of `batch_equals_scalar_sweep` (mirror, `ωi = ωo`, nearly
    /// opposite grazing, below the horizon, non-unit, NaN) plus `ωi = −ωo`.
    #[test]
    fn pdf_batch_equals_pdf() {
        let grid = RusinkiewiczGrid::new(90, 90, 180).unwrap();
        let values: Vec<f32> = (0..grid.len())
            .map(|i| ((i * 7919) % 1000) as f32 * 1e-3)
            .collect();
        let mut buf = vec![0.0f32; Tabulated::<f32>::sampling_buffer_len(&grid)];
        let plain = Tabulated::new(grid, &values).unwrap();
        let sampled = Tabulated::new(grid, &values)
            .unwrap()
            .with_sampling(&mut buf)
            .unwrap();
        let n = 20_003;
        let mut wi = Vec::with_capacity(n);
        let mut wo = Vec::with_capacity(n);
        for k in 0..n {
            let a = (k as f32 * 0.618_034).fract() * 1.56;
            let b = (k as f32 * 0.381_966).fract() * core::f32::consts::TAU;
            let c = (k as f32 * 0.754_878).fract() * 1.56;
            let d = (k as f32 * 0.569_840).fract() * core::f32::consts::TAU;
            let i = Vec3::new(a.sin() * b.cos(), a.sin() * b.sin(), a.cos());
            let o = Vec3::new(c.sin() * d.cos(), c.sin() * d.sin(), c.cos());
            let (i, o) = match k % 12 {
                1 => (i, Vec3::new(-i.x, -i.y, i.z)),
                2 => (i, i),
                3 => (Vec3::new(i.x, i.y, 1e-7), Vec3::new(-i.x, -i.y, 3e-7)),
                4 => (i, Vec3::new(o.x, o.y, -o.z)),
                5 => (i * 1.5, o),
                6 => (i, Vec3::NAN),
                7 => (i, -i),
                _ => (i, o),
            };
            wi.push(i);
            wo.push(o);
        }
        let mut positive = 0;
        for t in [&plain, &sampled] {
            let mut out = vec![-1.0f32; n + 2];
            t.pdf_batch(&wi, &wo, &mut out);
            for k in 0..n {
                let p = t.pdf(wi[k], wo[k]);
                assert_eq!(out[k].to_bits(), p.to_bits(), "{k}: {:?} {:?}", wi[k], wo[k]);
                positive += usize::from(p > 0.0);
            }
            assert_eq!(out[n], 0.0, "batch length rule: the tail is zeroed");
        }
        assert!(positive > n, "{positive}");
    }

    #[test]
    fn constructor_errors() {
        let grid = RusinkiewiczGrid::new(2, 2, 2).unwrap();
        let mut v: Vec<Vec3> = vec![Vec3::splat(0.1); 8];
        assert!(Tabulated::new(grid, &v[..7]).is_err());
        v[5].y = f32::NAN;
        assert_eq!(
            Tabulated::new(grid, &v).unwrap_err(),
            TabulatedError::NotFinite { index: 5, channel: 1 }
        );
        v[5].y = -1.0;
        assert!(matches!(
            Tabulated::new(grid, &v),
            Err(TabulatedError::OutOfRange {
                index: 5,
                channel: 1,
                ..
            })
        ));
        v[5].y = 2e30;
        assert!(Tabulated::new(grid, &v).is_err());
        v[5].y = 1e30;
        let t = Tabulated::new(grid, &v).unwrap();
        // Interpolating huge values stays finite.
        assert!(t.eval(Vec3::Z, Vec3::new(0.6, 0.0, 0.8)).is_finite());
    }

    /// Hard inputs: horizon, below, non-unit, zero, NaN, ωi = −ωo.
    #[test]
    fn hard_inputs_are_finite_and_zero_below() {
        let grid = RusinkiewiczGrid::new(6, 6, 6).unwrap();
        let values: Vec<f32> = (0..grid.len()).map(|i| (i % 7) as f32).collect();
        let mut buf = vec![0.0f32; Tabulated::<f32>::sampling_buffer_len(&grid)];
        let t = Tabulated::new(grid, &values)
            .unwrap()
            .with_sampling(&mut buf)
            .unwrap();
        let wo = Vec3::new(0.6, 0.0, 0.8);
        for w in [
            Vec3::ZERO,
            Vec3::NAN,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.6, 0.0, -0.8),
            -wo,
            Vec3::new(f32::INFINITY, 0.0, 1.0),
        ] {
            assert_eq!(t.eval(w, wo), 0.0, "{w:?}");
            assert_eq!(t.eval(wo, w), 0.0, "{w:?}");
            assert_eq!(t.pdf(w, wo), 0.0, "{w:?}");
        }
        assert!((t.eval(Vec3::Z * 3.0, wo * 1e-20) - t.eval(Vec3::Z, wo)).abs() < 1e-5);
        for u in [
            [0.0, 0.0],
            [1.0 - f32::EPSILON, 1.0 - f32::EPSILON],
            [0.25, 0.5],
            [0.3, 0.99],
        ] {
            if let Some(s) = t.sample(wo, u) {
                assert!(s.pdf > 0.0 && s.pdf.is_finite() && s.weight.is_finite());
                assert_eq!(s.pdf, t.pdf(s.wi, wo));
            }
        }
        assert!(t.sample(-wo, [0.5, 0.5]).is_none());
    }
}
