//! Issue 27 §2, the readers and writers: every hostile file of the issue, built small here, ends in
//! a clear error (or a result) under a 64 MB budget, and the process never allocates more than the
//! budget + 192 MB on the way.
//!
//! This test binary counts its allocations as the `cnets` binary does (`cap`'s wrapper around the
//! system allocator, registered with `cnets_engine::budget::set_allocated_probe`) and sets the
//! wrapper's hard limit to what it has allocated + budget + 192 MB before each case: a reader
//! that allocates past it fails the allocation, and the process aborts — this test then fails.
//! The cases run one after the other in one test (the count is the process's).

use std::path::{Path, PathBuf};

use base64::Engine as _;
use cnets_engine::eval::evaluate_node;
use cnets_engine::{MemoryBudget, NodeContext, Value};

#[global_allocator]
static ALLOCATOR: cap::Cap<std::alloc::System> = cap::Cap::new(std::alloc::System, usize::MAX);

fn allocated() -> u64 {
    ALLOCATOR.allocated() as u64
}

/// The budget of every case.
const BUDGET: u64 = 64_000_000;

/// What a case may allocate beyond the budget before the allocator refuses (and the test aborts).
const MARGIN: u64 = 192_000_000;

struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Self {
        let d = std::env::temp_dir().join(format!("cnets-reader-limits-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("out")).unwrap();
        Scratch(d)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs `node` on `inputs` in `dir` under the budget, with the allocator capped at what is
/// allocated now + budget + margin; returns the outputs or the error text.
fn run(dir: &Path, node: &str, inputs: &[(&str, Value)]) -> Result<Vec<Value>, String> {
    let registry = cnets_nodes::registry();
    let def = registry.get(node).unwrap_or_else(|| panic!("{node}"));
    let mut values: Vec<Value> = def
        .inputs
        .iter()
        .map(|p| p.default.clone().unwrap_or(Value::Null))
        .collect();
    for (name, v) in inputs {
        values[def.input_index(name).unwrap()] = v.clone();
    }
    let ctx = NodeContext::new(Some(dir.join("out")), Some(dir.to_path_buf()))
        .with_budget(MemoryBudget::new(BUDGET));
    let base = ALLOCATOR.allocated();
    ALLOCATOR
        .set_limit(base + (BUDGET + MARGIN) as usize)
        .expect("the limit is above what is allocated");
    let result = evaluate_node(def, &ctx, &values);
    ALLOCATOR.set_limit(usize::MAX).unwrap();
    result.map(|o| o.values).map_err(|e| e.to_string())
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    std::fs::write(dir.join(name), bytes).unwrap();
    name.to_string()
}

fn read_mesh(dir: &Path, file: &str) -> Result<Vec<Value>, String> {
    run(dir, "io.read_mesh", &[("path", Value::text(file))])
}

fn read_polylines(dir: &Path, file: &str, segments: i64) -> Result<Vec<Value>, String> {
    run(
        dir,
        "io.read_polylines",
        &[
            ("path", Value::text(file)),
            ("segments", Value::Integer(segments)),
        ],
    )
}

/// A glTF document (JSON) whose buffer 0 is `bin` as a data URI, with one triangle-list mesh of
/// `vertices` positions, and `extra` spliced into the top level.
fn gltf_json(vertices: usize, bin_uri: &str, nodes: &str, extra: &str) -> String {
    format!(
        r#"{{"asset": {{"version": "2.0"}},
"buffers": [{{"byteLength": {len}, "uri": "{bin_uri}"}}],
"bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": {len}}}],
"accessors": [{{"bufferView": 0, "componentType": 5126, "count": {vertices}, "type": "VEC3",
  "min": [0, 0, 0], "max": [1, 1, 1]}}],
"meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
{nodes}
{extra}}}"#,
        len = vertices * 12
    )
}

/// `vertices` float positions (a triangle fan's worth of points).
fn positions(vertices: usize) -> Vec<u8> {
    (0..vertices * 3)
        .flat_map(|k| ((k % 7) as f32 * 0.125).to_le_bytes())
        .collect()
}

