//! Row subdivision of a cone-net (`cnets.subdivide_rows`, paper Fig. 1: "the generatrix is further
//! subdivided in segments sweeping flat glass panels that pave the cone-net").
//!
//! Every row strip (rows i and i+1) is cut into `count` strips. On the first column the new vertices
//! divide the generatrix edge G_{i,0} G_{i+1,0} evenly; each further column is found by the central
//! projection through the apex of the coarse face between columns j−1 and j (the meeting point of
//! its two directrix-aligned edges, a point at infinity — a parallel projection — when they are
//! parallel) onto the coarse edge G_{i,j} G_{i+1,j}. So every fine vertex lies on a coarse edge,
//! every fine quad in the plane of its coarse face, and the fine directrix-aligned edges of a face
//! meet at the face's apex: the fine net is a cone-net with the same apices. The projection is
//! computed in homogeneous coordinates of the face plane, which treats a finite and an infinite apex
//! alike.

use glam::DVec3;
use rayon::prelude::*;

use crate::{GeometryError, QuadGrid};

/// The largest `count` accepted.
pub const MAX_COUNT: usize = 1024;
/// The largest number of vertices the subdivided mesh may have.
pub const MAX_VERTICES: usize = 1 << 27;

/// Subdivides every row strip of `mesh` into `count` strips (see the module docs). The result has
/// (N−1)·count + 1 rows (N·count when the rows wrap); coarse row i is fine row i·count, bit for bit.
/// Fails on `count` outside 1 … [`MAX_COUNT`], fewer than 2 rows, wrapping columns, non-finite
/// vertices, or a coarse face whose projection is undefined (collinear corners, the fine point at
/// the apex, a projection line parallel to the target edge).
pub fn subdivide_rows(mesh: &QuadGrid, count: usize) -> Result<QuadGrid, GeometryError> {
    mesh.validate()?;
    crate::error::check_finite_points("mesh", &mesh.vertices)?;
    if !(1..=MAX_COUNT).contains(&count) {
        return Err(GeometryError::InvalidParameter {
            what: "count",
            value: count as f64,
            expected: "an integer in 1 … 1024",
        });
    }
    if mesh.rows < 2 {
        return Err(GeometryError::TooFewPoints {
            what: "mesh rows",
            needed: 2,
            got: mesh.rows,
        });
    }
    if mesh.wrap_cols {
        return Err(GeometryError::Unsupported(
            "subdivide_rows needs a mesh whose columns do not wrap",
        ));
    }
    let (n, m) = (mesh.rows, mesh.cols);
    let strips = if mesh.wrap_rows { n } else { n - 1 };
    let fine_rows = strips * count + usize::from(!mesh.wrap_rows);
    if fine_rows.saturating_mul(m) > MAX_VERTICES {
        return Err(GeometryError::InvalidParameter {
            what: "count",
            value: count as f64,
            expected: "a count that keeps the mesh under 2^27 vertices",
        });
    }
    let mut vertices = vec![DVec3::ZERO; fine_rows * m];
    let fine: Result<(), GeometryError> =
        vertices
            .par_chunks_mut(m)
            .enumerate()
            .try_for_each(|(r, out)| {
                let (s, k) = (r / count, r % count);
                if k == 0 {
                    out.copy_from_slice(&mesh.vertices[(s % n) * m..(s % n + 1) * m]);
                    return Ok(());
                }
                let (i, i1) = (s, (s + 1) % n);
                let u = k as f64 / count as f64;
                let mut f = mesh.at(i, 0).lerp(mesh.at(i1, 0), u);
                out[0] = f;
                for (j, slot) in out.iter_mut().enumerate().skip(1) {
                    let from = [mesh.at(i, j - 1), mesh.at(i1, j - 1)];
                    let to = [mesh.at(i, j), mesh.at(i1, j)];
                    f = project(from, to, f).ok_or_else(|| no_projection(i, j - 1))?;
                    *slot = f;
                }
                Ok(())
            });
    fine?;
    Ok(QuadGrid {
        classes: Vec::new(),
        rows: fine_rows,
        cols: m,
        wrap_rows: mesh.wrap_rows,
        wrap_cols: false,
        vertices,
    })
}

/// The error of a coarse face (row i, column j) whose projection is undefined.
fn no_projection(i: usize, j: usize) -> GeometryError {
    GeometryError::Degenerate(format!(
        "subdivide_rows: the coarse face at row {i}, column {j} has no projection (collinear \
         corners, or the new vertex at its apex)"
    ))
}

