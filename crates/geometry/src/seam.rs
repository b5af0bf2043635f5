//! The seam between two meshes (`measure.seam`): where their boundaries meet, how far apart they
//! are there, and how long the seam is.
//!
//! A boundary vertex of one mesh lies *on the seam* when it is within the search distance of the
//! other mesh's boundary **and** it is the nearest point of its own boundary to the point of the
//! other boundary it is nearest to (mutual nearness). The second condition keeps a dense net's
//! side vertices near a shared corner out: the corner of the other mesh is nearest to them, but
//! their own corner is nearer to it, so a seam shared vertex for vertex reads exactly 0 however
//! fine the nets are. The boundaries are `parry3d-f64` polylines (a BVH over their segments), so a
//! query costs about O(log n).

use glam::DVec3;
use parry3d_f64::math::Vector as ParryVector;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::Polyline as ParryPolyline;
use rayon::prelude::*;

use crate::{GeometryError, PolygonMesh};

/// What [`seam`] measures.
#[derive(Debug, Clone, PartialEq)]
pub struct Seam {
    /// The largest distance from a seam vertex (of either mesh) to the other mesh's boundary.
    pub max_gap: f64,
    /// The seam's length along the first mesh's boundary (its boundary edges with both ends on the
    /// seam).
    pub length: f64,
    /// The seam's vertices of the first mesh, then those of the second, each in vertex order.
    pub points: Vec<DVec3>,
}

/// The boundary of a mesh: its edges used by exactly one face, and the vertices they touch.
struct Boundary {
    /// Boundary edges as vertex-index pairs.
    edges: Vec<[u32; 2]>,
    /// The vertices on the boundary, in index order.
    vertices: Vec<u32>,
    /// The boundary as a polyline with a BVH over its segments.
    shape: ParryPolyline,
}

fn to_parry(p: DVec3) -> ParryVector {
    ParryVector::new(p.x, p.y, p.z)
}

impl Boundary {
    fn of(mesh: &PolygonMesh, what: &'static str) -> Result<Self, GeometryError> {
        mesh.validate()?;
        crate::error::check_finite_points(what, &mesh.vertices)?;
        // Every edge as one sorted key; a key met once is a boundary edge (a sort, not a hash
        // map: a 1000 × 1000 net has four million edge uses).
        let mut keys: Vec<u64> = Vec::with_capacity(mesh.indices.len());
        for face in mesh.faces() {
            for k in 0..face.len() {
                let (a, b) = (face[k], face[(k + 1) % face.len()]);
                if a != b {
                    keys.push((u64::from(a.min(b)) << 32) | u64::from(a.max(b)));
                }
            }
        }
        keys.par_sort_unstable();
        let edges: Vec<[u32; 2]> = keys
            .chunk_by(|x, y| x == y)
            .filter(|run| run.len() == 1)
            .map(|run| [(run[0] >> 32) as u32, run[0] as u32])
            .collect();
        if edges.is_empty() {
            return Err(GeometryError::Degenerate(format!(
                "{what} has no boundary (no faces, or a closed surface): a seam runs along a boundary"
            )));
        }
        let mut vertices: Vec<u32> = edges.iter().flatten().copied().collect();
        vertices.sort_unstable();
        vertices.dedup();
        // The polyline holds the boundary's vertices only (a 1000 × 1000 net: 4 000, not 10⁶).
        let mut local = vec![u32::MAX; mesh.vertices.len()];
        for (k, &v) in vertices.iter().enumerate() {
            local[v as usize] = k as u32;
        }
        let shape = ParryPolyline::new(
            vertices
                .iter()
                .map(|&v| to_parry(mesh.vertices[v as usize]))
                .collect(),
            Some(
                edges
                    .iter()
                    .map(|&[a, b]| [local[a as usize], local[b as usize]])
                    .collect(),
            ),
        );
        Ok(Self {
            edges,
            vertices,
            shape,
        })
    }

    /// The nearest point of this boundary to `p`.
    fn nearest(&self, p: DVec3) -> DVec3 {
        let q = self.shape.project_local_point(to_parry(p), false).point;
        DVec3::new(q.x, q.y, q.z)
    }
}

/// The seam vertices of `own` (a boundary of `mesh`) against `other`, with their gaps.
fn seam_side(
    mesh: &PolygonMesh,
    own: &Boundary,
    other: &Boundary,
    search: f64,
    tolerance: f64,
) -> Vec<(u32, f64)> {
    own.vertices
        .iter()
        .filter_map(|&k| {
            let v = mesh.vertices[k as usize];
            let p = other.nearest(v);
            let gap = v.distance(p);
            let mutual = own.nearest(p).distance(p) >= gap - tolerance;
            (gap <= search && mutual).then_some((k, gap))
        })
        .collect()
}

/// The bounding-box diagonal of a mesh's vertices.
pub fn diagonal(mesh: &PolygonMesh) -> f64 {
    let (lo, hi) = mesh.vertices.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if mesh.vertices.is_empty() {
        0.0
    } else {
        lo.distance(hi)
    }
}

