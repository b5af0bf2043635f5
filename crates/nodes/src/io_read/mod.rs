//! Importing polylines from CSV, JSON, OBJ and SVG files (`io.read_polylines`).
//!
//! One parser per format ([`csv`], [`json`], [`obj`], [`svg`]), each a pure function from the
//! file's text to polylines (errors name the line); the node resolves the path against the graph
//! file's folder and reads the file. The accepted layouts are documented in `docs/inputs.md`.

pub mod csv;
pub mod dxf;
pub mod json;
pub mod mesh;
pub mod obj;
pub mod svg;

use std::path::Path;

use cnets_engine::budget::Guard;
use cnets_engine::files;
use cnets_engine::prelude::*;

/// A reader's error: what is wrong and, when the reader knows it, where in the file — the line
/// and column (from 1) as fields, which the node turns into [`NodeError::Located`] and a front end
/// shows or jumps to. Displays as `line 3, column 7: message` (`message` alone when unplaced), the
/// words the readers always used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}{message}", place(*.line, *.column))]
pub struct ReadError {
    /// The line, from 1, when known.
    pub line: Option<usize>,
    /// The column, from 1, when known (only with a line).
    pub column: Option<usize>,
    /// What is wrong there.
    pub message: String,
}

fn place(line: Option<usize>, column: Option<usize>) -> String {
    match (line, column) {
        (Some(l), Some(c)) => format!("line {l}, column {c}: "),
        (Some(l), None) => format!("line {l}: "),
        _ => String::new(),
    }
}

impl ReadError {
    /// An error on `line` (from 1).
    pub fn at(line: usize, message: impl Into<String>) -> Self {
        Self {
            line: Some(line),
            column: None,
            message: message.into(),
        }
    }

    /// An error at `line`, `column` (from 1).
    pub fn at_column(line: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            line: Some(line),
            column: Some(column),
            message: message.into(),
        }
    }

    /// The node's error about `file`: placed errors become [`NodeError::Located`] from these
    /// fields (the message cut to a short excerpt), others `file: message`.
    pub fn in_file(self, file: &str) -> NodeError {
        let message = files::excerpt(&self.message, 200);
        match self.line {
            Some(line) => NodeError::Located {
                file: file.to_string(),
                line,
                column: self.column,
                message,
            },
            None => NodeError::new(format!("{file}: {message}")),
        }
    }
}

impl From<String> for ReadError {
    fn from(message: String) -> Self {
        Self {
            line: None,
            column: None,
            message,
        }
    }
}

impl From<&str> for ReadError {
    fn from(message: &str) -> Self {
        message.to_string().into()
    }
}

/// A format input, lower-cased, and the key to match: the name itself, or for `auto` (or empty)
/// the file's extension.
pub(crate) fn format_key(name: &str, path: &str) -> (String, String) {
    let name = name.trim().to_ascii_lowercase();
    let key = if name.is_empty() || name == "auto" {
        Path::new(path)
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase()
    } else {
        name.clone()
    };
    (name, key)
}

/// The formats `io.read_polylines` reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma/semicolon/tab/space separated x, y[, z] rows; blank lines separate polylines.
    Csv,
    /// The runner's JSON encoding of polylines.
    Json,
    /// Wavefront OBJ `v` and `l` records.
    Obj,
    /// SVG `<polyline>`, `<polygon>`, `<line>` and `<path>` elements.
    Svg,
    /// DXF curves (LINE, LWPOLYLINE, POLYLINE, ARC, CIRCLE, ELLIPSE, SPLINE).
    Dxf,
}

impl Format {
    /// Parses a format name (`csv`, `json`, `obj`, `svg`, `dxf`) or, for `auto`, guesses it from the file
    /// extension (`.csv`/`.txt`/`.xyz` are CSV).
    pub fn resolve(name: &str, path: &str) -> Result<Self, String> {
        let (name, key) = format_key(name, path);
        match key.as_str() {
            "csv" | "txt" | "xyz" => Ok(Self::Csv),
            "json" => Ok(Self::Json),
            "obj" => Ok(Self::Obj),
            "svg" => Ok(Self::Svg),
            "dxf" => Ok(Self::Dxf),
            _ if name.is_empty() || name == "auto" => Err(format!(
                "cannot tell the format of '{path}' from its extension: set format to csv, json, obj, svg or dxf"
            )),
            _ => Err(format!(
                "unknown format '{name}': expected auto, csv, json, obj, svg or dxf"
            )),
        }
    }
}

/// Applies the rules shared by the text formats: consecutive repeated points are merged, and a
/// polyline whose last point repeats its first (with at least three other points) becomes closed.
pub(crate) fn tidy(points: Vec<DVec3>, closed: bool) -> Polyline {
    let mut out: Vec<DVec3> = Vec::with_capacity(points.len());
    for p in points {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    let mut closed = closed;
    if out.len() >= 4 && out.first() == out.last() {
        out.pop();
        closed = true;
    }
    if closed && out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    Polyline {
        points: out,
        closed,
    }
}

/// Parses a file's bytes in `format`; SVG flattening uses `segments` points per curved segment,
/// DXF sampling `segments` edges per curved piece. Returns the polylines and warnings.
pub fn parse(
    bytes: &[u8],
    format: Format,
    segments: usize,
) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    parse_within(bytes, format, segments, &mut Guard::unlimited())
}

