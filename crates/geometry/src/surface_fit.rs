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
//! **Sampling.** Every polygon is fanned into triangles (`[v0, v_c, v_{c+1}]`). With ℓ_t a
//! triangle's longest edge, h the *other* mesh's feature size (the mean longest edge of its
//! triangles) and r = ℓ_t / (f · h), f = [`FEATURE_RATIO`]: a triangle with r ≤ 1 (no larger
//! than the other mesh's facets, so the other surface is about flat over it and d about linear)
//! is integrated by the symmetric 3-point rule of degree 2 ([`SMALL_RULE`]), exact for d² when d
//! is linear; a larger one is split into n_t² equal sub-triangles, n_t = ⌈r⌉ clamped to
//! 1 … `samples`, each integrated by the symmetric 6-point rule of degree 4
//! ([`quadrature_rule`]), exact for d² while d is a quadratic over a sub-triangle — a flat face
//! over a curved reference, the case of a fit. All points are interior, all weights positive:
//! the mean is Σ_t A_t Σ_q w_q d(s_q)² / A. So an optimizer cannot lower the figure by bringing a
//! few sample points onto the reference while the face between them stays off it (as it could
//! with the sub-triangle centroids sampled before: 23 % low on a fitted hull). The symmetric measure is the mean of the two means; its largest distance is the sampled
//! Hausdorff distance.
//!
//! **Cost.** The closest points come from a [`TriangleBvh`] built once per direction over the
//! mesh measured to; the samples are never stored: fixed chunks of triangles run in parallel,
//! each query started from the previous sample's triangle, and the chunks' sums are added in
//! order (the result does not depend on the thread count). [`working_bytes`] is what a call
//! allocates at most, for a memory budget.
//!
//! The gradient with respect to the mesh's vertices is exact (piecewise: on the closest triangles
//! found, with each triangle's n_t held). Towards the reference, d(s)² changes by 2 (s − c) · ds
//! (c the closest point, fixed to first order), s a fixed barycentric combination of its
//! triangle's corners, and the triangles' areas move the weights. From the reference, d(r)² = min
//! over the closest triangle's barycentric coordinates (u_k) of |r − Σ u_k v_k|², whose
//! derivative in corner v_k is 2 u_k (c − r).

mod bvh;

pub use bvh::{Hit, TriangleBvh};

use glam::DVec3;
use rayon::prelude::*;

use crate::{GeometryError, PolygonMesh};

/// The most sub-triangles per triangle edge (the `samples` cap).
pub const MAX_SAMPLES: usize = 64;

/// A triangle is split so its sub-triangles' longest edges are at most this many times the other
/// mesh's feature size (the mean longest edge of its triangles).
pub const FEATURE_RATIO: f64 = 1.5;

/// Triangles a parallel task sweeps (fixed, so sums do not depend on the thread count).
const CHUNK: usize = 1024;

/// Chunks whose gradient parts are held at once before they are added in.
const BLOCK: usize = 64;

/// The symmetric 6-point quadrature rule of degree 4 on a triangle (Strang and Fix; Dunavant's
/// degree-4 rule): barycentric points and weights summing to 1. Exact for polynomials of degree
/// up to 4; every point is interior.
pub fn quadrature_rule() -> [([f64; 3], f64); 6] {
    let s10 = 10f64.sqrt();
    let r = (38.0 - 44.0 * (0.4f64).sqrt()).sqrt();
    let (a1, a2) = ((8.0 - s10 + r) / 18.0, (8.0 - s10 - r) / 18.0);
    let q = (213_125.0 - 53_320.0 * s10).sqrt();
    let (w1, w2) = ((620.0 + q) / 3720.0, (620.0 - q) / 3720.0);
    let (b1, b2) = (1.0 - 2.0 * a1, 1.0 - 2.0 * a2);
    [
        ([b1, a1, a1], w1),
        ([a1, b1, a1], w1),
        ([a1, a1, b1], w1),
        ([b2, a2, a2], w2),
        ([a2, b2, a2], w2),
        ([a2, a2, b2], w2),
    ]
}

/// The triangles of a mesh's polygons, fanned from each polygon's first corner.
pub fn fan_triangles(mesh: &PolygonMesh) -> Vec<[u32; 3]> {
    mesh.faces()
        .flat_map(|f| (1..f.len() - 1).map(move |c| [f[0], f[c], f[c + 1]]))
        .collect()
}

