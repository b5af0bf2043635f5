//! Supplementary and fabrication tools: apex from widths, node axes, support layers, parallel transform, strips, unrolling,
//! nesting and the panel schedule.
//!
//! Thin wrappers over `cnets_geometry::fabrication` (formulas in `docs/fabrication.md`).

use cnets_engine::prelude::*;
use cnets_geometry::fabrication::{self as fab, FabricationError, StripDirection, UnrollOptions};

/// A fabrication error as a node error (its message names the offending indices).
pub(crate) fn fab_err(e: FabricationError) -> NodeError {
    NodeError::new(e.to_string())
}

node! {
    /// CNets Graph to Apex Function (paper Sec. 4.4.2): the widths y_0 … y_{M−1} of the support strips
    /// along the directrix (e.g. from a graph mapper) give the apex-locating function
    /// `a_j = y_j / y_{j−1}` (M−1 values). With `normalized` the output is the normalized function
    /// `ā_j = 1 − (1 − a_j) L / l_j` for the given directrix (to feed a construction with its
    /// `normalized` input on).
    #[node(id = "cnets.graph_to_apex", category = "CNets", name = "Graph to apex function")]
    pub fn graph_to_apex(
        /// Widths y_0 … y_{M−1} (finite, > 0): one per directrix point.
        widths: k::List<k::Number>,
        /// Output the normalized apex function ā instead of a.
        normalized: k::Boolean = false,
        /// The directrix (needed when `normalized`: its edge lengths l_j).
        directrix: Option<k::Polyline>,
        /// Normalization scale L (> 0); empty: directrix length / 5.
        scale: Option<k::Number>,
    ) -> (
        /// The apex values (M−1), a_j or ā_j.
        apex: k::List<k::Number>,
    ) {
        let out = if normalized {
            let d = directrix.ok_or_else(|| {
                NodeError::new("normalized output needs the directrix (its edge lengths)")
            })?;
            fab::graph_to_normalized_apex(&widths, &d, scale).map_err(fab_err)?
        } else {
            fab::graph_to_apex(&widths).map_err(fab_err)?
        };
        Ok((out,))
    }
}

node! {
    /// CNet Get Torsion-Free Axes (paper Sec. 4.4.2): the node axis of every mesh vertex, the segment
    /// from the directrix point X_j to G_{i,j} (row-major, `i * M + j`). Axes of neighbouring vertices
    /// are coplanar, so they carry support beams and second layers.
    #[node(id = "cnets.torsion_free_axes", category = "CNets", name = "Torsion-free node axes")]
    pub fn torsion_free_axes(
        /// The directrix the mesh was built from (one point per mesh column, as swept).
        directrix: k::Polyline,
        /// The constructed cone-net.
        mesh: k::QuadMesh,
    ) -> (
        /// One segment X_j → G_{i,j} per vertex.
        #[ui(layer = Axes)]
        axes: k::Lines,
    ) {
        Ok((fab::torsion_free_axes(&directrix, &mesh).map_err(fab_err)?,))
    }
}

node! {
    /// CNet Construct Conical Support (paper Sec. 4.4.2): a second layer that is itself a cone-net with
    /// the same cone apices. The construction is rerun with the same apex values from
    /// `G'_{i,0} = X_0 + λ (G_{i,0} − X_0)`; every new vertex lies on its node axis X_j G_{i,j} (the
    /// construction plane meets the support plane in that axis) and every quad is planar.
    #[node(id = "cnets.conical_support", category = "CNets", name = "Conical support layer")]
    pub fn conical_support(
        /// The directrix the mesh was built from.
        directrix: k::Polyline,
        /// The constructed cone-net.
        mesh: k::QuadMesh,
        /// The construction's `apex` output: the M−1 apex values a_j actually used.
        apex: k::List<k::Number>,
        /// λ: scale of the first column about X_0 (finite, ≠ 0; 1 reproduces the mesh).
        factor: k::Number = 0.8,
    ) -> (
        /// The conical support layer (same size and wrap as the mesh).
        #[ui(layer = Supports)]
        mesh: k::QuadMesh,
    ) {
        Ok((fab::conical_support(&directrix, &mesh, &apex, factor).map_err(fab_err)?,))
    }
}

