//! Literal input values in graph files: RON ↔ [`Value`], typed by the port's item type.
//!
//! Points and vectors are `(x, y, z)` (tagged `Point(..)` / `Vector(..)` on ports of any type);
//! planes `(origin: .., normal: .., x_axis: ..)` or `XY`/`YZ`/`ZX`; polylines `(points: [..],
//! closed: ..)` or a list of points; lines `[((x,y,z), (x,y,z)), ..]`; quad meshes `(rows: .., cols:
//! .., wrap_rows: .., wrap_cols: .., vertices: [..])`; polygon meshes `(vertices: [..], faces: [[..]])`;
//! records `{"name": value}`; lists `[..]`; empty `None`. Numbers may be `inf`/`NaN`.

use std::fmt::Write as _;
use std::sync::Arc;

use cnets_geometry::{Line, Plane, PolygonMesh, Polyline, QuadGrid};
use glam::DVec3;

use super::ron::{Kind, Node, Pos};
use crate::value::{Record, Value, ValueType, is_orthonormal_frame, plane_from_fields};

/// A literal that does not fit its port: where and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LiteralError {
    /// Position of the offending value.
    pub pos: Pos,
    /// What was expected and found.
    pub message: String,
}

type Res<T> = Result<T, LiteralError>;

fn err<T>(node: &Node, message: impl Into<String>) -> Res<T> {
    Err(LiteralError {
        pos: node.pos,
        message: message.into(),
    })
}

fn expected<T>(node: &Node, what: &str) -> Res<T> {
    err(
        node,
        format!("expected {what}, found {}", node.kind.describe()),
    )
}

/// Decodes a RON literal into a value whose items have type `ty` (or nested lists of them).
pub fn decode(node: &Node, ty: &ValueType) -> Res<Value> {
    match &node.kind {
        Kind::None | Kind::Unit => return Ok(Value::Null),
        Kind::Some(inner) => return decode(inner, ty),
        _ => {}
    }
    if let Some(v) = decode_item(node, ty.base())? {
        return Ok(v);
    }
    match &node.kind {
        Kind::List(items) => {
            // Sized once: collecting through `Result` would grow the list by doubling.
            let mut values = Vec::with_capacity(items.len());
            for item in items {
                values.push(decode(item, ty)?);
            }
            Ok(Value::list(values))
        }
        _ => expected(node, &ty.base().to_string()),
    }
}

fn vec3(node: &Node) -> Option<DVec3> {
    match &node.kind {
        Kind::Tuple(None, items) | Kind::List(items) if items.len() == 3 => Some(DVec3::new(
            items[0].as_f64()?,
            items[1].as_f64()?,
            items[2].as_f64()?,
        )),
        Kind::Tuple(Some(name), items)
            if (name == "Point" || name == "Vector") && items.len() == 1 =>
        {
            vec3(&items[0])
        }
        Kind::Tuple(Some(name), items)
            if (name == "Point" || name == "Vector") && items.len() == 3 =>
        {
            Some(DVec3::new(
                items[0].as_f64()?,
                items[1].as_f64()?,
                items[2].as_f64()?,
            ))
        }
        _ => None,
    }
}

fn tag(node: &Node) -> Option<&str> {
    match &node.kind {
        Kind::Tuple(Some(name), _) | Kind::Struct(Some(name), _) => Some(name),
        _ => None,
    }
}

fn field<'a>(node: &'a Node, name: &str) -> Option<&'a Node> {
    node.fields()?
        .iter()
        .find(|(f, _)| f.name == name)
        .map(|(_, v)| v)
}

fn require<'a>(node: &'a Node, name: &str, what: &str) -> Res<&'a Node> {
    field(node, name).map_or_else(|| err(node, format!("{what} needs a '{name}' field")), Ok)
}

fn check_fields(node: &Node, allowed: &[&str], what: &str) -> Res<()> {
    for (f, _) in node.fields().unwrap_or(&[]) {
        if !allowed.contains(&f.name.as_str()) {
            return Err(LiteralError {
                pos: f.pos,
                message: format!(
                    "unknown {what} field '{}'; expected one of: {}",
                    f.name,
                    allowed.join(", ")
                ),
            });
        }
    }
    Ok(())
}

