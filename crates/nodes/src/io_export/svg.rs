//! SVG cutting sheets: one closed path per outline and its label, in millimetres (the document's
//! `width`/`height` are in mm and one user unit is 1 mm). A 5 mm margin surrounds the drawing; the
//! model's y axis points up, so y is flipped (`Y = top − y`); the `viewBox` is the drawing's bounds
//! plus the margin. Cut lines are red, 1/1500 of the drawing's diagonal wide (at least a 0.1 mm
//! hairline), labels blue text (for engraving) sized to the strips (`Sheet::text_height`), one
//! `<g id="strip-k">` per outline; nested outlines are grouped per sheet in `<g id="sheet-s">`,
//! an Inkscape layer each (Inkscape shows them as separate layers, "pages" to cut). Numbers have 4
//! decimals.

use std::fmt::Write;

use glam::DVec2;

use super::outlines::Sheet;

/// Margin around the drawing, in mm.
pub const MARGIN_MM: f64 = 5.0;

/// Escapes text for XML content and attributes.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\t' && c != '\n' && c != '\r' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A number with at most 4 decimals and no trailing zeros.
fn num(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// Encodes the sheet as an SVG document.
pub fn encode_svg(sheet: &Sheet) -> String {
    let (lo, hi) = sheet.bounds;
    let size = hi - lo + DVec2::splat(2.0 * MARGIN_MM);
    let map = |p: DVec2| DVec2::new(p.x - lo.x + MARGIN_MM, hi.y - p.y + MARGIN_MM);
    let h = sheet.text_height();
    let mut out = String::new();
    let _ = writeln!(out, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" version="1.1" width="{w}mm" height="{hh}mm" viewBox="0 0 {w} {hh}">"#,
        w = num(size.x),
        hh = num(size.y)
    );
    let _ = writeln!(out, "  <title>cnets unrolled strips (units: mm)</title>");
    let stroke = num(sheet.stroke_width());
    // Outlines in sheet order (stable: in input order within a sheet).
    let mut order: Vec<usize> = (0..sheet.paths.len()).collect();
    if let Some(sheets) = &sheet.sheets {
        order.sort_by_key(|&k| sheets[k]);
    }
    let mut open_sheet = None;
    for k in order {
        let ((pts, closed), (label, anchor)) =
            (&sheet.paths[k], (&sheet.labels[k], &sheet.anchors[k]));
        if let Some(sheets) = &sheet.sheets
            && open_sheet != Some(sheets[k])
        {
            if open_sheet.is_some() {
                let _ = writeln!(out, "  </g>");
            }
            let s = sheets[k];
            let _ = writeln!(
                out,
                r#"  <g id="sheet-{s}" inkscape:groupmode="layer" inkscape:label="sheet {}">"#,
                s + 1
            );
            open_sheet = Some(s);
        }
        let _ = writeln!(out, r#"  <g id="strip-{k}">"#);
        let mut d = String::new();
        for (i, p) in pts.iter().enumerate() {
            let q = map(*p);
            let _ = write!(
                d,
                "{}{} {}",
                if i == 0 { "M" } else { " L" },
                num(q.x),
                num(q.y)
            );
        }
        if *closed {
            d.push_str(" Z");
        }
        let _ = writeln!(
            out,
            r##"    <path d="{d}" fill="none" stroke="#e4002b" stroke-width="{stroke}"/>"##
        );
        if !label.is_empty() {
            let a = map(*anchor);
            let _ = writeln!(
                out,
                r##"    <text x="{}" y="{}" font-size="{}" font-family="sans-serif" text-anchor="middle" dominant-baseline="middle" fill="#0050a0">{}</text>"##,
                num(a.x),
                num(a.y),
                num(h),
                escape(label)
            );
        }
        let _ = writeln!(out, "  </g>");
    }
    if open_sheet.is_some() {
        let _ = writeln!(out, "  </g>");
    }
    out.push_str("</svg>\n");
    out
}
