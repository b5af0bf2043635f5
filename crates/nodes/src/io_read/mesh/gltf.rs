//! glTF 2.0 meshes (`.gltf` with its buffers, or one `.glb`), read with the `gltf` crate: every
//! triangle primitive of every mesh a scene node shows, with the node's transforms applied, in
//! scene order (or every mesh as it is, when the file has no scene). Strips and fans become
//! triangles; points and lines are skipped with a warning.

use std::borrow::Cow;

use base64::Engine as _;
use cnets_engine::budget::Guard;
use cnets_engine::prelude::*;
use glam::DMat4;
use gltf::mesh::Mode;

use super::MeshObject;
use crate::io_read::ReadError;

/// Reads a buffer the file refers to by a relative name.
pub type ExternalReader<'a> = dyn Fn(&str) -> Result<Vec<u8>, String> + 'a;

/// The buffers' bytes: the GLB chunk is borrowed however many buffers name it (a file of 1 000
/// buffers all naming a 10 MB chunk holds it once), a data URI is declared to `guard` before it is
/// decoded.
fn buffers<'d>(
    doc: &'d gltf::Gltf,
    external: &ExternalReader<'_>,
    guard: &mut Guard,
) -> Result<Vec<Cow<'d, [u8]>>, String> {
    doc.buffers()
        .map(|buffer| {
            let data: Cow<'d, [u8]> = match buffer.source() {
                gltf::buffer::Source::Bin => {
                    Cow::Borrowed(doc.blob.as_deref().ok_or_else(|| {
                        format!(
                            "buffer {} refers to a GLB chunk the file does not have",
                            buffer.index()
                        )
                    })?)
                }
                gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                    let (_, payload) = uri.split_once(";base64,").ok_or_else(|| {
                        format!("buffer {}: only base64 data URIs are read", buffer.index())
                    })?;
                    guard
                        .grow(payload.len() as u64 / 4 * 3)
                        .map_err(|e| format!("buffer {}: {e}", buffer.index()))?;
                    Cow::Owned(
                        base64::engine::general_purpose::STANDARD
                            .decode(payload)
                            .map_err(|e| {
                                format!("buffer {}: bad base64 data: {e}", buffer.index())
                            })?,
                    )
                }
                gltf::buffer::Source::Uri(uri) => Cow::Owned(external(uri)?),
            };
            if data.len() < buffer.length() {
                return Err(format!(
                    "buffer {} holds {} bytes, the file says {}",
                    buffer.index(),
                    data.len(),
                    buffer.length()
                ));
            }
            Ok(data)
        })
        .collect()
}

/// Checks that an accessor's elements lie inside its buffer view and its view inside its buffer,
/// with a stride at least one element wide: the `gltf` crate's reader asserts (panics) or reads
/// nothing otherwise. The error names the accessor and what does not fit.
fn check_accessor(
    accessor: &gltf::Accessor<'_>,
    data: &[Cow<'_, [u8]>],
    what: &str,
) -> Result<(), String> {
    let name = format!("{what}: accessor {}", accessor.index());
    if accessor.sparse().is_some() {
        return Err(format!("{name} is sparse, which is not read"));
    }
    let Some(view) = accessor.view() else {
        return Err(format!("{name} has no buffer view"));
    };
    let buffer = data
        .get(view.buffer().index())
        .ok_or_else(|| format!("{name}: buffer {} does not exist", view.buffer().index()))?;
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > buffer.len()) {
        return Err(format!(
            "{name}: buffer view {} (offset {}, length {}) runs past the end of buffer {} ({} bytes)",
            view.index(),
            view.offset(),
            view.length(),
            view.buffer().index(),
            buffer.len()
        ));
    }
    let size = accessor.size();
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "{name}: byteStride {stride} is smaller than an element ({size} bytes)"
        ));
    }
    let count = accessor.count();
    if count > 0 {
        let last = (count - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(accessor.offset()))
            .and_then(|x| x.checked_add(size));
        if last.is_none_or(|end| end > view.length()) {
            return Err(format!(
                "{name}: {count} elements from offset {} (stride {stride}) run past the end of buffer view {} ({} bytes)",
                accessor.offset(),
                view.index(),
                view.length()
            ));
        }
    }
    Ok(())
}

