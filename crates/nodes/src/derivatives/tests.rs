//! Every product against central differences of the node's own run (the fallback the optimizer
//! uses for nodes without one).

use cnets_engine::NodeContext;
use cnets_engine::eval::evaluate_node;
use cnets_engine::optimize::leaves;
use cnets_engine::optimize::vjp::{Wanted, node_vjp};
use cnets_engine::prelude::*;
use std::sync::Arc;

fn def(id: &str) -> NodeDef {
    crate::all()
        .into_iter()
        .find(|d| d.id == id)
        .unwrap_or_else(|| panic!("no node {id}"))
}

/// Inputs by name (defaults elsewhere).
fn inputs(d: &NodeDef, named: &[(&str, Value)]) -> Vec<Value> {
    d.inputs
        .iter()
        .map(|p| {
            named
                .iter()
                .find(|(n, _)| *n == p.name)
                .map(|(_, v)| v.clone())
                .or_else(|| p.default.clone())
                .unwrap_or(Value::Null)
        })
        .collect()
}

/// Compares the exact product with finite differences for the `wanted` inputs and cotangent
/// weights `w(k)` on every output number; returns the largest relative difference.
fn compare(id: &str, named: &[(&str, Value)], wanted: &[&str]) -> f64 {
    compare_components(id, named, wanted, |_| true)
}

/// [`compare`] over the components `keep` accepts (by index in the input's leaves) only.
fn compare_components(
    id: &str,
    named: &[(&str, Value)],
    wanted: &[&str],
    keep: impl Fn(usize) -> bool,
) -> f64 {
    let exact_def = def(id);
    assert!(exact_def.vjp.is_some(), "{id} has a product");
    let mut fd_def = exact_def.clone();
    fd_def.vjp = None;
    let ctx = NodeContext::default();
    let ins = inputs(&exact_def, named);
    let outs = evaluate_node(&exact_def, &ctx, &ins).unwrap().values;
    let cot: Vec<Option<Vec<f64>>> = outs
        .iter()
        .enumerate()
        .map(|(o, v)| {
            let n = leaves::count(v);
            // The alignment's largest term has no product: only its mean is weighted.
            // The surface distance's eight outputs (one-sided, symmetric, each direction) all
            // weighted.
            let outputs = match id {
                "measure.normal_alignment" => 1,
                "measure.surface_distance" => 8,
                // Mesh, apex values, apices, planes and the margins (the labels, records and
                // corrections between have no numbers or none to follow).
                "cnets.construct" | "ctube.construct" | "cnets.construct_coplanar" => 8,
                _ => 3,
            };
            (n > 0 && !leaves::opaque(v) && o < outputs).then(|| {
                (0..n)
                    .map(|k| ((k + o) as f64 * 0.37 + 0.5).sin())
                    .collect()
            })
        })
        .collect();
    let want: Vec<Wanted> = exact_def
        .inputs
        .iter()
        .map(|p| {
            if wanted.contains(&p.name.as_ref()) {
                Wanted::All
            } else {
                Wanted::No
            }
        })
        .collect();
    let exact = node_vjp(&exact_def, &ctx, &ins, &outs, &cot, &want).unwrap();
    assert!(
        exact.finite_differences.is_none(),
        "{id}: {:?}",
        exact.finite_differences
    );
    let fd = node_vjp(&fd_def, &ctx, &ins, &outs, &cot, &want).unwrap();
    let (mut diff, mut scale) = (0.0f64, 0.0f64);
    for (a, b) in exact.inputs.iter().zip(&fd.inputs) {
        if let (Some(a), Some(b)) = (a, b) {
            assert_eq!(a.len(), b.len());
            for (_, (x, y)) in a.iter().zip(b).enumerate().filter(|(k, _)| keep(*k)) {
                diff = diff.max((x - y).abs());
                scale = scale.max(y.abs());
            }
        }
    }
    assert!(scale > 0.0, "{id}: the gradient is not zero");
    diff / scale
}

fn pts(ps: &[[f64; 3]]) -> Value {
    Value::list(
        ps.iter()
            .map(|p| Value::Point(DVec3::from_array(*p)))
            .collect(),
    )
}

fn grid() -> Value {
    let mut v = Vec::new();
    for i in 0..4 {
        for j in 0..5 {
            let (x, y) = (j as f64, i as f64 * 0.8);
            v.push(DVec3::new(x, y, 0.1 * x * x - 0.15 * y * y + 0.05 * x * y));
        }
    }
    Value::QuadMesh(Arc::new(QuadGrid::new(4, 5, v).unwrap()))
}

#[test]
fn math_products_match_differences() {
    let n = Value::Number;
    for (id, named) in [
        ("math.add", vec![("a", n(1.5)), ("b", n(-0.5))]),
        ("math.subtract", vec![("a", n(1.5)), ("b", n(-0.5))]),
        ("math.multiply", vec![("a", n(1.5)), ("b", n(-0.7))]),
        ("math.divide", vec![("a", n(1.5)), ("b", n(-0.7))]),
        ("math.power", vec![("base", n(1.5)), ("exponent", n(2.3))]),
        ("math.min", vec![("a", n(1.5)), ("b", n(-0.7))]),
        ("math.max", vec![("a", n(1.5)), ("b", n(-0.7))]),
        ("math.clamp", vec![("value", n(0.4))]),
        (
            "vector.point",
            vec![("x", n(1.5)), ("y", n(-0.7)), ("z", n(2.0))],
        ),
    ] {
        let wanted: Vec<&str> = named.iter().map(|(k, _)| *k).collect();
        let rel = compare(id, &named, &wanted);
        assert!(rel < 1e-8, "{id}: {rel}");
    }
    let rel = compare(
        "math.remap",
        &[
            ("value", n(0.3)),
            ("from_start", n(-1.0)),
            ("from_end", n(2.0)),
            ("to_start", n(5.0)),
            ("to_end", n(7.0)),
        ],
        &["value", "from_start", "from_end", "to_start", "to_end"],
    );
    assert!(rel < 1e-8, "remap: {rel}");
    // Mapped over lists: a list of numbers times a number.
    let rel = compare(
        "math.multiply",
        &[
            ("a", crate::testing::nums(&[1.0, 2.0, -3.0])),
            ("b", n(0.5)),
        ],
        &["a", "b"],
    );
    assert!(rel < 1e-8, "mapped multiply: {rel}");
}

#[test]
fn structural_products_match_differences() {
    let list = crate::testing::nums(&[0.1, 0.7, -0.3, 0.9, 0.25]);
    for (id, named, wanted) in [
        ("list.reverse", vec![("list", list.clone())], vec!["list"]),
        (
            "list.item",
            vec![("list", list.clone()), ("index", Value::Integer(3))],
            vec!["list"],
        ),
        (
            "mesh.column",
            vec![("mesh", grid()), ("index", Value::Integer(-1))],
            vec!["mesh"],
        ),
        (
            "mesh.row",
            vec![("mesh", grid()), ("index", Value::Integer(1))],
            vec!["mesh"],
        ),
        (
            "param.list",
            vec![("values", Value::list(vec![list.clone(), list.clone()]))],
            vec!["values"],
        ),
    ] {
        let rel = compare(id, &named, &wanted);
        assert!(rel < 1e-8, "{id}: {rel}");
    }
}

