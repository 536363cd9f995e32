//! Checked conversions of C pointers into Rust references and slices: the only
//! place the crate turns raw pointers into references.

use crate::RadStatus;
use core::mem::{align_of, size_of};

/// `&T` from a C pointer: null → [`RadStatus::NullPointer`], misaligned →
/// [`RadStatus::Misaligned`].
///
/// # Safety
/// A non-null, aligned `p` must point to a readable `T` that nothing writes
/// for the duration of the call (the C caller's side of the contract).
#[inline]
pub(crate) unsafe fn as_ref<'a, T>(p: *const T) -> Result<&'a T, RadStatus> {
    if p.is_null() {
        return Err(RadStatus::NullPointer);
    }
    if !p.is_aligned() {
        return Err(RadStatus::Misaligned);
    }
    // SAFETY: non-null and aligned (checked); readable and unaliased by the
    // caller's contract.
    Ok(unsafe { &*p })
}

/// `&mut T` from a C pointer (checks as [`as_ref`]).
///
/// # Safety
/// A non-null, aligned `p` must point to writable memory for one `T` that
/// nothing else reads or writes for the duration of the call.
#[inline]
pub(crate) unsafe fn as_mut<'a, T>(p: *mut T) -> Result<&'a mut T, RadStatus> {
    if p.is_null() {
        return Err(RadStatus::NullPointer);
    }
    if !p.is_aligned() {
        return Err(RadStatus::Misaligned);
    }
    // SAFETY: non-null and aligned (checked); writable and exclusive by the
    // caller's contract.
    Ok(unsafe { &mut *p })
}

fn check_len<T>(p: *const T, n: usize) -> Result<(), RadStatus> {
    if p.is_null() {
        return Err(RadStatus::NullPointer);
    }
    if !p.is_aligned() {
        return Err(RadStatus::Misaligned);
    }
    let bytes = n.checked_mul(size_of::<T>()).ok_or(RadStatus::TooLong)?;
    if bytes > isize::MAX as usize || (p as usize).checked_add(bytes).is_none() {
        return Err(RadStatus::TooLong);
    }
    Ok(())
}

/// `&[T]` of length `n` from a C pointer. `n = 0` gives an empty slice for any
/// pointer, null included.
///
/// # Safety
/// For `n > 0`, a non-null, aligned `p` must point to `n` readable,
/// initialised `T`s that nothing writes for the duration of the call.
#[inline]
pub(crate) unsafe fn slice<'a, T>(p: *const T, n: usize) -> Result<&'a [T], RadStatus> {
    if n == 0 {
        return Ok(&[]);
    }
    check_len(p, n)?;
    // SAFETY: non-null, aligned, `n·size_of::<T>() ≤ isize::MAX` without
    // address wrap-around (checked); readable by the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts(p, n) })
}

/// The byte range `(address, length)` of an input slice, for
/// [`slice_mut_disjoint`].
#[inline]
pub(crate) fn span<T>(s: &[T]) -> (usize, usize) {
    (s.as_ptr() as usize, core::mem::size_of_val(s))
}

/// `&mut [T]` of length `n` from a C pointer (checks as [`slice`]) that must
/// not overlap any of the `inputs` (C callers may pass one buffer as input and
/// output; Rust may not alias a `&mut` with a `&`): [`RadStatus::Overlap`].
///
/// # Safety
/// For `n > 0`, a non-null, aligned `p` must point to `n` writable `T`s (any
/// bit pattern valid for `T`) that nothing outside `inputs` uses during the call.
#[inline]
pub(crate) unsafe fn slice_mut_disjoint<'a, T>(
    p: *mut T,
    n: usize,
    inputs: &[(usize, usize)],
) -> Result<&'a mut [T], RadStatus> {
    if n == 0 {
        return Ok(&mut []);
    }
    check_len(p, n)?;
    let (o0, o1) = (p as usize, p as usize + n * size_of::<T>());
    if inputs.iter().any(|&(a, len)| len > 0 && a < o1 && o0 < a + len) {
        return Err(RadStatus::Overlap);
    }
    // SAFETY: as in `slice`, plus exclusivity: no overlap with the inputs
    // (checked) and nothing else uses it by the caller's contract.
    Ok(unsafe { core::slice::from_raw_parts_mut(p, n) })
}

// `RadVec3` and `glam::Vec3` are both `#[repr(C)] { f32, f32, f32 }`, so a
// `[RadVec3]` may be viewed as a `[Vec3]` (see `brdf::as_vec3`).
const _: () = assert!(size_of::<crate::RadVec3>() == size_of::<radiometry::glam::Vec3>());
const _: () = assert!(align_of::<crate::RadVec3>() == align_of::<radiometry::glam::Vec3>());