/// [`parse`] counting what the parser builds against `guard` (records, sampled points).
pub fn parse_within(
    bytes: &[u8],
    format: Format,
    segments: usize,
    guard: &mut Guard,
) -> Result<(Vec<Polyline>, Vec<String>), ReadError> {
    let text = || {
        std::str::from_utf8(bytes).map_err(|e| {
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.valid_up_to()
            )
        })
    };
    match format {
        Format::Csv => csv::parse_within(text()?, guard).map(|p| (p, Vec::new())),
        Format::Json => json::parse(text()?).map(|p| (p, Vec::new())),
        Format::Obj => obj::parse(text()?),
        Format::Svg => svg::parse_within(text()?, segments, guard),
        Format::Dxf => dxf::parse_within(bytes, segments, guard),
    }
}

node! {
    /// Reads polylines from a file drawn elsewhere: CSV (x, y[, z] rows, blank lines between
    /// polylines), JSON (the runner's encoding: `{points, closed}` objects or arrays of [x, y, z],
    /// or lists of them), OBJ (`v` and `l` records), SVG (`<polyline>`, `<polygon>`, `<line>`,
    /// `<path>` with all commands; curves and arcs are flattened into `segments` points each; y is
    /// flipped so that SVG's downward y axis points up) or DXF (LINE, LWPOLYLINE with bulges,
    /// POLYLINE, ARC, CIRCLE, ELLIPSE, SPLINE — what Rhino and AutoCAD export; curved pieces are
    /// sampled with `segments` edges, splines `segments` per knot span). A relative path is resolved against the
    /// graph file's folder. Consecutive repeated points are merged; a polyline whose last point
    /// repeats its first becomes closed. A file that cannot be read or parsed is an error naming it.
    #[node(id = "io.read_polylines", category = "Import", flags(Import))]
    pub fn read_polylines[ctx](
        /// The file (relative to the graph file's folder, or absolute).
        #[ui(widget = FilePath)]
        path: k::Text,
        /// auto (from the extension), csv, json, obj, svg or dxf.
        format: k::Choice<crate::choices::PolylineFormat> = "auto",
        /// SVG and DXF: points per flattened curve, arc or spline span (≥ 1).
        segments: k::Integer = 16,
    ) -> (
        /// The polylines, in file order.
        curves: k::List<k::Polyline>,
    ) {
        if path.trim().is_empty() {
            return Err("no file given: set path".into());
        }
        let format = Format::resolve(format, &path)?;
        let segments = usize::try_from(segments)
            .ok()
            .filter(|s| (1..=10_000).contains(s))
            .ok_or_else(|| NodeError::new(format!("segments must be 1 to 10000, got {segments}")))?;
        let (file, bytes) = ctx.read_file(&path)?;
        let mut guard = ctx.guard(format!("reading '{}'", files::excerpt(&path, 60)));
        // The reader's place (line, column) becomes fields of the error.
        let (curves, warnings) = parse_within(&bytes, format, segments, &mut guard)
            .map_err(|e| e.in_file(&file.display().to_string()))?;
        if curves.is_empty() {
            return Err(format!("{}: no polylines found", file.display()).into());
        }
        for w in warnings {
            ctx.warn(format!("{}: {w}", file.display()));
        }
        Ok((curves,))
    }
}

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![read_polylines(), mesh::read_mesh()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_resolve_from_names_and_extensions() {
        assert_eq!(Format::resolve("auto", "a/b.SVG").unwrap(), Format::Svg);
        assert_eq!(Format::resolve("", "b.txt").unwrap(), Format::Csv);
        assert_eq!(Format::resolve("OBJ", "b.txt").unwrap(), Format::Obj);
        assert_eq!(Format::resolve("auto", "b.DXF").unwrap(), Format::Dxf);
        assert!(
            Format::resolve("auto", "b.dwg")
                .unwrap_err()
                .contains("extension")
        );
        assert!(
            Format::resolve("dwg", "b.obj")
                .unwrap_err()
                .contains("unknown format")
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]

        /// Garbage in any format is an error or a result, never a panic.
        #[test]
        fn parsers_never_panic(
            text in "[<>/=\"' a-zA-Z0-9.,;#&+\\-\n\t]{0,120}",
            prefix in proptest::sample::select(vec![
                "", "<path d=\"", "<polyline points=\"", "v 0 0 0\nl ", "[{\"points\": [", "0,0\n",
            ]),
        ) {
            let text = format!("{prefix}{text}");
            for format in [Format::Csv, Format::Json, Format::Obj, Format::Svg] {
                if let Ok((curves, _)) = parse(text.as_bytes(), format, 3) {
                    for c in curves {
                        proptest::prop_assert!(c.points.iter().all(|p| p.is_finite()));
                    }
                }
            }
        }
    }

    #[test]
    fn tidy_merges_repeats_and_closes() {
        let sq = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::X,
            DVec3::ONE,
            DVec3::Y,
            DVec3::ZERO,
        ];
        let p = tidy(sq, false);
        assert!(p.closed);
        assert_eq!(p.points.len(), 4);
        let open = tidy(vec![DVec3::ZERO, DVec3::X, DVec3::ZERO], false);
        assert!(!open.closed);
        assert_eq!(open.points.len(), 3);
    }
}
