//! Give the shared library a versioned SONAME on ELF targets, so that hosts
//! record `libbezjoin.so.<MAJOR>` and keep working across compatible
//! (minor/patch) updates; `scripts/install.sh` installs the matching
//! `libbezjoin.so -> libbezjoin.so.MAJOR -> libbezjoin.so.MAJOR.MINOR.PATCH`
//! symlinks. Only the cdylib is affected (the rlib and staticlib carry no SONAME).

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
    }
}
