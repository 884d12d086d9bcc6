//! The architecture kept by tests, as `ARCHITECTURE.md` states it: in the crates built in layers, a
//! module imports only the layers below its own, no modules form a cycle, modules import what they use
//! from the module that holds it (not through the crate root's re-exports), and no comment anywhere names a
//! file that is not in the repository.
//!
//! An import is any `use` of, or path through, `crate::…`, `super::…`, `self::…` or (in a `mod.rs` or
//! `lib.rs`) a child module. It is resolved to the deepest module file it names; a name that a `mod.rs`
//! re-exports from a child (`pub use child::Name`) resolves to the child. Re-exports themselves, and the
//! `mod` lines that declare children, are a module's face and no import of it. Comments and string
//! literals other than serde's `with` paths are no imports.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The crates built in layers: each layer a top-level module (or several at one rank), lowest first. A
/// module may import its own layer's modules and any layer of a lower rank; the same rank is no lower.
const LAYERED: [(&str, &[(&str, u32)]); 2] = [
    (
        "crates/suspensions/src",
        &[
            ("description", 0),
            ("wheel", 1),
            ("file", 1),
            ("import", 2),
            ("assembly", 2),
            ("drawing", 2),
            ("document", 3),
            ("analysis", 4),
            ("check", 5),
            ("kc", 6),
            ("study", 7),
            ("full_vehicle", 7),
            ("design", 8),
            ("compare", 9),
        ],
    ),
    (
        "crates/solver/src",
        &[
            ("kkt", 0),
            ("dense_reference", 0),
            ("error", 1),
            ("redundancy", 1),
            ("assembly", 2),
            ("options", 2),
            ("mobility", 3),
            ("results", 3),
            ("replay", 4),
            ("solver", 5),
        ],
    ),
];

/// One module file: its path from the crate root (`["assembly", "rig"]`; `[]` for `lib.rs`) and its text.
#[derive(Debug)]
struct Module {
    path: Vec<String>,
    file: PathBuf,
    text: String,
}

/// An import found in a module: the line it is on and the path as written (`crate::assembly::rig::Rig`).
#[derive(Debug, Clone)]
struct Import {
    line: usize,
    path: Vec<String>,
    /// A `pub use` / `pub(crate) use`: a re-export, the module's face when in a `mod.rs` or `lib.rs`.
    reexport: bool,
}

/// The byte ranges of the inline modules (`mod tests { … }`) of code, where `super` names the file's own
/// module.
fn inline_modules(code: &str) -> Vec<std::ops::Range<usize>> {
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    let mut search = 0;
    while let Some(k) = code[search..].find("mod ") {
        let at = search + k;
        search = at + 4;
        if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_') {
            continue;
        }
        let rest = &code[at + 4..];
        let name_end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
        let after = rest[name_end..].trim_start();
        if name_end == 0 || !after.starts_with('{') {
            continue;
        }
        let open = at + 4 + name_end + (rest[name_end..].len() - after.len());
        let mut depth = 0;
        for (j, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        out.push(open..open + j);
                        break;
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// A path written inside an inline module, made the file's: its first `super` is the file itself.
fn from_inline(mut path: Vec<String>) -> Vec<String> {
    if path.first().is_some_and(|s| s == "super") {
        path[0] = "self".to_string();
    }
    path
}

use crate::workspace_root as repo_root;

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_dir() {
            if !matches!(name, "target" | ".git" | "node_modules" | ".venv" | "python-venv") {
                rust_files(&path, out);
            }
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
}

/// The module files of the crate whose source root is `src`.
fn modules(src: &Path) -> Vec<Module> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files
        .into_iter()
        .map(|file| {
            let relative = file.strip_prefix(src).expect("under the source root");
            let mut path: Vec<String> =
                relative.iter().map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string()).collect();
            if matches!(path.last().map(String::as_str), Some("mod" | "lib" | "main")) {
                path.pop();
            }
            let text = std::fs::read_to_string(&file).expect("a source file reads");
            Module { path, file, text }
        })
        .collect()
}

