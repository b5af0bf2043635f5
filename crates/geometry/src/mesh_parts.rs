//! Named parts of a polygon mesh: which net each face of a joined structure came from.
//!
//! `mesh.join` names each mesh it joins (or keeps the parts a mesh already has); every operation
//! that makes a mesh from another (cut, mirror, weld, transform) carries each face's part along with
//! the face, so the legend, the planarity and class figures, the unrolled strips' labels and the GLB
//! mesh names can say which net a face came from.

/// Named parts of a mesh: a part for every face and the parts' names. Empty: the mesh is one
/// unnamed part (every mesh made by one net).
#[derive(Debug, Clone, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct MeshParts {
    /// The parts' names, in the order they were joined.
    pub names: Vec<String>,
    /// The part of every face (an index into `names`); empty exactly when `names` is.
    pub of_face: Vec<u32>,
}

impl MeshParts {
    /// True when the mesh is one unnamed part.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// One part named `name` covering `faces` faces.
    pub fn single(name: impl Into<String>, faces: usize) -> Self {
        Self {
            names: vec![name.into()],
            of_face: vec![0; faces],
        }
    }

    /// The name of the part face `face` belongs to (`None` for an unnamed mesh).
    pub fn name_of(&self, face: usize) -> Option<&str> {
        let k = *self.of_face.get(face)? as usize;
        self.names.get(k).map(String::as_str)
    }

    /// The parts of a mesh made from this one, whose face `k` came from face `sources[k]` of this
    /// mesh (a cut, a weld, a mirror image). Parts no face came from keep their names, so a part's
    /// index means the same part before and after.
    pub fn for_faces(&self, sources: &[u32]) -> Self {
        if self.is_empty() {
            return Self::default();
        }
        Self {
            names: self.names.clone(),
            of_face: sources
                .iter()
                .map(|&f| self.of_face.get(f as usize).copied().unwrap_or(0))
                .collect(),
        }
    }

    /// Whether these parts fit a mesh of `faces` faces (every face has a part with a name).
    pub fn fits(&self, faces: usize) -> bool {
        self.is_empty()
            || (self.of_face.len() == faces
                && self
                    .of_face
                    .iter()
                    .all(|&p| (p as usize) < self.names.len()))
    }

    /// The face ranges of each part as a list of face indices, in part order (faces in order).
    pub fn faces_of_each(&self) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); self.names.len()];
        for (f, &p) in self.of_face.iter().enumerate() {
            if let Some(list) = out.get_mut(p as usize) {
                list.push(f);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_follow_their_faces() {
        let parts = MeshParts {
            names: vec!["wall".into(), "canopy".into()],
            of_face: vec![0, 0, 1, 1],
        };
        assert!(parts.fits(4));
        assert!(!parts.fits(3));
        assert_eq!(parts.name_of(2), Some("canopy"));
        assert_eq!(parts.name_of(9), None);
        let mirrored = parts.for_faces(&[0, 1, 2, 3, 3, 2]);
        assert_eq!(mirrored.of_face, vec![0, 0, 1, 1, 1, 1]);
        assert_eq!(mirrored.faces_of_each(), vec![vec![0, 1], vec![2, 3, 4, 5]]);
        assert!(MeshParts::default().for_faces(&[0, 1]).is_empty());
        assert_eq!(MeshParts::single("A", 2).name_of(1), Some("A"));
    }
}