node! {
    /// PQ Mesh Construct Support (paper Sec. 4.4.2): a second layer with every edge parallel to the
    /// mesh, traced along the torsion-free node axes from H_{0,0} = G_{0,0} moved by `distance` along
    /// its axis (positive: away from the directrix). Faces are planar.
    #[node(id = "pq.parallel_support", category = "PQ", name = "Parallel support layer")]
    pub fn parallel_support(
        /// The directrix the mesh was built from (its points define the node axes).
        directrix: k::Polyline,
        /// The constructed cone-net.
        mesh: k::QuadMesh,
        /// Offset of the start vertex along its axis, in model units.
        distance: k::Number = 0.1,
    ) -> (
        /// The parallel support layer.
        #[ui(layer = Supports)]
        mesh: k::QuadMesh,
    ) {
        Ok((fab::parallel_support(&directrix, &mesh, distance).map_err(fab_err)?,))
    }
}

/// Bytes the unrolling holds per mesh vertex: the flat rungs (2 × 16), the outline (16 + 24), the
/// laid-out quads (96) and their working copies, as measured on a 3000 × 1000 net (≈ 400), plus
/// the panels folds and marks are computed from (corner ids, 3D and flat corners, three vectors:
/// 32 + 96 + 96 + 72 ≈ 300, counted, not measured) and the fold lines (≈ 100).
const UNROLL_BYTES_PER_VERTEX: usize = 800;

node! {
    /// PQ Mesh Parallel Transform (paper Sec. 4.4.2): the Combescure transform of any PQ quad grid. The
    /// edges of the boundary polylines G_{:,0} and G_{0,:} are scaled by μ and ν, every other vertex
    /// is where the two edge lines through its placed neighbours meet, so every edge stays parallel
    /// to its counterpart. Unless all μ are equal the result is in general not a cone-net. A wrapped
    /// mesh keeps its wrap only when the transform closes (otherwise a warning says so).
    #[node(id = "pq.parallel_transform", category = "PQ", name = "Parallel transform")]
    pub fn parallel_transform[ctx](
        /// Any PQ quad grid.
        mesh: k::QuadMesh,
        /// Scale factors μ_0 … μ_{N−2} of the edges of column 0 (one value: all of them); ≠ 0.
        mu: k::List<k::Number> = vec![1.0],
        /// Scale factors ν_0 … ν_{M−2} of the edges of row 0 (one value: all of them); ≠ 0.
        nu: k::List<k::Number> = vec![1.0],
    ) -> (
        /// The transformed mesh.
        mesh: k::QuadMesh,
    ) {
        let t = fab::parallel_transform(&mesh, &mu, &nu).map_err(fab_err)?;
        if t.dropped_wrap.0 {
            ctx.warn("the transform of the closed generatrix does not close: the closing quads were dropped");
        }
        if t.dropped_wrap.1 {
            ctx.warn("the transform of the closed directrix does not close: the closing quads were dropped");
        }
        Ok((t.mesh,))
    }
}

node! {
    /// PQ Mesh Extract Strips (paper Sec. 4.4.2): the strips of a quad grid as meshes. `directrix`:
    /// strip i is the quads between rows i and i+1 (a 2 × M grid); `generatrix`: strip j is the quads
    /// between columns j and j+1 (an N × 2 grid). Corner order and wrapping follow the mesh.
    #[node(id = "pq.extract_strips", category = "PQ", name = "Extract strips")]
    pub fn extract_strips(
        /// The quad grid.
        mesh: k::QuadMesh,
        /// `"directrix"` or `"generatrix"`.
        direction: k::Choice<crate::choices::Direction> = "directrix",
    ) -> (
        /// The strips, in order.
        strips: k::List<k::QuadMesh>,
    ) {
        Ok((fab::extract_strips(&mesh, direction).map_err(fab_err)?,))
    }
}

/// The flat strips of `pq.unroll_strips` before any split: outlines, the largest length error,
/// labels, label points and the panels. A quad grid arrives converted to a polygon mesh and is
/// unrolled as the grid it still is.
type Unrolled = (
    Vec<Polyline>,
    f64,
    Vec<String>,
    Vec<DVec3>,
    Vec<fab::StripPanels>,
);

