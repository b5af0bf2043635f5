//! Unrolling PQ strips (PQ Strip Unroll, paper Sec. 4.4.2, notes §7).
//!
//! Each strip is laid flat quad after quad, each sharing its first rung with the previous one (an
//! isometry per quad). Quad k, with corners in the mesh's own order, gets the frame
//! `o = a_k`, `e1 = (b_k − a_k)/|b_k − a_k|` (its first rung), `n` = its unit Newell normal,
//! `e2 = unit(n × e1)`, and local coordinates `((p − o)·e1, (p − o)·e2)`. The local frame is mapped
//! onto the already placed rung `A_k B_k` by the rotation that takes e1 to `u = (B_k − A_k)/|B_k − A_k|`
//! and e2 to `u` turned a quarter counter-clockwise, so the quad keeps its orientation (seen from its
//! normal side) and lies across the rung from its predecessor; the far rung `A_{k+1} B_{k+1}` is
//! placed by that map. The first rung is laid on the x axis from the origin.
//!
//! For a planar quad the map is an isometry: its edge lengths and angles are kept to rounding error.
//! Quads whose planarity (libigl measure) exceeds `tolerance` are rejected with an error naming the
//! strip and the quad; below that the projection onto the Newell plane is used and the result reports
//! the largest relative edge-length change (`max_length_error`; an edge collapsed to less than
//! [`super::COLLAPSED_EDGE`] of the mesh size is measured against the mesh size and listed in
//! [`UnrolledStrip::collapsed`], see [`super::collapsed`]). Closed strips are cut open at their
//! first rung, which then appears at both ends.
//!
//! The flat strips are laid out by [`super::layout::stack`]: turned so their minimum-area rectangle is
//! axis-aligned (long side along x) and stacked along +y with a gap, so no two strips overlap.

use glam::{DVec2, DVec3};

use super::FabricationError;
use super::collapsed::{CollapsedEdge, edge_error};
use super::layout;
use super::polygon::newell;
use super::strips::{Strip, StripDirection, strips};
use crate::conenet::quad_planarity;
use crate::{Polyline, QuadGrid};

/// Options of [`unroll_strips`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnrollOptions {
    /// Largest accepted quad planarity (libigl measure, relative to the diagonals); default 1e-6.
    pub tolerance: f64,
    /// Gap between the bounding boxes of consecutive strips; `None`: a tenth of the widest strip's
    /// height (its short side).
    pub spacing: Option<f64>,
}

impl Default for UnrollOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-6,
            spacing: None,
        }
    }
}

/// One strip laid flat in the XY plane.
#[derive(Debug, Clone, PartialEq)]
pub struct UnrolledStrip {
    /// Strip index.
    pub index: usize,
    /// `D<i>` or `G<j>`.
    pub label: String,
    /// The closed outline: the a-side rung ends from the first to the last rung, then the b-side
    /// back (z = 0).
    pub outline: Polyline,
    /// Where to put the label: the midpoint of the middle rung (inside the strip).
    pub label_point: DVec3,
    /// The placed corners of every quad, in the mesh's corner order (z = 0).
    pub quads: Vec<[DVec3; 4]>,
    /// The mesh quad (row, column) of every placed quad.
    pub mesh_quads: Vec<(usize, usize)>,
    /// Largest relative edge-length change in this strip (collapsed edges: relative to the mesh
    /// size).
    pub max_length_error: f64,
    /// The edges of this strip collapsed to less than [`super::COLLAPSED_EDGE`] of the mesh size.
    pub collapsed: Vec<CollapsedEdge>,
}

/// All strips of one direction, unrolled and laid out.
#[derive(Debug, Clone, PartialEq)]
pub struct Unrolled {
    /// The strips, in strip order.
    pub strips: Vec<UnrolledStrip>,
    /// Largest relative edge-length change over all strips (≤ 1e-9 for a planar mesh).
    pub max_length_error: f64,
}

/// A strip placed flat but not yet laid out: rung ends A_k, B_k (k = 0 … rungs, with the first rung
/// repeated at the end of a closed strip) and the placed quads.
struct Flat {
    a: Vec<DVec2>,
    b: Vec<DVec2>,
    quads: Vec<[DVec2; 4]>,
    max_length_error: f64,
    collapsed: Vec<CollapsedEdge>,
}