/// The text with comments blanked (line structure kept), and string literals blanked unless they hold a
/// path (serde's `with = "crate::…"`).
fn code_only(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < bytes.len() {
        let rest = &text[i..];
        if rest.starts_with("//") {
            let end = rest.find('\n').unwrap_or(rest.len());
            out.extend(std::iter::repeat_n(' ', rest[..end].chars().count()));
            i += end;
        } else if rest.starts_with("/*") {
            let end = rest.find("*/").map_or(rest.len(), |e| e + 2);
            out.extend(rest[..end].chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
            i += end;
        } else if rest.starts_with('"') {
            // A string literal, escapes stepped over.
            let mut j = 1;
            let b = rest.as_bytes();
            while j < b.len() && b[j] != b'"' {
                j += if b[j] == b'\\' { 2 } else { 1 };
            }
            let end = (j + 1).min(rest.len());
            let literal = &rest[..end];
            if literal.trim_matches('"').starts_with("crate::") {
                out.push_str(literal);
            } else {
                out.extend(literal.chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
            }
            i += end;
        } else if rest.starts_with('\'') && rest.len() > 2 && rest.as_bytes()[2] == b'\'' {
            // A character literal such as '"', which would open a string.
            out.push_str("   ");
            i += 3;
        } else if let Some(escaped) = rest.strip_prefix("'\\") {
            let end = escaped.find('\'').map_or(rest.len(), |e| e + 3);
            out.extend(std::iter::repeat_n(' ', rest[..end].chars().count()));
            i += end;
        } else {
            let c = rest.chars().next().expect("not at the end");
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// `a::{b, c::{d, e}}` expanded into `a::b`, `a::c::d`, `a::c::e` (`self` in a group names the group's
/// prefix; `as` renames are dropped).
fn expand(tree: &str) -> Vec<String> {
    let mut tree = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    for mark in ["{", "}", ",", "::"] {
        tree = tree.replace(&format!(" {mark}"), mark).replace(&format!("{mark} "), mark);
    }
    let Some(open) = tree.find('{') else {
        return vec![tree.split(" as ").next().unwrap_or("").to_string()];
    };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.len() - 1];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (k, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty())
        .flat_map(|p| {
            expand(p).into_iter().map(|q| {
                if q == "self" {
                    prefix.trim_end_matches("::").to_string()
                } else {
                    format!("{prefix}{q}")
                }
            })
        })
        .collect()
}

/// Every import of a module: its `use` statements and the paths written in its code.
fn imports(module: &Module, children: &BTreeSet<String>) -> Vec<Import> {
    let code = code_only(&module.text);
    let line_of = |offset: usize| code[..offset].matches('\n').count() + 1;
    let inline = inline_modules(&code);
    let place = |offset: usize, path: &str| -> Vec<String> {
        let path: Vec<String> = path.split("::").map(str::to_string).collect();
        if inline.iter().any(|r| r.contains(&offset)) {
            from_inline(path)
        } else {
            path
        }
    };
    let mut found = Vec::new();
    let mut covered = Vec::new();
    // `use` statements, possibly over several lines.
    let mut search = 0;
    while let Some(k) = code[search..].find("use ") {
        let at = search + k;
        search = at + 4;
        let before = &code[..at];
        let line_start = before.rfind('\n').map_or(0, |n| n + 1);
        let head = code[line_start..at].trim();
        let reexport = head.starts_with("pub");
        if !(head.is_empty() || head == "pub" || head.starts_with("pub(")) {
            continue;
        }
        if at > 0 && code[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let Some(end) = code[at..].find(';') else { continue };
        let tree = &code[at + 4..at + end];
        covered.push(at..at + end);
        for path in expand(tree) {
            found.push(Import { line: line_of(at), path: place(at, &path), reexport });
        }
    }
    // Paths in code: `crate::a::b`, `super::a`, and in a `mod.rs` a child's `child::item`.
    let bytes = code.as_bytes();
    let mut k = 0;
    while k < bytes.len() {
        let starts_word =
            k == 0 || !(bytes[k - 1].is_ascii_alphanumeric() || bytes[k - 1] == b'_' || bytes[k - 1] == b':');
        if starts_word && (bytes[k].is_ascii_alphabetic() || bytes[k] == b'_') {
            let mut e = k;
            while e < bytes.len() && (bytes[e].is_ascii_alphanumeric() || bytes[e] == b'_' || bytes[e] == b':') {
                e += 1;
            }
            let word = code[k..e].trim_end_matches(':');
            let first = word.split("::").next().unwrap_or("");
            let inside_use = covered.iter().any(|r| r.contains(&k));
            let is_path =
                word.contains("::") && (matches!(first, "crate" | "super" | "self") || children.contains(first));
            if is_path && !inside_use {
                found.push(Import {
                    line: line_of(k),
                    path: word.split("::").map(str::to_string).collect(),
                    reexport: false,
                });
            }
            k = e.max(k + 1);
        } else {
            k += 1;
        }
    }
    found
}

/// The module files of a crate by path, the children each declares, and what each `mod.rs` re-exports
/// from its children (name → child path).
struct Crate {
    modules: Vec<Module>,
    by_path: BTreeMap<Vec<String>, usize>,
    reexports: BTreeMap<Vec<String>, BTreeMap<String, Vec<String>>>,
}

impl Crate {
    fn read(src: &Path) -> Crate {
        let modules = modules(src);
        let by_path = modules.iter().enumerate().map(|(k, m)| (m.path.clone(), k)).collect();
        let mut krate = Crate { modules, by_path, reexports: BTreeMap::new() };
        for k in 0..krate.modules.len() {
            let children = krate.children(k);
            let module = &krate.modules[k];
            let mut names = BTreeMap::new();
            for import in imports(module, &children).into_iter().filter(|i| i.reexport) {
                if let Some(target) = krate.resolve(k, &import.path) {
                    if let Some(name) = import.path.last() {
                        names.insert(name.clone(), target);
                    }
                }
            }
            let path = krate.modules[k].path.clone();
            krate.reexports.insert(path, names);
        }
        krate
    }

    fn children(&self, k: usize) -> BTreeSet<String> {
        let own = &self.modules[k].path;
        self.modules
            .iter()
            .filter(|m| m.path.len() == own.len() + 1 && m.path.starts_with(own))
            .map(|m| m.path[own.len()].clone())
            .collect()
    }

    /// The module file an import path names: the deepest module it goes through, a re-exported name
    /// followed to the child that holds it. None for a path out of the crate.
    fn resolve(&self, from: usize, path: &[String]) -> Option<Vec<String>> {
        let own = &self.modules[from].path;
        let is_mod_file = self.modules[from].file.file_name().is_some_and(|n| n == "mod.rs" || n == "lib.rs");
        let (mut at, rest): (Vec<String>, &[String]) = match path.first().map(String::as_str) {
            Some("crate") => (Vec::new(), &path[1..]),
            Some("self") => (own.clone(), &path[1..]),
            Some("super") => {
                let mut at = own.clone();
                let mut rest = path;
                while rest.first().is_some_and(|s| s == "super") {
                    at.pop();
                    rest = &rest[1..];
                }
                (at, rest)
            }
            Some(child)
                if is_mod_file && self.by_path.contains_key(&[own.clone(), vec![child.to_string()]].concat()) =>
            {
                (own.clone(), path)
            }
            _ => return None,
        };
        for segment in rest {
            let deeper = [at.clone(), vec![segment.clone()]].concat();
            if self.by_path.contains_key(&deeper) {
                at = deeper;
            } else if let Some(child) = self.reexports.get(&at).and_then(|r| r.get(segment)) {
                at = child.clone();
                break;
            } else {
                break;
            }
        }
        Some(at)
    }

    /// Every import edge between module files: (from, to, line), re-exports left out.
    fn edges(&self) -> Vec<(usize, usize, usize)> {
        let mut edges = Vec::new();
        for (k, module) in self.modules.iter().enumerate() {
            let face = module.file.file_name().is_some_and(|n| n == "mod.rs" || n == "lib.rs");
            for import in imports(module, &self.children(k)) {
                if import.reexport && face {
                    continue;
                }
                if let Some(target) = self.resolve(k, &import.path).and_then(|p| self.by_path.get(&p).copied()) {
                    if target != k {
                        edges.push((k, target, import.line));
                    }
                }
            }
        }
        edges
    }
}

fn shown(module: &Module) -> String {
    let root = repo_root();
    module.file.strip_prefix(&root).unwrap_or(&module.file).display().to_string()
}

/// The layer rule's violations of one crate: a module importing a layer not below its own, or a module
/// importing through the crate root's re-exports.
fn layer_violations(src: &Path, layers: &[(&str, u32)]) -> Vec<String> {
    let krate = Crate::read(src);
    let rank = |path: &[String]| -> Option<(&str, u32)> {
        path.first().and_then(|top| layers.iter().find(|(name, _)| name == top).copied())
    };
    let mut out = Vec::new();
    for module in &krate.modules {
        if !module.path.is_empty() && rank(&module.path).is_none() {
            out.push(format!(
                "{}: module '{}' is in no layer: add it to the layer table of xtask/src/tidy.rs",
                shown(module),
                module.path[0]
            ));
        }
    }
    for (from, to, line) in krate.edges() {
        let (a, b) = (&krate.modules[from], &krate.modules[to]);
        if b.path.is_empty() && !a.path.is_empty() {
            out.push(format!(
                "{}:{line}: imports through the crate root's re-exports: import from the module that holds the item",
                shown(a)
            ));
            continue;
        }
        if let (Some((la, ra)), Some((lb, rb))) = (rank(&a.path), rank(&b.path)) {
            if la != lb && rb >= ra {
                out.push(format!(
                    "{}:{line}: layer '{la}' imports '{}' of layer '{lb}', which is not below it",
                    shown(a),
                    b.path.join("::")
                ));
            }
        }
    }
    out
}

/// The cycles among a crate's module files, each as the files in it.
fn cycles(src: &Path) -> Vec<String> {
    let krate = Crate::read(src);
    let n = krate.modules.len();
    let mut next: Vec<BTreeMap<usize, usize>> = vec![BTreeMap::new(); n];
    for (a, b, line) in krate.edges() {
        next[a].entry(b).or_insert(line);
    }
    // Tarjan's strongly connected components.
    struct State {
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        counter: usize,
        components: Vec<Vec<usize>>,
    }
    fn visit(v: usize, next: &[BTreeMap<usize, usize>], s: &mut State) {
        s.index[v] = Some(s.counter);
        s.low[v] = s.counter;
        s.counter += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for &w in next[v].keys() {
            match s.index[w] {
                None => {
                    visit(w, next, s);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(i) if s.on_stack[w] => s.low[v] = s.low[v].min(i),
                Some(_) => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut component = Vec::new();
            loop {
                let w = s.stack.pop().expect("v is on the stack");
                s.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            s.components.push(component);
        }
    }
    let mut s = State {
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        counter: 0,
        components: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(v, &next, &mut s);
        }
    }
    s.components
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| {
            let members: BTreeSet<usize> = c.iter().copied().collect();
            let lines: Vec<String> = c
                .iter()
                .flat_map(|&a| {
                    next[a]
                        .iter()
                        .filter(|(b, _)| members.contains(b))
                        .map(move |(&b, line)| (a, b, *line))
                        .collect::<Vec<_>>()
                })
                .map(|(a, b, line)| format!("{}:{line} → {}", shown(&krate.modules[a]), shown(&krate.modules[b])))
                .collect();
            format!("a cycle of {} modules: {}", c.len(), lines.join("; "))
        })
        .collect()
}

/// Files of the repository, as paths from its root.
fn repository_files() -> Vec<String> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) {
        let Ok(entries) = std::fs::read_dir(dir) else { return };
        for e in entries.flatten() {
            let path = e.path();
            let name = e.file_name().to_string_lossy().to_string();
            if path.is_dir() {
                if !matches!(name.as_str(), "target" | ".git" | "node_modules") && !name.ends_with("venv") {
                    walk(root, &path, out);
                }
            } else {
                out.push(path.strip_prefix(root).expect("under the root").to_string_lossy().replace('\\', "/"));
            }
        }
    }
    let root = repo_root();
    let mut out = Vec::new();
    walk(&root, &root, &mut out);
    out
}

/// File names a comment gives that are not in the repository: a path with a directory and an extension
/// (`docs/model-file.md`, `src/bench/alloc.rs`) that no repository file's path ends with, and any mention
/// of documents kept outside it.
fn foreign_references(text: &str, files: &[String]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let Some(at) = line.find("//") else { continue };
        let comment = &line[at..];
        for outside in ["../shared", "shared/", "DESIGN §", "DESIGN.md"] {
            if comment.contains(outside) {
                out.push((k + 1, format!("names a document outside the repository ({outside})")));
            }
        }
        for token in comment.split(|c: char| !(c.is_alphanumeric() || matches!(c, '/' | '.' | '_' | '-'))) {
            let token = token.trim_end_matches(['.', '/']).trim_start_matches('/');
            let Some((stem, ext)) = token.rsplit_once('.') else { continue };
            let is_file = stem.contains('/')
                && matches!(ext, "rs" | "md" | "json" | "txt" | "toml" | "py" | "csv" | "svg" | "html" | "sh" | "pyi");
            // A path under a capitalised metavariable (`DIR/batch.csv`, as a command's usage writes `--out
            // DIR`) or under the build output names no file of the repository by design.
            let under_metavariable = stem.split('/').next().is_some_and(|d| d.chars().all(|c| c.is_ascii_uppercase()));
            if !is_file || under_metavariable || token.starts_with("target/") {
                continue;
            }
            if !files.iter().any(|f| f == token || f.ends_with(&format!("/{token}"))) {
                out.push((k + 1, format!("names '{token}', which is no file of the repository")));
            }
        }
    }
    out
}

#[test]
fn each_layer_imports_only_the_layers_below_it() {
    let root = repo_root();
    let violations: Vec<String> =
        LAYERED.iter().flat_map(|(src, layers)| layer_violations(&root.join(src), layers)).collect();
    assert!(violations.is_empty(), "the layers are broken (see ARCHITECTURE.md):\n{}", violations.join("\n"));
}

/// Every crate's sources: no crate's modules may import one another in a circle, layered or not.
const CRATES: [&str; 7] = [
    "crates/core/src",
    "crates/elements/src",
    "crates/solver/src",
    "crates/suspensions/src",
    "src",
    "python/src",
    "xtask/src",
];

#[test]
fn no_modules_form_a_cycle() {
    let root = repo_root();
    let found: Vec<String> = CRATES.iter().flat_map(|src| cycles(&root.join(src))).collect();
    assert!(found.is_empty(), "modules import one another in a circle:\n{}", found.join("\n"));
}

/// The lines of `text` that create a solver taking part in no recording or replay
/// (`StaticSolver::new`, `StaticSolver::with_workspace`) where it should take part in the one its caller
/// was handed (`StaticSolver::taped`).
fn solvers_outside_the_taping(text: &str) -> Vec<usize> {
    let code = code_only(text);
    let mut found: Vec<usize> = ["StaticSolver::new(", "StaticSolver::with_workspace("]
        .iter()
        .flat_map(|call| code.match_indices(call).map(|(at, _)| code[..at].matches('\n').count() + 1))
        .collect();
    found.sort_unstable();
    found
}

/// Every solver of an analysis of the suite takes part in the recording or replay the analysis is
/// handed (`kc::run_taped`), so that a replay moves every equilibrium the analysis solves (a solver
/// outside it would solve the moved model outright: right, but as slow as a re-run, and its rate as noisy
/// as a difference of re-solves). The analyses' public functions outside the suite that take no taping
/// hand theirs `NO_TAPING`, except `anti_pitch`, which the suite does not call.
#[test]
fn every_solver_of_an_analysis_takes_part_in_its_taping() {
    let root = repo_root();
    let mut files = Vec::new();
    rust_files(&root.join("crates/suspensions/src/analysis"), &mut files);
    rust_files(&root.join("crates/suspensions/src/kc"), &mut files);
    let mut found = Vec::new();
    let mut taped = 0;
    for file in files {
        let text = std::fs::read_to_string(&file).expect("a source file reads");
        taped += code_only(&text).matches("StaticSolver::taped(").count();
        if file.ends_with("analysis/anti_pitch.rs") {
            continue;
        }
        for line in solvers_outside_the_taping(&text) {
            found.push(format!("{}:{line}", file.strip_prefix(&root).unwrap_or(&file).display()));
        }
    }
    assert!(taped >= 8, "the analyses create {taped} taped solvers: the rule reads no code");
    assert!(
        found.is_empty(),
        "solvers an analysis creates outside its taping (create them with StaticSolver::taped):\n{}",
        found.join("\n")
    );
    let planted = "let a = StaticSolver::taped(&m, o, t)?;\nlet b = StaticSolver::new(\n &m,\n o,\n)?;\n";
    assert_eq!(solvers_outside_the_taping(planted), vec![2]);
}

/// The keys a design file's reader accepts: every list given to `only(object, &[...], …)` in `text`.
fn accepted_keys(text: &str) -> Vec<String> {
    // The keys are string literals, which `code_only` blanks: comment lines are left out instead.
    let code: String = text.lines().filter(|l| !l.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n");
    let mut keys = Vec::new();
    for (at, _) in code.match_indices("only(") {
        let call = &code[at..];
        let Some(open) = call.find("&[") else { continue };
        let Some(close) = call[open..].find(']') else { continue };
        for key in call[open + 2..open + close].split(',') {
            let key = key.trim().trim_matches('"');
            if !key.is_empty() {
                keys.push(key.to_string());
            }
        }
    }
    keys
}

/// Every key the TARGETS and TOLERANCES readers accept is documented in `docs/design-files.md` (as
/// `` `key` ``): a key added to a reader and not to the page fails here.
#[test]
fn every_key_of_the_design_files_is_documented() {
    let root = repo_root();
    let page = std::fs::read_to_string(root.join("docs/design-files.md")).expect("the page reads");
    let mut keys = Vec::new();
    for reader in ["crates/suspensions/src/design/targets.rs", "crates/suspensions/src/design/tolerance.rs"] {
        let text = std::fs::read_to_string(root.join(reader)).expect("a reader reads");
        keys.extend(accepted_keys(&text));
    }
    assert!(keys.len() >= 20, "the readers accept {} keys: the rule reads no code", keys.len());
    let missing: Vec<&String> = keys.iter().filter(|k| !page.contains(&format!("`{k}`"))).collect();
    assert!(missing.is_empty(), "keys the design files take that docs/design-files.md leaves out: {missing:?}");
    let planted = "only(o, &[\"figure\", \"value\"], &key)?;\nonly(object, &[\"free\"], \"the top level\")?;";
    assert_eq!(accepted_keys(planted), ["figure", "value", "free"]);
}

/// The public functions of `text` whose error is text (`-> Result<_, String>`), by line: a library's
/// errors are typed to the top, rendered where text is written.
fn text_errors(text: &str) -> Vec<usize> {
    let code = code_only(text);
    let mut found = Vec::new();
    for (at, _) in code.match_indices("pub fn ") {
        let signature = &code[at..];
        let end = signature.find(['{', ';']).unwrap_or(signature.len());
        let signature: String = signature[..end].split_whitespace().collect::<Vec<_>>().join(" ");
        if signature.contains("-> Result<") && signature.ends_with(", String>") {
            found.push(code[..at].matches('\n').count() + 1);
        }
    }
    found
}

#[test]
fn no_library_function_gives_its_error_as_text() {
    let root = repo_root();
    let mut found = Vec::new();
    for src in ["crates/core/src", "crates/elements/src", "crates/solver/src", "crates/suspensions/src"] {
        let mut files = Vec::new();
        rust_files(&root.join(src), &mut files);
        for file in files {
            let text = std::fs::read_to_string(&file).expect("a source file reads");
            for line in text_errors(&text) {
                found.push(format!("{}:{line}", file.strip_prefix(&root).unwrap_or(&file).display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "public functions whose error is a String (give them a typed error):\n{}",
        found.join("\n")
    );
    // The rule finds one, over lines, and leaves a typed error and text that is no error alone.
    let planted = "pub fn read(\n    text: &str,\n) -> Result<Model,\n    String> {\n}\npub fn ok() -> Result<String, Error> {}\n";
    assert_eq!(text_errors(planted), vec![1]);
}

#[test]
fn comments_name_only_files_of_the_repository() {
    let root = repo_root();
    let files = repository_files();
    let mut sources = Vec::new();
    for dir in ["crates", "src", "xtask", "tests", "benches", "examples", "python/src"] {
        rust_files(&root.join(dir), &mut sources);
    }
    let mut found = Vec::new();
    // This file quotes the rule's own examples.
    sources.retain(|f| !f.ends_with("xtask/src/tidy.rs"));
    for file in &sources {
        let text = std::fs::read_to_string(file).expect("a source file reads");
        for (line, why) in foreign_references(&text, &files) {
            found.push(format!("{}:{line}: {why}", file.strip_prefix(&root).unwrap_or(file).display()));
        }
    }
    assert!(found.is_empty(), "comments that point outside the repository:\n{}", found.join("\n"));
}

/// The rule itself: a planted back-import, a planted cycle and a planted foreign reference are each
/// found, named by file and line.
#[test]
fn the_rule_finds_a_back_import_a_cycle_and_a_foreign_reference() {
    let dir = std::env::temp_dir().join(format!("elastokin-tidy-{}", std::process::id()));
    let src = dir.join("src");
    std::fs::create_dir_all(src.join("low")).unwrap();
    std::fs::write(src.join("lib.rs"), "pub mod low;\npub mod high;\n").unwrap();
    std::fs::write(src.join("low/mod.rs"), "pub mod a;\npub mod b;\npub use a::Thing;\n").unwrap();
    // `low::a` reaches up to `high`, and `low::a` ↔ `low::b` form a circle.
    std::fs::write(
        src.join("low/a.rs"),
        "use crate::low::b::Other;\npub struct Thing;\nfn f() { crate::high::g(); }\n",
    )
    .unwrap();
    std::fs::write(
        src.join("low/b.rs"),
        "// a comment: crate::high is no import\npub struct Other;\nuse super::a::Thing;\n",
    )
    .unwrap();
    std::fs::write(src.join("high.rs"), "use crate::low::Thing;\npub fn g() {}\n").unwrap();
    let layers = [("low", 0), ("high", 1)];
    let violations = layer_violations(&src, &layers);
    assert_eq!(violations.len(), 1, "{violations:?}");
    assert!(violations[0].contains("low/a.rs:3: layer 'low' imports 'high'"), "{violations:?}");
    let found = cycles(&src);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("low/a.rs:1") && found[0].contains("low/b.rs:3"), "{found:?}");
    // `high` imports `low::Thing` through `low`'s re-export: resolved to `low::a`, which is below it.
    std::fs::remove_dir_all(&dir).unwrap();
    let files = vec!["docs/model-file.md".to_string(), "crates/solver/src/lib.rs".to_string()];
    let text = "// see docs/model-file.md and solver/src/lib.rs\n// and shared/data/hardpoints.md\nlet a = 1; // src/gone.rs\n";
    let refs = foreign_references(text, &files);
    assert_eq!(refs.iter().map(|(l, _)| *l).collect::<Vec<_>>(), vec![2, 2, 3], "{refs:?}");
}
