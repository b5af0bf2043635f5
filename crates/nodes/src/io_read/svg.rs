//! SVG polylines: `<polyline>`, `<polygon>` (closed), `<line>` and `<path>` elements, in document
//! order. Path data supports every command, absolute and relative: M, L, H, V, Z move and draw
//! straight; C, S (cubic), Q, T (quadratic) and A (elliptical arc) are flattened into `segments`
//! points each. Each subpath is one polyline; Z closes it. Coordinates are user units with the y
//! axis flipped (x, y) ↦ (x, −y, 0), so a drawing looks the same way up as in the SVG viewer.
//! `transform` attributes are not applied (a warning says so); other elements are ignored.
//!
//! The XML is parsed by `roxmltree` (a maintained, dependency-free, non-recursive parser with entity
//! loop and billion-laughs protection: hostile files end in a clear error with their line); the
//! Bézier and arc maths is `cnets_geometry::curves::flatten`. Only the path-data syntax is read here.

use cnets_engine::budget::Guard;
use cnets_engine::prelude::*;
use cnets_geometry::curves::flatten::{elliptical_arc, flatten_cubic, flatten_quadratic};
use glam::DVec2;

use super::{ReadError, tidy};

/// The most undeclared namespace prefixes the reader declares on the fly (see [`declare`]).
const MAX_PREFIXES: usize = 16;

/// The most XML nodes (elements, text, comments) a document may have: far above any drawing, it stops
/// a hostile file before it eats the memory.
const MAX_NODES: u32 = 5_000_000;

/// Parses the XML with `roxmltree` (DTDs allowed, as older exporters write them; entity loops and
/// billion laughs are refused by the parser; external entities are not fetched).
fn document(text: &str) -> Result<roxmltree::Document<'_>, roxmltree::Error> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_NODES,
        ..roxmltree::ParsingOptions::default()
    };
    roxmltree::Document::parse_with_options(text, options)
}

/// `text` with `xmlns:{prefix}` declared on its root element. Hand-written SVG often uses a prefix
/// (`svg:`, `xlink:`) it never declares; the element names are read without prefix anyway. The
/// declaration goes right after the root element's name, on its line, so line numbers stay. `None`
/// when no root start tag is found.
fn declare(text: &str, prefix: &str) -> Option<String> {
    let mut i = 0;
    loop {
        let rest = &text[i..];
        let skip = rest.len()
            - rest
                .trim_start_matches(|c: char| c.is_whitespace() || c == '\u{feff}')
                .len();
        i += skip;
        let rest = &text[i..];
        if rest.starts_with("<?") {
            i += rest.find("?>")? + 2;
        } else if rest.starts_with("<!--") {
            i += rest.find("-->")? + 3;
        } else if rest.starts_with("<!") {
            // A doctype, possibly with an internal subset in brackets.
            let close = match (rest.find('['), rest.find('>')) {
                (Some(open), Some(gt)) if open < gt => {
                    let end = rest[open..].find(']')? + open;
                    end + rest[end..].find('>')?
                }
                (_, gt) => gt?,
            };
            i += close + 1;
        } else if let Some(tag) = rest.strip_prefix('<') {
            let name = tag
                .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
                .map_or(rest.len(), |n| n + 1);
            let at = i + name;
            return Some(format!(
                "{} xmlns:{prefix}=\"urn:cnets:undeclared:{prefix}\"{}",
                &text[..at],
                &text[at..]
            ));
        } else {
            return None;
        }
    }
}