#[test]
fn measure_products_match_differences() {
    let a = pts(&[[0.0, 0.1, 0.2], [1.0, 0.3, -0.2], [2.0, -0.4, 0.5]]);
    let b = pts(&[[0.2, 0.0, 0.1], [1.1, 0.0, 0.0], [1.7, 0.1, 0.2]]);
    let rel = compare("measure.point_distance", &[("a", a), ("b", b)], &["a", "b"]);
    assert!(rel < 1e-7, "point_distance: {rel}");
    let shifted = Value::list(vec![pts(&[[0.5, 0.2, 0.1]; 20])]);
    let rel = compare(
        "measure.point_distance",
        &[("a", grid()), ("b", shifted)],
        &["a"],
    );
    assert!(rel < 1e-7, "point_distance on a mesh: {rel}");
    let rel = compare(
        "measure.closure",
        &[("mesh", grid()), ("tangents", Value::Number(0.5))],
        &["mesh", "tangents"],
    );
    assert!(rel < 1e-7, "closure: {rel}");
    let rel = compare(
        "measure.normal_alignment",
        &[
            ("mesh", grid()),
            ("target", Value::Vector(DVec3::new(0.1, 0.3, 1.0))),
        ],
        &["mesh"],
    );
    assert!(rel < 1e-7, "normal_alignment: {rel}");
    let rel = compare("measure.fairness", &[("mesh", grid())], &["mesh"]);
    assert!(rel < 1e-7, "fairness (mesh): {rel}");
    let table = Value::list(vec![
        crate::testing::nums(&[0.1, 0.5, 0.3, 0.9]),
        crate::testing::nums(&[0.2, 0.4, 0.8, 0.1]),
        crate::testing::nums(&[0.7, 0.6, 0.5, 0.2]),
    ]);
    let rel = compare("measure.fairness", &[("values", table)], &["values"]);
    assert!(rel < 1e-7, "fairness (table): {rel}");
    let reference = Value::Mesh(Arc::new(PolygonMesh::from(
        &QuadGrid::new(
            2,
            2,
            vec![
                DVec3::new(-1.0, -1.0, -0.5),
                DVec3::new(6.0, -1.0, -0.5),
                DVec3::new(-1.0, 5.0, -0.3),
                DVec3::new(6.0, 5.0, -0.3),
            ],
        )
        .unwrap(),
    )));
    let rel = compare(
        "measure.surface_distance",
        &[("mesh", grid()), ("reference", reference)],
        &["mesh"],
    );
    assert!(rel < 1e-6, "surface_distance: {rel}");
    // A curved reference of polygons, partly beside the mesh (the reference → mesh direction
    // meets the mesh's boundary), sampled 3 times per edge.
    let mut v = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (x, y) = (j as f64 * 1.7 - 0.8, i as f64 * 1.1 - 0.6);
            v.push(DVec3::new(x, y, 0.3 * (0.9 * x).sin() - 0.2 - 0.05 * y * y));
        }
    }
    let curved = Value::Mesh(Arc::new(PolygonMesh::from(
        &QuadGrid::new(4, 4, v).unwrap(),
    )));
    let rel = compare(
        "measure.surface_distance",
        &[
            ("mesh", grid()),
            ("reference", curved),
            ("samples", Value::Integer(3)),
        ],
        &["mesh"],
    );
    assert!(rel < 1e-6, "surface_distance (curved, 3 samples): {rel}");
}

fn plane(origin: [f64; 3], normal: [f64; 3]) -> Value {
    Value::Plane(Arc::new(
        Plane::from_normal(DVec3::from_array(origin), DVec3::from_array(normal)).unwrap(),
    ))
}

#[test]
fn mesh_operation_products_match_differences() {
    // A plane across the grid at a slant: kept vertices and edge crossings, either side.
    for flip in [false, true] {
        let rel = compare(
            "mesh.cut_by_plane",
            &[
                ("mesh", grid()),
                ("plane", plane([1.55, 0.0, 0.0], [1.0, 0.3, 0.1])),
                ("flip", Value::Boolean(flip)),
            ],
            &["mesh"],
        );
        assert!(rel < 1e-7, "cut_by_plane (flip {flip}): {rel}");
    }
    // Row 0 lies 0.01 from the plane: welded (projected), the rest reflected.
    let rel = compare(
        "mesh.mirror",
        &[
            ("mesh", grid()),
            ("plane", plane([0.0, -0.01, 0.0], [0.0, 1.0, 0.0])),
            ("tolerance", Value::Number(0.05)),
        ],
        &["mesh"],
    );
    assert!(rel < 1e-7, "mirror: {rel}");
    let rel = compare(
        "mesh.mirror",
        &[
            ("mesh", grid()),
            ("plane", plane([-0.5, 0.0, 0.0], [1.0, 0.2, 0.3])),
        ],
        &["mesh"],
    );
    assert!(rel < 1e-7, "mirror (slanted): {rel}");
    let other = {
        let Value::QuadMesh(g) = grid() else {
            unreachable!()
        };
        let mut g = (*g).clone();
        g.vertices
            .iter_mut()
            .for_each(|p| *p += DVec3::new(0.3, 5.0, 0.2));
        Value::QuadMesh(Arc::new(g))
    };
    let rel = compare(
        "mesh.join",
        &[("meshes", Value::list(vec![grid(), other]))],
        &["meshes"],
    );
    assert!(rel < 1e-7, "join: {rel}");
    let transform = [
        ("translation", Value::Vector(DVec3::new(0.5, -1.0, 2.0))),
        ("angle", Value::Number(37.0)),
        ("axis", Value::Vector(DVec3::new(0.2, 0.3, 1.0))),
        ("centre", Value::Point(DVec3::new(1.0, 0.5, 0.0))),
        ("scale", Value::Number(1.3)),
        ("mirror", plane([0.2, 0.0, 0.1], [0.3, 1.0, 0.2])),
    ];
    let mut named = vec![("mesh", grid())];
    named.extend(transform.iter().cloned());
    let rel = compare("mesh.transform", &named, &["mesh", "translation"]);
    assert!(rel < 1e-7, "mesh.transform: {rel}");
    let mut named = vec![(
        "curve",
        Value::Polyline(Arc::new(Polyline::open(vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.2, 0.3),
            DVec3::new(2.0, -0.5, 0.1),
        ]))),
    )];
    named.extend(transform.iter().cloned());
    let rel = compare("curve.transform", &named, &["curve", "translation"]);
    assert!(rel < 1e-7, "curve.transform: {rel}");
}

