//! The cnets node library: thin wrappers over `cnets-geometry`, registered in one place.
//!
//! Each module declares its nodes with [`cnets_engine::node!`] and lists them in its `nodes()`
//! function; [`registry`] collects every module. To add a node: declare it in the module of its
//! category, add it to that module's `nodes()`, add its line to the frozen contract
//! `signatures.txt` (the failing `node_contracts` test prints it) and regenerate `docs/nodes.md`
//! (`cargo run -p cnets -- nodes --markdown > docs/nodes.md`).

pub mod analysis;
pub mod choices;
pub mod cnets;
pub mod curve;
pub mod derivatives;
pub mod fabrication;
pub mod grid;
pub mod io_export;
pub mod io_read;
pub mod list;
pub mod mapper;
pub mod math;
pub mod measure;
pub mod mesh;
pub mod mesh_parts;
pub mod param;
pub mod quality;
pub mod reference;
pub mod seam;
pub mod vector;
pub mod view;

#[cfg(test)]
pub(crate) mod testing;

use cnets_engine::{NodeDef, Registry};

/// Every node type of the library, in palette order.
pub fn all() -> Vec<NodeDef> {
    let defs = [
        param::nodes(),
        math::nodes(),
        vector::nodes(),
        curve::nodes(),
        mapper::nodes(),
        list::nodes(),
        io_read::nodes(),
        cnets::nodes(),
        quality::nodes(),
        grid::nodes(),
        measure::nodes(),
        seam::nodes(),
        analysis::nodes(),
        fabrication::nodes(),
        mesh::nodes(),
        mesh_parts::nodes(),
        io_export::nodes(),
        view::nodes(),
        cnets_engine::cluster::nodes(),
    ]
    .into_iter()
    .flatten()
    .collect();
    derivatives::attach(defs)
}

/// A registry with every node type of the library.
pub fn registry() -> Registry {
    let mut registry = Registry::new();
    for def in all() {
        registry.register(def);
    }
    registry
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_are_unique_namespaced_and_documented() {
        let defs = all();
        let mut ids: Vec<&str> = defs.iter().map(|d| d.id.as_ref()).collect();
        ids.sort();
        let before = ids.len();
        ids.dedup();
        assert_eq!(ids.len(), before, "duplicate node ids");
        for d in &defs {
            assert!(d.id.contains('.'), "{} is not namespaced", d.id);
            assert!(!d.doc.is_empty(), "{} has no doc", d.id);
            for p in d.inputs.iter().chain(&d.outputs) {
                assert!(!p.doc.is_empty(), "{}.{} has no doc", d.id, p.name);
            }
        }
    }
}

#[cfg(test)]
mod reference_tests {
    #[test]
    fn docs_nodes_md_is_up_to_date() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/nodes.md");
        let expected = crate::reference::markdown(&crate::registry());
        let actual = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            actual == expected,
            "docs/nodes.md is stale: run `cargo run -p cnets -- nodes --markdown > docs/nodes.md`"
        );
    }
}
