//! Helpers shared by the CLI's process tests.
#![allow(dead_code)] // each test binary uses its own subset

use std::ffi::{OsStr, OsString};
use std::io::Write as _;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Runs the `bezjoin` binary with `args`, writing `stdin` to its standard
/// input, and returns what it printed and its exit status.
pub fn run_bezjoin<S: AsRef<OsStr>>(args: &[S], stdin: &[u8]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_bezjoin"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the bezjoin binary starts");
    // A job the tool refuses early may close its stdin before all is written.
    child.stdin.take().unwrap().write_all(stdin).ok();
    child.wait_with_output().expect("the bezjoin binary runs")
}

/// Minimal XML well-formedness check: one root element, every start tag
/// closed by a matching end tag in order, quoted attribute values, no raw
/// `<` or stray `&` in text; comments, processing instructions, DOCTYPE and
/// CDATA sections are skipped.
pub fn assert_well_formed_xml(text: &str) {
    fn check_entities(s: &str, at: usize) {
        let mut rest = s;
        while let Some(i) = rest.find('&') {
            let after = &rest[i + 1..];
            let end = after
                .find(';')
                .unwrap_or_else(|| panic!("unterminated entity near byte {at}"));
            let name = &after[..end];
            let ok = matches!(name, "amp" | "lt" | "gt" | "quot" | "apos")
                || (name.starts_with("#x")
                    && name.len() > 2
                    && name[2..].chars().all(|c| c.is_ascii_hexdigit()))
                || (name.starts_with('#')
                    && name.len() > 1
                    && name[1..].chars().all(|c| c.is_ascii_digit()));
            assert!(ok, "bad entity &{name}; near byte {at}");
            rest = &after[end + 1..];
        }
    }
    fn is_name(s: &str) -> bool {
        let mut chars = s.chars();
        matches!(chars.next(), Some(c) if c.is_alphabetic() || c == '_' || c == ':')
            && chars.all(|c| c.is_alphanumeric() || matches!(c, '_' | ':' | '-' | '.'))
    }

    let bytes = text.as_bytes();
    let mut stack: Vec<String> = Vec::new();
    let mut roots = 0;
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] != b'<' {
            let next = text[i..].find('<').map_or(text.len(), |n| i + n);
            let chunk = &text[i..next];
            check_entities(chunk, i);
            assert!(
                !stack.is_empty() || chunk.trim().is_empty(),
                "text outside the root element near byte {i}"
            );
            i = next;
            continue;
        }
        let rest = &text[i..];
        let skip = |open: &str, close: &str| -> Option<usize> {
            rest.starts_with(open).then(|| {
                rest.find(close)
                    .unwrap_or_else(|| panic!("unterminated {open} at byte {i}"))
                    + close.len()
            })
        };
        if let Some(n) = skip("<!--", "-->")
            .or_else(|| skip("<![CDATA[", "]]>"))
            .or_else(|| skip("<?", "?>"))
            .or_else(|| skip("<!DOCTYPE", ">"))
        {
            i += n;
            continue;
        }
        // A tag: find its end, honouring quoted attribute values.
        let mut j = i + 1;
        let mut quote: Option<u8> = None;
        while j < bytes.len() {
            match (quote, bytes[j]) {
                (None, b'>') => break,
                (None, b'"' | b'\'') => quote = Some(bytes[j]),
                (Some(q), c) if c == q => quote = None,
                (None, b'<') => panic!("'<' inside a tag at byte {j}"),
                _ => {}
            }
            j += 1;
        }
        assert!(j < bytes.len(), "unterminated tag at byte {i}");
        let inner = &text[i + 1..j];
        if let Some(name) = inner.strip_prefix('/') {
            let name = name.trim_end();
            let open = stack
                .pop()
                .unwrap_or_else(|| panic!("</{name}> without a start tag at byte {i}"));
            assert_eq!(open, name, "</{name}> closes <{open}> at byte {i}");
        } else {
            let self_closing = inner.ends_with('/');
            let body = inner.strip_suffix('/').unwrap_or(inner);
            let name_end = body.find(|c: char| c.is_whitespace()).unwrap_or(body.len());
            let name = &body[..name_end];
            assert!(is_name(name), "bad tag name {name:?} at byte {i}");
            check_attributes(&body[name_end..], i);
            if stack.is_empty() {
                roots += 1;
                assert_eq!(roots, 1, "a second root element <{name}> at byte {i}");
            }
            if !self_closing {
                stack.push(name.to_string());
            }
        }
        i = j + 1;
    }
    assert!(stack.is_empty(), "unclosed elements: {stack:?}");
    assert_eq!(roots, 1, "no root element");

    fn check_attributes(mut s: &str, at: usize) {
        let mut seen = Vec::new();
        loop {
            s = s.trim_start();
            if s.is_empty() {
                return;
            }
            let eq = s
                .find('=')
                .unwrap_or_else(|| panic!("attribute without value near byte {at}: {s:?}"));
            let name = s[..eq].trim();
            assert!(is_name(name), "bad attribute name {name:?} near byte {at}");
            assert!(
                !seen.contains(&name.to_string()),
                "duplicate attribute {name}"
            );
            seen.push(name.to_string());
            let value = s[eq + 1..].trim_start();
            let q = value.chars().next().unwrap_or(' ');
            assert!(
                q == '"' || q == '\'',
                "unquoted attribute {name} near byte {at}"
            );
            let close = value[1..]
                .find(q)
                .unwrap_or_else(|| panic!("unterminated attribute {name} near byte {at}"));
            let v = &value[1..1 + close];
            assert!(!v.contains('<'), "'<' in attribute {name} near byte {at}");
            check_entities(v, at);
            s = &value[close + 2..];
        }
    }
}

