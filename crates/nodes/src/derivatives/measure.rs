//! Gradients of the measure nodes (objectives).

use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::fabrication::polygon::newell_vector;
use cnets_geometry::objectives;
use cnets_geometry::surface_fit::{
    Directions, DistanceCotangents, surface_distances, surface_distances_gradient, vertex_closest,
};

use super::flat;
use crate::measure::{
    alignment_targets, face_corners, points_of, reserve_surface_distance, sample_count, table_rows,
};

type Product = fn(&VjpArgs<'_>) -> VjpResult;

fn c(args: &VjpArgs<'_>, k: usize) -> f64 {
    args.cotangents
        .get(k)
        .and_then(|c| c.as_ref())
        .and_then(|c| c.first())
        .copied()
        .unwrap_or(0.0)
}

fn point_distance(args: &VjpArgs<'_>) -> VjpResult {
    let (Some(a), Some(b)) = (args.inputs[0].as_list(), args.inputs[1].as_list()) else {
        return Err(NodeError::new("internal: a and b are lists"));
    };
    let (pa, pb) = (points_of(a, "a")?, points_of(b, "b")?);
    let (c0, c1) = (c(args, 0), c(args, 1));
    let g: Vec<DVec3> = objectives::point_distance_gradient(&pa, &pb, c0)
        .into_iter()
        .zip(objectives::max_distance_gradient(&pa, &pb, c1))
        .map(|(x, y)| x + y)
        .collect();
    let ga = flat(&g);
    let gb: Vec<f64> = ga.iter().map(|x| -x).collect();
    Ok(vec![
        args.wanted[0].then_some(ga),
        args.wanted[1].then_some(gb),
    ])
}

fn closure(args: &VjpArgs<'_>) -> VjpResult {
    let Value::QuadMesh(mesh) = &args.inputs[0] else {
        return Err(NodeError::new("internal: closure needs a quad mesh"));
    };
    let w = args.inputs[1].as_f64().unwrap_or(0.0);
    let (c0, c1, c2) = (c(args, 0), c(args, 1), c(args, 2));
    let m = mesh.cols;
    let first: Vec<DVec3> = (0..mesh.rows).map(|i| mesh.at(i, 0)).collect();
    let last: Vec<DVec3> = (0..mesh.rows).map(|i| mesh.at(i, m - 1)).collect();
    let gap: Vec<DVec3> = objectives::point_distance_gradient(&last, &first, c0)
        .into_iter()
        .zip(objectives::max_distance_gradient(&last, &first, c1))
        .map(|(x, y)| x + y)
        .collect();
    let weight = c0 * w + c2;
    let (tangent, mut g) = if weight != 0.0 || args.wanted[1] {
        objectives::seam_tangents(mesh, weight)?
    } else {
        (0.0, vec![DVec3::ZERO; mesh.vertices.len()])
    };
    for (i, d) in gap.iter().enumerate() {
        g[i * m + m - 1] += *d;
        g[i * m] -= *d;
    }
    Ok(vec![
        args.wanted[0].then(|| flat(&g)),
        args.wanted[1].then(|| vec![c0 * tangent]),
    ])
}

fn surface_distance(args: &VjpArgs<'_>) -> VjpResult {
    let (Value::Mesh(mesh), Value::Mesh(reference)) = (&args.inputs[0], &args.inputs[1]) else {
        return Err(NodeError::new("internal: surface distance needs meshes"));
    };
    if args.wanted[1] {
        return Err(NodeError::new(
            "the distance's derivative in the reference mesh is not implemented",
        ));
    }
    let samples = sample_count(match &args.inputs[2] {
        Value::Integer(n) => *n,
        _ => 2,
    })?;
    let (c0, c1) = (c(args, 0), c(args, 1));
    // The two-way outputs: symmetric = ½ (to + from); the Hausdorff distance is the larger of the
    // two largest distances (to_reference_max on a tie).
    let (symmetric, hausdorff) = (c(args, 2), c(args, 3));
    let mut two_way = DistanceCotangents {
        to_reference: c(args, 4) + 0.5 * symmetric,
        to_reference_max: c(args, 5),
        from_reference: c(args, 6) + 0.5 * symmetric,
        from_reference_max: c(args, 7),
    };
    let one_sided = c0 != 0.0 || c1 != 0.0;
    let directions = Directions {
        to_reference: two_way.to_reference != 0.0 || two_way.to_reference_max != 0.0,
        from_reference: two_way.from_reference != 0.0 || two_way.from_reference_max != 0.0,
    };
    let directions = if hausdorff != 0.0 {
        Directions::BOTH
    } else {
        directions
    };
    reserve_surface_distance(args.ctx, mesh, reference, one_sided, directions, true)?;
    let mut g = vec![DVec3::ZERO; mesh.vertices.len()];
    if one_sided {
        let hits = vertex_closest(&mesh.vertices, reference)?;
        let n = mesh.vertices.len().max(1) as f64;
        for ((g, v), h) in g.iter_mut().zip(&mesh.vertices).zip(&hits) {
            *g = (*v - h.point) * (2.0 * c0 / n);
        }
        if c1 != 0.0
            && let Some((k, h)) = hits
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.distance_squared.total_cmp(&b.1.distance_squared))
            && h.distance_squared > 0.0
        {
            g[k] += (mesh.vertices[k] - h.point) * (c1 / h.distance_squared.sqrt());
        }
    }
    if hausdorff != 0.0 {
        // Recomputed: the outputs not asked for in the run are placeholders.
        let d = surface_distances(mesh, reference, samples, Directions::BOTH)?;
        let (to_max, from_max) = (d.to_reference_max, d.from_reference_max);
        if to_max >= from_max {
            two_way.to_reference_max += hausdorff;
        } else {
            two_way.from_reference_max += hausdorff;
        }
    }
    if two_way != DistanceCotangents::default() {
        let g2 = surface_distances_gradient(mesh, reference, samples, two_way)?;
        for (a, b) in g.iter_mut().zip(g2) {
            *a += b;
        }
    }
    Ok(vec![Some(flat(&g)), None, None])
}

