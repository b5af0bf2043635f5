//! The optimization setup stored in a graph file: variables with bounds, an objective, penalties.
//!
//! ```ron
//! optimization: (
//!     objective: "gap.value",
//!     variables: [
//!         (input: "ratios.value[1]", min: 0.1, max: 0.9),
//!     ],
//!     penalties: [
//!         (output: "width.value", weight: 10.0, kind: "at_most", target: 2.0),
//!     ],
//!     convex: ["construct"],
//!     method: "auto",
//!     max_iter: 100,
//! ),
//! ```
//!
//! `convex` names constructions whose faces must stay (++)(++) for the whole run (their
//! convexity margins, an output of role [`crate::node::Role::FaceMargins`], are kept positive by a
//! barrier: docs/optimizer.md).

use std::fmt::Write as _;

use super::path::ValuePath;
use crate::file::literal::{push_indent, quote};
use crate::file::ron::{Kind, Node, Pos};

/// One design variable: a number inside a node's literal input, with bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// Where the number lives (`node.input[...]`).
    pub input: ValuePath,
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
}

/// How a penalty measures its term.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PenaltyKind {
    /// `weight · (value − target)²`.
    Equal,
    /// `weight · max(0, value − target)²`.
    AtMost,
    /// `weight · max(0, target − value)²`.
    AtLeast,
}

impl PenaltyKind {
    fn name(self) -> &'static str {
        match self {
            PenaltyKind::Equal => "equal",
            PenaltyKind::AtMost => "at_most",
            PenaltyKind::AtLeast => "at_least",
        }
    }
}

/// A soft constraint added to the objective.
#[derive(Debug, Clone, PartialEq)]
pub struct Penalty {
    /// The measured number (`node.output[...]`).
    pub output: ValuePath,
    /// Weight (≥ 0).
    pub weight: f64,
    /// Kind of constraint.
    pub kind: PenaltyKind,
    /// Target value.
    pub target: f64,
}

impl Penalty {
    /// The penalty for a measured value.
    pub fn value(&self, v: f64) -> f64 {
        let d = match self.kind {
            PenaltyKind::Equal => v - self.target,
            PenaltyKind::AtMost => (v - self.target).max(0.0),
            PenaltyKind::AtLeast => (self.target - v).max(0.0),
        };
        self.weight * d * d
    }
}

/// Which minimizer to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Method {
    /// Bounded L-BFGS, falling back to Nelder–Mead when the objective is not smooth.
    #[default]
    Auto,
    /// Bounded (projected) L-BFGS with finite-difference gradients.
    Lbfgsb,
    /// Derivative-free Nelder–Mead simplex, kept inside the bounds.
    NelderMead,
}

impl Method {
    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Auto => "auto",
            Method::Lbfgsb => "lbfgsb",
            Method::NelderMead => "nelder_mead",
        }
    }

    /// Parses a method name.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "auto" => Method::Auto,
            "lbfgsb" | "l-bfgs-b" => Method::Lbfgsb,
            "nelder_mead" | "nelder-mead" => Method::NelderMead,
            _ => return None,
        })
    }
}

/// Everything needed to run an optimization of a graph.
#[derive(Debug, Clone, PartialEq)]
pub struct Setup {
    /// The number to minimize (`node.output[...]`).
    pub objective: ValuePath,
    /// The design variables.
    pub variables: Vec<Variable>,
    /// Soft constraints.
    pub penalties: Vec<Penalty>,
    /// Constructions (node ids) whose faces must stay (++)(++) for the whole run.
    pub convex: Vec<String>,
    /// The minimizer.
    pub method: Method,
    /// Iteration limit.
    pub max_iter: usize,
}

/// A setup problem with its position in the file.
pub type SetupError = (Pos, String);

