//! The World as data (issue 73): `World`'s methods live in `world/world.rs`, the mission-facing
//! API, and each stage of a step is a function over explicit borrows in a file of its own
//! (`ContactGate::mark_near_bodies` takes `GateInputs`, the neighbour index and its freshness),
//! not another `impl World` block that may touch every field.
//!
//! A file of usar-sim other than `world/world.rs` with an `impl World` block fails, and so
//! does a field of `struct World` that is not private (a stage reaches the state only through
//! the borrows `world.rs` hands it).

use std::path::{Path, PathBuf};

/// The one file whose `impl World` blocks are the World's API, from the workspace root.
const WORLD_FILE: &str = "crates/usar-sim/src/world/world.rs";

/// Whether Rust source `text` has an `impl World` block (inherent, generic or of a trait),
/// outside line comments: a line starting with `impl` whose header's last word is `World`.
fn has_impl_world(text: &str) -> bool {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .any(|l| {
            let Some(rest) = l.trim_start().strip_prefix("impl") else {
                return false;
            };
            // `impl World {`, `impl<'a> World {`, `impl Trait for World {`.
            let head = rest.split('{').next().unwrap_or("");
            let words: Vec<&str> = head
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .filter(|w| !w.is_empty())
                .collect();
            words.last() == Some(&"World")
        })
}

/// Every `.rs` file under `dir`, recursively, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The problems of the rule over the usar-sim sources under `root` (the workspace root): one
/// line per file other than [`WORLD_FILE`] with an `impl World`.
fn problems(root: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    for path in rust_files(&root.join("crates/usar-sim/src")) {
        let rel = path.strip_prefix(root).expect("under the root");
        let rel = rel.to_string_lossy().replace('\\', "/");
        let text = std::fs::read_to_string(&path).expect("a source file");
        if has_impl_world(&text) && rel != WORLD_FILE {
            problems.push(format!(
                "{rel}: an `impl World` outside {WORLD_FILE}: write the stage as a function over \
                 explicit borrows (as contact_gate.rs's ContactGate), or add a method to the \
                 World's API in {WORLD_FILE}"
            ));
        }
    }
    problems
}

/// The fields of `struct World` in Rust source `text` that are not private: one line each
/// (`pub`, `pub(super)`, `pub(crate)`...), between `pub struct World {` and its closing brace.
fn open_fields(text: &str) -> Vec<String> {
    let mut lines = text
        .lines()
        .skip_while(|l| !l.starts_with("pub struct World {"));
    lines.next();
    lines
        .take_while(|l| !l.starts_with('}'))
        .map(str::trim_start)
        .filter(|l| l.starts_with("pub ") || l.starts_with("pub("))
        .map(str::to_owned)
        .collect()
}

#[test]
fn world_fields_are_private() {
    let path = super::workspace_root().join(WORLD_FILE);
    let text = std::fs::read_to_string(&path).expect("world.rs");
    assert!(
        text.contains("pub struct World {"),
        "{WORLD_FILE} defines World"
    );
    let open = open_fields(&text);
    assert!(
        open.is_empty(),
        "{WORLD_FILE}: fields of World open to other files: {open:?}"
    );
}

#[test]
fn an_open_world_field_is_found() {
    let text = "pub struct World {\n    scene: Scene,\n    pub(super) nav: Vec<Nav>,\n}\n\
                pub struct Other {\n    pub x: f64,\n}\n";
    assert_eq!(
        open_fields(text),
        vec!["pub(super) nav: Vec<Nav>,".to_owned()]
    );
}

#[test]
fn world_methods_live_in_world_rs() {
    let problems = problems(&super::workspace_root());
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn an_impl_world_is_recognised_in_each_form() {
    assert!(has_impl_world("impl World {\n}"));
    assert!(has_impl_world("  impl<'a> World {"));
    assert!(has_impl_world("impl Default for World {"));
    assert!(!has_impl_world("impl WorldStats {"));
    assert!(!has_impl_world("impl ContactGate {"));
    assert!(!has_impl_world("// impl World {"));
    assert!(!has_impl_world("fn f(w: &World) {}"));
}

#[test]
fn a_planted_impl_world_is_found() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let world = dir.path().join("crates/usar-sim/src/world");
    std::fs::create_dir_all(&world).expect("the folders");
    std::fs::write(world.join("world.rs"), "impl World {}\n").expect("world.rs");
    std::fs::write(world.join("stage.rs"), "impl World {\n}\n").expect("stage.rs");
    let problems = problems(dir.path());
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(
        problems[0].starts_with("crates/usar-sim/src/world/stage.rs: an `impl World`"),
        "{problems:?}"
    );
}
