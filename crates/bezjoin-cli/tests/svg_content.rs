//! What the `--svg` pictures show, read back from the SVG the binary writes:
//! the result's control polygon (its vertices are the returned control
//! points under one similarity map of the picture), a curvature comb on
//! every curve that is not a discarded "as given" curve (spikes starting on
//! the curve and normal to it), join markers where the result's pieces
//! meet, and a caption with the degree and the continuity orders taken from
//! the job. 3D jobs are drawn in top view and say so; 2D jobs do not.

mod common;
use common::assert_well_formed_xml;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};

use serde_json::{Value, json};

type Pt = [f64; 2];

/// Pixel tolerance for positions written with two decimals.
const PX: f64 = 0.05;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Run `bezjoin <op> - --svg FILE` with `job` on stdin: (result, SVG text).
fn run(op: &str, job: &Value) -> (Value, String) {
    let svg = std::env::temp_dir().join(format!(
        "bezjoin-svg-content-{op}-{}-{:?}.svg",
        std::process::id(),
        std::thread::current().id()
    ));
    let args = [
        OsStr::new(op),
        OsStr::new("-"),
        OsStr::new("--svg"),
        svg.as_os_str(),
    ];
    let out = common::run_bezjoin(&args, job.to_string().as_bytes());
    assert!(
        out.status.success(),
        "bezjoin {op}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let result: Value = serde_json::from_slice(&out.stdout).expect("a JSON result");
    let text = std::fs::read_to_string(&svg).expect("the SVG is written");
    std::fs::remove_file(&svg).ok();
    assert_well_formed_xml(&text);
    (result, text)
}

/// The content of `<g id="ID" ...> ... </g>` (the picture's groups are not nested).
fn group<'a>(svg: &'a str, id: &str) -> &'a str {
    let start = svg
        .find(&format!("<g id=\"{id}\""))
        .unwrap_or_else(|| panic!("no group {id:?} in the picture"));
    let end = start + svg[start..].find("</g>").expect("the group is closed");
    &svg[start..end]
}

/// Opening tags `<NAME ...>` in `text`.
fn tags<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let open = format!("<{name} ");
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find(&open) {
        let end = i + rest[i..].find('>').expect("a closed tag") + 1;
        found.push(&rest[i..end]);
        rest = &rest[end..];
    }
    found
}

fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    Some(&tag[start..start + tag[start..].find('"')?])
}

fn number(text: &str) -> f64 {
    text.trim()
        .parse()
        .unwrap_or_else(|e| panic!("{text:?}: {e}"))
}

/// `points="x,y x,y ..."` of a polyline.
fn polyline_points(tag: &str) -> Vec<Pt> {
    attr(tag, "points")
        .expect("a points attribute")
        .split_whitespace()
        .map(|pair| {
            let (x, y) = pair.split_once(',').expect("x,y");
            [number(x), number(y)]
        })
        .collect()
}

/// The `M x y L x y` segments of a comb's spike path: (base, tip).
fn spikes(tag: &str) -> Vec<(Pt, Pt)> {
    attr(tag, "d")
        .expect("a d attribute")
        .split('M')
        .filter(|s| !s.trim().is_empty())
        .map(|seg| {
            let (a, b) = seg.split_once('L').expect("M x y L x y");
            let p = |s: &str| {
                let v: Vec<f64> = s.split_whitespace().map(number).collect();
                assert_eq!(v.len(), 2, "a point in {s:?}");
                [v[0], v[1]]
            };
            (p(a), p(b))
        })
        .collect()
}

