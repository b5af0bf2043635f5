//! The `cnets` command line as outside checks drive it: arguments, JSON, exit codes, messages.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use serde_json::Value as Json;

fn cnets(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .current_dir(workspace())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cnets starts");
    if let Some(text) = stdin {
        // The command may exit before reading its input (a usage error): ignore a broken pipe.
        let _ = child.stdin.take().unwrap().write_all(text.as_bytes());
    }
    drop(child.stdin.take());
    child.wait_with_output().unwrap()
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn stdout_json(o: &Output) -> Json {
    serde_json::from_slice(&o.stdout).unwrap_or_else(|e| {
        panic!(
            "stdout is not JSON ({e}): {}\nstderr: {}",
            String::from_utf8_lossy(&o.stdout),
            stderr(o)
        )
    })
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cnets-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn nodes_json_lists_every_type_with_ports() {
    let o = cnets(&["nodes", "--json"], None);
    assert!(o.status.success());
    let all = stdout_json(&o);
    let arc = all
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["id"] == "curve.arc")
        .expect("curve.arc listed");
    assert_eq!(arc["category"], "Curves");
    assert!(arc["doc"].as_str().unwrap().contains("arc"));
    let radius = arc["inputs"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "radius")
        .unwrap();
    assert_eq!(radius["type"], "number");
    assert_eq!(radius["default"], 1.0);
    assert_eq!(arc["outputs"][0]["name"], "curve");
    assert_eq!(arc["outputs"][0]["type"], "polyline");
    assert_eq!(radius["hint"]["widget"], "auto");
    // The hints and choices of issue 26: a slider, a choice port's words, a layer, a name.
    let find = |id: &str| {
        all.as_array()
            .unwrap()
            .iter()
            .find(|n| n["id"] == id)
            .unwrap()
            .clone()
    };
    let port = |node: &serde_json::Value, side: &str, name: &str| {
        node[side]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == name)
            .unwrap()
            .clone()
    };
    let slider = find("param.number");
    assert_eq!(slider["name"], "Number slider");
    assert_eq!(port(&slider, "inputs", "value")["hint"]["widget"], "slider");
    let construct = find("cnets.construct");
    let end_planes = port(&construct, "inputs", "end_planes");
    assert_eq!(end_planes["hint"]["widget"], "choice");
    assert_eq!(
        end_planes["choices"],
        serde_json::json!(["perpendicular", "mirror"])
    );
    assert_eq!(
        port(&construct, "outputs", "apices")["hint"]["layer"],
        "apices"
    );
    let mapper = find("mapper.graph");
    assert_eq!(
        port(&mapper, "inputs", "handles")["hint"]["range"],
        serde_json::json!([0.0, 1.0])
    );
    assert_eq!(port(&mapper, "inputs", "kind")["choices"][1], "bezier");
}

