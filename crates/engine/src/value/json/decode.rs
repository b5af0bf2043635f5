//! JSON [`Document`]s to values by the port's type. Packed number rows and point lists move into
//! the values (a list of numbers, a polyline's or a mesh's vertices) without a copy.

use std::sync::Arc;

use cnets_geometry::{Line, Plane, PolygonMesh, Polyline, QuadGrid};
use glam::DVec3;
use indexmap::IndexMap;
use serde_json::Value as Json;

use super::{Document, JsonError};
use crate::value::{Items, Record, Value, ValueType, plane_from_fields};

/// An object's fields.
type Fields = IndexMap<String, Document>;

/// Decodes a JSON tree into a value whose items have type `ty` (see [`from_document`]).
pub fn from_json(json: &Json, ty: &ValueType) -> Result<Value, JsonError> {
    from_document(Document::from(json), ty)
}

/// Decodes a document into a value whose items have type `ty` (or nested lists of such items).
/// `null` decodes to [`Value::Null`]. The error says what was expected and what was found.
pub fn from_document(doc: Document, ty: &ValueType) -> Result<Value, JsonError> {
    if doc == Document::Null {
        return Ok(Value::Null);
    }
    let doc = match decode_item(doc, ty.base())? {
        Item::Value(v) => return Ok(v),
        Item::List(doc) => doc,
    };
    let number = *ty.base() == ValueType::Number;
    // On a port of type `any` a row packs only when none of its numbers was written as an integer
    // (those stay integers, as a graph file's `[1, 2]` does).
    let any = *ty.base() == ValueType::Any;
    match doc {
        // An array of numbers where numbers are expected: one packed row (a ratio table of a
        // million entries is a thousand rows, not a million values).
        Document::Numbers(row, ints) if number || (any && ints.none()) => Ok(packed(row)),
        Document::Triple(row, ints) if number || (any && ints.none()) => Ok(packed(row.to_vec())),
        // Triples where numbers are expected: rows of one shared table.
        Document::Points(points, ints) if number || (any && ints.none()) => Ok(rows_of(&points)),
        other if other.is_array() => decode_items(other, ty),
        other => Err(JsonError::Expected {
            expected: ty.base().to_string(),
            found: other.kind(),
        }),
    }
}

fn packed(row: Vec<f64>) -> Value {
    let len = row.len();
    Value::List(Items::numbers(Arc::new(row), 0..len))
}

/// Triples of numbers as lists of three numbers, packed rows of one table.
fn rows_of(points: &[DVec3]) -> Value {
    let table: Arc<Vec<f64>> = Arc::new(points.iter().flat_map(|p| p.to_array()).collect());
    Value::list(
        (0..points.len())
            .map(|k| Value::List(Items::numbers(table.clone(), 3 * k..3 * k + 3)))
            .collect(),
    )
}

