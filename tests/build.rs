//! Hands the target triple to the tests, which compile the C programs in
//! `tests/c/` with the `cc` crate's compiler detection at run time (the
//! static library they link only exists once the dependencies are built).
fn main() {
    println!(
        "cargo:rustc-env=BZJ_TEST_TARGET={}",
        std::env::var("TARGET").unwrap()
    );
    println!("cargo:rerun-if-changed=build.rs");
}
