//! The rules the architecture test holds a crate to: no import cycle between files, no import
//! from a lower layer to a higher one, no import between peer files, every file short and
//! opening with a `//!` line that names its concept.
//!
//! Cycles are the strongly connected components of the file graph (Tarjan, "Depth-first search
//! and linear graph algorithms", SIAM J. Comput. 1(2), 1972).

use std::collections::BTreeMap;

use super::imports::{Import, imports};
use super::modules::ModuleTree;

/// How one crate is meant to be layered.
pub struct CrateLayout<'a> {
    /// The crate's name, for messages.
    pub name: &'a str,
    /// The crate's top-level modules, bottom layer first; a layer may import only from itself
    /// (without a cycle) and from the layers before it. Every top-level module must be listed.
    pub layers: &'a [&'a [&'a str]],
    /// Folders (module paths joined by `::`) whose files must not import one another, such as
    /// the binary's `commands`: shared logic goes below them.
    pub peers: &'a [&'a str],
}

/// The most lines of non-test code a source file may have (not blank, not a `//` comment line,
/// outside `#[cfg(test)]` items).
pub const MAX_CODE_LINES: usize = 500;

/// Every broken rule of `tree` under `layout`, one line each (empty: the crate is a layered tree).
pub fn layering_problems(tree: &ModuleTree, layout: &CrateLayout) -> Vec<String> {
    let edges = imports(tree);
    let name = |i: usize| tree.files[i].path.display().to_string();
    let mut problems = Vec::new();
    for component in cycles(tree.files.len(), &edges) {
        let files: Vec<String> = component.iter().map(|&i| name(i)).collect();
        let ties: Vec<String> = edges
            .iter()
            .filter(|e| component.contains(&e.from) && component.contains(&e.to))
            .map(|e| format!("{} -> {} ({})", name(e.from), name(e.to), e.name))
            .collect();
        problems.push(format!(
            "{}: import cycle between {}: {}",
            layout.name,
            files.join(", "),
            ties.join("; ")
        ));
    }
    problems.extend(module_cycles(tree, &edges, layout.name));
    let mut layer_of = BTreeMap::new();
    for (depth, layer) in layout.layers.iter().enumerate() {
        for module in *layer {
            layer_of.insert(module.to_string(), depth);
        }
    }
    let top = |i: usize| tree.files[i].module.first().cloned();
    for file in &tree.files {
        if let Some(module) = file.module.first()
            && !layer_of.contains_key(module)
        {
            problems.push(format!(
                "{}: top-level module `{module}` ({}) is in no layer of the architecture test",
                layout.name,
                file.path.display()
            ));
        }
    }
    for e in &edges {
        let (Some(a), Some(b)) = (top(e.from), top(e.to)) else {
            continue;
        };
        if let (Some(&la), Some(&lb)) = (layer_of.get(&a), layer_of.get(&b))
            && lb > la
        {
            problems.push(format!(
                "{}: upward import: {} (layer {la}, `{a}`) imports `{}` from {} (layer {lb}, `{b}`)",
                layout.name,
                name(e.from),
                e.name,
                name(e.to)
            ));
        }
        for peer in layout.peers {
            let folder: Vec<&str> = peer.split("::").collect();
            let inside = |i: usize| {
                let m = &tree.files[i].module;
                m.len() == folder.len() + 1 && m.iter().zip(&folder).all(|(x, y)| x == y)
            };
            if inside(e.from) && inside(e.to) {
                problems.push(format!(
                    "{}: {} imports `{}` from its peer {} (both in `{peer}`)",
                    layout.name,
                    name(e.from),
                    e.name,
                    name(e.to)
                ));
            }
        }
    }
    problems
}

