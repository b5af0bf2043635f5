//! Cutting outlines shared by the SVG and DXF exports: closed polylines in the XY plane (the output
//! of `pq.unroll_strips`), scaled to millimetres, with optional labels.

use cnets_geometry::{DVec3, Polyline};
use glam::DVec2;

/// Outlines prepared for a cutting file: points in millimetres (x right, y up), labels and their
/// anchor points.
#[derive(Debug, Clone, PartialEq)]
pub struct Sheet {
    /// One closed (or open) path per outline, in mm.
    pub paths: Vec<(Vec<DVec2>, bool)>,
    /// One label per path (empty when none was given).
    pub labels: Vec<String>,
    /// Label anchor per path, in mm.
    pub anchors: Vec<DVec2>,
    /// Lower-left and upper-right corners of everything, in mm.
    pub bounds: (DVec2, DVec2),
    /// Whether some outline was not in the XY plane (its z was dropped).
    pub dropped_z: bool,
    /// The sheet of each outline (`fab.nest`), or `None` when they are not nested.
    pub sheets: Option<Vec<usize>>,
    /// Fold lines (mm) with their text (the signed angle in degrees).
    pub folds: Vec<(Vec<DVec2>, String)>,
    /// Marks (mm) with their text.
    pub marks: Vec<(Vec<DVec2>, String)>,
}

/// Checks and scales the outlines. `scale` is millimetres per model unit (> 0). Labels and label
/// points, when given, must have one entry per outline; without points a label sits at the centre
/// of its outline's bounding box.
pub fn prepare(
    outlines: &[std::sync::Arc<Polyline>],
    labels: Option<&[String]>,
    label_points: Option<&[DVec3]>,
    scale: f64,
) -> Result<Sheet, String> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(format!(
            "scale (millimetres per model unit) must be a finite number > 0, got {scale}"
        ));
    }
    if outlines.is_empty() {
        return Err("nothing to export: no outline".into());
    }
    if let Some(l) = labels
        && l.len() != outlines.len()
    {
        return Err(format!(
            "labels has {} entries, expected {} (one per outline)",
            l.len(),
            outlines.len()
        ));
    }
    if let Some(p) = label_points
        && p.len() != outlines.len()
    {
        return Err(format!(
            "label_points has {} entries, expected {} (one per outline)",
            p.len(),
            outlines.len()
        ));
    }
    let mut paths = Vec::with_capacity(outlines.len());
    let mut anchors = Vec::with_capacity(outlines.len());
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let mut dropped_z = false;
    for (k, o) in outlines.iter().enumerate() {
        if o.points.len() < 2 {
            return Err(format!(
                "outline {k} has {} points, expected at least 2",
                o.points.len()
            ));
        }
        if let Some(v) = o.points.iter().position(|p| !p.is_finite()) {
            return Err(format!("outline {k}, point {v} is not finite"));
        }
        let size =
            cnets_geometry::quad_grid::bounds_of(&o.points).map_or(0.0, |(a, b)| a.distance(b));
        if o.points.iter().any(|p| p.z.abs() > 1e-9 * size.max(1.0)) {
            dropped_z = true;
        }
        let pts: Vec<DVec2> = o.points.iter().map(|p| p.truncate() * scale).collect();
        let (a, b) = pts.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(a, b), p| (a.min(*p), b.max(*p)),
        );
        lo = lo.min(a);
        hi = hi.max(b);
        let anchor = match label_points {
            Some(p) => {
                if !p[k].is_finite() {
                    return Err(format!("label point {k} is not finite"));
                }
                p[k].truncate() * scale
            }
            None => (a + b) * 0.5,
        };
        anchors.push(anchor);
        paths.push((pts, o.closed));
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Err("the outlines overflow after scaling".into());
    }
    Ok(Sheet {
        paths,
        labels: labels.map_or_else(|| vec![String::new(); outlines.len()], <[String]>::to_vec),
        anchors,
        bounds: (lo, hi),
        dropped_z,
        sheets: None,
        folds: Vec::new(),
        marks: Vec::new(),
    })
}

/// Scales workshop lines (folds or marks) to mm with one text each; `what` names them in errors.
fn workshop_lines(
    what: &str,
    lines: &[std::sync::Arc<Polyline>],
    texts: Vec<String>,
    scale: f64,
) -> Result<Vec<(Vec<DVec2>, String)>, String> {
    if texts.len() != lines.len() {
        return Err(format!(
            "{what} has {} entries and its texts {}: give one per line",
            lines.len(),
            texts.len()
        ));
    }
    lines
        .iter()
        .zip(texts)
        .enumerate()
        .map(|(k, (l, t))| {
            if l.points.len() < 2 {
                return Err(format!(
                    "{what} {k} has {} points, expected at least 2",
                    l.points.len()
                ));
            }
            if let Some(v) = l.points.iter().position(|p| !p.is_finite()) {
                return Err(format!("{what} {k}, point {v} is not finite"));
            }
            Ok((l.points.iter().map(|p| p.truncate() * scale).collect(), t))
        })
        .collect()
}

