//! Reading JSON jobs with messages that name the field.
//!
//! A job is parsed in two steps: `serde_json` turns the text into a
//! [`serde_json::Value`] (its syntax errors, and a key given twice in one
//! object, carry line and column), then the
//! readers here walk that value and report every problem with the JSON path
//! of the offending field (`p[2][1]`, `constraints[0].t`) and the reason.
//! Unknown fields are errors too, so a typo (`p_ordr`) is never silently
//! ignored. Curves (Bezier, NURBS, arcs) are read by [`Located::curve`]
//! (module `curves`).

use std::collections::BTreeSet;
use std::fmt;

use serde_json::{Map, Value};

mod curves;

/// A problem with the job: where (JSON path, or the source for syntax errors)
/// and why.
#[derive(Debug, Clone, PartialEq)]
pub struct JobError {
    /// JSON path of the offending field, e.g. `constraints[0].t`.
    pub path: String,
    /// What is wrong with it.
    pub reason: String,
}

impl JobError {
    /// An error at `path` for `reason`.
    pub fn new(path: impl Into<String>, reason: impl Into<String>) -> Self {
        JobError {
            path: path.into(),
            reason: reason.into(),
        }
    }
}

impl fmt::Display for JobError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.reason)
    }
}

impl std::error::Error for JobError {}

/// Result of reading part of a job.
pub type JobResult<T> = Result<T, JobError>;

/// The bytes of a job as text; bytes that are not UTF-8 are a job error
/// naming the source, the byte offset and the line of the first bad byte.
pub fn decode_text(source_name: &str, bytes: Vec<u8>) -> JobResult<String> {
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let line = 1 + e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count();
        JobError::new(
            source_name,
            format!("is not UTF-8 text: invalid byte at offset {at} (line {line})"),
        )
    })
}

/// Parse the text of a job; syntax errors name the line and column, and so
/// does a key given twice in one object (JSON allows it and `Value` would
/// keep the last silently: `"keep_p": true, "keep_p": false` would drop a
/// constraint the job states).
pub fn parse_text(source_name: &str, text: &str) -> JobResult<Value> {
    serde_json::from_str::<StrictValue>(text)
        .map(|strict| strict.0)
        .map_err(|e| {
            JobError::new(
                source_name,
                format!(
                    "invalid JSON: {e} (line {}, column {})",
                    e.line(),
                    e.column()
                ),
            )
            .without_duplicated_position()
        })
}

/// A JSON value read with every object's keys checked for repeats.
struct StrictValue(Value);

impl<'de> serde::Deserialize<'de> for StrictValue {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(StrictVisitor).map(StrictValue)
    }
}

struct StrictVisitor;

impl<'de> serde::de::Visitor<'de> for StrictVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }

    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }

    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(Value::from(v))
    }

    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(Value::from(v))
    }

    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        // JSON text has no NaN or infinity, so `from` never gives Null here.
        Ok(Value::from(v))
    }

    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }

    fn visit_string<E>(self, v: String) -> Result<Value, E> {
        Ok(Value::String(v))
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(StrictValue(item)) = seq.next_element()? {
            items.push(item);
        }
        Ok(Value::Array(items))
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut object = serde_json::Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if object.contains_key(&key) {
                return Err(serde::de::Error::custom(format!(
                    "the key \"{key}\" is given twice in one object"
                )));
            }
            let StrictValue(value) = map.next_value()?;
            object.insert(key, value);
        }
        Ok(Value::Object(object))
    }
}

impl JobError {
    /// serde_json's message already ends with "at line L column C"; keep one copy.
    fn without_duplicated_position(mut self) -> Self {
        if let Some(cut) = self.reason.find(" at line ") {
            if let Some(paren) = self.reason.rfind(" (line ") {
                self.reason = format!("{}{}", &self.reason[..cut], &self.reason[paren..]);
            }
        }
        self
    }
}

