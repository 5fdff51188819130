//! The imports between the files of one crate: every `crate::`, `super::` and `self::` path
//! (in `use` items, in code and in macro arguments), resolved to the file that defines the name.
//!
//! A name that a module re-exports (`pub use`, a glob `pub use x::*`, or a plain `use` that a
//! child reaches through `super::`) is followed to the file that defines it, so a `mod.rs`
//! facade hides no edge. A second name of the crate (`extern crate self as name;`) reads as
//! `crate`; a `#[macro_export]` macro is an import of the file that defines it wherever it is
//! invoked; and [`inherent_impls`] lists each `impl Type { .. }` with the file that defines
//! `Type`.

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
    /// The crate's second names (`extern crate self as name;`).
    aliases: BTreeSet<String>,
    /// `#[macro_export]` macros by name: the file that defines each.
    macro_exports: BTreeMap<String, usize>,
}

/// What reading every file of a crate gives.
struct Read {
    bindings: Bindings,
    /// Each file's paths into the crate, from the crate root.
    paths: Vec<(usize, ModulePath)>,
    /// Each file's single-name macro invocations (`name!(..)`).
    macro_calls: Vec<(usize, String)>,
    /// Each inherent `impl`: its file, its module and the self type's path as written.
    impls: Vec<(usize, ModulePath, Vec<String>)>,
}

fn read_crate(tree: &ModuleTree) -> Read {
    let mut bindings = Bindings::default();
    let (mut paths, mut macro_calls, mut impls) = (Vec::new(), Vec::new(), Vec::new());
    for (index, file) in tree.files.iter().enumerate() {
        let mut reader = Reader {
            tree,
            file: index,
            scope: file.module.clone(),
            bindings: &mut bindings,
            paths: Vec::new(),
            macro_calls: Vec::new(),
            impls: Vec::new(),
        };
        reader.visit_file(&file.ast);
        paths.extend(reader.paths.into_iter().map(|p| (index, p)));
        macro_calls.extend(reader.macro_calls.into_iter().map(|m| (index, m)));
        impls.extend(reader.impls);
    }
    Read {
        bindings,
        paths,
        macro_calls,
        impls,
    }
}

/// Every inherent `impl` of `tree` whose self type resolves into the crate: the file of the
/// `impl`, the type's name and the file that defines the type.
pub fn inherent_impls(tree: &ModuleTree) -> Vec<(usize, String, usize)> {
    let read = read_crate(tree);
    let mut out = Vec::new();
    for (file, scope, segments) in &read.impls {
        let Some(name) = segments.last() else {
            continue;
        };
        // The first segment as the module binds it (`use crate::low;` then `low::World`),
        // else as written.
        let bound = read
            .bindings
            .used
            .get(scope)
            .and_then(|u| u.get(&segments[0]));
        let path = match bound {
            Some(target) => [target.clone(), segments[1..].to_vec()].concat(),
            None if segments.len() == 1 => [scope.clone(), segments.clone()].concat(),
            None => match Reader::absolute_in(tree, &read.bindings, scope, segments) {
                Some(abs) => abs,
                None => continue,
            },
        };
        if let Some((module, true)) = resolve(tree, &read.bindings, &path, 0)
            && let Some(to) = tree.file_of(&module)
        {
            out.push((*file, name.clone(), to));
        }
    }
    out
}

