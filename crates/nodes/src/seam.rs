//! `measure.seam`: how well two nets meet along a shared edge (`cnets_geometry::seam`).

use cnets_engine::prelude::*;

node! {
    /// The seam between two meshes: the boundary vertices of each lying within `search` of the
    /// other's boundary (and nearest to it from their own side, so a dense net's side vertices near
    /// a shared corner do not count), the largest distance from one of them to the other mesh's
    /// boundary, and the seam's length. A seam shared vertex for vertex reads 0; two nets moved
    /// 1 cm apart read 1 cm. No boundary vertex within `search` is an error saying how near the
    /// boundaries come.
    #[node(id = "measure.seam", category = "Measure", name = "Seam")]
    pub fn seam(
        /// The first mesh (a quad mesh converts).
        a: k::Mesh,
        /// The second mesh (a quad mesh converts).
        b: k::Mesh,
        /// How far from the other boundary a boundary vertex may be and still lie on the seam;
        /// empty: 1 % of the larger mesh's bounding-box diagonal.
        search: Option<k::Number>,
    ) -> (
        /// The largest distance from a seam vertex (of either mesh) to the other mesh's boundary.
        max_gap: k::Number,
        /// The seam's length, along the first mesh's boundary.
        length: k::Number,
        /// The seam's vertices: the first mesh's, then the second's.
        points: k::List<k::Point>,
    ) {
        let found = cnets_geometry::seam::seam(&a, &b, search)?;
        Ok((found.max_gap, found.length, found.points))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![seam()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::run_named;

    fn grid(offset: DVec3) -> Value {
        let points = (0..3)
            .flat_map(|i| (0..4).map(move |j| DVec3::new(j as f64, i as f64, 0.0) + offset))
            .collect();
        Value::from(QuadGrid::new(3, 4, points).unwrap())
    }

    #[test]
    fn the_node_measures_a_gap_and_its_length() {
        let out = run_named(
            &seam(),
            &[
                ("a", grid(DVec3::ZERO)),
                ("b", grid(DVec3::new(3.0, 0.0, 0.01))),
            ],
        )
        .unwrap();
        assert!((out[0].as_f64().unwrap() - 0.01).abs() < 1e-12);
        assert!((out[1].as_f64().unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(out[2].as_list().unwrap().len(), 6);
        let far = run_named(
            &seam(),
            &[
                ("a", grid(DVec3::ZERO)),
                ("b", grid(DVec3::new(9.0, 0.0, 0.0))),
            ],
        )
        .unwrap_err();
        assert!(far.contains("no seam"), "{far}");
    }
}
