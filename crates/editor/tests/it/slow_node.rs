//! Never frozen by a slow node (issue 26, point 4): the facade with a slider on its support layer,
//! whose beams are unrolled and nested (`fab.nest`, the slow node, not previewed) below it. Every
//! slider step is drawn as soon as the previewed nodes are done, while the nest still runs; the
//! nest shows that it runs and how long it took last, and catches up after the last step.

use crate::common;

use std::time::{Duration, Instant};

use cnets_editor::edit::Edit;
use cnets_editor::worker::NodeStatus;
use cnets_engine::Value;
use common::{graphs_dir, harness_with, settle, temp_config};

/// graphs/facade.ron with a `lean` slider driving `support.factor` (as `scripts/scale-graphs.py`
/// writes the `--bench-drag` graph slow-nest.ron).
fn slow_nest() -> String {
    let facade = std::fs::read_to_string(graphs_dir().join("facade.ron")).unwrap();
    let slider = "        \"lean\": (type: \"param.number\", position: (1100.0, -200.0), \
                  inputs: {\"value\": 0.92, \"min\": 0.85, \"max\": 0.98}),\n";
    let text = facade.replacen("    nodes: {\n", &format!("    nodes: {{\n{slider}"), 1);
    text.replacen(
        "    edges: [\n",
        "    edges: [\n        \"lean.value -> support.factor\",\n",
        1,
    )
}

fn nest_ms(status: &NodeStatus) -> f64 {
    match status {
        NodeStatus::Ok { time_ms, .. } => *time_ms,
        other => panic!("the nest did not run: {other:?}"),
    }
}

#[test]
fn every_slider_step_is_drawn_before_the_slow_nest_below_it_finishes() {
    let dir = temp_config("slow-node-files");
    let file = dir.join("slow-nest.ron");
    std::fs::write(&file, slow_nest()).unwrap();
    let mut h = harness_with("slow-node", Some(file), temp_config("slow-node"));
    settle(&mut h);
    let first_nest_ms = nest_ms(&h.state().statuses()["nest"]);
    let mut times: Vec<(String, f64)> = h
        .state()
        .statuses()
        .iter()
        .filter_map(|(id, s)| match s {
            NodeStatus::Ok { time_ms, .. } if *time_ms >= 1.0 => Some((id.clone(), *time_ms)),
            _ => None,
        })
        .collect();
    times.sort_by(|a, b| b.1.total_cmp(&a.1));
    println!("node times after opening (ms): {times:?}");
    let steps = 10;
    let mut running_seen = 0;
    for k in 0..steps {
        let before = h.state().viewport().scene().clone();
        let pictures = h.state().latency().samples.len();
        let value = 0.86 + 0.01 * f64::from(k);
        assert!(h.state_mut().edit(Edit::SetValue {
            node: "lean".into(),
            input: "value".into(),
            value: Value::Number(value),
        }));
        // Frames as the window runs them, until this step's picture is drawn (the limit only
        // keeps a broken build from hanging: a picture comes within a second or two).
        let limit = Instant::now() + Duration::from_secs(120);
        while h.state().latency().samples.len() == pictures {
            assert!(Instant::now() < limit, "step {k}: no picture in 120 s");
            h.step();
            std::thread::sleep(Duration::from_millis(2));
        }
        let app = h.state();
        assert!(
            !std::sync::Arc::ptr_eq(&before, app.viewport().scene())
                && before.face_vertices() != app.viewport().scene().face_vertices(),
            "step {k}: the surface in the view follows the slider"
        );
        if let Some(NodeStatus::Running { last_ms }) = app.statuses().get("nest") {
            assert!(*last_ms > 0.0, "the running nest shows its last time");
            running_seen += 1;
        }
    }
    let early = h.state().latency().early_pictures;
    println!(
        "{early} of {steps} slider steps drawn before the nest ({first_nest_ms:.0} ms) finished; \
         the nest shown running at {running_seen}"
    );
    assert!(
        early * 10 >= steps as usize * 8,
        "only {early} of {steps} pictures came before the rest of the graph finished"
    );
    assert!(running_seen > 0, "the nest was never shown running");
    // The nest catches up with the last step.
    settle(&mut h);
    assert!(!h.state().busy());
    nest_ms(&h.state().statuses()["nest"]);
}