/// Every import between two different files of `tree`, sorted and without repeats.
pub fn imports(tree: &ModuleTree) -> Vec<Import> {
    let Read {
        bindings,
        paths: raw,
        macro_calls,
        ..
    } = read_crate(tree);
    let mut out = BTreeSet::new();
    for (from, name) in macro_calls {
        if let Some(&to) = bindings.macro_exports.get(&name)
            && to != from
        {
            out.insert(Import { from, to, name });
        }
    }
    for (from, path) in raw {
        if let [name] = path.as_slice()
            && let Some(&to) = bindings.macro_exports.get(name)
        {
            if to != from {
                out.insert(Import {
                    from,
                    to,
                    name: name.clone(),
                });
            }
            continue;
        }
        if let Some((module, _)) = resolve(tree, &bindings, &path, 0) {
            let Some(to) = tree.file_of(&module) else {
                continue;
            };
            if to != from {
                // A glob of the crate root (`use crate::*;`) names no item: `*`.
                let name = path
                    .get(module.len())
                    .or(path.last())
                    .cloned()
                    .unwrap_or_else(|| "*".into());
                out.insert(Import { from, to, name });
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

/// A visitor that knows the module path it is in (an inline `mod x { .. }` adds `x`).
pub trait Scoped<'ast>: Visit<'ast> {
    /// The module path being visited.
    fn scope(&mut self) -> &mut ModulePath;
}

/// Visits the items of the inline module `m` (nothing for a `mod x;`) with `x` on the
/// visitor's scope.
pub fn visit_inline_module<'ast, V: Scoped<'ast>>(v: &mut V, m: &'ast syn::ItemMod) {
    if let Some((_, items)) = &m.content {
        v.scope().push(m.ident.to_string());
        for item in items {
            v.visit_item(item);
        }
        v.scope().pop();
    }
}

impl<'ast> Scoped<'ast> for Reader<'_> {
    fn scope(&mut self) -> &mut ModulePath {
        &mut self.scope
    }
}

/// Walks one file: records its definitions and `use` bindings, and every path into the crate.
struct Reader<'a> {
    tree: &'a ModuleTree,
    file: usize,
    scope: ModulePath,
    bindings: &'a mut Bindings,
    paths: Vec<ModulePath>,
    macro_calls: Vec<String>,
    impls: Vec<(usize, ModulePath, Vec<String>)>,
}

impl Reader<'_> {
    /// `segments` as a path from the crate root, if it points into the crate.
    fn absolute(&self, segments: &[String]) -> Option<ModulePath> {
        Self::absolute_in(self.tree, self.bindings, &self.scope, segments)
    }

    /// `segments`, written in module `scope`, as a path from the crate root, if it points
    /// into the crate.
    fn absolute_in(
        tree: &ModuleTree,
        bindings: &Bindings,
        scope: &[String],
        segments: &[String],
    ) -> Option<ModulePath> {
        let first = segments.first()?;
        match first.as_str() {
            "crate" => Some(segments[1..].to_vec()),
            alias if bindings.aliases.contains(alias) => Some(segments[1..].to_vec()),
            "self" => Some([scope.to_vec(), segments[1..].to_vec()].concat()),
            "super" => {
                let mut base = scope.to_vec();
                let mut rest = segments;
                while rest.first().is_some_and(|s| s == "super") {
                    base.pop()?;
                    rest = &rest[1..];
                }
                Some([base, rest.to_vec()].concat())
            }
            _ => {
                let mut child = scope.to_vec();
                child.push(first.clone());
                tree.is_module(&child)
                    .then(|| [scope.to_vec(), segments.to_vec()].concat())
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
        if let syn::Item::Macro(m) = item
            && let Some(ident) = &m.ident
            && m.attrs.iter().any(|a| a.path().is_ident("macro_export"))
        {
            self.bindings
                .macro_exports
                .insert(ident.to_string(), self.file);
        }
        if let syn::Item::ExternCrate(e) = item
            && e.ident == "self"
            && let Some((_, alias)) = &e.rename
        {
            self.bindings.aliases.insert(alias.to_string());
        }
        if let syn::Item::Impl(i) = item
            && i.trait_.is_none()
            && let syn::Type::Path(p) = &*i.self_ty
            && p.qself.is_none()
        {
            let segments = p.path.segments.iter().map(|s| s.ident.to_string());
            self.impls
                .push((self.file, self.scope.clone(), segments.collect()));
        }
        if let Some(name) = name {
            self.define(name);
        }
        syn::visit::visit_item(self, item);
    }

    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        visit_inline_module(self, m);
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
        if let Some(name) = mac.path.get_ident() {
            self.macro_calls.push(name.to_string());
        }
        self.macro_tokens(mac.tokens.clone());
        syn::visit::visit_macro(self, mac);
    }
}
