//! Exact vector–Jacobian products of the node library, for the optimizer's reverse pass
//! (`cnets_engine::optimize::vjp`). [`attach`] gives every node type that has one its product; the
//! others are differentiated by finite differences of their own run.
//!
//! - math nodes: hand-written partial derivatives (`math`);
//! - list nodes and mesh rows/columns, which only move numbers around: one *tagged* run
//!   (`structural`) tells where every output number came from;
//! - measure nodes (`measure`) and the construction kernels (`construction`);
//! - mesh cut, mirror, join and the transforms (`mesh_ops`): piecewise affine, with branches.

mod construction;
mod curves;
mod dual;
mod mapper;
mod math;
mod measure;
mod mesh_ops;
mod nets;
mod structural;

use cnets_engine::NodeDef;

/// `defs` with their vector–Jacobian products attached (by node id).
pub fn attach(defs: Vec<NodeDef>) -> Vec<NodeDef> {
    defs.into_iter()
        .map(|def| {
            let id = def.id.to_string();
            if let Some(d) = math::product(&id) {
                return def.with_vjp(d);
            }
            if structural::IDS.contains(&id.as_str()) {
                let run = def.run.clone();
                return def.with_vjp(move |args| structural::product(&run, args));
            }
            if let Some(d) = measure::product(&id) {
                return def.with_vjp(d);
            }
            if let Some(d) = curves::product(&id) {
                let def = def.with_vjp(d);
                return match curves::branch(&id, def.inputs.clone()) {
                    Some(branch) => def.with_branch(branch),
                    None => def,
                };
            }
            if let Some(d) = mapper::product(&id) {
                let def = def.with_vjp(d);
                return match mapper::branch(&id) {
                    Some(branch) => def.with_branch(branch),
                    None => def,
                };
            }
            if let Some(d) = nets::product(&id) {
                return def.with_vjp(d);
            }
            if let Some(d) = mesh_ops::product(&id) {
                let def = def.with_vjp(d);
                return match mesh_ops::branch(&id) {
                    Some(branch) => def.with_branch(branch),
                    None => def,
                };
            }
            if let Some(d) = construction::product(&id) {
                let def = def.with_vjp(d);
                return match construction::branch(&id) {
                    Some((branch, needs)) => def.with_branch(branch).with_derivative_outputs(needs),
                    None => def,
                };
            }
            def
        })
        .collect()
}

/// Points from a flat leaf slice (x, y, z per point).
pub(crate) fn points(leaves: &[f64]) -> Vec<cnets_engine::prelude::DVec3> {
    leaves
        .chunks_exact(3)
        .map(|c| cnets_engine::prelude::DVec3::new(c[0], c[1], c[2]))
        .collect()
}

/// Flat leaves (x, y, z per point) from points.
pub(crate) fn flat(points: &[cnets_engine::prelude::DVec3]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

#[cfg(test)]
mod tests;
