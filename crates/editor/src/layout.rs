//! A layered (Sugiyama-style) layout of a directed acyclic graph of rectangles, for View ›
//! Arrange graph: sources on the left, sinks on the right, no overlaps, few crossings.
//!
//! 1. **Layers**: longest path from the sources (every wire goes left to right); a node without
//!    inputs (a slider, a curve) is then moved right to just before the first node it feeds, so
//!    parameters sit next to what they drive.
//! 2. **Order** within each layer: barycenter sweeps (each node at the mean rank of its neighbours
//!    in the layers already placed), alternating left-to-right and right-to-left; the order with
//!    the fewest crossings between adjacent layers is kept.
//! 3. **Coordinates**: columns as wide as their widest node; in each column the nodes keep their
//!    order and are pulled towards the centres of their neighbours, then pushed apart so that no
//!    two overlap.
//!
//! No layout crate is used: the ones on crates.io either lay out text (ASCII art) or pull a whole
//! graph-drawing stack; this is ~200 lines with the node sizes egui measured.

/// Positions (top-left corners) for rectangles of `sizes` joined by `edges` (from, to), with
/// `gap` = [horizontal, vertical] spacing. Edges that would close a cycle are ignored.
pub fn layered(sizes: &[[f32; 2]], edges: &[(usize, usize)], gap: [f32; 2]) -> Vec<[f32; 2]> {
    let n = sizes.len();
    if n == 0 {
        return Vec::new();
    }
    let edges: Vec<(usize, usize)> = edges
        .iter()
        .copied()
        .filter(|&(a, b)| a < n && b < n && a != b)
        .collect();
    let layer = layers(n, &edges);
    let count = layer.iter().copied().max().unwrap_or(0) + 1;
    let mut order: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (k, &l) in layer.iter().enumerate() {
        order[l].push(k);
    }
    reduce_crossings(&mut order, &edges, &layer);
    place(sizes, &edges, &order, gap)
}

/// Longest-path layers; then sources move right to just before their first target.
fn layers(n: usize, edges: &[(usize, usize)]) -> Vec<usize> {
    let mut indegree = vec![0usize; n];
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(a, b) in edges {
        out[a].push(b);
        indegree[b] += 1;
    }
    // Kahn's order; nodes left over (a cycle) are appended in index order.
    let mut queue: Vec<usize> = (0..n).filter(|&k| indegree[k] == 0).collect();
    let mut topo = Vec::with_capacity(n);
    let mut deg = indegree.clone();
    let mut head = 0;
    while head < queue.len() {
        let k = queue[head];
        head += 1;
        topo.push(k);
        for &m in &out[k] {
            deg[m] -= 1;
            if deg[m] == 0 {
                queue.push(m);
            }
        }
    }
    let mut seen = vec![false; n];
    for &k in &topo {
        seen[k] = true;
    }
    topo.extend((0..n).filter(|&k| !seen[k]));
    let position: Vec<usize> = {
        let mut p = vec![0; n];
        for (i, &k) in topo.iter().enumerate() {
            p[k] = i;
        }
        p
    };
    let mut layer = vec![0usize; n];
    for &k in &topo {
        for &m in &out[k] {
            if position[m] > position[k] {
                layer[m] = layer[m].max(layer[k] + 1);
            }
        }
    }
    for &k in topo.iter().rev() {
        if indegree[k] == 0
            && let Some(first) = out[k]
                .iter()
                .filter(|&&m| position[m] > position[k])
                .map(|&m| layer[m])
                .min()
        {
            layer[k] = first.saturating_sub(1).max(layer[k]);
        }
    }
    layer
}