/// The reader's message for an XML error: its line (and column), what is wrong.
fn xml_error(text: &str, e: &roxmltree::Error) -> ReadError {
    match e {
        roxmltree::Error::UnexpectedEndOfStream => {
            let line = text.bytes().filter(|&b| b == b'\n').count() + 1;
            ReadError::at(
                line,
                "the document ends early (an unterminated tag, value or element)",
            )
        }
        roxmltree::Error::NodesLimitReached => {
            format!("the document has more than {MAX_NODES} XML nodes").into()
        }
        roxmltree::Error::InvalidString(end @ ("-->" | "]]>" | "?>"), p) => {
            let what = match *end {
                "-->" => "comment",
                "]]>" => "CDATA section",
                _ => "processing instruction",
            };
            ReadError::at(p.row as usize, format!("unterminated {what}"))
        }
        e => {
            let p = e.pos();
            // roxmltree's message ends with the position, which leads here.
            let message = e.to_string();
            let suffix = format!(" at {}:{}", p.row, p.col);
            let message = message.strip_suffix(&suffix).unwrap_or(&message);
            ReadError::at_column(
                p.row as usize,
                p.col as usize,
                format!("malformed XML: {message}"),
            )
        }
    }
}

/// A cursor over path data or a points list: numbers, flags and command letters.
struct Lexer<'a> {
    s: &'a [u8],
    i: usize,
}

impl Lexer<'_> {
    fn skip_separators(&mut self) {
        while self.i < self.s.len()
            && (self.s[self.i].is_ascii_whitespace() || self.s[self.i] == b',')
        {
            self.i += 1;
        }
    }

    fn at_end(&mut self) -> bool {
        self.skip_separators();
        self.i >= self.s.len()
    }

    /// The next command letter, if the next token is one (consumed).
    fn command(&mut self) -> Option<u8> {
        self.skip_separators();
        let c = *self.s.get(self.i)?;
        if c.is_ascii_alphabetic() && c != b'e' && c != b'E' {
            self.i += 1;
            Some(c)
        } else {
            None
        }
    }

    /// True when a number starts here.
    fn number_next(&mut self) -> bool {
        self.skip_separators();
        self.s
            .get(self.i)
            .is_some_and(|c| c.is_ascii_digit() || matches!(c, b'-' | b'+' | b'.'))
    }

    fn number(&mut self) -> Result<f64, String> {
        self.skip_separators();
        let start = self.i;
        let s = self.s;
        let mut j = self.i;
        if j < s.len() && matches!(s[j], b'-' | b'+') {
            j += 1;
        }
        let mut digits = 0;
        while j < s.len() && s[j].is_ascii_digit() {
            j += 1;
            digits += 1;
        }
        if j < s.len() && s[j] == b'.' {
            j += 1;
            while j < s.len() && s[j].is_ascii_digit() {
                j += 1;
                digits += 1;
            }
        }
        if digits == 0 {
            return Err(format!("expected a number at character {}", start + 1));
        }
        if j < s.len() && matches!(s[j], b'e' | b'E') {
            let mut k = j + 1;
            if k < s.len() && matches!(s[k], b'-' | b'+') {
                k += 1;
            }
            if k < s.len() && s[k].is_ascii_digit() {
                while k < s.len() && s[k].is_ascii_digit() {
                    k += 1;
                }
                j = k;
            }
        }
        self.i = j;
        let text = std::str::from_utf8(&s[start..j]).map_err(|e| e.to_string())?;
        let x: f64 = text
            .parse()
            .map_err(|_| format!("'{text}' is not a number"))?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!("'{text}' is not a finite number"))
        }
    }

    fn flag(&mut self) -> Result<bool, String> {
        self.skip_separators();
        match self.s.get(self.i) {
            Some(b'0') => {
                self.i += 1;
                Ok(false)
            }
            Some(b'1') => {
                self.i += 1;
                Ok(true)
            }
            _ => Err(format!(
                "expected an arc flag (0 or 1) at character {}",
                self.i + 1
            )),
        }
    }

    fn pair(&mut self) -> Result<DVec2, String> {
        Ok(DVec2::new(self.number()?, self.number()?))
    }
}

