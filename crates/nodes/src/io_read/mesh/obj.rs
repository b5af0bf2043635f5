//! OBJ meshes: `v x y z` vertices and `f i j k …` faces (1-based indices, negative ones relative to
//! the last vertex, `i/t/n` forms allowed); `o` and `g` records start a new object. Polygons stay
//! polygons. Other records (normals, texture coordinates, materials, lines) are ignored.

use cnets_engine::prelude::*;

use super::{MeshFile, MeshObject};
use crate::io_read::obj::{index, vertex};

/// Parses OBJ text into its objects (errors name the line); objects share the file's vertices in
/// the joined mesh.
pub fn parse(text: &str) -> Result<MeshFile, String> {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut objects: Vec<(String, Vec<Vec<u32>>)> = vec![(String::new(), Vec::new())];
    for (k, raw) in text.lines().enumerate() {
        let line_no = k + 1;
        let mut tokens = raw.split_whitespace();
        match tokens.next() {
            Some("v") => vertices.push(vertex(tokens, line_no)?),
            Some("f") => {
                let face = tokens
                    .map(|t| index(t, vertices.len(), line_no).map(|i| i as u32))
                    .collect::<Result<Vec<_>, _>>()?;
                if face.len() < 3 {
                    return Err(format!(
                        "line {line_no}: a face needs at least 3 vertices, got {}",
                        face.len()
                    ));
                }
                if let Some(last) = objects.last_mut() {
                    last.1.push(face);
                }
            }
            Some("o" | "g") => {
                let name = tokens.collect::<Vec<_>>().join(" ");
                match objects.last_mut() {
                    Some(last) if last.1.is_empty() => last.0 = name,
                    _ => objects.push((name, Vec::new())),
                }
            }
            _ => {}
        }
    }
    let objects: Vec<(String, Vec<Vec<u32>>)> = objects
        .into_iter()
        .filter(|(_, faces)| !faces.is_empty())
        .collect();
    let all_faces: Vec<Vec<u32>> = objects
        .iter()
        .flat_map(|(_, f)| f.iter().cloned())
        .collect();
    let compacted = |faces: &[Vec<u32>]| {
        PolygonMesh::from_faces(vertices.clone(), faces)
            .map(|m| cnets_geometry::mesh_weld::compact(&m))
            .map_err(|e| e.to_string())
    };
    let joined = compacted(&all_faces)?;
    let objects = objects
        .into_iter()
        .map(|(name, faces)| {
            Ok(MeshObject {
                name,
                mesh: compacted(&faces)?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(MeshFile { joined, objects })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objects_polygons_and_relative_indices() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\no quad\nf 1 2 3 4\no tri\nv 2 0 0\nf -4/1/1 -1 -3\n";
        let file = parse(text).unwrap();
        let objects = &file.objects;
        assert_eq!(objects.len(), 2);
        assert_eq!(file.joined.vertices.len(), 5, "shared vertices stay shared");
        assert_eq!(objects[0].name, "quad");
        assert_eq!(
            objects[0].mesh.face(0),
            &[0, 1, 2, 3],
            "a quad stays a quad"
        );
        // Only the used vertices, in file order; the face refers to them in its own order.
        assert_eq!(
            objects[1].mesh.vertices,
            vec![
                DVec3::X,
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(2.0, 0.0, 0.0)
            ]
        );
        assert_eq!(objects[1].mesh.face(0), &[0, 2, 1]);
    }

    #[test]
    fn errors_name_the_line() {
        assert!(
            parse("v 0 0 0\nv 1 0 0\nf 1 2\n")
                .unwrap_err()
                .starts_with("line 3")
        );
        assert!(parse("v 0 0 0\nf 1 2 7\n").unwrap_err().contains("line 2"));
        assert!(parse("v 0 x 0\n").unwrap_err().starts_with("line 1"));
        assert!(parse("# nothing\n").unwrap().objects.is_empty());
    }
}
