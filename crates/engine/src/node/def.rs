//! The node contract: a node type's ports, documentation, flags and the functions that run and
//! differentiate it. A leaf of the engine: it imports values and the node's context and
//! derivative types, nothing of the evaluator or the optimizer.

use std::borrow::Cow;
use std::fmt;
use std::sync::Arc;

use super::context::NodeContext;
use super::derivative::{Branch, BranchFn, VjpArgs, VjpFn, VjpResult};
use super::hint::{Choices, PortHint};
use crate::error::NodeError;
use crate::kinds::PortKind;
use crate::value::{Access, Value, ValueType};

/// The function that evaluates a node on fully prepared inputs (defaults filled in, converted to the
/// port types, one item per item port) and returns one value per output port.
pub type RunFn = Arc<dyn Fn(&NodeContext, &[Value]) -> Result<Vec<Value>, NodeError> + Send + Sync>;

/// One input or output port of a node type.
#[derive(Debug, Clone)]
pub struct PortDef {
    /// The port name (a contract: graph files and `cnets eval` use it).
    pub name: Cow<'static, str>,
    /// Item type.
    pub ty: ValueType,
    /// Item, list or tree access.
    pub access: Access,
    /// Value used when nothing is connected and no value is set.
    pub default: Option<Value>,
    /// An optional input may stay empty (the node sees `None`).
    pub optional: bool,
    /// One line for tooltips.
    pub doc: Cow<'static, str>,
    /// How an editor shows and edits the port ([`PortHint`]).
    pub hint: PortHint,
    /// The fixed words of a choice port (checked when a value is set; a drop-down in an editor).
    pub choices: Option<Choices>,
}

impl PortDef {
    /// A port whose type, access and optionality come from the kind marker `K`.
    pub fn of<K: PortKind>(
        name: impl Into<Cow<'static, str>>,
        doc: impl Into<Cow<'static, str>>,
    ) -> Self {
        Self {
            name: name.into(),
            ty: K::item_type(),
            access: K::access(),
            default: None,
            optional: K::optional(),
            doc: doc.into(),
            hint: PortHint::default(),
            choices: K::choices(),
        }
    }

    /// A port with an explicit type and access.
    pub fn new(name: impl Into<Cow<'static, str>>, ty: ValueType, access: Access) -> Self {
        Self {
            name: name.into(),
            ty,
            access,
            default: None,
            optional: false,
            doc: Cow::Borrowed(""),
            hint: PortHint::default(),
            choices: None,
        }
    }

    /// Sets the default value (builder style).
    pub fn with_default(mut self, value: Value) -> Self {
        self.default = Some(value);
        self
    }

    /// Marks the port optional (builder style).
    pub fn optional(mut self) -> Self {
        self.optional = true;
        self
    }

    /// Sets the doc line (builder style).
    pub fn with_doc(mut self, doc: impl Into<Cow<'static, str>>) -> Self {
        self.doc = doc.into();
        self
    }

    /// Sets how the port is shown (builder style).
    pub fn with_hint(mut self, hint: PortHint) -> Self {
        self.hint = hint;
        self
    }

    /// The name shown to designers: the hint's display name, else the port name.
    pub fn display_name(&self) -> &str {
        self.hint.display_name.as_deref().unwrap_or(&self.name)
    }

    /// The widget for the port's value: the hint's, or [`Widget::Choice`] for a choice port.
    pub fn widget(&self) -> super::hint::Widget {
        use super::hint::Widget;
        match self.hint.widget {
            Widget::Auto if self.choices.is_some() => Widget::Choice,
            w => w,
        }
    }

    /// Checks a text set on a choice port: `Err("valid: perpendicular, mirror")` when the port
    /// has choices and the text is none of them; every other port and value passes.
    pub fn check_choice(&self, text: &str) -> Result<(), String> {
        match &self.choices {
            Some(c) if !(c.accepts)(text) => Err(format!(
                "'{}' is not one of its choices; {}",
                crate::files::excerpt(text, 60),
                c.valid_list()
            )),
            _ => Ok(()),
        }
    }

