//! Python objects ↔ engine values, without a Python object per vertex: numpy arrays become packed
//! lists, polylines and quad meshes in one copy, and numeric lists, tables and meshes come back as
//! numpy arrays.
//!
//! In: `None`, `bool`, `int`, `float`, `str`, numpy arrays and nested sequences (read by the port's
//! type: an `(n, 3)` array is a polyline on a polyline port, a list of points on a point port, rows
//! of numbers elsewhere), objects with `points` and `closed` (`cnets.Polyline`), with `vertices` of
//! shape `(N, M, 3)` (`cnets.QuadMesh`, `cnets.ConeNet`), with `vertices` and `faces`
//! (`cnets.PolygonMesh`), and dicts (records; planes on plane ports). Every array is checked
//! against the memory budget before it is copied.
//! Out: see [`to_py`] and [`to_py_typed`].

use std::sync::Arc;

use cnets_engine::budget::bytes_of;
use cnets_engine::value::{Packed, plane_from_fields};
use cnets_engine::{Items, MemoryBudget, Record, Value, ValueType};
use cnets_geometry::{DVec3, Line, PolygonMesh, Polyline, QuadGrid};
use numpy::{
    PyArray1, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// How deep nested Python sequences may go (a self-containing list would recurse forever).
const MAX_DEPTH: usize = 64;

/// Converts a Python object to a value for a port of item type `ty`. Arrays are checked against
/// `budget` before they are copied: a broadcast view of 10¹⁰ numbers fails with what it would
/// need at once, without allocating.
pub fn to_value(
    obj: &Bound<'_, PyAny>,
    ty: &ValueType,
    budget: &MemoryBudget,
) -> Result<Value, String> {
    In { budget }.value(obj, ty.base(), 0)
}

/// The conversion of inputs under a memory budget.
struct In<'a> {
    budget: &'a MemoryBudget,
}

