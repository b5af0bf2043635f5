//! The user documentation holds together: every relative link of README.md, CHANGELOG.md and
//! docs/**/*.md points to a file that exists and, for an anchor into a Markdown file, to one of its
//! headings (GitHub's slugs); README.md stays under 12 KB; and the user documentation names no
//! issue numbers (they belong in CHANGELOG.md and docs/internals/).

use std::collections::HashSet;
use std::fs;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// README.md, CHANGELOG.md and every Markdown file under docs/, sorted.
fn documents(root: &Path) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    for name in ["README.md", "CHANGELOG.md"] {
        let path = root.join(name);
        if path.exists() {
            out.push(path);
        }
    }
    walk(&root.join("docs"), &mut out);
    out.sort();
    out
}

/// The lines outside fenced code blocks, with their line numbers.
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fence: Option<&str> = None;
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let marker = if trimmed.starts_with("```") {
            Some("```")
        } else if trimmed.starts_with("~~~") {
            Some("~~~")
        } else {
            None
        };
        match (fence, marker) {
            (None, Some(m)) => fence = Some(m),
            (Some(f), Some(m)) if f == m => fence = None,
            (None, None) => out.push((k + 1, line)),
            _ => {}
        }
    }
    out
}

/// A line without its inline code spans.
fn without_code_spans(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find('`') {
        out.push_str(&rest[..start]);
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let after = &rest[start + ticks..];
        match after.find(&"`".repeat(ticks)) {
            Some(end) => rest = &after[end + ticks..],
            None => {
                out.push_str(&rest[start..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// GitHub's anchor of a heading's text: lower case, punctuation other than `-` and `_` dropped,
/// spaces made hyphens.
fn slug(heading: &str) -> String {
    // Link text only: [text](target) → text.
    let mut text = String::new();
    let mut rest = heading;
    while let Some(open) = rest.find('[') {
        text.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        match (after.find("]("), after.find(')')) {
            (Some(close), Some(end)) if close < end => {
                text.push_str(&after[..close]);
                rest = &after[end + 1..];
            }
            _ => {
                text.push('[');
                rest = after;
            }
        }
    }
    text.push_str(rest);
    text.trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| {
            if c == ' ' {
                Some('-')
            } else if c.is_alphanumeric() || c == '-' || c == '_' {
                Some(c)
            } else {
                None
            }
        })
        .collect()
}

/// The anchors of a Markdown file's headings (a repeated slug gets -1, -2 … as on GitHub).
fn anchors(text: &str) -> HashSet<String> {
    let mut seen = HashSet::new();
    for (_, line) in prose_lines(text) {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = slug(line[hashes..].trim().trim_end_matches('#'));
        let mut anchor = base.clone();
        let mut n = 0;
        while seen.contains(&anchor) {
            n += 1;
            anchor = format!("{base}-{n}");
        }
        seen.insert(anchor);
    }
    seen
}

/// The targets of the inline links and images of a line: `](target)` and `](target "title")`.
fn link_targets(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let Some(end) = after.find(')') else { break };
        let target = after[..end].split_whitespace().next().unwrap_or("");
        let target = target.trim_start_matches('<').trim_end_matches('>');
        if !target.is_empty() {
            out.push(target.to_string());
        }
        rest = &after[end..];
    }
    out
}

/// Every broken relative link of the given documents, as `file:line: message`.
fn broken_links(root: &Path, docs: &[PathBuf]) -> Vec<String> {
    let mut broken = Vec::new();
    for doc in docs {
        let text = fs::read_to_string(doc).unwrap();
        let name = doc.strip_prefix(root).unwrap_or(doc).display().to_string();
        for (line_no, line) in prose_lines(&text) {
            for target in link_targets(&without_code_spans(line)) {
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                let (path, anchor) = match target.split_once('#') {
                    Some((p, a)) => (p, Some(a)),
                    None => (target.as_str(), None),
                };
                let file = if path.is_empty() {
                    doc.clone()
                } else {
                    doc.parent().unwrap().join(path.replace("%20", " "))
                };
                if !file.exists() {
                    broken.push(format!("{name}:{line_no}: {target}: no such file"));
                    continue;
                }
                if let Some(anchor) = anchor
                    && file.extension().is_some_and(|e| e == "md")
                    && !anchors(&fs::read_to_string(&file).unwrap())
                        .contains(&anchor.to_lowercase())
                {
                    broken.push(format!("{name}:{line_no}: {target}: no heading #{anchor}"));
                }
            }
        }
    }
    broken
}

/// Lines naming an issue number (`issue 17`), outside CHANGELOG.md and docs/internals/.
fn issue_numbers(root: &Path, docs: &[PathBuf]) -> Vec<String> {
    let mut found = Vec::new();
    for doc in docs {
        let rel = doc.strip_prefix(root).unwrap_or(doc);
        if rel == Path::new("CHANGELOG.md") || rel.starts_with("docs/internals") {
            continue;
        }
        let text = fs::read_to_string(doc).unwrap();
        for (k, line) in text.lines().enumerate() {
            let hit = line.match_indices("issue ").any(|(at, _)| {
                line[at + "issue ".len()..].starts_with(|c: char| c.is_ascii_digit())
            });
            if hit {
                found.push(format!("{}:{}: {}", rel.display(), k + 1, line.trim()));
            }
        }
    }
    found
}

#[test]
fn every_relative_link_of_the_docs_resolves() {
    let root = repo();
    let docs = documents(&root);
    assert!(docs.len() > 10, "found only {docs:?}");
    let broken = broken_links(&root, &docs);
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_readme_is_a_front_door_under_12_kb() {
    let size = fs::metadata(repo().join("README.md")).unwrap().len();
    assert!(size < 12 * 1024, "README.md is {size} bytes, over 12 KB");
}

#[test]
fn user_docs_name_no_issue_numbers() {
    let root = repo();
    let found = issue_numbers(&root, &documents(&root));
    assert!(
        found.is_empty(),
        "issue numbers outside CHANGELOG.md and docs/internals/:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_checks_catch_a_broken_link_a_missing_heading_and_an_issue_number() {
    let root = std::env::temp_dir().join(format!("cnets-docs-links-{}", std::process::id()));
    let _ = fs::remove_dir_all(&root);
    fs::create_dir_all(root.join("docs/internals")).unwrap();
    fs::write(
        root.join("README.md"),
        "# Title\n\nSee [a](docs/a.md#the-first-part), [b](docs/missing.md), [c](docs/a.md#nothing), \
         [d](#title), [e](https://example.com/x) and `[f](not/checked.md)`.\n\n\
         ```sh\n[g](inside/a/block.md)\n```\n",
    )
    .unwrap();
    fs::write(
        root.join("docs/a.md"),
        "# A\n\n## The first part\n\nFixed in issue 12.\n",
    )
    .unwrap();
    fs::write(
        root.join("docs/internals/notes.md"),
        "# Notes\n\nissue 12 measured it.\n",
    )
    .unwrap();
    let docs = documents(&root);
    let broken = broken_links(&root, &docs);
    let issues = issue_numbers(&root, &docs);
    fs::remove_dir_all(&root).unwrap();
    assert_eq!(
        broken,
        [
            "README.md:3: docs/missing.md: no such file",
            "README.md:3: docs/a.md#nothing: no heading #nothing",
        ],
    );
    assert_eq!(issues, ["docs/a.md:5: Fixed in issue 12."]);
}

#[test]
fn slugs_follow_github() {
    assert_eq!(
        slug("Drawing and editing in the 3D view"),
        "drawing-and-editing-in-the-3d-view"
    );
    assert_eq!(
        slug("Timing targets (1000 × 1000, 2 cores)"),
        "timing-targets-1000--1000-2-cores"
    );
    assert_eq!(slug("The `cnets` command line"), "the-cnets-command-line");
    assert_eq!(
        slug("Python, Rhino, Grasshopper (Hops) and Dask"),
        "python-rhino-grasshopper-hops-and-dask"
    );
}
