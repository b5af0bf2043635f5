//! The choice ports of the node library: each a marker naming its words and the parser the node
//! uses ([`ChoiceEnum`]), so a graph with `end_planes: "mirrored"` fails to load with `valid:
//! perpendicular, mirror` and the editor shows a drop-down. The parsers are the geometry's own
//! (aliases, case and surrounding spaces accepted as before): stored values keep loading unchanged.

use cnets_engine::ChoiceEnum;
use cnets_geometry::conenet::EndPlanes as GeoEndPlanes;
use cnets_geometry::curves::{MapperKind, SplineKind, SubdivisionScheme};
use cnets_geometry::fabrication::StripDirection;

/// `end_planes` of the constructions: `perpendicular` or `mirror`.
pub struct EndPlanes;

impl ChoiceEnum for EndPlanes {
    type Value = GeoEndPlanes;
    const OPTIONS: &'static [&'static str] = &["perpendicular", "mirror"];
    fn parse(text: &str) -> Option<GeoEndPlanes> {
        GeoEndPlanes::parse(text)
    }
}

/// The strip direction of the fabrication nodes: `directrix` or `generatrix`.
pub struct Direction;

impl ChoiceEnum for Direction {
    type Value = StripDirection;
    const OPTIONS: &'static [&'static str] = &["directrix", "generatrix"];
    fn parse(text: &str) -> Option<StripDirection> {
        text.parse().ok()
    }
}

/// A graph mapper's curve type.
pub struct MapperCurve;

impl ChoiceEnum for MapperCurve {
    type Value = MapperKind;
    const OPTIONS: &'static [&'static str] = &[
        "linear",
        "bezier",
        "parabola",
        "power",
        "sine",
        "gaussian",
        "sqrt",
        "conic",
        "piecewise",
        "spline",
    ];
    fn parse(text: &str) -> Option<MapperKind> {
        MapperKind::parse(text).ok()
    }
}

/// `curve.spline`'s method: `catmull-rom` or `natural`.
pub struct SplineMethod;

impl ChoiceEnum for SplineMethod {
    type Value = SplineKind;
    const OPTIONS: &'static [&'static str] = &["catmull-rom", "natural"];
    fn parse(text: &str) -> Option<SplineKind> {
        SplineKind::parse(text).ok()
    }
}

/// `curve.subdivide`'s scheme: `linear`, `four-point` or `chaikin`.
pub struct Subdivision;

impl ChoiceEnum for Subdivision {
    type Value = SubdivisionScheme;
    const OPTIONS: &'static [&'static str] = &["linear", "four-point", "chaikin"];
    fn parse(text: &str) -> Option<SubdivisionScheme> {
        SubdivisionScheme::parse(text).ok()
    }
}

/// Reads a word of `options` (case and surrounding spaces ignored) as its canonical text.
fn word(text: &str, options: &[&'static str]) -> Option<&'static str> {
    let t = text.trim();
    options.iter().copied().find(|o| o.eq_ignore_ascii_case(t))
}

/// `list.table`'s rule: `sum`, `product` or `mean`.
pub struct TableRule;

impl ChoiceEnum for TableRule {
    type Value = &'static str;
    const OPTIONS: &'static [&'static str] = &["sum", "product", "mean"];
    fn parse(text: &str) -> Option<&'static str> {
        word(text, Self::OPTIONS)
    }
}

/// `io.read_mesh`'s format (`auto`: from the file's extension).
pub struct MeshFormat;

impl ChoiceEnum for MeshFormat {
    type Value = &'static str;
    const OPTIONS: &'static [&'static str] = &["auto", "obj", "stl", "ply", "gltf", "glb"];
    fn parse(text: &str) -> Option<&'static str> {
        if text.trim().is_empty() {
            return Some("auto");
        }
        word(text, Self::OPTIONS)
    }
}

/// `io.read_polylines`' format (`auto`: from the file's extension; `txt` and `xyz` are CSV).
pub struct PolylineFormat;

impl ChoiceEnum for PolylineFormat {
    type Value = &'static str;
    const OPTIONS: &'static [&'static str] = &["auto", "csv", "json", "obj", "svg", "dxf"];
    fn parse(text: &str) -> Option<&'static str> {
        if text.trim().is_empty() {
            return Some("auto");
        }
        word(text, Self::OPTIONS).or_else(|| word(text, &["txt", "xyz"]).map(|_| "csv"))
    }
}

/// `param.list`'s item type.
pub struct ListItemType;

impl ChoiceEnum for ListItemType {
    type Value = &'static str;
    const OPTIONS: &'static [&'static str] = &[
        "number", "integer", "boolean", "text", "point", "vector", "any",
    ];
    fn parse(text: &str) -> Option<&'static str> {
        word(text, Self::OPTIONS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn every_option_parses<E: ChoiceEnum>() {
        for o in E::OPTIONS {
            assert!(E::accepts(o), "{o}");
            assert!(E::accepts(&format!(" {} ", o.to_uppercase())), "{o}");
        }
        assert!(!E::accepts("no-such-choice"));
    }

    #[test]
    fn every_listed_word_is_accepted_and_others_are_not() {
        every_option_parses::<EndPlanes>();
        every_option_parses::<Direction>();
        every_option_parses::<MapperCurve>();
        every_option_parses::<SplineMethod>();
        every_option_parses::<Subdivision>();
        every_option_parses::<TableRule>();
        every_option_parses::<MeshFormat>();
        every_option_parses::<PolylineFormat>();
        every_option_parses::<ListItemType>();
    }

    #[test]
    fn the_mapper_words_are_the_geometry_kinds_in_order() {
        let names: Vec<&str> = MapperKind::ALL.iter().map(|k| k.name()).collect();
        assert_eq!(names, MapperCurve::OPTIONS);
    }
}
