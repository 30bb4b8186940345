//! Handle outputs: the one way every entry point clears, checks and writes
//! the caller's `BzjCurve*` slots.
//!
//! The discipline ("on any error handle out-pointers are set to NULL", and
//! nothing is written or leaked after a failure):
//! 1. before the body runs, every slot the caller gave is set to NULL
//!    ([`HandleOut::cleared`], [`HandleArray::cleared`]), so that whatever
//!    fails afterwards, a panic included, leaves NULL there;
//! 2. the body checks the slots ([`HandleOut::require`],
//!    [`HandleArray::require`], [`HandleSlots::check_room`]) where its
//!    documented order of errors puts them, before computing;
//! 3. handles are made only from finished results, after the last step
//!    that can fail ([`CheckedOut::write`], [`HandleSlots::write`]), so an
//!    error writes, and leaks, nothing.
//!
//! The Lagrange splines promise that `BZJ_ERR_BUFFER_TOO_SMALL` writes
//! nothing at all: they take their array with [`HandleArray::untouched`] and
//! clear it with [`HandleSlots::clear_first`] once its room is checked.

use std::ptr::null_mut;

use bezjoin_core::Curve;

use crate::status::{FfiError, FfiResult};

/// Opaque, immutable curve handle: a Bezier curve (degree `n >= 0`,
/// dimension `dim >= 1`, parameter in `[0, 1]`) or a NURBS curve (degree
/// `p >= 1`, parameter in its domain; `bzj_curve_is_nurbs`).
pub struct BzjCurve {
    pub(crate) curve: Curve,
}

/// A caller's slot for one handle.
type Slot = *mut *mut BzjCurve;

/// Move a curve (of either kind) into a new handle (released by `bzj_curve_free`).
fn new_handle(curve: impl Into<Curve>) -> *mut BzjCurve {
    Box::into_raw(Box::new(BzjCurve {
        curve: curve.into(),
    }))
}

/// One handle out-pointer as the caller passed it (possibly NULL), its
/// slot already set to NULL.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HandleOut {
    slot: Slot,
    name: &'static str,
}

impl HandleOut {
    /// Take the caller's out-pointer and set `*slot = NULL` at once; a NULL
    /// out-pointer is left for [`require`](Self::require) to report.
    ///
    /// # Safety
    /// `slot` is null or valid for writes until the entry point returns
    /// (the later [`CheckedOut::write`] relies on it).
    pub(crate) unsafe fn cleared(slot: Slot, name: &'static str) -> Self {
        if !slot.is_null() {
            // SAFETY: non-null, the caller promises it is writable.
            unsafe { slot.write(null_mut()) };
        }
        Self { slot, name }
    }

    /// A required out-pointer: `BZJ_ERR_NULL_POINTER` naming it when NULL.
    pub(crate) fn require(self) -> FfiResult<CheckedOut> {
        self.given()
            .ok_or_else(|| FfiError::NullPointer(self.name.into()))
    }

    /// An optional out-pointer: `None` when the caller passed NULL (the
    /// result is not wanted).
    pub(crate) fn given(self) -> Option<CheckedOut> {
        (!self.slot.is_null()).then_some(CheckedOut(self.slot))
    }
}

/// Several required out-pointers, checked in order: the first NULL one is
/// the one reported.
pub(crate) fn require_all<const N: usize>(outs: [HandleOut; N]) -> FfiResult<[CheckedOut; N]> {
    let mut slots = [null_mut(); N];
    for (slot, out) in slots.iter_mut().zip(outs) {
        *slot = out.require()?.0;
    }
    Ok(slots.map(CheckedOut))
}

/// A non-null, writable handle out-pointer.
#[must_use = "a checked slot is there to be written"]
pub(crate) struct CheckedOut(Slot);

impl CheckedOut {
    /// Store a new handle owning `curve` (a Bezier or a NURBS curve) in
    /// the slot. Call it after the last step that can fail.
    pub(crate) fn write(self, curve: impl Into<Curve>) {
        // SAFETY: non-null (checked) and writable ([`HandleOut::cleared`]).
        unsafe { self.0.write(new_handle(curve)) };
    }
}