/// The cycles between sibling modules (two folders, or a folder and a file, under one parent)
/// that no file cycle already shows: `a/x.rs` imports `b/y.rs` and `b/z.rs` imports `a/w.rs`.
fn module_cycles(tree: &ModuleTree, edges: &[Import], name: &str) -> Vec<String> {
    let mut modules: Vec<Vec<String>> = Vec::new();
    let mut index = BTreeMap::new();
    let mut module_edges = Vec::new();
    let mut why: BTreeMap<(usize, usize), String> = BTreeMap::new();
    for e in edges {
        let (a, b) = (&tree.files[e.from].module, &tree.files[e.to].module);
        let Some(d) = (0..a.len().min(b.len())).find(|&d| a[d] != b[d]) else {
            continue;
        };
        let mut node = |m: &[String]| -> usize {
            *index.entry(m.to_vec()).or_insert_with(|| {
                modules.push(m.to_vec());
                modules.len() - 1
            })
        };
        let (from, to) = (node(&a[..=d]), node(&b[..=d]));
        why.entry((from, to)).or_insert_with(|| {
            format!(
                "{} -> {} ({})",
                tree.files[e.from].path.display(),
                tree.files[e.to].path.display(),
                e.name
            )
        });
        module_edges.push(Import {
            from,
            to,
            name: e.name.clone(),
        });
    }
    let file_cycles = cycles(tree.files.len(), edges);
    let inside = |file: usize, m: &[String]| tree.files[file].module.starts_with(m);
    let mut problems = Vec::new();
    for c in cycles(modules.len(), &module_edges) {
        let shown = file_cycles.iter().any(|fc| {
            let touched = c
                .iter()
                .filter(|&&m| fc.iter().any(|&f| inside(f, &modules[m])))
                .count();
            touched >= 2
        });
        if shown {
            continue;
        }
        let names: Vec<String> = c
            .iter()
            .map(|&m| format!("`{}`", modules[m].join("::")))
            .collect();
        let ties: Vec<&String> = why
            .iter()
            .filter(|((a, b), _)| c.contains(a) && c.contains(b))
            .map(|(_, w)| w)
            .collect();
        problems.push(format!(
            "{name}: module cycle between {}: {}",
            names.join(", "),
            ties.iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("; ")
        ));
    }
    problems
}

/// The files of `tree` over [`MAX_CODE_LINES`] or without an opening `//!` line, one line each.
pub fn file_problems(tree: &ModuleTree) -> Vec<String> {
    let mut problems = Vec::new();
    for file in &tree.files {
        let lines = code_lines(&file.text, &file.test_lines);
        if lines > MAX_CODE_LINES {
            problems.push(format!(
                "{}: {lines} code lines (at most {MAX_CODE_LINES}): split it, one concept a file",
                file.path.display()
            ));
        }
        let first = file.text.lines().next().unwrap_or("");
        if !first.starts_with("//! ") || first.trim().len() < 8 {
            problems.push(format!(
                "{}:1: the file must open with `//! <its one concept>`",
                file.path.display()
            ));
        }
    }
    problems
}

/// Lines of `text` that are not blank, not `//` comment lines and not inside `test_lines`.
pub fn code_lines(text: &str, test_lines: &[(usize, usize)]) -> usize {
    text.lines()
        .enumerate()
        .filter(|(i, line)| {
            let n = i + 1;
            let t = line.trim();
            !t.is_empty()
                && !t.starts_with("//")
                && !test_lines.iter().any(|&(a, b)| (a..=b).contains(&n))
        })
        .count()
}

/// The import cycles of a graph of `n` files: its strongly connected components of more than
/// one file, each sorted, in the order of their smallest file.
pub fn cycles(n: usize, edges: &[Import]) -> Vec<Vec<usize>> {
    let mut next = vec![Vec::new(); n];
    for e in edges {
        next[e.from].push(e.to);
    }
    let mut t = Tarjan {
        next,
        index: vec![usize::MAX; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        counter: 0,
        found: Vec::new(),
    };
    for v in 0..n {
        if t.index[v] == usize::MAX {
            t.visit(v);
        }
    }
    let mut found: Vec<Vec<usize>> = t.found.into_iter().filter(|c| c.len() > 1).collect();
    for c in &mut found {
        c.sort_unstable();
    }
    found.sort();
    found
}

struct Tarjan {
    next: Vec<Vec<usize>>,
    index: Vec<usize>,
    low: Vec<usize>,
    on_stack: Vec<bool>,
    stack: Vec<usize>,
    counter: usize,
    found: Vec<Vec<usize>>,
}

impl Tarjan {
    fn visit(&mut self, v: usize) {
        self.index[v] = self.counter;
        self.low[v] = self.counter;
        self.counter += 1;
        self.stack.push(v);
        self.on_stack[v] = true;
        for k in 0..self.next[v].len() {
            let w = self.next[v][k];
            if self.index[w] == usize::MAX {
                self.visit(w);
                self.low[v] = self.low[v].min(self.low[w]);
            } else if self.on_stack[w] {
                self.low[v] = self.low[v].min(self.index[w]);
            }
        }
        if self.low[v] == self.index[v] {
            let mut component = Vec::new();
            while let Some(w) = self.stack.pop() {
                self.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            self.found.push(component);
        }
    }
}