/// Decodes the items of an array one by one, naming the position of a failing item.
fn decode_items(doc: Document, ty: &ValueType) -> Result<Value, JsonError> {
    let items = doc.into_items().expect("decode_items is given arrays");
    items
        .enumerate()
        .map(|(k, item)| {
            from_document(item, ty).map_err(|e| JsonError::At {
                index: k,
                source: Box::new(e),
            })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Value::list)
}

/// One item of a type, or the document handed back when it has the shape of a list instead.
enum Item {
    Value(Value),
    List(Document),
}

/// Decodes `doc` as one item of `ty`, or hands it back when it is a list of them.
fn decode_item(doc: Document, ty: &ValueType) -> Result<Item, JsonError> {
    use ValueType as T;
    let found = |doc: &Document| JsonError::Expected {
        expected: ty.to_string(),
        found: doc.kind(),
    };
    let list_or_error = |doc: Document| {
        if doc.is_array() {
            Ok(Item::List(doc))
        } else {
            Err(found(&doc))
        }
    };
    Ok(Item::Value(match (ty, doc) {
        (T::Number, doc) => match doc.as_f64() {
            Some(x) => Value::Number(x),
            None => return list_or_error(doc),
        },
        (T::Integer, Document::Integer(i)) => Value::Integer(i),
        (T::Integer, Document::Number(x)) => Value::Integer(as_integer(x)?),
        (T::Boolean, Document::Bool(b)) => Value::Boolean(b),
        (T::Text, Document::Text(s)) => Value::text(&s),
        (T::Point, Document::Triple(t, _)) => Value::Point(DVec3::from_array(t)),
        (T::Vector, Document::Triple(t, _)) => Value::Vector(DVec3::from_array(t)),
        (T::Plane, Document::Object(o)) => Value::Plane(Arc::new(decode_plane(&o)?)),
        (T::Lines, Document::Array(items)) if is_segments(&items) => {
            Value::Lines(Arc::new(items.iter().filter_map(as_segment).collect()))
        }
        (T::Polyline, Document::Object(o)) => Value::Polyline(Arc::new(decode_polyline(*o)?)),
        (T::Polyline, Document::Points(points, _)) => {
            Value::Polyline(Arc::new(Polyline::open(points)))
        }
        (T::QuadMesh, Document::Object(o)) => Value::QuadMesh(Arc::new(decode_quad_mesh(*o)?)),
        (T::Mesh, Document::Object(o)) if o.contains_key("rows") => {
            Value::QuadMesh(Arc::new(decode_quad_mesh(*o)?))
        }
        (T::Mesh, Document::Object(o)) => Value::Mesh(Arc::new(decode_mesh(*o)?)),
        (T::Record, Document::Object(o)) => Value::Record(Arc::new(decode_record(*o)?)),
        (T::Any, doc) => return decode_any(doc),
        (T::List(inner), doc) => return decode_item(doc, inner),
        (_, doc) => return list_or_error(doc),
    }))
}

/// An item of any type, told apart by its shape. Every array is a list, as in a graph file and in
/// Python (`[1, 2, 3]` is three numbers, not a point: JSON has no point literal of its own), and a
/// number written as an integer is an integer.
fn decode_any(doc: Document) -> Result<Item, JsonError> {
    Ok(Item::Value(match doc {
        Document::Null => Value::Null,
        Document::Bool(b) => Value::Boolean(b),
        Document::Number(x) => Value::Number(x),
        Document::Integer(i) => Value::Integer(i),
        Document::Text(s) => Value::text(&s),
        Document::Object(o) if o.contains_key("rows") => {
            Value::QuadMesh(Arc::new(decode_quad_mesh(*o)?))
        }
        Document::Object(o) if o.contains_key("points") => {
            Value::Polyline(Arc::new(decode_polyline(*o)?))
        }
        Document::Object(o) if o.contains_key("faces") => Value::Mesh(Arc::new(decode_mesh(*o)?)),
        Document::Object(o) if o.contains_key("normal") && o.contains_key("origin") => {
            Value::Plane(Arc::new(decode_plane(&o)?))
        }
        Document::Object(o) => Value::Record(Arc::new(decode_record(*o)?)),
        list => return Ok(Item::List(list)),
    }))
}

/// An integral number of at most 9·10¹⁵ in magnitude as an integer.
fn as_integer(x: f64) -> Result<i64, JsonError> {
    if x.fract() == 0.0 && x.abs() < 9.0e15 {
        Ok(x as i64)
    } else {
        let text = serde_json::Number::from_f64(x).map_or_else(|| x.to_string(), |n| n.to_string());
        Err(JsonError::NotIntegral(text))
    }
}

fn is_segments(items: &[Document]) -> bool {
    !items.is_empty() && items.iter().all(|s| as_segment(s).is_some())
}

fn as_segment(doc: &Document) -> Option<Line> {
    match doc {
        Document::Points(p, _) if p.len() == 2 => Some(Line::new(p[0], p[1])),
        _ => None,
    }
}

fn malformed(message: String) -> JsonError {
    JsonError::Malformed(message)
}

fn field<'a>(o: &'a Fields, name: &str, what: &str) -> Result<&'a Document, JsonError> {
    o.get(name)
        .ok_or_else(|| malformed(format!("{what} object needs a \"{name}\" field")))
}

fn take_field(o: &mut Fields, name: &str, what: &str) -> Result<Document, JsonError> {
    o.swap_remove(name)
        .ok_or_else(|| malformed(format!("{what} object needs a \"{name}\" field")))
}

/// An array of `[x, y, z]` points (a packed one is moved, not copied).
fn point_list(doc: Document, what: &str) -> Result<Vec<DVec3>, JsonError> {
    match doc {
        Document::Points(points, _) => Ok(points),
        other => other
            .into_items()
            .ok_or_else(|| malformed(format!("{what} must be an array of [x, y, z]")))?
            .enumerate()
            .map(|(k, p)| {
                p.as_vec3()
                    .ok_or_else(|| malformed(format!("{what}[{k}] is not an [x, y, z] point")))
            })
            .collect(),
    }
}

fn decode_point(o: &Fields, name: &str) -> Result<DVec3, JsonError> {
    field(o, name, "plane")?
        .as_vec3()
        .ok_or_else(|| malformed(format!("plane \"{name}\" is not [x, y, z]")))
}

