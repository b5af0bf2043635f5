//! The construction nodes through the engine: output shapes (a contract), planarity, input forms,
//! errors that say what and where.

use std::sync::Arc;

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, NodeDef, Registry, Value};
use cnets_geometry::{DVec3, Polyline};

fn registry() -> Arc<Registry> {
    Arc::new(cnets_nodes::registry())
}

fn def(id: &str) -> Arc<NodeDef> {
    registry()
        .get(id)
        .unwrap_or_else(|| panic!("{id} registered"))
        .clone()
}

fn arc(radius: f64, count: usize, axis_xy: bool, centre: DVec3) -> Polyline {
    Polyline::open(
        (0..count)
            .map(|k| {
                let t = std::f64::consts::FRAC_PI_2 * k as f64 / (count - 1) as f64;
                if axis_xy {
                    centre + DVec3::new(radius * t.cos(), radius * t.sin(), 0.0)
                } else {
                    centre + DVec3::new(radius * t.cos(), 0.0, radius * t.sin())
                }
            })
            .collect(),
    )
}

/// Runs a node with named inputs (others default / empty).
fn run(id: &str, named: &[(&str, Value)]) -> Result<Vec<Value>, String> {
    let d = def(id);
    let inputs: Vec<Value> = d
        .inputs
        .iter()
        .map(|p| {
            named
                .iter()
                .find(|(n, _)| *n == p.name)
                .map(|(_, v)| v.clone())
                .or_else(|| p.default.clone())
                .unwrap_or(Value::Null)
        })
        .collect();
    evaluate_node(&d, &NodeContext::default(), &inputs)
        .map(|o| o.values)
        .map_err(|e| e.to_string())
}

fn output<'a>(id: &str, values: &'a [Value], name: &str) -> &'a Value {
    let k = def(id)
        .output_index(name)
        .unwrap_or_else(|| panic!("{id} has output {name}"));
    &values[k]
}

fn torus_inputs(n: usize, m: usize) -> Vec<(&'static str, Value)> {
    vec![
        ("directrix", Value::from(arc(10.0, m, true, DVec3::ZERO))),
        (
            "generatrix",
            Value::from(arc(2.0, n, false, DVec3::new(10.0, 0.0, 0.0))),
        ),
    ]
}

#[test]
fn construction_outputs_have_the_contract_shapes() {
    let (n, m) = (5, 7);
    for id in [
        "ctube.construct",
        "cnets.construct",
        "cnets.construct_coplanar",
    ] {
        let out = run(id, &torus_inputs(n, m)).unwrap();
        let Value::QuadMesh(mesh) = output(id, &out, "mesh") else {
            panic!("{id}: mesh")
        };
        assert_eq!((mesh.rows, mesh.cols), (n, m), "{id}");
        assert_eq!(
            output(id, &out, "apex").as_list().unwrap().len(),
            m - 1,
            "{id}"
        );
        assert_eq!(
            output(id, &out, "apices").as_list().unwrap().len(),
            m - 1,
            "{id}"
        );
        assert!(
            output(id, &out, "apices")
                .as_list()
                .unwrap()
                .iter()
                .all(Value::is_null),
            "a ≡ 1: apices at infinity"
        );
        let planes = output(id, &out, "planes").as_list().unwrap();
        assert_eq!(planes.len(), n);
        assert!(
            planes
                .iter()
                .all(|row| row.as_list().unwrap().len() == m - 1)
        );
        let configurations = output(id, &out, "configurations").as_list().unwrap();
        assert_eq!(configurations.len(), n);
        for row in configurations {
            let row = row.as_list().unwrap();
            assert_eq!(row.len(), m - 1);
            assert!(
                row.iter().all(|c| c == &Value::text("++")),
                "{id}: a torus segment is all (++)"
            );
        }
        assert_eq!(output(id, &out, "corrections"), &Value::list(vec![]));
        let Value::Record(q) = output(id, &out, "quality") else {
            panic!("quality")
        };
        let max = q.get("max_planarity").and_then(Value::as_f64).unwrap();
        assert!(max <= 1e-12, "{id}: planarity {max}");
        assert!(q.get("mean_planarity").is_some());
    }
}

