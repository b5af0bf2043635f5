//! Vertex tables in the runner's JSON encoding (`cnets_engine::value::json`): JSON files hold the
//! value exactly as `cnets eval`/`cnets run --json` print it (a mesh is `{vertices, faces}`, a quad
//! mesh `{rows, cols, wrap_rows, wrap_cols, vertices}`, points `[x, y, z]`, non-finite numbers
//! `null`); CSV files list every vertex found in the value, one per line, or — for records, such as
//! the rows of `fab.schedule` — one line per record with a column per field
//! ([`write_record_table`]).

//!
//! Both are written as streams (`write_json`, `write_csv`): nothing but the value itself and a
//! buffer is in memory while a file of ten million points is written.

use std::io::Write;

use cnets_engine::value::json::JsonOut;
use cnets_engine::{Record, Value};
use cnets_geometry::DVec3;

/// Writes the value as pretty-printed JSON (runner encoding, streamed from the value: no JSON tree
/// is built), with a final newline.
pub fn write_json(out: &mut dyn Write, value: &Value) -> Result<(), String> {
    if value.is_null() {
        return Err("nothing to export: the value is empty".into());
    }
    serde_json::to_writer_pretty(&mut *out, &JsonOut(value)).map_err(|e| e.to_string())?;
    out.write_all(b"\n").map_err(|e| e.to_string())
}

/// Where CSV rows go, counting the vertices and numbering the top-level items.
struct Rows<'a> {
    out: &'a mut dyn Write,
    item: usize,
    written: usize,
}

/// Why a CSV table stopped.
enum Failure {
    Io(std::io::Error),
    Invalid(String),
}

impl From<std::io::Error> for Failure {
    fn from(e: std::io::Error) -> Self {
        Failure::Io(e)
    }
}

/// A number as the runner's JSON writes it (`null` for non-finite: an empty CSV field).
fn num(out: &mut dyn Write, x: f64) -> std::io::Result<()> {
    match serde_json::Number::from_f64(x) {
        Some(n) => write!(out, "{n}"),
        None => Ok(()),
    }
}

impl Rows<'_> {
    /// One row: which item, which vertex, grid position, coordinates.
    fn row(&mut self, index: usize, grid: Option<(usize, usize)>, p: DVec3) -> Result<(), Failure> {
        write!(self.out, "{},{},", self.item, index)?;
        if let Some((i, j)) = grid {
            write!(self.out, "{i},{j},")?;
        } else {
            self.out.write_all(b",,")?;
        }
        num(self.out, p.x)?;
        self.out.write_all(b",")?;
        num(self.out, p.y)?;
        self.out.write_all(b",")?;
        num(self.out, p.z)?;
        self.out.write_all(b"\n")?;
        self.written += 1;
        Ok(())
    }

    fn points(&mut self, points: impl Iterator<Item = DVec3>) -> Result<(), Failure> {
        points
            .enumerate()
            .try_for_each(|(k, p)| self.row(k, None, p))
    }

    /// Writes the vertices of `value` (points, vectors, polylines, lines, quad meshes, meshes, and
    /// lists of them); a top-level item that wrote rows advances the item number.
    fn value(&mut self, value: &Value, top: bool) -> Result<(), Failure> {
        let start = self.written;
        match value {
            Value::Point(p) | Value::Vector(p) => self.row(0, None, *p)?,
            Value::Polyline(pl) => self.points(pl.points.iter().copied())?,
            Value::Lines(lines) => self.points(lines.iter().flat_map(|l| [l.start, l.end]))?,
            Value::QuadMesh(g) => {
                g.validate().map_err(|e| Failure::Invalid(e.to_string()))?;
                let cols = g.cols.max(1);
                for (k, p) in g.vertices.iter().enumerate() {
                    self.row(k, Some((k / cols, k % cols)), *p)?;
                }
            }
            Value::Mesh(m) => self.points(m.vertices.iter().copied())?,
            Value::List(items) => {
                // A list of points is one item; any other list holds items.
                if items
                    .iter()
                    .all(|v| matches!(v, Value::Point(_) | Value::Vector(_)))
                {
                    self.points(items.iter().filter_map(Value::as_vec3))?;
                } else {
                    for v in items.iter() {
                        self.value(v, true)?;
                    }
                    return Ok(());
                }
            }
            Value::Null => return Ok(()),
            other => {
                return Err(Failure::Invalid(format!(
                    "cannot write {} as a vertex table: give points, polylines, lines or meshes",
                    other.type_name()
                )));
            }
        }
        if top && self.written > start {
            self.item += 1;
        }
        Ok(())
    }
}

