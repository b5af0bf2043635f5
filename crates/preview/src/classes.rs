//! Face classes of a quad mesh from a construction's `configurations` output, and their colours.

use cnets_engine::Value;
use cnets_geometry::QuadGrid;
use cnets_geometry::fabrication::FaceClass;
use cnets_render::Color;

/// The render colour of a face class (the same colours the glTF export uses).
pub fn class_color(class: FaceClass) -> Color {
    let c = class.colour();
    Color::from_f32([c.x as f32, c.y as f32, c.z as f32, 1.0])
}

/// The class of every face of `grid` (row-major over quads) from a construction node's
/// `configurations` output (N lists of M−1 labels), as [`cnets_geometry::fabrication::face_classes`]
/// defines it. `None` when the value is not such a table or does not fit the grid.
pub fn face_classes(grid: &QuadGrid, configurations: &Value) -> Option<Vec<FaceClass>> {
    let labels: Vec<Vec<String>> = configurations
        .as_list()?
        .iter()
        .map(|row| {
            row.as_list()?
                .iter()
                .map(|v| match v {
                    Value::Text(t) => Some(t.to_string()),
                    _ => None,
                })
                .collect()
        })
        .collect::<Option<_>>()?;
    cnets_geometry::fabrication::face_classes(grid, &labels).ok()
}
