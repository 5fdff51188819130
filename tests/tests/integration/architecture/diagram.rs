//! The layer figure of docs/architecture.md: each crate's layers (bottom first) and the imports
//! between its top-level modules, drawn as a Mermaid flowchart from the code.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

use super::imports::imports;
use super::modules::ModuleTree;
use super::rules::CrateLayout;

/// The marker lines between which docs/architecture.md holds the figure.
pub const BEGIN: &str = "<!-- layers: written by the architecture test, do not edit -->";
/// See [`BEGIN`].
pub const END: &str = "<!-- end of layers -->";

/// One Mermaid flowchart per crate: a box per layer (bottom first), a node per top-level module
/// with its file count, an arrow per module that imports from another. (No line counts: the
/// figure changes with the layers and the files, not with every edit.)
pub fn figure(crates: &[(&CrateLayout, &ModuleTree)]) -> String {
    let mut out = String::new();
    for (layout, tree) in crates {
        let mut files: BTreeMap<String, usize> = BTreeMap::new();
        for f in &tree.files {
            if let Some(top) = f.module.first() {
                *files.entry(top.clone()).or_default() += 1;
            }
        }
        let mut arrows: BTreeSet<(String, String)> = BTreeSet::new();
        for e in imports(tree) {
            let (Some(a), Some(b)) = (
                tree.files[e.from].module.first(),
                tree.files[e.to].module.first(),
            ) else {
                continue;
            };
            if a != b {
                arrows.insert((a.clone(), b.clone()));
            }
        }
        let id = |m: &str| format!("{}_{m}", layout.name.replace(['-', ' ', '(', ')'], ""));
        let _ = writeln!(out, "\n**{}** (bottom layer first)\n", layout.name);
        let _ = writeln!(out, "```mermaid\nflowchart BT");
        for (depth, layer) in layout.layers.iter().enumerate() {
            let _ = writeln!(
                out,
                "  subgraph {}[\"layer {}\"]",
                id(&format!("layer{depth}")),
                depth + 1
            );
            for m in *layer {
                let n = files.get(*m).copied().unwrap_or_default();
                let _ = writeln!(
                    out,
                    "    {}[\"{m}<br/>{n} file{}\"]",
                    id(m),
                    if n == 1 { "" } else { "s" }
                );
            }
            let _ = writeln!(out, "  end");
        }
        for (a, b) in &arrows {
            let _ = writeln!(out, "  {} --> {}", id(a), id(b));
        }
        let _ = writeln!(out, "```");
    }
    out
}

/// `doc` with the text between [`BEGIN`] and [`END`] replaced by `figure`; `None` when the
/// markers are missing.
pub fn with_figure(doc: &str, figure: &str) -> Option<String> {
    let start = doc.find(BEGIN)? + BEGIN.len();
    let end = start + doc[start..].find(END)?;
    Some(format!(
        "{}\n{}\n{}",
        &doc[..start],
        figure.trim(),
        &doc[end..]
    ))
}
