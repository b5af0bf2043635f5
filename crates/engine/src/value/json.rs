//! The runner's JSON encoding of values.
//!
//! number/integer → number; boolean; text → string; point/vector → `[x, y, z]`; list → array;
//! polyline → `{ "points": [[x,y,z], …], "closed": bool }` (a bare array of points is accepted as an
//! open polyline on input); quad mesh → `{ "rows", "cols", "wrap_rows", "wrap_cols", "vertices" }`;
//! polygon mesh → `{ "vertices", "faces": [[i, …], …] }`; plane → `{ "origin", "x_axis", "y_axis",
//! "normal" }`; lines → `[[[x,y,z],[x,y,z]], …]`; record → object; null and non-finite numbers → `null`.

use std::sync::Arc;

use cnets_geometry::{Line, Plane, PolygonMesh, Polyline, QuadGrid};
use glam::DVec3;
use serde_json::{Map, Value as Json, json};

use super::{Items, Record, Value, ValueType};

/// Why a JSON document does not decode into a value of a port's type.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JsonError {
    /// A JSON value of another kind than the type needs.
    #[error("expected {expected}, got {found}")]
    Expected {
        /// The type asked for.
        expected: String,
        /// What the JSON holds ("a string", "an object", …).
        found: &'static str,
    },
    /// A number with a fraction (or too large) where an integer is needed.
    #[error("expected integer, got the non-integral number {0}")]
    NotIntegral(String),
    /// A geometry object with a missing or malformed field.
    #[error("{0}")]
    Malformed(String),
    /// The geometry the object describes is invalid.
    #[error(transparent)]
    Geometry(#[from] cnets_geometry::GeometryError),
    /// Inside array item `index`: `[2]: …`, nested `[0][2]: …`.
    #[error("[{index}]{}{source}", separator(.source))]
    At {
        /// The item's position.
        index: usize,
        /// What went wrong inside it.
        source: Box<JsonError>,
    },
    /// Inside an object field of a record.
    #[error("{field}: {source}")]
    Field {
        /// The field name.
        field: String,
        /// What went wrong inside it.
        source: Box<JsonError>,
    },
}

