//! The flat fabrication layer drawn beside the design: unrolled strips and nested sheets lie in
//! the XY plane where the unrolling put them — often over the design's own plan — so the preview
//! moves them, as one block, next to the design (along +X, a gap apart, level with its base) and
//! flags what it draws of them ([`cnets_render::FLAG_BESIDE`]) so the design's size (W × D × H)
//! leaves them out.

use std::sync::Arc;

use cnets_engine::Value;
use cnets_geometry::{DVec3, Line, Polyline};
use cnets_render::Bounds;

/// The gap between the design and the flat layer, as a share of the design's larger horizontal
/// extent (at least [`MIN_GAP`]).
const GAP_SHARE: f64 = 0.15;
/// The smallest gap, in model units (metres).
const MIN_GAP: f64 = 1.0;

/// Grows `lo`/`hi` by every point of `value` (polylines, lines, points, meshes, lists of them).
fn grow(value: &Value, lo: &mut DVec3, hi: &mut DVec3) {
    let mut add = |p: DVec3| {
        if p.is_finite() {
            *lo = lo.min(p);
            *hi = hi.max(p);
        }
    };
    match value {
        Value::Polyline(p) => p.points.iter().copied().for_each(add),
        Value::Lines(lines) => lines.iter().for_each(|l| {
            add(l.start);
            add(l.end);
        }),
        Value::Point(p) => add(*p),
        Value::Mesh(m) => m.vertices.iter().copied().for_each(add),
        Value::QuadMesh(m) => m.vertices.iter().copied().for_each(add),
        Value::List(items) if items.as_packed().is_none() => {
            items.iter().for_each(|v| grow(v, lo, hi));
        }
        _ => {}
    }
}

/// The box of the points of `values`, if they have any.
pub(crate) fn bounds_of<'a>(values: impl IntoIterator<Item = &'a Value>) -> Option<(DVec3, DVec3)> {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    values.into_iter().for_each(|v| grow(v, &mut lo, &mut hi));
    (lo.x <= hi.x).then_some((lo, hi))
}

/// How far to move the flat layer (box `flat`) to lie beside the design (box `design`, `None`
/// when nothing else is drawn: it stays where it is): its lower-left corner a gap past the
/// design's +X side, level with the design's lowest point and its front.
pub(crate) fn offset_beside(design: Option<Bounds>, flat: (DVec3, DVec3)) -> DVec3 {
    let Some(d) = design else {
        return DVec3::ZERO;
    };
    let (min, max) = (d.min.as_dvec3(), d.max.as_dvec3());
    let gap = (GAP_SHARE * (max.x - min.x).max(max.y - min.y)).max(MIN_GAP);
    DVec3::new(max.x + gap - flat.0.x, min.y - flat.0.y, min.z - flat.0.z)
}

/// `value` moved by `by` (the shapes the preview draws; other values as they are).
pub(crate) fn translated(value: &Value, by: DVec3) -> Value {
    match value {
        Value::Polyline(p) => Value::Polyline(Arc::new(Polyline {
            points: p.points.iter().map(|&q| q + by).collect(),
            ..(**p).clone()
        })),
        Value::Lines(lines) => Value::Lines(Arc::new(
            lines
                .iter()
                .map(|l| Line {
                    start: l.start + by,
                    end: l.end + by,
                })
                .collect(),
        )),
        Value::Point(p) => Value::Point(*p + by),
        Value::Mesh(m) => {
            let mut moved = (**m).clone();
            moved.vertices.iter_mut().for_each(|q| *q += by);
            Value::Mesh(Arc::new(moved))
        }
        Value::QuadMesh(m) => {
            let mut moved = (**m).clone();
            moved.vertices.iter_mut().for_each(|q| *q += by);
            Value::QuadMesh(Arc::new(moved))
        }
        Value::List(items) if items.as_packed().is_none() => {
            Value::list(items.iter().map(|v| translated(v, by)).collect())
        }
        other => other.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flat_layer_goes_a_gap_past_the_design_level_with_its_base() {
        let outline = Value::Polyline(Arc::new(Polyline::closed(vec![
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(5.0, 1.0, 0.0),
            DVec3::new(5.0, 2.0, 0.0),
        ])));
        let flat = Value::list(vec![outline, Value::Point(DVec3::new(3.0, 1.5, 0.0))]);
        let design = Bounds {
            min: DVec3::new(-2.0, -1.0, 0.5).as_vec3(),
            max: DVec3::new(8.0, 3.0, 6.0).as_vec3(),
        };
        let (lo, hi) = bounds_of([&flat]).unwrap();
        assert_eq!(
            (lo, hi),
            (DVec3::new(1.0, 1.0, 0.0), DVec3::new(5.0, 2.0, 0.0))
        );
        let by = offset_beside(Some(design), (lo, hi));
        let moved = translated(&flat, by);
        let (mlo, mhi) = bounds_of([&moved]).unwrap();
        // 15 % of the design's 10 m width: 1.5 m past its +X side, at its base and front.
        assert!((mlo - DVec3::new(9.5, -1.0, 0.5)).length() < 1e-6, "{mlo}");
        assert!(
            (mhi - mlo - (hi - lo)).length() < 1e-9,
            "moved as one block"
        );
        assert_eq!(
            offset_beside(None, (lo, hi)),
            DVec3::ZERO,
            "alone, it stays"
        );
        // Numbers and texts are not moved (nor dropped).
        assert_eq!(translated(&Value::Number(2.0), by), Value::Number(2.0));
    }
}
