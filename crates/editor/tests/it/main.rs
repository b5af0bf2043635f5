//! The editor's integration tests, one test binary (one link of egui and wgpu instead of one a
//! file): each module is what was a `tests/<name>.rs` binary. Run one module's tests with
//! `cargo test -p cnets-editor --test it <module>::` (e.g. `window::`); snapshots stay in
//! `tests/snapshots/`, test data in `tests/data/`. The real-window tests (`window`) play the
//! binary's test kit: they need `--features drivers` (scripts/test.sh passes it).

/// Without the feature `drivers` the window tests cannot run: one test says so and fails, rather
/// than the suite passing without them (`CNETS_SKIP_WINDOW_TEST=1` lets it pass).
#[cfg(not(feature = "drivers"))]
#[test]
fn the_window_tests_need_the_drivers_feature() {
    assert!(
        std::env::var_os("CNETS_SKIP_WINDOW_TEST").is_some(),
        "the window tests play the editor binary's test kit: run `cargo test -p cnets-editor \
         --features drivers` (scripts/test.sh does), or set CNETS_SKIP_WINDOW_TEST=1"
    );
}

mod clusters;
mod common;
mod context_menus;
mod cplanes;
mod design_in_space;
mod editor;
mod everyday_fluency;
mod files_and_names;
mod glyphs;
mod imported_files;
mod library_components;
mod list_editor;
mod mapper_truth;
mod never_lose_work;
mod no_guessing;
mod open_and_view;
mod optimization;
mod parameters;
mod planarity_meshes;
mod project_size;
mod shipped_graphs;
mod slow_node;
mod toolbox_nodes;
#[cfg(feature = "drivers")]
mod window;
mod wire_coverage;
