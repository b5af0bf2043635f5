//! The symmetric distance between a mesh and a reference surface, for fitting (paper Fig. 10a).
//!
//! A one-sided measure — from the mesh's vertices to the reference — lets a fitted mesh pull away
//! from the hard regions of the reference: nothing measures how far the *reference* lies from the
//! mesh. This module measures both directions, each on points sampled over the faces (not only
//! the vertices):
//!
//! - **to the reference**: the area-weighted mean of d(s, R)² over samples s on the mesh's faces,
//!   and the largest d over those samples and the mesh's vertices;
//! - **from the reference**: the same with samples r on the reference's faces and d(r, M), the
//!   distance to the mesh.
//!
//! Every polygon is fanned into triangles (`[v0, v_c, v_{c+1}]`, as [`MeshQuery`] does); each
//! triangle is split into n² equal sub-triangles (n = `samples`) and sampled at their centroids,
//! each weighted by its area over the mesh's total area: the mean is the midpoint rule for
//! (1/A) ∫ d² dA. The symmetric measure is the mean of the two means; its largest distance is the
//! sampled Hausdorff distance.
//!
//! The gradient with respect to the mesh's vertices is exact (piecewise: on the closest triangles
//! found). Towards the reference, d(s)² changes by 2 (s − c) · ds (c the closest point, fixed to
//! first order), s a fixed barycentric combination of its triangle's corners, and the triangles'
//! areas move the weights. From the reference, d(r)² = min over the closest triangle's barycentric
//! coordinates (u_k) of |r − Σ u_k v_k|², whose derivative in corner v_k is 2 u_k (c − r).

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh_query::MeshQuery;
use crate::{GeometryError, PolygonMesh};

/// The most sub-triangles per triangle edge ([`surface_samples`]'s `n`).
pub const MAX_SAMPLES: usize = 64;

/// A point sampled on a mesh: a fixed barycentric combination of one triangle's corners.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The point.
    pub point: DVec3,
    /// The vertex indices of its triangle (all three the same for a vertex sample).
    pub corners: [u32; 3],
    /// Its barycentric coordinates in that triangle.
    pub bary: [f64; 3],
    /// Its fan triangle (index into [`fan_triangles`]); `None` for a vertex sample.
    pub triangle: Option<usize>,
    /// Its weight in the mean (the sub-triangle's area over the mesh's area; 0 for a vertex
    /// sample, which counts for the largest distance only).
    pub weight: f64,
}

/// The triangles of a mesh's polygons, fanned from each polygon's first corner.
pub fn fan_triangles(mesh: &PolygonMesh) -> Vec<[u32; 3]> {
    mesh.faces()
        .flat_map(|f| (1..f.len() - 1).map(move |c| [f[0], f[c], f[c + 1]]))
        .collect()
}

/// The area of triangle (a, b, c).
pub fn triangle_area(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    0.5 * (b - a).cross(c - a).length()
}

/// The barycentric coordinates (u, v, w) of the centroids of the n² sub-triangles of a triangle
/// split n times along each edge, in a fixed order.
pub fn sub_triangle_centroids(n: usize) -> Vec<[f64; 3]> {
    let nf = n as f64;
    let mut out = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n - i {
            // Upward sub-triangle (i, j), (i + 1, j), (i, j + 1).
            let (u, v) = ((i as f64 + 1.0 / 3.0) / nf, (j as f64 + 1.0 / 3.0) / nf);
            out.push([1.0 - u - v, u, v]);
            if i + j + 2 <= n {
                // Downward sub-triangle (i + 1, j), (i, j + 1), (i + 1, j + 1).
                let (u, v) = ((i as f64 + 2.0 / 3.0) / nf, (j as f64 + 2.0 / 3.0) / nf);
                out.push([1.0 - u - v, u, v]);
            }
        }
    }
    out
}

