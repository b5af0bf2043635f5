//! OBJ meshes: `v x y z` vertices and `f i j k …` faces (1-based indices, negative ones relative to
//! the last vertex, `i/t/n` forms allowed); `o` and `g` records start a new object. Polygons stay
//! polygons. Other records (normals, texture coordinates, materials, lines) are ignored.

use cnets_engine::budget::Guard;
use cnets_engine::prelude::*;

use super::{MeshFile, MeshObject};
use crate::io_read::ReadError;
use crate::io_read::obj::{index, vertex};

/// Records read between two looks at the memory budget.
const CHECK_EVERY: usize = 1 << 16;

/// Bytes a record may take while the file is read: a vertex (24 bytes, and its slot in the
/// compaction tables) or a face corner (4 bytes, counted as 16 with the joined and per-object
/// copies).
const VERTEX_BYTES: u64 = 48;
const CORNER_BYTES: u64 = 16;

/// An object of the file: its name and its faces, stored flat (corner indices and face starts).
#[derive(Default)]
struct Object {
    name: String,
    indices: Vec<u32>,
    starts: Vec<u32>,
}

/// Parses OBJ text into its objects (errors name the line); objects share the file's vertices in
/// the joined mesh.
pub fn parse(text: &str) -> Result<MeshFile, ReadError> {
    parse_within(text, &mut Guard::unlimited())
}

/// [`parse`] counting what it builds against `guard` every 65 536 records: a 240 MB file of
/// faces stops at the memory budget, not at the machine's end.
pub fn parse_within(text: &str, guard: &mut Guard) -> Result<MeshFile, ReadError> {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut objects: Vec<Object> = vec![Object::default()];
    let mut corners = 0u64;
    let mut face: Vec<u32> = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line_no = k + 1;
        if k % CHECK_EVERY == CHECK_EVERY - 1 {
            guard
                .grow(
                    (vertices.len() as u64 * VERTEX_BYTES + corners * CORNER_BYTES)
                        .saturating_sub(guard.grown()),
                )
                .map_err(|e| ReadError::at(line_no, e.to_string()))?;
        }
        let mut tokens = raw.split_whitespace();
        match tokens.next() {
            Some("v") => vertices.push(vertex(tokens, line_no)?),
            Some("f") => {
                face.clear();
                for t in tokens {
                    face.push(index(t, vertices.len(), line_no)? as u32);
                }
                if face.len() < 3 {
                    return Err(ReadError::at(
                        line_no,
                        format!("a face needs at least 3 vertices, got {}", face.len()),
                    ));
                }
                if let Some(last) = objects.last_mut() {
                    last.starts.push(last.indices.len() as u32);
                    last.indices.extend_from_slice(&face);
                    corners += face.len() as u64;
                }
            }
            Some("o" | "g") => {
                let name = tokens.collect::<Vec<_>>().join(" ");
                match objects.last_mut() {
                    Some(last) if last.starts.is_empty() => last.name = name,
                    _ => objects.push(Object {
                        name,
                        ..Object::default()
                    }),
                }
            }
            _ => {}
        }
    }
    objects.retain(|o| !o.starts.is_empty());
    // The meshes made from the records: the joined one and one per object (corners, face starts
    // and at most every vertex each), beside the records themselves.
    let faces: u64 = objects.iter().map(|o| o.starts.len() as u64).sum();
    let meshes = 2 * (corners * 4 + faces * 4 + vertices.len() as u64 * 24);
    guard
        .grow(meshes + vertices.len() as u64 * 4)
        .map_err(|e| ReadError::from(e.to_string()))?;
    // One table of the used vertices' new indices, reused object by object (no copy of the file's
    // vertices per object).
    let mut slot = vec![u32::MAX; vertices.len()];
    let mut compact = |indices: &mut dyn Iterator<Item = u32>,
                       starts: &mut dyn Iterator<Item = u32>| {
        let mut mesh = PolygonMesh::new();
        let mut used: Vec<u32> = Vec::new();
        mesh.indices = indices
            .map(|v| {
                let s = &mut slot[v as usize];
                if *s == u32::MAX {
                    *s = used.len() as u32;
                    used.push(v);
                }
                *s
            })
            .collect();
        mesh.face_starts = starts.collect();
        // New indices in order of first use; the vertices keep the file's order.
        let mut order: Vec<u32> = (0..used.len() as u32).collect();
        order.sort_unstable_by_key(|&k| used[k as usize]);
        let mut renumber = vec![0u32; used.len()];
        for (new, &old_slot) in order.iter().enumerate() {
            renumber[old_slot as usize] = new as u32;
        }
        mesh.vertices = order
            .iter()
            .map(|&k| vertices[used[k as usize] as usize])
            .collect();
        for i in &mut mesh.indices {
            *i = renumber[*i as usize];
        }
        for &v in &used {
            slot[v as usize] = u32::MAX;
        }
        mesh
    };
    let joined = {
        let mut starts = Vec::new();
        let mut offset = 0u32;
        for o in &objects {
            starts.extend(o.starts.iter().map(|s| s + offset));
            offset += o.indices.len() as u32;
        }
        compact(
            &mut objects.iter().flat_map(|o| o.indices.iter().copied()),
            &mut starts.into_iter(),
        )
    };
    let objects = objects
        .into_iter()
        .map(|o| MeshObject {
            mesh: compact(&mut o.indices.into_iter(), &mut o.starts.into_iter()),
            name: o.name,
        })
        .collect();
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
        let e = parse("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
        assert_eq!(e.line, Some(3), "{e}");
        assert!(e.to_string().starts_with("line 3: a face needs"), "{e}");
        assert_eq!(parse("v 0 0 0\nf 1 2 7\n").unwrap_err().line, Some(2));
        assert_eq!(parse("v 0 x 0\n").unwrap_err().line, Some(1));
        assert!(parse("# nothing\n").unwrap().objects.is_empty());
    }
}
