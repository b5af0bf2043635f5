//! Cutting a polygon mesh by a plane, keeping one side (`mesh.cut_by_plane`).
//!
//! Signed distances `d_v = ±(p_v − o)·n̂` (sign chosen so the kept side is d ≥ 0); |d| ≤ 1e-12 × the
//! mesh size counts as on the plane (d = 0). A face with no vertex below is kept whole (also a face
//! lying in the plane), a face with no vertex above is dropped. A face with vertices on both sides is
//! split exactly at the plane: an edge from p_u (d_u > 0) to p_v (d_v < 0) is cut at
//! `p_lo + (p_hi − p_lo) d_lo / (d_lo − d_hi)` (lo, hi = lower and higher vertex index, so both faces of
//! an edge get the same new vertex, shared). The kept part of the face boundary falls into *chains*
//! (maximal runs of kept vertices, from the entry point on the plane to the exit point); one chain is
//! one polygon. Several chains (a non-convex face crossing the plane more than twice) are joined along
//! the cut line `n_face × n̂`: the entry and exit points are sorted along it, consecutive pairs bound
//! the segments of the line inside the face, and each exit continues at the entry it is paired with.
//! If the pairing does not alternate (a self-intersecting face) the chains are joined in boundary order
//! (Sutherland–Hodgman). Chains that only touch the plane (one vertex or one edge in it) are dropped.
//! The result is a general polygon mesh (quads, pentagons, triangles) with unused vertices removed;
//! `section` holds the segments where faces were cut.

use std::collections::HashMap;

use glam::DVec3;

use super::FabricationError;
use super::polygon::{check_mesh, newell, size_of};
use crate::plane::unit;
use crate::{Line, Plane, PolygonMesh};

/// The result of a cut.
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// The kept part.
    pub mesh: PolygonMesh,
    /// The segments along which faces were cut (on the plane).
    pub section: Vec<Line>,
    /// Where each vertex of `mesh` came from (for derivatives: the cut is piecewise linear in the
    /// input vertices, its pieces set by the side of the plane each vertex is on).
    pub sources: Vec<VertexSource>,
}

/// Where a vertex of a cut mesh came from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VertexSource {
    /// A copy of this input vertex.
    Copy(u32),
    /// The point where the edge between input vertices `lo` and `hi` (lo < hi) crosses the
    /// plane: `p_lo + (p_hi − p_lo) d_lo / (d_lo − d_hi)`, d the signed distances (positive on
    /// the kept side, non-zero and of opposite signs).
    Cross {
        /// The lower vertex index.
        lo: u32,
        /// The higher vertex index.
        hi: u32,
        /// The signed distance of `lo`.
        d_lo: f64,
        /// The signed distance of `hi`.
        d_hi: f64,
    },
}

/// Builds the output vertices: kept originals and shared edge crossings.
struct Builder<'a> {
    src: &'a [DVec3],
    d: &'a [f64],
    map: Vec<Option<u32>>,
    edges: HashMap<(u32, u32), u32>,
    out: Vec<DVec3>,
    on_plane: Vec<bool>,
    sources: Vec<VertexSource>,
}

impl Builder<'_> {
    fn keep(&mut self, v: u32) -> u32 {
        if let Some(k) = self.map[v as usize] {
            return k;
        }
        let k = self.out.len() as u32;
        self.out.push(self.src[v as usize]);
        self.on_plane.push(self.d[v as usize] == 0.0);
        self.sources.push(VertexSource::Copy(v));
        self.map[v as usize] = Some(k);
        k
    }

    fn cross(&mut self, u: u32, v: u32) -> u32 {
        let key = (u.min(v), u.max(v));
        if let Some(&k) = self.edges.get(&key) {
            return k;
        }
        let (lo, hi) = (key.0 as usize, key.1 as usize);
        let t = self.d[lo] / (self.d[lo] - self.d[hi]);
        let p = self.src[lo] + (self.src[hi] - self.src[lo]) * t;
        let k = self.out.len() as u32;
        self.out.push(p);
        self.on_plane.push(true);
        self.sources.push(VertexSource::Cross {
            lo: key.0,
            hi: key.1,
            d_lo: self.d[lo],
            d_hi: self.d[hi],
        });
        self.edges.insert(key, k);
        k
    }
}

