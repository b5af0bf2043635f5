//! The preview's layers: the groups of geometry the 3D view shows or hides (View ▸ layers,
//! `cnets render --layers`), and the layer an output declares it is drawn in (`#[ui(layer =
//! Supports)]` in `node!`; an output that declares none is placed by its value's type).

/// A toggleable group of preview geometry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Layer {
    /// Meshes.
    Surfaces,
    /// Mesh edges.
    Edges,
    /// Polylines and segment sets (directrix, generatrix, …).
    Curves,
    /// Cone apices.
    Apices,
    /// Torsion-free node axes.
    Axes,
    /// Support layers.
    Supports,
    /// Other points.
    Points,
    /// Unrolled strips laid flat for the cutter (`pq.unroll_strips`, `fab.nest`: outlines and
    /// label points), drawn in the XY plane far from the design: off unless asked.
    Unrolled,
}

impl Layer {
    /// All layers, for menus.
    pub const ALL: [Layer; 8] = [
        Layer::Surfaces,
        Layer::Edges,
        Layer::Curves,
        Layer::Apices,
        Layer::Axes,
        Layer::Supports,
        Layer::Points,
        Layer::Unrolled,
    ];

    /// Layers off until asked for: apex dots (far from the surface, they clutter the view) and
    /// unrolled strips (flat on the XY plane, away from the design).
    pub const OFF_BY_DEFAULT: [Layer; 2] = [Layer::Apices, Layer::Unrolled];

    /// Menu label.
    pub fn label(self) -> &'static str {
        match self {
            Layer::Surfaces => "Surfaces",
            Layer::Edges => "Edges",
            Layer::Curves => "Curves (directrix…)",
            Layer::Apices => "Apices",
            Layer::Axes => "Torsion-free axes",
            Layer::Supports => "Support layers",
            Layer::Points => "Points",
            Layer::Unrolled => "Unrolled strips (flat)",
        }
    }

    /// Short name for command lines: surfaces, edges, curves, apices, axes, supports, points,
    /// unrolled.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Surfaces => "surfaces",
            Layer::Edges => "edges",
            Layer::Curves => "curves",
            Layer::Apices => "apices",
            Layer::Axes => "axes",
            Layer::Supports => "supports",
            Layer::Points => "points",
            Layer::Unrolled => "unrolled",
        }
    }

    /// The layer with this short name.
    pub fn parse(name: &str) -> Option<Layer> {
        Layer::ALL
            .into_iter()
            .find(|l| l.name().eq_ignore_ascii_case(name.trim()))
    }

    /// The word `cnets nodes --json` and docs/nodes.md print for an output declaring this layer
    /// (`support`, `fabrication`, `apices`, `axes`; the others by their short name).
    pub fn hint_word(self) -> &'static str {
        match self {
            Layer::Supports => "support",
            Layer::Unrolled => "fabrication",
            other => other.name(),
        }
    }
}