impl In<'_> {
    fn value(&self, obj: &Bound<'_, PyAny>, ty: &ValueType, depth: usize) -> Result<Value, String> {
        if depth > MAX_DEPTH {
            return Err(format!("nested more than {MAX_DEPTH} deep"));
        }
        if obj.is_none() {
            return Ok(Value::Null);
        }
        if obj.is_instance_of::<PyBool>() {
            return Ok(Value::Boolean(obj.extract::<bool>().map_err(err)?));
        }
        if obj.is_instance_of::<PyInt>() {
            return match obj.extract::<i64>() {
                Ok(i) if *ty == ValueType::Number => Ok(Value::Number(i as f64)),
                Ok(i) => Ok(Value::Integer(i)),
                Err(_) => Err("an integer too large for 64 bits".to_string()),
            };
        }
        if obj.is_instance_of::<PyFloat>() {
            return Ok(Value::Number(obj.extract::<f64>().map_err(err)?));
        }
        if obj.is_instance_of::<PyString>() {
            return Ok(Value::text(obj.extract::<String>().map_err(err)?));
        }
        if let Ok(array) = obj.cast::<PyUntypedArray>() {
            let (shape, data) = self.array_f64(array)?;
            return shaped_value(&shape, &data, ty);
        }
        if let Ok(dict) = obj.cast::<PyDict>() {
            return self.dict(dict, ty, depth);
        }
        if obj.hasattr("points").map_err(err)? && obj.hasattr("closed").map_err(err)? {
            let points = self.points(&obj.getattr("points").map_err(err)?, "points")?;
            let closed = obj
                .getattr("closed")
                .and_then(|c| c.is_truthy())
                .map_err(err)?;
            return Ok(Value::from(Polyline { points, closed }));
        }
        if obj.hasattr("vertices").map_err(err)? {
            return self.mesh(obj);
        }
        if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
            return self.sequence(obj, ty, depth);
        }
        Err(format!("cannot use a {} here", type_name(obj)))
    }

    /// The contents of a numeric numpy array (any numeric dtype, any strides) as f64 in row-major
    /// order, with its shape — after checking that the copy fits the budget.
    fn array_f64(
        &self,
        array: &Bound<'_, PyUntypedArray>,
    ) -> Result<(Vec<usize>, Vec<f64>), String> {
        let kind = array.dtype().kind();
        if !matches!(kind, b'f' | b'i' | b'u' | b'b') {
            return Err(format!(
                "a numpy array of dtype {} (expected numbers)",
                array
                    .dtype()
                    .str()
                    .map_or_else(|_| "?".into(), |s| s.to_string())
            ));
        }
        let shape = array.shape().to_vec();
        let count = shape
            .iter()
            .fold(1u128, |n, &d| n.saturating_mul(d as u128));
        self.budget
            .check(
                bytes_of(count, 8),
                0,
                &format!("an array of shape {shape:?}"),
            )
            .map_err(|e| e.to_string())?;
        let converted;
        let typed = match array.cast::<PyArrayDyn<f64>>() {
            Ok(a) => a,
            Err(_) => {
                converted = array.call_method1("astype", ("float64",)).map_err(err)?;
                converted
                    .cast::<PyArrayDyn<f64>>()
                    .map_err(|e| e.to_string())?
            }
        };
        let readonly = typed.try_readonly().map_err(|e| e.to_string())?;
        let data = match readonly.as_slice() {
            Ok(s) => s.to_vec(),
            Err(_) => readonly.as_array().iter().copied().collect(),
        };
        Ok((shape, data))
    }

    /// Any array-like of numbers (numpy array or nested sequences) as shape and data.
    fn numeric(&self, obj: &Bound<'_, PyAny>) -> Result<(Vec<usize>, Vec<f64>), String> {
        if let Ok(array) = obj.cast::<PyUntypedArray>() {
            return self.array_f64(array);
        }
        let np = obj.py().import("numpy").map_err(err)?;
        let array = np
            .call_method1("asarray", (obj, "float64"))
            .map_err(|e| format!("not an array of numbers ({e})"))?;
        let array = array.cast::<PyUntypedArray>().map_err(|e| e.to_string())?;
        self.array_f64(array)
    }

    /// Points from an `(n, 3)` array-like.
    fn points(&self, obj: &Bound<'_, PyAny>, what: &str) -> Result<Vec<DVec3>, String> {
        let (shape, data) = self.numeric(obj).map_err(|e| format!("{what}: {e}"))?;
        match shape.as_slice() {
            [_, 3] => Ok(vec3s(&data)),
            [0] => Ok(Vec::new()),
            _ => Err(format!(
                "{what}: expected an (n, 3) array, got shape {shape:?}"
            )),
        }
    }

    /// A dict: a plane on plane ports, else a record.
    fn dict(
        &self,
        dict: &Bound<'_, PyDict>,
        ty: &ValueType,
        depth: usize,
    ) -> Result<Value, String> {
        if *ty == ValueType::Plane {
            let get = |name: &str| -> Result<Option<DVec3>, String> {
                match dict.get_item(name).map_err(err)? {
                    Some(v) if !v.is_none() => {
                        let (shape, data) = self.numeric(&v)?;
                        if shape != [3] {
                            return Err(format!("plane {name}: expected 3 numbers"));
                        }
                        Ok(Some(DVec3::from_slice(&data)))
                    }
                    _ => Ok(None),
                }
            };
            let origin = get("origin")?.unwrap_or(DVec3::ZERO);
            let (normal, x, y) = (get("normal")?, get("x_axis")?, get("y_axis")?);
            if normal.is_none() && (x.is_none() || y.is_none()) {
                return Err("a plane needs a normal, or x_axis and y_axis".to_string());
            }
            // The engine's one rule (as JSON and graph files read planes): a given orthonormal
            // frame is kept exactly.
            return plane_from_fields(origin, normal, x, y)
                .map(Value::from)
                .map_err(|e| e.to_string());
        }
        let mut record = Record::new();
        for (k, v) in dict.iter() {
            let name = k
                .extract::<String>()
                .map_err(|_| "record keys must be strings".to_string())?;
            let value = self
                .value(&v, &ValueType::Any, depth + 1)
                .map_err(|e| format!("['{name}']: {e}"))?;
            record.set(name, value);
        }
        Ok(Value::from(record))
    }

    /// An object with `vertices`: `(N, M, 3)` is a quad mesh (with `wrap_rows` / `wrap_cols` when
    /// it has them); `(V, 3)` with `faces` a polygon mesh.
    fn mesh(&self, obj: &Bound<'_, PyAny>) -> Result<Value, String> {
        let (shape, data) = self
            .numeric(&obj.getattr("vertices").map_err(err)?)
            .map_err(|e| format!("vertices: {e}"))?;
        let flag = |name: &str| -> Result<bool, String> {
            match obj.getattr(name) {
                Ok(v) => v.is_truthy().map_err(err),
                Err(_) => Ok(false),
            }
        };
        match shape.as_slice() {
            [rows, cols, 3] => {
                let grid = QuadGrid::new(*rows, *cols, vec3s(&data))
                    .map_err(|e| e.to_string())?
                    .with_wrap(flag("wrap_rows")?, flag("wrap_cols")?);
                grid.validate().map_err(|e| e.to_string())?;
                Ok(Value::from(grid))
            }
            [_, 3] => {
                let faces = obj
                    .getattr("faces")
                    .map_err(|_| "a mesh of (V, 3) vertices needs faces".to_string())?;
                let faces: Vec<Vec<i64>> = faces
                    .extract()
                    .or_else(|_| faces.call_method0("tolist").and_then(|l| l.extract()))
                    .map_err(|_| "faces must be lists of vertex indices".to_string())?;
                let count = data.len() / 3;
                let mut indices = Vec::new();
                let mut face_starts = Vec::new();
                for (k, face) in faces.iter().enumerate() {
                    face_starts.push(indices.len() as u32);
                    for &i in face {
                        if i < 0 || i as usize >= count {
                            return Err(format!("faces[{k}]: vertex {i} is not in 0..{count}"));
                        }
                        indices.push(i as u32);
                    }
                }
                let mut mesh = PolygonMesh {
                    vertices: vec3s(&data),
                    indices,
                    face_starts,
                    parts: Default::default(),
                    classes: Vec::new(),
                };
                let names: Option<Vec<String>> = obj
                    .getattr("parts")
                    .ok()
                    .filter(|p| !p.is_none())
                    .map(|p| p.extract())
                    .transpose()
                    .map_err(|_| "parts must be a list of names".to_string())?;
                if let Some(names) = names {
                    let of_face: Vec<u32> = obj
                        .getattr("face_parts")
                        .and_then(|p| p.extract())
                        .map_err(|_| "face_parts must be a list of part indices".to_string())?;
                    mesh.parts = cnets_geometry::MeshParts { names, of_face };
                    if !mesh.parts.fits(mesh.face_count()) {
                        return Err(format!(
                            "face_parts: one index into parts a face ({} faces)",
                            mesh.face_count()
                        ));
                    }
                }
                Ok(Value::from(mesh))
            }
            _ => Err(format!(
                "vertices: expected shape (N, M, 3) or (V, 3), got {shape:?}"
            )),
        }
    }

    /// A list or tuple: a point (3 numbers) on point ports, a polyline (points) on polyline ports,
    /// a numeric row packed (on `any` ports only a row of floats: ints stay integers), anything
    /// else item by item.
    fn sequence(
        &self,
        obj: &Bound<'_, PyAny>,
        ty: &ValueType,
        depth: usize,
    ) -> Result<Value, String> {
        use ValueType as T;
        let items: Vec<Bound<'_, PyAny>> = obj
            .try_iter()
            .map_err(err)?
            .collect::<PyResult<_>>()
            .map_err(err)?;
        let is_number = |o: &Bound<'_, PyAny>| {
            (o.is_instance_of::<PyFloat>() || o.is_instance_of::<PyInt>())
                && !o.is_instance_of::<PyBool>()
        };
        let all_numbers = !items.is_empty() && items.iter().all(is_number);
        if all_numbers {
            let row: Vec<f64> = items
                .iter()
                .map(|o| o.extract::<f64>().map_err(err))
                .collect::<Result<_, _>>()?;
            return match ty {
                T::Point | T::Vector if row.len() == 3 => {
                    let p = DVec3::from_slice(&row);
                    Ok(if *ty == T::Point {
                        Value::Point(p)
                    } else {
                        Value::Vector(p)
                    })
                }
                // On `any` ports ints stay integers (as `[1, 2]` in a graph file or JSON): only
                // a row of floats is packed there.
                T::Number => {
                    let n = row.len();
                    Ok(Value::List(Items::numbers(Arc::new(row), 0..n)))
                }
                T::Any if !items.iter().any(|o| o.is_instance_of::<PyInt>()) => {
                    let n = row.len();
                    Ok(Value::List(Items::numbers(Arc::new(row), 0..n)))
                }
                _ => items
                    .iter()
                    .map(|o| self.value(o, ty, depth + 1))
                    .collect::<Result<Vec<_>, _>>()
                    .map(Value::list),
            };
        }
        if matches!(ty, T::Polyline | T::QuadMesh | T::Lines)
            && let Ok((shape, data)) = self.numeric(obj)
            && shape.len() >= 2
            && shape.last() == Some(&3)
        {
            return shaped_value(&shape, &data, ty);
        }
        items
            .iter()
            .enumerate()
            .map(|(k, o)| self.value(o, ty, depth + 1).map_err(|e| at_index(k, &e)))
            .collect::<Result<Vec<_>, _>>()
            .map(Value::list)
    }
}

