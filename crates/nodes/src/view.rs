//! Reading values on the canvas: `view.panel`, Grasshopper's Panel.
//!
//! The text layout is Grasshopper's: a single item is written as it is; a list is a branch headed by
//! its path (`{0}`), one indexed item a line; a nested list gives one branch per innermost list, its
//! path the indices that lead to it (`{0;1}`); records list their fields by name. Numbers are written
//! in full precision (the shortest text that reads back as the same `f64`).

use std::fmt::Write;

use cnets_engine::prelude::*;

/// Most lines a panel writes; longer values end with a line saying how many items were left out.
pub const MAX_PANEL_LINES: usize = 10_000;

/// The panel text of any value.
pub fn panel_text(value: &Value) -> String {
    let mut out = PanelWriter::default();
    match value {
        Value::List(_) => out.branches(value, &mut Vec::new()),
        other => out.item_lines(other, ""),
    }
    out.finish()
}

#[derive(Default)]
struct PanelWriter {
    text: String,
    lines: usize,
    skipped: usize,
}

impl PanelWriter {
    fn line(&mut self, line: &str) {
        if self.lines >= MAX_PANEL_LINES {
            self.skipped += 1;
            return;
        }
        if self.lines > 0 {
            self.text.push('\n');
        }
        self.text.push_str(line);
        self.lines += 1;
    }

    fn finish(mut self) -> String {
        if self.skipped > 0 {
            let note = format!("… {} more lines not shown", self.skipped);
            self.text.push('\n');
            self.text.push_str(&note);
        }
        self.text
    }

    /// One branch per innermost list, headed by its path.
    fn branches(&mut self, value: &Value, path: &mut Vec<usize>) {
        let Some(items) = value.as_list() else {
            return;
        };
        let nested = items.iter().any(|v| matches!(v, Value::List(_)));
        if !nested {
            self.line(&format!("{{{}}}", path_text(path, 0)));
            for (k, item) in items.iter().enumerate() {
                self.item_lines(item, &format!("{k}  "));
            }
            return;
        }
        for (k, item) in items.iter().enumerate() {
            path.push(k);
            match item {
                Value::List(_) => self.branches(item, path),
                // A lone item beside lists is a branch of one.
                leaf => {
                    self.line(&format!("{{{}}}", path_text(path, 0)));
                    self.item_lines(leaf, "0  ");
                }
            }
            path.pop();
            if self.lines >= MAX_PANEL_LINES {
                self.skipped += items.len() - k - 1;
                return;
            }
        }
    }

    /// The lines of one item: records give one line per field, everything else one line.
    fn item_lines(&mut self, value: &Value, prefix: &str) {
        match value {
            Value::Record(record) => {
                if !prefix.is_empty() {
                    self.line(prefix.trim_end());
                }
                let indent = if prefix.is_empty() { "" } else { "    " };
                for (name, field) in record.fields() {
                    self.line(&format!("{indent}{name}: {}", item_text(field)));
                }
            }
            other => self.line(&format!("{prefix}{}", item_text(other))),
        }
    }
}

/// A path as Grasshopper writes it: indices joined by `;` (`{0}` for a top-level list).
fn path_text(path: &[usize], default: usize) -> String {
    if path.is_empty() {
        return default.to_string();
    }
    let mut s = String::new();
    for (k, i) in path.iter().enumerate() {
        if k > 0 {
            s.push(';');
        }
        let _ = write!(s, "{i}");
    }
    s
}

