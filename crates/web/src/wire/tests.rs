//! The wire's round trips and its refusals of malformed messages.

use std::sync::Arc;

use cnets_editor::preview::{
    ColorMode, DistanceSide, Layer, LegendInfo, MeshFigures, MeshKind, PickCurve, PickGeometry,
    PickMesh, PreviewOptions, PreviewStats,
};
use cnets_geometry::fabrication::FaceClass;
use cnets_geometry::{DVec3, Polyline, QuadGrid};
use cnets_render::Color;

use super::*;

fn round_trip(message: &ToWorker) -> ToWorker {
    decode_to_worker(&encode_to_worker(message)).expect("decodes")
}

#[test]
fn requests_round_trip() {
    let mut options = PreviewOptions::default();
    options.color_mode = ColorMode::Planarity;
    options.distance_to = Some(17);
    options.distance_side = DistanceSide::Reference;
    options.set(Layer::Apices, false);
    assert!(options.set_planarity_limit(1e-5));
    let job = ToWorker::Evaluate(Job {
        seq: 42,
        ron: "(nodes: {})".into(),
        base_dir: Some("graphs".into()),
        view: vec!["bay".into(), "inner".into()],
        options,
        literals: vec![LiteralRef {
            node: "big".into(),
            input: "values".into(),
            key: 7,
        }],
        forget: vec![3, 5],
        held: true,
    });
    assert_eq!(round_trip(&job), job);
    assert_eq!(round_trip(&ToWorker::Released), ToWorker::Released);
    let literal = ToWorker::Literal {
        key: 7,
        value: Value::list(vec![
            Value::list(vec![Value::Number(-0.0), Value::Number(f64::MAX)]),
            Value::text("row"),
            Value::Point(DVec3::new(1.0, 2.0, 3.0)),
            Value::Integer(i64::MIN),
            Value::Null,
        ]),
    };
    assert_eq!(round_trip(&literal), literal);
    let parse = ToWorker::Parse(ParseJob {
        token: 3,
        origin: "big.ron".into(),
        library: vec!["graphs".into()],
        text: b"(nodes: {})".to_vec(),
    });
    assert_eq!(round_trip(&parse), parse);
    let file = ToWorker::Provide {
        name: "hull.obj".into(),
        bytes: vec![0, 1, 2, 255],
    };
    assert_eq!(round_trip(&file), file);
}

#[test]
fn answers_round_trip_with_statuses_scene_and_picks() {
    let mut scene = Scene::new();
    let grid = QuadGrid::new(
        2,
        3,
        (0..6)
            .map(|k| DVec3::new(f64::from(k % 3), f64::from(k / 3), 0.5))
            .collect(),
    )
    .unwrap();
    scene
        .add_quad_grid(
            &grid,
            cnets_render::FaceColors::Uniform(Color([10, 20, 30, 255])),
        )
        .unwrap();
    let picks = Picks {
        meshes: vec![PickMesh {
            node: "net".into(),
            output: "mesh".into(),
            item: Some(1),
            geometry: PickGeometry::Grid(Arc::new(grid)),
            classes: Some(vec![FaceClass::Convex, FaceClass::NegativeApex]),
            planarity: vec![1e-15, 2e-3],
        }],
        curves: vec![PickCurve {
            node: "arc".into(),
            output: "curve".into(),
            polyline: Arc::new(Polyline {
                points: vec![DVec3::X, DVec3::Y],
                closed: true,
            }),
        }],
    };
    let statuses = HashMap::from([
        (
            "mapper".to_string(),
            NodeStatus::Ok {
                warnings: vec!["careful".into()],
                outputs: vec!["0.5".into()],
                time_ms: 1.5,
                readout: Some("text".into()),
                ran_on: Some(vec![
                    Value::Number(0.25),
                    Value::text("bezier"),
                    Value::list(vec![Value::Integer(-3), Value::Point(DVec3::Z)]),
                ]),
            },
        ),
        ("bad".to_string(), NodeStatus::Error("needs 320 GB".into())),
        ("slow".to_string(), NodeStatus::Running { last_ms: 900.0 }),
        ("off".to_string(), NodeStatus::Disabled),
    ]);
    let response = EvalResponse {
        seq: 9,
        view: vec![],
        statuses: statuses.clone(),
        scene: Arc::new(scene.clone()),
        stats: PreviewStats {
            vertices: 6,
            faces: 2,
            max_planarity: Some(2e-3),
            max_planarity_mesh: Some("net.mesh".into()),
            meshes: vec![
                MeshFigures {
                    name: "net.mesh".into(),
                    kind: MeshKind::ConeNet,
                    vertices: 6,
                    faces: 2,
                    max_planarity: Some(2e-3),
                },
                MeshFigures {
                    name: "hull.mesh[3]".into(),
                    kind: MeshKind::Reference,
                    vertices: 4,
                    faces: 1,
                    max_planarity: None,
                },
            ],
            legend: LegendInfo::Classes(vec![(FaceClass::Convex, 1)]),
            apices: 0,
            distance: Some(cnets_editor::preview::DistanceFigures {
                reference: "hull".into(),
                net: vec!["net.mesh".into(), "net.mesh[1]".into()],
                rms: 0.025,
                max: 0.179,
                net_rms: 0.02,
                net_max: 0.1,
                reference_rms: 0.03,
                reference_max: 0.179,
                samples: (4, 2),
                side: DistanceSide::Reference,
                vertices: 560,
                colour_max: 0.17,
            }),
            distance_status: Some("nothing else is previewed".into()),
            build_ms: 0.5,
        },
        picks: Arc::new(picks),
        eval_ms: 3.0,
        ran: 4,
        changed_at: web_time::Instant::now(),
        finished_at: web_time::Instant::now(),
        complete: false,
    };
    let Ok(FromWorker::Answer(a)) = decode_from_worker(&encode_answer(&response, false)) else {
        panic!("an answer");
    };
    assert_eq!((a.seq, a.eval_ms, a.ran, a.complete), (9, 3.0, 4, false));
    assert_eq!(a.statuses, statuses);
    let (s, stats, p) = a.preview.expect("the preview");
    assert!(same_scene(&s, &scene) && s.bounds() == scene.bounds());
    assert_eq!(stats, response.stats);
    assert_eq!(p.meshes[0].classes, response.picks.meshes[0].classes);
    assert_eq!(p.meshes[0].planarity, response.picks.meshes[0].planarity);
    assert_eq!(p.meshes[0].geometry.vertices(), grid_vertices(&response));
    assert_eq!(p.curves[0].polyline, response.picks.curves[0].polyline);
    // Without the preview: the statuses only.
    let Ok(FromWorker::Answer(b)) = decode_from_worker(&encode_answer(&response, true)) else {
        panic!("an answer");
    };
    assert!(b.preview.is_none());
}