/// Crossings between adjacent layers (edges spanning several layers are counted between their
/// end layers, by rank).
pub fn crossings(order: &[Vec<usize>], edges: &[(usize, usize)], layer: &[usize]) -> usize {
    let mut rank = vec![0f32; layer.len()];
    for col in order {
        for (i, &k) in col.iter().enumerate() {
            rank[k] = (i as f32 + 0.5) / col.len() as f32;
        }
    }
    let mut total = 0;
    for (i, &(a, b)) in edges.iter().enumerate() {
        for &(c, d) in &edges[i + 1..] {
            if layer[a] != layer[c] || layer[b] != layer[d] || a == c || b == d {
                continue;
            }
            if (rank[a] - rank[c]) * (rank[b] - rank[d]) < 0.0 {
                total += 1;
            }
        }
    }
    total
}

fn reduce_crossings(order: &mut [Vec<usize>], edges: &[(usize, usize)], layer: &[usize]) {
    let n = layer.len();
    let mut preds: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut succs: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(a, b) in edges {
        if layer[a] < layer[b] {
            preds[b].push(a);
            succs[a].push(b);
        }
    }
    let mut best = order.to_vec();
    let mut best_crossings = crossings(order, edges, layer);
    let mut rank = vec![0f32; n];
    let set_ranks = |order: &[Vec<usize>], rank: &mut [f32]| {
        for col in order {
            for (i, &k) in col.iter().enumerate() {
                rank[k] = (i as f32 + 0.5) / col.len() as f32;
            }
        }
    };
    for sweep in 0..8 {
        set_ranks(order, &mut rank);
        let forward = sweep % 2 == 0;
        let columns: Vec<usize> = if forward {
            (1..order.len()).collect()
        } else {
            (0..order.len().saturating_sub(1)).rev().collect()
        };
        for c in columns {
            let neighbours = if forward { &preds } else { &succs };
            let mut keyed: Vec<(f32, usize)> = order[c]
                .iter()
                .enumerate()
                .map(|(i, &k)| {
                    let ns = &neighbours[k];
                    let key = if ns.is_empty() {
                        rank[k]
                    } else {
                        ns.iter().map(|&m| rank[m]).sum::<f32>() / ns.len() as f32
                    };
                    (key, i)
                })
                .collect();
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let col: Vec<usize> = keyed.iter().map(|&(_, i)| order[c][i]).collect();
            order[c] = col;
            for (i, &k) in order[c].iter().enumerate() {
                rank[k] = (i as f32 + 0.5) / order[c].len() as f32;
            }
        }
        let now = crossings(order, edges, layer);
        if now < best_crossings {
            best_crossings = now;
            best = order.to_vec();
        }
    }
    order.clone_from_slice(&best);
}

fn place(
    sizes: &[[f32; 2]],
    edges: &[(usize, usize)],
    order: &[Vec<usize>],
    gap: [f32; 2],
) -> Vec<[f32; 2]> {
    let n = sizes.len();
    let mut pos = vec![[0f32; 2]; n];
    let mut x = 0.0;
    for col in order {
        let width = col.iter().map(|&k| sizes[k][0]).fold(0.0, f32::max);
        let mut y = 0.0;
        for &k in col {
            pos[k] = [x, y];
            y += sizes[k][1] + gap[1];
        }
        x += width + gap[0];
    }
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(a, b) in edges {
        neighbours[a].push(b);
        neighbours[b].push(a);
    }
    let centre = |pos: &[[f32; 2]], k: usize| pos[k][1] + sizes[k][1] * 0.5;
    for _ in 0..6 {
        for col in order {
            // Desired tops: centred on the neighbours.
            let desired: Vec<f32> = col
                .iter()
                .map(|&k| {
                    let ns = &neighbours[k];
                    if ns.is_empty() {
                        pos[k][1]
                    } else {
                        ns.iter().map(|&m| centre(&pos, m)).sum::<f32>() / ns.len() as f32
                            - sizes[k][1] * 0.5
                    }
                })
                .collect();
            // Keep the order, no overlaps: one solution pushing down from the top, one pushing
            // up from the bottom; their mean keeps the gaps (both do) and balances the drift.
            let m = col.len();
            let mut down = desired.clone();
            for i in 1..m {
                down[i] = down[i].max(down[i - 1] + sizes[col[i - 1]][1] + gap[1]);
            }
            let mut up = desired;
            for i in (0..m.saturating_sub(1)).rev() {
                up[i] = up[i].min(up[i + 1] - sizes[col[i]][1] - gap[1]);
            }
            let tops: Vec<f32> = down.iter().zip(&up).map(|(a, b)| 0.5 * (a + b)).collect();
            for (i, &k) in col.iter().enumerate() {
                pos[k][1] = tops[i];
            }
        }
    }
    // Start at y = 0.
    let top = pos.iter().map(|p| p[1]).fold(f32::INFINITY, f32::min);
    for p in &mut pos {
        p[1] -= top;
    }
    pos
}