#[test]
fn ratios_accept_a_number_a_row_or_a_table() {
    let (n, m) = (4, 6);
    let mut base = torus_inputs(n, m);
    let row = Value::list(
        (0..m - 1)
            .map(|j| Value::Number(0.4 + 0.02 * j as f64))
            .collect(),
    );
    let table = Value::list((0..n).map(|_| row.clone()).collect());
    base.push(("ratios", row.clone()));
    let by_row = run("cnets.construct", &base).unwrap();
    base.pop();
    base.push(("ratios", table));
    let by_table = run("cnets.construct", &base).unwrap();
    assert_eq!(
        output("cnets.construct", &by_row, "mesh"),
        output("cnets.construct", &by_table, "mesh")
    );

    base.pop();
    base.push(("ratios", Value::list(vec![Value::Number(0.5); 3])));
    let e = run("cnets.construct", &base).unwrap_err();
    assert!(e.contains("ratios") && e.contains("5"), "{e}");
}

#[test]
fn half_ratios_equal_the_default_planes() {
    let inputs = torus_inputs(4, 6);
    let ctube = run("ctube.construct", &inputs).unwrap();
    let cnets = run("cnets.construct", &inputs).unwrap();
    let (Value::QuadMesh(a), Value::QuadMesh(b)) = (&ctube[0], &cnets[0]) else {
        panic!()
    };
    let scale = a.size();
    let worst = a
        .vertices
        .iter()
        .zip(&b.vertices)
        .map(|(p, q)| p.distance(*q))
        .fold(0.0, f64::max);
    assert!(worst <= 1e-12 * scale, "{worst}");
}

#[test]
fn encode_then_construct_reproduces_the_mesh() {
    let mut inputs = torus_inputs(4, 6);
    inputs.push((
        "apex",
        Value::list(
            vec![0.9, 0.95, 1.0, 1.05, 0.97]
                .into_iter()
                .map(Value::Number)
                .collect(),
        ),
    ));
    let built = run("cnets.construct", &inputs).unwrap();
    let mesh = built[0].clone();
    let enc = run("cnets.encode", &[("mesh", mesh.clone())]).unwrap();
    let again = run(
        "ctube.construct",
        &[
            ("directrix", enc[0].clone()),
            ("generatrix", enc[1].clone()),
            ("apex", enc[2].clone()),
            ("normals", enc[3].clone()),
        ],
    )
    .unwrap();
    let (Value::QuadMesh(a), Value::QuadMesh(b)) = (&mesh, &again[0]) else {
        panic!()
    };
    let worst = a
        .vertices
        .iter()
        .zip(&b.vertices)
        .map(|(p, q)| p.distance(*q))
        .fold(0.0, f64::max);
    assert!(worst <= 1e-9 * a.size(), "{worst}");
}

#[test]
fn bad_inputs_are_node_errors_not_panics_or_nans() {
    let mut nan = torus_inputs(3, 4);
    nan.push(("apex", Value::Number(f64::NAN)));
    let e = run("cnets.construct", &nan).unwrap_err();
    assert!(e.contains("apex") && !e.contains("panicked"), "{e}");

    let short = vec![
        ("directrix", Value::from(Polyline::open(vec![DVec3::ZERO]))),
        ("generatrix", Value::from(arc(1.0, 3, false, DVec3::X))),
    ];
    let e = run("cnets.construct", &short).unwrap_err();
    assert!(e.contains("directrix") && e.contains("2"), "{e}");

    let dup = vec![
        (
            "directrix",
            Value::from(Polyline::open(vec![DVec3::ZERO, DVec3::ZERO, DVec3::X])),
        ),
        ("generatrix", Value::from(arc(1.0, 3, false, DVec3::X))),
    ];
    let e = run("ctube.construct", &dup).unwrap_err();
    assert!(e.contains("zero-length"), "{e}");

    let mut bad_ratio = torus_inputs(3, 4);
    bad_ratio.push(("ratios", Value::text("half")));
    assert!(
        run("cnets.construct", &bad_ratio)
            .unwrap_err()
            .contains("ratios")
    );
}

