//! File › Export ▸ GLB / OBJ, the quick export of the preview: every mesh and curve the 3D view
//! draws ([`Picks`], so a layer switched off is not written and nothing drawn is dropped), in one
//! file, each named after the node that made it, through the library's export node for the format
//! (`io.export_gltf`, `io.export_obj`: the files `cnets run` writes). The report says what was
//! written, node by node.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use cnets_engine::{Evaluator, Graph, NodeResult, Value, Widget};

use crate::export::{ExportFormat, export_node};
use crate::preview::{PickGeometry, Picks};

/// What the preview holds for an export: values and names in the export node's item order
/// (meshes, then polylines), and the counts per node.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PreviewContents {
    /// The drawn meshes (quad grids and polygon meshes), in drawing order.
    pub meshes: Vec<Value>,
    /// The drawn curves, in drawing order.
    pub polylines: Vec<Value>,
    /// One name per mesh, then one per polyline.
    pub names: Vec<String>,
    /// One colour per face of every mesh, in order (linear RGB in [0, 1]): the node's preview
    /// colour where it has one, else the face's planarity colour (as `io.export_gltf` colours a
    /// mesh without colours).
    pub colours: Vec<cnets_geometry::DVec3>,
    /// Per node, in drawing order: its name, meshes, faces and curves.
    pub per_node: Vec<NodeCount>,
}

/// What one node contributed to an export.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct NodeCount {
    /// The node's name (its id when it has none).
    pub label: String,
    /// Meshes written.
    pub meshes: usize,
    /// Faces of those meshes.
    pub faces: usize,
    /// Curves written.
    pub curves: usize,
}

impl NodeCount {
    /// `roof: 1 mesh (210 faces), 2 curves`.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if self.meshes > 0 {
            parts.push(format!(
                "{} mesh{} ({} faces)",
                self.meshes,
                if self.meshes == 1 { "" } else { "es" },
                self.faces
            ));
        }
        if self.curves > 0 {
            parts.push(format!(
                "{} curve{}",
                self.curves,
                if self.curves == 1 { "" } else { "s" }
            ));
        }
        format!("{}: {}", self.label, parts.join(", "))
    }
}

/// The planarity above which a face is drawn fully red (`io.export_gltf`'s default).
const PLANARITY_LIMIT: f64 = 1e-3;

