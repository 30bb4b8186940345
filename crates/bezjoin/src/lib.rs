//! # bezjoin
//!
//! Smooth joins of Bezier curves of any degree in any dimension, after four
//! papers stated in `docs/mathematics.md`:
//!
//! * [`connect()`] — a connecting Bezier curve with C^k continuity at both ends
//!   and interior point/derivative constraints (Krivosheev, Mavrin, Starkova 2025);
//! * [`fillet()`] — rounding the corner between two crossing curves, built on
//!   [`intersect()`] and [`connect()`];
//! * [`merge()`] — the smallest change of two curves' control points that makes
//!   them one curve (Ganchuk, Krivosheev, Mavrin, Ryzhov 2024; Hu et al. 2001);
//! * `lagrange` ([`lagrange_spline`]) — cubic splines whose control points
//!   lie on the curve (Kovtun).
//!
//! The ground they stand on: [`BezierCurve`] with exact evaluation,
//! derivatives (The NURBS Book A2.3, module `basis`), degree elevation,
//! subdivision, segments and arc length; [`BSplineCurve`] for chains.
//!
//! # The public surface
//!
//! Everything public is re-exported here, at the crate root; the modules
//! themselves are private, so a path is always `bezjoin_core::Name`.
//!
//! **Points are flat row-major `f64` arrays everywhere**: a curve's control
//! points, a value with its derivatives, a constraint's prescribed
//! derivatives are `&[f64]` in and `Vec<f64>` out, `dim` values per point
//! (point `i`, coordinate `c` at `[i * dim + c]`). It is the layout of the C
//! ABI (`include/bezjoin.h`), of NumPy arrays and of OpenCASCADE's
//! `TColgp_Array1OfPnt` read coordinate by coordinate, so nothing is copied
//! or reshaped at a boundary, and it needs no linear-algebra type in the
//! caller's code. [`BezierCurve::from_rows`] is only a convenience for
//! literals (`&[[0.0, 0.0], [1.0, 2.0]]`); it builds the same flat array.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod arclength;
mod basis;
mod bezier;
mod compensated;
mod connect;
mod curve;
mod error;
mod fillet;
mod geometric;
mod intersect;
mod lagrange;
mod linalg;
mod merge;
mod minimize;
mod nurbs;
#[cfg(test)]
mod test_values;

pub use arclength::DEFAULT_ARC_LENGTH_ACCURACY;
pub use basis::KnotSide;
pub use bezier::{BezierCurve, MAX_DEGREE, distance};
pub use connect::{
    AUTO_SCALE_SEARCH_DECADES, BALANCED_SPEED_FLOOR, CONNECT_RESIDUAL_LIMIT, ConnectOptions,
    Connection, MAX_CONNECT_DEGREE, PointConstraint, ShapeScale, UNKINKED_POLYGON_CHORDS,
    check_connect_degree, connect, connect_curve, connect_dense_reference, connect_unchecked,
    fairness_energy,
};
pub use curve::{AsCurveRef, Curve, CurveJet, CurveRef};
pub use error::{BezjoinError, Result};
pub use fillet::{
    ARC_DEVIATION_SAMPLES, MAX_ARC_DEVIATION, MAX_CURVATURE_RATIO, RadiusChainFillet, RadiusCorner,
    RadiusFillet, VERTEX_TOLERANCE, fillet_radius, fillet_radius_chain,
};
pub use fillet::{
    ChainCorner, ChainFillet, ChainFilletOptions, DEFAULT_PARALLEL_THRESHOLD,
    DEFAULT_RELATIVE_DEVIATION_ACCURACY, DEFAULT_RELATIVE_LENGTH_ACCURACY, DEVIATION_SCALE_STEPS,
    DEVIATION_SCALE_TOLERANCE, DeviationFillet, DeviationFilletOptions, Fillet, FilletOptions,
    distance_to_curve, fillet, fillet_at, fillet_chain, fillet_vertex, fillet_within_deviation,
};
pub use geometric::{
    CURVATURE_SAMPLES, ENERGY_PANELS, FairnessReport, GEOMETRIC_CONDITION_LIMIT,
    GeometricConnection, GeometricCurve, GeometricOptions, MAX_GEOMETRIC_ORDER, MAX_LENGTH_RATIO,
    connect_geometric, connect_geometric_curve, curvature_variation, fairness_report, partial_bell,
};
pub use intersect::{
    DEFAULT_MAX_BOX_PAIRS, DEFAULT_MAX_DEPTH, DEFAULT_MAX_HITS,
    DEFAULT_RELATIVE_DISTANCE_TOLERANCE, DEFAULT_TANGENT_TOLERANCE, IntersectOptions, Intersection,
    IntersectionKind, intersect,
};
pub use lagrange::{
    BuildDirection, DEFAULT_LAGRANGE_ACCURACY, DerivedPoints, LagrangeOptions, LagrangeSpline,
    bezier_from_lagrange_points, chord_length_params, lagrange_points_of_bezier, lagrange_spline,
};
pub use merge::{
    BSplineChainMerge, BSplineMerge, CurveChainMerge, CurveMerge, MAX_MERGE_POLES, MIN_SPLIT,
    merge_bspline_chain, merge_bsplines, merge_bsplines_metric_at, merge_curve_chain, merge_curves,
};
pub use merge::{
    Breakpoints, CONSISTENCY_TOLERANCE, CONTRADICTION_MARGIN, ChainKeepPoint, ChainMerge,
    ChainMergeOptions, ChainMergeReport, DEFAULT_MERGE_ACCURACY, DEVIATION_SAMPLES, KeepPoint,
    MU_SEARCH_MAX_STEPS, MU_SEARCH_MIN, MU_SEARCH_SAMPLES, MU_SEARCH_TOLERANCE, Merge, MergeMetric,
    MergeOptions, MergeReport, RANK_TOLERANCE, merge, merge_chain, merge_metric_at,
};
pub use nurbs::{
    AXIS_TOLERANCE, BSplineCurve, MAX_RATIONAL_EVALUATIONS, NurbsCurve, ellipse_arc, join_jumps,
    relative_jump,
};
