//! Which software wrote an output: the `usar` version and the build (commit) that reports,
//! journals and plans record.

/// Software version written into reports: the crate version, plus the commit
/// (`git describe --always --dirty`, recorded by `build.rs` at build time, or taken from
/// `USAR_GIT_DESCRIBE` in the build environment).
pub fn software_version() -> String {
    match software_build() {
        g if !g.is_empty() => format!("usar {} ({g})", env!("CARGO_PKG_VERSION")),
        _ => format!(
            "usar {} (commit not recorded: built outside a git checkout)",
            env!("CARGO_PKG_VERSION")
        ),
    }
}

/// The build of this `usar`: `git describe --always --dirty` at build time, with `+` and 8
/// hex digits of a hash of the uncommitted changes when the checkout was dirty (recorded by
/// `build.rs`), or `USAR_GIT_DESCRIBE` from the build environment; empty when built outside
/// a git checkout. A sweep's journal records it ([`crate::journal::SweepHeader::build`]).
pub fn software_build() -> &'static str {
    option_env!("USAR_GIT_DESCRIBE").unwrap_or("")
}
