//! Making construction planes in the 3D view: the *CPlane from 3 points* tool (three clicks, each
//! snapped to a handle or a drawn vertex near the pointer, else to the grid of the current plane:
//! origin at the first, u towards the second, the normal from the three; Backspace removes the
//! last point, Esc cancels) and the points a plane is fitted through (a selected node's previewed
//! curve, or the row of a net whose vertex or face was clicked).

use cnets_geometry::DVec3;
use cnets_preview::{PickGeometry, Picks};
use egui::{Color32, Painter, Stroke};

use super::cplane::{CPlane, CPlaneError};
use super::pick::Hit;
use super::screen::ScreenMap;

/// The *CPlane from 3 points* tool's state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ThreePointTool {
    /// The points clicked so far (at most two between clicks).
    pub points: Vec<DVec3>,
}

/// What a click of the tool did.
#[derive(Clone, Debug, PartialEq)]
pub enum ThreePointClick {
    /// A first or second point was taken.
    Added,
    /// The third point made a plane.
    Made(CPlane),
    /// The third point made no plane (the three are on one line): it was dropped, this says why.
    Refused(CPlaneError),
}

impl ThreePointTool {
    /// A click on `p` (already snapped).
    pub fn click(&mut self, p: DVec3) -> ThreePointClick {
        if self.points.len() < 2 {
            // A double-click's second click lands on the point just taken.
            if self.points.last() != Some(&p) {
                self.points.push(p);
            }
            return ThreePointClick::Added;
        }
        match CPlane::from_three_points(self.points[0], self.points[1], p) {
            Ok(plane) => {
                self.points.clear();
                ThreePointClick::Made(plane)
            }
            Err(e) => ThreePointClick::Refused(e),
        }
    }

    /// What the status bar says the tool wants next.
    pub fn prompt(&self) -> &'static str {
        match self.points.len() {
            0 => {
                "CPlane from 3 points: click its origin (snaps to vertices and handles; Esc cancels)"
            }
            1 => "CPlane from 3 points: click a point along its first axis (u)",
            _ => "CPlane from 3 points: click a third point in the plane",
        }
    }

    /// Paints the points so far, the lines to the pointer and the pointer's point.
    pub fn paint(&self, painter: &Painter, map: &ScreenMap, hover: Option<DVec3>) {
        let ink = Color32::from_rgb(0x00, 0x8c, 0x8c);
        let mut chain: Vec<DVec3> = self.points.clone();
        chain.extend(hover);
        let screen: Vec<egui::Pos2> = chain.iter().filter_map(|p| map.to_screen(*p)).collect();
        if screen.len() >= 2 {
            let mut outline = screen.clone();
            if screen.len() == 3 {
                outline.push(screen[0]);
            }
            painter.add(egui::Shape::line(outline, Stroke::new(1.5, ink)));
        }
        for (k, s) in screen.iter().enumerate() {
            if k < self.points.len() {
                let r = if k == 0 { 5.0 } else { 4.0 };
                painter.circle(*s, r, Color32::WHITE, Stroke::new(1.5, ink));
            } else {
                painter.circle_stroke(*s, 4.0, Stroke::new(1.0, ink));
            }
        }
    }
}

/// The points a plane is fitted through: the row of the net whose vertex or face was last
/// clicked (`picked`, when its node is among `selected`), else the previewed curve of a selected
/// node. `None` with a message saying what to select.
pub fn fit_points(
    picks: &Picks,
    picked: Option<&Hit>,
    selected: &[String],
) -> Result<(Vec<DVec3>, String), CPlaneError> {
    if let Some(hit) = picked
        && let Some(mesh) = picks.meshes.get(hit.mesh())
        && selected.contains(&mesh.node)
        && let PickGeometry::Grid(g) = &mesh.geometry
    {
        let row = match hit {
            Hit::Vertex { vertex, .. } => mesh.geometry.vertex_row_col(*vertex).map(|(r, _)| r),
            Hit::Face { face, .. } => mesh.geometry.face_row_col(*face).map(|(r, _)| r),
        };
        if let Some(row) = row.filter(|&r| r < g.rows) {
            let points = g.row(row).points;
            return Ok((points, format!("row {row} of {}", mesh.node)));
        }
    }
    for id in selected {
        let curves: Vec<DVec3> = picks
            .curves
            .iter()
            .filter(|c| &c.node == id)
            .flat_map(|c| c.polyline.points.iter().copied())
            .collect();
        if !curves.is_empty() {
            return Ok((curves, format!("the curve of {id}")));
        }
    }
    Err(CPlaneError::NothingToFit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_geometry::QuadGrid;
    use cnets_preview::{PickCurve, PickMesh};
    use std::sync::Arc;

    #[test]
    fn three_clicks_make_a_plane_and_a_point_on_the_line_is_refused() {
        let mut tool = ThreePointTool::default();
        assert_eq!(tool.click(DVec3::ZERO), ThreePointClick::Added);
        assert_eq!(
            tool.click(DVec3::ZERO),
            ThreePointClick::Added,
            "double-click"
        );
        assert_eq!(tool.click(DVec3::X), ThreePointClick::Added);
        assert!(tool.prompt().contains("third"));
        let ThreePointClick::Refused(why) = tool.click(DVec3::X * 3.0) else {
            panic!("collinear")
        };
        assert_eq!(why, CPlaneError::ThreeOnALine);
        assert!(why.to_string().contains("one line"));
        assert_eq!(tool.points.len(), 2, "the first two are kept");
        let ThreePointClick::Made(plane) = tool.click(DVec3::new(1.0, 0.0, 1.0)) else {
            panic!("a plane")
        };
        assert_eq!(plane.origin, DVec3::ZERO);
        assert_eq!(plane.u, DVec3::X);
        assert!((plane.normal - DVec3::NEG_Y).length() < 1e-15);
        assert!(tool.points.is_empty());
    }

    #[test]
    fn a_fit_takes_the_clicked_row_of_a_selected_net_else_a_selected_curve() {
        let vertices: Vec<DVec3> = (0..3)
            .flat_map(|i| (0..4).map(move |j| DVec3::new(j as f64, i as f64, (i * j) as f64)))
            .collect();
        let grid = QuadGrid::new(3, 4, vertices).unwrap();
        let mut picks = Picks::default();
        picks.meshes.push(PickMesh {
            node: "net".into(),
            output: "mesh".into(),
            item: None,
            geometry: PickGeometry::Grid(Arc::new(grid)),
            classes: None,
            planarity: Vec::new(),
        });
        picks.curves.push(PickCurve {
            node: "spline".into(),
            output: "curve".into(),
            polyline: Arc::new(cnets_geometry::Polyline {
                points: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
                closed: false,
            }),
        });
        let hit = Hit::Vertex {
            mesh: 0,
            vertex: 6,
            point: DVec3::new(2.0, 1.0, 2.0),
        };
        let (points, what) = fit_points(&picks, Some(&hit), &["net".to_string()]).unwrap();
        assert_eq!(what, "row 1 of net");
        assert_eq!(points.len(), 4);
        assert!(points.iter().all(|p| p.y == 1.0));
        let (points, what) = fit_points(&picks, Some(&hit), &["spline".to_string()]).unwrap();
        assert_eq!((points.len(), what.as_str()), (3, "the curve of spline"));
        assert!(fit_points(&picks, None, &["net".to_string()]).is_err());
        assert!(fit_points(&picks, Some(&hit), &[]).is_err());
    }
}
