//! End-to-end tests of `usar trust` (runs the built binary).

use crate::common;

use common::usar;

/// The numeric cell of `row` under column `col` in the matrix that follows `title`.
fn cell(stdout: &str, title: &str, row: &str, col: usize) -> (f64, bool) {
    let section = stdout.split(title).nth(1).expect("section present");
    // Skip the rest of the title line and the column header; stop at the blank line.
    let mut rows = section.lines().skip(2).take_while(|l| !l.trim().is_empty());
    let line = rows
        .find(|l| l.split_whitespace().next() == Some(row))
        .expect("row present");
    let text = line.split_whitespace().nth(col + 1).expect("cell present");
    let marked = text.ends_with('*');
    (text.trim_end_matches('*').parse().expect("number"), marked)
}

fn close(got: f64, want: f64, tol: f64) -> bool {
    (got - want).abs() <= tol
}

#[test]
fn example1_prints_distributions_and_marks_the_most_trusted() {
    let out = usar([
        "trust",
        "--weights",
        "6,4,2",
        "--needs",
        "86,120,30",
        "--needs",
        "20,30,10",
        "--needs",
        "80,115,25",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = String::from_utf8(out.stdout).expect("utf-8");
    assert!(s.contains("0.488636   0.454545  0.0568182"), "{s}");
    assert!(s.contains("0.00372546") && s.contains("0.000504443"), "{s}");
    let title = "Robot-robot RNE";
    let (t12, m12) = cell(&s, title, "R1", 1);
    let (t13, m13) = cell(&s, title, "R1", 2);
    assert!(close(t12, 0.003_73, 5e-6) && !m12, "{s}");
    assert!(close(t13, 0.000_50, 5e-6) && m13, "{s}");
    assert_eq!(cell(&s, title, "R1", 0), (0.0, false));
}

#[test]
fn groups_add_agent_group_and_group_group_values() {
    let out = usar([
        "trust",
        "--weights",
        "6,4,2",
        "--needs",
        "86,120,30",
        "--group",
        "82,114,24;79,117,23",
        "--group",
        "40,56,12;56,48,15",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = String::from_utf8(out.stdout).expect("utf-8");
    assert!(
        close(cell(&s, "Robot-group RNE", "R1", 0).0, 0.001_022, 1e-6),
        "{s}"
    );
    assert!(
        close(cell(&s, "Robot-group RNE", "R1", 1).0, 0.007_767, 1e-6),
        "{s}"
    );
    assert!(
        close(cell(&s, "Group-group RNE", "G1", 1).0, 0.009_535, 1e-6),
        "{s}"
    );
    assert!(
        close(cell(&s, "Group-group RNE", "G2", 0).0, 0.009_419, 1e-6),
        "{s}"
    );
}

#[test]
fn log_base_and_no_smoothing() {
    let out = usar([
        "trust",
        "--weights",
        "1,1",
        "--needs",
        "1,0",
        "--needs",
        "1,1",
        "--epsilon",
        "0",
        "--log-base",
        "2",
    ]);
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).expect("utf-8");
    assert!(s.contains("bits"), "{s}");
    assert_eq!(cell(&s, "Robot-robot RNE", "R1", 1).0, 1.0);
    assert!(cell(&s, "Robot-robot RNE", "R2", 0).0.is_infinite());
}

#[test]
fn bad_input_is_a_one_line_error_with_nonzero_exit() {
    let out = usar([
        "trust",
        "--weights",
        "6,4,2",
        "--needs",
        "86,120,30",
        "--needs",
        "20,30",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).expect("utf-8");
    assert_eq!(
        err.trim_end(),
        "error: --needs #2 has 2 values but --weights has 3"
    );

    let out = usar(["trust", "--weights", "6,4,2", "--needs", "86,-1,30"]);
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).expect("utf-8");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("--needs #1") && err.contains("needs[1] = -1"),
        "{err}"
    );

    let out = usar([
        "trust",
        "--weights",
        "6,4,2",
        "--needs",
        "1,2,3",
        "--log-base",
        "ten",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: --log-base"));
}

#[test]
fn help_shows_examples() {
    let top = usar(["--help"]);
    assert!(String::from_utf8_lossy(&top.stdout).contains("usar trust --weights 6,4,2"));
    let sub = usar(["trust", "--help"]);
    let text = String::from_utf8_lossy(&sub.stdout);
    assert!(
        text.contains("Examples:") && text.contains("--log-base"),
        "{text}"
    );
}

#[test]
fn huge_or_tiny_numbers_are_written_short() {
    let base = ["trust", "--needs", "1,3", "--needs", "3,1"];
    let err = |extra: &[&str]| {
        let out = usar([&base[..], extra].concat());
        assert!(!out.status.success());
        String::from_utf8_lossy(&out.stderr).trim_end().to_owned()
    };
    assert_eq!(
        err(&["--weights", "1,1", "--log-base", "1e-320"]),
        "error: --log-base: log base is 1e-320; it must be finite and > 1"
    );
    assert_eq!(
        err(&["--weights", "-1e300,1"]),
        "error: --weights: weights[0] = -1e300; weights must be finite and > 0"
    );
    let out = usar([&base[..], &["--weights", "1,1", "--log-base", "1e300"]].concat());
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("in log base 1e300 units;"), "{text}");
}
