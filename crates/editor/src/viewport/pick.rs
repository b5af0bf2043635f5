//! Picking: what the pointer is over in the 3D view — a vertex or a face of a previewed mesh (the
//! node that made it, its row and column, coordinates, and for a face its configuration class and
//! planarity) — and the nearest drawn vertex for snapping.
//!
//! A face is found by casting the pointer's ray against the previewed meshes' triangles (quads
//! split along a diagonal, polygons fanned); a vertex is a corner of the face hit within
//! [`VERTEX_RADIUS`] on screen.

use cnets_geometry::DVec3;
use cnets_preview::{PickGeometry, PickMesh, Picks, paper_class};
use egui::Pos2;

use super::screen::{ScreenMap, WorldRay};
use crate::worker::format_number;

/// Screen distance (points) within which a vertex is picked instead of its face.
pub const VERTEX_RADIUS: f32 = 7.0;

/// What the pointer is over.
#[derive(Clone, Debug, PartialEq)]
pub enum Hit {
    /// A face of a previewed mesh.
    Face {
        /// Index into [`Picks::meshes`].
        mesh: usize,
        /// The face (quads row-major).
        face: usize,
        /// Where the ray met it.
        point: DVec3,
    },
    /// A vertex of a previewed mesh.
    Vertex {
        /// Index into [`Picks::meshes`].
        mesh: usize,
        /// The vertex.
        vertex: usize,
        /// Its position.
        point: DVec3,
    },
}

impl Hit {
    /// The mesh hit.
    pub fn mesh(&self) -> usize {
        match self {
            Hit::Face { mesh, .. } | Hit::Vertex { mesh, .. } => *mesh,
        }
    }
}

/// Möller–Trumbore: the ray parameter where it meets triangle (a, b, c).
fn ray_triangle(ray: &WorldRay, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = ray.direction.cross(e2);
    let det = e1.dot(p);
    let scale = e1.length() * e2.length();
    if det.abs() <= 1e-14 * scale || !det.is_finite() {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - a;
    let u = s.dot(p) * inv;
    if !(-1e-9..=1.0 + 1e-9).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = ray.direction.dot(q) * inv;
    if v < -1e-9 || u + v > 1.0 + 1e-9 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 0.0).then_some(t)
}

/// The nearest face of `mesh` along `ray`: (face, t).
fn cast(mesh: &PickMesh, ray: &WorldRay) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for f in 0..mesh.geometry.face_count() {
        let corners = mesh.geometry.face_corners(f);
        if corners.len() < 3 {
            continue;
        }
        for k in 1..corners.len() - 1 {
            if let Some(t) = ray_triangle(ray, corners[0], corners[k], corners[k + 1])
                && best.is_none_or(|(_, b)| t < b)
            {
                best = Some((f, t));
            }
        }
    }
    best
}

/// The vertex index of each corner of face `f`.
pub(super) fn face_vertex_indices(geometry: &PickGeometry, f: usize) -> Vec<usize> {
    match geometry {
        PickGeometry::Grid(g) => {
            let qc = g.quad_cols();
            if qc == 0 {
                return Vec::new();
            }
            g.quad_indices(f / qc, f % qc).to_vec()
        }
        PickGeometry::Mesh(m) => m.face(f).iter().map(|&k| k as usize).collect(),
    }
}

/// What is under the screen point `at`: the nearest face along the ray, or one of its corners when
/// that corner is within [`VERTEX_RADIUS`] (and within a third of the way to the face's centre on
/// screen).
pub fn pick(picks: &Picks, map: &ScreenMap, at: Pos2) -> Option<Hit> {
    let ray = map.ray(at);
    let (mesh, face, t) = picks
        .meshes
        .iter()
        .enumerate()
        .filter_map(|(m, mesh)| cast(mesh, &ray).map(|(f, t)| (m, f, t)))
        .min_by(|a, b| a.2.total_cmp(&b.2))?;
    let geometry = &picks.meshes[mesh].geometry;
    let corners: Vec<(usize, DVec3, Pos2)> = face_vertex_indices(geometry, face)
        .into_iter()
        .filter_map(|v| {
            let p = *geometry.vertices().get(v)?;
            Some((v, p, map.to_screen(p)?))
        })
        .collect();
    // On a face drawn small, its centre is near every corner: a vertex is picked only within a
    // third of the way from a corner to the face's centre on screen.
    let centre = corners
        .iter()
        .fold(egui::Vec2::ZERO, |acc, c| acc + c.2.to_vec2())
        / corners.len().max(1) as f32;
    let radius = corners
        .iter()
        .map(|c| c.2.distance(centre.to_pos2()) / 3.0)
        .fold(VERTEX_RADIUS, f32::min);
    let corner = corners
        .into_iter()
        .map(|(v, p, s)| (v, p, s.distance(at)))
        .filter(|(_, _, d)| *d <= radius)
        .min_by(|a, b| a.2.total_cmp(&b.2));
    Some(match corner {
        Some((vertex, point, _)) => Hit::Vertex {
            mesh,
            vertex,
            point,
        },
        None => Hit::Face {
            mesh,
            face,
            point: ray.at(t),
        },
    })
}

