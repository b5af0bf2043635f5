//! The objective plot: a value per iteration on a log scale, drawn with the painter.

use egui::{Color32, Pos2, Rect, Stroke, Ui};

/// Draws the objective per iteration on a log scale (painter lines; no plotting crate).
pub fn objective_plot(ui: &mut Ui, points: &[(f64, f64)]) -> Rect {
    let width = ui.available_width().clamp(160.0, 420.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 150.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, Color32::from_gray(250));
    painter.rect_stroke(
        rect,
        2.0,
        Stroke::new(1.0, Color32::from_gray(170)),
        egui::StrokeKind::Inside,
    );
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(_, y)| y.is_finite())
        .map(|&(x, y)| (x, y.max(1e-300).log10()))
        .collect();
    if logs.is_empty() {
        return rect;
    }
    let lo = logs
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .floor();
    let hi = logs
        .iter()
        .map(|p| p.1)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .max(lo + 1.0);
    let x_max = logs.iter().map(|p| p.0).fold(1.0, f64::max);
    let plot = Rect::from_min_max(
        rect.min + egui::vec2(44.0, 8.0),
        rect.max - egui::vec2(8.0, 20.0),
    );
    let to_screen = |x: f64, y: f64| {
        Pos2::new(
            plot.left() + (x / x_max) as f32 * plot.width(),
            plot.bottom() - ((y - lo) / (hi - lo)) as f32 * plot.height(),
        )
    };
    let text = ui.visuals().text_color();
    let font = egui::FontId::proportional(10.0);
    // Decades as grid lines, every one labelled when there is room.
    let decades = (hi - lo) as i64;
    let step = (decades / 6).max(1);
    let mut d = lo as i64;
    while d <= hi as i64 {
        let y = to_screen(0.0, d as f64).y;
        painter.line_segment(
            [Pos2::new(plot.left(), y), Pos2::new(plot.right(), y)],
            Stroke::new(0.5, Color32::from_gray(215)),
        );
        painter.text(
            Pos2::new(plot.left() - 4.0, y),
            egui::Align2::RIGHT_CENTER,
            format!("1e{d}"),
            font.clone(),
            text,
        );
        d += step;
    }
    painter.text(
        Pos2::new(plot.right(), rect.bottom() - 3.0),
        egui::Align2::RIGHT_BOTTOM,
        format!("iteration {}", x_max as usize),
        font.clone(),
        text,
    );
    painter.text(
        Pos2::new(plot.left(), rect.bottom() - 3.0),
        egui::Align2::LEFT_BOTTOM,
        "0",
        font,
        text,
    );
    let line: Vec<Pos2> = logs.iter().map(|&(x, y)| to_screen(x, y)).collect();
    let blue = Color32::from_rgb(0x1f, 0x5f, 0xbf);
    painter.add(egui::Shape::line(line.clone(), Stroke::new(1.5, blue)));
    for p in line {
        painter.circle_filled(p, 2.0, blue);
    }
    rect
}