/// Flattens path data into subpaths (points, closed).
fn path(d: &str, segments: usize) -> Result<Vec<(Vec<DVec2>, bool)>, String> {
    let mut lx = Lexer {
        s: d.as_bytes(),
        i: 0,
    };
    let mut out: Vec<(Vec<DVec2>, bool)> = Vec::new();
    let mut current: Vec<DVec2> = Vec::new();
    let (mut cur, mut start) = (DVec2::ZERO, DVec2::ZERO);
    // Last control points for the smooth (S, T) commands.
    let (mut last_cubic, mut last_quad): (Option<DVec2>, Option<DVec2>) = (None, None);
    let mut prev: Option<u8> = None;
    while !lx.at_end() {
        let cmd = match lx.command() {
            Some(c) => c,
            None => match prev {
                // Extra coordinate pairs after a move are implicit line-tos.
                Some(b'M') => b'L',
                Some(b'm') => b'l',
                Some(b'Z' | b'z') | None => {
                    return Err(format!(
                        "path data must start with a command (M), found '{}'",
                        char::from(lx.s[lx.i])
                    ));
                }
                Some(c) => c,
            },
        };
        let rel = cmd.is_ascii_lowercase();
        let base = if rel { cur } else { DVec2::ZERO };
        let upper = cmd.to_ascii_uppercase();
        if upper != b'M' && upper != b'Z' && current.is_empty() {
            current.push(cur);
        }
        let (mut next_cubic, mut next_quad) = (None, None);
        match upper {
            b'M' => {
                let p = base + lx.pair()?;
                if current.len() > 1 {
                    out.push((std::mem::take(&mut current), false));
                }
                current = vec![p];
                cur = p;
                start = p;
            }
            b'L' => {
                cur = base + lx.pair()?;
                current.push(cur);
            }
            b'H' => {
                let x = lx.number()?;
                cur = DVec2::new(if rel { cur.x + x } else { x }, cur.y);
                current.push(cur);
            }
            b'V' => {
                let y = lx.number()?;
                cur = DVec2::new(cur.x, if rel { cur.y + y } else { y });
                current.push(cur);
            }
            b'Z' => {
                if current.len() > 1 {
                    out.push((std::mem::take(&mut current), true));
                }
                current.clear();
                cur = start;
            }
            b'C' | b'S' => {
                let c1 = if upper == b'C' {
                    base + lx.pair()?
                } else {
                    last_cubic.map_or(cur, |c| 2.0 * cur - c)
                };
                let c2 = base + lx.pair()?;
                let end = base + lx.pair()?;
                current.extend(flatten_cubic(cur, c1, c2, end, segments));
                next_cubic = Some(c2);
                cur = end;
            }
            b'Q' | b'T' => {
                let c1 = if upper == b'Q' {
                    base + lx.pair()?
                } else {
                    last_quad.map_or(cur, |c| 2.0 * cur - c)
                };
                let end = base + lx.pair()?;
                current.extend(flatten_quadratic(cur, c1, end, segments));
                next_quad = Some(c1);
                cur = end;
            }
            b'A' => {
                let radii = DVec2::new(lx.number()?, lx.number()?);
                let rotation = lx.number()?;
                let large = lx.flag()?;
                let sweep = lx.flag()?;
                let end = base + lx.pair()?;
                current.extend(elliptical_arc(
                    cur, radii, rotation, large, sweep, end, segments,
                ));
                cur = end;
            }
            other => return Err(format!("unknown path command '{}'", char::from(other))),
        }
        last_cubic = next_cubic;
        last_quad = next_quad;
        prev = Some(cmd);
        if upper == b'Z' && lx.number_next() {
            return Err("numbers after a Z command".into());
        }
    }
    if current.len() > 1 {
        out.push((current, false));
    }
    Ok(out)
}

fn points_attr(s: &str) -> Result<Vec<DVec2>, String> {
    let mut lx = Lexer {
        s: s.as_bytes(),
        i: 0,
    };
    let mut numbers = Vec::new();
    while !lx.at_end() {
        numbers.push(lx.number()?);
    }
    if numbers.len() % 2 != 0 {
        return Err(format!("odd number of coordinates ({})", numbers.len()));
    }
    Ok(numbers.chunks(2).map(|c| DVec2::new(c[0], c[1])).collect())
}

fn attr_number(node: &roxmltree::Node, name: &str) -> Result<f64, String> {
    match node.attribute(name) {
        None => Ok(0.0),
        Some(v) => {
            let mut lx = Lexer {
                s: v.as_bytes(),
                i: 0,
            };
            let x = lx.number()?;
            Ok(x)
        }
    }
}

