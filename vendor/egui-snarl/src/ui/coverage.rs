//! cnets: wires that would be drawn over wires already drawn are skipped.
//!
//! A slider feeding a thousand nodes sends a thousand wires down the same column of the canvas:
//! each was tessellated and filled, one over the other, and on a software rasterizer (lavapipe,
//! SwiftShader) that band cost more than the rest of the frame (issue 26: 28 ms of a 78 ms frame
//! with 1 250 such wires). The view is divided into square cells half a wire's width wide; a run
//! of a wire is not drawn when every point along it (sampled at most a cell apart in x and y) in view
//! lies in a cell that an earlier drawn wire of the same colour and width passes through. Such a run lies within
//! √2 · ½ ≈ 0.71 of a wire's width of a drawn wire of the same stroke everywhere, so the picture
//! is the same band. (Tested by the editor: `crates/editor/tests/it/wire_coverage.rs`.)

use egui::{Pos2, Rect, Stroke};

/// Above this many cells (a very large view) nothing is skipped.
const MAX_CELLS: usize = 1 << 24;

/// The cells of the view that drawn wires pass through, one bit set per stroke.
pub struct WireCoverage {
    view: Rect,
    cell: f32,
    cols: usize,
    rows: usize,
    /// Per stroke drawn so far: a bit per cell.
    strokes: Vec<(Stroke, Vec<u64>)>,
}

impl WireCoverage {
    /// Coverage over `view` (in the canvas's coordinates) for wires `wire_width` wide.
    pub fn new(view: Rect, wire_width: f32) -> Self {
        let cell = (wire_width * 0.5).max(0.25);
        let cols = (view.width() / cell).ceil().max(0.0) as usize + 1;
        let rows = (view.height() / cell).ceil().max(0.0) as usize + 1;
        let (cols, rows) = if view.is_finite() && cols.saturating_mul(rows) <= MAX_CELLS {
            (cols, rows)
        } else {
            (0, 0)
        };
        Self {
            view,
            cell,
            cols,
            rows,
            strokes: Vec::new(),
        }
    }

    /// True when every point of `run` within the view lies in a cell a drawn wire of `stroke`
    /// passes through;
    /// otherwise marks the run's cells as drawn and returns false.
    pub fn covered_else_mark(&mut self, run: &[Pos2], stroke: Stroke) -> bool {
        if self.cols == 0 || run.len() < 2 {
            return false;
        }
        let index = match self.strokes.iter().position(|(s, _)| *s == stroke) {
            Some(i) => i,
            None => {
                let words = (self.cols * self.rows).div_ceil(64);
                self.strokes.push((stroke, vec![0; words]));
                self.strokes.len() - 1
            }
        };
        let bits = &self.strokes[index].1;
        let mut covered = true;
        self.visit(run, |cell| {
            // (A point outside the view is not seen: it cannot show a difference.)
            let hit = cell.is_none_or(|c| bits[c / 64] >> (c % 64) & 1 == 1);
            covered &= hit;
            hit
        });
        if covered {
            return true;
        }
        let mut marks = std::mem::take(&mut self.strokes[index].1);
        self.visit(run, |cell| {
            if let Some(c) = cell {
                marks[c / 64] |= 1 << (c % 64);
            }
            true
        });
        self.strokes[index].1 = marks;
        false
    }

    /// Calls `f` with the cell of each point along `run` (consecutive points at most a cell apart
    /// in x and in y; `None` outside the view) until it returns false.
    fn visit(&self, run: &[Pos2], mut f: impl FnMut(Option<usize>) -> bool) {
        let inv = 1.0 / self.cell;
        let grid = |p: Pos2| ((p.x - self.view.min.x) * inv, (p.y - self.view.min.y) * inv);
        let (mut x, mut y) = grid(run[0]);
        if !f(self.cell_at(x, y)) {
            return;
        }
        for &b in &run[1..] {
            let (bx, by) = grid(b);
            let steps = (bx - x).abs().max((by - y).abs()).ceil().clamp(1.0, 1e6);
            let (sx, sy) = ((bx - x) / steps, (by - y) / steps);
            for _ in 0..steps as usize {
                x += sx;
                y += sy;
                if !f(self.cell_at(x, y)) {
                    return;
                }
            }
            (x, y) = (bx, by);
        }
    }

    /// The cell at grid coordinates (`None` outside the view).
    #[inline]
    fn cell_at(&self, x: f32, y: f32) -> Option<usize> {
        if !(x >= 0.0 && y >= 0.0) {
            return None;
        }
        let (x, y) = (x as usize, y as usize);
        (x < self.cols && y < self.rows).then_some(y * self.cols + x)
    }
}