#[test]
fn a_cut_reports_its_piece_and_a_vertex_changing_side_changes_it() {
    let cut = def("mesh.cut_by_plane");
    let branch = cut.branch.clone().expect("the cut has a branch function");
    let run = |x: f64| {
        let ins = inputs(
            &cut,
            &[
                ("mesh", grid()),
                ("plane", plane([x, 0.0, 0.0], [1.0, 0.0, 0.0])),
            ],
        );
        let Value::QuadMesh(g) = &ins[0] else {
            unreachable!()
        };
        let ins = [
            vec![Value::Mesh(Arc::new(PolygonMesh::from(&**g)))],
            ins[1..].to_vec(),
        ]
        .concat();
        branch(&ins, &[]).unwrap()
    };
    let (a, b, c) = (run(1.5), run(1.6), run(2.5));
    assert_eq!(a.key, b.key, "{} / {}", a.summary, b.summary);
    assert_ne!(a.key, c.key, "{} / {}", a.summary, c.summary);
    assert_eq!(a.summary, "vertices kept: 12 of 20, edges cut: 4");
    let mirror = def("mesh.mirror")
        .branch
        .expect("the mirror has a branch function");
    let m = |y: f64| {
        let Value::QuadMesh(g) = grid() else {
            unreachable!()
        };
        mirror(
            &[
                Value::Mesh(Arc::new(PolygonMesh::from(&*g))),
                plane([0.0, y, 0.0], [0.0, 1.0, 0.0]),
                Value::Number(0.05),
            ],
            &[],
        )
        .unwrap()
    };
    assert_eq!(m(-0.01).summary, "vertices welded on the plane: 5 of 20");
    assert_ne!(m(-0.01).key, m(-0.1).key);
}

fn curve(ps: &[[f64; 3]], closed: bool) -> Value {
    let points: Vec<DVec3> = ps.iter().map(|p| DVec3::from_array(*p)).collect();
    Value::Polyline(Arc::new(if closed {
        Polyline::closed(points)
    } else {
        Polyline::open(points)
    }))
}

/// Irregular control points in space, no two consecutive ones close.
const WIGGLE: [[f64; 3]; 6] = [
    [0.0, 0.1, 0.0],
    [1.1, 0.7, 0.2],
    [2.3, -0.4, 0.5],
    [3.0, 0.9, -0.3],
    [4.4, 0.2, 0.1],
    [5.1, 1.3, 0.6],
];

#[test]
fn curve_construction_products_match_differences() {
    let rel = compare("curve.polyline", &[("points", pts(&WIGGLE))], &["points"]);
    assert!(rel < 1e-8, "polyline (open): {rel}");
    let rel = compare(
        "curve.polyline",
        &[("points", pts(&WIGGLE)), ("closed", Value::Boolean(true))],
        &["points"],
    );
    assert!(rel < 1e-8, "polyline (closed): {rel}");
    // Closed, the last point repeating the first: dropped, so its cotangent is zero (finite
    // differences cannot see this piece: moving the repeat keeps it).
    let mut looped = WIGGLE.to_vec();
    looped.push(WIGGLE[0]);
    let d = def("curve.polyline");
    let ins = inputs(
        &d,
        &[("points", pts(&looped)), ("closed", Value::Boolean(true))],
    );
    let ctx = NodeContext::default();
    let outs = evaluate_node(&d, &ctx, &ins).unwrap().values;
    let cot: Vec<f64> = (0..18).map(|k| k as f64 * 0.5 - 3.0).collect();
    let g = node_vjp(
        &d,
        &ctx,
        &ins,
        &outs,
        &[Some(cot.clone())],
        &[Wanted::All, Wanted::No],
    )
    .unwrap();
    assert!(g.finite_differences.is_none());
    let mut expected = cot;
    expected.extend([0.0; 3]);
    assert_eq!(g.inputs[0].as_deref(), Some(&expected[..]));
    let polyline = def("curve.polyline");
    let piece = polyline
        .branch
        .clone()
        .expect("the polyline has a branch function");
    let dropped = piece(
        &inputs(
            &polyline,
            &[("points", pts(&looped)), ("closed", Value::Boolean(true))],
        ),
        &[],
    )
    .unwrap();
    let kept = piece(
        &inputs(
            &polyline,
            &[("points", pts(&WIGGLE)), ("closed", Value::Boolean(true))],
        ),
        &[],
    )
    .unwrap();
    assert_ne!(
        dropped.key, kept.key,
        "{} / {}",
        dropped.summary, kept.summary
    );
}

#[test]
fn curve_transform_products_match_differences_in_every_parameter() {
    let all = ["curve", "translation", "angle", "axis", "centre", "scale"];
    for (closed, mirror) in [(false, true), (true, false)] {
        let mut named = vec![
            ("curve", curve(&WIGGLE[..4], closed)),
            ("translation", Value::Vector(DVec3::new(0.5, -1.0, 2.0))),
            ("angle", Value::Number(37.0)),
            ("axis", Value::Vector(DVec3::new(0.2, 0.3, 1.0))),
            ("centre", Value::Point(DVec3::new(1.0, 0.5, -0.2))),
            ("scale", Value::Number(1.3)),
        ];
        if mirror {
            named.push(("mirror", plane([0.2, 0.0, 0.1], [0.3, 1.0, 0.2])));
        }
        let rel = compare("curve.transform", &named, &all);
        assert!(rel < 1e-7, "curve.transform (mirror {mirror}): {rel}");
    }
    // At angle 0 the rotation's derivative in the angle is k̂ × v; the axis has none.
    let rel = compare(
        "curve.transform",
        &[
            ("curve", curve(&WIGGLE, false)),
            ("axis", Value::Vector(DVec3::new(0.5, -0.3, 0.8))),
            ("centre", Value::Point(DVec3::new(1.0, 0.5, -0.2))),
            ("scale", Value::Number(-0.7)),
        ],
        &all,
    );
    assert!(rel < 1e-7, "curve.transform (angle 0): {rel}");
}

#[test]
fn resample_products_match_differences() {
    for closed in [false, true] {
        for (count, length) in [
            (Value::Integer(13), Value::Null),
            (Value::Integer(16), Value::Number(0.61)),
        ] {
            let rel = compare(
                "curve.resample",
                &[
                    ("curve", curve(&WIGGLE, closed)),
                    ("count", count.clone()),
                    ("length", length.clone()),
                ],
                &["curve"],
            );
            assert!(rel < 1e-6, "resample (closed {closed}, {length:?}): {rel}");
        }
        // Counts whose equal division exists on this curve.
        let counts: &[i64] = if closed { &[6, 9, 18] } else { &[2, 3, 7, 12] };
        for &count in counts {
            let rel = compare(
                "curve.resample",
                &[
                    ("curve", curve(&WIGGLE, closed)),
                    ("count", Value::Integer(count)),
                    ("chords", Value::Boolean(true)),
                ],
                &["curve"],
            );
            assert!(
                rel < 1e-6,
                "resample in chords (closed {closed}, {count}): {rel}"
            );
        }
    }
}