fn fields(node: &Node, what: &str) -> Result<Vec<(String, Pos, Node)>, SetupError> {
    match &node.kind {
        Kind::Struct(_, fields) => Ok(fields
            .iter()
            .map(|(f, v)| (f.name.clone(), f.pos, v.clone()))
            .collect()),
        other => Err((
            node.pos,
            format!(
                "{what} must be a struct (field: value, …), found {}",
                other.describe()
            ),
        )),
    }
}

fn path(node: &Node, what: &str) -> Result<ValuePath, SetupError> {
    let text = node
        .as_str()
        .ok_or((node.pos, format!("{what} must be a string \"node.port\"")))?;
    ValuePath::parse(text).map_err(|e| (node.pos, e))
}

fn number(node: &Node, what: &str) -> Result<f64, SetupError> {
    node.as_f64()
        .filter(|x| x.is_finite())
        .ok_or((node.pos, format!("{what} must be a finite number")))
}

fn variable(node: &Node) -> Result<Variable, SetupError> {
    let mut input = None;
    let (mut min, mut max) = (None, None);
    for (name, pos, v) in fields(node, "a variable")? {
        match name.as_str() {
            "input" => input = Some(path(&v, "'input'")?),
            "min" => min = Some(number(&v, "'min'")?),
            "max" => max = Some(number(&v, "'max'")?),
            other => {
                return Err((
                    pos,
                    format!("unknown variable field '{other}'; expected input, min, max"),
                ));
            }
        }
    }
    let input = input.ok_or((
        node.pos,
        "a variable needs 'input: \"node.input\"'".to_string(),
    ))?;
    let (min, max) = (
        min.unwrap_or(f64::NEG_INFINITY),
        max.unwrap_or(f64::INFINITY),
    );
    if min > max {
        return Err((
            node.pos,
            format!("variable {input}: min {min} is greater than max {max}"),
        ));
    }
    Ok(Variable { input, min, max })
}

fn penalty(node: &Node) -> Result<Penalty, SetupError> {
    let mut output = None;
    let mut weight = 1.0;
    let mut kind = PenaltyKind::Equal;
    let mut target = 0.0;
    for (name, pos, v) in fields(node, "a penalty")? {
        match name.as_str() {
            "output" => output = Some(path(&v, "'output'")?),
            "weight" => weight = number(&v, "'weight'")?,
            "target" => target = number(&v, "'target'")?,
            "kind" => {
                kind = match v.as_str() {
                    Some("equal") => PenaltyKind::Equal,
                    Some("at_most") => PenaltyKind::AtMost,
                    Some("at_least") => PenaltyKind::AtLeast,
                    _ => {
                        return Err((
                            v.pos,
                            "'kind' must be \"equal\", \"at_most\" or \"at_least\"".into(),
                        ));
                    }
                }
            }
            other => {
                return Err((
                    pos,
                    format!(
                        "unknown penalty field '{other}'; expected output, weight, kind, target"
                    ),
                ));
            }
        }
    }
    if weight < 0.0 {
        return Err((node.pos, "a penalty weight must be ≥ 0".into()));
    }
    let output = output.ok_or((
        node.pos,
        "a penalty needs 'output: \"node.output\"'".to_string(),
    ))?;
    Ok(Penalty {
        output,
        weight,
        kind,
        target,
    })
}

