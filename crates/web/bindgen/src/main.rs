//! `cnets-web-bindgen INPUT.wasm OUT_DIR`: writes the web page's JavaScript glue and its processed
//! module into `OUT_DIR`, as `wasm-bindgen INPUT.wasm --out-dir OUT_DIR --target web
//! --no-typescript` does (scripts/web.sh). The library is the one the `wasm-bindgen` command runs,
//! at the version Cargo.lock pins, so the site needs no `cargo install`.

use std::path::PathBuf;

use anyhow::{Context, bail};
use wasm_bindgen_cli_support::Bindgen;

fn main() -> anyhow::Result<()> {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [input, out_dir] = args.as_slice() else {
        bail!("usage: cnets-web-bindgen INPUT.wasm OUT_DIR");
    };
    Bindgen::new()
        .input_path(input)
        .web(true)?
        .typescript(false)
        .demangle(true)
        .omit_default_module_path(false)
        .generate(out_dir)
        .with_context(|| format!("wasm-bindgen on {}", input.display()))
}
