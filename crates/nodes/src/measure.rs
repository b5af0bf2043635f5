//! Objective measures for optimization: point distances, tube closure (positions and tangents),
//! distance to a reference surface, face-normal alignment, fairness. Every one has an exact
//! gradient for the optimizer (`crate::derivatives::measure`).

use cnets_engine::prelude::*;
use cnets_geometry::fabrication::polygon::newell_vector;
use cnets_geometry::surface_fit::{
    Directions, MAX_SAMPLES, fan_triangle_count, surface_and_vertex_distances,
    vertex_working_bytes, working_bytes,
};
use cnets_geometry::{measure, objectives};

/// The points of a list of points, polylines and/or meshes (their vertices in order), in order.
pub(crate) fn points_of(values: &[Value], what: &str) -> Result<Vec<DVec3>, NodeError> {
    let mut points = Vec::new();
    for (k, v) in values.iter().enumerate() {
        match v {
            Value::Point(p) | Value::Vector(p) => points.push(*p),
            Value::Polyline(p) => points.extend_from_slice(&p.points),
            Value::QuadMesh(m) => points.extend_from_slice(&m.vertices),
            Value::Mesh(m) => points.extend_from_slice(&m.vertices),
            Value::List(items) => points.extend(points_of(items, what)?),
            other => {
                return Err(NodeError::new(format!(
                    "{what}[{k}] must be a point, a polyline or a mesh, got {}",
                    other.type_name()
                )));
            }
        }
    }
    Ok(points)
}

