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

/// The demo's scenarios: connections without and with interior constraints,
/// symmetric and asymmetric corner rounding, G2/G3 fillets by radius (two
/// lines at 90 degrees, two cubics) compared with the arc and the C^k
/// fillet, a wire of an arc, a line and a rational B-spline with every
/// vertex rounded, a closed plate outline with every corner rounded by
/// radius, merges with each metric and each constraint kind and of two
/// B-splines, Lagrange splines, and an intersection.
const SCENARIOS: [&str; 19] = [
    "connect-plain",
    "connect-constrained",
    "connect-auto-scale",
    "fillet-symmetric-c2",
    "fillet-asymmetric-c3",
    "fillet-radius-lines",
    "fillet-radius-curved",
    "fillet-chain-arc-line-nurbs",
    "fillet-chain-radius-plate",
    "merge-discrete",
    "merge-integral-optimal",
    "merge-keep-p",
    "merge-keep-q",
    "merge-fix-ends",
    "merge-keep-point",
    "merge-bsplines",
    "spline-cubic-c1",
    "spline-quintic-c2",
    "intersect-wavy-cubics",
];

/// The printed table: a header naming the columns scenario, degree, worst
/// continuity residual and max deviation, then one row per scenario whose
/// degree is the result's and whose continuity residual is the worst
/// promised jump the result reports (merges: P^ and Q^ meet as pieces of
/// one polynomial, so at rounding level).
fn assert_summary_table(table: &str, out: &Path) {
    let header = table.lines().next().expect("a table");
    let mut at = 0;
    for column in [
        "scenario",
        "degree",
        "worst continuity residual",
        "max deviation",
    ] {
        let i = header[at..]
            .find(column)
            .unwrap_or_else(|| panic!("column {column:?} missing or out of order in {header:?}"));
        at += i + column.len();
    }
    for name in SCENARIOS {
        let row = table
            .lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} has no row in the summary table"));
        let cells: Vec<&str> = row.split_whitespace().collect();
        let result = read_json(&out.join(format!("{name}.result.json")));
        let degree = ["curve", "blend"]
            .iter()
            .find_map(|k| result[k]["degree"].as_u64())
            .or_else(|| result["degree"].as_u64());
        if let Some(degree) = degree {
            assert_eq!(cells[1], degree.to_string(), "{name}: degree column");
        }
        let residual = cells[2];
        if let Some(joins) = result["report"]["measured_continuity"].as_array() {
            // The table's figure is the worst over the joins of the chain;
            // a single fillet's also covers its joins against the original
            // curves (`ops/fillet.rs`).
            let against_original = result["report"]["measured_continuity_against_original_curves"]
                .as_array()
                .cloned()
                .unwrap_or_default();
            let worst_of = |joins: &mut dyn Iterator<Item = &Value>| {
                joins
                    .map(|j| j["worst_promised_jump"].as_f64().unwrap())
                    .fold(0.0, f64::max)
            };
            let chain = worst_of(&mut joins.iter());
            let with_original = worst_of(&mut joins.iter().chain(against_original.iter()));
            let printed: f64 = residual.parse().expect("a number");
            let matches = |worst: f64| (printed - worst).abs() <= 0.01 * worst.max(1e-300);
            let single_fillet =
                result["operation"] == "fillet" && result["report"]["mode"] != "radius";
            assert!(
                if single_fillet {
                    matches(with_original)
                } else {
                    matches(chain) || matches(with_original)
                },
                "{name}: table says {printed}, result says {chain} (chain joins), {with_original} (with the joins against the originals)"
            );
        } else if name.starts_with("merge") {
            let printed: f64 = residual.parse().expect("a number");
            assert!(printed < 1e-9, "{name}: P^|Q^ residual {printed}");
        }
    }
}

