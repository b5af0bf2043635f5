//! Bundles the gallery: every file under `graphs/` (the `.ron` graphs and the files they import)
//! becomes an `include_bytes!` entry of `$OUT_DIR/bundle.rs`, so a graph added there is on the
//! page without editing this crate.

use std::path::{Path, PathBuf};

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, out);
        } else if p.is_file() {
            out.push(p);
        }
    }
}

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let graphs = manifest.join("../../graphs");
    let graphs = graphs.canonicalize().unwrap_or(graphs);
    println!("cargo:rerun-if-changed={}", graphs.display());
    let mut files = Vec::new();
    walk(&graphs, &mut files);
    files.sort();
    let mut code = String::from("/// Every file of `graphs/`: (path relative to it, bytes).\n");
    code.push_str("pub const FILES: &[(&str, &[u8])] = &[\n");
    for f in &files {
        println!("cargo:rerun-if-changed={}", f.display());
        let rel = f.strip_prefix(&graphs).unwrap_or(f);
        let rel = rel.to_string_lossy().replace('\\', "/");
        code.push_str(&format!(
            "    ({rel:?}, include_bytes!({:?})),\n",
            f.display().to_string()
        ));
    }
    code.push_str("];\n");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets it")).join("bundle.rs");
    std::fs::write(out, code).expect("OUT_DIR is writable");
}
