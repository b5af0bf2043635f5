//! Input forms and normalization: a number, a list of M−1, or N lists of M−1 give the same result
//! when they carry the same values; the normalized apex function maps ā to a_j = 1 − (1 − ā_j) l_j / L
//! with L = directrix length / 5 by default; a closed directrix needs one value per stored point.

use cnets_geometry::conenet::{
    ConstructInputs, CoplanarInputs, CtubeInputs, GridValues, NormalsInput, construct,
    construct_coplanar, construct_ctube, normalize,
};
use cnets_geometry::{DVec3, GeometryError, Polyline};

fn directrix() -> Polyline {
    Polyline::open(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.2, 0.0),
        DVec3::new(2.5, 0.3, 0.4),
        DVec3::new(3.0, 1.0, 0.6),
    ])
}

fn generatrix() -> Polyline {
    Polyline::open(vec![
        DVec3::new(0.0, 1.0, -0.5),
        DVec3::new(-0.1, 1.5, 0.0),
        DVec3::new(0.0, 1.2, 0.7),
    ])
}

#[test]
fn ratio_forms_agree() {
    let base = ConstructInputs::new(directrix(), generatrix()).apex(vec![0.9, 1.1, 1.0]);
    let uniform = construct(&base.clone().ratios(0.35)).unwrap();
    let column = construct(&base.clone().ratios(vec![0.35; 3])).unwrap();
    let table = construct(&base.clone().ratios(vec![vec![0.35; 3]; 3])).unwrap();
    assert_eq!(uniform.mesh, column.mesh);
    assert_eq!(uniform.mesh, table.mesh);
    // Per-row tables really are per row: changing one row changes only that row.
    let mut rows = vec![vec![0.35; 3]; 3];
    rows[1][1] = 0.6;
    let changed = construct(&base.ratios(GridValues::PerVertex(rows))).unwrap();
    for j in 0..4 {
        assert_eq!(changed.mesh.at(0, j), uniform.mesh.at(0, j));
        assert_eq!(changed.mesh.at(2, j), uniform.mesh.at(2, j));
    }
    assert_ne!(changed.mesh.at(1, 2), uniform.mesh.at(1, 2));
}

#[test]
fn normal_forms_agree_and_are_oriented() {
    let normals = vec![
        DVec3::new(1.0, 0.1, 0.0),
        DVec3::new(-2.0, -0.3, -0.5),
        DVec3::new(0.2, 1.0, 0.1),
    ];
    let base = CtubeInputs::new(directrix(), generatrix()).apex(0.8);
    let shared = construct_ctube(&base.clone().normals(normals.clone())).unwrap();
    let table =
        construct_ctube(&base.normals(NormalsInput::PerVertex(vec![normals.clone(); 3]))).unwrap();
    assert_eq!(shared.mesh, table.mesh);
    assert!(shared.normals.is_shared() && !table.normals.is_shared());
    let x = &shared.directrix;
    for j in 1..4 {
        let p = shared.normals.get(2, j);
        assert!((p.length() - 1.0).abs() < 1e-15);
        assert!(p.dot(x[j] - x[j - 1]) > 0.0, "P·ê_j > 0 at column {j}");
        // Given normals are used up to orientation and length.
        assert!(p.cross(normals[j - 1]).length() < 1e-15);
    }
    assert_eq!(table.normals.to_rows().len(), 3);
    assert_eq!(table.normals.to_rows()[0].len(), 3);
}

#[test]
fn normalized_apex_matches_the_formula() {
    let d = directrix();
    let lengths: Vec<f64> = d.points.windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let abar = vec![0.7, 1.0, 1.4];
    let net = construct(
        &ConstructInputs::new(d.clone(), generatrix())
            .apex(abar.clone())
            .normalized(true, None),
    )
    .unwrap();
    for k in 0..3 {
        let expected = if abar[k] == 1.0 {
            1.0
        } else {
            1.0 - (1.0 - abar[k]) * lengths[k] / (total / 5.0)
        };
        assert!(
            (net.apex[k] - expected).abs() < 1e-15,
            "a_{} = {} vs {expected}",
            k + 1,
            net.apex[k]
        );
    }
    assert_eq!(net.apex[1], 1.0);
    // An explicit L, and the same construction from the denormalized values.
    let with_l = construct(
        &ConstructInputs::new(d.clone(), generatrix())
            .apex(abar.clone())
            .normalized(true, Some(2.0)),
    )
    .unwrap();
    let a = normalize::denormalize(&abar, &lengths, 2.0);
    assert_eq!(with_l.apex, a);
    let plain = construct(&ConstructInputs::new(d, generatrix()).apex(a)).unwrap();
    assert_eq!(plain.mesh, with_l.mesh);
    assert_eq!(normalize::default_scale(total), total / 5.0);
}

#[test]
fn closed_directrix_takes_one_value_per_stored_point() {
    let ring = Polyline::closed(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(3.0, 3.0, 0.5),
        DVec3::new(0.0, 3.0, 0.0),
    ]);
    let g = Polyline::open(vec![DVec3::new(0.3, 0.3, -0.5), DVec3::new(0.5, 0.5, 0.5)]);
    let net = construct(
        &ConstructInputs::new(ring.clone(), g.clone())
            .apex(vec![1.0, 0.9, 1.1, 1.0])
            .ratios(0.45),
    )
    .unwrap();
    assert_eq!(net.mesh.cols, 5);
    assert_eq!(net.apex.len(), 4);
    assert_eq!(net.configurations.cols(), 4);
    assert!(matches!(
        construct(&ConstructInputs::new(ring.clone(), g.clone()).apex(vec![1.0; 3])),
        Err(GeometryError::WrongLength {
            what: "apex",
            got: 3,
            ..
        })
    ));
    let cop =
        construct_coplanar(&CoplanarInputs::new(ring, g).plane_ratios(vec![0.5, 0.4, 0.6, 0.5]))
            .unwrap();
    assert_eq!(cop.mesh.cols, 5);
    assert!(cop.quality.max_planarity < 1e-12);
}

#[test]
fn apices_follow_the_apex_values() {
    let net =
        construct_ctube(&CtubeInputs::new(directrix(), generatrix()).apex(vec![0.5, 1.0, 2.0]))
            .unwrap();
    let x = &net.directrix;
    let c0 = net.apices[0].unwrap();
    assert!((c0 - (x[1] - x[0] * 0.5) / 0.5).length() < 1e-14);
    assert_eq!(net.apices[1], None);
    let c2 = net.apices[2].unwrap();
    assert!((c2 - (x[3] - x[2] * 2.0) / -1.0).length() < 1e-14);
}
