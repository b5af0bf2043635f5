//! The shipped library (`graphs/library/`) in the palette: the editor started on the examples
//! folder `graphs/` lists every reusable cluster of its `library` subfolder, and one inserts as a
//! cluster node with the graph's documented ports.

use crate::common;

use cnets_engine::cluster::Cluster;
use common::{graphs_dir, harness_on, temp_config};
use egui_kittest::kittest::Queryable;

#[test]
fn the_shipped_library_is_listed_in_the_palette_and_inserts() {
    let mut h = harness_on(temp_config("library-components"), None, graphs_dir());
    let names: Vec<String> = {
        h.state_mut()
            .rescan_library()
            .iter()
            .map(|e| e.name.clone())
            .collect()
    };
    for name in [
        "closed-tube",
        "reference-fit",
        "strip-fabrication",
        "support-structure",
    ] {
        assert!(names.contains(&name.to_string()), "{name} in {names:?}");
    }
    for name in ["strip-fabrication", "support-structure", "reference-fit"] {
        h.state_mut().open_palette_at([900.0, 700.0]);
        h.run_steps(2);
        h.get_by(|n| n.role() == egui::accesskit::Role::TextInput && n.is_focused())
            .type_text(name);
        h.run_steps(3);
        assert!(
            h.query_by_label(&format!("{name} (cluster)")).is_some(),
            "{name} is shown in the palette"
        );
        h.state_mut().close_palette();
        h.run_steps(2);
    }
    h.state_mut().open_palette_at([900.0, 700.0]);
    h.run_steps(2);
    h.get_by(|n| n.role() == egui::accesskit::Role::TextInput && n.is_focused())
        .type_text("closed-tube");
    h.run_steps(3);
    h.get_by_label("closed-tube (cluster)").click();
    h.run_steps(3);
    let id = common::focused_node(&h);
    let node = h.state().doc().graph.node(&id).expect("the node");
    let cluster = Cluster::of(&node.def).expect("a cluster node");
    assert_eq!(cluster.label(), "closed-tube.ron");
    let inputs: Vec<&str> = node.def.inputs.iter().map(|p| p.name.as_ref()).collect();
    assert_eq!(inputs, ["profile", "path", "apex", "ratios"]);
    assert!(node.def.inputs.iter().all(|p| !p.doc.is_empty()));
    assert!(
        h.state()
            .doc()
            .to_ron()
            .contains("source: \"closed-tube.ron\""),
        "resolved through graphs/library, as `--library graphs/library` resolves it"
    );
}