#[test]
fn resample_reports_the_segments_its_points_fall_on() {
    let resample = def("curve.resample");
    let branch = resample
        .branch
        .clone()
        .expect("resample has a branch function");
    let piece = |last: f64, chords: bool| {
        let mut ps = WIGGLE;
        ps[5][0] = last;
        branch(
            &inputs(
                &resample,
                &[
                    ("curve", curve(&ps, false)),
                    ("count", Value::Integer(9)),
                    ("chords", Value::Boolean(chords)),
                ],
            ),
            &[],
        )
        .unwrap()
    };
    for chords in [false, true] {
        let (a, b, c) = (
            piece(5.1, chords),
            piece(5.1 + 1e-7, chords),
            piece(12.0, chords),
        );
        assert_eq!(a.key, b.key, "{} / {}", a.summary, b.summary);
        assert_ne!(a.key, c.key, "{} / {}", a.summary, c.summary);
    }
    // A list of curves is mapped: one piece for the runs.
    let both = branch(
        &inputs(
            &resample,
            &[(
                "curve",
                Value::list(vec![curve(&WIGGLE, false), curve(&WIGGLE, true)]),
            )],
        ),
        &[],
    )
    .unwrap();
    assert!(both.summary.starts_with("2 runs"), "{}", both.summary);
}

#[test]
fn spline_products_match_differences() {
    for method in ["catmull-rom", "natural"] {
        for closed in [false, true] {
            for count in [17, 40] {
                let rel = compare(
                    "curve.spline",
                    &[
                        ("points", pts(&WIGGLE)),
                        ("closed", Value::Boolean(closed)),
                        ("count", Value::Integer(count)),
                        ("method", Value::text(method)),
                    ],
                    &["points"],
                );
                assert!(
                    rel < 1e-6,
                    "spline ({method}, closed {closed}, {count}): {rel}"
                );
            }
        }
        // The fewest control points.
        let rel = compare(
            "curve.spline",
            &[
                ("points", pts(&WIGGLE[..2])),
                ("count", Value::Integer(9)),
                ("method", Value::text(method)),
            ],
            &["points"],
        );
        assert!(rel < 1e-6, "spline ({method}, 2 points): {rel}");
        let rel = compare(
            "curve.spline",
            &[
                ("points", pts(&WIGGLE[1..4])),
                ("closed", Value::Boolean(true)),
                ("count", Value::Integer(10)),
                ("method", Value::text(method)),
            ],
            &["points"],
        );
        assert!(rel < 1e-6, "spline ({method}, closed, 3 points): {rel}");
    }
}

#[test]
fn a_spline_reports_the_table_intervals_of_its_samples() {
    let spline = def("curve.spline");
    let branch = spline
        .branch
        .clone()
        .expect("the spline has a branch function");
    let piece = |x: f64| {
        let mut ps = WIGGLE;
        ps[2][0] = x;
        branch(
            &inputs(
                &spline,
                &[("points", pts(&ps)), ("count", Value::Integer(12))],
            ),
            &[],
        )
        .unwrap()
    };
    let (a, b, c) = (piece(2.3), piece(2.3 + 1e-8), piece(4.0));
    assert_eq!(a.key, b.key, "{} / {}", a.summary, b.summary);
    assert_ne!(a.key, c.key, "{} / {}", a.summary, c.summary);
}

#[test]
fn graph_to_apex_products_match_differences() {
    let widths = crate::testing::nums(&[1.2, 0.9, 1.4, 1.1, 0.7, 1.0]);
    let rel = compare(
        "cnets.graph_to_apex",
        &[("widths", widths.clone())],
        &["widths"],
    );
    assert!(rel < 1e-7, "graph_to_apex: {rel}");
    // Normalized on an open directrix with the default scale (length / 5).
    let rel = compare(
        "cnets.graph_to_apex",
        &[
            ("widths", widths.clone()),
            ("normalized", Value::Boolean(true)),
            ("directrix", curve(&WIGGLE, false)),
        ],
        &["widths", "directrix"],
    );
    assert!(rel < 1e-7, "graph_to_apex (normalized): {rel}");
    // Normalized on a closed directrix (its closing edge counts) with a given scale: 5 points,
    // 6 swept.
    let rel = compare(
        "cnets.graph_to_apex",
        &[
            ("widths", widths),
            ("normalized", Value::Boolean(true)),
            ("directrix", curve(&WIGGLE[..5], true)),
            ("scale", Value::Number(0.8)),
        ],
        &["widths", "directrix", "scale"],
    );
    assert!(
        rel < 1e-7,
        "graph_to_apex (normalized, closed, scale): {rel}"
    );
}

#[test]
fn subdivide_rows_products_match_differences() {
    for count in [1, 3] {
        let rel = compare(
            "cnets.subdivide_rows",
            &[("mesh", grid()), ("count", Value::Integer(count))],
            &["mesh"],
        );
        assert!(rel < 1e-6, "subdivide_rows ({count}): {rel}");
    }
    // Far from planar faces: the plane of the projection (normal to the face's diagonals) turns
    // with the points, a first-order effect here (second order in the small twist of `grid`).
    let mut v = Vec::new();
    for i in 0..3 {
        for j in 0..4 {
            let (x, y) = (j as f64 * 1.1, i as f64 * 0.9);
            v.push(DVec3::new(
                x + 0.2 * (y * 1.3).sin(),
                y + 0.15 * (x * 2.1).cos(),
                0.4 * (1.7 * x + 2.3 * y).sin(),
            ));
        }
    }
    let twisted = Value::QuadMesh(Arc::new(QuadGrid::new(3, 4, v).unwrap()));
    let rel = compare(
        "cnets.subdivide_rows",
        &[("mesh", twisted), ("count", Value::Integer(4))],
        &["mesh"],
    );
    assert!(rel < 1e-6, "subdivide_rows (twisted faces): {rel}");
    // Wrapping rows: a ring of 5 rows around a cone-like surface.
    let mut v = Vec::new();
    for i in 0..5 {
        let a = i as f64 * std::f64::consts::TAU / 5.0 + 0.1 * (i * i) as f64;
        for j in 0..4 {
            let r = 1.0 + 0.3 * j as f64 + 0.05 * (i + j) as f64;
            v.push(DVec3::new(
                r * a.cos(),
                r * a.sin(),
                0.4 * j as f64 + 0.02 * i as f64,
            ));
        }
    }
    let ring = QuadGrid::new(5, 4, v).unwrap().with_wrap(true, false);
    let rel = compare(
        "cnets.subdivide_rows",
        &[
            ("mesh", Value::QuadMesh(Arc::new(ring))),
            ("count", Value::Integer(2)),
        ],
        &["mesh"],
    );
    assert!(rel < 1e-6, "subdivide_rows (wrapping rows): {rel}");
}

