//! The imports between the files of one crate: every `crate::`, `super::` and `self::` path
//! (in `use` items, in code and in macro arguments), resolved to the file that defines the name.
//!
//! A name that a module re-exports (`pub use`, a glob `pub use x::*`, or a plain `use` that a
//! child reaches through `super::`) is followed to the file that defines it, so a `mod.rs`
//! facade hides no edge.

use std::collections::{BTreeMap, BTreeSet};

use proc_macro2::{TokenStream, TokenTree};
use syn::visit::Visit;

use super::modules::{ModulePath, ModuleTree};

/// One import: file `from` names `name`, which file `to` defines.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Import {
    /// Index of the importing file in [`ModuleTree::files`].
    pub from: usize,
    /// Index of the file that defines the name.
    pub to: usize,
    /// The name imported (a module's name when a module itself is imported).
    pub name: String,
}

/// What each module binds: the items it defines, its `use` names and its globs.
#[derive(Default)]
struct Bindings {
    defined: BTreeMap<ModulePath, BTreeSet<String>>,
    used: BTreeMap<ModulePath, BTreeMap<String, ModulePath>>,
    globs: BTreeMap<ModulePath, Vec<ModulePath>>,
}

/// Every import between two different files of `tree`, sorted and without repeats.
pub fn imports(tree: &ModuleTree) -> Vec<Import> {
    let mut bindings = Bindings::default();
    let mut raw: Vec<(usize, ModulePath)> = Vec::new();
    for (index, file) in tree.files.iter().enumerate() {
        let mut reader = Reader {
            tree,
            scope: file.module.clone(),
            bindings: &mut bindings,
            paths: Vec::new(),
        };
        reader.visit_file(&file.ast);
        raw.extend(reader.paths.into_iter().map(|p| (index, p)));
    }
    let mut out = BTreeSet::new();
    for (from, path) in raw {
        if let Some((module, _)) = resolve(tree, &bindings, &path, 0) {
            let Some(to) = tree.file_of(&module) else {
                continue;
            };
            if to != from {
                let name = path
                    .get(module.len())
                    .unwrap_or_else(|| path.last().expect("path"));
                out.insert(Import {
                    from,
                    to,
                    name: name.clone(),
                });
            }
        }
    }
    out.into_iter().collect()
}

/// The module that defines `path`'s name, and whether the definition was seen (`false`: the
/// deepest module on the path, for a name not found in it).
fn resolve(
    tree: &ModuleTree,
    b: &Bindings,
    path: &[String],
    depth: usize,
) -> Option<(ModulePath, bool)> {
    let split = (0..=path.len())
        .rev()
        .find(|&n| tree.is_module(&path[..n]))?;
    let module = path[..split].to_vec();
    let Some(name) = path.get(split) else {
        return Some((module, true));
    };
    if b.defined.get(&module).is_some_and(|d| d.contains(name)) {
        return Some((module, true));
    }
    if depth < 16 {
        if let Some(target) = b.used.get(&module).and_then(|u| u.get(name)) {
            let mut next = target.clone();
            next.extend_from_slice(&path[split + 1..]);
            if next != path
                && let Some(found) = resolve(tree, b, &next, depth + 1)
            {
                return Some(found);
            }
        }
        for glob in b.globs.get(&module).into_iter().flatten() {
            let mut next = glob.clone();
            next.extend_from_slice(&path[split..]);
            if let Some((m, true)) = resolve(tree, b, &next, depth + 1) {
                return Some((m, true));
            }
        }
    }
    Some((module, false))
}

/// Walks one file: records its definitions and `use` bindings, and every path into the crate.
struct Reader<'a> {
    tree: &'a ModuleTree,
    scope: ModulePath,
    bindings: &'a mut Bindings,
    paths: Vec<ModulePath>,
}