impl Sheet {
    /// Adds the fold lines with their signed angles (degrees, written `+12.50`) and the marks with
    /// their labels (the outputs of `pq.unroll_strips`), scaled by `scale`. Angles and labels, when
    /// given, must have one entry per line.
    pub fn with_workshop_lines(
        mut self,
        folds: Option<&[std::sync::Arc<Polyline>]>,
        fold_angles: Option<&[f64]>,
        marks: Option<&[std::sync::Arc<Polyline>]>,
        mark_labels: Option<&[String]>,
        scale: f64,
    ) -> Result<Self, String> {
        let folds = folds.unwrap_or(&[]);
        let angles = match fold_angles {
            Some(a) => a
                .iter()
                .enumerate()
                .map(|(k, a)| {
                    a.is_finite()
                        .then(|| format!("{a:+.2}"))
                        .ok_or_else(|| format!("fold_angles[{k}] is {a}, expected a finite angle"))
                })
                .collect::<Result<_, _>>()?,
            None => vec![String::new(); folds.len()],
        };
        self.folds = workshop_lines("folds", folds, angles, scale)?;
        let marks = marks.unwrap_or(&[]);
        let labels =
            mark_labels.map_or_else(|| vec![String::new(); marks.len()], <[String]>::to_vec);
        self.marks = workshop_lines("marks", marks, labels, scale)?;
        for p in self.folds.iter().chain(&self.marks).flat_map(|(l, _)| l) {
            self.bounds.0 = self.bounds.0.min(*p);
            self.bounds.1 = self.bounds.1.max(*p);
        }
        Ok(self)
    }

    /// The sheet of every fold line, then of every mark: the sheet of the outline it lies on
    /// ([`cnets_geometry::fabrication::owner_of`]). `None` when the outlines are not on sheets.
    pub fn line_sheets(&self) -> Option<Vec<usize>> {
        let sheets = self.sheets.as_ref()?;
        let flat = |p: &[DVec2]| -> Vec<DVec3> { p.iter().map(|q| q.extend(0.0)).collect() };
        let outlines: Vec<Polyline> = self
            .paths
            .iter()
            .map(|(p, _)| Polyline::closed(flat(p)))
            .collect();
        Some(
            self.folds
                .iter()
                .chain(&self.marks)
                .map(|(l, _)| {
                    cnets_geometry::fabrication::owner_of(&flat(l), &outlines)
                        .map_or(0, |k| sheets[k])
                })
                .collect(),
        )
    }

    /// Whether the drawing has fold lines or marks: then it is written on the workshop layers
    /// `CUT`, `FOLDS`, `MARKS` and `TEXT`.
    pub fn is_workshop(&self) -> bool {
        !(self.folds.is_empty() && self.marks.is_empty())
    }

    /// Assigns every outline to a sheet (one entry per outline, each ≥ 0).
    pub fn with_sheets(mut self, sheets: Option<&[i64]>) -> Result<Self, String> {
        let Some(sheets) = sheets else {
            return Ok(self);
        };
        if sheets.len() != self.paths.len() {
            return Err(format!(
                "sheets has {} entries, expected {} (one per outline)",
                sheets.len(),
                self.paths.len()
            ));
        }
        let sheets = sheets
            .iter()
            .enumerate()
            .map(|(k, &s)| {
                usize::try_from(s)
                    .ok()
                    .filter(|&s| s < 1 << 20)
                    .ok_or_else(|| format!("sheets[{k}] is {s}, expected a sheet index ≥ 0"))
            })
            .collect::<Result<_, _>>()?;
        self.sheets = Some(sheets);
        Ok(self)
    }

    /// The diagonal of the drawing's bounds, in mm.
    pub fn diagonal(&self) -> f64 {
        (self.bounds.1 - self.bounds.0).length()
    }

    /// A stroke width in mm that reads at the drawing's size: 1/1500 of its diagonal, at least a
    /// 0.1 mm hairline (a cutter follows the path's centre line whatever the width).
    pub fn stroke_width(&self) -> f64 {
        (self.diagonal() / 1500.0).max(0.1)
    }

    /// A label height in mm: a quarter of the smallest outline's bounding-box side, at least 1 mm
    /// and at most 10 mm or 1/100 of the drawing's diagonal, whichever is larger.
    pub fn text_height(&self) -> f64 {
        let smallest = self
            .paths
            .iter()
            .map(|(pts, _)| {
                let (a, b) = pts.iter().fold(
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                    |(a, b), p| (a.min(*p), b.max(*p)),
                );
                (b - a).min_element()
            })
            .fold(f64::INFINITY, f64::min);
        (0.25 * smallest).clamp(1.0, (0.01 * self.diagonal()).max(10.0))
    }
}
