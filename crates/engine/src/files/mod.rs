//! Files only where they belong: what nodes and the graph loader may read and write.
//!
//! - [`names`]: export names are checked by name first (no control characters, no `.`, `..` or
//!   empty components, no root).
//! - [`write`]: every write is atomic (a locked temporary file, synced, moved into place) and
//!   replaces only nothing or a regular file ([`write_file`] for paths a user names, with
//!   [`check_replaceable`] to ask first; [`write_inside`] / [`create_inside`] for exports, which
//!   also never follow a symbolic link out of the output directory). Writes stream through
//!   [`AtomicFile`], which stops at a cancel request.
//! - [`temp`]: abandoned temporary files (our marker, unlocked, old) are removed when an export
//!   writes into their folder; a process's own are removed on SIGINT/SIGTERM
//!   ([`temp::remove_own`]).
//! - [`read`]: reads are allowed only under the graph file's folder and folders allowed
//!   explicitly (`--allow-read DIR`); devices, FIFOs and sockets are refused, and files over a size
//!   limit (1 GB by default). Nodes read through [`NodeContext::read_file`](crate::NodeContext::read_file)
//!   and the loader reads cluster files through the same check.
//! - [`memory`]: on the web (wasm32) reads come from the files the designer opened or dropped and
//!   exports are kept in memory for download (no file system there).
//! - [`excerpt`]: error messages quote at most a short, escaped excerpt of what they read.

pub mod memory;
pub mod names;
pub mod read;
pub mod temp;
pub mod write;

pub use names::check_export_name;
pub use read::{DEFAULT_MAX_READ_BYTES, ReadAccess};
pub use write::{
    AtomicFile, check_replaceable, create_file, create_inside, write_file, write_inside,
};

use std::path::PathBuf;

/// What a refused read's message says after the file's path (see [`FileError::NotAllowed`] and
/// [`refused_read`]).
pub const NOT_ALLOWED_MARK: &str = " is outside the folders reads are allowed in (";

/// The file a node was refused to read because it lies outside the allowed folders, from the
/// node's error message (`cannot read 'NAME': PATH is outside the folders …`); `None` for any
/// other message. Front ends offer to allow the file's folder (the editor's "Allow reading this
/// folder").
pub fn refused_read(message: &str) -> Option<PathBuf> {
    let head = &message[..message.find(NOT_ALLOWED_MARK)?];
    let path = match head.rfind("': ") {
        Some(k) => &head[k + 3..],
        None => head,
    };
    (!path.is_empty()).then(|| PathBuf::from(path))
}

/// A file that may not be read or written, or could not be.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The export name is refused by name.
    #[error("export name {0}: {1}")]
    BadName(String, &'static str),
    /// A folder inside the output directory is a symbolic link.
    #[error(
        "'{0}' inside the output directory is a symbolic link: exports do not follow links out of it"
    )]
    Link(String),
    /// A folder of the export name is taken by a file.
    #[error("cannot create the output folder '{0}': a file of that name is in the way")]
    NotAFolder(String),
    /// The file is outside every folder reads are allowed in.
    #[error(
        "{path} is outside the folders reads are allowed in ({allowed}); allow its folder with --allow-read"
    )]
    NotAllowed {
        /// The refused file.
        path: PathBuf,
        /// The allowed folders, for the message.
        allowed: String,
    },
    /// A device, FIFO, socket or folder where a file was expected.
    #[error("{0} is not a regular file (devices, FIFOs and sockets are not read)")]
    NotAFile(PathBuf),
    /// The file is larger than the read limit.
    #[error("{path} is {size} bytes, more than the read limit of {limit} bytes")]
    TooLarge {
        /// The refused file.
        path: PathBuf,
        /// Its size.
        size: u64,
        /// The limit.
        limit: u64,
    },
    /// Something other than a regular file is where a write would put its file.
    #[error("{0} is {1}: a write replaces only a regular file (or creates one)")]
    NotReplaceable(PathBuf, &'static str),
    /// The write was cancelled (Ctrl+C, SIGTERM, a newer edit); nothing was written.
    #[error("{0}: cancelled")]
    Cancelled(PathBuf),
    /// An operating-system error on a path.
    #[error("{0}: {1}")]
    Io(PathBuf, std::io::Error),
}

