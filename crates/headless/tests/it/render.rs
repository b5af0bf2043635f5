//! `cnets render` draws the previewed geometry off-screen: the picture is not blank and matches its
//! committed snapshot within a tolerance (set `UPDATE_SNAPSHOTS=1` to rewrite the snapshot after an
//! intended change, then look at it). A missing snapshot fails the test: no test records its own
//! expectation. Runs on the software Vulkan driver in CI.

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
    let line = String::from_utf8_lossy(&o.stdout);
    assert!(line.contains("480x270"), "{line}");
    // The summary leads with the cone-nets' figures and names the mesh of each.
    let headline = line.lines().nth(1).unwrap_or_default();
    assert!(
        headline.contains("max planarity") && headline.contains("headline: the cone-nets"),
        "{line}"
    );
    assert!(
        line.lines()
            .nth(2)
            .unwrap_or_default()
            .trim_start()
            .starts_with("cone-net "),
        "{line}"
    );
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
    let verdict = match_snapshot(&out, &snapshot, update_requested());
    let _ = std::fs::remove_file(&out);
    if let Err(message) = verdict {
        panic!("{message}");
    }
}

/// The command that re-records the snapshots of this file (then look at them before committing).
const RECORD: &str = "UPDATE_SNAPSHOTS=1 cargo test -p cnets --test it render::";

/// Whether `UPDATE_SNAPSHOTS` asks to rewrite snapshots (`1`, `true`, `yes`, `on`, `force`).
fn update_requested() -> bool {
    std::env::var("UPDATE_SNAPSHOTS").is_ok_and(|v| {
        matches!(
            v.to_ascii_lowercase().as_str(),
            "1" | "true" | "yes" | "on" | "force"
        )
    })
}

/// Compares the picture at `actual` with the committed `snapshot`: the same size, at most 1 % of
/// the pixels off by more than 16 in a channel. With `update` the snapshot is rewritten first; a
/// missing snapshot is an error naming the command that records it, never re-created here.
fn match_snapshot(actual: &Path, snapshot: &Path, update: bool) -> Result<(), String> {
    if update {
        std::fs::copy(actual, snapshot)
            .map_err(|e| format!("cannot write {}: {e}", snapshot.display()))?;
    }
    if !snapshot.is_file() {
        return Err(format!(
            "no snapshot at {}: record it with `{RECORD}` and look at it before committing",
            snapshot.display()
        ));
    }
    let (w, h, pixels) = read_png(actual);
    let (sw, sh, expected) = read_png(snapshot);
    if (sw, sh) != (w, h) {
        return Err(format!(
            "the picture is {w}x{h}, its snapshot {} is {sw}x{sh} (re-record with `{RECORD}`)",
            snapshot.display()
        ));
    }
    let differing = pixels
        .chunks(4)
        .zip(expected.chunks(4))
        .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 16))
        .count();
    if differing > (w * h) as usize / 100 {
        return Err(format!(
            "{differing} pixels differ from {} (more than 1 %; after an intended change re-record \
             with `{RECORD}`)",
            snapshot.display()
        ));
    }
    Ok(())
}

#[test]
fn a_missing_snapshot_fails_and_is_not_written() {
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/torus-monge.png");
    let missing = std::env::temp_dir().join(format!(
        "cnets-missing-snapshot-{}/torus-monge.png",
        std::process::id()
    ));
    let err = match_snapshot(&committed, &missing, false).unwrap_err();
    assert!(err.contains("no snapshot at"), "{err}");
    assert!(err.contains(RECORD), "{err}");
    assert!(!missing.exists(), "the test wrote its own expectation");
    // A snapshot compared with itself matches: the comparison above failed for the missing file only.
    assert_eq!(match_snapshot(&committed, &committed, false), Ok(()));
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

/// Pixels within 12 of `color` in each channel, inside the rectangle `x0..x1 × y0..y1`.
fn count_near(
    (w, _h, pixels): &(u32, u32, Vec<u8>),
    color: [u8; 3],
    (x0, y0, x1, y1): (u32, u32, u32, u32),
) -> usize {
    (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let k = ((y * w + x) * 4) as usize;
            pixels[k..k + 3]
                .iter()
                .zip(color)
                .all(|(a, b)| a.abs_diff(b) <= 12)
        })
        .count()
}

