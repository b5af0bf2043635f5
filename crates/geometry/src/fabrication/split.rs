//! Splitting unrolled strips into pieces that fit a sheet (issue 43, `max_length`).
//!
//! A strip is cut only at folds (the rung between two panels), so every piece is a chain of whole
//! panels and each joint is a straight line both pieces have. The *length* of a chain is the long
//! side of its minimum-area rectangle — the length it takes on a sheet once [`super::layout::stack`]
//! turns it. Pieces are grown greedily from the strip's first panel: a panel joins the current piece
//! while the piece stays ≤ `max_length`, otherwise it starts the next piece. A strip already
//! ≤ `max_length` stays whole with its label; a longer one becomes `D4.1`, `D4.2`, … (a mirror label
//! keeps its note: `D9.1 (mirror of D2)`). A single panel longer than `max_length` is an error naming
//! it. The pieces are laid out again as the strips were (turned to their rectangle, stacked along +y
//! with `spacing`), each by one rigid motion, so every panel keeps its shape.
//!
//! Every joint gives a mark on both pieces: the joint line itself, labelled `D4.1 | D4.2` (the
//! neighbour marks of [`super::marks`] add the other piece's name on each side as well).

use glam::{DVec2, DVec3};

use super::FabricationError;
use super::layout;
use super::marks::Mark;
use super::panels::{Panel, StripPanels, outline_of, shared_edge};
use crate::Polyline;

/// Strips split into pieces and laid out.
#[derive(Debug, Clone, PartialEq)]
pub struct Pieces {
    /// Every piece (a whole strip when it was short enough), in strip order.
    pub pieces: Vec<StripPanels>,
    /// The closed outline of every piece in the new layout.
    pub outlines: Vec<Polyline>,
    /// A label position inside every piece: the centroid of its middle panel.
    pub label_points: Vec<DVec3>,
    /// The joint lines, once on each of the two pieces they join.
    pub joints: Vec<Mark>,
}

/// The length of a set of flat points: the long side of their minimum-area rectangle.
pub fn chain_length(points: &[DVec2]) -> f64 {
    let angle = layout::min_area_angle(points);
    let turned: Vec<DVec2> = points.iter().map(|p| layout::rotate(*p, angle)).collect();
    layout::bounds(&turned).map_or(0.0, |(lo, hi)| (hi - lo).max_element())
}

fn flat_points(panels: &[Panel]) -> Vec<DVec2> {
    panels
        .iter()
        .flat_map(|p| p.flat.iter().map(|q| q.truncate()))
        .collect()
}

/// The panel ranges of one strip's pieces.
fn ranges(strip: &StripPanels, max_length: f64) -> Result<Vec<(usize, usize)>, FabricationError> {
    let n = strip.panels.len();
    if chain_length(&flat_points(&strip.panels)) <= max_length {
        return Ok(vec![(0, n)]);
    }
    let mut out = Vec::new();
    let mut start = 0;
    while start < n {
        let alone = chain_length(&flat_points(&strip.panels[start..start + 1]));
        if alone > max_length {
            return Err(FabricationError::PanelTooLong {
                strip: strip.name.clone(),
                panel: start,
                length: alone,
                max_length,
            });
        }
        let mut end = start + 1;
        while end < n && chain_length(&flat_points(&strip.panels[start..end + 1])) <= max_length {
            end += 1;
        }
        out.push((start, end));
        start = end;
    }
    Ok(out)
}

/// Splits every strip longer than `max_length` into pieces and lays all pieces out (see the module
/// docs). `spacing`: the gap between pieces (`None`: a tenth of the tallest).
pub fn split_strips(
    strips: &[StripPanels],
    max_length: f64,
    spacing: Option<f64>,
) -> Result<Pieces, FabricationError> {
    if !(max_length.is_finite() && max_length > 0.0) {
        return Err(FabricationError::BadParameter {
            what: "max_length",
            value: max_length,
            expected: "a finite number > 0",
        });
    }
    let mut pieces: Vec<StripPanels> = Vec::new();
    // (piece, next piece of the same strip) for the joints.
    let mut joined: Vec<(usize, usize)> = Vec::new();
    for strip in strips {
        let parts = ranges(strip, max_length)?;
        let whole = parts.len() == 1;
        for (p, &(a, b)) in parts.iter().enumerate() {
            let name = if whole {
                strip.name.clone()
            } else {
                format!("{}.{}", strip.name, p + 1)
            };
            if p > 0 {
                joined.push((pieces.len() - 1, pieces.len()));
            }
            pieces.push(StripPanels {
                label: strip.label.replacen(&strip.name, &name, 1),
                name,
                panels: strip.panels[a..b].to_vec(),
                first_panel: strip.first_panel + a,
                collapsed: strip
                    .collapsed
                    .iter()
                    .filter(|c| (a..b).contains(&c.panel))
                    .map(|c| super::CollapsedEdge {
                        panel: c.panel - a,
                        ..*c
                    })
                    .collect(),
            });
        }
    }
    let outlines: Vec<Polyline> = pieces
        .iter()
        .map(|p| {
            outline_of(&p.panels).ok_or_else(|| FabricationError::DegenerateFace {
                what: "split",
                face: p.first_panel,
                reason: format!("piece {}: its panels do not bound one flat piece", p.name),
            })
        })
        .collect::<Result<_, _>>()?;
    let mut shapes: Vec<Vec<DVec2>> = outlines
        .iter()
        .map(|o| o.points.iter().map(|p| p.truncate()).collect())
        .collect();
    let gap = spacing.unwrap_or_else(|| layout::default_gap(&shapes));
    let maps = layout::stack(&mut shapes, gap);
    let to3 = |p: DVec2| DVec3::new(p.x, p.y, 0.0);
    let mut label_points = Vec::with_capacity(pieces.len());
    for (piece, &(angle, shift)) in pieces.iter_mut().zip(&maps) {
        for panel in &mut piece.panels {
            for q in &mut panel.flat {
                *q = to3(layout::rotate(q.truncate(), angle) + shift);
            }
        }
        let mid = &piece.panels[piece.panels.len() / 2].flat;
        label_points.push(mid.iter().sum::<DVec3>() / mid.len() as f64);
    }
    let outlines = shapes
        .into_iter()
        .map(|s| Polyline::closed(s.into_iter().map(to3).collect()))
        .collect();
    let mut joints = Vec::with_capacity(2 * joined.len());
    for (a, b) in joined {
        let (last, first) = (
            pieces[a].panels.last().expect("a piece has panels"),
            pieces[b].panels.first().expect("a piece has panels"),
        );
        let Some((ea, eb)) = shared_edge(last, first) else {
            continue;
        };
        let label = format!("{} | {}", pieces[a].name, pieces[b].name);
        joints.push(Mark {
            strip: a,
            line: ea.iter().map(|&i| last.flat[i]).collect(),
            label: label.clone(),
        });
        joints.push(Mark {
            strip: b,
            line: eb.iter().map(|&i| first.flat[i]).collect(),
            label,
        });
    }
    Ok(Pieces {
        pieces,
        outlines,
        label_points,
        joints,
    })
}
