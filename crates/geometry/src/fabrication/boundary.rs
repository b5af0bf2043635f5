//! The boundary of a union of flat faces, walked as one loop: the outline of an unrolled strip
//! (quad grids and polygon meshes alike).

use std::collections::{HashMap, HashSet};
use std::hash::Hash;

/// Walks the boundary of a union of faces given as directed edges `(from, to, point at from)`,
/// every face counter-clockwise, so an edge two faces share appears once each way and cancels.
/// Returns the boundary's points in order from its first edge, and how many boundary edges there
/// are: the two are equal when the boundary is one loop.
pub fn boundary_loop<K: Copy + Eq + Hash, P: Copy>(directed: &[(K, K, P)]) -> (Vec<P>, usize) {
    let edges: HashSet<(K, K)> = directed.iter().map(|&(a, b, _)| (a, b)).collect();
    let boundary: Vec<&(K, K, P)> = directed
        .iter()
        .filter(|(a, b, _)| !edges.contains(&(*b, *a)))
        .collect();
    let next: HashMap<K, usize> = boundary
        .iter()
        .enumerate()
        .map(|(i, (a, _, _))| (*a, i))
        .collect();
    let mut points = Vec::with_capacity(boundary.len());
    if let Some(first) = boundary.first() {
        let mut at = first.0;
        while let Some(&i) = next.get(&at) {
            points.push(boundary[i].2);
            at = boundary[i].1;
            if at == first.0 || points.len() > boundary.len() {
                break;
            }
        }
    }
    (points, boundary.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_squares_side_by_side_give_one_loop_of_six() {
        // Squares 0-1-4-3 and 1-2-5-4 counter-clockwise: the shared edge 1-4 cancels.
        let p = |k: u8| k;
        let mut directed = Vec::new();
        for face in [[0u8, 1, 4, 3], [1, 2, 5, 4]] {
            for t in 0..4 {
                directed.push((face[t], face[(t + 1) % 4], p(face[t])));
            }
        }
        let (points, edges) = boundary_loop(&directed);
        assert_eq!(edges, 6);
        assert_eq!(points, vec![0, 1, 2, 5, 4, 3]);
    }
}
