//! Irregular nesting of flat outlines on rectangular sheets (`fab.nest`).
//!
//! Collision detection is `jagua-rs` (1.1, a maintained engine for 2-D irregular cutting and packing:
//! a quadtree of the placed polygons' edges, exact polygon–polygon and polygon–container tests, item
//! inflation by half the spacing). It works in f32; the placement it finds (a rotation and a
//! translation per outline) is applied to the f64 outline here, so placed outlines are exact rigid
//! motions of the input (lengths kept to f64 rounding).
//!
//! The placement heuristic on top of it is a deterministic bottom-left fill: outlines in decreasing
//! area (ties by index); for each, every open sheet in order and every allowed rotation
//! (`360° · r / rotations`) is tried at the candidate corners on the skyline of the boxes already
//! placed on that sheet — `x ∈ {0} ∪ {right edges}`, y the top of the highest box under
//! `[x, x + w]` — lowest y then lowest x first; the first collision-free candidate of each rotation
//! is then slid down and left by bisection (into the concavities of its neighbours, which box
//! stacking cannot use), and the rotation that ends lowest (then leftmost) wins. When no open sheet
//! holds it a new sheet is opened; a sheet whose free area is smaller than the outline's is passed
//! over without a check.
//!
//! **Work.** A candidate above every box it spans is free in box terms, so the first collision
//! check of a rotation nearly always succeeds and a placement costs about `rotations · (1 + 3 ·
//! SLIDE_STEPS)` engine checks whatever the count of outlines (the corner grid tried before, every
//! right edge × every top edge, made it about n^2.5: 299 outlines took 138 s).
//! [`Nested::collision_checks`] counts them.
//!
//! [`stack_sheets`] is the baseline the issue compares with: the bounding boxes stacked along y
//! (as `pq.unroll_strips` lays them out), a new sheet when the next box does not fit.

use std::sync::Arc;

use glam::{DVec2, DVec3};
use jagua_rs::collision_detection::CDEConfig;
use jagua_rs::collision_detection::hazards::filter::NoFilter;
use jagua_rs::entities::{Item, Layout};
use jagua_rs::geometry::fail_fast::SPSurrogateConfig;
use jagua_rs::geometry::geo_traits::Transformable;
use jagua_rs::geometry::primitives::Rect;
use jagua_rs::geometry::{DTransformation, Transformation};
use jagua_rs::io::ext_repr::{
    ExtContainer, ExtItem, ExtOrientation, ExtRotation, ExtSPolygon, ExtShape,
};
use jagua_rs::io::import::Importer;

use super::FabricationError;
use crate::Polyline;

/// The largest number of allowed rotations.
pub const MAX_ROTATIONS: usize = 360;
/// Bisection steps of each slide.
const SLIDE_STEPS: usize = 24;

/// The result of [`nest`].
#[derive(Debug, Clone, PartialEq)]
pub struct Nested {
    /// The placed outlines, in input order, in one plane: sheet s occupies
    /// `[s·(W + gap), s·(W + gap) + W] × [0, H]` (gap = [`Nested::gap`]).
    pub outlines: Vec<Polyline>,
    /// The sheet of each outline.
    pub sheets: Vec<usize>,
    /// Number of sheets used.
    pub sheet_count: usize,
    /// Outline area / area of the sheets used.
    pub utilization: f64,
    /// A point inside each placed outline (for its label).
    pub label_points: Vec<DVec3>,
    /// The gap between consecutive sheets in the output plane.
    pub gap: f64,
    /// Collision checks the nesting asked of the engine (its count of work).
    pub collision_checks: u64,
}

/// Nests closed outlines (their x and y; z is dropped) on sheets `width × height` with at least
/// `spacing` between outlines and from the sheet edges, allowing `rotations` orientations.
pub fn nest(
    outlines: &[Polyline],
    width: f64,
    height: f64,
    spacing: f64,
    rotations: usize,
) -> Result<Nested, FabricationError> {
    nest_until(outlines, width, height, spacing, rotations, &|| false)
}

