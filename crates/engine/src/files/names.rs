//! Export names, checked by name before any file is touched.

use super::FileError;

/// The most components (folders and the file) an export name may have.
pub const MAX_COMPONENTS: usize = 16;

/// The longest export name, in bytes.
pub const MAX_NAME_BYTES: usize = 1024;

/// The longest folder or file name, in bytes (the file systems' limit).
pub const MAX_COMPONENT_BYTES: usize = 255;

/// The folder components and file name of an export name written relative to the output
/// directory (`parts/left.obj` → `["parts", "left.obj"]`). Refused: an empty name, control
/// characters (a newline, NUL…), a root or drive, backslashes, `.`, `..` or empty components, more
/// than [`MAX_COMPONENTS`] components, a name over [`MAX_NAME_BYTES`] or a component over
/// [`MAX_COMPONENT_BYTES`] bytes. The error quotes at most the name's first 60 characters.
pub fn check_export_name(name: &str) -> Result<Vec<&str>, FileError> {
    let bad = |why| {
        Err(FileError::BadName(
            format!("\"{}\"", super::excerpt(name, 60)),
            why,
        ))
    };
    if name.trim().is_empty() {
        return bad("is empty");
    }

    if name.chars().any(char::is_control) {
        return bad("contains a control character");
    }
    if name.starts_with('/') || name.contains('\\') || name.get(1..2) == Some(":") {
        return bad("must be a relative path inside the output directory (no root, drive or '\\')");
    }
    let parts: Vec<&str> = name.split('/').collect();
    if parts.len() > MAX_COMPONENTS {
        return bad("has more than 16 folders and file name");
    }
    if name.len() > MAX_NAME_BYTES {
        return bad("is longer than 1024 bytes");
    }
    for part in &parts {
        match *part {
            "" => return bad("has an empty folder or file name"),
            "." | ".." => {
                return bad(
                    "may not contain '.' or '..': it names a file inside the output directory",
                );
            }
            p if p.trim().is_empty() => return bad("has a blank folder or file name"),
            p if p.len() > MAX_COMPONENT_BYTES => {
                return bad("has a folder or file name longer than 255 bytes");
            }
            _ => {}
        }
    }
    Ok(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn good_names_split_into_components() {
        assert_eq!(check_export_name("a.obj").unwrap(), vec!["a.obj"]);
        assert_eq!(
            check_export_name("parts/left.obj").unwrap(),
            vec!["parts", "left.obj"]
        );
    }

    #[test]
    fn bad_names_are_refused_by_name() {
        for name in [
            "",
            " ",
            ".",
            "..",
            "../x.obj",
            "a/../b",
            "/etc/passwd",
            "a//b",
            "a\nb",
            "a\0b",
            "./a",
            "a/.",
            "c:x",
            "a\\b",
            "\u{7}",
        ] {
            assert!(check_export_name(name).is_err(), "{name:?} accepted");
        }
    }

    #[test]
    fn names_are_bounded_in_depth_and_length() {
        let deep = vec!["d"; 30_000].join("/");
        let e = check_export_name(&deep).unwrap_err().to_string();
        assert!(e.contains("more than 16 folders"), "{e}");
        assert!(e.len() < 200, "the error quotes an excerpt: {e}");
        assert_eq!(
            check_export_name(&vec!["d"; 16].join("/")).unwrap().len(),
            16
        );
        assert!(check_export_name(&vec!["d"; 17].join("/")).is_err());
        assert!(check_export_name(&"x".repeat(256)).is_err());
        assert!(check_export_name(&"x".repeat(255)).is_ok());
        assert!(check_export_name(&vec!["x".repeat(200); 6].join("/")).is_err());
    }
}
