//! Static value types of ports and their compatibility rules.

use std::fmt;

/// The type of an item on a port. Lists are described by [`Access`] on ports; `List` appears only in
/// the dynamic type of a value.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum ValueType {
    /// Anything.
    Any,
    /// f64.
    Number,
    /// i64.
    Integer,
    /// bool.
    Boolean,
    /// Text.
    Text,
    /// A position.
    Point,
    /// A direction.
    Vector,
    /// A plane.
    Plane,
    /// A set of line segments.
    Lines,
    /// A polyline.
    Polyline,
    /// A quad-grid mesh.
    QuadMesh,
    /// A general polygon mesh.
    Mesh,
    /// Named fields.
    Record,
    /// A list of items of the inner type.
    List(Box<ValueType>),
}

/// How a port takes its data (as in Grasshopper).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Access {
    /// One item per run. A list arriving here runs the node once per item (longest-list matching).
    Item,
    /// A whole list per run. A single value arrives as a one-element list; a list of lists runs the
    /// node once per inner list.
    List,
    /// Up to two list levels, passed as they are: one item, a list, or a table (a list of lists).
    /// Deeper nesting (a list of tables) runs the node once per table.
    Table,
    /// Any nesting, passed as it is.
    Tree,
}

impl Access {
    /// How many list levels the port consumes itself (`None` = all of them).
    pub fn depth(self) -> Option<usize> {
        match self {
            Access::Item => Some(0),
            Access::List => Some(1),
            Access::Table => Some(2),
            Access::Tree => None,
        }
    }
}

impl ValueType {
    /// The item type with every list level removed.
    pub fn base(&self) -> &ValueType {
        match self {
            ValueType::List(inner) => inner.base(),
            other => other,
        }
    }

    /// True when a value whose items are `self` may flow into a port whose items are `target`, using
    /// only the implicit conversions a designer expects: integer ↔ number, point ↔ vector, a list of
    /// points → polyline, quad mesh → polygon mesh. `Any` matches everything.
    pub fn converts_to(&self, target: &ValueType) -> bool {
        use ValueType::*;
        let (from, to) = (self.base(), target.base());
        matches!(
            (from, to),
            (Any, _)
                | (_, Any)
                | (Integer, Number)
                | (Number, Integer)
                | (Point, Vector)
                | (Vector, Point)
                | (Point, Polyline)
                | (QuadMesh, Mesh)
        ) || from == to
    }

    /// The lowercase name used in files, messages and `cnets nodes`.
    pub fn name(&self) -> String {
        self.to_string()
    }

    /// Parses a name written by [`ValueType::name`] (e.g. `number`, `list<point>`).
    pub fn parse(s: &str) -> Option<ValueType> {
        let s = s.trim();
        if let Some(inner) = s.strip_prefix("list<").and_then(|r| r.strip_suffix('>')) {
            return ValueType::parse(inner).map(|t| ValueType::List(Box::new(t)));
        }
        Some(match s {
            "any" => ValueType::Any,
            "number" => ValueType::Number,
            "integer" => ValueType::Integer,
            "boolean" => ValueType::Boolean,
            "text" => ValueType::Text,
            "point" => ValueType::Point,
            "vector" => ValueType::Vector,
            "plane" => ValueType::Plane,
            "lines" => ValueType::Lines,
            "polyline" => ValueType::Polyline,
            "quad_mesh" => ValueType::QuadMesh,
            "mesh" => ValueType::Mesh,
            "record" => ValueType::Record,
            _ => return None,
        })
    }

    /// The type as seen by a port with the given access (`list<…>` for list access).
    pub fn with_access(&self, access: Access) -> String {
        match access {
            Access::Item => self.to_string(),
            Access::List => format!("list<{self}>"),
            Access::Table => format!("table<{self}>"),
            Access::Tree => format!("tree<{self}>"),
        }
    }
}

impl fmt::Display for ValueType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = match self {
            ValueType::Any => "any",
            ValueType::Number => "number",
            ValueType::Integer => "integer",
            ValueType::Boolean => "boolean",
            ValueType::Text => "text",
            ValueType::Point => "point",
            ValueType::Vector => "vector",
            ValueType::Plane => "plane",
            ValueType::Lines => "lines",
            ValueType::Polyline => "polyline",
            ValueType::QuadMesh => "quad_mesh",
            ValueType::Mesh => "mesh",
            ValueType::Record => "record",
            ValueType::List(inner) => return write!(f, "list<{inner}>"),
        };
        f.write_str(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn designer_conversions_are_allowed_and_others_refused() {
        use ValueType::*;
        assert!(Integer.converts_to(&Number));
        assert!(Number.converts_to(&Integer));
        assert!(Point.converts_to(&Vector));
        assert!(List(Box::new(Point)).converts_to(&Polyline));
        assert!(QuadMesh.converts_to(&Mesh));
        assert!(Any.converts_to(&Polyline));
        assert!(!Polyline.converts_to(&Number));
        assert!(!Text.converts_to(&Number));
        assert!(!Mesh.converts_to(&QuadMesh));
        assert!(!Boolean.converts_to(&Integer));
    }

    #[test]
    fn names_round_trip() {
        for t in [
            ValueType::Number,
            ValueType::QuadMesh,
            ValueType::List(Box::new(ValueType::List(Box::new(ValueType::Point)))),
        ] {
            assert_eq!(ValueType::parse(&t.name()), Some(t));
        }
        assert_eq!(ValueType::parse("nonsense"), None);
    }
}
