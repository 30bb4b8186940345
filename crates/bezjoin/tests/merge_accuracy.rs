//! Accuracy of merging against a known answer, degrees 1..30: the two pieces
//! of one curve split at `t` must merge back into that curve. Whatever the
//! degree, the merge either returns an answer within its promised accuracy
//! or refuses with `IllConditioned` — never silent garbage.
//!
//! `cargo test -p bezjoin-core --test merge_accuracy -- --nocapture` prints
//! the table published in docs/accuracy.md.

use bezjoin_core::BezierCurve;
use bezjoin_core::BezjoinError;
use bezjoin_core::{Breakpoints, DEFAULT_MERGE_ACCURACY, MergeMetric, MergeOptions, merge};

fn curve(degree: usize, seed: u64) -> BezierCurve {
    let mut state = seed;
    let pts = (0..(degree + 1) * 2)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 2.0
        })
        .collect();
    BezierCurve::new(2, degree, pts).unwrap()
}

#[test]
fn merge_back_accuracy_by_degree() {
    println!(
        "| degree | t | metric | result | error of R vs the curve (relative) | solve estimate | split check |"
    );
    println!("|---|---|---|---|---|---|---|");
    for degree in [1, 2, 3, 5, 7, 10, 12, 15, 20, 25, 30] {
        for t in [0.5, 0.3, 0.1] {
            for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
                let original = curve(degree, 1000 + degree as u64);
                let (p, q) = original.split_at(t).unwrap();
                let options = MergeOptions::default()
                    .with_metric(metric)
                    .with_split(Breakpoints::Given(vec![t]));
                let scale = original.coordinate_scale();
                match merge(&p, &q, &options) {
                    Ok(m) => {
                        let error = m
                            .merged
                            .points()
                            .iter()
                            .zip(original.points())
                            .map(|(a, b)| (a - b).abs())
                            .fold(0.0, f64::max)
                            / scale;
                        println!(
                            "| {degree} | {t} | {metric:?} | ok | {error:.1e} | {:.1e} | {:.1e} |",
                            m.report.solve_error_estimate, m.report.split_check_error
                        );
                        // The pieces are what the promise is about: they are
                        // reproduced within the accuracy ...
                        assert!(m.report.split_check_error <= DEFAULT_MERGE_ACCURACY);
                        // ... and R itself is within 10 times the accuracy
                        // of the known answer.
                        assert!(
                            error <= 10.0 * DEFAULT_MERGE_ACCURACY,
                            "degree {degree} t {t}: silent error {error:e}"
                        );
                    }
                    Err(BezjoinError::IllConditioned { what, estimate, .. }) => {
                        println!(
                            "| {degree} | {t} | {metric:?} | IllConditioned ({what}) | | {estimate:.1e} | |"
                        );
                    }
                    Err(e) => panic!("degree {degree}: unexpected {e}"),
                }
            }
        }
    }
}
