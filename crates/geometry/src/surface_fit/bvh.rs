//! A compact bounding-volume hierarchy over a mesh's fan triangles, for closest-point queries.
//!
//! Built once per mesh by median splits of the triangles' centroids along the longest axis of
//! their bounds (leaves of at most [`LEAF`] triangles), it takes at most
//! [`TriangleBvh::BYTES_PER_TRIANGLE`] bytes a triangle while it is built and less once it is, so
//! a caller can declare its size to a memory budget before building it. A query is a depth-first
//! search, nearer child first, pruned by the best squared distance so far; a *hint* (the triangle
//! the previous, nearby query ended on) starts it with a tight bound, which makes the coherent
//! queries of a sweep over a mesh's samples cheap. Queries allocate nothing.

use glam::DVec3;

use super::closest_barycentric;

/// The most triangles in a leaf.
pub const LEAF: usize = 4;

/// The deepest a median split of up to 2³² triangles goes, with room to spare.
const STACK: usize = 96;

#[derive(Debug, Clone, Copy)]
struct Node {
    min: DVec3,
    max: DVec3,
    /// A leaf's first triangle, or an inner node's first child (the second follows it).
    start: u32,
    /// A leaf's triangle count; 0 for an inner node.
    count: u32,
}

impl Node {
    /// The squared distance from `p` to the box (0 inside).
    #[inline]
    fn distance_squared(&self, p: DVec3) -> f64 {
        let d = (self.min - p).max(p - self.max).max(DVec3::ZERO);
        d.length_squared()
    }
}

/// The closest point of the indexed triangles to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The closest point.
    pub point: DVec3,
    /// Its squared distance from the query point.
    pub distance_squared: f64,
    /// The vertex indices of the triangle it lies on.
    pub corners: [u32; 3],
    /// Its barycentric coordinates in that triangle.
    pub bary: [f64; 3],
    /// The triangle's position in the hierarchy: a hint for the next query.
    pub slot: u32,
}

/// A bounding-volume hierarchy over triangles given by vertex indices into a vertex slice.
#[derive(Debug, Clone)]
pub struct TriangleBvh<'a> {
    vertices: &'a [DVec3],
    /// The triangles, in the hierarchy's order.
    triangles: Vec<[u32; 3]>,
    nodes: Vec<Node>,
}

impl<'a> TriangleBvh<'a> {
    /// The most bytes a triangle takes while the hierarchy is built: its corners (12), at most
    /// one node (56) and the build's centroid and index (32).
    pub const BYTES_PER_TRIANGLE: u64 = 12 + std::mem::size_of::<Node>() as u64 + 32;