/// Unrolls the strips of a mesh (a quad grid or a polygon mesh made from one) into panels.
fn unrolled_panels(
    mesh: &PolygonMesh,
    direction: StripDirection,
    options: UnrollOptions,
) -> Result<Unrolled, NodeError> {
    if let Some(grid) = fab::grid_of(mesh) {
        let u = fab::unroll_strips(&grid, direction, options).map_err(fab_err)?;
        let outlines: Vec<Polyline> = u.strips.iter().map(|s| s.outline.clone()).collect();
        let labels: Vec<String> = u.strips.iter().map(|s| s.label.clone()).collect();
        let points: Vec<DVec3> = u.strips.iter().map(|s| s.label_point).collect();
        let panels = fab::grid_panels(&grid, &u);
        Ok((outlines, u.max_length_error, labels, points, panels))
    } else {
        let u = fab::unroll_mesh_strips(mesh, direction, options).map_err(fab_err)?;
        let outlines: Vec<Polyline> = u.strips.iter().map(|s| s.outline.clone()).collect();
        let labels: Vec<String> = u.strips.iter().map(|s| s.label.clone()).collect();
        let points: Vec<DVec3> = u.strips.iter().map(|s| s.label_point).collect();
        let panels = fab::mesh_panels(mesh, &u);
        Ok((outlines, u.max_length_error, labels, points, panels))
    }
}

node! {
    /// PQ Strip Unroll (paper Sec. 4.4.2): every strip laid flat quad by quad (an isometry per quad,
    /// each quad sharing its rung with the previous one), turned so its minimum-area rectangle is
    /// axis-aligned and stacked along +y without overlap, labelled `D<i>` / `G<j>`. Quads less planar
    /// than `tolerance` are an error naming the strip and quad; `max_length_error` reports the largest
    /// relative edge-length change (≤ 1e-9 for a planar mesh). A polygon mesh — a cone-net cut by a
    /// plane, mirrored or joined — is unrolled by its strips found from the faces (trimmed panels
    /// included; strips end at the cut and at a mirror seam; a face of more than five corners — a
    /// transom — is a panel of its own, `P0`), and the mirrored half's strips are labelled `D9
    /// (mirror of D2)`. In a structure joined from several nets (`mesh.join`) strips
    /// stay within their net, numbered within it and named after it (`wall-D3`; docs/fabrication.md).
    #[node(id = "pq.unroll_strips", category = "PQ", name = "Unroll strips")]
    pub fn unroll_strips[ctx](
        /// The quad grid (a cone-net, a support layer, or one extracted strip), or a polygon mesh
        /// made from one (cut, mirrored, joined).
        mesh: k::Mesh,
        /// `"directrix"` or `"generatrix"`.
        direction: k::Choice<crate::choices::Direction> = "directrix",
        /// Largest accepted face planarity (libigl measure for quads); raise it to unroll nearly
        /// planar meshes.
        tolerance: k::Number = 1e-6,
        /// Gap between strips in model units; empty: a tenth of the tallest strip.
        spacing: Option<k::Number>,
        /// Station planes (frames, waterlines): each strip gets a mark where it crosses one,
        /// labelled `S<k>` for plane k.
        stations: Option<k::List<k::Plane>>,
        /// Longest piece (model units, along the strip): a longer strip is cut at folds into
        /// pieces `D4.1`, `D4.2`, … with the joint line marked on both; empty: strips stay whole.
        max_length: Option<k::Number>,
    ) -> (
        /// One closed outline per strip, in the XY plane.
        #[ui(layer = Unrolled)]
        outlines: k::List<k::Polyline>,
        /// Largest relative edge-length change over all quads.
        max_length_error: k::Number,
        /// The strip labels (`D0`, `D1`, … or `G0`, …).
        labels: k::List<k::Text>,
        /// Label positions (the midpoint of each strip's middle rung).
        #[ui(layer = Unrolled)]
        label_points: k::List<k::Point>,
        /// Every fold line between consecutive panels of a strip, in the flat layout (two points),
        /// strip after strip.
        #[ui(layer = Unrolled)]
        folds: k::List<k::Polyline>,
        /// The fold angle of every fold, in degrees, signed: mountain positive, seen from the side
        /// the panels' normals point to (the flat layout seen from +z; docs/fabrication.md).
        fold_angles: k::List<k::Number>,
        /// The collapsed edges, by strip and panel (`D4 panel 7 (mesh quad row 4, column 7): edge
        /// 0 collapsed to …`); their length change counts against the mesh size.
        degenerate: k::List<k::Text>,
        /// Marks in the flat layout: a tick on each long edge where a strip meets a neighbour
        /// (labelled with its name), the station lines, then the joint lines of split pieces,
        /// strip after strip.
        #[ui(layer = Unrolled)]
        marks: k::List<k::Polyline>,
        /// The text of every mark: the neighbour's name (`D3`), the station (`S0`) or the joint
        /// (`D4.1 | D4.2`).
        mark_labels: k::List<k::Text>,
    ) {
        let options = UnrollOptions { tolerance, spacing };
        // The flat strips, their outlines and laid-out quads, declared before they are built.
        ctx.reserve(
            cnets_engine::budget::bytes_of(mesh.vertices.len() as u128, UNROLL_BYTES_PER_VERTEX),
            &format!("unrolling the strips of a mesh of {} vertices", mesh.vertices.len()),
        )?;
        let (mut outlines, max_length_error, mut labels, mut points, mut panels) =
            unrolled_panels(&mesh, direction, options)?;
        let mut joints = Vec::new();
        if let Some(max_length) = max_length {
            let p = fab::split_strips(&panels, max_length, spacing).map_err(fab_err)?;
            outlines = p.outlines;
            labels = p.pieces.iter().map(|s| s.label.clone()).collect();
            points = p.label_points;
            panels = p.pieces;
            joints = p.joints;
        }
        let folds = fab::folds(&panels);
        let fold_lines: Vec<Polyline> = folds
            .iter()
            .map(|f| Polyline::open(f.line.to_vec()))
            .collect();
        let fold_angles: Vec<f64> = folds.iter().map(|f| f.angle.to_degrees()).collect();
        let degenerate = fab::collapsed::describe_all(&panels);
        let mut marks = fab::neighbour_marks(&panels);
        marks.extend(fab::station_marks(&panels, stations.as_deref().unwrap_or(&[])));
        marks.extend(joints);
        // Strip after strip: neighbours, stations, joints (a stable sort keeps each strip's order).
        marks.sort_by_key(|m| m.strip);
        let mark_labels: Vec<String> = marks.iter().map(|m| m.label.clone()).collect();
        let marks: Vec<Polyline> = marks.into_iter().map(|m| Polyline::open(m.line)).collect();
        Ok((
            outlines,
            max_length_error,
            labels,
            points,
            fold_lines,
            fold_angles,
            degenerate,
            marks,
            mark_labels,
        ))
    }
}

