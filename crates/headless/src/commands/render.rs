//! `cnets render <GRAPH.ron> --png <FILE> [--size WxH] [--view iso|top|front|side] [--color …]
//! [--apices] [--planarity-limit X]`: the picture carries its legend (the face classes in words
//! and the paper's notation, the planarity scale or the distance scale; the apices when shown).
//! The summary names the mesh of every figure: the previewed cone-nets first, a distance
//! reference apart (never in the net's planarity), and in the distance modes the symmetric,
//! area-weighted distance between the net and the reference (the fit objective's measure).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use cnets_engine::{Evaluator, Graph, NodeFlag};
use cnets_preview::{
    APEX_COLOR, APEX_LEGEND, ColorMode, DistanceSide, Layer, MeshKind, PreviewOptions,
    PreviewStats, build_scene, legend_rows,
};
use cnets_render::{Camera, Image, LegendBlock, Offscreen, View, draw_legend};

use crate::failure::{CommandResult, Failure};
use crate::session::SessionArgs;

/// Arguments of `cnets render`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The graph file.
    graph: PathBuf,
    /// The PNG file to write (atomically).
    #[arg(long)]
    png: PathBuf,
    /// Image size in pixels, `WIDTHxHEIGHT`.
    #[arg(long, default_value = "1280x720")]
    size: String,
    /// Camera direction: iso, top, front or side.
    #[arg(long, default_value = "iso")]
    view: String,
    /// Face colours: config (face class from the construction's configurations), planarity, plain,
    /// distance:NODE (each vertex of the net — every other previewed mesh — by its distance to
    /// NODE's mesh) or distance-reference:NODE (each vertex of NODE's mesh, drawn even when not
    /// previewed, by its distance to the net, the net translucent over it: shows where the
    /// reference is far from the net). Legend in metres; the summary gives the symmetric distance.
    #[arg(long, default_value = "config")]
    color: String,
    /// Hide a layer: surfaces, edges, curves, apices, axes, supports or points (repeatable).
    #[arg(long, value_name = "LAYER")]
    hide: Vec<String>,
    /// Draw the cones' apices (hidden unless asked; explained in the legend when drawn).
    #[arg(long)]
    apices: bool,
    /// The top of the planarity colour scale (`--color planarity`): faces from this relative
    /// planarity up are "not planar" (default 1e-3; planar below 1e-9 stays the anchor).
    #[arg(long, value_name = "X")]
    planarity_limit: Option<f64>,
    /// Override an input before rendering: `node.input=value` (as for `cnets run`).
    #[arg(long = "set", value_name = "NODE.INPUT=VALUE")]
    sets: Vec<String>,
    #[command(flatten)]
    session: SessionArgs,
}

fn parse_size(text: &str) -> Result<(u32, u32), Failure> {
    let bad = || {
        Failure::usage(format!(
            "--size '{text}': expected WIDTHxHEIGHT, e.g. 1280x720"
        ))
    };
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    if w == 0 || h == 0 || w > 8192 || h > 8192 {
        return Err(Failure::usage(format!(
            "--size '{text}': each side must be between 1 and 8192"
        )));
    }
    Ok((w, h))
}

/// The colour mode; for `distance:NODE` and `distance-reference:NODE` the reference node's id
/// and the side coloured.
fn parse_color(text: &str) -> Result<(ColorMode, Option<(String, DistanceSide)>), Failure> {
    match text {
        "config" | "configuration" | "class" => Ok((ColorMode::Configuration, None)),
        "planarity" => Ok((ColorMode::Planarity, None)),
        "plain" | "none" => Ok((ColorMode::Plain, None)),
        other => {
            let side = match other.split_once(':') {
                Some(("distance", node)) => Some((node, DistanceSide::Net)),
                Some(("distance-reference", node)) => Some((node, DistanceSide::Reference)),
                _ => None,
            };
            match side {
                Some((node, side)) if !node.trim().is_empty() => {
                    Ok((ColorMode::Distance, Some((node.trim().to_string(), side))))
                }
                _ => Err(Failure::usage(format!(
                    "--color '{other}': use config, planarity, plain, distance:NODE (the net \
                     coloured by its distance to NODE's mesh) or distance-reference:NODE (NODE's \
                     mesh coloured by its distance to the net)"
                ))),
            }
        }
    }
}

/// How a picture is taken: size, camera direction and display options.
pub struct Look {
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// Camera direction.
    pub view: View,
    /// Colours and visible layers.
    pub options: PreviewOptions,
    /// `--color distance:NODE` or `distance-reference:NODE`: the reference node's id, until
    /// [`Look::resolve`] finds it.
    pub distance_to: Option<String>,
}

