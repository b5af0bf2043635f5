//! The view's text overlay: vertex and face counts and the max planarity (top left), the legend
//! (top right) with its clickable fold entry, and the size of what is shown — W × D × H of the
//! previewed geometry's bounding box — in the bottom-right corner.

use cnets_render::Bounds;
use egui::{Color32, Rect, Sense, Ui, vec2};

use crate::preview::{LegendInfo, PreviewStats, paper_class};
use crate::worker::format_number;

const INK: Color32 = Color32::from_gray(30);

fn font() -> egui::FontId {
    egui::FontId::proportional(12.0)
}

/// Paints the counts and the max planarity (naming its mesh when several are previewed) in the
/// top-left corner.
/// Returns the rectangle the text covers.
pub fn paint_stats(ui: &Ui, rect: Rect, s: &PreviewStats) -> Rect {
    let painter = ui.painter_at(rect);
    let mut lines = vec![format!("{} vertices · {} faces", s.vertices, s.faces)];
    if let Some(p) = s.max_planarity {
        // Below 1e-12 the digits are rounding noise (and differ between machines).
        let shown = if p < 1e-12 {
            "< 1e-12".to_string()
        } else {
            format_number(p)
        };
        // With several meshes previewed, the one the figure is for.
        match &s.max_planarity_mesh {
            Some(mesh) => lines.push(format!("max planarity {shown} ({mesh})")),
            None => lines.push(format!("max planarity {shown}")),
        }
    }
    let mut covered = Rect::NOTHING;
    for (k, line) in lines.iter().enumerate() {
        covered = covered.union(painter.text(
            rect.left_top() + vec2(8.0, 6.0 + 16.0 * k as f32),
            egui::Align2::LEFT_TOP,
            line,
            font(),
            INK,
        ));
    }
    covered
}

/// The legend's width from the view's right edge (points).
const LEGEND_WIDTH: f32 = 170.0;

/// The legend as painted: whether its fold entry was clicked, that entry's rectangle, and the
/// legend's lower edge (the view's top when there is no legend).
#[derive(Clone, Copy, Debug)]
pub struct LegendShown {
    /// The fold entry was clicked.
    pub clicked: bool,
    /// Where the fold entry is.
    pub fold_entry: Option<Rect>,
    /// The legend's lower edge.
    pub bottom: f32,
}

/// The legend's fold entry: how many faces are not (++)(++).
pub fn fold_label(folds: usize) -> String {
    format!("⚠ {folds} faces not (++)(++): show")
}

/// Paints the legend in the top-right corner — below the statistics (`stats`, their rectangle)
/// when the view is too narrow for both side by side; with `folds` faces that are not
/// (++)(++), an entry counting them that the designer clicks to frame and outline them.
pub fn legend(ui: &mut Ui, rect: Rect, stats: Rect, s: &PreviewStats, folds: usize) -> LegendShown {
    let painter = ui.painter_at(rect);
    let swatch = |y: f32, color: cnets_render::Color, label: String| {
        let [r, g, b, _] = color.0;
        let x = rect.right() - LEGEND_WIDTH;
        painter.rect_filled(
            Rect::from_min_size(egui::pos2(x, y), vec2(14.0, 12.0)),
            2.0,
            Color32::from_rgb(r, g, b),
        );
        painter.text(
            egui::pos2(x + 20.0, y),
            egui::Align2::LEFT_TOP,
            label,
            font(),
            INK,
        );
    };
    let beside = !stats.is_positive() || stats.right() + 12.0 < rect.right() - LEGEND_WIDTH;
    let top = if beside {
        rect.top() + 8.0
    } else {
        stats.bottom() + 10.0
    };
    let title = |text: &str| {
        painter.text(
            egui::pos2(rect.right() - LEGEND_WIDTH, top),
            egui::Align2::LEFT_TOP,
            text,
            font(),
            INK,
        );
    };
    let rows = match &s.legend {
        LegendInfo::None => 0,
        LegendInfo::Classes(classes) => {
            title("configuration");
            for (k, (class, count)) in classes.iter().enumerate() {
                swatch(
                    top + 18.0 + 16.0 * k as f32,
                    crate::preview::class_color(*class),
                    format!("{}  {}  {count}", paper_class(*class), class.name()),
                );
            }
            classes.len()
        }
        LegendInfo::Planarity(legend) | LegendInfo::Distance(legend) => {
            title(&legend.title);
            for (k, (value, color)) in legend.stops.iter().enumerate().rev() {
                let row = legend.stops.len() - 1 - k;
                let label = legend
                    .labels
                    .get(k)
                    .cloned()
                    .unwrap_or_else(|| format_number(*value));
                swatch(top + 18.0 + 16.0 * row as f32, *color, label);
            }
            legend.stops.len()
        }
    };
    let bottom = if rows == 0 {
        rect.top()
    } else {
        top + 18.0 + 16.0 * rows as f32
    };
    if folds == 0 {
        return LegendShown {
            clicked: false,
            fold_entry: None,
            bottom,
        };
    }
    let y = top + 22.0 + 16.0 * rows as f32;
    let galley = painter.layout_no_wrap(
        fold_label(folds),
        font(),
        Color32::from_rgb(0xb0, 0x3a, 0x0a),
    );
    let entry =
        Rect::from_min_size(egui::pos2(rect.right() - LEGEND_WIDTH, y), galley.size()).expand(2.0);
    let response = ui
        .interact(entry, ui.id().with("fold-entry"), Sense::click())
        .on_hover_text("frame the folded faces and outline them (Esc clears)");
    if response.hovered() {
        painter.rect_filled(
            entry,
            2.0,
            Color32::from_rgba_unmultiplied(255, 220, 180, 200),
        );
    }
    painter.galley(entry.min + vec2(2.0, 2.0), galley, Color32::PLACEHOLDER);
    LegendShown {
        clicked: response.clicked(),
        fold_entry: Some(entry),
        bottom: entry.bottom(),
    }
}

/// `W × D × H` of a box in metres to the millimetre, as the corner shows it.
pub fn dimensions(b: &Bounds) -> String {
    let s = b.size();
    let f = |x: f32| {
        let t = format!("{:.3}", f64::from(x));
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    format!("W {} × D {} × H {} m", f(s.x), f(s.y), f(s.z))
}

/// Paints the size of the previewed geometry in the bottom-right corner.
pub fn paint_dimensions(ui: &Ui, rect: Rect, bounds: Option<&Bounds>) {
    let Some(b) = bounds else { return };
    let painter = ui.painter_at(rect);
    let text = dimensions(b);
    let galley = painter.layout_no_wrap(text, font(), INK);
    let at = rect.right_bottom() - vec2(galley.size().x + 10.0, galley.size().y + 8.0);
    let r = Rect::from_min_size(at, galley.size()).expand(3.0);
    painter.rect_filled(r, 3.0, Color32::from_rgba_unmultiplied(255, 255, 255, 210));
    painter.galley(at, galley, INK);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dimensions_read_width_depth_height() {
        let b = Bounds::new(
            glam::Vec3::new(-6.0, -3.0, 0.0),
            glam::Vec3::new(6.0, 3.0, 4.0),
        );
        assert_eq!(dimensions(&b), "W 12 × D 6 × H 4 m");
    }
}
