//! PLY meshes, ascii and binary (little and big endian), read with `ply-rs`: the `vertex` element's
//! `x`, `y`, `z` and the `face` element's `vertex_indices` (or `vertex_index`) lists.

use cnets_engine::budget::Guard;
use cnets_engine::files;
use cnets_engine::prelude::*;
use ply_rs::parser::Parser;
use ply_rs::ply::{DefaultElement, Property};

use super::MeshObject;
use crate::io_read::ReadError;

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

/// Bytes of a scalar PLY property type in a binary file (`None`: not a type).
fn type_size(name: &str) -> Option<u64> {
    Some(match name {
        "char" | "uchar" | "int8" | "uint8" => 1,
        "short" | "ushort" | "int16" | "uint16" => 2,
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => 4,
        "double" | "float64" => 8,
        _ => return None,
    })
}

/// Memory `ply-rs` takes per item of an element: its map and a slot per property.
const ITEM_BYTES: u64 = 96;
const PROPERTY_BYTES: u64 = 64;

/// Reads the header before `ply-rs` does: every element's count must be a number the rest of the
/// file can hold (each item takes at least one byte per property in binary, two in ascii), and what
/// `ply-rs` will build for them is declared to `guard`. A 242-byte file declaring 10⁹ items is an
/// error naming its line, not 3.8 GB of reservations; a count beyond 64 bits is an error, not a
/// panic inside `ply-rs`.
fn check_header(bytes: &[u8], guard: &mut Guard) -> Result<(), ReadError> {
    let end = bytes
        .windows(10)
        .position(|w| w == b"end_header")
        .ok_or("the PLY header has no end_header line")?;
    let header = String::from_utf8_lossy(&bytes[..end]);
    let data = bytes.len().saturating_sub(end + 11) as u64;
    let ascii = header.lines().any(|l| l.trim() == "format ascii 1.0");
    // (line, name, count, least bytes of an item)
    let mut elements: Vec<(usize, String, u64, u64)> = Vec::new();
    for (k, line) in header.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["element", name, count] => {
                let count: u64 = count.parse().map_err(|_| {
                    ReadError::at(
                        k + 1,
                        format!(
                            "element '{}' has the count '{}', not a whole number of at most 20 digits",
                            files::excerpt(name, 40),
                            files::excerpt(count, 40)
                        ),
                    )
                })?;
                elements.push((k + 1, name.to_string(), count, 0));
            }
            ["property", "list", count_type, _, _] => {
                if let Some(e) = elements.last_mut() {
                    e.3 += if ascii {
                        2
                    } else {
                        type_size(count_type).unwrap_or(1)
                    };
                }
            }
            ["property", ty, _] => {
                if let Some(e) = elements.last_mut() {
                    e.3 += if ascii { 2 } else { type_size(ty).unwrap_or(1) };
                }
            }
            _ => {}
        }
    }
    let mut least = 0u64;
    for (line, name, count, item) in &elements {
        let needs = count.saturating_mul((*item).max(1));
        least = least.saturating_add(needs);
        if least > data {
            return Err(ReadError::at(
                *line,
                format!(
                    "element '{}' declares {count} items, more than the file's {data} bytes of data can hold",
                    files::excerpt(name, 40)
                ),
            ));
        }
        let properties = (*item).max(1);
        guard
            .grow(count.saturating_mul(ITEM_BYTES + PROPERTY_BYTES * properties))
            .map_err(|e| ReadError::at(*line, e.to_string()))?;
    }
    Ok(())
}

/// `ply-rs`'s error as a [`ReadError`]: it writes "Line N: …" with the offending text on the
/// following lines; the line becomes the field, the rest a short excerpt.
fn ply_error(message: &str) -> ReadError {
    let mut lines = message.lines();
    let first = lines.next().unwrap_or("unreadable PLY");
    let rest: String = lines
        .map(|l| format!(" {}", l.trim()))
        .collect::<String>()
        .chars()
        .take(120)
        .collect();
    let placed = first
        .strip_prefix("Line ")
        .and_then(|r| r.split_once(": "))
        .and_then(|(n, m)| Some((n.trim().parse::<usize>().ok()?, m)));
    match placed {
        Some((line, m)) => ReadError::at(line, format!("{m}{rest}")),
        None => ReadError::from(format!("{first}{rest}")),
    }
}