/// Short description of a JSON value for messages.
pub(crate) fn describe(value: &Value) -> String {
    match value {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("the boolean {b}"),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) if s.len() <= 40 => format!("the string {s:?}"),
        Value::String(_) => "a string".into(),
        Value::Array(a) => format!("an array of {} values", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

/// A JSON value with its owned path (what readers hand out).
#[derive(Debug)]
pub struct Located<'a> {
    /// Path of the value inside the job.
    pub path: String,
    /// The value.
    pub value: &'a Value,
}

impl<'a> Located<'a> {
    /// The root of a job.
    pub fn root(value: &'a Value) -> Self {
        Located {
            path: "job".into(),
            value,
        }
    }

    pub(crate) fn error(&self, reason: impl Into<String>) -> JobError {
        JobError::new(self.path.clone(), reason)
    }

    /// A finite number.
    pub fn number(&self) -> JobResult<f64> {
        match self.value {
            Value::Number(n) => n
                .as_f64()
                .filter(|x| x.is_finite())
                .ok_or_else(|| self.error(format!("{n} is not a finite number"))),
            other => Err(self.error(format!("expected a number, found {}", describe(other)))),
        }
    }

    /// A number that must lie in the closed interval `[lo, hi]`.
    pub fn number_in(&self, lo: f64, hi: f64) -> JobResult<f64> {
        let x = self.number()?;
        if x < lo || x > hi {
            return Err(self.error(format!("{x} is outside [{lo}, {hi}]")));
        }
        Ok(x)
    }

    /// A number `> 0`.
    pub fn positive(&self) -> JobResult<f64> {
        let x = self.number()?;
        if x <= 0.0 {
            return Err(self.error(format!("{x} must be > 0")));
        }
        Ok(x)
    }

    /// A non-negative integer.
    pub fn count(&self) -> JobResult<usize> {
        match self.value {
            Value::Number(n) => n
                .as_u64()
                .and_then(|u| usize::try_from(u).ok())
                .ok_or_else(|| self.error(format!("expected a non-negative integer, found {n}"))),
            other => Err(self.error(format!(
                "expected a non-negative integer, found {}",
                describe(other)
            ))),
        }
    }

    /// `true` or `false`.
    pub fn boolean(&self) -> JobResult<bool> {
        self.value.as_bool().ok_or_else(|| {
            self.error(format!(
                "expected true or false, found {}",
                describe(self.value)
            ))
        })
    }

    /// A string.
    pub fn string(&self) -> JobResult<&'a str> {
        self.value
            .as_str()
            .ok_or_else(|| self.error(format!("expected a string, found {}", describe(self.value))))
    }

    /// One of the given strings.
    pub fn choice(&self, allowed: &[&str]) -> JobResult<&'a str> {
        let s = self.string()?;
        if allowed.contains(&s) {
            Ok(s)
        } else {
            Err(self.error(format!(
                "{s:?} is not one of {}",
                allowed
                    .iter()
                    .map(|a| format!("{a:?}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )))
        }
    }

    /// The elements of an array.
    pub fn array(&self) -> JobResult<Vec<Located<'a>>> {
        match self.value {
            Value::Array(items) => Ok(items
                .iter()
                .enumerate()
                .map(|(i, v)| Located {
                    path: format!("{}[{i}]", self.path),
                    value: v,
                })
                .collect()),
            other => Err(self.error(format!("expected an array, found {}", describe(other)))),
        }
    }

    /// A point: a non-empty array of finite numbers.
    pub fn point(&self) -> JobResult<Vec<f64>> {
        let items = self.array()?;
        if items.is_empty() {
            return Err(self.error("a point needs at least one coordinate"));
        }
        items.iter().map(Located::number).collect()
    }

    /// Points of one common dimension (`expected_dim` if given).
    pub fn points(&self, expected_dim: Option<usize>) -> JobResult<Vec<Vec<f64>>> {
        let items = self.array()?;
        let mut dim = expected_dim;
        let mut out = Vec::with_capacity(items.len());
        for item in &items {
            let p = item.point()?;
            match dim {
                None => dim = Some(p.len()),
                Some(d) if d != p.len() => {
                    return Err(item.error(format!(
                        "has {} coordinates, expected {d} like the other points",
                        p.len()
                    )));
                }
                Some(_) => {}
            }
            out.push(p);
        }
        Ok(out)
    }

    /// An array of finite numbers (a knot vector, a domain).
    pub fn numbers(&self) -> JobResult<Vec<f64>> {
        self.array()?.iter().map(Located::number).collect()
    }

    /// An object whose fields are read one by one; call
    /// [`ObjectReader::finish`] to reject unknown fields.
    pub fn object(&self) -> JobResult<ObjectReader<'a>> {
        match self.value {
            Value::Object(map) => Ok(ObjectReader {
                path: self.path.clone(),
                map,
                used: std::cell::RefCell::new(BTreeSet::new()),
            }),
            other => Err(self.error(format!("expected an object, found {}", describe(other)))),
        }
    }
}

/// Reads the fields of one JSON object and remembers which were read.
pub struct ObjectReader<'a> {
    path: String,
    map: &'a Map<String, Value>,
    used: std::cell::RefCell<BTreeSet<String>>,
}

impl<'a> ObjectReader<'a> {
    fn child_path(&self, key: &str) -> String {
        if self.path == "job" {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    /// The field `key`, if present (`null` counts as absent).
    pub fn optional(&self, key: &str) -> Option<Located<'a>> {
        self.used.borrow_mut().insert(key.to_string());
        match self.map.get(key) {
            None | Some(Value::Null) => None,
            Some(v) => Some(Located {
                path: self.child_path(key),
                value: v,
            }),
        }
    }

    /// The field `key`; missing is an error naming it.
    pub fn required(&self, key: &str) -> JobResult<Located<'a>> {
        self.optional(key)
            .ok_or_else(|| JobError::new(self.child_path(key), "is required but missing"))
    }

    /// Error if the object has a field that was never asked for.
    pub fn finish(&self) -> JobResult<()> {
        let used = self.used.borrow();
        if let Some(unknown) = self.map.keys().find(|k| !used.contains(*k)) {
            return Err(JobError::new(
                self.child_path(unknown),
                format!(
                    "unknown field (known here: {})",
                    used.iter().cloned().collect::<Vec<_>>().join(", ")
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod job_reading_tests {
    use super::*;

    fn root(text: &str) -> Value {
        parse_text("test.json", text).unwrap()
    }

    #[test]
    fn syntax_error_names_line_and_column() {
        let e = parse_text("test.json", "{\n  \"p\": [1, 2,]\n}").unwrap_err();
        assert_eq!(e.path, "test.json");
        assert!(e.reason.contains("line 2"), "{e}");
        assert_eq!(e.reason.matches("line").count(), 1, "{e}");
    }

    #[test]
    fn wrong_type_names_the_nested_field() {
        let v = root(r#"{"p": [[0, 0], [1, "x"]]}"#);
        let job = Located::root(&v).object().unwrap();
        let e = job.required("p").unwrap().curve().unwrap_err();
        assert_eq!(e.path, "p[1][1]");
        assert!(e.reason.contains("expected a number"), "{e}");
    }

    #[test]
    fn unknown_and_missing_fields_are_named() {
        let v = root(r#"{"p_ordr": 3}"#);
        let job = Located::root(&v).object().unwrap();
        assert_eq!(job.required("q").unwrap_err().path, "q");
        let _ = job.optional("p_order");
        let e = job.finish().unwrap_err();
        assert_eq!(e.path, "p_ordr");
    }

    #[test]
    fn curve_object_form_is_checked() {
        let v = root(r#"{"c": {"degree": 2, "dim": 2, "points": [[0, 0], [1, 1]]}}"#);
        let job = Located::root(&v).object().unwrap();
        let e = job.required("c").unwrap().curve().unwrap_err();
        assert_eq!(e.path, "c.points");
        let v = root(r#"{"c": [[0, 0], [1, 1, 2]]}"#);
        let job = Located::root(&v).object().unwrap();
        let e = job.required("c").unwrap().curve().unwrap_err();
        assert_eq!(e.path, "c[1]");
    }
}
