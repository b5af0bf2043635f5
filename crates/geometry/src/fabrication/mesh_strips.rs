//! Strips of a polygon mesh that was a quad grid (PQ Strip Unroll of cut and mirrored nets, issue 32).
//!
//! A cone-net cut by a plane (`mesh.cut_by_plane`), mirrored (`mesh.mirror`), joined or welded is no
//! longer a grid, but its strips are still chains of planar faces: whole quads, and the faces the cut
//! trimmed (a triangle, a quad or a pentagon keeping one, two or three corners of a quad). This module
//! finds those chains from the mesh's topology and unrolls them.
//!
//! **Edge families.** In a quad grid every edge runs along a row (a directrix polyline, family 0) or
//! a column (a generatrix, family 1), and in every quad the two families alternate: edges 0 and 2 of
//! the converted grid (corners `(i,j) (i,j+1) (i+1,j+1) (i+1,j)`) are row edges. The cut keeps whole
//! faces in their corner order and closes a trimmed face along the plane with its *last* edge
//! (`cut_by_plane`: a kept chain runs from the entry point on the plane to the exit point; the mirror
//! reverses corners, which keeps both properties). So in a face with four corners the edges
//! alternate; in any other face the last edge is the cut and the others alternate. Which family edge
//! 0 of a face has (its *parity*) is found by a breadth-first walk over shared edges, starting in each
//! connected part at its lowest-numbered face with parity 0; an edge that would get two families is
//! an error naming the two faces (the mesh is not a grid or a cut, mirror or join of one). A face of
//! four corners trimmed by the cut (two corners kept) is read as a quad: its cut edge then takes the
//! family of the opposite edge, which is where the strip through it ends.
//!
//! **Strips.** A directrix strip is a chain of faces joined by shared column edges (its *rungs*), a
//! generatrix strip one joined by shared row edges. Strips end at the cut and at a mirror seam: an
//! edge between a face and its mirror image in a plane through that edge (the image's corners run
//! the other way, as `mesh.mirror` writes them), so the two halves of a mirrored net are separate
//! parts, each half's strip labelled with the other. Every face has at most two rung edges, so the
//! chains are paths or cycles (a wrapped strip, opened at its first rung). Strips are numbered in the
//! order of their lowest face index (for an uncut grid: the grid's own strip numbers).
//!
//! **Unrolling.** As for quad grids ([`super::unroll`]): the first face is laid flat in the frame of
//! its first rung and Newell normal, every next face is placed by the rotation that puts its shared
//! rung on the rung already placed, keeping its orientation (a face whose corner order runs the same
//! way along the rung as its predecessor's, in a mesh not consistently oriented, is turned over). The
//! outline is the boundary of the placed faces; the strips are laid out as the grid strips are.
//!
//! **Panels of their own.** A face of more than five corners is neither a quad nor a quad the cut
//! trimmed: a transom, a panel closing a cut. It is in no chain (edge families and strips pass it
//! by) and is laid flat alone, named `P<k>` (numbered apart from the strips), in either direction.
//!
//! **Copies.** A strip whose outline is congruent to an earlier one's (edge lengths and turning angles
//! equal within 1e-7 of the strip's size) is labelled with it: `D7 (mirror of D2)` when it is the mirror
//! image — the mirrored half of a hull — or `D7 (copy of D2)` when it is the same part.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::FabricationError;
use super::collapsed::{CollapsedEdge, edge_error};
use super::face_attributes::polygon_planarity;
use super::layout;
use super::polygon::{check_mesh, newell};
use super::strips::StripDirection;
use super::unroll::UnrollOptions;
use crate::{PolygonMesh, Polyline, QuadGrid};

/// The family an edge of a face belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Family {
    /// Along a row (directrix polyline): family 0.
    Row,
    /// Along a column (generatrix): family 1.
    Column,
    /// The edge a cut closed a trimmed face with.
    Cut,
}

