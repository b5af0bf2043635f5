//! Port kinds: marker types that tie a port's declared type to the Rust type a node body sees.
//!
//! Node declarations name ports with these markers, conventionally through the alias `k`
//! (`radius: k::Number = 1.0`, `points: k::List<k::Point>`, `normal: Option<k::Vector>`).

use std::marker::PhantomData;
use std::sync::Arc;

use cnets_geometry::{Line, Plane as GeoPlane, PolygonMesh, Polyline as GeoPolyline, QuadGrid};
use glam::DVec3;

use crate::error::NodeError;
use crate::node::hint::Choices;
use crate::value::{Access, Record as RecordValue, Value, ValueType};

/// A port kind: its item type, access, optionality, and how the node body receives its value.
pub trait PortKind: 'static {
    /// What the node body receives.
    type In;
    /// The item type of the port.
    fn item_type() -> ValueType;
    /// Item, list or tree access.
    fn access() -> Access {
        Access::Item
    }
    /// Whether the port may stay empty.
    fn optional() -> bool {
        false
    }
    /// Takes the prepared value apart (it already has the port's type; `Null` means empty).
    fn extract(v: &Value, name: &str) -> Result<Self::In, NodeError>;
    /// The fixed words of a choice port ([`Choice`]); `None` for every other kind.
    fn choices() -> Option<Choices> {
        None
    }
}

/// The words of a choice port and the parser that reads them: a Rust enum behind a text port, so
/// `end_planes` is checked when a graph is loaded (`valid: perpendicular, mirror`) and an editor
/// shows a drop-down. Implemented on a marker type by the node library, for the enum it parses to.
pub trait ChoiceEnum: 'static {
    /// What the node body receives.
    type Value;
    /// The canonical words, in the order a drop-down lists them.
    const OPTIONS: &'static [&'static str];
    /// Reads a text (aliases, case and surrounding spaces as the node accepts them).
    fn parse(text: &str) -> Option<Self::Value>;
    /// Whether a text is accepted ([`Choices::accepts`]).
    fn accepts(text: &str) -> bool {
        Self::parse(text).is_some()
    }
}

/// A text port whose value is one of the words of `E` (see [`ChoiceEnum`]); the node body
/// receives `E::Value`.
#[derive(Debug, Clone, Copy)]
pub struct Choice<E>(PhantomData<E>);

impl<E: ChoiceEnum> PortKind for Choice<E> {
    type In = E::Value;
    fn item_type() -> ValueType {
        ValueType::Text
    }
    fn extract(v: &Value, name: &str) -> Result<E::Value, NodeError> {
        match v {
            Value::Text(t) => E::parse(t).ok_or_else(|| {
                NodeError::new(format!(
                    "input '{name}': '{}' is not one of its choices; valid: {}",
                    crate::files::excerpt(t, 60),
                    E::OPTIONS.join(", ")
                ))
            }),
            Value::Null => Err(missing(name)),
            other => Err(mismatch(name, "Text", other)),
        }
    }
    fn choices() -> Option<Choices> {
        Some(Choices {
            options: E::OPTIONS,
            accepts: E::accepts,
        })
    }
}

impl<E: ChoiceEnum> IntoPort<Choice<E>> for &str {
    fn into_port(self) -> Value {
        Value::text(self)
    }
}

/// Conversion of what a node body returns into the value on an output port of kind `K`.
pub trait IntoPort<K: PortKind> {
    /// Wraps the Rust value.
    fn into_port(self) -> Value;
}

fn missing(name: &str) -> NodeError {
    NodeError::new(format!("input '{name}' has no value"))
}

fn mismatch(name: &str, expected: &str, v: &Value) -> NodeError {
    NodeError::new(format!(
        "input '{name}' expected {expected}, got {}",
        v.type_name()
    ))
}

