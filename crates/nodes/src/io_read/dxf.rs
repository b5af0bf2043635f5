//! DXF polylines, read with the `dxf` crate: LINE, LWPOLYLINE (bulges become arcs), POLYLINE (2D and
//! 3D), ARC, CIRCLE, ELLIPSE and SPLINE (NURBS, evaluated exactly and sampled). Entities in an
//! object coordinate system (their extrusion direction) are mapped to world coordinates by DXF's
//! arbitrary-axis algorithm. Curved pieces are sampled with `segments` edges each (a circle:
//! `segments` points; a spline: `segments` edges per knot span). Other entities are counted in a
//! warning.

use std::f64::consts::TAU;

use cnets_engine::budget::Guard;
use cnets_engine::prelude::*;
use cnets_geometry::curves::Nurbs;
use dxf::entities::EntityType;

use super::{ReadError, tidy};

/// The bits of the integer a group code holds (DXF reference: 60–79 and 270–289 16-bit, 90–99 32-bit,
/// 170–179, 370–389, 400–409 16-bit, 420–429, 440–459, 1071 32-bit), `None` for other codes.
fn integer_bits(code: i32) -> Option<u32> {
    match code {
        60..=79 | 170..=179 | 270..=289 | 370..=389 | 400..=409 | 1060..=1070 => Some(16),
        90..=99 | 420..=429 | 440..=459 | 1071 => Some(32),
        _ => None,
    }
}

/// Reads the group codes of an ascii DXF before the `dxf` crate does: an integer value that does
/// not fit its code's width (a count over 32 bits) is named with its line, where the crate would
/// say that the *next* code pair was not expected.
fn check_integer_values(bytes: &[u8]) -> Result<(), ReadError> {
    if bytes.starts_with(b"AutoCAD Binary DXF") {
        return Ok(());
    }
    let text = String::from_utf8_lossy(bytes);
    let mut lines = text.lines().enumerate();
    while let (Some((_, code)), Some((k, value))) = (lines.next(), lines.next()) {
        let Some(bits) = code.trim().parse::<i32>().ok().and_then(integer_bits) else {
            continue;
        };
        let value = value.trim();
        let fits = match bits {
            16 => value.parse::<i16>().is_ok(),
            _ => value.parse::<i32>().is_ok(),
        };
        if !fits {
            return Err(ReadError::at(
                k + 1,
                format!(
                    "group code {} holds '{}', not a {bits}-bit integer",
                    code.trim(),
                    cnets_engine::files::excerpt(value, 30)
                ),
            ));
        }
    }
    Ok(())
}

/// The `dxf` crate's error, said where the numbers come from: a count that does not fit its field
/// (over 32 bits) is "code pair 70 not expected" there.
fn dxf_error(e: dxf::DxfError) -> String {
    let text = e.to_string();
    if text.contains("not expected") || text.contains("Unexpected") {
        format!(
            "{text} (a value out of its field's range, e.g. a count over 32 bits, or a misplaced group code)"
        )
    } else {
        text
    }
}

fn point(p: &dxf::Point) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

fn vector(v: &dxf::Vector) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

/// The object coordinate system of an extrusion direction (DXF's arbitrary-axis algorithm): its x
/// and y axes and the normal.
fn ocs(normal: DVec3) -> (DVec3, DVec3, DVec3) {
    let n = if normal.length_squared() > 0.0 && normal.is_finite() {
        normal.normalize()
    } else {
        DVec3::Z
    };
    let limit = 1.0 / 64.0;
    let x = if n.x.abs() < limit && n.y.abs() < limit {
        DVec3::Y.cross(n)
    } else {
        DVec3::Z.cross(n)
    }
    .normalize();
    (x, n.cross(x), n)
}

fn to_world(axes: (DVec3, DVec3, DVec3), p: DVec3) -> DVec3 {
    axes.0 * p.x + axes.1 * p.y + axes.2 * p.z
}

/// Points of the arc from `start` to `start + sweep` (radians) about `center`, `segments` edges.
fn arc_points(center: DVec3, radius: f64, start: f64, sweep: f64, segments: usize) -> Vec<DVec3> {
    (0..=segments)
        .map(|k| {
            let a = start + sweep * k as f64 / segments as f64;
            center + DVec3::new(radius * a.cos(), radius * a.sin(), 0.0)
        })
        .collect()
}

