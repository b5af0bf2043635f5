//! Values to JSON: a `serde_json::Value` tree ([`to_json`]) or streamed item by item to a writer
//! ([`write_json`], [`JsonOut`]) with the same bytes.

use cnets_geometry::PolygonMesh;
use glam::DVec3;
use serde_json::{Map, Value as Json, json};

use crate::value::Value;

/// Encodes a value as JSON. Non-finite numbers become `null`.
pub fn to_json(value: &Value) -> Json {
    match value {
        Value::Null => Json::Null,
        Value::Number(x) => num(*x),
        Value::Integer(i) => json!(i),
        Value::Boolean(b) => json!(b),
        Value::Text(s) => json!(s.as_ref()),
        Value::Point(p) | Value::Vector(p) => vec3(*p),
        Value::Plane(p) => json!({
            "origin": vec3(p.origin),
            "x_axis": vec3(p.x_axis),
            "y_axis": vec3(p.y_axis),
            "normal": vec3(p.normal),
        }),
        Value::Lines(lines) => Json::Array(
            lines
                .iter()
                .map(|l| json!([vec3(l.start), vec3(l.end)]))
                .collect(),
        ),
        Value::Polyline(p) => json!({ "points": points(&p.points), "closed": p.closed }),
        Value::QuadMesh(g) => json!({
            "rows": g.rows,
            "cols": g.cols,
            "wrap_rows": g.wrap_rows,
            "wrap_cols": g.wrap_cols,
            "vertices": points(&g.vertices),
        }),
        Value::Mesh(m) if m.parts.is_empty() => json!({
            "vertices": points(&m.vertices),
            "faces": m.faces().map(|f| json!(f)).collect::<Vec<_>>(),
        }),
        Value::Mesh(m) => json!({
            "vertices": points(&m.vertices),
            "faces": m.faces().map(|f| json!(f)).collect::<Vec<_>>(),
            "parts": m.parts.names,
            "face_parts": m.parts.of_face,
        }),
        Value::List(items) => match items.as_packed() {
            // Item by item, without building the values first.
            Some(packed) => Json::Array(
                (0..packed.len())
                    .map(|k| to_json(&packed.value(k)))
                    .collect(),
            ),
            None => Json::Array(items.iter().map(to_json).collect()),
        },
        Value::Record(r) => Json::Object(
            r.fields()
                .iter()
                .map(|(k, v)| (k.clone(), to_json(v)))
                .collect::<Map<_, _>>(),
        ),
    }
}

/// A value as a serde [`Serialize`](serde::Serialize) implementation: serializing it writes the
/// same JSON as [`to_json`] (the same key order, numbers and `null`s), streamed item by item to a
/// writer without building a JSON tree first (a tree of a 10⁷-point curve takes gigabytes).
#[derive(Debug, Clone, Copy)]
pub struct JsonOut<'a>(pub &'a Value);

/// Writes `value` as compact JSON to `writer`, streamed (see [`JsonOut`]); the bytes equal
/// `to_json(value).to_string()`.
pub fn write_json<W: std::io::Write>(writer: W, value: &Value) -> serde_json::Result<()> {
    serde_json::to_writer(writer, &JsonOut(value))
}

/// `[x, y, z]`, streamed.
struct Vec3Out(DVec3);

impl serde::Serialize for Vec3Out {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(3)?;
        t.serialize_element(&self.0.x)?;
        t.serialize_element(&self.0.y)?;
        t.serialize_element(&self.0.z)?;
        t.end()
    }
}

/// A list of points, streamed.
struct PointsOut<'a>(&'a [DVec3]);

impl serde::Serialize for PointsOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.0.iter().map(|p| Vec3Out(*p)))
    }
}

impl serde::Serialize for JsonOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        match self.0 {
            Value::Null => s.serialize_unit(),
            // serde_json writes a non-finite number as `null`, as `to_json` does.
            Value::Number(x) => s.serialize_f64(*x),
            Value::Integer(i) => s.serialize_i64(*i),
            Value::Boolean(b) => s.serialize_bool(*b),
            Value::Text(t) => s.serialize_str(t),
            Value::Point(p) | Value::Vector(p) => Vec3Out(*p).serialize(s),
            Value::Plane(p) => {
                let mut m = s.serialize_map(Some(4))?;
                m.serialize_entry("origin", &Vec3Out(p.origin))?;
                m.serialize_entry("x_axis", &Vec3Out(p.x_axis))?;
                m.serialize_entry("y_axis", &Vec3Out(p.y_axis))?;
                m.serialize_entry("normal", &Vec3Out(p.normal))?;
                m.end()
            }
            Value::Lines(lines) => {
                s.collect_seq(lines.iter().map(|l| [Vec3Out(l.start), Vec3Out(l.end)]))
            }
            Value::Polyline(p) => {
                let mut m = s.serialize_map(Some(2))?;
                m.serialize_entry("points", &PointsOut(&p.points))?;
                m.serialize_entry("closed", &p.closed)?;
                m.end()
            }
            Value::QuadMesh(g) => {
                let mut m = s.serialize_map(Some(5))?;
                m.serialize_entry("rows", &g.rows)?;
                m.serialize_entry("cols", &g.cols)?;
                m.serialize_entry("wrap_rows", &g.wrap_rows)?;
                m.serialize_entry("wrap_cols", &g.wrap_cols)?;
                m.serialize_entry("vertices", &PointsOut(&g.vertices))?;
                m.end()
            }
            Value::Mesh(mesh) => {
                struct Faces<'a>(&'a PolygonMesh);
                impl serde::Serialize for Faces<'_> {
                    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                        s.collect_seq(self.0.faces())
                    }
                }
                let named = !mesh.parts.is_empty();
                let mut m = s.serialize_map(Some(if named { 4 } else { 2 }))?;
                m.serialize_entry("vertices", &PointsOut(&mesh.vertices))?;
                m.serialize_entry("faces", &Faces(mesh))?;
                if named {
                    m.serialize_entry("parts", &mesh.parts.names)?;
                    m.serialize_entry("face_parts", &mesh.parts.of_face)?;
                }
                m.end()
            }
            Value::List(items) => match items.as_packed() {
                Some(packed) => s.collect_seq((0..packed.len()).map(|k| ValueOut(packed.value(k)))),
                None => s.collect_seq(items.iter().map(JsonOut)),
            },
            Value::Record(r) => {
                let mut m = s.serialize_map(Some(r.fields().len()))?;
                for (k, v) in r.fields() {
                    m.serialize_entry(k, &JsonOut(v))?;
                }
                m.end()
            }
        }
    }
}

/// An owned value, serialized as [`JsonOut`] (the items of packed lists are built one at a time).
struct ValueOut(Value);

impl serde::Serialize for ValueOut {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        JsonOut(&self.0).serialize(s)
    }
}

fn num(x: f64) -> Json {
    serde_json::Number::from_f64(x).map_or(Json::Null, Json::Number)
}

fn vec3(p: DVec3) -> Json {
    Json::Array(vec![num(p.x), num(p.y), num(p.z)])
}

fn points(ps: &[DVec3]) -> Json {
    Json::Array(ps.iter().map(|p| vec3(*p)).collect())
}
