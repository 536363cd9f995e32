//! Batched directions in structure-of-arrays form.
//!
//! A wavefront renderer keeps the components of many directions in separate
//! arrays (`x[k]`, `y[k]`, `z[k]`) so that vector units load eight `x`
//! values with one instruction. [`Vec3Soa`] is a borrowed view of such
//! arrays; [`Brdf::eval_batch_soa`](crate::Brdf::eval_batch_soa) takes two of
//! them. Slices of [`glam::Vec3`] (array-of-structures) go through
//! [`Brdf::eval_batch`](crate::Brdf::eval_batch) instead.
//!
//! ```
//! use radiometry::batch::Vec3Soa;
//! use radiometry::glam::Vec3;
//! let (x, y, z) = ([0.0f32, 0.6], [0.0f32, 0.0], [1.0f32, 0.8]);
//! let w = Vec3Soa::new(&x, &y, &z);
//! assert_eq!(w.len(), 2);
//! assert_eq!(w.get(1), Some(Vec3::new(0.6, 0.0, 0.8)));
//! assert_eq!(w.get(2), None);
//! ```

use glam::Vec3;

/// The length rule of every batch method in these crates
/// ([`Brdf::eval_batch`](crate::Brdf::eval_batch), `pdf_batch`,
/// `sample_batch`, `eval_batch_soa`, and the [`Integrand`](crate::Integrand)
/// batch methods): with inputs and output of different lengths, the first
/// `n = min(lengths)` outputs are computed and **every output past `n` is
/// set to zero** (`None` for samples) — a mismatched call never panics and
/// never leaves a stale value from an earlier call in `out`. This function
/// applies the second half of the rule; plugin authors who override a batch
/// method call it with the `n` they computed.
///
/// ```
/// use radiometry::Brdf;
/// use radiometry::batch::zero_tail;
/// use radiometry::glam::Vec3;
/// struct Half;
/// impl Brdf for Half {
///     type Spectrum = f32;
///     fn eval(&self, _wi: Vec3, _wo: Vec3) -> f32 { 0.5 }
/// }
/// // Two directions, three outputs: the third is zeroed, not left at 9.
/// let mut out = [9.0f32; 3];
/// Half.eval_batch(&[Vec3::Z; 2], &[Vec3::Z; 2], &mut out);
/// assert_eq!(out, [0.5, 0.5, 0.0]);
/// let mut out = [9.0f32; 4];
/// zero_tail(&mut out, 1);
/// assert_eq!(out, [9.0, 0.0, 0.0, 0.0]);
/// ```
#[inline]
pub fn zero_tail<T: Default>(out: &mut [T], n: usize) {
    for o in out.iter_mut().skip(n) {
        *o = T::default();
    }
}

/// Borrowed structure-of-arrays directions: direction `k` is
/// `(x[k], y[k], z[k])`.
///
/// There is no invariant: the view has [`len`](Self::len)` = min(x.len(),
/// y.len(), z.len())` elements and ignores the rest of the longer slices.
#[derive(Clone, Copy, Debug)]
pub struct Vec3Soa<'a> {
    /// The `x` components.
    pub x: &'a [f32],
    /// The `y` components.
    pub y: &'a [f32],
    /// The `z` components.
    pub z: &'a [f32],
}

impl<'a> Vec3Soa<'a> {
    /// A view of three component slices.
    #[inline]
    pub const fn new(x: &'a [f32], y: &'a [f32], z: &'a [f32]) -> Self {
        Vec3Soa { x, y, z }
    }

    /// Number of complete directions: the length of the shortest slice.
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len().min(self.y.len()).min(self.z.len())
    }

    /// Whether the view holds no complete direction.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Direction `k`, or `None` past the end.
    #[inline]
    pub fn get(&self, k: usize) -> Option<Vec3> {
        Some(Vec3::new(*self.x.get(k)?, *self.y.get(k)?, *self.z.get(k)?))
    }

    /// The first `n` directions (all of them if `n ≥ len`), with every
    /// component slice cut to the same length.
    #[inline]
    pub fn truncate(&self, n: usize) -> Vec3Soa<'a> {
        let n = n.min(self.len());
        Vec3Soa::new(&self.x[..n], &self.y[..n], &self.z[..n])
    }

    /// Directions `start..start + n` (clamped to the view).
    #[inline]
    pub fn window(&self, start: usize, n: usize) -> Vec3Soa<'a> {
        let len = self.len();
        let s = start.min(len);
        let e = s.saturating_add(n).min(len);
        Vec3Soa::new(&self.x[s..e], &self.y[s..e], &self.z[s..e])
    }

    /// Iterates over the directions as [`Vec3`].
    #[inline]
    pub fn iter(&self) -> impl Iterator<Item = Vec3> + 'a {
        let n = self.len();
        let (x, y, z) = (&self.x[..n], &self.y[..n], &self.z[..n]);
        x.iter().zip(y).zip(z).map(|((&x, &y), &z)| Vec3::new(x, y, z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn len_is_the_shortest_slice() {
        let x = [1.0f32, 2.0, 3.0];
        let y = [0.0f32; 2];
        let z = [0.5f32; 4];
        let w = Vec3Soa::new(&x, &y, &z);
        assert_eq!(w.len(), 2);
        assert_eq!(w.iter().count(), 2);
        assert_eq!(w.truncate(1).len(), 1);
        assert_eq!(w.window(1, 5).get(0), Some(Vec3::new(2.0, 0.0, 0.5)));
        assert!(w.window(7, 2).is_empty());
    }
}