#[test]
fn apex_lists_map_to_several_cone_nets() {
    // A list access port fed a list of lists runs the node once per inner list.
    let mut inputs = torus_inputs(3, 4);
    let a = |x: f64| Value::list(vec![Value::Number(x); 3]);
    inputs.push(("apex", Value::list(vec![a(1.0), a(0.9)])));
    let out = run("cnets.construct", &inputs).unwrap();
    assert_eq!(out[0].as_list().map(<[Value]>::len), Some(2));
}

#[test]
fn planarity_node_reports_per_face_values() {
    let built = run("cnets.construct", &torus_inputs(4, 5)).unwrap();
    let out = run("mesh.planarity", &[("mesh", built[0].clone())]).unwrap();
    assert_eq!(out[2].as_list().unwrap().len(), 3 * 4);
    assert!(out[0].as_f64().unwrap() <= 1e-12);
}

/// The `planes` and `configurations` outputs (packed rows of the construction's own tables) read
/// as exactly the kernel's normals and labels, row by row: per-vertex normals with a (−−)
/// configuration (ratios), and normals shared by all rows (Monge planes).
#[test]
fn planes_and_configurations_read_as_the_kernel_result() {
    use cnets_geometry::conenet::{ConstructInputs, CtubeInputs, construct, construct_ctube};
    let directrix = Polyline::open((0..6).map(|j| DVec3::new(j as f64, 0.0, 0.0)).collect());
    let generatrix = Polyline::open(vec![
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 1.5, 0.5),
        DVec3::new(0.0, 2.0, 0.2),
    ]);
    let ratios = vec![0.5, 0.9, 0.5, 0.5, 0.5];
    let ratio_net = construct(
        &ConstructInputs::new(directrix.clone(), generatrix.clone()).ratios(ratios.clone()),
    )
    .unwrap();
    let monge_net =
        construct_ctube(&CtubeInputs::new(directrix.clone(), generatrix.clone())).unwrap();
    let named = |extra: Option<(&'static str, Value)>| {
        let mut v = vec![
            ("directrix", Value::from(directrix.clone())),
            ("generatrix", Value::from(generatrix.clone())),
        ];
        v.extend(extra);
        v
    };
    let ratio_list = Value::list(ratios.iter().map(|&r| Value::Number(r)).collect());
    for (id, net, inputs) in [
        (
            "cnets.construct",
            &ratio_net,
            named(Some(("ratios", ratio_list))),
        ),
        ("ctube.construct", &monge_net, named(None)),
    ] {
        let out = run(id, &inputs).unwrap();
        let planes = value_table(net.normals.to_rows(), Value::Vector);
        assert_eq!(output(id, &out, "planes"), &planes, "{id}");
        let labels = value_table(net.configurations.to_strings(), Value::text);
        assert_eq!(output(id, &out, "configurations"), &labels, "{id}");
    }
    assert!(
        ratio_net.configurations.counts().minus_minus > 0,
        "the ratio case has a (−−) label"
    );
}

/// A list of lists of values, one per entry of `rows`.
fn value_table<T>(rows: Vec<Vec<T>>, item: impl Fn(T) -> Value + Copy) -> Value {
    Value::list(
        rows.into_iter()
            .map(|row| Value::list(row.into_iter().map(item).collect()))
            .collect(),
    )
}

#[test]
fn end_planes_choose_the_last_plane_and_reject_other_text() {
    // A quarter torus: with "mirror" the last ring lies in its meridian plane (x = 0 for an arc from
    // the x axis to the y axis), with the default it does not.
    for id in [
        "ctube.construct",
        "cnets.construct",
        "cnets.construct_coplanar",
    ] {
        let mut named = torus_inputs(7, 9);
        let off = |named: &[(&str, Value)]| {
            let out = run(id, named).unwrap();
            let Value::QuadMesh(mesh) = output(id, &out, "mesh") else {
                panic!("{id}: mesh")
            };
            (0..mesh.rows)
                .map(|i| mesh.at(i, mesh.cols - 1).x.abs())
                .fold(0.0, f64::max)
        };
        let perpendicular = off(&named);
        named.push(("end_planes", Value::text("mirror")));
        let mirror = off(&named);
        assert!(mirror <= 1e-12 * 13.0, "{id}: {mirror:e}");
        assert!(perpendicular > 1e-3, "{id}: {perpendicular:e}");
        named.pop();
        named.push(("end_planes", Value::text("bisector")));
        let err = run(id, &named).unwrap_err();
        assert!(err.contains("end_planes"), "{id}: {err}");
    }
}

