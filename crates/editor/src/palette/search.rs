//! Palette search: node types ranked by how well the designer's words name them.
//!
//! Ranking, best first: the display name or id is the query; every word of the query is a whole
//! word of the name; the name starts with the query; a word of the name starts with it; the name
//! or id contains it; a fuzzy match of name and id (`nucleo-matcher`, the matcher of the helix
//! editor: typos such as "cnstruct" still find CNets Construct); the words only in the category
//! or documentation. A Rhino or Grasshopper word for what a node does (trim, split, loft, sweep,
//! join, explode, bake, point …: [`SYNONYMS`]) ranks that node as if it were its name. Within a rank the paper's own components come first, then shorter names,
//! then registry order. Enter in the palette adds the top hit.

use std::sync::Arc;

use cnets_engine::{NodeDef, Registry};
use nucleo_matcher::pattern::{CaseMatching, Normalization, Pattern};
use nucleo_matcher::{Config, Matcher, Utf32Str};

use super::names::{PAPER_CATEGORY, display_category, display_name};

/// A node type matching a query, with its rank (lower is better).
#[derive(Clone, Debug)]
pub struct Ranked {
    /// The node type.
    pub def: Arc<NodeDef>,
    /// How it matched: 0 (exactly named) … 6 (only in the category or doc).
    pub rank: u8,
    /// The fuzzy score within rank 5 (higher is better).
    pub score: u32,
}

/// Rhino's and Grasshopper's words for what a node does, and the node they mean (a query that is
/// one of these words ranks that node first, as if it were its name).
const SYNONYMS: &[(&str, &str)] = &[
    ("trim", "mesh.cut_by_plane"),
    ("split", "mesh.cut_by_plane"),
    ("cut", "mesh.cut_by_plane"),
    ("loft", "cnets.construct"),
    ("sweep", "cnets.construct"),
    ("sweep1", "cnets.construct"),
    ("join", "mesh.join"),
    ("weld", "mesh.join"),
    ("explode", "mesh.deconstruct"),
    ("bake", "io.export_gltf"),
    ("point", "vector.point"),
    ("construct point", "vector.point"),
    ("pt", "vector.point"),
    ("arc", "curve.arc"),
    ("interpolate", "curve.spline"),
    ("interpcrv", "curve.spline"),
    ("reflect", "mesh.mirror"),
];

/// Whether `query` is a Rhino/Grasshopper word for `def` ([`SYNONYMS`]).
fn is_synonym(def: &NodeDef, query: &str) -> bool {
    let q = query.trim().to_lowercase();
    SYNONYMS
        .iter()
        .any(|(word, id)| *word == q && *id == def.id.as_ref())
}

fn words_of(text: &str) -> Vec<String> {
    text.split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect()
}

/// How `def` matches `query` (lower is better); `None` when it does not.
fn rank_of(def: &NodeDef, query: &str, fuzzy: Option<u32>) -> Option<u8> {
    let q = query.trim().to_lowercase();
    let name = display_name(def).to_lowercase();
    let id = def.id.to_lowercase();
    let words = words_of(&q);
    let name_words = words_of(&name);
    if name == q || id == q || is_synonym(def, &q) {
        return Some(0);
    }
    if !words.is_empty() && words.iter().all(|w| name_words.contains(w)) {
        return Some(1);
    }
    if name.starts_with(&q) {
        return Some(2);
    }
    if name_words.iter().any(|w| w.starts_with(&q)) {
        return Some(3);
    }
    if name.contains(&q) || id.contains(&q) {
        return Some(4);
    }
    if fuzzy.is_some() {
        return Some(5);
    }
    let haystack = format!(
        "{name} {id} {} {} {}",
        display_category(def).to_lowercase(),
        def.category.to_lowercase(),
        def.doc.to_lowercase()
    );
    (!words.is_empty() && words.iter().all(|w| haystack.contains(w.as_str()))).then_some(6)
}

/// Every node type matching `query`, best first (see the module docs). An empty query matches
/// nothing: the palette lists the categories then.
pub fn rank(registry: &Registry, query: &str) -> Vec<Ranked> {
    if query.trim().is_empty() {
        return Vec::new();
    }
    let mut matcher = Matcher::new(Config::DEFAULT);
    let pattern = Pattern::parse(query, CaseMatching::Ignore, Normalization::Smart);
    let mut buf = Vec::new();
    let mut found: Vec<(usize, Ranked)> = registry
        .iter()
        .enumerate()
        .filter_map(|(order, def)| {
            let target = format!("{} {}", display_name(def), def.id);
            let fuzzy = pattern.score(Utf32Str::new(&target, &mut buf), &mut matcher);
            let rank = rank_of(def, query, fuzzy)?;
            Some((
                order,
                Ranked {
                    def: def.clone(),
                    rank,
                    score: fuzzy.unwrap_or(0),
                },
            ))
        })
        .collect();
    found.sort_by(|(oa, a), (ob, b)| {
        let paper = |d: &NodeDef| display_category(d) != PAPER_CATEGORY;
        let fuzzy = |r: &Ranked| if r.rank == 5 { r.score } else { 0 };
        a.rank
            .cmp(&b.rank)
            .then_with(|| is_synonym(&b.def, query).cmp(&is_synonym(&a.def, query)))
            .then(fuzzy(b).cmp(&fuzzy(a)))
            .then_with(|| paper(&a.def).cmp(&paper(&b.def)))
            .then_with(|| display_name(&a.def).len().cmp(&display_name(&b.def).len()))
            .then(oa.cmp(ob))
    });
    found.into_iter().map(|(_, r)| r).collect()
}

