//! Camera: framing, presets, orbit / pan / zoom, degenerate input.

use cnets_render::{Bounds, Camera, View};
use glam::Vec3;

const ASPECTS: [f32; 3] = [0.5, 1.0, 16.0 / 9.0];

fn boxes() -> Vec<Bounds> {
    vec![
        Bounds::new(Vec3::splat(-1.0), Vec3::splat(1.0)),
        Bounds::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(10.0, 8.0, 0.0)), // flat
        Bounds::new(Vec3::new(-50.0, 3.0, 2.0), Vec3::new(150.0, 4.0, 2.5)), // long and thin
        Bounds::new(
            Vec3::new(1e4, 2e4, -3e3),
            Vec3::new(1.001e4, 2.002e4, -2.99e3),
        ), // far away
        Bounds::new(Vec3::new(0.0, 0.0, -20.0), Vec3::new(0.1, 0.1, 20.0)), // a tall post
    ]
}

fn assert_inside(camera: &Camera, p: Vec3, aspect: f32, what: &str) {
    let ndc = camera
        .project(p, aspect)
        .unwrap_or_else(|| panic!("{what}: {p} is behind the eye of {camera:?}"));
    assert!(
        ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0 && (0.0..=1.0).contains(&ndc.z),
        "{what}: {p} projects to {ndc} outside the view ({camera:?})"
    );
}

#[test]
fn fit_puts_every_corner_inside_the_frustum_for_every_preset() {
    for view in View::ALL {
        for aspect in ASPECTS {
            for b in boxes() {
                let camera = Camera::framing(view, Some(b), aspect);
                for corner in b.corners() {
                    assert_inside(&camera, corner, aspect, &format!("{view} {aspect}"));
                }
                // Not absurdly far either: the box fills a good part of the image.
                let ndc: Vec<Vec3> = b
                    .corners()
                    .iter()
                    .map(|&c| camera.project(c, aspect).unwrap())
                    .collect();
                let span_x = ndc.iter().map(|p| p.x).fold(f32::MIN, f32::max)
                    - ndc.iter().map(|p| p.x).fold(f32::MAX, f32::min);
                let span_y = ndc.iter().map(|p| p.y).fold(f32::MIN, f32::max)
                    - ndc.iter().map(|p| p.y).fold(f32::MAX, f32::min);
                // A long box seen end-on: its near end must stay clear of the near plane, so it
                // cannot fill the view.
                let extent = |axis: Vec3| (b.size() * axis).abs().element_sum();
                let end_on =
                    extent(camera.back()) > 10.0 * extent(camera.right()).max(extent(camera.up()));
                let min_fill = if end_on { 0.2 } else { 1.5 };
                assert!(
                    span_x.max(span_y) > min_fill,
                    "{view} {aspect} {b:?}: spans {span_x} {span_y}"
                );
            }
        }
    }
}

#[test]
fn fit_points_frames_points_tightly_and_centred() {
    // A curved strip of points.
    let points: Vec<Vec3> = (0..200)
        .map(|k| {
            let t = k as f32 / 199.0 * 3.0;
            Vec3::new(5.0 * t.cos(), 5.0 * t.sin(), 0.3 * t)
        })
        .collect();
    for view in View::ALL {
        let mut camera = Camera::new(view);
        camera.fit_points(&points, 1.5);
        let ndc: Vec<Vec3> = points
            .iter()
            .map(|&p| camera.project(p, 1.5).unwrap())
            .collect();
        for (p, n) in points.iter().zip(&ndc) {
            assert!(n.x.abs() <= 1.0 && n.y.abs() <= 1.0, "{view}: {p} -> {n}");
        }
        let (lo_x, hi_x) = ndc
            .iter()
            .fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p.x), h.max(p.x)));
        let (lo_y, hi_y) = ndc
            .iter()
            .fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p.y), h.max(p.y)));
        // Tight: one axis spans (almost) the whole view; centred: margins balanced.
        assert!(
            (hi_x - lo_x).max(hi_y - lo_y) > 1.7,
            "{view}: {lo_x} {hi_x} {lo_y} {hi_y}"
        );
        assert!(
            (hi_x + lo_x).abs() < 0.05 && (hi_y + lo_y).abs() < 0.05,
            "{view}: off-centre: x {lo_x}..{hi_x}, y {lo_y}..{hi_y}"
        );
    }
}

