//! Exports written into the run's output directory: glTF, OBJ, SVG, DXF, JSON, CSV.
//!
//! Every export builds its whole file in memory, then writes it atomically into the output directory
//! (`--out`): names may contain sub-folders but never `..` or a root; a missing extension is added.
//! The written path is the node's `path` output and is listed in the run summary. File format
//! details are in `docs/fabrication.md`.

use std::sync::Arc;

use cnets_engine::prelude::*;
use cnets_geometry::fabrication::{face_planarity, planarity_colour};

pub mod cad;
pub mod glb;
pub mod names;
pub mod obj;
pub mod outlines;
pub mod svg;
pub mod table;
pub mod write;

use write::{stream_export, write_export};

/// Face colours for the glTF meshes: the given list (one per face over all meshes, or one for all),
/// or the planarity colour map.
fn mesh_colours(
    meshes: &[Arc<PolygonMesh>],
    colours: Option<&[DVec3]>,
    limit: f64,
) -> Result<Vec<Vec<DVec3>>, NodeError> {
    let total: usize = meshes.iter().map(|m| m.face_count()).sum();
    match colours {
        Some(c) if c.len() == 1 => Ok(meshes.iter().map(|m| vec![c[0]; m.face_count()]).collect()),
        Some(c) if c.len() == total => {
            let mut rest = c;
            Ok(meshes
                .iter()
                .map(|m| {
                    let (head, tail) = rest.split_at(m.face_count());
                    rest = tail;
                    head.to_vec()
                })
                .collect())
        }
        Some(c) => Err(NodeError::new(format!(
            "colours has {} entries, expected {total} (one per face of all meshes) or 1",
            c.len()
        ))),
        None => {
            if !(limit.is_finite() && limit > 0.0) {
                return Err(
                    format!("planarity_limit must be a finite number > 0, got {limit}").into(),
                );
            }
            meshes
                .iter()
                .map(|m| {
                    if m.face_count() == 0 {
                        return Ok(Vec::new());
                    }
                    Ok(face_planarity(m)
                        .map_err(|e| NodeError::new(e.to_string()))?
                        .iter()
                        .map(|v| planarity_colour(*v, limit))
                        .collect())
                })
                .collect()
        }
    }
}

node! {
    /// Writes a binary glTF 2.0 file (.glb): meshes as triangles with positions, flat normals and one
    /// colour per face (given, e.g. from `analysis.face_classes`, or else the planarity colour map),
    /// line sets (e.g. node axes) as line primitives, polylines as line strips/loops. Model units;
    /// the root node turns Z-up into glTF's Y-up. Passes the Khronos glTF validator.
    #[node(id = "io.export_gltf", category = "Export", flags(Export))]
    pub fn export_gltf[ctx](
        /// File name inside the output directory (`.glb` is added when missing).
        #[ui(widget = OutputName)]
        name: k::Text = "model.glb",
        /// Meshes (quad grids convert).
        meshes: Option<k::List<k::Mesh>>,
        /// Face colours (RGB in [0, 1]): one per face of all meshes in order, or one for all; empty:
        /// planarity colours.
        colours: Option<k::List<k::Vector>>,
        /// Line sets, e.g. `cnets.torsion_free_axes`.
        lines: Option<k::List<k::Lines>>,
        /// Polylines, e.g. a directrix or strip outlines.
        polylines: Option<k::List<k::Polyline>>,
        /// Planarity shown fully red when no colours are given.
        planarity_limit: k::Number = 1e-3,
        /// Names of the items in order — meshes, then line sets, then polylines — for the file's
        /// nodes and meshes; missing ones are named `mesh 0`, `lines 0`, `polyline 0`.
        names: Option<k::List<k::Text>>,
    ) -> (
        /// The written file.
        path: k::Text,
    ) {
        let meshes = meshes.unwrap_or_default();
        let lines = lines.unwrap_or_default();
        let polylines = polylines.unwrap_or_default();
        let colours = mesh_colours(&meshes, colours.as_deref(), planarity_limit)?;
        let names = names.unwrap_or_default();
        let scene = glb::GlbScene {
            meshes: meshes.iter().map(|m| &**m).zip(colours).collect(),
            lines: lines.iter().map(|l| l.as_slice()).collect(),
            polylines: polylines.iter().map(|p| &**p).collect(),
            names: names::ItemNames::new(&names, meshes.len(), lines.len()),
        };
        let bytes = glb::encode_glb(&scene)?;
        Ok((write_export(ctx, &name, "glb", &bytes)?,))
    }
}