/// Node types whose name, id, category or doc match `query` (every word must match,
/// case-insensitive), grouped by category in registry order (the palette's listing for an empty
/// query, and the by-category view).
pub fn search(registry: &Registry, query: &str) -> Vec<(String, Vec<Arc<NodeDef>>)> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    let mut groups: Vec<(String, Vec<Arc<NodeDef>>)> = Vec::new();
    for def in registry.iter() {
        let category = display_category(def);
        let haystack = format!(
            "{} {} {} {} {}",
            display_name(def),
            def.id,
            category,
            def.category,
            def.doc
        )
        .to_lowercase();
        if !words.iter().all(|w| haystack.contains(w.as_str())) {
            continue;
        }
        match groups.iter_mut().find(|(c, _)| *c == category) {
            Some((_, defs)) => defs.push(def.clone()),
            None => groups.push((category, vec![def.clone()])),
        }
    }
    groups
}

/// Library graphs whose name, file or doc match `query` (every word, case-insensitive).
pub fn search_library<'a>(
    entries: &'a [cnets_host::LibraryEntry],
    query: &str,
) -> Vec<&'a cnets_host::LibraryEntry> {
    let words: Vec<String> = query.split_whitespace().map(str::to_lowercase).collect();
    entries
        .iter()
        .filter(|e| {
            let haystack =
                format!("library cluster {} {} {}", e.name, e.source, e.doc).to_lowercase();
            words.iter().all(|w| haystack.contains(w.as_str()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn top(registry: &Registry, query: &str) -> String {
        rank(registry, query)
            .first()
            .map(|r| r.def.id.to_string())
            .unwrap_or_default()
    }

    #[test]
    fn the_designers_words_rank_the_node_they_mean_first() {
        let registry = cnets_nodes::registry();
        for (query, expected) in [
            ("construct", "cnets.construct"),
            ("table", "list.table"),
            ("nest", "fab.nest"),
            ("export svg", "io.export_svg"),
            ("panel", "view.panel"),
            ("number slider", "param.number"),
            ("slider", "param.number"),
            ("graph mapper", "mapper.graph"),
            ("points", "param.points"),
            ("spline", "curve.spline"),
            ("deconstruct", "mesh.deconstruct"),
            ("cnets.encode", "cnets.encode"),
        ] {
            assert_eq!(top(&registry, query), expected, "'{query}'");
        }
        // Rhino's and Grasshopper's words find the node they mean first.
        for (query, expected) in [
            ("trim", "mesh.cut_by_plane"),
            ("split", "mesh.cut_by_plane"),
            ("loft", "cnets.construct"),
            ("sweep", "cnets.construct"),
            ("explode", "mesh.deconstruct"),
            ("bake", "io.export_gltf"),
            ("point", "vector.point"),
        ] {
            assert_eq!(top(&registry, query), expected, "'{query}'");
        }
        // "join" names two nodes: the curves' and the meshes' join are the first two hits.
        let joins: Vec<String> = rank(&registry, "join")
            .iter()
            .take(2)
            .map(|r| r.def.id.to_string())
            .collect();
        assert!(joins.contains(&"mesh.join".to_string()), "{joins:?}");
        // Every synonym names a registered node.
        for (word, id) in SYNONYMS {
            assert!(registry.get(id).is_some(), "{word} → {id}");
        }
        // A typo still finds it among the first hits (fuzzy).
        let typo: Vec<String> = rank(&registry, "cnstruct")
            .iter()
            .take(3)
            .map(|r| r.def.id.to_string())
            .collect();
        assert!(typo.contains(&"cnets.construct".to_string()), "{typo:?}");
        assert!(rank(&registry, "").is_empty());
        assert!(rank(&registry, "zzzqqq").is_empty());
        // Every word must be somewhere: "cone construct" finds only nodes that say both.
        for r in rank(&registry, "cone construct") {
            let text = format!("{} {} {}", r.def.id, r.def.category, r.def.doc).to_lowercase();
            assert!(text.contains("cone") || r.rank == 5, "{}", r.def.id);
        }
    }

    #[test]
    fn search_filters_and_groups() {
        let registry = cnets_nodes::registry();
        let all = search(&registry, "");
        let total: usize = all.iter().map(|(_, d)| d.len()).sum();
        assert_eq!(total, registry.len());
        let paper: Vec<&str> = all
            .iter()
            .filter(|(c, _)| c == PAPER_CATEGORY)
            .flat_map(|(_, d)| d.iter().map(|d| d.id.as_ref()))
            .collect();
        assert!(paper.contains(&"cnets.construct") && paper.contains(&"cnets.graph_to_apex"));
        assert!(!all.iter().any(|(c, _)| c == "Cone-nets" || c == "CNets"));
        let names: Vec<String> = all
            .iter()
            .flat_map(|(_, d)| d.iter().map(|d| display_name(d)))
            .collect();
        assert!(
            names.contains(&"Closest point".to_string()),
            "fallback from the id"
        );
        assert!(search(&registry, "no-such-node-xyz").is_empty());
    }
}