node! {
    /// CNet Support Strips (paper Sec. 4.4.2, Fig. 3). With `directrix`: the support strips, one per
    /// directrix-aligned polyline G_{i,:}, the planar quads X_j X_{j+1} G_{i,j+1} G_{i,j} (a 2 × M
    /// grid: the directrix, then the mesh row). With `layer` (a second layer from
    /// `cnets.conical_support` or `pq.parallel_support`): the beams on the torsion-free node axes
    /// between the mesh and the layer, one strip per polyline of `direction`, quads G G' G' G. Every
    /// quad is planar (to rounding error); `pq.unroll_strips` unrolls them for cutting.
    #[node(id = "cnets.support_strips", category = "CNets")]
    pub fn support_strips(
        /// The constructed cone-net.
        mesh: k::QuadMesh,
        /// The directrix the mesh was built from (gives the support strips of Fig. 3).
        directrix: Option<k::Polyline>,
        /// A second layer of the same size (gives the beams between the layers).
        layer: Option<k::QuadMesh>,
        /// The beams' polylines: `"directrix"` or `"generatrix"` (support strips: `"directrix"`).
        direction: k::Choice<crate::choices::Direction> = "directrix",
    ) -> (
        /// One strip per polyline (2 × M or 2 × N quad grids).
        #[ui(layer = Supports)]
        strips: k::List<k::QuadMesh>,
    ) {
        let strips = match (directrix, layer) {
            (Some(_), Some(_)) => {
                return Err(NodeError::new(
                    "give either directrix (support strips) or layer (beams), not both",
                ));
            }
            (None, None) => {
                return Err(NodeError::new(
                    "give the directrix (support strips) or a second layer (beams)",
                ));
            }
            (Some(directrix), None) => {
                if direction != StripDirection::Directrix {
                    return Err(NodeError::new(
                        "the support strips of the directrix run along the directrix: direction must be \"directrix\"",
                    ));
                }
                fab::directrix_support_strips(&directrix, &mesh).map_err(fab_err)?
            }
            (None, Some(layer)) => fab::beam_strips(&mesh, &layer, direction).map_err(fab_err)?,
        };
        Ok((strips,))
    }
}