/// The records of a value that is a table: one record, or a non-empty list of records only.
fn records(value: &Value) -> Option<Vec<&Record>> {
    match value {
        Value::Record(r) => Some(vec![r]),
        Value::List(items) if !items.is_empty() => items
            .iter()
            .map(|v| match v {
                Value::Record(r) => Some(&**r),
                _ => None,
            })
            .collect(),
        _ => None,
    }
}

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break (RFC 4180).
fn field(out: &mut dyn Write, text: &str) -> std::io::Result<()> {
    if text.contains([',', '"', '\n', '\r']) {
        write!(out, "\"{}\"", text.replace('"', "\"\""))
    } else {
        out.write_all(text.as_bytes())
    }
}

/// The text of one cell: numbers as the runner's JSON writes them (non-finite: empty), integers,
/// `true`/`false`, texts as they are, a point or vector as `x y z`, a list as its items joined by
/// `; `, nothing for null.
fn cell(value: &Value, text: &mut Vec<u8>) -> Result<(), String> {
    let io = |e: std::io::Error| e.to_string();
    match value {
        Value::Null => {}
        Value::Number(x) => num(text, *x).map_err(io)?,
        Value::Integer(n) => write!(text, "{n}").map_err(io)?,
        Value::Boolean(b) => write!(text, "{b}").map_err(io)?,
        Value::Text(t) => text.extend_from_slice(t.as_bytes()),
        Value::Point(p) | Value::Vector(p) => {
            num(text, p.x).map_err(io)?;
            text.push(b' ');
            num(text, p.y).map_err(io)?;
            text.push(b' ');
            num(text, p.z).map_err(io)?;
        }
        Value::List(items) => {
            for (k, item) in items.iter().enumerate() {
                if matches!(item, Value::List(_)) {
                    return Err("a table cell holds a list of lists: give a flat list".into());
                }
                if k > 0 {
                    text.extend_from_slice(b"; ");
                }
                cell(item, text)?;
            }
        }
        other => {
            return Err(format!(
                "cannot write {} in a table cell: give numbers, integers, texts, points or lists of them",
                other.type_name()
            ));
        }
    }
    Ok(())
}

/// Writes records as a CSV table: a header of the field names (in the order they first appear),
/// then one line per record, a field the record lacks left empty. Cells as [`cell`] writes them.
pub fn write_record_table(out: &mut dyn Write, records: &[&Record]) -> Result<(), String> {
    let io = |e: std::io::Error| e.to_string();
    let mut columns: Vec<&str> = Vec::new();
    for r in records {
        for (name, _) in r.fields() {
            if !columns.contains(&name.as_str()) {
                columns.push(name);
            }
        }
    }
    if columns.is_empty() {
        return Err("nothing to export: the records have no fields".into());
    }
    for (k, name) in columns.iter().enumerate() {
        if k > 0 {
            out.write_all(b",").map_err(io)?;
        }
        field(out, name).map_err(io)?;
    }
    out.write_all(b"\n").map_err(io)?;
    let mut text = Vec::new();
    for (row, r) in records.iter().enumerate() {
        for (k, name) in columns.iter().enumerate() {
            if k > 0 {
                out.write_all(b",").map_err(io)?;
            }
            text.clear();
            if let Some(v) = r.get(name) {
                cell(v, &mut text).map_err(|e| format!("record {row}, field '{name}': {e}"))?;
            }
            field(out, &String::from_utf8_lossy(&text)).map_err(io)?;
        }
        out.write_all(b"\n").map_err(io)?;
    }
    Ok(())
}

/// Writes `value` as CSV. Records (one, or a list of them: a table such as `fab.schedule`'s) are
/// written by [`write_record_table`]. Anything else as its vertices, row by row: header
/// `item,index,row,col,x,y,z`; `row`/`col` are filled for quad meshes (vertex (i, j)) and empty
/// otherwise.
pub fn write_csv(out: &mut dyn Write, value: &Value) -> Result<(), String> {
    if let Some(records) = records(value) {
        return write_record_table(out, &records);
    }
    let message = |f: Failure| match f {
        Failure::Io(e) => e.to_string(),
        Failure::Invalid(m) => m,
    };
    out.write_all(b"item,index,row,col,x,y,z\n")
        .map_err(|e| e.to_string())?;
    let mut rows = Rows {
        out,
        item: 0,
        written: 0,
    };
    rows.value(value, true).map_err(message)?;
    if rows.written == 0 {
        return Err("nothing to export: the value has no vertices".into());
    }
    Ok(())
}
