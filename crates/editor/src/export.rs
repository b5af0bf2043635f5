//! File › Export: runs the graph's own export nodes (every enabled node whose type is flagged
//! `Export`: `io.export_*`, the fabrication exporters), as `cnets run` does, and lists the files
//! they wrote ([`run_exports`]); or, as a quick export of the preview, writes the previewed
//! cone-net as glTF binary, OBJ, SVG or DXF under a name the designer gives, through the
//! library's export node for that format ([`export`]), so the editor and `cnets run` write the
//! same files.
//!
//! For the quick export
//! the export node's ports are read from the registry: its first input that accepts the mesh is
//! wired to the first previewed quad mesh (else polygon mesh) of the graph, and a text input named
//! like `file`, `name` or `path` gets the document's name. The graph is evaluated on a copy with
//! the chosen folder as output directory.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::{Evaluator, Graph, Layer, NodeDef, NodeFlag, NodeResult, Registry, ValueType};

/// An export format of the File menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    /// glTF binary.
    Glb,
    /// Wavefront OBJ.
    Obj,
    /// SVG (unrolled strips / flat drawings).
    Svg,
    /// DXF.
    Dxf,
}

impl ExportFormat {
    /// All formats.
    pub const ALL: [ExportFormat; 4] = [
        ExportFormat::Glb,
        ExportFormat::Obj,
        ExportFormat::Svg,
        ExportFormat::Dxf,
    ];

    /// File extension and menu label.
    pub fn extension(self) -> &'static str {
        match self {
            ExportFormat::Glb => "glb",
            ExportFormat::Obj => "obj",
            ExportFormat::Svg => "svg",
            ExportFormat::Dxf => "dxf",
        }
    }

    fn matches(self, id: &str) -> bool {
        let id = id.to_ascii_lowercase();
        match self {
            ExportFormat::Glb => id.contains("glb") || id.contains("gltf"),
            other => id.contains(other.extension()),
        }
    }
}

/// The export node type for a format: an `Export`-flagged node whose id names the format.
pub fn export_node(registry: &Registry, format: ExportFormat) -> Option<Arc<NodeDef>> {
    registry
        .iter()
        .find(|d| d.has_flag(NodeFlag::Export) && format.matches(&d.id))
        .cloned()
}

/// The node output to export: the first previewed, enabled node output of type quad mesh, else
/// polygon mesh, as `(node id, output name, type)`.
pub fn export_source(graph: &Graph) -> Option<(String, String, ValueType)> {
    for wanted in [ValueType::QuadMesh, ValueType::Mesh] {
        for (_, n) in graph.nodes() {
            if !(n.preview && n.enabled) || n.def.has_flag(NodeFlag::Export) {
                continue;
            }
            if let Some(p) = n.def.outputs.iter().find(|p| p.ty == wanted) {
                return Some((n.id.clone(), p.name.to_string(), wanted));
            }
        }
    }
    None
}

/// A registered node that lays a quad mesh flat as outlines (e.g. `pq.unroll_strips`): an input
/// accepting a quad mesh and a polyline output in the fabrication layer.
pub fn unroller(registry: &Registry) -> Option<Arc<NodeDef>> {
    registry
        .iter()
        .find(|d| {
            !d.has_flag(NodeFlag::Export)
                && d.inputs
                    .iter()
                    .any(|p| p.ty != ValueType::Any && ValueType::QuadMesh.converts_to(&p.ty))
                && d.outputs
                    .iter()
                    .any(|p| p.hint.layer == Some(Layer::Unrolled) && p.ty == ValueType::Polyline)
        })
        .cloned()
}

