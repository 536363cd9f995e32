//! The value type of light and reflectance.
//!
//! [`Spectrum`] is implemented for `f32` (monochrome), [`glam::Vec3`] (linear
//! RGB) and [`SampledSpectrum<N>`] (N wavelength samples). Generic code over
//! `S: Spectrum` pays only for the channels of the type it is instantiated
//! with.
//!
//! ```
//! use radiometry::{Spectrum, SampledSpectrum, glam::Vec3};
//! fn luminance_proxy<S: Spectrum>(s: S) -> f32 { s.average() }
//! assert_eq!(luminance_proxy(0.5f32), 0.5);
//! assert_eq!(luminance_proxy(Vec3::new(0.0, 0.5, 1.0)), 0.5);
//! assert_eq!(luminance_proxy(SampledSpectrum::<4>::splat(2.0)), 2.0);
//! ```

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Sub};
use glam::{DVec3, Vec3};

/// A per-channel quantity: radiance, irradiance, reflectance, …
///
/// Arithmetic is channel-wise. `CHANNELS` is known at compile time, so loops
/// over channels unroll.
pub trait Spectrum:
    Copy
    + Debug
    + PartialEq
    + Default
    + Add<Output = Self>
    + AddAssign
    + Sub<Output = Self>
    + Mul<Output = Self>
    + MulAssign
    + Mul<f32, Output = Self>
    + Div<f32, Output = Self>
    + 'static
{
    /// Number of channels.
    const CHANNELS: usize;

    /// The `f64` counterpart used for accumulation and results of
    /// integrators (`f64`, `DVec3`, `[f64; N]`).
    type Wide: WideSpectrum;

    /// Widens every channel to `f64` (exact).
    #[inline]
    fn to_wide(self) -> Self::Wide {
        Self::Wide::from_fn(|i| self.channel(i) as f64)
    }

    /// Rounds every channel of a wide value to `f32`.
    #[inline]
    fn from_wide(w: Self::Wide) -> Self {
        Self::from_fn(|i| w.channel(i) as f32)
    }

    /// Every channel equal to `v`.
    fn splat(v: f32) -> Self;

    /// All channels zero.
    #[inline]
    fn zero() -> Self {
        Self::splat(0.0)
    }

    /// Channel `i` (`0 ≤ i < CHANNELS`); `0.0` when `i` is out of range.
    fn channel(&self, i: usize) -> f32;

    /// Builds a spectrum channel by channel from `f(i)`.
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self;

    /// Applies `f` to every channel.
    #[inline]
    fn map(self, mut f: impl FnMut(f32) -> f32) -> Self {
        Self::from_fn(|i| f(self.channel(i)))
    }

    /// Largest channel.
    #[inline]
    fn max_channel(&self) -> f32 {
        let mut m = self.channel(0);
        for i in 1..Self::CHANNELS {
            m = m.max(self.channel(i));
        }
        m
    }

    /// Smallest channel.
    #[inline]
    fn min_channel(&self) -> f32 {
        let mut m = self.channel(0);
        for i in 1..Self::CHANNELS {
            m = m.min(self.channel(i));
        }
        m
    }

    /// Arithmetic mean of the channels.
    #[inline]
    fn average(&self) -> f32 {
        let mut s = 0.0;
        for i in 0..Self::CHANNELS {
            s += self.channel(i);
        }
        s / Self::CHANNELS as f32
    }

    /// Whether every channel is finite.
    #[inline]
    fn is_finite(&self) -> bool {
        (0..Self::CHANNELS).all(|i| self.channel(i).is_finite())
    }

    /// Whether every channel is zero.
    #[inline]
    fn is_black(&self) -> bool {
        (0..Self::CHANNELS).all(|i| self.channel(i) == 0.0)
    }
}

impl Spectrum for f32 {
    const CHANNELS: usize = 1;
    type Wide = f64;
    #[inline]
    fn splat(v: f32) -> Self {
        v
    }
    #[inline]
    fn channel(&self, i: usize) -> f32 {
        if i == 0 { *self } else { 0.0 }
    }
    #[inline]
    fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        f(0)
    }
}

impl Spectrum for Vec3 {
    const CHANNELS: usize = 3;
    type Wide = DVec3;
    #[inline]
    fn splat(v: f32) -> Self {
        Vec3::splat(v)
    }
    #[inline]
    fn channel(&self, i: usize) -> f32 {
        match i {
            0 => self.x,
            1 => self.y,
            2 => self.z,
            _ => 0.0,
        }
    }
    #[inline]
    fn from_fn(mut f: impl FnMut(usize) -> f32) -> Self {
        Vec3::new(f(0), f(1), f(2))
    }
}

