//! Shared pieces of the fuzz targets: turning libFuzzer's bytes into
//! arguments of the C ABI, and the checks every call must pass.
//!
//! Every target drives the `extern "C"` functions of the `bezjoin` crate
//! (the FFI crate, used as an rlib) exactly as a C host would, with
//! arbitrary doubles (NaN, infinities, subnormals, huge values and raw bit
//! patterns), sizes and option values. The oracle: no crash, no hang, and
//! never `BZJ_ERR_INTERNAL` (a caught panic is a bug too); a failed call
//! leaves a message and NULL handles; a successful one returns handles
//! that answer `bzj_curve_degree`/`bzj_curve_dim`. Sizes are bounded
//! (degree <= 40, dim <= 4, chains <= 16 curves) so one input cannot run
//! for long.

use std::ffi::CStr;
use std::ptr::null_mut;
use std::sync::OnceLock;

pub use bezjoin::*;

/// Largest degree a target builds or asks for.
pub const MAX_DEGREE: usize = 40;
/// Largest dimension a target builds.
pub const MAX_DIM: usize = 4;
/// Largest number of curves in a chain a target builds.
pub const MAX_CHAIN: usize = 16;

/// What a target writes into handle slots before a call, to see which ones
/// the library wrote (never dereferenced).
pub fn sentinel() -> *mut BzjCurve {
    std::ptr::dangling_mut::<BzjCurve>()
}

/// A cursor over the fuzzer's bytes; reads past the end give zeros.
pub struct Input<'a> {
    data: &'a [u8],
}

impl<'a> Input<'a> {
    /// Wrap the fuzzer's input.
    pub fn new(data: &'a [u8]) -> Self {
        Self { data }
    }

    /// The next byte (0 when the input is used up).
    pub fn byte(&mut self) -> u8 {
        match self.data.split_first() {
            Some((&b, rest)) => {
                self.data = rest;
                b
            }
            None => 0,
        }
    }

    /// A value in `0..n` (`n >= 1`) from two bytes.
    pub fn below(&mut self, n: usize) -> usize {
        let v = (usize::from(self.byte()) << 8) | usize::from(self.byte());
        v % n
    }

    /// A size: mostly small, sometimes the extreme values that overflow
    /// careless arithmetic.
    pub fn size(&mut self, small: usize) -> usize {
        match self.byte() % 16 {
            0 => usize::MAX,
            1 => usize::MAX / 2 + 1,
            2 => 0,
            _ => self.below(small + 1),
        }
    }

    /// A count that no array of elements of 8 bytes or more can have (more
    /// than `isize::MAX` bytes): `SIZE_MAX`, `SIZE_MAX / 2 + 1` or
    /// `isize::MAX / 8 + 1`. The library must refuse it before reading, so it
    /// may be passed with a real (short) buffer.
    pub fn impossible_count(&mut self) -> usize {
        match self.byte() % 3 {
            0 => usize::MAX,
            1 => usize::MAX / 2 + 1,
            _ => isize::MAX as usize / 8 + 1,
        }
    }

    /// Any double: special values, raw bit patterns, or ordinary numbers.
    pub fn double(&mut self) -> f64 {
        match self.byte() % 20 {
            0 => 0.0,
            1 => -0.0,
            2 => 1.0,
            3 => 0.5,
            4 => f64::NAN,
            5 => f64::INFINITY,
            6 => f64::NEG_INFINITY,
            7 => 5e-324,
            8 => f64::MAX,
            9 => -f64::MAX,
            10 => f64::MIN_POSITIVE,
            11 => 1e-300,
            12 => 1e300,
            13..=15 => {
                let mut bits = [0u8; 8];
                bits.iter_mut().for_each(|b| *b = self.byte());
                f64::from_bits(u64::from_le_bytes(bits))
            }
            _ => self.ordinary(),
        }
    }

    /// A moderate finite number in about [-100, 100] (most coordinates).
    pub fn ordinary(&mut self) -> f64 {
        let v = (i32::from(self.byte()) << 8 | i32::from(self.byte())) - 32768;
        f64::from(v) / 327.68
    }

    /// A parameter: mostly in [-0.5, 1.5], sometimes any double.
    pub fn parameter(&mut self) -> f64 {
        if self.byte().is_multiple_of(8) {
            self.double()
        } else {
            let v = (u32::from(self.byte()) << 8) | u32::from(self.byte());
            -0.5 + 2.0 * f64::from(v) / 65535.0
        }
    }

    /// A coordinate: mostly ordinary, sometimes any double.
    pub fn coordinate(&mut self) -> f64 {
        if self.byte().is_multiple_of(8) {
            self.double()
        } else {
            self.ordinary()
        }
    }
}

