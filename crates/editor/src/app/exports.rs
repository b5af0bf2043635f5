//! File › Export: the graph's own export nodes run into a chosen folder, and quick exports of
//! the preview under a name the designer gives; what was written is listed in a dialog
//! ([`crate::export::ExportReport`]).

use std::path::{Path, PathBuf};

use crate::export::{self, ExportFormat, ExportReport, ExportRun};

use super::EditorApp;

impl EditorApp {
    /// Where export dialogs start: the document's folder, else the designer's own folder (never
    /// the shipped examples' folder).
    pub(super) fn export_folder(&self) -> PathBuf {
        self.doc.path.as_deref().and_then(Path::parent).map_or_else(
            || super::files::user_folder(&self.examples_dir),
            Path::to_path_buf,
        )
    }

    /// The name a quick export starts with: the document's file name, else `cone-net`.
    pub(super) fn export_name(&self) -> String {
        self.doc
            .resolve_file()
            .and_then(Path::file_stem)
            .map_or_else(
                || "cone-net".to_string(),
                |s| s.to_string_lossy().into_owned(),
            )
    }

    /// Runs the graph's own export nodes into `folder` (each writes the file its inputs name,
    /// with the graph's settings, as `cnets run --out FOLDER`) and lists what they wrote.
    pub fn run_exports(&mut self, folder: &Path) {
        let graph = self.doc.eval_graph();
        let base = self.doc.base_dir();
        match export::run_exports(&graph, base, &self.doc.allowed_reads, folder) {
            Ok(runs) => self.report(folder, runs),
            Err(e) => self.message = format!("export failed: {e}"),
        }
    }

    /// A quick export of the preview as the file `path` (the name the designer typed).
    pub fn export_preview(&mut self, format: ExportFormat, path: &Path) {
        let folder = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let name = path
            .file_stem()
            .map_or_else(|| self.export_name(), |s| s.to_string_lossy().into_owned());
        let base = self.doc.base_dir();
        // GLB and OBJ: everything the 3D view draws; SVG and DXF: the flat outlines.
        let (result, contents) = match format {
            ExportFormat::Glb | ExportFormat::Obj => {
                match crate::export_preview::export_preview(
                    self.viewport.picks(),
                    &self.doc.graph,
                    base,
                    &self.doc.allowed_reads,
                    format,
                    &folder,
                    &name,
                ) {
                    Ok((files, counts)) => {
                        (Ok(files), counts.iter().map(|c| c.describe()).collect())
                    }
                    Err(e) => (Err(e), Vec::new()),
                }
            }
            ExportFormat::Svg | ExportFormat::Dxf => (
                export::export(
                    &self.doc.graph,
                    base,
                    &self.doc.allowed_reads,
                    format,
                    &folder,
                    &name,
                ),
                Vec::new(),
            ),
        };
        let run = ExportRun {
            node: String::new(),
            label: format!("the preview as {}", format.extension().to_uppercase()),
            result,
            contents,
        };
        self.report(&folder, vec![run]);
    }

    fn report(&mut self, folder: &Path, runs: Vec<ExportRun>) {
        let report = ExportReport {
            folder: folder.to_path_buf(),
            runs,
        };
        self.message = report.summary();
        if let [run] = report.runs.as_slice()
            && let Err(e) = &run.result
        {
            self.message = format!("export failed: {e}");
        }
        self.modals.open(super::Modal::ExportReport(report));
    }
}