/// Whether two rectangles (top-left, size) overlap by more than `slack` on both axes.
pub fn overlap(a: ([f32; 2], [f32; 2]), b: ([f32; 2], [f32; 2]), slack: f32) -> bool {
    let (pa, sa) = a;
    let (pb, sb) = b;
    pa[0] + sa[0] - slack > pb[0]
        && pb[0] + sb[0] - slack > pa[0]
        && pa[1] + sa[1] - slack > pb[1]
        && pb[1] + sb[1] - slack > pa[1]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_overlaps(pos: &[[f32; 2]], sizes: &[[f32; 2]]) {
        for i in 0..pos.len() {
            for j in i + 1..pos.len() {
                assert!(
                    !overlap((pos[i], sizes[i]), (pos[j], sizes[j]), 0.0),
                    "{i} and {j} overlap: {:?} {:?}",
                    (pos[i], sizes[i]),
                    (pos[j], sizes[j])
                );
            }
        }
    }

    #[test]
    fn sources_left_sinks_right_no_overlaps() {
        // Two chains feeding one sink, with sizes of different heights.
        let sizes = vec![
            [120.0, 80.0],
            [140.0, 200.0],
            [100.0, 60.0],
            [160.0, 90.0],
            [130.0, 150.0],
        ];
        let edges = vec![(0, 1), (2, 3), (1, 4), (3, 4)];
        let pos = layered(&sizes, &edges, [60.0, 30.0]);
        for &(a, b) in &edges {
            assert!(pos[a][0] + sizes[a][0] <= pos[b][0], "{a} → {b} goes right");
        }
        no_overlaps(&pos, &sizes);
    }

    #[test]
    fn barycenter_sweeps_untangle_a_crossed_pair() {
        // Layer 0: a, b; layer 1: c, d; wires a → d, b → c cross in input order.
        let sizes = vec![[100.0, 50.0]; 4];
        let edges = vec![(0, 3), (1, 2)];
        let layer = layers(4, &edges);
        let tangled = vec![vec![0, 1], vec![2, 3]];
        assert_eq!(crossings(&tangled, &edges, &layer), 1);
        let mut order = tangled.clone();
        reduce_crossings(&mut order, &edges, &layer);
        assert_eq!(crossings(&order, &edges, &layer), 0, "{order:?}");
        let pos = layered(&sizes, &edges, [60.0, 30.0]);
        no_overlaps(&pos, &sizes);
    }

    #[test]
    fn a_parameter_sits_just_before_what_it_drives() {
        // a → b → c → d, and a slider s feeding d only: s goes into d's previous column.

        let edges = vec![(0, 1), (1, 2), (2, 3), (4, 3)];
        let l = layers(5, &edges);
        assert_eq!(l, vec![0, 1, 2, 3, 2]);
    }

    #[test]
    fn cycles_and_bad_edges_do_not_panic() {
        let sizes = vec![[10.0, 10.0]; 3];
        let pos = layered(
            &sizes,
            &[(0, 1), (1, 2), (2, 0), (5, 1), (1, 1)],
            [10.0, 10.0],
        );
        assert_eq!(pos.len(), 3);
        no_overlaps(&pos, &sizes);
    }
}
