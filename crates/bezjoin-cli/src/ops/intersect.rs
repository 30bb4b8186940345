//! `bezjoin intersect` (being written).

use crate::demo::Scenario;
use crate::job::Located;
use crate::{CliError, Outcome};

/// Run a intersect job.
pub fn run(job: &Located) -> Result<Outcome, CliError> {
    let _ = job;
    Err(CliError::Operation(
        "bezjoin intersect is not available in this build".into(),
    ))
}

/// The demo's intersect scenarios.
pub fn demo_scenarios() -> Vec<Scenario> {
    Vec::new()
}
