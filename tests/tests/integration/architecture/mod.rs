//! The architecture test: each crate's source files form a layered tree (docs/architecture.md).
//!
//! It reads every crate's `src/` from its root file's `mod` items, resolves each `crate::`,
//! `super::` and `self::` path (in `use` items, code and macro arguments; through `mod.rs`
//! re-exports) to the file that defines the name, and fails on
//! - an import cycle between files;
//! - an import from a lower layer to a higher one (the layer order of each crate is written
//!   once, below, in [`LAYOUTS`]), or between two peer files such as two `usar` commands;
//! - a file of more than [`rules::MAX_CODE_LINES`] code lines, or one that does not open with a
//!   `//!` line naming its concept;
//! - a cycle between sibling modules that no file cycle shows, and each construct of
//!   [`tricks`] that would hide an import (a second name of the crate, `include!`, a module
//!   file chosen by `cfg_attr`, a glob of the crate root, an `impl` outside the type's own
//!   top-level module). The Python glue, the test crates and the benches ([`OTHER_CRATES`])
//!   are held to no cycle and no trick.
//!
//! It also draws the layers into docs/architecture.md (a Mermaid figure between two marker
//! lines) and fails when the figure there is not the code's; after a change of the layers,
//! `USAR_WRITE_ARCHITECTURE=1 cargo test -p integration-tests --test integration architecture` rewrites it.
//!
//! The tests at the bottom plant each fault in a small crate of their own and check that it is
//! found (a test of the test). Run: `cargo test -p integration-tests --test integration architecture`.

mod diagram;
mod imports;
mod modules;
mod rules;
mod tricks;
mod tricks_planted;
mod world_methods;

use std::path::{Path, PathBuf};

use modules::ModuleTree;
use rules::{CrateLayout, file_problems, layering_problems};
use tricks::trick_problems;

/// Each crate's root file (from the workspace root) and its layers, bottom first.
const LAYOUTS: &[(&str, CrateLayout)] = &[
    (
        "crates/rne-core/src/lib.rs",
        CrateLayout {
            name: "rne-core",
            layers: &[
                &["message_text"],
                &["error"],
                &["vector_newtype"],
                &["needs"],
                &["distribution"],
                &["rne", "combinations"],
                &["grouping"],
            ],
            peers: &[],
        },
    ),
    (
        "crates/usar-sim/src/lib.rs",
        CrateLayout {
            name: "usar-sim",
            layers: &[&["scenario"], &["world"], &["mission"]],
            peers: &[],
        },
    ),
    (
        "crates/usar-sweep/src/lib.rs",
        CrateLayout {
            name: "usar-sweep",
            layers: &[
                // Base: files, logs and names that know nothing of a sweep.
                &[
                    "atomic",
                    "bounded_file",
                    "checked_log",
                    "fingerprint",
                    "idle_threads",
                    "journal",
                    "journal_error",
                    "lock",
                    "method_factory",
                    "metrics",
                    "notice",
                    "settings",
                    "spec_ron",
                    "progress",
                    "trial_json",
                    "vary",
                ],
                // Data: the sweep's plan, outcome, limits and output names.
                &["data"],
                // Design, run.
                &["grid"],
                &[
                    "error",
                    "executor",
                    "stale_outputs",
                    "sweep",
                    "shard",
                    "slurm",
                ],
            ],
            peers: &[],
        },
    ),
    (
        "crates/usar-report/src/lib.rs",
        CrateLayout {
            name: "usar-report",
            layers: &[
                // Base: numbers, tables, charts and the targets' vocabulary.
                &[
                    "chart",
                    "error",
                    "scenario_summary",
                    "source_date",
                    "stats",
                    "paired",
                    "rounds_table",
                    "table",
                    "targets",
                    "testing",
                ],
                // Judge, analyse, write.
                &["claims", "calibration"],
                &["analysis"],
                &[
                    "csv_tables",
                    "figures",
                    "report",
                    "grid_outputs",
                    "console",
                    "output",
                    "render",
                    "replay",
                ],
            ],
            peers: &[],
        },
    ),
    (
        "crates/usar-study/src/lib.rs",
        CrateLayout {
            name: "usar-study",
            // The studies: a calibration, then the multiverse that runs one per universe.
            layers: &[&["calibrate"], &["multiverse"], &["refused_setting"]],
            peers: &[],
        },
    ),
    (
        "crates/experiments/src/bin/usar/main.rs",
        CrateLayout {
            name: "usar (binary)",
            layers: &[&["shared"], &["commands"], &["cli"]],
            peers: &["commands"],
        },
    ),
];