fn normal_alignment(args: &VjpArgs<'_>) -> VjpResult {
    let Value::Mesh(mesh) = &args.inputs[0] else {
        return Err(NodeError::new("internal: alignment needs a mesh"));
    };
    if c(args, 1) != 0.0 {
        return Err(NodeError::new("the largest term has no derivative here"));
    }
    if args.wanted[1] || args.wanted[2] {
        return Err(NodeError::new(
            "the alignment's derivative in its targets is not implemented",
        ));
    }
    let target = match &args.inputs[1] {
        Value::Vector(v) | Value::Point(v) => Some(*v),
        _ => None,
    };
    let reference = match &args.inputs[2] {
        Value::Mesh(m) => Some(m.as_ref()),
        _ => None,
    };
    // With a reference, each face's target is the normal of the reference face closest to its
    // centroid: piecewise constant, differentiated on the face found.
    let targets = alignment_targets(mesh, target, reference)?;
    let (_, _, g) = objectives::normal_alignment(mesh, &targets, c(args, 0))?;
    Ok(vec![Some(flat(&g)), None, None])
}

fn fairness(args: &VjpArgs<'_>) -> VjpResult {
    let c0 = c(args, 0);
    let values = match &args.inputs[0] {
        Value::Null => None,
        v if args.wanted[0] => {
            let (_, g) = objectives::table_fairness(&table_rows(v)?, c0);
            Some(g.concat())
        }
        _ => None,
    };
    let mesh = match &args.inputs[1] {
        Value::QuadMesh(m) if args.wanted[1] => Some(flat(&objectives::mesh_fairness(m, c0)?.1)),
        _ => None,
    };
    Ok(vec![values, mesh])
}

/// The area's product: a face's area A = |N| / 2, N = Σ_k p_k × p_{k+1} its Newell normal, so
/// ∂A/∂p_k = ½ n × (p_{k−1} − p_{k+1}) with n = N / |N| (none for a face without area, where the
/// length is not differentiable), weighted by the total's cotangent plus the face's.
fn area(args: &VjpArgs<'_>) -> VjpResult {
    let Value::Mesh(mesh) = &args.inputs[0] else {
        return Err(NodeError::new("internal: the area needs a mesh"));
    };
    let total = c(args, 0);
    let faces = args.cotangents.get(1).and_then(|c| c.as_deref());
    let mut g = vec![DVec3::ZERO; mesh.vertices.len()];
    for f in 0..mesh.face_count() {
        let w = total + faces.and_then(|c| c.get(f)).copied().unwrap_or(0.0);
        if w == 0.0 {
            continue;
        }
        let corners = face_corners(mesh, f);
        let Some(n) = newell_vector(&corners).try_normalize() else {
            continue;
        };
        let count = corners.len();
        for (k, &v) in mesh.face(f).iter().enumerate() {
            let (prev, next) = (corners[(k + count - 1) % count], corners[(k + 1) % count]);
            g[v as usize] += n.cross(prev - next) * (0.5 * w);
        }
    }
    Ok(vec![args.wanted[0].then(|| flat(&g))])
}

/// The product of a measure node, by id.
pub fn product(id: &str) -> Option<Product> {
    Some(match id {
        "measure.point_distance" => point_distance,
        "measure.closure" => closure,
        "measure.surface_distance" => surface_distance,
        "measure.normal_alignment" => normal_alignment,
        "measure.fairness" => fairness,
        "measure.area" => area,
        _ => return None,
    })
}
