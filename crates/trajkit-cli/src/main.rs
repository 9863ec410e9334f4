//! The `trajkit` command line tool.
fn main() {}
