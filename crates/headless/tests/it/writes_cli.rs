//! Issue 27 §4 through the command line: a write replaces only a regular file (or nothing), a
//! live run's temporary file is never taken for a stale one, a signal stops an export mid-file,
//! reads are refused by name before the file system is asked, `cnets run g.ron` reads beside the
//! graph, export names are bounded, and an unwritable stderr or stdout is not a crash.

#![cfg(unix)]

use crate::common;

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn cnets_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn mkfifo(path: &Path) {
    assert!(Command::new("mkfifo").arg(path).status().unwrap().success());
}

fn is_fifo(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_fifo())
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// A graph with a previewed curve (something to render) and a stored optimization.
const GRAPH: &str = r#"(version: 1, nodes: {
    "x": (type: "param.number", inputs: {"value": 0.3, "min": 0.0, "max": 1.0}),
    "c": (type: "curve.circle", inputs: {"count": 8}),
    "q": (type: "math.multiply", inputs: {"b": 1.0}),
}, edges: ["x.value -> q.a"],
optimization: (objective: "q.result", variables: [(input: "x.value", min: 0.0, max: 1.0)]))"#;

#[test]
fn png_and_out_never_replace_a_fifo_a_device_or_a_folder() {
    let d = common::Folder::new("writes-special");
    let g = write(&d, "g.ron", GRAPH);
    let fifo = d.join("picture.png");
    mkfifo(&fifo);
    std::fs::create_dir(d.join("folder.ron")).unwrap();
    let g = g.to_str().unwrap();
    for (args, kind) in [
        (vec!["render", g, "--png", "picture.png"], "a FIFO"),
        (vec!["run", g, "--png", "picture.png"], "a FIFO"),
        (vec!["optimize", g, "--out", "picture.png"], "a FIFO"),
        (vec!["optimize", g, "--out", "folder.ron"], "a folder"),
        (
            vec!["render", g, "--png", "/dev/null"],
            "a character device",
        ),
    ] {
        let o = cnets_in(&d, &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(kind), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("replaces only a regular file"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    assert!(is_fifo(&fifo), "the FIFO is still a FIFO");
    assert!(d.join("folder.ron").is_dir());
    let null = std::fs::metadata("/dev/null").unwrap();
    assert!(null.file_type().is_char_device());
    // A regular file is replaced (optimize needs no GPU).
    let out = write(&d, "optimized.ron", "old");
    let o = cnets_in(&d, &["optimize", g, "--out", "optimized.ron"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .contains("version: 1")
    );
    let leftovers: Vec<_> = std::fs::read_dir(&*d)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

/// A graph exporting a `points`-point circle as OBJ.
fn big_export(d: &Path, points: u32) -> PathBuf {
    write(
        d,
        "big.ron",
        &format!(
            r#"(version: 1, nodes: {{
    "c": (type: "curve.circle", inputs: {{"count": {points}}}),
    "e": (type: "io.export_obj", inputs: {{"name": "big.obj"}}),
}}, edges: ["c.curve -> e.polylines"])"#
        ),
    )
}

fn temp_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir).map_or(Vec::new(), |r| {
        r.flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    })
}

