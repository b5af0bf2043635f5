//! OBJ export: read back with `tobj` (faces stay quads: arity 4, never triangulated) and with a small
//! independent reader (exact f64 coordinates, `l` lines for line sets and polylines).

use crate::fab_support;

use cnets_engine::Value;
use cnets_geometry::fabrication::{cut_by_plane, torsion_free_axes};
use cnets_geometry::{DVec3, Plane, PolygonMesh, Polyline};
use fab_support::*;

/// One OBJ object: name, faces and lines (0-based global vertex indices).
type Object = (String, Vec<Vec<usize>>, Vec<Vec<usize>>);

/// A minimal OBJ reader: objects with their vertices, faces and lines (1-based global indices).
#[derive(Default, Debug)]
struct Obj {
    vertices: Vec<DVec3>,
    objects: Vec<Object>,
}

fn read_obj(text: &str) -> Obj {
    let mut obj = Obj::default();
    for line in text.lines() {
        let mut parts = line.split_whitespace();
        let index = |s: &str| s.parse::<usize>().expect("index") - 1;
        match parts.next() {
            Some("o") => obj
                .objects
                .push((parts.next().unwrap().to_string(), vec![], vec![])),
            Some("v") => {
                let c: Vec<f64> = parts.map(|x| x.parse().expect("coordinate")).collect();
                assert_eq!(c.len(), 3);
                obj.vertices.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => obj
                .objects
                .last_mut()
                .unwrap()
                .1
                .push(parts.map(index).collect()),
            Some("l") => obj
                .objects
                .last_mut()
                .unwrap()
                .2
                .push(parts.map(index).collect()),
            Some(c) if c.starts_with('#') => {}
            None => {}
            Some(other) => panic!("unexpected OBJ element {other}"),
        }
    }
    obj
}

#[test]
fn quads_stay_quads_and_lines_are_l_elements() {
    let net = cone_net(4, 6, false);
    let quads = PolygonMesh::from(&net.mesh);
    // A cut mesh has pentagons and triangles: they are written as they are.
    let plane = Plane::from_normal(DVec3::new(2.5, 0.0, 0.3), DVec3::new(1.0, 0.8, 0.6)).unwrap();
    let cut = cut_by_plane(&quads, &plane, true).unwrap().mesh;
    let axes = torsion_free_axes(&directrix(6), &net.mesh).unwrap();
    let closed = Polyline::closed(vec![DVec3::ZERO, DVec3::X, DVec3::new(0.1, 0.7, 1e-7)]);
    let dir = scratch("obj");
    let ctx = ctx_in(&dir);
    let out = run(
        &ctx,
        "io.export_obj",
        &[
            ("name", Value::text("parts/net.obj")),
            (
                "meshes",
                Value::list(vec![quads.clone().into(), cut.clone().into()]),
            ),
            ("lines", Value::Lines(std::sync::Arc::new(axes.clone()))),
            ("polylines", closed.clone().into()),
        ],
    )
    .unwrap();
    let Value::Text(path) = get(&out, "path") else {
        panic!("path")
    };
    assert!(path.ends_with("parts/net.obj"));
    let text = std::fs::read_to_string(path.as_ref()).unwrap();

    // tobj: faces are not triangulated.
    let (models, _) = tobj::load_obj_buf(
        &mut std::io::BufReader::new(text.as_bytes()),
        &tobj::LoadOptions {
            triangulate: false,
            single_index: false,
            ..Default::default()
        },
        |_| Ok(Default::default()),
    )
    .expect("tobj reads the file");
    let first = models.iter().find(|m| m.name == "mesh_0").expect("mesh_0");
    assert_eq!(first.mesh.face_arities.len(), quads.face_count());
    assert!(first.mesh.face_arities.iter().all(|&a| a == 4));
    // tobj renumbers each object's vertices; compare the corners face by face.
    assert_eq!(first.mesh.indices.len(), 4 * quads.face_count());
    for (f, face) in quads.faces().enumerate() {
        for (c, &v) in face.iter().enumerate() {
            let k = first.mesh.indices[4 * f + c] as usize;
            let q = &first.mesh.positions[3 * k..3 * k + 3];
            let p = quads.vertices[v as usize];
            assert!((DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64) - p).length() < 1e-5);
        }
    }
    let second = models.iter().find(|m| m.name == "mesh_1").expect("mesh_1");
    let arities: Vec<u32> = cut.faces().map(|f| f.len() as u32).collect();
    assert_eq!(second.mesh.face_arities, arities);
    assert!(arities.iter().any(|&a| a != 4));

    // The exact reader: every coordinate and index as written.
    let obj = read_obj(&text);
    let names: Vec<&str> = obj.objects.iter().map(|o| o.0.as_str()).collect();
    assert_eq!(names, ["mesh_0", "mesh_1", "lines_0", "polyline_0"]);
    assert_eq!(&obj.vertices[..quads.vertices.len()], &quads.vertices[..]);
    for (f, face) in quads.faces().enumerate() {
        let want: Vec<usize> = face.iter().map(|&v| v as usize).collect();
        assert_eq!(obj.objects[0].1[f], want);
    }
    let offset = quads.vertices.len();
    for (f, face) in cut.faces().enumerate() {
        let got: Vec<DVec3> = obj.objects[1].1[f]
            .iter()
            .map(|&v| obj.vertices[v])
            .collect();
        let want: Vec<DVec3> = face.iter().map(|&v| cut.vertices[v as usize]).collect();
        assert_eq!(got, want);
        assert!(obj.objects[1].1[f].iter().all(|&v| v >= offset));
    }
    let lines = &obj.objects[2].2;
    assert_eq!(lines.len(), axes.len());
    for (l, a) in lines.iter().zip(&axes) {
        assert_eq!(l.len(), 2);
        assert_eq!((obj.vertices[l[0]], obj.vertices[l[1]]), (a.start, a.end));
    }
    let poly = &obj.objects[3].2;
    assert_eq!(poly.len(), 1);
    assert_eq!(
        poly[0].len(),
        4,
        "a closed polyline repeats its first index"
    );
    assert_eq!(poly[0][0], poly[0][3]);
    assert_eq!(obj.vertices[poly[0][2]], closed.points[2]);
    std::fs::remove_dir_all(&dir).unwrap();
}
