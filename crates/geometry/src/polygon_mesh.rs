//! General polygon meshes (faces with any number of corners).

use glam::DVec3;

use crate::{FaceClass, GeometryError, MeshParts, QuadGrid};

/// A polygon mesh: shared vertices and faces given as vertex-index loops, stored flat.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct PolygonMesh {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// All face corner indices, face after face.
    pub indices: Vec<u32>,
    /// Start of each face in `indices`; face k spans `face_starts[k]..face_starts[k + 1]` (or the end).
    pub face_starts: Vec<u32>,
    /// The named parts the faces belong to (empty: one unnamed part); see [`MeshParts`].
    pub parts: MeshParts,
    /// The configuration class of every face, carried from the cone-net it came from (empty: not
    /// known); see [`FaceClass`].
    pub classes: Vec<FaceClass>,
}

impl PolygonMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self::default()
    }

    /// Builds a mesh from vertices and faces, validating indices and face sizes.
    pub fn from_faces(vertices: Vec<DVec3>, faces: &[Vec<u32>]) -> Result<Self, GeometryError> {
        let mut mesh = Self {
            vertices,
            ..Self::default()
        };
        for face in faces {
            mesh.push_face(face)?;
        }
        Ok(mesh)
    }

    /// Appends a vertex and returns its index.
    pub fn push_vertex(&mut self, p: DVec3) -> u32 {
        self.vertices.push(p);
        (self.vertices.len() - 1) as u32
    }

    /// Appends a face (≥ 3 valid vertex indices).
    pub fn push_face(&mut self, face: &[u32]) -> Result<(), GeometryError> {
        let k = self.face_starts.len();
        if face.len() < 3 {
            return Err(GeometryError::InvalidFace {
                face: k,
                reason: format!("{} corners", face.len()),
            });
        }
        if let Some(bad) = face.iter().find(|&&v| v as usize >= self.vertices.len()) {
            return Err(GeometryError::InvalidFace {
                face: k,
                reason: format!(
                    "vertex {bad} does not exist ({} vertices)",
                    self.vertices.len()
                ),
            });
        }
        self.face_starts.push(self.indices.len() as u32);
        self.indices.extend_from_slice(face);
        Ok(())
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_starts.len()
    }

    /// Corner indices of face `k`.
    pub fn face(&self, k: usize) -> &[u32] {
        let start = self.face_starts[k] as usize;
        let end = self
            .face_starts
            .get(k + 1)
            .map_or(self.indices.len(), |&e| e as usize);
        &self.indices[start..end]
    }

    /// Iterator over faces as index slices.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.face_count()).map(|k| self.face(k))
    }

    /// Checks that every face has ≥ 3 corners and valid indices and the starts are increasing.
    pub fn validate(&self) -> Result<(), GeometryError> {
        let n = self.vertices.len();
        for k in 0..self.face_count() {
            let start = self.face_starts[k] as usize;
            let end = self
                .face_starts
                .get(k + 1)
                .map_or(self.indices.len(), |&e| e as usize);
            if end < start + 3 || end > self.indices.len() {
                return Err(GeometryError::InvalidFace {
                    face: k,
                    reason: "fewer than 3 corners".into(),
                });
            }
            if let Some(bad) = self.indices[start..end].iter().find(|&&v| v as usize >= n) {
                return Err(GeometryError::InvalidFace {
                    face: k,
                    reason: format!("vertex {bad} does not exist ({n} vertices)"),
                });
            }
        }
        if !self.parts.fits(self.face_count()) {
            return Err(GeometryError::InvalidFace {
                face: 0,
                reason: format!(
                    "the mesh's parts name {} faces of its {}",
                    self.parts.of_face.len(),
                    self.face_count()
                ),
            });
        }
        Ok(())
    }

    /// Appends all vertices and faces of `other`. Named parts are merged by name; when only one of
    /// the two has parts, the other's faces join a part named `unnamed`.
    pub fn append(&mut self, other: &PolygonMesh) {
        self.append_parts(&other.parts, other.face_count());
        self.append_classes(other);
        let offset = self.vertices.len() as u32;
        let index_offset = self.indices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.indices
            .extend(other.indices.iter().map(|&v| v + offset));
        self.face_starts
            .extend(other.face_starts.iter().map(|&s| s + index_offset));
    }

    /// Appends `other`'s face classes (before the faces are appended); when only one of the two
    /// knows its classes, the other's faces are [`FaceClass::Unclassified`].
    fn append_classes(&mut self, other: &PolygonMesh) {
        let (own, theirs) = (
            self.face_classes().is_some(),
            other.face_classes().is_some(),
        );
        if !own && !theirs {
            self.classes.clear();
            return;
        }
        if !own {
            self.classes = vec![FaceClass::Unclassified; self.face_count()];
        }
        match other.face_classes() {
            Some(c) => self.classes.extend_from_slice(c),
            None => self.classes.extend(std::iter::repeat_n(
                FaceClass::Unclassified,
                other.face_count(),
            )),
        }
    }

    /// The faces' classes when they are known and fit the mesh (one per face).
    pub fn face_classes(&self) -> Option<&[FaceClass]> {
        (!self.classes.is_empty() && self.classes.len() == self.face_count())
            .then_some(self.classes.as_slice())
    }

    /// Gives this mesh, made from `source` with face `k` from face `sources[k]` of it (a cut, a
    /// weld, a mirror image), the parts and classes of those faces.
    pub fn carry_faces_from(&mut self, source: &PolygonMesh, sources: &[u32]) {
        self.parts = source.parts.for_faces(sources);
        self.classes = match source.face_classes() {
            Some(c) => sources
                .iter()
                .map(|&f| {
                    c.get(f as usize)
                        .copied()
                        .unwrap_or(FaceClass::Unclassified)
                })
                .collect(),
            None => Vec::new(),
        };
    }

    /// Appends `other`'s `faces` faces to this mesh's parts (before the faces are appended).
    fn append_parts(&mut self, other: &MeshParts, faces: usize) {
        if self.parts.is_empty() && other.is_empty() {
            return;
        }
        let own = self.face_count();
        if self.parts.is_empty() && own > 0 {
            self.parts = MeshParts::single("unnamed", own);
        }
        let index_of = |parts: &mut MeshParts, name: &str| -> u32 {
            match parts.names.iter().position(|n| n == name) {
                Some(k) => k as u32,
                None => {
                    parts.names.push(name.to_string());
                    (parts.names.len() - 1) as u32
                }
            }
        };
        if other.is_empty() {
            let k = index_of(&mut self.parts, "unnamed");
            self.parts.of_face.extend(std::iter::repeat_n(k, faces));
        } else {
            let map: Vec<u32> = other
                .names
                .iter()
                .map(|n| index_of(&mut self.parts, n))
                .collect();
            self.parts.of_face.extend(
                other
                    .of_face
                    .iter()
                    .map(|&p| map.get(p as usize).copied().unwrap_or(0)),
            );
        }
    }
}

