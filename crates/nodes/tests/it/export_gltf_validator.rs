//! glTF export: the .glb is read back with the `gltf` crate and compared with what was written
//! (positions, flat normals, per-face colours, line primitives), and passes the Khronos glTF
//! validator (npm `gltf-validator`, run under Node.js by scripts/validate-gltf.js) with no errors.

use crate::fab_support;

use cnets_engine::Value;
use cnets_geometry::fabrication::torsion_free_axes;
use cnets_geometry::{DVec3, PolygonMesh, Polyline};
use fab_support::*;

fn export(dir: &std::path::Path, given: &[(&str, Value)]) -> std::path::PathBuf {
    let ctx = ctx_in(dir);
    let (out, extras) = run_full(&ctx, "io.export_gltf", given).unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    let files = extras.files;
    assert_eq!(files.len(), 1);
    assert_eq!(files[0].to_string_lossy(), path.as_ref());
    std::path::PathBuf::from(path.as_ref())
}

#[test]
fn glb_reads_back_and_passes_the_khronos_validator() {
    let net = cone_net(5, 7, true);
    let mesh = PolygonMesh::from(&net.mesh);
    let axes = torsion_free_axes(&directrix(7), &net.mesh).unwrap();
    let outline = Polyline::closed(vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)]);
    let open = Polyline::open(net.directrix.clone());
    // One colour per face: a gradient, so every face's colour is known.
    let faces = mesh.face_count();
    let colours: Vec<Value> = (0..faces)
        .map(|f| {
            Value::Vector(DVec3::new(
                f as f64 / faces as f64,
                0.5,
                1.0 - f as f64 / faces as f64,
            ))
        })
        .collect();
    let dir = scratch("gltf");
    let path = export(
        &dir,
        &[
            ("name", Value::text("net")),
            ("meshes", Value::list(vec![mesh.clone().into()])),
            ("colours", Value::list(colours.clone())),
            ("lines", Value::Lines(std::sync::Arc::new(axes.clone()))),
            ("polylines", Value::list(vec![outline.into(), open.into()])),
        ],
    );
    assert!(path.ends_with("net.glb"));
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
        bytes.len()
    );

    let gltf = gltf::Gltf::from_slice(&bytes).expect("the gltf crate reads the file");
    let blob = gltf.blob.clone().expect("binary chunk");
    let scene = gltf.default_scene().expect("a default scene");
    let root = scene.nodes().next().unwrap();
    let r = root.transform().decomposed().1;
    assert!(
        (r[0] + std::f32::consts::FRAC_1_SQRT_2).abs() < 1e-6,
        "Z-up to Y-up rotation"
    );
    let mut modes = Vec::new();
    for node in root.children() {
        let m = node.mesh().unwrap();
        for prim in m.primitives() {
            modes.push(prim.mode());
            let reader = prim.reader(|_| Some(&blob));
            let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            match prim.mode() {
                gltf::mesh::Mode::Triangles => {
                    let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
                    let rgb: Vec<[f32; 3]> =
                        reader.read_colors(0).unwrap().into_rgb_f32().collect();
                    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
                    // Four duplicated corners per quad, two triangles per quad.
                    assert_eq!(positions.len(), 4 * faces);
                    assert_eq!(indices.len(), 6 * faces);
                    for (f, face) in mesh.faces().enumerate() {
                        let want = colours[f].as_vec3().unwrap();
                        for (c, &v) in face.iter().enumerate() {
                            let p = mesh.vertices[v as usize];
                            let got = positions[4 * f + c];
                            assert!(
                                (DVec3::new(got[0] as f64, got[1] as f64, got[2] as f64) - p)
                                    .length()
                                    < 1e-5
                            );
                            let col = rgb[4 * f + c];
                            assert!(
                                (col[0] as f64 - want.x).abs() < 1e-6
                                    && (col[2] as f64 - want.z).abs() < 1e-6
                            );
                            let n = normals[4 * f + c];
                            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                            assert!((len - 1.0).abs() < 1e-6);
                        }
                    }
                    // Every triangle uses the corners of one face only.
                    for t in indices.chunks(3) {
                        assert!(t.iter().all(|&i| i / 4 == t[0] / 4));
                    }
                }
                gltf::mesh::Mode::Lines => {
                    assert_eq!(positions.len(), 2 * axes.len());
                    let p = positions[2 * 9 + 1];
                    assert!(
                        (DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) - axes[9].end).length()
                            < 1e-5
                    );
                }
                gltf::mesh::Mode::LineLoop => assert_eq!(positions.len(), 3),
                gltf::mesh::Mode::LineStrip => assert_eq!(positions.len(), 7),
                other => panic!("unexpected mode {other:?}"),
            }
        }
    }
    modes.sort_by_key(|m| *m as u32);
    assert_eq!(
        modes,
        vec![
            gltf::mesh::Mode::Lines,
            gltf::mesh::Mode::LineLoop,
            gltf::mesh::Mode::LineStrip,
            gltf::mesh::Mode::Triangles
        ]
    );

    let report = run_checker("node", "scripts/validate-gltf.js", &path);
    let json: serde_json::Value = serde_json::from_str(&report).expect("validator report is JSON");
    let issues = &json["issues"];
    assert_eq!(
        issues["numErrors"].as_u64(),
        Some(0),
        "the glTF validator reports errors: {}",
        serde_json::to_string_pretty(&issues["messages"]).unwrap()
    );
    assert_eq!(
        issues["numWarnings"].as_u64(),
        Some(0),
        "{}",
        issues["messages"]
    );
    assert_eq!(json["info"]["drawCallCount"].as_u64(), Some(4));
    assert_eq!(
        json["info"]["totalTriangleCount"].as_u64(),
        Some(2 * faces as u64)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn planarity_colours_by_default_and_non_planar_polygons_validate() {
    // A bent quad and a cut pentagon: planarity colours differ, and the file still validates.
    let mesh = PolygonMesh::from_faces(
        vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.3),
            DVec3::Y,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.5, 0.5, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ],
        &[vec![0, 1, 2, 3], vec![1, 4, 5, 6, 7]],
    )
    .unwrap();
    let dir = scratch("gltf-planarity");
    let path = export(&dir, &[("meshes", mesh.into())]);
    assert!(path.ends_with("model.glb"));
    let bytes = std::fs::read(&path).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.clone().unwrap();
    let prim = gltf.meshes().next().unwrap().primitives().next().unwrap();
    let rgb: Vec<[f32; 3]> = prim
        .reader(|_| Some(&blob))
        .read_colors(0)
        .unwrap()
        .into_rgb_f32()
        .collect();
    // The bent quad is red (planarity far above the limit), the flat pentagon green.
    assert!(rgb[0][0] > 0.8 && rgb[0][1] < 0.2, "{:?}", rgb[0]);
    assert!(rgb[4][1] > 0.5 && rgb[4][0] < 0.2, "{:?}", rgb[4]);
    let report = run_checker("node", "scripts/validate-gltf.js", &path);
    let json: serde_json::Value = serde_json::from_str(&report).unwrap();
    assert_eq!(
        json["issues"]["numErrors"].as_u64(),
        Some(0),
        "{}",
        json["issues"]["messages"]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
