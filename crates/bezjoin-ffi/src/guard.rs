//! The panic guard every entry point runs in, the per-thread last error it
//! stores ([`bzj_last_error`]), and [`bzj_version`].
//!
//! Status codes and the error-to-status mapping are in `status.rs`, the
//! pointer helpers in `pointers.rs`, the handle outputs in `handles.rs`.

use std::cell::{Cell, RefCell};
use std::ffi::{CStr, CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::status::{BzjStatus, FfiResult};

thread_local! {
    static LAST_ERROR: RefCell<Message> = RefCell::new(Message::default());
    /// Whether `LAST_ERROR` may hold a message. Constant-initialised and
    /// without a destructor: one thread-local load, no lazy initialisation,
    /// no borrow.
    static HAS_MESSAGE: Cell<bool> = const { Cell::new(false) };
}

/// How many threads may hold a message (each thread counts itself once,
/// from its first stored message until the message is cleared or the
/// thread exits). While it is 0 -- the normal state of a program whose
/// calls succeed -- a success has nothing to clear in any thread, so it
/// returns without touching thread-local storage (a `__tls_get_addr` call
/// from a shared library). Sound with relaxed ordering: a thread that holds
/// a message has itself added 1 before, and only the adding thread takes
/// its 1 away, so that thread's own loads never read 0.
static THREADS_WITH_MESSAGE: AtomicUsize = AtomicUsize::new(0);

/// A thread's last error message, and whether the thread is counted in
/// [`THREADS_WITH_MESSAGE`].
#[derive(Default)]
struct Message {
    text: CString,
    counted: bool,
}

impl Message {
    fn set(&mut self, text: CString) {
        let has = !text.as_bytes().is_empty();
        if has && !self.counted {
            THREADS_WITH_MESSAGE.fetch_add(1, Ordering::Relaxed);
        } else if !has && self.counted {
            THREADS_WITH_MESSAGE.fetch_sub(1, Ordering::Relaxed);
        }
        self.counted = has;
        self.text = text;
    }
}

impl Drop for Message {
    /// At thread exit: the thread no longer holds a message.
    fn drop(&mut self) {
        if self.counted {
            THREADS_WITH_MESSAGE.fetch_sub(1, Ordering::Relaxed);
        }
    }
}

/// Returned by [`bzj_last_error`] when the thread's message cannot be read
/// (its thread-local storage already destroyed, during thread exit).
static NO_MESSAGE: &CStr = c"";

/// Store the calling thread's message. Never panics: while the thread-local
/// is being destroyed (a call from another thread-local's destructor at
/// thread exit) the message is dropped, and the status still returned.
#[inline]
fn set_last_error(message: &str) {
    // A success while no thread holds a message: nothing to clear, and no
    // thread-local access (the hot path of evaluation calls).
    if message.is_empty() && THREADS_WITH_MESSAGE.load(Ordering::Relaxed) == 0 {
        return;
    }
    store_last_error(message);
}

/// [`set_last_error`] past its shortcut. A function of its own, never
/// inlined: otherwise the compiler computes the thread-local addresses
/// (a `__tls_get_addr` call) before the shortcut's test.
#[inline(never)]
fn store_last_error(message: &str) {
    // A success after a success: nothing to store (no allocation, and no
    // access to the message storage).
    if message.is_empty() && !HAS_MESSAGE.try_with(Cell::get).unwrap_or(true) {
        return;
    }
    let _ = LAST_ERROR.try_with(|e| {
        if message.is_empty() && e.try_borrow().is_ok_and(|m| m.text.as_bytes().is_empty()) {
            return;
        }
        let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
        if let Ok(mut slot) = e.try_borrow_mut() {
            slot.set(text);
            let _ = HAS_MESSAGE.try_with(|has| has.set(!message.is_empty()));
        }
    });
}

/// Run the body of an entry point that cannot report a status (it returns
/// a pointer) inside catch_unwind: a panic, which the body is written never
/// to raise, gives `fallback` instead of unwinding into C.
pub(crate) fn no_unwind<T>(fallback: T, body: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or(fallback)
}

/// Run one entry point's body: a panic becomes `BZJ_ERR_INTERNAL`, an error
/// its status with the message stored for [`bzj_last_error`].
///
/// Inlined into each entry point, with the error and panic reports out of
/// line: the body's arguments then stay in registers instead of being
/// spilled for a closure that another function reads back (a third of a
/// degree-3 evaluation's instructions were this guard's; issue 20).
#[inline(always)]
pub(crate) fn guard(body: impl FnOnce() -> FfiResult) -> BzjStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            set_last_error("");
            BzjStatus::BZJ_OK
        }
        Ok(Err(e)) => report_error(e),
        Err(panic) => report_panic(panic),
    }
}

