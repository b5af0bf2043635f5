//! The node palette: every registered node type by category, filtered by a search text. Opened
//! from the menu (Add node) or by double-clicking the canvas, as in Grasshopper; picking an entry
//! adds that node where the palette was opened.

use std::sync::Arc;

use cnets_engine::{NodeDef, Registry};

/// Node types whose id, category or doc match `query` (every word must match, case-insensitive),
/// grouped by category in registry order. Ids that start with the query come first within a
/// category.
pub fn search(registry: &Registry, query: &str) -> Vec<(String, Vec<Arc<NodeDef>>)> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    let mut groups: Vec<(String, Vec<Arc<NodeDef>>)> = Vec::new();
    for def in registry.iter() {
        let haystack = format!("{} {} {}", def.id, def.category, def.doc).to_lowercase();
        if !words.iter().all(|w| haystack.contains(w.as_str())) {
            continue;
        }
        match groups.iter_mut().find(|(c, _)| *c == def.category) {
            Some((_, defs)) => defs.push(def.clone()),
            None => groups.push((def.category.to_string(), vec![def.clone()])),
        }
    }
    if let Some(first) = words.first() {
        for (_, defs) in &mut groups {
            defs.sort_by_key(|d| !d.id.to_lowercase().contains(first.as_str()));
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
}

impl PaletteState {
    /// Opens the palette for adding a node at canvas position `at`.
    pub fn open_at(&mut self, at: [f32; 2]) {
        self.open = true;
        self.query.clear();
        self.at = at;
        self.focus = true;
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
    egui::Window::new("Add node")
        .id(egui::Id::new("cnets-palette"))
        .open(&mut open)
        .collapsible(false)
        .resizable(true)
        .default_width(320.0)
        .default_height(420.0)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
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
                        let r = ui
                            .selectable_label(false, def.id.as_ref())
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