/// A polyline value for the construction's tests.
fn construction_curve(points: Vec<DVec3>, closed: bool) -> Value {
    Value::Polyline(Arc::new(if closed {
        Polyline::closed(points)
    } else {
        Polyline::open(points)
    }))
}

/// Asserts that `id`'s exact product gives every wanted input with numbers a cotangent (`compare`
/// only compares the inputs both sides give).
fn gives_every_wanted(id: &str, named: &[(&str, Value)], wanted: &[&str]) {
    let d = def(id);
    let ctx = NodeContext::default();
    let ins = inputs(&d, named);
    let outs = evaluate_node(&d, &ctx, &ins).unwrap().values;
    // The first output (the mesh of a construction) weighted.
    let cot: Vec<Option<Vec<f64>>> = (0..outs.len())
        .map(|o| (o == 0).then(|| vec![1.0; leaves::count(&outs[0])]))
        .collect();
    let want: Vec<Wanted> = d
        .inputs
        .iter()
        .map(|p| {
            if wanted.contains(&p.name.as_ref()) {
                Wanted::All
            } else {
                Wanted::No
            }
        })
        .collect();
    let g = node_vjp(&d, &ctx, &ins, &outs, &cot, &want).unwrap();
    assert!(g.finite_differences.is_none(), "{:?}", g.finite_differences);
    for (k, p) in d.inputs.iter().enumerate() {
        if wanted.contains(&p.name.as_ref()) && leaves::count(&ins[k]) > 0 {
            assert!(g.inputs[k].is_some(), "{id}: no cotangent for '{}'", p.name);
        }
    }
}

#[test]
fn construction_products_match_differences() {
    let arc = |closed: bool| {
        let step = if closed {
            std::f64::consts::PI / 3.0
        } else {
            0.4
        };
        let points = (0..6)
            .map(|k| {
                let t = k as f64 * step;
                DVec3::new(
                    3.0 * t.cos() + 0.05 * t,
                    3.0 * t.sin(),
                    0.4 * (2.0 * t).sin(),
                )
            })
            .collect();
        construction_curve(points, closed)
    };
    let generatrix = construction_curve(
        (0..4)
            .map(|k| DVec3::new(3.4 + 0.4 * k as f64, 0.1, 0.3 * k as f64 - 0.4))
            .collect(),
        false,
    );
    let n = Value::Number;
    // Ratios near the kink at ½ on either side (not at it), apex values away from 1 (an apex at
    // infinity has no point: the apices output would change its size under finite differences).
    let open_ratios = crate::testing::nums(&[0.47, 0.53, 0.4995, 0.5005, 0.6]);
    let open_apex = crate::testing::nums(&[0.9, 0.95, 1.08, 0.85, 1.05]);
    let everything = [
        "directrix",
        "generatrix",
        "apex",
        "ratios",
        "scale",
        "seam_apex",
    ];
    // A shared seam apex off the first edge's line (a turning directrix: a_1 the nearest value).
    let seam = Value::Point(DVec3::new(1.6, 9.5, 2.8));
    for (what, named) in [
        (
            "open, a shared seam apex",
            vec![
                ("directrix", arc(false)),
                ("apex", open_apex.clone()),
                ("ratios", open_ratios.clone()),
                ("seam_apex", seam.clone()),
            ],
        ),
        (
            "open, normalized, one apex value, a shared seam apex",
            vec![
                ("directrix", arc(false)),
                ("apex", n(0.93)),
                ("ratios", open_ratios.clone()),
                ("normalized", Value::Boolean(true)),
                ("seam_apex", seam.clone()),
            ],
        ),
        (
            "open",
            vec![
                ("directrix", arc(false)),
                ("apex", open_apex.clone()),
                ("ratios", open_ratios.clone()),
            ],
        ),
        (
            "open, mirror end planes, one apex value",
            vec![
                ("directrix", arc(false)),
                ("apex", n(0.93)),
                ("ratios", open_ratios.clone()),
                ("end_planes", Value::Text("mirror".into())),
            ],
        ),
        (
            "open, normalized, scale given",
            vec![
                ("directrix", arc(false)),
                ("apex", open_apex.clone()),
                ("ratios", open_ratios.clone()),
                ("normalized", Value::Boolean(true)),
                ("scale", n(1.7)),
            ],
        ),
        (
            "closed, normalized, default scale",
            vec![
                ("directrix", arc(true)),
                (
                    "apex",
                    crate::testing::nums(&[0.9, 0.95, 1.08, 0.85, 1.05, 0.97]),
                ),
                (
                    "ratios",
                    crate::testing::nums(&[0.47, 0.53, 0.4995, 0.5005, 0.6, 0.45]),
                ),
                ("normalized", Value::Boolean(true)),
            ],
        ),
    ] {
        let mut named = named;
        named.push(("generatrix", generatrix.clone()));
        let rel = compare("cnets.construct", &named, &everything);
        gives_every_wanted("cnets.construct", &named, &everything);
        assert!(rel < 1e-6, "cnets.construct ({what}): {rel}");
    }
    // Planes only (α = 0) turns the planes of column 2 (a ruling leaning back): the product
    // follows the plane fixes, ε included.
    let straight = construction_curve(
        (0..6)
            .map(|j| DVec3::new(j as f64, 0.05 * (j as f64).sin(), 0.03 * (j * j) as f64))
            .collect(),
        false,
    );
    let short = construction_curve(
        vec![
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 1.5, 0.5),
            DVec3::new(0.0, 2.0, 0.2),
        ],
        false,
    );
    let named = [
        ("directrix", straight),
        ("generatrix", short),
        (
            "apex",
            crate::testing::nums(&[0.98, 0.97, 1.02, 0.99, 1.01]),
        ),
        ("ratios", crate::testing::nums(&[0.5, 0.9, 0.45, 0.55, 0.5])),
        ("assistance", n(0.0)),
    ];
    let d = def("cnets.construct");
    let outs = evaluate_node(&d, &NodeContext::default(), &inputs(&d, &named))
        .unwrap()
        .values;
    assert!(
        matches!(&outs[5], Value::List(c) if !c.is_empty()),
        "the correction turned planes: {:?}",
        outs[5]
    );
    let wanted = ["directrix", "generatrix", "apex", "ratios", "epsilon"];
    let rel = compare("cnets.construct", &named, &wanted);
    assert!(rel < 1e-6, "cnets.construct (planes only): {rel}");
    gives_every_wanted("cnets.construct", &named, &wanted);
    // Apex only (α = 1) lowers a_1: the product follows the apex fix.
    let mut named = named.to_vec();
    named[4] = ("assistance", n(1.0));
    let outs = evaluate_node(&d, &NodeContext::default(), &inputs(&d, &named))
        .unwrap()
        .values;
    assert!(
        matches!(&outs[5], Value::List(c) if !c.is_empty()),
        "the correction changed the apex function: {:?}",
        outs[5]
    );
    let rel = compare("cnets.construct", &named, &wanted);
    assert!(rel < 1e-6, "cnets.construct (apex only): {rel}");
    gives_every_wanted("cnets.construct", &named, &wanted);
    // A blend (α = 0.5) moves a_1 half way to apex only's and turns planes on top: the product
    // follows both sweeps (no finite differences).
    named[4] = ("assistance", n(0.5));
    let outs = evaluate_node(&d, &NodeContext::default(), &inputs(&d, &named))
        .unwrap()
        .values;
    let lines = match &outs[5] {
        Value::List(c) => c
            .iter()
            .filter_map(|v| match v {
                Value::Text(t) => Some(t.to_string()),
                _ => None,
            })
            .collect::<Vec<_>>(),
        other => panic!("corrections: {other:?}"),
    };
    assert!(
        lines.iter().any(|l| l.starts_with("apex fix"))
            && lines.iter().any(|l| l.starts_with("plane fix")),
        "the blend changed the apex function and turned planes: {lines:?}"
    );
    let rel = compare("cnets.construct", &named, &wanted);
    println!("cnets.construct (blend, α = 0.5): {rel:.2e}");
    assert!(rel < 1e-6, "cnets.construct (blend): {rel}");
    gives_every_wanted("cnets.construct", &named, &wanted);
}

