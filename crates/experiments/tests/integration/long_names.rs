//! Names longer than Rust's formatter pads (65,535 characters): a task name in `usar check`
//! and `usar run`, a `--vary` value in a sweep's summary. Their tables print them whole
//! instead of panicking ("Formatting argument out of range").

use crate::common;

use common::{PAPER, ok, usar};

/// `tests/data/thirteen-tasks.ron`: 13 tasks, the summarised task table of `usar check`.
const THIRTEEN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/thirteen-tasks.ron");

/// A name one character past the formatter's widest padding.
fn long_name(c: char) -> String {
    std::iter::repeat_n(c, usize::from(u16::MAX) + 1).collect()
}

/// `text` with every whole-word `t00` (the first task's name and quota key) renamed `name`.
fn rename_first_task(text: &str, name: &str) -> String {
    text.replace("t00:", &format!("{name}:"))
        .replace("\"t00\"", &format!("\"{name}\""))
}

#[test]
fn a_task_name_longer_than_the_widest_padding_is_checked_and_run() {
    let tmp = tempfile::tempdir().unwrap();
    let name = long_name('h');
    let text = std::fs::read_to_string(THIRTEEN).unwrap();
    let renamed = rename_first_task(&text, &name);
    assert_ne!(renamed, text, "the scenario names its first task t00");
    let path = tmp.path().join("long-task.ron");
    std::fs::write(&path, renamed).unwrap();
    let path = path.to_str().unwrap();
    let checked = ok(&usar(["check", path]));
    assert!(checked.contains(&name), "the long name in the summary");
    let ran = ok(&usar(["run", path, "--method", "dis", "--duration", "5"]));
    assert!(
        ran.lines().any(|l| l.starts_with(&name)),
        "the long name's row"
    );
}

#[test]
fn a_vary_value_longer_than_the_widest_padding_is_summarised() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("grid");
    let value = long_name('a');
    let vary = format!("description=\"{value}\",\"b\"");
    let printed = ok(&usar([
        "sweep",
        PAPER,
        "--trials",
        "1",
        "--duration",
        "5",
        "--threads",
        "1",
        "--methods",
        "rne",
        "--vary",
        &vary,
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(printed.contains(&value), "the long value's cell label");
}
