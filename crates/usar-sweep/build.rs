//! Records which code the `usar` binary is built from in `USAR_GIT_DESCRIBE`, so sweep
//! reports name the code that made their numbers and a sweep's journal is continued only by
//! the build that wrote it: `git describe --always --dirty`, and for a checkout with
//! uncommitted changes (`-dirty`) a `+` and 8 hex digits of an FNV-1a hash of those changes
//! (`git diff HEAD --binary` and the untracked files' names and contents), so two different
//! edits of one commit are two builds. A value set in the environment wins; without git (e.g.
//! a source tarball) nothing is recorded.

use std::process::Command;

/// Runs git with `args` in the workspace; its standard output if it succeeded.
fn git(args: &[&str]) -> Option<Vec<u8>> {
    Command::new("git")
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| o.stdout)
}

/// FNV-1a 64 over `bytes`, continuing from `h`.
fn fnv1a(mut h: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Hash of the uncommitted changes: the diff against HEAD, then each untracked (not ignored)
/// file's name and contents.
fn changes_hash() -> u64 {
    let mut h = fnv1a(
        0xcbf2_9ce4_8422_2325,
        &git(&["diff", "HEAD", "--binary"]).unwrap_or_default(),
    );
    let untracked = git(&[
        "ls-files",
        "--others",
        "--exclude-standard",
        "-z",
        "--full-name",
    ])
    .unwrap_or_default();
    let top = git(&["rev-parse", "--show-toplevel"])
        .and_then(|t| String::from_utf8(t).ok())
        .map(|t| t.trim().to_owned())
        .unwrap_or_default();
    for name in untracked.split(|&b| b == 0).filter(|n| !n.is_empty()) {
        h = fnv1a(h, name);
        let path = std::path::Path::new(&top).join(String::from_utf8_lossy(name).as_ref());
        h = fnv1a(h, &std::fs::read(path).unwrap_or_default());
    }
    h
}

fn main() {
    println!("cargo:rerun-if-env-changed=USAR_GIT_DESCRIBE");
    // A new commit or a staged change moves HEAD or the index; an edit of the sources changes
    // the hash of a dirty checkout.
    for path in [
        "../../.git/HEAD",
        "../../.git/index",
        "../../crates",
        "../../Cargo.toml",
        "../../Cargo.lock",
    ] {
        if std::path::Path::new(path).exists() {
            println!("cargo:rerun-if-changed={path}");
        }
    }
    if std::env::var_os("USAR_GIT_DESCRIBE").is_some() {
        return;
    }
    let described = git(&["describe", "--always", "--dirty"])
        .and_then(|o| String::from_utf8(o).ok())
        .map(|d| d.trim().to_owned())
        .filter(|d| !d.is_empty());
    if let Some(d) = described {
        let d = if d.ends_with("-dirty") {
            format!("{d}+{:08x}", changes_hash() as u32)
        } else {
            d
        };
        println!("cargo:rustc-env=USAR_GIT_DESCRIBE={d}");
    }
}