/// An 8-bit sRGB component as linear light (glTF colours are linear).
fn linear(c: u8) -> f64 {
    let s = f64::from(c) / 255.0;
    if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// The faces' colours of a drawn mesh: its node's preview colour (8-bit sRGB) on every face, else
/// each face's planarity colour.
fn face_colours(
    geometry: &PickGeometry,
    node_colour: Option<[u8; 3]>,
) -> Vec<cnets_geometry::DVec3> {
    use cnets_geometry::fabrication::face_attributes::{face_planarity, planarity_colour};
    if let Some([r, g, b]) = node_colour {
        let c = cnets_geometry::DVec3::new(linear(r), linear(g), linear(b));
        return vec![c; geometry.face_count()];
    }
    let planarity = match geometry {
        PickGeometry::Grid(g) => face_planarity(&cnets_geometry::PolygonMesh::from(&**g)),
        PickGeometry::Mesh(m) => face_planarity(m),
    }
    .unwrap_or_else(|_| vec![0.0; geometry.face_count()]);
    planarity
        .into_iter()
        .map(|v| planarity_colour(v, PLANARITY_LIMIT))
        .collect()
}

/// The previewed meshes and curves of `picks`, named after their nodes in `graph`: a node's only
/// item takes the node's name; several take `name output` and, for list items, `[k]`.
pub fn preview_contents(picks: &Picks, graph: &Graph) -> PreviewContents {
    let label = |id: &str| {
        graph
            .node(id)
            .map_or_else(|| id.to_string(), |n| n.label().to_string())
    };
    let mut items_per_node: HashMap<&str, usize> = HashMap::new();
    for m in &picks.meshes {
        *items_per_node.entry(&m.node).or_default() += 1;
    }
    for c in &picks.curves {
        *items_per_node.entry(&c.node).or_default() += 1;
    }
    let name = |node: &str, output: &str, item: Option<usize>| {
        let base = label(node);
        if items_per_node.get(node).copied().unwrap_or(0) <= 1 {
            return base;
        }
        match item {
            Some(k) => format!("{base} {output}[{k}]"),
            None => format!("{base} {output}"),
        }
    };
    let mut out = PreviewContents::default();
    let count = |out: &mut PreviewContents, node: &str| -> usize {
        let label = label(node);
        match out.per_node.iter().position(|c| c.label == label) {
            Some(k) => k,
            None => {
                out.per_node.push(NodeCount {
                    label,
                    ..Default::default()
                });
                out.per_node.len() - 1
            }
        }
    };
    for m in &picks.meshes {
        let k = count(&mut out, &m.node);
        out.per_node[k].meshes += 1;
        out.per_node[k].faces += m.geometry.face_count();
        out.meshes.push(match &m.geometry {
            PickGeometry::Grid(g) => Value::QuadMesh(g.clone()),
            PickGeometry::Mesh(p) => Value::Mesh(p.clone()),
        });
        let node_colour = graph.node(&m.node).and_then(|n| n.color);
        out.colours.extend(face_colours(&m.geometry, node_colour));
        out.names.push(name(&m.node, &m.output, m.item));
    }
    let mut curve_index: HashMap<(&str, &str), usize> = HashMap::new();
    for c in &picks.curves {
        let k = count(&mut out, &c.node);
        out.per_node[k].curves += 1;
        out.polylines.push(Value::Polyline(c.polyline.clone()));
        let at = curve_index.entry((&c.node, &c.output)).or_default();
        let several = picks
            .curves
            .iter()
            .filter(|o| o.node == c.node && o.output == c.output)
            .count()
            > 1;
        out.names
            .push(name(&c.node, &c.output, several.then_some(*at)));
        *at += 1;
    }
    out
}

/// Writes every mesh and curve of `picks` as `folder/name.<glb|obj>`: returns the files written
/// and what each node contributed. Fails for the flat formats (SVG, DXF: the unroll path of
/// [`crate::export::export`]) and when the preview shows nothing.
pub fn export_preview(
    picks: &Picks,
    graph: &Graph,
    base_dir: Option<PathBuf>,
    allow_read: &[PathBuf],
    format: ExportFormat,
    folder: &Path,
    name: &str,
) -> Result<(Vec<PathBuf>, Vec<NodeCount>), String> {
    if !matches!(format, ExportFormat::Glb | ExportFormat::Obj) {
        return Err(format!(
            "the preview is written as GLB or OBJ, not {}",
            format.extension()
        ));
    }
    let contents = preview_contents(picks, graph);
    if contents.meshes.is_empty() && contents.polylines.is_empty() {
        return Err("nothing to export: the 3D view shows no mesh or curve".into());
    }
    let def = export_node(graph.registry(), format).ok_or_else(|| {
        format!(
            "no {} export node is registered in this build",
            format.extension()
        )
    })?;
    // A graph of the export node alone, its inputs the preview's values.
    let mut g = Graph::new(graph.registry().clone());
    let id = "export_preview";
    g.add_node_with_def(id, def.clone())
        .map_err(|e| e.to_string())?;
    let set = |g: &mut Graph, port: &str, v: Value| -> Result<(), String> {
        g.set_value(id, port, v)
            .map(|_| ())
            .map_err(|e| format!("{}.{port}: {e}", def.id))
    };
    set(&mut g, "meshes", Value::list(contents.meshes.clone()))?;
    // The GLB's materials take the nodes' preview colours (the OBJ has no colours).
    if def.input_index("colours").is_some() && !contents.colours.is_empty() {
        set(
            &mut g,
            "colours",
            Value::list(contents.colours.iter().map(|&c| Value::Vector(c)).collect()),
        )?;
    }
    set(&mut g, "polylines", Value::list(contents.polylines.clone()))?;
    set(
        &mut g,
        "names",
        Value::list(
            contents
                .names
                .iter()
                .map(|n| Value::text(n.as_str()))
                .collect(),
        ),
    )?;
    if let Some(file_port) = def
        .inputs
        .iter()
        .find(|p| p.hint.widget == Widget::OutputName)
    {
        let file = format!("{name}.{}", format.extension());
        set(&mut g, &file_port.name, Value::text(file))?;
    }
    let ctx = cnets_host::Session::new()
        .with_allow_read(allow_read.iter().cloned())
        .with_out_dir(Some(folder.to_path_buf()))
        .export_context(base_dir, true)
        .map_err(|e| e.to_string())?;
    let mut eval = Evaluator::new();
    let index = g.index(id).map_err(|e| e.to_string())?;
    eval.evaluate(&g, &[index], &ctx, &mut |_, _| {});
    match eval.result(&g, id) {
        Some(NodeResult::Ok(out)) => Ok((out.files.clone(), contents.per_node)),
        Some(other) => Err(other
            .error()
            .map_or("export failed".into(), |e| e.into_owned())),
        None => Err("export did not run".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preview::{PreviewOptions, build_preview};
    use std::sync::Arc;

    /// The default graph with a second, previewed net beside the first (another apex).
    fn two_nets() -> Graph {
        let registry = Arc::new(cnets_nodes::registry());
        let text = include_str!("../../../graphs/editor-default.ron").replace(
            r#""planarity": ("#,
            r##""wing_b": (type: "cnets.construct", name: "Wing B", color: "#3a6ec8", inputs: {"apex": 0.9}),
        "planarity": ("##,
        );
        let text = text.replace(
            r#""construct.mesh -> planarity.mesh","#,
            r#""construct.mesh -> planarity.mesh",
        "directrix.curve -> wing_b.directrix", "generatrix.curve -> wing_b.generatrix","#,
        );
        cnets_engine::file::load_str(&text, "two nets", &registry)
            .unwrap()
            .graph
    }

    fn picks_of(graph: &Graph) -> Picks {
        let mut eval = Evaluator::new();
        let all: Vec<_> = graph.nodes().map(|(k, _)| k).collect();
        eval.evaluate(
            graph,
            &all,
            &cnets_engine::NodeContext::default(),
            &mut |_, _| {},
        );
        build_preview(graph, &eval, &PreviewOptions::default()).picks
    }

    #[test]
    fn the_preview_export_writes_every_drawn_mesh_and_curve_named_after_its_node() {
        let graph = two_nets();
        let picks = picks_of(&graph);
        let shown: usize = picks.meshes.iter().map(|m| m.geometry.face_count()).sum();
        assert_eq!(picks.meshes.len(), 2, "both nets are drawn");
        assert_eq!(shown, 2 * 10 * 18);
        let dir = std::env::temp_dir().join(format!("cnets-preview-export-{}", std::process::id()));
        let (files, counts) =
            export_preview(&picks, &graph, None, &[], ExportFormat::Obj, &dir, "roof").unwrap();
        assert_eq!(files, vec![dir.join("roof.obj")]);
        let obj = std::fs::read_to_string(&files[0]).unwrap();
        // Faces per object, read back from the file.
        let mut faces: Vec<(String, usize)> = Vec::new();
        for line in obj.lines() {
            if let Some(name) = line.strip_prefix("o ") {
                faces.push((name.to_string(), 0));
            } else if line.starts_with("f ") {
                faces.last_mut().unwrap().1 += 1;
            }
        }
        let written: usize = faces.iter().map(|f| f.1).sum();
        assert_eq!(written, shown, "every face shown is written: {faces:?}");
        assert!(faces.contains(&("construct".to_string(), 180)), "{faces:?}");
        assert!(faces.contains(&("Wing_B".to_string(), 180)), "{faces:?}");
        // The drawn curves (the directrix and the generatrix) are written too.
        assert_eq!(faces.len(), 2 + picks.curves.len());
        let described: Vec<String> = counts.iter().map(NodeCount::describe).collect();
        assert!(
            described.contains(&"Wing B: 1 mesh (180 faces)".to_string()),
            "{described:?}"
        );
        // The GLB names its nodes the same way.
        let (files, _) =
            export_preview(&picks, &graph, None, &[], ExportFormat::Glb, &dir, "roof").unwrap();
        let glb = std::fs::read(&files[0]).unwrap();
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        let json = std::str::from_utf8(&glb[20..20 + json_len]).unwrap();
        assert!(json.contains(r#""name":"Wing B""#) && json.contains(r#""name":"construct""#));
        assert!(!json.contains(r#""name":"mesh 0""#));
        // Each mesh's material is named after its node; Wing B's base colour is its preview
        // colour (#3a6ec8 as linear light), the other net (no colour) keeps its faces' colours.
        let doc: serde_json::Value = serde_json::from_str(json).unwrap();
        let materials = doc["materials"].as_array().unwrap();
        let material = |name: &str| {
            materials
                .iter()
                .find(|m| m["name"] == name)
                .unwrap_or_else(|| panic!("a material named {name}: {materials:?}"))
        };
        let base: Vec<f64> = material("Wing B")["pbrMetallicRoughness"]["baseColorFactor"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let expected = [linear(0x3a), linear(0x6e), linear(0xc8), 1.0];
        for (got, want) in base.iter().zip(expected) {
            assert!((got - want).abs() < 1e-6, "{base:?} vs {expected:?}");
        }
        assert!(material("construct").get("pbrMetallicRoughness").is_some());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_preview_with_nothing_drawn_is_an_error() {
        let graph = two_nets();
        let err = export_preview(
            &Picks::default(),
            &graph,
            None,
            &[],
            ExportFormat::Glb,
            Path::new("unused"),
            "x",
        )
        .unwrap_err();
        assert!(err.contains("nothing to export"), "{err}");
    }
}
