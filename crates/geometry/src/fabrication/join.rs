//! Joining polygon meshes and welding coincident vertices (`mesh.join`).
//!
//! Joining appends vertices and faces (indices shifted). Welding merges every vertex within
//! `tolerance` of an earlier kept vertex into it (first come, first kept; a uniform grid of cell size
//! `tolerance` finds the candidates); faces are renumbered, repeated consecutive corners removed, and
//! faces left with fewer than three corners dropped. Unused vertices are removed.

use std::collections::HashMap;

use glam::DVec3;

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
    let mut reps: Vec<DVec3> = Vec::new();
    let mut map = Vec::with_capacity(mesh.vertices.len());
    if tolerance == 0.0 {
        let mut seen: HashMap<[u64; 3], u32> = HashMap::new();
        for p in &mesh.vertices {
            // +0.0 and −0.0 are the same position.
            let key = (*p + DVec3::ZERO).to_array().map(f64::to_bits);
            let k = *seen.entry(key).or_insert_with(|| {
                reps.push(*p);
                (reps.len() - 1) as u32
            });
            map.push(k);
        }
    } else {
        let cell = |p: DVec3| -> Result<[i64; 3], FabricationError> {
            let c = (p / tolerance).floor();
            if c.abs().max_element() > 1e15 {
                return Err(FabricationError::BadParameter {
                    what: "weld tolerance",
                    value: tolerance,
                    expected: "a tolerance not that small compared with the coordinates",
                });
            }
            Ok([c.x as i64, c.y as i64, c.z as i64])
        };
        let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        for p in &mesh.vertices {
            let c = cell(*p)?;
            let mut found = None;
            'search: for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        if let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                            && let Some(&k) = list
                                .iter()
                                .find(|&&k| reps[k as usize].distance(*p) <= tolerance)
                        {
                            found = Some(k);
                            break 'search;
                        }
                    }
                }
            }
            let k = found.unwrap_or_else(|| {
                reps.push(*p);
                let k = (reps.len() - 1) as u32;
                grid.entry(c).or_default().push(k);
                k
            });
            map.push(k);
        }
    }
    let mut out = PolygonMesh::new();
    let mut remap = vec![u32::MAX; reps.len()];
    let mut faces = Vec::with_capacity(mesh.face_count());
    for face in mesh.faces() {
        let mut f: Vec<u32> = face.iter().map(|&v| map[v as usize]).collect();
        f.dedup();
        while f.len() > 1 && f.first() == f.last() {
            f.pop();
        }
        if f.len() >= 3 {
            faces.push(f);
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
    Ok(out)
}
