//! Adjoints of the construction kernels (`cnets_geometry::conenet::adjoint`).

use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::conenet::ConstructInputs;
use cnets_geometry::conenet::adjoint::construct_adjoint;

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

/// The product of a construction node, by id.
pub fn product(id: &str) -> Option<Product> {
    match id {
        "cnets.construct" => Some(construct),
        _ => None,
    }
}
