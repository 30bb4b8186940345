//! Exit codes of the binary: a job that is not UTF-8 text is a bad job
//! (exit 2, message naming the source and where), a missing file is an
//! input/output error (exit 1), and a panic is reported as one line with
//! exit code 3 instead of a panic trace.

use std::io::Write as _;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let path = std::env::temp_dir().join(format!("bezjoin-exit-{}-{name}", std::process::id()));
    std::fs::write(&path, bytes).unwrap();
    path
}

fn bezjoin(args: &[&str], stdin: &[u8], env: Option<(&str, &str)>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_bezjoin"));
    cmd.args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    if let Some((k, v)) = env {
        cmd.env(k, v);
    }
    let mut child = cmd.spawn().expect("the bezjoin binary runs");
    child.stdin.take().unwrap().write_all(stdin).ok();
    child.wait_with_output().unwrap()
}

/// A valid connect job with one byte that is not UTF-8 inside a string on line 2.
fn not_utf8_job() -> Vec<u8> {
    let mut bytes = b"{\"p\": [[0, 0], [1, 1], [2, 0]],\n \"colour\": \"".to_vec();
    bytes.push(0xff);
    bytes.extend_from_slice(b"\", \"q\": [[2, 0], [3, 1], [4, 0]]}");
    bytes
}

#[test]
fn a_job_file_that_is_not_utf8_exits_2_naming_the_file() {
    let bytes = not_utf8_job();
    let at = bytes.iter().position(|&b| b == 0xff).unwrap();
    let path = temp_file("latin1.json", &bytes);
    let out = bezjoin(&["connect", path.to_str().unwrap()], b"", None);
    std::fs::remove_file(&path).ok();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(path.to_str().unwrap()), "{stderr}");
    assert!(stderr.contains("not UTF-8"), "{stderr}");
    assert!(
        stderr.contains(&format!("offset {at} (line 2)")),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
}

#[test]
fn standard_input_that_is_not_utf8_exits_2() {
    let out = bezjoin(&["merge", "-"], &not_utf8_job(), None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("<stdin>: is not UTF-8"), "{stderr}");
}

#[test]
fn the_same_job_as_utf8_gets_past_decoding() {
    // Control: with the bad byte replaced, the job is read and rejected for
    // its unknown field instead, so exit 2 above was the encoding.
    let bytes: Vec<u8> = not_utf8_job()
        .into_iter()
        .map(|b| if b == 0xff { b'x' } else { b })
        .collect();
    let out = bezjoin(&["connect", "-"], &bytes, None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("colour: unknown field"), "{stderr}");
    assert!(!stderr.contains("UTF-8"), "{stderr}");
}

#[test]
fn a_missing_job_file_is_an_io_error_exit_1() {
    let path =
        std::env::temp_dir().join(format!("bezjoin-exit-{}-missing.json", std::process::id()));
    let out = bezjoin(&["spline", path.to_str().unwrap()], b"", None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("cannot read"), "{stderr}");
}

#[test]
fn a_panic_is_one_line_and_exit_3() {
    let out = bezjoin(
        &["connect", "-"],
        b"{}",
        Some(("BEZJOIN_CLI_TEST_PANIC", "1")),
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    assert!(
        stderr.starts_with("bezjoin: internal error: deliberate panic"),
        "{stderr}"
    );
    assert!(stderr.contains("src/main.rs:"), "names the place: {stderr}");
    assert!(!stderr.contains("panicked at"), "{stderr}");
    assert!(!stderr.contains("RUST_BACKTRACE"), "{stderr}");
    assert!(out.stdout.is_empty());
}

/// A key given twice in one object is a bad job naming the key and where
/// (JSON allows it, and reading the last silently dropped a constraint the
/// job states: `"keep_p": true, "keep_p": false` merged with nothing kept);
/// also inside a nested object. Control: the job with the key once is
/// answered.
#[test]
fn a_key_given_twice_exits_2_naming_it() {
    let job = |keep: &str| {
        format!(
            "{{\"p\": [[0, 0], [1, 2], [2, 2], [3, 1]],\n \"q\": [[3.1, 1], [4, 0], [5, 1], [6, 3]],\n {keep}}}"
        )
    };
    let out = bezjoin(
        &["merge", "-"],
        job("\"keep_p\": true, \"keep_p\": false").as_bytes(),
        None,
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("the key \"keep_p\" is given twice in one object (line 3"),
        "{stderr}"
    );
    let nested = job("\"p_points\": [{\"param\": 0.5, \"param\": 0.25, \"max_order\": 0}]");
    let out = bezjoin(&["merge", "-"], nested.as_bytes(), None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("the key \"param\" is given twice"),
        "{stderr}"
    );
    let out = bezjoin(&["merge", "-"], job("\"keep_p\": true").as_bytes(), None);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
