//! The typed value model: everything that flows along a wire.

mod equality;
mod finite;
mod footprint;
pub mod json;
pub mod leaves;
mod list;
mod plane;
mod record;
mod serial;
mod types;
pub(crate) mod walk;

pub use equality::content_hash;
pub use finite::{first_non_finite, is_all_finite};
pub use footprint::{Footprint, footprint};
pub use list::{Items, Packed};
pub use plane::{is_orthonormal_frame, plane_from_fields};
pub use record::Record;
pub use serial::MAX_NESTING;
pub use types::{Access, ValueType};

use std::sync::Arc;

use cnets_geometry::{Line, Plane, PolygonMesh, Polyline, QuadGrid};
use glam::DVec3;

/// A value on a wire or an input. Cheap to clone: big payloads are shared behind `Arc`.
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub enum Value {
    /// No value (an optional input left empty, an apex at infinity).
    #[default]
    Null,
    /// A real number.
    Number(f64),
    /// A whole number.
    Integer(i64),
    /// A truth value.
    Boolean(bool),
    /// A piece of text.
    Text(Arc<str>),
    /// A position in space.
    Point(DVec3),
    /// A direction or displacement.
    Vector(DVec3),
    /// An oriented plane with a frame.
    Plane(Arc<Plane>),
    /// A set of line segments (e.g. torsion-free node axes).
    Lines(Arc<Vec<Line>>),
    /// A polyline: points stored once plus a `closed` flag.
    Polyline(Arc<Polyline>),
    /// A regular quad-grid mesh.
    QuadMesh(#[serde(deserialize_with = "cnets_geometry::serial::checked")] Arc<QuadGrid>),
    /// A general polygon mesh.
    Mesh(#[serde(deserialize_with = "cnets_geometry::serial::checked")] Arc<PolygonMesh>),
    /// An ordered list (lists may nest).
    List(#[serde(deserialize_with = "serial::nested")] Items),
    /// Named fields, e.g. a quality report.
    Record(#[serde(deserialize_with = "serial::nested")] Arc<Record>),
}

impl Value {
    /// The dynamic type of this value (lists report the type of their first item).
    pub fn value_type(&self) -> ValueType {
        match self {
            Value::Null => ValueType::Any,
            Value::Number(_) => ValueType::Number,
            Value::Integer(_) => ValueType::Integer,
            Value::Boolean(_) => ValueType::Boolean,
            Value::Text(_) => ValueType::Text,
            Value::Point(_) => ValueType::Point,
            Value::Vector(_) => ValueType::Vector,
            Value::Plane(_) => ValueType::Plane,
            Value::Lines(_) => ValueType::Lines,
            Value::Polyline(_) => ValueType::Polyline,
            Value::QuadMesh(_) => ValueType::QuadMesh,
            Value::Mesh(_) => ValueType::Mesh,
            Value::Record(_) => ValueType::Record,
            Value::List(items) => ValueType::List(Box::new(match items.as_packed() {
                Some(packed) if !packed.is_empty() => packed.value(0).value_type(),
                _ => items.first().map_or(ValueType::Any, Value::value_type),
            })),
        }
    }

    /// A short human name of the dynamic type, for messages.
    pub fn type_name(&self) -> String {
        self.value_type().to_string()
    }

    /// Builds a list value.
    pub fn list(items: Vec<Value>) -> Value {
        Value::List(Items::new(items))
    }

    /// Builds a text value.
    pub fn text(s: impl AsRef<str>) -> Value {
        Value::Text(Arc::from(s.as_ref()))
    }

    /// The items when this is a list.
    pub fn as_list(&self) -> Option<&[Value]> {
        match self {
            Value::List(items) => Some(items),
            _ => None,
        }
    }

    /// The number when this is a number or an integer.
    pub fn as_f64(&self) -> Option<f64> {
        match *self {
            Value::Number(x) => Some(x),
            Value::Integer(i) => Some(i as f64),
            _ => None,
        }
    }

    /// The coordinates when this is a point or a vector.
    pub fn as_vec3(&self) -> Option<DVec3> {
        match *self {
            Value::Point(p) | Value::Vector(p) => Some(p),
            _ => None,
        }
    }

    /// True for [`Value::Null`].
    pub fn is_null(&self) -> bool {
        matches!(self, Value::Null)
    }

    /// Bitwise structural equality: numbers compare by their bits (so NaN equals NaN and 0.0 differs
    /// from −0.0). This is the equality used for early cutoff.
    pub fn same_as(&self, other: &Value) -> bool {
        equality::same(self, other)
    }
}

impl PartialEq for Value {
    fn eq(&self, other: &Self) -> bool {
        self.same_as(other)
    }
}

impl From<f64> for Value {
    fn from(x: f64) -> Self {
        Value::Number(x)
    }
}

impl From<i64> for Value {
    fn from(i: i64) -> Self {
        Value::Integer(i)
    }
}

impl From<bool> for Value {
    fn from(b: bool) -> Self {
        Value::Boolean(b)
    }
}

impl From<&str> for Value {
    fn from(s: &str) -> Self {
        Value::text(s)
    }
}

impl From<String> for Value {
    fn from(s: String) -> Self {
        Value::Text(Arc::from(s))
    }
}

impl From<Polyline> for Value {
    fn from(p: Polyline) -> Self {
        Value::Polyline(Arc::new(p))
    }
}

impl From<QuadGrid> for Value {
    fn from(g: QuadGrid) -> Self {
        Value::QuadMesh(Arc::new(g))
    }
}

impl From<PolygonMesh> for Value {
    fn from(m: PolygonMesh) -> Self {
        Value::Mesh(Arc::new(m))
    }
}

impl From<Plane> for Value {
    fn from(p: Plane) -> Self {
        Value::Plane(Arc::new(p))
    }
}

impl From<Record> for Value {
    fn from(r: Record) -> Self {
        Value::Record(Arc::new(r))
    }
}

impl From<Vec<Value>> for Value {
    fn from(items: Vec<Value>) -> Self {
        Value::list(items)
    }
}