fn data_uri(bytes: &[u8]) -> String {
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

fn expect_budget_error(case: &str, result: Result<Vec<Value>, String>) -> String {
    let e = result.expect_err(case);
    assert!(
        e.contains("the limit is 64 MB") || e.contains("more than the file"),
        "{case}: {e}"
    );
    assert!(e.len() < 600, "{case}: a short message: {e}");
    e
}

#[test]
fn every_hostile_reader_case_stops_at_the_budget() {
    cnets_engine::budget::set_allocated_probe(allocated);
    let scratch = Scratch::new();
    let dir = &scratch.0;

    // PLY: 242 bytes declaring a billion items.
    let mut ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement junk 1000000000\nproperty uchar a\nend_header\n".to_vec();
    ply.extend_from_slice(&[0u8; 36]);
    let e = expect_budget_error("ply", read_mesh(dir, &write(dir, "junk.ply", &ply)));
    assert!(
        e.contains("element 'junk' declares 1000000000 items"),
        "{e}"
    );

    // glTF: one node listing the same child 2 000 times, the child's mesh 3 000 vertices: 6·10⁶
    // vertices made (288 MB), the file 50 kB.
    let children = vec!["1"; 2000].join(",");
    let nodes = format!(
        r#""nodes": [{{"children": [{children}]}}, {{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0,"#
    );
    let text = gltf_json(3000, &data_uri(&positions(3000)), &nodes, r#""extras": {}"#);
    expect_budget_error(
        "gltf instances",
        read_mesh(dir, &write(dir, "twice.gltf", text.as_bytes())),
    );

    // GLB: a 1 MB binary chunk named by 1 000 buffers (1 GB when each copies it): read at once.
    let vertices = 1 << 16;
    let bin = positions(vertices);
    let buffers = vec![format!(r#"{{"byteLength": {}}}"#, bin.len()); 1000].join(",");
    let json = gltf_json(
        vertices,
        "x",
        r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],"#,
        r#""extras": {}"#,
    )
    .replace(
        &format!(r#"[{{"byteLength": {}, "uri": "x"}}]"#, bin.len()),
        &format!("[{buffers}]"),
    );
    let file = write(dir, "shared.glb", &glb(&json, &bin));
    drop((json, bin));
    let out = read_mesh(dir, &file);
    // (No faces: the positions are a triangle list of 2¹⁶ points: 21 845 triangles.)
    let Ok(out) = out else {
        panic!("the GLB reads: {}", out.unwrap_err())
    };
    assert!(matches!(&out[0], Value::Mesh(m) if m.face_count() == vertices / 3));

    // A data URI of 40 MB of base64 (30 MB decoded) beside its 40 MB file text. (The test's own
    // copies are dropped before the case: the count is the whole process's.)
    let file = {
        let big = positions(2_500_000);
        let text = gltf_json(
            2_500_000,
            &data_uri(&big),
            r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],"#,
            r#""extras": {}"#,
        );
        write(dir, "uri.gltf", text.as_bytes())
    };
    expect_budget_error("data uri", read_mesh(dir, &file));

    // DXF: 2 000 circles sampled with 10 000 segments each (2·10⁷ points).
    let mut dxf = String::from("0\nSECTION\n2\nENTITIES\n");
    for k in 0..2000 {
        dxf.push_str(&format!(
            "0\nCIRCLE\n8\n0\n10\n{k}.0\n20\n0.0\n30\n0.0\n40\n1.0\n"
        ));
    }
    dxf.push_str("0\nENDSEC\n0\nEOF\n");
    expect_budget_error(
        "dxf circles",
        read_polylines(dir, &write(dir, "c.dxf", dxf.as_bytes()), 10_000),
    );

    // SVG: 2 000 cubic curves flattened with 10 000 segments; an entity expanded 10⁴ times.
    let paths: String = (0..2000)
        .map(|k| format!(r#"<path d="M{k} 0 C1 1 2 2 3 3"/>"#))
        .collect();
    let svg = format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{paths}</svg>"#);
    expect_budget_error(
        "svg curves",
        read_polylines(dir, &write(dir, "c.svg", svg.as_bytes()), 10_000),
    );
    let entity = "L1 1 ".repeat(2000);
    let refs = "&e;".repeat(10_000);
    let svg = format!(
        r#"<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY e "{entity}">]><svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 {refs}"/></svg>"#
    );
    let e = expect_budget_error(
        "svg entity",
        read_polylines(dir, &write(dir, "e.svg", svg.as_bytes()), 16),
    );
    assert!(e.contains("entities"), "{e}");

    // CSV: one line of 3·10⁶ columns.
    let file = write(dir, "wide.csv", "1,".repeat(3_000_000).as_bytes());
    let e = read_polylines(dir, &file, 16).unwrap_err();
    assert!(
        e.contains("line 1: expected 2 or 3 numbers, got 4 or more fields"),
        "{e}"
    );

    // OBJ: 20 MB of faces (1.6·10⁶ triangles over 3 vertices).
    let file = {
        let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        obj.push_str(&"f 1 2 3\n".repeat(2_500_000));
        write(dir, "big.obj", obj.as_bytes())
    };
    expect_budget_error("obj", read_mesh(dir, &file));

    // Writers: a 10⁶-point curve as JSON and CSV (a JSON tree of it took 6 GB at 10⁷) is written
    // within the budget.
    let curve = run(dir, "curve.circle", &[("count", Value::Integer(1_000_000))])
        .unwrap()
        .remove(0);
    for node in ["io.export_json", "io.export_csv"] {
        let out =
            run(dir, node, &[("value", curve.clone())]).unwrap_or_else(|e| panic!("{node}: {e}"));
        let Value::Text(path) = &out[0] else {
            panic!("{node}: a path")
        };
        assert!(
            std::fs::metadata(path.as_ref()).unwrap().len() > 20_000_000,
            "{node}"
        );
    }
}

/// A GLB file of a JSON chunk and a binary chunk.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}