node! {
    /// The sum of squared distances between corresponding points of two point lists (polylines give
    /// their points, meshes their vertices in order): 0 when they coincide. The lists must have the
    /// same length.
    #[node(id = "measure.point_distance", category = "Measure")]
    pub fn point_distance(
        /// First points (or polylines, or meshes).
        a: k::List<k::Any>,
        /// Second points (or polylines, or meshes), as many as in `a`.
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
    /// With `tangents` > 0 it adds that weight times the tangent gap Σ_i |t_i^last − t_i^first|²
    /// (t^first the unit direction of the first strip's edge G_{i,1} − G_{i,0}, t^last of the last
    /// strip's G_{i,M−1} − G_{i,M−2}): the tube then also continues smoothly across the seam.
    #[node(id = "measure.closure", category = "Measure")]
    pub fn closure(
        /// A quad mesh (rows along the generatrix, columns along the directrix).
        mesh: k::QuadMesh,
        /// Weight of the tangent gap in `value` (0: positions only).
        tangents: k::Number = 0.0,
    ) -> (
        /// Σ |G_{i,M−1} − G_{i,0}|² + tangents · Σ |t_i^last − t_i^first|².
        value: k::Number,
        /// The largest gap |G_{i,M−1} − G_{i,0}|.
        max: k::Number,
        /// The tangent gap Σ |t_i^last − t_i^first|² (needs 3 columns; 0 with fewer).
        tangent: k::Number,
    ) {
        if !tangents.is_finite() || tangents < 0.0 {
            return Err(NodeError::new(format!("tangents must be a number ≥ 0, got {tangents}")));
        }
        let (gap, max) = measure::closure_gap(&mesh)?;
        let tangent = match objectives::seam_tangents(&mesh, 0.0) {
            Ok((t, _)) => t,
            Err(e) if tangents > 0.0 => return Err(e.into()),
            Err(_) => 0.0,
        };
        Ok((gap + tangents * tangent, max, tangent))
    }
}

node! {
    /// The distance between a mesh and a reference surface (its polygons fanned into triangles),
    /// e.g. to fit a cone-net to a target hull. `value` and `max` measure from the mesh's vertices
    /// to the reference only; the other outputs measure both directions on points sampled over the
    /// faces, at interior quadrature points, area-weighted: a fan triangle no longer than 1.5 × the
    /// other mesh's mean longest triangle edge by a 3-point rule of degree 2, a longer one split
    /// into n² sub-triangles (n its length over that, rounded up, at most `samples`), each by a
    /// 6-point rule of degree 4: from the mesh to the reference and from the reference to the
    /// mesh, so a fit cannot pull away from parts of the reference unseen. `symmetric` is the
    /// measure to minimize when fitting. Every output has an exact gradient in the mesh's
    /// vertices.
    #[node(id = "measure.surface_distance", category = "Measure")]
    pub fn surface_distance[ctx](
        /// The mesh whose vertices are measured (quad or polygon mesh).
        mesh: k::Mesh,
        /// The reference surface.
        reference: k::Mesh,
        /// The most sub-triangles per triangle edge for the sampled (two-way) outputs (1 to 64):
        /// up to 6 · samples² points on a triangle longer than 1.5 × the other mesh's mean
        /// longest edge, 3 on a shorter one.
        samples: k::Integer = 2,
    ) -> (
        /// Mean of the squared vertex distances (mesh vertices → reference).
        value: k::Number,
        /// The largest vertex distance.
        max: k::Number,
        /// The symmetric measure: ½ (to_reference + from_reference), a mean squared distance.
        symmetric: k::Number,
        /// The sampled Hausdorff distance: the larger of to_reference_max and from_reference_max.
        hausdorff: k::Number,
        /// Area-weighted mean of the squared distances from the mesh's faces to the reference.
        to_reference: k::Number,
        /// The largest distance from the mesh (face samples and vertices) to the reference.
        to_reference_max: k::Number,
        /// Area-weighted mean of the squared distances from the reference's faces to the mesh.
        from_reference: k::Number,
        /// The largest distance from the reference (face samples and vertices) to the mesh.
        from_reference_max: k::Number,
    ) {
        let samples = sample_count(samples)?;
        let one_sided = ctx.wants("value") || ctx.wants("max");
        let both = ["symmetric", "hausdorff"].iter().any(|o| ctx.wants(o));
        let directions = Directions {
            to_reference: both || ctx.wants("to_reference") || ctx.wants("to_reference_max"),
            from_reference: both || ctx.wants("from_reference") || ctx.wants("from_reference_max"),
        };
        reserve_surface_distance(ctx, &mesh, &reference, one_sided, directions, false)?;
        // One hierarchy of the reference serves the vertices and the samples towards it.
        let (d, (value, max)) =
            surface_and_vertex_distances(&mesh, &reference, samples, directions, one_sided)?;
        Ok((
            value,
            max,
            d.symmetric(),
            d.hausdorff(),
            d.to_reference,
            d.to_reference_max,
            d.from_reference,
            d.from_reference_max,
        ))
    }
}

/// Declares to the memory budget, before anything is built, what `measure.surface_distance` (or,
/// with `gradient`, its product) will allocate: the closest-point hierarchies and fan triangles
/// of the directions asked for (the samples are never stored).
pub(crate) fn reserve_surface_distance(
    ctx: &NodeContext,
    mesh: &PolygonMesh,
    reference: &PolygonMesh,
    one_sided: bool,
    directions: Directions,
    gradient: bool,
) -> Result<(), NodeError> {
    let (tm, tr) = (fan_triangle_count(mesh), fan_triangle_count(reference));
    let (vm, vr) = (mesh.vertices.len(), reference.vertices.len());
    let mut bytes = if one_sided {
        vertex_working_bytes(vm, tr, gradient)
    } else {
        0
    };
    if directions.to_reference || directions.from_reference {
        bytes = bytes.max(working_bytes(tm, vm, tr, vr, directions, gradient));
    }
    ctx.reserve(
        bytes,
        &format!(
            "the surface distance between a mesh of {tm} triangles and a reference of {tr} \
             triangles"
        ),
    )
}

/// The `samples` input of `measure.surface_distance`, checked.
pub(crate) fn sample_count(samples: i64) -> Result<usize, NodeError> {
    usize::try_from(samples)
        .ok()
        .filter(|n| (1..=MAX_SAMPLES).contains(n))
        .ok_or_else(|| {
            NodeError::new(format!(
                "samples must be a whole number from 1 to {MAX_SAMPLES}, got {samples}"
            ))
        })
}

/// One target direction per face of `mesh`: the given direction, or the normal of the reference
/// face closest to each face's centroid.
pub(crate) fn alignment_targets(
    mesh: &PolygonMesh,
    target: Option<DVec3>,
    reference: Option<&PolygonMesh>,
) -> Result<Vec<DVec3>, NodeError> {
    match (target, reference) {
        (Some(t), None) => Ok(vec![t]),
        (None, Some(r)) => {
            let query = cnets_geometry::mesh_query::MeshQuery::new(r)
                .map_err(|e| NodeError::new(format!("the reference mesh: {e}")))?;
            let hits = query.closest_all(&objectives::face_centroids(mesh))?;
            Ok(hits
                .iter()
                .map(|h| objectives::face_normal(r, h.face))
                .collect())
        }
        _ => Err(NodeError::new(
            "give either a target direction or a reference mesh (not both)",
        )),
    }
}

node! {
    /// Face-normal alignment: the mean over the faces of 1 − (n · t)², n a face's unit normal and t
    /// its target (a direction, or the normal of the reference mesh's face closest to the face's
    /// centroid): 0 when every face is perpendicular to its target direction (either side).
    #[node(id = "measure.normal_alignment", category = "Measure")]
    pub fn normal_alignment(
        /// The mesh whose face normals are measured (quad or polygon mesh).
        mesh: k::Mesh,
        /// The target direction (or give `reference`).
        target: Option<k::Vector>,
        /// A reference mesh whose normals are the targets (or give `target`).
        reference: Option<k::Mesh>,
    ) -> (
        /// Mean of 1 − (n · t)² over the faces.
        value: k::Number,
        /// The largest term.
        max: k::Number,
    ) {
        let targets = alignment_targets(&mesh, target, reference.as_deref())?;
        let (value, max, _) = objectives::normal_alignment(&mesh, &targets, 0.0)?;
        Ok((value, max))
    }
}

/// The rows of a table of numbers (a list of numbers is one row).
pub(crate) fn table_rows(value: &Value) -> Result<Vec<Vec<f64>>, NodeError> {
    let row = |v: &Value| -> Result<Vec<f64>, NodeError> {
        match v {
            Value::List(items) => items
                .iter()
                .map(|x| {
                    x.as_f64().ok_or_else(|| {
                        NodeError::new(format!("values: expected numbers, got {}", x.type_name()))
                    })
                })
                .collect(),
            other => other.as_f64().map(|x| vec![x]).ok_or_else(|| {
                NodeError::new(format!(
                    "values: expected numbers, got {}",
                    other.type_name()
                ))
            }),
        }
    };
    match value {
        Value::List(items) if items.iter().any(|v| matches!(v, Value::List(_))) => {
            items.iter().map(row).collect()
        }
        other => Ok(vec![row(other)?]),
    }
}

node! {
    /// Fairness: the sum of squared second differences x_{j−1} − 2x_j + x_{j+1} along the rows and
    /// columns of a table of numbers (e.g. a ratio table; columns when the rows have equal lengths),
    /// or |G_{j−1} − 2G_j + G_{j+1}|² along the polylines (rows and columns) of a quad mesh. 0 for
    /// linear progressions: a smoothness term to add to an objective.
    #[node(id = "measure.fairness", category = "Measure")]
    pub fn fairness(
        /// A table (or list) of numbers (or give `mesh`).
        values: Option<k::Table<k::Number>>,
        /// A quad mesh (or give `values`).
        mesh: Option<k::QuadMesh>,
    ) -> (
        /// Σ of squared second differences.
        value: k::Number,
    ) {
        match (values, mesh) {
            (Some(v), None) => Ok((objectives::table_fairness(&table_rows(&v)?, 0.0).0,)),
            (None, Some(m)) => Ok((objectives::mesh_fairness(&m, 0.0)?.0,)),
            _ => Err(NodeError::new("give either values or a mesh (not both)")),
        }
    }
}

/// The corners of face `f` of `mesh`, in order.
pub(crate) fn face_corners(mesh: &PolygonMesh, f: usize) -> Vec<DVec3> {
    mesh.face(f)
        .iter()
        .map(|&v| mesh.vertices[v as usize])
        .collect()
}

/// The area of every face of `mesh`: half the length of its Newell normal (a planar polygon's
/// area; a non-planar face's vector area, the area of its projection on its Newell plane).
pub(crate) fn face_areas(mesh: &PolygonMesh) -> Vec<f64> {
    (0..mesh.face_count())
        .map(|f| 0.5 * newell_vector(&face_corners(mesh, f)).length())
        .collect()
}

node! {
    /// The area of a mesh: the sum of its faces' areas, each half the length of the face's Newell
    /// normal Σ p_k × p_{k+1} (a planar polygon's area; a non-planar face counts the area of its
    /// projection on its Newell plane). Has an exact gradient in the mesh's vertices, for sweeps
    /// and objectives on the surface a design covers.
    #[node(id = "measure.area", category = "Measure")]
    pub fn area(
        /// The mesh (quad or polygon mesh).
        mesh: k::Mesh,
    ) -> (
        /// The sum of the faces' areas.
        total: k::Number,
        /// The area of every face, in face order.
        faces: k::List<k::Number>,
    ) {
        let faces = face_areas(&mesh);
        Ok((faces.iter().sum::<f64>(), faces))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        point_distance(),
        closure(),
        surface_distance(),
        normal_alignment(),
        fairness(),
        area(),
    ]
}
