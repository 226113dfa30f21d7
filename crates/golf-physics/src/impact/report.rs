//! What one run of a model gives ([`ModelRun`]): the launch, the model's own numbers beside it (its [`Report`],
//! published with every launch, e.g. the ground model's `ground` object), and, when asked, the course of a model
//! resolved in time ([`Course`]: the contact time and peak force, and a [`Trace`] of named columns). The wire,
//! `predict` and the plots read these by name, never by the model's type, so a new model that reports the same
//! names is published, printed and drawn with no change outside its own file.

use std::fmt;

use serde::de::{MapAccess, Visitor};
use serde::ser::{SerializeMap, SerializeSeq};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::Launch;
use crate::math::Real;

/// What a run asks of a model.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RunOptions {
    /// A model resolved in time keeps a trace point every this many steps (0: no course at all).
    pub trace_every: usize,
}

impl RunOptions {
    /// A run with its course, a trace point every `every` steps.
    pub fn traced(every: usize) -> Self {
        RunOptions { trace_every: every }
    }
}

/// One run of a model.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelRun {
    /// The ball and the club after impact.
    pub launch: Launch,
    /// Published with every launch of this model (`None` for the impulse models).
    pub report: Option<Report>,
    /// The contact's course, when asked (`RunOptions::trace_every > 0`) of a model resolved in time.
    pub course: Option<Course>,
}

impl ModelRun {
    /// A run that gives a launch and nothing else.
    pub fn launch_only(launch: Launch) -> Self {
        ModelRun { launch, report: None, course: None }
    }
}

/// A model's own numbers, published with each of its launches under `key` (the ground model's `ground`).
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The key it is published under.
    pub key: &'static str,
    /// Its numbers, in order.
    pub fields: Fields,
}

/// The course of a run resolved in time: its summary numbers (printed beside the launch) and its trace.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Course {
    /// Its summary numbers.
    pub summary: Fields,
    /// Its trace points.
    pub trace: Trace,
}

/// One named value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A number.
    Number(Real),
    /// A count.
    Count(u64),
    /// A fixed text (a name).
    Text(&'static str),
    /// Written as `null`.
    Null,
    /// Not written at all.
    Absent,
}

impl From<Real> for Value {
    fn from(v: Real) -> Self {
        Value::Number(v)
    }
}

impl From<Option<Real>> for Value {
    fn from(v: Option<Real>) -> Self {
        v.map_or(Value::Null, Value::Number)
    }
}

impl Serialize for Value {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match *self {
            Value::Number(v) => s.serialize_f64(v),
            Value::Count(v) => s.serialize_u64(v),
            Value::Text(v) => s.serialize_str(v),
            Value::Null | Value::Absent => s.serialize_none(),
        }
    }
}

/// Named values in the order they are written (units in the names, as everywhere on the wire).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fields(pub Vec<(&'static str, Value)>);

impl Fields {
    /// The value named `name`.
    pub fn get(&self, name: &str) -> Option<Value> {
        self.0.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
    }

    /// The number named `name` (a count reads as a number).
    pub fn number(&self, name: &str) -> Option<Real> {
        match self.get(name)? {
            Value::Number(v) => Some(v),
            Value::Count(v) => Some(v as Real),
            _ => None,
        }
    }

    /// The text named `name`.
    pub fn text(&self, name: &str) -> Option<&'static str> {
        match self.get(name)? {
            Value::Text(v) => Some(v),
            _ => None,
        }
    }

    /// Whether it holds no field.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl Serialize for Fields {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let present = self.0.iter().filter(|(_, v)| *v != Value::Absent);
        let mut map = s.serialize_map(Some(present.clone().count()))?;
        for (name, value) in present {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// Trace points, one row of named values each (the same names in every row).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trace(pub Vec<Fields>);

impl Trace {
    /// The points `(x, y)` of two columns, for a chart (rows without either are left out).
    pub fn series(&self, x: &str, y: &str) -> Vec<(Real, Real)> {
        self.0.iter().filter_map(|row| Some((row.number(x)?, row.number(y)?))).collect()
    }

    /// Whether it has no point.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl Serialize for Trace {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for row in &self.0 {
            seq.serialize_element(row)?;
        }
        seq.end()
    }
}

/// A report as it travels: the numbers a model wrote (in order), or, read back from the wire, its JSON as parsed.
#[derive(Debug, Clone, PartialEq)]
pub enum WireReport {
    /// The report a model wrote.
    Written(Report),
    /// The report read back from the wire, as its JSON.
    Read {
        /// The key it was published under.
        key: String,
        /// Its JSON object.
        value: serde_json::Value,
    },
}

