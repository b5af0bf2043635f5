//! Display options of the preview: the colour mode and the layers shown.

use cnets_render::ToleranceMap;

/// How surfaces are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum ColorMode {
    /// By face class (paper Fig. 5b: the configurations of a face's two support-strip quads) from
    /// the construction node's `configurations` output; plain when the node has none.
    #[default]
    Configuration,
    /// By per-face planarity (viridis on a log scale anchored to tolerances: planar below 1e-9
    /// relative, not planar from 1e-3; `ToleranceMap`).
    Planarity,
    /// By distance to a reference mesh ([`PreviewOptions::distance_to`]), viridis from 0 to the
    /// largest distance, the legend in metres: each vertex of every other previewed mesh (the
    /// net) by its distance to the reference, or each vertex of the reference by its distance to
    /// the net ([`PreviewOptions::distance_side`]). The figures are the fit objective's
    /// symmetric, area-weighted measure between the net and the reference.
    Distance,
    /// One colour (each node's own preview colour, when it has one).
    Plain,
}

impl ColorMode {
    /// All modes, for menus.
    pub const ALL: [ColorMode; 4] = [
        ColorMode::Configuration,
        ColorMode::Planarity,
        ColorMode::Distance,
        ColorMode::Plain,
    ];

    /// Menu label.
    pub fn label(self) -> &'static str {
        match self {
            ColorMode::Configuration => "Configuration class",
            ColorMode::Planarity => "Planarity",
            ColorMode::Distance => "Distance to a reference",
            ColorMode::Plain => "Plain",
        }
    }
}

/// Which side [`ColorMode::Distance`] colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum DistanceSide {
    /// The net (every previewed mesh but the reference), each vertex by its distance to the
    /// reference: where the net strays from the reference.
    #[default]
    Net,
    /// The reference (drawn even when not previewed), each vertex by its distance to the net,
    /// the net drawn translucent over it: where the reference is far from the net — a gap the
    /// net's own colours cannot show.
    Reference,
}

impl DistanceSide {
    /// Menu label.
    pub fn label(self) -> &'static str {
        match self {
            DistanceSide::Net => "Colour the net (its distance to the reference)",
            DistanceSide::Reference => "Colour the reference (its distance to the net)",
        }
    }
}

pub use cnets_engine::Layer;

/// The bit of `layer` in [`PreviewOptions`]' set of shown layers.
fn bit(layer: Layer) -> u8 {
    1 << (layer as u8)
}

/// Display options of the viewport: colour mode and visible layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct PreviewOptions {
    /// Surface colouring.
    pub color_mode: ColorMode,
    /// The reference of [`ColorMode::Distance`]: the [`uid`](cnets_engine::NodeInstance::uid) of
    /// the node whose first mesh output the other meshes are measured against (`None`: not picked
    /// yet; the meshes are then drawn plainly).
    pub distance_to: Option<u64>,
    /// What [`ColorMode::Distance`] colours: the net or the reference.
    pub distance_side: DistanceSide,
    layers: u8,
    /// The top of the planarity scale (see [`PreviewOptions::planarity_limit`]), as `f64` bits
    /// so the options stay `Eq`; read through serde only within [`PLANARITY_LIMIT_RANGE`].
    #[serde(deserialize_with = "limit_in_range")]
    planarity_limit: u64,
}

impl Default for PreviewOptions {
    fn default() -> Self {
        Self {
            color_mode: ColorMode::default(),
            distance_to: None,
            distance_side: DistanceSide::Net,
            layers: Layer::ALL
                .iter()
                .filter(|l| !Layer::OFF_BY_DEFAULT.contains(l))
                .fold(0, |acc, l| acc | bit(*l)),
            planarity_limit: ToleranceMap::DEFAULT.limit.to_bits(),
        }
    }
}

/// The smallest and largest planarity limit a designer can set (the scale's bottom, 1e-9
/// relative, stays the anchor).
pub const PLANARITY_LIMIT_RANGE: (f64, f64) = (1e-8, 1.0);

/// Reads a planarity limit's bits, refusing a limit outside [`PLANARITY_LIMIT_RANGE`].
fn limit_in_range<'de, D: serde::Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
    use serde::Deserialize as _;
    use serde::de::Error as _;
    let bits = u64::deserialize(d)?;
    if PreviewOptions::default().set_planarity_limit(f64::from_bits(bits)) {
        Ok(bits)
    } else {
        Err(D::Error::custom(format!(
            "a planarity limit of {} is outside {PLANARITY_LIMIT_RANGE:?}",
            f64::from_bits(bits)
        )))
    }
}

impl PreviewOptions {
    /// The user-set top of the planarity colour scale: faces from this relative planarity up are
    /// "not planar" (default 1e-3). The bottom stays anchored at 1e-9 ([`ToleranceMap::DEFAULT`]).
    pub fn planarity_limit(&self) -> f64 {
        f64::from_bits(self.planarity_limit)
    }

    /// Sets the top of the planarity scale; refused (false) unless finite and within
    /// [`PLANARITY_LIMIT_RANGE`].
    pub fn set_planarity_limit(&mut self, limit: f64) -> bool {
        let (lo, hi) = PLANARITY_LIMIT_RANGE;
        if !(limit.is_finite() && (lo..=hi).contains(&limit)) {
            return false;
        }
        self.planarity_limit = limit.to_bits();
        true
    }

    /// The planarity colour scale: planar below 1e-9, not planar from the user-set limit.
    pub fn planarity_map(&self) -> ToleranceMap {
        ToleranceMap {
            planar: ToleranceMap::DEFAULT.planar,
            limit: self.planarity_limit(),
        }
    }

    /// Whether a layer is shown.
    pub fn shows(&self, layer: Layer) -> bool {
        self.layers & bit(layer) != 0
    }

    /// Shows or hides a layer.
    pub fn set(&mut self, layer: Layer, on: bool) {
        if on {
            self.layers |= bit(layer);
        } else {
            self.layers &= !bit(layer);
        }
    }
}