/// The vector value of `v`.
fn vector(v: DVec3) -> Value {
    Value::Vector(v)
}

#[test]
fn ctube_products_match_differences() {
    let arc = |closed: bool| {
        let step = if closed {
            std::f64::consts::PI / 3.0
        } else {
            0.4
        };
        let points = (0..6)
            .map(|k| {
                let t = k as f64 * step;
                DVec3::new(
                    3.0 * t.cos() + 0.05 * t,
                    3.0 * t.sin(),
                    0.4 * (2.0 * t).sin(),
                )
            })
            .collect();
        construction_curve(points, closed)
    };
    let generatrix = construction_curve(
        (0..4)
            .map(|k| DVec3::new(3.4 + 0.4 * k as f64, 0.1, 0.3 * k as f64 - 0.4))
            .collect(),
        false,
    );
    let n = Value::Number;
    // Normals near the Monge planes of the arc (the edge direction turned a little), some
    // pointing backwards (the construction flips them) and of various lengths.
    let normal = |k: usize, i: usize, columns: usize| {
        let t = (k as f64 + 0.5)
            * if columns == 6 {
                std::f64::consts::PI / 3.0
            } else {
                0.4
            };
        let along = DVec3::new(-t.sin(), t.cos(), 0.1 * (k as f64 - 2.0));
        let tilt = DVec3::new(0.1 * (i as f64 + 1.0), -0.05 * k as f64, 0.15);
        let sign = if (k + i) % 3 == 1 { -1.0 } else { 1.0 };
        (along + tilt) * sign * (1.0 + 0.3 * k as f64)
    };
    let shared = |columns: usize| {
        Value::list(
            (0..columns)
                .map(|k| vector(normal(k, 0, columns)))
                .collect(),
        )
    };
    let table = |columns: usize| {
        Value::list(
            (0..4)
                .map(|i| {
                    Value::list(
                        (0..columns)
                            .map(|k| vector(normal(k, i, columns)))
                            .collect(),
                    )
                })
                .collect(),
        )
    };
    let open_apex = crate::testing::nums(&[0.9, 0.95, 1.08, 0.85, 1.05]);
    let everything = ["directrix", "generatrix", "apex", "normals", "scale"];
    for (what, named) in [
        (
            "open, shared normals",
            vec![
                ("directrix", arc(false)),
                ("apex", open_apex.clone()),
                ("normals", shared(5)),
            ],
        ),
        (
            "open, normals per vertex, mirror end planes",
            vec![
                ("directrix", arc(false)),
                ("apex", open_apex.clone()),
                ("normals", table(5)),
                ("end_planes", Value::Text("mirror".into())),
            ],
        ),
        (
            "open, Monge planes, normalized, scale given",
            vec![
                ("directrix", arc(false)),
                ("apex", open_apex.clone()),
                ("normalized", Value::Boolean(true)),
                ("scale", n(1.7)),
            ],
        ),
        (
            "closed, normals per vertex, one apex value",
            vec![
                ("directrix", arc(true)),
                ("apex", n(0.93)),
                ("normals", table(6)),
            ],
        ),
        (
            "closed, shared normals, normalized",
            vec![
                ("directrix", arc(true)),
                (
                    "apex",
                    crate::testing::nums(&[0.9, 0.95, 1.08, 0.85, 1.05, 0.97]),
                ),
                ("normals", shared(6)),
                ("normalized", Value::Boolean(true)),
            ],
        ),
    ] {
        let mut named = named;
        named.push(("generatrix", generatrix.clone()));
        let rel = compare("ctube.construct", &named, &everything);
        println!("ctube.construct ({what}): {rel:.2e}");
        gives_every_wanted("ctube.construct", &named, &everything);
        assert!(rel < 1e-6, "ctube.construct ({what}): {rel}");
        // Each input alone.
        for one in everything {
            if named.iter().any(|(k, _)| *k == one)
                || ["directrix", "generatrix", "apex"].contains(&one)
            {
                let rel = compare("ctube.construct", &named, &[one]);
                assert!(rel < 1e-6, "ctube.construct ({what}, {one} alone): {rel}");
            }
        }
    }
}