fn point_list(node: &Node, what: &str) -> Res<Vec<DVec3>> {
    match &node.kind {
        Kind::List(items) => items
            .iter()
            .map(|p| vec3(p).map_or_else(|| expected(p, "a point (x, y, z)"), Ok))
            .collect(),
        _ => expected(node, &format!("a list of points for {what}")),
    }
}

fn boolean(node: Option<&Node>) -> Res<bool> {
    match node {
        None => Ok(false),
        Some(Node {
            kind: Kind::Bool(b),
            ..
        }) => Ok(*b),
        Some(other) => expected(other, "true or false"),
    }
}

fn count(node: &Node, what: &str) -> Res<usize> {
    match node.kind {
        Kind::Int(i) if i >= 0 => Ok(i as usize),
        _ => expected(node, &format!("a non-negative integer for {what}")),
    }
}

fn plane(node: &Node) -> Res<Plane> {
    if let Kind::Ident(name) = &node.kind {
        return match name.as_str() {
            "XY" => Ok(Plane::XY),
            "YZ" => Ok(Plane::YZ),
            "ZX" => Ok(Plane::ZX),
            _ => err(
                node,
                format!("unknown plane '{name}'; use XY, YZ, ZX or (origin: .., normal: ..)"),
            ),
        };
    }
    check_fields(node, &["origin", "normal", "x_axis", "y_axis"], "plane")?;
    let point = |name: &str| -> Res<DVec3> {
        let n = require(node, name, "a plane")?;
        vec3(n).map_or_else(|| expected(n, "a point (x, y, z)"), Ok)
    };
    let origin = point("origin")?;
    let normal = point("normal")?;
    let (x_axis, y_axis) = (
        field(node, "x_axis").and_then(vec3),
        field(node, "y_axis").and_then(vec3),
    );
    if let (Some(x), Some(y)) = (x_axis, y_axis)
        && !is_orthonormal_frame(x, y, normal)
    {
        return err(node, "plane axes are not a right-handed orthonormal frame");
    }
    plane_from_fields(origin, Some(normal), x_axis, y_axis).or_else(|e| err(node, e.to_string()))
}

fn polyline(node: &Node) -> Res<Polyline> {
    check_fields(node, &["points", "closed"], "polyline")?;
    let points = point_list(require(node, "points", "a polyline")?, "points")?;
    Ok(Polyline {
        points,
        closed: boolean(field(node, "closed"))?,
    })
}

fn quad_mesh(node: &Node) -> Res<QuadGrid> {
    check_fields(
        node,
        &["rows", "cols", "wrap_rows", "wrap_cols", "vertices"],
        "quad mesh",
    )?;
    let rows = count(require(node, "rows", "a quad mesh")?, "rows")?;
    let cols = count(require(node, "cols", "a quad mesh")?, "cols")?;
    let vertices = point_list(require(node, "vertices", "a quad mesh")?, "vertices")?;
    let grid = QuadGrid::new(rows, cols, vertices).or_else(|e| err(node, e.to_string()))?;
    Ok(grid.with_wrap(
        boolean(field(node, "wrap_rows"))?,
        boolean(field(node, "wrap_cols"))?,
    ))
}

fn polygon_mesh(node: &Node) -> Res<PolygonMesh> {
    check_fields(node, &["vertices", "faces"], "mesh")?;
    let vertices = point_list(require(node, "vertices", "a mesh")?, "vertices")?;
    let faces_node = require(node, "faces", "a mesh")?;
    let Kind::List(faces) = &faces_node.kind else {
        return expected(faces_node, "a list of faces");
    };
    let faces = faces
        .iter()
        .map(|f| match &f.kind {
            Kind::List(ix) => ix
                .iter()
                .map(|i| match i.kind {
                    Kind::Int(v) if (0..=u32::MAX as i64).contains(&v) => Ok(v as u32),
                    _ => expected(i, "a vertex index"),
                })
                .collect::<Res<Vec<u32>>>(),
            _ => expected(f, "a face [i, j, k, ..]"),
        })
        .collect::<Res<Vec<_>>>()?;
    PolygonMesh::from_faces(vertices, &faces).or_else(|e| err(node, e.to_string()))
}

