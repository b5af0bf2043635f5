//! The cells of a list editor window: a header of column names, a column of row numbers (click
//! to select rows), and the cells in a monospace font, every number in full, columns as wide as
//! their widest text. Only the rows in view are drawn (a list of 10 000 points scrolls smoothly).
//! Clicking a cell selects it (where pasted text goes) and, unless the table is read-only, edits
//! it in a text field: Enter or a click elsewhere commits, Esc cancels.

use std::collections::BTreeSet;

use egui::text::{CCursor, CCursorRange};
use egui::{Align2, FontId, Rect, Sense, Stroke, TextStyle, Ui, Vec2, vec2};

use cnets_engine::Value;

use super::table::{Cell, Table};

/// A cell being typed in.
#[derive(Clone, Debug)]
pub struct Editing {
    /// Row.
    pub row: usize,
    /// Column.
    pub col: usize,
    /// The text typed so far.
    pub text: String,
    /// Focus the field (and select its text) on the next frame it is drawn.
    pub focus: bool,
}

/// What the grid remembers between frames.
#[derive(Default)]
pub struct GridState {
    /// Selected rows (click a row number).
    pub rows: BTreeSet<usize>,
    /// The selected cell: where pasted text goes.
    pub cell: Option<(usize, usize)>,
    /// The cell being typed in.
    pub editing: Option<Editing>,
    /// Column widths in characters, for the value they were measured on.
    widths: Option<(Value, Vec<usize>, usize)>,
}

/// A cell typed in: commit `text` to (row, col).
#[derive(Clone, Debug, PartialEq)]
pub struct Commit {
    /// Row.
    pub row: usize,
    /// Column.
    pub col: usize,
    /// The text typed.
    pub text: String,
}

impl GridState {
    /// Forgets selections beyond the table (after undo, a removal, another value).
    pub fn clamp(&mut self, table: &Table) {
        let n = table.len();
        self.rows.retain(|&r| r < n);
        if self.cell.is_some_and(|(r, c)| table.text(r, c).is_none()) {
            self.cell = None;
        }
    }

    /// Column widths (in characters) of the value's cells, and of its row numbers.
    fn widths(&mut self, table: &Table, value: &Value) -> (Vec<usize>, usize) {
        if let Some((v, w, h)) = &self.widths
            && v.same_as(value)
        {
            return (w.clone(), *h);
        }
        let mut widths: Vec<usize> = (0..table.width())
            .map(|c| table.column_name(c).chars().count())
            .collect();
        for row in table.rows() {
            for (c, w) in widths.iter_mut().enumerate() {
                if let Some(cell) = row.cell(c) {
                    *w = (*w).max(cell.text().chars().count().min(MAX_CELL_CHARS));
                }
            }
        }
        let header = table.len().saturating_sub(1).to_string().len().max(1);
        self.widths = Some((value.clone(), widths.clone(), header));
        (widths, header)
    }
}

/// The widest a column gets, in characters (longer texts scroll inside the cell's field).
const MAX_CELL_CHARS: usize = 40;

