//! One list editor window: the table of one input's literal list with its tools — Add row,
//! Remove rows, Copy as TSV, where Ctrl+V pastes (at the selected cell or replacing all rows) —
//! and a line saying what the last action did or why it was refused. It always shows the
//! document's current value (so it follows undo and redo); a wired input is shown read-only.

use cnets_engine::{NodeInstance, Value};
use egui::{Color32, Ui};

use super::errors::NotATable;
use super::grid::{self, GridState};
use super::summary::count;
use super::table::Table;
use super::{EditorKey, PART_ITEMS, item_type, parts, summary, tsv};
use crate::widgets;

/// Where Ctrl+V puts pasted text.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PasteMode {
    /// Into the cells from the selected cell on, right and down (rows added past the end).
    #[default]
    AtCell,
    /// In place of every row.
    ReplaceAll,
}

/// What the window's last action did, or why it was refused.
#[derive(Clone, Debug)]
struct Note {
    text: String,
    error: bool,
}

/// What the designer asked of the window this frame.
#[derive(Clone, Debug)]
pub enum Request {
    /// Text pasted (Ctrl+V) while the window was active.
    Paste(String),
    /// Copy (Ctrl+C) while the window was active: the selected rows, else all.
    Copy,
    /// Delete while the window was active and rows were selected: remove them.
    RemoveSelected,
}

/// The state of one window.
pub struct EditorWindow {
    /// Which input it edits.
    pub key: EditorKey,
    /// Selection and the cell being typed in.
    pub grid: GridState,
    /// Where Ctrl+V pastes.
    pub paste_mode: PasteMode,
    note: Option<Note>,
    /// Where to open it (screen), the first time it is shown.
    pub open_at: Option<egui::Pos2>,
    /// The part shown of a list edited a part at a time ([`super::parts`]).
    part: usize,
    /// Bring it to the front on the next frame.
    pub raise: bool,
}

/// What one frame of a window produced.
pub struct Shown {
    /// The new value of the input and what changed, in words (one undo step).
    pub value: Option<(Value, String)>,
    /// The designer closed the window.
    pub closed: bool,
    /// The window's layer (for clicks and the active window).
    pub layer: Option<egui::LayerId>,
}

impl EditorWindow {
    /// A window for `key`, opened at `at` (screen).
    pub fn new(key: EditorKey, at: Option<egui::Pos2>) -> Self {
        Self {
            key,
            grid: GridState::default(),
            paste_mode: PasteMode::default(),
            note: None,
            open_at: at,
            part: 0,
            raise: true,
        }
    }

    /// The window's id (its layer is `LayerId::new(Order::Middle, id)`).
    pub fn id(&self) -> egui::Id {
        egui::Id::new((
            "cnets-list-editor",
            &self.key.view,
            &self.key.node,
            &self.key.input,
        ))
    }

    /// Whether a cell is being typed in (its text field takes pasted text without tabs or line
    /// breaks, and Ctrl+C copies its selected text).
    pub fn typing(&self) -> bool {
        self.grid.editing.is_some()
    }

    /// Notes what happened (shown under the table).
    pub fn note(&mut self, text: impl Into<String>, error: bool) {
        self.note = Some(Note {
            text: text.into(),
            error,
        });
    }

