//! Joining polygon meshes and welding coincident vertices (`mesh.join`).
//!
//! Joining appends vertices and faces (indices shifted). Welding merges every vertex within
//! `tolerance` of an earlier kept vertex into it (first come, first kept; the spatial hash of
//! `mesh_weld::merge_map` finds the candidates); faces are renumbered, repeated consecutive corners removed, and
//! faces left with fewer than three corners dropped. Unused vertices are removed.

use super::FabricationError;
use crate::PolygonMesh;
use crate::error::check_finite_points;

/// All meshes in one (no welding). Empty meshes are allowed; the result must have a face.
pub fn join(meshes: &[&PolygonMesh]) -> Result<PolygonMesh, FabricationError> {
    let mut out = PolygonMesh::new();
    for (k, m) in meshes.iter().enumerate() {
        m.validate()?;
        check_finite_points("mesh", &m.vertices).map_err(|_| {
            FabricationError::Geometry(crate::GeometryError::NonFinite {
                what: "mesh (of the joined list)",
                index: k,
            })
        })?;
        out.append(m);
    }
    if out.face_count() == 0 {
        return Err(FabricationError::Empty("the joined mesh"));
    }
    Ok(out)
}

/// Welds vertices closer than `tolerance` (finite, ≥ 0; 0 merges only identical positions).
pub fn weld(mesh: &PolygonMesh, tolerance: f64) -> Result<PolygonMesh, FabricationError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(FabricationError::BadParameter {
            what: "weld tolerance",
            value: tolerance,
            expected: "a finite number ≥ 0",
        });
    }
    mesh.validate()?;
    check_finite_points("mesh", &mesh.vertices)?;
    // The shared spatial hash (`mesh_weld::merge_map`): near-linear for any tolerance and any
    // coordinates, where a grid of i64 cells saturated.
    let (reps, map, _) = crate::mesh_weld::merge_map(&mesh.vertices, tolerance);
    let mut out = PolygonMesh::new();
    let mut remap = vec![u32::MAX; reps.len()];
    let mut faces = Vec::with_capacity(mesh.face_count());
    let mut sources = Vec::with_capacity(mesh.face_count());
    for (k, face) in mesh.faces().enumerate() {
        let mut f: Vec<u32> = face.iter().map(|&v| map[v as usize]).collect();
        f.dedup();
        while f.len() > 1 && f.first() == f.last() {
            f.pop();
        }
        if f.len() >= 3 {
            faces.push(f);
            sources.push(k as u32);
        }
    }
    for f in &mut faces {
        for v in f.iter_mut() {
            if remap[*v as usize] == u32::MAX {
                remap[*v as usize] = out.push_vertex(reps[*v as usize]);
            }
            *v = remap[*v as usize];
        }
    }
    for f in faces {
        out.push_face(&f)?;
    }
    out.carry_faces_from(mesh, &sources);
    Ok(out)
}
