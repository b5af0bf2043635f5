//! The node palette: every registered node type by category, filtered by a search text. Opened
//! from the menu (Add node) or by double-clicking the canvas, as in Grasshopper, at the point
//! clicked; picking an entry adds that node there. Entries read as a designer names them
//! ("Number slider", "CNets Construct", "Graph mapper") with the node id after; the paper's
//! components share one category.

use std::sync::Arc;

use cnets_engine::{NodeDef, Registry};

/// The category the paper's components are listed under (the node library files them as
/// "Cone-nets" and "CNets").
pub const PAPER_CATEGORY: &str = "CNets (the paper's components)";

/// Names designers use for node types, where the id alone does not say it.
const NAMES: &[(&str, &str)] = &[
    ("param.number", "Number slider"),
    ("param.integer", "Integer slider"),
    ("param.boolean", "Boolean toggle"),
    ("param.choice", "Value list"),
    ("param.text", "Text"),
    ("param.list", "List of numbers"),
    ("param.point", "Point"),
    ("param.vector", "Vector"),
    ("param.range", "Range"),
    ("param.series", "Series"),
    ("mapper.graph", "Graph mapper"),
    ("view.panel", "Panel"),
    ("cnets.construct", "CNets Construct"),
    ("cnets.construct_coplanar", "CNets Construct Coplanar"),
    ("cnets.encode", "CNets Encode"),
    ("cnets.graph_to_apex", "Graph to apex function"),
    ("cnets.conical_support", "Conical support layer"),
    ("cnets.torsion_free_axes", "Torsion-free node axes"),
    ("cnets.cone_check", "Cone check"),
    ("ctube.construct", "C-tube Construct"),
    ("pq.extract_strips", "Extract strips"),
    ("pq.unroll_strips", "Unroll strips"),
    ("pq.parallel_support", "Parallel support layer"),
    ("pq.parallel_transform", "Parallel transform"),
    ("mesh.planarity", "Planarity"),
    ("math.expression", "Expression"),
];

/// The name a designer reads for a node type: from the table above, else the id's last part
/// with spaces (`curve.closest_point` → "Closest point").
pub fn display_name(def: &NodeDef) -> String {
    if let Some((_, name)) = NAMES.iter().find(|(id, _)| *id == def.id) {
        return (*name).to_string();
    }
    let last = def
        .id
        .rsplit('.')
        .next()
        .unwrap_or(&def.id)
        .replace('_', " ");
    let mut chars = last.chars();
    match chars.next() {
        Some(c) => c.to_uppercase().chain(chars).collect(),
        None => def.id.to_string(),
    }
}

/// The category a node type is listed under (the paper's components under one).
pub fn display_category(def: &NodeDef) -> String {
    match def.category.as_ref() {
        "Cone-nets" | "CNets" => PAPER_CATEGORY.to_string(),
        other => other.to_string(),
    }
}

/// Node types whose name, id, category or doc match `query` (every word must match,
/// case-insensitive), grouped by category in registry order. Within a category, names that
/// start with the query's first word come first, then names or ids containing it.
pub fn search(registry: &Registry, query: &str) -> Vec<(String, Vec<Arc<NodeDef>>)> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    let mut groups: Vec<(String, Vec<Arc<NodeDef>>)> = Vec::new();
    for def in registry.iter() {
        let category = display_category(def);
        let haystack = format!(
            "{} {} {} {} {}",
            display_name(def),
            def.id,
            category,
            def.category,
            def.doc
        )
        .to_lowercase();
        if !words.iter().all(|w| haystack.contains(w.as_str())) {
            continue;
        }
        match groups.iter_mut().find(|(c, _)| *c == category) {
            Some((_, defs)) => defs.push(def.clone()),
            None => groups.push((category, vec![def.clone()])),
        }
    }
    if let Some(first) = words.first() {
        for (_, defs) in &mut groups {
            defs.sort_by_key(|d| {
                let name = display_name(d).to_lowercase();
                if name.starts_with(first.as_str()) {
                    0
                } else if name.contains(first.as_str())
                    || d.id.to_lowercase().contains(first.as_str())
                {
                    1
                } else {
                    2
                }
            });
        }
    }
    groups
}

/// Library graphs whose name, file or doc match `query` (every word, case-insensitive).
pub fn search_library<'a>(
    entries: &'a [crate::library::LibraryEntry],
    query: &str,
) -> Vec<&'a crate::library::LibraryEntry> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    entries
        .iter()
        .filter(|e| {
            let haystack =
                format!("library cluster {} {} {}", e.name, e.source, e.doc).to_lowercase();
            words.iter().all(|w| haystack.contains(w.as_str()))
        })
        .collect()
}

/// What was picked in the palette.
#[derive(Clone, Debug, PartialEq)]
pub enum Pick {
    /// A registered node type.
    Type(String),
    /// A library graph, inserted as a cluster node.
    Library(crate::library::LibraryEntry),
}

/// The palette window's state.
#[derive(Clone, Debug, Default)]
pub struct PaletteState {
    /// Whether the palette is shown.
    pub open: bool,
    /// The search text.
    pub query: String,
    /// Canvas position where a picked node goes.
    pub at: [f32; 2],
    /// Focus the search field on the next frame.
    pub focus: bool,
    /// Screen point the window opens at (the click), taken on its first frame.
    pub place: Option<egui::Pos2>,
}

impl PaletteState {
    /// Opens the palette for adding a node at canvas position `at`.
    pub fn open_at(&mut self, at: [f32; 2]) {
        self.open = true;
        self.query.clear();
        self.at = at;
        self.focus = true;
    }

