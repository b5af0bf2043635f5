//! File ▸ Export: writes the previewed cone-net as glTF binary, OBJ, SVG or DXF through the
//! export nodes of the library (flag `Export`), so the editor and `cnets run` write the same files.
//!
//! The export node's ports are read from the registry: its first input that accepts the mesh is
//! wired to the first previewed quad mesh (else polygon mesh) of the graph, and a text input named
//! like `file`, `name` or `path` gets the document's name. The graph is evaluated on a copy with
//! the chosen folder as output directory.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_engine::{
    Evaluator, Graph, NodeContext, NodeDef, NodeFlag, NodeResult, Registry, ValueType,
};

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

/// Exports the graph's mesh into `folder`; returns the files written.
pub fn export(
    graph: &Graph,
    base_dir: Option<PathBuf>,
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
    let (source, output, ty) =
        export_source(graph).ok_or("nothing to export: no previewed mesh")?;
    let mut g = graph.clone();
    let id = crate::document::fresh_id(&g, &format!("export_{}", format.extension()));
    g.add_node_with_def(&id, def.clone())
        .map_err(|e| e.to_string())?;
    let input = def
        .inputs
        .iter()
        .find(|p| ty.converts_to(&p.ty) && p.ty != ValueType::Any)
        .or_else(|| def.inputs.iter().find(|p| ty.converts_to(&p.ty)))
        .ok_or_else(|| format!("{} has no input for a mesh", def.id))?;
    g.connect(&source, &output, &id, &input.name)
        .map_err(|e| e.to_string())?;
    if let Some(file_port) = def.inputs.iter().find(|p| {
        p.ty == ValueType::Text && ["file", "name", "path"].iter().any(|w| p.name.contains(w))
    }) {
        let file = format!("{name}.{}", format.extension());
        g.set_value(&id, &file_port.name, cnets_engine::Value::text(file))
            .map_err(|e| e.to_string())?;
    }
    std::fs::create_dir_all(folder)
        .map_err(|e| format!("cannot create {}: {e}", folder.display()))?;
    let ctx = NodeContext::new(Some(folder.to_path_buf()), base_dir);
    let mut eval = Evaluator::new();
    let index = g.index(&id).map_err(|e| e.to_string())?;
    eval.evaluate(&g, &[index], &ctx, &mut |_, _| {});
    match eval.result(&g, &id) {
        Some(NodeResult::Ok(out)) => Ok(out.files.clone()),
        Some(other) => Err(other.error().unwrap_or("export failed").to_string()),
        None => Err("export did not run".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::{Access, PortDef, Value};

    /// A stand-in export node (the real ones are written in parallel): writes the mesh's vertex
    /// count into the named file.
    fn stand_in() -> NodeDef {
        NodeDef::new("io.export_obj", "Export", "Test OBJ export.")
            .input(PortDef::new("mesh", ValueType::Mesh, Access::Item))
            .input(
                PortDef::new("file", ValueType::Text, Access::Item)
                    .with_default(Value::text("out.obj")),
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

    #[test]
    fn exports_the_previewed_mesh_through_the_export_node() {
        let mut r = cnets_nodes::registry();
        r.register(stand_in());
        let registry = Arc::new(r);
        let text = include_str!("../../../graphs/editor-default.ron");
        let doc = cnets_engine::file::load_str(text, "default", &registry).unwrap();
        assert_eq!(export_source(&doc.graph).unwrap().0, "construct");
        let dir = std::env::temp_dir().join(format!("cnets-export-{}", std::process::id()));
        let files = export(&doc.graph, None, ExportFormat::Obj, &dir, "net").unwrap();
        assert_eq!(files, vec![dir.join("net.obj")]);
        let count: usize = std::fs::read_to_string(&files[0]).unwrap().parse().unwrap();
        assert_eq!(count, 11 * 19);
        assert!(
            export(&doc.graph, None, ExportFormat::Dxf, &dir, "net").is_err()
                || export_node(&registry, ExportFormat::Dxf).is_some()
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