fn unescape(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// Text contents of the `<text>` elements in `part`.
fn texts(part: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = part;
    while let Some(i) = rest.find("<text") {
        let start = i + rest[i..].find('>').unwrap() + 1;
        let end = start + rest[start..].find("</text>").unwrap();
        found.push(unescape(&rest[start..end]));
        rest = &rest[end..];
    }
    found
}

/// One drawn curve of the `curves` group: its sampled points, stroke and label.
struct Drawn {
    points: Vec<Pt>,
    stroke: String,
    label: String,
}

fn drawn_curves(svg: &str) -> Vec<Drawn> {
    let curves = group(svg, "curves");
    let mut found = Vec::new();
    let mut rest = curves;
    while let Some(i) = rest.find("<polyline ") {
        let tag_end = i + rest[i..].find('>').unwrap() + 1;
        let tag = &rest[i..tag_end];
        let title_start = tag_end
            + rest[tag_end..]
                .find("<title>")
                .expect("every curve has a title")
            + "<title>".len();
        let title_end = title_start + rest[title_start..].find("</title>").unwrap();
        found.push(Drawn {
            points: polyline_points(tag),
            stroke: attr(tag, "stroke").unwrap().to_string(),
            label: unescape(&rest[title_start..title_end]),
        });
        rest = &rest[title_end..];
    }
    found
}

fn dist(a: Pt, b: Pt) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn distance_to_polyline(p: Pt, line: &[Pt]) -> f64 {
    line.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let ab = [b[0] - a[0], b[1] - a[1]];
            let len2 = ab[0] * ab[0] + ab[1] * ab[1];
            let t = if len2 > 0.0 {
                (((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            dist(p, [a[0] + t * ab[0], a[1] + t * ab[1]])
        })
        .fold(f64::INFINITY, f64::min)
}

/// Control points (first two coordinates) of a result curve object.
fn control_points(curve: &Value) -> Vec<Pt> {
    curve["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
        .collect()
}

/// Point of the Bezier curve with control points `b` at `t` (de Casteljau).
fn bezier_at(b: &[Pt], t: f64) -> Pt {
    let mut w = b.to_vec();
    for r in 1..w.len() {
        for i in 0..w.len() - r {
            let next = w[i + 1];
            w[i] = [
                (1.0 - t) * w[i][0] + t * next[0],
                (1.0 - t) * w[i][1] + t * next[1],
            ];
        }
    }
    w[0]
}

/// The picture's map from model x-y to pixels: `(a + s x, b - s y)`.
struct Map {
    s: f64,
    a: f64,
    b: f64,
}

impl Map {
    /// Least-squares fit of the similarity map taking `model` to `pixels`.
    fn fit(model: &[Pt], pixels: &[Pt]) -> Map {
        let n = model.len() as f64;
        let mean = |v: &[Pt], c: usize| v.iter().map(|p| p[c]).sum::<f64>() / n;
        let (mx, my, px, py) = (
            mean(model, 0),
            mean(model, 1),
            mean(pixels, 0),
            mean(pixels, 1),
        );
        let (mut num, mut den) = (0.0, 0.0);
        for (m, p) in model.iter().zip(pixels) {
            num += (p[0] - px) * (m[0] - mx) - (p[1] - py) * (m[1] - my);
            den += (m[0] - mx).powi(2) + (m[1] - my).powi(2);
        }
        let s = num / den;
        Map {
            s,
            a: px - s * mx,
            b: py + s * my,
        }
    }

    fn apply(&self, p: Pt) -> Pt {
        [self.a + self.s * p[0], self.b - self.s * p[1]]
    }
}

/// The result curves' control polygons are drawn: for every curve in
/// `results` there is a polygon polyline in the result's colour whose
/// vertices are its control points under one map (fitted on the first).
/// Returns that map.
fn assert_result_polygons(svg: &str, results: &[Vec<Pt>], result_stroke: &str) -> Map {
    let polygons: Vec<Vec<Pt>> = tags(group(svg, "polygons"), "polyline")
        .into_iter()
        .filter(|t| attr(t, "stroke") == Some(result_stroke))
        .map(polyline_points)
        .collect();
    let first = &results[0];
    let map = polygons
        .iter()
        .filter(|poly| poly.len() == first.len())
        .map(|poly| (Map::fit(first, poly), poly))
        .find(|(map, poly)| {
            map.s > 0.0
                && first
                    .iter()
                    .zip(poly.iter())
                    .all(|(&m, &p)| dist(map.apply(m), p) < PX)
        })
        .map(|(map, _)| map)
        .unwrap_or_else(|| {
            panic!("no control polygon in the result's colour matches the returned control points")
        });
    for (i, curve) in results.iter().enumerate() {
        assert!(
            polygons.iter().any(|poly| poly.len() == curve.len()
                && curve
                    .iter()
                    .zip(poly)
                    .all(|(&m, &p)| dist(map.apply(m), p) < PX)),
            "the control polygon of result curve {i} is not drawn"
        );
        // Each control point is drawn as a small square centred on it.
        let squares: Vec<Pt> = tags(group(svg, "polygons"), "rect")
            .into_iter()
            .map(|t| {
                [
                    number(attr(t, "x").unwrap()) + number(attr(t, "width").unwrap()) / 2.0,
                    number(attr(t, "y").unwrap()) + number(attr(t, "height").unwrap()) / 2.0,
                ]
            })
            .collect();
        for &m in curve {
            assert!(
                squares.iter().any(|&q| dist(q, map.apply(m)) < PX),
                "control point {m:?} of result curve {i} has no square"
            );
        }
    }
    map
}

/// Every drawn curve except the discarded "as given" ones carries a
/// curvature comb: a spike path whose spikes all start on that curve and
/// are normal to it (checked on spikes longer than 3 px), with a tip line.
/// Curves whose label starts with one of `curved` must have spikes longer
/// than 1 px somewhere (they are not straight). Returns the number of combs.
fn assert_combs(svg: &str, curved: &[&str]) -> usize {
    let combs = group(svg, "combs");
    let spike_paths: Vec<Vec<(Pt, Pt)>> = tags(combs, "path").into_iter().map(spikes).collect();
    let tip_lines = tags(combs, "polyline").len();
    assert_eq!(tip_lines, spike_paths.len(), "every comb has its tip line");
    let curves = drawn_curves(svg);
    let mut combed = 0;
    for curve in curves.iter().filter(|c| !c.label.contains("as given")) {
        let line = &curve.points;
        let comb = spike_paths
            .iter()
            .find(|path| {
                !path.is_empty()
                    && path
                        .iter()
                        .all(|&(base, _)| distance_to_polyline(base, line) < PX)
            })
            .unwrap_or_else(|| panic!("{:?} has no curvature comb", curve.label));
        combed += 1;
        for &(base, tip) in comb {
            let length = dist(base, tip);
            if length <= 3.0 {
                continue;
            }
            let j = (0..line.len())
                .min_by(|&a, &b| dist(line[a], base).total_cmp(&dist(line[b], base)))
                .unwrap();
            if j == 0 || j + 1 == line.len() {
                continue;
            }
            let tangent = [
                line[j + 1][0] - line[j - 1][0],
                line[j + 1][1] - line[j - 1][1],
            ];
            let cos = ((tip[0] - base[0]) * tangent[0] + (tip[1] - base[1]) * tangent[1])
                / (length * tangent[0].hypot(tangent[1]));
            assert!(
                cos.abs() < 0.05,
                "a spike of {:?} is not normal to it (cos {cos:.3})",
                curve.label
            );
        }
        if curved.iter().any(|p| curve.label.starts_with(p)) {
            assert!(
                comb.iter().any(|&(b, t)| dist(b, t) > 1.0),
                "{:?} is curved but its comb is flat",
                curve.label
            );
        }
    }
    combed
}

/// Centres of the join markers (circles) in the drawing.
fn join_markers(svg: &str) -> Vec<Pt> {
    tags(group(svg, "markers"), "circle")
        .into_iter()
        .map(|t| {
            [
                number(attr(t, "cx").unwrap()),
                number(attr(t, "cy").unwrap()),
            ]
        })
        .collect()
}

/// The join markers are exactly at `expected` (model points under `map`),
/// and the legend explains them.
fn assert_join_markers(svg: &str, map: &Map, expected: &[Pt]) {
    let markers = join_markers(svg);
    assert_eq!(markers.len(), expected.len(), "join markers {markers:?}");
    for &e in expected {
        let at = map.apply(e);
        assert!(
            markers.iter().any(|&m| dist(m, at) < PX),
            "no join marker at {e:?} (pixel {at:?}); markers {markers:?}"
        );
    }
    assert!(
        texts(group(svg, "legend"))
            .iter()
            .any(|t| t == "join point"),
        "the legend explains the join marker"
    );
}

fn caption(svg: &str) -> String {
    texts(group(svg, "caption")).join("\n")
}

fn assert_caption_has(svg: &str, needles: &[String]) {
    let caption = caption(svg);
    for needle in needles {
        assert!(
            caption.contains(needle.as_str()),
            "caption lacks {needle:?}:\n{caption}"
        );
    }
}

const TOP_VIEW_NOTE: &str = "shown in top view";

fn result_stroke(svg: &str, label_start: &str) -> String {
    drawn_curves(svg)
        .into_iter()
        .find(|c| c.label.starts_with(label_start))
        .unwrap_or_else(|| panic!("no drawn curve labelled {label_start:?}"))
        .stroke
}

/// The caption of a connect or fillet picture names the result's degree and,
/// at both joins, the continuity order the job asked for, promised and
/// measured.
fn assert_caption_names_degree_and_join_orders(svg: &str, job: &Value, degree: u64) {
    let (kp, kq) = (
        job["p_order"].as_u64().unwrap(),
        job["q_order"].as_u64().unwrap(),
    );
    assert_caption_has(
        svg,
        &[
            format!("degree {degree}"),
            format!("P|R: C{kp} promised, C{kp} measured"),
            format!("R|Q: C{kq} promised, C{kq} measured"),
        ],
    );
}

#[test]
fn connect_picture_shows_polygon_combs_joins_and_caption() {
    let job = read_json(&example("connect.json"));
    let (result, svg) = run("connect", &job);
    let r = control_points(&result["curve"]);
    let degree = result["curve"]["degree"].as_u64().unwrap();
    let map = assert_result_polygons(&svg, std::slice::from_ref(&r), &result_stroke(&svg, "R,"));
    // P, Q and R each carry a comb.
    assert!(assert_combs(&svg, &["R,"]) >= 3);
    // The join markers are R(0) = P(u0) and R(1) = Q(v0).
    assert_join_markers(&svg, &map, &[r[0], *r.last().unwrap()]);
    assert_caption_names_degree_and_join_orders(&svg, &job, degree);
    assert!(
        !caption(&svg).contains(TOP_VIEW_NOTE),
        "a 2D job is not projected"
    );
}

#[test]
fn fillet_picture_shows_polygon_combs_joins_and_caption() {
    let job = read_json(&example("fillet.json"));
    let (result, svg) = run("fillet", &job);
    let r = control_points(&result["blend"]);
    let degree = result["blend"]["degree"].as_u64().unwrap();
    let map = assert_result_polygons(
        &svg,
        std::slice::from_ref(&r),
        &result_stroke(&svg, "blend R"),
    );
    // The kept parts of P and Q, the blend and the circular-arc reference.
    assert!(assert_combs(&svg, &["blend R", "circular-arc"]) >= 4);
    assert_join_markers(&svg, &map, &[r[0], *r.last().unwrap()]);
    assert_caption_names_degree_and_join_orders(&svg, &job, degree);
    assert!(!caption(&svg).contains(TOP_VIEW_NOTE));
}

#[test]
fn merge_picture_shows_polygon_combs_split_point_and_caption() {
    let job = read_json(&example("merge.json"));
    let (result, svg) = run("merge", &job);
    let r = control_points(&result["curve"]);
    let degree = result["curve"]["degree"].as_u64().unwrap();
    let mu = result["report"]["mu"].as_f64().unwrap();
    let map = assert_result_polygons(&svg, std::slice::from_ref(&r), &result_stroke(&svg, "R,"));
    assert!(assert_combs(&svg, &["R,"]) >= 3);
    // Where P^ and Q^ meet: R(mu).
    assert_join_markers(&svg, &map, &[bezier_at(&r, mu)]);
    // One polynomial: P^ and Q^ join with every derivative up to the degree.
    assert_caption_has(
        &svg,
        &[
            format!("degree {degree}"),
            format!("P^|Q^ at R(mu): C{degree} promised, C{degree} measured"),
        ],
    );
    assert!(!caption(&svg).contains(TOP_VIEW_NOTE));
}

#[test]
fn spline_picture_shows_polygons_combs_nodes_and_caption() {
    let job = read_json(&example("spline.json"));
    let (result, svg) = run("spline", &job);
    let segments: Vec<Vec<Pt>> = result["segments"]
        .as_array()
        .unwrap()
        .iter()
        .map(control_points)
        .collect();
    let degree = job["degree"].as_u64().unwrap();
    let k = job["continuity"].as_u64().unwrap();
    let map = assert_result_polygons(&svg, &segments, &result_stroke(&svg, "segment 0"));
    assert_eq!(
        assert_combs(&svg, &["segment"]),
        segments.len(),
        "one comb per segment"
    );
    // Every node (a segment end) is a join marker.
    let nodes: Vec<Pt> = job["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
        .collect();
    assert_eq!(nodes.len(), segments.len() + 1);
    assert_join_markers(&svg, &map, &nodes);
    assert_caption_has(
        &svg,
        &[
            format!("segments of degree {degree}, C{k} promised at every node"),
            format!("Measured at all {} nodes: C{k}", segments.len() - 1),
        ],
    );
    assert!(!caption(&svg).contains(TOP_VIEW_NOTE));
}

/// A 4D job is answered (any dimension is) and its picture names its
/// dimension in the top-view note (not "3D").
#[test]
fn four_dimensional_connection_names_its_dimension_in_the_note() {
    let job = json!({
        "p": [[0.0, 0.0, 0.0, 0.0], [1.0, 2.0, 1.0, 0.5]],
        "q": [[7.0, 2.0, 3.0, 1.0], [8.0, 3.0, 1.0, 2.0]],
        "p_order": 1,
        "q_order": 1
    });
    let (result, svg) = run("connect", &job);
    assert_eq!(result["curve"]["dim"], 4);
    assert_caption_has(
        &svg,
        &["4D curves shown in top view (x-y projection)".to_string()],
    );
    assert!(!caption(&svg).contains("3D curves"));
}

#[test]
fn three_dimensional_connection_is_drawn_in_top_view_with_a_note() {
    let job = json!({
        "p": [[0.0, 0.0, 0.0], [1.0, 2.0, 1.0], [3.0, 3.0, 2.5], [4.0, 2.5, 4.0]],
        "q": [[7.0, 2.0, 3.0], [8.0, 3.0, 1.0], [10.0, 1.0, 0.5], [11.0, -1.0, 0.0]],
        "p_order": 2,
        "q_order": 1
    });
    let (result, svg) = run("connect", &job);
    assert_eq!(result["curve"]["dim"], 3);
    assert_caption_has(
        &svg,
        &["3D curves shown in top view (x-y projection)".to_string()],
    );
    // The top view: the polygon drawn is the x-y projection of R's control points.
    let r = control_points(&result["curve"]);
    let map = assert_result_polygons(&svg, std::slice::from_ref(&r), &result_stroke(&svg, "R,"));
    assert!(assert_combs(&svg, &["R,"]) >= 3);
    assert_join_markers(&svg, &map, &[r[0], *r.last().unwrap()]);
    assert_caption_has(
        &svg,
        &[
            format!("degree {}", result["curve"]["degree"]),
            "P|R: C2 promised".to_string(),
            "R|Q: C1 promised".to_string(),
        ],
    );
}

#[test]
fn the_picture_readers_reject_what_they_must_not_find() {
    // The checks above can fail: a picture without a comb, with a polygon
    // that is not the control polygon, or with a misplaced marker.
    let job = read_json(&example("connect.json"));
    let (result, svg) = run("connect", &job);
    let r = control_points(&result["curve"]);
    let stroke = result_stroke(&svg, "R,");
    let no_combs = {
        let start = svg.find("<g id=\"combs\"").unwrap();
        let end = start + svg[start..].find("</g>").unwrap();
        format!("{}<g id=\"combs\">{}", &svg[..start], &svg[end..])
    };
    assert!(std::panic::catch_unwind(|| assert_combs(&no_combs, &[])).is_err());
    // Spikes turned horizontal (same length) are not normal to the curves.
    let mut sideways = svg.clone();
    for tag in tags(group(&svg, "combs"), "path") {
        let d = attr(tag, "d").unwrap();
        let turned: String = spikes(tag)
            .into_iter()
            .map(|(b, t)| format!("M{} {}L{} {}", b[0], b[1], b[0] + dist(b, t), b[1]))
            .collect();
        sideways = sideways.replace(d, &turned);
    }
    assert_ne!(sideways, svg);
    assert!(std::panic::catch_unwind(|| assert_combs(&sideways, &[])).is_err());
    let mut moved = r.clone();
    moved[1][0] += 0.5;
    assert!(std::panic::catch_unwind(|| assert_result_polygons(&svg, &[moved], &stroke)).is_err());
    let map = assert_result_polygons(&svg, std::slice::from_ref(&r), &stroke);
    let elsewhere = bezier_at(&r, 0.5);
    assert!(
        std::panic::catch_unwind(|| assert_join_markers(&svg, &map, &[r[0], elsewhere])).is_err()
    );
}

/// NURBS curves are drawn from their own points and derivatives: in the
/// fillet of `examples/fillet-vertex-nurbs.json`, an exact circular arc
/// (the job's `"arc"` form: centre (3, 0), radius 3, a rational quadratic
/// NURBS) and a rational cubic B-spline, the kept part of the arc
/// is drawn on the circle (centre and radius mapped by the picture's map),
/// its comb spikes all have one length (constant curvature) and lie on
/// lines through the centre, the B-spline's poles are its polygon's
/// squares, and every kept piece and the blend carry a comb.
#[test]
fn nurbs_curves_are_drawn_with_polygons_and_combs() {
    let job = read_json(&example("fillet-vertex-nurbs.json"));
    let (result, svg) = run("fillet", &job);
    assert!(result["p_trimmed"]["knots"].is_array() && result["q_trimmed"]["weights"].is_array());
    let r = control_points(&result["blend"]);
    let map = assert_result_polygons(
        &svg,
        std::slice::from_ref(&r),
        &result_stroke(&svg, "blend R"),
    );
    let curves = drawn_curves(&svg);
    let labelled = |start: &str| {
        curves
            .iter()
            .find(|c| c.label.starts_with(start))
            .unwrap_or_else(|| panic!("no curve labelled {start:?}"))
    };
    labelled("P, NURBS of degree 2, rational, 2 spans, as given");
    labelled("Q, NURBS of degree 3, rational, 2 spans, as given");
    let arc = labelled("P on [");
    let centre = map.apply([3.0, 0.0]);
    let radius = 3.0 * map.s;
    for &p in &arc.points {
        assert!(
            (dist(p, centre) - radius).abs() < PX,
            "a drawn point of the arc is off its circle"
        );
    }
    // The arc's comb: the spike path whose bases lie on the arc.
    let combs = group(&svg, "combs");
    let comb = tags(combs, "path")
        .into_iter()
        .map(spikes)
        .find(|s| {
            s.iter()
                .all(|&(b, _)| distance_to_polyline(b, &arc.points) < PX)
        })
        .expect("the arc has a comb");
    let length = dist(comb[0].0, comb[0].1);
    assert!(length > 3.0, "a visible comb");
    for &(base, tip) in &comb {
        assert!(
            (dist(base, tip) - length).abs() < 2.0 * PX,
            "constant curvature"
        );
        // On the line through the centre: base, tip and centre collinear.
        let cross =
            (tip[0] - base[0]) * (centre[1] - base[1]) - (tip[1] - base[1]) * (centre[0] - base[0]);
        assert!(cross.abs() / (length * radius) < 0.01, "spike not radial");
        // Away from the centre of curvature.
        assert!(dist(tip, centre) > dist(base, centre));
    }
    // The B-spline's poles are drawn as its polygon's squares.
    let squares: Vec<Pt> = tags(group(&svg, "polygons"), "rect")
        .into_iter()
        .map(|t| {
            [
                number(attr(t, "x").unwrap()) + 2.5,
                number(attr(t, "y").unwrap()) + 2.5,
            ]
        })
        .collect();
    for pole in job["q"]["poles"].as_array().unwrap() {
        let at = map.apply([pole[0].as_f64().unwrap(), pole[1].as_f64().unwrap()]);
        assert!(
            squares.iter().any(|&s| dist(s, at) < PX),
            "pole {pole} has no square"
        );
    }
    // Kept arc, kept B-spline, blend: each has a comb; the blend and both
    // kept parts bend.
    assert!(assert_combs(&svg, &["P on [", "Q on [", "blend R"]) >= 3);
    assert_join_markers(&svg, &map, &[r[0], *r.last().unwrap()]);
}

/// Marker labels stay inside the picture: measured with DejaVu Sans's widest
/// common advance at font size 12 (about 0.6 em = 7.2 px per character, an
/// upper bound for these labels), a label that starts at `x` ends before the
/// picture's width, and one anchored at its end starts after 0. The merge
/// and spline examples put a label at a point near the right edge.
#[test]
fn marker_labels_stay_inside_the_picture() {
    for (op, file) in [
        ("merge", "merge.json"),
        ("spline", "spline.json"),
        ("connect", "connect.json"),
        ("fillet", "fillet.json"),
    ] {
        let (_, svg) = run(op, &read_json(&example(file)));
        let width = number(attr(tags(&svg, "svg")[0], "width").unwrap());
        let markers = group(&svg, "markers");
        let labels = tags(markers, "text");
        let contents = texts(markers);
        assert_eq!(labels.len(), contents.len());
        for (tag, text) in labels.iter().zip(&contents) {
            let x = number(attr(tag, "x").unwrap());
            let extent = 7.2 * text.chars().count() as f64;
            let (left, right) = match attr(tag, "text-anchor") {
                Some("end") => (x - extent, x),
                None | Some("start") => (x, x + extent),
                Some(other) => panic!("{file}: anchor {other:?}"),
            };
            assert!(
                left >= 0.0 && right <= width,
                "{file}: label {text:?} spans {left:.1}..{right:.1} of a {width} px picture"
            );
        }
    }
}
