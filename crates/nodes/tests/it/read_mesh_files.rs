//! `io.read_mesh` reads files written here by independent, hand-written writers — OBJ, ascii and
//! binary STL, ascii and binary PLY, glTF with an external buffer and with a data URI, GLB — and
//! gives back the same counts and coordinates; malformed files are errors naming the line or byte.

use std::path::{Path, PathBuf};

use base64::Engine as _;
use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, Value};
use cnets_geometry::{DVec3, PolygonMesh};

/// A folder of the test's own (the tests run side by side in one process).
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-read-mesh-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Two unit quads side by side (6 vertices) — the reference every file encodes.
fn quads() -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let v = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.25),
        DVec3::new(2.0, 0.0, 0.5),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.25),
        DVec3::new(2.0, 1.0, 0.5),
    ];
    (v, vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]])
}

/// The same two quads as four triangles.
fn triangles() -> Vec<[u32; 3]> {
    vec![[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]]
}

fn read(
    dir: &Path,
    path: &str,
    weld: Option<f64>,
) -> Result<(PolygonMesh, Vec<PolygonMesh>), String> {
    let ctx = NodeContext::new(None, Some(dir.to_path_buf()));
    let def = cnets_nodes::io_read::mesh::read_mesh();
    let out = evaluate_node(
        &def,
        &ctx,
        &[
            Value::text(path),
            Value::text("auto"),
            weld.map_or(Value::Null, Value::Number),
        ],
    )
    .map_err(|e| e.to_string())?;
    let mesh = |v: &Value| match v {
        Value::Mesh(m) => (**m).clone(),
        other => panic!("a mesh, got {}", other.type_name()),
    };
    let meshes = out.values[1].as_list().unwrap().iter().map(mesh).collect();
    Ok((mesh(&out.values[0]), meshes))
}

fn assert_same_points(got: &[DVec3], expected: &[DVec3], tolerance: f64) {
    assert_eq!(got.len(), expected.len());
    for (g, e) in got.iter().zip(expected) {
        assert!((*g - *e).length() <= tolerance, "{g} vs {e}");
    }
}

