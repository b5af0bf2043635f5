//! The node palette: every registered node type by category, or, once the designer types, the best
//! matches ranked ([`search`]; Enter adds the top hit). Opened from the menu (Add node) or by
//! double-clicking the canvas, as in Grasshopper, at the point clicked; picking an entry adds that
//! node there. Entries read as a designer names them
//! ("Number slider", "CNets Construct", "Graph mapper") with the node id after; the paper's
//! components share one category.

use cnets_engine::Registry;

mod names;
mod search;

pub use names::{PAPER_CATEGORY, display_category, display_name};
pub use search::{Ranked, rank, search, search_library};

/// What was picked in the palette.
#[derive(Clone, Debug, PartialEq)]
pub enum Pick {
    /// A registered node type.
    Type(String),
    /// A library graph, inserted as a cluster node.
    Library(cnets_host::LibraryEntry),
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
    library: &[cnets_host::LibraryEntry],
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
        let ranked = rank(registry, &state.query);
        // With no query, every node type by category; with one, the best matches first.
        let groups = if state.query.trim().is_empty() {
            search(registry, "")
        } else {
            vec![(
                "Best matches".to_string(),
                ranked.iter().map(|r| r.def.clone()).collect(),
            )]
        };
        let graphs = search_library(library, &state.query);
        let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if enter {
            if let Some(r) = ranked.first() {
                picked = Some(Pick::Type(r.def.id.to_string()));
            } else if let Some(e) = graphs.first() {
                picked = Some(Pick::Library((*e).clone()));
            }
        }
        ui.separator();
        egui::ScrollArea::vertical().show(ui, |ui| {
            if groups.iter().all(|(_, d)| d.is_empty()) && graphs.is_empty() {
                ui.weak("no node matches");
            }
            for (category, defs) in groups.iter().filter(|(_, d)| !d.is_empty()) {
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
                    crate::probe::record(ui.ctx(), &display_name(def), r.rect);
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
