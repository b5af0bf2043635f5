//! Optimization candidates: the numbers an input offers as variables (with default bounds) and
//! the right-click menu that picks one.

use cnets_engine::optimize::ValuePath;
use cnets_engine::{NodeInstance, Value, ValueType};
use egui::Ui;

use super::fmt;
use crate::request::UiRequest;
use crate::widgets::{effective_value, slider_range};

/// Most numbers one input offers in its "Optimize" menu.
pub const MAX_CANDIDATES: usize = 64;

/// A number inside an input's literal value that can become a variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// Where it is.
    pub path: ValuePath,
    /// Its current value.
    pub value: f64,
    /// Default lower bound.
    pub min: f64,
    /// Default upper bound.
    pub max: f64,
    /// A literal to set on the input first (a mapper's default handles have none yet).
    pub prepare: Option<Value>,
}

/// Default bounds for a number without a natural range: ±50 % of it (±1 around zero).
pub fn default_bounds(x: f64) -> (f64, f64) {
    if x == 0.0 {
        (-1.0, 1.0)
    } else {
        let d = 0.5 * x.abs();
        (x - d, x + d)
    }
}

fn leaves(value: &Value, indices: &mut Vec<usize>, out: &mut Vec<(Vec<usize>, f64)>) {
    if out.len() >= MAX_CANDIDATES {
        return;
    }
    match value {
        Value::Number(x) => out.push((indices.clone(), *x)),
        Value::Point(p) | Value::Vector(p) => {
            for (c, x) in p.to_array().into_iter().enumerate() {
                indices.push(c);
                out.push((indices.clone(), x));
                indices.pop();
            }
        }
        Value::List(items) => {
            for (i, item) in items.iter().enumerate() {
                if out.len() >= MAX_CANDIDATES {
                    break; // (a list of millions of numbers offers its first ones)
                }
                indices.push(i);
                leaves(item, indices, out);
                indices.pop();
            }
        }
        _ => {}
    }
}

/// The numbers of input `k` of `node` that can become optimization variables, with default
/// bounds (empty for wired-only types, integers, text…).
pub fn variable_candidates(node: &NodeInstance, k: usize) -> Vec<Candidate> {
    let Some(port) = node.def.inputs.get(k) else {
        return Vec::new();
    };
    // `Any` ports (a literal list or table, e.g. `param.list`) offer the numbers they hold.
    if !matches!(
        port.ty,
        ValueType::Number | ValueType::Point | ValueType::Vector | ValueType::Any
    ) {
        return Vec::new();
    }
    let is_handles =
        crate::mapper::node::is_mapper(node) && crate::mapper::node::handles_port(node) == Some(k);
    let (value, prepare) = match effective_value(node, k) {
        Some(v) if !(is_handles && matches!(&v, Value::List(items) if items.is_empty())) => {
            (v, None)
        }
        _ if is_handles => {
            // No handles set: the kind's defaults, written on the input with the variable.
            let handles = Value::list(
                crate::mapper::node::handles(node)
                    .into_iter()
                    .map(|h| Value::Point(cnets_geometry::DVec3::new(h.x, h.y, 0.0)))
                    .collect(),
            );
            (handles.clone(), Some(handles))
        }
        _ => return Vec::new(),
    };
    let mut found = Vec::new();
    leaves(&value, &mut Vec::new(), &mut found);
    let slider = port.widget() == cnets_engine::Widget::Slider;
    found
        .into_iter()
        .filter(|(indices, _)| !is_handles || indices.last() != Some(&2))
        .map(|(indices, x)| {
            // The range the port declares (a slider's `min` and `max` inputs, a declared soft or
            // hard range); a mapper's handles lie in the unit square; else around the value.
            let declared = port
                .hint
                .soft_range
                .or(port.hint.hard_range.filter(|&(a, b)| {
                    // An open bound (a step's 0 to f64::MAX) is no range to search.
                    a.abs() < 1e300 && b.abs() < 1e300
                }));
            let (min, max) = if slider {
                let (lo, hi, _) = slider_range(node, k);
                (lo, hi)
            } else if let Some(range) = declared {
                range
            } else if is_handles {
                (0.0, 1.0)
            } else {
                default_bounds(x)
            };
            Candidate {
                path: ValuePath {
                    node: node.id.clone(),
                    port: port.name.to_string(),
                    indices,
                },
                value: x,
                min,
                max,
                prepare: prepare.clone(),
            }
        })
        .collect()
}

fn candidate_request(c: &Candidate) -> UiRequest {
    UiRequest::Optimize {
        path: c.path.clone(),
        min: c.min,
        max: c.max,
        prepare: c.prepare.clone(),
    }
}