/// At most `max` characters of `text` for an error message, control characters escaped and an
/// ellipsis when cut: a CSV error on `/etc/passwd` quotes a few characters, not the line.
pub fn excerpt(text: &str, max: usize) -> String {
    let mut out = String::new();
    for (k, c) in text.chars().enumerate() {
        if k == max {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// `text` with every control character but the line break escaped (`\u{1b}`, `\u{7}`): a name,
/// id or value echoed in a message can neither set a terminal's title nor clear its screen.
pub fn escape_controls(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(|c| c.is_control() && c != '\n') {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() && c != '\n' {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

/// `message` for an error line: when it is longer than `4 × max` characters, every quoted piece
/// (`'…'`) longer than `max` becomes an excerpt of `max` characters and the whole at most `20 ×
/// max` characters. An error that quotes a 10 MB edge, a 1 MB input name or a path of a million
/// characters says a short excerpt, not all of it; short messages stay as they are.
pub fn short_quotes(message: &str, max: usize) -> String {
    if message.chars().nth(4 * max).is_none() {
        return message.to_string();
    }
    let mut out = String::new();
    for (k, piece) in message.split('\'').enumerate() {
        if k > 0 {
            out.push('\'');
        }
        if k % 2 == 1 && piece.chars().nth(max).is_some() {
            out.push_str(&excerpt(piece, max));
        } else {
            out.push_str(piece);
        }
    }
    if out.chars().nth(20 * max).is_some() {
        excerpt(&out, 20 * max)
    } else {
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_quotes_are_cut_and_short_messages_kept() {
        let short = "unknown input 'x' for math.add\nvalid: a, b";
        assert_eq!(short_quotes(short, 60), short);
        // Lines of a longer message stay lines.
        let lines = format!("{}\nUsage: cnets run", "a ".repeat(200));
        assert_eq!(short_quotes(&lines, 60), lines);
        let long = format!("unknown input '{}' for math.add", "k".repeat(1_000_000));
        let cut = short_quotes(&long, 60);
        assert_eq!(
            cut,
            format!("unknown input '{}…' for math.add", "k".repeat(60))
        );
        let unquoted = "p".repeat(1_000_000) + " is outside";
        assert_eq!(short_quotes(&unquoted, 60).chars().count(), 1201);
    }

    #[test]
    fn control_characters_are_escaped_in_messages() {
        assert_eq!(
            escape_controls("node 'a\u{1b}]0;PWNED\u{7}\u{1b}[2J': bad\nnext"),
            "node 'a\\u{1b}]0;PWNED\\u{7}\\u{1b}[2J': bad\nnext"
        );
        assert!(matches!(
            escape_controls("plain"),
            std::borrow::Cow::Borrowed(_)
        ));
    }

    #[test]
    fn excerpts_are_short_and_escaped() {
        assert_eq!(
            excerpt("root:x:0:0:root:/root:/bin/bash", 10),
            "root:x:0:0…"
        );
        assert_eq!(excerpt("a\nb\0", 10), "a\\nb\\u{0}");
        assert_eq!(excerpt("short", 10), "short");
    }

    #[test]
    fn a_refused_read_names_its_file() {
        let e = FileError::NotAllowed {
            path: PathBuf::from("/data/site plan.svg"),
            allowed: "/work/graphs".into(),
        };
        let message = format!("cannot read '../site plan.svg': {e}");
        assert_eq!(
            refused_read(&message),
            Some(PathBuf::from("/data/site plan.svg"))
        );
        assert_eq!(
            refused_read(&e.to_string()),
            Some(PathBuf::from("/data/site plan.svg"))
        );
        assert_eq!(refused_read("cannot read 'x.svg': no such file"), None);
    }
}
