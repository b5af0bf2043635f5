//! Files only where they belong, through the command line: exports never leave `--out`, reads stay
//! under the graph's folder and `--allow-read` folders, temporary files clean up, a closed or full
//! stdout is not a crash.

#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn cnets(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .output()
        .unwrap()
}

fn folder(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("cnets-files-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn export_graph(d: &Path, name: &str) -> PathBuf {
    let g = d.join(format!("export-{}.ron", name.len()));
    let name = name
        .replace('\\', "\\\\")
        .replace('\n', "\\n")
        .replace('"', "\\\"");
    std::fs::write(
        &g,
        format!(
            r#"(version: 1, nodes: {{
    "l": (type: "curve.line"),
    "e": (type: "io.export_json", inputs: {{"name": "{name}"}}),
}}, edges: ["l.curve -> e.value"])"#
        ),
    )
    .unwrap();
    g
}

#[test]
fn exports_do_not_follow_links_out_of_the_output_directory() {
    let d = folder("link");
    let (out, elsewhere) = (d.join("out"), d.join("elsewhere"));
    std::fs::create_dir_all(&out).unwrap();
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::os::unix::fs::symlink(&elsewhere, out.join("link")).unwrap();
    let g = export_graph(&d, "link/escaped.obj");
    let o = cnets(&["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("is a symbolic link"), "{}", stderr(&o));
    assert_eq!(std::fs::read_dir(&elsewhere).unwrap().count(), 0);
}

#[test]
fn bad_export_names_are_refused_by_name() {
    let d = folder("names");
    let out = d.join("out");
    for (name, why) in [
        (".", "may not contain '.' or '..'"),
        ("..", "may not contain '.' or '..'"),
        ("", "is empty"),
        ("a\nb", "contains a control character"),
        ("sub//x", "empty folder or file name"),
    ] {
        let g = export_graph(&d, name);
        let o = cnets(&["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{name:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(why), "{name:?}: {}", stderr(&o));
    }
    let files: Vec<_> = std::fs::read_dir(&out).map_or(Vec::new(), |r| r.flatten().collect());
    assert!(files.is_empty(), "{files:?}");
}

#[test]
fn an_export_removes_only_abandoned_temporary_files_of_its_own_scheme() {
    let d = folder("stale");
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let old = std::time::SystemTime::now() - Duration::from_secs(120);
    let aged = |p: &Path| {
        std::fs::File::options()
            .write(true)
            .open(p)
            .unwrap()
            .set_modified(old)
            .unwrap()
    };
    // Ours, abandoned (killed mid-write): the marker, no lock, two minutes old.
    let stale = out.join(".data.json.cnets-tmp-00112233aabbccdd.tmp");
    std::fs::write(&stale, vec![0u8; 1 << 16]).unwrap();
    aged(&stale);
    // A user's file of the old shape (a pid that is not running here): not ours to delete.
    let users = out.join(".data.json.4000000000.0.tmp");
    std::fs::write(&users, b"mine").unwrap();
    aged(&users);
    let g = export_graph(&d, "data");
    let o = cnets(&["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("data.json").is_file());
    assert!(
        !stale.exists(),
        "the abandoned temporary file is still there"
    );
    assert_eq!(std::fs::read(&users).unwrap(), b"mine");
}

fn read_graph(d: &Path, path: &str) -> PathBuf {
    let g = d.join("read.ron");
    std::fs::write(
        &g,
        format!(
            r#"(version: 1, nodes: {{ "r": (type: "io.read_polylines", inputs: {{"path": "{path}", "format": "csv"}}) }}, edges: [])"#
        ),
    )
    .unwrap();
    g
}

#[test]
fn reads_outside_the_graph_folder_devices_and_fifos_are_refused() {
    let d = folder("reads");
    let g = read_graph(&d, "/etc/passwd");
    let start = Instant::now();
    let o = cnets(&["run", g.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("outside the folders reads are allowed in"),
        "{}",
        stderr(&o)
    );
    assert!(!stderr(&o).contains("root:"), "{}", stderr(&o));

    // Allowed, the CSV error quotes a short excerpt, not the line.
    let o = cnets(&["run", g.to_str().unwrap(), "--allow-read", "/etc"]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.lines().all(|l| l.len() < 300), "{err}");

    let g = read_graph(&d, "/dev/zero");
    let o = cnets(&["run", g.to_str().unwrap(), "--allow-read", "/dev"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));

    assert!(
        Command::new("mkfifo")
            .arg(d.join("fifo"))
            .status()
            .unwrap()
            .success()
    );
    let g = read_graph(&d, "fifo");
    let o = cnets(&["run", g.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("not a regular file"), "{}", stderr(&o));
    eprintln!("four refused reads: {:?}", start.elapsed());
    assert!(start.elapsed() < Duration::from_secs(30));
}

#[test]
fn a_cluster_file_outside_the_allowed_folders_is_refused() {
    let d = folder("cluster-read");
    let lib = folder("cluster-read-elsewhere");
    std::fs::write(
        lib.join("c.ron"),
        r#"(version: 1, nodes: {
    "x": (type: "graph.input", inputs: {"name": "x", "type": "number"}),
    "y": (type: "graph.output", inputs: {"name": "y", "type": "number"}),
}, edges: ["x.value -> y.value"])"#,
    )
    .unwrap();
    let g = d.join("top.ron");
    std::fs::write(
        &g,
        format!(
            r#"(version: 1, nodes: {{ "c": (type: "cluster", source: "{}") }}, edges: [])"#,
            lib.join("c.ron").display()
        ),
    )
    .unwrap();
    let o = cnets(&["check", g.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("outside the folders reads are allowed in"),
        "{}",
        stderr(&o)
    );
    let o = cnets(&[
        "check",
        g.to_str().unwrap(),
        "--allow-read",
        lib.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// Issue 27 §4: a cluster source outside the allowed folders is refused by its name, in the same
/// words whether the file is there or not (it used to say "not found" for a missing one).
#[test]
fn a_cluster_source_outside_says_the_same_whether_or_not_it_exists() {
    let d = folder("cluster-probe");
    let lib = folder("cluster-probe-elsewhere");
    std::fs::write(lib.join("there.ron"), "(version: 1, nodes: {}, edges: [])").unwrap();
    let mut said = Vec::new();
    for name in ["there.ron", "gone.ron"] {
        let g = d.join("top.ron");
        std::fs::write(
            &g,
            format!(
                r#"(version: 1, nodes: {{ "c": (type: "cluster", source: "{}") }}, edges: [])"#,
                lib.join(name).display()
            ),
        )
        .unwrap();
        let o = cnets(&["check", g.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let err = stderr(&o);
        assert!(
            err.contains("outside the folders reads are allowed in"),
            "{err}"
        );
        assert!(!err.contains("not found"), "{err}");
        said.push(err.replace(name, "NAME"));
    }
    assert_eq!(said[0], said[1]);
}

#[test]
fn a_closed_stdout_ends_quietly_and_a_full_disk_is_one_line() {
    let mut child = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["nodes"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));

    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["nodes"])
        .stdout(full)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: cannot write the output:"), "{err}");
}

#[test]
fn sigint_cancels_a_run_within_a_second_and_leaves_no_partial_file() {
    let d = folder("sigint");
    let out = d.join("out");
    // A long evaluation: a series mapped through many items, then an export.
    let g = d.join("long.ron");
    std::fs::write(
        &g,
        r#"(version: 1, nodes: {
    "s": (type: "param.series", inputs: {"count": 3000000}),
    "m": (type: "math.multiply", inputs: {"b": 2.0}),
    "n": (type: "math.multiply", inputs: {"b": 3.0}),
    "e": (type: "io.export_json", inputs: {"name": "big"}),
}, edges: ["s.values -> m.a", "m.result -> n.a", "n.result -> e.value"])"#,
    )
    .unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Signal once the run is well into its work (its handler is installed at start-up): after
    // 300 ms of its processor time, not after a fixed wait a busy machine may spend starting it.
    let started = Instant::now();
    while cpu_time(child.id()) < Duration::from_millis(300) {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "the run never got going"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    let sent = Instant::now();
    assert!(
        Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status()
            .unwrap()
            .success()
    );
    let o = child.wait_with_output().unwrap();
    let waited = sent.elapsed();
    eprintln!("SIGINT to exit: {waited:?}");
    // The run takes seconds (3 million mapped items, then a 60 MB JSON export): it is cancelled.
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("cancelled"), "{}", stderr(&o));
    // The promise is a second (the handler's grace is 0.8 s); 5 s is the margin for a loaded
    // machine, as for the signals during an export (writes_cli.rs).
    assert!(waited < Duration::from_secs(5), "stopped after {waited:?}");
    let leftovers: Vec<_> = std::fs::read_dir(&out).map_or(Vec::new(), |r| {
        r.flatten()
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect()
    });
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// The processor time (user + system) a running process has used so far, from /proc; zero once it
/// has exited.
fn cpu_time(pid: u32) -> Duration {
    let Ok(stat) = std::fs::read_to_string(format!("/proc/{pid}/stat")) else {
        return Duration::ZERO;
    };
    // Fields after the command name (which may hold spaces) start at ") ".
    let fields: Vec<&str> = stat
        .rsplit_once(") ")
        .map_or(Vec::new(), |(_, rest)| rest.split(' ').collect());
    // utime and stime are fields 14 and 15 of the whole line: 12 and 13 after the name.
    let ticks: u64 = [11, 12]
        .iter()
        .filter_map(|&k| fields.get(k).and_then(|f| f.parse::<u64>().ok()))
        .sum();
    Duration::from_millis(ticks * 10)
}