#[test]
fn eval_prints_outputs_as_one_json_object() {
    let o = cnets(
        &["eval", "curve.arc", "--inputs", "-"],
        Some(r#"{"radius": 2, "count": 3, "end": 180}"#),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout_json(&o);
    let points = out["curve"]["points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    assert_eq!(points[0], serde_json::json!([2.0, 0.0, 0.0]));
    assert_eq!(out["curve"]["closed"], false);
}

#[test]
fn eval_reads_inputs_from_a_file_and_reports_timing() {
    let dir = temp_dir("eval-file");
    let file = dir.join("in.json");
    std::fs::write(
        &file,
        r#"{"curve": {"points": [[0,0,0],[3,4,0]], "closed": true}}"#,
    )
    .unwrap();
    let o = cnets(
        &[
            "eval",
            "curve.length",
            "--inputs",
            file.to_str().unwrap(),
            "--timing",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout_json(&o)["length"], 10.0);
    let err = stderr(&o);
    let line = err
        .lines()
        .find(|l| l.starts_with("time: "))
        .expect("a time line");
    let ms: f64 = line
        .trim_start_matches("time: ")
        .trim_end_matches(" ms")
        .parse()
        .unwrap();
    assert!((0.0..1000.0).contains(&ms));
}

#[test]
fn eval_usage_errors_exit_2_and_name_the_input() {
    let o = cnets(
        &["eval", "curve.arc", "--inputs", "-"],
        Some(r#"{"radiuss": 1}"#),
    );
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("'radiuss'") && e.contains("centre, radius, start, end, plane, count"),
        "{e}"
    );

    let o = cnets(
        &["eval", "curve.arc", "--inputs", "-"],
        Some(r#"{"radius": "big"}"#),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("input 'radius' (number)"),
        "{}",
        stderr(&o)
    );

    let o = cnets(&["eval", "curve.length", "--inputs", "-"], Some("{}"));
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("missing required input 'curve'"),
        "{}",
        stderr(&o)
    );

    let o = cnets(&["eval", "curve.arcs", "--inputs", "-"], Some("{}"));
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("did you mean curve.arc"),
        "{}",
        stderr(&o)
    );

    let o = cnets(
        &["eval", "curve.arc", "--inputs", "-"],
        Some("{\"radius\": 1,"),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).starts_with("error: <stdin>:1:"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn eval_node_failure_exits_1_with_the_message() {
    let o = cnets(
        &["eval", "curve.arc", "--inputs", "-"],
        Some(r#"{"radius": -1}"#),
    );
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.starts_with("error: curve.arc: ") && e.contains("radius") && e.contains("-1"),
        "{e}"
    );
    assert!(o.stdout.is_empty());
}

#[test]
fn run_prints_a_summary_and_json() {
    let o = cnets(&["run", "graphs/curves-demo.ron"], None);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("3 nodes evaluated"), "{text}");

    let o = cnets(
        &[
            "run",
            "graphs/curves-demo.ron",
            "--json",
            "--set",
            "radius.value=1",
        ],
        None,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout_json(&o);
    let length = out["nodes"]["length"]["outputs"]["length"]
        .as_f64()
        .unwrap();
    assert!((length - std::f64::consts::PI).abs() < 0.01, "{length}");
    assert_eq!(out["nodes"]["length"]["errors"], serde_json::json!([]));
    assert!(out["nodes"]["arc"]["time_ms"].as_f64().unwrap() >= 0.0);
}

#[test]
fn run_reports_node_failures_with_exit_1_and_bad_files_with_exit_2() {
    let o = cnets(
        &[
            "run",
            "graphs/curves-demo.ron",
            "--json",
            "--set",
            "arc.count=1",
        ],
        None,
    );
    assert_eq!(o.status.code(), Some(1));
    let out = stdout_json(&o);
    let arc_error = out["nodes"]["arc"]["errors"][0].as_str().unwrap();
    assert!(
        arc_error.contains("count") && arc_error.contains('1'),
        "{arc_error}"
    );
    assert!(
        out["nodes"]["length"]["errors"][0]
            .as_str()
            .unwrap()
            .contains("'arc'")
    );
    assert_eq!(out["nodes"]["radius"]["outputs"]["value"], 2.5);

    let dir = temp_dir("bad-file");
    let bad = dir.join("bad.ron");
    std::fs::write(
        &bad,
        "(\n    version: 1,\n    nodes: {\"a\": (type: \"curve.arcc\")},\n)",
    )
    .unwrap();
    let o = cnets(&["run", bad.to_str().unwrap()], None);
    assert_eq!(o.status.code(), Some(2));
    let expected = format!(
        "error: {}:3:25: node 'a': unknown node type 'curve.arcc'",
        bad.display()
    );
    assert!(stderr(&o).starts_with(&expected), "{}", stderr(&o));

    let o = cnets(
        &["run", "graphs/curves-demo.ron", "--set", "arc.radiuss=1"],
        None,
    );
    assert_eq!(o.status.code(), Some(2));
    let o = cnets(&["run", "no/such/file.ron"], None);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no/such/file.ron: cannot read"));
}

#[test]
fn check_loads_without_evaluating() {
    let o = cnets(&["check", "graphs/curves-demo.ron"], None);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("3 nodes, 2 edges"));
    let dir = temp_dir("check");
    let cyc = dir.join("cycle.ron");
    std::fs::write(
        &cyc,
        "(version: 1, nodes: {\"a\": (type: \"curve.arc\"), \"l\": (type: \"curve.length\")},\n edges: [\"a.curve -> l.curve\", \"l.length -> a.radius\"])",
    )
    .unwrap();
    let o = cnets(&["check", cyc.to_str().unwrap()], None);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains(":2:32: edge 'l.length -> a.radius': connecting l.length -> a.radius would create a cycle"), "{}", stderr(&o));
}

#[test]
fn eval_outputs_computes_and_prints_only_the_outputs_asked_for() {
    let inputs = r#"{
        "directrix": {"points": [[0,0,0],[1,0,0.2],[2,0,0.1],[3,0,0]], "closed": false},
        "generatrix": {"points": [[0,0,0],[0,1,0.1],[0,2,0]], "closed": false}
    }"#;
    let all = cnets(&["eval", "ctube.construct", "--inputs", "-"], Some(inputs));
    assert!(
        all.status.success(),
        "{}",
        String::from_utf8_lossy(&all.stderr)
    );
    let all = stdout_json(&all);
    let o = cnets(
        &[
            "eval",
            "ctube.construct",
            "--inputs",
            "-",
            "--outputs",
            "mesh",
        ],
        Some(inputs),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mesh_only = stdout_json(&o);
    let keys: Vec<&String> = mesh_only.as_object().unwrap().keys().collect();
    assert_eq!(keys, vec!["mesh"]);
    assert_eq!(
        mesh_only["mesh"], all["mesh"],
        "the mesh alone equals the full run's"
    );
    let o = cnets(
        &[
            "eval",
            "ctube.construct",
            "--inputs",
            "-",
            "--outputs",
            "mesh,quality",
        ],
        Some(inputs),
    );
    let two = stdout_json(&o);
    assert_eq!(two.as_object().unwrap().len(), 2);
    assert_eq!(two["quality"], all["quality"]);
    let o = cnets(
        &[
            "eval",
            "ctube.construct",
            "--inputs",
            "-",
            "--outputs",
            "nope",
        ],
        Some(inputs),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown output 'nope'"));
}