/// Cuts `mesh` by `plane` and keeps the side the normal points to (`keep_positive`) or the other.
pub fn cut_by_plane(
    mesh: &PolygonMesh,
    plane: &Plane,
    keep_positive: bool,
) -> Result<Cut, FabricationError> {
    check_mesh(mesh, "mesh")?;
    if !plane.is_finite() {
        return Err(crate::GeometryError::NonFinite {
            what: "plane",
            index: 0,
        }
        .into());
    }
    let normal = unit(plane.normal, "plane normal")?;
    let sign = if keep_positive { 1.0 } else { -1.0 };
    let raw: Vec<f64> = mesh
        .vertices
        .iter()
        .map(|p| sign * (*p - plane.origin).dot(normal))
        .collect();
    let reach = raw.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    let eps = 1e-12 * size_of(&mesh.vertices).max(reach);
    let d: Vec<f64> = raw
        .iter()
        .map(|&x| if x.abs() <= eps { 0.0 } else { x })
        .collect();
    let mut b = Builder {
        src: &mesh.vertices,
        d: &d,
        map: vec![None; mesh.vertices.len()],
        edges: HashMap::new(),
        out: Vec::new(),
        on_plane: Vec::new(),
        sources: Vec::new(),
    };
    let mut faces: Vec<Vec<u32>> = Vec::with_capacity(mesh.face_count());
    // The mesh face every kept face came from (for the mesh's named parts).
    let mut face_sources: Vec<u32> = Vec::with_capacity(mesh.face_count());
    let mut section = Vec::new();
    for (k, face) in mesh.faces().enumerate() {
        let below = face.iter().any(|&v| d[v as usize] < 0.0);
        let above = face.iter().any(|&v| d[v as usize] > 0.0);
        if !below {
            faces.push(face.iter().map(|&v| b.keep(v)).collect());
        } else if above {
            split_face(face, &d, &mut b, normal, &mut faces, &mut section);
        }
        face_sources.resize(faces.len(), k as u32);
    }
    // Drop repeated corners, faces with fewer than three, and unused vertices.
    let mut used = vec![false; b.out.len()];
    let mut result = PolygonMesh::new();
    let mut kept_faces = Vec::with_capacity(faces.len());
    let mut kept_sources = Vec::with_capacity(faces.len());
    for (mut f, source) in faces.into_iter().zip(face_sources) {
        f.dedup();
        while f.len() > 1 && f.first() == f.last() {
            f.pop();
        }
        if f.len() >= 3 {
            for &v in &f {
                used[v as usize] = true;
            }
            kept_faces.push(f);
            kept_sources.push(source);
        }
    }
    let mut remap = vec![u32::MAX; b.out.len()];
    let mut sources = Vec::with_capacity(b.out.len());
    for (k, p) in b.out.iter().enumerate() {
        if used[k] {
            remap[k] = result.push_vertex(*p);
            sources.push(b.sources[k]);
        }
    }
    for f in kept_faces {
        let f: Vec<u32> = f.iter().map(|&v| remap[v as usize]).collect();
        result.push_face(&f)?;
    }
    result.carry_faces_from(mesh, &kept_sources);
    Ok(Cut {
        mesh: result,
        section,
        sources,
    })
}

/// A kept run of the face boundary: output vertex indices from the entry point to the exit point.
struct Chain {
    points: Vec<u32>,
}