/// One strip of a polygon mesh: a chain of faces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MeshStrip {
    /// Strip number (in the order of the strips' lowest face index).
    pub index: usize,
    /// The family.
    pub direction: StripDirection,
    /// The faces in chain order.
    pub faces: Vec<usize>,
    /// The rung shared by faces k and k+1, as the two mesh vertex indices.
    pub rungs: Vec<(u32, u32)>,
    /// Whether the last face is joined to the first (a wrapped strip, opened at that rung).
    pub closed: bool,
    /// Its name: `D<n>` or `G<n>`, numbered within its part and prefixed by the part's name
    /// (`wall-D3`) in a mesh of named parts ([`crate::MeshParts`]).
    pub name: String,
}

/// The most corners a face of a strip has: a quad the cut trimmed keeps at most three of its
/// corners and adds two on the plane. A face with more is a panel of its own (`P<k>`).
const MAX_TRIMMED_CORNERS: usize = 5;

/// The family of local edge `t` of a face of `n` corners with parity `p`.
fn family(n: usize, t: usize, p: u8) -> Family {
    if n != 4 && t == n - 1 {
        Family::Cut
    } else if (t as u8 + p).is_multiple_of(2) {
        Family::Row
    } else {
        Family::Column
    }
}

fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// Whether face `g` is the mirror image of face `f` in a plane through their shared edge (edge `t`
/// of `f`, edge `s` of `g`): `mesh.mirror` reverses the corners of the image, so walking `f` forward
/// from the edge meets the reflections of the corners met walking `g` backward, within 1e-9 of the
/// mesh size.
fn mirror_pair(v: &[DVec3], f: &[u32], t: usize, g: &[u32], s: usize, size: f64) -> bool {
    let n = f.len();
    if g.len() != n || s != (2 * n - 2 - t) % n {
        return false;
    }
    let (u, w) = (v[f[t] as usize], v[f[(t + 1) % n] as usize]);
    // Corner k steps after the edge's end in f, and k steps before the edge's start in g.
    let fk = |k: usize| v[f[(t + 1 + k) % n] as usize];
    let gk = |k: usize| v[g[(s + n - k) % n] as usize];
    let Some(normal) = (fk(1) - gk(1)).try_normalize() else {
        return false;
    };
    let tol = 1e-9 * size.max(f64::MIN_POSITIVE);
    let reflect = |p: DVec3| p - normal * (2.0 * (p - u).dot(normal));
    (w - u).dot(normal).abs() <= tol && (1..n - 1).all(|k| reflect(fk(k)).distance(gk(k)) <= tol)
}

