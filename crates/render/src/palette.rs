//! Colours and colour maps: the default look, a perceptual sequential map for planarity values and
//! fixed, distinguishable colours for the four configuration classes of a cone-net.
//!
//! All colours are sRGB-encoded 8-bit RGBA ([`Color`]); the renderer lights them in linear space and
//! writes sRGB-encoded values again, so what you pick is what you see on a flat, facing surface.

use bytemuck::{Pod, Zeroable};

/// An sRGB-encoded RGBA colour, 8 bits per channel (alpha 255 = opaque).
#[repr(C)]
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    Default,
    Pod,
    Zeroable,
    serde::Serialize,
    serde::Deserialize,
)]
pub struct Color(pub [u8; 4]);

impl Color {
    /// Opaque white.
    pub const WHITE: Color = Color::rgb(255, 255, 255);
    /// Opaque black.
    pub const BLACK: Color = Color::rgb(0, 0, 0);

    /// An opaque colour from sRGB bytes.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Self {
        Self([r, g, b, 255])
    }

    /// A colour from sRGB bytes and alpha.
    pub const fn rgba(r: u8, g: u8, b: u8, a: u8) -> Self {
        Self([r, g, b, a])
    }

    /// An opaque colour from `0xRRGGBB`.
    pub const fn hex(rgb: u32) -> Self {
        Self::rgb((rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8)
    }

    /// The same colour with another alpha.
    pub const fn with_alpha(self, a: u8) -> Self {
        Self([self.0[0], self.0[1], self.0[2], a])
    }

    /// Channels as `0..=1` floats (still sRGB-encoded).
    pub fn to_f32(self) -> [f32; 4] {
        self.0.map(|c| f32::from(c) / 255.0)
    }

    /// A colour from `0..=1` sRGB-encoded floats (clamped; NaN becomes 0).
    pub fn from_f32(rgba: [f32; 4]) -> Self {
        Self(rgba.map(|c| {
            let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
            (c * 255.0).round() as u8
        }))
    }

    /// Channel-wise linear interpolation in sRGB space (`t` clamped to `0..=1`).
    pub fn lerp(self, other: Color, t: f32) -> Self {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        let (a, b) = (self.to_f32(), other.to_f32());
        Self::from_f32([0, 1, 2, 3].map(|k| a[k] + (b[k] - a[k]) * t))
    }

    /// The colour as `wgpu::Color` with sRGB-encoded components, as clear colour of a `*Unorm` target.
    pub fn to_wgpu(self) -> wgpu::Color {
        let [r, g, b, a] = self.to_f32().map(f64::from);
        wgpu::Color { r, g, b, a }
    }
}

/// Default viewport background: a light, neutral grey.
pub const BACKGROUND: Color = Color::hex(0xeceef1);
/// Default surface colour: a light blue-grey that shades well under the headlight.
pub const SURFACE: Color = Color::hex(0xb8c6d6);
/// Default colour of mesh edges (slightly translucent, so dense meshes do not turn black).
pub const EDGE: Color = Color::hex(0x1e232b).with_alpha(150);
/// Default colour of polylines and segments.
pub const LINE: Color = Color::hex(0x1f5fbf);
/// Default colour of point markers.
pub const POINT: Color = Color::hex(0xd0312d);
/// Colour used for values that cannot be mapped (NaN).
pub const INVALID: Color = Color::hex(0xff00ff);

/// Viridis (matplotlib) sampled at 0, 0.1, …, 1; interpolated linearly in between.
const VIRIDIS: [u32; 11] = [
    0x440154, 0x482475, 0x414487, 0x355f8d, 0x2a788e, 0x21918c, 0x22a884, 0x44bf70, 0x7ad151,
    0xbddf26, 0xfde725,
];

/// The perceptual sequential map (viridis) at `t` in `0..=1` (clamped; NaN gives [`INVALID`]).
pub fn viridis(t: f32) -> Color {
    if t.is_nan() {
        return INVALID;
    }
    let x = t.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f32;
    let k = (x.floor() as usize).min(VIRIDIS.len() - 2);
    Color::hex(VIRIDIS[k]).lerp(Color::hex(VIRIDIS[k + 1]), x - k as f32)
}

/// A sequential colour map over a value range (e.g. planarity), with the description of its legend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SequentialMap {
    /// Value mapped to the first colour.
    pub min: f64,
    /// Value mapped to the last colour.
    pub max: f64,
}

impl SequentialMap {
    /// A map over `min..=max` (swapped if given the wrong way round).
    pub fn new(min: f64, max: f64) -> Self {
        if min <= max {
            Self { min, max }
        } else {
            Self { min: max, max: min }
        }
    }

    /// A map over the finite values of `values` (`0..=1` when there are none).
    pub fn fit(values: &[f64]) -> Self {
        let (lo, hi) = values
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        if lo > hi {
            Self::new(0.0, 1.0)
        } else {
            Self::new(lo, hi)
        }
    }

    /// Position of `value` in the range, `0..=1` (0.5 for an empty range; NaN stays NaN).
    pub fn normalize(&self, value: f64) -> f32 {
        let span = self.max - self.min;
        if value.is_nan() {
            f32::NAN
        } else if span <= 0.0 || !span.is_finite() {
            0.5
        } else {
            (((value - self.min) / span).clamp(0.0, 1.0)) as f32
        }
    }

    /// The colour of one value (NaN gives [`INVALID`]).
    pub fn color(&self, value: f64) -> Color {
        viridis(self.normalize(value))
    }