/// Wires the graph's geometry into export node `id`: a mesh input gets the previewed mesh; a
/// polyline input (flat drawings: SVG, DXF) gets a previewed `outlines` output, else the outlines
/// of an unroller node added for the purpose; other inputs with the same name as an output of
/// that node (labels, label points) are wired too.
fn wire_export(g: &mut Graph, id: &str, def: &NodeDef) -> Result<(), String> {
    let err = |e: cnets_engine::GraphError| e.to_string();
    let (source, output, ty) = export_source(g).ok_or("nothing to export: no previewed mesh")?;
    if let Some(input) = def
        .inputs
        .iter()
        .find(|p| p.ty != ValueType::Any && ty.converts_to(&p.ty))
    {
        g.connect(&source, &output, id, &input.name).map_err(err)?;
        return Ok(());
    }
    let Some(outlines_in) = def.inputs.iter().find(|p| p.ty == ValueType::Polyline) else {
        return Err(format!("{} takes neither a mesh nor outlines", def.id));
    };
    // A previewed node that already makes outlines (e.g. an unroll node in the graph)?
    let existing = g.nodes().find_map(|(_, n)| {
        (n.preview && n.enabled && !n.def.has_flag(NodeFlag::Export))
            .then(|| n.def.output_index("outlines").map(|_| n.id.clone()))
            .flatten()
    });
    let flat = match existing {
        Some(node) => node,
        None => {
            let unroll = unroller(g.registry()).ok_or_else(|| {
                format!(
                    "{} needs flat outlines and no unroll node is registered",
                    def.id
                )
            })?;
            let flat = crate::document::fresh_id(g, &unroll.id);
            g.add_node_with_def(&flat, unroll.clone()).map_err(err)?;
            let mesh_in = unroll
                .inputs
                .iter()
                .find(|p| p.ty != ValueType::Any && ValueType::QuadMesh.converts_to(&p.ty))
                .map(|p| p.name.to_string())
                .unwrap_or_default();
            g.connect(&source, &output, &flat, &mesh_in).map_err(err)?;
            flat
        }
    };
    g.connect(&flat, "outlines", id, &outlines_in.name)
        .map_err(err)?;
    let outputs: Vec<String> = g
        .node(&flat)
        .map(|n| n.def.outputs.iter().map(|p| p.name.to_string()).collect())
        .unwrap_or_default();
    for p in &def.inputs {
        if p.name != outlines_in.name && outputs.iter().any(|o| *o == p.name) {
            // Optional extras (labels…): a type mismatch just leaves them out.
            let _ = g.connect(&flat, &p.name, id, &p.name);
        }
    }
    Ok(())
}

/// The graph's own export nodes, in file order: enabled nodes whose type is flagged `Export`.
pub fn export_nodes(graph: &Graph) -> Vec<String> {
    graph
        .nodes()
        .filter(|(_, n)| n.enabled && n.def.has_flag(NodeFlag::Export))
        .map(|(_, n)| n.id.clone())
        .collect()
}

/// What one export node did when File › Export ran it.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportRun {
    /// The node's id.
    pub node: String,
    /// What the designer calls it (its name, else its id).
    pub label: String,
    /// The files it wrote, or why it wrote nothing.
    pub result: Result<Vec<PathBuf>, String>,
    /// What went into them, a line each (a quick export of the preview: per node).
    pub contents: Vec<String>,
}

/// What File › Export wrote: listed in a dialog until it is closed.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportReport {
    /// The folder written into.
    pub folder: PathBuf,
    /// One entry per export node run (a quick export: one, for the preview).
    pub runs: Vec<ExportRun>,
}

impl ExportReport {
    /// Every file written, in order.
    pub fn files(&self) -> Vec<PathBuf> {
        self.runs
            .iter()
            .filter_map(|r| r.result.as_ref().ok())
            .flatten()
            .cloned()
            .collect()
    }

    /// The status bar's line: how many files, and how many exports failed.
    pub fn summary(&self) -> String {
        let failed = self.runs.iter().filter(|r| r.result.is_err()).count();
        let files = self.files().len();
        if let [run] = self.runs.as_slice()
            && run.result.is_ok()
            && !run.contents.is_empty()
        {
            return format!(
                "exported {files} file(s) into {}: {}",
                self.folder.display(),
                run.contents.join("; ")
            );
        }
        match failed {
            0 => format!("exported {files} file(s) into {}", self.folder.display()),
            n => format!(
                "exported {files} file(s) into {}; {n} export(s) failed",
                self.folder.display()
            ),
        }
    }

