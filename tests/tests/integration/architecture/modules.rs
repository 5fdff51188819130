//! The module tree of one crate: which source file holds which module path, read from the
//! crate root's `mod` items (test-only items removed).
//!
//! A file module `a/b.rs` (or `a/b/mod.rs`) has the path `["a", "b"]`; the crate root
//! (`lib.rs` or `main.rs`) has the empty path. An inline `mod c { .. }` is a module of its
//! own held by the same file. Items under `#[cfg(test)]` are dropped before anything else
//! reads the tree, so tests beside the code never count as imports or code lines.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use syn::spanned::Spanned;

/// A module path below the crate root, such as `["world", "navigation"]`.
pub type ModulePath = Vec<String>;

/// One source file of a crate, parsed.
pub struct SourceFile {
    /// Where it is on disk.
    pub path: PathBuf,
    /// The module path of the file's own module.
    pub module: ModulePath,
    /// The file's text as read.
    pub text: String,
    /// The parsed file with every `#[cfg(test)]` item removed (also inside inline modules).
    pub ast: syn::File,
    /// 1-based inclusive line ranges of the removed test-only items.
    pub test_lines: Vec<(usize, usize)>,
}

/// Every file module of a crate and the file that holds each module path.
pub struct ModuleTree {
    /// The files, the crate root first.
    pub files: Vec<SourceFile>,
    /// Module path -> index into `files` (inline modules map to the file that holds them).
    pub modules: BTreeMap<ModulePath, usize>,
}

impl ModuleTree {
    /// The tree of the crate whose root file (`lib.rs` or `main.rs`) is `root`.
    ///
    /// # Errors
    /// A file that cannot be read or parsed, or a `mod x;` whose file is missing.
    pub fn read(root: &Path) -> Result<Self, String> {
        let mut tree = ModuleTree {
            files: Vec::new(),
            modules: BTreeMap::new(),
        };
        tree.read_file(root.to_path_buf(), Vec::new())?;
        Ok(tree)
    }

    /// The index of the file that holds `module`, if it is a module of this crate.
    pub fn file_of(&self, module: &[String]) -> Option<usize> {
        self.modules.get(module).copied()
    }

    /// Whether `module` is a module of this crate.
    pub fn is_module(&self, module: &[String]) -> bool {
        self.modules.contains_key(module)
    }

    fn read_file(&mut self, path: PathBuf, module: ModulePath) -> Result<(), String> {
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut ast = syn::parse_file(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut test_lines = Vec::new();
        strip_test_items(&mut ast.items, &mut test_lines);
        let index = self.files.len();
        self.modules.insert(module.clone(), index);
        let child_dir = child_dir(&path);
        let own_dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        let mut children = Vec::new();
        collect_mods(
            &ast.items,
            &module,
            &child_dir,
            Some(&own_dir),
            &mut |m, file| {
                children.push((m, file));
            },
        );
        self.files.push(SourceFile {
            path,
            module: module.clone(),
            text,
            ast,
            test_lines,
        });
        for (child, file) in children {
            match file {
                Some(file) => self.read_file(file, child)?,
                None => {
                    self.modules.insert(child, index);
                }
            }
        }
        Ok(())
    }
}

/// The folder that holds the file modules declared in `path`.
fn child_dir(path: &Path) -> PathBuf {
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    match path.file_name().and_then(|n| n.to_str()) {
        Some("lib.rs" | "main.rs" | "mod.rs") => dir,
        _ => dir.join(path.file_stem().unwrap_or_default()),
    }
}

/// Calls `found(module path, Some(file))` for every `mod x;` and `(module path, None)` for
/// every inline `mod x { .. }` (whose own `mod` items are visited too). `dir` holds the file
/// modules declared here; a `#[path]` is relative to `own_dir` (the folder of the source file)
/// outside inline modules and to `dir` inside them, as rustc reads it (the Rust Reference,
/// "Modules: the path attribute").
fn collect_mods(
    items: &[syn::Item],
    module: &[String],
    dir: &Path,
    own_dir: Option<&Path>,
    found: &mut dyn FnMut(ModulePath, Option<PathBuf>),
) {
    for item in items {
        let syn::Item::Mod(m) = item else { continue };
        let name = m.ident.to_string();
        let mut child = module.to_vec();
        child.push(name.clone());
        match &m.content {
            Some((_, inner)) => {
                found(child.clone(), None);
                collect_mods(inner, &child, &dir.join(&name), None, found);
            }
            None => {
                let file = path_attribute(&m.attrs)
                    .map(|p| own_dir.unwrap_or(dir).join(p))
                    .unwrap_or_else(|| {
                        let flat = dir.join(format!("{name}.rs"));
                        if flat.exists() {
                            flat
                        } else {
                            dir.join(&name).join("mod.rs")
                        }
                    });
                found(child, Some(file));
            }
        }
    }
}

/// The value of a `#[path = "..."]` attribute.
fn path_attribute(attrs: &[syn::Attribute]) -> Option<String> {
    attrs.iter().find_map(|a| match &a.meta {
        syn::Meta::NameValue(nv) if nv.path.is_ident("path") => match &nv.value {
            syn::Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Str(s),
                ..
            }) => Some(s.value()),
            _ => None,
        },
        _ => None,
    })
}

/// Whether the attributes make an item test-only: `#[cfg(test)]` or `#[cfg(all(test, ..))]`.
pub fn is_test_only(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        let syn::Meta::List(list) = &a.meta else {
            return false;
        };
        if !list.path.is_ident("cfg") {
            return false;
        }
        let tokens: String = list
            .tokens
            .to_string()
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect();
        tokens == "test" || tokens.starts_with("all(test,")
    })
}

/// Removes test-only items (recursively through inline modules) and records their lines.
fn strip_test_items(items: &mut Vec<syn::Item>, lines: &mut Vec<(usize, usize)>) {
    items.retain(|item| {
        if is_test_only(item_attrs(item)) {
            let span = item.span();
            lines.push((span.start().line, span.end().line));
            false
        } else {
            true
        }
    });
    for item in items.iter_mut() {
        if let syn::Item::Mod(syn::ItemMod {
            content: Some((_, inner)),
            ..
        }) = item
        {
            strip_test_items(inner, lines);
        }
    }
}

/// The attributes of any item.
fn item_attrs(item: &syn::Item) -> &[syn::Attribute] {
    use syn::Item::*;
    match item {
        Const(i) => &i.attrs,
        Enum(i) => &i.attrs,
        ExternCrate(i) => &i.attrs,
        Fn(i) => &i.attrs,
        ForeignMod(i) => &i.attrs,
        Impl(i) => &i.attrs,
        Macro(i) => &i.attrs,
        Mod(i) => &i.attrs,
        Static(i) => &i.attrs,
        Struct(i) => &i.attrs,
        Trait(i) => &i.attrs,
        TraitAlias(i) => &i.attrs,
        Type(i) => &i.attrs,
        Union(i) => &i.attrs,
        Use(i) => &i.attrs,
        _ => &[],
    }
}
