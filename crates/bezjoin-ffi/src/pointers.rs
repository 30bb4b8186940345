//! Pointer helpers for the inputs and the non-handle outputs of the entry
//! points: a curve handle to read, input arrays and values, output buffers
//! of doubles, out-pointers for one value. Handle outputs are in `handles.rs`.

use bezjoin_core::{BezjoinError, Curve};

use crate::handles::BzjCurve;
use crate::status::{FfiError, FfiResult};

/// The caller's curve (Bezier or NURBS) behind `ptr`, or NULL_POINTER
/// naming `name`.
///
/// # Safety
/// `ptr` is null or a live handle from this library.
pub(crate) unsafe fn curve_ref<'a>(ptr: *const BzjCurve, name: &str) -> FfiResult<&'a Curve> {
    // SAFETY: the caller promises a live handle or null.
    match unsafe { ptr.as_ref() } {
        Some(h) => Ok(&h.curve),
        None => Err(null_pointer(name)),
    }
}

/// NULL_POINTER naming `name`. Cold and out of line, as every error of
/// these helpers: the entry points' hot paths keep no string building in
/// their frames (issue 20: a third of an evaluation's time was the frame
/// of its guard).
#[cold]
#[inline(never)]
fn null_pointer(name: &str) -> FfiError {
    FfiError::NullPointer(name.into())
}

/// BUFFER_TOO_SMALL for the output `name` (cold, as [`null_pointer`]).
#[cold]
#[inline(never)]
fn buffer_too_small(name: &str, needed: usize, given: usize) -> FfiError {
    FfiError::BufferTooSmall {
        name: name.into(),
        needed,
        given,
    }
}

/// INVALID_ARGUMENT for a length no array can have (cold, as
/// [`null_pointer`]).
#[cold]
#[inline(never)]
fn impossible_length(name: &str, len: usize) -> FfiError {
    FfiError::Core(BezjoinError::invalid(
        format!("length of {name}"),
        format!("{len} is larger than any array can be"),
    ))
}

/// The caller's array of `len` doubles; a null pointer is accepted only when `len == 0`.
///
/// # Safety
/// `ptr` is null or points to `len` readable doubles.
pub(crate) unsafe fn input_slice<'a, T>(
    ptr: *const T,
    len: usize,
    name: &str,
) -> FfiResult<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(null_pointer(name));
    }
    check_possible_length::<T>(len, name)?;
    // SAFETY: non-null and the caller promises `len` readable elements.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// The caller's output buffer, checked against the length needed.
///
/// # Safety
/// `ptr` is null or points to `given` writable doubles.
#[inline]
pub(crate) unsafe fn output_slice<'a>(
    ptr: *mut f64,
    given: usize,
    needed: usize,
    name: &str,
) -> FfiResult<&'a mut [f64]> {
    if ptr.is_null() {
        return Err(null_pointer(name));
    }
    check_possible_length::<f64>(given, name)?;
    if given < needed {
        return Err(buffer_too_small(name, needed, given));
    }
    // SAFETY: non-null and the caller promises `given >= needed` writable doubles.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, needed) })
}

/// A length no array can have (more than `isize::MAX` bytes) is a caller
/// error, reported before any slice is made (making one would be UB).
#[inline]
fn check_possible_length<T>(len: usize, name: &str) -> FfiResult {
    let largest = isize::MAX as usize / std::mem::size_of::<T>().max(1);
    if len > largest {
        return Err(impossible_length(name, len));
    }
    Ok(())
}

/// A required pointer to one value to read.
///
/// # Safety
/// `ptr` is null or valid for reads.
pub(crate) unsafe fn input_ref<'a, T>(ptr: *const T, name: &str) -> FfiResult<&'a T> {
    // SAFETY: the caller promises null or a valid pointer.
    unsafe { ptr.as_ref() }.ok_or_else(|| FfiError::NullPointer(name.into()))
}

/// A required out-pointer for one value.
pub(crate) fn require_out<T>(ptr: *mut T, name: &str) -> FfiResult<*mut T> {
    if ptr.is_null() {
        Err(FfiError::NullPointer(name.into()))
    } else {
        Ok(ptr)
    }
}

/// Write `value` through an optional out-pointer (a report, a chosen
/// scale): nothing when the caller passed NULL.
///
/// # Safety
/// `ptr` is null or valid for writes.
pub(crate) unsafe fn write_optional<T>(ptr: *mut T, value: T) {
    if !ptr.is_null() {
        // SAFETY: non-null, the caller promises it is writable.
        unsafe { ptr.write(value) };
    }
}

/// The scales a library-chosen scale used, `alpha` and `beta`, through two
/// optional out-pointers (the automatic scale's single `s` passes NULL as
/// the second: `alpha = beta = s`).
///
/// # Safety
/// Each pointer is null or valid for writes.
pub(crate) unsafe fn write_scales([p_out, q_out]: [*mut f64; 2], (alpha, beta): (f64, f64)) {
    // SAFETY: forwarded.
    unsafe {
        write_optional(p_out, alpha);
        write_optional(q_out, beta);
    }
}
