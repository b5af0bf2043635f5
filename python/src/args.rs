//! Arguments of the Python API read by hand: every argument of the wrong kind is a `CnetsError`
//! naming the argument and saying what was expected (pyo3's own extraction would raise a
//! `TypeError` naming the Rust parameter).

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyInt, PyList, PyString, PyTuple};

use crate::error;

/// A short description of a Python value for messages: its type and, for small values, its repr
/// (`a str ('abc')`, `None`, `a list of 2 items`).
pub fn describe(obj: &Bound<'_, PyAny>) -> String {
    if obj.is_none() {
        return "None".to_string();
    }
    let ty = obj
        .get_type()
        .name()
        .map_or_else(|_| "value".to_string(), |n| n.to_string());
    if let Ok(n) = obj.len()
        && (obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>())
    {
        return format!("a {ty} of {n} item{}", if n == 1 { "" } else { "s" });
    }
    let repr = obj.repr().map(|r| r.to_string()).unwrap_or_default();
    let article = if ty.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    if repr.is_empty() || repr.chars().count() > 40 {
        format!("{article} {ty}")
    } else {
        format!("{article} {ty} ({repr})")
    }
}

/// A `str` argument.
pub fn text(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    if obj.is_instance_of::<PyString>() {
        return obj.extract::<String>();
    }
    Err(error(format!(
        "{name}: expected a str, got {}",
        describe(obj)
    )))
}

/// Strings: one `str`, or a list or tuple of them; `None` (or a missing argument) is `None`.
pub fn texts(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<Vec<String>>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    if obj.is_instance_of::<PyString>() {
        return Ok(Some(vec![obj.extract()?]));
    }
    let items = sequence(obj, name, "a str or a list of str")?;
    items
        .iter()
        .enumerate()
        .map(|(k, item)| text(item, &format!("{name}[{k}]")))
        .collect::<PyResult<Vec<_>>>()
        .map(Some)
}

/// The items of a list or tuple (any other iterable is refused: a str or a dict would be read
/// character by character or key by key).
fn sequence<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    expected: &str,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        return obj.try_iter()?.collect();
    }
    Err(error(format!(
        "{name}: expected {expected}, got {}",
        describe(obj)
    )))
}

/// A path: a `str` or an `os.PathLike` (`pathlib.Path`).
pub fn path(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<PathBuf> {
    let bad = || {
        error(format!(
            "{name}: expected a path (a str or a pathlib.Path), got {}",
            describe(obj)
        ))
    };
    if obj.is_none() || obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyInt>() {
        return Err(bad());
    }
    let fspath = obj
        .py()
        .import("os")?
        .call_method1("fspath", (obj,))
        .map_err(|_| bad())?;
    let text = if let Ok(b) = fspath.cast::<PyBytes>() {
        String::from_utf8(b.as_bytes().to_vec())
            .map_err(|_| error(format!("{name}: the path is not valid UTF-8")))?
    } else {
        fspath.extract::<String>().map_err(|_| bad())?
    };
    if text.is_empty() {
        return Err(error(format!("{name}: the path is empty")));
    }
    if text.contains('\0') {
        return Err(error(format!("{name}: the path contains a NUL character")));
    }
    Ok(PathBuf::from(text))
}

/// An optional path (`None` is `None`).
pub fn opt_path(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<PathBuf>> {
    obj.filter(|o| !o.is_none())
        .map(|o| path(o, name))
        .transpose()
}

/// Folders: one path, or a list or tuple of them; `None` is none.
pub fn paths(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Vec<PathBuf>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(Vec::new());
    };
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        return obj
            .try_iter()?
            .enumerate()
            .map(|(k, item)| path(&item?, &format!("{name}[{k}]")))
            .collect();
    }
    Ok(vec![path(obj, name)?])
}

/// A `bool` (numpy's `bool_` too); numbers and other objects are refused rather than read by
/// their truth value.
pub fn flag(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<bool> {
    if obj.is_instance_of::<PyBool>() {
        return obj.extract();
    }
    let numpy_bool = obj
        .get_type()
        .name()
        .is_ok_and(|n| n == "bool" || n == "bool_");
    if numpy_bool && let Ok(b) = obj.call_method0("__bool__").and_then(|b| b.extract()) {
        return Ok(b);
    }
    Err(error(format!(
        "{name}: expected True or False, got {}",
        describe(obj)
    )))
}

/// A count: an `int` ≥ 0 (not a `bool`).
pub fn count(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    if obj.is_instance_of::<PyInt>()
        && !obj.is_instance_of::<PyBool>()
        && let Ok(n) = obj.extract::<usize>()
    {
        return Ok(n);
    }
    if obj.is_instance_of::<PyInt>() && !obj.is_instance_of::<PyBool>() {
        return Err(error(format!(
            "{name}: expected a count (an int ≥ 0), got {}",
            describe(obj)
        )));
    }
    Err(error(format!(
        "{name}: expected an int, got {}",
        describe(obj)
    )))
}