/// A long object seen end-on in perspective (a bridge 30 m long and 4 m wide from its side): the
/// near end's image is far larger than the far end's, and the framing still centres the image.
#[test]
fn a_long_object_seen_end_on_is_framed_centred() {
    let points: Vec<Vec3> = (0..300)
        .flat_map(|k| {
            let x = k as f32 / 299.0 * 30.0;
            let y = 2.0 * (x / 30.0 * std::f32::consts::TAU).sin() + 5.0;
            [
                Vec3::new(x, y - 2.0, 1.0),
                Vec3::new(x, y + 2.0, 1.0),
                Vec3::new(x, y, -0.5),
            ]
        })
        .collect();
    for (view, aspect) in [
        (View::Side, 16.0 / 9.0),
        (View::Front, 1.0),
        (View::Iso, 0.6),
    ] {
        let mut camera = Camera::new(view);
        camera.fit_points(&points, aspect);
        let ndc: Vec<Vec3> = points
            .iter()
            .map(|&p| camera.project(p, aspect).unwrap())
            .collect();
        let (lo_x, hi_x) = ndc
            .iter()
            .fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p.x), h.max(p.x)));
        let (lo_y, hi_y) = ndc
            .iter()
            .fold((f32::MAX, f32::MIN), |(l, h), p| (l.min(p.y), h.max(p.y)));
        assert!(
            lo_x >= -1.0 && hi_x <= 1.0 && lo_y >= -1.0 && hi_y <= 1.0,
            "{view}: in view: x {lo_x}..{hi_x}, y {lo_y}..{hi_y}"
        );
        assert!(
            (hi_x - lo_x).max(hi_y - lo_y) > 1.7,
            "{view}: tight: x {lo_x}..{hi_x}, y {lo_y}..{hi_y}"
        );
        assert!(
            (hi_x + lo_x).abs() < 0.01 && (hi_y + lo_y).abs() < 0.01,
            "{view}: off-centre: x {lo_x}..{hi_x}, y {lo_y}..{hi_y}"
        );
    }
}

#[test]
fn presets_orient_the_image_like_rhino() {
    let aspect = 1.0;
    let b = Bounds::new(Vec3::splat(-1.0), Vec3::splat(1.0));
    let screen = |view: View, p: Vec3| {
        Camera::framing(view, Some(b), aspect)
            .project(p, aspect)
            .unwrap()
    };
    // Top: X right, Y up.
    assert!(screen(View::Top, Vec3::X).x > 0.1 && screen(View::Top, Vec3::X).y.abs() < 1e-4);
    assert!(screen(View::Top, Vec3::Y).y > 0.1);
    // Front: X right, Z up, looking along +Y.
    assert!(screen(View::Front, Vec3::X).x > 0.1);
    assert!(screen(View::Front, Vec3::Z).y > 0.1);
    assert!(
        Camera::new(View::Front)
            .forward()
            .abs_diff_eq(Vec3::Y, 1e-6)
    );
    // Side (right): Y right, Z up, looking along -X.
    assert!(screen(View::Side, Vec3::Y).x > 0.1);
    assert!(screen(View::Side, Vec3::Z).y > 0.1);
    assert!(
        Camera::new(View::Side)
            .forward()
            .abs_diff_eq(-Vec3::X, 1e-6)
    );
    // Iso: from +X -Y +Z, Z up on screen.
    let eye_dir = Camera::new(View::Iso).back();
    assert!(eye_dir.x > 0.0 && eye_dir.y < 0.0 && eye_dir.z > 0.0);
    assert!(screen(View::Iso, Vec3::Z).y > 0.1);
    // The camera frame is orthonormal in every preset (also straight down).
    for view in View::ALL {
        let c = Camera::new(view);
        let (r, u, f) = (c.right(), c.up(), c.forward());
        for v in [r, u, f] {
            assert!((v.length() - 1.0).abs() < 1e-5, "{view}");
        }
        assert!(
            r.dot(u).abs() < 1e-5 && u.dot(f).abs() < 1e-5 && r.dot(f).abs() < 1e-5,
            "{view}"
        );
    }
}

#[test]
fn views_parse_from_cli_names() {
    for view in View::ALL {
        assert_eq!(view.name().parse::<View>().unwrap(), view);
        assert_eq!(view.to_string(), view.name());
    }
    assert_eq!(" TOP ".parse::<View>().unwrap(), View::Top);
    let err = "bottom".parse::<View>().unwrap_err();
    assert!(err.to_string().contains("iso, top, front or side"), "{err}");
}

