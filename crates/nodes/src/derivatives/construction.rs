//! Adjoints of the construction kernels (`cnets_geometry::conenet::adjoint`).

use cnets_engine::optimize::branch::{Branch, key_of};
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::conenet::adjoint::construct_adjoint;
use cnets_geometry::conenet::{ConstructInputs, GridValues};

use super::{flat, points};
use crate::cnets::{apex_input, grid_values, parse_end_planes};

type Product = fn(&VjpArgs<'_>) -> VjpResult;

/// `cnets.construct`: the backward sweep for the ratios and the generatrix (inputs 3 and 1). The
/// directrix, the apex function and the other outputs are not differentiated (declined: finite
/// differences), nor a run in which the assisted correction changed planes (a branch).
fn construct(args: &VjpArgs<'_>) -> VjpResult {
    for (k, name) in [
        (0, "directrix"),
        (2, "apex"),
        (4, "assistance"),
        (6, "scale"),
        (7, "epsilon"),
    ] {
        if args.wanted.get(k) == Some(&true) {
            return Err(NodeError::new(format!(
                "the construction's derivative in '{name}' is not implemented"
            )));
        }
    }
    if args.cotangents.iter().skip(1).any(Option::is_some) {
        return Err(NodeError::new(
            "only the mesh output of the construction is differentiated",
        ));
    }
    if let Some(Value::List(c)) = args.outputs.get(5)
        && !c.is_empty()
    {
        return Err(NodeError::new(format!(
            "the assisted correction changed {} planes (a branch of the construction)",
            c.len()
        )));
    }
    let (Value::Polyline(directrix), Value::Polyline(generatrix), Value::QuadMesh(mesh)) =
        (&args.inputs[0], &args.inputs[1], &args.outputs[0])
    else {
        return Err(NodeError::new("internal: construction inputs"));
    };
    let apex: Vec<f64> = args.inputs[2]
        .as_list()
        .map(|l| l.iter().filter_map(Value::as_f64).collect())
        .or_else(|| args.inputs[2].as_f64().map(|x| vec![x]))
        .unwrap_or_default();
    let normalized = matches!(args.inputs[5], Value::Boolean(true));
    let scale = args.inputs[6].as_f64();
    let mut inputs = ConstructInputs::new((**directrix).clone(), (**generatrix).clone());
    inputs.apex = apex_input(apex, normalized, scale);
    inputs.ratios = grid_values(&args.inputs[3], "ratios")?;
    inputs.assistance.alpha = args.inputs[4].as_f64().unwrap_or(-1.0);
    inputs.end_planes = parse_end_planes(match &args.inputs[8] {
        Value::Text(t) => t,
        _ => "perpendicular",
    })?;
    let bar = points(&args.cotangent(0));
    let adjoint = construct_adjoint(&inputs, mesh, &bar)?;
    let mut result = vec![None; args.inputs.len()];
    if args.wanted[1] {
        result[1] = Some(flat(&adjoint.generatrix));
    }
    if args.wanted[3] {
        result[3] = Some(adjoint.ratios);
    }
    Ok(result)
}

/// `cnets.construct`'s smooth piece: which side of ½ each ratio is on (the ratio → angle map has
/// its kink there) and which values the assisted correction changed (by kind, column and row).
fn construct_branch(inputs: &[Value], outputs: &[Value]) -> Option<Branch> {
    let ratios = match grid_values(inputs.get(3)?, "ratios").ok()? {
        GridValues::Uniform(r) => vec![r],
        GridValues::PerColumn(v) => v,
        GridValues::PerVertex(rows) => rows.concat(),
    };
    let side = |r: f64| match r.partial_cmp(&0.5) {
        Some(std::cmp::Ordering::Less) => 0u64,
        Some(std::cmp::Ordering::Equal) => 1,
        _ => 2,
    };
    let mut counts = [0usize; 3];
    for &r in &ratios {
        counts[side(r) as usize] += 1;
    }
    // A correction line reads "<what> at column j[, row i]: <old> → <new>": the part before the
    // colon names the changed value, the numbers after it move continuously.
    // (A construction mapped over several inputs has a list of such lists.)
    fn lines<'a>(v: &'a Value, out: &mut Vec<&'a str>) {
        match v {
            Value::Text(t) => out.push(t.split(':').next().unwrap_or(t)),
            Value::List(items) => items.iter().for_each(|i| lines(i, out)),
            _ => {}
        }
    }
    let mut corrected = Vec::new();
    if let Some(v) = outputs.get(5) {
        lines(v, &mut corrected);
    }
    let key = key_of(
        ratios.iter().map(|&r| side(r)).chain([3]).chain(
            corrected
                .iter()
                .flat_map(|c| c.bytes().map(u64::from).chain([4])),
        ),
    );
    Some(Branch {
        key,
        summary: format!(
            "ratios below ½: {}, at ½: {}, above ½: {}; corrections: {}",
            counts[0],
            counts[1],
            counts[2],
            corrected.len()
        ),
    })
}

/// The product of a construction node, by id.
pub fn product(id: &str) -> Option<Product> {
    match id {
        "cnets.construct" => Some(construct),
        _ => None,
    }
}

/// The branch function of a construction node and the outputs its derivative reads off the path
/// (the corrections: a run the assisted correction changed is declined), by id.
pub fn branch(id: &str) -> Option<(BranchFn, &'static [&'static str])> {
    match id {
        "cnets.construct" => Some((construct_branch, &["corrections"])),
        _ => None,
    }
}

type BranchFn = fn(&[Value], &[Value]) -> Option<Branch>;
