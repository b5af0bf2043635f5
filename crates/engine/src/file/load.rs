//! Reading a graph file: parsing, validating every node, input and edge into a [`Document`], and
//! reporting each problem with its location.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::FORMAT_VERSION;
use super::clusters::load_cluster;
use super::diagnostics::{Diagnostic, LoadError};
use super::literal::{self, LiteralError};
use super::ron::{self, Kind, Node, Pos};
use crate::cluster::{CLUSTER_TYPE, Cluster};
use crate::files::ReadAccess;
use crate::graph::{Graph, GraphError, WireRef};
use crate::registry::Registry;

/// Metadata of a graph file besides nodes and edges.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GraphMeta {
    /// Short title.
    pub name: Option<String>,
    /// What the graph is for.
    pub description: Option<String>,
    /// A stored optimization setup (see [`crate::optimize`]).
    pub optimization: Option<crate::optimize::Setup>,
    /// The editor's named construction planes (empty when the file has none).
    pub cplanes: Vec<super::cplanes::NamedPlane>,
}

/// A loaded graph file.
#[derive(Debug, Clone)]
pub struct Document {
    /// The graph.
    pub graph: Graph,
    /// Its metadata.
    pub meta: GraphMeta,
    /// Problems that do not stop loading (e.g. a required input neither wired nor set): the graph
    /// loads and can be edited, but the node will fail when evaluated.
    pub warnings: Vec<Diagnostic>,
}

/// Where cluster sources are looked up, and the chain of files being loaded (to refuse recursion).
#[derive(Debug, Clone, Default)]
pub struct LoadOptions {
    /// Folder relative cluster sources resolve against first (the graph file's folder).
    pub base_dir: Option<PathBuf>,
    /// Library folders searched next for cluster sources.
    pub library: Vec<PathBuf>,
    /// Further folders cluster files may be read from (`--allow-read DIR`). Cluster files are read
    /// only under the top graph's folder, the library folders and these.
    pub allow_read: Vec<PathBuf>,
    /// The top graph's folder (set when the first file is loaded).
    top_dir: Option<PathBuf>,
    /// Canonical paths of the files being loaded, outermost first.
    pub(super) stack: Vec<PathBuf>,
}

impl LoadOptions {
    /// Options for loading `path`: cluster sources resolve in its folder, and in library folders
    /// added with [`LoadOptions::with_library`] (the engine reads no environment: a front end
    /// reads `CNETS_LIBRARY` and adds its folders, `cnets_host::library_from_env`).
    pub fn for_file(path: &Path) -> Self {
        Self {
            base_dir: path.parent().map(Path::to_path_buf),
            library: Vec::new(),
            allow_read: Vec::new(),
            top_dir: None,
            stack: Vec::new(),
        }
    }

    /// Adds a library folder (builder style).
    pub fn with_library(mut self, dir: impl Into<PathBuf>) -> Self {
        self.library.push(dir.into());
        self
    }

    /// Where cluster files may be read: the top graph's folder (else the base folder), the library
    /// folders and the `allow_read` folders.
    pub(super) fn read_access(&self) -> ReadAccess {
        let top = self
            .top_dir
            .clone()
            .or_else(|| self.base_dir.clone())
            .unwrap_or_else(|| PathBuf::from("."));
        ReadAccess::new(
            std::iter::once(&top)
                .chain(&self.library)
                .chain(&self.allow_read)
                .cloned()
                .collect(),
        )
    }

    /// Finds a cluster source: relative to the base folder, then in each library folder (with or
    /// without the `.ron` extension). A candidate outside the folders cluster files may be read
    /// from is skipped by its name, before anything looks at the file system: a graph cannot
    /// tell a missing file from a present one outside (issue 27 §4).
    pub(super) fn resolve(&self, written: &str) -> Result<PathBuf, Unresolved> {
        let rel = Path::new(written);
        let mut looked = Vec::new();
        let mut outside = None;
        let access = self.read_access();
        let dirs = self.base_dir.iter().chain(&self.library);
        let candidates: Vec<PathBuf> = if rel.is_absolute() {
            vec![rel.to_path_buf()]
        } else {
            dirs.map(|d| d.join(rel))
                .chain(std::iter::once(rel.to_path_buf()).filter(|_| self.base_dir.is_none()))
                .collect()
        };
        for c in candidates {
            for path in [c.clone(), c.with_extension("ron")] {
                if let Err(e) = access.check_name(&path) {
                    outside.get_or_insert(e);
                    continue;
                }
                if path.is_file() {
                    return Ok(path);
                }
                looked.push(path);
            }
        }
        match outside {
            Some(e) if looked.is_empty() => Err(Unresolved::Outside(e)),
            _ => Err(Unresolved::NotFound(looked)),
        }
    }
}

