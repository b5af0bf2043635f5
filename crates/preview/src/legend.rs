//! The legend of the preview: face classes in words and the paper's notation, or the planarity
//! scale; the apex legend.

use cnets_geometry::fabrication::FaceClass;
use cnets_render::Color;
use cnets_render::palette;

use crate::classes::class_color;

/// The legend to draw next to the viewport.
#[derive(Clone, Debug, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub enum LegendInfo {
    /// Nothing coloured.
    #[default]
    None,
    /// Face classes with their face counts (classes that occur).
    Classes(Vec<(FaceClass, usize)>),
    /// A planarity colour scale.
    Planarity(cnets_render::Legend),
    /// The distance colour scale (`distance to <node>`, labels in metres).
    Distance(cnets_render::Legend),
}

/// The configuration class of a face in the paper's notation: the (±±) configurations of its two
/// construction planes (CNets, Fig. 4).
pub fn paper_class(class: FaceClass) -> &'static str {
    match class {
        FaceClass::Convex => "(++)(++)",
        FaceClass::NonConvex => "(++)(−−)",
        FaceClass::MinusMinus => "(−−)(−−)",
        FaceClass::NegativeApex => "(+−)/(−+)",
        FaceClass::Unclassified => "—",
    }
}

/// The colour apices are drawn in.
pub const APEX_COLOR: Color = palette::POINT;

/// What an apex point is, for legends.
pub const APEX_LEGEND: &str = "apex of a strip's cone";

/// The surface legend as a title and rows of (swatch colour, words): face classes in the paper's
/// notation with their words and face counts (`(++)(++)  convex  170`), or the planarity scale
/// (`planar (< 1e-9)` … `not planar (≥ 1e-3)`, top row the largest). `None` without one.
pub fn legend_rows(legend: &LegendInfo) -> Option<(String, Vec<(Color, String)>)> {
    match legend {
        LegendInfo::None => None,
        LegendInfo::Classes(classes) => Some((
            "configuration".to_string(),
            classes
                .iter()
                .map(|&(c, n)| {
                    (
                        class_color(c),
                        format!("{}  {}  {n}", paper_class(c), c.name()),
                    )
                })
                .collect(),
        )),
        LegendInfo::Planarity(l) | LegendInfo::Distance(l) => Some((
            l.title.clone(),
            l.stops
                .iter()
                .enumerate()
                .rev()
                .map(|(k, (v, c))| {
                    (
                        *c,
                        l.labels
                            .get(k)
                            .cloned()
                            .unwrap_or_else(|| format!("{v:.0e}")),
                    )
                })
                .collect(),
        )),
    }
}