/// The calling thread's last error message.
pub fn last_error() -> String {
    // SAFETY: bzj_last_error never returns NULL and the string lives until
    // this thread's next call.
    unsafe { CStr::from_ptr(bzj_last_error()) }
        .to_string_lossy()
        .into_owned()
}

/// The oracle for one call's status: never `BZJ_ERR_INTERNAL`, and a failed
/// call leaves a message.
///
/// With `BEZJOIN_FUZZ_TRACE` set in the environment every status is printed
/// to stderr with its message (to see which path a seed reaches:
/// `BEZJOIN_FUZZ_TRACE=1 cargo +nightly fuzz run <target> fuzz/seeds/<target>/*`).
pub fn check(status: BzjStatus, call: &str) {
    static TRACE: OnceLock<bool> = OnceLock::new();
    if *TRACE.get_or_init(|| std::env::var_os("BEZJOIN_FUZZ_TRACE").is_some()) {
        eprintln!("{call}: {status:?} {}", last_error());
    }
    assert_ne!(
        status,
        BzjStatus::BZJ_ERR_INTERNAL,
        "{call} returned BZJ_ERR_INTERNAL: {}",
        last_error()
    );
    if status != BzjStatus::BZJ_OK {
        assert!(
            !last_error().is_empty(),
            "{call} failed ({status:?}) without a message"
        );
    }
}

/// Check a handle returned by a call with `status`: NULL after a failure,
/// a live curve of dimension `1..` after success (then freed).
///
/// `handle` must be NULL or a handle the library just returned (the
/// targets only pass what a call wrote into an out-pointer).
#[allow(clippy::not_unsafe_ptr_arg_deref)]
pub fn check_and_free(status: BzjStatus, handle: *mut BzjCurve, call: &str) {
    check(status, call);
    if status != BzjStatus::BZJ_OK {
        assert!(handle.is_null(), "{call} failed but returned a handle");
        return;
    }
    assert!(!handle.is_null(), "{call} succeeded without a handle");
    let mut dim = 0usize;
    let mut poles = 0usize;
    // SAFETY: a live handle from the library; out-pointers are valid.
    unsafe {
        check(bzj_curve_dim(handle, &mut dim), "bzj_curve_dim");
        check(
            bzj_curve_pole_count(handle, &mut poles),
            "bzj_curve_pole_count",
        );
        assert!(dim >= 1);
        let mut points = vec![0.0; poles * dim];
        check(
            bzj_curve_points(handle, points.as_mut_ptr(), points.len()),
            "bzj_curve_points",
        );
        bzj_curve_free(handle);
    }
}

/// A curve built from the input through `bzj_curve_new` (degree <= 40,
/// dim <= 4), or `None` when the input describes an invalid one (the call's
/// status is checked either way). Free it with `bzj_curve_free`.
pub fn curve(input: &mut Input) -> Option<*mut BzjCurve> {
    let dim = 1 + input.below(MAX_DIM);
    curve_in(input, dim, MAX_DEGREE)
}

/// `BzjFilletOptions` from the input: setbacks mostly short and positive,
/// sometimes any double; orders up to 6 (or `SIZE_MAX`, see
/// [`Input::size`]); scales 1 or any double.
pub fn fillet_options(input: &mut Input) -> BzjFilletOptions {
    let mut setback = || {
        if input.byte().is_multiple_of(4) {
            input.double()
        } else {
            input.ordinary().abs() / 20.0
        }
    };
    let p_setback = setback();
    let q_setback = setback();
    let p_order = input.size(6);
    let q_order = input.size(6);
    let mut scale = || {
        if input.byte().is_multiple_of(4) {
            input.double()
        } else {
            1.0
        }
    };
    let p_scale = scale();
    let q_scale = scale();
    BzjFilletOptions {
        p_setback,
        q_setback,
        p_order,
        q_order,
        p_scale,
        q_scale,
    }
}

/// `handles` as a C array of `const BzjCurve*`, one entry sometimes (1 in
/// 16) replaced by NULL: the array and the index of that entry.
pub fn handle_array(
    input: &mut Input,
    handles: &[*mut BzjCurve],
) -> (Vec<*const BzjCurve>, Option<usize>) {
    let n = handles.len();
    let mut curves: Vec<*const BzjCurve> = handles.iter().map(|&h| h.cast_const()).collect();
    let null_entry = if n > 0 && input.byte().is_multiple_of(16) {
        let i = input.below(n);
        curves[i] = std::ptr::null();
        Some(i)
    } else {
        None
    };
    (curves, null_entry)
}

