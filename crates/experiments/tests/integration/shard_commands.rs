//! The commands shard runs and merges suggest can be pasted as they are: quoted for the shell,
//! and runnable from the folder the message was shown in, whichever folder the shard ran in.

use crate::common;

use std::process::{Command, Output};

use common::{PAPER, usar_in};

fn text(o: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn suggested_commands_are_quoted_and_run_from_the_folder_they_are_shown_in() {
    let tmp = tempfile::tempdir().unwrap();
    // As the current folder reads (no symbolic link in it).
    let root = tmp.path().canonicalize().unwrap();
    let (a, b) = (root.join("a"), root.join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    std::fs::copy(PAPER, a.join("my paper.ron")).unwrap();
    let out = "o ut;x";
    let shard = usar_in(
        &a,
        [
            "sweep",
            "my paper.ron",
            "--methods",
            "rne,dis",
            "--trials",
            "2",
            "--duration",
            "8",
            "--quiet",
            "--shard",
            "0/2",
            "--out",
            out,
        ],
    );
    let (stdout, stderr) = text(&shard);
    assert!(shard.status.success(), "{stderr}");
    assert!(
        stdout.contains("when every shard of 2 is done: usar merge 'o ut;x'"),
        "{stdout}"
    );

    // A merge from the parent folder names shard 1 with a command that runs from anywhere.
    let merge = usar_in(&root, ["merge", "a/o ut;x"]);
    let (_, stderr) = text(&merge);
    assert!(!merge.status.success());
    let command = stderr
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("usar sweep"))
        .unwrap_or_else(|| panic!("no command in: {stderr}"));
    let root = root.display();
    assert!(
        command.contains(&format!("'{root}/a/my paper.ron'")),
        "{command}"
    );
    assert!(command.contains(&format!("'{root}/a/o ut;x'")), "{command}");
    let usar_bin = env!("CARGO_BIN_EXE_usar");
    let pasted = Command::new("sh")
        .current_dir(&b)
        .arg("-c")
        .arg(command.replacen("usar", &format!("'{usar_bin}'"), 1))
        .output()
        .unwrap();
    assert!(pasted.status.success(), "{}", text(&pasted).1);
    assert!(
        !b.join("o ut").exists(),
        "the command wrote into the folder it ran in"
    );
    let merge = usar_in(&a, ["merge", out]);
    assert!(merge.status.success(), "{}", text(&merge).1);
}
