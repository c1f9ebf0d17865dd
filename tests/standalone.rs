//! The repository stands alone: a fresh clone has every file its README and docs point to, and no
//! document points outside the repository (to a sibling folder, an absolute path on a developer's
//! machine, or the project's shared folder).

use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        let name = entry.file_name().to_string_lossy().into_owned();
        if path.is_dir() {
            if !name.starts_with('.') && name != "target" {
                markdown_files(&path, out);
            }
        } else if name.ends_with(".md") {
            out.push(path);
        }
    }
}

/// Relative link targets of a markdown text: `[text](target)` with no scheme and no anchor-only target.
fn relative_links(text: &str) -> Vec<String> {
    let mut links = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        let Some(end) = rest.find(')') else { break };
        let target = rest[..end].split('#').next().unwrap_or("").trim().to_string();
        if !target.is_empty() && !target.contains("://") && !target.starts_with("mailto:") && !target.contains(' ') {
            links.push(target);
        }
    }
    links
}

#[test]
fn no_document_points_outside_the_repository() {
    let root = repo_root();
    let mut files = Vec::new();
    for dir in ["docs", "data", "scenarios", "crates", "benches", "scripts"] {
        if root.join(dir).is_dir() {
            markdown_files(&root.join(dir), &mut files);
        }
    }
    files.push(root.join("README.md"));
    assert!(files.len() >= 8, "found only {} markdown files under {}", files.len(), root.display());
    let mut problems = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        let shown = file.strip_prefix(&root).unwrap_or(file).display().to_string();
        for (n, line) in text.lines().enumerate() {
            for bad in ["../shared", "shared/paper", "shared/data", "design.md", "/work/"] {
                if line.contains(bad) {
                    problems.push(format!("{shown}:{}: mentions {bad:?}: {line}", n + 1));
                }
            }
        }
        for link in relative_links(&text) {
            let target = file.parent().unwrap().join(&link);
            match target.canonicalize() {
                Ok(t) if t.starts_with(&root) => {}
                Ok(t) => problems.push(format!("{shown}: link {link:?} leaves the repository ({})", t.display())),
                Err(_) => problems.push(format!("{shown}: link {link:?} points to nothing")),
            }
        }
    }
    assert!(problems.is_empty(), "documents that do not stand alone:\n{}", problems.join("\n"));
}

#[test]
fn the_link_finder_finds_links() {
    let links = relative_links("see [a](docs/a.md#x), [web](https://e.org) and [up](../../shared/p.md)");
    assert_eq!(links, vec!["docs/a.md".to_string(), "../../shared/p.md".to_string()]);
}
