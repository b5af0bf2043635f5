//! Cone-net construction: C-tube, CNets Construct, Construct Coplanar, encoding.
//!
//! Every construction node outputs `mesh`, `apex` (the a_j actually used), `apices` (C_j, `null` at
//! infinity), `planes` (N lists of M−1 normals), `configurations` (N lists of M−1 labels),
//! `corrections` (text) and `quality` (a record).

use std::sync::Arc;

use cnets_engine::prelude::*;
use cnets_engine::value::Packed;
use cnets_geometry::conenet::{
    self, ApexInput, ColumnValues, ConeNet, Configuration, ConstructInputs, CoplanarInputs,
    CtubeInputs, EndPlanes, GridValues, NormalsInput, Reports,
};
use rayon::prelude::*;

/// The apex input: one number broadcast to every column, or one value per directrix edge.
pub(crate) fn apex_input(values: Vec<f64>, normalized: bool, scale: Option<f64>) -> ApexInput {
    let values = match values.as_slice() {
        [single] => ColumnValues::Uniform(*single),
        _ => ColumnValues::List(values),
    };
    ApexInput {
        values,
        normalized,
        scale,
        seam: None,
    }
}

/// Reads the `end_planes` choice.
pub(crate) fn parse_end_planes(text: &str) -> Result<EndPlanes, NodeError> {
    EndPlanes::parse(text).ok_or_else(|| {
        NodeError::new(format!(
            "end_planes must be \"perpendicular\" or \"mirror\", got {text:?}"
        ))
    })
}

/// Reads a number, a list of numbers, or a list of lists of numbers.
pub(crate) fn grid_values(value: &Value, what: &str) -> Result<GridValues, NodeError> {
    // The location is only formatted for an error: tables have a million entries.
    let number = |v: &Value, at: &(dyn Fn() -> String + Sync)| -> Result<f64, NodeError> {
        v.as_f64().ok_or_else(|| {
            NodeError::new(format!(
                "{what}{} must be a number, got {}",
                at(),
                v.type_name()
            ))
        })
    };
    match value {
        // A per-vertex table (a million entries at 1000 × 1000) is read in parallel by rows.
        Value::List(items) if items.iter().any(|v| matches!(v, Value::List(_))) => items
            .par_iter()
            .enumerate()
            .map(|(i, row)| match row {
                // A packed row of numbers (JSON input) is copied as it is.
                Value::List(row) => match row.as_packed() {
                    Some(Packed::Numbers { table, range }) => Ok(table[range.clone()].to_vec()),
                    _ => row
                        .iter()
                        .enumerate()
                        .map(|(j, v)| number(v, &|| format!("[{i}][{j}]")))
                        .collect(),
                },
                _ => Err(NodeError::new(format!(
                    "{what}[{i}] must be a list (a table needs one list per generatrix point)"
                ))),
            })
            .collect::<Result<Vec<Vec<f64>>, _>>()
            .map(GridValues::PerVertex),
        Value::List(items) => match &items[..] {
            [single] => number(single, &|| "[0]".into()).map(GridValues::Uniform),
            _ => items
                .iter()
                .enumerate()
                .map(|(j, v)| number(v, &|| format!("[{j}]")))
                .collect::<Result<_, _>>()
                .map(GridValues::PerColumn),
        },
        other => number(other, &String::new).map(GridValues::Uniform),
    }
}

/// Reads M−1 vectors shared by all rows, or N lists of M−1 vectors.
fn normals_input(value: Option<Value>) -> Result<NormalsInput, NodeError> {
    let Some(value) = value else {
        return Ok(NormalsInput::Monge);
    };
    let vector = |v: &Value, at: &dyn Fn() -> String| -> Result<DVec3, NodeError> {
        v.as_vec3().ok_or_else(|| {
            NodeError::new(format!(
                "normals{} must be a vector, got {}",
                at(),
                v.type_name()
            ))
        })
    };
    match &value {
        Value::List(items) if items.iter().any(|v| v.as_list().is_some()) => items
            .iter()
            .enumerate()
            .map(|(i, row)| match row.as_list() {
                Some(row) => row
                    .iter()
                    .enumerate()
                    .map(|(j, v)| vector(v, &|| format!("[{i}][{j}]")))
                    .collect(),
                None => Err(NodeError::new(format!(
                    "normals[{i}] must be a list of vectors"
                ))),
            })
            .collect::<Result<Vec<Vec<DVec3>>, _>>()
            .map(NormalsInput::PerVertex),
        Value::List(items) => items
            .iter()
            .enumerate()
            .map(|(j, v)| vector(v, &|| format!("[{j}]")))
            .collect::<Result<Vec<DVec3>, _>>()
            .map(NormalsInput::PerColumn),
        other => vector(other, &String::new).map(|v| NormalsInput::PerColumn(vec![v])),
    }
}

