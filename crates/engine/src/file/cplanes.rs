//! The named construction planes a graph file keeps for the editor's 3D view (optional; files
//! without them load as before):
//!
//! ```ron
//! cplanes: [
//!     (name: "CPlane 1", origin: (1.0, 0.0, 2.0), u: (0.6, 0.0, 0.8), v: (0.0, 1.0, 0.0)),
//! ],
//! ```
//!
//! `u` and `v` are the plane's in-plane axes (the editor makes them orthonormal; the normal is
//! `u × v`).

use super::literal::{push_indent, quote};
use super::ron::{Kind, Node, Pos};

/// A named construction plane: an origin and two in-plane axes.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedPlane {
    /// The name shown in the editor's menu (`CPlane 1`).
    pub name: String,
    /// The plane's origin.
    pub origin: [f64; 3],
    /// Its first axis.
    pub u: [f64; 3],
    /// Its second axis.
    pub v: [f64; 3],
}

/// Reads the `cplanes` list; an error with the position of the offending value.
pub fn parse(section: &Node) -> Result<Vec<NamedPlane>, (Pos, String)> {
    let Kind::List(items) = &section.kind else {
        return Err((
            section.pos,
            format!(
                "'cplanes' must be a list of (name: \"..\", origin: (x, y, z), u: (..), v: (..)), \
                 found {}",
                section.kind.describe()
            ),
        ));
    };
    items.iter().map(parse_plane).collect()
}

fn parse_plane(item: &Node) -> Result<NamedPlane, (Pos, String)> {
    let Kind::Struct(_, fields) = &item.kind else {
        return Err((
            item.pos,
            format!(
                "a construction plane is (name: \"..\", origin: (x, y, z), u: (..), v: (..)), \
                 found {}",
                item.kind.describe()
            ),
        ));
    };
    let (mut name, mut origin, mut u, mut v) = (None, None, None, None);
    for (field, value) in fields {
        match field.name.as_str() {
            "name" => match &value.kind {
                Kind::Str(s) => name = Some(s.clone()),
                other => {
                    return Err((
                        value.pos,
                        format!("'name' must be a string, found {}", other.describe()),
                    ));
                }
            },
            "origin" => origin = Some(vector(value, "origin")?),
            "u" => u = Some(vector(value, "u")?),
            "v" => v = Some(vector(value, "v")?),
            other => {
                return Err((
                    field.pos,
                    format!(
                        "unknown field '{other}' of a construction plane; expected name, origin, u, v"
                    ),
                ));
            }
        }
    }
    let missing = |what: &str| {
        (
            item.pos,
            format!("construction plane: missing field '{what}'"),
        )
    };
    let plane = NamedPlane {
        name: name.ok_or_else(|| missing("name"))?,
        origin: origin.ok_or_else(|| missing("origin"))?,
        u: u.ok_or_else(|| missing("u"))?,
        v: v.ok_or_else(|| missing("v"))?,
    };
    let (a, b) = (glam::DVec3::from(plane.u), glam::DVec3::from(plane.v));
    if a.cross(b).length() <= 1e-12 * a.length() * b.length() || a.length() == 0.0 {
        return Err((
            item.pos,
            format!(
                "construction plane '{}': u and v must be non-zero and not parallel",
                plane.name
            ),
        ));
    }
    Ok(plane)
}

fn vector(value: &Node, what: &str) -> Result<[f64; 3], (Pos, String)> {
    let bad = || {
        (
            value.pos,
            format!(
                "'{what}' must be three finite numbers (x, y, z), found {}",
                value.kind.describe()
            ),
        )
    };
    let (Kind::Tuple(None, items) | Kind::List(items)) = &value.kind else {
        return Err(bad());
    };
    if items.len() != 3 {
        return Err(bad());
    }
    let mut out = [0.0; 3];
    for (slot, item) in out.iter_mut().zip(items) {
        *slot = match item.kind {
            Kind::Float(x) if x.is_finite() => x,
            Kind::Int(n) => n as f64,
            _ => return Err(bad()),
        };
    }
    Ok(out)
}

/// Writes `cplanes: [..],` at `indent` (nothing when there are none).
pub fn write(out: &mut String, planes: &[NamedPlane], indent: usize) {
    if planes.is_empty() {
        return;
    }
    let triple = |p: [f64; 3]| format!("({:?}, {:?}, {:?})", p[0], p[1], p[2]);
    push_indent(out, indent);
    out.push_str("cplanes: [\n");
    for plane in planes {
        push_indent(out, indent + 1);
        out.push_str("(name: ");
        quote(out, &plane.name);
        out.push_str(&format!(
            ", origin: {}, u: {}, v: {}),\n",
            triple(plane.origin),
            triple(plane.u),
            triple(plane.v)
        ));
    }
    push_indent(out, indent);
    out.push_str("],\n");
}