node! {
    /// Writes a Wavefront OBJ file: mesh faces as polygons (quads stay quads, never triangulated),
    /// line sets and polylines as `l` lines, one object per item. Model units, full f64 precision.
    #[node(id = "io.export_obj", category = "Export", flags(Export))]
    pub fn export_obj[ctx](
        /// File name inside the output directory (`.obj` is added when missing).
        #[ui(widget = OutputName)]
        name: k::Text = "model.obj",
        /// Meshes (quad grids convert).
        meshes: Option<k::List<k::Mesh>>,
        /// Line sets, e.g. `cnets.torsion_free_axes`.
        lines: Option<k::List<k::Lines>>,
        /// Polylines.
        polylines: Option<k::List<k::Polyline>>,
        /// Names of the items in order — meshes, then line sets, then polylines — for the `o`
        /// lines (white space becomes `_`); missing ones are named `mesh_0`, `lines_0`, `polyline_0`.
        names: Option<k::List<k::Text>>,
    ) -> (
        /// The written file.
        path: k::Text,
    ) {
        let meshes = meshes.unwrap_or_default();
        let lines = lines.unwrap_or_default();
        let polylines = polylines.unwrap_or_default();
        let names = names.unwrap_or_default();
        let item_names = names::ItemNames::new(&names, meshes.len(), lines.len());
        let meshes: Vec<_> = meshes.iter().map(|m| &**m).collect();
        let lines: Vec<_> = lines.iter().map(|l| l.as_slice()).collect();
        let polylines: Vec<_> = polylines.iter().map(|p| &**p).collect();
        let path = stream_export(ctx, &name, "obj", |out| {
            obj::write_obj(out, &meshes, &lines, &polylines, item_names)
        })?;
        Ok((path,))
    }
}

/// Warns when an outline was not flat in XY.
fn warn_z(ctx: &NodeContext, sheet: &outlines::Sheet) {
    if sheet.dropped_z {
        ctx.warn("some outlines are not in the XY plane: their z coordinates were ignored");
    }
}

node! {
    /// Writes an SVG cutting sheet: every outline (e.g. `pq.unroll_strips`) as a path (closed ones
    /// closed), 1:1 in millimetres, with its label; red cut lines and blue labels sized to the
    /// drawing, a 5 mm margin; nested outlines grouped per sheet (an Inkscape layer each).
    #[node(id = "io.export_svg", category = "Export", flags(Export))]
    pub fn export_svg[ctx](
        /// File name inside the output directory (`.svg` is added when missing).
        #[ui(widget = OutputName)]
        name: k::Text = "strips.svg",
        /// The outlines (their x and y are used).
        outlines: k::List<k::Polyline>,
        /// One label per outline.
        labels: Option<k::List<k::Text>>,
        /// One label position per outline; empty: the centre of each outline's box.
        label_points: Option<k::List<k::Point>>,
        /// Millimetres per model unit (1000: the model is in metres).
        scale: k::Number = 1000.0,
        /// The sheet of each outline (`fab.nest`): one group / layer set per sheet.
        sheets: Option<k::List<k::Integer>>,
    ) -> (
        /// The written file.
        path: k::Text,
    ) {
        let sheet = outlines::prepare(&outlines, labels.as_deref(), label_points.as_deref(), scale)?
            .with_sheets(sheets.as_deref())?;
        warn_z(ctx, &sheet);
        let text = svg::encode_svg(&sheet);
        Ok((write_export(ctx, &name, "svg", text.as_bytes())?,))
    }
}

