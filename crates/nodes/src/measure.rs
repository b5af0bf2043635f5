//! Objective measures for optimization: point distances, tube closure, distance to a reference surface.

use cnets_engine::prelude::*;
use cnets_geometry::measure;

/// The points of a list of points and/or polylines, in order.
fn points_of(values: &[Value], what: &str) -> Result<Vec<DVec3>, NodeError> {
    let mut points = Vec::new();
    for (k, v) in values.iter().enumerate() {
        match v {
            Value::Point(p) | Value::Vector(p) => points.push(*p),
            Value::Polyline(p) => points.extend_from_slice(&p.points),
            Value::List(items) => points.extend(points_of(items, what)?),
            other => {
                return Err(NodeError::new(format!(
                    "{what}[{k}] must be a point or a polyline, got {}",
                    other.type_name()
                )));
            }
        }
    }
    Ok(points)
}

node! {
    /// The sum of squared distances between corresponding points of two point lists (polylines give
    /// their points): 0 when they coincide. The lists must have the same length.
    #[node(id = "measure.point_distance", category = "Measure")]
    pub fn point_distance(
        /// First points (or polylines).
        a: k::List<k::Any>,
        /// Second points (or polylines), as many as in `a`.
        b: k::List<k::Any>,
    ) -> (
        /// Σ |a_k − b_k|².
        value: k::Number,
        /// The largest distance |a_k − b_k|.
        max: k::Number,
    ) {
        let (pa, pb) = (points_of(&a, "a")?, points_of(&b, "b")?);
        Ok(measure::point_distance(&pa, &pb)?)
    }
}

node! {
    /// The closure gap of a tube: the sum of squared distances between its first and last
    /// generatrix-aligned polylines (columns 0 and M−1 of the quad mesh): 0 when the tube closes.
    #[node(id = "measure.closure", category = "Measure")]
    pub fn closure(
        /// A quad mesh (rows along the generatrix, columns along the directrix).
        mesh: k::QuadMesh,
    ) -> (
        /// Σ |G_{i,M−1} − G_{i,0}|².
        value: k::Number,
        /// The largest gap |G_{i,M−1} − G_{i,0}|.
        max: k::Number,
    ) {
        Ok(measure::closure_gap(&mesh)?)
    }
}

node! {
    /// The mean squared distance from the vertices of a mesh to the surface of a reference mesh (its
    /// polygons fanned into triangles), e.g. to fit a cone-net to a target hull.
    #[node(id = "measure.surface_distance", category = "Measure")]
    pub fn surface_distance(
        /// The mesh whose vertices are measured (quad or polygon mesh).
        mesh: k::Mesh,
        /// The reference surface.
        reference: k::Mesh,
    ) -> (
        /// Mean of the squared vertex distances.
        value: k::Number,
        /// The largest vertex distance.
        max: k::Number,
    ) {
        Ok(measure::surface_distance(&mesh.vertices, &reference)?)
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![point_distance(), closure(), surface_distance()]
}
