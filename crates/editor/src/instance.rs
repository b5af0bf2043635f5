//! One window per settings folder: `cnets-editor FILE` started while a window is open hands the
//! file to that window (over a Unix socket `editor.sock` in the settings folder) instead of
//! starting a second editor that would share its recovery file. The window opens it through the
//! unsaved-changes guard like any other open.

#[cfg(unix)]
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::Receiver;
#[cfg(unix)]
use std::sync::mpsc::channel;

/// The socket file in the settings folder.
pub fn socket_path(config_dir: &Path) -> PathBuf {
    config_dir.join("editor.sock")
}

/// Sends `file` (made absolute) to the window listening on the settings folder's socket;
/// returns whether a window took it.
#[cfg(unix)]
pub fn hand_over(config_dir: &Path, file: &Path) -> bool {
    let Ok(mut stream) = std::os::unix::net::UnixStream::connect(socket_path(config_dir)) else {
        return false;
    };
    let file = std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf());
    writeln!(stream, "{}", file.display()).is_ok() && stream.flush().is_ok()
}

/// Listens on the settings folder's socket (a stale one left by a killed window is replaced);
/// every path received is sent on the returned channel and `wake` is called.
#[cfg(unix)]
pub fn listen(config_dir: &Path, wake: Arc<dyn Fn() + Send + Sync>) -> Option<Receiver<PathBuf>> {
    use std::os::unix::net::{UnixListener, UnixStream};
    let sock = socket_path(config_dir);
    std::fs::create_dir_all(config_dir).ok()?;
    if UnixStream::connect(&sock).is_err() {
        // Nobody answers: a socket file left behind by a window that was killed.
        let _ = std::fs::remove_file(&sock);
    }
    let listener = UnixListener::bind(&sock).ok()?;
    let (tx, rx) = channel();
    std::thread::Builder::new()
        .name("cnets-editor-instance".into())
        .spawn(move || {
            for stream in listener.incoming().flatten() {
                for line in BufReader::new(stream).lines().map_while(Result::ok) {
                    let line = line.trim();
                    if line.is_empty() {
                        continue;
                    }
                    if tx.send(PathBuf::from(line)).is_err() {
                        return;
                    }
                    wake();
                }
            }
        })
        .ok()?;
    Some(rx)
}

/// Without Unix sockets every start is a window of its own.
#[cfg(not(unix))]
pub fn hand_over(_config_dir: &Path, _file: &Path) -> bool {
    false
}

/// Without Unix sockets every start is a window of its own.
#[cfg(not(unix))]
pub fn listen(_config_dir: &Path, _wake: Arc<dyn Fn() + Send + Sync>) -> Option<Receiver<PathBuf>> {
    None
}

/// Removes the socket file (the window is closing normally).
pub fn release(config_dir: &Path) {
    let _ = std::fs::remove_file(socket_path(config_dir));
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn a_second_start_hands_its_file_to_the_window() {
        let dir = std::env::temp_dir().join(format!("cnets-instance-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        assert!(!hand_over(&dir, Path::new("a.ron")), "no window yet");
        // A stale socket file (a killed window) does not stop a new window from listening.
        std::fs::write(socket_path(&dir), b"").unwrap();
        let rx = listen(&dir, Arc::new(|| {})).expect("listening");
        assert!(hand_over(&dir, Path::new("/g/bridge.ron")));
        let got = rx.recv_timeout(Duration::from_secs(30)).unwrap();
        assert_eq!(got, PathBuf::from("/g/bridge.ron"));
        assert!(hand_over(&dir, Path::new("rel.ron")));
        let got = rx.recv_timeout(Duration::from_secs(30)).unwrap();
        assert!(got.is_absolute() && got.ends_with("rel.ron"), "{got:?}");
        release(&dir);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
