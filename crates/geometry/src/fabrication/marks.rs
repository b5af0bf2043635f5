//! Placing marks on unrolled strips (issue 43): where each strip meets its neighbours and where it
//! crosses the frames.
//!
//! **Neighbour marks.** Every panel edge a strip shares in the mesh with a panel of another strip (a
//! long edge, the seam to the mirrored half, or the joint to the next piece of a split strip) belongs
//! to a *run*: consecutive panels of the strip sharing edges with the same neighbour. Each run gets
//! one tick at the midpoint of its middle edge, pointing into the panel towards its centroid, 0.3 of
//! the way there, labelled with the neighbour's short name (`D3`).
//!
//! **Station marks.** For a station plane (origin o, unit normal n) every panel edge whose corners'
//! signed distances `d = (c − o)·n` change sign (`d ≥ 0` against `d < 0`) is crossed at
//! `t = d₀ / (d₀ − d₁)`; the flat point is the same interpolation of the edge's placed corners (the
//! unrolling is an isometry per panel, so it maps the 3D crossing onto it). A panel's crossings,
//! sorted along the crossing, give its segments; consecutive panels' segments meeting at their
//! shared rung (within 1e-9 of the strip size) are joined into one polyline, labelled `S<k>` for
//! station k.

use std::collections::HashMap;

use glam::DVec3;

use super::panels::StripPanels;
use crate::Plane;

/// One mark on an unrolled strip: a polyline in the flat layout and its text.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// The strip (index into the list of strips or pieces) it is on.
    pub strip: usize,
    /// The mark (z = 0).
    pub line: Vec<DVec3>,
    /// Its text: the neighbour's short name, or `S<k>`.
    pub label: String,
}

/// The neighbour marks of every strip (see the module docs), strip after strip.
pub fn neighbour_marks(strips: &[StripPanels]) -> Vec<Mark> {
    let key = |a: usize, b: usize| (a.min(b), a.max(b));
    let mut owners: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (s, strip) in strips.iter().enumerate() {
        for p in &strip.panels {
            let n = p.ids.len();
            for t in 0..n {
                let list = owners.entry(key(p.ids[t], p.ids[(t + 1) % n])).or_default();
                if !list.contains(&s) {
                    list.push(s);
                }
            }
        }
    }
    let mut out = Vec::new();
    for (s, strip) in strips.iter().enumerate() {
        // (neighbour, panel, edge) in panel order.
        let mut shared: Vec<(usize, usize, usize)> = Vec::new();
        for (k, p) in strip.panels.iter().enumerate() {
            let n = p.ids.len();
            for t in 0..n {
                let list = &owners[&key(p.ids[t], p.ids[(t + 1) % n])];
                if let Some(&other) = list.iter().find(|&&o| o != s) {
                    shared.push((other, k, t));
                }
            }
        }
        let mut neighbours: Vec<usize> = shared.iter().map(|x| x.0).collect();
        neighbours.sort_unstable();
        neighbours.dedup();
        for other in neighbours {
            let edges: Vec<(usize, usize)> = shared
                .iter()
                .filter(|x| x.0 == other)
                .map(|x| (x.1, x.2))
                .collect();
            let mut start = 0;
            for i in 1..=edges.len() {
                if i == edges.len() || edges[i].0 > edges[i - 1].0 + 1 {
                    let (k, t) = edges[(start + i - 1) / 2];
                    out.push(Mark {
                        strip: s,
                        line: tick(&strip.panels[k].flat, t),
                        label: strips[other].name.clone(),
                    });
                    start = i;
                }
            }
        }
    }
    out
}

/// A tick from the midpoint of edge `t` of a placed panel towards its centroid, 0.3 of the way.
fn tick(flat: &[DVec3], t: usize) -> Vec<DVec3> {
    let n = flat.len();
    let mid = (flat[t] + flat[(t + 1) % n]) * 0.5;
    let centroid = flat.iter().sum::<DVec3>() / n as f64;
    vec![mid, mid + (centroid - mid) * 0.3]
}

/// The station marks of every strip for every plane (see the module docs), strip after strip,
/// station after station.
pub fn station_marks(strips: &[StripPanels], stations: &[Plane]) -> Vec<Mark> {
    let mut out = Vec::new();
    for (s, strip) in strips.iter().enumerate() {
        let size = strip
            .panels
            .iter()
            .flat_map(|p| p.flat.iter())
            .fold(0.0f64, |m, p| m.max(p.length()));
        let tol = 1e-9 * size.max(f64::MIN_POSITIVE);
        for (k, plane) in stations.iter().enumerate() {
            let mut lines: Vec<Vec<DVec3>> = Vec::new();
            for p in &strip.panels {
                let d: Vec<f64> = p
                    .corners
                    .iter()
                    .map(|c| (*c - plane.origin).dot(plane.normal))
                    .collect();
                let n = d.len();
                let mut hits: Vec<DVec3> = (0..n)
                    .filter(|&i| (d[i] >= 0.0) != (d[(i + 1) % n] >= 0.0))
                    .map(|i| {
                        let j = (i + 1) % n;
                        let t = d[i] / (d[i] - d[j]);
                        p.flat[i] + (p.flat[j] - p.flat[i]) * t
                    })
                    .collect();
                if hits.len() < 2 {
                    continue;
                }
                let dir = hits[1] - hits[0];
                hits.sort_by(|a, b| a.dot(dir).total_cmp(&b.dot(dir)));
                for pair in hits.chunks_exact(2) {
                    let (a, b) = (pair[0], pair[1]);
                    match lines.last_mut() {
                        Some(l) if l.last().is_some_and(|q| q.distance(a) <= tol) => l.push(b),
                        Some(l) if l.last().is_some_and(|q| q.distance(b) <= tol) => l.push(a),
                        _ => lines.push(vec![a, b]),
                    }
                }
            }
            out.extend(lines.into_iter().map(|line| Mark {
                strip: s,
                line,
                label: format!("S{k}"),
            }));
        }
    }
    out
}