fn check_samples(n: usize) -> Result<(), GeometryError> {
    if n == 0 || n > MAX_SAMPLES {
        return Err(GeometryError::InvalidParameter {
            what: "samples",
            value: n as f64,
            expected: "a whole number from 1 to 64",
        });
    }
    Ok(())
}

/// The samples of a mesh: n² per fan triangle (area-weighted, weights summing to 1), then one per
/// vertex used by a face (weight 0). Fails on a mesh without area.
pub fn surface_samples(mesh: &PolygonMesh, n: usize) -> Result<Vec<Sample>, GeometryError> {
    check_samples(n)?;
    mesh.validate()?;
    crate::error::check_finite_points("mesh", &mesh.vertices)?;
    let v = &mesh.vertices;
    let triangles = fan_triangles(mesh);
    let areas: Vec<f64> = triangles
        .iter()
        .map(|t| triangle_area(v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]))
        .collect();
    let total: f64 = areas.iter().sum();
    if !(total > 0.0 && total.is_finite()) {
        return Err(GeometryError::Degenerate(
            "a surface distance needs a mesh with area".into(),
        ));
    }
    let pattern = sub_triangle_centroids(n);
    let per = 1.0 / (n * n) as f64 / total;
    let mut samples = Vec::with_capacity(triangles.len() * pattern.len() + v.len());
    for (k, (t, area)) in triangles.iter().zip(&areas).enumerate() {
        let (a, b, c) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
        for bary in &pattern {
            samples.push(Sample {
                point: a * bary[0] + b * bary[1] + c * bary[2],
                corners: *t,
                bary: *bary,
                triangle: Some(k),
                weight: area * per,
            });
        }
    }
    let mut used = vec![false; v.len()];
    for &i in &mesh.indices {
        used[i as usize] = true;
    }
    for (i, p) in v.iter().enumerate().filter(|(i, _)| used[*i]) {
        samples.push(Sample {
            point: *p,
            corners: [i as u32; 3],
            bary: [1.0, 0.0, 0.0],
            triangle: None,
            weight: 0.0,
        });
    }
    Ok(samples)
}

/// The barycentric coordinates of the point of triangle (a, b, c) closest to p (the regions of
/// [`crate::measure::closest_point_on_triangle`]).
pub fn closest_barycentric(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        return [1.0 - t, t, 0.0];
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        return [1.0 - t, 0.0, t];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - t, t];
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE {
        // A degenerate triangle: the closest point of its edges.
        let edges = [(0, 1), (1, 2), (2, 0)];
        let corners = [a, b, c];
        let mut best = ([1.0, 0.0, 0.0], f64::INFINITY);
        for (s, e) in edges {
            let d = corners[e] - corners[s];
            let len2 = d.length_squared();
            let t = if len2 <= f64::MIN_POSITIVE {
                0.0
            } else {
                ((p - corners[s]).dot(d) / len2).clamp(0.0, 1.0)
            };
            let q = corners[s] + d * t;
            let dist = q.distance_squared(p);
            if dist < best.1 {
                let mut w = [0.0; 3];
                w[s] = 1.0 - t;
                w[e] = t;
                best = (w, dist);
            }
        }
        return best.0;
    }
    let (v, w) = (vb / denom, vc / denom);
    [1.0 - v - w, v, w]
}

/// The two directions of the distance between a mesh and a reference surface ([module
/// docs](self)).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceDistances {
    /// Area-weighted mean of the squared distances from the mesh's face samples to the reference.
    pub to_reference: f64,
    /// The largest distance from the mesh's samples and vertices to the reference.
    pub to_reference_max: f64,
    /// Area-weighted mean of the squared distances from the reference's face samples to the mesh.
    pub from_reference: f64,
    /// The largest distance from the reference's samples and vertices to the mesh.
    pub from_reference_max: f64,
}

impl SurfaceDistances {
    /// The symmetric measure: the mean of the two directions' means.
    pub fn symmetric(&self) -> f64 {
        0.5 * (self.to_reference + self.from_reference)
    }

