//! The web page around the editor (the browser build, `crates/web`): where the desktop editor
//! uses files and dialogs, the editor in a page queues a [`PageRequest`] and the page carries it
//! out with the browser (a file picker, a download, the clipboard and the address bar). The
//! editor itself stays free of browser APIs; on the desktop there is no page (`EditorApp::page`
//! is `None`) and nothing here is used.

/// Something only the page can do.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PageRequest {
    /// Show the browser's file picker (File ▸ Open…): a `.ron` opens as the document, any other
    /// file becomes readable by the nodes that import it.
    PickFile,
    /// Offer `bytes` as a download named `name` (Save, Save as…, Export).
    Download {
        /// The file name.
        name: String,
        /// Its content.
        bytes: Vec<u8>,
    },
    /// Put a share link of the graph into the address bar and the clipboard (File ▸ Copy link).
    CopyLink {
        /// The graph's canonical text.
        ron: String,
    },
}

/// The page's queue: filled by the editor during a frame, emptied by the page after it.
#[derive(Clone, Debug, Default)]
pub struct Page {
    /// Requests in the order they were made.
    pub requests: Vec<PageRequest>,
}

impl Page {
    /// Takes the queued requests.
    pub fn take(&mut self) -> Vec<PageRequest> {
        std::mem::take(&mut self.requests)
    }
}
