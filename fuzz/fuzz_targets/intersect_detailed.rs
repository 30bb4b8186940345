//! `bzj_intersect_detailed` on fuzzed curve pairs with NULL (default) or
//! fuzzed options (any tolerance double, `max_depth`, `max_box_pairs`,
//! `max_hits` up to `SIZE_MAX`, also 0), output capacities 0..8 (declared
//! capacity at most the buffer; any capacity, also `SIZE_MAX`, with a NULL
//! `out`), and NULL `p`, `q`, `count` or `out` (`BZJ_ERR_NULL_POINTER`).
//! The hits written are `min(count, capacity)`, each with `u`, `v`, `u_end`,
//! `v_end` in [0, 1], a valid kind (an overlap has `u_end > u`, other hits
//! `u_end == u`, `v_end == v`), a distance >= 0, ordered by `u`; nothing is
//! written past the declared capacity, nor anything after a failure. With
//! NULL options the hits must be those of `bzj_intersect` (same defaults).
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

/// `BzjIntersection` as raw C data, so that guard entries can hold any kind.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
struct RawIntersection {
    u: f64,
    v: f64,
    u_end: f64,
    v_end: f64,
    distance: f64,
    kind: i32,
}
const _: () = assert!(size_of::<RawIntersection>() == size_of::<BzjIntersection>());
const _: () = assert!(align_of::<RawIntersection>() == align_of::<BzjIntersection>());

const GUARD: RawIntersection = RawIntersection {
    u: f64::NAN,
    v: f64::NAN,
    u_end: f64::NAN,
    v_end: f64::NAN,
    distance: f64::NAN,
    kind: -12345,
};

fn untouched(h: &RawIntersection) -> bool {
    h.u.is_nan()
        && h.v.is_nan()
        && h.u_end.is_nan()
        && h.v_end.is_nan()
        && h.distance.is_nan()
        && h.kind == GUARD.kind
}

/// A tolerance: mostly the default, sometimes an ordinary value in [0, 1),
/// sometimes any double.
fn tolerance(input: &mut Input, default: f64) -> f64 {
    match input.byte() % 4 {
        0 => input.double(),
        1 => (input.ordinary().abs() / 100.0).min(0.999),
        _ => default,
    }
}

/// A work bound: mostly the default, sometimes a size (0, small or huge).
fn bound(input: &mut Input, default: usize, small: usize) -> usize {
    match input.byte() % 4 {
        0 => input.size(small),
        _ => default,
    }
}

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some((p, q)) = curve_pair(&mut input) else {
        return;
    };
    let mut defaults = BzjIntersectOptions {
        relative_distance_tolerance: f64::NAN,
        tangent_tolerance: f64::NAN,
        max_depth: 0,
        max_box_pairs: 0,
        max_hits: 0,
    };
    // SAFETY: writable out-pointer.
    let status = unsafe { bzj_intersect_options_default(&mut defaults) };
    assert_eq!(status, BzjStatus::BZJ_OK);
    let options = BzjIntersectOptions {
        relative_distance_tolerance: tolerance(&mut input, defaults.relative_distance_tolerance),
        tangent_tolerance: tolerance(&mut input, defaults.tangent_tolerance),
        max_depth: bound(&mut input, defaults.max_depth, 80),
        max_box_pairs: bound(&mut input, defaults.max_box_pairs, 5000),
        max_hits: bound(&mut input, defaults.max_hits, 16),
    };
    let options_null = input.byte().is_multiple_of(4);

    let buffer_len = input.below(9);
    let mut out = vec![GUARD; buffer_len + 2];
    let (out_ptr, capacity) = match input.byte() % 8 {
        // A NULL `out` with any capacity (an error unless 0).
        0 => (null_mut(), input.size(16)),
        1 => (out.as_mut_ptr(), input.below(buffer_len + 1)),
        _ => (out.as_mut_ptr(), buffer_len),
    };
    let drop_one = input.byte() % 16;
    let mut count = usize::MAX;
    // SAFETY: `p`, `q` live or NULL; options readable or NULL; `out` NULL or
    // holding `buffer_len + 2 > capacity` elements of the C layout; `count`
    // writable or NULL.
    let status = unsafe {
        bzj_intersect_detailed(
            if drop_one == 1 { null() } else { p },
            if drop_one == 2 { null() } else { q },
            if options_null { null() } else { &options },
            out_ptr.cast::<BzjIntersection>(),
            capacity,
            if drop_one == 3 {
                null_mut()
            } else {
                &mut count
            },
        )
    };
    let call = "bzj_intersect_detailed";
    check(status, call);
    if (1..=3).contains(&drop_one) || (out_ptr.is_null() && capacity > 0) {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "{call}: NULL argument"
        );
    }
    let written = if status == BzjStatus::BZJ_OK {
        count.min(capacity)
    } else {
        assert_eq!(count, usize::MAX, "{call} wrote count after {status:?}");
        0
    };
    let mut previous = f64::NEG_INFINITY;
    for h in &out[..written] {
        let unit = |x: f64| (0.0..=1.0).contains(&x);
        assert!(
            unit(h.u) && unit(h.v) && unit(h.u_end) && unit(h.v_end),
            "{call}: {h:?}"
        );
        assert!(h.distance >= 0.0, "{call}: {h:?}");
        match h.kind {
            0 | 1 => assert!(h.u_end == h.u && h.v_end == h.v, "{call}: {h:?}"),
            2 => assert!(h.u_end > h.u, "{call}: overlap {h:?}"),
            k => panic!("{call}: kind {k} in {h:?}"),
        }
        assert!(h.u >= previous, "{call}: hits not ordered by u: {out:?}");
        previous = h.u;
    }
    assert!(
        out[written..].iter().all(untouched),
        "{call} wrote past {written} hits: {out:?}"
    );

    // NULL options are the defaults of `bzj_intersect`: the same hits.
    if options_null && drop_one == 0 && status != BzjStatus::BZJ_ERR_NULL_POINTER {
        let mut pairs = vec![f64::NAN; 2 * written];
        let mut plain_count = usize::MAX;
        // SAFETY: live handles; `pairs` holds `2 * written` doubles.
        let plain = unsafe { bzj_intersect(p, q, pairs.as_mut_ptr(), written, &mut plain_count) };
        check(plain, "bzj_intersect");
        assert_eq!(plain, status, "{call} and bzj_intersect disagree");
        if status == BzjStatus::BZJ_OK {
            assert_eq!(
                plain_count, count,
                "{call} and bzj_intersect count differently"
            );
            for (h, pair) in out[..written].iter().zip(pairs.chunks(2)) {
                assert!(
                    h.u.to_bits() == pair[0].to_bits() && h.v.to_bits() == pair[1].to_bits(),
                    "{call} {h:?} but bzj_intersect {pair:?}"
                );
            }
        }
    }
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