/// Like [`nest`], asking `cancelled` before each outline is placed: a slow nesting stops with
/// [`FabricationError::Cancelled`] as soon as its caller no longer wants it (an editor whose
/// designer dragged on).
pub fn nest_until(
    outlines: &[Polyline],
    width: f64,
    height: f64,
    spacing: f64,
    rotations: usize,
    cancelled: &dyn Fn() -> bool,
) -> Result<Nested, FabricationError> {
    for (what, v) in [("sheet_width", width), ("sheet_height", height)] {
        if !(v.is_finite() && v > 0.0 && v < 1e12) {
            return Err(FabricationError::BadParameter {
                what,
                value: v,
                expected: "a finite number > 0",
            });
        }
    }
    if width.min(height) < 1e-6 * width.max(height) {
        return Err(FabricationError::BadParameter {
            what: "sheet_width",
            value: width,
            expected: "a sheet whose sides differ by less than a factor of 10⁶",
        });
    }
    if !(spacing.is_finite() && spacing >= 0.0 && spacing < width.min(height)) {
        return Err(FabricationError::BadParameter {
            what: "spacing",
            value: spacing,
            expected: "a finite number ≥ 0, smaller than the sheet",
        });
    }
    if !(1..=MAX_ROTATIONS).contains(&rotations) {
        return Err(FabricationError::BadParameter {
            what: "rotations",
            value: rotations as f64,
            expected: "an integer in 1 … 360",
        });
    }
    if outlines.is_empty() {
        return Err(FabricationError::Empty("outlines"));
    }
    // Work in sheet units scaled so the sheet's long side is 1000 (f32 keeps ~1e-4 of that).
    let unit = 1000.0 / width.max(height);
    let importer = Importer::new(
        CDEConfig {
            quadtree_depth: 5,
            cd_threshold: 16,
            item_surrogate_config: SPSurrogateConfig::none(),
        },
        None,
        None,
    );
    let importer = if spacing > 0.0 {
        importer
            .with_min_item_separation((spacing * unit) as f32)
            .map_err(|e| jagua("the spacing", e))?
    } else {
        importer
    };
    let container = importer
        .import_container(&ExtContainer {
            id: 0,
            shape: ExtShape::Rectangle {
                x_min: 0.0,
                y_min: 0.0,
                width: (width * unit) as f32,
                height: (height * unit) as f32,
            },
            zones: vec![],
        })
        .map_err(|e| jagua("the sheet", e))?;
    let angles: Vec<f32> = (0..rotations)
        .map(|r| (360.0 * r as f64 / rotations as f64) as f32)
        .collect();

    // Items: each outline moved to its box's lower-left corner (f64), then imported.
    let mut items = Vec::with_capacity(outlines.len());
    let mut origins = Vec::with_capacity(outlines.len());
    let mut area = 0.0;
    for (k, o) in outlines.iter().enumerate() {
        if cancelled() {
            return Err(FabricationError::Cancelled);
        }
        if o.points.len() < 3 {
            return Err(FabricationError::TooSmall {
                what: "outline",
                needed: 3,
                unit: "points",
                got: o.points.len(),
            });
        }
        if let Some(index) = o.points.iter().position(|p| !p.is_finite()) {
            return Err(FabricationError::Nesting(format!(
                "outline {k}, point {index} is not finite"
            )));
        }
        let flat: Vec<DVec2> = o.points.iter().map(|p| p.truncate()).collect();
        let lo = flat.iter().fold(DVec2::INFINITY, |a, p| a.min(*p));
        let hi = flat.iter().fold(DVec2::NEG_INFINITY, |a, p| a.max(*p));
        // Larger than the sheet's diagonal: fits in no rotation (and keeps f32 coordinates small).
        if !((hi - lo).max_element() <= width.hypot(height)) {
            return Err(FabricationError::Nesting(format!(
                "outline {k} does not fit on a {width} × {height} sheet in any allowed rotation"
            )));
        }
        area += polygon_area(&flat).abs();
        let item = import_item(&importer, &flat, lo, unit, &angles, k)?;
        items.push(item);
        origins.push(lo);
    }

    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| items[b].area().total_cmp(&items[a].area()).then(a.cmp(&b)));
    let mut sheets: Vec<Sheet> = Vec::new();
    let mut placed: Vec<Option<(usize, DTransformation)>> = vec![None; items.len()];
    for &k in &order {
        if cancelled() {
            return Err(FabricationError::Cancelled);
        }
        let item = &items[k];
        let mut done = false;
        for (s, sheet) in sheets.iter_mut().enumerate() {
            if sheet.used_area + item.area() > sheet.area {
                continue;
            }
            if let Some(pose) = sheet.best_pose(item, &angles) {
                sheet.place(item, pose);
                placed[k] = Some((s, pose));
                done = true;
                break;
            }
        }
        if !done {
            let mut sheet = Sheet::new(Layout::new(container.clone()));
            let Some(pose) = sheet.best_pose(item, &angles) else {
                return Err(FabricationError::Nesting(format!(
                    "outline {k} does not fit on a {width} × {height} sheet in any allowed rotation"
                )));
            };
            sheet.place(item, pose);
            placed[k] = Some((sheets.len(), pose));
            sheets.push(sheet);
        }
    }

    let gap = (0.05 * width).max(2.0 * spacing);
    let mut out = Vec::with_capacity(outlines.len());
    let mut sheet_of = Vec::with_capacity(outlines.len());
    let mut label_points = Vec::with_capacity(outlines.len());
    for (k, o) in outlines.iter().enumerate() {
        let (s, pose) = placed[k].expect("every outline was placed");
        // The f64 rigid motion: jagua's centring (the f32 centroid it subtracted), the rotation, the
        // translation, all in sheet units, then back to model units and onto sheet s.
        let (cx, cy) = items[k].shape_orig().pre_transform.translation();
        let centring = DVec2::new(f64::from(cx), f64::from(cy));
        let (sin, cos) = f64::from(pose.rotation()).sin_cos();
        let (tx, ty) = pose.translation();
        let shift = DVec2::new(f64::from(tx), f64::from(ty));
        let offset = DVec2::new(s as f64 * (width + gap), 0.0);
        let map = |p: DVec3| {
            let local = (p.truncate() - origins[k]) * unit + centring;
            let turned = DVec2::new(cos * local.x - sin * local.y, sin * local.x + cos * local.y);
            let q = (turned + shift) / unit + offset;
            DVec3::new(q.x, q.y, 0.0)
        };
        let points: Vec<DVec3> = o.points.iter().map(|p| map(*p)).collect();
        label_points.push(inside_point(&points));
        out.push(Polyline {
            points,
            closed: true,
        });
        sheet_of.push(s);
    }
    Ok(Nested {
        outlines: out,
        sheets: sheet_of,
        sheet_count: sheets.len(),
        utilization: area / (sheets.len() as f64 * width * height),
        label_points,
        gap,
        collision_checks: sheets.iter().map(|s| s.checks.get()).sum(),
    })
}