fn err(e: PyErr) -> String {
    e.to_string()
}

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map_or_else(|_| "value".to_string(), |n| n.to_string())
}

fn vec3s(data: &[f64]) -> Vec<DVec3> {
    data.chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect()
}

fn shaped_value(shape: &[usize], data: &[f64], ty: &ValueType) -> Result<Value, String> {
    use ValueType as T;
    let sub = |data: &[f64], shape: &[usize]| -> Result<Value, String> {
        let n = shape[0];
        let stride: usize = shape[1..].iter().product();
        (0..n)
            .map(|k| shaped_value(&shape[1..], &data[k * stride..(k + 1) * stride], ty))
            .collect::<Result<Vec<_>, _>>()
            .map(Value::list)
    };
    match (ty, shape) {
        (_, []) => Ok(match ty {
            T::Integer if data[0].fract() == 0.0 && data[0].abs() < 9.0e15 => {
                Value::Integer(data[0] as i64)
            }
            _ => Value::Number(data[0]),
        }),
        (T::Point, [3]) => Ok(Value::Point(DVec3::from_slice(data))),
        (T::Vector, [3]) => Ok(Value::Vector(DVec3::from_slice(data))),
        (T::Polyline, [_, 3]) => Ok(Value::from(Polyline::open(vec3s(data)))),
        (T::QuadMesh | T::Mesh, [rows, cols, 3]) => QuadGrid::new(*rows, *cols, vec3s(data))
            .map(Value::from)
            .map_err(|e| e.to_string()),
        (T::Lines, [_, 2, 3]) => Ok(Value::Lines(Arc::new(
            vec3s(data)
                .chunks_exact(2)
                .map(|p| Line::new(p[0], p[1]))
                .collect(),
        ))),
        (T::Point | T::Vector | T::Polyline | T::QuadMesh | T::Lines, [_, ..])
            if shape.len() > 1 =>
        {
            sub(data, shape)
        }
        (_, [n]) => Ok(Value::List(Items::numbers(Arc::new(data.to_vec()), 0..*n))),
        // Rows of numbers share one table.
        (_, [rows, cols]) if !matches!(ty, T::Point | T::Vector) => {
            let table = Arc::new(data.to_vec());
            Ok(Value::list(
                (0..*rows)
                    .map(|i| Value::List(Items::numbers(table.clone(), i * cols..(i + 1) * cols)))
                    .collect(),
            ))
        }
        _ => sub(data, shape),
    }
}