/// The points of a polyline with bulges (in its plane's coordinates): each bulged edge becomes an
/// arc of `segments` edges (bulge = tan(¼ of the included angle), positive counter-clockwise).
fn bulged(vertices: &[(DVec3, f64)], closed: bool, segments: usize) -> Vec<DVec3> {
    let mut out = Vec::new();
    let n = vertices.len();
    let edges = if closed { n } else { n.saturating_sub(1) };
    for k in 0..n {
        let (p, bulge) = vertices[k];
        out.push(p);
        if k >= edges || bulge == 0.0 || !bulge.is_finite() {
            continue;
        }
        let q = vertices[(k + 1) % n].0;
        let chord = q - p;
        let d = chord.truncate().length();
        if d == 0.0 {
            continue;
        }
        let left = DVec3::new(-chord.y, chord.x, 0.0) / d;
        let center = (p + q) * 0.5 + left * (d * 0.5 * (1.0 - bulge * bulge) / (2.0 * bulge));
        let radius = (p - center).truncate().length();
        let start = (p.y - center.y).atan2(p.x - center.x);
        let sweep = 4.0 * bulge.atan();
        let arc = arc_points(
            DVec3::new(center.x, center.y, p.z),
            radius,
            start,
            sweep,
            segments,
        );
        out.extend_from_slice(&arc[1..arc.len() - 1]);
    }
    out
}

/// Bytes a sampled point may take while it is made (the point and its copy in the tidied curve).
const POINT_BYTES: usize = 48;

/// At most how many points an entity samples to (declared to the memory guard before it is).
fn sampled_points(entity: &EntityType, segments: usize) -> u64 {
    let s = segments as u64 + 1;
    match entity {
        EntityType::Line(_) => 2,
        EntityType::LwPolyline(l) => (l.vertices.len() as u64).saturating_mul(s),
        EntityType::Polyline(l) => (l.vertices().count() as u64).saturating_mul(s),
        EntityType::Arc(_) | EntityType::Circle(_) | EntityType::Ellipse(_) => s.max(4),
        EntityType::Spline(sp) => {
            let spans = (sp.knot_values.len() as u64).max(sp.fit_points.len() as u64) + 1;
            spans.saturating_mul(s)
        }
        _ => 0,
    }
}

/// Parses DXF bytes (ascii or binary) into polylines and warnings.
pub fn parse(bytes: &[u8], segments: usize) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    parse_within(bytes, segments, &mut Guard::unlimited())
}

