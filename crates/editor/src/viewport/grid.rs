//! The ground grid, the world axes and the axis gizmo: orientation and size at a glance.
//!
//! The grid lies in the view's construction plane (Top: XY, Front: XZ, Right: YZ, Perspective:
//! the chosen plane, world XY by default), around the plane's origin; a plane other than the world
//! planes also has its own axes drawn through its origin (u reddish, v greenish). Its spacing adapts to the zoom — 1, 2 or 5 × 10ⁿ metres,
//! the smallest whose cells are at least [`MIN_CELL_POINTS`] on screen — with a major line every
//! 5 or 10 cells, labelled in metres along the axes. The spacing is also the snap step of every
//! tool. The world axes are drawn through the origin (x red, y green, z blue) and a small gizmo in
//! the view's corner shows how they point.

use cnets_geometry::DVec3;
use cnets_render::{Color, Segment};
use egui::{Color32, Painter, Pos2, Rect, vec2};

use cnets_engine::numbers::snap;

use super::screen::{CPlane, ScreenMap};

/// The smallest grid cell on screen, in points.
pub const MIN_CELL_POINTS: f64 = 14.0;

/// Minor and major grid lines per side of the target, at most.
const HALF_CELLS: i64 = 60;

/// The x axis colour (red).
pub const X_COLOR: Color32 = Color32::from_rgb(0xd0, 0x31, 0x2d);
/// The y axis colour (green).
pub const Y_COLOR: Color32 = Color32::from_rgb(0x2a, 0x9d, 0x3c);
/// The z axis colour (blue).
pub const Z_COLOR: Color32 = Color32::from_rgb(0x1f, 0x5f, 0xd0);
/// The colour of a construction plane's own u axis (not a world plane's).
pub const PLANE_U_COLOR: Color32 = Color32::from_rgb(0xe8, 0x80, 0x70);
/// The colour of a construction plane's own v axis.
pub const PLANE_V_COLOR: Color32 = Color32::from_rgb(0x70, 0xc0, 0x78);

/// The grid's spacing at a zoom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spacing {
    /// Distance between minor lines (the snap step), in metres.
    pub minor: f64,
    /// Distance between major (labelled) lines.
    pub major: f64,
}

impl Spacing {
    /// The spacing for a view where one screen point is `world_per_point` metres at the target.
    pub fn for_scale(world_per_point: f64) -> Spacing {
        let wanted = (world_per_point * MIN_CELL_POINTS).max(1e-9);
        let decade = 10f64.powf(wanted.log10().floor());
        let (mantissa, per_major) = [(1.0, 5.0), (2.0, 5.0), (5.0, 2.0), (10.0, 5.0)]
            .into_iter()
            .find(|(m, _)| m * decade >= wanted * (1.0 - 1e-9))
            .unwrap_or((10.0, 5.0));
        let minor = snap(mantissa * decade, 0.0, decade);
        Spacing {
            minor,
            major: snap(minor * per_major, 0.0, minor),
        }
    }
}

