//! Mesh operations: conversion to polygons, cutting by a plane, mirroring, joining.
//!
//! Thin wrappers over `cnets_geometry::fabrication` (formulas in `docs/fabrication.md`). Quad meshes
//! convert to polygon meshes implicitly on every `mesh` input.

use cnets_engine::prelude::*;
use cnets_geometry::fabrication as fab;
use cnets_geometry::{MeshParts, PolygonMesh};

use crate::fabrication::fab_err;

node! {
    /// A quad grid as a general polygon mesh: the same vertices, one quad face per grid quad (corner
    /// order `(i,j), (i,j+1), (i+1,j+1), (i+1,j)`, wrapping quads included).
    #[node(id = "mesh.to_polygons", category = "Mesh")]
    pub fn to_polygons(
        /// The quad grid.
        mesh: k::QuadMesh,
    ) -> (
        /// The polygon mesh.
        mesh: k::Mesh,
    ) {
        mesh.validate()?;
        Ok((PolygonMesh::from(&*mesh),))
    }
}

node! {
    /// Cuts a mesh by a plane and keeps one side. Faces crossing the plane are split exactly at it
    /// (new vertices on the plane, shared by neighbouring faces), so quads may become triangles or
    /// pentagons: the result is a general polygon mesh. Faces on the plane are kept.
    #[node(id = "mesh.cut_by_plane", category = "Mesh")]
    pub fn cut_by_plane(
        /// The mesh (a quad grid converts).
        mesh: k::Mesh,
        /// The cutting plane (the 3D view draws it, and the side kept, while the node is selected).
        #[ui(role = CutPlane)]
        plane: k::Plane = Plane::XY,
        /// Keep the side opposite to the plane's normal (default: the side the normal points to).
        #[ui(role = FlipsSide)]
        flip: k::Boolean = false,
    ) -> (
        /// The kept part.
        mesh: k::Mesh,
        /// The segments where faces were cut.
        section: k::Lines,
    ) {
        let cut = fab::cut_by_plane(&mesh, &plane, !flip).map_err(fab_err)?;
        Ok((cut.mesh, cut.section))
    }
}

node! {
    /// Reflects a mesh in a plane and joins the reflection to it. Vertices within `tolerance` of the
    /// plane are moved onto it and shared by both halves (welded); the mirrored faces are reversed so
    /// the orientation stays consistent; faces lying in the plane are not duplicated.
    #[node(id = "mesh.mirror", category = "Mesh")]
    pub fn mirror(
        /// The mesh (a quad grid converts).
        mesh: k::Mesh,
        /// The mirror plane.
        plane: k::Plane = Plane::YZ,
        /// Weld distance to the plane, in model units (≥ 0).
        tolerance: k::Number = 1e-6,
    ) -> (
        /// The mesh and its mirror image, joined.
        mesh: k::Mesh,
    ) {
        Ok((fab::mirror(&mesh, &plane, tolerance).map_err(fab_err)?,))
    }
}

node! {
    /// Joins meshes into one (vertices and faces appended in list order). With `weld`, vertices closer
    /// than that distance are merged and faces that collapse are dropped. Each mesh becomes a named
    /// part of the result, so figures, strip labels and GLB meshes say which net a face came from:
    /// the name given in `names`, else the parts the mesh already has (a joined structure), else a
    /// letter by its place in the list (`A`, `B`, … `Z`, `AA`, …).
    #[node(id = "mesh.join", category = "Mesh")]
    pub fn join(
        /// The meshes (quad grids convert).
        meshes: k::List<k::Mesh>,
        /// Weld distance in model units (≥ 0); empty: no welding.
        weld: Option<k::Number>,
        /// A part name for each mesh, in list order (an empty text keeps the mesh's own parts or
        /// letter); empty: letters.
        names: Option<k::List<k::Text>>,
    ) -> (
        /// The joined mesh.
        mesh: k::Mesh,
    ) {
        let names = names.unwrap_or_default();
        if names.len() > meshes.len() {
            return Err(format!(
                "names: {} names for {} meshes (one name a mesh, in list order)",
                names.len(),
                meshes.len()
            )
            .into());
        }
        let named: Vec<PolygonMesh> = meshes
            .iter()
            .enumerate()
            .map(|(k, m)| {
                let given = names.get(k).map(|n| n.trim()).filter(|n| !n.is_empty());
                let mut part = (**m).clone();
                match given {
                    Some(name) => part.parts = MeshParts::single(name, m.face_count()),
                    None if m.parts.is_empty() => {
                        part.parts = MeshParts::single(part_letter(k), m.face_count())
                    }
                    None => {}
                }
                part
            })
            .collect();
        let refs: Vec<&PolygonMesh> = named.iter().collect();
        let joined = fab::join(&refs).map_err(fab_err)?;
        Ok((match weld {
            Some(t) => fab::weld(&joined, t).map_err(fab_err)?,
            None => joined,
        },))
    }
}

/// The letter naming the `k`-th joined mesh (0 → `A`, 25 → `Z`, 26 → `AA`), as spreadsheet
/// columns are named.
fn part_letter(mut k: usize) -> String {
    let mut letters = Vec::new();
    loop {
        letters.push(b'A' + (k % 26) as u8);
        if k < 26 {
            break;
        }
        k = k / 26 - 1;
    }
    letters.reverse();
    String::from_utf8(letters).unwrap_or_default()
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![to_polygons(), cut_by_plane(), mirror(), join()]
}

#[cfg(test)]
mod tests {
    use super::part_letter;

    #[test]
    fn parts_are_lettered_as_spreadsheet_columns() {
        let names: Vec<String> = [0, 1, 25, 26, 27, 51, 52, 701, 702]
            .into_iter()
            .map(part_letter)
            .collect();
        assert_eq!(names, ["A", "B", "Z", "AA", "AB", "AZ", "BA", "ZZ", "AAA"]);
    }
}