    /// Shows the window for input `k` of `node` (`wired`: read-only) and carries out the
    /// `requests` routed to it.
    pub fn show(
        &mut self,
        ctx: &egui::Context,
        node: &NodeInstance,
        k: usize,
        wired: bool,
        requests: Vec<Request>,
    ) -> Shown {
        let id = self.id();
        let layer = egui::LayerId::new(egui::Order::Middle, id);
        if std::mem::take(&mut self.raise) {
            ctx.move_to_top(layer);
        }
        // Escape closes the topmost list window, unless it ends a cell's edit (a cell was being
        // typed in when the frame began: the edit is cancelled, the window stays).
        let escape = ctx.input(|i| i.key_pressed(egui::Key::Escape))
            && self.grid.editing.is_none()
            && ctx.memory(|m| m.areas().top_layer_id(egui::Order::Middle)) == Some(layer);
        let current = widgets::effective_value(node, k);
        let items = item_type(node, k);
        let parts = current.as_ref().and_then(parts);
        let table = match (parts, current.as_ref().and_then(Value::as_list)) {
            (Some(n), Some(list)) => {
                self.part = self.part.min(n - 1);
                Table::new(Some(&list[self.part]), &PART_ITEMS)
            }
            _ => Table::new(current.as_ref(), &items),
        };
        // Sized to the table at first (up to a screenful): 21 points a row, about 64 a column.
        let (rows, columns) = table.as_ref().map_or((0, 1), |t| (t.len(), t.width()));
        let size = [
            (70.0 + 64.0 * columns as f32).clamp(380.0, 720.0),
            (180.0 + 21.0 * (rows + 1) as f32).clamp(240.0, 520.0),
        ];
        let mut open = true;
        let mut window = egui::Window::new(format!("{} · {}", self.key.node, self.key.input))
            .id(id)
            .open(&mut open)
            .collapsible(false)
            .resizable(true)
            .default_size(size);
        if let Some(at) = self.open_at.take() {
            window = window.default_pos(at);
        }
        let mut value = None;
        let response = window.show(ctx, |ui| {
            if let (Some(n), Some(list)) = (parts, current.as_ref().and_then(Value::as_list)) {
                self.part_picker(ui, list, n);
            }
            value = self.body(ui, node, k, (current.as_ref(), table), wired, requests);
            // A part edited: the list with that part replaced, every other part as it was.
            if let (Some(_), Some(list)) = (parts, current.as_ref().and_then(Value::as_list))
                && let Some((part, what)) = value.take()
            {
                let mut whole = list.to_vec();
                whole[self.part] = part;
                value = Some((Value::list(whole), format!("part {}: {what}", self.part)));
            }
        });
        Shown {
            value,
            closed: !open || escape,
            layer: response.map(|r| r.response.layer_id),
        }
    }

    fn body(
        &mut self,
        ui: &mut Ui,
        node: &NodeInstance,
        k: usize,
        (current, table): (Option<&Value>, Result<Table, NotATable>),
        wired: bool,
        requests: Vec<Request>,
    ) -> Option<(Value, String)> {
        let port = &node.def.inputs[k];
        ui.horizontal(|ui| {
            ui.weak(port.type_name());
            if let Some(v) = current {
                ui.label(summary::summary(v));
            }
        });
        if wired {
            ui.colored_label(
                WARNING,
                "Connected: this input takes its value from a wire. Its literal is shown \
                 read-only.",
            );
        }
        let table = match table {
            Ok(t) => t,
            Err(e) => {
                ui.label(format!(
                    "This value is not a table of cells or points: {e}."
                ));
                return None;
            }
        };
        let shown_value = table.to_value();
        self.grid.clamp(&table);
        let mut next = table.clone();
        let mut done: Vec<String> = Vec::new();
        ui.horizontal_wrapped(|ui| {
            if !wired {
                self.toolbar(ui, &mut next, &mut done);
            }
            if ui
                .button("Copy as TSV")
                .on_hover_text("copy every row as tab-separated text, numbers in full")
                .clicked()
            {
                ui.ctx().copy_text(table.to_tsv(None));
                self.note(
                    format!(
                        "copied {} as tab-separated text",
                        count(table.len(), ("row", "rows"))
                    ),
                    false,
                );
            }
        });
        if !wired {
            self.paste_choice(ui, &table);
        }
        ui.separator();
        // The note line stays at the bottom; the grid takes the room above it.
        let note_height = ui.text_style_height(&egui::TextStyle::Body) + 6.0;
        let grid_height = (ui.available_height() - note_height).max(60.0);
        let grid_id = self.id().with(self.part);
        let commits = ui
            .allocate_ui(egui::vec2(ui.available_width(), grid_height), |ui| {
                if table.is_empty() {
                    ui.weak("No rows: Add row, or paste rows with Ctrl+V.");
                }
                grid::show(ui, grid_id, &table, &shown_value, &mut self.grid, wired)
            })
            .inner;
        for c in commits {
            match next.set_cell(c.row, c.col, &c.text) {
                Ok(true) => done.push(format!("set {}", next.cell_name(c.row, c.col))),
                Ok(false) => {}
                Err(e) => {
                    self.note(e.to_string(), true);
                    // Back to the field, with the text as typed, to correct it.
                    self.grid.editing = Some(grid::Editing {
                        row: c.row,
                        col: c.col,
                        text: c.text,
                        focus: true,
                    });
                }
            }
        }
        for request in requests {
            self.carry_out(ui, request, &table, &mut next, &mut done, wired);
        }
        match &self.note {
            Some(note) if note.error => {
                ui.colored_label(ERROR, &note.text);
            }
            Some(note) => {
                ui.weak(&note.text);
            }
            None => {
                ui.weak("Click a cell to type in it; click row numbers to select rows.");
            }
        }
        if done.is_empty() {
            return None;
        }
        let value = next.to_value();
        (!value.same_as(&shown_value)).then(|| (value, done.join(", ")))
    }

