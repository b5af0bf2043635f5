//! The panel schedule: one row per panel of the unrolled strips, for the quantity surveyor and the
//! workshop's parts list.
//!
//! Every row names the panel as the cutting files do — the strip's label from the unrolling (`D4`,
//! `D9 (mirror of D2)`), the piece it is cut on when strips are split at a length (`D4.2`), its
//! number in the strip and its face in the mesh — and measures the 3D panel: its corners, its area
//! (half the length of the Newell vector: exact for a planar polygon, convex or not), the length of
//! every edge (edge e runs from corner e to corner e + 1, in the mesh's corner order), its planarity
//! ([`super::polygon_planarity`]) and the signed fold angles to the previous and the next panel of
//! its strip ([`super::folds`]: mountain positive; none at a strip's ends and where a closed strip
//! was cut open). The folds are those of the *whole* strip, so a joint between two pieces still
//! has its angle: the pieces are bent there once joined.

use glam::DVec3;

use super::folds::folds;
use super::panels::{PanelSource, StripPanels};
use super::polygon::newell_vector;
use super::polygon_planarity;

/// One panel of the schedule.
#[derive(Debug, Clone, PartialEq)]
pub struct ScheduleRow {
    /// The strip's position in the list of strips.
    pub strip: usize,
    /// The strip's label, as `pq.unroll_strips` writes it without `max_length` (`D4`).
    pub label: String,
    /// The label of the piece the panel is cut on (the strip's label when it is not split).
    pub piece: String,
    /// The panel's number in its strip (0 at the strip's first panel).
    pub panel: usize,
    /// Where the panel is in the mesh.
    pub source: PanelSource,
    /// The 3D corners, in the mesh's corner order.
    pub corners: Vec<DVec3>,
    /// The panel's area: |Newell vector| / 2.
    pub area: f64,
    /// The length of every edge, edge e from corner e to corner e + 1.
    pub edges: Vec<f64>,
    /// The signed fold angle (radians) to the previous panel of the strip, if there is a fold.
    pub fold_previous: Option<f64>,
    /// The signed fold angle (radians) to the next panel of the strip, if there is a fold.
    pub fold_next: Option<f64>,
    /// The panel's planarity (libigl measure for quads).
    pub planarity: f64,
}

/// The area of a polygon in 3D: half the length of its Newell vector.
pub fn polygon_area(corners: &[DVec3]) -> f64 {
    0.5 * newell_vector(corners).length()
}

/// The piece label of every panel of every strip: `pieces` are the strips' pieces in strip order
/// (each strip's first piece starts at panel 0), or the strips themselves.
fn piece_labels(strips: &[StripPanels], pieces: &[StripPanels]) -> Vec<Vec<String>> {
    let mut out: Vec<Vec<String>> = strips
        .iter()
        .map(|s| vec![s.label.clone(); s.panels.len()])
        .collect();
    let mut strip = 0usize;
    for (k, piece) in pieces.iter().enumerate() {
        if k > 0 && piece.first_panel == 0 {
            strip += 1;
        }
        let Some(labels) = out.get_mut(strip) else {
            break;
        };
        for p in 0..piece.panels.len() {
            if let Some(slot) = labels.get_mut(piece.first_panel + p) {
                *slot = piece.label.clone();
            }
        }
    }
    out
}

/// The schedule of unrolled strips: one row per panel, strip after strip, panel after panel.
/// `pieces`: the pieces the strips were split into (`split_strips`), or `strips` itself.
pub fn schedule(strips: &[StripPanels], pieces: &[StripPanels]) -> Vec<ScheduleRow> {
    let labels = piece_labels(strips, pieces);
    let mut rows: Vec<ScheduleRow> = Vec::new();
    let mut first_row = Vec::with_capacity(strips.len());
    for (s, strip) in strips.iter().enumerate() {
        first_row.push(rows.len());
        for (k, panel) in strip.panels.iter().enumerate() {
            let c = &panel.corners;
            let n = c.len();
            rows.push(ScheduleRow {
                strip: s,
                label: strip.label.clone(),
                piece: labels[s][k].clone(),
                panel: strip.first_panel + k,
                source: panel.source,
                corners: c.clone(),
                area: polygon_area(c),
                edges: (0..n).map(|e| c[e].distance(c[(e + 1) % n])).collect(),
                fold_previous: None,
                fold_next: None,
                planarity: polygon_planarity(c),
            });
        }
    }
    for fold in folds(strips) {
        let at = first_row[fold.strip] + fold.panel;
        rows[at - 1].fold_next = Some(fold.angle);
        rows[at].fold_previous = Some(fold.angle);
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fabrication::panels::Panel;

    fn panel(corners: Vec<DVec3>, ids: Vec<usize>, flat: Vec<DVec3>, face: usize) -> Panel {
        Panel {
            source: PanelSource::Face(face),
            ids,
            corners,
            flat,
        }
    }

    /// Two unit squares folded by a quarter turn about their shared edge x = 1, the second going
    /// down (a mountain seen from +z).
    fn folded() -> StripPanels {
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let a = panel(
            vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.), p(0., 1., 0.)],
            vec![0, 1, 2, 3],
            vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 1., 0.), p(0., 1., 0.)],
            0,
        );
        let b = panel(
            vec![p(1., 0., 0.), p(1., 0., -2.), p(1., 1., -2.), p(1., 1., 0.)],
            vec![1, 4, 5, 2],
            vec![p(1., 0., 0.), p(3., 0., 0.), p(3., 1., 0.), p(1., 1., 0.)],
            1,
        );
        StripPanels {
            label: "D0".into(),
            name: "D0".into(),
            panels: vec![a, b],
            first_panel: 0,
            collapsed: Vec::new(),
        }
    }

    #[test]
    fn rows_measure_the_panels_and_their_fold() {
        let strip = folded();
        let rows = schedule(std::slice::from_ref(&strip), std::slice::from_ref(&strip));
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].area, 1.0);
        assert_eq!(rows[1].area, 2.0);
        assert_eq!(rows[1].edges, vec![2.0, 1.0, 2.0, 1.0]);
        assert_eq!(rows[0].fold_previous, None);
        assert_eq!(rows[1].fold_next, None);
        let angle = rows[0].fold_next.unwrap();
        assert!(
            (angle - std::f64::consts::FRAC_PI_2).abs() < 1e-15,
            "{angle}"
        );
        assert_eq!(rows[1].fold_previous, Some(angle));
        assert_eq!((rows[1].panel, rows[1].piece.as_str()), (1, "D0"));
    }

    #[test]
    fn pieces_name_their_panels() {
        let strip = folded();
        let mut one = strip.clone();
        one.panels.truncate(1);
        one.label = "D0.1".into();
        let mut two = strip.clone();
        two.panels.remove(0);
        two.label = "D0.2".into();
        two.first_panel = 1;
        let rows = schedule(std::slice::from_ref(&strip), &[one, two]);
        let names: Vec<&str> = rows.iter().map(|r| r.piece.as_str()).collect();
        assert_eq!(names, ["D0.1", "D0.2"]);
        // The joint keeps its fold.
        assert!(rows[0].fold_next.is_some());
    }
}
