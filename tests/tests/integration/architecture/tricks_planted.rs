//! Tests of the test's [`super::tricks`]: each construct that would walk around the layering
//! rules, planted in a small crate of its own, is found with a message.

use super::rules::{CrateLayout, layering_problems};
use super::tricks::trick_problems;
use super::{FLAT, planted};

/// Two layers, `low` below `high`, as `world` below `mission`.
const TWO: CrateLayout = CrateLayout {
    name: "planted",
    layers: &[&["low"], &["high"]],
    peers: &[],
};

/// Every problem of a planted crate: the layering and the tricks.
fn all_problems(files: &[(&str, &str)], layout: &CrateLayout) -> Vec<String> {
    let (_dir, tree) = planted(files);
    let mut problems = layering_problems(&tree, layout);
    problems.extend(trick_problems(&tree));
    problems
}

fn has(problems: &[String], text: &str) -> bool {
    problems.iter().any(|p| p.contains(text))
}

#[test]
fn a_second_name_of_the_crate_is_followed_and_refused() {
    let p = all_problems(
        &[
            (
                "lib.rs",
                "//! Root.\nextern crate self as me;\nmod low;\nmod high;\n",
            ),
            ("low.rs", "//! Low.\npub fn f() -> u8 { me::high::N }\n"),
            ("high.rs", "//! High.\npub const N: u8 = 1;\n"),
        ],
        &TWO,
    );
    assert!(has(&p, "upward import") && has(&p, "`N`"), "{p:?}");
    assert!(has(&p, "`extern crate self`"), "{p:?}");
}

#[test]
fn an_impl_of_a_lower_type_in_a_higher_module_is_refused() {
    let p = all_problems(
        &[
            ("lib.rs", "//! Root.\nmod low;\nmod high;\n"),
            (
                "low.rs",
                "//! Low.\npub struct World;\npub fn f(w: &World) { w.plan() }\n",
            ),
            (
                "high.rs",
                "//! High.\nimpl crate::low::World {\n    pub fn plan(&self) {}\n}\n",
            ),
        ],
        &TWO,
    );
    assert!(
        has(&p, "`impl World` outside the module tree of `World`"),
        "{p:?}"
    ); // The same through a module imported by name, and `std::include!`.
    let p = all_problems(
        &[
            ("lib.rs", "//! Root.\nmod low;\nmod high;\n"),
            ("low.rs", "//! Low.\npub struct World;\n"),
            (
                "high.rs",
                "//! High.\nuse crate::low;\nimpl low::World {}\nstd::include!(\"x.rs\");\n",
            ),
        ],
        &TWO,
    );
    assert!(has(&p, "`impl World` outside"), "{p:?}");
    assert!(has(&p, "`include!`"), "{p:?}");
    // A feature named like the attribute is no module file chosen by a condition.
    let p = all_problems(
        &[
            (
                "lib.rs",
                "//! Root.\n#[cfg_attr(feature = \"xpath\", allow(dead_code))]\nmod low;\nmod high;\n",
            ),
            ("low.rs", "//! Low.\n"),
            ("high.rs", "//! High.\n"),
        ],
        &TWO,
    );
    assert!(p.is_empty(), "{p:?}");
}

#[test]
fn an_exported_macro_is_an_import_of_its_file() {
    let p = all_problems(
        &[
            ("lib.rs", "//! Root.\nmod low;\nmod high;\n"),
            ("low.rs", "//! Low.\npub fn f() -> u8 { crate::n!() }\n"),
            (
                "high.rs",
                "//! High.\npub const N: u8 = 1;\n#[macro_export]\nmacro_rules! n {\n    () => {\n        $crate::high::N\n    };\n}\n",
            ),
        ],
        &TWO,
    );
    assert!(
        has(&p, "upward import") && has(&p, "imports `n` from"),
        "{p:?}"
    );
}

#[test]
fn included_code_is_refused() {
    let p = all_problems(
        &[
            ("lib.rs", "//! Root.\nmod low;\nmod high;\n"),
            ("low.rs", "//! Low.\ninclude!(\"hidden.rs\");\n"),
            ("hidden.rs", "pub fn f() -> u8 { crate::high::N }\n"),
            ("high.rs", "//! High.\npub const N: u8 = 1;\n"),
        ],
        &TWO,
    );
    assert!(has(&p, "`include!`"), "{p:?}");
}

#[test]
fn a_path_attribute_is_read_as_rustc_reads_it() {
    // rustc reads `low/../b.rs` relative to low.rs's folder: `b.rs` beside it, not `low/b.rs`
    // (a decoy without the import).
    let p = all_problems(
        &[
            ("lib.rs", "//! Root.\nmod low;\nmod high;\n"),
            ("low.rs", "//! Low.\n#[path = \"b.rs\"]\nmod b;\n"),
            ("b.rs", "//! B.\npub fn f() -> u8 { crate::high::N }\n"),
            ("low/b.rs", "//! Decoy.\npub fn f() -> u8 { 1 }\n"),
            ("high.rs", "//! High.\npub const N: u8 = 1;\n"),
        ],
        &TWO,
    );
    assert!(
        has(&p, "upward import") && has(&p, "b.rs (layer 0"),
        "{p:?}"
    );
    let conditional = all_problems(
        &[
            (
                "lib.rs",
                "//! Root.\n#[cfg_attr(all(), path = \"x.rs\")]\nmod low;\nmod high;\n",
            ),
            ("low.rs", "//! Low.\n"),
            ("x.rs", "//! X.\n"),
            ("high.rs", "//! High.\n"),
        ],
        &TWO,
    );
    assert!(
        has(&conditional, "chosen by a condition"),
        "{conditional:?}"
    );
}

#[test]
fn a_cycle_between_modules_of_one_layer_without_a_file_cycle_is_found() {
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod a;\nmod b;\n"),
        ("a/mod.rs", "//! A.\nmod x;\nmod w;\n"),
        ("a/x.rs", "//! X.\npub fn f() -> u8 { crate::b::y::N }\n"),
        ("a/w.rs", "//! W.\npub const M: u8 = 1;\n"),
        ("b/mod.rs", "//! B.\npub mod y;\nmod z;\n"),
        ("b/y.rs", "//! Y.\npub const N: u8 = 1;\n"),
        ("b/z.rs", "//! Z.\npub fn g() -> u8 { crate::a::w::M }\n"),
    ]);
    let p = layering_problems(&tree, &FLAT);
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(has(&p, "module cycle between `a`, `b`"), "{p:?}");
}

#[test]
fn a_glob_of_the_crate_root_fails_with_a_message() {
    let p = all_problems(
        &[
            ("lib.rs", "//! Root.\nmod a;\npub struct R;\n"),
            ("a.rs", "//! A.\nuse crate::*;\npub fn f(_: R) {}\n"),
        ],
        &FLAT,
    );
    assert!(
        has(&p, "`use crate::*;`: a glob import of the crate root"),
        "{p:?}"
    );
}