    /// The parts of a list edited a part at a time: one selectable label each (`polyline 1 · 3
    /// points`); picking another part starts its table afresh (selection, scrolling).
    fn part_picker(&mut self, ui: &mut Ui, list: &[Value], n: usize) {
        ui.horizontal_wrapped(|ui| {
            ui.label("Part:");
            for (k, item) in list.iter().enumerate().take(n) {
                let noun = match item {
                    Value::Polyline(_) => "polyline",
                    _ => "list",
                };
                let text = format!("{noun} {k} · {}", summary::summary(item));
                if ui.selectable_label(self.part == k, text).clicked() && self.part != k {
                    self.part = k;
                    self.grid = GridState::default();
                }
            }
        });
    }

    /// Add row, Remove rows.
    fn toolbar(&mut self, ui: &mut Ui, next: &mut Table, done: &mut Vec<String>) {
        let after = self.grid.rows.last().copied();
        let hint = match after {
            Some(r) => format!("add a row after row {r} (midway to the next row)"),
            None => "add a row at the end (continuing the last step)".to_string(),
        };
        if ui.button("Add row").on_hover_text(hint).clicked() {
            let at = next.add_row(after);
            done.push(format!("added row {at}"));
            self.grid.rows.clear();
            self.grid.rows.insert(at);
        }
        let n = self.grid.rows.len();
        let label = if n == 0 {
            "Remove rows".to_string()
        } else {
            format!("Remove {}", count(n, ("row", "rows")))
        };
        if ui
            .add_enabled(n > 0, egui::Button::new(label))
            .on_hover_text("remove the selected rows (click row numbers to select them)")
            .on_disabled_hover_text("select rows first: click their numbers")
            .clicked()
        {
            let removed = next.remove_rows(&self.grid.rows);
            done.push(format!("removed {}", count(removed, ("row", "rows"))));
            self.grid.rows.clear();
            self.grid.cell = None;
        }
    }

    /// Where Ctrl+V pastes: at the selected cell or replacing all rows.
    fn paste_choice(&mut self, ui: &mut Ui, table: &Table) {
        let (r, c) = self.grid.cell.unwrap_or((0, 0));
        ui.horizontal(|ui| {
            ui.label("Paste (Ctrl+V):").on_hover_text(
                "tab-, semicolon- or comma-separated text, e.g. cells copied from a spreadsheet; \
                 numbers with '.' as the decimal point",
            );
            ui.radio_value(
                &mut self.paste_mode,
                PasteMode::AtCell,
                format!("at {}", table.cell_name(r, c)),
            )
            .on_hover_text("into the cells from the selected cell on (click a cell to choose)");
            ui.radio_value(
                &mut self.paste_mode,
                PasteMode::ReplaceAll,
                "replacing all rows",
            )
            .on_hover_text("the pasted lines become the rows");
        });
    }

    fn carry_out(
        &mut self,
        ui: &Ui,
        request: Request,
        table: &Table,
        next: &mut Table,
        done: &mut Vec<String>,
        wired: bool,
    ) {
        match request {
            Request::Copy => {
                let only = (!self.grid.rows.is_empty()).then_some(&self.grid.rows);
                ui.ctx().copy_text(table.to_tsv(only));
                let n = only.map_or(table.len(), |o| o.len());
                self.note(
                    format!("copied {} as tab-separated text", count(n, ("row", "rows"))),
                    false,
                );
            }
            Request::Paste(_) | Request::RemoveSelected if wired => {
                self.note("read-only: the input is connected by a wire", true);
            }
            Request::Paste(text) => {
                // Block text pasted while a cell was typed in goes into the table at that cell.
                self.grid.editing = None;
                let lines = tsv::parse(&text);
                let (r, c) = self.grid.cell.unwrap_or((0, 0));
                let result = match self.paste_mode {
                    PasteMode::AtCell => next.paste_at(r, c, &lines),
                    PasteMode::ReplaceAll => next.replace_all(&lines),
                };
                match result {
                    Ok(what) => {
                        self.note(what.clone(), false);
                        done.push(what);
                    }
                    Err(e) => self.note(e.to_string(), true),
                }
            }
            Request::RemoveSelected => {
                self.grid.editing = None;
                let removed = next.remove_rows(&self.grid.rows);
                done.push(format!("removed {}", count(removed, ("row", "rows"))));
                self.grid.rows.clear();
                self.grid.cell = None;
            }
        }
    }
}

const ERROR: Color32 = Color32::from_rgb(0xd6, 0x2f, 0x2f);
const WARNING: Color32 = Color32::from_rgb(0xe0, 0x9a, 0x2b);
