//! CSV polylines: one point per row, `x, y` or `x, y, z` (z = 0 when absent), fields separated by
//! commas, semicolons, tabs or spaces. A blank line ends a polyline; `#` starts a comment line; a
//! first row with no number at all is a header and is skipped (a first row that mixes numbers and
//! words is an error on its own line). At most four fields of a row are looked at: a line of 3·10⁸
//! columns is an error, not 3·10⁸ fields in memory.

use cnets_engine::budget::Guard;
use cnets_engine::prelude::*;

use super::{ReadError, tidy};

/// Points read between two looks at the memory budget.
const CHECK_EVERY: usize = 1 << 16;

/// Parses CSV text into polylines; errors name the line (1-based).
pub fn parse(text: &str) -> Result<Vec<Polyline>, ReadError> {
    parse_within(text, &mut Guard::unlimited())
}

/// [`parse`] counting its points against `guard` every 65 536 points.
pub fn parse_within(text: &str, guard: &mut Guard) -> Result<Vec<Polyline>, ReadError> {
    let mut out = Vec::new();
    let mut current: Vec<DVec3> = Vec::new();
    let mut start_line = 0;
    let mut seen_data = false;
    let mut points = 0usize;
    let finish = |points: &mut Vec<DVec3>, start: usize, out: &mut Vec<Polyline>| {
        if points.is_empty() {
            return Ok(());
        }
        if points.len() < 2 {
            return Err(ReadError::at(
                start,
                "a polyline needs at least 2 points, this one has 1",
            ));
        }
        out.push(tidy(std::mem::take(points), false));
        Ok(())
    };
    for (k, raw) in text.lines().enumerate() {
        let line_no = k + 1;
        let line = raw.trim().trim_start_matches('\u{feff}');
        if line.is_empty() {
            finish(&mut current, start_line, &mut out)?;
            continue;
        }
        if line.starts_with('#') {
            continue;
        }
        // The first four fields, no more.
        let mut fields = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty());
        let first: Vec<&str> = fields.by_ref().take(4).collect();
        if first.len() > 3 {
            return Err(ReadError::at(
                line_no,
                format!(
                    "expected 2 or 3 numbers, got 4 or more fields ('{}')",
                    cnets_engine::files::excerpt(line, 40)
                ),
            ));
        }
        let parsed: Vec<Option<f64>> = first.iter().map(|f| f.parse::<f64>().ok()).collect();
        let numbers: Vec<f64> = match parsed.iter().copied().collect::<Option<Vec<f64>>>() {
            Some(n) => n,
            // A header: the first row, with no number in it.
            None if !seen_data && parsed.iter().all(Option::is_none) => {
                seen_data = true;
                continue;
            }
            None => {
                return Err(ReadError::at(
                    line_no,
                    format!(
                        "expected 2 or 3 numbers, got '{}'",
                        cnets_engine::files::excerpt(line, 40)
                    ),
                ));
            }
        };
        seen_data = true;
        let p = match numbers.as_slice() {
            [x, y] => DVec3::new(*x, *y, 0.0),
            [x, y, z] => DVec3::new(*x, *y, *z),
            _ => {
                return Err(ReadError::at(
                    line_no,
                    format!("expected 2 or 3 numbers, got {}", numbers.len()),
                ));
            }
        };
        if !p.is_finite() {
            return Err(ReadError::at(line_no, "the point is not finite"));
        }
        if current.is_empty() {
            start_line = line_no;
        }
        points += 1;
        if points.is_multiple_of(CHECK_EVERY) {
            // A point, its slot as the vector doubles and its tidied copy.
            guard
                .grow_items(CHECK_EVERY as u64, 72)
                .map_err(|e| ReadError::at(line_no, e.to_string()))?;
        }
        current.push(p);
    }
    finish(&mut current, start_line, &mut out)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_blank_lines_headers_and_comments() {
        let text = "x,y,z\n0,0,0\n1;0;0\n# comment\n1 1 0\n\n\n5\t5\n6,5\n";
        let ps = parse(text).unwrap();
        assert_eq!(ps.len(), 2);
        assert_eq!(
            ps[0].points,
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)]
        );
        assert_eq!(ps[1].points[1], DVec3::new(6.0, 5.0, 0.0));
        assert!(!ps[0].closed);
    }

    #[test]
    fn repeated_first_point_closes() {
        let ps = parse("0,0\n1,0\n1,1\n0,0\n").unwrap();
        assert!(ps[0].closed);
        assert_eq!(ps[0].points.len(), 3);
    }

    /// Issue 27 §5: the place is a field of the error, not only words.
    #[test]
    fn the_line_is_a_field_of_the_error() {
        let e = parse("x,y\n0,0\n1,a\n").unwrap_err();
        assert_eq!((e.line, e.column), (Some(3), None));
        assert_eq!(e.message, "expected 2 or 3 numbers, got '1,a'");
        let located = e.in_file("p.csv");
        assert_eq!(
            located,
            NodeError::Located {
                file: "p.csv".into(),
                line: 3,
                column: None,
                message: "expected 2 or 3 numbers, got '1,a'".into()
            }
        );
        assert_eq!(
            located.to_string(),
            "p.csv: line 3: expected 2 or 3 numbers, got '1,a'"
        );
    }

    #[test]
    fn errors_name_the_line() {
        assert!(
            parse("0,0\n1,a\n")
                .unwrap_err()
                .to_string()
                .starts_with("line 2")
        );
        assert!(
            parse("0,0,0,0\n")
                .unwrap_err()
                .to_string()
                .contains("got 4")
        );
        // A first row that mixes numbers and words is not a header: line 1 is to blame.
        assert!(
            parse("1,x,3\n0,0\n")
                .unwrap_err()
                .to_string()
                .starts_with("line 1")
        );
        assert!(parse("x,y,z\n0,0\n1,1\n").is_ok());
        // Millions of columns are an error on their line, without a field list of them.
        let wide = "1,".repeat(1_000_000);
        assert!(
            parse(&wide)
                .unwrap_err()
                .to_string()
                .starts_with("line 1: expected 2 or 3 numbers")
        );
        assert!(
            parse("0,0\n\n1,1\n")
                .unwrap_err()
                .to_string()
                .starts_with("line 1: a polyline")
        );
        assert!(
            parse("0,0\n1,1\n\n2,2\n")
                .unwrap_err()
                .to_string()
                .starts_with("line 4")
        );
        assert!(
            parse("0,0\nnan,1\n")
                .unwrap_err()
                .to_string()
                .contains("not finite")
        );
        assert!(parse("").unwrap().is_empty());
    }
}