/// The other crates read (from the workspace root): the Python glue, the integration-test
/// crates, the benches and the test crates' own sources. They have no layers written down;
/// the test holds them to no import cycle between files or modules and none of the
/// [`tricks`] (and the Python glue, a library, to short files too).
const OTHER_CRATES: &[&str] = &[
    "python/src/lib.rs",
    "crates/rne-core/benches/grouping.rs",
    "crates/usar-sim/benches/world.rs",
    "crates/usar-sim/tests/integration/main.rs",
    "crates/usar-study/benches/multiverse.rs",
    "crates/experiments/benches/sweep.rs",
    "crates/experiments/benches/trials_per_cpu.rs",
    "crates/usar-sweep/examples/random_method.rs",
    "crates/experiments/tests/integration/main.rs",
    "crates/usar-study/tests/integration/main.rs",
    "tests/src/lib.rs",
    "tests/downstream/src/lib.rs",
    "tests/tests/integration/main.rs",
];

/// The problems of a crate without written layers: every top-level module in one layer.
fn unlayered_problems(tree: &ModuleTree, name: &str) -> Vec<String> {
    let mut tops: Vec<&str> = tree
        .files
        .iter()
        .filter_map(|f| f.module.first().map(String::as_str))
        .collect();
    tops.sort_unstable();
    tops.dedup();
    let layers = [tops.as_slice()];
    let layout = CrateLayout {
        name,
        layers: &layers,
        peers: &[],
    };
    let mut problems = layering_problems(tree, &layout);
    problems.extend(trick_problems(tree));
    problems
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ has a parent")
        .to_path_buf()
}

fn read(root_file: &Path) -> ModuleTree {
    ModuleTree::read(root_file).unwrap_or_else(|e| panic!("reading the crate: {e}"))
}

#[test]
fn each_crate_is_a_layered_tree_without_cycles() {
    let mut problems = Vec::new();
    for (root, layout) in LAYOUTS {
        let tree = read(&workspace_root().join(root));
        assert!(tree.files.len() > 3, "{}: too few files read", layout.name);
        problems.extend(layering_problems(&tree, layout));
        problems.extend(trick_problems(&tree));
    }
    assert!(problems.is_empty(), "\n{}\n", problems.join("\n"));
}

#[test]
fn the_python_glue_tests_and_benches_have_no_cycle_and_no_trick() {
    let mut problems = Vec::new();
    for root in OTHER_CRATES {
        let tree = read(&workspace_root().join(root));
        problems.extend(unlayered_problems(&tree, root));
    }
    assert!(problems.is_empty(), "\n{}\n", problems.join("\n"));
}

#[test]
fn every_source_file_is_short_and_names_its_concept() {
    let mut problems = Vec::new();
    let roots = LAYOUTS.iter().map(|(root, _)| *root);
    for root in roots.chain(["python/src/lib.rs"]) {
        problems.extend(file_problems(&read(&workspace_root().join(root))));
    }
    assert!(problems.is_empty(), "\n{}\n", problems.join("\n"));
}

#[test]
fn docs_architecture_draws_the_current_layers() {
    let trees: Vec<ModuleTree> = LAYOUTS
        .iter()
        .map(|(root, _)| read(&workspace_root().join(root)))
        .collect();
    let crates: Vec<(&CrateLayout, &ModuleTree)> =
        LAYOUTS.iter().map(|(_, l)| l).zip(trees.iter()).collect();
    let figure = diagram::figure(&crates);
    let path = workspace_root().join("docs/architecture.md");
    let doc = std::fs::read_to_string(&path).expect("docs/architecture.md is readable");
    let wanted = diagram::with_figure(&doc, &figure).unwrap_or_else(|| {
        panic!(
            "docs/architecture.md lacks the marker lines `{}` and `{}`",
            diagram::BEGIN,
            diagram::END
        )
    });
    if std::env::var_os("USAR_WRITE_ARCHITECTURE").is_some() {
        std::fs::write(&path, &wanted).expect("docs/architecture.md written");
    } else {
        assert!(
            doc == wanted,
            "docs/architecture.md's layer figure is not the code's: run \
             `USAR_WRITE_ARCHITECTURE=1 cargo test -p integration-tests --test integration architecture`"
        );
    }
}

// ---- Tests of the test: each fault planted in a small crate of its own. ----

/// A crate in a temporary folder from `(relative path, text)` pairs; returns its tree.
fn planted(files: &[(&str, &str)]) -> (tempfile::TempDir, ModuleTree) {
    let dir = tempfile::tempdir().expect("temporary folder");
    for (path, text) in files {
        let path = dir.path().join(path);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("folder");
        std::fs::write(path, text).expect("file written");
    }
    let tree = read(&dir.path().join("lib.rs"));
    (dir, tree)
}

