//! SVG polylines: `<polyline>`, `<polygon>` (closed), `<line>` and `<path>` elements, in document
//! order. Path data supports every command, absolute and relative: M, L, H, V, Z move and draw
//! straight; C, S (cubic), Q, T (quadratic) and A (elliptical arc) are flattened into `segments`
//! points each. Each subpath is one polyline; Z closes it. Coordinates are user units with the y
//! axis flipped (x, y) ↦ (x, −y, 0), so a drawing looks the same way up as in the SVG viewer.
//! `transform` attributes are not applied (a warning says so); other elements are ignored.

use std::f64::consts::TAU;

use cnets_engine::prelude::*;
use glam::DVec2;

use super::tidy;

/// One start tag: name (without namespace prefix), attributes, line number.
struct Tag<'a> {
    name: &'a str,
    attrs: Vec<(&'a str, String)>,
    line: usize,
}

impl Tag<'_> {
    fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v.as_str())
    }
}

fn line_of(text: &str, offset: usize) -> usize {
    text[..offset].bytes().filter(|&b| b == b'\n').count() + 1
}

/// Decodes the five predefined XML entities and numeric character references.
fn unescape(s: &str) -> String {
    if !s.contains('&') {
        return s.to_string();
    }
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(p) = rest.find('&') {
        out.push_str(&rest[..p]);
        rest = &rest[p..];
        let Some(end) = rest.find(';') else {
            out.push_str(rest);
            return out;
        };
        let entity = &rest[1..end];
        let decoded = match entity {
            "lt" => Some('<'),
            "gt" => Some('>'),
            "amp" => Some('&'),
            "quot" => Some('"'),
            "apos" => Some('\''),
            e if e.starts_with("#x") => u32::from_str_radix(&e[2..], 16)
                .ok()
                .and_then(char::from_u32),
            e if e.starts_with('#') => e[1..].parse().ok().and_then(char::from_u32),
            _ => None,
        };
        match decoded {
            Some(c) => {
                out.push(c);
                rest = &rest[end + 1..];
            }
            None => {
                out.push('&');
                rest = &rest[1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// Scans the start tags of an XML document (comments, CDATA, processing instructions, doctype and
/// end tags are skipped).
fn tags(text: &str) -> Result<Vec<Tag<'_>>, String> {
    let mut out = Vec::new();
    let mut i = 0;
    let skip_to = |from: usize, end: &str, what: &str| -> Result<usize, String> {
        text[from..]
            .find(end)
            .map(|p| from + p + end.len())
            .ok_or_else(|| format!("line {}: unterminated {what}", line_of(text, from)))
    };
    while let Some(p) = text[i..].find('<') {
        let s = i + p;
        let rest = &text[s..];
        if rest.starts_with("<!--") {
            i = skip_to(s, "-->", "comment")?;
            continue;
        }
        if rest.starts_with("<![CDATA[") {
            i = skip_to(s, "]]>", "CDATA section")?;
            continue;
        }
        if rest.starts_with("<?") {
            i = skip_to(s, "?>", "processing instruction")?;
            continue;
        }
        if rest.starts_with("<!") || rest.starts_with("</") {
            i = skip_to(s, ">", "tag")?;
            continue;
        }
        let line = line_of(text, s);
        let bytes = text.as_bytes();
        let mut j = s + 1;
        while j < bytes.len()
            && !bytes[j].is_ascii_whitespace()
            && bytes[j] != b'>'
            && bytes[j] != b'/'
        {
            j += 1;
        }
        let full_name = &text[s + 1..j];
        let name = full_name.rsplit(':').next().unwrap_or(full_name);
        let mut attrs = Vec::new();
        loop {
            while j < bytes.len() && bytes[j].is_ascii_whitespace() {
                j += 1;
            }
            if j >= bytes.len() {
                return Err(format!("line {line}: unterminated <{full_name}> tag"));
            }
            if bytes[j] == b'>' {
                j += 1;
                break;
            }
            if bytes[j] == b'/' {
                j += 1;
                continue;
            }
            let a = j;
            while j < bytes.len()
                && !bytes[j].is_ascii_whitespace()
                && !matches!(bytes[j], b'=' | b'>' | b'/')
            {
                j += 1;
            }
            let attr_name = &text[a..j];
            while j < bytes.len() && bytes[j].is_ascii_whitespace() {
                j += 1;
            }
            if j < bytes.len() && bytes[j] == b'=' {
                j += 1;
                while j < bytes.len() && bytes[j].is_ascii_whitespace() {
                    j += 1;
                }
                let Some(&quote) = bytes.get(j).filter(|q| matches!(q, b'"' | b'\'')) else {
                    return Err(format!(
                        "line {line}: attribute '{attr_name}' of <{full_name}> needs a quoted value"
                    ));
                };
                let v0 = j + 1;
                let len = text[v0..].find(quote as char).ok_or_else(|| {
                    format!("line {line}: unterminated value of attribute '{attr_name}'")
                })?;
                attrs.push((attr_name, unescape(&text[v0..v0 + len])));
                j = v0 + len + 1;
            } else {
                attrs.push((attr_name, String::new()));
            }
        }
        out.push(Tag { name, attrs, line });
        i = j;
    }
    Ok(out)
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

fn cubic(p0: DVec2, p1: DVec2, p2: DVec2, p3: DVec2, t: f64) -> DVec2 {
    let s = 1.0 - t;
    p0 * (s * s * s) + p1 * (3.0 * s * s * t) + p2 * (3.0 * s * t * t) + p3 * (t * t * t)
}

fn quadratic(p0: DVec2, p1: DVec2, p2: DVec2, t: f64) -> DVec2 {
    let s = 1.0 - t;
    p0 * (s * s) + p1 * (2.0 * s * t) + p2 * (t * t)
}

/// Points of an SVG elliptical arc from `p1` to `p2` (excluding `p1`), by the endpoint-to-centre
/// conversion of the SVG specification (appendix F.6.5/F.6.6, out-of-range radii scaled up).
fn arc(
    p1: DVec2,
    radii: DVec2,
    rotation: f64,
    large: bool,
    sweep: bool,
    p2: DVec2,
    segments: usize,
) -> Vec<DVec2> {
    if p1 == p2 {
        return Vec::new();
    }
    let (mut rx, mut ry) = (radii.x.abs(), radii.y.abs());
    if rx == 0.0 || ry == 0.0 {
        return vec![p2];
    }
    let (s, c) = rotation.to_radians().sin_cos();
    let d = (p1 - p2) * 0.5;
    let x1 = c * d.x + s * d.y;
    let y1 = -s * d.x + c * d.y;
    let lambda = (x1 * x1) / (rx * rx) + (y1 * y1) / (ry * ry);
    if lambda > 1.0 {
        rx *= lambda.sqrt();
        ry *= lambda.sqrt();
    }
    let num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    let den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    let mut coef = (num / den).max(0.0).sqrt();
    if large == sweep {
        coef = -coef;
    }
    let cxp = coef * rx * y1 / ry;
    let cyp = -coef * ry * x1 / rx;
    let mid = (p1 + p2) * 0.5;
    let centre = DVec2::new(c * cxp - s * cyp + mid.x, s * cxp + c * cyp + mid.y);
    let angle = |u: DVec2, v: DVec2| (u.x * v.y - u.y * v.x).atan2(u.dot(v));
    let u = DVec2::new((x1 - cxp) / rx, (y1 - cyp) / ry);
    let v = DVec2::new((-x1 - cxp) / rx, (-y1 - cyp) / ry);
    let theta1 = angle(DVec2::X, u);
    let mut dtheta = angle(u, v);
    if !sweep && dtheta > 0.0 {
        dtheta -= TAU;
    } else if sweep && dtheta < 0.0 {
        dtheta += TAU;
    }
    (1..=segments)
        .map(|k| {
            if k == segments {
                return p2;
            }
            let t = theta1 + dtheta * k as f64 / segments as f64;
            let (st, ct) = t.sin_cos();
            centre + DVec2::new(rx * ct * c - ry * st * s, rx * ct * s + ry * st * c)
        })
        .collect()
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
                current.extend((1..=segments).map(|k| {
                    if k == segments {
                        end
                    } else {
                        cubic(cur, c1, c2, end, k as f64 / segments as f64)
                    }
                }));
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
                current.extend((1..=segments).map(|k| {
                    if k == segments {
                        end
                    } else {
                        quadratic(cur, c1, end, k as f64 / segments as f64)
                    }
                }));
                next_quad = Some(c1);
                cur = end;
            }
            b'A' => {
                let radii = DVec2::new(lx.number()?, lx.number()?);
                let rotation = lx.number()?;
                let large = lx.flag()?;
                let sweep = lx.flag()?;
                let end = base + lx.pair()?;
                current.extend(arc(cur, radii, rotation, large, sweep, end, segments));
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

fn attr_number(tag: &Tag, name: &str) -> Result<f64, String> {
    match tag.attr(name) {
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

/// Parses SVG text into polylines (and warnings).
pub fn parse(text: &str, segments: usize) -> Result<(Vec<Polyline>, Vec<String>), String> {
    let mut out = Vec::new();
    let mut transforms = 0;
    let mut skipped = 0;
    for tag in tags(text)? {
        if tag.attr("transform").is_some() {
            transforms += 1;
        }
        let at = |e: String| format!("line {}: <{}>: {e}", tag.line, tag.name);
        let shapes: Vec<(Vec<DVec2>, bool)> = match tag.name {
            "polyline" | "polygon" => {
                let pts = points_attr(tag.attr("points").unwrap_or("")).map_err(at)?;
                vec![(pts, tag.name == "polygon")]
            }
            "line" => {
                let a = DVec2::new(
                    attr_number(&tag, "x1").map_err(at)?,
                    attr_number(&tag, "y1").map_err(at)?,
                );
                let b = DVec2::new(
                    attr_number(&tag, "x2").map_err(at)?,
                    attr_number(&tag, "y2").map_err(at)?,
                );
                vec![(vec![a, b], false)]
            }
            "path" => path(tag.attr("d").unwrap_or(""), segments).map_err(at)?,
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
        assert!(e.starts_with("line 2: <path>"), "{e}");
        assert!(
            parse(r#"<path d="0 0 L1 1"/>"#, 4)
                .unwrap_err()
                .contains("start with a command")
        );
        assert!(
            parse(r#"<polyline points="0 0 1"/>"#, 4)
                .unwrap_err()
                .contains("odd")
        );
        assert!(
            parse(r#"<path d="M0 0 X1 1"/>"#, 4)
                .unwrap_err()
                .contains("unknown path command")
        );
        assert!(parse(r#"<path d="M0 0 L1 1"#, 4).is_err());
        assert!(
            parse("<!-- open", 4)
                .unwrap_err()
                .contains("unterminated comment")
        );
        let (ps, w) = parse(
            r#"<g transform="scale(2)"><path d="M0 0 L1 1"/><path d="M3 3"/></g>"#,
            4,
        )
        .unwrap();
        assert_eq!(ps.len(), 1);
        assert!(w.iter().any(|m| m.contains("transform")));
        assert_eq!(unescape("a&lt;b&#65;&#x42;&bogus;"), "a<bAB&bogus;");
    }
}
