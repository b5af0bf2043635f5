//! The panels of unrolled strips in one form (issue 43): every panel's mesh vertices, its 3D corners
//! and its placed flat corners, whether it came from a quad grid ([`super::unroll_strips`]) or a
//! polygon mesh ([`super::unroll_mesh_strips`]). Folds, marks and pieces are computed from this.

use std::fmt;

use glam::{DVec2, DVec3};

use super::collapsed::CollapsedEdge;
use super::mesh_strips::UnrolledMesh;
use super::unroll::Unrolled;
use crate::{PolygonMesh, Polyline, QuadGrid};

/// Where a panel is in the mesh, for messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PanelSource {
    /// Quad (row, column) of a quad grid.
    Quad(usize, usize),
    /// Face of a polygon mesh.
    Face(usize),
}

impl fmt::Display for PanelSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Quad(i, j) => write!(f, "mesh quad row {i}, column {j}"),
            Self::Face(k) => write!(f, "mesh face {k}"),
        }
    }
}

/// One flat panel of a strip.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Where it is in the mesh.
    pub source: PanelSource,
    /// The mesh vertex of every corner, in the mesh's corner order.
    pub ids: Vec<usize>,
    /// The corners in 3D.
    pub corners: Vec<DVec3>,
    /// The placed corners (z = 0), in the same order.
    pub flat: Vec<DVec3>,
}

/// One unrolled strip (or a piece of one) as its chain of panels.
#[derive(Debug, Clone, PartialEq)]
pub struct StripPanels {
    /// The label written on the part (`D4`, `D9 (mirror of D2)`, `D4.2`).
    pub label: String,
    /// The strip's short name (the label's first word: `D4`, `D9`, `D4.2`).
    pub name: String,
    /// The panels in strip order; panel k shares a rung (a fold) with panel k + 1.
    pub panels: Vec<Panel>,
    /// The number in the strip of panel 0 (0 unless this is a later piece of a split strip).
    pub first_panel: usize,
    /// The collapsed edges (panel numbers of this chain: of the piece for a piece).
    pub collapsed: Vec<CollapsedEdge>,
}

/// The short name of a label: its first word.
pub fn short_name(label: &str) -> String {
    label.split_whitespace().next().unwrap_or(label).to_string()
}

/// The panels of quad-grid strips unrolled by [`super::unroll_strips`].
pub fn grid_panels(mesh: &QuadGrid, unrolled: &Unrolled) -> Vec<StripPanels> {
    let cols = mesh.cols;
    unrolled
        .strips
        .iter()
        .map(|s| StripPanels {
            label: s.label.clone(),
            name: short_name(&s.label),
            panels: s
                .quads
                .iter()
                .zip(&s.mesh_quads)
                .map(|(flat, &(i, j))| {
                    let (i1, j1) = ((i + 1) % mesh.rows, (j + 1) % cols);
                    let ids = vec![i * cols + j, i * cols + j1, i1 * cols + j1, i1 * cols + j];
                    Panel {
                        source: PanelSource::Quad(i, j),
                        corners: ids.iter().map(|&v| mesh.vertices[v]).collect(),
                        ids,
                        flat: flat.to_vec(),
                    }
                })
                .collect(),
            first_panel: 0,
            collapsed: s.collapsed.clone(),
        })
        .collect()
}

/// The panels of polygon-mesh strips unrolled by [`super::unroll_mesh_strips`].
pub fn mesh_panels(mesh: &PolygonMesh, unrolled: &UnrolledMesh) -> Vec<StripPanels> {
    unrolled
        .strips
        .iter()
        .map(|s| StripPanels {
            label: s.label.clone(),
            name: short_name(&s.label),
            panels: s
                .faces
                .iter()
                .zip(&s.mesh_faces)
                .map(|(flat, &f)| {
                    let ids: Vec<usize> = mesh.face(f).iter().map(|&v| v as usize).collect();
                    Panel {
                        source: PanelSource::Face(f),
                        corners: ids.iter().map(|&v| mesh.vertices[v]).collect(),
                        ids,
                        flat: flat.clone(),
                    }
                })
                .collect(),
            first_panel: 0,
            collapsed: s.collapsed.clone(),
        })
        .collect()
}

/// The corners (positions in `a`, then in `b`) of the edge panels `a` and `b` share: the rung
/// between consecutive panels of a strip. `None` when they share no edge.
pub fn shared_edge(a: &Panel, b: &Panel) -> Option<([usize; 2], [usize; 2])> {
    let n = a.ids.len();
    (0..n).find_map(|t| {
        let (u, w) = (a.ids[t], a.ids[(t + 1) % n]);
        let m = b.ids.len();
        let pu = b.ids.iter().position(|&x| x == u)?;
        let pw = b.ids.iter().position(|&x| x == w)?;
        ((pu + 1) % m == pw || (pw + 1) % m == pu).then_some(([t, (t + 1) % n], [pu, pw]))
    })
}

/// The closed outline of a chain of placed panels: the boundary of their union, edges shared by
/// two panels cancelled (by mesh vertex and placed position), counter-clockwise. `None` when the
/// boundary is not one loop.
pub fn outline_of(panels: &[Panel]) -> Option<Polyline> {
    type Key = (usize, u64, u64);
    let key = |c: usize, p: DVec3| -> Key { (c, p.x.to_bits(), p.y.to_bits()) };
    let mut directed: Vec<(Key, Key, DVec3)> = Vec::new();
    for p in panels {
        let mut corners: Vec<(usize, DVec3)> =
            p.ids.iter().copied().zip(p.flat.iter().copied()).collect();
        let flat: Vec<DVec2> = p.flat.iter().map(|q| q.truncate()).collect();
        let area2: f64 = (0..flat.len())
            .map(|i| flat[i].perp_dot(flat[(i + 1) % flat.len()]))
            .sum();
        if area2 < 0.0 {
            corners.reverse();
        }
        for t in 0..corners.len() {
            let (a, b) = (corners[t], corners[(t + 1) % corners.len()]);
            directed.push((key(a.0, a.1), key(b.0, b.1), a.1));
        }
    }
    let (points, edges) = super::boundary::boundary_loop(&directed);
    (points.len() == edges && points.len() >= 3).then(|| Polyline::closed(points))
}
