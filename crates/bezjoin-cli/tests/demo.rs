//! `bezjoin demo` run as a process: it exits 0 and writes index.html and, for
//! every scenario the index lists, its picture, job and result; every
//! picture is well-formed XML, and every job re-run through its subcommand
//! gives the result the demo wrote.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// Minimal XML well-formedness check: one root element, every start tag
/// closed by a matching end tag in order, quoted attribute values, no raw
/// `<` or stray `&` in text; comments, processing instructions, DOCTYPE and
/// CDATA sections are skipped.
fn assert_well_formed_xml(text: &str) {
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
