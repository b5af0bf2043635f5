//! STL meshes, ascii and binary, read with `stl_io`. STL stores every triangle's corners on their
//! own (in single precision); `stl_io` shares exactly equal corners, and `weld` merges near ones.

use std::io::Cursor;

use cnets_engine::prelude::*;

use super::MeshObject;
use crate::io_read::ReadError;

/// Size of a binary STL header plus its triangle count, and of one triangle record.
const BINARY_HEADER: usize = 84;
const BINARY_TRIANGLE: usize = 50;

/// True when the bytes start like an ascii STL (`solid` and a `facet` soon after): binary files
/// may also start with "solid" in their 80-byte header.
fn is_ascii(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(512)];
    let text = String::from_utf8_lossy(head);
    text.trim_start().starts_with("solid")
        && (text.contains("facet") || text.contains("endsolid"))
        && !bytes_are_binary_sized(bytes)
}

fn bytes_are_binary_sized(bytes: &[u8]) -> bool {
    bytes.len() >= BINARY_HEADER && {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        bytes.len() == BINARY_HEADER + count * BINARY_TRIANGLE
    }
}

/// True when a line is a well-formed ascii STL record.
fn is_stl_line(line: &str) -> bool {
    let mut tokens = line.split_whitespace();
    let numbers = |t: std::str::SplitWhitespace<'_>| {
        let v: Vec<&str> = t.collect();
        v.len() == 3 && v.iter().all(|x| x.parse::<f32>().is_ok())
    };
    match tokens.next() {
        None | Some("solid" | "endsolid" | "endloop" | "endfacet") => true,
        Some("outer") => tokens.next() == Some("loop"),
        Some("facet") => tokens.next() == Some("normal") && numbers(tokens),
        Some("vertex") => numbers(tokens),
        _ => false,
    }
}

/// The 1-based line an ascii STL error is on: the first malformed line of the `k`-th facet (0-based)
/// or, when all its lines look right, the facet's first line.
fn facet_line(text: &str, k: usize) -> usize {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with("facet"))
        .nth(k)
        .map_or(lines.len().saturating_sub(1), |(n, _)| n);
    let end = lines[start..]
        .iter()
        .position(|l| l.trim_start().starts_with("endfacet"))
        .map_or(lines.len(), |d| start + d + 1);
    (start..end)
        .find(|&n| !is_stl_line(lines[n]))
        .unwrap_or(start)
        + 1
}

/// Parses STL bytes (ascii or binary) into one mesh object.
pub fn parse(bytes: &[u8]) -> Result<Vec<MeshObject>, ReadError> {
    let ascii = is_ascii(bytes);
    if !ascii {
        if bytes.len() < BINARY_HEADER {
            return Err(format!(
                "not an STL file: {} bytes, shorter than a binary STL header (84 bytes) and not ascii",
                bytes.len()
            )
            .into());
        }
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        let needed = BINARY_HEADER as u128 + count as u128 * BINARY_TRIANGLE as u128;
        if (bytes.len() as u128) < needed {
            return Err(format!(
                "binary STL: the header at byte 80 declares {count} triangles ({needed} bytes), but the file has {} bytes",
                bytes.len()
            )
            .into());
        }
    }
    let mut cursor = Cursor::new(bytes);
    let reader =
        stl_io::create_stl_reader(&mut cursor).map_err(|e| ReadError::at(1, e.to_string()))?;
    let mut mesh = PolygonMesh::new();
    let mut shared: std::collections::HashMap<[u32; 3], u32> = std::collections::HashMap::new();
    for (k, triangle) in reader.enumerate() {
        let triangle = triangle.map_err(|e| {
            if ascii {
                let text = String::from_utf8_lossy(bytes);
                ReadError::at(facet_line(&text, k), format!("facet {k}: {e}"))
            } else {
                ReadError::from(format!(
                    "byte {} (triangle {k}): {e}",
                    BINARY_HEADER + k * BINARY_TRIANGLE
                ))
            }
        })?;
        let mut corners = [0u32; 3];
        for (c, v) in triangle.vertices.iter().enumerate() {
            let p = [v[0], v[1], v[2]];
            if !p.iter().all(|x| x.is_finite()) {
                return Err(format!("triangle {k}: corner {c} is not finite").into());
            }
            let key = p.map(f32::to_bits);
            corners[c] = *shared.entry(key).or_insert_with(|| {
                mesh.push_vertex(DVec3::new(
                    f64::from(p[0]),
                    f64::from(p[1]),
                    f64::from(p[2]),
                ))
            });
        }
        if corners[0] != corners[1] && corners[1] != corners[2] && corners[2] != corners[0] {
            mesh.push_face(&corners)
                .map_err(|e| ReadError::from(e.to_string()))?;
        }
    }
    Ok(vec![MeshObject {
        name: String::new(),
        mesh,
    }])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_errors_name_the_line_and_binary_ones_the_byte() {
        let good = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        let objects = parse(good.as_bytes()).unwrap();
        assert_eq!(objects[0].mesh.face_count(), 1);
        let bad = good.replace("vertex 1 0 0", "vertex 1 zero 0");
        let e = parse(bad.as_bytes()).unwrap_err();
        assert_eq!((e.line, e.column), (Some(5), None), "{e}");
        assert!(e.to_string().starts_with("line 5: facet 0: "), "{e}");
        let mut binary = vec![0u8; 84];
        binary[80] = 200;
        let e = parse(&binary).unwrap_err().to_string();
        assert!(e.contains("declares 200 triangles"), "{e}");
        assert!(
            parse(b"abc")
                .unwrap_err()
                .to_string()
                .contains("not an STL")
        );
    }
}
