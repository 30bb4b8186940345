//! The committed header `include/bezjoin.h` must equal what cbindgen
//! generates from the current sources. Regenerate with
//! `BEZJOIN_UPDATE_HEADER=1 cargo test -p bezjoin-ffi --test header`.

use std::path::PathBuf;

#[test]
fn committed_header_is_current() {
    let crate_dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let header_path = crate_dir.join("../../include/bezjoin.h");
    let config =
        cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_crate(&crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen failed to parse the FFI crate")
        .write(&mut generated);
    let generated = String::from_utf8(generated).unwrap();
    if std::env::var_os("BEZJOIN_UPDATE_HEADER").is_some() {
        std::fs::write(&header_path, &generated).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&header_path).unwrap_or_default();
    assert!(
        committed == generated,
        "include/bezjoin.h is stale: run `BEZJOIN_UPDATE_HEADER=1 cargo test -p bezjoin-ffi --test header` and commit it"
    );
}
