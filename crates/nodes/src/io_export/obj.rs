//! Wavefront OBJ: one object (`o`) per mesh, line set and polyline; faces keep their polygons (quads
//! stay quads: `f a b c d`), line sets become two-point `l` lines, polylines one `l` line through all
//! their points (a closed polyline repeats its first index at the end). Coordinates are written in
//! model units with the shortest decimal text that reads back to the same f64; indices are 1-based
//! and global.

use std::io::Write;

use cnets_geometry::{DVec3, Line, PolygonMesh, Polyline};

use super::names::{ItemNames, obj_token};

/// Writes a `v` line.
fn vertex(out: &mut dyn Write, p: DVec3) -> std::io::Result<()> {
    writeln!(out, "v {} {} {}", p.x, p.y, p.z)
}

/// Writes meshes, line sets and polylines as OBJ text into `out`, item by item (nothing is held
/// beyond one line). Fails when there is nothing to export, a coordinate is not finite or the
/// write fails (a cancelled export says "cancelled").
pub fn write_obj(
    out: &mut dyn Write,
    meshes: &[&PolygonMesh],
    lines: &[&[Line]],
    polylines: &[&Polyline],
    names: ItemNames<'_>,
) -> Result<(), String> {
    write_items(out, meshes, lines, polylines, names).map_err(|e| match e {
        Failure::Io(e) => e.to_string(),
        Failure::Invalid(m) => m,
    })
}

/// Why OBJ writing stopped.
enum Failure {
    Io(std::io::Error),
    Invalid(String),
}

impl From<std::io::Error> for Failure {
    fn from(e: std::io::Error) -> Self {
        Failure::Io(e)
    }
}

fn write_items(
    out: &mut dyn Write,
    meshes: &[&PolygonMesh],
    lines: &[&[Line]],
    polylines: &[&Polyline],
    names: ItemNames<'_>,
) -> Result<(), Failure> {
    let invalid = |m: String| Failure::Invalid(m);
    out.write_all(
        b"# cnets OBJ export (model units; faces are the mesh polygons, lines are l elements)\n",
    )?;
    let mut next = 1usize;
    let mut written = 0usize;
    for (k, m) in meshes.iter().enumerate() {
        if m.face_count() == 0 {
            continue;
        }
        if let Some(v) = m.vertices.iter().position(|p| !p.is_finite()) {
            return Err(invalid(format!("mesh {k}, vertex {v} is not finite")));
        }
        m.validate()
            .map_err(|e| invalid(format!("mesh {k}: {e}")))?;
        writeln!(out, "o {}", obj_token(&names.mesh(k)))?;
        for p in &m.vertices {
            vertex(out, *p)?;
        }
        for f in m.faces() {
            out.write_all(b"f")?;
            for v in f {
                write!(out, " {}", next + *v as usize)?;
            }
            out.write_all(b"\n")?;
        }
        next += m.vertices.len();
        written += 1;
    }
    for (k, set) in lines.iter().enumerate() {
        if set.is_empty() {
            continue;
        }
        if let Some(s) = set
            .iter()
            .position(|l| !(l.start.is_finite() && l.end.is_finite()))
        {
            return Err(invalid(format!("line set {k}, segment {s} is not finite")));
        }
        writeln!(out, "o {}", obj_token(&names.lines(k)))?;
        for l in set.iter() {
            vertex(out, l.start)?;
            vertex(out, l.end)?;
        }
        for s in 0..set.len() {
            writeln!(out, "l {} {}", next + 2 * s, next + 2 * s + 1)?;
        }
        next += 2 * set.len();
        written += 1;
    }
    for (k, p) in polylines.iter().enumerate() {
        if p.points.len() < 2 {
            continue;
        }
        if let Some(v) = p.points.iter().position(|q| !q.is_finite()) {
            return Err(invalid(format!("polyline {k}, point {v} is not finite")));
        }
        writeln!(out, "o {}", obj_token(&names.polyline(k)))?;
        for q in &p.points {
            vertex(out, *q)?;
        }
        out.write_all(b"l")?;
        for v in 0..p.points.len() {
            write!(out, " {}", next + v)?;
        }
        if p.closed {
            write!(out, " {next}")?;
        }
        out.write_all(b"\n")?;
        next += p.points.len();
        written += 1;
    }
    if written == 0 {
        return Err(invalid(
            "nothing to export: no mesh face, line or polyline".into(),
        ));
    }
    Ok(())
}
