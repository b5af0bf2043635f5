//! The view's text overlay: vertex and face counts and the max planarity (top left), the legend
//! (top right) with its clickable fold entry, and the size of what is shown — W × D × H of the
//! previewed geometry's bounding box — in the bottom-right corner.

use cnets_render::Bounds;
use egui::{Color32, Rect, Sense, Ui, vec2};

use crate::preview::{LegendInfo, MeshKind, PreviewStats, format_metres, paper_class};
use crate::worker::format_number;

const INK: Color32 = Color32::from_gray(30);

fn font() -> egui::FontId {
    egui::FontId::proportional(12.0)
}

/// A planarity as the corner shows it: below 1e-12 the digits are rounding noise (and differ
/// between machines).
fn planarity(p: f64) -> String {
    if p < 1e-12 {
        "< 1e-12".to_string()
    } else {
        format_number(p)
    }
}

/// The lines of the top-left corner, each figure naming its mesh: the counts; the headline max
/// planarity (the cone-nets', or without any the other meshes' — never a distance reference's);
/// the largest planarity of the meshes it leaves out (other meshes beside cone-nets, the
/// reference); in the distance mode the symmetric distance, or why there is none (the second
/// item: a warning).
pub fn stats_lines(s: &PreviewStats) -> Vec<(String, bool)> {
    let mut lines = vec![(
        format!("{} vertices · {} faces", s.vertices, s.faces),
        false,
    )];
    if let (Some(p), Some(mesh)) = (s.max_planarity, &s.max_planarity_mesh) {
        lines.push((format!("max planarity {} ({mesh})", planarity(p)), false));
    }
    let lead = s
        .meshes
        .iter()
        .map(|m| m.kind)
        .find(|k| *k != MeshKind::Reference);
    for kind in [MeshKind::Mesh, MeshKind::Reference] {
        if Some(kind) == lead {
            continue;
        }
        let worst = s
            .meshes
            .iter()
            .filter(|m| m.kind == kind)
            .filter_map(|m| Some((m.max_planarity?, &m.name)))
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((p, name)) = worst {
            let what = match kind {
                MeshKind::Reference => "reference",
                _ => "other meshes",
            };
            lines.push((
                format!("{what}: max planarity {} ({name})", planarity(p)),
                false,
            ));
        }
    }
    if let Some(d) = &s.distance {
        lines.push((
            format!(
                "distance {} ↔ {}: rms {} · max {}",
                d.net_name(),
                d.reference,
                format_metres(d.rms),
                format_metres(d.max)
            ),
            false,
        ));
    } else if let Some(why) = &s.distance_status {
        lines.push((format!("⚠ distance: {why}"), true));
    }
    lines
}

/// The colour of a warning in the corner.
const WARN: Color32 = Color32::from_rgb(0xb0, 0x3a, 0x0a);

/// Paints the counts, the max planarity naming its mesh and the distance figures
/// ([`stats_lines`]) in the top-left corner, at most `width` wide (a longer line wraps).
/// Returns the rectangle the text covers.
pub fn paint_stats(ui: &Ui, rect: Rect, s: &PreviewStats, width: f32) -> Rect {
    let painter = ui.painter_at(rect);
    let mut covered = Rect::NOTHING;
    let mut y = rect.top() + 6.0;
    for (line, warning) in stats_lines(s) {
        let ink = if warning { WARN } else { INK };
        let galley = painter.layout(line, font(), ink, width.max(80.0));
        let at = egui::pos2(rect.left() + 8.0, y);
        let r = Rect::from_min_size(at, galley.size());
        y = r.bottom() + 2.0;
        painter.galley(at, galley, ink);
        covered = covered.union(r);
    }
    covered
}

/// The legend's width from the view's right edge (points).
pub const LEGEND_WIDTH: f32 = 170.0;

