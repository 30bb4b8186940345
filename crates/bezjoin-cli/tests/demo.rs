//! `bezjoin demo` run as a process: it exits 0 and writes index.html and, for
//! every scenario the index lists, its picture, job and result; every
//! picture is well-formed XML, and every job re-run through its subcommand
//! gives the result the demo wrote.

mod common;
use common::assert_well_formed_xml;

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// The scenario names listed in index.html (`src="NAME.svg"`).
fn listed_scenarios(index: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut rest = index;
    while let Some(i) = rest.find("src=\"") {
        let after = &rest[i + 5..];
        let end = after.find('"').expect("a closed src attribute");
        if let Some(name) = after[..end].strip_suffix(".svg") {
            names.push(name.to_string());
        }
        rest = &after[end..];
    }
    names
}

fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("demo-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// Equal JSON, numbers up to a relative 1e-12 (a re-run of the same job;
/// only summation order may differ).
fn assert_same_json(a: &Value, b: &Value, at: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0),
                "{at}: {x} != {y}"
            );
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{at}: array lengths");
            for (i, (x, y)) in x.iter().zip(y).enumerate() {
                assert_same_json(x, y, &format!("{at}[{i}]"));
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            assert_eq!(
                x.keys().collect::<Vec<_>>(),
                y.keys().collect::<Vec<_>>(),
                "{at}: fields"
            );
            for (k, v) in x {
                assert_same_json(v, &y[k], &format!("{at}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}

#[test]
fn demo_writes_every_listed_scenario() {
    let out = out_dir();
    let run = Command::new(env!("CARGO_BIN_EXE_bezjoin"))
        .arg("demo")
        .arg("--out")
        .arg(&out)
        .output()
        .expect("the bezjoin binary runs");
    assert!(
        run.status.success(),
        "demo exit {:?}: {}",
        run.status.code(),
        String::from_utf8_lossy(&run.stderr)
    );
    let index = std::fs::read_to_string(out.join("index.html")).expect("index.html written");
    let names = listed_scenarios(&index);
    // The connect scenarios are part of the demo.
    for expected in ["connect-plain", "connect-constrained", "connect-auto-scale"] {
        assert!(names.iter().any(|n| n == expected), "{expected} not listed");
    }
    let table = String::from_utf8_lossy(&run.stdout);
    for name in &names {
        assert!(
            table.contains(name.as_str()),
            "{name} missing from the summary table"
        );
        let svg = std::fs::read_to_string(out.join(format!("{name}.svg")))
            .unwrap_or_else(|e| panic!("{name}.svg: {e}"));
        assert!(svg.contains("<svg"), "{name}.svg is an SVG document");
        assert_well_formed_xml(&svg);
        let job_path = out.join(format!("{name}.job.json"));
        let job = read_json(&job_path);
        let result = read_json(&out.join(format!("{name}.result.json")));
        assert!(job.is_object(), "{name}.job.json is a job object");
        assert!(result.is_object(), "{name}.result.json is a result object");
        // The job is accepted as it is by the subcommand that produced the
        // result, and gives the same result.
        if let Some(operation) = result.get("operation").and_then(Value::as_str) {
            let again = Command::new(env!("CARGO_BIN_EXE_bezjoin"))
                .arg(operation)
                .arg(&job_path)
                .output()
                .expect("the bezjoin binary runs");
            assert!(
                again.status.success(),
                "{name}: `bezjoin {operation}` rejects the demo's job: {}",
                String::from_utf8_lossy(&again.stderr)
            );
            let rerun: Value = serde_json::from_slice(&again.stdout).expect("JSON result");
            assert_same_json(&rerun, &result, name);
        } else {
            assert!(
                !name.starts_with("connect"),
                "{name}: result names its operation"
            );
        }
    }
    std::fs::remove_dir_all(&out).ok();
}
