//! Every glyph is drawn at every zoom: the canvas scales text laid out at its normal size, so a
//! glyph quad shorter than a pixel can fall between pixel centres and vanish (the minus sign of
//! `-1` did). These tests check the glyph quads of the fonts in use against the smallest canvas
//! zoom, that every character the UI's strings use has a glyph, and — in rendered pictures —
//! that a negative value has more ink than the positive one at three zoom levels.

use crate::common;

use cnets_editor::app::EditorApp;
use cnets_editor::canvas::MIN_ZOOM;
use cnets_engine::Value;
use egui::{FontFamily, FontId};
use egui_kittest::Harness;

/// The glyphs of `text` laid out in `font` by the editor's fonts (egui's defaults, as the app
/// sets them up).
fn glyphs(text: &str, font: FontId) -> Vec<(char, egui::Vec2)> {
    glyphs_at(text, font, 1.0)
}

/// Like [`glyphs`] at `ppp` physical pixels per point; quad sizes in physical pixels.
fn glyphs_at(text: &str, font: FontId, ppp: f32) -> Vec<(char, egui::Vec2)> {
    let ctx = egui::Context::default();
    ctx.set_pixels_per_point(ppp);
    let mut out = Vec::new();
    let mut frame = ctx.run_ui(Default::default(), |ui| {
        let galley = ui
            .ctx()
            .fonts_mut(|f| f.layout_no_wrap(text.to_string(), font.clone(), egui::Color32::WHITE));
        for row in &galley.rows {
            for g in &row.row.glyphs {
                out.push((g.chr, g.uv_rect.size * ppp));
            }
        }
    });
    frame.textures_delta.clear();
    out
}

#[test]
fn every_number_glyph_quad_is_at_least_a_pixel_tall_at_the_smallest_zoom() {
    // What the canvas writes numbers with (canvas text is laid out at these sizes whatever the
    // zoom): small, body and button text, proportional and monospace, on screens of 1, 1.5 and 2
    // pixels per point. (egui's number formatter writes the ASCII hyphen-minus.)
    let mut thin = Vec::new();
    for ppp in [1.0, 1.5, 2.0] {
        for size in [9.0, 12.5, 14.0] {
            for family in [FontFamily::Proportional, FontFamily::Monospace] {
                let font = FontId::new(size, family.clone());
                for (c, quad) in glyphs_at("-0123456789.,e+:=", font, ppp) {
                    if quad.y * MIN_ZOOM < 1.0 || quad.x * MIN_ZOOM < 1.0 {
                        thin.push(format!(
                            "'{c}' {size} pt {family:?} at {ppp} px/pt: {quad:?} px"
                        ));
                    }
                }
            }
        }
    }
    assert!(
        thin.is_empty(),
        "glyph quads under a pixel at zoom {MIN_ZOOM}: {thin:#?}"
    );
    // The cause, pinned: the hinted hyphen is one pixel row of ink; the atlas margin (vendor/
    // epaint) makes its quad three pixels tall.
    let minus = glyphs("-", FontId::proportional(14.0))[0].1;
    assert!(minus.y >= 3.0, "{minus:?}");
}