    /// True when the port must be connected or given a value.
    pub fn required(&self) -> bool {
        !self.optional && self.default.is_none()
    }

    /// The type as shown to users, e.g. `number` or `list<point>`.
    pub fn type_name(&self) -> String {
        self.ty.with_access(self.access)
    }
}

/// Special behaviour of a node type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NodeFlag {
    /// A designer-facing parameter (slider, toggle, …): the editor shows its inputs inline.
    Parameter,
    /// Writes files into the run's output directory; always demanded by `cnets run`.
    Export,
    /// Reads files from disk (relative to the graph file).
    Import,
}

/// A node type: id, documentation, ports and the function that runs it.
#[derive(Clone)]
pub struct NodeDef {
    /// Namespaced id, e.g. `curve.arc` (a contract).
    pub id: Cow<'static, str>,
    /// Palette category, e.g. `Curves`.
    pub category: Cow<'static, str>,
    /// The name shown to designers, e.g. `Number slider` (Grasshopper's names); `None`: derived
    /// from the id.
    pub display_name: Option<Cow<'static, str>>,
    /// One paragraph: the tooltip and the `cnets nodes` description.
    pub doc: Cow<'static, str>,
    /// Input ports in order.
    pub inputs: Vec<PortDef>,
    /// Output ports in order.
    pub outputs: Vec<PortDef>,
    /// Special behaviour.
    pub flags: Vec<NodeFlag>,
    /// The evaluation function.
    pub run: RunFn,
    /// Per-type data of dynamic node types (e.g. a cluster's subgraph), for introspection.
    pub extension: Option<Arc<dyn std::any::Any + Send + Sync>>,
    /// The node's exact vector–Jacobian product for the optimizer's reverse pass; `None`: not
    /// differentiable, the optimizer uses finite differences for this node
    /// ([`crate::optimize::vjp`]).
    pub vjp: Option<VjpFn>,
    /// For a piecewise-smooth node, which smooth piece a run was on, so the optimizer reports a
    /// step that crosses a kink ([`crate::optimize::branch`]); `None`: smooth, or not told.
    pub branch: Option<BranchFn>,
    /// Outputs the vector–Jacobian product and the branch function read besides those on the
    /// path to the objective (e.g. the construction's `corrections`): the optimizer asks for them
    /// in the same run, so a lazily computed output is never read empty.
    pub derivative_outputs: &'static [&'static str],
}

impl fmt::Debug for NodeDef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NodeDef")
            .field("id", &self.id)
            .field(
                "inputs",
                &self.inputs.iter().map(|p| &p.name).collect::<Vec<_>>(),
            )
            .field(
                "outputs",
                &self.outputs.iter().map(|p| &p.name).collect::<Vec<_>>(),
            )
            .finish()
    }
}