node! {
    /// Fabrication Nest: places flat outlines (e.g. `pq.unroll_strips`) on as few rectangular sheets
    /// as it can, with `spacing` between outlines and from the sheet edges and `rotations` allowed
    /// orientations (360°/rotations apart). Collision detection by the irregular-nesting engine
    /// jagua-rs; a bottom-left fill that slides every outline into its neighbours' concavities. The
    /// outlines are moved rigidly; sheet s lies at x = s · (sheet_width + gap). Fold lines and marks
    /// drawn on the outlines (`pq.unroll_strips`) are moved with the outline they lie on. Feed
    /// `sheets` to the SVG / DXF exports for one group of layers (SVG) or one block (DXF) per sheet.
    #[node(id = "fab.nest", category = "Fabrication")]
    pub fn nest[ctx](
        /// Closed flat outlines (their x and y are used).
        outlines: k::List<k::Polyline>,
        /// Sheet width, model units.
        sheet_width: k::Number,
        /// Sheet height, model units.
        sheet_height: k::Number,
        /// Least distance between outlines and from the sheet edges.
        spacing: k::Number = 0.005,
        /// Allowed orientations (1: as given; 4: quarter turns).
        rotations: k::Integer = 4,
        /// One label per outline; empty: `P0`, `P1`, …
        labels: Option<k::List<k::Text>>,
        /// Fold lines on the outlines (`pq.unroll_strips`), moved with the outline each lies on.
        folds: Option<k::List<k::Polyline>>,
        /// Marks on the outlines (`pq.unroll_strips`), moved with the outline each lies on.
        marks: Option<k::List<k::Polyline>>,
    ) -> (
        /// The placed outlines, in input order.
        #[ui(layer = Unrolled)]
        outlines: k::List<k::Polyline>,
        /// The sheet of each outline (0, 1, …).
        sheets: k::List<k::Integer>,
        /// Outline area / area of the sheets used.
        utilization: k::Number,
        /// The labels, in input order.
        labels: k::List<k::Text>,
        /// A point inside each placed outline.
        #[ui(layer = Unrolled)]
        label_points: k::List<k::Point>,
        /// The fold lines on the placed outlines, in input order (empty when none were given).
        #[ui(layer = Unrolled)]
        folds: k::List<k::Polyline>,
        /// The marks on the placed outlines, in input order (empty when none were given).
        #[ui(layer = Unrolled)]
        marks: k::List<k::Polyline>,
    ) {
        if let Some(l) = &labels
            && l.len() != outlines.len()
        {
            return Err(NodeError::new(format!(
                "labels has {} entries, expected {} (one per outline)",
                l.len(),
                outlines.len()
            )));
        }
        let rotations = usize::try_from(rotations)
            .map_err(|_| NodeError::new(format!("rotations must be at least 1, got {rotations}")))?;
        let flat: Vec<Polyline> = outlines.iter().map(|o| (**o).clone()).collect();
        // Stops between outlines once the evaluation is cancelled (the editor: a newer edit).
        let n = fab::nest_until(&flat, sheet_width, sheet_height, spacing, rotations, &|| {
            ctx.cancelled()
        })
        .map_err(fab_err)?;
        let labels = labels
            .unwrap_or_else(|| (0..outlines.len()).map(|k| format!("P{k}")).collect());
        let sheets: Vec<i64> = n.sheets.iter().map(|&s| s as i64).collect();
        let carried = |lines: Option<Vec<std::sync::Arc<Polyline>>>| -> Result<Vec<Polyline>, NodeError> {
            let lines: Vec<Polyline> = lines.unwrap_or_default().iter().map(|l| (**l).clone()).collect();
            Ok(fab::carry(&lines, &flat, &n.outlines).map_err(fab_err)?.0)
        };
        let (folds, marks) = (carried(folds)?, carried(marks)?);
        Ok((n.outlines, sheets, n.utilization, labels, n.label_points, folds, marks))
    }
}