/// Runs `bezjoin OP -` with `job` on stdin (and `--svg PATH` when given):
/// exit code, stdout, stderr.
pub fn run_job(op: &str, job: &serde_json::Value, svg: Option<&Path>) -> (i32, String, String) {
    let mut args = vec![OsString::from(op), OsString::from("-")];
    if let Some(path) = svg {
        args.push("--svg".into());
        args.push(path.into());
    }
    let out = run_bezjoin(&args, job.to_string().as_bytes());
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// [`run_job`] that must succeed: the printed JSON result.
pub fn job_result(op: &str, job: &serde_json::Value) -> serde_json::Value {
    let (code, stdout, stderr) = run_job(op, job, None);
    assert_eq!(code, 0, "{job}: {stderr}");
    serde_json::from_str(&stdout).expect("JSON result")
}

/// A printed Bezier curve (`{"points": [...]}`) or a job's array of points.
pub fn bezier_of(value: &serde_json::Value) -> bezjoin_core::BezierCurve {
    let rows: Vec<Vec<f64>> =
        serde_json::from_value(value.get("points").unwrap_or(value).clone()).unwrap();
    bezjoin_core::BezierCurve::new(rows[0].len(), rows.len() - 1, rows.concat()).unwrap()
}

/// `a . b`.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `|v|`.
pub fn norm(v: &[f64]) -> f64 {
    dot(v, v).sqrt()
}

/// `|a - b|`.
pub fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The Frenet data at `t` from the parametric derivatives `r'`, `r''`,
/// `r'''`: unit tangent `T = r'/v`, curvature vector
/// `K = (r'' - (r''.T) T) / v^2` and its arc-length derivative
/// `K_s = (r''' - (r'''.T + v^3 |K|^2) T - 3 v v' K) / v^3`
/// (`v = |r'|`, `v' = r''.T`; from `r''' = v'' T + 3 v v' K + v^3 K_s`
/// and `K_s . T = -|K|^2`).
pub fn frenet(c: &bezjoin_core::BezierCurve, t: f64) -> [Vec<f64>; 3] {
    let d = c.eval_derivatives(t, 3);
    let n = c.dim();
    let (d1, d2, d3) = (&d[n..2 * n], &d[2 * n..3 * n], &d[3 * n..4 * n]);
    let v = norm(d1);
    let tangent: Vec<f64> = d1.iter().map(|x| x / v).collect();
    let v1 = dot(d2, &tangent);
    let k: Vec<f64> = (0..n)
        .map(|i| (d2[i] - v1 * tangent[i]) / (v * v))
        .collect();
    let v2 = dot(d3, &tangent) + v.powi(3) * dot(&k, &k);
    let ks: Vec<f64> = (0..n)
        .map(|i| (d3[i] - v2 * tangent[i] - 3.0 * v * v1 * k[i]) / v.powi(3))
        .collect();
    [tangent, k, ks]
}

/// Largest `|K|` and `|K_s|` over the blend `c` (sampled): the sizes jumps
/// are measured against.
pub fn sizes(c: &bezjoin_core::BezierCurve) -> (f64, f64) {
    (0..=200).fold((0.0f64, 0.0f64), |(k, ks), i| {
        let [_, a, b] = frenet(c, i as f64 / 200.0);
        (k.max(norm(&a)), ks.max(norm(&b)))
    })
}

/// The end of `a` (at 1) and the start of `b` (at 0) meet with G^order:
/// the same point, unit tangent and curvature vector (and `dK/ds` for
/// order 3), relative to the largest curvature (and its derivative) of
/// `blend`, the blend on one side; with order 2 the slope of the curvature
/// jumps (G2 only: the blend need not continue it, and the check can tell
/// G2 from G3).
pub fn assert_geometric_join(
    name: &str,
    a: &bezjoin_core::BezierCurve,
    b: &bezjoin_core::BezierCurve,
    blend: &bezjoin_core::BezierCurve,
    order: usize,
) {
    let (k_size, ks_size) = sizes(blend);
    assert!(dist(&a.eval(1.0), &b.eval(0.0)) < 1e-12, "{name}: G0");
    let [t1, k1, s1] = frenet(a, 1.0);
    let [t2, k2, s2] = frenet(b, 0.0);
    assert!(
        dist(&t1, &t2) < 1e-12,
        "{name}: unit tangents {t1:?} {t2:?}"
    );
    assert!(
        dist(&k1, &k2) < 1e-9 * k_size,
        "{name}: curvature vectors {k1:?} {k2:?} (largest {k_size})"
    );
    let ks_jump = dist(&s1, &s2) / ks_size;
    if order >= 3 {
        assert!(ks_jump < 1e-8, "{name}: dK/ds {s1:?} {s2:?}");
    } else {
        assert!(ks_jump > 1e-6, "{name}: dK/ds unexpectedly continuous");
    }
}

/// The SVG picture at `path`: well-formed XML that contains every text of
/// `texts`.
pub fn read_picture(path: &Path, texts: &[&str]) -> String {
    let picture = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    assert_well_formed_xml(&picture);
    for text in texts {
        assert!(picture.contains(text), "the picture lacks {text:?}");
    }
    picture
}
