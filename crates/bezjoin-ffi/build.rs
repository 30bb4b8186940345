//! Give the shared library a versioned SONAME on ELF targets, so that hosts
//! record `libbezjoin.so.<MAJOR>` and keep working across compatible
//! (minor/patch) updates; `scripts/install.sh` installs the matching
//! `libbezjoin.so -> libbezjoin.so.MAJOR -> libbezjoin.so.MAJOR.MINOR.PATCH`
//! symlinks. Only the cdylib is affected (the rlib and staticlib carry no SONAME).
//!
//! A host linked against the build tree (`-L target/release -lbezjoin`, as
//! the C contract's "built into `target/release/`" invites) records that
//! SONAME too, so the build tree gets the link `libbezjoin.so.MAJOR ->
//! libbezjoin.so` beside the library; without it such a program does not
//! start ("libbezjoin.so.0: cannot open shared object file").

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let target_os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let elf = matches!(
        target_os.as_str(),
        "linux"
            | "android"
            | "freebsd"
            | "netbsd"
            | "openbsd"
            | "dragonfly"
            | "illumos"
            | "solaris"
    );
    if elf {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").expect("cargo sets the version");
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libbezjoin.so.{major}");
        link_soname_in_the_build_tree(&major);
    }
}

/// `libbezjoin.so.MAJOR -> libbezjoin.so` in the profile directory that
/// receives the cdylib (`OUT_DIR` is `<profile>/build/<package>-<hash>/out`;
/// the link may dangle until the library is linked, moments later). A
/// warning, not a failure, when the directory is not where it is expected
/// or the link cannot be made.
#[cfg(unix)]
fn link_soname_in_the_build_tree(major: &str) {
    use std::path::Path;
    let Some(out_dir) = std::env::var_os("OUT_DIR") else {
        return;
    };
    let Some(profile) = Path::new(&out_dir).ancestors().nth(3) else {
        return;
    };
    if !profile.join("deps").is_dir() {
        println!(
            "cargo:warning=no libbezjoin.so.{major} link: {} is not a profile directory",
            profile.display()
        );
        return;
    }
    let link = profile.join(format!("libbezjoin.so.{major}"));
    let target = Path::new("libbezjoin.so");
    if std::fs::read_link(&link).is_ok_and(|existing| existing == target) {
        return;
    }
    let _ = std::fs::remove_file(&link);
    if let Err(error) = std::os::unix::fs::symlink(target, &link) {
        println!("cargo:warning=could not make {}: {error}", link.display());
    }
}

#[cfg(not(unix))]
fn link_soname_in_the_build_tree(_major: &str) {}