    /// Builds the hierarchy of `triangles` (vertex indices into `vertices`, all in range and
    /// finite: the caller checks). At least one triangle.
    pub fn new(vertices: &'a [DVec3], triangles: &[[u32; 3]]) -> Self {
        let corner = |t: &[u32; 3], k: usize| vertices[t[k] as usize];
        let mut items: Vec<(DVec3, u32)> = triangles
            .iter()
            .enumerate()
            .map(|(k, t)| ((corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0, k as u32))
            .collect();
        let mut nodes = Vec::with_capacity(triangles.len().max(1));
        nodes.push(Node {
            min: DVec3::ZERO,
            max: DVec3::ZERO,
            start: 0,
            count: 0,
        });
        build(&mut nodes, 0, &mut items, 0, vertices, triangles);
        let ordered = items.iter().map(|&(_, k)| triangles[k as usize]).collect();
        Self {
            vertices,
            triangles: ordered,
            nodes,
        }
    }

    /// The number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there are no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    #[inline]
    fn test(&self, slot: u32, p: DVec3, best: &mut Hit) {
        let t = self.triangles[slot as usize];
        let v = self.vertices;
        let (a, b, c) = (v[t[0] as usize], v[t[1] as usize], v[t[2] as usize]);
        // The triangle's box first: a cheap lower bound that rejects most of a leaf.
        let gap = (a.min(b).min(c) - p)
            .max(p - a.max(b).max(c))
            .max(DVec3::ZERO);
        if gap.length_squared() > best.distance_squared {
            return;
        }
        let bary = closest_barycentric(p, a, b, c);
        let q = a * bary[0] + b * bary[1] + c * bary[2];
        let d2 = q.distance_squared(p);
        if d2 < best.distance_squared {
            *best = Hit {
                point: q,
                distance_squared: d2,
                corners: t,
                bary,
                slot,
            };
        }
    }

    /// The closest point to `p` (finite), starting from the triangle at `hint` (a previous hit's
    /// `slot`) when given. On a tie the first triangle found is kept.
    pub fn closest(&self, p: DVec3, hint: Option<u32>) -> Hit {
        let mut best = Hit {
            point: p,
            distance_squared: f64::INFINITY,
            corners: [0; 3],
            bary: [1.0, 0.0, 0.0],
            slot: 0,
        };
        if let Some(h) = hint.filter(|&h| (h as usize) < self.triangles.len()) {
            self.test(h, p, &mut best);
        }
        let mut stack = [0u32; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if node.distance_squared(p) > best.distance_squared {
                continue;
            }
            if node.count > 0 {
                for slot in node.start..node.start + node.count {
                    self.test(slot, p, &mut best);
                }
                continue;
            }
            let (l, r) = (node.start, node.start + 1);
            let (dl, dr) = (
                self.nodes[l as usize].distance_squared(p),
                self.nodes[r as usize].distance_squared(p),
            );
            // Push the farther child first so the nearer one is searched first.
            let (near, far, d_near, d_far) = if dl <= dr {
                (l, r, dl, dr)
            } else {
                (r, l, dr, dl)
            };
            if d_far <= best.distance_squared && top < STACK {
                stack[top] = far;
                top += 1;
            }
            if d_near <= best.distance_squared && top < STACK {
                stack[top] = near;
                top += 1;
            }
        }
        best
    }
}

fn bounds_of(items: &[(DVec3, u32)], vertices: &[DVec3], triangles: &[[u32; 3]]) -> (DVec3, DVec3) {
    let (mut min, mut max) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &(_, k) in items {
        for &i in &triangles[k as usize] {
            let p = vertices[i as usize];
            min = min.min(p);
            max = max.max(p);
        }
    }
    (min, max)
}

/// Fills node `at` with `items` (which start at triangle `offset` of the final order), splitting
/// at the median centroid along the longest axis of the centroids' bounds; a node's box is the
/// union of its children's (bottom-up: every triangle's corners are read once).
fn build(
    nodes: &mut Vec<Node>,
    at: usize,
    items: &mut [(DVec3, u32)],
    offset: u32,
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
) {
    if items.len() <= LEAF {
        let (min, max) = bounds_of(items, vertices, triangles);
        nodes[at] = Node {
            min,
            max,
            start: offset,
            count: items.len() as u32,
        };
        return;
    }
    let (mut cmin, mut cmax) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &(c, _) in items.iter() {
        cmin = cmin.min(c);
        cmax = cmax.max(c);
    }
    let extent = cmax - cmin;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    let first = nodes.len();
    let empty = Node {
        min: DVec3::ZERO,
        max: DVec3::ZERO,
        start: 0,
        count: 0,
    };
    nodes.push(empty);
    nodes.push(empty);
    let (left, right) = items.split_at_mut(mid);
    build(nodes, first, left, offset, vertices, triangles);
    build(
        nodes,
        first + 1,
        right,
        offset + mid as u32,
        vertices,
        triangles,
    );
    let (l, r) = (nodes[first], nodes[first + 1]);
    nodes[at] = Node {
        min: l.min.min(r.min),
        max: l.max.max(r.max),
        start: first as u32,
        count: 0,
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_closest_point_of_every_triangle_with_and_without_hints() {
        // A wavy grid of triangles and points around it, checked against every triangle.
        let n = 9;
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                vertices.push(DVec3::new(x, y, 0.3 * (4.0 * x).sin() * (3.0 * y).cos()));
            }
        }
        let id = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let bvh = TriangleBvh::new(&vertices, &triangles);
        assert_eq!(bvh.len(), triangles.len());
        let mut seed = 7u64;
        let mut hint = None;
        for _ in 0..500 {
            let mut r = || {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (seed >> 11) as f64 / (1u64 << 53) as f64 * 1.6 - 0.3
            };
            let p = DVec3::new(r(), r(), r() * 0.5);
            let brute = triangles
                .iter()
                .map(|t| {
                    let (a, b, c) = (
                        vertices[t[0] as usize],
                        vertices[t[1] as usize],
                        vertices[t[2] as usize],
                    );
                    let w = closest_barycentric(p, a, b, c);
                    (a * w[0] + b * w[1] + c * w[2]).distance_squared(p)
                })
                .fold(f64::INFINITY, f64::min);
            let cold = bvh.closest(p, None);
            let warm = bvh.closest(p, hint);
            assert!(
                (cold.distance_squared - brute).abs() <= 1e-14,
                "{cold:?} vs {brute}"
            );
            assert!((warm.distance_squared - cold.distance_squared).abs() <= 1e-15);
            let [a, b, c] = cold.corners.map(|i| vertices[i as usize]);
            let q = a * cold.bary[0] + b * cold.bary[1] + c * cold.bary[2];
            assert!(q.distance(cold.point) < 1e-15);
            hint = Some(cold.slot);
        }
    }
}