    /// Opens the palette at screen point `screen` (the click) for a node at canvas position `at`.
    pub fn open_at_screen(&mut self, at: [f32; 2], screen: egui::Pos2) {
        self.open_at(at);
        self.place = Some(screen);
    }
}

/// Shows the palette window (registered types by category, then the "Library" category); returns
/// what was picked, if anything.
pub fn show(
    ctx: &egui::Context,
    state: &mut PaletteState,
    registry: &Registry,
    library: &[crate::library::LibraryEntry],
) -> Option<Pick> {
    if !state.open {
        return None;
    }
    let mut picked = None;
    let mut open = state.open;
    let mut window = egui::Window::new("Add node")
        .id(egui::Id::new("cnets-palette"))
        .open(&mut open)
        .collapsible(false)
        .resizable(true)
        .default_width(320.0)
        .default_height(420.0)
        .constrain(true);
    window = match state.place.take() {
        // At the click (kept inside the window by `constrain`), movable afterwards.
        Some(p) => window.current_pos(p),
        None => window.default_pos(ctx.content_rect().center() - egui::vec2(160.0, 210.0)),
    };
    window.show(ctx, |ui| {
        let edit = ui.add(
            egui::TextEdit::singleline(&mut state.query)
                .hint_text("search nodes…")
                .desired_width(f32::INFINITY),
        );
        if state.focus {
            edit.request_focus();
            state.focus = false;
        }
        let groups = search(registry, &state.query);
        let graphs = search_library(library, &state.query);
        let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if enter {
            if let Some(def) = groups.first().and_then(|(_, d)| d.first()) {
                picked = Some(Pick::Type(def.id.to_string()));
            } else if let Some(e) = graphs.first() {
                picked = Some(Pick::Library((*e).clone()));
            }
        }
        ui.separator();
        egui::ScrollArea::vertical().show(ui, |ui| {
            if groups.is_empty() && graphs.is_empty() {
                ui.weak("no node matches");
            }
            for (category, defs) in &groups {
                ui.strong(category);
                for def in defs {
                    let mut job = egui::text::LayoutJob::default();
                    job.append(
                        &display_name(def),
                        0.0,
                        egui::TextFormat::simple(
                            egui::TextStyle::Button.resolve(ui.style()),
                            ui.visuals().strong_text_color(),
                        ),
                    );
                    job.append(
                        &format!("  {}", def.id),
                        0.0,
                        egui::TextFormat::simple(
                            egui::TextStyle::Small.resolve(ui.style()),
                            ui.visuals().weak_text_color(),
                        ),
                    );
                    let r = ui
                        .selectable_label(false, job)
                        .on_hover_text(def.doc.as_ref());
                    if r.clicked() {
                        picked = Some(Pick::Type(def.id.to_string()));
                    }
                }
                ui.add_space(4.0);
            }
            if !graphs.is_empty() {
                ui.strong("Library");
                for e in graphs {
                    let r = ui
                        .selectable_label(false, format!("{} (cluster)", e.name))
                        .on_hover_text(format!(
                            "{}\n{}\ninputs: {}\noutputs: {}",
                            e.path.display(),
                            e.doc,
                            e.ports.0.join(", "),
                            e.ports.1.join(", ")
                        ));
                    if r.clicked() {
                        picked = Some(Pick::Library(e.clone()));
                    }
                }
            }
        });
    });
    state.open = open && picked.is_none();
    if ui_escape(ctx) {
        state.open = false;
    }
    picked
}

fn ui_escape(ctx: &egui::Context) -> bool {
    ctx.input(|i| i.key_pressed(egui::Key::Escape))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn search_filters_and_groups() {
        let registry = cnets_nodes::registry();
        let all = search(&registry, "");
        let total: usize = all.iter().map(|(_, d)| d.len()).sum();
        assert_eq!(total, registry.len());
        let arcs = search(&registry, "ARC");
        assert!(
            arcs.iter()
                .any(|(c, d)| c == "Curves" && d[0].id == "curve.arc")
        );
        // Human names, and one category for the paper's components.
        let slider = search(&registry, "number slider");
        assert_eq!(slider[0].1[0].id, "param.number", "{slider:?}");
        assert_eq!(display_name(&slider[0].1[0]), "Number slider");
        let paper: Vec<&str> = all
            .iter()
            .filter(|(c, _)| c == PAPER_CATEGORY)
            .flat_map(|(_, d)| d.iter().map(|d| d.id.as_ref()))
            .collect();
        assert!(paper.contains(&"cnets.construct") && paper.contains(&"cnets.graph_to_apex"));
        assert!(!all.iter().any(|(c, _)| c == "Cone-nets" || c == "CNets"));
        let names: Vec<String> = all
            .iter()
            .flat_map(|(_, d)| d.iter().map(|d| display_name(d)))
            .collect();
        assert!(
            names.contains(&"Closest point".to_string()),
            "fallback from the id"
        );
        let none = search(&registry, "no-such-node-xyz");
        assert!(none.is_empty());
        let two = search(&registry, "cone construct");
        let found: Vec<_> = two.iter().flat_map(|(_, d)| d).collect();
        assert!(found.iter().any(|d| d.id == "cnets.construct"));
        for d in &found {
            let text = format!("{} {} {}", d.id, d.category, d.doc).to_lowercase();
            assert!(
                text.contains("cone") && text.contains("construct"),
                "{} matches every word",
                d.id
            );
        }
        assert!(found.len() < registry.len());
    }
}