/// The number of fan triangles of a mesh (without building them).
pub fn fan_triangle_count(mesh: &PolygonMesh) -> usize {
    mesh.faces().map(|f| f.len().saturating_sub(2)).sum()
}

/// The area of triangle (a, b, c).
pub fn triangle_area(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    0.5 * (b - a).cross(c - a).length()
}

/// The longest edge of triangle (a, b, c).
pub fn longest_edge(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    a.distance(b).max(b.distance(c)).max(c.distance(a))
}

/// How a triangle with longest edge `longest` is sampled against a mesh of feature size
/// `feature` ([module docs](self)): 0 when it is no longer than [`FEATURE_RATIO`] · `feature`
/// (the whole triangle by the 3-point rule of degree 2), else its sub-triangles per edge,
/// ⌈longest / (FEATURE_RATIO · feature)⌉ within 1 … `cap` (each by the 6-point rule).
pub fn split_count(longest: f64, feature: f64, cap: usize) -> usize {
    let ratio = longest / (FEATURE_RATIO * feature);
    if !ratio.is_finite() {
        cap
    } else if ratio <= 1.0 + 1e-9 {
        // A ratio a hair above 1 (rounding) is 1.
        0
    } else {
        ((ratio - 1e-9).ceil() as usize).clamp(1, cap)
    }
}

/// The symmetric 3-point rule of degree 2 on a triangle (points (⅔, ⅙, ⅙) and its permutations,
/// weights ⅓): exact for polynomials of degree up to 2; every point is interior.
pub const SMALL_RULE: [([f64; 3], f64); 3] = [
    ([2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0], 1.0 / 3.0),
    ([1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0], 1.0 / 3.0),
    ([1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0], 1.0 / 3.0),
];

/// Calls `f(barycentric, fraction)` for every sample of a triangle sampled as [`split_count`]
/// says: with `n` = 0 the points of [`SMALL_RULE`], else `rule`'s points in each of the n²
/// sub-triangles, in a fixed order; the fractions sum to 1.
#[inline]
pub fn for_each_sample(n: usize, rule: &[([f64; 3], f64); 6], mut f: impl FnMut([f64; 3], f64)) {
    if n == 0 {
        for (b, w) in SMALL_RULE {
            f(b, w);
        }
        return;
    }
    let nf = n as f64;
    let per = 1.0 / (nf * nf);
    let mut sub = |p: [[f64; 2]; 3]| {
        for &(l, w) in rule {
            let u = (l[0] * p[0][0] + l[1] * p[1][0] + l[2] * p[2][0]) / nf;
            let v = (l[0] * p[0][1] + l[1] * p[1][1] + l[2] * p[2][1]) / nf;
            f([1.0 - u - v, u, v], w * per);
        }
    };
    for i in 0..n {
        for j in 0..n - i {
            let (x, y) = (i as f64, j as f64);
            sub([[x, y], [x + 1.0, y], [x, y + 1.0]]);
            if i + j + 2 <= n {
                sub([[x + 1.0, y], [x, y + 1.0], [x + 1.0, y + 1.0]]);
            }
        }
    }
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

/// Triangles a task sweeps with up to `cap` splits per edge: about [`CHUNK`] · 6 samples.
fn chunk_len(cap: usize) -> usize {
    (CHUNK / (cap * cap)).max(1)
}

/// A mesh checked and fanned: its triangles, their total area and its feature size.
struct Fanned<'a> {
    vertices: &'a [DVec3],
    triangles: Vec<[u32; 3]>,
    area: f64,
    feature: f64,
}

impl<'a> Fanned<'a> {
    /// Checks `mesh` (valid, finite, with faces) and fans it; `what` prefixes its errors.
    fn new(mesh: &'a PolygonMesh, what: Option<&str>) -> Result<Self, GeometryError> {
        let label = |e: GeometryError| match what {
            Some(w) => GeometryError::Degenerate(format!("{w}: {e}")),
            None => e,
        };
        mesh.validate().map_err(label)?;
        crate::error::check_finite_points("mesh", &mesh.vertices).map_err(label)?;
        let triangles = fan_triangles(mesh);
        if triangles.is_empty() {
            return Err(label(GeometryError::Degenerate(
                "the mesh has no faces".into(),
            )));
        }
        let v = &mesh.vertices;
        let (mut area, mut longest) = (0.0, 0.0);
        for t in &triangles {
            let (a, b, c) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
            area += triangle_area(a, b, c);
            longest += longest_edge(a, b, c);
        }
        Ok(Self {
            vertices: v,
            feature: longest / triangles.len() as f64,
            triangles,
            area,
        })
    }

