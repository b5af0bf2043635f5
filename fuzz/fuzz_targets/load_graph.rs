//! Fuzzes the graph-file loader with the real node registry: it must never panic, and whatever
//! loads must save and load again to the same text.
#![no_main]

use std::sync::{Arc, OnceLock};

use cnets_engine::Registry;
use cnets_engine::file::{load_str, to_ron};
use libfuzzer_sys::fuzz_target;

fn registry() -> &'static Arc<Registry> {
    static REGISTRY: OnceLock<Arc<Registry>> = OnceLock::new();
    REGISTRY.get_or_init(|| Arc::new(cnets_nodes::registry()))
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(doc) = load_str(text, "fuzz.ron", registry()) {
        let saved = to_ron(&doc.graph, &doc.meta);
        let again = load_str(&saved, "again.ron", registry()).expect("a saved graph loads again");
        assert_eq!(to_ron(&again.graph, &again.meta), saved);
    }
});