/// Shows the grid of `table` (the value `value`); returns the cells committed this frame.
/// `id` keeps the scroll position and the text field of this window apart from others'.
pub fn show(
    ui: &mut Ui,
    id: egui::Id,
    table: &Table,
    value: &Value,
    state: &mut GridState,
    read_only: bool,
) -> Vec<Commit> {
    let mut commits = Vec::new();
    let font = TextStyle::Monospace.resolve(ui.style());
    let char_w = ui.fonts_mut(|f| f.glyph_width(&font, '0'));
    let row_h = ui.fonts_mut(|f| f.row_height(&font)) + 6.0;
    let (chars, header_chars) = state.widths(table, value);
    let widths: Vec<f32> = chars
        .iter()
        .map(|&n| (n.max(3) as f32 * char_w + 14.0).max(44.0))
        .collect();
    let header_w = header_chars.max(2) as f32 * char_w + 14.0;
    let visuals = ui.visuals().clone();
    let line = Stroke::new(
        1.0,
        visuals
            .widgets
            .noninteractive
            .bg_stroke
            .color
            .gamma_multiply(0.7),
    );
    let edit_id = id.with("cell-edit");
    let mut editing_drawn = false;
    egui::ScrollArea::horizontal()
        .id_salt(id.with("h"))
        .auto_shrink([false, true])
        .show(ui, |ui| {
            ui.spacing_mut().item_spacing = Vec2::ZERO;
            ui.vertical(|ui| {
                ui.horizontal(|ui| {
                    let (rect, _) = ui.allocate_exact_size(vec2(header_w, row_h), Sense::hover());
                    ui.painter().text(
                        rect.center(),
                        Align2::CENTER_CENTER,
                        "#",
                        font.clone(),
                        visuals.weak_text_color(),
                    );
                    for (c, w) in widths.iter().enumerate() {
                        let (rect, _) = ui.allocate_exact_size(vec2(*w, row_h), Sense::hover());
                        ui.painter().rect_filled(rect, 0.0, visuals.faint_bg_color);
                        ui.painter().text(
                            rect.center(),
                            Align2::CENTER_CENTER,
                            table.column_name(c),
                            font.clone(),
                            visuals.strong_text_color(),
                        );
                    }
                });
                egui::ScrollArea::vertical()
                    .id_salt(id.with("v"))
                    .auto_shrink([true, false])
                    .show_rows(ui, row_h, table.len(), |ui, range| {
                        for r in range {
                            ui.horizontal(|ui| {
                                row_number(ui, id, table, state, r, [header_w, row_h], &font);
                                for (c, w) in widths.iter().enumerate() {
                                    let rect =
                                        ui.allocate_exact_size(vec2(*w, row_h), Sense::hover()).0;
                                    let editing_here = state
                                        .editing
                                        .as_ref()
                                        .is_some_and(|e| (e.row, e.col) == (r, c));
                                    if editing_here {
                                        editing_drawn = true;
                                        if let Some(commit) = edit_cell(ui, rect, edit_id, state) {
                                            commits.push(commit);
                                        }
                                        continue;
                                    }
                                    let clicked =
                                        cell(ui, id, rect, table, state, (r, c), &font, line);
                                    if clicked {
                                        state.cell = Some((r, c));
                                        if !read_only {
                                            if let Some(e) = state.editing.take() {
                                                commits.push(Commit {
                                                    row: e.row,
                                                    col: e.col,
                                                    text: e.text,
                                                });
                                            }
                                            // Its field is drawn from the next frame on.
                                            editing_drawn = true;
                                            state.editing = Some(Editing {
                                                row: r,
                                                col: c,
                                                text: table.text(r, c).unwrap_or_default(),
                                                focus: true,
                                            });
                                        }
                                    }
                                }
                            });
                        }
                    });
            });
        });
    // A cell scrolled out of view while typed in is committed (its field is gone).
    if !editing_drawn && let Some(e) = state.editing.take() {
        commits.push(Commit {
            row: e.row,
            col: e.col,
            text: e.text,
        });
    }
    commits
}

/// The row number: click to select or deselect the row.
fn row_number(
    ui: &mut Ui,
    id: egui::Id,
    table: &Table,
    state: &mut GridState,
    r: usize,
    [width, height]: [f32; 2],
    font: &FontId,
) {
    let rect = ui
        .allocate_exact_size(vec2(width, height), Sense::hover())
        .0;
    let resp = ui.interact(rect, id.with(("row", r)), Sense::click());
    let selected = state.rows.contains(&r);
    let visuals = ui.visuals();
    let fill = if selected {
        visuals.selection.bg_fill
    } else if resp.hovered() {
        visuals.widgets.hovered.weak_bg_fill
    } else {
        visuals.faint_bg_color
    };
    ui.painter().rect_filled(rect, 0.0, fill);
    let color = if selected {
        visuals.selection.stroke.color
    } else {
        visuals.weak_text_color()
    };
    ui.painter().text(
        rect.center(),
        Align2::CENTER_CENTER,
        r.to_string(),
        font.clone(),
        color,
    );
    resp.widget_info(|| {
        let mut info = egui::WidgetInfo::selected(
            egui::WidgetType::Checkbox,
            true,
            selected,
            format!("row {r}"),
        );
        info.label = Some(format!("select row {r}"));
        info
    });
    let resp = resp.on_hover_text(format!(
        "row {r} of {}: click to select or deselect it (Remove rows, Copy)",
        table.len()
    ));
    if resp.clicked() && !state.rows.remove(&r) {
        state.rows.insert(r);
    }
}

