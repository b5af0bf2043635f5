//! Degenerate and hostile inputs: NaN, ±∞, huge and tiny magnitudes, coincident points, parallel
//! planes, wrong list lengths. Every call returns a typed error or an output without a single
//! non-finite number; nothing panics.

use cnets_geometry::conenet::{
    ColumnValues, ConeNet, ConstructInputs, CoplanarInputs, CtubeInputs, GridValues, NormalsInput,
    cone_check, construct, construct_coplanar, construct_ctube, encode, planarity,
};
use cnets_geometry::{DVec3, GeometryError, Polyline, QuadGrid};
use proptest::prelude::*;

/// Mostly moderate numbers, sometimes anything (`f64::ANY`), sometimes a special value.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -3.0..3.0f64,
        2 => proptest::num::f64::ANY,
        1 => prop::sample::select(vec![
            0.0, -0.0, 1.0, 0.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300, -1e300, 1e-300,
            f64::MIN_POSITIVE, f64::MAX, f64::EPSILON,
        ]),
    ]
}

fn point() -> impl Strategy<Value = DVec3> {
    (number(), number(), number()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn polyline() -> impl Strategy<Value = Polyline> {
    (prop::collection::vec(point(), 0..5), any::<bool>())
        .prop_map(|(points, closed)| Polyline { points, closed })
}

fn finite_net(net: &ConeNet) -> Result<(), TestCaseError> {
    prop_assert!(net.mesh.vertices.iter().all(|v| v.is_finite()));
    prop_assert!(net.apex.iter().all(|a| a.is_finite()));
    prop_assert!(net.apices.iter().flatten().all(|c| c.is_finite()));
    prop_assert!(
        net.normals
            .to_rows()
            .iter()
            .flatten()
            .all(|p| p.is_finite())
    );
    let q = &net.quality;
    prop_assert!(
        q.max_planarity.is_finite()
            && q.mean_planarity.is_finite()
            && q.max_cone_residual.is_finite()
    );
    prop_assert!(q.cone_residuals.iter().all(|r| r.is_finite()));
    prop_assert!(
        net.corrections
            .iter()
            .all(|c| c.old.is_finite() && c.new.is_finite())
    );
    Ok(())
}

fn check(result: Result<ConeNet, GeometryError>) -> Result<(), TestCaseError> {
    match result {
        Ok(net) => finite_net(&net),
        // Every error renders a message.
        Err(e) => {
            prop_assert!(!e.to_string().is_empty());
            Ok(())
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn constructions_never_panic_nor_leak_non_finite_values(
        directrix in polyline(),
        generatrix in polyline(),
        apex in prop::collection::vec(number(), 0..5),
        ratio in number(),
        ratios in prop::collection::vec(number(), 0..5),
        normals in prop::collection::vec(point(), 0..5),
        alpha in number(),
        epsilon in number(),
        normalized in any::<bool>(),
        scale in prop::option::of(number()),
    ) {
        let n = generatrix.points.len();
        let apex_in: ColumnValues = if apex.len() == 1 { apex[0].into() } else { apex.clone().into() };
        check(construct_ctube(&CtubeInputs::new(directrix.clone(), generatrix.clone()).apex(apex_in).normalized(normalized, scale)))?;
        check(construct_ctube(
            &CtubeInputs::new(directrix.clone(), generatrix.clone())
                .apex(apex.clone())
                .normals(NormalsInput::PerColumn(normals.clone())),
        ))?;
        check(construct_ctube(
            &CtubeInputs::new(directrix.clone(), generatrix.clone())
                .normals(NormalsInput::PerVertex(vec![normals.clone(); n])),
        ))?;
        for grid in [GridValues::Uniform(ratio), GridValues::PerColumn(ratios.clone()), GridValues::PerVertex(vec![ratios.clone(); n])] {
            check(construct(
                &ConstructInputs::new(directrix.clone(), generatrix.clone())
                    .apex(apex.clone())
                    .ratios(grid)
                    .assistance(alpha)
                    .epsilon(epsilon)
                    .normalized(normalized, scale),
            ))?;
        }
        check(construct_coplanar(
            &CoplanarInputs::new(directrix.clone(), generatrix.clone())
                .apex(apex.clone())
                .ruling_ratios(ratio)
                .plane_ratios(ratios.clone())
                .assistance(alpha)
                .epsilon(epsilon),
        ))?;
    }

    /// Moderate designs with one hostile number injected: still typed errors or finite outputs.
    #[test]
    fn near_valid_designs_with_one_hostile_value(
        k in 0usize..20,
        bad in number(),
        alpha in prop::sample::select(vec![-1.0, 0.0, 0.5, 1.0]),
    ) {
        let mut d: Vec<DVec3> = (0..5).map(|j| DVec3::new(j as f64, 0.2 * (j as f64).sin(), 0.0)).collect();
        let mut g: Vec<DVec3> = (0..4).map(|i| DVec3::new(0.0, 1.0 + 0.3 * i as f64, 0.4 * i as f64)).collect();
        let mut apex = vec![1.1, 0.9, 1.3, 0.8];
        let mut ratios = vec![0.4, 0.8, 0.2, 0.6];
        match k {
            0..=4 => d[k].x = bad,
            5..=8 => g[k - 5].z = bad,
            9..=12 => apex[k - 9] = bad,
            13..=16 => ratios[k - 13] = bad,
            17 => d[1] = d[0],
            18 => g[2] = g[1],
            _ => d[2] = DVec3::new(bad, bad, bad),
        }
        let directrix = Polyline::open(d);
        let generatrix = Polyline::open(g);
        check(construct(&ConstructInputs::new(directrix.clone(), generatrix.clone()).apex(apex.clone()).ratios(ratios.clone()).assistance(alpha)))?;
        check(construct_coplanar(&CoplanarInputs::new(directrix.clone(), generatrix.clone()).apex(apex.clone()).ruling_ratios(ratios.clone()).plane_ratios(ratios).assistance(alpha)))?;
        check(construct_ctube(&CtubeInputs::new(directrix, generatrix).apex(apex)))?;
    }

    #[test]
    fn mesh_tools_never_panic(points in prop::collection::vec(point(), 0..13), rows in 0usize..5, wrap in any::<(bool, bool)>()) {
        let cols = points.len().checked_div(rows).unwrap_or(0);
        let Ok(mesh) = QuadGrid::new(rows, cols, points[..rows * cols].to_vec()) else { return Ok(()) };
        let mesh = mesh.with_wrap(wrap.0, wrap.1);
        if let Ok(p) = planarity(&mesh) {
            prop_assert!(p.max.is_finite() && p.mean.is_finite() && p.per_face.iter().all(|v| v.is_finite()));
            prop_assert_eq!(p.per_face.len(), mesh.quad_count());
        }
        if let Ok(c) = cone_check(&mesh) {
            prop_assert!(c.max.is_finite() && c.residuals.iter().all(|v| v.is_finite()));
            prop_assert!(c.apices.iter().flatten().all(|v| v.is_finite()));
        }
        if let Ok(e) = encode(&mesh) {
            prop_assert!(e.apex.iter().all(|a| a.is_finite() && *a > 0.0));
            prop_assert!(e.directrix.points.iter().all(|p| p.is_finite()));
            prop_assert!(e.normals.iter().flatten().all(|p| p.is_finite()));
        }
    }
}

fn line(m: usize) -> Polyline {
    Polyline::open((0..m).map(|j| DVec3::new(j as f64, 0.0, 0.0)).collect())
}

fn gen2() -> Polyline {
    Polyline::open(vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 2.0, 0.5)])
}

#[test]
fn typed_errors_name_what_and_where() {
    // Too few points.
    let one = Polyline::open(vec![DVec3::ZERO]);
    assert!(matches!(
        construct(&ConstructInputs::new(one.clone(), gen2())),
        Err(GeometryError::TooFewPoints {
            what: "directrix",
            needed: 2,
            got: 1
        })
    ));
    assert!(matches!(
        construct(&ConstructInputs::new(line(3), one)),
        Err(GeometryError::TooFewPoints {
            what: "generatrix",
            ..
        })
    ));
    // Coincident points.
    let dup = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::X]);
    assert!(matches!(
        construct_ctube(&CtubeInputs::new(dup, gen2())),
        Err(GeometryError::ZeroLengthEdge {
            what: "directrix",
            index: 1,
            next: 2
        })
    ));
    // Non-finite.
    let nan = Polyline::open(vec![DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)]);
    assert!(matches!(
        construct_ctube(&CtubeInputs::new(nan, gen2())),
        Err(GeometryError::NonFinite {
            what: "directrix",
            index: 1
        })
    ));
    assert!(matches!(
        construct(&ConstructInputs::new(line(3), gen2()).apex(vec![1.0, f64::INFINITY])),
        Err(GeometryError::NonFinite {
            what: "apex",
            index: 1
        })
    ));
    assert!(matches!(
        construct(
            &ConstructInputs::new(line(3), gen2())
                .ratios(vec![vec![0.5, 0.5], vec![0.5, f64::NAN]])
        ),
        Err(GeometryError::NonFiniteEntry {
            what: "ratios",
            row: 1,
            column: 2
        })
    ));
    // Wrong lengths.
    assert!(matches!(
        construct(&ConstructInputs::new(line(4), gen2()).apex(vec![1.0, 1.0])),
        Err(GeometryError::WrongLength {
            what: "apex",
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        construct(&ConstructInputs::new(line(4), gen2()).ratios(vec![vec![0.5; 3], vec![0.5; 2]])),
        Err(GeometryError::WrongRowLength {
            what: "ratios",
            row: 1,
            expected: 3,
            got: 2
        })
    ));
    assert!(matches!(
        construct(&ConstructInputs::new(line(4), gen2()).ratios(vec![vec![0.5; 3]; 3])),
        Err(GeometryError::WrongLength {
            what: "ratios",
            got: 3,
            ..
        })
    ));
    assert!(matches!(
        construct_ctube(&CtubeInputs::new(line(4), gen2()).normals(vec![DVec3::X; 2])),
        Err(GeometryError::WrongLength {
            what: "normals",
            got: 2,
            ..
        })
    ));
    // Out of range.
    let e = construct(&ConstructInputs::new(line(3), gen2()).ratios(vec![0.5, 1.5])).unwrap_err();
    assert!(matches!(
        e,
        GeometryError::OutOfRange {
            what: "ratios",
            column: Some(2),
            ..
        }
    ));
    assert!(e.to_string().contains("column 2"), "{e}");
    // A plane parallel to its incoming edge (P·ê = 0), a zero normal.
    assert!(matches!(
        construct_ctube(&CtubeInputs::new(line(3), gen2()).normals(vec![DVec3::X, DVec3::Y])),
        Err(GeometryError::PlaneContainsEdge {
            row: None,
            column: 2
        })
    ));
    assert!(matches!(
        construct_ctube(
            &CtubeInputs::new(line(3), gen2())
                .normals(vec![vec![DVec3::X; 2], vec![DVec3::X, DVec3::ZERO]])
        ),
        Err(GeometryError::ZeroNormal {
            row: Some(1),
            column: 2
        })
    ));
    // V·P = 0: a translation (a = 1) along x towards a plane containing the x direction … is excluded
    // above; a skew plane with V in it: V = X_1 − X_0 = x̂ for a = 1, P ⊥ x̂ is rejected as
    // PlaneContainsEdge. With a ≠ 1, V = (a − 1)(g − X_0) + x̂; choose P ⊥ V.
    let g = Polyline::open(vec![DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 2.0, 0.0)]);
    let v = DVec3::new(1.0, -0.5, 0.0); // a = 0.5, g = (0,1,0): V = −0.5 (0,1,0) + (1,0,0)
    let p = DVec3::new(0.5, 1.0, 0.0).normalize(); // ⊥ V, P·x̂ ≠ 0
    assert!(p.dot(v).abs() < 1e-15);
    assert!(matches!(
        construct_ctube(
            &CtubeInputs::new(line(2), g)
                .apex(0.5)
                .normals(vec![vec![p], vec![DVec3::X]])
        ),
        Err(GeometryError::ParallelStep { row: 0, column: 1 })
    ));
    // The directrix reverses: no bisecting plane.
    let back = Polyline::open(vec![DVec3::ZERO, DVec3::X, DVec3::ZERO]);
    assert!(matches!(
        construct(&ConstructInputs::new(back, gen2())),
        Err(GeometryError::DirectrixReverses { column: 1 })
    ));
    // A generatrix point on the directrix line: no support plane for the ratio construction.
    let on_line = Polyline::open(vec![DVec3::new(-1.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0)]);
    assert!(matches!(
        construct(&ConstructInputs::new(line(3), on_line).ratios(0.3)),
        Err(GeometryError::DegenerateSupport { row: 0, column: 1 })
    ));
    // Ratio corner cases 0 and 1 put the plane through the incoming edge.
    assert!(matches!(
        construct(&ConstructInputs::new(line(3), gen2()).ratios(vec![0.0, 0.5])),
        Err(GeometryError::PlaneContainsEdge {
            row: Some(0),
            column: 1
        })
    ));
    assert!(matches!(
        construct_coplanar(&CoplanarInputs::new(line(3), gen2()).ruling_ratios(vec![0.5, 1.0])),
        Err(GeometryError::PlaneContainsEdge {
            row: None,
            column: 2
        })
    ));
    // Invalid normalization scale.
    for scale in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            construct(&ConstructInputs::new(line(3), gen2()).normalized(true, Some(scale))),
            Err(GeometryError::InvalidParameter { what: "scale", .. })
        ));
    }
}