/// Places one strip flat.
fn flatten(
    mesh: &QuadGrid,
    strip: &Strip,
    strip_no: usize,
    tolerance: f64,
    scale: f64,
) -> Result<Flat, FabricationError> {
    let v = &mesh.vertices;
    let count = strip.quad_count();
    let r0 = strip.rungs[0];
    let first = v[r0.1].distance(v[r0.0]);
    let mut a = vec![DVec2::ZERO];
    let mut b = vec![DVec2::new(first, 0.0)];
    let mut quads = Vec::with_capacity(count);
    let mut max_err = 0.0f64;
    let mut collapsed = Vec::new();
    for k in 0..count {
        let (row, column) = strip.mesh_quad(k);
        let idx = strip.quad_indices(k);
        let corners = idx.map(|i| v[i]);
        let planarity = quad_planarity(corners);
        if !(planarity <= tolerance) {
            return Err(FabricationError::NonPlanarFace {
                strip: strip_no,
                quad: k,
                row,
                column,
                planarity,
                tolerance,
            });
        }
        let degenerate = |reason: &str| FabricationError::DegenerateFace {
            what: "unroll",
            face: k,
            reason: format!("strip {strip_no}, mesh quad at row {row}, column {column}: {reason}"),
        };
        let n = newell(&corners).ok_or_else(|| degenerate("it has no area"))?;
        let (ra, rb) = strip.quad_rungs(k);
        let o = v[ra.0];
        let rung = v[ra.1] - o;
        let e1 = rung
            .try_normalize()
            .ok_or_else(|| degenerate("its first rung has zero length"))?;
        let e2 = n
            .cross(e1)
            .try_normalize()
            .ok_or_else(|| degenerate("its first rung is perpendicular to its plane"))?;
        let local = |p: DVec3| DVec2::new((p - o).dot(e1), (p - o).dot(e2));
        let (pa, pb) = (a[k], b[k]);
        let u = (pb - pa)
            .try_normalize()
            .ok_or_else(|| degenerate("its first rung was placed with zero length"))?;
        let w = u.perp();
        let place = |p: DVec3| {
            let l = local(p);
            pa + u * l.x + w * l.y
        };
        let (na, nb) = (place(v[rb.0]), place(v[rb.1]));
        a.push(na);
        b.push(nb);
        let flat = idx.map(|i| {
            if i == ra.0 {
                pa
            } else if i == ra.1 {
                pb
            } else if i == rb.0 {
                na
            } else {
                nb
            }
        });
        for e in 0..4 {
            let l3 = corners[e].distance(corners[(e + 1) % 4]);
            let l2 = flat[e].distance(flat[(e + 1) % 4]);
            let (err, short) = edge_error(l3, l2, scale);
            if short {
                collapsed.push(CollapsedEdge {
                    panel: k,
                    edge: e,
                    length: l3,
                });
            }
            max_err = max_err.max(err);
        }
        quads.push(flat);
    }
    if !(max_err.is_finite()) || a.iter().chain(&b).any(|p| !p.is_finite()) {
        return Err(FabricationError::DegenerateFace {
            what: "unroll",
            face: 0,
            reason: format!("strip {strip_no}: the unrolled strip overflows"),
        });
    }
    Ok(Flat {
        a,
        b,
        quads,
        max_length_error: max_err,
        collapsed,
    })
}

/// Checks the tolerance and spacing of unroll options.
pub(crate) fn check_options(options: &UnrollOptions) -> Result<(), FabricationError> {
    if !(options.tolerance.is_finite() && options.tolerance >= 0.0) {
        return Err(FabricationError::BadParameter {
            what: "tolerance",
            value: options.tolerance,
            expected: "a finite number ≥ 0",
        });
    }
    if let Some(s) = options.spacing
        && !(s.is_finite() && s >= 0.0)
    {
        return Err(FabricationError::BadParameter {
            what: "spacing",
            value: s,
            expected: "a finite number ≥ 0",
        });
    }
    Ok(())
}

/// Unrolls every strip of `mesh` in `direction` and lays the strips out side by side.
pub fn unroll_strips(
    mesh: &QuadGrid,
    direction: StripDirection,
    options: UnrollOptions,
) -> Result<Unrolled, FabricationError> {
    check_options(&options)?;
    let list = strips(mesh, direction)?;
    if list.is_empty() {
        return Err(FabricationError::Empty("the strip list"));
    }
    let scale = mesh.size().max(f64::MIN_POSITIVE);
    let flats = list
        .iter()
        .enumerate()
        .map(|(n, s)| flatten(mesh, s, n, options.tolerance, scale))
        .collect::<Result<Vec<_>, _>>()?;
    // Lay out the outlines; the same rigid map moves the quads.
    let mut shapes: Vec<Vec<DVec2>> = flats
        .iter()
        .map(|f| f.a.iter().chain(f.b.iter().rev()).copied().collect())
        .collect();
    let gap = options
        .spacing
        .unwrap_or_else(|| layout::default_gap(&shapes));
    let maps = layout::stack(&mut shapes, gap);
    let to3 = |p: DVec2| DVec3::new(p.x, p.y, 0.0);
    let mut out = Vec::with_capacity(list.len());
    let mut max_length_error = 0.0f64;
    for ((strip, flat), (shape, (angle, shift))) in
        list.iter().zip(&flats).zip(shapes.into_iter().zip(maps))
    {
        let moved = |p: DVec2| to3(layout::rotate(p, angle) + shift);
        let mid = flat.a.len() / 2;
        let label_point = (moved(flat.a[mid]) + moved(flat.b[mid])) * 0.5;
        max_length_error = max_length_error.max(flat.max_length_error);
        out.push(UnrolledStrip {
            index: strip.index,
            label: strip.label(),
            outline: Polyline::closed(shape.into_iter().map(to3).collect()),
            label_point,
            quads: flat.quads.iter().map(|q| q.map(moved)).collect(),
            mesh_quads: (0..strip.quad_count())
                .map(|k| strip.mesh_quad(k))
                .collect(),
            max_length_error: flat.max_length_error,
            collapsed: flat.collapsed.clone(),
        });
    }
    Ok(Unrolled {
        strips: out,
        max_length_error,
    })
}
