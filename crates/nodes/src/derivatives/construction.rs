//! Adjoints of the construction kernels (`cnets_geometry::conenet::adjoint`).

use cnets_engine::optimize::branch::{Branch, key_of};
use cnets_engine::optimize::vjp::{VjpArgs, VjpResult};
use cnets_engine::prelude::*;
use cnets_geometry::conenet::adjoint::{
    OutputBars, Wrt, construct_adjoint_for, coplanar_adjoint_for, ctube_adjoint_for,
};
use cnets_geometry::conenet::{
    ColumnValues, ConstructInputs, CoplanarInputs, CtubeInputs, GridValues, NormalsInput,
};
use cnets_geometry::{Polyline, QuadGrid};

use super::{flat, points};
use crate::cnets::{apex_input, grid_values, parse_end_planes};

type Product = fn(&VjpArgs<'_>) -> VjpResult;

/// The outputs of `cnets.construct` whose cotangents its product takes: mesh, apex, apices, planes
/// and margins.
const DIFFERENTIATED: [usize; 5] = [0, 1, 2, 3, 7];

/// `cnets.construct`: the backward sweep (`construct_adjoint_for`) for the directrix, generatrix,
/// apex function, ratios, scale, ε and the shared seam apex (inputs 0, 1, 2, 3, 6, 7, 9), from the cotangents of the mesh,
/// the apex values used, the apices, the plane normals and the convexity margins (outputs 0, 1,
/// 2, 3, 7). A run of the assisted correction is differentiated on the piece it took: planes
/// only, apex only, or a blend (its apex-only sweep differentiated too); a mixed run (a plane fix
/// falling back to an apex fix, decided by rounding) is declined (finite differences), as are the
/// other outputs' cotangents.
/// `assistance` selects the correction's form: its derivative is 0 when the correction is off or
/// changed nothing, else declined.
fn construct(args: &VjpArgs<'_>) -> VjpResult {
    let wanted = |k: usize| args.wanted.get(k) == Some(&true);
    let corrected = matches!(args.outputs.get(5), Some(Value::List(c)) if !c.is_empty());
    let alpha = args.inputs[4].as_f64().unwrap_or(-1.0);
    if wanted(4) && alpha >= 0.0 && corrected {
        return Err(NodeError::new(
            "the construction's derivative in 'assistance' is not implemented for a corrected run \
             (α chooses the correction's form)",
        ));
    }
    let (directrix, generatrix, mesh) = curves_and_mesh(args)?;
    let normalized = matches!(args.inputs[5], Value::Boolean(true));
    let scale = args.inputs[6].as_f64();
    let mut inputs = ConstructInputs::new(directrix, generatrix);
    inputs.apex = apex_input(apex_values(&args.inputs[2]), normalized, scale);
    inputs.ratios = grid_values(&args.inputs[3], "ratios")?;
    inputs.assistance.alpha = alpha;
    if let Some(epsilon) = args.inputs[7].as_f64() {
        inputs.assistance.epsilon = epsilon;
    }
    inputs.end_planes = parse_end_planes(match &args.inputs[8] {
        Value::Text(t) => t,
        _ => "perpendicular",
    })?;
    inputs.apex.seam = match args.inputs.get(9) {
        Some(Value::Point(c)) => Some(*c),
        _ => None,
    };
    let wrt = Wrt {
        apex: wanted(2) || wanted(6) || wanted(9),
        directrix: wanted(0),
        epsilon: wanted(7),
        normals: false,
    };
    let owned = OwnedBars::of(args)?;
    let adjoint = construct_adjoint_for(&inputs, mesh, owned.bars(), wrt)?;
    let mut result = vec![None; args.inputs.len()];
    if wanted(0) {
        result[0] = adjoint.directrix.as_deref().map(flat);
    }
    if wanted(1) {
        result[1] = Some(flat(&adjoint.generatrix));
    }
    if wanted(2) {
        result[2] = adjoint.apex;
    }
    if wanted(3) {
        result[3] = Some(adjoint.ratios);
    }
    if wanted(4) {
        result[4] = Some(vec![0.0]);
    }
    // A scale that is not given (null) has no numbers.
    if wanted(6) && scale.is_some() {
        result[6] = adjoint.scale.map(|s| vec![s]);
    }
    if wanted(7) {
        result[7] = adjoint.epsilon.map(|e| vec![e]);
    }
    // A shared apex that is not given (null) has no numbers.
    if wanted(9) {
        result[9] = adjoint.seam.map(|c| flat(&[c]));
    }
    Ok(result)
}

/// The directrix, the generatrix and the mesh built of a construction (inputs 0 and 1, output 0),
/// after checking only the differentiated outputs have cotangents.
fn curves_and_mesh<'a>(
    args: &'a VjpArgs<'_>,
) -> Result<(Polyline, Polyline, &'a QuadGrid), NodeError> {
    if let Some(k) = (0..args.cotangents.len())
        .find(|&k| args.cotangents[k].is_some() && !DIFFERENTIATED.contains(&k))
    {
        return Err(NodeError::new(format!(
            "only the mesh, apex, apices, planes and margins outputs of the construction are \
             differentiated (output {k} has a cotangent)"
        )));
    }
    let (Value::Polyline(directrix), Value::Polyline(generatrix), Value::QuadMesh(mesh)) =
        (&args.inputs[0], &args.inputs[1], &args.outputs[0])
    else {
        return Err(NodeError::new("internal: construction inputs"));
    };
    Ok(((**directrix).clone(), (**generatrix).clone(), mesh))
}

