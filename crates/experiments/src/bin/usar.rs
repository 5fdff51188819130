//! The `usar` command line.
fn main() {}