#[test]
fn sigterm_while_an_export_is_written_stops_it_and_leaves_nothing() {
    for signal in ["-TERM", "-HUP", "-INT"] {
        let d = common::Folder::new("writes-signal");
        let out = d.join("out");
        // Three million points: an OBJ of ~120 MB, written for seconds.
        let g = big_export(&d, 3_000_000);
        let child = Command::new(env!("CARGO_BIN_EXE_cnets"))
            .args(["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Wait until the export is being written (its temporary file exists).
        let started = Instant::now();
        while temp_files(&out).is_empty() {
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "no export started"
            );
            std::thread::sleep(Duration::from_millis(2));
        }
        eprintln!("{signal}: the export started after {:?}", started.elapsed());
        let sent = Instant::now();
        assert!(
            Command::new("kill")
                .args([signal, &child.id().to_string()])
                .status()
                .unwrap()
                .success()
        );
        let o = child.wait_with_output().unwrap();
        let waited = sent.elapsed();
        eprintln!("{signal}: signal to exit {waited:?}");
        assert_eq!(o.status.code(), Some(130), "{signal}: {}", stderr(&o));
        assert!(stderr(&o).contains("cancelled"), "{}", stderr(&o));
        assert!(!out.join("big.obj").exists(), "{signal}: a partial export");
        assert!(
            temp_files(&out).is_empty(),
            "{signal}: {:?}",
            temp_files(&out)
        );
        // The promise is a second; 5 s is the margin for a loaded machine.
        assert!(
            waited < Duration::from_secs(5),
            "{signal}: stopped after {waited:?}"
        );
    }
}

#[test]
fn a_live_runs_temporary_file_is_not_removed_by_another_run() {
    let d = common::Folder::new("writes-live");
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // A live writer in another PID namespace looks dead by its pid; here: a temporary file of the
    // scheme, old, whose lock is held (by this test, as the other run would hold it).
    let live = out.join(".big.obj.cnets-tmp-0123456789abcdef.tmp");
    let file = std::fs::File::create(&live).unwrap();
    file.set_modified(std::time::SystemTime::now() - Duration::from_secs(600))
        .unwrap();
    rustix_flock(&file);
    let g = big_export(&d, 16);
    let o = cnets_in(
        &d,
        &["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("big.obj").is_file());
    assert!(live.exists(), "a locked temporary file was removed");
    drop(file);
    // Unlocked now: the next export into the folder removes it.
    let o = cnets_in(
        &d,
        &["run", g.to_str().unwrap(), "--out", out.to_str().unwrap()],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!live.exists());
}

/// Takes an exclusive `flock` on `file`, as a writing run holds it on its temporary file.
fn rustix_flock(file: &std::fs::File) {
    rustix::fs::flock(file, rustix::fs::FlockOperation::NonBlockingLockExclusive)
        .expect("the lock is free");
}

/// A graph reading `path` as CSV polylines.
fn read_graph(d: &Path, path: &str) -> PathBuf {
    write(
        d,
        "read.ron",
        &format!(
            r#"(version: 1, nodes: {{ "r": (type: "io.read_polylines", inputs: {{"path": "{path}", "format": "csv"}}) }}, edges: [])"#
        ),
    )
}

#[test]
fn a_graph_cannot_probe_which_files_exist_outside_its_folders() {
    let d = common::Folder::new("writes-probe");
    let graph = d.join("graph");
    std::fs::create_dir(&graph).unwrap();
    std::fs::write(d.join("there.csv"), "0,0,0\n1,1,1\n").unwrap();
    let mut said = Vec::new();
    for name in ["../there.csv", "../missing.csv"] {
        let g = read_graph(&graph, name);
        let o = cnets_in(&d, &["run", g.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let err = stderr(&o);
        assert!(
            err.contains("outside the folders reads are allowed in"),
            "{err}"
        );
        assert!(!err.contains("No such file"), "{err}");
        said.push(err.replace(name, "NAME"));
    }
    assert_eq!(
        said[0], said[1],
        "the same answer whether the file exists or not"
    );
}

#[test]
fn run_from_the_graphs_own_folder_reads_beside_it() {
    let d = common::Folder::new("writes-here");
    std::fs::write(d.join("in.csv"), "0,0,0\n1,0,0\n2,0,0\n").unwrap();
    read_graph(&d, "in.csv");
    let o = cnets_in(&d, &["run", "read.ron", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("[2.0,0.0,0.0]"));
}

#[test]
fn an_export_name_of_thirty_thousand_folders_creates_none() {
    let d = common::Folder::new("writes-deep");
    let name = vec!["d"; 30_000].join("/");
    let g = write(
        &d,
        "deep.ron",
        &format!(
            r#"(version: 1, nodes: {{
    "l": (type: "curve.line"),
    "e": (type: "io.export_json", inputs: {{"name": "{name}"}}),
}}, edges: ["l.curve -> e.value"])"#
        ),
    );
    let o = cnets_in(&d, &["run", g.to_str().unwrap(), "--out", "out"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("more than 16 folders"),
        "{}",
        stderr(&o)
    );
    assert!(
        stderr(&o).len() < 1000,
        "the name is quoted short: {}",
        stderr(&o)
    );
    let created = std::fs::read_dir(d.join("out")).map_or(0, |r| r.count());
    assert_eq!(created, 0);
}

#[test]
fn out_naming_a_file_says_so() {
    let d = common::Folder::new("writes-out-file");
    write(&d, "out", "a file");
    let g = big_export(&d, 8);
    let o = cnets_in(&d, &["run", g.to_str().unwrap(), "--out", "out"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("a file of that name is in the way"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn an_unwritable_stderr_or_stdout_is_an_exit_code_not_a_panic() {
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    // An error while stderr is full: the exit code still says it (no panic, no 101).
    let o = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["check", "/nonexistent/g.ron"])
        .stderr(full())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let o = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .args(["eval", "no.such.node", "--inputs", "-"])
        .stdin(Stdio::null())
        .stderr(full())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    // Help on a full stdout: the failed write is reported, not exit 0.
    for args in [&["--help"][..], &["run", "--help"], &["--version"]] {
        let o = Command::new(env!("CARGO_BIN_EXE_cnets"))
            .args(args)
            .stdout(full())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&o).starts_with("error: cannot write the output"),
            "{}",
            stderr(&o)
        );
    }
    // And on a good stdout, help is printed with success.
    let o = Command::new(env!("CARGO_BIN_EXE_cnets"))
        .arg("--help")
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("Usage"));
}