/// [`guard`]'s failure: the error's message stored, its status returned.
#[cold]
#[inline(never)]
fn report_error(e: crate::status::FfiError) -> BzjStatus {
    set_last_error(&e.message());
    e.status()
}

/// [`guard`]'s panic (a bug): `BZJ_ERR_INTERNAL` with the panic's text.
#[cold]
#[inline(never)]
fn report_panic(panic: Box<dyn std::any::Any + Send>) -> BzjStatus {
    let what = panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into());
    set_last_error(&format!(
        "internal error (a bug in bezjoin, please report): {what}"
    ));
    BzjStatus::BZJ_ERR_INTERNAL
}

/// Run the body of a function that cannot fail and returns nothing (the
/// release functions) inside the one catch_unwind: the last error is left
/// as it was, so `bzj_curve_free(tmp)` between a failed call and
/// `bzj_last_error()` does not erase the message. A panic (a bug) still
/// replaces it.
pub(crate) fn guard_release(body: impl FnOnce()) {
    if catch_unwind(AssertUnwindSafe(body)).is_err() {
        set_last_error("internal error (a bug in bezjoin, please report): panic while releasing");
    }
}

static VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "\0");

/// The library version, `"MAJOR.MINOR.PATCH"` (a static string).
#[unsafe(no_mangle)]
pub extern "C" fn bzj_version() -> *const c_char {
    // Cannot panic (a static's address); inside `no_unwind` all the same, so
    // that every extern "C" body runs under catch_unwind without exception.
    let version: *const c_char = VERSION.as_ptr().cast();
    no_unwind(version, || version)
}

/// The message of the calling thread's last failed call (empty after a
/// success). Valid until this thread's next bezjoin call; never NULL (an
/// empty static string when called during thread exit, after the thread's
/// message storage is gone).
#[unsafe(no_mangle)]
pub extern "C" fn bzj_last_error() -> *const c_char {
    no_unwind(NO_MESSAGE.as_ptr(), || {
        LAST_ERROR
            .try_with(|e| {
                e.try_borrow()
                    .map_or(NO_MESSAGE.as_ptr(), |m| m.text.as_ptr())
            })
            .unwrap_or(NO_MESSAGE.as_ptr())
    })
}

/// The calling thread's last error message as a `String` (for the unit
/// tests of every module of this crate).
#[cfg(test)]
pub(crate) fn last_error() -> String {
    // SAFETY: never NULL, NUL-terminated.
    unsafe { std::ffi::CStr::from_ptr(bzj_last_error()) }
        .to_str()
        .unwrap()
        .to_owned()
}

#[cfg(test)]
mod guard_tests {
    use super::*;
    use crate::status::FfiError;

    fn text(p: *const c_char) -> String {
        assert!(!p.is_null());
        // SAFETY: the library's strings are NUL-terminated and live long enough.
        unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_owned()
    }

    fn last_error() -> String {
        text(bzj_last_error())
    }