fn segment(node: &Node) -> Option<Line> {
    match &node.kind {
        Kind::Tuple(None, items) | Kind::List(items) if items.len() == 2 => {
            Some(Line::new(vec3(&items[0])?, vec3(&items[1])?))
        }
        _ => None,
    }
}

fn record(entries: &[(Node, Node)]) -> Res<Record> {
    let mut r = Record::new();
    for (k, v) in entries {
        let name = k
            .as_str()
            .map_or_else(|| expected(k, "a field name string"), Ok)?;
        r.set(name, decode(v, &ValueType::Any)?);
    }
    Ok(r)
}

/// One item of type `ty`; `Ok(None)` when the node is a list of items instead.
fn decode_item(node: &Node, ty: &ValueType) -> Res<Option<Value>> {
    use ValueType as T;
    let is_list = matches!(node.kind, Kind::List(_));
    Ok(Some(match ty {
        T::Number => match node.kind {
            Kind::Int(i) => Value::Number(i as f64),
            Kind::Float(x) => Value::Number(x),
            _ if is_list => return Ok(None),
            _ => return expected(node, "a number"),
        },
        T::Integer => match node.kind {
            Kind::Int(i) => Value::Integer(i),
            Kind::Float(x) if x.fract() == 0.0 && x.abs() < 9.0e15 => Value::Integer(x as i64),
            _ if is_list => return Ok(None),
            _ => return expected(node, "an integer"),
        },
        T::Boolean => match node.kind {
            Kind::Bool(b) => Value::Boolean(b),
            _ if is_list => return Ok(None),
            _ => return expected(node, "true or false"),
        },
        T::Text => match &node.kind {
            Kind::Str(s) => Value::text(s),
            _ if is_list => return Ok(None),
            _ => return expected(node, "a string"),
        },
        T::Point | T::Vector => match vec3(node) {
            Some(p) if *ty == T::Point => Value::Point(p),
            Some(p) => Value::Vector(p),
            None if is_list => return Ok(None),
            None => return expected(node, "a point (x, y, z)"),
        },
        T::Plane => match &node.kind {
            Kind::Struct(..) | Kind::Ident(_) => Value::from(plane(node)?),
            _ if is_list => return Ok(None),
            _ => return expected(node, "a plane"),
        },
        T::Lines => match &node.kind {
            Kind::List(items)
                if !items.is_empty() && items.iter().all(|s| segment(s).is_some()) =>
            {
                Value::Lines(Arc::new(items.iter().filter_map(segment).collect()))
            }
            _ if is_list => return Ok(None),
            _ => return expected(node, "a list of segments ((x,y,z), (x,y,z))"),
        },
        T::Polyline => match &node.kind {
            Kind::Struct(..) => Value::from(polyline(node)?),
            Kind::List(items) if !items.is_empty() && items.iter().all(|p| vec3(p).is_some()) => {
                Value::from(Polyline::open(items.iter().filter_map(vec3).collect()))
            }
            _ if is_list => return Ok(None),
            _ => return expected(node, "a polyline (points: [..], closed: ..)"),
        },
        T::QuadMesh => match &node.kind {
            Kind::Struct(..) => Value::from(quad_mesh(node)?),
            _ if is_list => return Ok(None),
            _ => return expected(node, "a quad mesh"),
        },
        T::Mesh => match &node.kind {
            Kind::Struct(..) if field(node, "rows").is_some() => Value::from(quad_mesh(node)?),
            Kind::Struct(..) => Value::from(polygon_mesh(node)?),
            _ if is_list => return Ok(None),
            _ => return expected(node, "a mesh"),
        },
        T::Record => match &node.kind {
            Kind::Map(entries) => Value::from(record(entries)?),
            _ if is_list => return Ok(None),
            _ => return expected(node, "a record {\"name\": value}"),
        },
        T::Any => match &node.kind {
            Kind::Bool(b) => Value::Boolean(*b),
            Kind::Int(i) => Value::Integer(*i),
            Kind::Float(x) => Value::Number(*x),
            Kind::Str(s) => Value::text(s),
            Kind::Char(c) => Value::text(c.to_string()),
            Kind::Map(entries) => Value::from(record(entries)?),
            Kind::Tuple(Some(n), items) if n == "Lines" && items.len() == 1 => {
                return decode_item(&items[0], &T::Lines);
            }
            Kind::Tuple(..) if tag(node) == Some("Vector") => match vec3(node) {
                Some(p) => Value::Vector(p),
                None => return expected(node, "Vector(x, y, z)"),
            },
            Kind::Tuple(..) => match vec3(node) {
                Some(p) => Value::Point(p),
                None => return expected(node, "a point (x, y, z)"),
            },
            Kind::Struct(..) if field(node, "rows").is_some() => Value::from(quad_mesh(node)?),
            Kind::Struct(..) if field(node, "faces").is_some() => Value::from(polygon_mesh(node)?),
            Kind::Struct(..) if field(node, "points").is_some() => Value::from(polyline(node)?),
            Kind::Struct(..) if field(node, "normal").is_some() => Value::from(plane(node)?),
            Kind::List(_) => return Ok(None),
            _ => return expected(node, "a value"),
        },
        T::List(inner) => return decode_item(node, inner),
    }))
}