/// A fillet picture draws, next to the blend, the plain circular-arc
/// fillet for comparison: a dashed curve labelled as such, starting where
/// the blend starts (at P(u0)), whose drawn points lie on one circle, and a
/// caption line naming it.
fn assert_circular_arc_reference(name: &str, svg: &str) {
    let curves = &svg[svg.find("<g id=\"curves\"").expect("a curves group")..];
    let curves = &curves[..curves.find("</g>").unwrap()];
    let drawn = |label: &str| -> (String, Vec<[f64; 2]>) {
        let end = curves
            .find(&format!("><title>{label}"))
            .unwrap_or_else(|| panic!("{name}: no curve labelled {label:?}"));
        let start = curves[..end].rfind("<polyline ").unwrap();
        let tag = &curves[start..end];
        let points = tag
            .split("points=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap();
        let points = points
            .split_whitespace()
            .map(|p| {
                let (x, y) = p.split_once(',').unwrap();
                [x.parse().unwrap(), y.parse().unwrap()]
            })
            .collect();
        (tag.to_string(), points)
    };
    let (arc_tag, arc) = drawn("circular-arc fillet");
    let (_, blend) = drawn("blend R");
    assert!(
        arc_tag.contains("stroke-dasharray"),
        "{name}: the reference is dashed"
    );
    let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    assert!(
        d(arc[0], blend[0]) < 0.05,
        "{name}: the arc starts at P(u0)"
    );
    // Circle through the first, middle and last drawn points.
    let (a, b, c) = (arc[0], arc[arc.len() / 2], arc[arc.len() - 1]);
    let det = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
    assert!(det.abs() > 1e-6, "{name}: the reference is not straight");
    let sq = |p: [f64; 2]| p[0] * p[0] + p[1] * p[1];
    let centre = [
        (sq(a) * (b[1] - c[1]) + sq(b) * (c[1] - a[1]) + sq(c) * (a[1] - b[1])) / det,
        (sq(a) * (c[0] - b[0]) + sq(b) * (a[0] - c[0]) + sq(c) * (b[0] - a[0])) / det,
    ];
    let radius = d(a, centre);
    for p in &arc {
        assert!(
            (d(*p, centre) - radius).abs() < 0.05,
            "{name}: the reference is not a circular arc"
        );
    }
    assert!(
        svg.contains("Reference: circular arc tangent to P at P(u0)"),
        "{name}: the caption names the reference"
    );
}

/// A fillet-by-radius scenario (issue 18): its job asks for the
/// comparison; the result compares the G1 arc (curvature jumps by about
/// 1/r at both cuts), the C2 fillet of the same setbacks and the G2 and G3
/// blends by radius (no jumps), all cut at the same points; the picture
/// has a panel title and a curvature graph per variant, and the joins of
/// the result are measured G2.
fn assert_radius_comparison(name: &str, out: &Path) {
    let job = read_json(&out.join(format!("{name}.job.json")));
    assert_eq!(
        job["compare"], true,
        "{name}: the job asks for the comparison"
    );
    let r = job["radius"].as_f64().unwrap();
    let result = read_json(&out.join(format!("{name}.result.json")));
    assert_eq!(result["report"]["mode"], "radius");
    for join in result["report"]["measured_continuity"].as_array().unwrap() {
        assert_eq!(join["continuity"], "geometric", "{name}: {join}");
        assert!(
            join["measured_order"].as_u64().unwrap() >= 2,
            "{name}: {join}"
        );
    }
    let variants = result["comparison"].as_array().expect("a comparison");
    let names: Vec<&str> = variants
        .iter()
        .map(|v| v["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "G1 arc",
            "C2, same setbacks",
            "G2 by radius",
            "G3 by radius"
        ],
        "{name}"
    );
    let (u0, v0) = (
        result["u0"].as_f64().unwrap(),
        result["v0"].as_f64().unwrap(),
    );
    for v in variants {
        assert!((v["u0"].as_f64().unwrap() - u0).abs() < 1e-9, "{name}: {v}");
        assert!((v["v0"].as_f64().unwrap() - v0).abs() < 1e-9, "{name}: {v}");
        let jumps: Vec<f64> = serde_json::from_value(v["curvature_jumps"].clone()).unwrap();
        assert_eq!(jumps.len(), 2);
        if v["name"] == "G1 arc" {
            // From the curves' own curvature (small here) to 1/r and back.
            for j in jumps {
                assert!((j.abs() - 1.0 / r).abs() < 0.5 / r, "{name}: arc jump {j}");
            }
        } else {
            for j in jumps {
                assert!(j.abs() < 1e-6 / r, "{name}: {} jumps by {j}", v["name"]);
            }
        }
    }
    let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
    for label in names {
        assert!(
            svg.contains(&format!(">{label}</text>")),
            "{name}.svg: no title {label:?}"
        );
    }
    let plots = &svg[svg.find("<g id=\"plots\"").expect("a row of graphs")..];
    assert_eq!(
        plots.matches("<clipPath ").count(),
        4,
        "{name}: four graphs"
    );
}

/// The wire scenario (issue 16): its job has an arc, a line and a rational
/// B-spline; its result has five pieces (three trimmed curves, the arc and
/// the B-spline still NURBS with their weights, and two blends), every one
/// of the four joins measured C3 at least; its summary row reports that
/// continuity; its picture draws the NURBS curves and a curvature comb on
/// every kept piece and blend, and names the measured orders.
fn assert_nurbs_wire_scenario(table: &str, out: &Path) {
    let name = "fillet-chain-arc-line-nurbs";
    let job = read_json(&out.join(format!("{name}.job.json")));
    let curves = job["curves"].as_array().expect("a wire of curves");
    assert!(curves[0].get("arc").is_some(), "first curve is an arc");
    assert!(curves[1].is_array(), "second curve is a line");
    let weights = curves[2]["weights"]
        .as_array()
        .expect("a rational B-spline");
    assert!(weights.iter().any(|w| w.as_f64() != Some(1.0)));
    let result = read_json(&out.join(format!("{name}.result.json")));
    let pieces = result["pieces"].as_array().unwrap();
    assert_eq!(pieces.len(), 5);
    for i in [0, 4] {
        assert!(pieces[i]["knots"].is_array() && pieces[i]["weights"].is_array());
    }
    let joins = result["report"]["measured_continuity"].as_array().unwrap();
    assert_eq!(joins.len(), 4, "two joins per corner");
    let mut worst: f64 = 0.0;
    for j in joins {
        assert!(j["measured_order"].as_u64().unwrap() >= 3, "{j}");
        worst = worst.max(j["worst_promised_jump"].as_f64().unwrap());
    }
    assert!(worst < 1e-9, "{worst}");
    let row = table
        .lines()
        .find(|l| l.starts_with(name))
        .expect("a summary row");
    let printed: f64 = row.split_whitespace().nth(2).unwrap().parse().unwrap();
    assert!(printed < 1e-9 && (printed - worst).abs() <= 0.01 * worst.max(1e-300));
    let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
    for label in [
        "curve 0, NURBS of degree 2, rational",
        "curve 2, NURBS of degree 3, rational, 2 spans",
        "blend 0, degree 7 (C3 | C3)",
        "blend 1, degree 7 (C3 | C3)",
        "blend 1|curve 2: C3 promised, C3 measured",
    ] {
        assert!(svg.contains(label), "{name}.svg lacks {label:?}");
    }
    let combs = &svg[svg.find("<g id=\"combs\"").unwrap()..];
    let combs = &combs[..combs.find("</g>").unwrap()];
    // Five kept pieces and blends carry combs; the "as given" curves do not.
    assert_eq!(combs.matches("<polyline ").count(), 5);
}

/// The closed wire rounded by radius (issue 18): its job is a closed
/// chain of lines, a cubic and an arc with a radius and G2; every corner
/// is reported with its arc's centre, and every join of the result (two
/// per corner, the closing one included) is measured G2 from derivatives
/// with respect to arc length; the picture has combs on the pieces, the
/// arcs and one curvature graph around the wire.
fn assert_radius_plate_scenario(out: &Path) {
    let name = "fillet-chain-radius-plate";
    let job = read_json(&out.join(format!("{name}.job.json")));
    assert_eq!(job["closed"], true);
    assert_eq!(job["order"], 2);
    let curves = job["curves"].as_array().unwrap();
    assert!(curves.iter().any(|c| c.get("arc").is_some()), "an arc edge");
    assert!(
        curves
            .iter()
            .any(|c| c.as_array().is_some_and(|p| p.len() == 4)),
        "a cubic edge"
    );
    let n = curves.len();
    let result = read_json(&out.join(format!("{name}.result.json")));
    assert_eq!(result["pieces"].as_array().unwrap().len(), 2 * n);
    let corners = result["corners"].as_array().unwrap();
    assert_eq!(corners.len(), n, "every corner of the closed wire");
    let r = job["radius"].as_f64().unwrap();
    for c in corners {
        let distances: Vec<f64> =
            serde_json::from_value(c["measured_centre_distances"].clone()).unwrap();
        for d in distances {
            assert!((d - r).abs() < 1e-9 * r, "{name}: centre at {d}, not r");
        }
    }
    let joins = result["report"]["measured_continuity"].as_array().unwrap();
    assert_eq!(joins.len(), 2 * n);
    assert_eq!(
        joins[2 * n - 1]["join"],
        "blend 5|curve 0",
        "the closing join"
    );
    for j in joins {
        assert_eq!(j["continuity"], "geometric", "{name}: {j}");
        assert!(j["measured_order"].as_u64().unwrap() >= 2, "{name}: {j}");
    }
    let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
    assert!(svg.contains("circular arc of radius 1"));
    let plots = &svg[svg.find("<g id=\"plots\"").expect("a curvature graph")..];
    assert_eq!(plots.matches("<clipPath ").count(), 1, "{name}: one graph");
    let combs = &svg[svg.find("<g id=\"combs\"").unwrap()..];
    let combs = &combs[..combs.find("</g>").unwrap()];
    // A comb on every kept piece and blend; none on the given curves and
    // the arcs (the graph shows the arcs' curvature).
    assert_eq!(combs.matches("<polyline ").count(), 2 * n, "{name}: combs");
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

/// The picture's caption lines after its title (degree, continuity
/// measured, the library's residual, ...) are in the SVG, which the page
/// shows: the page's figure does not print them a second time.
fn assert_caption_not_repeated(name: &str, index: &str, svg: &str) {
    let open = format!("<figure id=\"{name}\">");
    let start = index
        .find(&open)
        .unwrap_or_else(|| panic!("{name}: no figure"));
    let figure = &index[start..start + index[start..].find("</figure>").unwrap()];
    let group_start = svg.find("<g id=\"caption\"").expect("a caption group");
    let group = &svg[group_start..group_start + svg[group_start..].find("</g>").unwrap()];
    let mut lines = Vec::new();
    let mut rest = group;
    while let Some(i) = rest.find("<text") {
        let begin = i + rest[i..].find('>').unwrap() + 1;
        let end = begin + rest[begin..].find("</text>").unwrap();
        lines.push(&rest[begin..end]);
        rest = &rest[end..];
    }
    assert!(lines.len() > 1, "{name}: the picture has caption lines");
    for line in &lines[1..] {
        assert!(
            !figure.contains(line),
            "{name}: the page repeats the picture's caption line {line:?}"
        );
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
    // Every scenario of the papers (issue 8, item 3), once each, in order.
    assert_eq!(names, SCENARIOS, "the scenarios index.html lists");
    for name in &names {
        let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
        assert_caption_not_repeated(name, &index, &svg);
    }
    let table = String::from_utf8_lossy(&run.stdout);
    assert_summary_table(&table, &out);
    for name in names.iter().filter(|n| n.starts_with("fillet-")) {
        let result = read_json(&out.join(format!("{name}.result.json")));
        if result["operation"] == "fillet" && result["report"]["mode"] != "radius" {
            let svg = std::fs::read_to_string(out.join(format!("{name}.svg"))).unwrap();
            assert_circular_arc_reference(name, &svg);
        }
    }
    for name in ["fillet-radius-lines", "fillet-radius-curved"] {
        assert_radius_comparison(name, &out);
    }
    assert_nurbs_wire_scenario(&table, &out);
    assert_radius_plate_scenario(&out);
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