/// How a too-short handle array is reported. The message is part of the
/// behaviour of an entry point, so each keeps the one it has always given.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ShortArray {
    /// `"NAME has room for N handles, M are needed"` (the Lagrange splines).
    Handles,
    /// `"LABEL holds N doubles, M are needed"`, the buffer-of-doubles
    /// wording under `LABEL` (`bzj_fillet_chain`, `bzj_merge_chain`).
    AsDoubles(&'static str),
}

/// A caller's array of `capacity` handle slots as passed (possibly NULL).
#[derive(Debug, Clone, Copy)]
pub(crate) struct HandleArray {
    slots: Slot,
    capacity: usize,
    name: &'static str,
    short: ShortArray,
}

impl HandleArray {
    /// Take the caller's array and set all its `capacity` slots to NULL at
    /// once (a NULL array is left alone).
    ///
    /// # Safety
    /// `slots` is null or points to `capacity` handle slots writable until
    /// the entry point returns.
    pub(crate) unsafe fn cleared(
        slots: Slot,
        capacity: usize,
        name: &'static str,
        short: ShortArray,
    ) -> Self {
        // SAFETY: forwarded.
        let array = unsafe { Self::untouched(slots, capacity, name, short) };
        if let Some(given) = array.given() {
            given.clear_first(capacity);
        }
        array
    }

    /// Take the caller's array without writing to it.
    ///
    /// # Safety
    /// As [`cleared`](Self::cleared).
    pub(crate) unsafe fn untouched(
        slots: Slot,
        capacity: usize,
        name: &'static str,
        short: ShortArray,
    ) -> Self {
        Self {
            slots,
            capacity,
            name,
            short,
        }
    }

    /// Whether the caller passed NULL.
    pub(crate) fn is_null(&self) -> bool {
        self.slots.is_null()
    }

    /// The number of slots the caller declared.
    pub(crate) fn capacity(&self) -> usize {
        self.capacity
    }

    /// A required array: `BZJ_ERR_NULL_POINTER` naming it when NULL.
    pub(crate) fn require(self) -> FfiResult<HandleSlots> {
        self.given()
            .ok_or_else(|| FfiError::NullPointer(self.name.into()))
    }

    /// An optional array: `None` when the caller passed NULL.
    pub(crate) fn given(self) -> Option<HandleSlots> {
        (!self.is_null()).then_some(HandleSlots(self))
    }
}

/// A non-null array of writable handle slots.
#[must_use = "checked slots are there to be written"]
pub(crate) struct HandleSlots(HandleArray);

impl HandleSlots {
    /// Whether `needed` handles fit.
    pub(crate) fn has_room(&self, needed: usize) -> bool {
        needed <= self.0.capacity
    }

    /// `BZJ_ERR_BUFFER_TOO_SMALL` when `needed` handles do not fit, in the
    /// wording of [`ShortArray`].
    pub(crate) fn check_room(&self, needed: usize) -> FfiResult {
        if self.has_room(needed) {
            return Ok(());
        }
        let given = self.0.capacity;
        Err(match self.0.short {
            ShortArray::Handles => FfiError::HandleArrayTooSmall {
                name: self.0.name.into(),
                needed,
                given,
            },
            ShortArray::AsDoubles(label) => FfiError::BufferTooSmall {
                name: label.into(),
                needed,
                given,
            },
        })
    }

    /// Set the first `n` slots to NULL.
    ///
    /// # Panics
    /// If `n` is above the capacity (a bug: check the room first).
    pub(crate) fn clear_first(&self, n: usize) {
        assert!(
            self.has_room(n),
            "{}: {n} slots cleared in {}",
            self.0.name,
            self.0.capacity
        );
        for i in 0..n {
            // SAFETY: `i < capacity` writable slots ([`HandleArray::cleared`]).
            unsafe { self.0.slots.add(i).write(null_mut()) };
        }
    }

