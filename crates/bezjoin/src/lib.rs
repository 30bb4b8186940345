//! # bezjoin
//!
//! Smooth joins of Bezier curves of any degree in any dimension, after four
//! papers restated in `shared/spec/mathematics.md`:
//!
//! * [`connect`] — a connecting Bezier curve with C^k continuity at both ends
//!   and interior point/derivative constraints (Krivosheev, Mavrin, Starkova 2025);
//! * [`fillet`] — rounding the corner between two crossing curves, built on
//!   [`intersect`] and [`connect`];
//! * [`merge`] — the smallest change of two curves' control points that makes
//!   them one curve (Ganchuk, Krivosheev, Mavrin, Ryzhov 2024; Hu et al. 2001);
//! * [`lagrange`] — cubic splines whose control points lie on the curve (Kovtun).
//!
//! The ground they stand on: [`BezierCurve`] with exact evaluation,
//! derivatives (The NURBS Book A2.3 in [`basis`]), degree elevation,
//! subdivision, segments and arc length; [`BSplineCurve`] for chains.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod arclength;
pub mod basis;
pub mod bezier;
pub mod bspline;
pub mod connect;
pub mod error;
pub mod fillet;
pub mod intersect;
pub mod lagrange;
pub mod linalg;
pub mod merge;
mod minimize;

pub use arclength::DEFAULT_ARC_LENGTH_ACCURACY;
pub use basis::KnotSide;
pub use bezier::{BezierCurve, MAX_DEGREE};
pub use bspline::BSplineCurve;
pub use connect::{
    CONNECT_RESIDUAL_LIMIT, ConnectOptions, Connection, MAX_CONNECT_DEGREE, PointConstraint,
    connect, connect_auto_scale, connect_dense_reference, connect_unchecked, fairness_energy,
};
pub use error::{BezjoinError, Result};
pub use fillet::{
    ChainCorner, ChainFillet, ChainFilletOptions, DeviationFillet, DeviationFilletOptions, Fillet,
    FilletOptions, fillet, fillet_at, fillet_chain, fillet_within_deviation,
};
pub use intersect::{IntersectOptions, Intersection, IntersectionKind, intersect};
pub use lagrange::{
    BuildDirection, DEFAULT_LAGRANGE_ACCURACY, DerivedPoints, LagrangeOptions, LagrangeSpline,
    bezier_from_lagrange_points, lagrange_points_of_bezier, lagrange_spline,
};
pub use merge::{
    ChainBreakpoints, ChainKeepPoint, ChainMerge, ChainMergeOptions, ChainMergeReport,
    DEFAULT_MERGE_ACCURACY, KeepPoint, Merge, MergeMetric, MergeOptions, MergeReport,
    SplitParameter, merge, merge_chain, merge_metric_at,
};
