//! The simulation's files form a pipeline, not a web: no file in `src/sim` imports, directly or
//! through others (re-exports included), a file that imports it back; and the core never
//! imports the JavaScript bindings.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module path under `crate::sim` (e.g. `["network", "server"]`) for each file.
fn modules(root: &Path) -> BTreeMap<Vec<String>, PathBuf> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            if p.extension().and_then(|e| e.to_str()) != Some("rs") {
                continue;
            }
            let rel = p.strip_prefix(root).unwrap();
            let mut segs: Vec<String> = rel
                .iter()
                .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
                .collect();
            if segs.last().map(String::as_str) == Some("mod") {
                segs.pop();
            }
            out.insert(segs, p);
        }
    }
    out
}

/// Source without comments and string literals (enough to find paths).
fn code(text: &str) -> String {
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Expands `a::{b, c::{d, e}}` into `a::b`, `a::c::d`, `a::c::e`.
fn expand(path: &str) -> Vec<String> {
    let path: String = path.chars().filter(|c| !c.is_whitespace()).collect();
    let Some(open) = path.find('{') else {
        return vec![path];
    };
    let prefix = &path[..open];
    let inner = &path[open + 1..path.len() - 1];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty() && *p != "self")
        .flat_map(|p| expand(&format!("{prefix}{p}")))
        .collect()
}

/// Every path a file names that starts with `super::`, `self::` or `crate::sim::`.
fn paths(text: &str) -> Vec<String> {
    let text = code(text);
    let mut out = Vec::new();
    // `use` statements, braces and all.
    for stmt in text.split(';') {
        if let Some(i) = stmt.find("use ") {
            let body = stmt[i + 4..].trim();
            if body.starts_with("super::") || body.starts_with("crate::sim::") {
                out.extend(expand(body.split(" as ").next().unwrap_or(body)));
            }
        }
    }
    // Paths written out in code.
    for start in ["super::", "crate::sim::"] {
        for (i, _) in text.match_indices(start) {
            let rest: String = text[i..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            out.push(rest.trim_end_matches(':').to_string());
        }
    }
    out
}

struct Graph {
    files: BTreeMap<Vec<String>, PathBuf>,
    text: BTreeMap<Vec<String>, String>,
}

impl Graph {
    /// The file that defines `item` when named in module `module`: a child module's file, or
    /// through a `pub use` re-export, or the module's own file.
    fn resolve(&self, module: &[String], rest: &[String], depth: usize) -> Option<Vec<String>> {
        if depth > 16 {
            return None;
        }
        let Some(first) = rest.first() else {
            return Some(module.to_vec());
        };
        if first == "*" {
            return None;
        }
        let mut child = module.to_vec();
        child.push(first.clone());
        if self.files.contains_key(&child) {
            return self.resolve(&child, &rest[1..], depth + 1);
        }
        // A re-export in this module's file?
        let text = self.text.get(module)?;
        for stmt in code(text).split(';') {
            let Some(i) = stmt.find("pub use ") else {
                continue;
            };
            for p in expand(stmt[i + 8..].trim()) {
                let segs: Vec<String> = p.split("::").map(String::from).collect();
                if segs.last() == Some(first) {
                    if let Some(target) = self.absolute(module, &segs) {
                        return self.resolve(&[], &target, depth + 1);
                    }
                }
            }
        }
        Some(module.to_vec())
    }

    /// A path written in module `module` as one relative to `crate::sim`, if it is one.
    fn absolute(&self, module: &[String], segs: &[String]) -> Option<Vec<String>> {
        let is_dir = self
            .files
            .get(module)
            .is_some_and(|p| p.ends_with("mod.rs"))
            || module.is_empty();
        match segs.first().map(String::as_str) {
            Some("crate") if segs.get(1).map(String::as_str) == Some("sim") => {
                Some(segs[2..].to_vec())
            }
            Some("super") => {
                // `super` of a file `a/b.rs` is `a`; of `a/b/mod.rs` it is `a` too.
                let mut base = module.to_vec();
                if is_dir || !module.is_empty() {
                    base.pop();
                }
                let mut rest = &segs[1..];
                while rest.first().map(String::as_str) == Some("super") {
                    base.pop();
                    rest = &rest[1..];
                }
                let mut out = base;
                out.extend_from_slice(rest);
                Some(out)
            }
            Some("self") => {
                let mut out = module.to_vec();
                out.extend_from_slice(&segs[1..]);
                Some(out)
            }
            Some(first)
                if is_dir
                    && self
                        .files
                        .contains_key(&[module, &[first.to_string()]].concat()) =>
            {
                Some([module, segs].concat())
            }
            _ => None,
        }
    }
}

#[test]
fn no_file_in_sim_imports_a_file_that_imports_it_back() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/sim");
    let files = modules(&root);
    let text: BTreeMap<Vec<String>, String> = files
        .iter()
        .map(|(m, p)| (m.clone(), std::fs::read_to_string(p).unwrap()))
        .collect();
    let g = Graph { files, text };
    let mut edges: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    for (module, text) in &g.text {
        // A module's `#[cfg(test)] mod tests` may use `super::*`: not a dependency.
        let body = text.split("#[cfg(test)]").next().unwrap_or(text);
        for p in paths(body) {
            let segs: Vec<String> = p.split("::").map(String::from).collect();
            let Some(abs) = g.absolute(module, &segs) else {
                continue;
            };
            if let Some(target) = g.resolve(&[], &abs, 0) {
                // The parent module (mod.rs) declares and re-exports its children: that is
                // the parent's own edge, not the child's.
                if &target != module && !module.starts_with(&target) {
                    edges.entry(module.clone()).or_default().insert(target);
                }
            }
        }
    }
    // Any file reachable from one of its own targets is in a cycle.
    let mut cycles = Vec::new();
    for (from, targets) in &edges {
        for t in targets {
            let mut seen = BTreeSet::new();
            let mut stack = vec![t.clone()];
            while let Some(m) = stack.pop() {
                if &m == from {
                    cycles.push(format!(
                        "{} -> {} -> ... -> {}",
                        from.join("/"),
                        t.join("/"),
                        from.join("/")
                    ));
                    break;
                }
                if seen.insert(m.clone()) {
                    stack.extend(edges.get(&m).into_iter().flatten().cloned());
                }
            }
        }
    }
    assert!(
        cycles.is_empty(),
        "import cycles in src/sim:\n{}",
        cycles.join("\n")
    );
    assert!(
        edges.len() > 10,
        "the scan found the files' imports ({} files with edges)",
        edges.len()
    );
}

#[test]
fn the_core_never_imports_the_javascript_bindings() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut stack = vec![root.clone()];
    let mut checked = 0;
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                if !p.ends_with("bin") {
                    stack.push(p);
                }
                continue;
            }
            if p.ends_with("wasm.rs") || p.extension().and_then(|e| e.to_str()) != Some("rs") {
                continue;
            }
            let text = code(&std::fs::read_to_string(&p).unwrap());
            for banned in ["wasm_bindgen", "js_sys", "crate::wasm"] {
                assert!(!text.contains(banned), "{} names {banned}", p.display());
            }
            checked += 1;
        }
    }
    assert!(checked > 50);
}
