//! Quad-grid access: rows and columns as polylines.

use cnets_engine::prelude::*;
use cnets_geometry::curves::Transform;

/// Resolves an index that may count from the end (−1 = last).
fn resolve(index: i64, len: usize, what: &str) -> Result<usize, NodeError> {
    let k = if index < 0 { len as i64 + index } else { index };
    if (0..len as i64).contains(&k) {
        Ok(k as usize)
    } else {
        Err(NodeError::new(format!(
            "{what} index {index} is out of range (the mesh has {len})"
        )))
    }
}

node! {
    /// Row i of a quad mesh as a polyline: the directrix-aligned polyline G_{i,:} (closed when the
    /// columns wrap). Negative indices count from the end (−1 = last row).
    #[node(id = "mesh.row", category = "Mesh")]
    pub fn row(
        /// A quad mesh.
        mesh: k::QuadMesh,
        /// Row index (negative: from the end).
        index: k::Integer = 0,
    ) -> (
        /// The row.
        curve: k::Polyline,
    ) {
        Ok((mesh.row(resolve(index, mesh.rows, "row")?),))
    }
}

node! {
    /// Column j of a quad mesh as a polyline: the generatrix-aligned polyline G_{:,j} (closed when the
    /// rows wrap). Negative indices count from the end (−1 = last column, e.g. a tube's end polygon).
    #[node(id = "mesh.column", category = "Mesh")]
    pub fn column(
        /// A quad mesh.
        mesh: k::QuadMesh,
        /// Column index (negative: from the end).
        index: k::Integer = 0,
    ) -> (
        /// The column.
        curve: k::Polyline,
    ) {
        Ok((mesh.column(resolve(index, mesh.cols, "column")?),))
    }
}

node! {
    /// Moves, rotates, scales or mirrors a quad mesh, keeping its grid: scale about `centre`, then
    /// rotate by `angle` degrees about `axis` through `centre`, then mirror in `mirror`, then move by
    /// `translation` (the same order as `curve.transform`).
    #[node(id = "mesh.transform", category = "Mesh")]
    pub fn transform(
        /// The quad mesh.
        mesh: k::QuadMesh,
        /// Vector to move by (applied last).
        translation: k::Vector = DVec3::ZERO,
        /// Rotation angle in degrees about `axis` through `centre`.
        angle: k::Number = 0.0,
        /// Direction of the rotation axis (non-zero when `angle` ≠ 0).
        axis: k::Vector = DVec3::Z,
        /// Centre of scaling and a point on the rotation axis.
        centre: k::Point = DVec3::ZERO,
        /// Uniform scale factor (≠ 0).
        scale: k::Number = 1.0,
        /// Plane to mirror in (none: no mirroring).
        mirror: Option<k::Plane>,
    ) -> (
        /// The transformed mesh.
        mesh: k::QuadMesh,
    ) {
        let t = Transform { translation, angle, axis, centre, scale, mirror };
        let vertices = mesh.vertices.iter().map(|&p| t.apply(p)).collect::<Result<Vec<_>, _>>()?;
        Ok((QuadGrid { vertices, ..(*mesh).clone() },))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![row(), column(), transform()]
}