/// The sheets the bounding boxes of `outlines` need when stacked along y with `spacing` between them
/// (and from the sheet's edges), a new sheet whenever the next box does not fit; and the resulting
/// utilization. Boxes wider than the sheet are an error.
pub fn stack_sheets(
    outlines: &[Polyline],
    width: f64,
    height: f64,
    spacing: f64,
) -> Result<(usize, f64), FabricationError> {
    let mut sheets = 0;
    let mut used = f64::INFINITY;
    let mut area = 0.0;
    for o in outlines {
        let flat: Vec<DVec2> = o.points.iter().map(|p| p.truncate()).collect();
        area += polygon_area(&flat).abs();
        let lo = flat.iter().fold(DVec2::INFINITY, |a, p| a.min(*p));
        let hi = flat.iter().fold(DVec2::NEG_INFINITY, |a, p| a.max(*p));
        let size = hi - lo;
        if size.x + 2.0 * spacing > width || size.y + 2.0 * spacing > height {
            return Err(FabricationError::BadParameter {
                what: "sheet size",
                value: width.min(height),
                expected: "a sheet that holds every box",
            });
        }
        if used + spacing + size.y + spacing > height {
            sheets += 1;
            used = 0.0;
        }
        used += spacing + size.y;
    }
    let utilization = if sheets == 0 {
        0.0
    } else {
        area / (sheets as f64 * width * height)
    };
    Ok((sheets, utilization))
}

