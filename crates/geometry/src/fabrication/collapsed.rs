//! Collapsed edges of unrolled strips (issue 43): an edge the correction shrank to (almost) nothing.
//!
//! A panel edge shorter than [`COLLAPSED_EDGE`] times the mesh size cannot be cut and its relative
//! length change is rounding noise over a tiny length (an edge of 2.5e-12 m on a 12 m hull reads as a
//! 3.4e-5 relative error). Such an edge is *collapsed*: it is reported by strip and panel (the
//! `degenerate` output of `pq.unroll_strips`), and its length change counts in `max_length_error`
//! relative to the mesh size instead of its own length, so the figure stays the honest ≤ 1e-9 of a
//! planar mesh.

use super::panels::StripPanels;

/// Edges shorter than this fraction of the mesh size are collapsed.
pub const COLLAPSED_EDGE: f64 = 1e-6;

/// One collapsed edge of an unrolled strip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollapsedEdge {
    /// The panel (face) of the strip, in strip order.
    pub panel: usize,
    /// The edge of the panel (from corner `edge` to the next), in the mesh's corner order.
    pub edge: usize,
    /// Its length in the 3D mesh.
    pub length: f64,
}

/// The length error of one edge (3D length `l3`, flat length `l2`) in a mesh of size `scale`:
/// relative to the edge, or to the mesh size for a collapsed edge; `true` when it is collapsed.
pub fn edge_error(l3: f64, l2: f64, scale: f64) -> (f64, bool) {
    if l3 > COLLAPSED_EDGE * scale {
        ((l2 - l3).abs() / l3, false)
    } else {
        ((l2 - l3).abs() / scale, true)
    }
}

/// What the `degenerate` output says of a collapsed edge: strip, panel, where in the mesh, and how
/// long it is.
pub fn describe(strip: &str, edge: &CollapsedEdge, source: &str) -> String {
    format!(
        "{strip} panel {} ({source}): edge {} collapsed to {:.3e} (shorter than {COLLAPSED_EDGE:e} of the mesh size)",
        edge.panel, edge.edge, edge.length
    )
}

/// The `degenerate` lines of every collapsed edge of the strips, strip after strip.
pub fn describe_all(strips: &[StripPanels]) -> Vec<String> {
    strips
        .iter()
        .flat_map(|s| {
            s.collapsed.iter().map(move |c| {
                let source = s
                    .panels
                    .get(c.panel)
                    .map_or(String::new(), |p| p.source.to_string());
                describe(&s.name, c, &source)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tiny_edge_is_measured_against_the_mesh_size() {
        let (err, collapsed) = edge_error(2.5e-12, 2.5e-12 + 8.5e-17, 12.0);
        assert!(collapsed);
        assert!(err < 1e-15, "{err}");
        let (err, collapsed) = edge_error(1.0, 1.0 + 1e-12, 12.0);
        assert!(!collapsed);
        assert!((err - 1e-12).abs() < 1e-15);
    }
}