/// `[0][2]: …` for nested positions, `[2]: …` before a message.
fn separator(inner: &JsonError) -> &'static str {
    if matches!(inner, JsonError::At { .. }) {
        ""
    } else {
        ": "
    }
}

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
        Value::Mesh(m) => json!({
            "vertices": points(&m.vertices),
            "faces": m.faces().map(|f| json!(f)).collect::<Vec<_>>(),
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
                let mut m = s.serialize_map(Some(2))?;
                m.serialize_entry("vertices", &PointsOut(&mesh.vertices))?;
                m.serialize_entry("faces", &Faces(mesh))?;
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

/// Decodes JSON into a value whose items have type `ty` (or nested lists of such items).
/// `null` decodes to [`Value::Null`]. The error says what was expected and what was found.
pub fn from_json(json: &Json, ty: &ValueType) -> Result<Value, JsonError> {
    if json.is_null() {
        return Ok(Value::Null);
    }
    if let Some(v) = decode_item(json, ty.base())? {
        return Ok(v);
    }
    match json {
        // An array of numbers where numbers are expected: one packed row (a ratio table of a
        // million entries is a thousand rows, not a million values).
        Json::Array(items) if *ty.base() == ValueType::Number && !items.is_empty() => {
            match items.iter().map(Json::as_f64).collect::<Option<Vec<f64>>>() {
                Some(row) => {
                    let len = row.len();
                    Ok(Value::List(Items::numbers(Arc::new(row), 0..len)))
                }
                None => decode_items(items, ty),
            }
        }
        Json::Array(items) => decode_items(items, ty),
        other => Err(JsonError::Expected {
            expected: ty.base().to_string(),
            found: kind(other),
        }),
    }
}

/// Decodes the items of a JSON array one by one, naming the position of a failing item.
fn decode_items(items: &[Json], ty: &ValueType) -> Result<Value, JsonError> {
    items
        .iter()
        .enumerate()
        .map(|(k, j)| {
            from_json(j, ty).map_err(|e| JsonError::At {
                index: k,
                source: Box::new(e),
            })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Value::list)
}

fn kind(j: &Json) -> &'static str {
    match j {
        Json::Null => "null",
        Json::Bool(_) => "a boolean",
        Json::Number(_) => "a number",
        Json::String(_) => "a string",
        Json::Array(_) => "an array",
        Json::Object(_) => "an object",
    }
}

/// Decodes `json` as one item of `ty`; `Ok(None)` when it has the shape of a list instead.
fn decode_item(json: &Json, ty: &ValueType) -> Result<Option<Value>, JsonError> {
    use ValueType as T;
    let found = || JsonError::Expected {
        expected: ty.to_string(),
        found: kind(json),
    };
    Ok(Some(match ty {
        T::Number => match json {
            Json::Number(n) => Value::Number(n.as_f64().ok_or_else(found)?),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Integer => match json {
            Json::Number(n) => {
                Value::Integer(as_integer(n).ok_or_else(|| JsonError::NotIntegral(n.to_string()))?)
            }
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Boolean => match json {
            Json::Bool(b) => Value::Boolean(*b),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Text => match json {
            Json::String(s) => Value::text(s),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Point | T::Vector => match json {
            Json::Array(_) => match as_vec3(json) {
                Some(p) if *ty == T::Point => Value::Point(p),
                Some(p) => Value::Vector(p),
                None => return Ok(None),
            },
            _ => return Err(found()),
        },
        T::Plane => match json {
            Json::Object(o) => Value::Plane(Arc::new(decode_plane(o)?)),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Lines => match json {
            Json::Array(items)
                if items.iter().all(|s| as_segment(s).is_some()) && !items.is_empty() =>
            {
                Value::Lines(Arc::new(items.iter().filter_map(as_segment).collect()))
            }
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Polyline => match json {
            Json::Object(o) => Value::Polyline(Arc::new(decode_polyline(o)?)),
            Json::Array(items)
                if !items.is_empty() && items.iter().all(|p| as_vec3(p).is_some()) =>
            {
                Value::Polyline(Arc::new(Polyline::open(
                    items.iter().filter_map(as_vec3).collect(),
                )))
            }
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::QuadMesh => match json {
            Json::Object(o) => Value::QuadMesh(Arc::new(decode_quad_mesh(o)?)),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Mesh => match json {
            Json::Object(o) if o.contains_key("rows") => {
                Value::QuadMesh(Arc::new(decode_quad_mesh(o)?))
            }
            Json::Object(o) => Value::Mesh(Arc::new(decode_mesh(o)?)),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Record => match json {
            Json::Object(o) => Value::Record(Arc::new(decode_record(o)?)),
            Json::Array(_) => return Ok(None),
            _ => return Err(found()),
        },
        T::Any => match json {
            Json::Bool(b) => Value::Boolean(*b),
            Json::Number(n) => Value::Number(n.as_f64().ok_or_else(found)?),
            Json::String(s) => Value::text(s),
            Json::Array(_) => match as_vec3(json) {
                Some(p) => Value::Point(p),
                None => return Ok(None),
            },
            Json::Object(o) if o.contains_key("rows") => {
                Value::QuadMesh(Arc::new(decode_quad_mesh(o)?))
            }
            Json::Object(o) if o.contains_key("points") => {
                Value::Polyline(Arc::new(decode_polyline(o)?))
            }
            Json::Object(o) if o.contains_key("faces") => Value::Mesh(Arc::new(decode_mesh(o)?)),
            Json::Object(o) if o.contains_key("normal") && o.contains_key("origin") => {
                Value::Plane(Arc::new(decode_plane(o)?))
            }
            Json::Object(o) => Value::Record(Arc::new(decode_record(o)?)),
            Json::Null => Value::Null,
        },
        T::List(inner) => return decode_item(json, inner),
    }))
}

fn as_integer(n: &serde_json::Number) -> Option<i64> {
    n.as_i64().or_else(|| {
        let x = n.as_f64()?;
        (x.fract() == 0.0 && x.abs() < 9.0e15).then_some(x as i64)
    })
}

fn as_vec3(j: &Json) -> Option<DVec3> {
    match j.as_array()?.as_slice() {
        [x, y, z] => Some(DVec3::new(x.as_f64()?, y.as_f64()?, z.as_f64()?)),
        _ => None,
    }
}

fn as_segment(j: &Json) -> Option<Line> {
    match j.as_array()?.as_slice() {
        [a, b] => Some(Line::new(as_vec3(a)?, as_vec3(b)?)),
        _ => None,
    }
}

fn malformed(message: String) -> JsonError {
    JsonError::Malformed(message)
}

fn field<'a>(o: &'a Map<String, Json>, name: &str, what: &str) -> Result<&'a Json, JsonError> {
    o.get(name)
        .ok_or_else(|| malformed(format!("{what} object needs a \"{name}\" field")))
}

fn point_list(j: &Json, what: &str) -> Result<Vec<DVec3>, JsonError> {
    let items = j
        .as_array()
        .ok_or_else(|| malformed(format!("{what} must be an array of [x, y, z]")))?;
    items
        .iter()
        .enumerate()
        .map(|(k, p)| {
            as_vec3(p).ok_or_else(|| malformed(format!("{what}[{k}] is not an [x, y, z] point")))
        })
        .collect()
}

fn decode_point(o: &Map<String, Json>, name: &str) -> Result<DVec3, JsonError> {
    as_vec3(field(o, name, "plane")?)
        .ok_or_else(|| malformed(format!("plane \"{name}\" is not [x, y, z]")))
}

fn decode_plane(o: &Map<String, Json>) -> Result<Plane, JsonError> {
    let origin = decode_point(o, "origin")?;
    let normal = decode_point(o, "normal")?;
    let plane = match o.get("x_axis").and_then(as_vec3) {
        Some(x) => Plane::from_axes(origin, x, normal.cross(x)),
        None => Plane::from_normal(origin, normal),
    };
    Ok(plane?)
}

fn decode_polyline(o: &Map<String, Json>) -> Result<Polyline, JsonError> {
    let points = point_list(field(o, "points", "polyline")?, "points")?;
    let closed = match o.get("closed") {
        None => false,
        Some(Json::Bool(b)) => *b,
        Some(_) => return Err(malformed("polyline \"closed\" must be a boolean".into())),
    };
    Ok(Polyline { points, closed })
}

fn usize_field(o: &Map<String, Json>, name: &str) -> Result<usize, JsonError> {
    field(o, name, "quad mesh")?
        .as_u64()
        .and_then(|n| usize::try_from(n).ok())
        .ok_or_else(|| {
            malformed(format!(
                "quad mesh \"{name}\" must be a non-negative integer"
            ))
        })
}

fn bool_field(o: &Map<String, Json>, name: &str) -> Result<bool, JsonError> {
    match o.get(name) {
        None => Ok(false),
        Some(Json::Bool(b)) => Ok(*b),
        Some(_) => Err(malformed(format!("quad mesh \"{name}\" must be a boolean"))),
    }
}

fn decode_quad_mesh(o: &Map<String, Json>) -> Result<QuadGrid, JsonError> {
    let rows = usize_field(o, "rows")?;
    let cols = usize_field(o, "cols")?;
    let vertices = point_list(field(o, "vertices", "quad mesh")?, "vertices")?;
    let grid = QuadGrid::new(rows, cols, vertices)?;
    Ok(grid.with_wrap(bool_field(o, "wrap_rows")?, bool_field(o, "wrap_cols")?))
}

fn decode_mesh(o: &Map<String, Json>) -> Result<PolygonMesh, JsonError> {
    let vertices = point_list(field(o, "vertices", "mesh")?, "vertices")?;
    let faces = field(o, "faces", "mesh")?
        .as_array()
        .ok_or_else(|| malformed("mesh \"faces\" must be an array".into()))?;
    let faces = faces
        .iter()
        .enumerate()
        .map(|(k, f)| {
            f.as_array()
                .and_then(|ix| {
                    ix.iter()
                        .map(|i| i.as_u64().and_then(|i| u32::try_from(i).ok()))
                        .collect()
                })
                .ok_or_else(|| {
                    malformed(format!(
                        "mesh faces[{k}] must be an array of vertex indices"
                    ))
                })
        })
        .collect::<Result<Vec<Vec<u32>>, JsonError>>()?;
    Ok(PolygonMesh::from_faces(vertices, &faces)?)
}

fn decode_record(o: &Map<String, Json>) -> Result<Record, JsonError> {
    let mut r = Record::new();
    for (k, v) in o {
        r.set(
            k.clone(),
            from_json(v, &ValueType::Any).map_err(|e| JsonError::Field {
                field: k.clone(),
                source: Box::new(e),
            })?,
        );
    }
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodes_contract_shapes() {
        let p = Value::from(Polyline::open(vec![DVec3::ZERO, DVec3::X]));
        assert_eq!(
            to_json(&p),
            json!({"points": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], "closed": false})
        );
        let g = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::Y]).unwrap();
        assert_eq!(
            to_json(&Value::from(g)),
            json!({"rows": 1, "cols": 2, "wrap_rows": false, "wrap_cols": false,
                   "vertices": [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]})
        );
        assert_eq!(to_json(&Value::Number(f64::INFINITY)), Json::Null);
        assert_eq!(
            to_json(&Value::list(vec![Value::Null, Value::Integer(3)])),
            json!([null, 3])
        );
    }

    #[test]
    fn decodes_by_port_type() {
        assert!(
            from_json(&json!([1, 2, 3]), &ValueType::Point)
                .unwrap()
                .same_as(&Value::Point(DVec3::new(1.0, 2.0, 3.0)))
        );
        let list = from_json(&json!([1, 2, 3]), &ValueType::Number).unwrap();
        assert_eq!(list.as_list().unwrap().len(), 3);
        let bare = from_json(&json!([[0, 0, 0], [1, 0, 0]]), &ValueType::Polyline).unwrap();
        assert!(matches!(bare, Value::Polyline(p) if p.points.len() == 2 && !p.closed));
        assert!(
            from_json(&json!("x"), &ValueType::Number)
                .unwrap_err()
                .to_string()
                .contains("expected number")
        );
        assert_eq!(
            from_json(&json!([[0.5, "x"], [0.5, 0.5]]), &ValueType::Number)
                .unwrap_err()
                .to_string(),
            "[0][1]: expected number, got a string"
        );
        assert!(from_json(&json!(1.5), &ValueType::Integer).is_err());
        assert_eq!(
            from_json(&json!(2.0), &ValueType::Integer).unwrap(),
            Value::Integer(2)
        );
    }

    #[test]
    fn round_trips_meshes() {
        let g = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE])
            .unwrap()
            .with_wrap(true, false);
        let v = Value::from(g);
        assert_eq!(from_json(&to_json(&v), &ValueType::QuadMesh).unwrap(), v);
        let m = Value::from(
            PolygonMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[vec![0, 1, 2]])
                .unwrap(),
        );
        assert_eq!(from_json(&to_json(&m), &ValueType::Mesh).unwrap(), m);
    }

    #[test]
    fn streamed_output_equals_the_tree_output() {
        let grid = QuadGrid::new(
            2,
            2,
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, -0.0)],
        )
        .unwrap();
        let mesh = PolygonMesh::from_faces(vec![DVec3::ZERO, DVec3::X, DVec3::Y], &[vec![0, 1, 2]])
            .unwrap();
        let values = vec![
            Value::Null,
            Value::Number(0.1),
            Value::Number(3.0),
            Value::Number(f64::NAN),
            Value::Number(f64::NEG_INFINITY),
            Value::Number(1e300),
            Value::Integer(-7),
            Value::Boolean(true),
            Value::text("a \"quoted\"\n text"),
            Value::Point(DVec3::new(1.5, -2.0, 1e-12)),
            Value::Vector(DVec3::Z),
            Value::Plane(Arc::new(Plane::from_normal(DVec3::X, DVec3::Z).unwrap())),
            Value::Lines(Arc::new(vec![Line::new(DVec3::ZERO, DVec3::X)])),
            Value::Polyline(Arc::new(Polyline::open(vec![DVec3::ZERO, DVec3::Y]))),
            Value::QuadMesh(Arc::new(grid.with_wrap(true, false))),
            Value::Mesh(Arc::new(mesh)),
            Value::List(Items::numbers(Arc::new(vec![0.5, f64::NAN, 2.0]), 1..3)),
            Value::list(vec![
                Value::list(vec![Value::Number(1.0), Value::Null]),
                Value::list(vec![]),
            ]),
            Value::Record(Arc::new(
                Record::new()
                    .with("z", 1.0)
                    .with("a", Value::list(vec![Value::text("x")])),
            )),
        ];
        for v in values {
            let mut bytes = Vec::new();
            write_json(&mut bytes, &v).unwrap();
            assert_eq!(
                String::from_utf8(bytes).unwrap(),
                to_json(&v).to_string(),
                "{v:?}"
            );
        }
    }
}
