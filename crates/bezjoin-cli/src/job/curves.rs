//! Curves in a job, read into [`bezjoin_core::Curve`] with errors that name
//! the JSON path of the bad value.
//!
//! Three forms (README-connect.md, "Curves"):
//! - Bezier: an array of control points `[[x, y], ...]`, or
//!   `{"points": [...]}` with optional `degree` and `dim` that are checked
//!   (what the tool writes);
//! - NURBS: `{"degree": p, "poles": [[x, y], ...], "knots": [flat], "weights":
//!   [...]}` (weights optional: all 1; `dim` and `domain` optional and
//!   checked, so the tool's own output is accepted as it is);
//! - arc: `{"arc": {"centre", "radius" | "radii", "x_axis", "y_axis",
//!   "start_angle", "end_angle"}}`, the exact rational quadratic of
//!   [`bezjoin_core::ellipse_arc`] (angles in radians).

use bezjoin_core::{BezierCurve, BezjoinError, Curve, NurbsCurve, ellipse_arc};
use serde_json::Value;

use super::{JobError, JobResult, Located, describe};

/// The accepted forms, for messages.
const CURVE_FORMS: &str = "an array of control points or {\"points\": [...]} (Bezier), \
                           {\"degree\", \"poles\", \"knots\", \"weights\"} (NURBS) or {\"arc\": {...}}";

/// Which form a curve value is written in.
enum Form {
    Bezier,
    Nurbs,
    Arc,
}