/// The drawn vertex (mesh vertex or curve point) nearest the screen point `at` within `radius`
/// points.
pub fn nearest_vertex(picks: &Picks, map: &ScreenMap, at: Pos2, radius: f32) -> Option<DVec3> {
    picks
        .vertices()
        .filter_map(|p| Some((p, map.to_screen(p)?.distance(at))))
        .filter(|(_, d)| *d <= radius)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(p, _)| p)
}

/// Coordinates as the tooltip writes them.
pub fn coordinates(p: DVec3) -> String {
    format!(
        "({}, {}, {})",
        format_number(p.x),
        format_number(p.y),
        format_number(p.z)
    )
}

/// The tooltip of a hit: the node (by its name in `graph`, when it has one) and output that made
/// it, the row and column (i, j) (or the index), the coordinates, and for a face its class and
/// planarity.
pub fn describe(picks: &Picks, hit: &Hit, graph: &cnets_engine::Graph) -> String {
    let mesh = &picks.meshes[hit.mesh()];
    let item = mesh.item.map_or(String::new(), |k| format!(" [{k}]"));
    let node = graph
        .node(&mesh.node)
        .map_or(mesh.node.as_str(), |n| n.label());
    let mut lines = vec![format!("{node} · {}{item}", mesh.output)];
    match *hit {
        Hit::Vertex { vertex, point, .. } => {
            lines.push(match mesh.geometry.vertex_row_col(vertex) {
                Some((i, j)) => format!("vertex (i {i}, j {j})"),
                None => format!("vertex {vertex}"),
            });
            lines.push(coordinates(point));
        }
        Hit::Face { face, point, .. } => {
            lines.push(match mesh.geometry.face_row_col(face) {
                Some((i, j)) => format!("face (i {i}, j {j})"),
                None => format!("face {face}"),
            });
            if let Some(class) = mesh.classes.as_ref().and_then(|c| c.get(face)) {
                lines.push(format!("{}  {}", paper_class(*class), class.name()));
            }
            if let Some(p) = mesh.planarity.get(face) {
                lines.push(format!("planarity {}", format_number(*p)));
            }
            lines.push(format!("at {}", coordinates(point)));
        }
    }
    lines.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_geometry::QuadGrid;
    use cnets_preview::PickMesh;
    use cnets_render::{Camera, Projection, View};
    use egui::Rect;
    use std::sync::Arc;

    #[test]
    fn the_face_under_the_pointer_is_named_by_row_and_column() {
        // A 3 × 4 grid in the XY plane, 1 m cells, seen from the top.
        let vertices = (0..3)
            .flat_map(|i| (0..4).map(move |j| DVec3::new(j as f64, i as f64, 0.0)))
            .collect();
        let grid = QuadGrid::new(3, 4, vertices).unwrap();
        let picks = Picks {
            meshes: vec![PickMesh {
                node: "net".into(),
                output: "mesh".into(),
                item: None,
                geometry: PickGeometry::Grid(Arc::new(grid)),
                classes: None,
                planarity: vec![0.0; 6],
            }],
            curves: Vec::new(),
        };
        let mut camera = Camera::new(View::Top);
        camera.projection = Projection::Orthographic;
        camera.target = glam::Vec3::new(1.5, 1.0, 0.0);
        camera.distance = 5.0;
        let map = ScreenMap {
            rect: Rect::from_min_size(Pos2::ZERO, egui::vec2(400.0, 400.0)),
            camera,
        };
        // The centre of face (i 1, j 2): x 2.5, y 1.5.
        let at = map.to_screen(DVec3::new(2.5, 1.5, 0.0)).unwrap();
        let hit = pick(&picks, &map, at).expect("a face");
        assert!(matches!(hit, Hit::Face { face: 5, .. }), "{hit:?}");
        let graph = cnets_engine::Graph::new(std::sync::Arc::new(cnets_engine::Registry::new()));
        let text = describe(&picks, &hit, &graph);
        assert!(text.starts_with("net · mesh\n") && text.contains("face (i 1, j 2)"));
        // On a corner: the vertex (i 2, j 3).
        let at = map.to_screen(DVec3::new(3.0, 2.0, 0.0)).unwrap();
        let hit = pick(&picks, &map, at + egui::vec2(-2.0, 2.0)).expect("a vertex");
        assert!(matches!(hit, Hit::Vertex { vertex: 11, .. }), "{hit:?}");
        assert!(describe(&picks, &hit, &graph).contains("vertex (i 2, j 3)"));
        assert!(pick(&picks, &map, Pos2::new(5.0, 5.0)).is_none(), "outside");
    }
}