/// Writes a value as RON for a port whose items have type `ty`; `indent` is the current indentation.
pub fn encode(value: &Value, ty: &ValueType, indent: usize) -> String {
    let mut out = String::new();
    write_value(&mut out, value, ty.base(), indent);
    out
}

fn float(out: &mut String, x: f64) {
    if x.is_nan() {
        out.push_str("NaN");
    } else if x.is_infinite() {
        out.push_str(if x > 0.0 { "inf" } else { "-inf" });
    } else {
        let s = format!("{x:?}");
        out.push_str(&s);
        if !s.contains(['.', 'e', 'E']) {
            out.push_str(".0");
        }
    }
}

fn point(out: &mut String, p: DVec3) {
    out.push('(');
    float(out, p.x);
    out.push_str(", ");
    float(out, p.y);
    out.push_str(", ");
    float(out, p.z);
    out.push(')');
}

fn points(out: &mut String, ps: &[DVec3]) {
    out.push('[');
    for (k, p) in ps.iter().enumerate() {
        if k > 0 {
            out.push_str(", ");
        }
        point(out, *p);
    }
    out.push(']');
}

/// Writes a string literal with RON escapes.
pub fn quote(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn is_scalar(v: &Value) -> bool {
    matches!(
        v,
        Value::Null
            | Value::Number(_)
            | Value::Integer(_)
            | Value::Boolean(_)
            | Value::Point(_)
            | Value::Vector(_)
    )
}

fn write_value(out: &mut String, value: &Value, ty: &ValueType, indent: usize) {
    let any = *ty == ValueType::Any;
    match value {
        Value::Null => out.push_str("None"),
        Value::Number(x) => float(out, *x),
        Value::Integer(i) => {
            let _ = write!(out, "{i}");
        }
        Value::Boolean(b) => out.push_str(if *b { "true" } else { "false" }),
        Value::Text(s) => quote(out, s),
        Value::Point(p) => {
            if any {
                out.push_str("Point");
            }
            point(out, *p);
        }
        Value::Vector(p) => {
            if any {
                out.push_str("Vector");
            }
            point(out, *p);
        }
        Value::Plane(p) => {
            out.push_str("(origin: ");
            point(out, p.origin);
            out.push_str(", normal: ");
            point(out, p.normal);
            out.push_str(", x_axis: ");
            point(out, p.x_axis);
            out.push_str(", y_axis: ");
            point(out, p.y_axis);
            out.push(')');
        }
        Value::Lines(lines) => {
            if any {
                out.push_str("Lines(");
            }
            out.push('[');
            for (k, l) in lines.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                out.push('(');
                point(out, l.start);
                out.push_str(", ");
                point(out, l.end);
                out.push(')');
            }
            out.push(']');
            if any {
                out.push(')');
            }
        }
        Value::Polyline(p) => {
            out.push_str("(points: ");
            points(out, &p.points);
            let _ = write!(out, ", closed: {})", p.closed);
        }
        Value::QuadMesh(g) => {
            let _ = write!(
                out,
                "(rows: {}, cols: {}, wrap_rows: {}, wrap_cols: {}, vertices: ",
                g.rows, g.cols, g.wrap_rows, g.wrap_cols
            );
            points(out, &g.vertices);
            out.push(')');
        }
        Value::Mesh(m) => {
            out.push_str("(vertices: ");
            points(out, &m.vertices);
            out.push_str(", faces: [");
            for (k, f) in m.faces().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                let _ = write!(out, "{f:?}");
            }
            out.push_str("])");
        }
        Value::List(items) => {
            if items.iter().all(is_scalar) {
                out.push('[');
                for (k, item) in items.iter().enumerate() {
                    if k > 0 {
                        out.push_str(", ");
                    }
                    write_value(out, item, ty, indent);
                }
                out.push(']');
            } else {
                out.push_str("[\n");
                for item in items.iter() {
                    push_indent(out, indent + 1);
                    write_value(out, item, ty, indent + 1);
                    out.push_str(",\n");
                }
                push_indent(out, indent);
                out.push(']');
            }
        }
        Value::Record(r) => {
            out.push('{');
            for (k, (name, v)) in r.fields().iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                quote(out, name);
                out.push_str(": ");
                write_value(out, v, &ValueType::Any, indent);
            }
            out.push('}');
        }
    }
}