    /// Store a new handle for each curve (Bezier or NURBS) in the first
    /// slots, in order. Call it after the last step that can fail.
    ///
    /// # Panics
    /// If there are more curves than slots (a bug: check the room first);
    /// then nothing is written and nothing leaks.
    pub(crate) fn write<C: Into<Curve>>(self, curves: Vec<C>) {
        assert!(
            self.has_room(curves.len()),
            "{}: {} handles for {} slots",
            self.0.name,
            curves.len(),
            self.0.capacity
        );
        for (i, curve) in curves.into_iter().enumerate() {
            // SAFETY: `i < capacity` writable slots ([`HandleArray::cleared`]).
            unsafe { self.0.slots.add(i).write(new_handle(curve)) };
        }
    }
}

#[cfg(test)]
mod handle_output_tests {
    use super::*;
    use bezjoin_core::BezierCurve;

    fn point(x: f64) -> BezierCurve {
        BezierCurve::new(1, 0, vec![x]).unwrap()
    }

    fn marker() -> *mut BzjCurve {
        std::ptr::dangling_mut()
    }

    /// Take back the handles written by a test.
    fn release(slots: &[*mut BzjCurve]) -> Vec<f64> {
        slots
            .iter()
            // SAFETY: each is a handle made by `new_handle`, released once.
            .map(|&h| unsafe { Box::from_raw(h) }.curve.points()[0])
            .collect()
    }

    #[test]
    fn one_slot_is_cleared_checked_and_written() {
        let mut slot = marker();
        // SAFETY: a writable local.
        let out = unsafe { HandleOut::cleared(&mut slot, "out") };
        assert!(slot.is_null());
        out.require().unwrap().write(point(2.0));
        assert_eq!(release(&[slot]), [2.0]);

        // SAFETY: NULL is accepted.
        let missing = unsafe { HandleOut::cleared(null_mut(), "left") };
        assert!(missing.given().is_none());
        let err = missing.require().err().unwrap();
        assert_eq!(err.message(), "left is a null pointer");
    }

    #[test]
    fn require_all_reports_the_first_null_and_writes_nothing() {
        let (mut a, mut c) = (marker(), marker());
        // SAFETY: writable locals or NULL.
        let outs = unsafe {
            [
                HandleOut::cleared(&mut a, "p_trimmed"),
                HandleOut::cleared(null_mut(), "blend"),
                HandleOut::cleared(&mut c, "q_trimmed"),
            ]
        };
        assert!(a.is_null() && c.is_null());
        let err = require_all(outs).err().unwrap();
        assert_eq!(err.message(), "blend is a null pointer");
        assert!(a.is_null() && c.is_null());
    }

    #[test]
    fn arrays_are_cleared_or_untouched_and_report_their_room() {
        let mut slots = [marker(); 3];
        // SAFETY: 3 writable slots.
        let array = unsafe {
            HandleArray::untouched(slots.as_mut_ptr(), 3, "out_segments", ShortArray::Handles)
        };
        assert_eq!(slots, [marker(); 3]);
        let given = array.require().unwrap();
        assert_eq!(
            given.check_room(4).err().unwrap().message(),
            "out_segments has room for 3 handles, 4 are needed"
        );
        given.clear_first(2);
        assert!(slots[0].is_null() && slots[1].is_null() && slots[2] == marker());

        let mut slots = [marker(); 2];
        // SAFETY: 2 writable slots.
        let array = unsafe {
            HandleArray::cleared(
                slots.as_mut_ptr(),
                2,
                "out_pieces",
                ShortArray::AsDoubles("out_pieces (handles)"),
            )
        };
        assert!(slots.iter().all(|h| h.is_null()));
        let given = array.require().unwrap();
        assert_eq!(
            given.check_room(3).err().unwrap().message(),
            "out_pieces (handles) holds 2 doubles, 3 are needed"
        );
        given.write(vec![point(1.0), point(2.0)]);
        assert_eq!(release(&slots), [1.0, 2.0]);

        // SAFETY: NULL is accepted.
        let missing = unsafe { HandleArray::cleared(null_mut(), 5, "pieces", ShortArray::Handles) };
        assert!(missing.is_null() && missing.given().is_none());
        assert_eq!(
            missing.require().err().unwrap().message(),
            "pieces is a null pointer"
        );
    }
}