    /// The sampled Hausdorff distance: the larger of the two directions' largest distances.
    pub fn hausdorff(&self) -> f64 {
        self.to_reference_max.max(self.from_reference_max)
    }
}

/// Which directions to measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Directions {
    /// From the mesh to the reference.
    pub to_reference: bool,
    /// From the reference to the mesh.
    pub from_reference: bool,
}

impl Directions {
    /// Both directions.
    pub const BOTH: Directions = Directions {
        to_reference: true,
        from_reference: true,
    };
}

fn query(mesh: &PolygonMesh, what: &str) -> Result<MeshQuery, GeometryError> {
    MeshQuery::new(mesh).map_err(|e| GeometryError::Degenerate(format!("{what}: {e}")))
}

/// Weighted mean of squared distances and largest distance over samples.
fn aggregate(samples: &[Sample], distances: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut mean, mut max) = (0.0, 0.0f64);
    for (s, d) in samples.iter().zip(distances) {
        mean += s.weight * d * d;
        max = max.max(d);
    }
    (mean, max)
}

/// Both directions of the distance between `mesh` and `reference` (the directions not asked for
/// stay 0), with `samples` sub-triangles per triangle edge (1 to [`MAX_SAMPLES`]). The sums run in
/// sample order, so the result does not depend on the thread count.
pub fn surface_distances(
    mesh: &PolygonMesh,
    reference: &PolygonMesh,
    samples: usize,
    directions: Directions,
) -> Result<SurfaceDistances, GeometryError> {
    let mut out = SurfaceDistances::default();
    if directions.to_reference {
        let on_mesh = surface_samples(mesh, samples)?;
        let r = query(reference, "the reference mesh")?;
        let points: Vec<DVec3> = on_mesh.iter().map(|s| s.point).collect();
        let hits = r.closest_all(&points)?;
        (out.to_reference, out.to_reference_max) =
            aggregate(&on_mesh, hits.iter().map(|h| h.distance));
    }
    if directions.from_reference {
        let on_reference = surface_samples(reference, samples)
            .map_err(|e| GeometryError::Degenerate(format!("the reference mesh: {e}")))?;
        let m = query(mesh, "the mesh")?;
        let points: Vec<DVec3> = on_reference.iter().map(|s| s.point).collect();
        let hits = m.closest_all(&points)?;
        (out.from_reference, out.from_reference_max) =
            aggregate(&on_reference, hits.iter().map(|h| h.distance));
    }
    Ok(out)
}

/// The cotangents of [`SurfaceDistances`]' four numbers (∂objective/∂each).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DistanceCotangents {
    /// Of `to_reference`.
    pub to_reference: f64,
    /// Of `to_reference_max`.
    pub to_reference_max: f64,
    /// Of `from_reference`.
    pub from_reference: f64,
    /// Of `from_reference_max`.
    pub from_reference_max: f64,
}

fn add_area_gradient(g: &mut [DVec3], v: &[DVec3], t: [u32; 3], scale: f64) {
    let (a, b, c) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
    let n = (b - a).cross(c - a);
    let len = n.length();
    if len <= f64::MIN_POSITIVE {
        return;
    }
    let n = n / len;
    // ∂A/∂a = ½ (b − c) × n̂, cyclically.
    g[t[0] as usize] += (b - c).cross(n) * (0.5 * scale);
    g[t[1] as usize] += (c - a).cross(n) * (0.5 * scale);
    g[t[2] as usize] += (a - b).cross(n) * (0.5 * scale);
}

fn scatter(g: &mut [DVec3], corners: [u32; 3], bary: [f64; 3], d: DVec3) {
    for (k, &i) in corners.iter().enumerate() {
        if bary[k] != 0.0 {
            g[i as usize] += d * bary[k];
        }
    }
}

