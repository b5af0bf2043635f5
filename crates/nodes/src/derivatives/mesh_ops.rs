//! Gradients of the mesh operations: `mesh.cut_by_plane`, `mesh.mirror`, `mesh.join` and the
//! transforms (`mesh.transform`, `curve.transform`), in their input geometry.
//!
//! On the piece a run is on every output vertex is an affine function of one or two input
//! vertices: a copy, a projection onto the plane or a reflection in it (mirror), the point where an
//! edge crosses the plane (cut: `p_lo + (p_hi − p_lo) t`, t = d_lo / (d_lo − d_hi), d the signed
//! distances), an affine map (transforms). The pieces change where a vertex changes side of the
//! cutting plane or enters the mirror's weld band: those are the nodes' branches, reported by the
//! optimizer when a step crosses one. The plane, the weld tolerance and the transform's parameters
//! other than the translation are not differentiated (declined: finite differences of the node's
//! run), nor a welded join.

use cnets_engine::optimize::branch::{Branch, key_of};
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::curves::Transform;
use cnets_geometry::fabrication as fab;
use cnets_geometry::fabrication::cut::VertexSource;

use super::{flat, points};
use crate::fabrication::fab_err;

type Product = fn(&VjpArgs<'_>) -> VjpResult;
type BranchFn = fn(&[Value], &[Value]) -> Option<Branch>;

fn decline(args: &VjpArgs<'_>, inputs: &[(usize, &str)], node: &str) -> Result<(), NodeError> {
    for &(k, name) in inputs {
        if args.wanted.get(k).copied().unwrap_or(false) {
            return Err(NodeError::new(format!(
                "{node}'s derivative in its {name} is not implemented"
            )));
        }
    }
    Ok(())
}

fn plane_of(v: &Value) -> Result<Plane, NodeError> {
    match v {
        Value::Plane(p) => Ok(**p),
        _ => Err(NodeError::new("internal: the plane is a plane")),
    }
}

/// The cut's inputs as its run reads them.
fn cut_run(inputs: &[Value]) -> Result<(&PolygonMesh, Plane, bool), NodeError> {
    let Some(Value::Mesh(mesh)) = inputs.first() else {
        return Err(NodeError::new("internal: the cut needs a mesh"));
    };
    let plane = plane_of(inputs.get(1).unwrap_or(&Value::Null))?;
    let keep_positive = !matches!(inputs.get(2), Some(Value::Boolean(true)));
    Ok((mesh, plane, keep_positive))
}

/// `mesh.cut_by_plane`: kept vertices pass their cotangents on; a crossing point passes
/// `(1 − t) c + (c · (p_hi − p_lo)) ∂t/∂p_lo` to its lower vertex and the like to its higher one,
/// ∂t/∂p_lo = −d_hi / (d_lo − d_hi)² · n̂, ∂t/∂p_hi = d_lo / (d_lo − d_hi)² · n̂ (n̂ the unit
/// normal towards the kept side).
fn cut(args: &VjpArgs<'_>) -> VjpResult {
    decline(args, &[(1, "plane"), (2, "flip")], "the cut")?;
    let (mesh, plane, keep_positive) = cut_run(args.inputs)?;
    let result = fab::cut_by_plane(mesh, &plane, keep_positive).map_err(fab_err)?;
    let normal = cnets_geometry::plane::unit(plane.normal, "plane normal")?
        * if keep_positive { 1.0 } else { -1.0 };
    let c = points(&args.cotangent(0));
    if c.len() != result.sources.len() {
        return Err(NodeError::new(
            "internal: the cut's cotangent does not match its vertices",
        ));
    }
    let v = &mesh.vertices;
    let mut g = vec![DVec3::ZERO; v.len()];
    for (source, c) in result.sources.iter().zip(c) {
        match *source {
            VertexSource::Copy(k) => g[k as usize] += c,
            VertexSource::Cross { lo, hi, d_lo, d_hi } => {
                let (lo, hi) = (lo as usize, hi as usize);
                let delta = d_lo - d_hi;
                let t = d_lo / delta;
                let e = c.dot(v[hi] - v[lo]) / (delta * delta);
                g[lo] += c * (1.0 - t) - normal * (e * d_hi);
                g[hi] += c * t + normal * (e * d_lo);
            }
        }
    }
    Ok(vec![Some(flat(&g)), None, None])
}

/// `mesh.cut_by_plane`'s piece: the input vertices kept and the edges cut.
fn cut_branch(inputs: &[Value], _outputs: &[Value]) -> Option<Branch> {
    let (mesh, plane, keep_positive) = cut_run(inputs).ok()?;
    let result = fab::cut_by_plane(mesh, &plane, keep_positive).ok()?;
    let (mut kept, mut crossed) = (0usize, 0usize);
    let key = key_of(result.sources.iter().flat_map(|s| match *s {
        VertexSource::Copy(k) => {
            kept += 1;
            [0, u64::from(k), 0]
        }
        VertexSource::Cross { lo, hi, .. } => {
            crossed += 1;
            [1, u64::from(lo), u64::from(hi)]
        }
    }));
    Some(Branch {
        key,
        summary: format!(
            "vertices kept: {kept} of {}, edges cut: {crossed}",
            mesh.vertices.len()
        ),
    })
}

/// The mirror's inputs and which vertices it welds (within `tolerance` of the plane, as
/// `fab::mirror` decides).
fn mirror_run(inputs: &[Value]) -> Result<(&PolygonMesh, DVec3, Vec<bool>), NodeError> {
    let Some(Value::Mesh(mesh)) = inputs.first() else {
        return Err(NodeError::new("internal: the mirror needs a mesh"));
    };
    let plane = plane_of(inputs.get(1).unwrap_or(&Value::Null))?;
    let tolerance = inputs.get(2).and_then(Value::as_f64).unwrap_or(1e-6);
    let n = cnets_geometry::plane::unit(plane.normal, "plane normal")?;
    let on = mesh
        .vertices
        .iter()
        .map(|p| (*p - plane.origin).dot(n).abs() <= tolerance)
        .collect();
    Ok((mesh, n, on))
}

/// `mesh.mirror`: the first |V| output vertices are the input's (projected onto the plane where
/// welded: I − n̂n̂ᵀ), then the reflections of the vertices not welded (I − 2n̂n̂ᵀ), in order.
fn mirror(args: &VjpArgs<'_>) -> VjpResult {
    decline(args, &[(1, "plane"), (2, "tolerance")], "the mirror")?;
    let (mesh, n, on) = mirror_run(args.inputs)?;
    let c = points(&args.cotangent(0));
    let count = mesh.vertices.len();
    if c.len() != count + on.iter().filter(|w| !**w).count() {
        return Err(NodeError::new(
            "internal: the mirror's cotangent does not match its vertices",
        ));
    }
    let mut g = Vec::with_capacity(count);
    let mut image = count;
    for (k, &welded) in on.iter().enumerate() {
        let mut gk = if welded { c[k] - n * n.dot(c[k]) } else { c[k] };
        if !welded {
            gk += c[image] - n * (2.0 * n.dot(c[image]));
            image += 1;
        }
        g.push(gk);
    }
    Ok(vec![Some(flat(&g)), None, None])
}

/// `mesh.mirror`'s piece: the vertices welded on the plane.
fn mirror_branch(inputs: &[Value], _outputs: &[Value]) -> Option<Branch> {
    let (mesh, _, on) = mirror_run(inputs).ok()?;
    let welded = on.iter().filter(|w| **w).count();
    Some(Branch {
        key: key_of(on.iter().map(|&w| u64::from(w))),
        summary: format!(
            "vertices welded on the plane: {welded} of {}",
            mesh.vertices.len()
        ),
    })
}

/// `mesh.join` without welding: the meshes' vertices in list order, so the cotangent is passed on
/// as it is. A welded join is declined.
fn join(args: &VjpArgs<'_>) -> VjpResult {
    decline(args, &[(1, "weld distance")], "the join")?;
    if !matches!(args.inputs.get(1), None | Some(Value::Null)) {
        return Err(NodeError::new(
            "a welded join has no exact derivative (vertices merge)",
        ));
    }
    Ok(vec![Some(args.cotangent(0)), None, None])
}

/// The transform of `mesh.transform` and `curve.transform` (inputs 1–6).
fn transform_of(inputs: &[Value]) -> Result<Transform, NodeError> {
    let vector = |k: usize, default: DVec3| match inputs.get(k) {
        Some(Value::Vector(v) | Value::Point(v)) => *v,
        _ => default,
    };
    let number = |k: usize, default: f64| inputs.get(k).and_then(Value::as_f64).unwrap_or(default);
    Ok(Transform {
        translation: vector(1, DVec3::ZERO),
        angle: number(2, 0.0),
        axis: vector(3, DVec3::Z),
        centre: vector(4, DVec3::ZERO),
        scale: number(5, 1.0),
        mirror: match inputs.get(6) {
            Some(Value::Plane(p)) => Some(**p),
            _ => None,
        },
    })
}

/// `mesh.transform` and `curve.transform`: p ↦ A p + b, so the geometry's cotangent is Aᵀ c per
/// point (A's columns from the transform of the unit vectors) and the translation's Σ c.
fn transform(args: &VjpArgs<'_>) -> VjpResult {
    decline(
        args,
        &[
            (2, "angle"),
            (3, "axis"),
            (4, "centre"),
            (5, "scale"),
            (6, "mirror plane"),
        ],
        "the transform",
    )?;
    let t = transform_of(args.inputs)?;
    let origin = t.apply(DVec3::ZERO)?;
    let columns = [
        t.apply(DVec3::X)? - origin,
        t.apply(DVec3::Y)? - origin,
        t.apply(DVec3::Z)? - origin,
    ];
    let c = points(&args.cotangent(0));
    let geometry = args.wanted[0].then(|| {
        let g: Vec<DVec3> = c
            .iter()
            .map(|c| DVec3::new(columns[0].dot(*c), columns[1].dot(*c), columns[2].dot(*c)))
            .collect();
        flat(&g)
    });
    let translation = args.wanted[1].then(|| c.iter().copied().sum::<DVec3>().to_array().to_vec());
    Ok(vec![geometry, translation, None, None, None, None, None])
}

/// The product of a mesh operation, by id.
pub fn product(id: &str) -> Option<Product> {
    Some(match id {
        "mesh.cut_by_plane" => cut,
        "mesh.mirror" => mirror,
        "mesh.join" => join,
        "mesh.transform" | "curve.transform" => transform,
        _ => return None,
    })
}

/// The branch function of a piecewise mesh operation, by id.
pub fn branch(id: &str) -> Option<BranchFn> {
    match id {
        "mesh.cut_by_plane" => Some(cut_branch),
        "mesh.mirror" => Some(mirror_branch),
        _ => None,
    }
}
