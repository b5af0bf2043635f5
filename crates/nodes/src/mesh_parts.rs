//! Meshes taken apart and put together (`mesh.deconstruct`, `mesh.construct`) and closest points on
//! a mesh (`mesh.closest_point`, BVH-accelerated through `cnets_geometry::mesh_query`).

use cnets_engine::prelude::*;
use cnets_geometry::mesh_query::MeshQuery;

node! {
    /// The vertices and faces of a mesh (a quad mesh converts: one quad a grid cell). Each face is a
    /// list of vertex indices, in order around the face.
    #[node(id = "mesh.deconstruct", category = "Mesh", name = "Deconstruct mesh")]
    pub fn deconstruct(
        /// The mesh.
        mesh: k::Mesh,
    ) -> (
        /// Its vertices.
        vertices: k::List<k::Point>,
        /// Its faces: a list of vertex-index lists.
        faces: k::Tree<k::Integer>,
    ) {
        let faces = mesh
            .faces()
            .map(|f| Value::list(f.iter().map(|&i| Value::Integer(i64::from(i))).collect()))
            .collect();
        Ok((mesh.vertices.clone(), Value::list(faces)))
    }
}

/// One face of `mesh.construct`'s input: a list of at least three vertex indices.
fn face_indices(k: usize, face: &Value, vertex_count: usize) -> Result<Vec<u32>, NodeError> {
    let items = face.as_list().ok_or_else(|| {
        NodeError::new(format!(
            "face {k} is a {}, not a list of vertex indices",
            face.type_name()
        ))
    })?;
    if items.len() < 3 {
        return Err(format!(
            "face {k} has {} corners: a face needs at least 3",
            items.len()
        )
        .into());
    }
    items
        .iter()
        .map(|v| {
            let index = match v {
                Value::Integer(i) => Some(*i),
                Value::Number(x) if x.fract() == 0.0 && x.abs() < 1e15 => Some(*x as i64),
                _ => None,
            };
            index
                .and_then(|i| u32::try_from(i).ok())
                .filter(|&i| (i as usize) < vertex_count)
                .ok_or_else(|| {
                    NodeError::new(format!(
                        "face {k}: {} is not a vertex index (there are {vertex_count} vertices, 0 to {})",
                        crate::view::item_text(v),
                        vertex_count.saturating_sub(1)
                    ))
                })
        })
        .collect()
}

node! {
    /// A mesh from vertices and faces (each face a list of at least three vertex indices, in order
    /// around it). Every index is checked: a bad one is an error naming its face.
    #[node(id = "mesh.construct", category = "Mesh", name = "Construct mesh")]
    pub fn construct(
        /// The vertices.
        vertices: k::List<k::Point>,
        /// The faces: a list of vertex-index lists.
        faces: k::Tree<k::Integer>,
    ) -> (
        /// The mesh.
        mesh: k::Mesh,
    ) {
        let faces: Vec<Value> = match faces.as_list() {
            Some(items) if items.iter().all(|f| matches!(f, Value::List(_))) => items.to_vec(),
            // A single face given as a flat list of indices.
            Some(_) => vec![faces.clone()],
            None => return Err("faces must be a list of vertex-index lists".into()),
        };
        if let Some(k) = vertices.iter().position(|p| !p.is_finite()) {
            return Err(format!("vertex {k} is not finite").into());
        }
        let mut mesh = PolygonMesh { vertices, ..PolygonMesh::default() };
        for (k, face) in faces.iter().enumerate() {
            let indices = face_indices(k, face, mesh.vertices.len())?;
            mesh.push_face(&indices)?;
        }
        Ok((mesh,))
    }
}

