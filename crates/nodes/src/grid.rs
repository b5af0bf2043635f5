//! Quad-grid access: rows and columns as polylines.

use cnets_engine::prelude::*;

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

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![row(), column()]
}
