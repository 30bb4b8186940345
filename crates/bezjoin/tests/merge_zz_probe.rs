mod common;
use bezjoin_core::*;
use common::Random;
#[test]
fn probe() {
    let mut rng = Random(5);
    for n in [15, 20, 25, 27, 29, 31] {
        for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
            let p = rng.curve(2, n, 2.0);
            let q = rng.curve(2, n, 2.0);
            for split in [
                Breakpoints::Given(vec![0.5]),
                Breakpoints::Given(vec![0.2]),
                Breakpoints::Optimal,
            ] {
                let mut o = MergeOptions::default()
                    .with_metric(metric)
                    .with_split(split.clone());
                o.accuracy = 1.0;
                match merge(&p, &q, &o) {
                    Ok(m) => println!(
                        "n {n} {metric:?} {split:?} mu {:.4} est {:.1e} split {:.1e} metric {:.3e}",
                        m.report.mu,
                        m.report.solve_error_estimate,
                        m.report.split_check_error,
                        m.report.metric_value
                    ),
                    Err(e) => println!("n {n} {metric:?} {split:?} ERR {e}"),
                }
            }
        }
    }
}