#[test]
fn pictures_carry_their_legend_and_apices_only_when_asked() {
    let dir = std::env::temp_dir().join(format!("cnets-render-legend-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let shot = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let mut args = vec![
            "graphs/torus-monge.ron",
            "--png",
            out.to_str().unwrap(),
            "--size",
            "800x450",
        ];
        args.extend_from_slice(extra);
        let o = render(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        if let Some(keep) = std::env::var_os("CNETS_KEEP_RENDERS") {
            let _ = std::fs::copy(&out, Path::new(&keep).join(name));
        }
        read_png(&out)
    };
    let top_right = (560, 0, 800, 160);
    let whole = (0, 0, 800, 450);
    let [cr, cg, cb, _] =
        cnets_preview::class_color(cnets_geometry::fabrication::FaceClass::Convex).0;
    let [ar, ag, ab, _] = cnets_preview::APEX_COLOR.0;
    // Default: the class legend top right (its convex swatch), no apices anywhere.
    let plain = shot("classes.png", &[]);
    assert!(
        count_near(&plain, [cr, cg, cb], top_right) > 60,
        "the convex swatch"
    );
    assert_eq!(
        count_near(&plain, [ar, ag, ab], whole),
        0,
        "apices hidden by default"
    );
    // --apices: the points are drawn, and explained in the legend (their dot, below the classes).
    let apices = shot("apices.png", &["--apices"]);
    let in_legend = count_near(&apices, [ar, ag, ab], top_right);
    let everywhere = count_near(&apices, [ar, ag, ab], whole);
    assert!(in_legend > 20, "the legend's apex dot: {in_legend}");
    assert!(everywhere > in_legend + 100, "apices drawn: {everywhere}");
    // Planarity with a user-set limit: the scale's swatches in the legend.
    let planarity = shot(
        "planarity.png",
        &["--color", "planarity", "--planarity-limit", "1e-4"],
    );
    let planar = cnets_render::ToleranceMap::DEFAULT.color(0.0).0;
    assert!(
        count_near(&planarity, [planar[0], planar[1], planar[2]], top_right) > 60,
        "the planar swatch"
    );
    let bad = render(&[
        "graphs/torus-monge.ron",
        "--png",
        dir.join("x.png").to_str().unwrap(),
        "--planarity-limit",
        "2",
    ]);
    assert_eq!(
        bad.status.code(),
        Some(2),
        "a limit above 1 is a usage error"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn planarity_colours_every_previewed_mesh_and_names_the_mesh_of_its_figure() {
    // The catamaran hull with its reference (an imported OBJ of non-planar quads) previewed: both
    // are polygon meshes (the hull cut and mirrored). Before issue 32 they stayed grey in the
    // planarity mode and the figure was the planar cone-net's.
    let dir = std::env::temp_dir().join(format!("cnets-render-poly-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("reference")).unwrap();
    let graphs = workspace().join("graphs");
    std::fs::copy(
        graphs.join("reference/catamaran-hull.obj"),
        dir.join("reference/catamaran-hull.obj"),
    )
    .unwrap();
    let text = std::fs::read_to_string(graphs.join("catamaran-hull.ron")).unwrap();
    let at = text.find("\"reference_hull\": (").unwrap();
    let hidden = at + text[at..].find("preview: false,").unwrap();
    let text = format!(
        "{}{}",
        &text[..hidden],
        &text[hidden + "preview: false,".len()..]
    );
    std::fs::write(dir.join("hull.ron"), text).unwrap();
    let shot = |name: &str, color: &str| {
        let out = dir.join(name);
        let o = render(&[
            dir.join("hull.ron").to_str().unwrap(),
            "--png",
            out.to_str().unwrap(),
            "--size",
            "800x450",
            "--color",
            color,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        if let Some(keep) = std::env::var_os("CNETS_KEEP_RENDERS") {
            let _ = std::fs::copy(&out, Path::new(&keep).join(name));
        }
        (
            String::from_utf8_lossy(&o.stdout).into_owned(),
            read_png(&out),
        )
    };
    // Green to yellow (the not-planar end of the scale): g well above b. The surface's plain grey
    // blue and the planar purple never are.
    let greenish = |(w, h, pixels): &(u32, u32, Vec<u8>)| {
        pixels
            .chunks_exact(4)
            .filter(|p| p[1] as i32 > p[2] as i32 + 40)
            .count() as f64
            / (w * h) as f64
    };
    let (line, planarity) = shot("planarity.png", "planarity");
    // No cone-net previewed (the construction is cut and mirrored): the meshes lead, named.
    assert!(
        line.contains("max planarity")
            && line.contains("(reference_hull.mesh; headline: the meshes"),
        "{line}"
    );
    assert!(line.contains("mesh whole.mesh: "), "{line}");
    // Measured against the hull, the reference is no longer in the headline: the net's is.
    let (line, _) = shot("distance.png", "distance:reference_hull");
    let headline = line.lines().nth(1).unwrap();
    assert!(
        headline.contains("(whole.mesh; headline: the meshes"),
        "{line}"
    );
    assert!(
        line.contains("reference reference_hull.mesh: ")
            && line.contains("not in the net's figures"),
        "{line}"
    );
    let (_, plain) = shot("plain.png", "plain");
    assert!(greenish(&planarity) > 0.05, "{}", greenish(&planarity));
    assert!(greenish(&plain) < 0.001, "{}", greenish(&plain));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn distance_colours_the_net_by_its_distance_to_the_reference() {
    // The catamaran hull fitted to its reference (not previewed): `--color distance:NODE`.
    let dir = std::env::temp_dir().join(format!("cnets-render-dist-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let graph = workspace().join("graphs/catamaran-hull.ron");
    let shot = |name: &str, color: &str| {
        let out = dir.join(name);
        let o = render(&[
            graph.to_str().unwrap(),
            "--png",
            out.to_str().unwrap(),
            "--size",
            "800x450",
            "--color",
            color,
        ]);
        (o, out)
    };
    let (o, out) = shot("distance.png", "distance:reference_hull");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let line = String::from_utf8_lossy(&o.stdout).into_owned();
    // "  distance whole.mesh ↔ reference_hull (symmetric, area-weighted): rms 0.00520 m max
    // 0.0940 m; net → reference rms … max …; reference → net rms … max …"
    let figure = |line: &str, key: &str| -> f64 {
        let at = line.find(key).unwrap_or_else(|| panic!("{key} in {line}")) + key.len();
        line[at..]
            .split(" m")
            .next()
            .unwrap()
            .trim()
            .parse()
            .unwrap()
    };
    assert!(
        line.contains("distance whole.mesh ↔ reference_hull (symmetric, area-weighted)"),
        "{line}"
    );
    let (rms, max) = (
        figure(&line, "area-weighted): rms "),
        figure(&line, " m max "),
    );
    assert!(0.0 < rms && rms < max && max < 1.0, "{line}");
    let (net_max, reference_max) = (
        figure(&line, "net → reference rms "),
        figure(&line, "reference → net rms "),
    );
    assert!(net_max > 0.0 && reference_max > 0.0, "{line}");
    assert!(
        line.contains("colours: the net's vertices by their distance to reference_hull"),
        "{line}"
    );
    if let Some(keep) = std::env::var_os("CNETS_KEEP_RENDERS") {
        let _ = std::fs::copy(&out, Path::new(&keep).join("distance.png"));
    }
    // Viridis from purple (near) to yellow (far): both ends show; the plain picture has neither.
    let share = |(w, h, pixels): &(u32, u32, Vec<u8>), f: &dyn Fn(&[u8]) -> bool| {
        pixels.chunks_exact(4).filter(|p| f(p)).count() as f64 / (w * h) as f64
    };
    let greenish = |p: &[u8]| p[1] as i32 > p[2] as i32 + 40;
    let purple = |p: &[u8]| p[2] as i32 > p[1] as i32 + 40 && p[0] as i32 > p[1] as i32 + 20;
    let picture = read_png(&out);
    assert!(
        share(&picture, &greenish) > 0.002,
        "{}",
        share(&picture, &greenish)
    );
    assert!(
        share(&picture, &purple) > 0.01,
        "{}",
        share(&picture, &purple)
    );
    let (o, plain) = shot("plain.png", "plain");
    assert!(o.status.success());
    let plain = read_png(&plain);
    assert!(share(&plain, &greenish) < 0.001 && share(&plain, &purple) < 0.001);
    // The other side: the reference (not previewed) drawn and coloured by its distance to the
    // net, the same symmetric figure; the summary says which side the colours show.
    let (o, out) = shot(
        "distance-reference.png",
        "distance-reference:reference_hull",
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let other = String::from_utf8_lossy(&o.stdout).into_owned();
    assert_eq!(
        figure(&other, "area-weighted): rms "),
        rms,
        "the same figure: {other}"
    );
    assert!(
        other.contains("colours: reference_hull's vertices by their distance to the net"),
        "{other}"
    );
    assert!(other.contains("reference reference_hull.mesh: "), "{other}");
    if let Some(keep) = std::env::var_os("CNETS_KEEP_RENDERS") {
        let _ = std::fs::copy(&out, Path::new(&keep).join("distance-reference.png"));
    }
    // Both ends of the scale on the reference: near the net (purple) and far (green to yellow).
    let picture = read_png(&out);
    assert!(
        share(&picture, &purple) > 0.003 && share(&picture, &greenish) > 0.05,
        "{} {}",
        share(&picture, &purple),
        share(&picture, &greenish)
    );
    // A reference that is not in the graph is a usage error naming it, in either spelling.
    for spelling in ["distance", "distance-reference"] {
        let (o, _) = shot("none.png", &format!("{spelling}:no_such_node"));
        assert_eq!(o.status.code(), Some(2));
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(&format!(
                "--color {spelling}:no_such_node: the graph has no node"
            )),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // The net itself as the reference: nothing else to measure, and the summary says so.
    let (o, _) = shot("self.png", "distance:whole");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let line = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        line.contains("no distance measured: nothing else is previewed to measure against 'whole'"),
        "{line}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The bounding box `(x0, y0, x1, y1)` of the pixels that are not the background (the first
/// pixel's colour), leaving out the legend (the box of its white panel's pixels in the top-right quarter).
fn drawn_box((w, h, pixels): &(u32, u32, Vec<u8>)) -> (u32, u32, u32, u32) {
    let at = |x: u32, y: u32| {
        let k = ((y * w + x) * 4) as usize;
        [pixels[k], pixels[k + 1], pixels[k + 2]]
    };
    let background = at(0, 0);
    let (mut legend, mut drawn) = ((u32::MAX, u32::MAX, 0, 0), (u32::MAX, u32::MAX, 0, 0));
    let grow = |b: &mut (u32, u32, u32, u32), x: u32, y: u32| {
        *b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
    };
    for y in 0..*h {
        for x in 0..*w {
            if x > w / 2 && y < h / 4 && at(x, y).iter().all(|&c| c >= 250) {
                grow(&mut legend, x, y);
            }
        }
    }
    for y in 0..*h {
        for x in 0..*w {
            let in_legend =
                (legend.0..=legend.2).contains(&x) && (legend.1..=legend.3).contains(&y);
            let differs: u32 = at(x, y)
                .iter()
                .zip(background)
                .map(|(a, b)| u32::from(a.abs_diff(b)))
                .sum();
            if !in_legend && differs > 30 {
                grow(&mut drawn, x, y);
            }
        }
    }
    drawn
}

/// `--view side` frames the object centred. The pedestrian bridge is 30 m long and a few metres
/// wide: seen from its end in perspective its near end is far larger than its far end, and the
/// picture was framed with the bridge in the right half (its box's centre at x 960 of 1280).
#[test]
fn the_side_view_frames_the_object_centred() {
    let dir = std::env::temp_dir().join(format!("cnets-render-side-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for graph in ["graphs/pedestrian-bridge.ron", "graphs/torus-monge.ron"] {
        let out = dir.join("side.png");
        let o = render(&[
            graph,
            "--png",
            out.to_str().unwrap(),
            "--size",
            "1280x720",
            "--view",
            "side",
            // The surfaces are what is framed (curves and markers may reach far beyond them).
            "--hide",
            "curves",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let image = read_png(&out);
        let (x0, y0, x1, y1) = drawn_box(&image);
        assert!(x0 < x1 && y0 < y1, "{graph}: something is drawn");
        let centre = ((x0 + x1) as f64 / 2.0, (y0 + y1) as f64 / 2.0);
        println!("{graph}: drawn box x {x0}..{x1}, y {y0}..{y1}, centre {centre:?} of (640, 360)");
        // Centred to 2 % of the picture's size (a pixel's rounding and the edges' width).
        assert!(
            (centre.0 - 640.0).abs() < 0.02 * 1280.0 && (centre.1 - 360.0).abs() < 0.02 * 720.0,
            "{graph}: the drawn box x {x0}..{x1}, y {y0}..{y1} is off-centre"
        );
        // Framed: the object spans most of the picture one way.
        assert!(
            (x1 - x0) as f64 > 0.7 * 1280.0 || (y1 - y0) as f64 > 0.7 * 720.0,
            "{graph}: the drawn box x {x0}..{x1}, y {y0}..{y1} is small"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