impl Setup {
    /// Reads the `optimization: (…)` section of a graph file.
    pub fn parse(node: &Node) -> Result<Setup, SetupError> {
        let mut objective = None;
        let mut variables = Vec::new();
        let mut penalties = Vec::new();
        let mut convex = Vec::new();
        let mut method = Method::Auto;
        let mut max_iter = 100;
        for (name, pos, v) in fields(node, "'optimization'")? {
            match name.as_str() {
                "objective" => objective = Some(path(&v, "'objective'")?),
                "variables" => {
                    let items = v.items().filter(|_| matches!(v.kind, Kind::List(_)));
                    let items = items.ok_or((v.pos, "'variables' must be a list".to_string()))?;
                    variables = items.iter().map(variable).collect::<Result<_, _>>()?;
                }
                "penalties" => {
                    let items = v.items().filter(|_| matches!(v.kind, Kind::List(_)));
                    let items = items.ok_or((v.pos, "'penalties' must be a list".to_string()))?;
                    penalties = items.iter().map(penalty).collect::<Result<_, _>>()?;
                }
                "convex" => {
                    let items = v.items().filter(|_| matches!(v.kind, Kind::List(_)));
                    let items = items.ok_or((
                        v.pos,
                        "'convex' must be a list of node ids [\"construct\", …]".to_string(),
                    ))?;
                    convex = items
                        .iter()
                        .map(|n| {
                            n.as_str().map(str::to_string).ok_or((
                                n.pos,
                                "'convex' must list node ids as strings".to_string(),
                            ))
                        })
                        .collect::<Result<_, _>>()?;
                }
                "method" => {
                    method = v.as_str().and_then(Method::parse).ok_or((
                        v.pos,
                        "'method' must be \"auto\", \"lbfgsb\" or \"nelder_mead\"".to_string(),
                    ))?;
                }
                "max_iter" => {
                    max_iter = match v.kind {
                        Kind::Int(i) if i > 0 => i as usize,
                        _ => return Err((v.pos, "'max_iter' must be a positive integer".into())),
                    }
                }
                other => {
                    return Err((
                        pos,
                        format!(
                            "unknown optimization field '{other}'; expected objective, variables, penalties, convex, method, max_iter"
                        ),
                    ));
                }
            }
        }
        let objective = objective.ok_or((
            node.pos,
            "an optimization needs 'objective: \"node.output\"'".to_string(),
        ))?;
        if variables.is_empty() {
            return Err((
                node.pos,
                "an optimization needs at least one variable".into(),
            ));
        }
        Ok(Setup {
            objective,
            variables,
            penalties,
            convex,
            method,
            max_iter,
        })
    }

    /// Writes the section as RON at indentation `level` (the value only, after `optimization: `).
    pub fn to_ron(&self, level: usize) -> String {
        let mut out = String::from("(\n");
        let line = |out: &mut String, text: &str| {
            push_indent(out, level + 1);
            out.push_str(text);
            out.push('\n');
        };
        let mut q = String::new();
        quote(&mut q, &self.objective.to_string());
        line(&mut out, &format!("objective: {q},"));
        line(&mut out, "variables: [");
        for v in &self.variables {
            let mut q = String::new();
            quote(&mut q, &v.input.to_string());
            let mut text = format!("(input: {q}");
            for (name, bound) in [("min", v.min), ("max", v.max)] {
                if bound.is_finite() {
                    let _ = write!(text, ", {name}: {bound:?}");
                }
            }
            text.push_str("),");
            push_indent(&mut out, level + 2);
            out.push_str(&text);
            out.push('\n');
        }
        line(&mut out, "],");
        if !self.penalties.is_empty() {
            line(&mut out, "penalties: [");
            for p in &self.penalties {
                let mut q = String::new();
                quote(&mut q, &p.output.to_string());
                push_indent(&mut out, level + 2);
                let _ = writeln!(
                    out,
                    "(output: {q}, weight: {:?}, kind: \"{}\", target: {:?}),",
                    p.weight,
                    p.kind.name(),
                    p.target
                );
            }
            line(&mut out, "],");
        }
        if !self.convex.is_empty() {
            let ids: Vec<String> = self
                .convex
                .iter()
                .map(|id| {
                    let mut q = String::new();
                    quote(&mut q, id);
                    q
                })
                .collect();
            line(&mut out, &format!("convex: [{}],", ids.join(", ")));
        }
        line(&mut out, &format!("method: \"{}\",", self.method.name()));
        line(&mut out, &format!("max_iter: {},", self.max_iter));
        push_indent(&mut out, level);
        out.push(')');
        out
    }
}
