//! `usar check` of a scenario with many tasks: a short summary by default (`--tasks` for
//! every task's line and columns); a scenario of a few tasks prints a line and a column per
//! task as before.

use crate::common;

use common::{PAPER, usar};

/// `scenarios/swarm-100000.ron`: 80 tasks.
const SWARM_100000: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenarios/swarm-100000.ron"
);

/// `usar check ARGS`'s stdout, the command having succeeded.
fn check(args: &[&str]) -> String {
    let o = usar(["check"].iter().chain(args));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).expect("UTF-8 output")
}

#[test]
fn eighty_tasks_check_in_a_short_summary_that_names_tasks() {
    let out = check(&[SWARM_100000]);
    let widest = out.lines().map(|l| l.chars().count()).max().unwrap_or(0);
    assert!(widest <= 200, "a line of {widest} characters in\n{out}");
    assert!(
        out.lines().count() < 40,
        "{} lines:\n{out}",
        out.lines().count()
    );
    assert!(out.contains("--tasks"), "{out}");
    assert!(out.contains("80 tasks; difficulty"), "{out}");
    assert!(out.contains("... 74 more tasks"), "{out}");
    // The first and last tasks are shown, the middle ones are not.
    for shown in ["hardest_0 ", "easy_9 "] {
        assert!(
            out.lines().any(|l| l.starts_with(shown)),
            "{shown} in\n{out}"
        );
    }
    assert!(!out.contains("tough_4"), "{out}");
    let supplier = out
        .lines()
        .find(|l| l.starts_with("supplier "))
        .expect("a supplier row");
    assert!(
        supplier.contains("416..417") && supplier.contains("80 of 80"),
        "{supplier}"
    );
    assert!(out.contains("scenarios/swarm-100000.ron: valid"), "{out}");
}

#[test]
fn tasks_lists_every_task_of_eighty() {
    let out = check(&[SWARM_100000, "--tasks"]);
    let tasks = out.lines().filter(|l| l.starts_with("task ")).count();
    assert_eq!(tasks, 80, "{out}");
    assert!(
        out.contains("->easy_9 m"),
        "a distance column per task in\n{out}"
    );
    assert!(!out.contains("more tasks"), "{out}");
}

#[test]
fn the_papers_two_tasks_keep_their_lines_and_quota_columns() {
    let out = check(&[PAPER]);
    let tasks: Vec<&str> = out.lines().filter(|l| l.starts_with("task ")).collect();
    assert_eq!(tasks.len(), 2, "{out}");
    assert!(tasks.iter().all(|l| l.contains("(difficulty ")), "{out}");
    let header = out
        .lines()
        .find(|l| l.starts_with("kind ") && l.contains("role"))
        .expect("the kinds table's header");
    for column in [" easy", " hard", " speed"] {
        assert!(header.contains(column), "{column} in {header}");
    }
    assert!(out.contains("(task columns = quota per task;"), "{out}");
    assert!(!out.contains("quota per task  "), "{out}");
    // --tasks changes nothing for a scenario of a few tasks.
    assert_eq!(check(&[PAPER, "--tasks"]), out);
}
