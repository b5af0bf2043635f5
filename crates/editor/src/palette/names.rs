//! The names designers read in the palette: Grasshopper-like display names for node types and the
//! category the paper's components share.

use cnets_engine::NodeDef;

/// The category the paper's components are listed under (the node library files them as
/// "Cone-nets" and "CNets").
pub const PAPER_CATEGORY: &str = "CNets (the paper's components)";

/// Names designers use for node types, where the id alone does not say it.
const NAMES: &[(&str, &str)] = &[
    ("param.number", "Number slider"),
    ("param.integer", "Integer slider"),
    ("param.boolean", "Boolean toggle"),
    ("param.choice", "Value list"),
    ("param.text", "Text"),
    ("param.list", "List of numbers"),
    ("param.point", "Point"),
    ("param.points", "Points"),
    ("curve.points", "Curve points"),
    ("mesh.construct", "Construct mesh"),
    ("mesh.deconstruct", "Deconstruct mesh"),
    ("vector.deconstruct", "Deconstruct vector"),
    ("param.vector", "Vector"),
    ("param.range", "Range"),
    ("param.series", "Series"),
    ("mapper.graph", "Graph mapper"),
    ("view.panel", "Panel"),
    ("cnets.construct", "CNets Construct"),
    ("cnets.construct_coplanar", "CNets Construct Coplanar"),
    ("cnets.encode", "CNets Encode"),
    ("cnets.graph_to_apex", "Graph to apex function"),
    ("cnets.conical_support", "Conical support layer"),
    ("cnets.torsion_free_axes", "Torsion-free node axes"),
    ("cnets.cone_check", "Cone check"),
    ("ctube.construct", "C-tube Construct"),
    ("pq.extract_strips", "Extract strips"),
    ("pq.unroll_strips", "Unroll strips"),
    ("pq.parallel_support", "Parallel support layer"),
    ("pq.parallel_transform", "Parallel transform"),
    ("mesh.planarity", "Planarity"),
    ("math.expression", "Expression"),
];

/// The name a designer reads for a node type: from the table above, else the id's last part
/// with spaces (`curve.closest_point` → "Closest point").
pub fn display_name(def: &NodeDef) -> String {
    if let Some((_, name)) = NAMES.iter().find(|(id, _)| *id == def.id) {
        return (*name).to_string();
    }
    let last = def
        .id
        .rsplit('.')
        .next()
        .unwrap_or(&def.id)
        .replace('_', " ");
    let mut chars = last.chars();
    match chars.next() {
        Some(c) => c.to_uppercase().chain(chars).collect(),
        None => def.id.to_string(),
    }
}

/// The category a node type is listed under (the paper's components under one).
pub fn display_category(def: &NodeDef) -> String {
    match def.category.as_ref() {
        "Cone-nets" | "CNets" => PAPER_CATEGORY.to_string(),
        other => other.to_string(),
    }
}
