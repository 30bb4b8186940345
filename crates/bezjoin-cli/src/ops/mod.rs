//! The subcommands: one module per operation, each turning a JSON job into
//! an [`Outcome`].

use std::path::PathBuf;

use clap::{Args, Subcommand};

use bezjoin_core::BezierCurve;

use crate::job::Located;
use crate::svg::{CurveItem, Figure, Role};
use crate::{CliError, Outcome};

/// Arguments shared by the operations.
#[derive(Args, Debug, Clone)]
pub struct JobArgs {
    /// The JSON job; `-` or nothing reads standard input.
    pub job: Option<PathBuf>,
    /// Also draw the result as an SVG picture into FILE.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

/// The operations, as subcommands.
#[derive(Subcommand, Debug, Clone)]
pub enum Operation {}

impl Operation {
    /// The shared arguments.
    pub fn args(&self) -> &JobArgs {
        match *self {}
    }

    /// Run the job.
    pub fn run(&self, job: &Located) -> Result<Outcome, CliError> {
        let _ = job;
        match *self {}
    }
}

/// Run the operation called `name` (as on the command line) on `job`.
pub fn run_named(name: &str, job: &Located) -> Result<Outcome, CliError> {
    let _ = job;
    Err(CliError::Operation(format!("unknown operation {name:?}")))
}

/// Draw the part `[a, b]` of `curve` in `role` with its comb, over the
/// whole given curve drawn as discarded (grey, dashed, with its control
/// polygon). When `[a, b]` is all of `[0, 1]` the curve is drawn once.
pub fn draw_part(figure: &mut Figure, curve: &BezierCurve, a: f64, b: f64, role: Role, name: &str) {
    let degree = curve.degree();
    if a <= 0.0 && b >= 1.0 {
        figure.curve(CurveItem::bezier(
            curve,
            role,
            format!("{name}, degree {degree}"),
        ));
        return;
    }
    let mut given = CurveItem::bezier(
        curve,
        Role::Discarded,
        format!("{name}, degree {degree}, as given"),
    );
    given.polygon = true;
    figure.curve(given);
    if b > a {
        if let Ok(kept) = curve.segment(a, b) {
            figure.curve(
                CurveItem::bezier(
                    &kept,
                    role,
                    format!("{name} on [{a:.4}, {b:.4}] (kept part)"),
                )
                .without_polygon(),
            );
        }
    }
}