/// The apex input's values (one number or a list).
fn apex_values(value: &Value) -> Vec<f64> {
    value
        .as_list()
        .map(|l| l.iter().filter_map(Value::as_f64).collect())
        .or_else(|| value.as_f64().map(|x| vec![x]))
        .unwrap_or_default()
}

/// The cotangents of a construction's differentiated outputs (mesh, apex, apices, planes,
/// margins), owned; [`OwnedBars::bars`] lends them to the adjoint.
struct OwnedBars {
    mesh: Vec<DVec3>,
    apex: Vec<f64>,
    apices: Vec<DVec3>,
    planes: Vec<DVec3>,
    margins: Vec<f64>,
}

impl OwnedBars {
    /// The cotangents of `args`' outputs 0, 1, 2, 3 and 7 (empty when none).
    fn of(args: &VjpArgs<'_>) -> Result<Self, NodeError> {
        let leaves = |k: usize| {
            args.cotangents
                .get(k)
                .cloned()
                .flatten()
                .unwrap_or_default()
        };
        let apices = match args.cotangents.get(2).and_then(Option::as_ref) {
            Some(c) => apices_cotangent(&args.outputs[2], c)?,
            None => Vec::new(),
        };
        Ok(Self {
            mesh: points(&args.cotangent(0)),
            apex: leaves(1),
            apices,
            planes: points(&leaves(3)),
            margins: leaves(7),
        })
    }

    /// The adjoint's view of the cotangents.
    fn bars(&self) -> OutputBars<'_> {
        OutputBars {
            mesh: &self.mesh,
            apex: &self.apex,
            apices: &self.apices,
            planes: &self.planes,
            margins: &self.margins,
        }
    }
}

/// The normals input of `ctube.construct` as the node reads it (`cnets::normals_input`): null or
/// an empty list for the Monge planes, a list of vectors shared by every row, or a table of them.
fn ctube_normals(value: &Value) -> Result<NormalsInput, NodeError> {
    let vector = |v: &Value| {
        v.as_vec3()
            .ok_or_else(|| NodeError::new("internal: a normal is not a vector"))
    };
    match value {
        Value::Null => Ok(NormalsInput::Monge),
        Value::List(items) if items.is_empty() => Ok(NormalsInput::Monge),
        Value::List(items) if items.iter().any(|v| v.as_list().is_some()) => items
            .iter()
            .map(|row| {
                row.as_list()
                    .ok_or_else(|| NodeError::new("internal: a row of normals is not a list"))?
                    .iter()
                    .map(vector)
                    .collect()
            })
            .collect::<Result<Vec<Vec<DVec3>>, _>>()
            .map(NormalsInput::PerVertex),
        Value::List(items) => items
            .iter()
            .map(vector)
            .collect::<Result<Vec<DVec3>, _>>()
            .map(NormalsInput::PerColumn),
        other => vector(other).map(|v| NormalsInput::PerColumn(vec![v])),
    }
}

/// `ctube.construct`: the backward sweep with the planes given (`ctube_adjoint_for`) for the
/// directrix, generatrix, apex function, normals and scale (inputs 0, 1, 2, 3, 5), from the
/// cotangents of the mesh, the apex values used, the apices, the plane normals and the
/// convexity margins (outputs 0, 1, 2, 3, 7). The normals may be shared by every row (M−1) or
/// given per vertex (N lists of M−1); the Monge planes (no normals) follow the directrix. The
/// construction has no correction: every run is on one smooth piece.
fn ctube(args: &VjpArgs<'_>) -> VjpResult {
    let wanted = |k: usize| args.wanted.get(k) == Some(&true);
    let (directrix, generatrix, mesh) = curves_and_mesh(args)?;
    let normalized = matches!(args.inputs[4], Value::Boolean(true));
    let scale = args.inputs[5].as_f64();
    let inputs = CtubeInputs {
        directrix,
        generatrix,
        apex: apex_input(apex_values(&args.inputs[2]), normalized, scale),
        normals: ctube_normals(&args.inputs[3])?,
        end_planes: parse_end_planes(match &args.inputs[6] {
            Value::Text(t) => t,
            _ => "perpendicular",
        })?,
    };
    let wrt = Wrt {
        apex: wanted(2) || wanted(5),
        directrix: wanted(0),
        epsilon: false,
        normals: wanted(3),
    };
    let owned = OwnedBars::of(args)?;
    let adjoint = ctube_adjoint_for(&inputs, mesh, owned.bars(), wrt)?;
    let mut result = vec![None; args.inputs.len()];
    if wanted(0) {
        result[0] = adjoint.directrix.as_deref().map(flat);
    }
    if wanted(1) {
        result[1] = Some(flat(&adjoint.generatrix));
    }
    if wanted(2) {
        result[2] = adjoint.apex;
    }
    // The Monge planes (no normals given) have no numbers.
    if wanted(3) {
        result[3] = adjoint.normals.as_deref().map(flat);
    }
    if wanted(5) && scale.is_some() {
        result[5] = adjoint.scale.map(|s| vec![s]);
    }
    Ok(result)
}