/// The configuration labels by [`Configuration`] discriminant. Each output row makes its own four
/// shared texts, so rows convert in parallel without contending for one reference count.
fn labels() -> [Value; 4] {
    Configuration::ALL.map(|c| Value::text(c.as_str()))
}

/// The quality record of a cone-net.
pub fn quality_record(net: &ConeNet) -> Record {
    let q = &net.quality;
    let counts = &q.configurations;
    Record::new()
        .with("max_planarity", q.max_planarity)
        .with("mean_planarity", q.mean_planarity)
        .with("max_cone_residual", q.max_cone_residual)
        .with(
            "cone_residuals",
            Value::list(q.cone_residuals.iter().map(|&r| Value::Number(r)).collect()),
        )
        .with(
            "configurations",
            Record::new()
                .with("++", counts.plus_plus as i64)
                .with("--", counts.minus_minus as i64)
                .with("+-", counts.plus_minus as i64)
                .with("-+", counts.minus_plus as i64),
        )
        .with(
            "first_bad",
            q.first_bad.map_or(Value::Null, |(i, j)| {
                Value::list(vec![Value::Integer(i as i64), Value::Integer(j as i64)])
            }),
        )
        .with("corrections", net.corrections.len() as i64)
        .with("vertices", net.mesh.vertices.len() as i64)
        .with("faces", net.mesh.quad_count() as i64)
}

/// The common outputs of every construction node, in output order.
type Outputs = (
    QuadGrid,
    Vec<f64>,
    Vec<Option<DVec3>>,
    Value,
    Value,
    Vec<String>,
    Record,
    Vec<f64>,
);

/// The reports a construction node computes: those whose outputs were asked for (lazy outputs).
fn reports(ctx: &NodeContext) -> Reports {
    Reports {
        apices: ctx.wants("apices"),
        quality: ctx.wants("quality"),
    }
}

/// The node's outputs from a construction; outputs not asked for ([`NodeContext::wants`]) are
/// left empty.
fn outputs(ctx: &NodeContext, mut net: ConeNet) -> Outputs {
    // Every sweep step fails on a non-finite vertex (`GeometryError::NonFiniteOutput`).
    ctx.vouch_finite("mesh");
    // The mesh keeps its faces' classes (one byte a face), through cuts, mirrors and joins.
    net.mesh.classes = net.configurations.face_classes(&net.mesh);
    let margins = if ctx.wants("margins") {
        conenet::margins::face_margins(&net)
    } else {
        Vec::new()
    };
    let quality = if ctx.wants("quality") {
        quality_record(&net)
    } else {
        Record::new()
    };
    let corrections = if ctx.wants("corrections") {
        net.correction_lines()
    } else {
        Vec::new()
    };
    // A 1000 × 1000 net has a million normals and labels: each output row is a packed row of one
    // shared table (the construction's own normals, moved; one byte per label), not a million
    // values.
    let configurations = if ctx.wants("configurations") {
        let codes = Arc::new(net.configurations.codes());
        let labels: Arc<[Value]> = labels().into();
        Value::list(
            (0..net.configurations.rows())
                .map(|i| {
                    let range = net.configurations.row_range(i);
                    Value::List(Items::labels(codes.clone(), range, labels.clone()))
                })
                .collect(),
        )
    } else {
        Value::list(Vec::new())
    };
    let planes = if ctx.wants("planes") {
        let normal_rows: Vec<_> = (0..net.normals.rows())
            .map(|i| net.normals.row_range(i))
            .collect();
        let normals = Arc::new(net.normals.into_data());
        Value::list(
            normal_rows
                .into_iter()
                .map(|range| Value::List(Items::vectors(normals.clone(), range)))
                .collect(),
        )
    } else {
        Value::list(Vec::new())
    };
    let apex = if ctx.wants("apex") {
        net.apex
    } else {
        Vec::new()
    };
    (
        net.mesh,
        apex,
        net.apices,
        planes,
        configurations,
        corrections,
        quality,
        margins,
    )
}