/// Splits one face that has vertices on both sides.
fn split_face(
    face: &[u32],
    d: &[f64],
    b: &mut Builder<'_>,
    normal: DVec3,
    faces: &mut Vec<Vec<u32>>,
    section: &mut Vec<Line>,
) {
    let n = face.len();
    let dv = |k: usize| d[face[k % n] as usize];
    let start = (0..n).find(|&k| dv(k) < 0.0).unwrap_or(0);
    let mut chains: Vec<Chain> = Vec::new();
    let mut current: Option<Vec<u32>> = None;
    for step in 1..=n {
        let (prev, k) = (start + step - 1, start + step);
        let (dp, dk) = (dv(prev), dv(k));
        let (vp, vk) = (face[prev % n], face[k % n]);
        if dp < 0.0 {
            if dk > 0.0 {
                current = Some(vec![b.cross(vp, vk), b.keep(vk)]);
            } else if dk == 0.0 {
                current = Some(vec![b.keep(vk)]);
            }
        } else if dk >= 0.0 {
            if let Some(c) = current.as_mut() {
                c.push(b.keep(vk));
            }
        } else {
            let mut c = current.take().unwrap_or_default();
            if dp > 0.0 {
                c.push(b.cross(vp, vk));
            }
            // A chain of one vertex or one edge in the plane only touches it.
            let touching = c.len() < 3 && c.iter().all(|&v| b.on_plane[v as usize]);
            if !c.is_empty() && !touching {
                chains.push(Chain { points: c });
            }
        }
    }
    match chains.len() {
        0 => {}
        1 => {
            let c = &chains[0].points;
            section.push(Line::new(
                b.out[*c.last().unwrap_or(&c[0]) as usize],
                b.out[c[0] as usize],
            ));
            faces.push(chains.swap_remove(0).points);
        }
        _ => join_chains(face, chains, b, normal, faces, section),
    }
}

/// Joins several chains of one face along the cut line.
fn join_chains(
    face: &[u32],
    chains: Vec<Chain>,
    b: &Builder<'_>,
    normal: DVec3,
    faces: &mut Vec<Vec<u32>>,
    section: &mut Vec<Line>,
) {
    let corners: Vec<DVec3> = face.iter().map(|&v| b.src[v as usize]).collect();
    let line = newell(&corners).map(|nf| nf.cross(normal));
    let concatenate = |faces: &mut Vec<Vec<u32>>, section: &mut Vec<Line>| {
        for k in 0..chains.len() {
            let next = &chains[(k + 1) % chains.len()].points;
            let here = &chains[k].points;
            section.push(Line::new(
                b.out[here[here.len() - 1] as usize],
                b.out[next[0] as usize],
            ));
        }
        faces.push(
            chains
                .iter()
                .flat_map(|c| c.points.iter().copied())
                .collect(),
        );
    };
    let Some(dir) = line.filter(|l| l.length() > 1e-12) else {
        concatenate(faces, section);
        return;
    };
    // Endpoints: (parameter along the cut line, chain, is_exit).
    let mut ends: Vec<(f64, usize, bool)> = Vec::with_capacity(2 * chains.len());
    for (k, c) in chains.iter().enumerate() {
        ends.push((b.out[c.points[0] as usize].dot(dir), k, false));
        ends.push((
            b.out[c.points[c.points.len() - 1] as usize].dot(dir),
            k,
            true,
        ));
    }
    ends.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut next_of = vec![usize::MAX; chains.len()];
    for pair in ends.chunks(2) {
        let (x, y) = (pair[0], pair[1]);
        match (x.2, y.2) {
            (true, false) => next_of[x.1] = y.1,
            (false, true) => next_of[y.1] = x.1,
            _ => {
                concatenate(faces, section);
                return;
            }
        }
    }
    let mut visited = vec![false; chains.len()];
    for first in 0..chains.len() {
        if visited[first] {
            continue;
        }
        let mut polygon = Vec::new();
        let mut k = first;
        while !visited[k] {
            visited[k] = true;
            polygon.extend_from_slice(&chains[k].points);
            let next = next_of[k];
            let here = &chains[k].points;
            section.push(Line::new(
                b.out[here[here.len() - 1] as usize],
                b.out[chains[next].points[0] as usize],
            ));
            k = next;
        }
        faces.push(polygon);
    }
}