/// Flips SVG's downward y axis: (x, y) ↦ (x, −y, 0).
fn to_world(points: &[DVec2]) -> Vec<DVec3> {
    points.iter().map(|p| DVec3::new(p.x, -p.y, 0.0)).collect()
}

/// At most how many points a path's `d` flattens to: a curve takes at least two numbers and gives
/// at most `segments` points, a line at least one number and one point.
fn path_points_bound(d: &str, segments: usize) -> u64 {
    let bytes = d.as_bytes();
    let numbers = bytes
        .iter()
        .enumerate()
        .filter(|&(k, &b)| {
            let starts = b.is_ascii_digit() || b == b'.';
            starts && (k == 0 || !(bytes[k - 1].is_ascii_digit() || bytes[k - 1] == b'.'))
        })
        .count() as u64;
    let curves = bytes
        .iter()
        .any(|b| matches!(b.to_ascii_uppercase(), b'C' | b'S' | b'Q' | b'T' | b'A'));
    if curves {
        (numbers / 2 + 1).saturating_mul(segments as u64 + 1)
    } else {
        numbers + 1
    }
}

/// At most how many bytes the document's text takes once its internal entities are expanded: the
/// text plus, for every `&name;`, the length of what `name` expands to (entities inside entities
/// expanded as far as they go). A 2 GB expansion hidden in a 1 kB file is seen before parsing.
fn expanded_bound(text: &str) -> u64 {
    if !text.contains("<!ENTITY") {
        return text.len() as u64;
    }
    // `<!ENTITY name "value">` or with single quotes.
    let mut entities: Vec<(&str, &str)> = Vec::new();
    for decl in text.split("<!ENTITY").skip(1) {
        let decl = decl.trim_start();
        let Some((name, rest)) = decl.split_once(char::is_whitespace) else {
            continue;
        };
        let rest = rest.trim_start();
        let Some(quote) = rest.chars().next().filter(|c| *c == '"' || *c == '\'') else {
            continue;
        };
        if let Some(value) = rest[1..].split(quote).next() {
            entities.push((name, value));
        }
    }
    let count = |s: &str, name: &str| s.matches(&format!("&{name};")).count() as u64;
    // Sizes by fixed point over the declarations (nested references), saturating.
    let mut sizes: Vec<u64> = entities.iter().map(|(_, v)| v.len() as u64).collect();
    for _ in 0..entities.len().min(64) {
        let next: Vec<u64> = entities
            .iter()
            .map(|(_, v)| {
                entities
                    .iter()
                    .zip(&sizes)
                    .fold(v.len() as u64, |acc, ((n, _), &size)| {
                        acc.saturating_add(count(v, n).saturating_mul(size))
                    })
            })
            .collect();
        if next == sizes {
            break;
        }
        sizes = next;
    }
    entities
        .iter()
        .zip(&sizes)
        .fold(text.len() as u64, |acc, ((n, _), &size)| {
            acc.saturating_add(count(text, n).saturating_mul(size))
        })
}

/// Parses SVG text into polylines (and warnings). The XML is parsed by `roxmltree`; undeclared
/// namespace prefixes are tolerated (at most [`MAX_PREFIXES`]).
pub fn parse(text: &str, segments: usize) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    parse_within(text, segments, &mut Guard::unlimited())
}

/// [`parse`] declaring to `guard` the expanded text (entities) before parsing and every path's
/// flattened points before flattening them.
pub fn parse_within(
    text: &str,
    segments: usize,
    guard: &mut Guard,
) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    // The parser keeps the text and its expansions (about twice the expanded text).
    guard
        .grow(expanded_bound(text).saturating_mul(2))
        .map_err(|e| format!("{e} (the document's entities expand the text)"))?;
    let mut patched: Option<String> = None;
    for _ in 0..=MAX_PREFIXES {
        let src = patched.as_deref().unwrap_or(text);
        let next = match document(src) {
            Ok(doc) => return shapes(&doc, segments, guard),
            Err(roxmltree::Error::UnknownNamespace(prefix, pos)) => declare(src, &prefix)
                .ok_or_else(|| {
                    ReadError::at_column(
                        pos.row as usize,
                        pos.col as usize,
                        format!("undeclared namespace prefix '{prefix}'"),
                    )
                })?,
            Err(e) => return Err(xml_error(src, &e)),
        };
        patched = Some(next);
    }
    Err(format!("more than {MAX_PREFIXES} undeclared namespace prefixes").into())
}