fn primitive_mesh(
    primitive: &gltf::Primitive<'_>,
    data: &[Cow<'_, [u8]>],
    transform: &DMat4,
    warnings: &mut Vec<String>,
    what: &str,
    guard: &mut Guard,
) -> Result<Option<PolygonMesh>, String> {
    let Some(positions) = primitive.get(&gltf::Semantic::Positions) else {
        warnings.push(format!("{what} has no positions: skipped"));
        return Ok(None);
    };
    check_accessor(&positions, data, what)?;
    let indices = primitive.indices();
    if let Some(indices) = &indices {
        check_accessor(indices, data, what)?;
    }
    // Every instance is made anew (a node listing the same child 99 990 times makes it 99 990
    // times): declared before it is read. A vertex is 24 bytes, a corner 4 and its face start 4,
    // each twice (the object and the joined mesh).
    let corners = indices.as_ref().map_or(positions.count(), |i| i.count()) as u64;
    guard
        .grow(
            (positions.count() as u64)
                .saturating_mul(48)
                .saturating_add(corners.saturating_mul(24)),
        )
        .map_err(|e| format!("{what}: {e}"))?;
    let reader = primitive.reader(|b| data.get(b.index()).map(|d| &**d));
    let Some(positions) = reader.read_positions() else {
        warnings.push(format!("{what} has no positions: skipped"));
        return Ok(None);
    };
    let vertices: Vec<DVec3> = positions
        .map(|p| {
            transform.transform_point3(DVec3::new(
                f64::from(p[0]),
                f64::from(p[1]),
                f64::from(p[2]),
            ))
        })
        .collect();
    if let Some(k) = vertices.iter().position(|p| !p.is_finite()) {
        return Err(format!("{what}: position {k} is not finite"));
    }
    let indices: Vec<u32> = match reader.read_indices() {
        Some(i) => i.into_u32().collect(),
        None => (0..vertices.len() as u32).collect(),
    };
    let triangles: Vec<[u32; 3]> = match primitive.mode() {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        Mode::TriangleStrip => (2..indices.len())
            .map(|k| {
                if k % 2 == 0 {
                    [indices[k - 2], indices[k - 1], indices[k]]
                } else {
                    [indices[k - 1], indices[k - 2], indices[k]]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..indices.len())
            .map(|k| [indices[0], indices[k - 1], indices[k]])
            .collect(),
        other => {
            warnings.push(format!("{what} draws {other:?}, not triangles: skipped"));
            return Ok(None);
        }
    };
    let mut mesh = PolygonMesh {
        vertices,
        ..PolygonMesh::default()
    };
    for (k, t) in triangles.iter().enumerate() {
        mesh.push_face(t)
            .map_err(|e| format!("{what}: triangle {k}: {e}"))?;
    }
    // Front faces stay front faces under a mirroring node transform.
    if transform.determinant() < 0.0 {
        let faces: Vec<Vec<u32>> = mesh
            .faces()
            .map(|f| f.iter().rev().copied().collect())
            .collect();
        mesh = PolygonMesh::from_faces(mesh.vertices.clone(), &faces).map_err(|e| e.to_string())?;
    }
    Ok(Some(mesh))
}

fn mesh_objects(
    mesh: &gltf::Mesh<'_>,
    data: &[Cow<'_, [u8]>],
    transform: &DMat4,
    out: &mut Vec<MeshObject>,
    warnings: &mut Vec<String>,
    guard: &mut Guard,
) -> Result<(), String> {
    let name = mesh.name().unwrap_or("").to_string();
    for primitive in mesh.primitives() {
        let what = format!("mesh {} primitive {}", mesh.index(), primitive.index());
        if let Some(m) = primitive_mesh(&primitive, data, transform, warnings, &what, guard)? {
            out.push(MeshObject {
                name: name.clone(),
                mesh: m,
            });
        }
    }
    Ok(())
}

/// Depth of the node hierarchy followed (deeper nodes are reported, not followed).
const MAX_NODE_DEPTH: usize = 64;
/// Most node visits (a hostile file can make its hierarchy a graph with shared children).
const MAX_NODE_VISITS: usize = 100_000;

/// Parses glTF or GLB bytes into one object per primitive.
pub fn parse(
    bytes: &[u8],
    external: &ExternalReader<'_>,
) -> Result<(Vec<MeshObject>, Vec<String>), ReadError> {
    parse_within(bytes, external, &mut Guard::unlimited())
}

/// [`parse`] declaring every buffer it decodes and every primitive instance it makes to `guard`.
pub fn parse_within(
    bytes: &[u8],
    external: &ExternalReader<'_>,
    guard: &mut Guard,
) -> Result<(Vec<MeshObject>, Vec<String>), ReadError> {
    let doc = gltf::Gltf::from_slice(bytes).map_err(|e| match e {
        // A JSON error of a `.gltf` (or of a GLB's JSON chunk) has its line and column.
        gltf::Error::Deserialize(j) if j.line() > 0 => {
            let message = j.to_string();
            let message = message
                .rsplit_once(" at line ")
                .map_or(message.as_str(), |(m, _)| m);
            ReadError::at_column(j.line(), j.column().max(1), message.to_string())
        }
        other => ReadError::from(other.to_string()),
    })?;
    primitives(&doc, external, guard).map_err(ReadError::from)
}

/// The objects of a parsed document (see [`parse`]).
fn primitives(
    doc: &gltf::Gltf,
    external: &ExternalReader<'_>,
    guard: &mut Guard,
) -> Result<(Vec<MeshObject>, Vec<String>), String> {
    let data = buffers(doc, external, guard)?;
    let mut out = Vec::new();
    let mut warnings = Vec::new();
    let scene = doc.default_scene().or_else(|| doc.scenes().next());
    match scene {
        Some(scene) => {
            let mut stack: Vec<(gltf::Node<'_>, DMat4, usize)> =
                scene.nodes().map(|n| (n, DMat4::IDENTITY, 0)).collect();
            stack.reverse();
            let mut visits = 0usize;
            while let Some((node, parent, depth)) = stack.pop() {
                visits += 1;
                if visits > MAX_NODE_VISITS {
                    return Err(format!(
                        "the scene shows more than {MAX_NODE_VISITS} nodes (a node hierarchy that repeats itself?)"
                    ));
                }
                let local =
                    DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
                let world = parent * local;
                if let Some(mesh) = node.mesh() {
                    mesh_objects(&mesh, &data, &world, &mut out, &mut warnings, guard)?;
                }
                if depth >= MAX_NODE_DEPTH {
                    warnings.push(format!("node {} nests deeper than {MAX_NODE_DEPTH} levels: its children are skipped", node.index()));
                    continue;
                }
                let first_child = stack.len();
                stack.extend(node.children().map(|c| (c, world, depth + 1)));
                stack[first_child..].reverse();
            }
        }
        None => {
            for mesh in doc.meshes() {
                mesh_objects(
                    &mesh,
                    &data,
                    &DMat4::IDENTITY,
                    &mut out,
                    &mut warnings,
                    guard,
                )?;
            }
        }
    }
    Ok((out, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A glTF of one triangle whose position accessor and view are given as JSON.
    fn document(accessor: &str, view: &str) -> String {
        let floats: Vec<u8> = [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let uri = format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&floats)
        );
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": 36, "uri": "{uri}"}}],
"bufferViews": [{view}], "accessors": [{accessor}],
"meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}]}}"#
        )
    }

    fn read(text: &str) -> Result<Vec<MeshObject>, ReadError> {
        parse(text.as_bytes(), &|_| Err("no files".into())).map(|(o, _)| o)
    }

    #[test]
    fn a_json_error_has_its_place_as_fields() {
        let e = read("{\n  \"asset\": {\"version\": \"2.0\"},\n  \"buffers\": [,]\n}").unwrap_err();
        assert_eq!(e.line, Some(3), "{e}");
        assert!(e.column.is_some(), "{e}");
        assert!(!e.message.contains(" at line "), "{e}");
    }

    #[test]
    fn a_well_formed_triangle_reads() {
        let text = document(
            r#"{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#,
            r#"{"buffer": 0, "byteLength": 36}"#,
        );
        assert_eq!(read(&text).unwrap()[0].mesh.face_count(), 1);
    }

    #[test]
    fn strides_counts_and_offsets_outside_the_buffer_are_named() {
        let cases = [
            // A stride of 4 bytes for 12-byte elements (the gltf crate's assertion).
            (
                r#"{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#,
                r#"{"buffer": 0, "byteLength": 36, "byteStride": 4}"#,
                "byteStride 4 is smaller than an element (12 bytes)",
            ),
            // A count far beyond the view.
            (
                r#"{"bufferView": 0, "componentType": 5126, "count": 1000000000, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#,
                r#"{"buffer": 0, "byteLength": 36}"#,
                "1000000000 elements from offset 0 (stride 12) run past the end of buffer view 0",
            ),
            // An offset beyond the view.
            (
                r#"{"bufferView": 0, "byteOffset": 4000, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#,
                r#"{"buffer": 0, "byteLength": 36}"#,
                "run past the end of buffer view 0",
            ),
            // A view beyond the buffer.
            (
                r#"{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}"#,
                r#"{"buffer": 0, "byteOffset": 18446744073709551000, "byteLength": 36}"#,
                "",
            ),
        ];
        for (accessor, view, expected) in cases {
            let e = read(&document(accessor, view)).unwrap_err().to_string();
            assert!(e.contains(expected), "{e}");
            assert!(!e.contains("no faces"), "{e}");
        }
    }
}
