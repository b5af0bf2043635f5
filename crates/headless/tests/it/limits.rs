//! Bounded resources through the command line: graphs and inputs that used to abort the process
//! (allocation failure, stack overflow) end with a clear error and exit 1 (a node) or 2 (a graph
//! that cannot load), quickly. Each reproducer is the issue's, sized to fail fast under a small
//! `--max-memory`.

use crate::common;

use std::path::{Path, PathBuf};

use common::Folder;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn cnets(args: &[&str]) -> (Output, Duration) {
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .output()
        .unwrap();
    let time = start.elapsed();
    // A figure (issue 30): the limits below are ≥ 10× the measured time.
    eprintln!("cnets {}: {time:?}", args[0]);
    (out, time)
}

fn folder(name: &str) -> Folder {
    Folder::new(&format!("limits-{name}"))
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `graph` under a 64 MB budget and checks it fails on a node, quickly, naming the size.
fn run_fails_within_budget(graph: &Path, node: &str) -> String {
    let (o, time) = cnets(&["run", graph.to_str().unwrap(), "--max-memory", "64MB"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(&format!("node '{node}'")), "{err}");
    assert!(
        err.contains("needs") && err.contains("the limit is 64 MB"),
        "{err}"
    );
    assert!(time < Duration::from_secs(30), "took {time:?}");
    err
}

#[test]
fn a_construction_on_huge_polylines_fails_before_allocating() {
    let d = folder("construct");
    let line = |axis: usize| {
        let pts: Vec<String> = (0..100_000)
            .map(|k| {
                let mut p = [0.0; 3];
                p[axis] = k as f64 * 0.01;
                format!("[{},{},{}]", p[0], p[1], p[2])
            })
            .collect();
        format!("{{\"points\": [{}], \"closed\": false}}", pts.join(","))
    };
    let inputs = d.join("inputs.json");
    std::fs::write(
        &inputs,
        format!(
            "{{\"directrix\": {}, \"generatrix\": {}}}",
            line(0),
            line(1)
        ),
    )
    .unwrap();
    let (o, time) = cnets(&[
        "eval",
        "ctube.construct",
        "--inputs",
        inputs.to_str().unwrap(),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("a cone-net of 100000 × 100000 vertices needs 640 GB, the limit is"),
        "{err}"
    );
    assert!(time < Duration::from_secs(30), "took {time:?}");
    let (o, _) = cnets(&[
        "eval",
        "ctube.construct",
        "--inputs",
        inputs.to_str().unwrap(),
        "--max-memory",
        "nonsense",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

/// A graph whose previewed table `t` of a 10⁵-number series by itself needs 320 GB (and a circle,
/// something to render).
fn table_graph(d: &Path) -> PathBuf {
    let g = d.join("table.ron");
    std::fs::write(
        &g,
        r#"(
    version: 1,
    nodes: {
        "s": (type: "param.series", inputs: {"count": 100000}),
        "t": (type: "list.table", preview: true),
        "circle": (type: "curve.circle", inputs: {"count": 8}),
    },
    edges: ["s.values -> t.rows", "s.values -> t.columns"],
)"#,
    )
    .unwrap();
    g
}

#[test]
fn a_series_into_both_inputs_of_a_table_fails() {
    let d = folder("table");
    let g = table_graph(&d);
    let err = run_fails_within_budget(&g, "t");
    assert!(
        err.contains("a table of 100000 × 100000 numbers needs 320 GB"),
        "{err}"
    );
}

#[test]
fn repeating_a_list_and_a_long_series_fail() {
    let d = folder("repeat");
    let g = d.join("repeat.ron");
    std::fs::write(
        &g,
        r#"(
    version: 1,
    nodes: {
        "s": (type: "param.series", inputs: {"count": 1000}),
        "r": (type: "list.repeat", inputs: {"count": 10000000}),
        "f": (type: "list.flatten"),
        "big": (type: "param.series", inputs: {"count": 10000000}),
    },
    edges: ["s.values -> r.value", "r.list -> f.tree"],
)"#,
    )
    .unwrap();
    let (o, time) = cnets(&["run", g.to_str().unwrap(), "--max-memory", "64MB"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "node 'r' (list.repeat): a list of 10000000 copies needs 320 MB, the limit is 64 MB"
        ),
        "{err}"
    );
    assert!(
        err.contains("node 'big' (param.series): a series of 10000000 numbers needs 320 MB"),
        "{err}"
    );
    assert!(time < Duration::from_secs(30), "took {time:?}");
}

#[test]
fn a_flatten_ladder_stops_at_the_budget() {
    let d = folder("ladder");
    let mut nodes = vec![
        r#""a0": (type: "param.series", inputs: {"count": 4}),"#.to_string(),
        r#""b0": (type: "param.series", inputs: {"count": 4}),"#.to_string(),
    ];
    let mut edges = Vec::new();
    for k in 1..=28 {
        let out = if k == 1 { "values" } else { "list" };
        for n in ["a", "b"] {
            nodes.push(format!(r#""{n}{k}": (type: "list.flatten"),"#));
            edges.push(format!(r#""a{}.{out} -> {n}{k}.tree""#, k - 1));
            edges.push(format!(r#""b{}.{out} -> {n}{k}.tree""#, k - 1));
        }
    }
    let g = d.join("ladder.ron");
    std::fs::write(
        &g,
        format!(
            "(version: 1, nodes: {{ {} }}, edges: [{}])",
            nodes.join("\n"),
            edges.join(", ")
        ),
    )
    .unwrap();
    // Level 17's lists (524 288 items, 17 MB each) do not fit beside what the process holds
    // for the levels below (about 50 MB, counted by the process's allocator): refused before
    // they are built.
    let err = run_fails_within_budget(&g, "b17");
    assert!(
        err.contains("524288 items needs 17 MB, the limit is 64 MB"),
        "{err}"
    );
}

#[test]
fn clusters_used_twice_nested_deep_stop_at_the_budget() {
    // Level k runs level k − 1 twice and merges both results into its output: 2ᵏ copies. Once
    // with the copies merged as they are (the list doubles in memory at every level), once
    // flattened by a node.
    for flatten in [false, true] {
        let d = folder(&format!("twice-{flatten}"));
        std::fs::write(
            d.join("level0.ron"),
            r#"(version: 1, nodes: {
    "x": (type: "graph.input", inputs: {"name": "x", "type": "tree<number>"}),
    "y": (type: "graph.output", inputs: {"name": "y", "type": "tree<number>"}),
}, edges: ["x.value -> y.value"])"#,
        )
        .unwrap();
        let (node, edges) = if flatten {
            (
                r#""f": (type: "list.flatten"),"#,
                r#""c1.y -> f.tree", "c2.y -> f.tree", "f.list -> y.value""#,
            )
        } else {
            ("", r#""c1.y -> y.value", "c2.y -> y.value""#)
        };
        for k in 1..=25 {
            std::fs::write(
                d.join(format!("level{k}.ron")),
                format!(
                    r#"(version: 1, nodes: {{
    "x": (type: "graph.input", inputs: {{"name": "x", "type": "tree<number>"}}),
    "c1": (type: "cluster", source: "level{p}.ron"),
    "c2": (type: "cluster", source: "level{p}.ron"),
    {node}
    "y": (type: "graph.output", inputs: {{"name": "y", "type": "tree<number>"}}),
}}, edges: ["x.value -> c1.x", "x.value -> c2.x", {edges}])"#,
                    p = k - 1
                ),
            )
            .unwrap();
        }
        let g = d.join("top.ron");
        std::fs::write(
            &g,
            r#"(version: 1, nodes: {
    "s": (type: "param.series", inputs: {"count": 16}),
    "c": (type: "cluster", source: "level25.ron"),
}, edges: ["s.values -> c.x"])"#,
        )
        .unwrap();
        let err = run_fails_within_budget(&g, "c");
        assert!(err.contains("inside cluster"), "{err}");
    }
}

/// A chain of `len` cluster files, `c0.ron` using `c1.ron` using … a last one that doubles.
fn chain(d: &Path, len: usize) -> PathBuf {
    for k in 0..len {
        let body = if k + 1 == len {
            r#""m": (type: "math.multiply", inputs: {"b": 2.0}),"#.to_string()
        } else {
            format!(r#""m": (type: "cluster", source: "c{}.ron"),"#, k + 1)
        };
        let edges = if k + 1 == len {
            r#""x.value -> m.a", "m.result -> y.value""#
        } else {
            r#""x.value -> m.x", "m.y -> y.value""#
        };
        std::fs::write(
            d.join(format!("c{k}.ron")),
            format!(
                r#"(version: 1, nodes: {{
    "x": (type: "graph.input", inputs: {{"name": "x", "type": "number"}}),
    {body}
    "y": (type: "graph.output", inputs: {{"name": "y", "type": "number"}}),
}}, edges: [{edges}])"#
            ),
        )
        .unwrap();
    }
    let top = d.join("top.ron");
    std::fs::write(
        &top,
        r#"(version: 1, nodes: {
    "n": (type: "param.number", inputs: {"value": 0.75}),
    "c": (type: "cluster", source: "c0.ron"),
}, edges: ["n.value -> c.x"])"#,
    )
    .unwrap();
    top
}