/// The polylines of a parsed document, in document order (and warnings).
fn shapes(
    doc: &roxmltree::Document,
    segments: usize,
    guard: &mut Guard,
) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    let mut out = Vec::new();
    let mut transforms = 0;
    let mut skipped = 0;
    for node in doc.descendants().filter(|n| n.is_element()) {
        if node.attribute("transform").is_some() {
            transforms += 1;
        }
        let name = node.tag_name().name();
        // The line only for an error: finding it scans the text from the start.
        let at = |e: String| {
            let line = doc.text_pos_at(node.range().start).row;
            ReadError::at(line as usize, format!("<{name}>: {e}"))
        };
        let shapes: Vec<(Vec<DVec2>, bool)> = match name {
            "polyline" | "polygon" => {
                let pts = points_attr(node.attribute("points").unwrap_or("")).map_err(at)?;
                vec![(pts, name == "polygon")]
            }
            "line" => {
                let a = DVec2::new(
                    attr_number(&node, "x1").map_err(at)?,
                    attr_number(&node, "y1").map_err(at)?,
                );
                let b = DVec2::new(
                    attr_number(&node, "x2").map_err(at)?,
                    attr_number(&node, "y2").map_err(at)?,
                );
                vec![(vec![a, b], false)]
            }
            "path" => {
                let d = node.attribute("d").unwrap_or("");
                // A point as flattened and as kept (16 + 24 bytes, and the tidied copy).
                guard
                    .grow_items(path_points_bound(d, segments), 64)
                    .map_err(|e| at(e.to_string()))?;
                path(d, segments).map_err(at)?
            }
            _ => continue,
        };
        for (pts, closed) in shapes {
            let p = tidy(to_world(&pts), closed);
            if p.points.len() >= 2 {
                out.push(p);
            } else {
                skipped += 1;
            }
        }
    }
    let mut warnings = Vec::new();
    if transforms > 0 {
        warnings.push(format!(
            "{transforms} element(s) have a transform attribute, which is not applied"
        ));
    }
    if skipped > 0 {
        warnings.push(format!(
            "{skipped} shape(s) with fewer than 2 distinct points skipped"
        ));
    }
    Ok((out, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: DVec3, b: DVec3) -> bool {
        a.distance(b) < 1e-9
    }

    #[test]
    fn polylines_polygons_lines_with_flipped_y() {
        let text = r#"<?xml version="1.0"?>
<!-- a comment with <polyline points="9 9 9 9"/> inside -->
<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">
  <polyline points="0,0 1,2 3,4" fill='none'/>
  <svg:polygon points="0 0 2 0 2 2"></svg:polygon>
  <line x1="1" y1="1" x2="4" y2="5" />
  <rect x="0" y="0" width="3" height="3"/>
</svg>"#;
        let (ps, warnings) = parse(text, 8).unwrap();
        assert!(warnings.is_empty());
        assert_eq!(ps.len(), 3);
        assert_eq!(ps[0].points[2], DVec3::new(3.0, -4.0, 0.0));
        assert!(ps[1].closed);
        assert_eq!(
            ps[2].points,
            vec![DVec3::new(1.0, -1.0, 0.0), DVec3::new(4.0, -5.0, 0.0)]
        );
    }

    #[test]
    fn path_commands_absolute_and_relative() {
        // A unit square drawn with relative commands, then an open subpath with H/V.
        let (ps, _) = parse(r#"<path d="m1 1 h1 v1 h-1 z M5 5 H7 V8 L 9,8 l1-1"/>"#, 4).unwrap();
        assert_eq!(ps.len(), 2);
        assert!(ps[0].closed);
        assert_eq!(ps[0].points.len(), 4);
        assert_eq!(ps[0].points[2], DVec3::new(2.0, -2.0, 0.0));
        assert_eq!(
            ps[1].points.last().copied(),
            Some(DVec3::new(10.0, -7.0, 0.0))
        );
        // Implicit line-tos after a move, compact numbers.
        let (ps, _) = parse(r#"<path d="M0 0 1 0 1.5.5-2e0,3"/>"#, 4).unwrap();
        assert_eq!(ps[0].points.len(), 4);
        assert_eq!(ps[0].points[3], DVec3::new(-2.0, -3.0, 0.0));
    }

    #[test]
    fn curves_and_arcs_are_flattened_onto_the_true_curves() {
        // Quadratic: midpoint of (0,0) (1,2) (2,0) at t = 1/2 is (1, 1).
        let (ps, _) = parse(r#"<path d="M0 0 Q1 2 2 0"/>"#, 4).unwrap();
        assert_eq!(ps[0].points.len(), 5);
        assert!(near(ps[0].points[2], DVec3::new(1.0, -1.0, 0.0)));
        // Cubic then a smooth continuation mirrors the control point.
        let (ps, _) = parse(r#"<path d="M0 0 C0 1 1 1 1 0 S2 -1 2 0"/>"#, 2).unwrap();
        assert_eq!(ps[0].points.len(), 5);
        assert!(near(ps[0].points[1], DVec3::new(0.5, -0.75, 0.0)));
        assert!(near(ps[0].points[3], DVec3::new(1.5, 0.75, 0.0)));
        // Half circle of radius 1 about (1, 0), sweep 1: through (1, −1) in SVG, (1, 1) flipped.
        let (ps, _) = parse(r#"<path d="M0 0 A1 1 0 0 1 2 0"/>"#, 8).unwrap();
        assert_eq!(ps[0].points.len(), 9);
        for p in &ps[0].points {
            assert!(((*p - DVec3::X).length() - 1.0).abs() < 1e-12);
        }
        assert!(near(ps[0].points[4], DVec3::new(1.0, 1.0, 0.0)));
        // Radii too small are scaled up; flags may be packed ("a1 1 0 01 2 0").
        let (ps, _) = parse(r#"<path d="M0 0 a0.1 0.1 0 01 2 0"/>"#, 8).unwrap();
        assert!(near(ps[0].points[4], DVec3::new(1.0, 1.0, 0.0)));
    }

    #[test]
    fn errors_and_warnings() {
        let e = parse(
            r#"<svg>
<path d="M0 0 L1"/></svg>"#,
            4,
        )
        .unwrap_err();
        assert_eq!((e.line, e.column), (Some(2), None), "{e}");
        let e = e.to_string();
        assert!(e.starts_with("line 2: <path>"), "{e}");
        assert!(
            parse(r#"<path d="0 0 L1 1"/>"#, 4)
                .unwrap_err()
                .to_string()
                .contains("start with a command")
        );
        assert!(
            parse(r#"<polyline points="0 0 1"/>"#, 4)
                .unwrap_err()
                .to_string()
                .contains("odd")
        );
        assert!(
            parse(r#"<path d="M0 0 X1 1"/>"#, 4)
                .unwrap_err()
                .to_string()
                .contains("unknown path command")
        );
        assert!(parse(r#"<path d="M0 0 L1 1"#, 4).is_err());
        assert!(
            parse("<!-- open", 4)
                .unwrap_err()
                .to_string()
                .contains("unterminated comment")
        );
        let (ps, w) = parse(
            r#"<g transform="scale(2)"><path d="M0 0 L1 1"/><path d="M3 3"/></g>"#,
            4,
        )
        .unwrap();
        assert_eq!(ps.len(), 1);
        assert!(w.iter().any(|m| m.contains("transform")));
        // Entities in attribute values are decoded (by the XML parser).
        let (ps, _) = parse(r#"<polyline points="0&#44;0 1&#x2C;2 3,4&#32;"/>"#, 4).unwrap();
        assert_eq!(ps[0].points[1], DVec3::new(1.0, -2.0, 0.0));
    }

    #[test]
    fn hostile_documents_end_in_clear_errors() {
        // Billion laughs: refused by the parser's entity limits, quickly.
        let mut lol =
            String::from("<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY a \"0 0 1 1 \">");
        let mut prev = "a".to_string();
        for k in 0..9 {
            let name = format!("e{k}");
            lol.push_str(&format!(
                "<!ENTITY {name} \"{}\">",
                format!("&{prev};").repeat(10)
            ));
            prev = name;
        }
        lol.push_str(&format!("]><svg><polyline points=\"&{prev};\"/></svg>"));
        let t = std::time::Instant::now();
        let e = parse(&lol, 4).unwrap_err().to_string();
        assert!(e.contains("malformed XML") && e.contains("line 1"), "{e}");
        assert!(t.elapsed().as_secs_f64() < 1.0);
        // An external entity is not fetched.
        let ext = r#"<!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]><svg><polyline points="&x;"/></svg>"#;
        assert!(parse(ext, 4).is_err());
        // A DOCTYPE as older exporters write it is fine.
        let dtd = r#"<?xml version="1.0"?>
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">
<svg xmlns="http://www.w3.org/2000/svg"><line x1="0" y1="0" x2="1" y2="1"/></svg>"#;
        assert_eq!(parse(dtd, 4).unwrap().0.len(), 1);
        // Deep nesting neither overflows the stack nor is refused.
        let depth = 100_000;
        let deep = format!(
            "{}<path d=\"M0 0 L1 1\"/>{}",
            "<g>".repeat(depth),
            "</g>".repeat(depth)
        );
        assert_eq!(parse(&deep, 4).unwrap().0.len(), 1);
        // Undeclared prefixes: a few are declared on the fly (line numbers kept), too many are an error.
        let (ps, _) = parse("<svg>\n<a:path d=\"M0 0 L1 1\" b:x=\"1\"/></svg>", 4).unwrap();
        assert_eq!(ps.len(), 1);
        let e = parse("<svg>\n<a:path d=\"M0 0 L1\"/></svg>", 4)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("line 2: <path>"), "{e}");
        let many: String = (0..20).map(|k| format!("<p{k}:g/>")).collect();
        let e = parse(&format!("<svg>{many}</svg>"), 4)
            .unwrap_err()
            .to_string();
        assert!(e.contains("undeclared namespace prefixes"), "{e}");
        // Not XML at all, mismatched tags, duplicate attributes: the line and what is wrong.
        for (text, says) in [
            ("plain text", "unknown token"),
            ("<svg><g></svg>", "expected 'g' tag"),
            ("<svg a='1' a='2'/>", "already defined"),
            ("", "root node"),
            ("<svg><![CDATA[ open", "unterminated CDATA"),
        ] {
            let e = parse(text, 4).unwrap_err().to_string();
            assert!(e.starts_with("line 1") && e.contains(says), "{text:?}: {e}");
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]

        /// Any text, and any byte-level mutation of a valid drawing, parses or fails with a message;
        /// nothing panics.
        #[test]
        fn arbitrary_and_mutated_documents_never_panic(
            noise in "\\PC{0,200}",
            cut in 0usize..400,
            insert in "[<>&;\"'=/!?:a-z0-9 \\[\\]-]{0,12}",
        ) {
            let _ = parse(&noise, 4);
            let valid = r#"<?xml version="1.0"?><!DOCTYPE svg><svg xmlns="http://www.w3.org/2000/svg"><!-- c --><g transform="x"><path d="M0 0 C1 2 3 4 5 6 S7 8 9 0 Q1 1 2 2 T3 3 A1 2 30 1 0 4 4 Z"/><polygon points="0,0 1,0 1,1"/><line x1="0" x2="1"/></g></svg>"#;
            let at = cut.min(valid.len());
            let at = (0..=at).rev().find(|&k| valid.is_char_boundary(k)).unwrap_or(0);
            let mutated = format!("{}{insert}{}", &valid[..at], &valid[at..]);
            let _ = parse(&mutated, 4);
        }
    }
}