/// Bytes a construction needs per mesh vertex: the vertex (24), its plane normal (24), its
/// configuration label (1) and the kernel's working rows (15); the faces' classes the mesh keeps
/// (a byte a face) are inside that estimate's margin.
const CONSTRUCTION_BYTES_PER_VERTEX: usize = 64;

/// Checks, before anything is allocated, that a construction sweeping `generatrix` along
/// `directrix` fits in the memory budget (two 100 000-point polylines make 10¹⁰ vertices: 640 GB).
fn reserve_construction(
    ctx: &NodeContext,
    directrix: &Polyline,
    generatrix: &Polyline,
) -> Result<(), NodeError> {
    let rows = generatrix.len() as u128;
    let cols = directrix.len() as u128 + u128::from(directrix.closed);
    ctx.reserve(
        cnets_engine::budget::bytes_of(rows.saturating_mul(cols), CONSTRUCTION_BYTES_PER_VERTEX),
        &format!("a cone-net of {rows} × {cols} vertices"),
    )
}

fn unwrap_arc<T: Clone>(a: Arc<T>) -> T {
    Arc::try_unwrap(a).unwrap_or_else(|a| (*a).clone())
}

node! {
    /// The base C-tube construction (paper Sec. 3.2): sweeps the generatrix along the directrix; each
    /// vertex G_ij is where the line towards the cone apex meets the construction plane through X_j.
    /// Planes are given by their normals, or default to the bisecting (Monge) planes.
    #[node(id = "ctube.construct", category = "Cone-nets", name = "C-tube Construct")]
    pub fn ctube_construct[ctx](
        /// Directrix X (open, or closed: swept once around).
        directrix: k::Polyline,
        /// Generatrix G_{:,0} (closed: the mesh wraps).
        generatrix: k::Polyline,
        /// Apex-locating function a_j: one number or one per directrix edge (M−1); 1 = translation.
        apex: k::List<k::Number> = 1.0,
        /// Plane normals: M−1 vectors shared by all rows, or N lists of M−1; empty = Monge planes.
        normals: Option<k::Table<k::Vector>>,
        /// Whether `apex` is the normalized apex function ā (paper Sec. 4.3).
        normalized: k::Boolean = false,
        /// Normalization scale L (default: directrix length / 5).
        scale: Option<k::Number>,
        /// The plane at an open directrix's last vertex: "perpendicular" to the last edge, or "mirror"
        /// (the plane at X_{M−2} reflected in the last edge's bisector plane: the meridian on an arc).
        end_planes: k::Choice<crate::choices::EndPlanes> = "perpendicular",
    ) -> (
        /// The cone-net, N rows × M columns.
        mesh: k::QuadMesh,
        /// The apex values a_j used (M−1), after normalization.
        apex: k::List<k::Number>,
        /// Cone apices C_j (M−1), null at infinity.
        #[ui(layer = Apices)]
        apices: k::List<Option<k::Point>>,
        /// Plane normals P_ij: N lists of M−1 vectors.
        planes: k::Tree<k::Vector>,
        /// Configurations c_ij (j = 0 … M−2, one per support-strip quad): N lists of M−1 labels "++", "--", "+-", "-+".
        #[ui(role = Configurations)]
        configurations: k::Tree<k::Text>,
        /// Corrections made (none for this construction).
        corrections: k::List<k::Text>,
        /// Quality: max_planarity, mean_planarity, cone residuals, configuration counts, first_bad.
        quality: k::Record,
        /// Convexity margins: four unit-free numbers per face (row-major), s1 and s2 of its two
        /// configurations over the directrix edge; all four are positive exactly when the face is
        /// (++)(++). The optimizer's `convex` constraint keeps them positive.
        #[ui(role = FaceMargins)]
        margins: k::List<k::Number>,
    ) {
        reserve_construction(ctx, &directrix, &generatrix)?;
        let inputs = CtubeInputs {
            directrix: unwrap_arc(directrix),
            generatrix: unwrap_arc(generatrix),
            apex: apex_input(apex, normalized, scale),
            normals: normals_input(normals)?,
            end_planes,
        };
        // Only the mesh asked for: the sweep alone, no apices, quality pass or output tables.
        let others = ["apex", "apices", "planes", "configurations", "corrections", "quality", "margins"];
        if !others.iter().any(|o| ctx.wants(o)) {
            let mesh = conenet::ctube_mesh(&inputs)?;
            ctx.vouch_finite("mesh");
            return Ok((mesh, Vec::new(), Vec::new(), Value::list(Vec::new()), Value::list(Vec::new()), Vec::new(), Record::new(), Vec::new()));
        }
        Ok(outputs(ctx, conenet::construct_ctube_with(&inputs, reports(ctx))?))
    }
}

