//! Shared helpers of the fabrication and export node tests: running a registered node by port name,
//! test cone-nets, scratch output directories and the external readers (glTF validator, ezdxf).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use cnets_engine::eval::evaluate_node;
use cnets_engine::{NodeContext, NodeDef, Value};
use cnets_geometry::conenet::{ConeNet, CtubeInputs, construct_ctube};
use cnets_geometry::{DVec3, Polyline};

/// The registered node type with this id (so the id itself is checked).
pub fn def(id: &str) -> Arc<NodeDef> {
    cnets_nodes::registry()
        .get(id)
        .unwrap_or_else(|| panic!("{id} is not registered"))
        .clone()
}

/// Input and output port names of a node type.
pub fn ports(id: &str) -> (Vec<String>, Vec<String>) {
    let d = def(id);
    (
        d.inputs.iter().map(|p| p.name.to_string()).collect(),
        d.outputs.iter().map(|p| p.name.to_string()).collect(),
    )
}

/// What a node run produced besides its outputs.
#[derive(Debug, Default)]
pub struct Extras {
    /// Files the node recorded.
    pub files: Vec<PathBuf>,
    /// Warnings.
    pub warnings: Vec<String>,
}

/// Runs node `id` with the named inputs (others: their defaults, or empty), returning the outputs by
/// name or the node's error message.
pub fn run(
    ctx: &NodeContext,
    id: &str,
    given: &[(&str, Value)],
) -> Result<Vec<(String, Value)>, String> {
    run_full(ctx, id, given).map(|(o, _)| o)
}

/// Like [`run`], also returning the recorded files and warnings.
pub fn run_full(
    ctx: &NodeContext,
    id: &str,
    given: &[(&str, Value)],
) -> Result<(Vec<(String, Value)>, Extras), String> {
    let d = def(id);
    for (name, _) in given {
        assert!(d.input_index(name).is_some(), "{id} has no input '{name}'");
    }
    let inputs: Vec<Value> = d
        .inputs
        .iter()
        .map(|p| {
            given
                .iter()
                .find(|(n, _)| *n == p.name)
                .map(|(_, v)| v.clone())
                .or_else(|| p.default.clone())
                .unwrap_or(Value::Null)
        })
        .zip(&d.inputs)
        // As the evaluator does: a quad mesh given to a mesh port arrives as a polygon mesh.
        .map(|(v, p)| cnets_engine::convert::coerce_for_port(&v, &p.ty, p.access).unwrap_or(v))
        .collect();
    let out = evaluate_node(&d, ctx, &inputs).map_err(|e| e.to_string())?;
    let named = d
        .outputs
        .iter()
        .map(|p| p.name.to_string())
        .zip(out.values)
        .collect();
    Ok((
        named,
        Extras {
            files: out.files,
            warnings: out.warnings,
        },
    ))
}

/// The output `name` of a run.
pub fn get<'a>(outputs: &'a [(String, Value)], name: &str) -> &'a Value {
    &outputs
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no output '{name}'"))
        .1
}

/// A curved open directrix of `m` points.
pub fn directrix(m: usize) -> Polyline {
    Polyline::open(
        (0..m)
            .map(|j| {
                let t = j as f64;
                DVec3::new(t, 0.3 * (0.7 * t).sin(), 0.04 * t * t)
            })
            .collect(),
    )
}

/// A C-tube cone-net of n × m vertices (open or closed generatrix).
pub fn cone_net(n: usize, m: usize, closed: bool) -> ConeNet {
    let points = (0..n)
        .map(|i| {
            let t = if closed {
                std::f64::consts::TAU * i as f64 / n as f64
            } else {
                0.3 + 2.2 * i as f64 / (n - 1) as f64
            };
            DVec3::new(-0.1 * t.cos(), 1.2 * t.cos(), 0.9 * t.sin() + 0.2)
        })
        .collect();
    let apex: Vec<f64> = (1..m)
        .map(|j| if j % 2 == 0 { 1.06 } else { 0.93 })
        .collect();
    construct_ctube(&CtubeInputs::new(directrix(m), Polyline { points, closed }).apex(apex))
        .expect("the test cone-net constructs")
}

/// A fresh, empty scratch directory under the system temp dir.
pub fn scratch(name: &str) -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "cnets-{name}-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A context that writes into `dir`.
pub fn ctx_in(dir: &Path) -> NodeContext {
    NodeContext::new(Some(dir.to_path_buf()), None)
}

/// The repository root.
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs an external checker (`program script file`) and returns its stdout. Fails the test with a
/// clear message when the program or its package is missing: these tools are installed by
/// `scripts/install-test-deps.sh` and must run in CI.
pub fn run_checker(program: &str, script: &str, file: &Path) -> String {
    let root = repo_root();
    let out = Command::new(program)
        .arg(root.join(script))
        .arg(file)
        .current_dir(&root)
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run `{program}` ({e}): it is needed by this test; install the test tools with scripts/install-test-deps.sh"
            )
        });
    assert!(
        out.status.success(),
        "`{program} {script}` failed ({}): {}\ninstall the test tools with scripts/install-test-deps.sh",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 report")
}

/// The names of every entry of a directory.
pub fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|r| {
            r.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}
