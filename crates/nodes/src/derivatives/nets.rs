//! Gradients of the cone-net nodes between a curve and a net: `cnets.graph_to_apex` (widths →
//! apex values, and when normalized the directrix and the scale) and `cnets.subdivide_rows` (the
//! coarse mesh → the fine one). Both are smooth wherever they run: no branches.

use cnets_engine::PortKind;
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::conenet::normalize::default_scale;

use super::dual::{
    Dual, V3, add3, constant3, cross3, dot3, pull3, scale3, sub3, value3, variable3,
};
use super::{flat, points};

type Product = fn(&VjpArgs<'_>) -> VjpResult;

fn input<K: PortKind>(inputs: &[Value], k: usize, name: &str) -> Result<K::In, NodeError> {
    K::extract(inputs.get(k).unwrap_or(&Value::Null), name)
}

/// `cnets.graph_to_apex`: a_j = y_j / y_{j−1}; normalized, ā_j = 1 − (1 − a_j) L / l_j with
/// ∂ā/∂a = L / l_j, ∂ā/∂L = −(1 − a_j) / l_j, ∂ā/∂l_j = (1 − a_j) L / l_j², the edge lengths l_j
/// of the swept directrix (a closed one's closing edge included) and L the given scale or the
/// directrix length / 5.
fn graph_to_apex(args: &VjpArgs<'_>) -> VjpResult {
    let widths = input::<k::List<k::Number>>(args.inputs, 0, "widths")?;
    let normalized = input::<k::Boolean>(args.inputs, 1, "normalized")?;
    let directrix = input::<Option<k::Polyline>>(args.inputs, 2, "directrix")?;
    let scale = input::<Option<k::Number>>(args.inputs, 3, "scale")?;
    let c = args.cotangent(0);
    if widths.len() < 2 || c.len() + 1 != widths.len() {
        return Err(NodeError::new(
            "internal: the apex cotangent does not match the widths",
        ));
    }
    let a: Vec<f64> = widths.windows(2).map(|w| w[1] / w[0]).collect();
    let mut a_bar = c.clone();
    let (mut directrix_bar, mut scale_bar) = (None, None);
    if normalized {
        let d = directrix.ok_or_else(|| {
            NodeError::new("normalized output needs the directrix (its edge lengths)")
        })?;
        let pts = d.swept_points();
        if pts.len() != widths.len() {
            return Err(NodeError::new(
                "internal: the widths do not match the directrix",
            ));
        }
        let lengths: Vec<f64> = pts.windows(2).map(|w| w[0].distance(w[1])).collect();
        let total: f64 = lengths.iter().sum();
        let l = scale.unwrap_or_else(|| default_scale(total));
        let mut lengths_bar = vec![0.0; lengths.len()];
        let mut l_bar = 0.0;
        for (j, (&lj, &aj)) in lengths.iter().zip(&a).enumerate() {
            a_bar[j] = c[j] * l / lj;
            l_bar -= c[j] * (1.0 - aj) / lj;
            lengths_bar[j] += c[j] * (1.0 - aj) * l / (lj * lj);
        }
        if scale.is_some() {
            scale_bar = Some(vec![l_bar]);
        } else {
            // L = default_scale(total) = total / 5.
            let per = l_bar / 5.0;
            lengths_bar.iter_mut().for_each(|b| *b += per);
        }
        if args.wanted[2] {
            let mut g = vec![DVec3::ZERO; pts.len()];
            for (j, lb) in lengths_bar.iter().enumerate() {
                let u = (pts[j + 1] - pts[j]) / lengths[j];
                g[j + 1] += u * *lb;
                g[j] -= u * *lb;
            }
            if d.closed
                && let Some(last) = g.pop()
            {
                g[0] += last;
            }
            directrix_bar = Some(flat(&g));
        }
    }
    let mut widths_bar = vec![0.0; widths.len()];
    for (j, ab) in a_bar.iter().enumerate() {
        widths_bar[j + 1] += ab / widths[j];
        widths_bar[j] -= ab * widths[j + 1] / (widths[j] * widths[j]);
    }
    Ok(vec![
        args.wanted[0].then_some(widths_bar),
        None,
        directrix_bar,
        scale_bar.filter(|_| args.wanted[3]),
    ])
}

/// The central projection of `subdivide_rows` (`project` in
/// `cnets_geometry::conenet::subdivide`) on dual numbers in the 15 coordinates of p0, q0, p1, q1
/// and f: the point of the line p1 q1 on the line through f and the apex of the face, in
/// homogeneous coordinates of the plane through p0 normal to the face's diagonals. The result
/// does not depend on the frame in that plane nor on the scale of the coordinates, so any smooth
/// frame gives the derivative. `None` when undefined.
fn project_dual(from: [DVec3; 2], to: [DVec3; 2], f: DVec3) -> Option<V3<15>> {
    type D = Dual<15>;
    let [p0, q0] = from;
    let [p1, q1] = to;
    if q1 - p1 == DVec3::ZERO {
        return Some(variable3(p1, 6));
    }
    let h = [q0 - p0, p1 - p0, q1 - p1, q1 - q0]
        .iter()
        .fold(0.0f64, |h, e| h.max(e.abs().max_element()));
    let (vp0, vq0, vp1, vq1, vf) = (
        variable3::<15>(p0, 0),
        variable3(q0, 3),
        variable3(p1, 6),
        variable3(q1, 9),
        variable3(f, 12),
    );
    let raw = cross3(sub3(vq1, vp0), sub3(vq0, vp1));
    let len = dot3(raw, raw).sqrt();
    if len.v == 0.0 {
        return None;
    }
    let normal = scale3(raw, D::constant(1.0) / len);
    // A frame in the face plane: the coordinate axis least aligned with the normal, crossed.
    let nv = value3(normal).abs();
    let helper = if nv.x <= nv.y && nv.x <= nv.z {
        DVec3::X
    } else if nv.y <= nv.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let e1_raw = cross3(constant3(helper), normal);
    let e1 = scale3(e1_raw, D::constant(1.0) / dot3(e1_raw, e1_raw).sqrt());
    let e2 = cross3(normal, e1);
    let inv_h = D::constant(1.0 / h);
    let plane = |p: V3<15>| {
        let v = scale3(sub3(p, vp0), inv_h);
        [dot3(v, e1), dot3(v, e2), D::constant(1.0)]
    };
    let (a0, b0, a1, b1) = (plane(vp0), plane(vq0), plane(vp1), plane(vq1));
    let apex = cross3(cross3(a0, a1), cross3(b0, b1));
    let ray = cross3(apex, plane(vf));
    let x = cross3(ray, cross3(a1, b1));
    let d2 = [b1[0] - a1[0], b1[1] - a1[1]];
    let beta = ((x[0] - a1[0] * x[2]) * d2[0] + (x[1] - a1[1] * x[2]) * d2[1])
        / (d2[0] * d2[0] + d2[1] * d2[1]);
    let t = beta / x[2];
    if !t.v.is_finite() {
        return None;
    }
    Some(add3(vp1, scale3(sub3(vq1, vp1), t)))
}

/// `cnets.subdivide_rows`: coarse rows are copied; a fine row starts at
/// `lerp(G_{i,0}, G_{i+1,0}, k / count)` and each further vertex is the central projection of the
/// previous one (through the apex of the coarse face between them) onto the next coarse edge. The
/// reverse pass runs each fine row backwards, the projection's Jacobian from dual numbers.
fn subdivide_rows(args: &VjpArgs<'_>) -> VjpResult {
    let mesh = input::<k::QuadMesh>(args.inputs, 0, "mesh")?;
    let count = input::<k::Integer>(args.inputs, 1, "count")?;
    let Some(Value::QuadMesh(fine)) = args.outputs.first() else {
        return Err(NodeError::new(
            "internal: the subdivision's output is a mesh",
        ));
    };
    let count = usize::try_from(count)
        .ok()
        .filter(|c| *c >= 1)
        .ok_or_else(|| NodeError::new("internal: the subdivision count"))?;
    let c = points(&args.cotangent(0));
    let (n, m) = (mesh.rows, mesh.cols);
    if c.len() != fine.vertices.len() || fine.cols != m {
        return Err(NodeError::new(
            "internal: the subdivision's cotangent does not match its vertices",
        ));
    }
    let mut g = vec![DVec3::ZERO; n * m];
    for r in 0..fine.rows {
        let (s, k) = (r / count, r % count);
        let row_bar = &c[r * m..(r + 1) * m];
        if k == 0 {
            let coarse = (s % n) * m;
            for (j, cb) in row_bar.iter().enumerate() {
                g[coarse + j] += *cb;
            }
            continue;
        }
        let (i, i1) = (s, (s + 1) % n);
        let f = &fine.vertices[r * m..(r + 1) * m];
        let mut f_bar = row_bar.to_vec();
        for j in (1..m).rev() {
            let from = [mesh.at(i, j - 1), mesh.at(i1, j - 1)];
            let to = [mesh.at(i, j), mesh.at(i1, j)];
            let result = project_dual(from, to, f[j - 1]).ok_or_else(|| {
                NodeError::new(format!(
                    "the coarse face at row {i}, column {} has no projection",
                    j - 1
                ))
            })?;
            let pulled = pull3(result, f_bar[j]);
            let part = |k: usize| DVec3::new(pulled[3 * k], pulled[3 * k + 1], pulled[3 * k + 2]);
            g[i * m + j - 1] += part(0);
            g[i1 * m + j - 1] += part(1);
            g[i * m + j] += part(2);
            g[i1 * m + j] += part(3);
            f_bar[j - 1] += part(4);
        }
        let u = k as f64 / count as f64;
        g[i * m] += f_bar[0] * (1.0 - u);
        g[i1 * m] += f_bar[0] * u;
    }
    Ok(vec![args.wanted[0].then(|| flat(&g)), None])
}

/// The product of a cone-net node, by id.
pub fn product(id: &str) -> Option<Product> {
    Some(match id {
        "cnets.graph_to_apex" => graph_to_apex,
        "cnets.subdivide_rows" => subdivide_rows,
        _ => return None,
    })
}