impl WireReport {
    /// The key it is published under.
    pub fn key(&self) -> &str {
        match self {
            WireReport::Written(r) => r.key,
            WireReport::Read { key, .. } => key,
        }
    }

    /// The number named `name`, however the report arrived.
    pub fn number(&self, name: &str) -> Option<Real> {
        match self {
            WireReport::Written(r) => r.fields.number(name),
            WireReport::Read { value, .. } => value.get(name)?.as_f64(),
        }
    }

    /// The text named `name`, however the report arrived.
    pub fn text(&self, name: &str) -> Option<&str> {
        match self {
            WireReport::Written(r) => r.fields.text(name),
            WireReport::Read { value, .. } => value.get(name)?.as_str(),
        }
    }
}

/// The reports a published launch carries, each as one field named by its key (flattened into the message).
/// Boxed: most launches carry none, and a launch travels by value through the pipeline's events.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WireReports(Option<Box<ReportList>>);

/// The reports themselves (behind one pointer in [`WireReports`]).
#[derive(Debug, Clone, Default, PartialEq)]
struct ReportList(Vec<WireReport>);

impl WireReports {
    /// Whether a launch carries no report.
    pub fn is_empty(&self) -> bool {
        self.iter().next().is_none()
    }

    /// The reports, in order.
    pub fn iter(&self) -> impl Iterator<Item = &WireReport> + Clone {
        self.0.iter().flat_map(|v| v.0.iter())
    }

    /// The report published under `key`.
    pub fn get(&self, key: &str) -> Option<&WireReport> {
        self.iter().find(|r| r.key() == key)
    }

    /// Adds a report after the others.
    pub fn push(&mut self, report: WireReport) {
        self.0.get_or_insert_with(Default::default).0.push(report);
    }
}

impl From<Option<Report>> for WireReports {
    fn from(r: Option<Report>) -> Self {
        WireReports(r.map(|r| Box::new(ReportList(vec![WireReport::Written(r)]))))
    }
}

impl Serialize for WireReports {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.iter().count()))?;
        for r in self.iter() {
            match r {
                WireReport::Written(r) => map.serialize_entry(r.key, &r.fields)?,
                WireReport::Read { key, value } => map.serialize_entry(key, value)?,
            }
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for WireReports {
    /// The fields of a message that no other field of it claims: each JSON object among them is a report (other
    /// values are left alone, so a newer sender's plain fields do not make the message unreadable).
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct ReportsVisitor;
        impl<'de> Visitor<'de> for ReportsVisitor {
            type Value = WireReports;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("the model's reports")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<WireReports, A::Error> {
                let mut out = WireReports::default();
                while let Some(key) = map.next_key::<String>()? {
                    if let value @ serde_json::Value::Object(_) = map.next_value::<serde_json::Value>()? {
                        out.push(WireReport::Read { key, value });
                    }
                }
                Ok(out)
            }
        }
        d.deserialize_map(ReportsVisitor)
    }
}

impl schemars::JsonSchema for WireReports {
    fn schema_name() -> String {
        "ModelReports".into()
    }

    /// Each report is an object of numbers, texts and nulls under its key; the one model that reports today is
    /// the ground model (`ground`).
    fn json_schema(_: &mut schemars::gen::SchemaGenerator) -> schemars::schema::Schema {
        use schemars::schema::{InstanceType, Schema, SchemaObject, SingleOrVec};
        let scalar = SchemaObject {
            instance_type: Some(SingleOrVec::Vec(vec![InstanceType::Number, InstanceType::String, InstanceType::Null])),
            ..Default::default()
        };
        let mut report = SchemaObject { instance_type: Some(InstanceType::Object.into()), ..Default::default() };
        report.object().additional_properties = Some(Box::new(scalar.into()));
        report.metadata().description = Some(
            "The ground model's report (seed chapter 4): strike (thin, good, fat), ground_contact_before_ball_ms, \
             club_speed_loss_mph, face_angle_change_deg, dynamic_loft_change_deg, divot_depth_mm, divot_length_mm, \
             peak_ground_force_n, ground_contact_ms, ball_contact_us"
                .into(),
        );
        let mut schema = SchemaObject { instance_type: Some(InstanceType::Object.into()), ..Default::default() };
        schema.object().properties.insert("ground".into(), Schema::Object(report.clone()));
        schema.object().additional_properties = Some(Box::new(report.into()));
        schema.into()
    }
}