node! {
    /// CNets Construct (paper Sec. 4.4.1): like the C-tube construction, but each plane is chosen by a
    /// ratio r_ij ∈ [0, 1] that picks the ruling of support strip i at X_j (½ = the bisecting plane,
    /// a Monge surface when a ≡ 1). With `assistance` ≥ 0 folded-over configurations are repaired
    /// (0: planes only, 1: apex only — at the first column the generatrix is scaled towards X_0 —,
    /// between: the apex values move the fraction α of the way to the apex-only ones and the planes
    /// repair the rest, never changing the apex more than α = 1 nor turning the planes more than
    /// α = 0) and every correction is reported.
    #[node(id = "cnets.construct", category = "Cone-nets", name = "CNets Construct")]
    pub fn construct[ctx](
        /// Directrix X (open, or closed: swept once around).
        directrix: k::Polyline,
        /// Generatrix G_{:,0} (closed: the mesh wraps).
        generatrix: k::Polyline,
        /// Apex-locating function a_j: one number or one per directrix edge (M−1); 1 = translation.
        apex: k::List<k::Number> = 1.0,
        /// Ratios r_ij: one number, a list of M−1 (shared by rows), or N lists of M−1.
        ratios: k::Table<k::Number> = 0.5,
        /// Assisted correction α: negative = off, 0 = planes only, 1 = apex only, between = monotone blend.
        assistance: k::Number = -1.0,
        /// Whether `apex` is the normalized apex function ā (paper Sec. 4.3).
        normalized: k::Boolean = false,
        /// Normalization scale L (default: directrix length / 5).
        scale: Option<k::Number>,
        /// Safety margin ε of every correction, in (0, 1).
        epsilon: k::Number = 0.01,
        /// The plane at an open directrix's last vertex: "perpendicular" to the last edge, or "mirror"
        /// (the plane at X_{M−2} reflected in the last edge's bisector plane: the meridian on an arc).
        end_planes: k::Choice<crate::choices::EndPlanes> = "perpendicular",
        /// The apex the first strip shares with the net this one continues (wire that net's last
        /// `apices` item, with its last row as the generatrix): a_1 is set so and the rows run
        /// straight across the seam when the directrix starts along that net's last edge; where it
        /// turns, a_1 is the nearest value and `quality.seam_offset` says how far the apex is from
        /// reach. Empty (or null: an apex at infinity) keeps `apex` as given.
        seam_apex: Option<k::Point>,
    ) -> (
        /// The cone-net, N rows × M columns.
        mesh: k::QuadMesh,
        /// The apex values a_j used (M−1), after normalization and correction.
        apex: k::List<k::Number>,
        /// Cone apices C_j (M−1), null at infinity.
        #[ui(layer = Apices)]
        apices: k::List<Option<k::Point>>,
        /// Plane normals P_ij: N lists of M−1 vectors.
        planes: k::Tree<k::Vector>,
        /// Configurations c_ij (j = 0 … M−2, one per support-strip quad): N lists of M−1 labels "++", "--", "+-", "-+".
        #[ui(role = Configurations)]
        configurations: k::Tree<k::Text>,
        /// Every correction made: column, row, old → new.
        corrections: k::List<k::Text>,
        /// Quality: max_planarity, mean_planarity, cone residuals, configuration counts, first_bad.
        quality: k::Record,
        /// Convexity margins: four unit-free numbers per face (row-major), s1 and s2 of its two
        /// configurations over the directrix edge; all four are positive exactly when the face is
        /// (++)(++). The optimizer's `convex` constraint keeps them positive.
        #[ui(role = FaceMargins)]
        margins: k::List<k::Number>,
    ) {
        reserve_construction(ctx, &directrix, &generatrix)?;
        let mut inputs = ConstructInputs::new(unwrap_arc(directrix), unwrap_arc(generatrix));
        inputs.apex = apex_input(apex, normalized, scale);
        inputs.ratios = grid_values(&ratios, "ratios")?;
        inputs.assistance.alpha = assistance;
        inputs.assistance.epsilon = epsilon;
        inputs.end_planes = end_planes;
        let seam_offset = match seam_apex {
            Some(c) if inputs.directrix.points.len() >= 2 => {
                let x = &inputs.directrix.points;
                Some(conenet::seam_apex::seam_apex(x[0], x[1], c)?.offset)
            }
            _ => None,
        };
        inputs.apex.seam = seam_apex;
        let mut out = outputs(ctx, conenet::construct_with(&inputs, reports(ctx))?);
        if let Some(offset) = seam_offset.filter(|_| ctx.wants("quality")) {
            out.6 = out.6.with("seam_offset", offset);
        }
        Ok(out)
    }
}