#[test]
fn coplanar_products_match_differences() {
    let arc = |closed: bool| {
        let step = if closed {
            std::f64::consts::PI / 3.0
        } else {
            0.4
        };
        let points = (0..6)
            .map(|k| {
                let t = k as f64 * step;
                DVec3::new(
                    3.0 * t.cos() + 0.05 * t,
                    3.0 * t.sin(),
                    0.4 * (2.0 * t).sin(),
                )
            })
            .collect();
        construction_curve(points, closed)
    };
    let generatrix = construction_curve(
        (0..4)
            .map(|k| DVec3::new(3.4 + 0.4 * k as f64, 0.1, 0.3 * k as f64 - 0.4))
            .collect(),
        false,
    );
    let n = Value::Number;
    let nums = crate::testing::nums;
    let everything = [
        "directrix",
        "generatrix",
        "apex",
        "ruling_ratios",
        "plane_ratios",
        "scale",
    ];
    for (what, named) in [
        (
            "open, ratios per column",
            vec![
                ("directrix", arc(false)),
                ("apex", nums(&[0.9, 0.95, 1.08, 0.85, 1.05])),
                ("ruling_ratios", nums(&[0.47, 0.53, 0.4995, 0.5005, 0.6])),
                ("plane_ratios", nums(&[0.5, 0.45, 0.55, 0.6, 0.4])),
            ],
        ),
        (
            "open, mirror end planes, one value each",
            vec![
                ("directrix", arc(false)),
                ("apex", n(0.93)),
                ("ruling_ratios", n(0.46)),
                ("plane_ratios", n(0.52)),
                ("end_planes", Value::Text("mirror".into())),
            ],
        ),
        (
            "open, normalized, scale given, correction on (nothing to correct)",
            vec![
                ("directrix", arc(false)),
                ("apex", nums(&[0.9, 0.95, 1.08, 0.85, 1.05])),
                ("ruling_ratios", nums(&[0.55, 0.48, 0.52, 0.45, 0.51])),
                ("normalized", Value::Boolean(true)),
                ("scale", n(1.7)),
                ("assistance", n(0.0)),
            ],
        ),
        (
            "closed, normalized",
            vec![
                ("directrix", arc(true)),
                ("apex", nums(&[0.9, 0.95, 1.08, 0.85, 1.05, 0.97])),
                (
                    "ruling_ratios",
                    nums(&[0.47, 0.53, 0.4995, 0.5005, 0.6, 0.45]),
                ),
                ("plane_ratios", nums(&[0.5, 0.45, 0.55, 0.6, 0.4, 0.48])),
                ("normalized", Value::Boolean(true)),
            ],
        ),
    ] {
        let mut named = named;
        named.push(("generatrix", generatrix.clone()));
        let d = def("cnets.construct_coplanar");
        let outs = evaluate_node(&d, &NodeContext::default(), &inputs(&d, &named))
            .unwrap()
            .values;
        assert!(
            matches!(&outs[5], Value::List(c) if c.is_empty()),
            "{what}: nothing corrected: {:?}",
            outs[5]
        );
        let rel = compare("cnets.construct_coplanar", &named, &everything);
        println!("cnets.construct_coplanar ({what}): {rel:.2e}");
        gives_every_wanted("cnets.construct_coplanar", &named, &everything);
        assert!(rel < 1e-6, "cnets.construct_coplanar ({what}): {rel}");
        // Each input alone (the scale only when given: else it has no numbers).
        for one in everything {
            if one == "scale" && !named.iter().any(|(k, _)| *k == one) {
                continue;
            }
            let rel = compare("cnets.construct_coplanar", &named, &[one]);
            assert!(
                rel < 1e-6,
                "cnets.construct_coplanar ({what}, {one} alone): {rel}"
            );
        }
    }
}

#[test]
fn area_product_matches_differences() {
    let d = def("measure.area");
    // The area itself: a unit square and a planar pentagon (shoelace area 4) in a tilted
    // plane (orthonormal axes u, v keep areas), their sum the total.
    let (u, v) = (
        DVec3::new(1.0, 2.0, 2.0) / 3.0,
        DVec3::new(2.0, 1.0, -2.0) / 3.0,
    );
    let pentagon = [[0.0, 0.0], [2.0, 0.0], [2.5, 1.0], [1.0, 2.0], [-0.5, 1.0]]
        .map(|[x, y]| DVec3::new(3.0, -1.0, 2.0) + u * x + v * y);
    let mut vertices = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    vertices.extend(pentagon);
    let mesh = PolygonMesh::from_faces(vertices, &[vec![0, 1, 2, 3], vec![4, 5, 6, 7, 8]]).unwrap();
    let out =
        crate::testing::run_named(&d, &[("mesh", Value::Mesh(Arc::new(mesh.clone())))]).unwrap();
    let faces: Vec<f64> = out[1]
        .as_list()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!((faces[0] - 1.0).abs() < 1e-14, "{faces:?}");
    assert!((faces[1] - 4.0).abs() < 1e-13, "{faces:?}");
    assert!((out[0].as_f64().unwrap() - 5.0).abs() < 1e-13, "{out:?}");
    // A quad grid converts: its faces' areas sum to the total.
    let out = crate::testing::run_named(&d, &[("mesh", grid())]).unwrap();
    let faces = out[1].as_list().unwrap();
    assert_eq!(faces.len(), 3 * 4);
    let sum: f64 = faces.iter().map(|v| v.as_f64().unwrap()).sum();
    assert!((sum - out[0].as_f64().unwrap()).abs() < 1e-12);
    // The product against differences: a non-planar quad grid (both outputs weighted), polygons
    // of 3 to 5 corners, and a wrapping grid (its faces share vertices across the seam).
    let rel = compare("measure.area", &[("mesh", grid())], &["mesh"]);
    assert!(rel < 1e-7, "measure.area (grid): {rel}");
    let mut bumpy = mesh;
    for (k, v) in bumpy.vertices.iter_mut().enumerate() {
        v.z += 0.3 * (k as f64 * 1.7).sin();
    }
    let bumpy = PolygonMesh::from_faces(
        bumpy.vertices.clone(),
        &[vec![0, 1, 2, 3], vec![4, 5, 6, 7, 8], vec![1, 4, 2]],
    )
    .unwrap();
    let rel = compare(
        "measure.area",
        &[("mesh", Value::Mesh(Arc::new(bumpy)))],
        &["mesh"],
    );
    assert!(rel < 1e-7, "measure.area (polygons): {rel}");
    let mut v = Vec::new();
    for i in 0..5 {
        let t = i as f64 / 5.0 * std::f64::consts::TAU;
        for j in 0..4 {
            let r = 1.0 + 0.2 * j as f64;
            v.push(DVec3::new(
                r * t.cos(),
                r * t.sin(),
                0.7 * j as f64 + 0.1 * t.sin(),
            ));
        }
    }
    let ring = QuadGrid::new(5, 4, v).unwrap().with_wrap(true, false);
    let rel = compare(
        "measure.area",
        &[("mesh", Value::QuadMesh(Arc::new(ring)))],
        &["mesh"],
    );
    assert!(rel < 1e-7, "measure.area (wrapping rows): {rel}");
}

fn mapper_handles(hs: &[(f64, f64)]) -> Value {
    Value::list(
        hs.iter()
            .map(|&(u, v)| Value::Point(DVec3::new(u, v, 0.0)))
            .collect(),
    )
}

