//! `cnets render <GRAPH.ron> --png <FILE> [--size WxH] [--view iso|top|front|side] [--color …]
//! [--apices] [--planarity-limit X]`: the picture carries its legend (the face classes in words
//! and the paper's notation, or the planarity scale; the apices when shown).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use cnets_engine::{Evaluator, Graph, NodeContext, NodeFlag};
use cnets_preview::{
    APEX_COLOR, APEX_LEGEND, ColorMode, Layer, PreviewOptions, PreviewStats, build_scene,
    legend_rows,
};
use cnets_render::{Camera, Image, LegendBlock, Offscreen, View, draw_legend};

use crate::failure::{CommandResult, Failure};
use crate::library;

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
    /// or distance:NODE (each vertex's distance to NODE's mesh, legend in metres).
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
    /// Extra folders searched for cluster graph files.
    #[arg(long)]
    library: Vec<PathBuf>,
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

/// The colour mode, and for `distance:NODE` the reference node's id.
fn parse_color(text: &str) -> Result<(ColorMode, Option<String>), Failure> {
    match text {
        "config" | "configuration" | "class" => Ok((ColorMode::Configuration, None)),
        "planarity" => Ok((ColorMode::Planarity, None)),
        "plain" | "none" => Ok((ColorMode::Plain, None)),
        other => match other.split_once(':') {
            Some(("distance", node)) if !node.trim().is_empty() => {
                Ok((ColorMode::Distance, Some(node.trim().to_string())))
            }
            _ => Err(Failure::usage(format!(
                "--color '{other}': use config, planarity, plain or distance:NODE (the node whose \
                 mesh the others are measured against)"
            ))),
        },
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
    /// `--color distance:NODE`: the reference node's id, until [`Look::resolve`] finds it.
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
        let (mode, distance_to) = parse_color(color)?;
        options.color_mode = mode;
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
            Failure::usage(format!(
                "--color distance:{id}: the graph has no node '{id}'"
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
/// returns a one-line summary.
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
    // With several meshes previewed, the one the figure is for.
    let planarity = match (stats.max_planarity, &stats.max_planarity_mesh) {
        (Some(p), Some(mesh)) => format!(", max planarity {p:.1e} ({mesh})"),
        (Some(p), None) => format!(", max planarity {p:.1e}"),
        _ => String::new(),
    };
    let distance = match (&stats.distance, look.options.color_mode) {
        (Some(d), _) => format!(
            ", distance to {}: max {} rms {} over {} vertices",
            d.reference,
            cnets_preview::format_metres(d.max),
            cnets_preview::format_metres(d.rms),
            d.vertices
        ),
        (None, ColorMode::Distance) => ", no mesh measured (the reference has no mesh, or \
                                        nothing else is previewed)"
            .to_string(),
        _ => String::new(),
    };
    Ok(format!(
        "wrote {} ({width}x{height}, {} view, {} vertices, {} faces{planarity}{distance})",
        png.display(),
        look.view,
        stats.vertices,
        stats.faces
    ))
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
    let doc = library::load_graph(&args.graph, &args.library, &args.sets)?;
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
    let ctx = NodeContext::new(None, args.graph.parent().map(Path::to_path_buf));
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