    /// Fails unless the mesh has area (it is sampled).
    fn check_area(&self, what: Option<&str>) -> Result<(), GeometryError> {
        if self.area > 0.0 && self.area.is_finite() {
            return Ok(());
        }
        let e = "a surface distance needs a mesh with area";
        Err(GeometryError::Degenerate(match what {
            Some(w) => format!("{w}: {e}"),
            None => e.into(),
        }))
    }

    fn corners(&self, t: &[u32; 3]) -> (DVec3, DVec3, DVec3) {
        let v = self.vertices;
        (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize])
    }

    /// The vertices used by a face.
    fn used(&self) -> Vec<bool> {
        let mut used = vec![false; self.vertices.len()];
        for t in &self.triangles {
            for &i in t {
                used[i as usize] = true;
            }
        }
        used
    }
}

/// The sample at the largest distance found: where it is and its closest point.
#[derive(Debug, Clone, Copy)]
struct Far {
    point: DVec3,
    corners: [u32; 3],
    bary: [f64; 3],
    hit: Hit,
}

fn farther(a: Option<Far>, b: Option<Far>) -> Option<Far> {
    match (a, b) {
        (Some(x), Some(y)) if y.hit.distance_squared > x.hit.distance_squared => Some(y),
        (Some(x), _) => Some(x),
        (None, y) => y,
    }
}

/// One direction: the area-weighted mean of d² over `from`'s samples and the sample (or vertex)
/// at the largest distance, distances to `to`'s triangles.
fn sweep(from: &Fanned, to: &TriangleBvh, feature: f64, cap: usize) -> (f64, Option<Far>) {
    let (mean, far) = sweep_samples(from, to, feature, cap);
    // The vertices count for the largest distance only.
    let used = from.used();
    let (_, _, vertex_far) = vertex_sweep(from.vertices, Some(&used), false, to);
    (mean, farther(far, vertex_far))
}

/// The area-weighted mean of d² over `from`'s face samples and the sample at the largest
/// distance (vertices not included).
fn sweep_samples(from: &Fanned, to: &TriangleBvh, feature: f64, cap: usize) -> (f64, Option<Far>) {
    let rule = quadrature_rule();
    let chunk = chunk_len(cap);
    let (mut sum, mut far) = (0.0, None);
    for block in from.triangles.chunks(chunk * BLOCK) {
        let parts: Vec<(f64, Option<Far>)> = block
            .par_chunks(chunk)
            .map(|tris| {
                let (mut sum, mut far, mut hint) = (0.0, None::<Far>, None);
                for t in tris {
                    let (a, b, c) = from.corners(t);
                    let n = split_count(longest_edge(a, b, c), feature, cap);
                    let mut mean = 0.0;
                    for_each_sample(n, &rule, |w, frac| {
                        let p = a * w[0] + b * w[1] + c * w[2];
                        let h = to.closest(p, hint);
                        hint = Some(h.slot);
                        mean += frac * h.distance_squared;
                        if far.is_none_or(|f| h.distance_squared > f.hit.distance_squared) {
                            far = Some(Far {
                                point: p,
                                corners: *t,
                                bary: w,
                                hit: h,
                            });
                        }
                    });
                    sum += triangle_area(a, b, c) * mean;
                }
                (sum, far)
            })
            .collect();
        for (s, f) in parts {
            sum += s;
            far = farther(far, f);
        }
    }
    (sum / from.area, far)
}

