//! Usage errors (an unknown flag, a bad value, a missing argument) are one line on stderr with
//! exit code 2, like every other error of `usar`; `--help` and a bare `usar` still print help.

mod common;

use common::usar;

#[test]
fn usage_errors_are_one_line_with_the_tip_and_the_usage() {
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &["sweep", "--trial", "3", "x.ron"],
            &[
                "error: unexpected argument '--trial' found",
                "'--trials'",
                "usar sweep",
            ],
        ),
        (
            &["run", "--trial", "x", "x.ron"],
            &["error: invalid value 'x' for '--trial <N>'", "--help"],
        ),
        (
            &["run"],
            &["error: the following required arguments were not provided: <SCENARIO>"],
        ),
        (&["frob"], &["error: unrecognized subcommand 'frob'"]),
    ];
    for (args, needles) in cases {
        let o = usar(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{args:?}: {n:?} not in {err}");
        }
    }
}

#[test]
fn help_is_still_printed_whole() {
    let o = usar(["run", "--help"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).lines().count() > 5);
    let bare = usar([] as [&str; 0]);
    let text = String::from_utf8_lossy(&bare.stderr);
    assert!(
        text.contains("Commands:") && text.lines().count() > 5,
        "{text}"
    );
}