/// One sheet being filled: jagua's layout and the boxes placed on it (sheet units).
struct Sheet {
    layout: Layout,
    /// The area of the outlines placed on it and the sheet's (sheet units).
    used_area: f32,
    area: f32,
    boxes: Vec<Rect>,
    /// Collision checks asked of the engine on this sheet (the nesting's count of work).
    checks: std::cell::Cell<u64>,
}

impl Sheet {
    fn new(layout: Layout) -> Self {
        let b = layout.container().outer_cd().bbox();
        Self {
            area: (b.x_max - b.x_min) * (b.y_max - b.y_min),
            used_area: 0.0,
            layout,
            boxes: Vec::new(),
            checks: std::cell::Cell::new(0),
        }
    }

    fn place(&mut self, item: &Arc<Item>, pose: DTransformation) {
        self.used_area += item.area();
        self.boxes
            .push(item.shape_cd().transform_clone(&pose.compose()).bbox());
        self.layout.place_item(item, pose);
    }

    /// Whether the item fits at this pose (inside the sheet, no collision).
    fn fits(&self, item: &Item, angle: f32, x: f32, y: f32) -> bool {
        self.checks.set(self.checks.get() + 1);
        let pose = DTransformation::new(angle, (x, y));
        let shape = item.shape_cd().transform_clone(&pose.compose());
        let b = shape.bbox();
        let c = self.layout.container().outer_cd().bbox();
        if b.x_min < c.x_min || b.y_min < c.y_min || b.x_max > c.x_max || b.y_max > c.y_max {
            return false;
        }
        !self.layout.cde().detect_poly_collision(&shape, &NoFilter)
    }