#[test]
fn subdivide_rows_keeps_rows_and_counts() {
    let out = run("cnets.construct", &torus_inputs(5, 6)).unwrap();
    let Value::QuadMesh(coarse) = output("cnets.construct", &out, "mesh").clone() else {
        panic!("mesh")
    };
    let fine = run(
        "cnets.subdivide_rows",
        &[
            ("mesh", Value::QuadMesh(coarse.clone())),
            ("count", Value::Integer(3)),
        ],
    )
    .unwrap();
    let Value::QuadMesh(fine) = &fine[0] else {
        panic!("mesh")
    };
    assert_eq!(fine.rows, (coarse.rows - 1) * 3 + 1);
    for i in 0..coarse.rows {
        for j in 0..coarse.cols {
            assert_eq!(fine.at(3 * i, j), coarse.at(i, j));
        }
    }
    for bad in [0, -2, 5000] {
        let err = run(
            "cnets.subdivide_rows",
            &[
                ("mesh", Value::QuadMesh(coarse.clone())),
                ("count", Value::Integer(bad)),
            ],
        )
        .unwrap_err();
        assert!(err.contains("count"), "{bad}: {err}");
    }
}

/// The angle between a's last directrix-direction edge and b's first, largest over the rows.
fn seam_crease(a: &cnets_geometry::QuadGrid, b: &cnets_geometry::QuadGrid) -> f64 {
    (0..a.rows)
        .map(|i| {
            let before = a.at(i, a.cols - 1) - a.at(i, a.cols - 2);
            let after = b.at(i, 1) - b.at(i, 0);
            // atan2 of |a × b| and a · b: acos near 1 resolves only about 1.5e-8 rad.
            before.cross(after).length().atan2(before.dot(after))
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_net_continued_with_the_shared_seam_apex_runs_straight_across_the_seam() {
    let first = [("apex", Value::Number(0.96))]
        .into_iter()
        .chain(torus_inputs(5, 7))
        .collect::<Vec<_>>();
    let a_out = run("cnets.construct", &first).unwrap();
    let Value::QuadMesh(a) = output("cnets.construct", &a_out, "mesh") else {
        panic!("a mesh")
    };
    let apex = match output("cnets.construct", &a_out, "apices")
        .as_list()
        .and_then(|l| l.last().cloned())
    {
        Some(Value::Point(c)) => c,
        other => panic!("the last apex: {other:?}"),
    };
    // The directrix continues along the arc's last edge, then turns.
    let d = match &first[1].1 {
        Value::Polyline(d) => d.points.clone(),
        _ => unreachable!(),
    };
    let (x, e) = (d[d.len() - 1], d[d.len() - 1] - d[d.len() - 2]);
    let next = Polyline::open(vec![x, x + e, x + 2.0 * e + DVec3::new(0.0, 0.0, 0.4)]);
    let continued = |seam: Value| {
        run(
            "cnets.construct",
            &[
                ("directrix", Value::from(next.clone())),
                ("generatrix", Value::from(a.column(a.cols - 1))),
                ("seam_apex", seam),
            ],
        )
        .unwrap()
    };
    let b_out = continued(Value::Point(apex));
    let Value::QuadMesh(b) = output("cnets.construct", &b_out, "mesh") else {
        panic!("a mesh")
    };
    assert!(seam_crease(a, b) < 1e-9, "{}", seam_crease(a, b));
    let Value::Record(q) = output("cnets.construct", &b_out, "quality") else {
        panic!("a record")
    };
    let offset = q.get("seam_offset").and_then(Value::as_f64).unwrap();
    assert!(offset < 1e-9, "{offset}");
    // Null (an apex at infinity) keeps the apex as given: the seam creases.
    let plain = continued(Value::Null);
    let Value::QuadMesh(c) = output("cnets.construct", &plain, "mesh") else {
        panic!("a mesh")
    };
    assert!(seam_crease(a, c) > 1e-3, "{}", seam_crease(a, c));
}
