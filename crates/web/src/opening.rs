//! Files opened on the page (picked or dropped) wait here until they are read. A large graph is
//! parsed on the page's thread, which then answers nothing for seconds (docs/web.md, "Large
//! files"): the page first draws a notice saying so, and parses only after that notice has been
//! drawn ([`NOTICE_FRAMES`] frames).

/// A graph file (`.ron`) of at least this many bytes is announced before it is parsed (4 MiB:
/// about a quarter of a second of parsing in the page).
pub const LARGE_GRAPH_BYTES: usize = 4 << 20;

/// Frames drawn with the notice before the files are handed over: the first draws it, the
/// second lets the browser put that frame on screen before the page stops answering.
pub const NOTICE_FRAMES: u32 = 2;

/// A file's name and content, as the browser read it.
pub type OpenedFile = (String, Vec<u8>);

/// How the last large graph was opened (reported to the browser test).
#[derive(Clone, Debug, PartialEq)]
pub struct LargeOpen {
    /// The file's name.
    pub name: String,
    /// Its size in bytes.
    pub bytes: usize,
    /// Frames drawn with the notice before parsing began.
    pub notice_frames: u32,
    /// How long reading it as the document took, in milliseconds (set by the page).
    pub open_ms: Option<f64>,
}

/// What the page shows while a large graph waits to be parsed.
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

/// Files read by the browser, waiting to be opened.
#[derive(Default)]
pub struct Opening {
    waiting: Vec<OpenedFile>,
    /// Frames drawn with the notice for the files waiting.
    shown: u32,
    /// The last large graph opened, once handed over.
    pub last_large: Option<LargeOpen>,
}

/// Whether `name` of `len` bytes is a graph large enough to announce.
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

    /// Called once a frame, before the editor's UI: the files to open now. While a large graph
    /// waits, nothing is handed over until the notice has been drawn in [`NOTICE_FRAMES`]
    /// frames; then every waiting file is, in the order they arrived.
    pub fn due(&mut self) -> Vec<OpenedFile> {
        if let Some((name, bytes)) = self.waiting_large() {
            if self.shown < NOTICE_FRAMES {
                self.shown += 1;
                return Vec::new();
            }
            self.last_large = Some(LargeOpen {
                name: name.clone(),
                bytes: bytes.len(),
                notice_frames: self.shown,
                open_ms: None,
            });
        }
        self.shown = 0;
        std::mem::take(&mut self.waiting)
    }

    /// The notice to draw this frame, while a large graph waits.
    pub fn notice(&self) -> Option<Notice> {
        let (name, bytes) = self.waiting_large()?;
        Some(Notice {
            title: format!("Opening {name} ({})", size_text(bytes.len())),
            detail: "The page does not answer until it is read, which can take a few seconds."
                .to_string(),
        })
    }

    /// The first large graph among the files waiting.
    fn waiting_large(&self) -> Option<&OpenedFile> {
        self.waiting
            .iter()
            .find(|(name, bytes)| is_large_graph(name, bytes.len()))
    }

    /// Whether files wait (the page asks for another frame).
    pub fn pending(&self) -> bool {
        !self.waiting.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(name: &str, len: usize) -> OpenedFile {
        (name.to_string(), vec![b' '; len])
    }

    #[test]
    fn small_files_are_handed_over_at_once() {
        let mut o = Opening::default();
        o.arrive(vec![file("a.ron", 100), file("profile.csv", 10 << 20)]);
        assert_eq!(
            o.notice(),
            None,
            "a large CSV is not parsed as the document"
        );
        let due = o.due();
        assert_eq!(due.len(), 2);
        assert!(!o.pending());
        assert_eq!(o.last_large, None);
    }

    #[test]
    fn a_large_graph_waits_for_its_notice_to_be_drawn() {
        let mut o = Opening::default();
        o.arrive(vec![
            file("small.csv", 10),
            file("big.RON", LARGE_GRAPH_BYTES),
        ]);
        let notice = o.notice().expect("a notice for the large graph");
        assert_eq!(notice.title, "Opening big.RON (4.2 MB)");
        assert_eq!(
            notice.sentence(),
            "Opening big.RON (4.2 MB): the page does not answer until it is read, which can take a few seconds."
        );
        for frame in 1..=NOTICE_FRAMES {
            assert!(
                o.due().is_empty(),
                "frame {frame}: the notice is drawn first"
            );
            assert!(o.pending() && o.notice().is_some());
        }
        let due = o.due();
        let names: Vec<&str> = due.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["small.csv", "big.RON"], "every file, in order");
        assert!(!o.pending() && o.notice().is_none());
        let last = o.last_large.clone().expect("recorded");
        assert_eq!(
            (last.name.as_str(), last.bytes, last.notice_frames),
            ("big.RON", LARGE_GRAPH_BYTES, NOTICE_FRAMES)
        );
        // The next large file waits for its own notice again.
        o.arrive(vec![file("again.ron", LARGE_GRAPH_BYTES + 1)]);
        assert!(o.due().is_empty());
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
