//! Records the git commit the `usar` binary is built from (`git describe --always --dirty`) in
//! `USAR_GIT_DESCRIBE`, so sweep reports name the code that made their numbers. A value set in
//! the environment wins; without git (e.g. a source tarball) nothing is recorded.

use std::process::Command;

fn main() {
    println!("cargo:rerun-if-env-changed=USAR_GIT_DESCRIBE");
    // A new commit or a staged change moves HEAD or the index.
    for path in ["../../.git/HEAD", "../../.git/index"] {
        if std::path::Path::new(path).exists() {
            println!("cargo:rerun-if-changed={path}");
        }
    }
    if std::env::var_os("USAR_GIT_DESCRIBE").is_some() {
        return;
    }
    let described = Command::new("git")
        .args(["describe", "--always", "--dirty"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok());
    if let Some(d) = described
        .map(|d| d.trim().to_owned())
        .filter(|d| !d.is_empty())
    {
        println!("cargo:rustc-env=USAR_GIT_DESCRIBE={d}");
    }
}
