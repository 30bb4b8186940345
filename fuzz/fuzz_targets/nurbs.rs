//! NURBS handles (issue 16): `bzj_nurbs_new` on fuzzed poles, weights and
//! knot vectors (clamped or not, repeated knots, raw doubles), then every
//! operation that takes them: inspection (knots, weights, domain, pole
//! count, with short buffers and size queries), evaluation (single and
//! many, any order), split, segment, reverse, elevate, length, Bezier
//! spans, conversion, connect, intersection and the fillets (`bzj_fillet`,
//! `bzj_fillet_vertex` against the reversed curve, `bzj_fillet_chain`), the
//! B-spline merge (`bzj_merge` of two NURBS handles), and
//! `bzj_nurbs_ellipse_arc` with fuzzed arguments.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

/// A parameter in the domain `[a, b]` from a fuzzed one (mostly in
/// `[-0.5, 1.5]`, so ends and outside values are reached too).
fn in_domain(input: &mut Input, a: f64, b: f64) -> f64 {
    a + input.parameter() * (b - a)
}

/// `bzj_merge` of two NURBS handles (the B-spline merge; a rational one
/// is refused) with fuzzed metric, split, `mu`, flags and keep points in
/// and around the domains: on success `0 < mu < 1` and a live handle.
///
/// # Safety
/// `p` and `q` are live handles.
unsafe fn merge_pair(input: &mut Input, p: *mut BzjCurve, q: *mut BzjCurve) {
    let mut points = [BzjKeepPoint {
        param: 0.0,
        max_order: 0,
    }; 2];
    let (mut a, mut b) = (0.0, 0.0);
    // SAFETY: live handle, writable outs.
    unsafe { bzj_curve_domain(q, &mut a, &mut b) };
    for kp in &mut points {
        kp.param = in_domain(input, a, b);
        kp.max_order = input.below(5);
    }
    let options = BzjMergeOptions {
        metric: if input.byte().is_multiple_of(2) {
            BzjMetric::BZJ_METRIC_DISCRETE
        } else {
            BzjMetric::BZJ_METRIC_L2
        },
        split: match input.byte() % 4 {
            0 => BzjSplit::BZJ_SPLIT_GIVEN,
            1 => BzjSplit::BZJ_SPLIT_HALF,
            2 => BzjSplit::BZJ_SPLIT_POLYGON,
            _ => BzjSplit::BZJ_SPLIT_OPTIMAL,
        },
        mu: input.parameter(),
        keep_p: input.byte().is_multiple_of(4),
        keep_q: input.byte().is_multiple_of(4),
        fix_ends: input.byte().is_multiple_of(2),
        p_points: null(),
        p_point_count: 0,
        q_points: points.as_ptr(),
        q_point_count: input.below(3),
    };
    let (mut merged, mut p_hat, mut q_hat) = (null_mut(), null_mut(), null_mut());
    let mut report = BzjMergeReport {
        mu: f64::NAN,
        metric_value: f64::NAN,
        max_deviation: f64::NAN,
    };
    // SAFETY: live handles, readable options, writable outs.
    let status = unsafe {
        bzj_merge(
            p,
            q,
            &options,
            &mut merged,
            &mut p_hat,
            &mut q_hat,
            &mut report,
        )
    };
    check_and_free(status, merged, "bzj_merge");
    check_and_free(status, p_hat, "bzj_merge");
    check_and_free(status, q_hat, "bzj_merge");
    if status == BzjStatus::BZJ_OK {
        assert!(
            report.mu > 0.0 && report.mu < 1.0,
            "bzj_merge: mu = {}",
            report.mu
        );
        assert!(
            report.max_deviation >= 0.0,
            "bzj_merge: {}",
            report.max_deviation
        );
    }
}

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    if input.byte() % 8 == 0 {
        let dim = 1 + input.below(3);
        let centre: Vec<f64> = (0..3).map(|_| input.coordinate()).collect();
        let x: Vec<f64> = (0..3).map(|_| input.coordinate()).collect();
        let y: Vec<f64> = (0..3).map(|_| input.coordinate()).collect();
        let mut out = null_mut();
        // SAFETY: 3 readable doubles each (dim <= 3), `out` writable.
        let status = unsafe {
            bzj_nurbs_ellipse_arc(
                dim,
                centre.as_ptr(),
                x.as_ptr(),
                y.as_ptr(),
                input.double(),
                input.double(),
                input.double(),
                input.double(),
                &mut out,
            )
        };
        check_and_free(status, out, "bzj_nurbs_ellipse_arc");
    }
    let Some(c) = nurbs(&mut input) else { return };
    let (mut a, mut b) = (0.0, 0.0);
    let mut dim = 0usize;
    // SAFETY (whole block): `c` is live; out-pointers and buffers are valid
    // for the lengths passed.
    unsafe {
        check(bzj_curve_domain(c, &mut a, &mut b), "bzj_curve_domain");
        check(bzj_curve_dim(c, &mut dim), "bzj_curve_dim");
        for _ in 0..6 {
            match input.byte() % 10 {
                0 => {
                    let mut count = 0usize;
                    check(
                        bzj_curve_knots(c, null_mut(), 0, &mut count),
                        "bzj_curve_knots",
                    );
                    let len = input.below(count + 2);
                    let mut buf = vec![0.0; len];
                    check(
                        bzj_curve_knots(c, buf.as_mut_ptr(), len, &mut count),
                        "bzj_curve_knots",
                    );
                    let mut weights = vec![0.0; input.below(count + 2)];
                    check(
                        bzj_curve_weights(c, weights.as_mut_ptr(), weights.len()),
                        "bzj_curve_weights",
                    );
                }
                1 => {
                    let order = input.size(6);
                    let len = input.below(((order.min(8) + 1) * dim).max(1) + 2);
                    let mut buf = vec![0.0; len];
                    let t = in_domain(&mut input, a, b);
                    check(
                        bzj_curve_eval(c, t, order, buf.as_mut_ptr(), len),
                        "bzj_curve_eval",
                    );
                    let ts: Vec<f64> = (0..input.below(5))
                        .map(|_| in_domain(&mut input, a, b))
                        .collect();
                    let mut many = vec![0.0; ts.len() * (order.min(8) + 1) * dim];
                    check(
                        bzj_curve_eval_many(
                            c,
                            ts.as_ptr(),
                            ts.len(),
                            order.min(8),
                            many.as_mut_ptr(),
                            many.len(),
                        ),
                        "bzj_curve_eval_many",
                    );
                }
                2 => {
                    let (mut l, mut r) = (null_mut(), null_mut());
                    let status = bzj_curve_split(c, in_domain(&mut input, a, b), &mut l, &mut r);
                    check_and_free(status, l, "bzj_curve_split");
                    check_and_free(status, r, "bzj_curve_split");
                }
                3 => {
                    let mut out = null_mut();
                    let (s, t) = (in_domain(&mut input, a, b), in_domain(&mut input, a, b));
                    check_and_free(
                        bzj_curve_segment(c, s, t, &mut out),
                        out,
                        "bzj_curve_segment",
                    );
                }
                4 => {
                    let mut out = null_mut();
                    let degree = input.below(MAX_DEGREE + 1);
                    check_and_free(
                        bzj_curve_elevate(c, degree, &mut out),
                        out,
                        "bzj_curve_elevate",
                    );
                    let mut out = null_mut();
                    check_and_free(bzj_curve_reverse(c, &mut out), out, "bzj_curve_reverse");
                    let mut out = null_mut();
                    check_and_free(bzj_curve_to_nurbs(c, &mut out), out, "bzj_curve_to_nurbs");
                }
                5 => {
                    let mut len = 0.0;
                    let (s, t) = (in_domain(&mut input, a, b), in_domain(&mut input, a, b));
                    check(bzj_curve_length(c, s, t, &mut len), "bzj_curve_length");
                }
                6 => {
                    let mut count = 0usize;
                    check(
                        bzj_curve_bezier_spans(c, null_mut(), 0, &mut count),
                        "bzj_curve_bezier_spans",
                    );
                    let capacity = input.below(count.min(64) + 2);
                    let mut spans = vec![null_mut(); capacity];
                    let status =
                        bzj_curve_bezier_spans(c, spans.as_mut_ptr(), capacity, &mut count);
                    check(status, "bzj_curve_bezier_spans");
                    for &s in &spans {
                        if status == BzjStatus::BZJ_OK && !s.is_null() {
                            check_and_free(BzjStatus::BZJ_OK, s, "bzj_curve_bezier_spans");
                        }
                    }
                }
                7 => {
                    let options = BzjConnectOptions {
                        p_order: input.size(6),
                        q_order: input.size(6),
                        p_scale: 1.0,
                        q_scale: 1.0,
                        constraints: null(),
                        constraint_count: 0,
                    };
                    let mut out = null_mut();
                    let (u, v) = (in_domain(&mut input, a, b), in_domain(&mut input, a, b));
                    check_and_free(
                        bzj_connect(c, u, c, v, &options, &mut out),
                        out,
                        "bzj_connect",
                    );
                }
                8 => {
                    let mut r = null_mut();
                    check(bzj_curve_reverse(c, &mut r), "bzj_curve_reverse");
                    if r.is_null() {
                        continue;
                    }
                    let mut pairs = [0.0; 8];
                    let mut count = 0usize;
                    check(
                        bzj_intersect(c, r, pairs.as_mut_ptr(), 4, &mut count),
                        "bzj_intersect",
                    );
                    let options = fillet_options(&mut input);
                    let (mut pt, mut bl, mut qt) = (null_mut(), null_mut(), null_mut());
                    let gap = input.double().abs();
                    // Odd orders: the automatic scale (decided by a value
                    // already read, so that older inputs decode as before).
                    let (status, call) = if options.p_order % 2 == 1 {
                        let mut s = f64::NAN;
                        let status = bzj_fillet_vertex_auto_scale(
                            c, r, &options, gap, &mut pt, &mut bl, &mut qt, &mut s,
                        );
                        if status == BzjStatus::BZJ_OK {
                            assert!(s > 0.0 && s.is_finite(), "vertex auto scale {s}");
                        }
                        (status, "bzj_fillet_vertex_auto_scale")
                    } else {
                        let status =
                            bzj_fillet_vertex(c, r, &options, gap, &mut pt, &mut bl, &mut qt);
                        (status, "bzj_fillet_vertex")
                    };
                    check_and_free(status, pt, call);
                    check_and_free(status, bl, call);
                    check_and_free(status, qt, call);
                    bzj_curve_free(r);
                }
                _ => {
                    let options = fillet_options(&mut input);
                    let (mut pt, mut bl, mut qt) = (null_mut(), null_mut(), null_mut());
                    let other = nurbs(&mut input);
                    let q = other.unwrap_or(c);
                    let status = bzj_fillet(c, q, &options, &mut pt, &mut bl, &mut qt);
                    check_and_free(status, pt, "bzj_fillet");
                    check_and_free(status, bl, "bzj_fillet");
                    check_and_free(status, qt, "bzj_fillet");
                    let chain = [c.cast_const(), q.cast_const()];
                    let mut pieces = [null_mut(); 4];
                    let mut count = 0usize;
                    let status = bzj_fillet_chain(
                        chain.as_ptr(),
                        2,
                        &options,
                        1,
                        pieces.as_mut_ptr(),
                        4,
                        &mut count,
                    );
                    check(status, "bzj_fillet_chain");
                    if status == BzjStatus::BZJ_OK {
                        for p in pieces {
                            check_and_free(BzjStatus::BZJ_OK, p, "bzj_fillet_chain");
                        }
                    }
                    merge_pair(&mut input, c, q);
                    if let Some(o) = other {
                        bzj_curve_free(o);
                    }
                }
            }
        }
        bzj_curve_free(c);
    }
});
