//! Wavefront OBJ: one object (`o`) per mesh, line set and polyline; faces keep their polygons (quads
//! stay quads: `f a b c d`), line sets become two-point `l` lines, polylines one `l` line through all
//! their points (a closed polyline repeats its first index at the end). Coordinates are written in
//! model units with the shortest decimal text that reads back to the same f64; indices are 1-based
//! and global.

use std::fmt::Write;

use cnets_geometry::{DVec3, Line, PolygonMesh, Polyline};

/// Appends a `v` line.
fn vertex(out: &mut String, p: DVec3) {
    let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
}

/// Encodes meshes, line sets and polylines as OBJ text. Fails when there is nothing to export or a
/// coordinate is not finite.
pub fn encode_obj(
    meshes: &[&PolygonMesh],
    lines: &[&[Line]],
    polylines: &[&Polyline],
) -> Result<String, String> {
    let mut out = String::from(
        "# cnets OBJ export (model units; faces are the mesh polygons, lines are l elements)\n",
    );
    let mut next = 1usize;
    let mut written = 0usize;
    for (k, m) in meshes.iter().enumerate() {
        if m.face_count() == 0 {
            continue;
        }
        if let Some(v) = m.vertices.iter().position(|p| !p.is_finite()) {
            return Err(format!("mesh {k}, vertex {v} is not finite"));
        }
        m.validate().map_err(|e| format!("mesh {k}: {e}"))?;
        let _ = writeln!(out, "o mesh_{k}");
        for p in &m.vertices {
            vertex(&mut out, *p);
        }
        for f in m.faces() {
            out.push('f');
            for v in f {
                let _ = write!(out, " {}", next + *v as usize);
            }
            out.push('\n');
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
            return Err(format!("line set {k}, segment {s} is not finite"));
        }
        let _ = writeln!(out, "o lines_{k}");
        for l in set.iter() {
            vertex(&mut out, l.start);
            vertex(&mut out, l.end);
        }
        for s in 0..set.len() {
            let _ = writeln!(out, "l {} {}", next + 2 * s, next + 2 * s + 1);
        }
        next += 2 * set.len();
        written += 1;
    }
    for (k, p) in polylines.iter().enumerate() {
        if p.points.len() < 2 {
            continue;
        }
        if let Some(v) = p.points.iter().position(|q| !q.is_finite()) {
            return Err(format!("polyline {k}, point {v} is not finite"));
        }
        let _ = writeln!(out, "o polyline_{k}");
        for q in &p.points {
            vertex(&mut out, *q);
        }
        out.push('l');
        for v in 0..p.points.len() {
            let _ = write!(out, " {}", next + v);
        }
        if p.closed {
            let _ = write!(out, " {next}");
        }
        out.push('\n');
        next += p.points.len();
        written += 1;
    }
    if written == 0 {
        return Err("nothing to export: no mesh face, line or polyline".into());
    }
    Ok(out)
}