/// The closest points of `vertices` to `to`, chunk by chunk: with `all`, the sum of the squared
/// distances and the largest squared distance over every vertex (in a fixed order); the vertex
/// at the largest distance among those `used` (every one without a mask). A vertex is queried
/// when `all` or used.
fn vertex_sweep(
    vertices: &[DVec3],
    used: Option<&[bool]>,
    all: bool,
    to: &TriangleBvh,
) -> (f64, f64, Option<Far>) {
    let parts: Vec<(f64, f64, Option<Far>)> = vertices
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(k, points)| {
            let (mut sum, mut max2, mut far, mut hint) = (0.0, 0.0f64, None::<Far>, None);
            for (i, &p) in points.iter().enumerate() {
                let index = k * CHUNK + i;
                let counts = used.is_none_or(|u| u[index]);
                if !(all || counts) {
                    continue;
                }
                let h = to.closest(p, hint);
                hint = Some(h.slot);
                sum += h.distance_squared;
                max2 = max2.max(h.distance_squared);
                if counts && far.is_none_or(|f| h.distance_squared > f.hit.distance_squared) {
                    far = Some(Far {
                        point: p,
                        corners: [index as u32; 3],
                        bary: [1.0, 0.0, 0.0],
                        hit: h,
                    });
                }
            }
            (sum, max2, far)
        })
        .collect();
    parts
        .into_iter()
        .fold((0.0, 0.0f64, None), |(s, m, f), (a, b, g)| {
            (s + a, m.max(b), farther(f, g))
        })
}

/// Bytes [`surface_distances`] (or, with `gradient`, [`surface_distances_gradient`]) allocates at
/// most for a mesh of `mesh_triangles` fan triangles and `mesh_vertices` vertices against a
/// reference of `reference_triangles` and `reference_vertices`, `samples` the cap: the fan
/// triangles of both meshes, the hierarchy of the one measured to, a vertex mask, the gradient's
/// two vertex vectors and one block of its parts. Nothing grows with the samples.
pub fn working_bytes(
    mesh_triangles: usize,
    mesh_vertices: usize,
    reference_triangles: usize,
    reference_vertices: usize,
    directions: Directions,
    gradient: bool,
) -> u64 {
    let t = |n: usize| n as u64;
    let one = |sampled: usize, sampled_vertices: usize, target: usize| {
        12 * t(sampled) + t(sampled_vertices) + (12 + TriangleBvh::BYTES_PER_TRIANGLE) * t(target)
    };
    let mut bytes = 0;
    if directions.to_reference {
        bytes = bytes.max(one(mesh_triangles, mesh_vertices, reference_triangles));
    }
    if directions.from_reference {
        bytes = bytes.max(one(reference_triangles, reference_vertices, mesh_triangles));
    }
    if gradient {
        // The gradient and the area gradient; a block of parts (≤ 6 · CHUNK samples a chunk, 64
        // bytes each).
        bytes += 48 * t(mesh_vertices) + (BLOCK * 6 * CHUNK * 64) as u64;
    }
    bytes
}

/// Both directions of the distance between `mesh` and `reference` (the directions not asked for
/// stay 0), each triangle split up to `samples` times per edge (1 to [`MAX_SAMPLES`]; [module
/// docs](self)). The sums run in a fixed order, so the result does not depend on the thread
/// count.
pub fn surface_distances(
    mesh: &PolygonMesh,
    reference: &PolygonMesh,
    samples: usize,
    directions: Directions,
) -> Result<SurfaceDistances, GeometryError> {
    Ok(surface_and_vertex_distances(mesh, reference, samples, directions, false)?.0)
}

/// [`surface_distances`] and, with `vertices`, [`vertex_distances`] of the mesh's vertices, with
/// one hierarchy of the reference for both (and one query a vertex): the mean of the squared
/// distances of every vertex and the largest distance ((0, 0) without `vertices`).
pub fn surface_and_vertex_distances(
    mesh: &PolygonMesh,
    reference: &PolygonMesh,
    samples: usize,
    directions: Directions,
    vertices: bool,
) -> Result<(SurfaceDistances, (f64, f64)), GeometryError> {
    check_samples(samples)?;
    const REF: Option<&str> = Some("the reference mesh");
    let mut out = SurfaceDistances::default();
    let mut one_sided = (0.0, 0.0);
    if directions.to_reference || vertices {
        let m = if directions.to_reference {
            let m = Fanned::new(mesh, None)?;
            m.check_area(None)?;
            Some(m)
        } else {
            crate::error::check_finite_points("points", &mesh.vertices)?;
            None
        };
        let r = Fanned::new(reference, REF)?;
        let bvh = TriangleBvh::new(r.vertices, &r.triangles);
        drop(r.triangles);
        let mut far = None;
        if let Some(m) = &m {
            let (mean, samples_far) = sweep_samples(m, &bvh, r.feature, samples);
            out.to_reference = mean;
            far = samples_far;
        }
        let used = m.as_ref().map(Fanned::used);
        let (sum, max2, vertex_far) = vertex_sweep(&mesh.vertices, used.as_deref(), vertices, &bvh);
        if vertices {
            one_sided = (sum / mesh.vertices.len().max(1) as f64, max2.sqrt());
        }
        out.to_reference_max =
            farther(far, vertex_far).map_or(0.0, |f| f.hit.distance_squared.sqrt());
    }
    if directions.from_reference {
        let m = Fanned::new(mesh, None)?;
        let r = Fanned::new(reference, REF)?;
        r.check_area(REF)?;
        let bvh = TriangleBvh::new(m.vertices, &m.triangles);
        drop(m.triangles);
        let (mean, far) = sweep(&r, &bvh, m.feature, samples);
        out.from_reference = mean;
        out.from_reference_max = far.map_or(0.0, |f| f.hit.distance_squared.sqrt());
    }
    Ok((out, one_sided))
}

