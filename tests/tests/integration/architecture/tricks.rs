//! Constructs that would let code walk around the layering rules, each refused with a message:
//! a second name of the crate, code pulled in by `include!`, a module file chosen by a
//! condition, a glob import of the crate root, and an `impl` of a type outside the type's own
//! top-level module (behaviour added from another layer).

use syn::visit::Visit;

use super::imports::{Scoped, inherent_impls, visit_inline_module};
use super::modules::ModuleTree;

/// Every such construct in `tree`, one line each (`file: what: why`).
pub fn trick_problems(tree: &ModuleTree) -> Vec<String> {
    let mut problems = Vec::new();
    for file in &tree.files {
        let mut finder = Finder {
            scope: file.module.clone(),
            found: Vec::new(),
        };
        finder.visit_file(&file.ast);
        let path = file.path.display();
        problems.extend(finder.found.into_iter().map(|f| format!("{path}: {f}")));
    }
    for (at, name, defined) in inherent_impls(tree) {
        let (here, there) = (&tree.files[at], &tree.files[defined]);
        if here.module.first() != there.module.first() {
            problems.push(format!(
                "{}: `impl {name}` outside the module tree of `{name}` ({}): behaviour of a \
                 type belongs beside it; call a function of this module instead",
                here.path.display(),
                there.path.display()
            ));
        }
    }
    problems
}

/// Walks one file for the constructs.
struct Finder {
    scope: Vec<String>,
    found: Vec<String>,
}

impl Finder {
    /// A glob `use` whose prefix is the crate root.
    fn root_glob(&mut self, tree: &syn::UseTree, prefix: &mut Vec<String>) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.root_glob(&p.tree, prefix);
                prefix.pop();
            }
            syn::UseTree::Group(g) => {
                for t in &g.items {
                    self.root_glob(t, prefix);
                }
            }
            syn::UseTree::Glob(_) => {
                let supers = prefix.iter().take_while(|s| *s == "super").count();
                let root = prefix.as_slice() == ["crate"]
                    || (supers == prefix.len() && supers == self.scope.len() && supers > 0);
                if root {
                    self.found.push(format!(
                        "`use {}::*;`: a glob import of the crate root hides which module is \
                         used; name the items",
                        prefix.join("::")
                    ));
                }
            }
            _ => {}
        }
    }
}

impl<'ast> Scoped<'ast> for Finder {
    fn scope(&mut self) -> &mut Vec<String> {
        &mut self.scope
    }
}

impl<'ast> Visit<'ast> for Finder {
    fn visit_item_extern_crate(&mut self, e: &'ast syn::ItemExternCrate) {
        if e.ident == "self" {
            self.found.push(
                "`extern crate self`: a second name of the crate hides its imports; write \
                 `crate::`"
                    .into(),
            );
        }
    }

    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        for a in &m.attrs {
            let compact = |list: &syn::MetaList| -> String {
                let text = list.tokens.to_string();
                text.chars().filter(|c| !c.is_whitespace()).collect()
            };
            if let syn::Meta::List(list) = &a.meta
                && list.path.is_ident("cfg_attr")
                && compact(list).contains(",path=")
            {
                self.found.push(format!(
                    "`mod {}` with `#[cfg_attr(.., path = ..)]`: a module file chosen by a \
                     condition; give the module one file",
                    m.ident
                ));
            }
        }
        visit_inline_module(self, m);
    }

    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        self.root_glob(&u.tree, &mut Vec::new());
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        let last = mac.path.segments.last().map(|s| s.ident.to_string());
        let std_path = mac.path.segments.len() == 1
            || ["std", "core"].contains(&mac.path.segments[0].ident.to_string().as_str());
        if last.as_deref() == Some("include") && std_path {
            self.found.push(
                "`include!`: code no `mod` item reaches, which the layers cannot see; make it \
                 a module"
                    .into(),
            );
        }
        syn::visit::visit_macro(self, mac);
    }
}
