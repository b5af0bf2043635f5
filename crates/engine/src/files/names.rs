//! Export names, checked by name before any file is touched.

use super::FileError;

/// The folder components and file name of an export name written relative to the output
/// directory (`parts/left.obj` → `["parts", "left.obj"]`). Refused: an empty name, control
/// characters (a newline, NUL…), a root or drive, backslashes, and `.`, `..` or empty components.
pub fn check_export_name(name: &str) -> Result<Vec<&str>, FileError> {
    let bad = |why| Err(FileError::BadName(format!("{name:?}"), why));
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
    for part in &parts {
        match *part {
            "" => return bad("has an empty folder or file name"),
            "." | ".." => {
                return bad(
                    "may not contain '.' or '..': it names a file inside the output directory",
                );
            }
            p if p.trim().is_empty() => return bad("has a blank folder or file name"),
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
}