/// Two curves built as by [`curve`], or `None` (nothing left to free) when
/// either is invalid. Free both with `bzj_curve_free`.
pub fn curve_pair(input: &mut Input) -> Option<(*mut BzjCurve, *mut BzjCurve)> {
    let p = curve(input)?;
    match curve(input) {
        Some(q) => Some((p, q)),
        None => {
            // SAFETY: live handle, released once.
            unsafe { bzj_curve_free(p) };
            None
        }
    }
}

/// A curve of dimension `dim` and degree `<= max_degree` built as by
/// [`curve`] (chains share one dimension so that they reach the success path).
pub fn curve_in(input: &mut Input, dim: usize, max_degree: usize) -> Option<*mut BzjCurve> {
    let degree = input.below(max_degree + 1);
    let points: Vec<f64> = (0..(degree + 1) * dim)
        .map(|_| input.coordinate())
        .collect();
    let mut out = null_mut();
    // SAFETY: `points` holds `points.len()` doubles; `out` is writable.
    let status = unsafe { bzj_curve_new(dim, degree, points.as_ptr(), points.len(), &mut out) };
    check(status, "bzj_curve_new");
    if status == BzjStatus::BZJ_OK {
        assert!(!out.is_null());
        Some(out)
    } else {
        assert!(out.is_null());
        None
    }
}

/// Check an array of handle slots after a call that clears the first
/// `declared` slots and, on success, writes `written <= declared` handles:
/// those must be live (they are freed), the rest of the declared slots NULL,
/// and every slot past `declared` still [`sentinel`] (never written).
///
/// `slots` must hold NULL, [`sentinel`] or handles the library just wrote.
pub fn check_handle_slots(
    status: BzjStatus,
    slots: &[*mut BzjCurve],
    written: usize,
    declared: usize,
    call: &str,
) {
    check(status, call);
    for (i, &s) in slots.iter().enumerate() {
        if i >= declared {
            assert_eq!(
                s,
                sentinel(),
                "{call} wrote slot {i} past the declared {declared}"
            );
        } else if status == BzjStatus::BZJ_OK && i < written {
            assert_ne!(s, sentinel(), "{call}: slot {i} not written");
            check_and_free(status, s, call);
        } else {
            assert!(s.is_null(), "{call}: slot {i} not NULL after {status:?}");
        }
    }
}

/// Release the handles of a chain the target built.
pub fn free_all(handles: &[*mut BzjCurve]) {
    for &h in handles {
        // SAFETY: live handles from `curve`/`curve_in`, each released once.
        unsafe { bzj_curve_free(h) };
    }
}

/// A NURBS curve from the input through `bzj_nurbs_new`: dimension <= 4,
/// degree 1..=8, `degree + 1 ..= degree + 12` poles; knots mostly a
/// non-decreasing sequence with repeats (clamped or not), sometimes raw
/// doubles; weights absent, ordinary positive, or any doubles. `None` when
/// the library refuses it (the status is checked either way). Free it with
/// `bzj_curve_free`.
pub fn nurbs(input: &mut Input) -> Option<*mut BzjCurve> {
    let dim = 1 + input.below(MAX_DIM);
    let degree = 1 + input.below(8);
    let count = degree + 1 + input.below(12);
    let poles: Vec<f64> = (0..count * dim).map(|_| input.coordinate()).collect();
    let weights: Vec<f64> = match input.byte() % 4 {
        0 => Vec::new(),
        1 => (0..count).map(|_| input.double()).collect(),
        _ => (0..count)
            .map(|_| 0.1 + input.ordinary().abs() / 10.0)
            .collect(),
    };
    let len = count + degree + 1;
    let knots: Vec<f64> = if input.byte().is_multiple_of(8) {
        (0..len).map(|_| input.double()).collect()
    } else {
        let clamped = input.byte() % 2 == 0;
        let mut knots = Vec::with_capacity(len);
        let mut x = input.ordinary();
        while knots.len() < len {
            let repeat = if clamped && (knots.is_empty() || knots.len() + degree + 1 >= len) {
                degree + 1
            } else {
                1 + input.below(degree)
            };
            for _ in 0..repeat {
                if knots.len() < len {
                    knots.push(x);
                }
            }
            x += if input.byte().is_multiple_of(16) {
                input.double().abs()
            } else {
                0.05 + input.ordinary().abs() / 50.0
            };
        }
        knots
    };
    let mut out = std::ptr::null_mut();
    // SAFETY: the arrays are live with the lengths given; `out` is writable.
    let status = unsafe {
        bzj_nurbs_new(
            dim,
            degree,
            poles.as_ptr(),
            poles.len(),
            if weights.is_empty() {
                std::ptr::null()
            } else {
                weights.as_ptr()
            },
            weights.len(),
            knots.as_ptr(),
            knots.len(),
            &mut out,
        )
    };
    check(status, "bzj_nurbs_new");
    (status == BzjStatus::BZJ_OK).then_some(out)
}