/// Measures the seam between meshes `a` and `b`: the boundary vertices of each within `search` of
/// the other's boundary (and mutually nearest, see the module doc). `search` defaults to 1 % of
/// the larger mesh's bounding-box diagonal. No vertex on the seam is an error that says how near
/// the boundaries come.
pub fn seam(a: &PolygonMesh, b: &PolygonMesh, search: Option<f64>) -> Result<Seam, GeometryError> {
    let (ba, bb) = (Boundary::of(a, "mesh a")?, Boundary::of(b, "mesh b")?);
    let size = diagonal(a).max(diagonal(b));
    let search = match search {
        Some(s) if s.is_finite() && s >= 0.0 => s,
        Some(s) => {
            return Err(GeometryError::InvalidParameter {
                what: "search",
                value: s,
                expected: "a finite distance ≥ 0",
            });
        }
        None => 0.01 * size,
    };
    let tolerance = 1e-12 * size.max(f64::MIN_POSITIVE);
    let on_a = seam_side(a, &ba, &bb, search, tolerance);
    let on_b = seam_side(b, &bb, &ba, search, tolerance);
    if on_a.is_empty() && on_b.is_empty() {
        let nearest = ba
            .vertices
            .iter()
            .map(|&k| {
                let v = a.vertices[k as usize];
                v.distance(bb.nearest(v))
            })
            .fold(f64::INFINITY, f64::min);
        return Err(GeometryError::Degenerate(format!(
            "no seam: no boundary vertex of either mesh lies within search ({search:.6}) of the \
             other's boundary (the nearest is {nearest:.6} away)"
        )));
    }
    let max_gap = on_a
        .iter()
        .chain(&on_b)
        .map(|&(_, g)| g)
        .fold(0.0, f64::max);
    let mut on_seam = vec![false; a.vertices.len()];
    on_a.iter().for_each(|&(k, _)| on_seam[k as usize] = true);
    let length = ba
        .edges
        .iter()
        .filter(|[p, q]| on_seam[*p as usize] && on_seam[*q as usize])
        .map(|&[p, q]| a.vertices[p as usize].distance(a.vertices[q as usize]))
        .sum();
    let points = on_a
        .iter()
        .map(|&(k, _)| a.vertices[k as usize])
        .chain(on_b.iter().map(|&(k, _)| b.vertices[k as usize]))
        .collect();
    Ok(Seam {
        max_gap,
        length,
        points,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::QuadGrid;

    /// A rows × cols grid over [0, w] × [0, h] in the plane z = 0, moved by `offset`.
    fn sheet(rows: usize, cols: usize, w: f64, h: f64, offset: DVec3) -> PolygonMesh {
        let points = (0..rows)
            .flat_map(|i| {
                (0..cols).map(move |j| {
                    DVec3::new(
                        w * j as f64 / (cols - 1) as f64,
                        h * i as f64 / (rows - 1) as f64,
                        0.0,
                    ) + offset
                })
            })
            .collect();
        PolygonMesh::from(&QuadGrid::new(rows, cols, points).unwrap())
    }

    #[test]
    fn a_seam_shared_vertex_for_vertex_reads_zero_even_on_dense_nets() {
        for cols in [3, 50, 400] {
            let a = sheet(5, cols, 2.0, 1.0, DVec3::ZERO);
            let b = sheet(5, cols, 2.0, 1.0, DVec3::new(2.0, 0.0, 0.0));
            let s = seam(&a, &b, None).unwrap();
            assert_eq!(s.max_gap, 0.0, "{cols} columns");
            assert!((s.length - 1.0).abs() < 1e-12, "{}", s.length);
            assert_eq!(s.points.len(), 10, "5 vertices a side");
        }
    }

    #[test]
    fn nets_moved_a_centimetre_apart_read_a_centimetre() {
        let a = sheet(6, 8, 4.0, 2.0, DVec3::ZERO);
        for offset in [
            DVec3::new(4.01, 0.0, 0.0),
            DVec3::new(4.0, 0.0, 0.01),
            DVec3::new(4.0, 0.0, -0.01),
        ] {
            let b = sheet(6, 8, 4.0, 2.0, offset);
            let s = seam(&a, &b, None).unwrap();
            assert!((s.max_gap - 0.01).abs() < 1e-12, "{offset}: {}", s.max_gap);
            assert!((s.length - 2.0).abs() < 1e-12);
        }
        // Out of a smaller search: no seam, and the error says how near they come.
        let b = sheet(6, 8, 4.0, 2.0, DVec3::new(4.01, 0.0, 0.0));
        let e = seam(&a, &b, Some(0.005)).unwrap_err().to_string();
        assert!(e.contains("no seam") && e.contains("0.01"), "{e}");
    }

    #[test]
    fn a_closed_surface_and_bad_searches_are_errors() {
        let a = sheet(3, 3, 1.0, 1.0, DVec3::ZERO);
        let b = sheet(3, 3, 1.0, 1.0, DVec3::X);
        for bad in [f64::NAN, -1.0, f64::INFINITY] {
            assert!(seam(&a, &b, Some(bad)).is_err());
        }
        let empty = PolygonMesh::default();
        assert!(seam(&a, &empty, None).is_err());
    }
}
