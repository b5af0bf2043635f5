//! Convexity margins: how far each face of a constructed net is from folding (paper Sec. 4.2,
//! `shared/inverse-design-notes.md`). A configuration c_{i,j} is (++) when
//! `s1 = (G_{i,j+1} − X_j)·P_{i,j} > 0` and `s2 = (X_{j+1} − G_{i,j})·P_{i,j+1} > 0`
//! ([`super::configuration`]); a face (i, j) is (++)(++) when c_{i,j} and c_{i+1,j} are. Divided by
//! the directrix edge `|X_{j+1} − X_j|` the two numbers are unit-free, so one margin threshold fits
//! every design. These are what the optimizer's `convex` constraint keeps positive.

use glam::DVec3;

use super::configuration::generatrix_normal;
use super::result::ConeNet;

/// Margins per face.
pub const PER_FACE: usize = 4;

/// The unit-free margins of every face of `net`, row-major over its quads (quad rows × M−1),
/// [`PER_FACE`] each: s1 and s2 of c_{i,j}, then of c_{i+1,j} (the row after, wrapping when the
/// generatrix is closed), each divided by `|X_{j+1} − X_j|`. A face is (++)(++) exactly when its
/// four margins are positive.
pub fn face_margins(net: &ConeNet) -> Vec<f64> {
    let configs = configuration_margins(net);
    let (n, m) = (net.mesh.rows, net.directrix.len());
    let cols = m.saturating_sub(1);
    let quad_rows = net.mesh.quad_rows();
    let mut out = Vec::with_capacity(quad_rows * cols * PER_FACE);
    for i in 0..quad_rows {
        let next = (i + 1) % n.max(1);
        for j in 0..cols {
            let a = 2 * (i * cols + j);
            let b = 2 * (next * cols + j);
            out.extend_from_slice(&[configs[a], configs[a + 1], configs[b], configs[b + 1]]);
        }
    }
    out
}

/// The unit-free s1, s2 of every configuration c_{i,j} (N rows × M−1, two numbers each).
pub fn configuration_margins(net: &ConeNet) -> Vec<f64> {
    let x = &net.directrix;
    let (n, m) = (net.mesh.rows, x.len());
    let cols = m.saturating_sub(1);
    let g = |i: usize, j: usize| net.mesh.vertices[i * m + j];
    let mut out = Vec::with_capacity(n * cols * 2);
    let e1 = (x.get(1).copied().unwrap_or(DVec3::X) - x[0]).normalize_or(DVec3::X);
    for i in 0..n {
        for j in 0..cols {
            let length = (x[j + 1] - x[j]).length();
            let scale = if length > 0.0 { 1.0 / length } else { 0.0 };
            let p_before = if j == 0 {
                generatrix_normal(x[0], e1, g(i, 0))
            } else {
                net.normals.get(i, j)
            };
            let s1 = (g(i, j + 1) - x[j]).dot(p_before);
            let s2 = (x[j + 1] - g(i, j)).dot(net.normals.get(i, j + 1));
            out.push(s1 * scale);
            out.push(s2 * scale);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Polyline;
    use crate::conenet::{ConstructInputs, GridValues, construct};

    fn net(ratios: Vec<Vec<f64>>, apex: f64) -> ConeNet {
        let directrix = Polyline::open(
            (0..9)
                .map(|k| {
                    let t = k as f64 * 0.3;
                    DVec3::new(4.0 * t.cos(), 4.0 * t.sin(), 0.4 * t)
                })
                .collect(),
        );
        let generatrix = Polyline::open(
            (0..6)
                .map(|k| DVec3::new(4.5 + 0.5 * k as f64, 0.0, 0.6 * k as f64 + 0.3))
                .collect(),
        );
        let mut c = ConstructInputs::new(directrix, generatrix);
        c.ratios = GridValues::PerVertex(ratios);
        c.apex.values = crate::conenet::ColumnValues::Uniform(apex);
        construct(&c).unwrap()
    }

    #[test]
    fn the_signs_of_the_margins_are_the_configurations() {
        // Smooth ratios (all (++)), then wild ones that fold some configurations.
        for (k, table) in [
            vec![vec![0.5; 8]; 6],
            (0..6)
                .map(|i| {
                    (0..8)
                        .map(|j| 0.05 + 0.09 * ((i * 7 + j * 3) % 10) as f64)
                        .collect()
                })
                .collect::<Vec<Vec<f64>>>(),
        ]
        .into_iter()
        .enumerate()
        {
            let net = net(table, 0.97);
            let margins = configuration_margins(&net);
            let cols = net.directrix.len() - 1;
            let mut folded = 0;
            for i in 0..net.mesh.rows {
                for j in 0..cols {
                    let (s1, s2) = (margins[2 * (i * cols + j)], margins[2 * (i * cols + j) + 1]);
                    let c = crate::conenet::Configuration::from_signs(s1, s2);
                    assert_eq!(c, net.configurations.get(i, j), "case {k} ({i}, {j})");
                    folded += usize::from(!c.is_good());
                }
            }
            assert_eq!(
                folded > 0,
                k == 1,
                "case {k}: {folded} folded configurations"
            );
            // Faces: (++)(++) exactly when their four margins are positive.
            let faces = face_margins(&net);
            assert_eq!(faces.len(), net.mesh.quad_rows() * cols * PER_FACE);
            for (f, four) in faces.chunks_exact(PER_FACE).enumerate() {
                let (i, j) = (f / cols, f % cols);
                let good = net.configurations.get(i, j).is_good()
                    && net.configurations.get(i + 1, j).is_good();
                assert_eq!(four.iter().all(|&s| s > 0.0), good, "face ({i}, {j})");
            }
        }
    }
}