node! {
    /// The closest point of a mesh to each given point, its distance, and the face it lies on
    /// (index into the mesh's faces). Uses a bounding-volume hierarchy over the mesh's triangles
    /// (parry3d), so many points against a large mesh stay fast: 10⁵ points against 10⁵ triangles
    /// take well under a second.
    #[node(id = "mesh.closest_point", category = "Mesh")]
    pub fn closest_point(
        /// The mesh (a quad mesh converts).
        mesh: k::Mesh,
        /// The points to project.
        points: k::List<k::Point>,
    ) -> (
        /// The closest points on the mesh.
        points: k::List<k::Point>,
        /// Their distances from the given points.
        distances: k::List<k::Number>,
        /// The face each closest point lies on.
        faces: k::List<k::Integer>,
    ) {
        let query = MeshQuery::new(&mesh)?;
        let hits = query.closest_all(&points)?;
        Ok((
            hits.iter().map(|h| h.point).collect::<Vec<_>>(),
            hits.iter().map(|h| h.distance).collect::<Vec<_>>(),
            hits.iter().map(|h| h.face as i64).collect::<Vec<_>>(),
        ))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![deconstruct(), construct(), closest_point()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{ints, nums, points, run_named};

    fn square_and_triangle() -> (Value, Value) {
        let vertices = points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
        ]);
        let faces = Value::list(vec![ints(&[0, 1, 2, 3]), ints(&[1, 4, 2])]);
        (vertices, faces)
    }

    #[test]
    fn construct_and_deconstruct_round_trip_polygons() {
        let (vertices, faces) = square_and_triangle();
        let out = run_named(
            &construct(),
            &[("vertices", vertices.clone()), ("faces", faces.clone())],
        )
        .unwrap();
        let Value::Mesh(mesh) = &out[0] else {
            panic!("a mesh")
        };
        assert_eq!(mesh.face_count(), 2);
        assert_eq!(mesh.face(0), &[0, 1, 2, 3], "a quad stays a quad");
        let parts = run_named(&deconstruct(), &[("mesh", out[0].clone())]).unwrap();
        assert_eq!(parts, vec![vertices, faces]);
        // A quad grid converts.
        let grid = QuadGrid::new(
            2,
            3,
            (0..6)
                .map(|k| DVec3::new(k as f64, 0.0, (k / 3) as f64))
                .collect(),
        )
        .unwrap();
        let parts = run_named(&deconstruct(), &[("mesh", Value::from(grid))]).unwrap();
        assert_eq!(parts[1].as_list().unwrap().len(), 2);
    }

    #[test]
    fn construct_names_the_bad_face() {
        let (vertices, _) = square_and_triangle();
        let bad = Value::list(vec![ints(&[0, 1, 2]), ints(&[1, 2, 9])]);
        let e = run_named(
            &construct(),
            &[("vertices", vertices.clone()), ("faces", bad)],
        )
        .unwrap_err();
        assert!(
            e.contains("face 1") && e.contains("9 is not a vertex index"),
            "{e}"
        );
        let short = Value::list(vec![ints(&[0, 1])]);
        let e = run_named(
            &construct(),
            &[("vertices", vertices.clone()), ("faces", short)],
        )
        .unwrap_err();
        assert!(e.contains("face 0 has 2 corners"), "{e}");
        let negative = Value::list(vec![ints(&[0, -1, 2])]);
        assert!(
            run_named(
                &construct(),
                &[("vertices", vertices.clone()), ("faces", negative)]
            )
            .is_err()
        );
        let fractional = Value::list(vec![nums(&[0.0, 1.5, 2.0])]);
        assert!(
            run_named(
                &construct(),
                &[("vertices", vertices), ("faces", fractional)]
            )
            .is_err()
        );
    }

    #[test]
    fn closest_points_report_distance_and_face() {
        let (vertices, faces) = square_and_triangle();
        let mesh = run_named(&construct(), &[("vertices", vertices), ("faces", faces)])
            .unwrap()
            .remove(0);
        let probes = points(&[[0.5, 0.5, 2.0], [1.9, 0.05, -1.0], [-1.0, 0.5, 0.0]]);
        let out = run_named(&closest_point(), &[("mesh", mesh), ("points", probes)]).unwrap();
        assert_eq!(
            out[0],
            points(&[[0.5, 0.5, 0.0], [1.9, 0.05, 0.0], [0.0, 0.5, 0.0]])
        );
        assert_eq!(out[1], nums(&[2.0, 1.0, 1.0]));
        assert_eq!(out[2], ints(&[0, 1, 0]));
    }
}