#[test]
fn orbit_and_zoom_keep_the_target_pan_keeps_the_direction() {
    let mut c = Camera::framing(
        View::Iso,
        Some(Bounds::new(Vec3::ZERO, Vec3::new(4.0, 2.0, 1.0))),
        1.5,
    );
    let target = c.target;
    let d = c.distance;
    c.orbit(0.7, -0.2);
    assert_eq!(c.target, target);
    assert!((c.eye().distance(c.target) - d).abs() < 1e-4 * d);
    c.orbit(0.0, 10.0); // clamped at straight down
    assert!(c.pitch <= std::f32::consts::FRAC_PI_2 && c.view_projection(1.5).is_finite());
    c.orbit(f32::NAN, f32::INFINITY); // ignored
    assert!(c.yaw.is_finite() && c.pitch.is_finite());

    c.zoom(0.5);
    assert_eq!(c.target, target);
    assert!((c.distance - d * 0.5).abs() < 1e-5 * d);
    c.zoom(0.0); // ignored
    c.zoom(-1.0); // ignored
    assert!((c.distance - d * 0.5).abs() < 1e-5 * d);
    c.zoom(1e-30); // clamped, still invertible
    assert!(c.distance > 0.0 && c.view_projection(1.5).is_finite());

    let mut c = Camera::new(View::Front);
    c.distance = 10.0;
    let forward = c.forward();
    c.pan(100.0, 0.0, 500.0); // drag to the right: the scene follows, the target moves left (-X)
    assert!(c.target.x < 0.0 && c.target.y.abs() < 1e-6 && c.target.z.abs() < 1e-6);
    assert_eq!(c.forward(), forward);
    // The target's screen position moved by exactly the drag.
    let mut before = Camera::new(View::Front);
    before.distance = 10.0;
    let p = before.project(Vec3::ZERO, 1.0).unwrap();
    let q = c.project(Vec3::ZERO, 1.0).unwrap();
    assert!(
        ((q.x - p.x) * 250.0 - 100.0).abs() < 1e-2,
        "moved {} px",
        (q.x - p.x) * 250.0
    );
}

#[test]
fn degenerate_bounds_give_a_usable_camera() {
    // Empty scene.
    let c = Camera::framing(View::Iso, None, 1.0);
    assert!(c.distance.is_finite() && c.distance > 0.0);
    assert!(c.view_projection(1.0).is_finite());
    assert_inside(&c, Vec3::splat(0.5), 1.0, "unit cube");
    // A single point: it is the target, seen in the middle.
    let p = Vec3::new(3.0, -2.0, 7.0);
    for view in View::ALL {
        let c = Camera::framing(view, Some(Bounds::point(p)), 1.0);
        assert_eq!(c.target, p);
        assert!(c.distance > 0.0 && c.distance.is_finite());
        let ndc = c.project(p, 1.0).unwrap();
        assert!(ndc.x.abs() < 1e-5 && ndc.y.abs() < 1e-5, "{view}: {ndc}");
        let mut c2 = Camera::new(view);
        c2.fit_points(&[p, p, Vec3::NAN], 1.0);
        assert_eq!(c2.target, p);
    }
    // Non-finite bounds and silly parameters do not produce NaN matrices.
    let c = Camera::framing(
        View::Top,
        Some(Bounds {
            min: Vec3::NAN,
            max: Vec3::ONE,
        }),
        0.0,
    );
    assert!(c.view_projection(0.0).is_finite());
    let silly = Camera {
        distance: f32::NAN,
        fov_y: 0.0,
        ..Camera::default()
    };
    assert!(silly.view_projection(f32::NAN).is_finite());
    assert!(Camera::default().view_projection(1.0).is_finite());
    let mut c = Camera::new(View::Iso);
    c.fit_points(&[], 1.0);
    assert!(c.view_projection(1.0).is_finite());
}

#[test]
fn orthographic_views_frame_tightly_keep_sizes_and_zoom_towards_a_point() {
    use cnets_render::Projection;
    for b in boxes() {
        for view in View::ALL {
            for aspect in ASPECTS {
                let mut camera = Camera::new(view);
                camera.projection = Projection::Orthographic;
                camera.fit(Some(b), aspect);
                for p in b.corners() {
                    assert_inside(&camera, p, aspect, &format!("ortho {view:?} {b:?}"));
                }
                // Parallel projection: a segment's image does not depend on its depth.
                let r = b.radius();
                let (right, back) = (camera.right() * r, camera.back() * r);
                let near = camera.project(b.center() + back, aspect).unwrap();
                let near2 = camera.project(b.center() + back + right, aspect).unwrap();
                let far = camera.project(b.center() - back, aspect).unwrap();
                let far2 = camera.project(b.center() - back + right, aspect).unwrap();
                let (a, c) = (near2.x - near.x, far2.x - far.x);
                assert!(
                    (a - c).abs() <= 1e-3 * a.abs().max(1.0),
                    "{view:?} {b:?}: sizes kept with depth ({a} vs {c})"
                );
                // The wheel's zoom keeps the point under the pointer in place.
                let (x, y) = (0.6, -0.3);
                let h = camera.half_height_at_target();
                let under =
                    camera.target + camera.right() * (x * h * aspect) + camera.up() * (y * h);
                let before = camera.project(under, aspect).unwrap();
                camera.zoom_at(0.5, x, y, aspect);
                let after = camera.project(under, aspect).unwrap();
                assert!(
                    (before.truncate() - after.truncate()).length() < 1e-3,
                    "{view:?}: {before} → {after}"
                );
            }
        }
    }
}