fn grid_vertices(r: &EvalResponse) -> &[DVec3] {
    r.picks.meshes[0].geometry.vertices()
}

#[test]
fn read_files_round_trip_with_their_literals_or_their_error() {
    let parsed = Parsed {
        skeleton: "(nodes: {})".into(),
        literals: vec![(
            LiteralRef {
                node: "numbers".into(),
                input: "values".into(),
                key: 1 << 63,
            },
            Value::list(vec![Value::Number(0.5), Value::Number(-2.0)]),
        )],
    };
    let registry = std::sync::Arc::new(cnets_engine::Registry::new());
    let error = cnets_engine::file::load_str_with(
        "(nodes: {\"a\": (type: \"no.such\")})",
        "big.ron",
        &registry,
        &Default::default(),
    )
    .expect_err("an unknown node type");
    for result in [Ok(parsed), Err(error)] {
        match decode_from_worker(&encode_parsed(9, result.clone())).expect("decodes") {
            FromWorker::Parsed {
                token,
                result: back,
            } => {
                assert_eq!((token, back), (9, result));
            }
            _ => panic!("not a read file"),
        }
    }
}

#[test]
fn malformed_messages_are_errors_not_panics() {
    let job = encode_to_worker(&ToWorker::Provide {
        name: "a.csv".into(),
        bytes: vec![1; 100],
    });
    for cut in 0..job.len() {
        assert!(decode_to_worker(&job[..cut]).is_err(), "cut at {cut}");
    }
    let mut longer = job.clone();
    longer.push(0);
    let err = decode_to_worker(&longer).unwrap_err().to_string();
    assert!(err.contains("1 bytes past its end"), "{err}");
    // A count far past the message is refused before anything is allocated.
    let provide = encode_to_worker(&ToWorker::Provide {
        name: String::new(),
        bytes: vec![],
    })[0];
    let mut huge = vec![provide];
    huge.extend_from_slice(&[0xff; 9]);
    huge.push(0x01);
    assert!(decode_to_worker(&huge).is_err());
    assert!(decode_from_worker(&[99]).is_err());
    assert!(decode_from_worker(&[]).is_err());
}

#[test]
fn values_nested_past_the_limit_are_an_error_not_a_stack_overflow() {
    let literal = |value| encode_to_worker(&ToWorker::Literal { key: 7, value });
    let null = literal(Value::Null);
    let list = literal(Value::list(vec![Value::Null]));
    // `list` is `null` with the list's tag and its length 1 before the null's tag.
    let (prefix, one_level) = (
        &null[..null.len() - 1],
        &list[null.len() - 1..list.len() - 1],
    );
    let nested = |levels: usize| {
        let mut bytes = prefix.to_vec();
        for _ in 0..levels {
            bytes.extend_from_slice(one_level);
        }
        bytes.push(*null.last().unwrap());
        decode_to_worker(&bytes)
    };
    assert!(nested(cnets_engine::value::MAX_NESTING).is_ok());
    // One level more is refused (postcard keeps no message), and far more does not overflow.
    assert!(nested(cnets_engine::value::MAX_NESTING + 1).is_err());
    assert!(nested(100_000).is_err());
}

#[test]
fn a_scene_or_mesh_breaking_its_invariants_is_refused() {
    // A triangle index past the vertices.
    let parts = cnets_render::SceneParts {
        face_indices: vec![0, 1, 2],
        ..Default::default()
    };
    let bytes = postcard::to_allocvec(&parts).unwrap();
    assert!(postcard::from_bytes::<Scene>(&bytes).is_err());
    // A buffer that is not a whole number of items.
    let parts = cnets_render::SceneParts {
        face_indices: vec![7],
        ..Default::default()
    };
    let mut bytes = postcard::to_allocvec(&parts).unwrap();
    let at = bytes
        .iter()
        .position(|&b| b == 4)
        .expect("the indices' byte count");
    bytes[at] = 3;
    bytes.remove(at + 1);
    assert!(postcard::from_bytes::<Scene>(&bytes).is_err());
    // A grid whose vertices are not rows × columns, as a literal value.
    let grid = QuadGrid {
        rows: 3,
        cols: 2,
        vertices: vec![DVec3::ZERO; 4],
        ..QuadGrid::default()
    };
    let message = encode_to_worker(&ToWorker::Literal {
        key: 1,
        value: Value::QuadMesh(Arc::new(grid)),
    });
    let err = decode_to_worker(&message).unwrap_err().to_string();
    assert!(err.contains("malformed"), "{err}");
}