/// The central projection of `f` (on the edge `from`) through the apex of the face `from`, `to` (the
/// meeting point of the lines from[0] to[0] and from[1] to[1]) onto the line of the edge `to`.
/// `None` when it is undefined.
fn project(from: [DVec3; 2], to: [DVec3; 2], f: DVec3) -> Option<DVec3> {
    let [p0, q0] = from;
    let [p1, q1] = to;
    let d = q1 - p1;
    if d == DVec3::ZERO {
        return Some(p1);
    }
    let h = [q0 - p0, p1 - p0, d, q1 - q0]
        .iter()
        .fold(0.0f64, |h, e| h.max(e.abs().max_element()));
    // The face's normal from its diagonals, a frame in its plane, homogeneous 2-D coordinates.
    let normal = ((q1 - p0).cross(q0 - p1)).normalize_or_zero();
    if normal == DVec3::ZERO {
        return None;
    }
    let e1 = normal.any_orthonormal_vector();
    let e2 = normal.cross(e1);
    let plane = |p: DVec3| {
        let v = (p - p0) / h;
        DVec3::new(v.dot(e1), v.dot(e2), 1.0)
    };
    let (a0, b0, a1, b1) = (plane(p0), plane(q0), plane(p1), plane(q1));
    let apex = a0.cross(a1).cross(b0.cross(b1));
    let ray = apex.cross(plane(f));
    let x = ray.cross(a1.cross(b1));
    // x = α a1 + β b1 with x.z = α + β; t = β / (α + β).
    let d2 = (b1 - a1).truncate();
    let beta = (x.truncate() - a1.truncate() * x.z).dot(d2) / d2.length_squared();
    let t = beta / x.z;
    if !t.is_finite() || apex == DVec3::ZERO || ray == DVec3::ZERO {
        return None;
    }
    Some(p1 + d * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn central_and_parallel_projections() {
        // A trapezoid with apex (0, 2, 0): the midpoint of the bottom edge projects to the midpoint
        // of the top edge; a point at ¼ projects to ¼.
        let from = [DVec3::new(-2.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0)];
        let to = [DVec3::new(-1.0, 1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
        let p = project(from, to, DVec3::new(-1.0, 0.0, 0.0)).unwrap();
        assert!((p - DVec3::new(-0.5, 1.0, 0.0)).length() < 1e-15, "{p}");
        // A skewed face, apex (0, 0, 4): the line from the apex through f hits the top edge.
        let from = [DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.0, 3.0, 0.0)];
        let apex = DVec3::new(0.0, 0.0, 4.0);
        let to = [from[0].lerp(apex, 0.5), from[1].lerp(apex, 0.25)];
        let f = from[0].lerp(from[1], 0.3);
        let p = project(from, to, f).unwrap();
        let expected_dir = (f - apex).normalize();
        assert!(((p - apex).normalize() - expected_dir).length() < 1e-14);
        // A parallelogram (apex at infinity): a parallel projection.
        let to = [DVec3::new(1.0, 0.0, 2.0), DVec3::new(0.0, 3.0, 2.0)];
        let p = project(from, to, f).unwrap();
        assert!(
            (p - (f + DVec3::new(0.0, 0.0, 2.0))).length() < 1e-14,
            "{p}"
        );
        // Collinear corners: undefined.
        let line = [DVec3::ZERO, DVec3::X];
        assert_eq!(
            project(line, [DVec3::X * 2.0, DVec3::X * 3.0], DVec3::X * 0.5),
            None
        );
    }

    #[test]
    fn rejects_bad_input() {
        let mesh = QuadGrid::new(2, 2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE]).unwrap();
        assert!(subdivide_rows(&mesh, 0).is_err());
        assert!(subdivide_rows(&mesh, MAX_COUNT + 1).is_err());
        assert!(subdivide_rows(&mesh.clone().with_wrap(false, true), 2).is_err());
        let one_row = QuadGrid::new(1, 2, vec![DVec3::ZERO, DVec3::X]).unwrap();
        assert!(subdivide_rows(&one_row, 2).is_err());
        let mut nan = mesh.clone();
        nan.vertices[3].x = f64::NAN;
        assert!(subdivide_rows(&nan, 2).is_err());
    }
}