/// Why a cluster source was not found.
#[derive(Debug)]
pub(super) enum Unresolved {
    /// Not at any of these paths (inside the allowed folders).
    NotFound(Vec<PathBuf>),
    /// Every candidate lies outside the allowed folders (refused by name).
    Outside(crate::files::FileError),
}

/// The state of one file's loading: where it is, what went wrong so far, the cluster files read.
pub(super) struct Loader<'a> {
    pub(super) file: &'a str,
    pub(super) diagnostics: Vec<Diagnostic>,
    pub(super) warnings: Vec<Diagnostic>,
    pub(super) options: &'a LoadOptions,
    /// Cluster files loaded so far in this file: each is read once, instances get their own copy.
    pub(super) clusters: HashMap<PathBuf, Option<Arc<Cluster>>>,
}

impl Loader<'_> {
    pub(super) fn error(&mut self, pos: Pos, message: impl Into<String>) {
        self.report(Some(pos), message);
    }

    /// Reports a problem at `pos` of this file (`None`: of no place in it).
    pub(super) fn report(&mut self, pos: Option<Pos>, message: impl Into<String>) {
        self.diagnostics.push(Diagnostic {
            file: self.file.to_string(),
            pos,
            message: crate::files::escape_controls(&short_quotes(&message.into())).into_owned(),
        });
    }

    pub(super) fn literal(&mut self, e: LiteralError, context: &str) {
        self.error(e.pos, format!("{context}: {}", e.message));
    }
}

/// Reads a graph file from disk (cluster sources resolve next to it; no library folders).
pub fn load_file(path: &Path, registry: &Arc<Registry>) -> Result<Document, LoadError> {
    load_file_with(path, registry, &LoadOptions::for_file(path))
}

/// Reads a graph file from disk with explicit options.
pub fn load_file_with(
    path: &Path,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Result<Document, LoadError> {
    let mut options = options.clone();
    if options.top_dir.is_none() {
        options.top_dir = Some(match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        });
    }
    if let Ok(canonical) = path.canonicalize()
        && options.stack.last() != Some(&canonical)
    {
        options.stack.push(canonical);
    }
    let file = path.display().to_string();
    // The file itself is allowed (the caller named it); a device, a FIFO or a huge file is not.
    let own_folder = ReadAccess::new(vec![path.parent().map_or_else(
        || PathBuf::from("."),
        |p| {
            if p.as_os_str().is_empty() {
                PathBuf::from(".")
            } else {
                p.to_path_buf()
            }
        },
    )]);
    let text = own_folder.read_text(path).map_err(|e| LoadError {
        diagnostics: vec![Diagnostic {
            file: file.clone(),
            pos: None,
            message: format!("cannot read: {e}"),
        }],
    })?;
    load_str_with(&text, &file, registry, &options)
}

/// Parses and validates a graph file's text; `file` names it in diagnostics. Relative cluster
/// sources resolve against the current directory.
pub fn load_str(text: &str, file: &str, registry: &Arc<Registry>) -> Result<Document, LoadError> {
    load_str_with(text, file, registry, &LoadOptions::default())
}

/// Parses and validates a graph file's text with explicit options.
pub fn load_str_with(
    text: &str,
    file: &str,
    registry: &Arc<Registry>,
    options: &LoadOptions,
) -> Result<Document, LoadError> {
    let mut loader = Loader {
        file,
        diagnostics: Vec::new(),
        warnings: Vec::new(),
        options,
        clusters: HashMap::new(),
    };
    let root = match ron::parse(text) {
        Ok(root) => root,
        Err(e) => {
            loader.error(e.pos, format!("syntax error: {}", e.message));
            return Err(LoadError {
                diagnostics: loader.diagnostics,
            });
        }
    };
    let mut document = load_root(&mut loader, &root, registry);
    if loader.diagnostics.is_empty() {
        document.warnings = loader.warnings;
        Ok(document)
    } else {
        let own = file.to_string();
        loader.diagnostics.sort_by_key(|d| (d.file != own, d.pos));
        Err(LoadError {
            diagnostics: loader.diagnostics,
        })
    }
}