fn at_index(k: usize, error: &str) -> String {
    if error.starts_with('[') {
        format!("[{k}]{error}")
    } else {
        format!("[{k}]: {error}")
    }
}

// ---------------------------------------------------------------------------------------------
// Out

/// Converts a value to Python: numbers, `int`, `bool`, `str`, `None`; points and vectors as `(3,)`
/// arrays; lists of numbers, of points (with `None` as a NaN row) and rectangular nests of them
/// as one numpy array; lines as `(K, 2, 3)`; planes and records as dicts; polylines, quad meshes
/// and polygon meshes as `cnets.Polyline`, `cnets.QuadMesh`, `cnets.PolygonMesh`; other lists as
/// Python lists.
pub fn to_py<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Number(x) => x.into_pyobject(py)?.into_any(),
        Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Text(t) => PyString::new(py, t).into_any(),
        Value::Point(p) | Value::Vector(p) => PyArray1::from_slice(py, &p.to_array()).into_any(),
        Value::Plane(p) => {
            let d = PyDict::new(py);
            d.set_item("origin", PyArray1::from_slice(py, &p.origin.to_array()))?;
            d.set_item("x_axis", PyArray1::from_slice(py, &p.x_axis.to_array()))?;
            d.set_item("y_axis", PyArray1::from_slice(py, &p.y_axis.to_array()))?;
            d.set_item("normal", PyArray1::from_slice(py, &p.normal.to_array()))?;
            d.into_any()
        }
        Value::Lines(lines) => {
            let flat: Vec<f64> = lines
                .iter()
                .flat_map(|l| l.start.to_array().into_iter().chain(l.end.to_array()))
                .collect();
            PyArray1::from_vec(py, flat)
                .reshape([lines.len(), 2, 3])?
                .into_any()
        }
        Value::Polyline(p) => {
            types(py, "Polyline")?.call1((points_array(py, &p.points)?, p.closed))?
        }
        Value::QuadMesh(g) => quad_mesh(py, g)?,
        Value::Mesh(m) => {
            let faces = PyList::empty(py);
            for k in 0..m.face_starts.len() {
                let start = m.face_starts[k] as usize;
                let end = m
                    .face_starts
                    .get(k + 1)
                    .map_or(m.indices.len(), |&e| e as usize);
                let face = m.indices.get(start..end).unwrap_or_default();
                faces.append(PyList::new(py, face)?)?;
            }
            if m.parts.is_empty() {
                types(py, "PolygonMesh")?.call1((points_array(py, &m.vertices)?, faces))?
            } else {
                types(py, "PolygonMesh")?.call1((
                    points_array(py, &m.vertices)?,
                    faces,
                    m.parts.names.clone(),
                    m.parts.of_face.clone(),
                ))?
            }
        }
        Value::Record(r) => {
            let d = PyDict::new(py);
            for (name, v) in r.fields() {
                d.set_item(name, to_py(py, v)?)?;
            }
            d.into_any()
        }
        Value::List(items) => list_to_py(py, items, false)?,
    })
}

