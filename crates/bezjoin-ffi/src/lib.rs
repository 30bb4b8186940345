//! The C ABI of bezjoin.
//!
//! Conventions (the published contract, `shared/spec/c-api.md`):
//! * every fallible function returns a [`BzjStatus`] and writes results
//!   through out-pointers; `BZJ_OK == 0`;
//! * after a failure [`bzj_last_error`] returns a message for the calling
//!   thread that names the offending argument;
//! * no panic crosses the boundary: every body runs inside one
//!   `catch_unwind` guard and a panic becomes `BZJ_ERR_INTERNAL`;
//! * null pointers give `BZJ_ERR_NULL_POINTER`, NaN/infinity
//!   `BZJ_ERR_NON_FINITE`; on any error handle out-pointers are set to NULL;
//! * `BzjCurve` handles are immutable and may be read from several threads
//!   at once; release each with `bzj_curve_free`.
//!
//! Enumerations that come *from* C (metric, split mode) are read as plain
//! integers and validated, so an out-of-range value is an error, never
//! undefined behaviour.

// The order of the modules is the order of their items in the generated
// header (cbindgen follows it): keep `guard` first.
mod guard;
mod handles;
mod pointers;
mod status;

mod connect;
mod connect_points;
mod curve;
mod fillet;
mod geometric;
mod lagrange;
mod merge;
mod nurbs;
mod version;

pub use connect::*;
pub use connect_points::*;
pub use curve::*;
pub use fillet::*;
pub use geometric::*;
pub use guard::{bzj_last_error, bzj_version};
pub use handles::BzjCurve;
pub use lagrange::*;
pub use merge::*;
pub use nurbs::*;
pub use status::{BzjStatus, bzj_status_name};
pub use version::*;