/// Bytes of the schedule per mesh vertex on top of the unrolling: a row holds its corners (24 each),
/// edges (8 each), labels and field names (≈ 200 a row, counted, not measured).
const SCHEDULE_BYTES_PER_VERTEX: usize = 300;

/// One schedule row as a record (the CSV columns, in order).
fn schedule_record(row: &fab::ScheduleRow) -> Record {
    let fold = |a: Option<f64>| a.map_or(Value::Null, |a| Value::Number(a.to_degrees()));
    Record::new()
        .with("strip", Value::text(&row.label))
        .with("piece", Value::text(&row.piece))
        .with("panel", Value::Integer(row.panel as i64))
        .with("face", Value::text(row.source.to_string()))
        .with(
            "corners",
            Value::list(row.corners.iter().map(|&c| Value::Point(c)).collect()),
        )
        .with("area", row.area)
        .with(
            "edges",
            Value::list(row.edges.iter().map(|&e| Value::Number(e)).collect()),
        )
        .with("fold_previous_deg", fold(row.fold_previous))
        .with("fold_next_deg", fold(row.fold_next))
        .with("planarity", row.planarity)
}

node! {
    /// Fabrication Schedule: the panel schedule of the strips `pq.unroll_strips` cuts, one record per
    /// panel, strip after strip: `strip` (its label, `D4`, `D9 (mirror of D2)`), `piece` (the part
    /// it is cut on: `D4.2` with `max_length`, else the strip's label), `panel` (its number in the
    /// strip), `face` (in the mesh), `corners` (3D), `area`, `edges` (edge e from corner e to
    /// e + 1), `fold_previous_deg` / `fold_next_deg` (the signed fold angles to its neighbours in
    /// the strip, degrees, mountain positive; empty at a strip's end) and `planarity`. Give it the
    /// mesh, direction, tolerance and max_length given to `pq.unroll_strips` so the names agree;
    /// `io.export_csv` writes the table for the quantity surveyor (docs/fabrication.md).
    #[node(id = "fab.schedule", category = "Fabrication", name = "Panel schedule")]
    pub fn schedule[ctx](
        /// The mesh as given to `pq.unroll_strips`: a quad grid, or a polygon mesh made from one.
        mesh: k::Mesh,
        /// `"directrix"` or `"generatrix"`.
        direction: k::Choice<crate::choices::Direction> = "directrix",
        /// Largest accepted face planarity (libigl measure for quads).
        tolerance: k::Number = 1e-6,
        /// Longest piece, as given to `pq.unroll_strips` (names the pieces `D4.1`, `D4.2`, …);
        /// empty: strips stay whole.
        max_length: Option<k::Number>,
    ) -> (
        /// One record per panel (the columns listed above).
        table: k::List<k::Record>,
        /// The sum of the panels' areas.
        total_area: k::Number,
    ) {
        ctx.reserve(
            cnets_engine::budget::bytes_of(
                mesh.vertices.len() as u128,
                UNROLL_BYTES_PER_VERTEX + SCHEDULE_BYTES_PER_VERTEX,
            ),
            &format!("the panel schedule of a mesh of {} vertices", mesh.vertices.len()),
        )?;
        let options = UnrollOptions { tolerance, spacing: None };
        let (_, _, _, _, panels) = unrolled_panels(&mesh, direction, options)?;
        let rows = match max_length {
            Some(max_length) => {
                let pieces = fab::split_strips(&panels, max_length, None).map_err(fab_err)?;
                fab::schedule(&panels, &pieces.pieces)
            }
            None => fab::schedule(&panels, &panels),
        };
        let total_area: f64 = rows.iter().map(|r| r.area).sum();
        Ok((rows.iter().map(schedule_record).collect::<Vec<_>>(), total_area))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        graph_to_apex(),
        torsion_free_axes(),
        conical_support(),
        parallel_support(),
        parallel_transform(),
        extract_strips(),
        unroll_strips(),
        support_strips(),
        nest(),
        schedule(),
    ]
}