node! {
    /// Writes a DXF drawing (R2000, millimetres, metric, extents set, the same bytes for the same
    /// input) of the outlines for cutting: one LWPOLYLINE per outline on its own layer
    /// `STRIP_<label>` (`SHEET<s>_STRIP_<label>` when nested on sheets), with its label as TEXT on
    /// the same layer. With `folds` or `marks` (from `pq.unroll_strips`) the workshop layers are
    /// used instead: outlines on `CUT`, labels on `TEXT`, fold lines on `FOLDS` each with its
    /// signed angle as TEXT, marks on `MARKS` with their labels. With `sheets` (`fab.nest`) each
    /// sheet's outlines, labels, folds and marks are one block `SHEET_<s+1>`, inserted at its place.
    #[node(id = "io.export_dxf", category = "Export", flags(Export))]
    pub fn export_dxf[ctx](
        /// File name inside the output directory (`.dxf` is added when missing).
        #[ui(widget = OutputName)]
        name: k::Text = "strips.dxf",
        /// The outlines (their x and y are used).
        outlines: k::List<k::Polyline>,
        /// One label per outline (also names its layer).
        labels: Option<k::List<k::Text>>,
        /// One label position per outline; empty: the centre of each outline's box.
        label_points: Option<k::List<k::Point>>,
        /// Millimetres per model unit (1000: the model is in metres).
        scale: k::Number = 1000.0,
        /// The sheet of each outline (`fab.nest`): one block `SHEET_<s+1>` per sheet.
        sheets: Option<k::List<k::Integer>>,
        /// Fold lines (`pq.unroll_strips`): written on layer `FOLDS`; with folds or marks the
        /// outlines go on `CUT` and their labels on `TEXT`.
        folds: Option<k::List<k::Polyline>>,
        /// The signed angle of every fold in degrees (mountain positive), written beside it.
        fold_angles: Option<k::List<k::Number>>,
        /// Marks (`pq.unroll_strips`): written on layer `MARKS`.
        marks: Option<k::List<k::Polyline>>,
        /// The text of every mark, written at its end.
        mark_labels: Option<k::List<k::Text>>,
    ) -> (
        /// The written file.
        path: k::Text,
    ) {
        let sheet = outlines::prepare(&outlines, labels.as_deref(), label_points.as_deref(), scale)?
            .with_sheets(sheets.as_deref())?
            .with_workshop_lines(
                folds.as_deref(),
                fold_angles.as_deref(),
                marks.as_deref(),
                mark_labels.as_deref(),
                scale,
            )?;
        warn_z(ctx, &sheet);
        let bytes = cad::encode_dxf(&sheet)?;
        Ok((write_export(ctx, &name, "dxf", &bytes)?,))
    }
}

node! {
    /// Writes any value (a mesh, points, polylines, a quality record, …) as JSON in the runner's
    /// encoding (as `cnets eval` prints it: meshes are vertex tables `{vertices, faces}`).
    #[node(id = "io.export_json", category = "Export", flags(Export))]
    pub fn export_json[ctx](
        /// File name inside the output directory (`.json` is added when missing).
        #[ui(widget = OutputName)]
        name: k::Text = "data.json",
        /// The value to write (passed whole, lists included).
        value: k::Tree<k::Any>,
    ) -> (
        /// The written file.
        path: k::Text,
    ) {
        Ok((stream_export(ctx, &name, "json", |out| table::write_json(out, &value))?,))
    }
}

node! {
    /// Writes the vertices of points, polylines, lines and meshes as a CSV table
    /// `item,index,row,col,x,y,z` (row/col for quad-mesh vertices), numbers as the runner's JSON
    /// writes them. Records (a list of them, e.g. `fab.schedule`'s table) are written as a table
    /// instead: a column per field, a line per record (a point as `x y z`, a list joined by `; `).
    #[node(id = "io.export_csv", category = "Export", flags(Export))]
    pub fn export_csv[ctx](
        /// File name inside the output directory (`.csv` is added when missing).
        #[ui(widget = OutputName)]
        name: k::Text = "vertices.csv",
        /// The geometry whose vertices are listed (passed whole, lists included), or records.
        value: k::Tree<k::Any>,
    ) -> (
        /// The written file.
        path: k::Text,
    ) {
        Ok((stream_export(ctx, &name, "csv", |out| table::write_csv(out, &value))?,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![
        export_gltf(),
        export_obj(),
        export_svg(),
        export_dxf(),
        export_json(),
        export_csv(),
    ]
}