pub(super) fn load_root(
    loader: &mut Loader<'_>,
    root: &Node,
    registry: &Arc<Registry>,
) -> Document {
    let mut document = Document {
        graph: Graph::new(registry.clone()),
        meta: GraphMeta::default(),
        warnings: Vec::new(),
    };
    let Kind::Struct(_, fields) = &root.kind else {
        loader.error(
            root.pos,
            format!(
                "a graph file is a struct (version: 1, nodes: {{..}}, edges: [..]), found {}",
                root.kind.describe()
            ),
        );
        return document;
    };
    let mut version = None;
    let mut optimization = None;
    let mut nodes = None;
    let mut edges = None;
    for (field, value) in fields {
        match field.name.as_str() {
            "version" => version = Some(value),
            "nodes" => nodes = Some(value),
            "edges" => edges = Some(value),
            "name" => document.meta.name = text_field(loader, value, "name"),
            "optimization" => optimization = Some(value),
            "description" => document.meta.description = text_field(loader, value, "description"),
            "cplanes" => match super::cplanes::parse(value) {
                Ok(planes) => document.meta.cplanes = planes,
                Err((pos, message)) => loader.error(pos, format!("cplanes: {message}")),
            },
            other => loader.error(
                field.pos,
                format!(
                    "unknown field '{other}'; expected version, name, description, nodes, edges, optimization, cplanes"
                ),
            ),
        }
    }
    match version.map(|v| (v, &v.kind)) {
        None => loader.error(
            root.pos,
            "missing field 'version' (this build writes version 1)",
        ),
        Some((_, Kind::Int(FORMAT_VERSION))) => {}
        Some((v, Kind::Int(n))) if *n > FORMAT_VERSION => {
            loader.error(v.pos, format!("file version {n} is newer than this cnets supports ({FORMAT_VERSION}); upgrade cnets"));
            return document;
        }
        Some((v, _)) => {
            loader.error(
                v.pos,
                format!("unsupported file version; expected {FORMAT_VERSION}"),
            );
            return document;
        }
    }
    let mut failed_nodes = Vec::new();
    if let Some(nodes) = nodes {
        load_nodes(loader, nodes, &mut document.graph, &mut failed_nodes);
    }
    if let Some(edges) = edges {
        load_edges(loader, edges, &mut document.graph, &failed_nodes);
    }
    if let Some(nodes) = nodes {
        warn_unset_inputs(loader, nodes, &document.graph);
    }
    if let Some(section) = optimization {
        document.meta.optimization = load_optimization(loader, section, &document.graph);
    }
    document
}

/// Reads the optimization setup and checks that the nodes and ports it names exist.
fn load_optimization(
    loader: &mut Loader<'_>,
    section: &Node,
    graph: &Graph,
) -> Option<crate::optimize::Setup> {
    let setup = match crate::optimize::Setup::parse(section) {
        Ok(s) => s,
        Err((pos, message)) => {
            loader.error(pos, format!("optimization: {message}"));
            return None;
        }
    };
    let refs = std::iter::once((&setup.objective, false))
        .chain(setup.variables.iter().map(|v| (&v.input, true)))
        .chain(setup.penalties.iter().map(|p| (&p.output, false)));
    let mut ok = true;
    for (path, is_input) in refs {
        let problem = match graph.node(&path.node) {
            None => Some(format!("no node '{}'", path.node)),
            Some(n) if is_input && n.def.input_index(&path.port).is_none() => Some(format!(
                "node '{}' has no input '{}'; its inputs are: {}",
                path.node,
                path.port,
                n.def.input_names()
            )),
            Some(n) if !is_input && n.def.output_index(&path.port).is_none() => Some(format!(
                "node '{}' has no output '{}'; its outputs are: {}",
                path.node,
                path.port,
                n.def.output_names()
            )),
            Some(_) => None,
        };
        if let Some(p) = problem {
            loader.error(section.pos, format!("optimization: {path}: {p}"));
            ok = false;
        }
    }
    ok.then_some(setup)
}

/// Warns about required inputs that are neither wired nor set (at the node's position).
fn warn_unset_inputs(loader: &mut Loader<'_>, nodes: &Node, graph: &Graph) {
    let Kind::Map(entries) = &nodes.kind else {
        return;
    };
    for (key, body) in entries {
        let Some(id) = key.as_str() else { continue };
        let (Ok(index), Some(node)) = (graph.index(id), graph.node(id)) else {
            continue;
        };
        let wired: Vec<usize> = graph
            .wires_into(index)
            .iter()
            .map(|(_, w)| w.to_input)
            .collect();
        for (k, port) in node.def.inputs.iter().enumerate() {
            if port.required() && node.value(k).is_none() && !wired.contains(&k) {
                loader.warnings.push(Diagnostic {
                    file: loader.file.to_string(),
                    pos: Some(body.pos),
                    message: format!(
                        "node '{id}': required input '{}' is neither connected nor set",
                        port.name
                    ),
                });
            }
        }
    }
}

