//! The subcommands: one module per operation, each turning a JSON job into
//! an [`Outcome`], and the demo's [`Scenario`]s of every operation.

use std::path::PathBuf;

use clap::{Args, Subcommand};

use bezjoin_core::CurveRef;
use serde_json::Value;

use crate::job::Located;
use crate::svg::{CurveItem, Figure, Role};
use crate::{CliError, Outcome};

pub mod connect;
pub mod connect_geometric;
pub mod fillet;
pub mod fillet_chain;
pub mod fillet_radius;
pub mod intersect;
pub mod merge;
pub mod spline;

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
pub enum Operation {
    /// Connect P(u0) to Q(v0) with a C^k Bezier curve (mathematics.md section 1), or G^k with
    /// `"continuity": "geometric"`.
    Connect(JobArgs),
    /// Round the corner between two crossing curves, or at a vertex (section 2); with `"radius"`
    /// sized like the arc of that radius and rounded by a fair G^k blend.
    Fillet(JobArgs),
    /// Round every corner of a chain (a wire) of curves, open or closed; with `"radius"` each
    /// sized like the arc of that radius and rounded by a fair G^k blend.
    FilletChain(JobArgs),
    /// Merge two curves (Bezier, or polynomial B-splines) into one by the smallest change
    /// (sections 3 and 6).
    Merge(JobArgs),
    /// Spline with control points on the curve (section 4).
    Spline(JobArgs),
    /// All meeting points of two curves.
    Intersect(JobArgs),
}

impl Operation {
    /// The shared arguments.
    pub fn args(&self) -> &JobArgs {
        match self {
            Operation::Connect(a)
            | Operation::Fillet(a)
            | Operation::FilletChain(a)
            | Operation::Merge(a)
            | Operation::Spline(a)
            | Operation::Intersect(a) => a,
        }
    }

    /// Which operation this subcommand runs.
    pub fn kind(&self) -> OperationKind {
        match self {
            Operation::Connect(_) => OperationKind::Connect,
            Operation::Fillet(_) => OperationKind::Fillet,
            Operation::FilletChain(_) => OperationKind::FilletChain,
            Operation::Merge(_) => OperationKind::Merge,
            Operation::Spline(_) => OperationKind::Spline,
            Operation::Intersect(_) => OperationKind::Intersect,
        }
    }

    /// Run the job.
    pub fn run(&self, job: &Located) -> Result<Outcome, CliError> {
        self.kind().run(job)
    }
}

/// The operations without their command-line arguments: what a demo
/// [`Scenario`] runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OperationKind {
    /// `bezjoin connect`.
    Connect,
    /// `bezjoin fillet`.
    Fillet,
    /// `bezjoin fillet-chain`.
    FilletChain,
    /// `bezjoin merge`.
    Merge,
    /// `bezjoin spline`.
    Spline,
    /// `bezjoin intersect`.
    Intersect,
}

impl OperationKind {
    /// The subcommand's name.
    pub fn name(self) -> &'static str {
        match self {
            OperationKind::Connect => "connect",
            OperationKind::Fillet => "fillet",
            OperationKind::FilletChain => "fillet-chain",
            OperationKind::Merge => "merge",
            OperationKind::Spline => "spline",
            OperationKind::Intersect => "intersect",
        }
    }

    /// Run `job` through this operation.
    pub fn run(self, job: &Located) -> Result<Outcome, CliError> {
        match self {
            OperationKind::Connect => connect::run(job),
            OperationKind::Fillet => fillet::run(job),
            OperationKind::FilletChain => fillet_chain::run(job),
            OperationKind::Merge => merge::run(job),
            OperationKind::Spline => spline::run(job),
            OperationKind::Intersect => intersect::run(job),
        }
    }
}

/// One scenario of the demo: an ordinary job of one operation, with the
/// names and texts its outputs are shown under.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// File stem of its outputs.
    pub name: &'static str,
    /// The operation (subcommand) that runs it.
    pub operation: OperationKind,
    /// Title of its picture.
    pub title: &'static str,
    /// What it shows and where it comes from.
    pub description: &'static str,
    /// The job.
    pub job: Value,
}

impl Scenario {
    /// Run the scenario's job through its operation.
    pub fn run(&self) -> Result<Outcome, CliError> {
        self.operation.run(&Located::root(&self.job))
    }
}

/// The demo's scenarios of every operation, in the order the index shows them.
pub fn scenarios() -> Vec<Scenario> {
    let mut all = connect::demo_scenarios();
    all.extend(fillet::demo_scenarios());
    all.extend(fillet_radius::demo_scenarios());
    all.extend(fillet_chain::demo_scenarios());
    all.extend(merge::demo_scenarios());
    all.extend(spline::demo_scenarios());
    all.extend(intersect::demo_scenarios());
    all
}

/// How a curve is named in legends: `degree 3` for a Bezier curve,
/// `NURBS of degree 2, rational, 3 spans` for a NURBS curve.
pub fn describe_curve<'a>(curve: impl Into<CurveRef<'a>>) -> String {
    match curve.into() {
        CurveRef::Bezier(c) => format!("degree {}", c.degree()),
        CurveRef::Nurbs(c) => {
            let spans = c.span_count();
            format!(
                "NURBS of degree {}, {}, {spans} span{}",
                c.degree(),
                if c.is_rational() {
                    "rational"
                } else {
                    "polynomial"
                },
                if spans == 1 { "" } else { "s" }
            )
        }
    }
}

/// Draw the part `[a, b]` of `curve` (in its own parameters: `[0, 1]` for
/// a Bezier curve, the domain for a NURBS curve) in `role` with its comb,
/// over the whole given curve drawn as discarded (grey, dashed, with its
/// control polygon). When `[a, b]` is the whole domain the curve is drawn
/// once.
pub fn draw_part<'a>(
    figure: &mut Figure,
    curve: impl Into<CurveRef<'a>>,
    a: f64,
    b: f64,
    role: Role,
    name: &str,
) {
    let curve = curve.into();
    let (first, last) = curve.domain();
    let kind = describe_curve(curve);
    if a <= first && b >= last {
        figure.curve(CurveItem::new(curve, role, format!("{name}, {kind}")));
        return;
    }
    let mut given = CurveItem::new(curve, Role::Discarded, format!("{name}, {kind}, as given"));
    given.polygon = true;
    figure.curve(given);
    if b > a {
        if let Ok(kept) = curve.segment(a.max(first), b.min(last)) {
            figure.curve(
                CurveItem::new(
                    &kept,
                    role,
                    format!("{name} on [{a:.4}, {b:.4}] (kept part)"),
                )
                .without_polygon(),
            );
        }
    }
}