impl Look {
    /// Parses the command-line forms of size, view, colour mode and hidden layers.
    pub fn parse(size: &str, view: &str, color: &str, hide: &[String]) -> Result<Self, Failure> {
        let size = parse_size(size)?;
        let view: View = view
            .parse()
            .map_err(|_| Failure::usage(format!("--view '{view}': use iso, top, front or side")))?;
        let mut options = PreviewOptions::default();
        let (mode, distance) = parse_color(color)?;
        options.color_mode = mode;
        let distance_to = distance.map(|(node, side)| {
            options.distance_side = side;
            node
        });
        // Apices are far from the surface and clutter a picture: shown only when asked.
        options.set(Layer::Apices, false);
        for name in hide {
            let layer = Layer::parse(name).ok_or_else(|| {
                let names: Vec<_> = Layer::ALL.iter().map(|l| l.name()).collect();
                Failure::usage(format!("--hide '{name}': use one of {}", names.join(", ")))
            })?;
            options.set(layer, false);
        }
        Ok(Self {
            size,
            view,
            options,
            distance_to,
        })
    }

    /// Finds the reference node of `--color distance:NODE` in the graph.
    pub fn resolve(&mut self, graph: &Graph) -> Result<(), Failure> {
        let Some(id) = &self.distance_to else {
            return Ok(());
        };
        let node = graph.node(id).ok_or_else(|| {
            let spelling = match self.options.distance_side {
                DistanceSide::Net => "distance",
                DistanceSide::Reference => "distance-reference",
            };
            Failure::usage(format!(
                "--color {spelling}:{id}: the graph has no node '{id}'"
            ))
        })?;
        self.options.distance_to = Some(node.uid());
        Ok(())
    }
}

impl Look {
    /// Draws the apices too (`--apices`).
    pub fn show_apices(&mut self) {
        self.options.set(Layer::Apices, true);
    }

    /// Sets the top of the planarity scale (`--planarity-limit`).
    pub fn set_planarity_limit(&mut self, limit: f64) -> Result<(), Failure> {
        if self.options.set_planarity_limit(limit) {
            Ok(())
        } else {
            let (lo, hi) = cnets_preview::PLANARITY_LIMIT_RANGE;
            Err(Failure::usage(format!(
                "--planarity-limit {limit}: use a number from {lo:e} to {hi:e}"
            )))
        }
    }
}

/// The legend drawn into a picture: the surface colours (face classes in words and the paper's
/// notation with their counts, or the planarity scale), and the apices when they are drawn.
pub fn legend_blocks(stats: &PreviewStats) -> Vec<LegendBlock> {
    let mut blocks = Vec::new();
    if let Some((title, rows)) = legend_rows(&stats.legend) {
        blocks.push(LegendBlock {
            title,
            rows,
            dots: false,
        });
    }
    if stats.apices > 0 {
        blocks.push(LegendBlock {
            title: "points".into(),
            rows: vec![(APEX_COLOR, format!("{APEX_LEGEND}  {}", stats.apices))],
            dots: true,
        });
    }
    blocks
}

/// Refuses, before any work, a file argument naming something a write may not replace (a FIFO, a
/// device, a folder, a link); the write checks again.
pub fn check_target(path: &Path) -> Result<(), Failure> {
    cnets_engine::files::check_replaceable(path)
        .map_err(|e| Failure::usage(format!("cannot write there: {e}")))
}

/// Renders the previewed geometry of an evaluated graph to a PNG (atomically), with its legend;
/// returns a summary: `wrote …` and the figures ([`summary`]), one indented line each.
pub fn render_png(
    graph: &Graph,
    evaluator: &Evaluator,
    look: &Look,
    png: &Path,
) -> Result<String, Failure> {
    let (width, height) = look.size;
    let (scene, stats) = build_scene(graph, evaluator, &look.options);
    if scene.is_empty() {
        return Err(Failure::node("nothing to render (no previewed geometry)"));
    }
    let mut camera = Camera::new(look.view);
    camera.fit_surfaces(&scene, width as f32 / height as f32);
    let mut gpu = Offscreen::new().map_err(|e| Failure::node(format!("cannot render: {e}")))?;
    let mut image: Image = gpu
        .render(&scene, &camera, width, height)
        .map_err(|e| Failure::node(format!("cannot render: {e}")))?;
    draw_legend(&mut image, &legend_blocks(&stats));
    let bytes = image
        .encode_png()
        .map_err(|e| Failure::node(format!("{}: cannot encode the picture: {e}", png.display())))?;
    // Atomic, and only over nothing or a regular file (never a FIFO or a device).
    cnets_engine::files::write_file(png, &bytes)
        .map_err(|e| Failure::usage(format!("cannot write the picture: {e}")))?;
    Ok(format!(
        "wrote {} ({width}x{height}, {} view)\n{}",
        png.display(),
        look.view,
        summary(&stats, look.options.color_mode)
    ))
}

/// A planarity for the summary: `< 1e-12` below rounding noise, else two digits.
fn planarity(p: f64) -> String {
    if p < 1e-12 {
        "< 1e-12".into()
    } else {
        format!("{p:.1e}")
    }
}

/// Meshes of one kind listed one a line before the rest are counted.
const LISTED: usize = 8;

