//! Per-face analysis overlays: planarity and configuration class as face values and colours (used by
//! the export colours and the editor).

use cnets_engine::prelude::*;
use cnets_geometry::fabrication::{self as fab, FaceClass};

use crate::fabrication::fab_err;

node! {
    /// Planarity of every face of a mesh, in face order: quads by the libigl measure (distance between
    /// the diagonals over their mean length), triangles 0, larger polygons by the largest distance from
    /// their Newell plane over the mean edge length. `colours` maps 0 → green, limit/2 → yellow,
    /// ≥ limit → red (RGB in [0, 1], for `io.export_gltf`).
    #[node(id = "analysis.face_planarity", category = "Analysis")]
    pub fn face_planarity(
        /// The mesh (a quad grid converts).
        mesh: k::Mesh,
        /// The planarity shown fully red (> 0).
        limit: k::Number = 1e-3,
    ) -> (
        /// Planarity per face.
        values: k::List<k::Number>,
        /// The largest value.
        max: k::Number,
        /// Colour per face (RGB in [0, 1]).
        colours: k::List<k::Vector>,
    ) {
        if !(limit.is_finite() && limit > 0.0) {
            return Err(format!("limit must be a finite number > 0, got {limit}").into());
        }
        let values = fab::face_planarity(&mesh).map_err(fab_err)?;
        let max = values.iter().copied().fold(0.0, f64::max);
        let colours: Vec<DVec3> = values
            .iter()
            .map(|v| fab::planarity_colour(*v, limit))
            .collect();
        Ok((values, max, colours))
    }
}

/// Reads the configurations: N lists of M−1 labels.
fn label_rows(v: &Value) -> Result<Vec<Vec<String>>, NodeError> {
    let rows = v
        .as_list()
        .ok_or_else(|| NodeError::new("configurations must be N lists of M−1 labels"))?;
    rows.iter()
        .enumerate()
        .map(|(i, row)| match row {
            Value::List(items) => items
                .iter()
                .enumerate()
                .map(|(k, item)| match item {
                    Value::Text(t) => Ok(t.to_string()),
                    other => Err(NodeError::new(format!(
                        "configurations[{i}][{k}] is {}, expected a label such as \"++\"",
                        other.type_name()
                    ))),
                })
                .collect(),
            other => Err(NodeError::new(format!(
                "configurations[{i}] is {}, expected a list of labels",
                other.type_name()
            ))),
        })
        .collect()
}

node! {
    /// The configuration class of every face of a cone-net (paper Sec. 4.2.1, Fig. 5b) from the
    /// construction's `configurations` (N lists of M−1 labels c_{i,j}): face (i, j) combines c_{i,j}
    /// and c_{i+1,j}. Classes: 0 convex ((++),(++), green), 1 non-convex (mixed, red), 2 minus-minus
    /// ((−−),(−−), orange), 3 negative apex ((+−) or (−+), purple), 4 unclassified (no configuration: column 0 of an older M−2-label table, grey).
    /// `convex` and `convex_share` count the convex faces, e.g. a figure for a sweep.
    #[node(id = "analysis.face_classes", category = "Analysis")]
    pub fn face_classes(
        /// The constructed cone-net.
        mesh: k::QuadMesh,
        /// The construction's configurations: N lists of M−1 labels (`++`, `--`, `+-`, `-+`).
        configurations: k::Tree<k::Text>,
    ) -> (
        /// Class index per face (0 … 4, row-major over the quads).
        classes: k::List<k::Integer>,
        /// Class name per face.
        labels: k::List<k::Text>,
        /// Colour per face (RGB in [0, 1]).
        colours: k::List<k::Vector>,
        /// The number of convex faces (class 0, ((++),(++))).
        convex: k::Integer,
        /// The convex faces' share of all faces (0 to 1; 0 for a mesh without faces).
        convex_share: k::Number,
    ) {
        let rows = label_rows(&configurations)?;
        let classes = fab::face_classes(&mesh, &rows).map_err(fab_err)?;
        let index: Vec<usize> = classes.iter().map(|c| c.index()).collect();
        let names: Vec<&str> = classes.iter().map(|c| c.name()).collect();
        let colours: Vec<DVec3> = classes.iter().map(|c| FaceClass::colour(*c)).collect();
        let convex = classes.iter().filter(|c| **c == FaceClass::Convex).count();
        let share = if classes.is_empty() {
            0.0
        } else {
            convex as f64 / classes.len() as f64
        };
        Ok((index, names, colours, convex as i64, share))
    }
}

/// The face-attribute nodes.
pub fn nodes() -> Vec<NodeDef> {
    vec![face_planarity(), face_classes()]
}
