//! PLY meshes, ascii and binary (little and big endian), read with `ply-rs`: the `vertex` element's
//! `x`, `y`, `z` and the `face` element's `vertex_indices` (or `vertex_index`) lists.

use cnets_engine::prelude::*;
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, Property};

use super::MeshObject;

fn number(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(x) => f64::from(x),
        Property::UChar(x) => f64::from(x),
        Property::Short(x) => f64::from(x),
        Property::UShort(x) => f64::from(x),
        Property::Int(x) => f64::from(x),
        Property::UInt(x) => f64::from(x),
        Property::Float(x) => f64::from(x),
        Property::Double(x) => x,
        _ => return None,
    })
}

fn indices(p: &Property) -> Option<Vec<i64>> {
    Some(match p {
        Property::ListChar(v) => v.iter().map(|&i| i64::from(i)).collect(),
        Property::ListUChar(v) => v.iter().map(|&i| i64::from(i)).collect(),
        Property::ListShort(v) => v.iter().map(|&i| i64::from(i)).collect(),
        Property::ListUShort(v) => v.iter().map(|&i| i64::from(i)).collect(),
        Property::ListInt(v) => v.iter().map(|&i| i64::from(i)).collect(),
        Property::ListUInt(v) => v.iter().map(|&i| i64::from(i)).collect(),
        _ => return None,
    })
}

/// Parses PLY bytes into one mesh object (header and ascii errors name the line).
pub fn parse(bytes: &[u8]) -> Result<Vec<MeshObject>, String> {
    let mut reader = bytes;
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut reader)
        .map_err(|e| {
            let message = e.to_string();
            // ply-rs writes "Line N: …" with the offending text on the following lines.
            message
                .lines()
                .next()
                .unwrap_or("unreadable PLY")
                .replace("Line", "line")
                .to_string()
                + &message
                    .lines()
                    .skip(1)
                    .map(|l| format!(" {}", l.trim()))
                    .collect::<String>()
                    .chars()
                    .take(120)
                    .collect::<String>()
        })?;
    let vertices = ply
        .payload
        .get("vertex")
        .ok_or("the PLY file has no 'vertex' element")?;
    let mut mesh = PolygonMesh::new();
    for (k, v) in vertices.iter().enumerate() {
        let coord = |name: &str| v.get(name).and_then(number);
        match (coord("x"), coord("y"), coord("z")) {
            (Some(x), Some(y), Some(z)) if x.is_finite() && y.is_finite() && z.is_finite() => {
                mesh.push_vertex(DVec3::new(x, y, z));
            }
            _ => return Err(format!("vertex {k} has no finite x, y and z")),
        }
    }
    let n = mesh.vertices.len();
    for (k, f) in ply.payload.get("face").into_iter().flatten().enumerate() {
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .and_then(indices)
            .ok_or_else(|| format!("face {k} has no vertex_indices list"))?;
        let face = list
            .iter()
            .map(|&i| {
                u32::try_from(i)
                    .ok()
                    .filter(|&i| (i as usize) < n)
                    .ok_or_else(|| format!("face {k}: vertex {i} does not exist ({n} vertices)"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        mesh.push_face(&face).map_err(|e| e.to_string())?;
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
    fn ascii_ply_reads_and_errors_name_the_line() {
        let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
        let objects = parse(text.as_bytes()).unwrap();
        assert_eq!(objects[0].mesh.face(0), &[0, 1, 2, 3]);
        let bad = text.replace("1 1 0\n", "1 one 0\n");
        let e = parse(bad.as_bytes()).unwrap_err();
        assert!(e.starts_with("line"), "{e}");
        let out_of_range = text.replace("4 0 1 2 3", "4 0 1 2 9");
        assert!(
            parse(out_of_range.as_bytes())
                .unwrap_err()
                .contains("vertex 9")
        );
    }
}
