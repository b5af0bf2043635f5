//! Vertex tables in the runner's JSON encoding (`cnets_engine::value::json`): JSON files hold the
//! value exactly as `cnets eval`/`cnets run --json` print it (a mesh is `{vertices, faces}`, a quad
//! mesh `{rows, cols, wrap_rows, wrap_cols, vertices}`, points `[x, y, z]`, non-finite numbers
//! `null`); CSV files list every vertex found in the value, one per line.

use std::fmt::Write;

use cnets_engine::Value;
use cnets_engine::value::json::to_json;
use cnets_geometry::DVec3;

/// The value as pretty-printed JSON text (runner encoding), with a final newline.
pub fn encode_json(value: &Value) -> Result<String, String> {
    if value.is_null() {
        return Err("nothing to export: the value is empty".into());
    }
    let mut text = serde_json::to_string_pretty(&to_json(value)).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

/// One CSV row: which item, which vertex, grid position, coordinates.
struct Row {
    item: usize,
    index: usize,
    grid: Option<(usize, usize)>,
    p: DVec3,
}

/// Collects the vertices of `value` (points, vectors, polylines, lines, quad meshes, meshes, and
/// lists of them); `item` numbers the top-level items in order.
fn collect(value: &Value, item: &mut usize, rows: &mut Vec<Row>, top: bool) -> Result<(), String> {
    let start = rows.len();
    match value {
        Value::Point(p) | Value::Vector(p) => rows.push(Row {
            item: *item,
            index: 0,
            grid: None,
            p: *p,
        }),
        Value::Polyline(pl) => rows.extend(pl.points.iter().enumerate().map(|(k, p)| Row {
            item: *item,
            index: k,
            grid: None,
            p: *p,
        })),
        Value::Lines(lines) => rows.extend(
            lines
                .iter()
                .flat_map(|l| [l.start, l.end])
                .enumerate()
                .map(|(k, p)| Row {
                    item: *item,
                    index: k,
                    grid: None,
                    p,
                }),
        ),
        Value::QuadMesh(g) => {
            g.validate().map_err(|e| e.to_string())?;
            rows.extend(g.vertices.iter().enumerate().map(|(k, p)| Row {
                item: *item,
                index: k,
                grid: Some((k / g.cols.max(1), k % g.cols.max(1))),
                p: *p,
            }))
        }
        Value::Mesh(m) => rows.extend(m.vertices.iter().enumerate().map(|(k, p)| Row {
            item: *item,
            index: k,
            grid: None,
            p: *p,
        })),
        Value::List(items) => {
            // A list of points is one item; any other list holds items.
            if items
                .iter()
                .all(|v| matches!(v, Value::Point(_) | Value::Vector(_)))
            {
                rows.extend(items.iter().enumerate().filter_map(|(k, v)| {
                    v.as_vec3().map(|p| Row {
                        item: *item,
                        index: k,
                        grid: None,
                        p,
                    })
                }));
            } else {
                for v in items.iter() {
                    collect(v, item, rows, true)?;
                }
                return Ok(());
            }
        }
        Value::Null => return Ok(()),
        other => {
            return Err(format!(
                "cannot write {} as a vertex table: give points, polylines, lines or meshes",
                other.type_name()
            ));
        }
    }
    if top && rows.len() > start {
        *item += 1;
    }
    Ok(())
}

/// A number as the runner's JSON writes it (`null` for non-finite: an empty CSV field).
fn num(x: f64) -> String {
    serde_json::Number::from_f64(x).map_or_else(String::new, |n| n.to_string())
}

/// The vertices of `value` as CSV: header `item,index,row,col,x,y,z`; `row`/`col` are filled for quad
/// meshes (vertex (i, j)) and empty otherwise.
pub fn encode_csv(value: &Value) -> Result<String, String> {
    let mut rows = Vec::new();
    let mut item = 0;
    collect(value, &mut item, &mut rows, true)?;
    if rows.is_empty() {
        return Err("nothing to export: the value has no vertices".into());
    }
    let mut out = String::from("item,index,row,col,x,y,z\n");
    for r in rows {
        let (i, j) = r.grid.map_or((String::new(), String::new()), |(i, j)| {
            (i.to_string(), j.to_string())
        });
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{}",
            r.item,
            r.index,
            i,
            j,
            num(r.p.x),
            num(r.p.y),
            num(r.p.z)
        );
    }
    Ok(out)
}