/// The strips of a polygon mesh in the given direction (see the module docs).
pub fn mesh_strips(
    mesh: &PolygonMesh,
    direction: StripDirection,
) -> Result<Vec<MeshStrip>, FabricationError> {
    check_mesh(mesh, "mesh")?;
    let faces: Vec<&[u32]> = mesh.faces().collect();
    if faces.is_empty() {
        return Err(FabricationError::Empty("the mesh"));
    }
    let structure = |face: usize, reason: String| FabricationError::DegenerateFace {
        what: "strips",
        face,
        reason,
    };
    // Undirected edge → (face, local edge) of the faces around it.
    let mut edges: HashMap<(u32, u32), Vec<(usize, usize)>> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        for t in 0..face.len() {
            let (a, b) = (face[t], face[(t + 1) % face.len()]);
            if a == b {
                return Err(structure(f, "it repeats a corner".into()));
            }
            edges.entry(edge_key(a, b)).or_default().push((f, t));
        }
    }
    if let Some(list) = edges.values().find(|l| l.len() > 2) {
        return Err(structure(
            list[0].0,
            format!(
                "an edge of it is shared by {} faces; strips need each edge between at most two",
                list.len()
            ),
        ));
    }
    // The named part of every face: strips and edge families stay within one part (one net).
    let part = |f: usize| mesh.parts.of_face.get(f).copied();
    // A face of more than five corners is no quad, nor a quad the cut trimmed (a transom, a
    // closing panel): a panel of its own, in no chain.
    let loose = |f: usize| faces[f].len() > MAX_TRIMMED_CORNERS;
    let neighbour = |f: usize, t: usize| -> Option<(usize, usize)> {
        let face = faces[f];
        let key = edge_key(face[t], face[(t + 1) % face.len()]);
        edges[&key].iter().copied().find(|&(g, _)| g != f)
    };
    // Parity of every face by a breadth-first walk.
    let mut parity: Vec<Option<u8>> = vec![None; faces.len()];
    let mut queue = std::collections::VecDeque::new();
    for seed in 0..faces.len() {
        if parity[seed].is_some() || loose(seed) {
            continue;
        }
        parity[seed] = Some(0);
        queue.push_back(seed);
        while let Some(f) = queue.pop_front() {
            let (n, p) = (faces[f].len(), parity[f].unwrap_or(0));
            for t in 0..n {
                let fam = family(n, t, p);
                if fam == Family::Cut {
                    continue;
                }
                let Some((g, s)) = neighbour(f, t) else {
                    continue;
                };
                if part(g) != part(f) || loose(g) {
                    continue;
                }
                let m = faces[g].len();
                if family(m, s, 0) == Family::Cut {
                    continue;
                }
                let want = ((fam as u8) + s as u8) % 2;
                match parity[g] {
                    None => {
                        parity[g] = Some(want);
                        queue.push_back(g);
                    }
                    Some(q) if q != want => {
                        return Err(structure(
                            f.min(g),
                            format!(
                                "faces {f} and {g} disagree on which way their shared edge runs; the mesh is not a quad grid or a cut, mirror or join of one"
                            ),
                        ));
                    }
                    Some(_) => {}
                }
            }
        }
    }
    let size = {
        let (lo, hi) = mesh
            .vertices
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        (hi - lo).length()
    };
    let rung_family = match direction {
        StripDirection::Directrix => Family::Column,
        StripDirection::Generatrix => Family::Row,
    };
    // Each face's links to the next faces of its strip: (neighbour, rung vertices).
    let links: Vec<Vec<(usize, (u32, u32))>> = faces
        .iter()
        .enumerate()
        .map(|(f, face)| {
            if loose(f) {
                return Vec::new();
            }
            let (n, p) = (face.len(), parity[f].unwrap_or(0));
            (0..n)
                .filter(|&t| family(n, t, p) == rung_family)
                .filter_map(|t| {
                    let (g, s) = neighbour(f, t)?;
                    if part(g) != part(f) || loose(g) {
                        return None;
                    }
                    // A mirror seam: strips end there, as they end at the cut.
                    let seam = mirror_pair(&mesh.vertices, face, t, faces[g], s, size);
                    (!seam).then_some((g, (face[t], face[(t + 1) % n])))
                })
                .collect()
        })
        .collect();
    let mut seen = vec![false; faces.len()];
    let mut out = Vec::new();
    for start in 0..faces.len() {
        if seen[start] {
            continue;
        }
        // Walk back to an end of the chain (or around a cycle).
        let (mut first, mut came_from) = (start, usize::MAX);
        let mut closed = false;
        for _ in 0..faces.len() {
            let back = links[first].iter().find(|(g, _)| *g != came_from);
            match back {
                Some(&(g, _)) if g == start => {
                    closed = true;
                    break;
                }
                Some(&(g, _)) => {
                    came_from = first;
                    first = g;
                }
                None => break,
            }
        }
        if closed {
            // A cycle: open it at its lowest face, heading to its lower neighbour.
            first = start;
        }
        let mut chain = vec![first];
        let mut rungs = Vec::new();
        seen[first] = true;
        let mut here = first;
        let mut prev = usize::MAX;
        loop {
            let mut next: Vec<(usize, (u32, u32))> = links[here]
                .iter()
                .copied()
                .filter(|&(g, _)| g != prev && !seen[g])
                .collect();
            next.sort_by_key(|&(g, _)| g);
            let Some(&(g, rung)) = next.first() else {
                break;
            };
            seen[g] = true;
            chain.push(g);
            rungs.push(rung);
            prev = here;
            here = g;
        }
        let closed = closed && links[here].iter().any(|&(g, _)| g == first);
        // A path starts at its end with the lower face number (an uncut grid's own order).
        if !closed && chain.last() < chain.first() {
            chain.reverse();
            rungs.reverse();
        }
        out.push(MeshStrip {
            index: 0,
            direction,
            faces: chain,
            rungs,
            closed,
            name: String::new(),
        });
    }
    out.sort_by_key(|s| s.faces.iter().copied().min().unwrap_or(0));
    // Strips and loose panels are numbered apart, within each part.
    let mut numbers = vec![(0usize, 0usize); mesh.parts.names.len().max(1)];
    for (k, s) in out.iter_mut().enumerate() {
        s.index = k;
        let owner = part(s.faces[0]).unwrap_or(0) as usize;
        let (strips, panels) = &mut numbers[owner];
        let short = if loose(s.faces[0]) {
            *panels += 1;
            format!("P{}", *panels - 1)
        } else {
            *strips += 1;
            format!("{}{}", direction.prefix(), *strips - 1)
        };
        s.name = match mesh.parts.names.get(owner) {
            Some(name) => format!("{}-{short}", label_word(name)),
            None => short,
        };
    }
    Ok(out)
}

