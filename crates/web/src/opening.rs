//! Files opened on the page (picked or dropped) wait here until they are read. A large graph is
//! read (parsed) by the evaluation worker, not on the page's thread (docs/web.md, "Large files"):
//! the page keeps answering, and shows a notice until the worker's answer replaces the document.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cnets_editor::document::GraphDocument;
use cnets_engine::Registry;
use cnets_engine::file::LoadError;

use crate::wire::Parsed;

/// A graph file (`.ron`) of at least this many bytes is read by the worker (4 MiB: about a
/// quarter of a second of parsing; the desktop editor's threshold for reading off its UI thread).
pub const LARGE_GRAPH_BYTES: usize = cnets_editor::app::LARGE_GRAPH_BYTES as usize;

/// A file's name and content, as the browser read it.
pub type OpenedFile = (String, Vec<u8>);

/// How the last large graph was opened (reported to the browser test).
#[derive(Clone, Debug, PartialEq)]
pub struct LargeOpen {
    /// The file's name.
    pub name: String,
    /// Its size in bytes.
    pub bytes: usize,
    /// Frames the page drew while the worker read it.
    pub frames_while_reading: u32,
    /// From handing it to the worker to the document replaced, in milliseconds.
    pub open_ms: Option<f64>,
    /// Of that, the page's own time (the worker's answer decoded, the document built).
    pub page_ms: Option<f64>,
}

/// What the page shows while a large graph is read.
#[derive(Clone, Debug, PartialEq)]
pub struct Notice {
    /// "Opening big.ron (57.0 MB)".
    pub title: String,
    /// What the designer should expect.
    pub detail: String,
}

impl Notice {
    /// Title and detail in one line (the status bar).
    pub fn sentence(&self) -> String {
        format!("{}: {}", self.title, self.detail.to_lowercase())
    }
}

/// A large graph the worker reads.
#[derive(Clone, Debug, PartialEq)]
struct Reading {
    token: u64,
    name: String,
    bytes: usize,
    since_ms: f64,
}

/// Files read by the browser, waiting to be opened, and the large graph the worker reads.
#[derive(Default)]
pub struct Opening {
    waiting: Vec<OpenedFile>,
    reading: Option<Reading>,
    /// The last large graph opened.
    pub last_large: Option<LargeOpen>,
}

/// Whether `name` of `len` bytes is a graph large enough to be read by the worker.
pub fn is_large_graph(name: &str, len: usize) -> bool {
    name.to_ascii_lowercase().ends_with(".ron") && len >= LARGE_GRAPH_BYTES
}

/// Bytes as the designer reads them: "57.0 MB", "812 KB".
pub fn size_text(bytes: usize) -> String {
    let b = bytes as f64;
    if b >= 1e6 {
        format!("{:.1} MB", b / 1e6)
    } else if b >= 1e3 {
        format!("{:.0} KB", b / 1e3)
    } else {
        format!("{bytes} bytes")
    }
}

impl Opening {
    /// Files the browser has read.
    pub fn arrive(&mut self, files: Vec<OpenedFile>) {
        self.waiting.extend(files);
    }

    /// The files to open now (every one waiting, in the order they arrived).
    pub fn due(&mut self) -> Vec<OpenedFile> {
        std::mem::take(&mut self.waiting)
    }

    /// The worker reads `name` (`bytes` long) for the answer `token`, from `now_ms` on; a graph
    /// read before and not yet answered no longer opens (the latest file wins).
    pub fn start_reading(&mut self, token: u64, name: &str, bytes: usize, now_ms: f64) {
        self.reading = Some(Reading {
            token,
            name: name.to_string(),
            bytes,
            since_ms: now_ms,
        });
        self.last_large = Some(LargeOpen {
            name: name.to_string(),
            bytes,
            frames_while_reading: 0,
            open_ms: None,
            page_ms: None,
        });
    }

    /// Another document was opened meanwhile: the graph being read no longer opens.
    pub fn cancel_reading(&mut self) {
        self.reading = None;
    }

    /// Called once a frame.
    pub fn frame(&mut self) {
        if self.reading.is_some()
            && let Some(large) = &mut self.last_large
        {
            large.frames_while_reading += 1;
        }
    }

    /// The worker answered `token` at `now_ms`: the file's name when it is the one to open.
    pub fn answered(&mut self, token: u64, now_ms: f64) -> Option<String> {
        let reading = self.reading.take_if(|r| r.token == token)?;
        if let Some(large) = &mut self.last_large {
            large.open_ms = Some(now_ms - reading.since_ms);
        }
        Some(reading.name)
    }

    /// The notice to draw this frame, while a large graph waits or is read.
    pub fn notice(&self) -> Option<Notice> {
        let (name, bytes) = match &self.reading {
            Some(r) => (r.name.as_str(), r.bytes),
            None => self
                .waiting
                .iter()
                .find(|(name, bytes)| is_large_graph(name, bytes.len()))
                .map(|(name, bytes)| (name.as_str(), bytes.len()))?,
        };
        Some(Notice {
            title: cnets_editor::opening_notice::title(name, bytes as u64),
            detail: cnets_editor::opening_notice::DETAIL.to_string(),
        })
    }

    /// Whether files wait or a graph is read (the page asks for another frame).
    pub fn pending(&self) -> bool {
        !self.waiting.is_empty() || self.reading.is_some()
    }
}