/// Converts an output of a port of type `ty` to Python as [`to_py`] does, except that on ports of
/// points or vectors a list is always an array of points: `(n, 3)` with NaN rows for missing
/// points (apices at infinity), even when every point is missing or the list is empty.
pub fn to_py_typed<'py>(
    py: Python<'py>,
    value: &Value,
    ty: &ValueType,
) -> PyResult<Bound<'py, PyAny>> {
    match value {
        Value::List(items) if matches!(ty.base(), ValueType::Point | ValueType::Vector) => {
            list_to_py(py, items, true)
        }
        _ => to_py(py, value),
    }
}

/// A quad mesh as `cnets.QuadMesh(vertices (rows, cols, 3), wrap_rows, wrap_cols)`.
pub fn quad_mesh<'py>(py: Python<'py>, g: &QuadGrid) -> PyResult<Bound<'py, PyAny>> {
    let vertices = PyArray1::from_vec(py, flatten(&g.vertices)).reshape([g.rows, g.cols, 3])?;
    types(py, "QuadMesh")?.call1((vertices, g.wrap_rows, g.wrap_cols))
}

fn types<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("cnets._types")?.getattr(name)
}

fn flatten(points: &[DVec3]) -> Vec<f64> {
    let mut flat = Vec::with_capacity(points.len() * 3);
    for p in points {
        flat.extend_from_slice(&[p.x, p.y, p.z]);
    }
    flat
}

fn points_array<'py>(py: Python<'py>, points: &[DVec3]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, flatten(points))
        .reshape([points.len(), 3])?
        .into_any())
}

/// The shape of a value as a numeric array, when it is one: numbers `[]`, points `[3]`, lists of
/// equal shapes `[n, …]`. `None` for anything else (text, meshes, ragged lists, empty lists).
/// `ints` stays true while every leaf is an integer. A `Null` item takes its siblings' shape when
/// they are points (an apex at infinity: a NaN row). With `points` (the port carries points or
/// vectors) a `Null` is a point even without siblings, and an empty list a list of no points.
fn shape_of(v: &Value, ints: &mut bool, points: bool) -> Option<Vec<usize>> {
    match v {
        Value::Number(_) => {
            *ints = false;
            Some(Vec::new())
        }
        Value::Integer(_) => Some(Vec::new()),
        Value::Point(_) | Value::Vector(_) => {
            *ints = false;
            Some(vec![3])
        }
        Value::Null if points => {
            *ints = false;
            Some(vec![3])
        }
        Value::List(items) => {
            if let Some(packed) = items.as_packed() {
                return match packed {
                    Packed::Numbers { range, .. } if !range.is_empty() => {
                        *ints = false;
                        Some(vec![range.len()])
                    }
                    Packed::Vectors { range, .. } if !range.is_empty() || points => {
                        *ints = false;
                        Some(vec![range.len(), 3])
                    }
                    _ => None,
                };
            }
            if items.is_empty() && points {
                *ints = false;
                return Some(vec![0, 3]);
            }
            let mut inner: Option<Vec<usize>> = None;
            let mut nulls = false;
            for item in items.iter() {
                if item.is_null() && !points {
                    nulls = true;
                    continue;
                }
                let s = shape_of(item, ints, points)?;
                match &inner {
                    None => inner = Some(s),
                    Some(prev) if *prev == s => {}
                    Some(_) => return None,
                }
            }
            let inner = inner?;
            if nulls {
                if inner != [3] {
                    return None;
                }
                *ints = false;
            }
            let mut shape = vec![items.len()];
            shape.extend(inner);
            Some(shape)
        }
        _ => None,
    }
}