fn text_field(loader: &mut Loader<'_>, value: &Node, name: &str) -> Option<String> {
    match &value.kind {
        Kind::Str(s) => Some(s.clone()),
        other => {
            loader.error(
                value.pos,
                format!("'{name}' must be a string, found {}", other.describe()),
            );
            None
        }
    }
}

/// `message` with every quoted piece ('…') longer than 60 characters cut to an excerpt: an error
/// about a 10 MB edge or a 10⁷-character type name quotes a short excerpt, not all of it.
fn short_quotes(message: &str) -> String {
    crate::files::short_quotes(message, 60)
}

fn load_nodes(loader: &mut Loader<'_>, nodes: &Node, graph: &mut Graph, failed: &mut Vec<String>) {
    let Kind::Map(entries) = &nodes.kind else {
        loader.error(
            nodes.pos,
            format!(
                "'nodes' must be a map {{\"id\": (type: ..)}}, found {}",
                nodes.kind.describe()
            ),
        );
        return;
    };
    for (key, body) in entries {
        let Some(id) = key.as_str() else {
            loader.error(
                key.pos,
                format!("node ids are strings, found {}", key.kind.describe()),
            );
            continue;
        };
        if !load_node(loader, id, body, graph) {
            failed.push(id.to_string());
        }
    }
}

/// Loads one node; returns false when it could not be created.
fn load_node(loader: &mut Loader<'_>, id: &str, body: &Node, graph: &mut Graph) -> bool {
    let Kind::Struct(_, fields) = &body.kind else {
        loader.error(
            body.pos,
            format!(
                "node '{id}' must be a struct (type: \"..\", ..), found {}",
                body.kind.describe()
            ),
        );
        return false;
    };
    let get = |name: &str| fields.iter().find(|(f, _)| f.name == name).map(|(_, v)| v);
    let is_cluster = get("type").and_then(Node::as_str) == Some(CLUSTER_TYPE);
    for (f, _) in fields {
        let known = [
            "type", "name", "position", "inputs", "preview", "enabled", "color",
        ]
        .contains(&f.name.as_str())
            || (is_cluster && ["source", "graph"].contains(&f.name.as_str()));
        if !known {
            let extra = if is_cluster { ", source, graph" } else { "" };
            loader.error(f.pos, format!("node '{id}': unknown field '{}'; expected type, name, position, inputs, preview, enabled, color{extra}", f.name));
        }
    }
    let Some(type_node) = get("type") else {
        loader.error(body.pos, format!("node '{id}' has no 'type'"));
        return false;
    };
    let Some(type_id) = type_node.as_str() else {
        loader.error(
            type_node.pos,
            format!("node '{id}': 'type' must be a string"),
        );
        return false;
    };
    let added = if type_id == CLUSTER_TYPE {
        match load_cluster(
            loader,
            id,
            body,
            graph.registry().clone(),
            get("source"),
            get("graph"),
        ) {
            Some(cluster) => graph.add_node_with_def(id, Arc::new(cluster.node_def())),
            None => return false,
        }
    } else {
        graph.add_node(id, type_id)
    };
    if let Err(e) = added {
        let pos = if matches!(e, GraphError::UnknownType { .. }) {
            type_node.pos
        } else {
            body.pos
        };
        loader.error(pos, format!("node '{id}': {e}"));
        return false;
    }
    if let Some(p) = get("position") {
        match p
            .items()
            .map(|xy| xy.iter().map(Node::as_f64).collect::<Option<Vec<f64>>>())
        {
            Some(Some(xy)) if xy.len() == 2 => {
                let _ = graph.set_position(id, [xy[0] as f32, xy[1] as f32]);
            }
            _ => loader.error(p.pos, format!("node '{id}': 'position' must be (x, y)")),
        }
    }
    for (flag, setter) in [
        (
            "preview",
            Graph::set_preview as fn(&mut Graph, &str, bool) -> _,
        ),
        ("enabled", Graph::set_enabled),
    ] {
        match get(flag).map(|v| &v.kind) {
            None => {}
            Some(Kind::Bool(b)) => {
                let _ = setter(graph, id, *b);
            }
            Some(_) => loader.error(
                get(flag).map_or(body.pos, |v| v.pos),
                format!("node '{id}': '{flag}' must be true or false"),
            ),
        }
    }
    if let Some(c) = get("color") {
        match c.as_str().and_then(parse_color) {
            Some(rgb) => {
                let _ = graph.set_color(id, Some(rgb));
            }
            None => loader.error(
                c.pos,
                format!("node '{id}': 'color' must be a colour \"#rrggbb\""),
            ),
        }
    }
    if let Some(n) = get("name") {
        match n.as_str() {
            Some(name) => {
                let _ = graph.set_name(id, Some(name.to_string()));
            }
            None => loader.error(n.pos, format!("node '{id}': 'name' must be a string")),
        }
    }
    if let Some(inputs) = get("inputs") {
        load_inputs(loader, id, inputs, graph);
    }
    true
}

