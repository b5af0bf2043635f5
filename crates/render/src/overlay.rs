//! Legends drawn into rendered pictures (`cnets render`): a light panel in the top-right corner
//! with blocks of a title and rows of a colour swatch and words, as the editor's viewport draws
//! them. Glyphs are rasterized with `ab_glyph` from the Ubuntu Light font egui ships
//! (`epaint_default_fonts`), so a picture needs no system fonts.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};

use crate::offscreen::Image;
use crate::palette::Color;

/// One block of a legend: a title and its rows.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendBlock {
    /// The block's title (`configuration`, `planarity (relative)`, `points`).
    pub title: String,
    /// Rows: swatch colour and words.
    pub rows: Vec<(Color, String)>,
    /// Draw the swatches as dots (points in the picture) instead of squares (faces).
    pub dots: bool,
}

/// Where a legend was drawn, in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PanelRect {
    /// Left edge.
    pub x: u32,
    /// Top edge.
    pub y: u32,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
}

const INK: [u8; 3] = [30, 30, 30];
const PANEL: [u8; 3] = [255, 255, 255];

/// The text height legends use on an image `height` pixels high.
pub fn legend_text_px(height: u32) -> f32 {
    (height as f32 / 48.0).clamp(12.0, 32.0)
}

/// Draws `blocks` into the top-right corner of `image` on a light panel; returns the panel's
/// rectangle, or `None` when there is nothing to draw or the image is too small for it.
pub fn draw_legend(image: &mut Image, blocks: &[LegendBlock]) -> Option<PanelRect> {
    let rows: usize = blocks.iter().map(|b| 1 + b.rows.len()).sum();
    if rows == 0 {
        return None;
    }
    let font = FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).ok()?;
    let px = legend_text_px(image.height);
    let scale = PxScale::from(px);
    let line = (px * 1.4).ceil();
    let pad = (px * 0.7).ceil();
    let swatch = (px * 0.9).round();
    let gap = (px * 0.5).round();
    let block_gap = (px * 0.5).round();
    let text_width = |t: &str| width_of(&font, scale, t);
    let mut width: f32 = 0.0;
    for b in blocks {
        width = width.max(text_width(&b.title));
        for (_, t) in &b.rows {
            width = width.max(swatch + gap + text_width(t));
        }
    }
    let panel_w = (width + 2.0 * pad).ceil();
    let panel_h = (rows as f32 * line + (blocks.len() - 1) as f32 * block_gap + 2.0 * pad).ceil();
    let margin = pad;
    if panel_w + 2.0 * margin > image.width as f32 || panel_h + 2.0 * margin > image.height as f32 {
        return None;
    }
    let x0 = image.width as f32 - margin - panel_w;
    let y0 = margin;
    fill(image, x0, y0, panel_w, panel_h, PANEL, 0.88);
    let mut y = y0 + pad;
    let ascent = font.as_scaled(scale).ascent();
    for b in blocks {
        draw_text(image, &font, scale, x0 + pad, y + ascent, &b.title, INK);
        y += line;
        for (color, text) in &b.rows {
            let [r, g, bl, _] = color.0;
            let sy = y + (line - swatch) * 0.5 - px * 0.15;
            if b.dots {
                disc(
                    image,
                    x0 + pad + swatch * 0.5,
                    sy + swatch * 0.5,
                    swatch * 0.42,
                    [r, g, bl],
                );
            } else {
                fill(image, x0 + pad, sy, swatch, swatch, [r, g, bl], 1.0);
            }
            draw_text(
                image,
                &font,
                scale,
                x0 + pad + swatch + gap,
                y + ascent,
                text,
                INK,
            );
            y += line;
        }
        y += block_gap;
    }
    Some(PanelRect {
        x: x0 as u32,
        y: y0 as u32,
        width: panel_w as u32,
        height: panel_h as u32,
    })
}

fn width_of(font: &FontRef<'_>, scale: PxScale, text: &str) -> f32 {
    let f = font.as_scaled(scale);
    let mut x = 0.0;
    let mut last = None;
    for c in text.chars() {
        let id = f.glyph_id(c);
        if let Some(prev) = last {
            x += f.kern(prev, id);
        }
        x += f.h_advance(id);
        last = Some(id);
    }
    x
}

fn draw_text(
    image: &mut Image,
    font: &FontRef<'_>,
    scale: PxScale,
    x: f32,
    baseline: f32,
    text: &str,
    ink: [u8; 3],
) {
    let f = font.as_scaled(scale);
    let mut caret = x;
    let mut last = None;
    for c in text.chars() {
        let id = f.glyph_id(c);
        if let Some(prev) = last {
            caret += f.kern(prev, id);
        }
        let glyph = id.with_scale_and_position(scale, point(caret, baseline));
        caret += f.h_advance(id);
        last = Some(id);
        if let Some(outline) = font.outline_glyph(glyph) {
            let b = outline.px_bounds();
            outline.draw(|gx, gy, coverage| {
                blend(
                    image,
                    b.min.x as i64 + i64::from(gx),
                    b.min.y as i64 + i64::from(gy),
                    ink,
                    coverage,
                );
            });
        }
    }
}