/// The legend as painted: whether its fold entry was clicked, that entry's rectangle, the
/// legend's lower edge (the view's top when there is no legend) and what it covers.
#[derive(Clone, Copy, Debug)]
pub struct LegendShown {
    /// The fold entry was clicked.
    pub clicked: bool,
    /// Where the fold entry is.
    pub fold_entry: Option<Rect>,
    /// The legend's lower edge.
    pub bottom: f32,
    /// The rectangle the legend covers (title, swatches, labels, fold entry; `Rect::NOTHING`
    /// without one): the grid's labels keep out of it.
    pub covers: Rect,
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
    let covered = std::cell::Cell::new(Rect::NOTHING);
    let swatch = |y: f32, color: cnets_render::Color, label: String| {
        let [r, g, b, _] = color.0;
        let x = rect.right() - LEGEND_WIDTH;
        let square = Rect::from_min_size(egui::pos2(x, y), vec2(14.0, 12.0));
        painter.rect_filled(square, 2.0, Color32::from_rgb(r, g, b));
        let text = painter.text(
            egui::pos2(x + 20.0, y),
            egui::Align2::LEFT_TOP,
            label,
            font(),
            INK,
        );
        covered.set(covered.get().union(square).union(text));
    };
    let beside = !stats.is_positive() || stats.right() + 12.0 < rect.right() - LEGEND_WIDTH;
    let top = if beside {
        rect.top() + 8.0
    } else {
        stats.bottom() + 10.0
    };
    let title = |text: &str| {
        let r = painter.text(
            egui::pos2(rect.right() - LEGEND_WIDTH, top),
            egui::Align2::LEFT_TOP,
            text,
            font(),
            INK,
        );
        covered.set(covered.get().union(r));
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
            covers: covered.get(),
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
    let covers = covered.get().union(entry);
    LegendShown {
        clicked: response.clicked(),
        fold_entry: Some(entry),
        bottom: entry.bottom(),
        covers,
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

/// Paints the size of the previewed geometry in the bottom-right corner; returns the rectangle
/// it covers (`Rect::NOTHING` without geometry).
pub fn paint_dimensions(ui: &Ui, rect: Rect, bounds: Option<&Bounds>) -> Rect {
    let Some(b) = bounds else {
        return Rect::NOTHING;
    };
    let painter = ui.painter_at(rect);
    let text = dimensions(b);
    let galley = painter.layout_no_wrap(text, font(), INK);
    let at = rect.right_bottom() - vec2(galley.size().x + 10.0, galley.size().y + 8.0);
    let r = Rect::from_min_size(at, galley.size()).expand(3.0);
    painter.rect_filled(r, 3.0, Color32::from_rgba_unmultiplied(255, 255, 255, 210));
    painter.galley(at, galley, INK);
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_corner_names_the_mesh_of_each_figure_and_keeps_the_reference_apart() {
        use crate::preview::MeshFigures;
        let mesh = |name: &str, kind, p| MeshFigures {
            name: name.into(),
            kind,
            vertices: 4,
            faces: 1,
            max_planarity: Some(p),
        };
        let s = PreviewStats {
            vertices: 8,
            faces: 2,
            max_planarity: Some(1e-13),
            max_planarity_mesh: Some("net.mesh".into()),
            meshes: vec![
                mesh("net.mesh", MeshKind::ConeNet, 1e-13),
                mesh("hull.mesh", MeshKind::Reference, 0.16),
            ],
            distance_status: None,
            ..PreviewStats::default()
        };
        let lines: Vec<String> = stats_lines(&s).into_iter().map(|(l, _)| l).collect();
        assert_eq!(
            lines,
            [
                "8 vertices · 2 faces".to_string(),
                "max planarity < 1e-12 (net.mesh)".into(),
                "reference: max planarity 0.16 (hull.mesh)".into(),
            ]
        );
        // No figures in the distance mode: the reason, as a warning.
        let s = PreviewStats {
            distance_status: Some("nothing else is previewed to measure against 'net'".into()),
            ..s
        };
        let last = stats_lines(&s).pop().unwrap();
        assert!(
            last.1 && last.0.contains("nothing else is previewed"),
            "{last:?}"
        );
    }

    #[test]
    fn dimensions_read_width_depth_height() {
        let b = Bounds::new(
            glam::Vec3::new(-6.0, -3.0, 0.0),
            glam::Vec3::new(6.0, 3.0, 4.0),
        );
        assert_eq!(dimensions(&b), "W 12 × D 6 × H 4 m");
    }
}