    /// One colour per value, e.g. per-face colours for [`crate::FaceColors::PerFace`].
    pub fn colors(&self, values: &[f64]) -> Vec<Color> {
        values.iter().map(|&v| self.color(v)).collect()
    }

    /// The legend: the range and `stops` evenly spaced colour stops from min to max.
    pub fn legend(&self, title: &str, stops: usize) -> Legend {
        let n = stops.max(2);
        Legend {
            title: title.to_string(),
            min: self.min,
            max: self.max,
            stops: (0..n)
                .map(|k| {
                    let t = k as f32 / (n - 1) as f32;
                    (self.min + (self.max - self.min) * f64::from(t), viridis(t))
                })
                .collect(),
            labels: Vec::new(),
        }
    }
}

/// A planarity colour scale anchored to tolerances rather than stretched to the data: values up to
/// `planar` (relative planarity: rounding noise) take the first colour, values from `limit` up the
/// last, and in between the colour follows the logarithm of the value. A mesh planar to rounding
/// error is one calm colour, not a patchwork of 1e-16 and 1e-15.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToleranceMap {
    /// Below this, a face counts as planar.
    pub planar: f64,
    /// From this up, a face counts as not planar (the top of the scale).
    pub limit: f64,
}

impl ToleranceMap {
    /// Planar below 1e-9 relative (the paper's constructions are exact to rounding), not planar
    /// from 1e-3 (a millimetre on a metre panel).
    pub const DEFAULT: Self = Self {
        planar: 1e-9,
        limit: 1e-3,
    };

    /// Position of `value` on the scale, `0..=1` (NaN stays NaN).
    pub fn normalize(&self, value: f64) -> f32 {
        if value.is_nan() {
            return f32::NAN;
        }
        if value <= self.planar || self.limit <= self.planar {
            return 0.0;
        }
        ((value / self.planar).log10() / (self.limit / self.planar).log10()).clamp(0.0, 1.0) as f32
    }

    /// The colour of one value (NaN gives [`INVALID`]).
    pub fn color(&self, value: f64) -> Color {
        viridis(self.normalize(value))
    }

    /// The legend in words: planar, the decades between, not planar.
    pub fn legend(&self) -> Legend {
        let decades = (self.limit / self.planar).log10().round().max(1.0) as i32;
        let step = (decades / 3).max(1);
        let mut stops = vec![(self.planar, viridis(0.0))];
        let mut labels = vec![format!("planar (< {:.0e})", self.planar)];
        let mut k = step;
        while k < decades {
            let v = self.planar * 10f64.powi(k);
            stops.push((v, self.color(v)));
            labels.push(format!("{v:.0e}"));
            k += step;
        }
        stops.push((self.limit, viridis(1.0)));
        labels.push(format!("not planar (≥ {:.0e})", self.limit));
        Legend {
            title: "planarity (relative)".into(),
            min: self.planar,
            max: self.limit,
            stops,
            labels,
        }
    }
}

/// What a colour legend shows: a title, the value range and colour stops from min to max.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Legend {
    /// E.g. "planarity".
    pub title: String,
    /// Value at the bottom of the scale.
    pub min: f64,
    /// Value at the top of the scale.
    pub max: f64,
    /// `(value, colour)` pairs from min to max.
    pub stops: Vec<(f64, Color)>,
    /// A label per stop, in words (empty: write the values).
    pub labels: Vec<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tolerance_map_is_anchored_not_stretched() {
        let m = ToleranceMap::DEFAULT;
        // Rounding noise is planar, whatever its spread.
        assert_eq!(m.color(1e-16), m.color(3e-15));
        assert_eq!(m.color(0.0), viridis(0.0));
        assert_eq!(m.color(1e-2), viridis(1.0));
        assert!(
            (m.normalize(1e-6) - 0.5).abs() < 1e-6,
            "log scale: 1e-6 is half way"
        );
        let l = m.legend();
        assert_eq!(l.stops.len(), l.labels.len());
        assert!(l.labels[0].starts_with("planar"), "{:?}", l.labels);
        assert!(l.labels.last().unwrap().starts_with("not planar"));
    }

    #[test]
    fn viridis_ends_and_monotone_lightness() {
        assert_eq!(viridis(0.0), Color::hex(0x440154));
        assert_eq!(viridis(1.0), Color::hex(0xfde725));
        assert_eq!(viridis(-3.0), viridis(0.0));
        assert_eq!(viridis(f32::NAN), INVALID);
        // Perceptual map: luma increases along the map.
        let luma = |c: Color| {
            let [r, g, b, _] = c.to_f32();
            0.2126 * r + 0.7152 * g + 0.0722 * b
        };
        let l: Vec<f32> = (0..=20).map(|k| luma(viridis(k as f32 / 20.0))).collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
    }

    #[test]
    fn sequential_map_range_and_legend() {
        let m = SequentialMap::fit(&[3.0, f64::NAN, 1.0, 2.0]);
        assert_eq!((m.min, m.max), (1.0, 3.0));
        assert_eq!(m.normalize(2.0), 0.5);
        assert_eq!(m.color(1.0), viridis(0.0));
        assert_eq!(m.color(99.0), viridis(1.0));
        assert_eq!(SequentialMap::new(5.0, 5.0).normalize(5.0), 0.5);
        let legend = m.legend("planarity", 5);
        assert_eq!(legend.stops.len(), 5);
        assert_eq!(legend.stops[4], (3.0, viridis(1.0)));
        assert_eq!(SequentialMap::fit(&[]).max, 1.0);
    }
}
