//! Version numbers for the header. cbindgen copies literal constants only,
//! so they are written out here and a test checks them against Cargo's.

/// Major version (the SONAME's number): changes only with an ABI break.
pub const BZJ_VERSION_MAJOR: u32 = 0;
/// Minor version: new functions and structs.
pub const BZJ_VERSION_MINOR: u32 = 1;
/// Patch version: fixes only.
pub const BZJ_VERSION_PATCH: u32 = 0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_constants_match_cargo_version() {
        assert_eq!(
            BZJ_VERSION_MAJOR.to_string(),
            env!("CARGO_PKG_VERSION_MAJOR")
        );
        assert_eq!(
            BZJ_VERSION_MINOR.to_string(),
            env!("CARGO_PKG_VERSION_MINOR")
        );
        assert_eq!(
            BZJ_VERSION_PATCH.to_string(),
            env!("CARGO_PKG_VERSION_PATCH")
        );
        let v = unsafe { std::ffi::CStr::from_ptr(crate::bzj_version()) }
            .to_str()
            .unwrap();
        assert_eq!(v, env!("CARGO_PKG_VERSION"));
    }
}