/// A number in full precision: the shortest text that reads back as the same `f64`, in scientific
/// notation when it is very large or very small (`3.5e-15`, not fifteen zeros).
pub fn number_text(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || (1e-5..1e16).contains(&a) || !a.is_finite() {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

fn vec_text(v: DVec3) -> String {
    format!(
        "{{{}, {}, {}}}",
        number_text(v.x),
        number_text(v.y),
        number_text(v.z)
    )
}

/// One value on one line.
pub fn item_text(value: &Value) -> String {
    match value {
        Value::Null => "<empty>".into(),
        Value::Number(x) => number_text(*x),
        Value::Integer(i) => i.to_string(),
        Value::Boolean(b) => b.to_string(),
        Value::Text(t) => t.replace('\n', " ⏎ "),
        Value::Point(p) => vec_text(*p),
        Value::Vector(v) => format!("vector {}", vec_text(*v)),
        Value::Plane(p) => format!(
            "plane (origin {}, normal {})",
            vec_text(p.origin),
            vec_text(p.normal)
        ),
        Value::Lines(lines) => format!("{} line segments", lines.len()),
        Value::Polyline(p) => format!(
            "polyline ({} points, {})",
            p.points.len(),
            if p.closed { "closed" } else { "open" }
        ),
        Value::QuadMesh(g) => format!(
            "quad mesh ({} × {} vertices{}{})",
            g.rows,
            g.cols,
            if g.wrap_rows { ", rows wrap" } else { "" },
            if g.wrap_cols { ", columns wrap" } else { "" }
        ),
        Value::Mesh(m) => format!(
            "mesh ({} vertices, {} faces)",
            m.vertices.len(),
            m.face_count()
        ),
        Value::List(items) => format!("list of {} items", items.len()),
        Value::Record(r) => {
            let fields: Vec<String> = r
                .fields()
                .iter()
                .map(|(n, v)| format!("{n}: {}", item_text(v)))
                .collect();
            format!("{{{}}}", fields.join(", "))
        }
    }
}

node! {
    /// Shows any value as readable text, as Grasshopper's Panel does: a single item as it is, a list
    /// as a branch `{0}` with one indexed item a line, nested lists as one branch per innermost list
    /// headed by its path (`{0;1}`), records field by field. Numbers in full precision. The editor
    /// shows the text inside the node; at most 10 000 lines are written.
    #[node(id = "view.panel", category = "Display", name = "Panel")]
    pub fn panel(
        /// What to show (anything: an item, a list, a table, a record…).
        value: k::Tree<k::Any>,
    ) -> (
        /// The text shown.
        #[ui(role = Readout)]
        text: k::Text,
    ) {
        Ok((panel_text(&value),))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![panel()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use cnets_engine::eval::evaluate_node;

    fn nums(xs: &[f64]) -> Value {
        Value::list(xs.iter().map(|&x| Value::Number(x)).collect())
    }

    fn show(v: Value) -> String {
        let out = evaluate_node(&panel(), &NodeContext::default(), &[v]).unwrap();
        match &out.values[0] {
            Value::Text(t) => t.to_string(),
            other => panic!("text expected, got {other:?}"),
        }
    }

    #[test]
    fn items_lists_and_trees_read_like_grasshopper() {
        assert_eq!(show(Value::Number(0.1 + 0.2)), "0.30000000000000004");
        assert_eq!(show(nums(&[1.5, -2.0])), "{0}\n0  1.5\n1  -2");
        let tree = Value::list(vec![nums(&[1.0]), nums(&[2.0, 3.0])]);
        assert_eq!(show(tree), "{0}\n0  1\n{1}\n0  2\n1  3");
        let deep = Value::list(vec![Value::list(vec![nums(&[7.0]), nums(&[8.0])])]);
        assert_eq!(show(deep), "{0;0}\n0  7\n{0;1}\n0  8");
        assert_eq!(
            show(Value::Point(DVec3::new(1.0, -0.5, 2.0))),
            "{1, -0.5, 2}"
        );
    }

    #[test]
    fn records_show_their_fields_by_name() {
        let r = Record::new()
            .with("max_planarity", 3.5e-15)
            .with("faces", Value::Integer(12));
        assert_eq!(
            show(Value::from(r.clone())),
            "max_planarity: 3.5e-15\nfaces: 12"
        );
        let listed = show(Value::list(vec![Value::from(r)]));
        assert_eq!(listed, "{0}\n0\n    max_planarity: 3.5e-15\n    faces: 12");
    }

    #[test]
    fn long_values_are_cut_with_a_count() {
        let many = nums(&vec![1.0; MAX_PANEL_LINES + 5]);
        let text = show(many);
        assert_eq!(text.lines().count(), MAX_PANEL_LINES + 1);
        assert!(
            text.ends_with("… 6 more lines not shown"),
            "{}",
            &text[text.len() - 40..]
        );
    }
}
