//! Welding and compacting polygon meshes: vertices closer than a tolerance become one, faces that
//! collapse are dropped, unused vertices are removed.
//!
//! The candidates of a merge are found through a spatial hash ([`merge_map`]), so welding is
//! near-linear for any input: a tolerance of 0 hashes exact positions; a positive tolerance hashes
//! cells `tolerance` wide, and along an axis where a coordinate is too large for its cell index
//! (coordinates near 1e25, or a tolerance of 1e-300: the index would saturate and every vertex share
//! one cell) the coordinate itself is the key — there the spacing of doubles is wider than the
//! tolerance, so only equal coordinates can be within it.

use std::collections::HashMap;

use glam::DVec3;

use crate::{GeometryError, PolygonMesh};

/// Beyond this many cells from the origin an axis is keyed by its coordinate (see the module):
/// there doubles are at least 4 cells apart, so a coordinate within one cell of it is equal to it.
const EXACT_BEYOND: f64 = (1u64 << 55) as f64;

/// One axis of a cell key: a cell index, or a coordinate too large for one (its bits).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Axis {
    Cell(i64),
    Exact(u64),
}

fn axis(x: f64, cell: f64) -> Axis {
    let t = (x / cell).floor();
    if t.abs() < EXACT_BEYOND {
        Axis::Cell(t as i64)
    } else {
        // +0.0 and -0.0 never get here; a coordinate is its own key.
        Axis::Exact(x.to_bits())
    }
}

/// The keys to search along one axis: the cell and its two neighbours, or the exact coordinate.
fn around(a: Axis) -> impl Iterator<Item = Axis> {
    let (first, count) = match a {
        Axis::Cell(c) => (Axis::Cell(c - 1), 3),
        Axis::Exact(_) => (a, 1),
    };
    (0..count).map(move |k| match first {
        Axis::Cell(c) => Axis::Cell(c + k),
        exact => exact,
    })
}

/// Which vertex each of `points` merges into: every point within `tolerance` (finite, ≥ 0) of an
/// earlier kept point maps to the first such one, the others are kept. Returns the kept points and
/// the map (an index into them per point). Near-linear for any input (see the module); the second
/// value counts the distance tests made, for the tests of that bound.
pub fn merge_map(points: &[DVec3], tolerance: f64) -> (Vec<DVec3>, Vec<u32>, usize) {
    let mut kept: Vec<DVec3> = Vec::new();
    let mut map: Vec<u32> = Vec::with_capacity(points.len());
    let mut tests = 0usize;
    if tolerance == 0.0 {
        let mut seen: HashMap<[u64; 3], u32> = HashMap::with_capacity(points.len());
        for &p in points {
            // +0.0 and -0.0 are the same position.
            let key = (p + DVec3::ZERO).to_array().map(f64::to_bits);
            let k = *seen.entry(key).or_insert_with(|| {
                kept.push(p);
                (kept.len() - 1) as u32
            });
            map.push(k);
        }
        return (kept, map, tests);
    }
    let key = |p: DVec3| {
        [
            axis(p.x, tolerance),
            axis(p.y, tolerance),
            axis(p.z, tolerance),
        ]
    };
    // Within the tolerance, measured in tolerances (no underflow of a squared tiny distance).
    let near = |a: DVec3, b: DVec3| ((a - b) / tolerance).length_squared() <= 1.0;
    let mut cells: HashMap<[Axis; 3], Vec<u32>> = HashMap::with_capacity(points.len());
    for &p in points {
        let c = key(p);
        let mut found = None;
        'search: for x in around(c[0]) {
            for y in around(c[1]) {
                for z in around(c[2]) {
                    if let Some(list) = cells.get(&[x, y, z]) {
                        for &k in list {
                            tests += 1;
                            if near(kept[k as usize], p) {
                                found = Some(k);
                                break 'search;
                            }
                        }
                    }
                }
            }
        }
        let k = found.unwrap_or_else(|| {
            kept.push(p);
            let k = (kept.len() - 1) as u32;
            cells.entry(c).or_default().push(k);
            k
        });
        map.push(k);
    }
    (kept, map, tests)
}

