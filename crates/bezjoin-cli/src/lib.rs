//! The `bezjoin` command-line tool as a library: JSON jobs in, JSON results
//! and SVG pictures out, and the demo.
//!
//! Every subcommand reads one JSON job, calls `bezjoin_core` directly, and
//! returns an [`Outcome`]: the JSON result, a [`svg::Figure`] and a one-line
//! [`Summary`] (what the demo's table prints). The job formats are
//! documented per subcommand in `crates/bezjoin-cli/README-connect.md`
//! (which also describes the curve forms: Bezier, NURBS, arc),
//! `README-fillet.md` (fillet, fillet-chain and intersect), `README-merge.md`
//! and `README-spline.md`, with example jobs in `examples/`.
//!
//! Exit codes of the `bezjoin` binary: 0 success; 1 a file or standard
//! input/output could not be read or written; 2 the job is invalid (not
//! UTF-8, not JSON, or a bad field or value, the message naming the field);
//! 3 an internal error (a panic, which is a bug), reported as one line on
//! standard error instead of a panic trace.
#![forbid(unsafe_code)]

pub mod arc;
pub mod check;
pub mod curvature;
pub mod demo;
pub mod job;
pub mod ops;
pub mod series;
pub mod svg;

use std::fmt;

/// Why the tool stopped.
#[derive(Debug)]
pub enum CliError {
    /// The job is not valid JSON, or a field has a bad type or value
    /// (exit code 2).
    Job(job::JobError),
    /// The library rejected the values (exit code 2); the message is
    /// bezjoin's own and names the argument.
    Operation(String),
    /// Reading or writing a file failed (exit code 1).
    Io(String),
}

impl CliError {
    /// Process exit code for this error.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Job(_) | CliError::Operation(_) => 2,
            CliError::Io(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CliError::Job(e) => write!(f, "invalid job: {e}"),
            CliError::Operation(m) => write!(f, "invalid job: {m}"),
            CliError::Io(m) => write!(f, "{m}"),
        }
    }
}

impl From<job::JobError> for CliError {
    fn from(e: job::JobError) -> Self {
        CliError::Job(e)
    }
}

impl From<bezjoin_core::BezjoinError> for CliError {
    fn from(e: bezjoin_core::BezjoinError) -> Self {
        CliError::Operation(e.to_string())
    }
}

/// One line of the demo's summary table.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Degree of the computed curve (the highest, for chains).
    pub degree: usize,
    /// Worst relative derivative jump over the promised orders, measured
    /// by the tool ([`check::JoinCheck`]); `None` when there is no join.
    pub worst_continuity_jump: Option<f64>,
    /// Largest distance from what the operation must keep; what it is
    /// measured against is said in `deviation_meaning`.
    pub max_deviation: Option<f64>,
    /// What `max_deviation` measures.
    pub deviation_meaning: &'static str,
}

/// What a subcommand produces.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The JSON result.
    pub json: serde_json::Value,
    /// The picture.
    pub figure: svg::Figure,
    /// The summary line.
    pub summary: Summary,
}