/// The document a file read by the worker makes: its text without the large literals loaded as
/// the page loads a file (`origin` and the library folders as for [`cnets_host`]'s documents),
/// the literals put back (the graph holds the very values decoded, which the worker keeps under
/// their keys).
pub fn document_of(
    parsed: Parsed,
    origin: &Path,
    registry: &Arc<Registry>,
    library: &[PathBuf],
) -> Result<GraphDocument, LoadError> {
    let options = cnets_host::document_options(Some(origin), library);
    let name = origin.display().to_string();
    let mut doc = cnets_engine::file::load_str_with(&parsed.skeleton, &name, registry, &options)?;
    for (at, value) in parsed.literals {
        doc.graph
            .set_value(&at.node, &at.input, value)
            .map_err(|e| LoadError::message(format!("{name}: {e}")))?;
    }
    Ok(GraphDocument::from_parts(doc.graph, doc.meta, None))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(name: &str, len: usize) -> OpenedFile {
        (name.to_string(), vec![b' '; len])
    }

    #[test]
    fn files_are_handed_over_at_once_and_only_large_graphs_are_announced() {
        let mut o = Opening::default();
        o.arrive(vec![file("a.ron", 100), file("profile.csv", 10 << 20)]);
        assert_eq!(o.notice(), None, "a large CSV is not a graph to read");
        o.arrive(vec![file("big.RON", LARGE_GRAPH_BYTES)]);
        assert_eq!(
            o.notice().map(|n| n.title).as_deref(),
            Some("Opening big.RON (4.2 MB)")
        );
        let names: Vec<String> = o.due().into_iter().map(|(n, _)| n).collect();
        assert_eq!(
            names,
            ["a.ron", "profile.csv", "big.RON"],
            "every file, in order"
        );
        assert!(!o.pending() && o.notice().is_none());
    }

    #[test]
    fn a_large_graph_is_announced_while_the_worker_reads_it() {
        let mut o = Opening::default();
        o.start_reading(1, "big.ron", LARGE_GRAPH_BYTES, 100.0);
        let notice = o.notice().expect("a notice while it is read");
        assert_eq!(
            notice.sentence(),
            "Opening big.ron (4.2 MB): it is read in the background; it replaces the document when it is ready."
        );
        o.frame();
        o.frame();
        assert!(o.pending());
        assert_eq!(o.answered(7, 150.0), None, "another answer");
        assert_eq!(o.answered(1, 400.0).as_deref(), Some("big.ron"));
        assert!(!o.pending() && o.notice().is_none());
        let last = o.last_large.clone().unwrap();
        assert_eq!((last.frames_while_reading, last.open_ms), (2, Some(300.0)));
        // The latest file wins: a graph opened meanwhile cancels the reading.
        o.start_reading(2, "again.ron", LARGE_GRAPH_BYTES, 0.0);
        o.cancel_reading();
        assert_eq!(o.answered(2, 10.0), None);
        assert!(!o.pending());
    }

    #[test]
    fn a_file_read_by_the_worker_opens_as_the_page_would_have_read_it() {
        use crate::literals::{LARGE_LITERAL_ITEMS, LiteralCache};
        use crate::wire::{FromWorker, ParseJob, decode_from_worker};
        let registry = Arc::new(cnets_nodes::registry());
        let numbers: Vec<String> = (0..LARGE_LITERAL_ITEMS).map(|k| k.to_string()).collect();
        let text = format!(
            "(version: 1, name: \"big\", description: \"kept\", nodes: {{\"n\": (type: \
             \"param.list\", position: (5.0, 6.0), inputs: {{\"values\": [{}], \
             \"item_type\": \"integer\"}})}})",
            numbers.join(", ")
        );
        let mut worker = crate::service::Service::new(registry.clone());
        let message = worker.parse(ParseJob {
            token: 1,
            origin: "big.ron".into(),
            library: Vec::new(),
            text: text.clone().into_bytes(),
        });
        let Ok(FromWorker::Parsed {
            result: Ok(parsed), ..
        }) = decode_from_worker(&message)
        else {
            panic!("not read");
        };
        let literals = parsed.literals.clone();
        let doc = document_of(parsed, Path::new("big.ron"), &registry, &[]).unwrap();
        let direct = GraphDocument::from_text_with(
            &text,
            "big.ron",
            None,
            &registry,
            &cnets_host::document_options(Some(Path::new("big.ron")), &[]),
        )
        .unwrap();
        assert_eq!(doc.to_ron(), direct.to_ron());
        assert!(!doc.is_dirty(), "a freshly opened document");
        // The page adopts the decoded values: its first request sends no literal, as the graph
        // holds those very values (the worker has them).
        let mut cache = LiteralCache::default();
        for (at, value) in literals {
            cache.adopt(at.key, value);
        }
        let split = cache.split(&doc.graph);
        assert!(split.new.is_empty() && split.refs.len() == 1);
    }

    #[test]
    fn just_under_the_threshold_is_not_announced() {
        assert!(!is_large_graph("a.ron", LARGE_GRAPH_BYTES - 1));
        assert!(is_large_graph("a.ron", LARGE_GRAPH_BYTES));
        assert!(!is_large_graph("a.obj", LARGE_GRAPH_BYTES));
        assert_eq!(size_text(57_000_000), "57.0 MB");
        assert_eq!(size_text(812_400), "812 KB");
        assert_eq!(size_text(12), "12 bytes");
    }
}
