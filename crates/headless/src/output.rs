//! Writing to stdout and stderr without panicking: `println!` panics when stdout is a closed pipe
//! (`cnets nodes | head`) or a full disk (`> /dev/full`), `eprintln!` when stderr is. [`outln!`]
//! and [`out!`] return the write error to the command instead (`?` turns it into a [`Failure`]): a
//! broken pipe ends the program quietly, as other command-line tools do; any other error is one
//! line and exit 2. [`errln!`] writes a line to stderr and ignores a failure (there is nowhere left
//! to report it): the exit code still tells.

use std::io::{self, Write};

use crate::failure::Failure;

/// Writes formatted text to stdout.
pub fn text(args: std::fmt::Arguments<'_>) -> Result<(), Failure> {
    io::stdout().lock().write_fmt(args).map_err(Failure::from)
}

/// Writes formatted text and a newline to stdout.
pub fn line(args: std::fmt::Arguments<'_>) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    out.write_fmt(args)
        .and_then(|()| out.write_all(b"\n"))
        .map_err(Failure::from)
}

/// Writes `value` as compact JSON and a newline to stdout, streamed through a buffer (no JSON
/// tree is built: the output of a large result takes little more memory than the result).
pub fn json_line<T: serde::Serialize + ?Sized>(value: &T) -> Result<(), Failure> {
    let mut out = io::BufWriter::with_capacity(1 << 16, io::stdout().lock());
    serde_json::to_writer(&mut out, value).map_err(|e| match e.io_error_kind() {
        Some(kind) => Failure::from(io::Error::new(kind, e.to_string())),
        None => Failure::usage(format!("cannot write the output: {e}")),
    })?;
    out.write_all(b"\n")
        .and_then(|()| out.flush())
        .map_err(Failure::from)
}

/// Writes formatted text and a newline to stderr; a failure to write is ignored. A line that
/// quotes a long input (a 1 MB input name, a path of a million characters) says a short excerpt
/// of it (`files::short_quotes`: quoted pieces over 200 characters, the line at most 4 000), and
/// control characters escaped (`files::escape_controls`).
pub fn error_line(args: std::fmt::Arguments<'_>) {
    let line = std::fmt::format(args);
    let line = cnets_engine::files::short_quotes(&line, 200);
    // Names and values echoed in a message never reach the terminal as control sequences.
    let line = cnets_engine::files::escape_controls(&line);
    let mut err = io::stderr().lock();
    let _ = err
        .write_all(line.as_bytes())
        .and_then(|()| err.write_all(b"\n"));
}

/// Flushes stdout (the end of every command), so a late write error is reported too.
pub fn flush() -> Result<(), Failure> {
    io::stdout().lock().flush().map_err(Failure::from)
}

/// `println!` that returns write errors to the calling command (which must return a
/// `Result<_, Failure>`).
#[macro_export]
macro_rules! outln {
    ($($t:tt)*) => {
        $crate::output::line(format_args!($($t)*))?
    };
}

/// `eprintln!` that never panics (a write error on stderr is ignored).
#[macro_export]
macro_rules! errln {
    ($($t:tt)*) => {
        $crate::output::error_line(format_args!($($t)*))
    };
}

/// `print!` that returns write errors to the calling command.
#[macro_export]
macro_rules! out {
    ($($t:tt)*) => {
        $crate::output::text(format_args!($($t)*))?
    };
}