/// The mesh with vertices closer than `tolerance` merged (each into the first of them in vertex
/// order, found through [`merge_map`]'s spatial hash, so welding is near-linear), repeated corners
/// of a face removed, faces left with fewer than three corners dropped, and unused vertices
/// removed. Tolerance 0 merges exactly equal positions only.
pub fn weld(mesh: &PolygonMesh, tolerance: f64) -> Result<PolygonMesh, GeometryError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(GeometryError::InvalidParameter {
            what: "weld tolerance",
            value: tolerance,
            expected: "a finite number ≥ 0",
        });
    }
    mesh.validate()?;
    crate::error::check_finite_points("mesh", &mesh.vertices)?;
    let (kept, map, _) = merge_map(&mesh.vertices, tolerance);
    let mut welded = PolygonMesh {
        vertices: kept,
        ..PolygonMesh::default()
    };
    let mut corners: Vec<u32> = Vec::new();
    let mut sources = Vec::with_capacity(mesh.face_count());
    for (k, face) in mesh.faces().enumerate() {
        corners.clear();
        for &v in face {
            let w = map[v as usize];
            if corners.last() != Some(&w) {
                corners.push(w);
            }
        }
        while corners.len() > 1 && corners.first() == corners.last() {
            corners.pop();
        }
        if corners.len() >= 3 {
            welded.push_face(&corners)?;
            sources.push(k as u32);
        }
    }
    welded.carry_faces_from(mesh, &sources);
    Ok(compact(&welded))
}