    /// The dialog: each export with the files it wrote (selectable, to copy) or why it failed.
    /// Returns false once it is closed.
    pub fn show(&self, ctx: &egui::Context) -> bool {
        let mut open = true;
        let mut close = false;
        egui::Window::new("Exported")
            .id(egui::Id::new("cnets-export-report"))
            .open(&mut open)
            .collapsible(false)
            .default_width(460.0)
            .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
            .show(ctx, |ui| {
                ui.weak(format!("into {}", self.folder.display()));
                for run in &self.runs {
                    ui.strong(&run.label);
                    for line in &run.contents {
                        ui.label(line);
                    }
                    match &run.result {
                        Ok(files) if files.is_empty() => {
                            ui.weak("wrote nothing");
                        }
                        Ok(files) => {
                            for f in files {
                                ui.add(
                                    egui::Label::new(f.display().to_string())
                                        .selectable(true)
                                        .wrap(),
                                );
                            }
                        }
                        Err(e) => {
                            ui.colored_label(egui::Color32::from_rgb(0xd6, 0x2f, 0x2f), e);
                        }
                    }
                }
                let ok = ui.button("Close");
                crate::probe::record(ui.ctx(), "Close export list", ok.rect);
                // Escape closes it, as every dialog.
                close = ok.clicked() || ui.input(|i| i.key_pressed(egui::Key::Escape));
            });
        open && !close
    }
}

/// Runs the graph's own export nodes ([`export_nodes`]) with `folder` as the output folder, as
/// `cnets run --out FOLDER` does: each writes the file its own inputs name, with the graph's
/// settings. `allow_read`: the document's allowed reads (as `--allow-read`). Returns one
/// [`ExportRun`] per export node; an error when the graph has none or the folder cannot be made.
pub fn run_exports(
    graph: &Graph,
    base_dir: Option<PathBuf>,
    allow_read: &[PathBuf],
    folder: &Path,
) -> Result<Vec<ExportRun>, String> {
    let ids = export_nodes(graph);
    if ids.is_empty() {
        return Err(
            "this graph has no export nodes (add one from the palette's Export \
                    category, or use a quick export of the preview)"
                .into(),
        );
    }
    let ctx = cnets_host::Session::new()
        .with_allow_read(allow_read.iter().cloned())
        .with_out_dir(Some(folder.to_path_buf()))
        .export_context(base_dir, true)
        .map_err(|e| e.to_string())?;
    let mut eval = Evaluator::new();
    let indices = ids
        .iter()
        .map(|id| graph.index(id).map_err(|e| e.to_string()))
        .collect::<Result<Vec<_>, _>>()?;
    eval.evaluate(graph, &indices, &ctx, &mut |_, _| {});
    Ok(ids
        .into_iter()
        .map(|id| {
            let result = match eval.result(graph, &id) {
                Some(NodeResult::Ok(out)) => Ok(out.files.clone()),
                Some(other) => Err(other
                    .error()
                    .map_or("export failed".into(), |e| e.into_owned())),
                None => Err("did not run".into()),
            };
            let label = graph
                .node(&id)
                .map_or_else(|| id.clone(), |n| n.label().to_string());
            ExportRun {
                node: id,
                label,
                result,
                contents: Vec::new(),
            }
        })
        .collect())
}