#[test]
fn huge_and_tiny_scales() {
    // The construction is scale-invariant: the same design at 1e-100 and 1e100 gives the scaled mesh,
    // or a typed error once magnitudes leave the representable range.
    let reference =
        construct(&ConstructInputs::new(line(4), gen2()).apex(0.8).ratios(0.4)).unwrap();
    for s in [1e-100, 1e-20, 1e20, 1e100] {
        let scale = |p: &Polyline| Polyline::open(p.points.iter().map(|q| *q * s).collect());
        let net = construct(
            &ConstructInputs::new(scale(&line(4)), scale(&gen2()))
                .apex(0.8)
                .ratios(0.4),
        )
        .unwrap();
        for (a, b) in net.mesh.vertices.iter().zip(&reference.mesh.vertices) {
            assert!((*a / s - *b).length() < 1e-12, "scale {s}: {a} vs {b}");
        }
        assert_eq!(net.configurations, reference.configurations);
    }
    for s in [1e-300, 1e300] {
        let scale = |p: &Polyline| Polyline::open(p.points.iter().map(|q| *q * s).collect());
        match construct(
            &ConstructInputs::new(scale(&line(4)), scale(&gen2()))
                .apex(0.8)
                .ratios(0.4),
        ) {
            Ok(net) => assert!(net.mesh.vertices.iter().all(|v| v.is_finite())),
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
}