#[test]
fn obj_keeps_polygons_and_objects() {
    let dir = scratch("obj");
    let (v, f) = quads();
    let mut text = String::from("# two objects\n");
    for p in &v {
        text += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    text += "vn 0 0 1\no left\n";
    text += &format!(
        "f {}//1 {}//1 {}//1 {}//1\n",
        f[0][0] + 1,
        f[0][1] + 1,
        f[0][2] + 1,
        f[0][3] + 1
    );
    text += "g right\n";
    text += &format!(
        "f {} {} {} {}\n",
        f[1][0] + 1,
        f[1][1] + 1,
        f[1][2] + 1,
        f[1][3] + 1
    );
    std::fs::write(dir.join("quads.obj"), &text).unwrap();
    let (mesh, meshes) = read(&dir, "quads.obj", None).unwrap();
    assert_eq!(mesh.vertices, v);
    assert_eq!(mesh.faces().map(<[u32]>::to_vec).collect::<Vec<_>>(), f);
    assert_eq!(meshes.len(), 2);
    assert_eq!(
        meshes[1].vertices.len(),
        4,
        "each object keeps only its own vertices"
    );
    assert_eq!(meshes[1].face(0), &[0, 1, 3, 2]);

    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n").unwrap();
    let e = read(&dir, "bad.obj", None).unwrap_err();
    assert!(e.contains("bad.obj") && e.contains("line 4"), "{e}");
}

fn f32s(p: DVec3) -> [f32; 3] {
    [p.x as f32, p.y as f32, p.z as f32]
}

#[test]
fn stl_ascii_and_binary_read_the_same_triangles() {
    let dir = scratch("stl");
    let (v, _) = quads();
    let mut ascii = String::from("solid quads\n");
    let mut binary = vec![0u8; 80];
    binary.extend_from_slice(&(triangles().len() as u32).to_le_bytes());
    for t in triangles() {
        ascii += "  facet normal 0 0 1\n    outer loop\n";
        binary.extend(std::iter::repeat_n(0u8, 12));
        for &i in &t {
            let p = f32s(v[i as usize]);
            ascii += &format!("      vertex {:e} {:e} {:e}\n", p[0], p[1], p[2]);
            p.iter()
                .for_each(|x| binary.extend_from_slice(&x.to_le_bytes()));
        }
        ascii += "    endloop\n  endfacet\n";
        binary.extend_from_slice(&[0, 0]);
    }
    ascii += "endsolid quads\n";
    std::fs::write(dir.join("a.stl"), &ascii).unwrap();
    std::fs::write(dir.join("b.stl"), &binary).unwrap();
    for name in ["a.stl", "b.stl"] {
        let (mesh, meshes) = read(&dir, name, Some(1e-9)).unwrap();
        assert_eq!(meshes.len(), 1);
        assert_eq!(mesh.face_count(), 4, "{name}");
        assert_eq!(mesh.vertices.len(), 6, "{name}: shared corners");
        for (k, t) in triangles().iter().enumerate() {
            let corners: Vec<DVec3> = mesh
                .face(k)
                .iter()
                .map(|&i| mesh.vertices[i as usize])
                .collect();
            let expected: Vec<DVec3> = t.iter().map(|&i| v[i as usize]).collect();
            assert_same_points(&corners, &expected, 1e-7);
        }
    }
    let truncated = &binary[..binary.len() - 20];
    std::fs::write(dir.join("short.stl"), truncated).unwrap();
    let e = read(&dir, "short.stl", None).unwrap_err();
    assert!(
        e.contains("byte 80") && e.contains("declares 4 triangles"),
        "{e}"
    );
    let mut lines: Vec<&str> = ascii.lines().collect();
    lines[11] = "      vertex 1 one 0";
    std::fs::write(dir.join("broken.stl"), lines.join("\n")).unwrap();
    let e = read(&dir, "broken.stl", None).unwrap_err();
    assert!(e.contains("line 12: facet 1: "), "{e}");
}

#[test]
fn ply_ascii_and_binary_keep_polygons() {
    let dir = scratch("ply");
    let (v, f) = quads();
    let header = |format: &str| {
        format!(
            "ply\nformat {format} 1.0\ncomment written by hand\nelement vertex 6\nproperty double x\nproperty double y\nproperty double z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        )
    };
    let mut ascii = header("ascii");
    let mut binary = header("binary_little_endian").into_bytes();
    for p in &v {
        ascii += &format!("{} {} {}\n", p.x, p.y, p.z);
        [p.x, p.y, p.z]
            .iter()
            .for_each(|x| binary.extend_from_slice(&x.to_le_bytes()));
    }
    for face in &f {
        ascii += &format!("4 {} {} {} {}\n", face[0], face[1], face[2], face[3]);
        binary.push(4);
        face.iter()
            .for_each(|&i| binary.extend_from_slice(&(i as i32).to_le_bytes()));
    }
    std::fs::write(dir.join("a.ply"), &ascii).unwrap();
    std::fs::write(dir.join("b.ply"), &binary).unwrap();
    for name in ["a.ply", "b.ply"] {
        let (mesh, _) = read(&dir, name, None).unwrap();
        assert_eq!(mesh.vertices, v, "{name}");
        assert_eq!(
            mesh.faces().map(<[u32]>::to_vec).collect::<Vec<_>>(),
            f,
            "{name}"
        );
    }
    std::fs::write(
        dir.join("bad.ply"),
        ascii.replace("element face 2", "element face two"),
    )
    .unwrap();
    let e = read(&dir, "bad.ply", None).unwrap_err();
    assert!(e.contains("line"), "{e}");
}

/// A glTF document (hand-written JSON) for the four triangles, its positions moved by a node
/// translation, and the binary buffer it refers to.
fn gltf_parts(uri: Option<&str>) -> (String, Vec<u8>) {
    let (v, _) = quads();
    let mut bin = Vec::new();
    for p in &v {
        f32s(*p)
            .iter()
            .for_each(|x| bin.extend_from_slice(&x.to_le_bytes()));
    }
    let index_offset = bin.len();
    for t in triangles() {
        t.iter()
            .for_each(|&i| bin.extend_from_slice(&(i as u16).to_le_bytes()));
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let uri = uri.map_or(String::new(), |u| format!(r#", "uri": "{u}""#));
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0", "generator": "hand"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0, "translation": [10, 0, 0]}}],
  "meshes": [{{"name": "quads", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "buffers": [{{"byteLength": {len}{uri}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": {index_offset}}},
    {{"buffer": 0, "byteOffset": {index_offset}, "byteLength": 24}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [0, 0, 0], "max": [2, 1, 0.5]}},
    {{"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}}
  ]
}}"#,
        len = bin.len()
    );
    (json, bin)
}

#[test]
fn gltf_with_external_and_embedded_buffers_and_glb_apply_node_transforms() {
    let dir = scratch("gltf");
    let (v, _) = quads();
    let moved: Vec<DVec3> = v.iter().map(|p| *p + DVec3::new(10.0, 0.0, 0.0)).collect();

    let (json, bin) = gltf_parts(Some("quads.bin"));
    std::fs::write(dir.join("quads.gltf"), json).unwrap();
    std::fs::write(dir.join("quads.bin"), &bin).unwrap();
    let data = base64::engine::general_purpose::STANDARD.encode(&bin);
    let (json, _) = gltf_parts(Some(&format!(
        "data:application/octet-stream;base64,{data}"
    )));
    std::fs::write(dir.join("embedded.gltf"), json).unwrap();

    let (json, bin) = gltf_parts(None);
    let mut json = json.into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut glb = Vec::new();
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
    glb.extend_from_slice(&(json.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    std::fs::write(dir.join("quads.glb"), &glb).unwrap();

    for name in ["quads.gltf", "embedded.gltf", "quads.glb"] {
        let (mesh, meshes) = read(&dir, name, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(meshes.len(), 1);
        assert_same_points(&mesh.vertices, &moved, 1e-6);
        let faces: Vec<Vec<u32>> = mesh.faces().map(<[u32]>::to_vec).collect();
        let expected: Vec<Vec<u32>> = triangles().iter().map(|t| t.to_vec()).collect();
        assert_eq!(faces, expected, "{name}");
    }
    std::fs::remove_file(dir.join("quads.bin")).unwrap();
    let e = read(&dir, "quads.gltf", None).unwrap_err();
    assert!(
        e.contains("quads.bin"),
        "a missing buffer names its file: {e}"
    );
    std::fs::write(
        dir.join("bad.gltf"),
        "{\"asset\": {\"version\": \"2.0\"},\n \"nodes\": [}",
    )
    .unwrap();
    let e = read(&dir, "bad.gltf", None).unwrap_err();
    assert!(e.contains("line 2"), "{e}");
}

/// Issue 27 §3: a weld of 1e-300 or coordinates near 1e25 saturated the weld's cell index (every
/// vertex in one cell: quadratic, and in a debug build an overflow panic). Now each reads with its
/// vertices welded exactly where they coincide; the weld's cost per vertex is tested in
/// `cnets_geometry::mesh_weld` (distance tests counted).
#[test]
fn welds_of_tiny_tolerances_and_huge_coordinates_read() {
    let dir = scratch("welds");
    // A strip of 2 000 triangles over 1 002 distinct corners, each triangle stored apart (STL).
    let n = 2_000u32;
    for (name, scale, offset, weld) in [
        ("tiny-weld.stl", 1.0, 0.0, 1e-300),
        ("huge-zero.stl", 1e24, 1e25, 0.0),
        ("huge-weld.stl", 1e24, 1e25, 1e-3),
    ] {
        let corner = |k: u32| {
            let x = f64::from(k / 2) * 1e-3;
            let y = f64::from(k % 2) * 1e-3;
            [
                (x * scale + offset) as f32,
                (y * scale + offset) as f32,
                offset as f32,
            ]
        };
        let mut binary = vec![0u8; 80];
        binary.extend_from_slice(&n.to_le_bytes());
        for t in 0..n {
            binary.extend(std::iter::repeat_n(0u8, 12));
            for k in [t, t + 1, t + 2] {
                corner(k)
                    .iter()
                    .for_each(|x| binary.extend_from_slice(&x.to_le_bytes()));
            }
            binary.extend_from_slice(&[0, 0]);
        }
        std::fs::write(dir.join(name), &binary).unwrap();
        let (mesh, _) = read(&dir, name, Some(weld)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(mesh.face_count(), n as usize, "{name}");
        assert_eq!(mesh.vertices.len(), n as usize + 2, "{name}");
    }
}