/// The mean of the squared distances from `points` to `reference`'s surface and the largest
/// distance (both 0 without points); the sums run in a fixed order of chunks, so the result does
/// not depend on the thread count.
pub fn vertex_distances(
    points: &[DVec3],
    reference: &PolygonMesh,
) -> Result<(f64, f64), GeometryError> {
    let r = Fanned::new(reference, Some("the reference mesh"))?;
    crate::error::check_finite_points("points", points)?;
    let bvh = TriangleBvh::new(r.vertices, &r.triangles);
    drop(r.triangles);
    let (sum, max2, _) = vertex_sweep(points, None, true, &bvh);
    Ok((sum / points.len().max(1) as f64, max2.sqrt()))
}

/// The closest point of `reference`'s surface to each of `points`, in order.
pub fn vertex_closest(
    points: &[DVec3],
    reference: &PolygonMesh,
) -> Result<Vec<Hit>, GeometryError> {
    let r = Fanned::new(reference, Some("the reference mesh"))?;
    crate::error::check_finite_points("points", points)?;
    let tree = TriangleBvh::new(r.vertices, &r.triangles);
    drop(r.triangles);
    let bvh = &tree;
    Ok(points
        .par_chunks(CHUNK)
        .flat_map_iter(|chunk| {
            let mut hint = None;
            chunk.iter().map(move |&p| {
                let h = bvh.closest(p, hint);
                hint = Some(h.slot);
                h
            })
        })
        .collect())
}

