//! The connect's curve-only path (`bezjoin_core::connect_curve`, the one
//! `bzj_connect` and `bzj_connect_points` take: a screen without square
//! roots, then the full check where the screen does not pass) against
//! `connect` (the full check always): on fuzzed Bezier pairs of dimensions
//! 1 to 4 and degrees 0 to 15, coordinates of any size (a fuzzed power of
//! ten from 1e-192 to 1e190, offsets far from the origin, any double),
//! parameters, orders 0 to 15 and scales, both must give the same control
//! points bit for bit or the same error message (mathematics.md, "The curve
//! alone"). A difference panics.
#![no_main]

use bezjoin_core::{BezierCurve, ConnectOptions, connect, connect_curve};
use bezjoin_fuzz::Input;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let dim = 1 + input.below(4);
    let size = 10f64.powi((i32::from(input.byte()) - 128) * 3 / 2);
    let offset = if input.byte() % 4 == 0 {
        size * 1e6 * input.ordinary()
    } else {
        0.0
    };
    let curve = |input: &mut Input| {
        let degree = input.below(16);
        let points: Vec<f64> = (0..(degree + 1) * dim)
            .map(|_| offset + size * input.coordinate())
            .collect();
        BezierCurve::new(dim, degree, points).ok()
    };
    let (Some(p), Some(q)) = (curve(&mut input), curve(&mut input)) else {
        return;
    };
    let scale = |input: &mut Input| match input.byte() % 4 {
        0 => input.double(),
        1 => 10f64.powf(f64::from(input.byte()) / 16.0 - 4.0),
        _ => 1.0,
    };
    let (alpha, beta) = (scale(&mut input), scale(&mut input));
    let options = ConnectOptions::new(input.below(16), input.below(16)).with_scales(alpha, beta);
    let (u0, v0) = (input.parameter(), input.parameter());
    let full = connect(&p, u0, &q, v0, &options);
    let curve = connect_curve(&p, u0, &q, v0, &options);
    match (&full, &curve) {
        (Ok(c), Ok(r)) => {
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(c.curve.points()),
                bits(r.points()),
                "{p:?} {q:?} {options:?}"
            );
        }
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
        _ => panic!(
            "connect {full:?} against connect_curve {curve:?}: {p:?} {q:?} {options:?} {u0} {v0}"
        ),
    }
});