/// The gradient of `Σ cotangent · measure` ([`surface_distances`]) with respect to the mesh's
/// vertices (exact on the closest triangles found; at the largest distance, the derivative of
/// the sample that attains it).
pub fn surface_distances_gradient(
    mesh: &PolygonMesh,
    reference: &PolygonMesh,
    samples: usize,
    c: DistanceCotangents,
) -> Result<Vec<DVec3>, GeometryError> {
    let v = &mesh.vertices;
    let mut g = vec![DVec3::ZERO; v.len()];
    if c.to_reference != 0.0 || c.to_reference_max != 0.0 {
        let on_mesh = surface_samples(mesh, samples)?;
        let r = query(reference, "the reference mesh")?;
        let points: Vec<DVec3> = on_mesh.iter().map(|s| s.point).collect();
        let hits = r.closest_all(&points)?;
        if c.to_reference != 0.0 {
            let (mean, _) = aggregate(&on_mesh, hits.iter().map(|h| h.distance));
            let triangles = fan_triangles(mesh);
            let total: f64 = triangles
                .iter()
                .map(|t| triangle_area(v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]))
                .sum();
            // Per triangle: Σ over its samples of d² / n² (the triangle's mean of d²).
            let mut tri_mean = vec![0.0; triangles.len()];
            let per = 1.0 / (samples * samples) as f64;
            for (s, h) in on_mesh.iter().zip(&hits) {
                if let Some(t) = s.triangle {
                    tri_mean[t] += h.distance * h.distance * per;
                    scatter(
                        &mut g,
                        s.corners,
                        s.bary,
                        (s.point - h.point) * (2.0 * s.weight * c.to_reference),
                    );
                }
            }
            // mean = Σ_t A_t m_t / Σ_t A_t: ∂/∂A_t = (m_t − mean) / A.
            for (t, m) in triangles.iter().zip(&tri_mean) {
                add_area_gradient(&mut g, v, *t, c.to_reference * (m - mean) / total);
            }
        }
        if c.to_reference_max != 0.0
            && let Some((k, h)) = hits
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.distance.total_cmp(&b.1.distance))
            && h.distance > 0.0
        {
            let s = &on_mesh[k];
            scatter(
                &mut g,
                s.corners,
                s.bary,
                (s.point - h.point) * (c.to_reference_max / h.distance),
            );
        }
    }
    if c.from_reference != 0.0 || c.from_reference_max != 0.0 {
        let on_reference = surface_samples(reference, samples)
            .map_err(|e| GeometryError::Degenerate(format!("the reference mesh: {e}")))?;
        let m = query(mesh, "the mesh")?;
        let points: Vec<DVec3> = on_reference.iter().map(|s| s.point).collect();
        let hits = m.closest_triangles(&points)?;
        let bary = |r: DVec3, t: [u32; 3]| {
            closest_barycentric(r, v[t[0] as usize], v[t[1] as usize], v[t[2] as usize])
        };
        if c.from_reference != 0.0 {
            let parts: Vec<([u32; 3], [f64; 3], DVec3)> = on_reference
                .par_iter()
                .zip(&hits)
                .filter(|(s, _)| s.weight != 0.0)
                .map(|(s, (h, t))| {
                    (
                        *t,
                        bary(s.point, *t),
                        (h.point - s.point) * (2.0 * s.weight * c.from_reference),
                    )
                })
                .collect();
            for (t, b, d) in parts {
                scatter(&mut g, t, b, d);
            }
        }
        if c.from_reference_max != 0.0
            && let Some((k, (h, t))) = hits
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.0.distance.total_cmp(&b.1.0.distance))
            && h.distance > 0.0
        {
            let r = on_reference[k].point;
            scatter(
                &mut g,
                *t,
                bary(r, *t),
                (h.point - r) * (c.from_reference_max / h.distance),
            );
        }
    }
    Ok(g)
}

#[cfg(test)]
mod tests;
