//! What a port says about how it is shown and edited (Graphite's `#[widget]` / `#[range]`
//! parameter attributes): a display name, soft and hard ranges, a step, a widget, the choices of a
//! choice port, and the preview layer of an output. Declared in `node!` with `#[ui(…)]` on a port;
//! read by the editor, the parameter panel, the palette, the optimizer and the preview, so none of
//! them guesses from node ids or port names.

use std::borrow::Cow;
use std::ops::RangeInclusive;

use super::layer::Layer;

/// The widget an editor uses for an input port's literal value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Widget {
    /// Chosen from the port's type (a number field, a check box, a text field, …).
    #[default]
    Auto,
    /// A slider over the node's range (a designer-facing parameter: shown in the parameter panel,
    /// a variable the optimizer offers).
    Slider,
    /// A number dragged or typed, without a track.
    DragValue,
    /// A check box (a designer-facing toggle: shown in the parameter panel).
    Toggle,
    /// One of the port's choices (a drop-down), or the index into a node's own option list.
    Choice,
    /// The curve handles of a graph mapper (drawn and dragged in the mapper widget; the optimizer
    /// keeps them in the unit square).
    MapperHandles,
    /// Points drawn as handles in the 3D view (dragged, boxed, nudged).
    PointHandles,
    /// A path to a file the node reads: a text field with Browse….
    FilePath,
    /// The name of a file the node writes (inside the output folder).
    OutputName,
    /// Multi-line text.
    MultilineText,
    /// Not shown as an editable field on the node (set by wires or by the node's own widget, e.g.
    /// a graph mapper's `kind`, picked in the mapper widget).
    Hidden,
}

impl Widget {
    /// The word used by `cnets nodes --json` and docs/nodes.md.
    pub fn as_str(self) -> &'static str {
        match self {
            Widget::Auto => "auto",
            Widget::Slider => "slider",
            Widget::DragValue => "drag_value",
            Widget::Toggle => "toggle",
            Widget::Choice => "choice",
            Widget::MapperHandles => "mapper_handles",
            Widget::PointHandles => "point_handles",
            Widget::FilePath => "file_path",
            Widget::OutputName => "output_name",
            Widget::MultilineText => "multiline_text",
            Widget::Hidden => "hidden",
        }
    }

    /// True for the widgets of designer-facing parameters: what the parameter panel lists.
    pub fn is_parameter(self) -> bool {
        matches!(
            self,
            Widget::Slider | Widget::Toggle | Widget::Choice | Widget::MapperHandles
        )
    }
}

/// What an output means to the engine's tools beyond its type (read by role, never by name).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Role {
    /// Nothing special.
    #[default]
    Plain,
    /// A construction's convexity margins: a list of numbers, four per face of its mesh, all
    /// positive exactly when the face is (++)(++) (`cnets_geometry::conenet::margins`). The
    /// optimizer's `convex` constraint keeps them positive and counts the faces that are not.
    FaceMargins,
    /// The plane of a cut that keeps one side of it: the side its normal points to, the other
    /// when the node's [`Role::FlipsSide`] input is on. The 3D view draws it, with an arrow to
    /// the kept side, while the node is selected.
    CutPlane,
    /// A boolean that makes the node's [`Role::CutPlane`] keep the side opposite its normal.
    FlipsSide,
    /// A construction's support-strip configurations (`++`, `--`, `+-`, `-+`): N lists of M−1
    /// labels, read with the node's quad-mesh output for the face classes and fold warnings.
    Configurations,
    /// A text the editor shows inside the node (a panel's readout).
    Readout,
}

/// The fixed words a choice port accepts, and the rule that accepts a text (aliases and case
/// included), from the port's [`crate::kinds::Choice`] kind.
#[derive(Debug, Clone, Copy)]
pub struct Choices {
    /// The canonical words, in the order a drop-down lists them.
    pub options: &'static [&'static str],
    /// Whether a text names one of them (the parser the node uses).
    pub accepts: fn(&str) -> bool,
}

