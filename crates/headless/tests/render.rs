//! `cnets render` draws the previewed geometry off-screen: the picture is not blank and matches its
//! committed snapshot within a tolerance (set `UPDATE_SNAPSHOTS=1` to rewrite the snapshot after an
//! intended change, then look at it). Runs on the software Vulkan driver in CI.

use std::path::{Path, PathBuf};
use std::process::Command;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba, "{}", path.display());
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

fn render(args: &[&str]) -> std::process::Output {
    let runtime = std::env::temp_dir().join(format!("cnets-xdg-{}", std::process::id()));
    let _ = std::fs::create_dir_all(&runtime);
    Command::new(env!("CARGO_BIN_EXE_cnets"))
        .arg("render")
        .args(args)
        .current_dir(workspace())
        .env("XDG_RUNTIME_DIR", &runtime)
        .output()
        .unwrap()
}

#[test]
fn torus_render_is_not_blank_and_matches_its_snapshot() {
    let out = std::env::temp_dir().join(format!("cnets-render-{}.png", std::process::id()));
    let o = render(&[
        "graphs/torus-monge.ron",
        "--png",
        out.to_str().unwrap(),
        "--size",
        "480x270",
        "--hide",
        "apices",
    ]);
    assert!(
        o.status.success(),
        "cnets render failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains("480x270"));
    let (w, h, pixels) = read_png(&out);
    assert_eq!((w, h), (480, 270));
    let background = [pixels[0], pixels[1], pixels[2]];
    let covered = pixels.chunks(4).filter(|p| p[..3] != background).count();
    let fraction = covered as f64 / (w * h) as f64;
    assert!(
        fraction > 0.04,
        "the picture is nearly blank ({:.1} % covered)",
        100.0 * fraction
    );

    let snapshot = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/torus-monge.png");
    if std::env::var_os("UPDATE_SNAPSHOTS").is_some() || !snapshot.exists() {
        std::fs::copy(&out, &snapshot).unwrap();
    }
    let (sw, sh, expected) = read_png(&snapshot);
    assert_eq!((sw, sh), (w, h));
    let differing = pixels
        .chunks(4)
        .zip(expected.chunks(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 16))
        .count();
    let _ = std::fs::remove_file(&out);
    assert!(
        differing <= (w * h) as usize / 100,
        "{differing} pixels differ from {} (more than 1 %)",
        snapshot.display()
    );
}

#[test]
fn bad_arguments_are_usage_errors() {
    for args in [
        &[
            "graphs/torus-monge.ron",
            "--png",
            "/tmp/x.png",
            "--size",
            "big",
        ][..],
        &[
            "graphs/torus-monge.ron",
            "--png",
            "/tmp/x.png",
            "--view",
            "below",
        ][..],
        &[
            "graphs/torus-monge.ron",
            "--png",
            "/tmp/x.png",
            "--hide",
            "everything",
        ][..],
        &[
            "graphs/torus-monge.ron",
            "--png",
            "/tmp/x.png",
            "--color",
            "rainbow",
        ][..],
    ] {
        let o = render(args);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}