/// A part's name as one word of a label (labels are split at white space for their short name):
/// white space becomes `_`.
fn label_word(name: &str) -> String {
    name.split_whitespace().collect::<Vec<_>>().join("_")
}

/// One strip of a polygon mesh laid flat in the XY plane.
#[derive(Debug, Clone, PartialEq)]
pub struct UnrolledMeshStrip {
    /// Strip number.
    pub index: usize,
    /// `D<n>` or `G<n>`, with `(mirror of D<k>)` or `(copy of D<k>)` for a repeated part.
    pub label: String,
    /// The closed outline (z = 0), counter-clockwise.
    pub outline: Polyline,
    /// Where to put the label: the centroid of the strip's middle face.
    pub label_point: DVec3,
    /// The placed corners of every face, in the mesh's corner order (z = 0).
    pub faces: Vec<Vec<DVec3>>,
    /// The mesh face of every placed face.
    pub mesh_faces: Vec<usize>,
    /// The earlier strip this one is a mirror image of.
    pub mirror_of: Option<usize>,
    /// The earlier strip this one is the same part as.
    pub copy_of: Option<usize>,
    /// Largest relative edge-length change in this strip.
    pub max_length_error: f64,
    /// Largest face planarity in this strip.
    pub max_planarity: f64,
    /// The edges of this strip collapsed to less than [`super::COLLAPSED_EDGE`] of the mesh size.
    pub collapsed: Vec<CollapsedEdge>,
}

/// All strips of one direction of a polygon mesh, unrolled and laid out.
#[derive(Debug, Clone, PartialEq)]
pub struct UnrolledMesh {
    /// The strips, in strip order.
    pub strips: Vec<UnrolledMeshStrip>,
    /// Largest relative edge-length change over all strips.
    pub max_length_error: f64,
    /// Largest face planarity over all strips.
    pub max_planarity: f64,
}

/// A strip placed flat before the layout.
struct FlatStrip {
    faces: Vec<Vec<DVec2>>,
    outline: Vec<DVec2>,
    max_length_error: f64,
    max_planarity: f64,
    collapsed: Vec<CollapsedEdge>,
}