/// The whole-input variable of several candidates of one input (`node.port`: every number of the
/// list, table, points or handles), bounded by the widest of their default bounds; `None` for
/// fewer than two.
pub fn whole_input(candidates: &[Candidate]) -> Option<Candidate> {
    let [first, _, ..] = candidates else {
        return None;
    };
    Some(Candidate {
        path: ValuePath {
            indices: Vec::new(),
            ..first.path.clone()
        },
        value: first.value,
        min: candidates
            .iter()
            .map(|c| c.min)
            .fold(f64::INFINITY, f64::min),
        max: candidates
            .iter()
            .map(|c| c.max)
            .fold(f64::NEG_INFINITY, f64::max),
        prepare: first.prepare.clone(),
    })
}

/// The "Optimize" entries of an input's context menu; returns the action picked.
pub fn variable_menu(ui: &mut Ui, candidates: &[Candidate]) -> Option<UiRequest> {
    let mut picked = None;
    if let Some(all) = whole_input(candidates)
        && ui
            .button("Optimize every value")
            .on_hover_text(format!(
                "add every number of {} as optimization variables in [{}, {}] (one whole-input variable)",
                all.path,
                fmt(all.min),
                fmt(all.max)
            ))
            .clicked()
    {
        ui.close();
        return Some(candidate_request(&all));
    }
    if let [c] = candidates {
        if ui
            .button("Optimize this value")
            .on_hover_text(format!(
                "add {} as an optimization variable in [{}, {}]",
                c.path,
                fmt(c.min),
                fmt(c.max)
            ))
            .clicked()
        {
            picked = Some(candidate_request(c));
            ui.close();
        }
        return picked;
    }
    ui.menu_button("Optimize a value", |ui| {
        egui::ScrollArea::vertical()
            .max_height(320.0)
            .show(ui, |ui| {
                for c in candidates {
                    let label = format!(
                        "{} = {}",
                        c.path
                            .indices
                            .iter()
                            .map(|i| format!("[{i}]"))
                            .collect::<String>(),
                        fmt(c.value)
                    );
                    if ui.button(label).clicked() {
                        picked = Some(candidate_request(c));
                        ui.close();
                    }
                }
            });
    });
    picked
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimization::tests::graph;

    #[test]
    fn a_declared_range_bounds_the_candidates() {
        // `curve.arc`'s radius with a declared range: the variable offers that range, not ±50 %.
        let nodes = cnets_nodes::registry();
        let mut arc = (**nodes.get("curve.arc").unwrap()).clone();
        let k = arc.input_index("radius").unwrap();
        arc.inputs[k].hint.soft_range = Some((1.0, 9.0));
        let mut registry = cnets_engine::Registry::new();
        registry.register(arc);
        let mut g = cnets_engine::Graph::new(std::sync::Arc::new(registry));
        g.add_node("arc", "curve.arc").unwrap();
        let c = variable_candidates(g.node("arc").unwrap(), k);
        assert_eq!((c[0].min, c[0].max), (1.0, 9.0));
    }

    #[test]
    fn candidates_have_sensible_bounds() {
        let g = graph();
        let n = g.node("n").unwrap();
        let c = variable_candidates(n, n.def.input_index("value").unwrap());
        assert_eq!(c.len(), 1);
        assert_eq!((c[0].min, c[0].max, c[0].value), (0.1, 2.0, 0.3));
        assert_eq!(c[0].path.to_string(), "n.value");
        let arc = g.node("arc").unwrap();
        let c = variable_candidates(arc, arc.def.input_index("radius").unwrap());
        assert_eq!((c[0].min, c[0].max), (2.0, 6.0), "±50 %");
        let c = variable_candidates(arc, arc.def.input_index("centre").unwrap());
        assert_eq!(c.len(), 3, "a point's coordinates");
        assert_eq!(c[1].path.to_string(), "arc.centre[1]");
        assert!(variable_candidates(arc, arc.def.input_index("count").unwrap()).is_empty());
        let m = g.node("m").unwrap();
        let k = crate::mapper::node::handles_port(m).unwrap();
        let c = variable_candidates(m, k);
        let handles = crate::mapper::node::handles(m);
        assert_eq!(c.len(), 2 * handles.len(), "u and v of each default handle");
        assert!(c.iter().all(|c| c.min == 0.0 && c.max == 1.0));
        assert!(
            c[0].prepare.is_some(),
            "the default handles are written first"
        );
        let all = whole_input(&c).expect("a whole-input variable");
        assert_eq!(all.path.to_string(), "m.handles");
        assert_eq!((all.min, all.max), (0.0, 1.0));
        assert!(all.prepare.is_some());
        let one = variable_candidates(n, n.def.input_index("value").unwrap());
        assert!(
            whole_input(&one).is_none(),
            "one number: no whole-input entry"
        );
        assert_eq!(default_bounds(0.0), (-1.0, 1.0));
        assert_eq!(default_bounds(-2.0), (-3.0, -1.0));
    }
}
