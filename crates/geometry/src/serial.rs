//! Meshes read through serde (the web page's worker messages) checked as they are read: a grid's
//! vertex count, a polygon mesh's faces and parts ([`QuadGrid::validate`],
//! [`PolygonMesh::validate`]). A field that holds a shared mesh reads it with
//! `#[serde(deserialize_with = "cnets_geometry::serial::checked")]`.

use std::sync::Arc;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer};

use crate::{GeometryError, PolygonMesh, QuadGrid};

/// A mesh with invariants serde's derive does not know.
pub trait Checked {
    /// The mesh's invariants hold.
    fn check(&self) -> Result<(), GeometryError>;
}

impl Checked for QuadGrid {
    fn check(&self) -> Result<(), GeometryError> {
        self.validate()
    }
}

impl Checked for PolygonMesh {
    fn check(&self) -> Result<(), GeometryError> {
        self.validate()
    }
}

/// Reads a shared mesh and refuses one whose invariants do not hold.
pub fn checked<'de, D, T>(d: D) -> Result<Arc<T>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de> + Checked,
{
    let mesh = T::deserialize(d)?;
    mesh.check().map_err(D::Error::custom)?;
    Ok(Arc::new(mesh))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DVec3;

    #[derive(serde::Deserialize, Debug)]
    struct Holder(#[serde(deserialize_with = "checked")] Arc<QuadGrid>);

    #[test]
    fn a_grid_whose_vertices_are_not_rows_times_columns_is_refused() {
        let grid = QuadGrid::new(2, 2, vec![DVec3::ZERO; 4]).unwrap();
        let mut text = serde_json::to_string(&grid).unwrap();
        let back = serde_json::from_str::<Holder>(&text).expect("a whole grid reads");
        assert_eq!(*back.0, grid);
        text = text.replace("\"rows\":2", "\"rows\":3");
        let err = serde_json::from_str::<Holder>(&text)
            .unwrap_err()
            .to_string();
        assert!(err.contains("3") && err.contains("4"), "{err}");
    }
}