    /// The lowest (then leftmost) collision-free pose over the allowed rotations, or `None`.
    fn best_pose(&self, item: &Item, angles: &[f32]) -> Option<DTransformation> {
        // Candidates keep a hair (1e-5 of the sheet) off the edges and the boxes they touch: the
        // engine counts touching as a collision.
        let c = self.layout.container().outer_cd().bbox();
        let hair = 1e-5 * (c.x_max - c.x_min).max(c.y_max - c.y_min);
        let c = Rect {
            x_min: c.x_min + hair,
            y_min: c.y_min + hair,
            x_max: c.x_max - hair,
            y_max: c.y_max - hair,
        };
        let mut best: Option<(f32, f32, DTransformation)> = None;
        for &degrees in angles {
            let angle = degrees.to_radians();
            let turned = item
                .shape_cd()
                .transform_clone(&Transformation::from_rotation(angle))
                .bbox();
            // Translations that put the turned box's lower-left corner at (x, y).
            let (dx, dy) = (-turned.x_min, -turned.y_min);
            let (w, h) = (turned.x_max - turned.x_min, turned.y_max - turned.y_min);
            if w > c.x_max - c.x_min || h > c.y_max - c.y_min {
                continue;
            }
            // Bottom-left candidates on the boxes' skyline: the turned box's left edge at the
            // sheet's edge or just right of a placed box, as low as the boxes under that span
            // allow. One per placed box, each checked for collisions only when it beats the best
            // rotation so far; a candidate above every box it spans is free in box terms, so the
            // first check usually succeeds (the engine's exact shapes only refine it).
            let mut candidates: Vec<(f32, f32)> = std::iter::once(c.x_min)
                .chain(self.boxes.iter().map(|b| b.x_max + hair))
                .filter(|x| x + w <= c.x_max)
                .map(|x| {
                    let y = self
                        .boxes
                        .iter()
                        .filter(|b| b.x_min < x + w && b.x_max > x)
                        .fold(c.y_min, |y, b| y.max(b.y_max + hair));
                    (y, x)
                })
                .filter(|(y, _)| y + h <= c.y_max)
                .collect();
            candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            candidates.dedup();
            let found = candidates.iter().find_map(|&(y, x)| {
                if best.is_some_and(|(by, _, _)| y > by) {
                    return Some(None);
                }
                self.fits(item, angle, x + dx, y + dy)
                    .then_some(Some((x + dx, y + dy)))
            });
            let Some(Some((mut x, mut y))) = found else {
                continue;
            };
            // Slide down, left, down again: each by bisection towards the sheet's edge.
            for axis in [1, 0, 1] {
                let (lo_edge, now) = if axis == 1 {
                    (c.y_min + dy, y)
                } else {
                    (c.x_min + dx, x)
                };
                let at = |v: f32| {
                    if axis == 1 {
                        self.fits(item, angle, x, v)
                    } else {
                        self.fits(item, angle, v, y)
                    }
                };
                let target = if at(lo_edge) {
                    lo_edge
                } else {
                    let (mut bad, mut good) = (lo_edge, now);
                    for _ in 0..SLIDE_STEPS {
                        let mid = 0.5 * (bad + good);
                        if at(mid) {
                            good = mid;
                        } else {
                            bad = mid;
                        }
                    }
                    good
                };
                if axis == 1 {
                    y = target;
                } else {
                    x = target;
                }
            }
            let bottom = y - dy;
            let left = x - dx;
            if best.is_none_or(|(by, bx, _)| (bottom, left) < (by, bx)) {
                best = Some((bottom, left, DTransformation::new(angle, (x, y))));
            }
        }
        best.map(|(_, _, pose)| pose)
    }
}

/// Imports one outline as a jagua item (its points relative to `lo`, in sheet units). An outline
/// jagua does not accept as a simple polygon (repeated points, a self-touching seam) is nested by
/// its bounding box instead, which is always safe.
fn import_item(
    importer: &Importer,
    flat: &[DVec2],
    lo: DVec2,
    unit: f64,
    angles: &[f32],
    k: usize,
) -> Result<Arc<Item>, FabricationError> {
    let orientation = || ExtOrientation {
        rotation: ExtRotation::Discrete {
            angles: angles.to_vec(),
        },
        reflection_axes: vec![],
    };
    let points: Vec<(f32, f32)> = flat
        .iter()
        .map(|p| {
            let q = (*p - lo) * unit;
            (q.x as f32, q.y as f32)
        })
        .collect();
    let exact = ExtItem {
        id: k as u64,
        orientation: orientation(),
        shape: ExtShape::SimplePolygon(ExtSPolygon(points)),
        min_quality: None,
    };
    if let Ok(item) = importer.import_item(&exact, k) {
        return Ok(item);
    }
    let hi = flat.iter().fold(DVec2::NEG_INFINITY, |a, p| a.max(*p));
    let size = (hi - lo) * unit;
    let boxed = ExtItem {
        id: k as u64,
        orientation: orientation(),
        shape: ExtShape::Rectangle {
            x_min: 0.0,
            y_min: 0.0,
            width: (size.x as f32).max(f32::MIN_POSITIVE * 1e6),
            height: (size.y as f32).max(f32::MIN_POSITIVE * 1e6),
        },
        min_quality: None,
    };
    importer
        .import_item(&boxed, k)
        .map_err(|e| jagua("an outline", e))
}