#[test]
fn a_chain_of_cluster_files_deeper_than_the_limit_is_refused_by_check_and_run() {
    let d = folder("chain");
    let top = chain(&d, 1850);
    for command in ["check", "run"] {
        let (o, time) = cnets(&[command, top.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{command}: {err}");
        assert!(
            err.contains("clusters nested more than 256 deep: the chain starting at")
                && err.contains("top.ron"),
            "{command}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "one line, not one per file: {err}");
        assert!(time < Duration::from_secs(30), "took {time:?}");
    }
}

#[test]
fn a_chain_of_cluster_files_within_the_limit_loads_and_runs() {
    let d = folder("chain-ok");
    let top = chain(&d, 200);
    let (o, _) = cnets(&["run", top.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["nodes"]["c"]["outputs"]["y"].as_f64(), Some(1.5));
}

/// `cnets eval` of `inputs` (a file in `dir`) under `ulimit -v kb` through the shell.
fn eval_under_ulimit(dir: &Path, kb: u64, node: &str, inputs: &str, extra: &str) -> Output {
    std::fs::write(dir.join("in.json"), inputs).unwrap();
    Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {kb} && exec '{}' eval {node} --inputs in.json {extra}",
            env!("CARGO_BIN_EXE_cnets")
        ))
        .current_dir(dir)
        .output()
        .unwrap()
}

#[test]
fn the_default_budget_is_half_the_address_space_the_process_has() {
    let d = folder("rlimit");
    // A table of 10⁴ × 10⁴ numbers (3.2 GB) under RLIMIT_AS of 3 GB: refused by a budget of half
    // of it, where the machine's half would have let it run into the limit and abort.
    let row = vec!["0.5"; 10_000].join(",");
    let inputs = format!(r#"{{"rows": [{row}], "columns": [{row}]}}"#);
    let o = eval_under_ulimit(&d, 3_000_000, "list.table", &inputs, "");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("the limit is 1.5 GB"), "{}", stderr(&o));
    // --max-memory still overrides it.
    let o = eval_under_ulimit(&d, 3_000_000, "list.table", &inputs, "--max-memory 64M");
    assert!(stderr(&o).contains("the limit is 64 MB"), "{}", stderr(&o));
}

#[test]
fn a_json_list_larger_than_the_budget_is_refused_while_it_is_read() {
    let d = folder("json-budget");
    // 4·10⁶ numbers (32 MB as f64) into math.add under 16 MB: refused in the text, where it is.
    let numbers = vec!["0.5"; 4_000_000].join(",");
    std::fs::write(
        d.join("in.json"),
        format!(r#"{{"b": 1, "a": [{numbers}]}}"#),
    )
    .unwrap();
    let (o, _) = cnets(&[
        "eval",
        "math.add",
        "--inputs",
        d.join("in.json").to_str().unwrap(),
        "--max-memory",
        "16M",
        "--timing",
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the input needs more than the memory limit of 16 MB"),
        "{err}"
    );
    assert!(!err.contains("invalid JSON"), "{err}");
    // 10⁶ numbers fit as a document (8 MB) but not expanded into values for the mapping (32 MB
    // of values, 32 MB of results): refused before any value is made.
    let numbers = vec!["0.5"; 1_000_000].join(",");
    std::fs::write(
        d.join("in.json"),
        format!(r#"{{"b": 1, "a": [{numbers}]}}"#),
    )
    .unwrap();
    let (o, _) = cnets(&[
        "eval",
        "math.add",
        "--inputs",
        d.join("in.json").to_str().unwrap(),
        "--max-memory",
        "40M",
        "--timing",
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("running 'math.add' on 1000000 items needs 32 MB, the limit is 40 MB"),
        "{err}"
    );
    let peak: f64 = err
        .lines()
        .find_map(|l| l.strip_prefix("peak memory: "))
        .and_then(|l| l.trim_end_matches(" MB").parse().ok())
        .expect("--timing prints the peak");
    assert!(peak < 40.0 + 256.0, "peak {peak} MB");
}

/// A cluster file that doubles its input (put outside the graph's folder: reading it needs
/// `--allow-read`).
const DOUBLE: &str = r#"(version: 1, nodes: {
    "x": (type: "graph.input", inputs: {"name": "x", "type": "number"}),
    "d": (type: "math.multiply", inputs: {"b": 2.0}),
    "y": (type: "graph.output", inputs: {"name": "y", "type": "number"}),
}, edges: ["x.value -> d.a", "d.result -> y.value"])"#;

/// Issue 46 §4: every subcommand that evaluates takes the session flags of `run` —
/// `--max-memory` and `--allow-read` included for `render`, `optimize` and `drag`.
#[test]
fn render_optimize_and_drag_take_the_session_flags() {
    let d = folder("session");
    let elsewhere = folder("session-elsewhere");
    std::fs::write(elsewhere.join("double.ron"), DOUBLE).unwrap();
    let g = d.join("g.ron");
    std::fs::write(
        &g,
        format!(
            r#"(version: 1, nodes: {{
    "x": (type: "param.number", inputs: {{"value": 0.3, "min": 0.0, "max": 1.0}}),
    "c": (type: "cluster", source: "{}"),
    "q": (type: "math.multiply", inputs: {{"b": 1.0}}),
    "circle": (type: "curve.circle", inputs: {{"count": 8}}),
}}, edges: ["x.value -> c.x", "c.y -> q.a"],
optimization: (objective: "q.result", variables: [(input: "x.value", min: 0.0, max: 1.0)]))"#,
            elsewhere.join("double.ron").display()
        ),
    )
    .unwrap();
    let (g, allowed) = (g.to_str().unwrap(), elsewhere.to_str().unwrap());
    let png = d.join("g.png");
    let png = png.to_str().unwrap();
    // Without `--allow-read` the cluster file is refused, by every subcommand alike.
    for args in [vec!["optimize", g], vec!["render", g, "--png", png]] {
        let (o, _) = cnets(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("outside the folders reads are allowed in"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    let session = ["--allow-read", allowed, "--max-memory", "512MB"];
    let (o, _) = cnets(&[&["optimize", g][..], &session].concat());
    assert!(o.status.success(), "optimize: {}", stderr(&o));
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("objective"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let (o, _) = cnets(&[&["render", g, "--png", png][..], &session].concat());
    assert!(o.status.success(), "render: {}", stderr(&o));
    assert!(Path::new(png).is_file());
    // `drag` parses them too (the drag itself fails: the graph has no quad mesh to drag).
    let drag = [
        "drag", g, "--node", "circle", "--vertex", "0,0", "--to", "0,0,1",
    ];
    let (o, _) = cnets(&[&drag[..], &session].concat());
    assert_ne!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        !stderr(&o).contains("unexpected argument"),
        "{}",
        stderr(&o)
    );
    // A bad size is a usage error everywhere.
    for sub in [vec!["optimize", g], vec!["render", g, "--png", png]] {
        let (o, _) = cnets(&[&sub[..], &["--max-memory", "nonsense"]].concat());
        assert_eq!(o.status.code(), Some(2), "{sub:?}: {}", stderr(&o));
    }
}

/// A too-small `--max-memory` stops `render`'s evaluation with the words `run` uses.
#[test]
fn render_under_a_small_budget_says_what_run_says() {
    let d = folder("render-budget");
    let g = table_graph(&d);
    let said = |err: &str| -> String {
        err.lines()
            .find_map(|l| l.split_once("node 't' (list.table): ").map(|(_, m)| m))
            .unwrap_or_else(|| panic!("no error of node 't' in:\n{err}"))
            .to_string()
    };
    let run = run_fails_within_budget(&g, "t");
    let png = d.join("table.png");
    let (o, time) = cnets(&[
        "render",
        g.to_str().unwrap(),
        "--png",
        png.to_str().unwrap(),
        "--max-memory",
        "64MB",
    ]);
    let render = stderr(&o);
    assert!(time < Duration::from_secs(30), "took {time:?}");
    assert_eq!(said(&render), said(&run), "{render}");
    assert!(
        said(&render)
            .contains("a table of 100000 × 100000 numbers needs 320 GB, the limit is 64 MB"),
        "{render}"
    );
}