fn blend(image: &mut Image, x: i64, y: i64, color: [u8; 3], alpha: f32) {
    if x < 0 || y < 0 || x >= i64::from(image.width) || y >= i64::from(image.height) {
        return;
    }
    let a = alpha.clamp(0.0, 1.0);
    let k = (y as usize * image.width as usize + x as usize) * 4;
    if let Some(p) = image.pixels.get_mut(k..k + 4) {
        for (c, &v) in p.iter_mut().zip(&color) {
            *c = (f32::from(*c) * (1.0 - a) + f32::from(v) * a).round() as u8;
        }
        p[3] = 255;
    }
}

fn fill(image: &mut Image, x: f32, y: f32, w: f32, h: f32, color: [u8; 3], alpha: f32) {
    let (x0, y0) = (x.round() as i64, y.round() as i64);
    let (x1, y1) = ((x + w).round() as i64, (y + h).round() as i64);
    for py in y0..y1 {
        for px in x0..x1 {
            blend(image, px, py, color, alpha);
        }
    }
}

fn disc(image: &mut Image, cx: f32, cy: f32, r: f32, color: [u8; 3]) {
    let (x0, x1) = ((cx - r - 1.0) as i64, (cx + r + 1.0) as i64);
    let (y0, y1) = ((cy - r - 1.0) as i64, (cy + r + 1.0) as i64);
    for py in y0..=y1 {
        for px in x0..=x1 {
            let d = ((px as f32 + 0.5 - cx).powi(2) + (py as f32 + 0.5 - cy).powi(2)).sqrt();
            let a = (r + 0.5 - d).clamp(0.0, 1.0);
            if a > 0.0 {
                blend(image, px, py, color, a);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blank(w: u32, h: u32) -> Image {
        Image {
            width: w,
            height: h,
            pixels: [200, 210, 220, 255].repeat((w * h) as usize),
        }
    }

    fn block(rows: &[(u32, &str)]) -> LegendBlock {
        LegendBlock {
            title: "configuration".into(),
            rows: rows
                .iter()
                .map(|&(c, t)| (Color::hex(c), t.to_string()))
                .collect(),
            dots: false,
        }
    }

    #[test]
    fn a_legend_draws_a_panel_with_swatches_and_text_top_right() {
        let mut img = blank(640, 400);
        let b = block(&[
            (0x2060d0, "(++)(++)  convex  170"),
            (0xd03030, "(−−)(−−)  minus-minus  3"),
        ]);
        let r = draw_legend(&mut img, &[b]).expect("drawn");
        assert!(r.x + r.width <= 640 && r.x > 320, "top right: {r:?}");
        assert_eq!(r.y, (legend_text_px(400) * 0.7).ceil() as u32);
        // The swatches are there in their own colours, and dark text ink inside the panel.
        assert!(img.count_color([0x20, 0x60, 0xd0, 255]) > 50);
        assert!(img.count_color([0xd0, 0x30, 0x30, 255]) > 50);
        let dark = (r.y..r.y + r.height)
            .flat_map(|y| (r.x..r.x + r.width).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                img.pixel(x, y)
                    .is_some_and(|p| p[0] < 170 && p[1] < 170 && p[2] < 170)
            })
            .count();
        assert!(dark > 200, "text ink: {dark} dark pixels");
        // Outside the panel nothing changed.
        assert_eq!(img.pixel(5, 395), Some([200, 210, 220, 255]));
        // Longer words make a wider panel.
        let mut img2 = blank(640, 400);
        let wide = block(&[(0x2060d0, "(++)(++)  convex  170 faces and more words")]);
        let r2 = draw_legend(&mut img2, &[wide]).unwrap();
        assert!(r2.width > r.width);
    }

    #[test]
    fn the_minus_sign_of_the_paper_classes_is_drawn() {
        // U+2212 has a glyph in the font: "−−" inks more than "++" minus the vertical bars.
        let font = FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).unwrap();
        for c in ['−', '+', '≥', '·'] {
            assert_ne!(font.glyph_id(c).0, 0, "{c:?} has a glyph");
        }
    }

    #[test]
    fn nothing_to_draw_or_no_room_draws_nothing() {
        let mut img = blank(640, 400);
        assert!(draw_legend(&mut img, &[]).is_none());
        let mut tiny = blank(8, 8);
        let before = tiny.clone();
        assert!(draw_legend(&mut tiny, &[block(&[(0x2060d0, "convex")])]).is_none());
        assert_eq!(tiny, before);
    }
}
