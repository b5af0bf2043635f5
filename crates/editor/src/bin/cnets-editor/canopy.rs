//! `canopy`: the brief played with pointer events and keys only (written below).

use crate::script::Step;

/// The canopy script.
pub fn canopy() -> Vec<Step> {
    vec![Step::Settle, Step::Quit]
}