const FLAT: CrateLayout = CrateLayout {
    name: "planted",
    layers: &[&["a", "b", "c", "m"]],
    peers: &[],
};

#[test]
fn a_planted_cycle_is_found() {
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod a;\nmod b;\n"),
        ("a.rs", "//! A thing.\nuse crate::b::B;\npub struct A;\n"),
        ("b.rs", "//! B thing.\nuse crate::a::A;\npub struct B;\n"),
    ]);
    let problems = layering_problems(&tree, &FLAT);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].contains("import cycle"), "{problems:?}");
    assert!(problems[0].contains("a.rs -> ") && problems[0].contains("(B)"));
}

#[test]
fn a_cycle_through_a_reexport_or_an_inline_path_is_found() {
    // b reaches A through m's `pub use` (a facade), a names b's function inline in its code.
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod a;\nmod m;\n"),
        (
            "a.rs",
            "//! A thing.\npub struct A;\npub fn f() { crate::m::b::g(); }\n",
        ),
        (
            "m/mod.rs",
            "//! Facade.\npub mod b;\npub use crate::a::*;\n",
        ),
        ("m/b.rs", "//! B thing.\nuse super::A;\npub fn g() {}\n"),
    ]);
    let problems = layering_problems(&tree, &FLAT);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].contains("import cycle"), "{problems:?}");
    assert!(problems[0].contains("m/b.rs -> ") && problems[0].contains("a.rs (A)"));
}

#[test]
fn test_only_imports_do_not_count() {
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod a;\nmod b;\n"),
        ("a.rs", "//! A thing.\nuse crate::b::B;\npub struct A;\n"),
        (
            "b.rs",
            "//! B thing.\npub struct B;\n#[cfg(test)]\nmod tests {\n    use crate::a::A;\n}\n",
        ),
    ]);
    assert!(layering_problems(&tree, &FLAT).is_empty());
}

#[test]
fn a_planted_upward_import_and_a_peer_import_are_found() {
    let layout = CrateLayout {
        name: "planted",
        layers: &[&["low"], &["high"]],
        peers: &["high"],
    };
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod low;\nmod high;\n"),
        (
            "low.rs",
            "//! Low.\npub fn f() -> usize { crate::high::one::N }\n",
        ),
        ("high/mod.rs", "//! High.\nmod one;\nmod two;\n"),
        ("high/one.rs", "//! One.\npub const N: usize = 1;\n"),
        (
            "high/two.rs",
            "//! Two.\nuse super::one::N;\nuse crate::low::f;\n",
        ),
    ]);
    let problems = layering_problems(&tree, &layout);
    assert_eq!(problems.len(), 3, "{problems:?}");
    assert!(
        problems
            .iter()
            .any(|p| p.contains("upward import") && p.contains("`N`"))
    );
    assert!(problems.iter().any(|p| p.contains("from its peer")));
    // low -> high/one.rs and high/two.rs -> low: no file cycle, but one between the modules.
    assert!(
        problems
            .iter()
            .any(|p| p.contains("module cycle between `low`, `high`"))
    );
}

#[test]
fn a_module_in_no_layer_is_named() {
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod a;\nmod z;\n"),
        ("a.rs", "//! A thing.\n"),
        ("z.rs", "//! Z thing.\n"),
    ]);
    let problems = layering_problems(&tree, &FLAT);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].contains("`z`") && problems[0].contains("no layer"));
}

#[test]
fn a_long_file_and_a_file_without_its_concept_are_found() {
    let long: String = std::iter::once("//! Long.\n".to_string())
        .chain((0..501).map(|i| format!("pub const C{i}: u8 = 0;\n")))
        .collect();
    let with_tests: String = std::iter::once("//! Fine.\n".to_string())
        .chain((0..10).map(|i| format!("pub const C{i}: u8 = 0;\n")))
        .chain(std::iter::once("#[cfg(test)]\nmod tests {\n".to_string()))
        .chain((0..600).map(|i| format!("    const T{i}: u8 = 0;\n")))
        .chain(std::iter::once("}\n".to_string()))
        .collect();
    let (_dir, tree) = planted(&[
        ("lib.rs", "//! Root.\nmod a;\nmod b;\nmod c;\n"),
        ("a.rs", &long),
        ("b.rs", "// not a module comment\npub struct B;\n"),
        ("c.rs", &with_tests),
    ]);
    let problems = file_problems(&tree);
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].contains("a.rs: 501 code lines"), "{problems:?}");
    assert!(problems[1].contains("b.rs:1:"), "{problems:?}");
}