#[test]
fn every_character_of_the_ui_strings_has_a_glyph() {
    let sources = [
        include_str!("../../src/app/mod.rs"),
        include_str!("../../src/app/arrivals.rs"),
        include_str!("../../src/app/loading.rs"),
        include_str!("../../src/app/clusters.rs"),
        include_str!("../../src/app/commands.rs"),
        include_str!("../../src/app/dialogs.rs"),
        include_str!("../../src/app/exports.rs"),
        include_str!("../../src/app/files.rs"),
        include_str!("../../src/app/layout.rs"),
        include_str!("../../src/app/reads.rs"),
        include_str!("../../src/app/worker.rs"),
        include_str!("../../src/canvas/mod.rs"),
        include_str!("../../src/canvas/viewer.rs"),
        include_str!("../../src/canvas/pins.rs"),
        include_str!("../../src/canvas/action.rs"),
        include_str!("../../src/menus.rs"),
        include_str!("../../src/palette/mod.rs"),
        include_str!("../../src/palette/names.rs"),
        include_str!("../../src/widgets.rs"),
        include_str!("../../src/mapper/mod.rs"),
        include_str!("../../src/optimization/mod.rs"),
        include_str!("../../src/optimization/candidates.rs"),
        include_str!("../../src/optimization/panel.rs"),
        include_str!("../../src/plot.rs"),
        include_str!("../../src/parameters.rs"),
        include_str!("../../src/list_editor/mod.rs"),
        include_str!("../../src/list_editor/grid.rs"),
        include_str!("../../src/list_editor/summary.rs"),
        include_str!("../../src/list_editor/table.rs"),
        include_str!("../../src/list_editor/window.rs"),
        include_str!("../../src/viewport/mod.rs"),
        include_str!("../../src/viewport/draw.rs"),
        include_str!("../../src/viewport/grid.rs"),
        include_str!("../../src/viewport/measure.rs"),
        include_str!("../../src/viewport/navigation.rs"),
        include_str!("../../src/viewport/overlay.rs"),
        include_str!("../../src/viewport/pick.rs"),
        include_str!("../../src/file_dialog.rs"),
        include_str!("../../src/export.rs"),
        include_str!("../../src/unsaved.rs"),
        include_str!("../../src/load_failure.rs"),
        include_str!("../../../preview/src/legend.rs"),
        include_str!("../../../preview/src/options.rs"),
    ];
    // Characters inside string literals (between quotes on one line), outside comments.
    let mut used = std::collections::BTreeSet::new();
    for src in sources {
        for line in src.lines() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            let mut inside = false;
            let mut prev = ' ';
            for c in line.chars() {
                if c == '"' && prev != '\\' {
                    inside = !inside;
                } else if inside && !c.is_ascii() {
                    used.insert(c);
                }
                prev = c;
            }
        }
    }
    assert!(
        used.contains(&'▸') || used.contains(&'›'),
        "the scan finds UI symbols: {used:?}"
    );
    // A character no font has is drawn as the replacement glyph: compare atlas rectangles.
    let ctx = egui::Context::default();
    let mut missing = Vec::new();
    let mut frame = ctx.run_ui(Default::default(), |ui| {
        ui.ctx().fonts_mut(|f| {
            let font = FontId::proportional(14.0);
            let mut uv = |c: char| {
                let g = f.layout_no_wrap(c.to_string(), font.clone(), egui::Color32::WHITE);
                g.rows[0]
                    .row
                    .glyphs
                    .first()
                    .map(|g| (g.uv_rect.min, g.uv_rect.max))
            };
            let replacement = uv('\u{0378}');
            for &c in &used {
                if uv(c) == replacement {
                    missing.push(c);
                }
            }
        });
    });
    frame.textures_delta.clear();
    assert!(
        missing.is_empty(),
        "no glyph for {missing:?} (drawn as an empty box)"
    );
}

/// The text's ink in the rectangle: the canvas is dark and its text light (egui's dark theme),
/// so the ink is the brightness above the box's fill (its median brightness), summed.
fn ink(image: &image::RgbaImage, r: egui::Rect) -> u32 {
    let (x0, y0) = (r.left().max(0.0) as u32, r.top().max(0.0) as u32);
    let (x1, y1) = (
        (r.right() as u32).min(image.width()),
        (r.bottom() as u32).min(image.height()),
    );
    let mut v: Vec<u32> = Vec::new();
    for y in y0..y1 {
        for x in x0..x1 {
            let p = image.get_pixel(x, y).0;
            v.push(u32::from(p[0].max(p[1]).max(p[2])));
        }
    }
    let mut sorted = v.clone();
    sorted.sort_unstable();
    let fill = sorted.get(sorted.len() / 2).copied().unwrap_or(0);
    v.iter().map(|&b| b.saturating_sub(fill + 8)).sum()
}

/// The value box of a `param.number` slider editor (right of its 110-point rail).
fn value_box(h: &Harness<'static, EditorApp>) -> egui::Rect {
    let canvas = &h.state().canvas();
    let r = canvas
        .editor_screen_rect("ratio", "value")
        .expect("the slider is drawn");
    let mut b = r;
    b.min.x = r.left() + (110.0 + 4.0) * canvas.zoom();
    b
}

fn set_ratio(h: &mut Harness<'static, EditorApp>, x: f64) {
    h.state_mut()
        .edit_graph(|g, _| {
            g.set_value("ratio", "value", Value::Number(x))
                .map(|_| ())
                .map_err(|e| e.to_string())
        })
        .unwrap();
    common::settle(h);
}

#[test]
fn negative_values_show_their_minus_sign_at_three_zoom_levels() {
    let mut h = common::harness("minus");
    for (zoom, name) in [
        (MIN_ZOOM, "editor_minus_zoom_050"),
        (0.8, "editor_minus_zoom_080"),
        (1.3, "editor_minus_zoom_130"),
    ] {
        let centre = h
            .state()
            .canvas()
            .node_rect("ratio")
            .expect("drawn")
            .center();
        h.state_mut().zoom_canvas(zoom, Some(centre));
        h.run_steps(3);
        set_ratio(&mut h, 1.0);
        let rect = value_box(&h);
        let positive = ink(&h.render().unwrap(), rect);
        set_ratio(&mut h, -1.0);
        let rect2 = value_box(&h);
        let image = h.render().unwrap();
        let negative = ink(&image, rect2);
        eprintln!("zoom {zoom}: ink of '-1' {negative}, of '1' {positive}");
        assert!(
            negative > positive,
            "zoom {zoom}: '-1' has no more ink than '1' ({negative} vs {positive}): the minus is not drawn"
        );
        h.snapshot(name);
    }
}