/// A length in metres as the grid labels write it: `5 m`, `0.25 m`, `1 200 m`.
pub fn metres(x: f64) -> String {
    let text = if x.abs() >= 1e4 || (x != 0.0 && x.abs() < 1e-3) {
        format!("{x:e}")
    } else {
        let s = format!("{x:.6}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    format!("{text} m")
}

fn rgba(c: Color32) -> Color {
    Color::rgba(c.r(), c.g(), c.b(), c.a())
}

fn segment(a: DVec3, b: DVec3, color: Color, width: f32) -> Segment {
    let f = |p: DVec3| [p.x as f32, p.y as f32, p.z as f32];
    Segment {
        a: f(a),
        b: f(b),
        color,
        width,
        flags: 0,
    }
}

/// The grid of a view: its spacing, the square it covers and the line segments to draw.
pub struct Grid {
    /// The spacing.
    pub spacing: Spacing,
    /// The construction plane it lies in.
    pub plane: CPlane,
    /// The plane's name, written in the view's corner (`World XY`, `CPlane 1`).
    pub name: String,
    /// Grid lines and world axes, for the renderer (depth-tested with the scene).
    pub segments: Vec<Segment>,
    /// Major line positions along the plane's first and second axis, for labels.
    majors: (Vec<f64>, Vec<f64>),
}

impl Grid {
    /// The grid of `plane` around the camera's target, spaced for the map's zoom: up to
    /// [`HALF_CELLS`] cells each way, and no farther than `around` (the geometry shown, when
    /// given) reaches past its edges by [`around_margin`] — a perspective view of a 50 m design
    /// shows a grid about as large as the design, not 120 m of it.
    pub fn new(map: &ScreenMap, plane: CPlane, around: Option<&cnets_render::Bounds>) -> Grid {
        let spacing = Spacing::for_scale(map.world_per_point());
        // The target projected into the plane, on the major grid.
        let target = map.target();
        let local = plane.local(target);
        let centre = |x: f64| (x / spacing.major).round() * spacing.major;
        let (cu, cv) = (centre(local.x), centre(local.y));
        let half = spacing.minor * HALF_CELLS as f64;
        let (mut u0, mut u1, mut v0, mut v1) = (cu - half, cu + half, cv - half, cv + half);
        if let Some((a0, a1, b0, b1)) = around.and_then(|b| extent_in_plane(b, plane, spacing)) {
            let (c0, c1, d0, d1) = (u0.max(a0), u1.min(a1), v0.max(b0), v1.min(b1));
            // The geometry out of reach of the target's grid (panned far away): the target's.
            if c0 < c1 && d0 < d1 {
                (u0, u1, v0, v1) = (c0, c1, d0, d1);
            }
        }
        let within = |x: f64, lo: f64, hi: f64| x >= lo - 1e-9 * half && x <= hi + 1e-9 * half;
        let at = |a: f64, b: f64| plane.at(a, b, 0.0);
        let minor = rgba(Color32::from_rgba_unmultiplied(120, 128, 140, 70));
        let major = rgba(Color32::from_rgba_unmultiplied(90, 98, 110, 140));
        let world = plane.is_world();
        let mut segments = Vec::with_capacity(4 * HALF_CELLS as usize + 10);
        let mut majors = (Vec::new(), Vec::new());
        let per_major = (spacing.major / spacing.minor).round() as i64;
        for k in -HALF_CELLS..=HALF_CELLS {
            let is_major = k.rem_euclid(per_major) == 0;
            let (color, width) = if is_major { (major, 1.2) } else { (minor, 1.0) };
            let a = snap(cu + k as f64 * spacing.minor, 0.0, spacing.minor);
            let b = snap(cv + k as f64 * spacing.minor, 0.0, spacing.minor);
            // Lines on a world plane's axes are drawn as the world axes below; another plane's
            // own axes are drawn in their colours.
            let (a_color, a_width) = if a == 0.0 {
                (rgba(PLANE_V_COLOR), 1.5)
            } else {
                (color, width)
            };
            let (b_color, b_width) = if b == 0.0 {
                (rgba(PLANE_U_COLOR), 1.5)
            } else {
                (color, width)
            };
            let (a_in, b_in) = (within(a, u0, u1), within(b, v0, v1));
            if a_in && (a != 0.0 || !world) {
                segments.push(segment(at(a, v0), at(a, v1), a_color, a_width));
            }
            if b_in && (b != 0.0 || !world) {
                segments.push(segment(at(u0, b), at(u1, b), b_color, b_width));
            }
            if is_major && a_in {
                majors.0.push(a);
            }
            if is_major && b_in {
                majors.1.push(b);
            }
        }
        // World axes through the origin, across the grid (and as far the other way).
        let reach = half + target.length();
        for (axis, color) in [
            (DVec3::X, X_COLOR),
            (DVec3::Y, Y_COLOR),
            (DVec3::Z, Z_COLOR),
        ] {
            segments.push(segment(-axis * reach, axis * reach, rgba(color), 1.6));
        }
        Grid {
            spacing,
            plane,
            name: plane.label().to_string(),
            segments,
            majors,
        }
    }

    /// Labels the major lines in metres where they cross the plane's axes, and names the
    /// spacing in the view's corner. No label is drawn over `keep_out` (the corner figures, the
    /// legend, the gizmo, W × D × H): one that would touch them is left out, and the spacing's
    /// name moves up above what it would touch. Returns the rectangle of the spacing's name.
    pub fn paint_labels(&self, painter: &Painter, map: &ScreenMap, keep_out: &[Rect]) -> Rect {
        let plane = self.plane;
        let font = egui::FontId::proportional(10.5);
        let ink = Color32::from_gray(95);
        let inside = map.rect.shrink(4.0);
        let mut placed: Vec<Rect> = keep_out
            .iter()
            .copied()
            .filter(|r| r.is_positive())
            .collect();
        let mut label = |p: DVec3, text: String| {
            let Some(at) = map.to_screen(p) else {
                return;
            };
            if !inside.contains(at) {
                return;
            }
            let galley = painter.layout_no_wrap(text, font.clone(), ink);
            let r = Rect::from_min_size(at + vec2(3.0, 2.0), galley.size());
            if placed.iter().any(|o| o.expand(3.0).intersects(r)) {
                return;
            }
            placed.push(r);
            painter.galley(r.min, galley, ink);
        };
        for &a in &self.majors.0 {
            if a != 0.0 {
                label(plane.at(a, 0.0, 0.0), metres(a));
            }
        }
        for &b in &self.majors.1 {
            if b != 0.0 {
                label(plane.at(0.0, b, 0.0), metres(b));
            }
        }
        let caption = painter.layout_no_wrap(
            format!("grid {} · {}", metres(self.spacing.minor), self.name),
            font,
            ink,
        );
        let mut at = map.rect.left_bottom() + vec2(76.0, -8.0 - caption.size().y);
        let clear = |r: Rect| !keep_out.iter().any(|o| o.is_positive() && o.intersects(r));
        for _ in 0..4 {
            if clear(Rect::from_min_size(at, caption.size())) {
                break;
            }
            at.y -= caption.size().y + 4.0;
        }
        let r = Rect::from_min_size(at, caption.size());
        painter.galley(at, caption, ink);
        r
    }
}

/// How far the grid reaches past the geometry it is sized to: two major cells, or a quarter of
/// the geometry's larger side in the plane when that is more.
pub fn around_margin(width: f64, depth: f64, spacing: Spacing) -> f64 {
    (2.0 * spacing.major).max(0.25 * width.max(depth))
}

/// The rectangle `(u0, u1, v0, v1)` of the plane's coordinates a grid sized to `bounds` covers:
/// the box's corners in the plane, widened by [`around_margin`] and out to major lines. `None`
/// for a box that is not finite.
fn extent_in_plane(
    bounds: &cnets_render::Bounds,
    plane: CPlane,
    spacing: Spacing,
) -> Option<(f64, f64, f64, f64)> {
    let (lo, hi) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let (mut u0, mut u1, mut v0, mut v1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for k in 0..8 {
        let corner = DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        let l = plane.local(corner);
        (u0, u1, v0, v1) = (u0.min(l.x), u1.max(l.x), v0.min(l.y), v1.max(l.y));
    }
    let margin = around_margin(u1 - u0, v1 - v0, spacing);
    let major = spacing.major;
    Some((
        ((u0 - margin) / major).floor() * major,
        ((u1 + margin) / major).ceil() * major,
        ((v0 - margin) / major).floor() * major,
        ((v1 + margin) / major).ceil() * major,
    ))
}

/// Paints the axis gizmo in the view's bottom-left corner: the world axes as the camera sees them.
/// Returns the square it covers.
pub fn paint_gizmo(painter: &Painter, map: &ScreenMap) -> Rect {
    let centre = map.rect.left_bottom() + vec2(36.0, -40.0);
    let cam = map.camera;
    let (right, up) = (cam.right(), cam.up());
    let font = egui::FontId::proportional(11.0);
    painter.circle_filled(
        centre,
        27.0,
        Color32::from_rgba_unmultiplied(255, 255, 255, 150),
    );
    // Back to front, so the axis pointing at the viewer is drawn last.
    let mut axes = [
        (glam::Vec3::X, X_COLOR, "x"),
        (glam::Vec3::Y, Y_COLOR, "y"),
        (glam::Vec3::Z, Z_COLOR, "z"),
    ];
    axes.sort_by(|a, b| a.0.dot(cam.back()).total_cmp(&b.0.dot(cam.back())));
    for (axis, color, name) in axes {
        let d = egui::vec2(axis.dot(right), -axis.dot(up)) * 20.0;
        let tip: Pos2 = centre + d;
        painter.line_segment([centre, tip], egui::Stroke::new(2.0, color));
        painter.text(
            centre + d * 1.25,
            egui::Align2::CENTER_CENTER,
            name,
            font.clone(),
            color,
        );
    }
    Rect::from_center_size(centre, vec2(60.0, 60.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid lines' extent in the XY plane (the world axes left out): (u0, u1, v0, v1).
    fn line_extent(grid: &Grid) -> (f64, f64, f64, f64) {
        grid.segments
            .iter()
            .filter(|s| s.width < 1.55)
            .flat_map(|s| [s.a, s.b])
            .fold(
                (
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                ),
                |(u0, u1, v0, v1), p| {
                    let (x, y) = (f64::from(p[0]), f64::from(p[1]));
                    (u0.min(x), u1.max(x), v0.min(y), v1.max(y))
                },
            )
    }

    /// The perspective view of a design 49 m × 48.5 m (torus-monge's three surfaces), framed on
    /// it: the grid covers the design and reaches past it by its margin only (it reached 120 m
    /// each way from the target, 60 cells of 2 m).
    #[test]
    fn a_grid_sized_to_the_geometry_covers_it_and_little_more() {
        let bounds = cnets_render::Bounds::new(
            glam::Vec3::new(10.0, 0.0, 0.0),
            glam::Vec3::new(59.0, 48.5, 8.2),
        );
        let mut camera = cnets_render::Camera::new(cnets_render::View::Iso);
        let rect = Rect::from_min_size(Pos2::ZERO, vec2(630.0, 770.0));
        camera.fit(Some(bounds), rect.width() / rect.height());
        let map = ScreenMap { rect, camera };
        let free = Grid::new(&map, CPlane::XY, None);
        let sized = Grid::new(&map, CPlane::XY, Some(&bounds));
        let spacing = sized.spacing;
        let (u0, u1, v0, v1) = line_extent(&sized);
        let (f0, f1, g0, g1) = line_extent(&free);
        let margin = around_margin(49.0, 48.5, spacing) + spacing.major;
        assert!(
            u0 <= 10.0 && u1 >= 59.0 && v0 <= 0.0 && v1 >= 48.5,
            "covers the design: {u0}..{u1} × {v0}..{v1}"
        );
        assert!(
            u0 >= 10.0 - margin && u1 <= 59.0 + margin && v0 >= -margin && v1 <= 48.5 + margin,
            "within {margin} m of it: {u0}..{u1} × {v0}..{v1} (grid {spacing:?})"
        );
        assert!(
            (f1 - f0) > 1.5 * (u1 - u0) && (g1 - g0) > 1.5 * (v1 - v0),
            "smaller than the grid around the target: {f0}..{f1} × {g0}..{g1}"
        );
        // Labels only on the lines drawn.
        assert!(sized.majors.0.iter().all(|&a| (u0..=u1).contains(&a)));
        assert!(sized.majors.1.iter().all(|&b| (v0..=v1).contains(&b)));
        // Geometry out of the target's reach (panned far away): the target's grid.
        let far = cnets_render::Bounds::new(glam::Vec3::splat(1e5), glam::Vec3::splat(1e5 + 1.0));
        assert_eq!(
            line_extent(&Grid::new(&map, CPlane::XY, Some(&far))),
            (f0, f1, g0, g1)
        );
    }

    #[test]
    fn the_spacing_is_one_two_or_five_and_cells_stay_readable() {
        for wpp in [1e-4, 0.003, 0.01, 0.037, 0.1, 0.5, 2.0, 70.0] {
            let s = Spacing::for_scale(wpp);
            let cell_points = s.minor / wpp;
            assert!(cell_points >= MIN_CELL_POINTS * 0.999, "{wpp}: {s:?}");
            assert!(cell_points < MIN_CELL_POINTS * 2.6, "{wpp}: {s:?}");
            let mantissa = s.minor / 10f64.powf(s.minor.log10().floor());
            assert!(
                [1.0, 2.0, 5.0].iter().any(|m| (m - mantissa).abs() < 1e-9),
                "{s:?}"
            );
            let per_major = s.major / s.minor;
            assert!((per_major - per_major.round()).abs() < 1e-9);
        }
        assert_eq!(Spacing::for_scale(0.05).minor, 1.0);
        assert_eq!(metres(5.0), "5 m");
        assert_eq!(metres(0.25), "0.25 m");
        assert_eq!(metres(snap(3.0 * 0.1, 0.0, 0.1)), "0.3 m");
    }
}
