//! Welding and compacting polygon meshes: vertices closer than a tolerance become one, faces that
//! collapse are dropped, unused vertices are removed.

use std::collections::HashMap;

use glam::DVec3;

use crate::{GeometryError, PolygonMesh};

/// The mesh with vertices closer than `tolerance` merged (each into the first of them in vertex
/// order, found through a spatial hash of cells `tolerance` wide, so welding is linear), repeated
/// corners of a face removed, faces left with fewer than three corners dropped, and unused vertices
/// removed. Tolerance 0 merges exactly equal positions only.
pub fn weld(mesh: &PolygonMesh, tolerance: f64) -> Result<PolygonMesh, GeometryError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(GeometryError::InvalidParameter {
            what: "weld tolerance",
            value: tolerance,
            expected: "a finite number ≥ 0",
        });
    }
    mesh.validate()?;
    crate::error::check_finite_points("mesh", &mesh.vertices)?;
    let cell_size = if tolerance > 0.0 { tolerance } else { 1.0 };
    let cell = |p: DVec3| -> [i64; 3] {
        let c = (p / cell_size).floor();
        [c.x as i64, c.y as i64, c.z as i64]
    };
    let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::with_capacity(mesh.vertices.len());
    let mut kept: Vec<DVec3> = Vec::new();
    let mut map: Vec<u32> = Vec::with_capacity(mesh.vertices.len());
    let tol2 = tolerance * tolerance;
    for &p in &mesh.vertices {
        let c = cell(p);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [c[0] + dx, c[1] + dy, c[2] + dz];
                    if let Some(list) = cells.get(&key)
                        && let Some(&k) = list
                            .iter()
                            .find(|&&k| kept[k as usize].distance_squared(p) <= tol2)
                    {
                        found = Some(k);
                        break 'search;
                    }
                }
            }
        }
        let k = found.unwrap_or_else(|| {
            kept.push(p);
            let k = (kept.len() - 1) as u32;
            cells.entry(c).or_default().push(k);
            k
        });
        map.push(k);
    }
    let mut welded = PolygonMesh {
        vertices: kept,
        ..PolygonMesh::default()
    };
    let mut corners: Vec<u32> = Vec::new();
    for face in mesh.faces() {
        corners.clear();
        for &v in face {
            let w = map[v as usize];
            if corners.last() != Some(&w) {
                corners.push(w);
            }
        }
        while corners.len() > 1 && corners.first() == corners.last() {
            corners.pop();
        }
        if corners.len() >= 3 {
            welded.push_face(&corners)?;
        }
    }
    Ok(compact(&welded))
}

/// The mesh without vertices that no face uses (faces keep their order; vertices keep their
/// relative order).
pub fn compact(mesh: &PolygonMesh) -> PolygonMesh {
    let mut used = vec![u32::MAX; mesh.vertices.len()];
    let mut vertices = Vec::new();
    for &v in &mesh.indices {
        if let Some(slot) = used.get_mut(v as usize)
            && *slot == u32::MAX
        {
            *slot = 0;
        }
    }
    for (k, slot) in used.iter_mut().enumerate() {
        if *slot != u32::MAX {
            *slot = vertices.len() as u32;
            vertices.push(mesh.vertices[k]);
        }
    }
    PolygonMesh {
        vertices,
        indices: mesh.indices.iter().map(|&v| used[v as usize]).collect(),
        face_starts: mesh.face_starts.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles of a unit square, stored STL-style: six corners, none shared.
    fn soup(jitter: f64) -> PolygonMesh {
        let v = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(jitter, 0.0, 0.0),
            DVec3::new(1.0, 1.0, jitter),
            DVec3::Y,
        ];
        PolygonMesh::from_faces(v, &[vec![0, 1, 2], vec![3, 4, 5]]).unwrap()
    }

    #[test]
    fn near_corners_merge_and_the_mesh_connects() {
        let w = weld(&soup(1e-7), 1e-6).unwrap();
        assert_eq!(w.vertices.len(), 4);
        assert_eq!(w.face(0), &[0, 1, 2]);
        assert_eq!(w.face(1), &[0, 2, 3]);
        let exact = weld(&soup(1e-7), 0.0).unwrap();
        assert_eq!(
            exact.vertices.len(),
            6,
            "tolerance 0 merges equal positions only"
        );
        assert_eq!(weld(&soup(0.0), 0.0).unwrap().vertices.len(), 4);
    }

    #[test]
    fn collapsed_faces_are_dropped_and_unused_vertices_removed() {
        let v = vec![
            DVec3::ZERO,
            DVec3::new(1e-9, 0.0, 0.0),
            DVec3::Y,
            DVec3::X,
            DVec3::splat(9.0),
        ];
        let m = PolygonMesh::from_faces(v, &[vec![0, 1, 2], vec![0, 3, 2]]).unwrap();
        let w = weld(&m, 1e-6).unwrap();
        assert_eq!(w.face_count(), 1, "the sliver collapsed");
        assert_eq!(w.vertices, vec![DVec3::ZERO, DVec3::Y, DVec3::X]);
        assert!(weld(&m, f64::NAN).is_err());
        assert!(weld(&m, -1.0).is_err());
    }
}