/// Bytes [`vertex_distances`] allocates at most for `points` points against a reference of
/// `reference_triangles` fan triangles (with `hits`, [`vertex_closest`]: one [`Hit`] a point).
pub fn vertex_working_bytes(points: usize, reference_triangles: usize, hits: bool) -> u64 {
    let per_point = if hits {
        std::mem::size_of::<Hit>() as u64
    } else {
        0
    };
    (12 + TriangleBvh::BYTES_PER_TRIANGLE) * reference_triangles as u64
        + per_point * points as u64
        + 16 * (points / CHUNK + 1) as u64
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

/// A reference sample's part of the gradient: the mesh triangle its closest point lies on, the
/// point's barycentric coordinates there and the vector they share.
type SamplePart = ([u32; 3], [f64; 3], DVec3);

/// A triangle's part of the gradient towards the reference: what its samples' points add to its
/// corners, and its mean of d².
struct TrianglePart {
    corners: [u32; 3],
    points: [DVec3; 3],
    mean: f64,
}

/// The gradient of `Σ cotangent · measure` ([`surface_distances`]) with respect to the mesh's
/// vertices (exact on the closest triangles found, each triangle's split held; at the largest
/// distance, the derivative of the sample that attains it).
pub fn surface_distances_gradient(
    mesh: &PolygonMesh,
    reference: &PolygonMesh,
    samples: usize,
    c: DistanceCotangents,
) -> Result<Vec<DVec3>, GeometryError> {
    check_samples(samples)?;
    const REF: Option<&str> = Some("the reference mesh");
    let v = &mesh.vertices;
    let mut g = vec![DVec3::ZERO; v.len()];
    let rule = quadrature_rule();
    let chunk = chunk_len(samples);
    if c.to_reference != 0.0 || c.to_reference_max != 0.0 {
        let m = Fanned::new(mesh, None)?;
        m.check_area(None)?;
        let r = Fanned::new(reference, REF)?;
        let bvh = TriangleBvh::new(r.vertices, &r.triangles);
        let feature = r.feature;
        drop(r.triangles);
        if c.to_reference != 0.0 {
            // mean = Σ_t A_t m_t / A: through the samples' points, and ∂/∂A_t = (m_t − mean) / A.
            let scale = c.to_reference / m.area;
            let mut g_area = vec![DVec3::ZERO; v.len()];
            let mut mean = 0.0;
            for block in m.triangles.chunks(chunk * BLOCK) {
                let parts: Vec<Vec<TrianglePart>> = block
                    .par_chunks(chunk)
                    .map(|tris| {
                        let mut hint = None;
                        tris.iter()
                            .map(|t| {
                                let (a, b, cc) = m.corners(t);
                                let n = split_count(longest_edge(a, b, cc), feature, samples);
                                let w_area = 2.0 * triangle_area(a, b, cc) * scale;
                                let mut part = TrianglePart {
                                    corners: *t,
                                    points: [DVec3::ZERO; 3],
                                    mean: 0.0,
                                };
                                for_each_sample(n, &rule, |w, frac| {
                                    let p = a * w[0] + b * w[1] + cc * w[2];
                                    let h = bvh.closest(p, hint);
                                    hint = Some(h.slot);
                                    part.mean += frac * h.distance_squared;
                                    let d = (p - h.point) * (w_area * frac);
                                    for (k, x) in part.points.iter_mut().enumerate() {
                                        *x += d * w[k];
                                    }
                                });
                                part
                            })
                            .collect()
                    })
                    .collect();
                for part in parts.iter().flatten() {
                    for (k, &i) in part.corners.iter().enumerate() {
                        g[i as usize] += part.points[k];
                    }
                    let (a, b, cc) = m.corners(&part.corners);
                    mean += triangle_area(a, b, cc) * part.mean;
                    add_area_gradient(&mut g, v, part.corners, scale * part.mean);
                    add_area_gradient(&mut g_area, v, part.corners, 1.0);
                }
            }
            mean /= m.area;
            for (x, y) in g.iter_mut().zip(&g_area) {
                *x -= *y * (scale * mean);
            }
        }
        if c.to_reference_max != 0.0
            && let (_, Some(f)) = sweep(&m, &bvh, feature, samples)
            && f.hit.distance_squared > 0.0
        {
            let d = f.hit.distance_squared.sqrt();
            scatter(
                &mut g,
                f.corners,
                f.bary,
                (f.point - f.hit.point) * (c.to_reference_max / d),
            );
        }
    }
    if c.from_reference != 0.0 || c.from_reference_max != 0.0 {
        let m = Fanned::new(mesh, None)?;
        let r = Fanned::new(reference, REF)?;
        r.check_area(REF)?;
        let bvh = TriangleBvh::new(m.vertices, &m.triangles);
        let feature = m.feature;
        drop(m.triangles);
        if c.from_reference != 0.0 {
            let scale = 2.0 * c.from_reference / r.area;
            for block in r.triangles.chunks(chunk * BLOCK) {
                let parts: Vec<Vec<SamplePart>> = block
                    .par_chunks(chunk)
                    .map(|tris| {
                        let (mut out, mut hint) = (Vec::with_capacity(tris.len() * 6), None);
                        for t in tris {
                            let (a, b, cc) = r.corners(t);
                            let n = split_count(longest_edge(a, b, cc), feature, samples);
                            let w_area = triangle_area(a, b, cc) * scale;
                            for_each_sample(n, &rule, |w, frac| {
                                let p = a * w[0] + b * w[1] + cc * w[2];
                                let h = bvh.closest(p, hint);
                                hint = Some(h.slot);
                                out.push((h.corners, h.bary, (h.point - p) * (w_area * frac)));
                            });
                        }
                        out
                    })
                    .collect();
                for &(t, b, d) in parts.iter().flatten() {
                    scatter(&mut g, t, b, d);
                }
            }
        }
        if c.from_reference_max != 0.0
            && let (_, Some(f)) = sweep(&r, &bvh, feature, samples)
            && f.hit.distance_squared > 0.0
        {
            let d = f.hit.distance_squared.sqrt();
            scatter(
                &mut g,
                f.hit.corners,
                f.hit.bary,
                (f.hit.point - f.point) * (c.from_reference_max / d),
            );
        }
    }
    Ok(g)
}

#[cfg(test)]
mod tests;
