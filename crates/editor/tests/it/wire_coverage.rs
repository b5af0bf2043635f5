//! egui-snarl's wire coverage (vendored, `vendor/egui-snarl/src/ui/coverage.rs`): a wire run over
//! wires already drawn with the same stroke is skipped, anything else is drawn (issue 26).

use egui::{Color32, Rect, Stroke, pos2};
use egui_snarl::ui::WireCoverage;

fn stroke(color: Color32) -> Stroke {
    Stroke::new(2.0, color)
}

#[test]
fn a_run_over_a_drawn_one_is_covered_and_one_beside_it_is_not() {
    let view = Rect::from_min_max(pos2(0.0, 0.0), pos2(100.0, 100.0));
    let mut c = WireCoverage::new(view, 2.0);
    let blue = stroke(Color32::BLUE);
    let down = [pos2(10.2, 0.0), pos2(10.2, 90.0)];
    assert!(!c.covered_else_mark(&down, blue), "the first wire is drawn");
    assert!(c.covered_else_mark(&[pos2(10.4, 5.0), pos2(10.4, 80.0)], blue));
    // Two wire widths to the side: drawn.
    assert!(!c.covered_else_mark(&[pos2(14.2, 5.0), pos2(14.2, 80.0)], blue));
    // Longer than the drawn ones: drawn.
    assert!(!c.covered_else_mark(&[pos2(10.2, 0.0), pos2(10.2, 99.0)], blue));
    // Another colour or width is never covered by this one.
    assert!(!c.covered_else_mark(&down, stroke(Color32::RED)));
    assert!(!c.covered_else_mark(&down, Stroke::new(3.0, Color32::BLUE)));
}

#[test]
fn only_the_part_in_view_counts_and_huge_views_skip_nothing() {
    let view = Rect::from_min_max(pos2(0.0, 0.0), pos2(50.0, 50.0));
    let mut c = WireCoverage::new(view, 2.0);
    let blue = stroke(Color32::BLUE);
    assert!(!c.covered_else_mark(&[pos2(10.0, 10.0), pos2(10.0, 70.0)], blue));
    // The same column to another node further down: its part in view is drawn already.
    assert!(c.covered_else_mark(&[pos2(10.0, 10.0), pos2(10.0, 700.0)], blue));
    // Beside it in view: drawn.
    assert!(!c.covered_else_mark(&[pos2(20.0, 10.0), pos2(20.0, 700.0)], blue));
    let huge = Rect::from_min_max(pos2(0.0, 0.0), pos2(1e7, 1e7));
    let mut c = WireCoverage::new(huge, 2.0);
    let run = [pos2(1.0, 1.0), pos2(2.0, 2.0)];
    assert!(!c.covered_else_mark(&run, blue));
    assert!(!c.covered_else_mark(&run, blue));
}
