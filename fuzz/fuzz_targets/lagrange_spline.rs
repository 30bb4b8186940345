//! `bzj_lagrange_spline` and `bzj_lagrange_spline_degree` with fuzzed
//! dimensions, node counts (<= 12), parameters (or NULL for chord length),
//! inner points, degrees, continuities, flags and handle-array capacities.
//! Every buffer has exactly the length the contract states, so an over-read
//! is caught by AddressSanitizer. After an error the first `node_count - 1`
//! handles must be NULL when the array holds that many (otherwise nothing
//! is written); after success each must be a live curve (then freed), and
//! nothing past `node_count - 1` is ever written.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

const MAX_NODES: usize = 12;

fn doubles(input: &mut Input, n: usize) -> Vec<f64> {
    (0..n).map(|_| input.coordinate()).collect()
}

fn ptr_or_null(v: &[f64], null_it: bool) -> *const f64 {
    if null_it { null() } else { v.as_ptr() }
}

fn check_segments(status: BzjStatus, segments: &mut [*mut BzjCurve], written: usize, call: &str) {
    check(status, call);
    let sentinel = std::ptr::dangling_mut::<BzjCurve>();
    if status == BzjStatus::BZJ_ERR_BUFFER_TOO_SMALL {
        assert!(
            segments.iter().all(|s| *s == sentinel),
            "{call} wrote into a short array"
        );
        return;
    }
    for (i, s) in segments.iter_mut().enumerate() {
        if i < written {
            if status == BzjStatus::BZJ_OK {
                check_and_free(status, *s, call);
            } else {
                assert!(s.is_null(), "{call}: segment {i} not NULL after {status:?}");
            }
        } else {
            assert_eq!(*s, sentinel, "{call} wrote past node_count - 1");
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let dim = input.size(MAX_DIM).min(MAX_DIM + 1);
    let node_count = input.size(MAX_NODES).min(MAX_NODES + 1);
    let capacity = input.below(MAX_NODES + 2);
    let sentinel = std::ptr::dangling_mut::<BzjCurve>();
    let mut segments = vec![sentinel; capacity];
    // Entries the library may write: all `node_count - 1` when they fit, else none.
    let needed = node_count.saturating_sub(1);
    let written = if capacity >= needed { needed } else { 0 };
    let nodes = doubles(&mut input, node_count * dim);
    let params: Vec<f64> = if input.byte().is_multiple_of(2) {
        let mut t = input.double();
        (0..node_count)
            .map(|_| {
                t += input.ordinary().abs() / 10.0;
                t
            })
            .collect()
    } else {
        doubles(&mut input, node_count)
    };
    let params_null = input.byte().is_multiple_of(3);

    if input.byte().is_multiple_of(2) {
        let first_inner = doubles(&mut input, 2 * dim);
        let second_inner = doubles(&mut input, node_count.saturating_sub(2) * dim);
        let second_null = input.byte().is_multiple_of(8);
        // SAFETY: every non-NULL buffer has the length the contract states.
        let status = unsafe {
            bzj_lagrange_spline(
                dim,
                node_count,
                ptr_or_null(&nodes, false),
                ptr_or_null(&params, params_null),
                first_inner.as_ptr(),
                ptr_or_null(&second_inner, second_null),
                if capacity == 0 {
                    null_mut()
                } else {
                    segments.as_mut_ptr()
                },
                capacity,
            )
        };
        check_segments(status, &mut segments, written, "bzj_lagrange_spline");
    } else {
        let degree = input.below(8);
        let continuity = input.below(6);
        let flags = if input.byte().is_multiple_of(8) {
            input.byte() as u32 | 0x100
        } else {
            input.below(4) as u32
        };
        let start_inner = doubles(&mut input, degree.saturating_sub(1) * dim);
        let free_inner = doubles(
            &mut input,
            node_count.saturating_sub(2) * degree.saturating_sub(1 + continuity) * dim,
        );
        // SAFETY: every non-NULL buffer has the length the contract states.
        let status = unsafe {
            bzj_lagrange_spline_degree(
                dim,
                degree,
                continuity,
                flags,
                node_count,
                nodes.as_ptr(),
                ptr_or_null(&params, params_null),
                start_inner.as_ptr(),
                ptr_or_null(
                    &free_inner,
                    free_inner.is_empty() && input.byte().is_multiple_of(2),
                ),
                if capacity == 0 {
                    null_mut()
                } else {
                    segments.as_mut_ptr()
                },
                capacity,
            )
        };
        check_segments(status, &mut segments, written, "bzj_lagrange_spline_degree");
    }
});
