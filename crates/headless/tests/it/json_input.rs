//! `cnets eval --inputs` reads its JSON as a stream into packed rows (issue 15, "Output size"): the
//! peak memory of a large input stays within about twice the file's size (a `serde_json::Value` tree
//! of the same points took about 4× here, and 7 GB for the 224 MB file), from a file and from
//! stdin alike, and the decoded values are the file's.

use crate::common;

use common::Folder;
use std::io::Write;
use std::process::{Command, Output, Stdio};

/// A polyline of `n` points along a helix, written as the runner's JSON; returns its text.
fn helix_inputs(n: usize) -> (String, f64) {
    let mut text = String::with_capacity(n * 48);
    text.push_str("{\"curve\": {\"points\": [");
    let mut length = 0.0;
    let point = |k: usize| {
        let t = k as f64 * 1e-3;
        [t.cos(), t.sin(), 0.1 * t]
    };
    for k in 0..n {
        let p = point(k);
        if k > 0 {
            text.push(',');
            let q = point(k - 1);
            length +=
                ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        }
        text.push_str(&format!("[{},{},{}]", p[0], p[1], p[2]));
    }
    text.push_str("], \"closed\": false}}");
    (text, length)
}

fn folder(name: &str) -> Folder {
    Folder::new(&format!("json-input-{name}"))
}

/// The `peak memory: <MB> MB` line of `--timing`, in bytes.
fn peak_of(o: &Output) -> Option<f64> {
    let err = String::from_utf8_lossy(&o.stderr);
    let line = err.lines().find(|l| l.starts_with("peak memory: "))?;
    let mb: f64 = line["peak memory: ".len()..]
        .trim_end_matches(" MB")
        .parse()
        .ok()?;
    Some(mb * 1e6)
}

fn length(o: &Output) -> f64 {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    v["length"].as_f64().unwrap()
}

fn eval(inputs: &str, stdin: Option<&str>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_cnets"));
    cmd.args(["eval", "curve.length", "--timing", "--inputs", inputs])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    match stdin {
        None => cmd.output().unwrap(),
        Some(text) => {
            let mut child = cmd.stdin(Stdio::piped()).spawn().unwrap();
            let mut pipe = child.stdin.take().unwrap();
            let text = text.to_owned();
            let writer = std::thread::spawn(move || pipe.write_all(text.as_bytes()));
            let out = child.wait_with_output().unwrap();
            writer.join().unwrap().unwrap();
            out
        }
    }
}

#[test]
fn a_large_json_input_peaks_within_twice_its_size() {
    let d = folder("large");
    let (small, small_length) = helix_inputs(10);
    let (text, expected) = helix_inputs(1_000_000);
    let (small_path, path) = (d.join("small.json"), d.join("large.json"));
    std::fs::write(&small_path, &small).unwrap();
    std::fs::write(&path, &text).unwrap();
    let base = eval(small_path.to_str().unwrap(), None);
    assert!((length(&base) - small_length).abs() < 1e-12);
    let from_file = eval(path.to_str().unwrap(), None);
    let from_stdin = eval("-", Some(&text));
    let size = text.len() as f64;
    for (how, o) in [("file", &from_file), ("stdin", &from_stdin)] {
        let got = length(o);
        assert!(
            (got - expected).abs() <= 1e-9 * expected,
            "{how}: length {got} against {expected}"
        );
        let Some(peak) = peak_of(o) else {
            return; // the system does not report the peak (not Linux)
        };
        println!(
            "{how}: {:.1} MB of JSON (1 000 000 points, 24 MB as f64), peak {:.1} MB (a 10-point input: {:.1} MB)",
            size / 1e6,
            peak / 1e6,
            peak_of(&base).unwrap_or(f64::NAN) / 1e6
        );
        assert!(
            peak <= 2.0 * size,
            "{how}: peak {:.1} MB for {:.1} MB of JSON",
            peak / 1e6,
            size / 1e6
        );
    }
}

#[test]
fn a_syntax_error_in_a_streamed_input_names_its_line_and_column() {
    let d = folder("bad");
    let path = d.join("bad.json");
    std::fs::write(&path, "{\"curve\": [[0, 0, 0],\n [1, 0, x]]}").unwrap();
    let o = eval(path.to_str().unwrap(), None);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("bad.json:2:9: invalid JSON"), "{err}");
    let o = eval("-", Some("{\"curve\": [[0, 0, 0], [1, 0, 0]]} trailing"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("<stdin>:1:35: invalid JSON"), "{err}");
}
