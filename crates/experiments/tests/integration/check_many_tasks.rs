//! `usar check` and `usar run` of a scenario with many tasks: a short summary by default
//! (`--tasks` for every task's line and columns); a scenario of a few tasks prints a line and a
//! column per task as before.

use crate::common;

use common::{PAPER, usar};

/// `scenarios/swarm-100000.ron`: 80 tasks.
const SWARM_100000: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenarios/swarm-100000.ron"
);

/// `tests/data/thirteen-tasks.ron`: 13 tasks of one small group each, quick in a debug build.
const THIRTEEN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/thirteen-tasks.ron");

/// `usar run THIRTEEN --duration 20 ARGS`'s stdout, the command having succeeded.
fn run_thirteen(args: &[&str]) -> String {
    let base = ["run", THIRTEEN, "--method", "dis", "--duration", "20"];
    let o = usar(base.iter().chain(args));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).expect("UTF-8 output")
}

#[test]
fn thirteen_tasks_run_in_a_short_summary() {
    let out = run_thirteen(&[]);
    // The first and last three tasks and the total; the seven between are counted.
    for shown in ["t00 ", "t02 ", "t10 ", "t12 ", "total "] {
        assert!(
            out.lines().any(|l| l.starts_with(shown)),
            "{shown} in\n{out}"
        );
    }
    assert!(!out.lines().any(|l| l.starts_with("t05 ")), "{out}");
    assert!(
        out.contains("... 7 more tasks (every task: --tasks)"),
        "{out}"
    );
    // The rounds table sums its rescuees over the tasks: no column per task.
    let header = out
        .lines()
        .find(|l| l.starts_with("round "))
        .expect("the rounds table's header");
    assert!(
        header.contains("rescuees") && header.contains("(13 tasks; per task: --tasks)"),
        "{header}"
    );
    assert!(!header.contains("t12"), "{header}");
    assert!(out.contains("13 groups of 3 robots"), "{out}");
    let total: u64 = out
        .lines()
        .find(|l| l.starts_with("total "))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
        .expect("the total row's rescuees");
    let by_round: u64 = out
        .lines()
        .skip_while(|l| !l.starts_with("round "))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .map(|l| {
            l.split_whitespace()
                .nth(5)
                .and_then(|v| v.parse::<u64>().ok())
        })
        .map(|v| v.expect("a round row's rescuees"))
        .sum();
    assert_eq!(by_round, total, "{out}");
}

#[test]
fn tasks_lists_every_task_of_a_run() {
    let out = run_thirteen(&["--tasks"]);
    let rows = (0..13)
        .filter(|t| out.lines().any(|l| l.starts_with(&format!("t{t:02} "))))
        .count();
    assert_eq!(rows, 13, "{out}");
    let header = out
        .lines()
        .find(|l| l.starts_with("round "))
        .expect("the rounds table's header");
    assert!(
        header.contains(" t12") && header.contains("groups ("),
        "{header}"
    );
    assert!(!out.contains("more tasks"), "{out}");
}

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