fn flatten(
    mesh: &PolygonMesh,
    strip: &MeshStrip,
    tolerance: f64,
    scale: f64,
) -> Result<FlatStrip, FabricationError> {
    let v = &mesh.vertices;
    let mut placed: Vec<Vec<DVec2>> = Vec::with_capacity(strip.faces.len());
    // +1: corner order runs counter-clockwise when placed; −1: the face was turned over.
    let mut signs: Vec<f64> = Vec::with_capacity(strip.faces.len());
    let (mut max_err, mut max_planarity) = (0.0f64, 0.0f64);
    let mut collapsed = Vec::new();
    for (k, &f) in strip.faces.iter().enumerate() {
        let face = mesh.face(f);
        let corners: Vec<DVec3> = face.iter().map(|&i| v[i as usize]).collect();
        let planarity = polygon_planarity(&corners);
        if !(planarity <= tolerance) {
            return Err(FabricationError::NonPlanarPolygon {
                strip: strip.index,
                face: f,
                planarity,
                tolerance,
            });
        }
        max_planarity = max_planarity.max(planarity);
        let degenerate = |reason: &str| FabricationError::DegenerateFace {
            what: "unroll",
            face: f,
            reason: format!("mesh face {f} of strip {}: {reason}", strip.name),
        };
        let n = newell(&corners).ok_or_else(|| degenerate("it has no area"))?;
        // The rung this face is placed by, and where its ends already are.
        let (u, w, pu, pw, sign) = if k == 0 {
            let (a, b) = strip
                .rungs
                .first()
                .copied()
                .unwrap_or((face[0], face[1 % face.len()]));
            let len = v[a as usize].distance(v[b as usize]);
            (a, b, DVec2::ZERO, DVec2::new(len, 0.0), 1.0)
        } else {
            let (a, b) = strip.rungs[k - 1];
            let prev = mesh.face(strip.faces[k - 1]);
            let pos = |face: &[u32], x: u32| face.iter().position(|&c| c == x);
            let (ia, ib) = (pos(prev, a), pos(prev, b));
            let (ja, jb) = (pos(face, a), pos(face, b));
            let (Some(ia), Some(ib), Some(ja), Some(jb)) = (ia, ib, ja, jb) else {
                return Err(degenerate(
                    "it does not share its rung with the previous face",
                ));
            };
            // Same direction along the rung in both faces: the mesh is not consistently
            // oriented here; turn this face over relative to its predecessor.
            let forward = |i: usize, j: usize, n: usize| (i + 1) % n == j;
            let same = forward(ia, ib, prev.len()) == forward(ja, jb, face.len());
            let sign = if same { -signs[k - 1] } else { signs[k - 1] };
            (a, b, placed[k - 1][ia], placed[k - 1][ib], sign)
        };
        let o = v[u as usize];
        let e1 = (v[w as usize] - o)
            .try_normalize()
            .ok_or_else(|| degenerate("its rung has zero length"))?;
        let e2 = (n * sign)
            .cross(e1)
            .try_normalize()
            .ok_or_else(|| degenerate("its rung is perpendicular to its plane"))?;
        let d = (pw - pu)
            .try_normalize()
            .ok_or_else(|| degenerate("its rung was placed with zero length"))?;
        let d_perp = d.perp();
        let flat: Vec<DVec2> = face
            .iter()
            .map(|&c| {
                if c == u {
                    pu
                } else if c == w {
                    pw
                } else {
                    let p = v[c as usize] - o;
                    pu + d * p.dot(e1) + d_perp * p.dot(e2)
                }
            })
            .collect();
        for e in 0..face.len() {
            let l3 = corners[e].distance(corners[(e + 1) % face.len()]);
            let l2 = flat[e].distance(flat[(e + 1) % face.len()]);
            let (err, short) = edge_error(l3, l2, scale);
            if short {
                collapsed.push(CollapsedEdge {
                    panel: k,
                    edge: e,
                    length: l3,
                });
            }
            max_err = max_err.max(err);
        }
        placed.push(flat);
        signs.push(sign);
    }
    if !max_err.is_finite() || placed.iter().flatten().any(|p| !p.is_finite()) {
        return Err(FabricationError::DegenerateFace {
            what: "unroll",
            face: strip.faces[0],
            reason: format!("strip {}: the unrolled strip overflows", strip.name),
        });
    }
    // The outline: directed boundary edges (counter-clockwise faces), shared rungs cancelled.
    type Key = (u32, u64, u64);
    let key = |c: u32, p: DVec2| -> Key { (c, p.x.to_bits(), p.y.to_bits()) };
    let mut directed: Vec<(Key, Key, DVec2)> = Vec::new();
    for (k, &f) in strip.faces.iter().enumerate() {
        let face = mesh.face(f);
        let mut corners: Vec<(u32, DVec2)> = face
            .iter()
            .copied()
            .zip(placed[k].iter().copied())
            .collect();
        if signs[k] < 0.0 {
            corners.reverse();
        }
        for t in 0..corners.len() {
            let (a, b) = (corners[t], corners[(t + 1) % corners.len()]);
            directed.push((key(a.0, a.1), key(b.0, b.1), a.1));
        }
    }
    let (outline, edges) = super::boundary::boundary_loop(&directed);
    if outline.len() != edges || outline.len() < 3 {
        return Err(FabricationError::DegenerateFace {
            what: "unroll",
            face: strip.faces[0],
            reason: format!(
                "strip {}: its faces do not bound one flat piece (a boundary of {} edges, {} on one loop)",
                strip.index,
                edges,
                outline.len()
            ),
        });
    }
    Ok(FlatStrip {
        faces: placed,
        outline,
        max_length_error: max_err,
        max_planarity,
        collapsed,
    })
}