/// The `f64` counterpart of a [`Spectrum`]: what integrators accumulate
/// into and report.
pub trait WideSpectrum: Copy + Debug + PartialEq + 'static {
    /// Number of channels.
    const CHANNELS: usize;
    /// Builds a value channel by channel.
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    /// Channel `i`; `0.0` when out of range.
    fn channel(&self, i: usize) -> f64;
    /// Every channel equal to `v`.
    #[inline]
    fn splat(v: f64) -> Self {
        Self::from_fn(|_| v)
    }
    /// Applies `f` channel-wise.
    #[inline]
    fn map(self, mut f: impl FnMut(f64) -> f64) -> Self {
        Self::from_fn(|i| f(self.channel(i)))
    }
    /// Channel-wise combination of two values.
    #[inline]
    fn zip(self, other: Self, mut f: impl FnMut(f64, f64) -> f64) -> Self {
        Self::from_fn(|i| f(self.channel(i), other.channel(i)))
    }
    /// Largest channel.
    #[inline]
    fn max_channel(&self) -> f64 {
        (1..Self::CHANNELS).fold(self.channel(0), |m, i| m.max(self.channel(i)))
    }
    /// Whether every channel is finite.
    #[inline]
    fn is_finite(&self) -> bool {
        (0..Self::CHANNELS).all(|i| self.channel(i).is_finite())
    }
}

impl WideSpectrum for f64 {
    const CHANNELS: usize = 1;
    #[inline]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        f(0)
    }
    #[inline]
    fn channel(&self, i: usize) -> f64 {
        if i == 0 { *self } else { 0.0 }
    }
}

impl WideSpectrum for DVec3 {
    const CHANNELS: usize = 3;
    #[inline]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        DVec3::new(f(0), f(1), f(2))
    }
    #[inline]
    fn channel(&self, i: usize) -> f64 {
        match i {
            0 => self.x,
            1 => self.y,
            2 => self.z,
            _ => 0.0,
        }
    }
}

impl<const N: usize> WideSpectrum for [f64; N] {
    const CHANNELS: usize = N;
    #[inline]
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self {
        core::array::from_fn(f)
    }
    #[inline]
    fn channel(&self, i: usize) -> f64 {
        self.get(i).copied().unwrap_or(0.0)
    }
}

/// A spectrum sampled at `N` wavelengths (which wavelengths is up to the
/// caller: a fixed grid, or hero-wavelength samples).
///
/// A plain array wrapper with channel-wise arithmetic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampledSpectrum<const N: usize>(pub [f32; N]);

impl<const N: usize> Default for SampledSpectrum<N> {
    fn default() -> Self {
        Self([0.0; N])
    }
}

impl<const N: usize> Spectrum for SampledSpectrum<N> {
    const CHANNELS: usize = N;
    type Wide = [f64; N];
    #[inline]
    fn splat(v: f32) -> Self {
        Self([v; N])
    }
    #[inline]
    fn channel(&self, i: usize) -> f32 {
        self.0.get(i).copied().unwrap_or(0.0)
    }
    #[inline]
    fn from_fn(f: impl FnMut(usize) -> f32) -> Self {
        Self(core::array::from_fn(f))
    }
}

macro_rules! sampled_binop {
    ($tr:ident, $f:ident, $op:tt, $atr:ident, $af:ident) => {
        impl<const N: usize> $tr for SampledSpectrum<N> {
            type Output = Self;
            #[inline]
            fn $f(self, rhs: Self) -> Self {
                Self(core::array::from_fn(|i| self.0[i] $op rhs.0[i]))
            }
        }
        impl<const N: usize> $atr for SampledSpectrum<N> {
            #[inline]
            fn $af(&mut self, rhs: Self) {
                for i in 0..N {
                    self.0[i] = self.0[i] $op rhs.0[i];
                }
            }
        }
    };
}
sampled_binop!(Add, add, +, AddAssign, add_assign);
sampled_binop!(Mul, mul, *, MulAssign, mul_assign);

impl<const N: usize> Sub for SampledSpectrum<N> {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self(core::array::from_fn(|i| self.0[i] - rhs.0[i]))
    }
}

impl<const N: usize> Mul<f32> for SampledSpectrum<N> {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: f32) -> Self {
        Self(self.0.map(|v| v * rhs))
    }
}

impl<const N: usize> Div<f32> for SampledSpectrum<N> {
    type Output = Self;
    #[inline]
    fn div(self, rhs: f32) -> Self {
        Self(self.0.map(|v| v / rhs))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn generic_roundtrip<S: Spectrum>() {
        let s = S::from_fn(|i| i as f32 + 1.0);
        assert_eq!(s.channel(0), 1.0);
        assert_eq!(s.max_channel(), S::CHANNELS as f32);
        assert_eq!(s.min_channel(), 1.0);
        assert!((s.average() - (S::CHANNELS as f32 + 1.0) / 2.0).abs() < 1e-6);
        assert_eq!(s.channel(S::CHANNELS), 0.0);
        assert!(s.is_finite());
        assert!(S::zero().is_black());
        assert_eq!((s * 2.0).channel(0), 2.0);
        assert_eq!((s + s - s), s);
        assert!(!S::splat(f32::NAN).is_finite());
    }

    #[test]
    fn all_spectra_behave_alike() {
        generic_roundtrip::<f32>();
        generic_roundtrip::<Vec3>();
        generic_roundtrip::<SampledSpectrum<8>>();
    }
}