    #[test]
    fn panic_becomes_internal_with_message() {
        let s = guard(|| panic!("boom"));
        assert_eq!(s, BzjStatus::BZJ_ERR_INTERNAL);
        let msg = last_error();
        assert!(msg.contains("boom"), "{msg}");
    }

    #[test]
    fn version_is_a_static_string() {
        assert_eq!(text(bzj_version()), env!("CARGO_PKG_VERSION"));
        assert_eq!(bzj_version(), bzj_version());
    }

    /// A success clears the calling thread's message and no other: with
    /// one thread holding a message, another thread's failure then success
    /// leaves that thread's message empty (the shortcut of
    /// `set_last_error` must see the count) and the first thread's intact;
    /// then the first thread's success clears its own.
    #[test]
    fn a_success_clears_this_threads_message_only() {
        use std::sync::{Arc, Barrier};
        let held = Arc::new(Barrier::new(2));
        let checked = Arc::new(Barrier::new(2));
        let holder = {
            let (held, checked) = (held.clone(), checked.clone());
            std::thread::spawn(move || {
                let s = guard(|| Err(FfiError::NullPointer("first".into())));
                assert_eq!(s, BzjStatus::BZJ_ERR_NULL_POINTER);
                held.wait();
                checked.wait();
                assert_eq!(last_error(), "first is a null pointer");
                assert_eq!(guard(|| Ok(())), BzjStatus::BZJ_OK);
                assert_eq!(last_error(), "");
            })
        };
        let other = std::thread::spawn(move || {
            held.wait();
            for _ in 0..3 {
                let s = guard(|| Err(FfiError::NullPointer("second".into())));
                assert_eq!(s, BzjStatus::BZJ_ERR_NULL_POINTER);
                assert_eq!(last_error(), "second is a null pointer");
                assert_eq!(guard(|| Ok(())), BzjStatus::BZJ_OK);
                assert_eq!(last_error(), "");
            }
            checked.wait();
        });
        other.join().expect("the other thread's checks hold");
        holder.join().expect("the holder's checks hold");
    }

    /// Calls made from another thread-local's destructor at thread exit,
    /// after `LAST_ERROR` is gone: `bzj_last_error` returns an empty string
    /// (with `LocalKey::with` it panicked, and a panic there aborts the
    /// process), an entry point still returns its status.
    #[test]
    fn last_error_during_thread_exit_is_empty_not_a_panic() {
        use std::sync::Mutex;
        static SEEN: Mutex<Vec<(bool, String, BzjStatus, String)>> = Mutex::new(Vec::new());

        struct CallsAtExit;
        impl Drop for CallsAtExit {
            fn drop(&mut self) {
                let gone = LAST_ERROR.try_with(|_| ()).is_err();
                let before = text(bzj_last_error());
                let status = guard(|| Err(FfiError::NullPointer("late".into())));
                let after = text(bzj_last_error());
                SEEN.lock().unwrap().push((gone, before, status, after));
            }
        }
        thread_local! {
            static AT_EXIT: CallsAtExit = const { CallsAtExit };
        }

        std::thread::spawn(|| {
            // Registered first, so destroyed after LAST_ERROR (destructors
            // run in reverse order of registration on this platform).
            AT_EXIT.with(|_| ());
            let s = guard(|| Err(FfiError::NullPointer("early".into())));
            assert_eq!(s, BzjStatus::BZJ_ERR_NULL_POINTER);
            assert_eq!(last_error(), "early is a null pointer");
        })
        .join()
        .expect("the thread exits cleanly");

        let seen = SEEN.lock().unwrap();
        assert_eq!(seen.len(), 1);
        let (gone, before, status, after) = &seen[0];
        assert_eq!(*status, BzjStatus::BZJ_ERR_NULL_POINTER);
        if *gone {
            assert_eq!(before, "");
            assert_eq!(after, "");
        } else {
            // Another destructor order: the storage is still there.
            assert_eq!(before, "early is a null pointer");
            assert_eq!(after, "late is a null pointer");
        }
    }
}