/// Appends four spaces per level.
pub fn push_indent(out: &mut String, level: usize) {
    for _ in 0..level {
        out.push_str("    ");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::file::ron::parse;

    fn round_trip(v: &Value, ty: &ValueType) -> Value {
        let text = encode(v, ty, 0);
        decode(
            &parse(&text).unwrap_or_else(|e| panic!("{text}: {e:?}")),
            ty,
        )
        .unwrap()
    }

    #[test]
    fn values_round_trip_through_ron() {
        let cases = [
            (Value::Number(0.1), ValueType::Number),
            (Value::Number(f64::NEG_INFINITY), ValueType::Number),
            (Value::Integer(-3), ValueType::Integer),
            (Value::text("a \"quoted\"\nline"), ValueType::Text),
            (
                Value::Vector(DVec3::new(1.0, -2.5, 1e-9)),
                ValueType::Vector,
            ),
            (Value::Vector(DVec3::new(1.0, -2.5, 1e-9)), ValueType::Any),
            (
                Value::from(Plane::from_normal(DVec3::ONE, DVec3::Y).unwrap()),
                ValueType::Plane,
            ),
            (
                Value::from(Polyline::closed(vec![DVec3::ZERO, DVec3::X, DVec3::Y])),
                ValueType::Polyline,
            ),
            (
                Value::list(vec![Value::Number(1.0), Value::Number(2.0)]),
                ValueType::Number,
            ),
            (
                Value::list(vec![
                    Value::list(vec![Value::Number(0.5)]),
                    Value::list(vec![]),
                ]),
                ValueType::Number,
            ),
            (
                Value::Lines(Arc::new(vec![Line::new(DVec3::ZERO, DVec3::X)])),
                ValueType::Lines,
            ),
            (
                Value::from(Record::new().with("a", 1.0).with("b", "x")),
                ValueType::Record,
            ),
        ];
        for (v, ty) in cases {
            assert_eq!(round_trip(&v, &ty), v, "{}", encode(&v, &ty, 0));
        }
        let nan = round_trip(&Value::Number(f64::NAN), &ValueType::Number);
        assert!(matches!(nan, Value::Number(x) if x.is_nan()));
    }

    #[test]
    fn type_errors_point_at_the_value() {
        let node = parse("[1.0, \"x\"]").unwrap();
        let e = decode(&node, &ValueType::Number).unwrap_err();
        assert_eq!(e.pos, Pos { line: 1, col: 7 });
        assert!(
            e.message.contains("expected a number, found a string"),
            "{}",
            e.message
        );
        let node = parse("(points: [(0, 0, 0)], closd: true)").unwrap();
        assert!(
            decode(&node, &ValueType::Polyline)
                .unwrap_err()
                .message
                .contains("closd")
        );
    }
}