impl NodeDef {
    /// Starts a definition with no ports and a run function that fails; see the `node!` macro for
    /// the usual way to declare nodes.
    pub fn new(
        id: impl Into<Cow<'static, str>>,
        category: impl Into<Cow<'static, str>>,
        doc: impl Into<Cow<'static, str>>,
    ) -> Self {
        Self {
            id: id.into(),
            category: category.into(),
            display_name: None,
            doc: doc.into(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            flags: Vec::new(),
            run: Arc::new(|_, _| Err(NodeError::new("node has no implementation"))),
            extension: None,
            vjp: None,
            branch: None,
            derivative_outputs: &[],
        }
    }

    /// Sets the display name (builder style).
    pub fn with_display_name(mut self, name: impl Into<Cow<'static, str>>) -> Self {
        self.display_name = Some(name.into());
        self
    }

    /// Adds an input port.
    pub fn input(mut self, port: PortDef) -> Self {
        self.inputs.push(port);
        self
    }

    /// Adds an output port.
    pub fn output(mut self, port: PortDef) -> Self {
        self.outputs.push(port);
        self
    }

    /// Adds a flag.
    pub fn flag(mut self, flag: NodeFlag) -> Self {
        self.flags.push(flag);
        self
    }

    /// Sets the run function.
    pub fn run(
        mut self,
        f: impl Fn(&NodeContext, &[Value]) -> Result<Vec<Value>, NodeError> + Send + Sync + 'static,
    ) -> Self {
        self.run = Arc::new(f);
        self
    }

    /// Sets the vector–Jacobian product (builder style; see [`crate::optimize::vjp`]).
    pub fn with_vjp(
        mut self,
        f: impl Fn(&VjpArgs<'_>) -> VjpResult + Send + Sync + 'static,
    ) -> Self {
        self.vjp = Some(Arc::new(f));
        self
    }

    /// Sets the branch function of a piecewise-smooth node (builder style; see
    /// [`crate::optimize::branch`]).
    pub fn with_branch(
        mut self,
        f: impl Fn(&[Value], &[Value]) -> Option<Branch> + Send + Sync + 'static,
    ) -> Self {
        self.branch = Some(Arc::new(f));
        self
    }

    /// Sets the outputs the derivative reads (builder style; see
    /// [`NodeDef::derivative_outputs`]).
    pub fn with_derivative_outputs(mut self, outputs: &'static [&'static str]) -> Self {
        self.derivative_outputs = outputs;
        self
    }

    /// True when the node has the flag.
    pub fn has_flag(&self, flag: NodeFlag) -> bool {
        self.flags.contains(&flag)
    }

    /// Index of the input port with this name.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|p| p.name == name)
    }

    /// Index of the output port with this name.
    pub fn output_index(&self, name: &str) -> Option<usize> {
        self.outputs.iter().position(|p| p.name == name)
    }

    /// Comma-separated input names, for error messages.
    pub fn input_names(&self) -> String {
        self.inputs
            .iter()
            .map(|p| p.name.as_ref())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Comma-separated output names, for error messages.
    pub fn output_names(&self) -> String {
        self.outputs
            .iter()
            .map(|p| p.name.as_ref())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The name a designer reads: the declared display name, else the id's last part with spaces
    /// and a capital (`curve.closest_point` → "Closest point").
    pub fn name(&self) -> Cow<'_, str> {
        if let Some(name) = &self.display_name {
            return Cow::Borrowed(name);
        }
        let last = self
            .id
            .rsplit('.')
            .next()
            .unwrap_or(&self.id)
            .replace('_', " ");
        let mut chars = last.chars();
        match chars.next() {
            Some(c) => Cow::Owned(c.to_uppercase().chain(chars).collect()),
            None => Cow::Borrowed(&self.id),
        }
    }

    /// The first line of the doc paragraph (a short summary).
    pub fn summary(&self) -> &str {
        self.doc.lines().next().unwrap_or("")
    }
}

/// A port name from a Rust identifier: raw identifiers (`r#type`) lose their `r#`.
pub fn port_name(ident: &'static str) -> &'static str {
    ident.strip_prefix("r#").unwrap_or(ident)
}

/// Joins doc-comment lines (as captured by the `node!` macro) into one trimmed text: lines are
/// trimmed, consecutive lines of a paragraph are joined by spaces, blank lines separate paragraphs.
pub fn doc_text(lines: &[&str]) -> String {
    let mut out = String::new();
    let mut blank = false;
    for line in lines.iter().map(|l| l.trim()) {
        if line.is_empty() {
            blank = !out.is_empty();
            continue;
        }
        if blank {
            out.push_str("\n\n");
            blank = false;
        } else if !out.is_empty() {
            out.push(' ');
        }
        out.push_str(line);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doc_text_joins_lines_and_keeps_paragraphs() {
        assert_eq!(
            doc_text(&[" A circular", " arc.", "", " More."]),
            "A circular arc.\n\nMore."
        );
    }
}