/// The figures of a picture, one indented line each, every figure naming its mesh: the headline
/// planarity (the cone-nets', or without any the other meshes' — never a distance reference's),
/// each previewed mesh (cone-nets first, the reference last), and in the distance modes the
/// symmetric distance and what the colours show.
pub fn summary(stats: &PreviewStats, mode: ColorMode) -> String {
    let mut lines = Vec::new();
    let lead = stats.meshes.iter().find(|m| m.kind != MeshKind::Reference);
    let headline_of = lead.map(|m| match m.kind {
        MeshKind::ConeNet => "the cone-nets",
        _ => "the meshes",
    });
    match (stats.max_planarity, &stats.max_planarity_mesh, headline_of) {
        (Some(p), Some(mesh), Some(of)) => lines.push(format!(
            "max planarity {} ({mesh}; headline: {of}, {} vertices, {} faces in all)",
            planarity(p),
            stats.vertices,
            stats.faces
        )),
        _ => lines.push(format!(
            "{} vertices, {} faces in all",
            stats.vertices, stats.faces
        )),
    }
    for kind in [MeshKind::ConeNet, MeshKind::Mesh, MeshKind::Reference] {
        let of_kind: Vec<_> = stats.meshes.iter().filter(|m| m.kind == kind).collect();
        for m in of_kind.iter().take(LISTED) {
            let p = m.max_planarity.map_or(String::new(), |p| {
                format!(", max planarity {}", planarity(p))
            });
            let note = if kind == MeshKind::Reference {
                " (the distance reference: not in the net's figures)"
            } else {
                ""
            };
            lines.push(format!(
                "{} {}: {} vertices, {} faces{p}{note}",
                kind.word(),
                m.name,
                m.vertices,
                m.faces
            ));
        }
        if of_kind.len() > LISTED {
            lines.push(format!(
                "… and {} more {}es",
                of_kind.len() - LISTED,
                kind.word()
            ));
        }
    }
    let metres = cnets_preview::format_metres;
    match (&stats.distance, mode) {
        (Some(d), _) => {
            lines.push(format!(
                "distance {} ↔ {} (symmetric, area-weighted): rms {} max {}; net → reference rms \
                 {} max {}; reference → net rms {} max {}",
                d.net_name(),
                d.reference,
                metres(d.rms),
                metres(d.max),
                metres(d.net_rms),
                metres(d.net_max),
                metres(d.reference_rms),
                metres(d.reference_max)
            ));
            let coloured = match d.side {
                DistanceSide::Net => {
                    format!("the net's vertices by their distance to {}", d.reference)
                }
                DistanceSide::Reference => {
                    format!("{}'s vertices by their distance to the net", d.reference)
                }
            };
            lines.push(format!(
                "colours: {coloured}, 0 … {} over {} vertices",
                metres(d.colour_max),
                d.vertices
            ));
        }
        (None, ColorMode::Distance) => lines.push(format!(
            "no distance measured: {}",
            stats
                .distance_status
                .as_deref()
                .unwrap_or("no reference mesh")
        )),
        _ => {}
    }
    lines
        .iter()
        .map(|l| format!("  {l}"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Runs the command.
pub fn run(args: Args) -> CommandResult {
    let mut look = Look::parse(&args.size, &args.view, &args.color, &args.hide)?;
    if args.apices
        && !args
            .hide
            .iter()
            .any(|h| Layer::parse(h) == Some(Layer::Apices))
    {
        look.show_apices();
    }
    if let Some(limit) = args.planarity_limit {
        look.set_planarity_limit(limit)?;
    }
    check_target(&args.png)?;
    let session = args.session.session();
    let doc = session.load_graph(&args.graph, &args.sets)?;
    let graph = doc.graph;
    look.resolve(&graph)?;
    // The reference is evaluated even when it is not previewed.
    let reference = look
        .distance_to
        .as_deref()
        .and_then(|id| graph.index(id).ok());
    // Pull only what is previewed (exports are not run by a render), and the distance reference.
    let request: Vec<_> = graph
        .nodes()
        .filter(|(_, n)| n.preview && n.enabled && !n.def.has_flag(NodeFlag::Export))
        .map(|(k, _)| k)
        .chain(reference)
        .collect();
    let ctx = session.context(args.graph.parent().map(Path::to_path_buf));
    let mut evaluator = Evaluator::new();
    evaluator.evaluate(&graph, &request, &ctx, &mut |_, _| {});
    for (index, node) in graph.nodes() {
        if let Some(r) = evaluator
            .result_at(&graph, index)
            .filter(|r| r.is_failure())
        {
            crate::errln!(
                "warning: node '{}' ({}): {}",
                node.id,
                node.def.id,
                r.error().as_deref().unwrap_or("")
            );
        }
    }
    crate::outln!("{}", render_png(&graph, &evaluator, &look, &args.png)?);
    Ok(ExitCode::SUCCESS)
}