/// Parses PLY bytes into one mesh object (header and ascii errors name the line).
pub fn parse(bytes: &[u8]) -> Result<Vec<MeshObject>, ReadError> {
    parse_within(bytes, &mut Guard::unlimited())
}

/// [`parse`] with the header checked against the file's size and `guard` first.
pub fn parse_within(bytes: &[u8], guard: &mut Guard) -> Result<Vec<MeshObject>, ReadError> {
    check_header(bytes, guard)?;
    let mut reader = bytes;
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut reader)
        .map_err(|e| ply_error(&e.to_string()))?;
    let vertices = ply
        .payload
        .get("vertex")
        .ok_or_else(|| ReadError::from("the PLY file has no 'vertex' element"))?;
    let mut mesh = PolygonMesh::new();
    for (k, v) in vertices.iter().enumerate() {
        let coord = |name: &str| v.get(name).and_then(number);
        match (coord("x"), coord("y"), coord("z")) {
            (Some(x), Some(y), Some(z)) if x.is_finite() && y.is_finite() && z.is_finite() => {
                mesh.push_vertex(DVec3::new(x, y, z));
            }
            _ => return Err(format!("vertex {k} has no finite x, y and z").into()),
        }
    }
    let n = mesh.vertices.len();
    for (k, f) in ply.payload.get("face").into_iter().flatten().enumerate() {
        let list = f
            .get("vertex_indices")
            .or_else(|| f.get("vertex_index"))
            .and_then(indices)
            .ok_or_else(|| ReadError::from(format!("face {k} has no vertex_indices list")))?;
        let face = list
            .iter()
            .map(|&i| {
                u32::try_from(i)
                    .ok()
                    .filter(|&i| (i as usize) < n)
                    .ok_or_else(|| {
                        ReadError::from(format!(
                            "face {k}: vertex {i} does not exist ({n} vertices)"
                        ))
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        mesh.push_face(&face)
            .map_err(|e| ReadError::from(e.to_string()))?;
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
        assert_eq!(e.line, Some(12), "{e}");
        assert!(e.to_string().starts_with("line 12: "), "{e}");
        let out_of_range = text.replace("4 0 1 2 3", "4 0 1 2 9");
        assert!(
            parse(out_of_range.as_bytes())
                .unwrap_err()
                .to_string()
                .contains("vertex 9")
        );
    }

    #[test]
    fn counts_the_file_cannot_hold_are_refused_before_ply_rs_reserves_them() {
        // The 242-byte file: an element of a billion items.
        let text = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement junk 1000000000\nproperty uchar a\nend_header\n";
        let mut bytes = text.as_bytes().to_vec();
        bytes.extend_from_slice(&[0u8; 36]);
        let e = parse(&bytes).unwrap_err();
        assert_eq!(e.line, Some(7));
        assert!(
            e.to_string()
                .starts_with("line 7: element 'junk' declares 1000000000 items"),
            "{e}"
        );
        // A count beyond 64 bits is an error, not ply-rs's panic.
        let huge = text.replace("1000000000", "99999999999999999999999");
        let e = parse(huge.as_bytes()).unwrap_err().to_string();
        assert!(e.contains("not a whole number"), "{e}");
        // A count the file holds but the budget does not.
        let ok = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
        let mut small = Guard::new(cnets_engine::MemoryBudget::new(100), 0, "reading 'x.ply'");
        assert!(
            parse_within(ok.as_bytes(), &mut small)
                .unwrap_err()
                .to_string()
                .contains("the limit is 100 bytes")
        );
    }
}