/// One cell (not being typed in); returns whether it was clicked. Rows shorter than the table
/// leave their extra cells shaded and empty.
#[allow(clippy::too_many_arguments)]
fn cell(
    ui: &mut Ui,
    id: egui::Id,
    rect: Rect,
    table: &Table,
    state: &GridState,
    (r, c): (usize, usize),
    font: &FontId,
    line: Stroke,
) -> bool {
    let visuals = ui.visuals().clone();
    let Some(cell) = table.rows().get(r).and_then(|row| row.cell(c)) else {
        ui.painter()
            .rect_filled(rect, 0.0, visuals.extreme_bg_color.gamma_multiply(0.5));
        return false;
    };
    let resp = ui.interact(rect, id.with(("cell", r, c)), Sense::click());
    let row_selected = state.rows.contains(&r);
    if row_selected {
        ui.painter()
            .rect_filled(rect, 0.0, visuals.selection.bg_fill.gamma_multiply(0.45));
    } else if resp.hovered() {
        ui.painter()
            .rect_filled(rect, 0.0, visuals.widgets.hovered.weak_bg_fill);
    }
    ui.painter()
        .rect_stroke(rect, 0.0, line, egui::StrokeKind::Inside);
    if state.cell == Some((r, c)) {
        ui.painter().rect_stroke(
            rect.shrink(1.0),
            0.0,
            Stroke::new(1.5, visuals.selection.stroke.color),
            egui::StrokeKind::Inside,
        );
    }
    let text = cell.text();
    let (shown, color) = match &cell {
        Cell::Null => ("none".to_string(), visuals.weak_text_color()),
        _ => (clip(&text), visuals.text_color()),
    };
    let (anchor, at) = match cell {
        Cell::Text(_) | Cell::Null => (Align2::LEFT_CENTER, rect.left_center() + vec2(6.0, 0.0)),
        _ => (Align2::RIGHT_CENTER, rect.right_center() - vec2(6.0, 0.0)),
    };
    ui.painter()
        .with_clip_rect(rect.intersect(ui.clip_rect()))
        .text(at, anchor, shown, font.clone(), color);
    let name = table.cell_name(r, c);
    resp.widget_info(|| {
        let mut info = egui::WidgetInfo::labeled(egui::WidgetType::Button, true, name.clone());
        info.current_text_value = Some(text.clone());
        info
    });
    resp.on_hover_text(format!("{name}: {text}")).clicked()
}

/// A text shown in a cell: texts longer than a column gets are cut with `…` (numbers never are:
/// their columns are as wide as their full text).
fn clip(text: &str) -> String {
    if text.chars().count() <= MAX_CELL_CHARS {
        return text.replace(['\n', '\t'], " ");
    }
    let mut s: String = text.chars().take(MAX_CELL_CHARS - 1).collect();
    s.push('…');
    s.replace(['\n', '\t'], " ")
}

/// The text field of the cell being typed in; returns the commit when it loses the focus
/// (Enter, Tab, a click elsewhere), nothing when Esc cancels.
fn edit_cell(ui: &mut Ui, rect: Rect, id: egui::Id, state: &mut GridState) -> Option<Commit> {
    let editing = state.editing.as_mut()?;
    if editing.focus {
        // Focused before it is drawn: an unfocused field collapses its selection.
        ui.memory_mut(|m| m.request_focus(id));
        let mut s = egui::text_edit::TextEditState::load(ui.ctx(), id).unwrap_or_default();
        let end = editing.text.chars().count();
        s.cursor
            .set_char_range(Some(CCursorRange::two(CCursor::new(0), CCursor::new(end))));
        s.store(ui.ctx(), id);
    }
    let resp = ui.put(
        rect,
        egui::TextEdit::singleline(&mut editing.text)
            .id(id)
            .font(TextStyle::Monospace)
            .margin(vec2(4.0, 2.0))
            .desired_width(rect.width())
            .background_color(ui.visuals().extreme_bg_color),
    );
    if std::mem::take(&mut editing.focus) {
        return None;
    }
    if resp.lost_focus() {
        let e = state.editing.take()?;
        if ui.input(|i| i.key_pressed(egui::Key::Escape)) {
            return None;
        }
        return Some(Commit {
            row: e.row,
            col: e.col,
            text: e.text,
        });
    }
    None
}