impl<'a> Located<'a> {
    /// The form of a curve value, told by its type and its fields.
    fn curve_form(&self) -> JobResult<Form> {
        match self.value {
            Value::Array(_) => Ok(Form::Bezier),
            Value::Object(map) if map.contains_key("arc") => Ok(Form::Arc),
            Value::Object(map)
                if ["poles", "knots", "weights"]
                    .iter()
                    .any(|k| map.contains_key(*k)) =>
            {
                Ok(Form::Nurbs)
            }
            Value::Object(map) if map.contains_key("points") => Ok(Form::Bezier),
            Value::Object(map) => Err(self.error(format!(
                "expected a curve: {CURVE_FORMS}; found an object with the fields {}",
                if map.is_empty() {
                    "(none)".to_string()
                } else {
                    map.keys()
                        .map(|k| format!("{k:?}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            ))),
            other => Err(self.error(format!(
                "expected a curve: {CURVE_FORMS}; found {}",
                describe(other)
            ))),
        }
    }

    /// A curve of any form: Bezier, NURBS or arc (module documentation).
    pub fn curve(&self) -> JobResult<Curve> {
        match self.curve_form()? {
            Form::Bezier => self.bezier_form().map(Curve::Bezier),
            Form::Nurbs => self.nurbs_form().map(Curve::Nurbs),
            Form::Arc => self.arc_form().map(Curve::Nurbs),
        }
    }

    /// A Bezier curve: an array of control points (degree = count - 1), or
    /// an object `{"points": [...]}` as the tool writes it (its `degree` and
    /// `dim`, if present, are checked).
    fn bezier_form(&self) -> JobResult<BezierCurve> {
        let points_field;
        let (points_at, degree, dim) = match self.value {
            Value::Object(_) => {
                let obj = self.object()?;
                let degree = obj.optional("degree").map(|d| d.count()).transpose()?;
                let dim = obj.optional("dim").map(|d| d.count()).transpose()?;
                points_field = obj.required("points")?;
                obj.finish()?;
                (&points_field, degree, dim)
            }
            _ => (self, None, None),
        };
        let rows = points_at.points(dim)?;
        if rows.is_empty() {
            return Err(points_at.error("a curve needs at least one control point"));
        }
        if let Some(d) = degree {
            if d + 1 != rows.len() {
                return Err(points_at.error(format!(
                    "has {} control points, but degree {d} needs {}",
                    rows.len(),
                    d + 1
                )));
            }
        }
        BezierCurve::from_rows(&rows).map_err(|e| points_at.error(e.to_string()))
    }

    /// `{"degree", "poles", "knots", "weights"?, "dim"?, "domain"?}`.
    fn nurbs_form(&self) -> JobResult<NurbsCurve> {
        let obj = self.object()?;
        let degree_field = obj.required("degree")?;
        let dim = obj.optional("dim").map(|d| d.count()).transpose()?;
        let poles_field = obj.required("poles")?;
        let knots_field = obj.required("knots")?;
        let weights_field = obj.optional("weights");
        let domain_field = obj.optional("domain");
        obj.finish()?;
        let degree = degree_field.count()?;
        if degree == 0 {
            return Err(degree_field.error("0: a NURBS curve needs degree >= 1"));
        }
        let rows = poles_field.points(dim)?;
        if rows.len() < degree + 1 {
            return Err(poles_field.error(format!(
                "has {} poles; degree {degree} needs at least {}",
                rows.len(),
                degree + 1
            )));
        }
        let knots = knots_field.numbers()?;
        let expected = rows.len() + degree + 1;
        if knots.len() != expected {
            return Err(knots_field.error(format!(
                "has {} values; {} poles of degree {degree} need {expected} knots (poles + degree + 1)",
                knots.len(),
                rows.len()
            )));
        }
        if let Some(i) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
            return Err(JobError::new(
                format!("{}[{i}]", knots_field.path),
                format!(
                    "{} is smaller than the knot before it ({}): knots must not decrease",
                    knots[i],
                    knots[i - 1]
                ),
            ));
        }
        let weights = match &weights_field {
            Some(f) => {
                let items = f.array()?;
                if items.len() != rows.len() {
                    return Err(f.error(format!(
                        "has {} values; one weight per pole ({}) is needed",
                        items.len(),
                        rows.len()
                    )));
                }
                Some(
                    items
                        .iter()
                        .map(Located::positive)
                        .collect::<JobResult<Vec<f64>>>()?,
                )
            }
            None => None,
        };
        let dim = rows[0].len();
        let names = [
            ("degree", degree_field.path.clone()),
            ("poles", poles_field.path.clone()),
            ("knots", knots_field.path.clone()),
            (
                "weights",
                weights_field
                    .as_ref()
                    .map_or_else(|| self.path.clone(), |f| f.path.clone()),
            ),
        ];
        let curve = NurbsCurve::new(dim, degree, rows.concat(), weights, knots)
            .map_err(|e| library_error(&e, &names, &self.path))?;
        if let Some(f) = domain_field {
            let given = f.numbers()?;
            let (a, b) = curve.domain();
            if given != [a, b] {
                return Err(f.error(format!(
                    "{given:?} is not the domain [{a}, {b}] of the knots \
                     (knots[degree] and knots[poles]); leave it out or make it agree"
                )));
            }
        }
        Ok(curve)
    }

    /// `{"arc": {"centre", "radius" | "radii", "x_axis"?, "y_axis"?,
    /// "start_angle", "end_angle"}}`.
    fn arc_form(&self) -> JobResult<NurbsCurve> {
        let outer = self.object()?;
        let arc = outer.required("arc")?;
        outer.finish()?;
        let obj = arc.object()?;
        let centre_field = obj.required("centre")?;
        let radius_field = obj.optional("radius");
        let radii_field = obj.optional("radii");
        let x_field = obj.optional("x_axis");
        let y_field = obj.optional("y_axis");
        let start_field = obj.required("start_angle")?;
        let end_field = obj.required("end_angle")?;
        obj.finish()?;
        let centre = centre_field.point()?;
        let dim = centre.len();
        if dim != 2 && dim != 3 {
            return Err(centre_field.error(format!(
                "has {dim} coordinates; an arc is built in 2D or 3D"
            )));
        }
        let (rx, ry, rx_path, ry_path) = match (&radius_field, &radii_field) {
            (Some(r), None) => {
                let v = r.positive()?;
                (v, v, r.path.clone(), r.path.clone())
            }
            (None, Some(r)) => {
                let items = r.array()?;
                if items.len() != 2 {
                    return Err(r.error(format!(
                        "expected [rx, ry] (radius along x_axis, along y_axis), found {} values",
                        items.len()
                    )));
                }
                (
                    items[0].positive()?,
                    items[1].positive()?,
                    items[0].path.clone(),
                    items[1].path.clone(),
                )
            }
            (Some(_), Some(r)) => {
                return Err(r.error("cannot be given together with \"radius\""));
            }
            (None, None) => {
                return Err(JobError::new(
                    obj.child_path("radius"),
                    "is required but missing (or \"radii\": [rx, ry] for an ellipse)",
                ));
            }
        };
        let a0 = start_field.number()?;
        let a1 = end_field.number()?;
        let x_axis = match &x_field {
            Some(f) => f.direction(dim)?,
            None if dim == 2 => vec![1.0, 0.0],
            None => {
                return Err(JobError::new(
                    obj.child_path("x_axis"),
                    "is required for a 3D arc",
                ));
            }
        };
        let y_axis = match &y_field {
            Some(f) => f.direction(dim)?,
            None if dim == 2 => vec![-x_axis[1], x_axis[0]],
            None => {
                return Err(JobError::new(
                    obj.child_path("y_axis"),
                    "is required for a 3D arc",
                ));
            }
        };
        let path_or = |f: &Option<Located>, key: &str| {
            f.as_ref()
                .map_or_else(|| obj.child_path(key), |f| f.path.clone())
        };
        let names = [
            ("dim", centre_field.path.clone()),
            ("centre", centre_field.path.clone()),
            ("x_axis", path_or(&x_field, "x_axis")),
            ("y_axis", path_or(&y_field, "y_axis")),
            ("x_radius", rx_path),
            ("y_radius", ry_path),
            ("a0", start_field.path.clone()),
            ("a1", end_field.path.clone()),
        ];
        ellipse_arc(dim, &centre, &x_axis, &y_axis, rx, ry, a0, a1)
            .map_err(|e| library_error(&e, &names, &arc.path))
    }

    /// A direction of `dim` coordinates, scaled to unit length.
    fn direction(&self, dim: usize) -> JobResult<Vec<f64>> {
        let v = self.point()?;
        if v.len() != dim {
            return Err(self.error(format!(
                "has {} coordinates, expected {dim} like the centre",
                v.len()
            )));
        }
        let length = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(length > 0.0 && length.is_finite()) {
            return Err(self.error("is not a direction (its length is 0)"));
        }
        Ok(v.iter().map(|x| x / length).collect())
    }
}

/// The name of the argument a library error is about, if it names one.
fn argument_name(e: &BezjoinError) -> Option<&str> {
    match e {
        BezjoinError::ParameterOutOfRange { name, .. }
        | BezjoinError::OrderAboveDegree { name, .. }
        | BezjoinError::LengthMismatch { name, .. }
        | BezjoinError::InvalidArgument { name, .. }
        | BezjoinError::NonFinite { name, .. }
        | BezjoinError::NonFiniteScalar { name, .. }
        | BezjoinError::DimensionMismatch { name, .. } => Some(name),
        BezjoinError::Inconsistent { .. }
        | BezjoinError::Singular { .. }
        | BezjoinError::IllConditioned { .. }
        | BezjoinError::NoIntersection { .. } => None,
    }
}

/// A library error as a job error at the JSON path of the argument it
/// names: `names` maps the library's argument names to paths, and an
/// index in the name (`weights[2]`) is kept; other errors are placed at
/// `fallback` (the curve).
fn library_error(e: &BezjoinError, names: &[(&str, String)], fallback: &str) -> JobError {
    let path = argument_name(e)
        .and_then(|name| {
            let (base, index) = name.split_at(name.find('[').unwrap_or(name.len()));
            names
                .iter()
                .find(|(k, _)| *k == base)
                .map(|(_, path)| format!("{path}{index}"))
        })
        .unwrap_or_else(|| fallback.to_string());
    JobError::new(path, e.to_string())
}

#[cfg(test)]
mod curve_reading_tests {
    use super::*;
    use crate::job::parse_text;

    fn read(text: &str) -> JobResult<Curve> {
        let v = parse_text("test.json", text).unwrap();
        let job = Located::root(&v).object().unwrap();
        job.required("c").unwrap().curve()
    }

    #[test]
    fn nurbs_form_is_read_with_weights_and_domain() {
        let c = read(
            r#"{"c": {"degree": 2, "poles": [[0, 0], [1, 1], [2, 0], [3, 1]],
                "knots": [0, 0, 0, 0.5, 1, 1, 1], "weights": [1, 2, 1, 1], "domain": [0, 1]}}"#,
        )
        .unwrap();
        let n = c.as_nurbs().unwrap();
        assert_eq!((n.degree(), n.dim(), n.point_count()), (2, 2, 4));
        assert!(n.is_rational());
        assert_eq!(n.weights().unwrap(), [1.0, 2.0, 1.0, 1.0]);
    }

    #[test]
    fn nurbs_errors_name_the_json_path() {
        let cases = [
            (
                r#"{"c": {"degree": 2, "poles": [[0, 0], [1, 1], [2, 0]], "knots": [0, 0, 0, 1, 1]}}"#,
                "c.knots",
                "need 6 knots",
            ),
            (
                r#"{"c": {"degree": 1, "poles": [[0, 0], [1, 1], [2, 0]], "knots": [0, 0, 1, 0.5, 1]}}"#,
                "c.knots[3]",
                "must not decrease",
            ),
            (
                r#"{"c": {"degree": 1, "poles": [[0, 0], [1, 1]], "knots": [0, 0, 1, 1], "weights": [1, 0]}}"#,
                "c.weights[1]",
                "must be > 0",
            ),
            (
                r#"{"c": {"degree": 1, "poles": [[0, 0], [1, "x"]], "knots": [0, 0, 1, 1]}}"#,
                "c.poles[1][1]",
                "expected a number",
            ),
            (
                r#"{"c": {"degree": 1, "poles": [[0, 0], [1, 1]], "knots": [0, 0, 1, 1], "weight": [1, 1]}}"#,
                "c.weight",
                "unknown field",
            ),
            (
                r#"{"c": {"degree": 2, "poles": [[0, 0], [1, 1], [2, 0], [3, 3]], "knots": [0, 0, 0, 0.5, 0.5, 0.5, 1]}}"#,
                "c.knots",
                "multiplicity",
            ),
            (
                r#"{"c": {"degree": 1, "poles": [[0, 0], [1, 1]], "knots": [0, 0, 1, 1], "domain": [0, 2]}}"#,
                "c.domain",
                "is not the domain [0, 1]",
            ),
            (
                r#"{"c": {"poles": [[0, 0], [1, 1]], "knots": [0, 0, 1, 1]}}"#,
                "c.degree",
                "required",
            ),
            (r#"{"c": 3}"#, "c", "expected a curve"),
            (r#"{"c": {"pionts": [[0, 0]]}}"#, "c", "\"pionts\""),
        ];
        for (text, path, reason) in cases {
            let e = read(text).unwrap_err();
            assert_eq!(e.path, path, "{text}: {e}");
            assert!(e.reason.contains(reason), "{text}: {e}");
        }
    }

    #[test]
    fn arc_form_builds_the_exact_circle_and_names_bad_fields() {
        let c = read(
            r#"{"c": {"arc": {"centre": [1, 2], "radius": 3, "start_angle": 0, "end_angle": 3}}}"#,
        )
        .unwrap();
        let n = c.as_nurbs().unwrap();
        assert_eq!(n.domain(), (0.0, 3.0));
        for i in 0..=20 {
            let p = n.eval(3.0 * i as f64 / 20.0);
            let r = (p[0] - 1.0).hypot(p[1] - 2.0);
            assert!((r - 3.0).abs() < 1e-13, "{r}");
        }
        let cases = [
            (
                r#"{"c": {"arc": {"centre": [0, 0], "radius": 1, "start_angle": 1, "end_angle": 0.5}}}"#,
                "c.arc.end_angle",
            ),
            (
                r#"{"c": {"arc": {"centre": [0, 0], "radii": [1, -2], "start_angle": 0, "end_angle": 1}}}"#,
                "c.arc.radii[1]",
            ),
            (
                r#"{"c": {"arc": {"centre": [0, 0, 0], "radius": 1, "x_axis": [1, 0, 0], "start_angle": 0, "end_angle": 1}}}"#,
                "c.arc.y_axis",
            ),
            (
                r#"{"c": {"arc": {"centre": [0, 0, 0], "radius": 1, "x_axis": [1, 0, 0], "y_axis": [1, 1, 0], "start_angle": 0, "end_angle": 1}}}"#,
                "c.arc.y_axis",
            ),
            (
                r#"{"c": {"arc": {"centre": [0, 0], "start_angle": 0, "end_angle": 1}}}"#,
                "c.arc.radius",
            ),
            (
                r#"{"c": {"arc": {"centre": [0, 0], "radius": 1, "x_axis": [0, 0], "start_angle": 0, "end_angle": 1}}}"#,
                "c.arc.x_axis",
            ),
        ];
        for (text, path) in cases {
            let e = read(text).unwrap_err();
            assert_eq!(e.path, path, "{text}: {e}");
        }
    }
}
