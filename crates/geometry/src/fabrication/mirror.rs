//! Mirroring a polygon mesh in a plane and joining it to itself (`mesh.mirror`).
//!
//! Vertices within `tolerance` of the plane are moved onto it (orthogonal projection) and shared by
//! both halves (welded); every other vertex gets its reflection `p − 2 ((p − o)·n̂) n̂`. The mirrored
//! faces have their corner order reversed, so both halves keep a consistent orientation. Faces lying
//! entirely in the plane are not duplicated.

use super::FabricationError;
use super::polygon::check_mesh;
use crate::plane::unit;
use crate::{Plane, PolygonMesh};

/// The mesh joined with its reflection in `plane`, welding the vertices within `tolerance` (finite,
/// ≥ 0, model units) of the plane.
pub fn mirror(
    mesh: &PolygonMesh,
    plane: &Plane,
    tolerance: f64,
) -> Result<PolygonMesh, FabricationError> {
    check_mesh(mesh, "mesh")?;
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(FabricationError::BadParameter {
            what: "tolerance",
            value: tolerance,
            expected: "a finite number ≥ 0",
        });
    }
    if !plane.is_finite() {
        return Err(crate::GeometryError::NonFinite {
            what: "plane",
            index: 0,
        }
        .into());
    }
    let n = unit(plane.normal, "plane normal")?;
    let mut out = PolygonMesh::new();
    let mut on = Vec::with_capacity(mesh.vertices.len());
    for p in &mesh.vertices {
        let d = (*p - plane.origin).dot(n);
        let weld = d.abs() <= tolerance;
        on.push(weld);
        out.push_vertex(if weld { *p - n * d } else { *p });
    }
    let mut image = Vec::with_capacity(mesh.vertices.len());
    for (k, p) in mesh.vertices.iter().enumerate() {
        image.push(if on[k] {
            k as u32
        } else {
            out.push_vertex(*p - n * (2.0 * (*p - plane.origin).dot(n)))
        });
    }
    let mut sources: Vec<u32> = (0..mesh.face_count() as u32).collect();
    for face in mesh.faces() {
        out.push_face(face)?;
    }
    for (k, face) in mesh.faces().enumerate() {
        if face.iter().all(|&v| on[v as usize]) {
            continue;
        }
        let reversed: Vec<u32> = face.iter().rev().map(|&v| image[v as usize]).collect();
        out.push_face(&reversed)?;
        sources.push(k as u32);
    }
    out.carry_faces_from(mesh, &sources);
    Ok(out)
}