/// Edge lengths and turning angles of a closed outline, for comparing shapes.
fn shape_signature(points: &[DVec2]) -> Vec<(f64, f64)> {
    let n = points.len();
    (0..n)
        .map(|i| {
            let d0 = points[(i + 1) % n] - points[i];
            let d1 = points[(i + 2) % n] - points[(i + 1) % n];
            (d0.length(), d0.perp_dot(d1).atan2(d0.dot(d1)))
        })
        .collect()
}

/// Whether two signatures are equal up to a cyclic shift, lengths within `tol`, angles within
/// `angle_tol`.
fn same_cycle(a: &[(f64, f64)], b: &[(f64, f64)], tol: f64, angle_tol: f64) -> bool {
    let n = a.len();
    n == b.len()
        && (0..n).any(|shift| {
            (0..n).all(|i| {
                let (x, y) = (a[i], b[(i + shift) % n]);
                (x.0 - y.0).abs() <= tol && (x.1 - y.1).abs() <= angle_tol
            })
        })
}

/// The outline reflected (x → −x) and re-ordered counter-clockwise.
fn reflected(points: &[DVec2]) -> Vec<DVec2> {
    points.iter().rev().map(|p| DVec2::new(-p.x, p.y)).collect()
}

/// Unrolls every strip of a polygon mesh (a cone-net cut, mirrored or joined; see the module docs)
/// and lays them out side by side as [`super::unroll_strips`] does for quad grids. Faces less planar
/// than `options.tolerance` (the measure of [`polygon_planarity`]) are an error naming the strip and
/// the mesh face.
pub fn unroll_mesh_strips(
    mesh: &PolygonMesh,
    direction: StripDirection,
    options: UnrollOptions,
) -> Result<UnrolledMesh, FabricationError> {
    super::unroll::check_options(&options)?;
    let list = mesh_strips(mesh, direction)?;
    let (lo, hi) = mesh
        .vertices
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let scale = (hi - lo).length().max(f64::MIN_POSITIVE);
    let flats = list
        .iter()
        .map(|s| flatten(mesh, s, options.tolerance, scale))
        .collect::<Result<Vec<_>, _>>()?;
    // Repeated parts: compare each outline with the earlier ones.
    let signatures: Vec<Vec<(f64, f64)>> =
        flats.iter().map(|f| shape_signature(&f.outline)).collect();
    let mirrored: Vec<Vec<(f64, f64)>> = flats
        .iter()
        .map(|f| shape_signature(&reflected(&f.outline)))
        .collect();
    let mut repeats: Vec<(Option<usize>, Option<usize>)> = vec![(None, None); flats.len()];
    for b in 0..flats.len() {
        let size = signatures[b].iter().map(|s| s.0).sum::<f64>();
        let (tol, angle_tol) = (1e-7 * size, 1e-7);
        for a in 0..b {
            if repeats[a] != (None, None) {
                continue;
            }
            if same_cycle(&signatures[a], &signatures[b], tol, angle_tol) {
                repeats[b].1 = Some(a);
                break;
            }
            if same_cycle(&mirrored[a], &signatures[b], tol, angle_tol) {
                repeats[b].0 = Some(a);
                break;
            }
        }
    }
    let mut shapes: Vec<Vec<DVec2>> = flats.iter().map(|f| f.outline.clone()).collect();
    let gap = options
        .spacing
        .unwrap_or_else(|| layout::default_gap(&shapes));
    let maps = layout::stack(&mut shapes, gap);
    let to3 = |p: DVec2| DVec3::new(p.x, p.y, 0.0);
    let mut strips = Vec::with_capacity(list.len());
    let (mut max_length_error, mut max_planarity) = (0.0f64, 0.0f64);
    for (((strip, flat), (shape, (angle, shift))), (mirror_of, copy_of)) in list
        .iter()
        .zip(&flats)
        .zip(shapes.into_iter().zip(maps))
        .zip(repeats)
    {
        let moved = |p: DVec2| to3(layout::rotate(p, angle) + shift);
        let mid = &flat.faces[flat.faces.len() / 2];
        let label_point = mid.iter().map(|p| moved(*p)).sum::<DVec3>() / mid.len() as f64;
        max_length_error = max_length_error.max(flat.max_length_error);
        max_planarity = max_planarity.max(flat.max_planarity);
        let mut label = strip.name.clone();
        if let Some(a) = mirror_of {
            label.push_str(&format!(" (mirror of {})", list[a].name));
        } else if let Some(a) = copy_of {
            label.push_str(&format!(" (copy of {})", list[a].name));
        }
        strips.push(UnrolledMeshStrip {
            index: strip.index,
            label,
            outline: Polyline::closed(shape.into_iter().map(to3).collect()),
            label_point,
            faces: flat
                .faces
                .iter()
                .map(|f| f.iter().map(|p| moved(*p)).collect())
                .collect(),
            mesh_faces: strip.faces.clone(),
            mirror_of,
            copy_of,
            max_length_error: flat.max_length_error,
            max_planarity: flat.max_planarity,
            collapsed: flat.collapsed.clone(),
        });
    }
    Ok(UnrolledMesh {
        strips,
        max_length_error,
        max_planarity,
    })
}

/// The quad grid a polygon mesh was converted from (`PolygonMesh::from(&grid)`: every face a quad
/// in row-major order, wrapping as the grid does), when it is exactly one; `None` otherwise.
pub fn grid_of(mesh: &PolygonMesh) -> Option<QuadGrid> {
    let first = mesh.faces().next()?;
    if first.len() != 4 || first[0] != 0 || first[1] != 1 {
        return None;
    }
    let cols = first[3] as usize;
    if cols < 2 || !mesh.vertices.len().is_multiple_of(cols) {
        return None;
    }
    let rows = mesh.vertices.len() / cols;
    for (wrap_rows, wrap_cols) in [(false, false), (false, true), (true, false), (true, true)] {
        let grid = QuadGrid {
            classes: Vec::new(),
            rows,
            cols,
            wrap_rows,
            wrap_cols,
            vertices: mesh.vertices.clone(),
        };
        if grid.validate().is_ok()
            && grid.quad_count() == mesh.face_count()
            && PolygonMesh::from(&grid) == *mesh
        {
            return Some(grid);
        }
    }
    None
}