/// A node's preview colour as written in graph files: `"#rrggbb"` (hexadecimal sRGB).
pub fn parse_color(text: &str) -> Option<[u8; 3]> {
    let hex = text.trim().strip_prefix('#')?;
    if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let byte = |k: usize| u8::from_str_radix(&hex[k..k + 2], 16).ok();
    Some([byte(0)?, byte(2)?, byte(4)?])
}

/// A node's preview colour in the form graph files use: `#rrggbb`.
pub fn format_color([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn load_inputs(loader: &mut Loader<'_>, id: &str, inputs: &Node, graph: &mut Graph) {
    let Kind::Map(entries) = &inputs.kind else {
        loader.error(
            inputs.pos,
            format!("node '{id}': 'inputs' must be a map {{\"name\": value}}"),
        );
        return;
    };
    let Some(def) = graph.node(id).map(|n| n.def.clone()) else {
        return;
    };
    for (key, value) in entries {
        let Some(name) = key.as_str() else {
            loader.error(key.pos, format!("node '{id}': input names are strings"));
            continue;
        };
        let Some(k) = def.input_index(name) else {
            loader.error(
                key.pos,
                format!(
                    "node '{id}' ({}) has no input '{name}'; its inputs are: {}",
                    def.id,
                    def.input_names()
                ),
            );
            continue;
        };
        match literal::decode(value, &def.inputs[k].ty) {
            Ok(v) => {
                if let Err(e) = graph.set_value(id, name, v) {
                    loader.error(value.pos, e.to_string());
                }
            }
            Err(e) => loader.literal(
                e,
                &format!("input '{id}.{name}' ({})", def.inputs[k].type_name()),
            ),
        }
    }
}

/// Parses `"from.output -> to.input"`.
pub fn parse_edge(text: &str) -> Option<WireRef> {
    let (from, to) = text.split_once("->")?;
    let (from, output) = from.trim().split_once('.')?;
    let (to, input) = to.trim().split_once('.')?;
    let ok = |s: &str| !s.is_empty() && !s.contains(char::is_whitespace);
    [from, output, to, input]
        .iter()
        .all(|s| ok(s))
        .then(|| WireRef {
            from: from.to_string(),
            output: output.to_string(),
            to: to.to_string(),
            input: input.to_string(),
        })
}

fn load_edges(loader: &mut Loader<'_>, edges: &Node, graph: &mut Graph, failed: &[String]) {
    let Kind::List(items) = &edges.kind else {
        loader.error(
            edges.pos,
            format!(
                "'edges' must be a list of \"from.output -> to.input\", found {}",
                edges.kind.describe()
            ),
        );
        return;
    };
    for item in items {
        let Some(text) = item.as_str() else {
            loader.error(
                item.pos,
                format!(
                    "an edge is a string \"from.output -> to.input\", found {}",
                    item.kind.describe()
                ),
            );
            continue;
        };
        let Some(w) = parse_edge(text) else {
            loader.error(
                item.pos,
                format!("malformed edge '{text}'; expected \"from.output -> to.input\""),
            );
            continue;
        };
        if failed.contains(&w.from) || failed.contains(&w.to) {
            continue;
        }
        if let Err(e) = graph.connect(&w.from, &w.output, &w.to, &w.input) {
            let message = match e {
                GraphError::UnknownNode(n) => format!("dangling edge '{text}': no node '{n}'"),
                other => format!("edge '{text}': {other}"),
            };
            loader.error(item.pos, message);
        }
    }
}