/// [`parse`] declaring every entity's sampled points to `guard` before sampling them: 100 000
/// bulged vertices × 10 000 segments stop at the memory budget.
pub fn parse_within(
    bytes: &[u8],
    segments: usize,
    guard: &mut Guard,
) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    check_integer_values(bytes)?;
    let drawing = dxf::Drawing::load(&mut std::io::Cursor::new(bytes)).map_err(dxf_error)?;
    let mut curves = Vec::new();
    let mut skipped = 0usize;
    for (k, entity) in drawing.entities().enumerate() {
        guard
            .grow_items(sampled_points(&entity.specific, segments), POINT_BYTES)
            .map_err(|e| format!("entity {k}: {e}"))?;
        match &entity.specific {
            EntityType::Line(l) => curves.push(tidy(vec![point(&l.p1), point(&l.p2)], false)),
            EntityType::LwPolyline(l) => {
                let axes = ocs(vector(&l.extrusion_direction));
                let vertices: Vec<(DVec3, f64)> = l
                    .vertices
                    .iter()
                    .map(|v| (DVec3::new(v.x, v.y, 0.0), v.bulge))
                    .collect();
                let closed = l.is_closed();
                let pts = bulged(&vertices, closed, segments);
                curves.push(tidy(
                    pts.into_iter().map(|p| to_world(axes, p)).collect(),
                    closed,
                ));
            }
            EntityType::Polyline(l) => {
                let three_d = l.flags & 8 != 0;
                let axes = if three_d {
                    (DVec3::X, DVec3::Y, DVec3::Z)
                } else {
                    ocs(vector(&l.normal))
                };
                let vertices: Vec<(DVec3, f64)> = l
                    .vertices()
                    .map(|v| (point(&v.location), if three_d { 0.0 } else { v.bulge }))
                    .collect();
                let closed = l.is_closed();
                let pts = bulged(&vertices, closed, segments);
                curves.push(tidy(
                    pts.into_iter().map(|p| to_world(axes, p)).collect(),
                    closed,
                ));
            }
            EntityType::Arc(a) => {
                let axes = ocs(vector(&a.normal));
                // The centre is given in the object coordinate system.
                let center = point(&a.center);
                let (start, end) = (a.start_angle.to_radians(), a.end_angle.to_radians());
                let sweep = (end - start).rem_euclid(TAU);
                let sweep = if sweep == 0.0 { TAU } else { sweep };
                let pts = arc_points(center, a.radius, start, sweep, segments);
                curves.push(tidy(
                    pts.into_iter().map(|p| to_world(axes, p)).collect(),
                    false,
                ));
            }
            EntityType::Circle(c) => {
                let axes = ocs(vector(&c.normal));
                let center = point(&c.center);
                let mut pts = arc_points(center, c.radius, 0.0, TAU, segments.max(3));
                pts.pop();
                curves.push(tidy(
                    pts.into_iter().map(|p| to_world(axes, p)).collect(),
                    true,
                ));
            }
            EntityType::Ellipse(e) => {
                let center = point(&e.center);
                let major = vector(&e.major_axis);
                let minor = vector(&e.normal).normalize_or_zero().cross(major) * e.minor_axis_ratio;
                let (start, end) = (e.start_parameter, e.end_parameter);
                let sweep = (end - start).rem_euclid(TAU);
                let full = sweep == 0.0 || (sweep - TAU).abs() < 1e-12;
                let sweep = if full { TAU } else { sweep };
                let mut pts: Vec<DVec3> = (0..=segments.max(3))
                    .map(|k| {
                        let t = start + sweep * k as f64 / segments.max(3) as f64;
                        center + major * t.cos() + minor * t.sin()
                    })
                    .collect();
                if full {
                    pts.pop();
                }
                curves.push(tidy(pts, full));
            }
            EntityType::Spline(s) => {
                let closed = s.flags & 1 != 0;
                let pts = if s.control_points.is_empty() {
                    s.fit_points.iter().map(point).collect()
                } else {
                    let nurbs = Nurbs {
                        degree: usize::try_from(s.degree_of_curve).unwrap_or(0),
                        knots: s.knot_values.clone(),
                        control: s.control_points.iter().map(point).collect(),
                        weights: if s.weight_values.iter().all(|&w| w == 1.0) {
                            Vec::new()
                        } else {
                            s.weight_values.clone()
                        },
                    };
                    nurbs.sample(segments).map_err(|e| format!("SPLINE: {e}"))?
                };
                curves.push(tidy(pts, closed));
            }
            _ => skipped += 1,
        }
    }
    if let Some(k) = curves
        .iter()
        .position(|c| c.points.iter().any(|p| !p.is_finite()))
    {
        return Err(format!("curve {k} has a coordinate that is not finite").into());
    }
    let curves: Vec<Polyline> = curves.into_iter().filter(|c| c.points.len() >= 2).collect();
    let warnings = if skipped > 0 {
        vec![format!(
            "{skipped} entities that are not curves were ignored"
        )]
    } else {
        Vec::new()
    };
    Ok((curves, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bulge_of_one_is_a_half_circle() {
        let pts = bulged(
            &[(DVec3::ZERO, 1.0), (DVec3::new(2.0, 0.0, 0.0), 0.0)],
            false,
            4,
        );
        assert_eq!(pts.len(), 5);
        for p in &pts {
            assert!(((*p - DVec3::X).length() - 1.0).abs() < 1e-15, "{p}");
        }
        // Counter-clockwise from (0,0) to (2,0): the arc passes below the chord.
        assert!(
            (pts[2] - DVec3::new(1.0, -1.0, 0.0)).length() < 1e-15,
            "{}",
            pts[2]
        );
    }

    #[test]
    fn a_count_over_32_bits_is_named_on_its_line() {
        let text = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\n0\n90\n99999999999\n70\n0\n0\nENDSEC\n0\nEOF\n";
        let e = parse(text.as_bytes(), 16).unwrap_err();
        assert_eq!((e.line, e.column), (Some(10), None));
        assert_eq!(
            e.to_string(),
            "line 10: group code 90 holds '99999999999', not a 32-bit integer"
        );
    }

    #[test]
    fn the_arbitrary_axis_algorithm_keeps_world_z_and_flips_for_minus_z() {
        let (x, y, n) = ocs(DVec3::Z);
        assert_eq!((x, y, n), (DVec3::X, DVec3::Y, DVec3::Z));
        let (x, _, _) = ocs(-DVec3::Z);
        assert_eq!(x, -DVec3::X);
    }
}