impl Reader<'_> {
    /// `segments` as a path from the crate root, if it points into the crate.
    fn absolute(&self, segments: &[String]) -> Option<ModulePath> {
        let first = segments.first()?;
        match first.as_str() {
            "crate" => Some(segments[1..].to_vec()),
            "self" => Some([self.scope.clone(), segments[1..].to_vec()].concat()),
            "super" => {
                let mut base = self.scope.clone();
                let mut rest = segments;
                while rest.first().is_some_and(|s| s == "super") {
                    base.pop()?;
                    rest = &rest[1..];
                }
                Some([base, rest.to_vec()].concat())
            }
            _ => {
                let mut child = self.scope.clone();
                child.push(first.clone());
                self.tree
                    .is_module(&child)
                    .then(|| [self.scope.clone(), segments.to_vec()].concat())
            }
        }
    }

    fn define(&mut self, name: String) {
        self.bindings
            .defined
            .entry(self.scope.clone())
            .or_default()
            .insert(name);
    }

    /// Flattens a `use` tree into bindings and recorded paths.
    fn use_tree(&mut self, tree: &syn::UseTree, prefix: &mut Vec<String>) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.use_tree(&p.tree, prefix);
                prefix.pop();
            }
            syn::UseTree::Name(n) => {
                let name = n.ident.to_string();
                let (full, bound) = if name == "self" {
                    (prefix.clone(), prefix.last().cloned())
                } else {
                    ([prefix.clone(), vec![name.clone()]].concat(), Some(name))
                };
                self.bind(&full, bound);
            }
            syn::UseTree::Rename(r) => {
                let full = [prefix.clone(), vec![r.ident.to_string()]].concat();
                self.bind(&full, Some(r.rename.to_string()));
            }
            syn::UseTree::Glob(_) => {
                if let Some(abs) = self.absolute(prefix) {
                    self.bindings
                        .globs
                        .entry(self.scope.clone())
                        .or_default()
                        .push(abs.clone());
                    self.paths.push(abs);
                }
            }
            syn::UseTree::Group(g) => {
                for t in &g.items {
                    self.use_tree(t, prefix);
                }
            }
        }
    }

    fn bind(&mut self, full: &[String], bound: Option<String>) {
        let Some(abs) = self.absolute(full) else {
            return;
        };
        if let Some(bound) = bound {
            self.bindings
                .used
                .entry(self.scope.clone())
                .or_default()
                .insert(bound, abs.clone());
        }
        self.paths.push(abs);
    }

    /// Paths such as `crate :: a :: b` inside a macro's tokens.
    fn macro_tokens(&mut self, tokens: TokenStream) {
        let flat: Vec<TokenTree> = tokens.into_iter().collect();
        let mut i = 0;
        while i < flat.len() {
            match &flat[i] {
                TokenTree::Group(g) => self.macro_tokens(g.stream()),
                TokenTree::Ident(id) if ["crate", "super", "self"].contains(&&*id.to_string()) => {
                    let mut segments = vec![id.to_string()];
                    let mut j = i + 1;
                    while let (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b))) =
                        (flat.get(j), flat.get(j + 1))
                    {
                        if a.as_char() != ':' || b.as_char() != ':' {
                            break;
                        }
                        match flat.get(j + 2) {
                            Some(TokenTree::Ident(next)) => segments.push(next.to_string()),
                            _ => break,
                        }
                        j += 3;
                    }
                    if segments.len() > 1
                        && let Some(abs) = self.absolute(&segments)
                    {
                        self.paths.push(abs);
                    }
                    i = j.max(i + 1);
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
    }
}

impl<'ast> Visit<'ast> for Reader<'_> {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let name = match item {
            syn::Item::Const(i) => Some(i.ident.to_string()),
            syn::Item::Enum(i) => Some(i.ident.to_string()),
            syn::Item::Fn(i) => Some(i.sig.ident.to_string()),
            syn::Item::Macro(i) => i.ident.as_ref().map(ToString::to_string),
            syn::Item::Static(i) => Some(i.ident.to_string()),
            syn::Item::Struct(i) => Some(i.ident.to_string()),
            syn::Item::Trait(i) => Some(i.ident.to_string()),
            syn::Item::Type(i) => Some(i.ident.to_string()),
            syn::Item::Union(i) => Some(i.ident.to_string()),
            _ => None,
        };
        if let Some(name) = name {
            self.define(name);
        }
        syn::visit::visit_item(self, item);
    }

    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if let Some((_, items)) = &m.content {
            self.scope.push(m.ident.to_string());
            for item in items {
                self.visit_item(item);
            }
            self.scope.pop();
        }
    }

    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        if u.leading_colon.is_none() {
            self.use_tree(&u.tree, &mut Vec::new());
        }
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        if path.leading_colon.is_none() && path.segments.len() > 1 {
            let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
            if let Some(abs) = self.absolute(&segments) {
                self.paths.push(abs);
            }
        }
        syn::visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        self.macro_tokens(mac.tokens.clone());
        syn::visit::visit_macro(self, mac);
    }
}