impl From<&QuadGrid> for PolygonMesh {
    fn from(grid: &QuadGrid) -> Self {
        let mut mesh = PolygonMesh {
            vertices: grid.vertices.clone(),
            indices: Vec::with_capacity(grid.quad_count() * 4),
            face_starts: Vec::with_capacity(grid.quad_count()),
            parts: MeshParts::default(),
            classes: grid
                .face_classes()
                .map(<[FaceClass]>::to_vec)
                .unwrap_or_default(),
        };
        for i in 0..grid.quad_rows() {
            for j in 0..grid.quad_cols() {
                mesh.face_starts.push(mesh.indices.len() as u32);
                mesh.indices
                    .extend(grid.quad_indices(i, j).map(|k| k as u32));
            }
        }
        mesh
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad_grid_converts_to_quads_and_appends() {
        let g = QuadGrid::new(2, 3, (0..6).map(|k| DVec3::splat(k as f64)).collect()).unwrap();
        let m = PolygonMesh::from(&g);
        assert_eq!(m.face_count(), 2);
        assert_eq!(m.face(1), &[1, 2, 5, 4]);
        let mut two = m.clone();
        two.append(&m);
        assert_eq!(two.face_count(), 4);
        assert_eq!(two.face(3), &[7, 8, 11, 10]);
        two.validate().unwrap();
    }

    #[test]
    fn bad_faces_are_rejected() {
        let mut m = PolygonMesh::from_faces(vec![DVec3::ZERO; 3], &[vec![0, 1, 2]]).unwrap();
        assert!(m.push_face(&[0, 1]).is_err());
        assert!(m.push_face(&[0, 1, 9]).is_err());
    }
}