/// `cnets.construct_coplanar`: the backward sweep with the shared planes pulled back through
/// their pencils (`coplanar_adjoint_for`) for the directrix, generatrix, apex function, ruling
/// ratios, plane ratios and scale (inputs 0, 1, 2, 3, 4, 7), from the cotangents of the mesh, the
/// apex values used, the apices, the plane normals and the convexity margins (outputs 0, 1, 2, 3,
/// 7). A run the assisted correction changed is declined (finite differences); when it changed
/// nothing, `assistance` and `epsilon` have derivative 0.
fn coplanar(args: &VjpArgs<'_>) -> VjpResult {
    let wanted = |k: usize| args.wanted.get(k) == Some(&true);
    if matches!(args.outputs.get(5), Some(Value::List(c)) if !c.is_empty()) {
        return Err(NodeError::new(
            "the assisted correction changed the coplanar construction: its derivative is not \
             implemented",
        ));
    }
    let (directrix, generatrix, mesh) = curves_and_mesh(args)?;
    let column = |v: &Value| match apex_values(v).as_slice() {
        [single] => ColumnValues::Uniform(*single),
        values => ColumnValues::List(values.to_vec()),
    };
    let normalized = matches!(args.inputs[6], Value::Boolean(true));
    let scale = args.inputs[7].as_f64();
    let mut inputs = CoplanarInputs::new(directrix, generatrix);
    inputs.apex = apex_input(apex_values(&args.inputs[2]), normalized, scale);
    inputs.ruling_ratios = column(&args.inputs[3]);
    inputs.plane_ratios = column(&args.inputs[4]);
    inputs.assistance.alpha = args.inputs[5].as_f64().unwrap_or(-1.0);
    if let Some(epsilon) = args.inputs[8].as_f64() {
        inputs.assistance.epsilon = epsilon;
    }
    inputs.end_planes = parse_end_planes(match &args.inputs[9] {
        Value::Text(t) => t,
        _ => "perpendicular",
    })?;
    let wrt = Wrt {
        apex: wanted(2) || wanted(7),
        directrix: wanted(0),
        epsilon: false,
        normals: false,
    };
    let owned = OwnedBars::of(args)?;
    let adjoint = coplanar_adjoint_for(&inputs, mesh, owned.bars(), wrt)?;
    let mut result = vec![None; args.inputs.len()];
    if wanted(0) {
        result[0] = adjoint.directrix.as_deref().map(flat);
    }
    if wanted(1) {
        result[1] = Some(flat(&adjoint.generatrix));
    }
    if wanted(2) {
        result[2] = adjoint.apex;
    }
    if wanted(3) {
        result[3] = Some(adjoint.ruling_ratios);
    }
    if wanted(4) {
        result[4] = Some(adjoint.plane_ratios);
    }
    // Nothing was corrected: α and ε change nothing here.
    for k in [5, 8] {
        if wanted(k) {
            result[k] = Some(vec![0.0]);
        }
    }
    if wanted(7) && scale.is_some() {
        result[7] = adjoint.scale.map(|s| vec![s]);
    }
    Ok(result)
}

/// The apices output's cotangent (its leaves: 3 per apex, none for one at infinity) as one vector
/// per apex (zero at infinity).
fn apices_cotangent(apices: &Value, leaves: &[f64]) -> Result<Vec<DVec3>, NodeError> {
    let items = apices.as_list().unwrap_or_default();
    let mut at = leaves.chunks_exact(3);
    let out: Vec<DVec3> = items
        .iter()
        .map(|v| match v {
            Value::Point(_) => at
                .next()
                .map_or(DVec3::ZERO, |c| DVec3::new(c[0], c[1], c[2])),
            _ => DVec3::ZERO,
        })
        .collect();
    if at.next().is_some() || !leaves.len().is_multiple_of(3) {
        return Err(NodeError::new(
            "internal: the apices' cotangent does not fit",
        ));
    }
    Ok(out)
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
        "ctube.construct" => Some(ctube),
        "cnets.construct_coplanar" => Some(coplanar),
        _ => None,
    }
}

/// The branch function of a construction node and the outputs its derivative reads off the path
/// (the corrections: which piece a corrected run took), by id.
pub fn branch(id: &str) -> Option<(BranchFn, &'static [&'static str])> {
    match id {
        // The coplanar construction's ruling ratios are its input 3 too.
        "cnets.construct" | "cnets.construct_coplanar" => {
            Some((construct_branch, &["corrections"]))
        }
        _ => None,
    }
}

type BranchFn = fn(&[Value], &[Value]) -> Option<Branch>;
