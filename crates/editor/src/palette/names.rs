//! The names designers read in the palette: Grasshopper-like display names for node types and the
//! category the paper's components share.

use cnets_engine::NodeDef;

/// The category the paper's components are listed under (the node library files them as
/// "Cone-nets" and "CNets").
pub const PAPER_CATEGORY: &str = "CNets (the paper's components)";

/// The name a designer reads for a node type: the node's declared display name (`#[node(name =
/// …)]`), else its id's last part with spaces (`curve.closest_point` → "Closest point").
pub fn display_name(def: &NodeDef) -> String {
    def.name().into_owned()
}

/// The category a node type is listed under (the paper's components under one).
pub fn display_category(def: &NodeDef) -> String {
    match def.category.as_ref() {
        "Cone-nets" | "CNets" => PAPER_CATEGORY.to_string(),
        other => other.to_string(),
    }
}
