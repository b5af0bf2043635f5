//! Each gallery graph runs through the engine and shows what its figure claims.

use cnets_engine::Value;
use cnets_geometry::{DVec3, QuadGrid};
use cnets_tests::{Evaluated, load};

fn meshes(v: &Value) -> Vec<&QuadGrid> {
    match v {
        Value::QuadMesh(g) => vec![g.as_ref()],
        Value::List(items) => items.iter().flat_map(meshes).collect(),
        _ => Vec::new(),
    }
}

fn records(v: &Value) -> Vec<&cnets_engine::Record> {
    match v {
        Value::Record(r) => vec![r.as_ref()],
        Value::List(items) => items.iter().flat_map(records).collect(),
        _ => Vec::new(),
    }
}

fn field(r: &cnets_engine::Record, name: &str) -> f64 {
    r.get(name)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("quality.{name}"))
}

fn count(r: &cnets_engine::Record, class: &str) -> i64 {
    match r.get("configurations") {
        Some(Value::Record(c)) => match c.get(class) {
            Some(Value::Integer(n)) => *n,
            other => panic!("count {class}: {other:?}"),
        },
        other => panic!("configurations: {other:?}"),
    }
}

/// Every cone-net of `node` is planar to rounding and entirely (++).
fn assert_clean(e: &Evaluated, node: &str) {
    for q in records(e.output(node, "quality")) {
        assert!(
            field(q, "max_planarity") <= 1e-12,
            "{node}: planarity {}",
            field(q, "max_planarity")
        );
        assert_eq!(
            count(q, "--") + count(q, "+-") + count(q, "-+"),
            0,
            "{node}: not all (++)"
        );
    }
}

fn radial(p: DVec3) -> (f64, f64) {
    (p.x.hypot(p.y), p.z)
}

#[test]
fn torus_monge_is_a_surface_of_revolution_and_its_variants_stay_clean() {
    let e = Evaluated::new(load("torus-monge"));
    for node in ["monge", "varying_apex", "varying_ratios"] {
        assert_clean(&e, node);
    }
    let monge = meshes(e.output("monge", "mesh"))[0];
    let size = monge.size();
    // Every column but the last lies in a bisecting plane, which contains the axis; the last one lies
    // in the plane normal to the last directrix edge (construction notes §2), so it is checked apart.
    for i in 0..monge.rows {
        let (rho0, z0) = radial(monge.at(i, 0));
        for j in 1..monge.cols - 1 {
            let (rho, z) = radial(monge.at(i, j));
            assert!(
                (rho - rho0).abs() <= 1e-12 * size && (z - z0).abs() <= 1e-12 * size,
                "({i}, {j}) leaves its circle"
            );
        }
    }
    assert!(
        e.output("monge", "apices")
            .as_list()
            .unwrap()
            .iter()
            .all(Value::is_null),
        "a ≡ 1: apices at infinity"
    );
    let apex = e.output("varying_apex", "apex");
    assert_eq!(
        apex,
        e.output("apex", "y"),
        "the apex values used are the mapper's"
    );
    assert!(
        e.output("varying_apex", "apices")
            .as_list()
            .unwrap()
            .iter()
            .any(|a| !a.is_null())
    );
    let (a, b) = (
        meshes(e.output("varying_apex", "mesh"))[0],
        meshes(e.output("varying_ratios", "mesh"))[0],
    );
    let shift = DVec3::new(e.number("spacing", "value"), 0.0, 0.0);
    let moved = a
        .vertices
        .iter()
        .zip(&b.vertices)
        .map(|(p, q)| (*q - shift - *p).length())
        .fold(0.0, f64::max);
    assert!(
        moved > 0.01 * size,
        "varying the ratios must change the surface"
    );
}

/// Largest distance between corresponding end-polygon vertices of two cone-nets, after removing a
/// translation.
fn end_gap(a: &QuadGrid, b: &QuadGrid, shift: DVec3) -> f64 {
    (0..a.rows)
        .map(|i| (b.at(i, b.cols - 1) - shift - a.at(i, a.cols - 1)).length())
        .fold(0.0, f64::max)
}

fn end_size(m: &QuadGrid) -> f64 {
    m.at(0, m.cols - 1).distance(m.at(m.rows - 1, m.cols - 1))
}

#[test]
fn normalized_variants_agree_under_refinement_while_plain_ones_drift() {
    let e = Evaluated::new(load("normalization"));
    assert_clean(&e, "normalized");
    assert_clean(&e, "plain");
    let step = DVec3::new(0.0, 16.0, 0.0);
    let n = meshes(e.output("normalized", "mesh"));
    let p = meshes(e.output("plain", "mesh"));
    assert_eq!(
        n.iter().map(|m| m.cols - 1).collect::<Vec<_>>(),
        vec![10, 20, 40]
    );
    let profile = 2.0 * 3.0 * (70f64.to_radians()).cos();
    let (n1, n2) = (end_gap(n[0], n[1], step), end_gap(n[1], n[2], step));
    assert!(
        n2 < n1,
        "normalized: differences shrink with refinement ({n1} then {n2})"
    );
    assert!(
        n2 < 0.02 * profile,
        "normalized: 20 and 40 edges agree ({n2})"
    );
    let (s10, s40) = (end_size(n[0]), end_size(n[2]));
    assert!(
        (s40 / s10 - 1.0).abs() < 0.05,
        "normalized: the end polygon keeps its size ({s10} vs {s40})"
    );
    let p2 = end_gap(p[1], p[2], step);
    assert!(
        p2 > 5.0 * n2,
        "plain: 20 and 40 edges differ ({p2} vs normalized {n2})"
    );
    let (t10, t40) = (end_size(p[0]), end_size(p[2]));
    assert!(
        t40 < 0.5 * t10,
        "plain: the surface shrinks under refinement ({t10} -> {t40})"
    );
}

#[test]
fn correction_repairs_fold_overs_for_every_assistance() {
    let e = Evaluated::new(load("correction"));
    let quality = records(e.output("nets", "quality"));
    let corrections = e.output("nets", "corrections").as_list().unwrap();
    let assistance = e.output("assistance", "values").as_list().unwrap();
    assert_eq!(quality.len(), 4);
    assert!(
        count(quality[0], "--") > 0,
        "unassisted: the inputs fold over"
    );
    assert_eq!(corrections[0].as_list().unwrap().len(), 0);
    for k in 1..4 {
        let alpha = assistance[k].as_f64().unwrap();
        assert_eq!(
            count(quality[k], "--") + count(quality[k], "+-") + count(quality[k], "-+"),
            0,
            "α = {alpha}: all (++)"
        );
        assert!(field(quality[k], "max_planarity") <= 1e-12, "α = {alpha}");
        let list = corrections[k].as_list().unwrap();
        assert!(!list.is_empty(), "α = {alpha}: corrections are reported");
        let text: Vec<String> = list
            .iter()
            .map(|v| match v {
                Value::Text(t) => t.to_string(),
                other => panic!("{other:?}"),
            })
            .collect();
        match alpha {
            0.0 => assert!(text.iter().all(|t| t.starts_with("plane fix")), "{text:?}"),
            1.0 => assert!(text.iter().all(|t| t.starts_with("apex fix")), "{text:?}"),
            _ => assert!(
                text.iter().any(|t| t.starts_with("plane fix"))
                    && text.iter().any(|t| t.starts_with("apex fix")),
                "{text:?}"
            ),
        }
    }
}