impl Choices {
    /// `valid: a, b, c` — the end of an error about a text that is none of them.
    pub fn valid_list(&self) -> String {
        format!("valid: {}", self.options.join(", "))
    }
}

impl PartialEq for Choices {
    fn eq(&self, other: &Self) -> bool {
        self.options == other.options
    }
}

/// How a port is shown and edited; everything optional (the default: chosen from the type).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PortHint {
    /// The name shown instead of the port name (e.g. `Apex` for `apex`); the port name stays the
    /// contract.
    pub display_name: Option<Cow<'static, str>>,
    /// The widget for the port's literal value.
    pub widget: Widget,
    /// The range a slider or drag value offers (values outside may still be typed).
    pub soft_range: Option<(f64, f64)>,
    /// The range the node accepts at all (a value outside is clamped or refused by the node).
    pub hard_range: Option<(f64, f64)>,
    /// The step of a drag or a slider.
    pub step: Option<f64>,
    /// For an output: the preview layer it is drawn in (`None`: chosen from the value's type —
    /// surfaces, curves, points).
    pub layer: Option<Layer>,
    /// For an output: what it means to the engine's tools ([`Role`]).
    pub role: Role,
    /// The inputs of the same node that hold this input's range (a slider's `min` and `max`),
    /// declared by the node so tools read the range instead of guessing it.
    pub range_inputs: Option<(&'static str, &'static str)>,
    /// The input of the same node that holds the step this input snaps to (a slider's `step`):
    /// with a positive step the value moves in whole steps, which a continuous solve (dragging
    /// the net) cannot take.
    pub step_input: Option<&'static str>,
    /// The input of the same node that holds the options a [`Widget::Choice`] index picks from
    /// (a Value list's `options`): the editor's drop-down lists them, and edits them in that
    /// input's own field.
    pub options_input: Option<&'static str>,
    /// The input of the same node that names the item type of this list input (a list of
    /// numbers' `item_type`): the list editor's new rows take that type.
    pub item_type_input: Option<&'static str>,
}

/// Builder of a [`PortHint`], fed by `#[ui(key = value, …)]` in `node!`.
#[derive(Debug, Default)]
pub struct HintBuilder(pub PortHint);

impl HintBuilder {
    /// `name = "…"`: the display name.
    pub fn name(&mut self, name: &'static str) {
        self.0.display_name = Some(Cow::Borrowed(name));
    }

    /// `widget = Slider`: the widget.
    pub fn widget(&mut self, widget: Widget) {
        self.0.widget = widget;
    }

    /// `range = 0.0..=1.0`: the soft range.
    pub fn range(&mut self, range: RangeInclusive<f64>) {
        self.0.soft_range = Some((*range.start(), *range.end()));
    }

    /// `hard = 0.0..=1.0`: the hard range.
    pub fn hard(&mut self, range: RangeInclusive<f64>) {
        self.0.hard_range = Some((*range.start(), *range.end()));
    }

    /// `step = 0.01`: the step.
    pub fn step(&mut self, step: f64) {
        self.0.step = Some(step);
    }

    /// `layer = Supports`: the preview layer of an output.
    pub fn layer(&mut self, layer: Layer) {
        self.0.layer = Some(layer);
    }

    /// `range_inputs = ("min", "max")`: the sibling inputs that hold this input's range.
    pub fn range_inputs(&mut self, names: (&'static str, &'static str)) {
        self.0.range_inputs = Some(names);
    }

    /// `step_input = "step"`: the sibling input that holds the step this input snaps to.
    pub fn step_input(&mut self, name: &'static str) {
        self.0.step_input = Some(name);
    }

    /// `options_input = "options"`: the sibling input that holds a choice's options.
    pub fn options_input(&mut self, name: &'static str) {
        self.0.options_input = Some(name);
    }

    /// `item_type_input = "item_type"`: the sibling input that names a list's item type.
    pub fn item_type_input(&mut self, name: &'static str) {
        self.0.item_type_input = Some(name);
    }

    /// `role = FaceMargins`: what an output means to the engine's tools.
    pub fn role(&mut self, role: Role) {
        self.0.role = role;
    }
}
