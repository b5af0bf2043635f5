//! The browser's files: on the web (wasm32) there is no file system, so the files a node may read
//! are those the designer opened or dropped on the page ([`provide`]), held in memory, and the
//! files an export writes are kept in memory until the page hands them to the browser as downloads
//! ([`take_written`]).
//!
//! The native build never uses this store: reads and writes go to the file system
//! ([`super::read`], [`super::write`]). It is plain Rust, compiled (and tested) on every target.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard};

#[derive(Default)]
struct Store {
    /// Uploaded files by the name the designer's file had (no folders).
    uploads: BTreeMap<String, Arc<[u8]>>,
    /// Files written by exports since the last [`take_written`], in order.
    written: Vec<(PathBuf, Vec<u8>)>,
}

static STORE: Mutex<Option<Store>> = Mutex::new(None);

fn store() -> MutexGuard<'static, Option<Store>> {
    STORE.lock().unwrap_or_else(|p| p.into_inner())
}

fn file_name(path: &Path) -> Option<String> {
    path.file_name().map(|n| n.to_string_lossy().into_owned())
}

/// Makes a file the designer opened or dropped readable by nodes under its file name: a node
/// reading `profiles/hull.csv` or `/any/folder/hull.csv` gets the upload named `hull.csv`.
/// A second upload of the same name replaces the first.
pub fn provide(name: &str, bytes: Vec<u8>) {
    let key = file_name(Path::new(name)).unwrap_or_else(|| name.to_string());
    store()
        .get_or_insert_with(Store::default)
        .uploads
        .insert(key, bytes.into());
}

/// The names of the uploaded files, sorted.
pub fn provided() -> Vec<String> {
    store()
        .as_ref()
        .map(|s| s.uploads.keys().cloned().collect())
        .unwrap_or_default()
}

/// The bytes of the upload that `path` names (by its file name), if there is one.
pub fn read(path: &Path) -> Option<Arc<[u8]>> {
    let name = file_name(path)?;
    store().as_ref()?.uploads.get(&name).cloned()
}

/// Keeps `bytes` as the file `folders/file` inside `out_dir` (an export); returns its path.
pub fn write(out_dir: &Path, folders: &[&str], file: &str, bytes: &[u8]) -> PathBuf {
    let mut path = out_dir.to_path_buf();
    path.extend(folders);
    path.push(file);
    store()
        .get_or_insert_with(Store::default)
        .written
        .push((path.clone(), bytes.to_vec()));
    path
}

/// The files written since the last call (the page offers each as a download), oldest first.
pub fn take_written() -> Vec<(PathBuf, Vec<u8>)> {
    store()
        .as_mut()
        .map(|s| std::mem::take(&mut s.written))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uploads_are_read_by_file_name_and_writes_are_taken_once() {
        provide("/home/me/hull-memory-test.csv", b"1,2,3\n".to_vec());
        assert!(provided().contains(&"hull-memory-test.csv".to_string()));
        let got = read(Path::new("profiles/hull-memory-test.csv")).unwrap();
        assert_eq!(&*got, b"1,2,3\n");
        assert!(read(Path::new("other-memory-test.csv")).is_none());
        provide("hull-memory-test.csv", b"4".to_vec());
        assert_eq!(&*read(Path::new("hull-memory-test.csv")).unwrap(), b"4");

        let p = write(
            Path::new("/out"),
            &["a"],
            "net-memory-test.obj",
            b"v 0 0 0\n",
        );
        assert_eq!(p, PathBuf::from("/out/a/net-memory-test.obj"));
        let taken = take_written();
        assert!(taken.contains(&(p, b"v 0 0 0\n".to_vec())));
        assert!(
            !take_written()
                .iter()
                .any(|(p, _)| p.ends_with("net-memory-test.obj"))
        );
    }
}