node! {
    /// CNets Construct Coplanar: one plane per directrix vertex, shared by all rows, so every
    /// generatrix-aligned polyline is planar. `ruling_ratios` pick the ruling of the first support
    /// strip; `plane_ratios` turn the plane about it (½ and ½: the bisecting plane).
    #[node(id = "cnets.construct_coplanar", category = "Cone-nets", name = "CNets Construct Coplanar")]
    pub fn construct_coplanar[ctx](
        /// Directrix X (open, or closed: swept once around).
        directrix: k::Polyline,
        /// Generatrix G_{:,0} (closed: the mesh wraps).
        generatrix: k::Polyline,
        /// Apex-locating function a_j: one number or one per directrix edge (M−1); 1 = translation.
        apex: k::List<k::Number> = 1.0,
        /// Ruling ratios ρ_j: one number or one per directrix edge (M−1).
        ruling_ratios: k::List<k::Number> = 0.5,
        /// Plane-rotation ratios τ_j: one number or one per directrix edge (M−1).
        plane_ratios: k::List<k::Number> = 0.5,
        /// Assisted correction α: negative = off, 0 = planes only, 1 = apex only, between = monotone blend.
        assistance: k::Number = -1.0,
        /// Whether `apex` is the normalized apex function ā (paper Sec. 4.3).
        normalized: k::Boolean = false,
        /// Normalization scale L (default: directrix length / 5).
        scale: Option<k::Number>,
        /// Safety margin ε of every correction, in (0, 1).
        epsilon: k::Number = 0.01,
        /// The plane at an open directrix's last vertex: "perpendicular" to the last edge, or "mirror"
        /// (the plane at X_{M−2} reflected in the last edge's bisector plane: the meridian on an arc).
        end_planes: k::Choice<crate::choices::EndPlanes> = "perpendicular",
    ) -> (
        /// The cone-net, N rows × M columns; every column is planar.
        mesh: k::QuadMesh,
        /// The apex values a_j used (M−1), after normalization and correction.
        apex: k::List<k::Number>,
        /// Cone apices C_j (M−1), null at infinity.
        #[ui(layer = Apices)]
        apices: k::List<Option<k::Point>>,
        /// Plane normals P_ij: N lists of M−1 vectors (equal along each column).
        planes: k::Tree<k::Vector>,
        /// Configurations c_ij (j = 0 … M−2, one per support-strip quad): N lists of M−1 labels "++", "--", "+-", "-+".
        #[ui(role = Configurations)]
        configurations: k::Tree<k::Text>,
        /// Every correction made: column, old → new.
        corrections: k::List<k::Text>,
        /// Quality: max_planarity, mean_planarity, cone residuals, configuration counts, first_bad.
        quality: k::Record,
        /// Convexity margins: four unit-free numbers per face (row-major), s1 and s2 of its two
        /// configurations over the directrix edge; all four are positive exactly when the face is
        /// (++)(++). The optimizer's `convex` constraint keeps them positive.
        #[ui(role = FaceMargins)]
        margins: k::List<k::Number>,
    ) {
        let column = |v: Vec<f64>| match v.as_slice() {
            [single] => ColumnValues::Uniform(*single),
            _ => ColumnValues::List(v),
        };
        reserve_construction(ctx, &directrix, &generatrix)?;
        let mut inputs = CoplanarInputs::new(unwrap_arc(directrix), unwrap_arc(generatrix));
        inputs.apex = apex_input(apex, normalized, scale);
        inputs.ruling_ratios = column(ruling_ratios);
        inputs.plane_ratios = column(plane_ratios);
        inputs.assistance.alpha = assistance;
        inputs.assistance.epsilon = epsilon;
        inputs.end_planes = end_planes;
        Ok(outputs(ctx, conenet::construct_coplanar_with(&inputs, reports(ctx))?))
    }
}

