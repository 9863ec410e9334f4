//! Pieces shared by subcommands: limits arguments, output arguments, atomic file writing.

use clap::{Args, ValueEnum};
use std::fmt;
use std::path::{Path, PathBuf};
use trajkit::limits::load;
use trajkit::{Limits, Order, SampleTable};

/// A command-line error: one line, exit status 2.
#[derive(Debug)]
pub struct CliError(pub String);

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<trajkit::Error> for CliError {
    fn from(e: trajkit::Error) -> Self {
        CliError(e.to_string())
    }
}

/// Shorthand.
pub type CliResult<T> = Result<T, CliError>;

/// Where joint limits come from.
#[derive(Args, Debug, Clone)]
pub struct LimitsArgs {
    /// Robot preset (panda, ur5e, iiwa14) or a limits file (.json/.yaml trajkit format, MoveIt
    /// joint_limits.yaml, or .urdf).
    #[arg(long, value_name = "PRESET|FILE", default_value = "panda")]
    pub limits: String,
    /// A MoveIt joint_limits.yaml whose entries override the limits, matched by joint name.
    #[arg(long, value_name = "FILE")]
    pub joint_limits: Option<PathBuf>,
    /// Fill absent acceleration and jerk limits (e.g. from a URDF) from this preset.
    #[arg(long, value_name = "PRESET")]
    pub fill_from: Option<String>,
    /// Override maximum velocities: one value for all joints or one per joint, comma-separated.
    #[arg(
        long,
        value_name = "V[,V..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub max_velocity: Option<Vec<f64>>,
    /// Override maximum accelerations (one, or one per joint).
    #[arg(
        long,
        value_name = "A[,A..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub max_acceleration: Option<Vec<f64>>,
    /// Override maximum jerks (one, or one per joint).
    #[arg(
        long,
        value_name = "J[,J..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub max_jerk: Option<Vec<f64>>,
    /// Scale every velocity limit (0 < s; 0.5 = half speed).
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1.0,
        allow_hyphen_values = true
    )]
    pub velocity_scale: f64,
    /// Scale every acceleration limit.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1.0,
        allow_hyphen_values = true
    )]
    pub acceleration_scale: f64,
    /// Scale every jerk limit.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1.0,
        allow_hyphen_values = true
    )]
    pub jerk_scale: f64,
}

impl LimitsArgs {
    /// Loads and combines the limits as the flags say.
    pub fn load(&self) -> CliResult<Limits> {
        let mut l = load::from_spec(&self.limits)?;
        if let Some(p) = &self.joint_limits {
            let text = trajkit::io::read_text(p)?;
            l = load::apply_moveit_joint_limits(&l, &text, &p.display().to_string())?;
        }
        if let Some(p) = &self.fill_from {
            let from = Limits::preset(p)?;
            l = load::fill_missing(&l, &from)?;
        }
        for (order, v) in [
            (Order::Velocity, &self.max_velocity),
            (Order::Acceleration, &self.max_acceleration),
            (Order::Jerk, &self.max_jerk),
        ] {
            if let Some(v) = v {
                l = l
                    .with_override(order, v)
                    .map_err(|e| CliError(format!("--max-{}: {e}", order.name())))?;
            }
        }
        if self.velocity_scale != 1.0 || self.acceleration_scale != 1.0 || self.jerk_scale != 1.0 {
            l = l.scaled(
                self.velocity_scale,
                self.acceleration_scale,
                self.jerk_scale,
            )?;
        }
        Ok(l)
    }
}

/// Table format.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header.
    Csv,
    /// JSON object with arrays.
    Json,
}

/// Sampling and output flags.
#[derive(Args, Debug, Clone)]
pub struct OutputArgs {
    /// Sample rate in Hz.
    #[arg(
        long,
        value_name = "HZ",
        default_value_t = 1000.0,
        allow_hyphen_values = true
    )]
    pub rate: f64,
    /// Table format (default: from the output file's extension, else CSV).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// Also write an SVG plot of q, q̇, q̈, q⃛ per joint with the limits drawn.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

impl OutputArgs {
    /// The table serialized for `out` in the chosen format.
    pub fn render(&self, table: &SampleTable, out: &Path) -> String {
        let fmt = self.format.unwrap_or(if trajkit::io::is_json(out) {
            Format::Json
        } else {
            Format::Csv
        });
        match fmt {
            Format::Csv => trajkit::io::table_to_csv(table),
            Format::Json => trajkit::io::table_to_json(table),
        }
    }
}

/// Files to write at the very end, all or nothing as far as the filesystem allows: each file
/// goes to a temporary sibling and is renamed into place; if any write fails, the temporaries
/// and the files already renamed by this run are removed.
#[derive(Default)]
pub struct Outputs {
    files: Vec<(PathBuf, String)>,
    stdout: Option<String>,
}

impl Outputs {
    /// Queues `content` for `path` (`-` means standard output).
    pub fn add(&mut self, path: &Path, content: String) {
        if path.as_os_str() == "-" {
            self.stdout = Some(content);
        } else {
            self.files.push((path.to_path_buf(), content));
        }
    }

    /// Writes everything queued.
    pub fn commit(self) -> CliResult<()> {
        let mut done: Vec<PathBuf> = Vec::new();
        for (path, content) in &self.files {
            // A target that exists and is not a regular file (/dev/null, a FIFO, a terminal)
            // is written in place: renaming over it would replace the device with a file.
            if let Ok(meta) = std::fs::metadata(path) {
                if !meta.is_file() {
                    std::fs::write(path, content)
                        .map_err(|e| CliError(format!("{}: {e}", path.display())))?;
                    continue;
                }
            }
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_default();
            let tmp = path.with_file_name(format!(".{name}.trajkit-tmp-{}", std::process::id()));
            let res = std::fs::write(&tmp, content).and_then(|_| std::fs::rename(&tmp, path));
            if let Err(e) = res {
                let _ = std::fs::remove_file(&tmp);
                for d in &done {
                    let _ = std::fs::remove_file(d);
                }
                return Err(CliError(format!("{}: {e}", path.display())));
            }
            done.push(path.clone());
        }
        if let Some(s) = self.stdout {
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            out.write_all(s.as_bytes())
                .map_err(|e| CliError(format!("<stdout>: {e}")))?;
        }
        Ok(())
    }
}

/// Parses a comma-separated list of numbers given to `flag`.
pub fn finite_list(flag: &str, v: &[f64]) -> CliResult<()> {
    for (i, x) in v.iter().enumerate() {
        if !x.is_finite() {
            return Err(CliError(format!(
                "--{flag}: value {} = {x} is not a finite number",
                i + 1
            )));
        }
    }
    Ok(())
}

/// Prints a subcommand's summary: on standard error when the table itself went to standard
/// output (`--out -`), else on standard output.
pub fn print_summary(out: &Path, summary: &str) {
    if out.as_os_str() == "-" {
        eprintln!("{summary}");
    } else {
        println!("{summary}");
    }
}

/// One summary line per via point: the largest position error of `traj` at the via point's
/// time, over the joints.
pub fn via_point_report(traj: &dyn trajkit::Trajectory, vias: &[(f64, &[f64])]) -> String {
    let mut y = vec![0.0; traj.dof()];
    let mut s = String::new();
    for (k, (t, q)) in vias.iter().enumerate() {
        traj.eval(*t, Order::Position, &mut y);
        let e = y
            .iter()
            .zip(q.iter())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        s.push_str(&format!(
            "\nvia point {} at t = {t}: max error {e:.3e}",
            k + 1
        ));
    }
    s
}
