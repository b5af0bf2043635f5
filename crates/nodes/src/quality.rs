//! Quality measures of quad meshes.

use cnets_engine::prelude::*;
use cnets_geometry::conenet;

node! {
    /// Planarity of every quad of a quad mesh: the distance between the two diagonal lines divided by
    /// the mean diagonal length (as libigl). 0 means exactly planar.
    #[node(id = "mesh.planarity", category = "Analysis", name = "Planarity")]
    pub fn planarity(
        /// A quad mesh.
        mesh: k::QuadMesh,
    ) -> (
        /// The largest planarity value.
        max: k::Number,
        /// The mean planarity.
        mean: k::Number,
        /// Planarity per face, row-major over quad rows × quad columns.
        per_face: k::List<k::Number>,
    ) {
        let p = conenet::planarity(&mesh)?;
        Ok((p.max, p.mean, p.per_face))
    }
}

node! {
    /// The cone check of a quad mesh: for each strip between columns j and j+1, how far the lines
    /// G_ij G_i,j+1 miss a common point (relative), and that point (null at infinity).
    #[node(id = "cnets.cone_check", category = "Analysis", name = "Cone check")]
    pub fn cone_check(
        /// A quad mesh.
        mesh: k::QuadMesh,
    ) -> (
        /// The largest residual.
        max: k::Number,
        /// The residual per strip (M−1).
        residuals: k::List<k::Number>,
        /// The fitted apex per strip, null at infinity.
        #[ui(layer = Apices)]
        apices: k::List<Option<k::Point>>,
    ) {
        let c = conenet::cone_check(&mesh)?;
        Ok((c.max, c.residuals, c.apices))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![planarity(), cone_check()]
}