node! {
    /// Encodes any cone-net as C-tube construction inputs (paper Sec. 4.1, Proposition 1): a
    /// directrix, the first generatrix, a positive apex function and per-vertex plane normals that
    /// reproduce the mesh with `ctube.construct`.
    #[node(id = "cnets.encode", category = "Cone-nets", name = "CNets Encode")]
    pub fn encode(
        /// A cone-net (a quad mesh whose directrix-direction strips lie on cones).
        mesh: k::QuadMesh,
    ) -> (
        /// A directrix X with every a_j > 0.
        directrix: k::Polyline,
        /// The generatrix: the mesh's first column.
        generatrix: k::Polyline,
        /// Apex values a_j > 0 (M−1).
        apex: k::List<k::Number>,
        /// Plane normals: N lists of M−1 vectors.
        normals: k::Tree<k::Vector>,
    ) {
        let e = conenet::encode(&mesh)?;
        let normals = Value::list(
            e.normals.into_iter().map(|row| Value::list(row.into_iter().map(Value::Vector).collect())).collect(),
        );
        Ok((e.directrix, e.generatrix, e.apex, normals))
    }
}

node! {
    /// Subdivides every row strip of a cone-net into `count` strips (paper Fig. 1: the generatrix
    /// subdivided so that flat panels pave the cone-net). The first column's new vertices divide the
    /// generatrix edges evenly; each further one is the central projection through the coarse face's
    /// apex onto the next coarse edge (parallel when the face's directrix-aligned edges are), so every
    /// new quad lies in its coarse face's plane and the result is a cone-net with the same apices.
    /// The coarse rows are kept exactly; wrapping rows keep wrapping.
    #[node(id = "cnets.subdivide_rows", category = "Cone-nets")]
    pub fn subdivide_rows(
        /// A cone-net (rows along the generatrix).
        mesh: k::QuadMesh,
        /// Strips each row strip is cut into (1 … 1024).
        count: k::Integer = 2,
    ) -> (
        /// The subdivided cone-net: (N−1)·count + 1 rows (N·count when the rows wrap).
        mesh: k::QuadMesh,
    ) {
        let count = usize::try_from(count)
            .map_err(|_| NodeError::new(format!("count must be at least 1, got {count}")))?;
        Ok((conenet::subdivide_rows(&mesh, count)?,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        ctube_construct(),
        construct(),
        construct_coplanar(),
        encode(),
        subdivide_rows(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_indexed_by_configuration() {
        let labels = labels();
        for (k, c) in Configuration::ALL.into_iter().enumerate() {
            assert_eq!(c as usize, k, "{c}");
            assert_eq!(labels[k], Value::text(c.as_str()), "{c}");
        }
    }
}