/// The mesh without vertices that no face uses (faces keep their order; vertices keep their
/// relative order).
pub fn compact(mesh: &PolygonMesh) -> PolygonMesh {
    let mut used = vec![u32::MAX; mesh.vertices.len()];
    let mut vertices = Vec::new();
    for &v in &mesh.indices {
        if let Some(slot) = used.get_mut(v as usize)
            && *slot == u32::MAX
        {
            *slot = 0;
        }
    }
    for (k, slot) in used.iter_mut().enumerate() {
        if *slot != u32::MAX {
            *slot = vertices.len() as u32;
            vertices.push(mesh.vertices[k]);
        }
    }
    PolygonMesh {
        vertices,
        indices: mesh.indices.iter().map(|&v| used[v as usize]).collect(),
        face_starts: mesh.face_starts.clone(),
        parts: mesh.parts.clone(),
        classes: mesh.classes.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles of a unit square, stored STL-style: six corners, none shared.
    fn soup(jitter: f64) -> PolygonMesh {
        let v = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(jitter, 0.0, 0.0),
            DVec3::new(1.0, 1.0, jitter),
            DVec3::Y,
        ];
        PolygonMesh::from_faces(v, &[vec![0, 1, 2], vec![3, 4, 5]]).unwrap()
    }

    #[test]
    fn near_corners_merge_and_the_mesh_connects() {
        let w = weld(&soup(1e-7), 1e-6).unwrap();
        assert_eq!(w.vertices.len(), 4);
        assert_eq!(w.face(0), &[0, 1, 2]);
        assert_eq!(w.face(1), &[0, 2, 3]);
        let exact = weld(&soup(1e-7), 0.0).unwrap();
        assert_eq!(
            exact.vertices.len(),
            6,
            "tolerance 0 merges equal positions only"
        );
        assert_eq!(weld(&soup(0.0), 0.0).unwrap().vertices.len(), 4);
    }

    /// `n` distinct points spread over a cube of side `size` around `centre` (deterministic).
    fn spread(n: usize, centre: f64, size: f64) -> Vec<DVec3> {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| DVec3::new(next(), next(), next()) * size + DVec3::splat(centre))
            .collect()
    }

    /// Issue 27 §3: a weld of 1e-300 (every cell index saturated) or coordinates near 1e25 put
    /// every vertex in one cell and welding was quadratic (a 10 MB STL past a minute); tolerance 0
    /// hashed unit cells, so a mesh inside a unit cube was quadratic too. The distance tests are
    /// counted: a few per point, whatever the tolerance and the coordinates.
    #[test]
    fn welding_is_near_linear_for_tiny_tolerances_and_huge_coordinates() {
        let n = 20_000;
        let cases = [
            (spread(n, 0.0, 1.0), 1e-300),
            (spread(n, 0.0, 1.0), 0.0),
            (spread(n, 0.0, 1.0), f64::from_bits(1)),
            (spread(n, 1e25, 1e25), 0.0),
            (spread(n, 1e25, 1e25), 1e-3),
            (spread(n, -1e25, 1e20), 1.0),
            (spread(n, 1e300, 1e300), 1e-300),
        ];
        for (points, tolerance) in cases {
            let (kept, map, tests) = merge_map(&points, tolerance);
            assert_eq!(kept.len(), n, "distinct points stay ({tolerance:e})");
            assert_eq!(map.len(), n);
            assert!(
                tests <= 8 * n,
                "{tests} distance tests for {n} points ({tolerance:e}): not linear"
            );
        }
        // Every point doubled (and shifted by less than the tolerance where there is room): each
        // copy merges into its original, still in a few tests each.
        for (points, tolerance, shift) in [
            (spread(n, 0.0, 1.0), 1e-300, 0.0),
            (spread(n, 1e25, 1e25), 1e-3, 0.0),
            (spread(n, 0.0, 1.0), 1e-9, 4e-10),
        ] {
            let doubled: Vec<DVec3> = points
                .iter()
                .copied()
                .chain(points.iter().map(|p| *p + DVec3::new(shift, 0.0, 0.0)))
                .collect();
            let (kept, map, tests) = merge_map(&doubled, tolerance);
            assert_eq!(kept.len(), n, "{tolerance:e}");
            assert!(map[n..].iter().zip(0..).all(|(&m, k)| m == k));
            assert!(tests <= 16 * n, "{tests} tests ({tolerance:e})");
        }
    }

    /// Points that straddle the switch from cell indices to exact coordinates still merge when
    /// within the tolerance: past it, a double's neighbours are further apart than the tolerance.
    #[test]
    fn near_points_merge_across_the_exact_key_switch() {
        let tolerance = 1e-3;
        let edge = EXACT_BEYOND * tolerance;
        for x in [edge * 0.999_999, edge, edge * 1.000_001, -edge] {
            let a = DVec3::new(x, 0.5, 0.5);
            let b = DVec3::new(x, 0.5 + 0.9 * tolerance, 0.5);
            let far = DVec3::new(x, 0.5 + 3.0 * tolerance, 0.5);
            let (kept, map, _) = merge_map(&[a, b, far], tolerance);
            assert_eq!(map, vec![0, 0, 1], "at x = {x:e}");
            assert_eq!(kept, vec![a, far]);
        }
    }

    #[test]
    fn collapsed_faces_are_dropped_and_unused_vertices_removed() {
        let v = vec![
            DVec3::ZERO,
            DVec3::new(1e-9, 0.0, 0.0),
            DVec3::Y,
            DVec3::X,
            DVec3::splat(9.0),
        ];
        let m = PolygonMesh::from_faces(v, &[vec![0, 1, 2], vec![0, 3, 2]]).unwrap();
        let w = weld(&m, 1e-6).unwrap();
        assert_eq!(w.face_count(), 1, "the sliver collapsed");
        assert_eq!(w.vertices, vec![DVec3::ZERO, DVec3::Y, DVec3::X]);
        assert!(weld(&m, f64::NAN).is_err());
        assert!(weld(&m, -1.0).is_err());
    }
}
