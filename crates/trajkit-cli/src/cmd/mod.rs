//! One module per subcommand, and the pieces they share.
//!
//! Conventions for a subcommand `x`: `cmd/x.rs` holds `XArgs` (clap derive, with an example in
//! its `after_help`) and `run(&XArgs) -> Result<u8, CliError>` returning the exit status
//! (0, or 1 for "ran fine but the result fails a check"). Bad input returns `Err`, which `main`
//! prints as one line and turns into exit status 2. Output files are written only at the end,
//! each atomically through [`common::Outputs`], so a failure leaves no partial file behind.

pub mod check;
pub mod common;
pub mod dmp;
pub mod kmp;
pub mod otg;
pub mod plan;
pub mod poly;
pub mod promp;
pub mod spline;