/// Every mapper kind at handles that are not the defaults, mapping values on a stretched domain
/// (inside the handles, between them and held or extended beyond them, off every kink) and
/// sampling: the product in the handles (u and v), the domains and the values.
#[test]
fn mapper_products_match_differences_for_every_kind() {
    let n = Value::Number;
    let cases: Vec<(&str, Vec<(f64, f64)>)> = vec![
        ("linear", vec![(0.2, 0.1), (0.7, 0.9)]),
        (
            "bezier",
            vec![(0.1, 0.2), (0.3, 0.9), (0.6, 0.0), (0.9, 0.8)],
        ),
        ("parabola", vec![(0.4, 0.2), (0.9, 0.7)]),
        ("power", vec![(0.1, 0.1), (0.9, 0.8), (0.6, 0.2)]),
        ("sine", vec![(0.2, 0.9), (0.45, 0.1)]),
        ("gaussian", vec![(0.6, 0.8), (0.4, 0.3)]),
        ("sqrt", vec![(0.1, 0.3), (0.8, 0.6)]),
        (
            "conic",
            vec![(0.0, 0.0), (0.2, 0.8), (1.0, 1.0), (0.3, 0.6)],
        ),
        ("piecewise", vec![(0.7, 0.1), (0.1, 0.5), (0.4, 0.9)]),
        // Extrema at the interior knots (zero slopes).
        (
            "spline",
            vec![(0.0, 0.2), (0.3, 0.7), (0.5, 0.4), (1.0, 0.9)],
        ),
        // Monotone, given out of order: harmonic-mean slopes, the three-point ends.
        (
            "spline",
            vec![
                (0.6, 0.65),
                (0.0, 0.1),
                (0.25, 0.5),
                (1.0, 1.0),
                (0.8, 0.95),
            ],
        ),
        // A peak at the first interior knot: the start slope clamped to 3δ.
        (
            "spline",
            vec![(0.0, 0.0), (0.1, 0.9), (0.9, 0.1), (1.0, 0.15)],
        ),
    ];
    let us = [-0.1, 0.13, 0.37, 0.58, 0.66, 0.81, 1.2];
    let (x0, x1) = (-2.0, 6.0);
    let values = Value::list(us.iter().map(|u| n(x0 + u * (x1 - x0))).collect());
    for (kind, hs) in &cases {
        let named = [
            ("kind", Value::text(*kind)),
            ("handles", mapper_handles(hs)),
            ("x_start", n(x0)),
            ("x_end", n(x1)),
            ("y_start", n(10.0)),
            ("y_end", n(5.0)),
            ("values", values.clone()),
        ];
        let all = ["handles", "x_start", "x_end", "y_start", "y_end", "values"];
        let rel = compare("mapper.graph", &named, &all);
        assert!(rel < 1e-6, "mapper.graph {kind} (values): {rel}");
        // Each input alone (a wrong partial is not hidden by a large one elsewhere).
        for one in all {
            let rel = compare("mapper.graph", &named, &[one]);
            assert!(rel < 1e-6, "mapper.graph {kind} in {one}: {rel}");
        }
        // Samples at u = k/7: kinds with a handle there sit on a kink (held or not) and are
        // covered by the values above.
        if hs
            .iter()
            .any(|h| (h.0 * 7.0 - (h.0 * 7.0).round()).abs() < 0.05)
        {
            continue;
        }
        let sampled = [
            ("kind", Value::text(*kind)),
            ("handles", mapper_handles(hs)),
            ("x_start", n(x0)),
            ("x_end", n(x1)),
            ("y_start", n(-1.0)),
            ("y_end", n(2.5)),
            ("count", Value::Integer(8)),
        ];
        let rel = compare(
            "mapper.graph",
            &sampled,
            &["handles", "x_start", "x_end", "y_start", "y_end"],
        );
        assert!(rel < 1e-6, "mapper.graph {kind} (sampled): {rel}");
    }
}

/// Sampled at its knots (count 9 on handles at u = 0, ½, 1: samples fall exactly on them), a
/// spline with a peak or a trough at the middle handle: the product in the handles' v matches
/// differences. (0.46, 0.55, 0.52) would put the last end slope on its clamp at 3δ, a kink
/// where the node declines and is differentiated by differences. The end handles' u is left
/// out: a sample on the first knot is held (slope 0) when that knot moves right and on the
/// spline (slope −d₀) when it moves left, a true kink whose central difference is the mean.
#[test]
fn a_spline_sampled_on_its_knots_matches_differences() {
    let n = Value::Number;
    for hs in [
        [(0.0, 0.46), (0.5, 0.55), (1.0, 0.50)],
        [(0.0, 0.53), (0.5, 0.47), (1.0, 0.58)],
    ] {
        for count in [9, 20] {
            let named = [
                ("kind", Value::text("spline")),
                ("handles", mapper_handles(&hs)),
                ("x_start", n(0.0)),
                ("x_end", n(1.0)),
                ("y_start", n(0.0)),
                ("y_end", n(1.0)),
                ("count", Value::Integer(count)),
            ];
            // Leaves: (u, v, 0) per handle; every v and the middle u.
            let rel = compare_components("mapper.graph", &named, &["handles"], |k| {
                k % 3 == 1 || k == 3
            });
            assert!(rel < 1e-6, "{hs:?}, count {count}: {rel}");
        }
    }
}

/// The spline's piece is the limiter branch of every knot: moving a handle's v across a level
/// (an interior extremum appears) changes it; a small move on the same piece does not.
#[test]
fn mapper_spline_branches_are_the_limiter_branches() {
    let d = def("mapper.graph");
    let branch = d.branch.clone().expect("the mapper has a branch function");
    let piece = |v: f64| {
        let ins = inputs(
            &d,
            &[
                ("kind", Value::text("spline")),
                (
                    "handles",
                    mapper_handles(&[(0.0, 0.1), (0.3, v), (0.6, 0.6), (1.0, 0.9)]),
                ),
                ("count", Value::Integer(9)),
            ],
        );
        branch(&ins, &[]).unwrap()
    };
    let (a, b, c) = (piece(0.3), piece(0.31), piece(0.7));
    assert_eq!(a.key, b.key);
    assert_ne!(a.key, c.key, "{} / {}", a.summary, c.summary);
    assert!(c.summary.contains("zero"), "{}", c.summary);
    // Extending kinds have one piece.
    let ins = inputs(&d, &[("kind", Value::text("sine"))]);
    assert!(branch(&ins, &[]).is_none());
}

#[test]
fn table_products_match_differences() {
    let n = Value::Number;
    let list = |xs: &[f64]| Value::list(xs.iter().map(|&x| n(x)).collect());
    for rule in ["sum", "product", "mean"] {
        let named = [
            ("rows", list(&[0.3, -1.2, 0.8])),
            ("columns", list(&[1.5, 0.4, -0.7, 2.0])),
            ("rule", Value::text(rule)),
            ("centre", n(0.45)),
        ];
        let rel = compare("list.table", &named, &["rows", "columns", "centre"]);
        assert!(rel < 1e-8, "list.table {rule}: {rel}");
        for one in ["rows", "columns"] {
            let rel = compare("list.table", &named, &[one]);
            assert!(rel < 1e-8, "list.table {rule} in {one}: {rel}");
        }
    }
}
