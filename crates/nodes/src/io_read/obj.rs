//! OBJ polylines: `v x y z` vertices and `l i j k …` polyline records (1-based indices, negative
//! ones relative to the last vertex, `i/t` forms allowed). Each `l` record is a polyline; a record
//! that starts at the vertex where the previous record ended continues it (exporters often write a
//! polyline as a chain of two-vertex records). Faces and everything else are ignored.

use cnets_engine::prelude::*;

use super::{ReadError, tidy};

/// A 1-based (or negative, relative) OBJ vertex reference (`i`, `i/t`, `i/t/n`) as a 0-based index.
pub(crate) fn index(token: &str, vertices: usize, line_no: usize) -> Result<usize, ReadError> {
    let head = token.split('/').next().unwrap_or("");
    let i: i64 = head
        .parse()
        .map_err(|_| ReadError::at(line_no, format!("'{token}' is not a vertex index")))?;
    let n = vertices as i64;
    let resolved = if i > 0 { i - 1 } else { n + i };
    if i == 0 || !(0..n).contains(&resolved) {
        return Err(ReadError::at(
            line_no,
            format!("vertex index {i} is out of range ({vertices} vertices so far)"),
        ));
    }
    Ok(resolved as usize)
}

/// The position of a `v x y z` record (the tokens after `v`).
pub(crate) fn vertex<'a>(
    tokens: impl Iterator<Item = &'a str>,
    line_no: usize,
) -> Result<DVec3, ReadError> {
    let coords: Result<Vec<f64>, _> = tokens.take(3).map(str::parse::<f64>).collect();
    match coords.as_deref() {
        Ok([x, y, z]) if x.is_finite() && y.is_finite() && z.is_finite() => {
            Ok(DVec3::new(*x, *y, *z))
        }
        _ => Err(ReadError::at(
            line_no,
            "expected 'v x y z' with finite numbers",
        )),
    }
}

/// Parses OBJ text into polylines (and a warning when faces were skipped).
pub fn parse(text: &str) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut chains: Vec<Vec<usize>> = Vec::new();
    let mut faces = 0usize;
    for (k, raw) in text.lines().enumerate() {
        let line_no = k + 1;
        let mut tokens = raw.split_whitespace();
        match tokens.next() {
            Some("v") => vertices.push(vertex(tokens, line_no)?),
            Some("l") => {
                let ids = tokens
                    .map(|t| index(t, vertices.len(), line_no))
                    .collect::<Result<Vec<_>, _>>()?;
                if ids.len() < 2 {
                    return Err(ReadError::at(
                        line_no,
                        "an 'l' record needs at least 2 vertices",
                    ));
                }
                match chains.last_mut() {
                    Some(prev) if prev.last() == ids.first() && prev.first() != prev.last() => {
                        prev.extend_from_slice(&ids[1..]);
                    }
                    _ => chains.push(ids),
                }
            }
            Some("f") => faces += 1,
            _ => {}
        }
    }
    let curves = chains
        .into_iter()
        .map(|ids| tidy(ids.iter().map(|&i| vertices[i]).collect(), false))
        .collect();
    let warnings = if faces > 0 {
        vec![format!(
            "{faces} faces ignored (only 'l' polylines are read)"
        )]
    } else {
        Vec::new()
    };
    Ok((curves, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polylines_chains_and_closing() {
        let text = "# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2\nl 2 3\nl 3/1 4 1\nv 5 5 5\nl -1 -2\nf 1 2 3\n";
        let (ps, warnings) = parse(text).unwrap();
        assert_eq!(ps.len(), 2);
        assert!(ps[0].closed);
        assert_eq!(ps[0].points.len(), 4);
        assert_eq!(ps[1].points, vec![DVec3::splat(5.0), DVec3::Y]);
        assert_eq!(warnings.len(), 1);
    }

    #[test]
    fn errors_name_the_line() {
        assert!(
            parse("v 0 0\n")
                .unwrap_err()
                .to_string()
                .starts_with("line 1")
        );
        // The place is a field of the error, not only words.
        assert_eq!(parse("v 0 0 0\n\nl 1 9\n").unwrap_err().line, Some(3));
        assert!(
            parse("v 0 0 0\nl 1 2\n")
                .unwrap_err()
                .to_string()
                .contains("out of range")
        );
        assert!(
            parse("v 0 0 0\nl 1\n")
                .unwrap_err()
                .to_string()
                .contains("at least 2")
        );
        assert!(parse("v 0 0 0\nl 0 1\n").is_err());
        assert!(
            parse("v 0 0 0\nl a 1\n")
                .unwrap_err()
                .to_string()
                .contains("'a'")
        );
    }
}
