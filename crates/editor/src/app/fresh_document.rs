//! What a newly opened document still waits for: the overlap check once its nodes are measured
//! (the status bar's hint to arrange them), and framing the canvas again when its first results
//! are drawn (nodes grow when their outputs get summaries).

use crate::canvas::Canvas;

/// The checks a document gets once, after it opens.
pub struct FreshDocument {
    /// Check whether the nodes overlap once they are measured.
    check_overlaps: bool,
    /// The status bar shows the hint to arrange: the document opened with overlapping nodes and
    /// they still overlap.
    pub overlap_hint: bool,
    /// Frame the canvas again once the first results are drawn.
    refit_on_results: bool,
}

impl Default for FreshDocument {
    fn default() -> Self {
        Self {
            check_overlaps: true,
            overlap_hint: false,
            refit_on_results: true,
        }
    }
}

impl FreshDocument {
    /// A document was opened: its checks are due again.
    pub fn opened(&mut self) {
        *self = FreshDocument::default();
    }

    /// Whether the canvas should be framed now, the first results being drawn (once).
    pub fn take_refit(&mut self) -> bool {
        std::mem::take(&mut self.refit_on_results)
    }

    /// Each frame: once the `node_count` nodes are measured, whether they overlap (the hint);
    /// the hint goes once they no longer overlap (arranged, or moved apart).
    pub fn watch_overlaps(&mut self, canvas: &Canvas, node_count: usize) {
        if self.check_overlaps && canvas.measured(node_count) {
            self.check_overlaps = false;
            self.overlap_hint = canvas.has_overlaps();
        } else if self.overlap_hint && !canvas.has_overlaps() {
            self.overlap_hint = false;
        }
    }
}