fn fill(v: &Value, out: &mut Vec<f64>) {
    match v {
        Value::Number(x) => out.push(*x),
        Value::Integer(i) => out.push(*i as f64),
        Value::Point(p) | Value::Vector(p) => out.extend_from_slice(&[p.x, p.y, p.z]),
        Value::Null => out.extend_from_slice(&[f64::NAN; 3]),
        Value::List(items) => match items.as_packed() {
            Some(Packed::Numbers { table, range }) => out.extend_from_slice(&table[range.clone()]),
            Some(Packed::Vectors { table, range }) => {
                for p in &table[range.clone()] {
                    out.extend_from_slice(&[p.x, p.y, p.z]);
                }
            }
            _ => items.iter().for_each(|item| fill(item, out)),
        },
        _ => {}
    }
}

fn fill_ints(v: &Value, out: &mut Vec<i64>) {
    match v {
        Value::Integer(i) => out.push(*i),
        Value::List(items) => items.iter().for_each(|item| fill_ints(item, out)),
        _ => {}
    }
}

fn list_to_py<'py>(py: Python<'py>, items: &Items, points: bool) -> PyResult<Bound<'py, PyAny>> {
    let list = Value::List(items.clone());
    let mut ints = true;
    if let Some(shape) = shape_of(&list, &mut ints, points) {
        if ints {
            let mut data = Vec::with_capacity(shape.iter().product());
            fill_ints(&list, &mut data);
            return Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any());
        }
        let mut data = Vec::with_capacity(shape.iter().product());
        fill(&list, &mut data);
        return Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any());
    }
    if let Some(Packed::Labels {
        table,
        range,
        labels,
    }) = items.as_packed()
    {
        let texts: Vec<Bound<'py, PyAny>> = labels
            .iter()
            .map(|l| to_py(py, l))
            .collect::<PyResult<_>>()?;
        let none = py.None().into_bound(py);
        let out = table[range.clone()]
            .iter()
            .map(|&c| texts.get(c as usize).unwrap_or(&none));
        return Ok(PyList::new(py, out)?.into_any());
    }
    let out = PyList::empty(py);
    for item in items.iter() {
        out.append(to_py(py, item)?)?;
    }
    Ok(out.into_any())
}

/// A list of packed label rows (the construction nodes' `configurations`) as `(codes, labels)`:
/// an (N, K) uint8 array of codes and the list of label texts they index, without a Python object
/// per label. `None` when the value is not such a list.
pub fn label_table<'py>(py: Python<'py>, value: &Value) -> PyResult<Option<Bound<'py, PyAny>>> {
    let Value::List(rows) = value else {
        return Ok(None);
    };
    let mut codes = Vec::new();
    let mut shared: Option<&Arc<[Value]>> = None;
    let mut width = None;
    for row in rows.iter() {
        let Value::List(items) = row else {
            return Ok(None);
        };
        let Some(Packed::Labels {
            table,
            range,
            labels,
        }) = items.as_packed()
        else {
            return Ok(None);
        };
        if *width.get_or_insert(range.len()) != range.len() {
            return Ok(None);
        }
        match shared {
            None => shared = Some(labels),
            Some(s) if Arc::ptr_eq(s, labels) || s[..] == labels[..] => {}
            Some(_) => return Ok(None),
        }
        codes.extend_from_slice(&table[range.clone()]);
    }
    let (Some(labels), Some(width)) = (shared, width) else {
        return Ok(None);
    };
    let codes = PyArray1::from_vec(py, codes).reshape([rows.len(), width])?;
    let texts = labels
        .iter()
        .map(|l| to_py(py, l))
        .collect::<PyResult<Vec<_>>>()?;
    Ok(Some(
        PyTuple::new(py, [codes.into_any(), PyList::new(py, texts)?.into_any()])?.into_any(),
    ))
}