macro_rules! item_kind {
    ($(#[$doc:meta])* $marker:ident, $ty:ident, $rust:ty, |$v:ident| $pat:pat => $out:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $marker;

        impl PortKind for $marker {
            type In = $rust;
            fn item_type() -> ValueType {
                ValueType::$ty
            }
            fn extract($v: &Value, name: &str) -> Result<$rust, NodeError> {
                match $v {
                    $pat => Ok($out),
                    Value::Null => Err(missing(name)),
                    other => Err(mismatch(name, stringify!($ty), other)),
                }
            }
        }

        impl IntoPort<$marker> for Value {
            fn into_port(self) -> Value {
                self
            }
        }
    };
}

item_kind!(
    /// A real number (`f64`).
    Number, Number, f64, |v| Value::Number(x) => *x
);
item_kind!(
    /// A whole number (`i64`).
    Integer, Integer, i64, |v| Value::Integer(i) => *i
);
item_kind!(
    /// A boolean.
    Boolean, Boolean, bool, |v| Value::Boolean(b) => *b
);
item_kind!(
    /// Text.
    Text, Text, String, |v| Value::Text(s) => s.to_string()
);
item_kind!(
    /// A point.
    Point, Point, DVec3, |v| Value::Point(p) => *p
);
item_kind!(
    /// A vector.
    Vector, Vector, DVec3, |v| Value::Vector(p) => *p
);
item_kind!(
    /// A plane.
    Plane, Plane, GeoPlane, |v| Value::Plane(p) => **p
);
item_kind!(
    /// A set of line segments.
    Lines, Lines, Arc<Vec<Line>>, |v| Value::Lines(l) => l.clone()
);
item_kind!(
    /// A polyline.
    Polyline, Polyline, Arc<GeoPolyline>, |v| Value::Polyline(p) => p.clone()
);
item_kind!(
    /// A quad-grid mesh.
    QuadMesh, QuadMesh, Arc<QuadGrid>, |v| Value::QuadMesh(g) => g.clone()
);
item_kind!(
    /// A general polygon mesh.
    Mesh, Mesh, Arc<PolygonMesh>, |v| Value::Mesh(m) => m.clone()
);
item_kind!(
    /// A record of named fields.
    Record, Record, Arc<RecordValue>, |v| Value::Record(r) => r.clone()
);

/// Any value, passed as it is.
#[derive(Debug, Clone, Copy)]
pub struct Any;

impl PortKind for Any {
    type In = Value;
    fn item_type() -> ValueType {
        ValueType::Any
    }
    fn extract(v: &Value, _name: &str) -> Result<Value, NodeError> {
        Ok(v.clone())
    }
}

impl IntoPort<Any> for Value {
    fn into_port(self) -> Value {
        self
    }
}

/// A whole list of `K` items per run.
#[derive(Debug, Clone, Copy)]
pub struct List<K>(PhantomData<K>);

impl<K: PortKind> PortKind for List<K> {
    type In = Vec<K::In>;
    fn item_type() -> ValueType {
        K::item_type()
    }
    fn access() -> Access {
        Access::List
    }
    fn choices() -> Option<Choices> {
        K::choices()
    }
    fn extract(v: &Value, name: &str) -> Result<Self::In, NodeError> {
        match v {
            Value::List(items) => items
                .iter()
                .enumerate()
                // The indexed name is only formatted for an error (lists can be long).
                .map(|(k, item)| {
                    K::extract(item, name).or_else(|_| K::extract(item, &format!("{name}[{k}]")))
                })
                .collect(),
            Value::Null => Err(missing(name)),
            other => Ok(vec![K::extract(other, name)?]),
        }
    }
}

/// Any nesting of `K` items (a single item, a list, a table…), passed as a raw value.
#[derive(Debug, Clone, Copy)]
pub struct Tree<K>(PhantomData<K>);

impl<K: PortKind> PortKind for Tree<K> {
    type In = Value;
    fn item_type() -> ValueType {
        K::item_type()
    }
    fn access() -> Access {
        Access::Tree
    }
    fn extract(v: &Value, name: &str) -> Result<Value, NodeError> {
        match v {
            Value::Null => Err(missing(name)),
            other => Ok(other.clone()),
        }
    }
}

/// One item, a list or a table (list of lists) of `K`, passed as a raw value; deeper nesting maps the
/// node over its outer levels.
#[derive(Debug, Clone, Copy)]
pub struct Table<K>(PhantomData<K>);

impl<K: PortKind> PortKind for Table<K> {
    type In = Value;
    fn item_type() -> ValueType {
        K::item_type()
    }
    fn access() -> Access {
        Access::Table
    }
    fn extract(v: &Value, name: &str) -> Result<Value, NodeError> {
        match v {
            Value::Null => Err(missing(name)),
            other => Ok(other.clone()),
        }
    }
}

impl<K: PortKind> PortKind for Option<K> {
    type In = Option<K::In>;
    fn item_type() -> ValueType {
        K::item_type()
    }
    fn access() -> Access {
        K::access()
    }
    fn optional() -> bool {
        true
    }
    fn choices() -> Option<Choices> {
        K::choices()
    }
    fn extract(v: &Value, name: &str) -> Result<Self::In, NodeError> {
        match v {
            Value::Null => Ok(None),
            other => K::extract(other, name).map(Some),
        }
    }
}

macro_rules! into_port {
    ($marker:ty: $($rust:ty => |$x:ident| $e:expr),* $(,)?) => {
        $(impl IntoPort<$marker> for $rust {
            fn into_port(self) -> Value {
                let $x = self;
                $e
            }
        })*
    };
}

into_port!(Number: f64 => |x| Value::Number(x));
into_port!(Integer: i64 => |x| Value::Integer(x), i32 => |x| Value::Integer(x as i64), usize => |x| Value::Integer(x as i64));
into_port!(Boolean: bool => |x| Value::Boolean(x));
into_port!(Text: String => |x| Value::from(x), &str => |x| Value::text(x), Arc<str> => |x| Value::Text(x));
into_port!(Point: DVec3 => |x| Value::Point(x));
into_port!(Vector: DVec3 => |x| Value::Vector(x));
into_port!(Plane: GeoPlane => |x| Value::from(x));
into_port!(Lines: Vec<Line> => |x| Value::Lines(Arc::new(x)), Arc<Vec<Line>> => |x| Value::Lines(x));
into_port!(Polyline: GeoPolyline => |x| Value::from(x), Arc<GeoPolyline> => |x| Value::Polyline(x));
into_port!(QuadMesh: QuadGrid => |x| Value::from(x), Arc<QuadGrid> => |x| Value::QuadMesh(x));
into_port!(Mesh: PolygonMesh => |x| Value::from(x), Arc<PolygonMesh> => |x| Value::Mesh(x));
into_port!(Record: RecordValue => |x| Value::from(x));
into_port!(Tree<Number>: f64 => |x| Value::Number(x));
into_port!(Table<Number>: f64 => |x| Value::Number(x));
// A single value as the default of a list port (the engine passes it as a one-element list).
into_port!(List<Number>: f64 => |x| Value::Number(x));
into_port!(List<Integer>: i64 => |x| Value::Integer(x), i32 => |x| Value::Integer(x as i64));
into_port!(List<Text>: &str => |x| Value::text(x));

impl<K: PortKind, T: IntoPort<K>> IntoPort<List<K>> for Vec<T> {
    fn into_port(self) -> Value {
        Value::list(self.into_iter().map(IntoPort::<K>::into_port).collect())
    }
}

impl<K: PortKind> IntoPort<List<K>> for Value {
    fn into_port(self) -> Value {
        self
    }
}

impl<K: PortKind> IntoPort<Table<K>> for Value {
    fn into_port(self) -> Value {
        self
    }
}

impl<K: PortKind> IntoPort<Tree<K>> for Value {
    fn into_port(self) -> Value {
        self
    }
}

impl<K: PortKind, T: IntoPort<K>> IntoPort<Option<K>> for Option<T> {
    fn into_port(self) -> Value {
        self.map_or(Value::Null, IntoPort::<K>::into_port)
    }
}

/// Builds the default value of a port of kind `K` from a Rust value.
pub fn default_value<K: PortKind, T: IntoPort<K>>(t: T) -> Value {
    t.into_port()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extract_checks_types_and_names_the_input() {
        assert_eq!(Number::extract(&Value::Number(2.0), "x").unwrap(), 2.0);
        let e = Number::extract(&Value::Null, "radius").unwrap_err();
        assert_eq!(e.to_string(), "input 'radius' has no value");
        let e = Number::extract(&Value::text("a"), "radius").unwrap_err();
        assert!(e.to_string().contains("radius"), "{e}");
        assert_eq!(<Option<Point>>::extract(&Value::Null, "p").unwrap(), None);
        let list = Value::list(vec![Value::Number(1.0), Value::text("x")]);
        assert!(
            List::<Number>::extract(&list, "xs")
                .unwrap_err()
                .to_string()
                .contains("xs[1]")
        );
    }

    #[test]
    fn outputs_wrap_rust_values() {
        let v = IntoPort::<List<Option<Point>>>::into_port(vec![Some(DVec3::X), None]);
        assert_eq!(v, Value::list(vec![Value::Point(DVec3::X), Value::Null]));
        assert_eq!(List::<Number>::access(), Access::List);
        assert!(<Option<Vector>>::optional());
    }
}
