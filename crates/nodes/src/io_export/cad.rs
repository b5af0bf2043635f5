//! DXF cutting drawings (with the `dxf` crate): header version R2000 (AC1015; the crate's default R12
//! has no LWPOLYLINE and silently drops them), `$INSUNITS` = 4 (millimetres). Every outline is an
//! LWPOLYLINE (closed flag set for closed outlines) on its own layer `STRIP_<label>` (or
//! `STRIP_<k>`), with its label as a TEXT entity on the same layer, centred on the label point.
//! Coordinates are the model's x and y times `scale` (no offset), so they match the model.

use dxf::entities::{Entity, EntityType, LwPolyline, Text};
use dxf::enums::{AcadVersion, HorizontalTextJustification, Units, VerticalTextJustification};
use dxf::tables::Layer;
use dxf::{Color, Drawing, LwPolylineVertex, Point};

use super::outlines::Sheet;

/// The layer name of outline `k`: `STRIP_` and its label reduced to letters, digits, `_` and `-`
/// (made unique with `_k` when needed).
pub fn layer_name(label: &str, k: usize, taken: &[String]) -> String {
    let clean: String = label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let base = if clean.is_empty() {
        format!("STRIP_{k}")
    } else {
        format!("STRIP_{clean}")
    };
    if taken.iter().any(|t| t.eq_ignore_ascii_case(&base)) {
        format!("{base}_{k}")
    } else {
        base
    }
}

/// Encodes the sheet as a DXF drawing.
pub fn encode_dxf(sheet: &Sheet) -> Result<Vec<u8>, String> {
    let mut drawing = Drawing::new();
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = Units::Millimeters;
    let height = sheet.text_height();
    let mut names: Vec<String> = Vec::with_capacity(sheet.paths.len());
    for (k, ((pts, closed), (label, anchor))) in sheet
        .paths
        .iter()
        .zip(sheet.labels.iter().zip(&sheet.anchors))
        .enumerate()
    {
        let name = layer_name(label, k, &names);
        drawing.add_layer(Layer {
            name: name.clone(),
            color: Color::from_index((k % 6 + 1) as u8),
            ..Default::default()
        });
        let mut poly = LwPolyline::default();
        poly.set_is_closed(*closed);
        poly.vertices = pts
            .iter()
            .map(|p| LwPolylineVertex {
                x: p.x,
                y: p.y,
                ..Default::default()
            })
            .collect();
        let mut entity = Entity::new(EntityType::LwPolyline(poly));
        entity.common.layer = name.clone();
        drawing.add_entity(entity);
        if !label.is_empty() {
            let at = Point::new(anchor.x, anchor.y, 0.0);
            let text = Text {
                location: at.clone(),
                second_alignment_point: at,
                text_height: height,
                value: label.clone(),
                horizontal_text_justification: HorizontalTextJustification::Center,
                vertical_text_justification: VerticalTextJustification::Middle,
                ..Default::default()
            };
            let mut entity = Entity::new(EntityType::Text(text));
            entity.common.layer = name.clone();
            drawing.add_entity(entity);
        }
        names.push(name);
    }
    let mut bytes = Vec::new();
    drawing
        .save(&mut bytes)
        .map_err(|e| format!("cannot encode the DXF drawing: {e}"))?;
    Ok(bytes)
}