fn decode_plane(o: &Fields) -> Result<Plane, JsonError> {
    let origin = decode_point(o, "origin")?;
    let normal = decode_point(o, "normal")?;
    let axis = |name: &str| o.get(name).and_then(Document::as_vec3);
    Ok(plane_from_fields(
        origin,
        Some(normal),
        axis("x_axis"),
        axis("y_axis"),
    )?)
}

fn decode_polyline(mut o: Fields) -> Result<Polyline, JsonError> {
    let points = point_list(take_field(&mut o, "points", "polyline")?, "points")?;
    let closed = match o.get("closed") {
        None => false,
        Some(Document::Bool(b)) => *b,
        Some(_) => return Err(malformed("polyline \"closed\" must be a boolean".into())),
    };
    Ok(Polyline { points, closed })
}

/// A non-negative integral number as an index or a count.
fn as_index(doc: &Document) -> Option<u64> {
    match *doc {
        Document::Integer(i) => u64::try_from(i).ok(),
        Document::Number(x) if x >= 0.0 && x.fract() == 0.0 && x <= (1u64 << 53) as f64 => {
            Some(x as u64)
        }
        _ => None,
    }
}

fn usize_field(o: &Fields, name: &str) -> Result<usize, JsonError> {
    as_index(field(o, name, "quad mesh")?)
        .and_then(|n| usize::try_from(n).ok())
        .ok_or_else(|| {
            malformed(format!(
                "quad mesh \"{name}\" must be a non-negative integer"
            ))
        })
}

fn bool_field(o: &Fields, name: &str) -> Result<bool, JsonError> {
    match o.get(name) {
        None => Ok(false),
        Some(Document::Bool(b)) => Ok(*b),
        Some(_) => Err(malformed(format!("quad mesh \"{name}\" must be a boolean"))),
    }
}

fn decode_quad_mesh(mut o: Fields) -> Result<QuadGrid, JsonError> {
    let rows = usize_field(&o, "rows")?;
    let cols = usize_field(&o, "cols")?;
    let (wrap_rows, wrap_cols) = (bool_field(&o, "wrap_rows")?, bool_field(&o, "wrap_cols")?);
    let vertices = point_list(take_field(&mut o, "vertices", "quad mesh")?, "vertices")?;
    let grid = QuadGrid::new(rows, cols, vertices)?;
    Ok(grid.with_wrap(wrap_rows, wrap_cols))
}

fn decode_mesh(mut o: Fields) -> Result<PolygonMesh, JsonError> {
    let vertices = point_list(take_field(&mut o, "vertices", "mesh")?, "vertices")?;
    let faces = take_field(&mut o, "faces", "mesh")?
        .into_items()
        .ok_or_else(|| malformed("mesh \"faces\" must be an array".into()))?;
    let faces = faces
        .enumerate()
        .map(|(k, face)| {
            face.into_items()
                .and_then(|ix| {
                    ix.map(|i| as_index(&i).and_then(|i| u32::try_from(i).ok()))
                        .collect()
                })
                .ok_or_else(|| {
                    malformed(format!(
                        "mesh faces[{k}] must be an array of vertex indices"
                    ))
                })
        })
        .collect::<Result<Vec<Vec<u32>>, JsonError>>()?;
    let mut mesh = PolygonMesh::from_faces(vertices, &faces)?;
    // Named parts (a joined structure): optional `parts` (names) and `face_parts` (a part a face).
    if let Some(names) = o.shift_remove("parts") {
        let names = names
            .into_items()
            .and_then(|items| {
                items
                    .map(|d| match d {
                        Document::Text(t) => Some(t),
                        _ => None,
                    })
                    .collect::<Option<Vec<String>>>()
            })
            .ok_or_else(|| malformed("mesh \"parts\" must be an array of names".into()))?;
        let of_face = take_field(&mut o, "face_parts", "mesh with parts")?
            .into_items()
            .and_then(|ix| {
                ix.map(|i| as_index(&i).and_then(|i| u32::try_from(i).ok()))
                    .collect::<Option<Vec<u32>>>()
            })
            .ok_or_else(|| {
                malformed("mesh \"face_parts\" must be an array of part indices".into())
            })?;
        mesh.parts = cnets_geometry::MeshParts { names, of_face };
        if !mesh.parts.fits(mesh.face_count()) {
            return Err(malformed(format!(
                "mesh \"face_parts\" must name a part of \"parts\" for each of its {} faces",
                mesh.face_count()
            )));
        }
    }
    Ok(mesh)
}

fn decode_record(o: Fields) -> Result<Record, JsonError> {
    let mut r = Record::new();
    for (k, v) in o {
        let value = from_document(v, &ValueType::Any).map_err(|e| JsonError::Field {
            field: k.clone(),
            source: Box::new(e),
        })?;
        r.set(k, value);
    }
    Ok(r)
}