fn jagua(what: &str, e: impl std::fmt::Display) -> FabricationError {
    FabricationError::Nesting(format!("jagua-rs rejected {what}: {e}"))
}

/// The signed area of a closed polygon (shoelace).
fn polygon_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    0.5 * (0..n).map(|i| p[i].perp_dot(p[(i + 1) % n])).sum::<f64>()
}

/// A point inside a closed polygon: the midpoint of the longest interval of the horizontal line
/// through its box's centre inside it (even-odd rule).
fn inside_point(points: &[DVec3]) -> DVec3 {
    let flat: Vec<DVec2> = points.iter().map(|p| p.truncate()).collect();
    let lo = flat.iter().fold(DVec2::INFINITY, |a, p| a.min(*p));
    let hi = flat.iter().fold(DVec2::NEG_INFINITY, |a, p| a.max(*p));
    let y = 0.5 * (lo.y + hi.y);
    let n = flat.len();
    let mut xs: Vec<f64> = (0..n)
        .filter_map(|i| {
            let (a, b) = (flat[i], flat[(i + 1) % n]);
            ((a.y <= y) != (b.y <= y)).then(|| a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x))
        })
        .collect();
    xs.sort_by(f64::total_cmp);
    let best = xs
        .chunks_exact(2)
        .max_by(|a, b| (a[1] - a[0]).total_cmp(&(b[1] - b[0])));
    match best {
        Some(pair) => DVec3::new(0.5 * (pair[0] + pair[1]), y, 0.0),
        None => DVec3::new(0.5 * (lo.x + hi.x), y, 0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x: f64, y: f64, w: f64, h: f64) -> Polyline {
        Polyline::closed(vec![
            DVec3::new(x, y, 0.0),
            DVec3::new(x + w, y, 0.0),
            DVec3::new(x + w, y + h, 0.0),
            DVec3::new(x, y + h, 0.0),
        ])
    }

    #[test]
    fn a_cancelled_nesting_stops_before_the_next_outline() {
        let outlines: Vec<Polyline> = (0..8)
            .map(|k| rect(k as f64 * 3.0, 5.0, 1.0, 0.45))
            .collect();
        let asked = std::cell::Cell::new(0);
        // Cancelled at the third question: during the import of the outlines.
        let r = nest_until(&outlines, 2.1, 2.0, 0.01, 4, &|| {
            asked.set(asked.get() + 1);
            asked.get() >= 3
        });
        assert_eq!(r, Err(FabricationError::Cancelled));
        assert_eq!(asked.get(), 3, "stopped at once");
        // Never cancelled: the same result as `nest`.
        assert_eq!(
            nest_until(&outlines, 2.1, 2.0, 0.01, 4, &|| false),
            nest(&outlines, 2.1, 2.0, 0.01, 4)
        );
    }

    /// Irregular outlines (a notched strip in a few sizes), `n` of them.
    fn strips(n: usize) -> Vec<Polyline> {
        (0..n)
            .map(|k| {
                let (l, w) = (1.0 + 0.37 * (k % 7) as f64, 0.2 + 0.05 * (k % 3) as f64);
                Polyline::closed(vec![
                    DVec3::new(0.0, 0.0, 0.0),
                    DVec3::new(l, 0.0, 0.0),
                    DVec3::new(l, w, 0.0),
                    DVec3::new(0.6 * l, w, 0.0),
                    DVec3::new(0.5 * l, 0.4 * w, 0.0),
                    DVec3::new(0.4 * l, w, 0.0),
                    DVec3::new(0.0, w, 0.0),
                ])
            })
            .collect()
    }

    /// The work of a nesting grows about linearly with the count of outlines (issue 47: 99 took
    /// 9 s and 299 took 138 s, about n^2.5): 4 × the outlines, at most 6 × the collision checks
    /// (n^2.5 would be 32 ×).
    #[test]
    fn collision_checks_grow_about_linearly_with_the_outlines() {
        let run = |n: usize| nest(&strips(n), 4.0, 3.0, 0.02, 4).unwrap();
        let (small, large) = (run(40), run(160));
        let per = |r: &Nested, n: usize| r.collision_checks as f64 / n as f64;
        println!(
            "40 outlines: {} checks, {} sheets ({:.3}); 160: {} checks, {} sheets ({:.3})",
            small.collision_checks,
            small.sheet_count,
            small.utilization,
            large.collision_checks,
            large.sheet_count,
            large.utilization
        );
        assert!(
            per(&large, 160) <= 1.5 * per(&small, 40),
            "{} checks an outline at 160 against {} at 40",
            per(&large, 160),
            per(&small, 40)
        );
        // Still a nesting: better than the boxes stacked.
        let stacked = stack_sheets(&strips(160), 4.0, 3.0, 0.02).unwrap().0;
        assert!(
            large.sheet_count < stacked,
            "{} vs {stacked}",
            large.sheet_count
        );
    }

    #[test]
    fn rectangles_fill_a_sheet_and_keep_their_shape() {
        let outlines: Vec<Polyline> = (0..8)
            .map(|k| rect(k as f64 * 3.0, 5.0, 1.0, 0.45))
            .collect();
        let n = nest(&outlines, 2.1, 2.0, 0.01, 4).unwrap();
        assert_eq!(n.sheet_count, 1);
        assert!((n.utilization - 8.0 * 0.45 / 4.2).abs() < 1e-12);
        for (a, b) in n.outlines.iter().zip(&outlines) {
            // Rigid: every edge keeps its length.
            for i in 0..4 {
                let la = a.points[i].distance(a.points[(i + 1) % 4]);
                let lb = b.points[i].distance(b.points[(i + 1) % 4]);
                assert!((la - lb).abs() < 1e-12, "{la} {lb}");
            }
            for p in &a.points {
                assert!(p.x >= -1e-9 && p.x <= 2.1 + 1e-9 && p.y >= -1e-9 && p.y <= 2.0 + 1e-9);
            }
        }
        assert_eq!(
            n,
            nest(&outlines, 2.1, 2.0, 0.01, 4).unwrap(),
            "deterministic"
        );
        // Spacing: no two placed rectangles closer than it (their boxes, axis-aligned here).
        let boxes: Vec<(DVec2, DVec2)> = n
            .outlines
            .iter()
            .map(|o| {
                let pts: Vec<DVec2> = o.points.iter().map(|p| p.truncate()).collect();
                let lo = pts.iter().fold(DVec2::INFINITY, |a, p| a.min(*p));
                let hi = pts.iter().fold(DVec2::NEG_INFINITY, |a, p| a.max(*p));
                (lo, hi)
            })
            .collect();
        for (a, (alo, ahi)) in boxes.iter().enumerate() {
            for (blo, bhi) in &boxes[a + 1..] {
                let gap = (blo.x - ahi.x)
                    .max(alo.x - bhi.x)
                    .max(blo.y - ahi.y)
                    .max(alo.y - bhi.y);
                assert!(gap >= 0.01 - 1e-6, "gap {gap}");
            }
        }
        assert!(
            nest(&outlines, 0.5, 0.5, 0.0, 4).is_err(),
            "too small a sheet"
        );
        assert!(nest(&outlines, 2.0, 2.0, -1.0, 4).is_err());
        assert!(nest(&outlines, 2.0, 2.0, 0.0, 0).is_err());
        assert!(nest(&[], 2.0, 2.0, 0.0, 4).is_err());
        assert_eq!(stack_sheets(&outlines, 2.1, 2.0, 0.01).unwrap().0, 2);
    }
}
