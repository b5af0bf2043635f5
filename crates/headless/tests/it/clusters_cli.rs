//! Clusters through the command line: `cnets run` with cluster files, `cnets eval cluster:<path>`,
//! `cnets nodes --library DIR`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn cnets(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // The command may exit before reading its input (a usage error): ignore a broken pipe.
    let _ = child.stdin.take().unwrap().write_all(stdin.as_bytes());
    child.wait_with_output().unwrap()
}

fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("cnets-clusters-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("lib")).unwrap();
    d
}

const ARC_LENGTH: &str = r#"(
    version: 1,
    name: "arc length",
    description: "The length of a half circle of a given radius.",
    nodes: {
        "r": (type: "graph.input", inputs: {"name": "radius", "type": "number", "default": 1.0, "doc": "Radius."}),
        "arc": (type: "curve.arc", inputs: {"end": 180.0, "count": 65}),
        "len": (type: "curve.length"),
        "out": (type: "graph.output", inputs: {"name": "length", "type": "number", "doc": "Arc length."}),
    },
    edges: ["r.value -> arc.radius", "arc.curve -> len.curve", "len.length -> out.value"],
)"#;

fn json(o: &Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&o.stderr)))
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

#[test]
fn eval_runs_a_graph_file_as_one_node() {
    let d = folder("eval");
    let file = d.join("lib/arc-length.ron");
    write(&file, ARC_LENGTH);
    let target = format!("cluster:{}", file.display());
    let o = cnets(&["eval", &target, "--inputs", "-"], r#"{"radius": 2}"#);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let length = json(&o)["length"].as_f64().unwrap();
    assert!(
        (length - 2.0 * std::f64::consts::PI).abs() < 0.01,
        "{length}"
    );

    let o = cnets(&["eval", &target, "--inputs", "-"], r#"{"diameter": 2}"#);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown input 'diameter'"));
    let o = cnets(&["eval", "cluster:/no/such.ron", "--inputs", "-"], "{}");
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn nodes_lists_a_library_folder_and_run_finds_clusters_there() {
    let d = folder("library");
    write(&d.join("lib/arc-length.ron"), ARC_LENGTH);
    write(&d.join("lib/broken.ron"), "(version: 1, nodes: {");
    let lib = d.join("lib");
    let o = cnets(&["nodes", "--json", "--library", lib.to_str().unwrap()], "");
    assert!(o.status.success());
    let all = json(&o);
    let list = all.as_array().unwrap();
    assert_eq!(list.len(), 1, "the broken file is skipped");
    assert_eq!(list[0]["inputs"][0]["name"], "radius");
    assert_eq!(list[0]["outputs"][0]["name"], "length");
    assert!(String::from_utf8_lossy(&o.stderr).contains("broken.ron"));

    let main = d.join("main.ron");
    write(
        &main,
        r#"(version: 1, nodes: {
            "a": (type: "cluster", source: "arc-length.ron", inputs: {"radius": 3.0}),
            "b": (type: "cluster", source: "arc-length", inputs: {"radius": 1.0}),
        }, edges: [])"#,
    );
    let o = cnets(&["run", main.to_str().unwrap(), "--json"], "");
    assert_eq!(o.status.code(), Some(2), "not found without the library");
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("cluster source 'arc-length.ron' not found")
    );
    let o = cnets(
        &[
            "run",
            main.to_str().unwrap(),
            "--json",
            "--library",
            lib.to_str().unwrap(),
        ],
        "",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = json(&o);
    let a = out["nodes"]["a"]["outputs"]["length"].as_f64().unwrap();
    let b = out["nodes"]["b"]["outputs"]["length"].as_f64().unwrap();
    assert!((a / b - 3.0).abs() < 1e-12, "{a} {b}");

    // A changed cluster file is picked up by the next run.
    write(
        &d.join("lib/arc-length.ron"),
        &ARC_LENGTH.replace("\"end\": 180.0", "\"end\": 90.0"),
    );
    let o = cnets(
        &[
            "run",
            main.to_str().unwrap(),
            "--json",
            "--library",
            lib.to_str().unwrap(),
        ],
        "",
    );
    let a2 = json(&o)["nodes"]["a"]["outputs"]["length"]
        .as_f64()
        .unwrap();
    assert!((a2 / a - 0.5).abs() < 1e-3, "{a2} {a}");
}

/// `CNETS_LIBRARY` (folders separated like `PATH`) is searched for cluster sources after the
/// graph's folder and before `--library`'s folders, by `run`, `check` and a graph run by `eval`
/// alike (the engine reads no environment: the command line hands these folders to its session).
#[test]
fn cnets_library_is_searched_before_the_library_flag() {
    let d = folder("env-library");
    let (env_a, env_b, flag) = (d.join("env-a"), d.join("env-b"), d.join("flag"));
    for dir in [&env_a, &env_b, &flag] {
        std::fs::create_dir_all(dir).unwrap();
    }
    write(&env_b.join("arc-length.ron"), ARC_LENGTH);
    write(
        &flag.join("arc-length.ron"),
        &ARC_LENGTH.replace("\"end\": 180.0", "\"end\": 90.0"),
    );
    let main = d.join("main.ron");
    write(
        &main,
        r#"(version: 1, nodes: {
            "a": (type: "cluster", source: "arc-length.ron", inputs: {"radius": 1.0}),
        }, edges: [])"#,
    );
    let with_env = |args: &[&str], env: Option<&std::ffi::OsStr>| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_cnets"));
        c.args(args).env_remove("CNETS_LIBRARY");
        if let Some(v) = env {
            c.env("CNETS_LIBRARY", v);
        }
        c.output().unwrap()
    };
    let joined = std::env::join_paths([&env_a, &env_b]).unwrap();
    let length = |o: &Output| json(o)["nodes"]["a"]["outputs"]["length"].as_f64().unwrap();
    let main = main.to_str().unwrap();
    let o = with_env(&["check", main], None);
    assert_eq!(o.status.code(), Some(2), "not found without a library");
    let o = with_env(&["check", main], Some(&joined));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = with_env(&["run", main, "--json"], Some(&joined));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        (length(&o) - std::f64::consts::PI).abs() < 0.01,
        "the half circle"
    );
    // `CNETS_LIBRARY`'s copy comes before `--library`'s.
    let flagged = ["run", main, "--json", "--library", flag.to_str().unwrap()];
    let o = with_env(&flagged, Some(&joined));
    assert!(
        (length(&o) - std::f64::consts::PI).abs() < 0.01,
        "CNETS_LIBRARY first"
    );
    let o = with_env(&flagged, None);
    assert!(
        (length(&o) - std::f64::consts::FRAC_PI_2).abs() < 0.01,
        "--library's"
    );
    // A graph run as one node finds its cluster sources there too.
    let target = format!("cluster:{}", d.join("outer.ron").display());
    write(
        &d.join("outer.ron"),
        r#"(version: 1, nodes: {
            "r": (type: "graph.input", inputs: {"name": "radius", "type": "number", "default": 1.0}),
            "a": (type: "cluster", source: "arc-length.ron"),
            "out": (type: "graph.output", inputs: {"name": "length", "type": "number"}),
        }, edges: ["r.value -> a.radius", "a.length -> out.value"])"#,
    );
    let inputs = d.join("inputs.json");
    write(&inputs, r#"{"radius": 2}"#);
    let o = with_env(
        &["eval", &target, "--inputs", inputs.to_str().unwrap()],
        Some(&joined),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let length = json(&o)["length"].as_f64().unwrap();
    assert!(
        (length - 2.0 * std::f64::consts::PI).abs() < 0.01,
        "{length}"
    );
}
