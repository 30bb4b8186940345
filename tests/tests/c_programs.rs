//! Every C program in `tests/c/` is compiled with the `cc` crate's compiler
//! against `include/bezjoin.h` (as C11 with `-Wall -Wextra -Werror`, and the
//! same source as C++17 to prove the header is C++-clean), linked with the
//! static library `libbezjoin.a` built for this test run, and run: it must
//! exit 0. Each program checks its own results and prints what failed.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// `libbezjoin.a` next to the test executable's dependencies.
fn static_library() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    for dir in [deps.to_path_buf(), deps.parent().unwrap().to_path_buf()] {
        let lib = dir.join("libbezjoin.a");
        if lib.exists() {
            return lib;
        }
    }
    panic!("libbezjoin.a not found next to {}", deps.display());
}

fn compiler(cpp: bool) -> cc::Tool {
    let target = env!("BZJ_TEST_TARGET");
    cc::Build::new()
        .cargo_metadata(false)
        .cargo_warnings(false)
        .target(target)
        .host(target)
        .opt_level(1)
        .cpp(cpp)
        .get_compiler()
}

fn build_and_run(source: &Path, cpp: bool) -> Result<(), String> {
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c-programs");
    std::fs::create_dir_all(&out_dir).unwrap();
    let stem = source.file_stem().unwrap().to_string_lossy();
    let exe = out_dir.join(format!("{stem}-{}", if cpp { "cpp" } else { "c" }));
    let tool = compiler(cpp);
    let mut cmd = tool.to_command();
    if cpp {
        cmd.args(["-x", "c++", "-std=c++17"]);
    } else {
        cmd.arg("-std=c11");
    }
    cmd.args(["-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(repo_root().join("include"))
        .arg(source)
        .arg("-o")
        .arg(&exe)
        .args(["-x", "none"])
        .arg(static_library())
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lutil", "-lgcc_s"]);
    let output = cmd
        .output()
        .map_err(|e| format!("cannot run the compiler: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "{} failed to compile as {}:\n{}",
            source.display(),
            if cpp { "C++" } else { "C" },
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let run = Command::new(&exe)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    if !run.status.success() {
        return Err(format!(
            "{} exited with {}:\n{}{}",
            exe.display(),
            run.status,
            String::from_utf8_lossy(&run.stdout),
            String::from_utf8_lossy(&run.stderr)
        ));
    }
    Ok(())
}

fn programs() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(repo_root().join("tests/c"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "c"))
        .collect();
    v.sort();
    v
}

#[test]
fn c_programs_pass_as_c() {
    let programs = programs();
    assert!(!programs.is_empty(), "no C programs found in tests/c");
    let failures: Vec<String> = programs
        .iter()
        .filter_map(|p| build_and_run(p, false).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn c_programs_pass_as_cpp() {
    let failures: Vec<String> = programs()
        .iter()
        .filter_map(|p| build_and_run(p, true).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