/// Exports the graph's geometry as `folder/name.<extension>` through the format's export node
/// (a quick export of the preview); returns the files written. `allow_read`: the document's
/// allowed reads.
pub fn export(
    graph: &Graph,
    base_dir: Option<PathBuf>,
    allow_read: &[PathBuf],
    format: ExportFormat,
    folder: &Path,
    name: &str,
) -> Result<Vec<PathBuf>, String> {
    let def = export_node(graph.registry(), format).ok_or_else(|| {
        format!(
            "no {} export node is registered in this build",
            format.extension()
        )
    })?;
    let mut g = graph.clone();
    let id = crate::document::fresh_id(&g, &format!("export_{}", format.extension()));
    g.add_node_with_def(&id, def.clone())
        .map_err(|e| e.to_string())?;
    wire_export(&mut g, &id, &def)?;
    if let Some(file_port) = def
        .inputs
        .iter()
        .find(|p| p.hint.widget == cnets_engine::Widget::OutputName)
    {
        let file = format!("{name}.{}", format.extension());
        g.set_value(&id, &file_port.name, cnets_engine::Value::text(file))
            .map_err(|e| e.to_string())?;
    }
    let ctx = cnets_host::Session::new()
        .with_allow_read(allow_read.iter().cloned())
        .with_out_dir(Some(folder.to_path_buf()))
        .export_context(base_dir, true)
        .map_err(|e| e.to_string())?;
    let mut eval = Evaluator::new();
    let index = g.index(&id).map_err(|e| e.to_string())?;
    eval.evaluate(&g, &[index], &ctx, &mut |_, _| {});
    match eval.result(&g, &id) {
        Some(NodeResult::Ok(out)) => Ok(out.files.clone()),
        Some(other) => Err(other
            .error()
            .map_or("export failed".into(), |e| e.into_owned())),
        None => Err("export did not run".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::{Access, PortDef, Value};

    /// The hint of an export node's file-name input.
    fn output_name() -> cnets_engine::PortHint {
        cnets_engine::PortHint {
            widget: cnets_engine::Widget::OutputName,
            ..Default::default()
        }
    }

    /// A stand-in export node (the real ones are written in parallel): writes the mesh's vertex
    /// count into the named file.
    fn stand_in() -> NodeDef {
        NodeDef::new("io.export_obj", "Export", "Test OBJ export.")
            .input(PortDef::new("mesh", ValueType::Mesh, Access::Item))
            .input(
                PortDef::new("file", ValueType::Text, Access::Item)
                    .with_default(Value::text("out.obj"))
                    .with_hint(output_name()),
            )
            .output(PortDef::new("path", ValueType::Text, Access::Item))
            .flag(NodeFlag::Export)
            .run(|ctx, inputs| {
                let Value::Text(name) = &inputs[1] else {
                    return Err("no name".into());
                };
                let path = ctx.output_path(name)?;
                let n = match &inputs[0] {
                    Value::Mesh(m) => m.vertices.len(),
                    _ => 0,
                };
                std::fs::write(&path, format!("{n}"))?;
                ctx.record_file(path.clone());
                Ok(vec![Value::text(path.display().to_string())])
            })
    }

    /// A stand-in flat-drawing export: outlines and labels, writes "<outlines> <labels>".
    fn svg_stand_in() -> NodeDef {
        NodeDef::new("io.export_svg", "Export", "Test SVG export.")
            .input(
                PortDef::new("name", ValueType::Text, Access::Item)
                    .with_default(Value::text("strips.svg"))
                    .with_hint(output_name()),
            )
            .input(PortDef::new("outlines", ValueType::Polyline, Access::List))
            .input(PortDef::new("labels", ValueType::Text, Access::List).optional())
            .output(PortDef::new("path", ValueType::Text, Access::Item))
            .flag(NodeFlag::Export)
            .run(|ctx, inputs| {
                let Value::Text(name) = &inputs[0] else {
                    return Err("no name".into());
                };
                let path = ctx.output_path(name)?;
                let n = inputs[1].as_list().map_or(0, <[Value]>::len);
                let l = inputs[2].as_list().map_or(0, <[Value]>::len);
                std::fs::write(&path, format!("{n} {l}"))?;
                ctx.record_file(path.clone());
                Ok(vec![Value::text(path.display().to_string())])
            })
    }

    /// A stand-in unroller: one outline and one label per quad row.
    fn unroll_stand_in() -> NodeDef {
        NodeDef::new("pq.unroll_strips", "PQ", "Test unroll.")
            .input(PortDef::new("mesh", ValueType::QuadMesh, Access::Item))
            .output(PortDef::new("outlines", ValueType::Polyline, Access::List))
            .output(PortDef::new("labels", ValueType::Text, Access::List))
            .run(|_, inputs| {
                let Value::QuadMesh(g) = &inputs[0] else {
                    return Err("no mesh".into());
                };
                let rows = g.quad_rows();
                let outline = Value::Polyline(Arc::new(cnets_geometry::Polyline::open(vec![
                    cnets_geometry::DVec3::ZERO,
                    cnets_geometry::DVec3::X,
                ])));
                Ok(vec![
                    Value::list(vec![outline; rows]),
                    Value::list((0..rows).map(|i| Value::text(format!("D{i}"))).collect()),
                ])
            })
    }

    #[test]
    fn flat_drawings_export_unrolled_outlines_with_labels() {
        let mut r = cnets_nodes::registry();
        r.register(svg_stand_in());
        if unroller(&r).is_none() {
            r.register(unroll_stand_in());
        }
        let registry = Arc::new(r);
        let text = include_str!("../../../graphs/editor-default.ron");
        let doc = cnets_engine::file::load_str(text, "default", &registry).unwrap();
        let dir = std::env::temp_dir().join(format!("cnets-export-svg-{}", std::process::id()));
        let files = export(&doc.graph, None, &[], ExportFormat::Svg, &dir, "net").unwrap();
        assert_eq!(files, vec![dir.join("net.svg")]);
        // The default net has 10 quad rows along the directrix: 10 strips, each labelled.
        assert_eq!(std::fs::read_to_string(&files[0]).unwrap(), "10 10");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// With the library's own export nodes (when this build registers them): every format
    /// writes a non-empty file.
    #[test]
    fn the_library_export_nodes_write_files() {
        let registry = Arc::new(cnets_nodes::registry());
        let text = include_str!("../../../graphs/editor-default.ron");
        let doc = cnets_engine::file::load_str(text, "default", &registry).unwrap();
        let dir = std::env::temp_dir().join(format!("cnets-export-real-{}", std::process::id()));
        for f in ExportFormat::ALL {
            let flat = matches!(f, ExportFormat::Svg | ExportFormat::Dxf);
            if export_node(&registry, f).is_none() || (flat && unroller(&registry).is_none()) {
                eprintln!("{f:?}: no export node registered yet, skipped");
                continue;
            }
            let files = export(&doc.graph, None, &[], f, &dir, "net")
                .unwrap_or_else(|e| panic!("{f:?}: {e}"));
            assert!(!files.is_empty(), "{f:?} wrote nothing");
            for file in files {
                assert!(
                    std::fs::metadata(&file).unwrap().len() > 0,
                    "{} is empty",
                    file.display()
                );
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn exports_the_previewed_mesh_through_the_export_node() {
        let mut r = cnets_nodes::registry();
        r.register(stand_in());
        let registry = Arc::new(r);
        let text = include_str!("../../../graphs/editor-default.ron");
        let doc = cnets_engine::file::load_str(text, "default", &registry).unwrap();
        assert_eq!(export_source(&doc.graph).unwrap().0, "construct");
        let dir = std::env::temp_dir().join(format!("cnets-export-{}", std::process::id()));
        let files = export(&doc.graph, None, &[], ExportFormat::Obj, &dir, "net").unwrap();
        assert_eq!(files, vec![dir.join("net.obj")]);
        let count: usize = std::fs::read_to_string(&files[0]).unwrap().parse().unwrap();
        assert_eq!(count, 11 * 19);
        assert!(
            export(&doc.graph, None, &[], ExportFormat::Dxf, &dir, "net").is_err()
                || export_node(&registry, ExportFormat::Dxf).is_some()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
