//! Pieces shared by subcommands: limits arguments, output arguments, atomic file writing.

use clap::{Args, ValueEnum};
use std::fmt;
use std::path::{Path, PathBuf};
use trajkit::limits::{load, FillBy, LimitsSpec, Needs, PartialLimits, SpecStep, TextFile};
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

/// How `--fill-from` pairs joints.
#[derive(ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum FillByArg {
    /// By joint name (the default).
    Name,
    /// By position: joint j takes the source's joint j.
    Index,
}

/// Where joint limits come from.
#[derive(Args, Debug, Clone)]
pub struct LimitsArgs {
    /// Robot preset (panda, ur5e, iiwa14) or a limits file (.json/.yaml trajkit format, MoveIt
    /// joint_limits.yaml, or .urdf). No default: give it, or the limits themselves with
    /// --max-velocity/--max-acceleration/--max-jerk/--position-range.
    #[arg(long, value_name = "PRESET|FILE")]
    pub limits: Option<String>,
    /// A MoveIt joint_limits.yaml whose entries override the limits, matched by joint name.
    #[arg(long, value_name = "FILE")]
    pub joint_limits: Option<PathBuf>,
    /// Fill absent acceleration and jerk limits (e.g. of a URDF) from this preset or limits
    /// file, matched by joint name (see --fill-by).
    #[arg(long, value_name = "PRESET|FILE")]
    pub fill_from: Option<String>,
    /// How --fill-from pairs joints: by name, or by index when the joints correspond but
    /// their names differ.
    #[arg(long, value_enum, default_value = "name")]
    pub fill_by: FillByArg,
    /// Maximum velocities: one value for all joints or one per joint, comma-separated ('inf'
    /// states "unlimited").
    #[arg(
        long,
        value_name = "V[,V..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub max_velocity: Option<Vec<f64>>,
    /// Maximum accelerations (one, or one per joint).
    #[arg(
        long,
        value_name = "A[,A..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub max_acceleration: Option<Vec<f64>>,
    /// Maximum jerks (one, or one per joint).
    #[arg(
        long,
        value_name = "J[,J..]",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub max_jerk: Option<Vec<f64>>,
    /// Position ranges: one LO:HI for all joints or one per joint, comma-separated
    /// ('-inf:inf' states "unbounded").
    #[arg(
        long,
        value_name = "LO:HI[,LO:HI..]",
        value_delimiter = ',',
        allow_hyphen_values = true,
        value_parser = parse_range
    )]
    pub position_range: Option<Vec<(f64, f64)>>,
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

/// Parses one `LO:HI` of `--position-range`.
fn parse_range(s: &str) -> Result<(f64, f64), String> {
    let bad = || format!("'{s}' is not a range LO:HI (e.g. -2.9:2.9, or -inf:inf)");
    let (lo, hi) = s.split_once(':').ok_or_else(bad)?;
    let lo: f64 = lo.trim().parse().map_err(|_| bad())?;
    let hi: f64 = hi.trim().parse().map_err(|_| bad())?;
    if lo.is_nan() || hi.is_nan() {
        return Err(bad());
    }
    Ok((lo, hi))
}

pub use trajkit::limits::ResolvedLimits;

impl LimitsArgs {
    /// Resolves the flags for data of `dof` joints named `names` (`what`: "waypoint",
    /// "table") with the library's recipe ([`LimitsSpec::resolve`]): the source (`--limits`,
    /// else the overrides alone, else `default` when given, else an error asking for limits),
    /// `--joint-limits`, `--fill-from`, pairing with the data by name or position, then the
    /// overrides (one value, or one per data column) and the scales. Errors name the flag.
    pub fn resolve(
        &self,
        what: &'static str,
        names: Option<&[String]>,
        dof: usize,
        default: Option<&str>,
    ) -> CliResult<ResolvedLimits> {
        let mut spec = LimitsSpec {
            fill_by: match self.fill_by {
                FillByArg::Name => FillBy::Name,
                FillByArg::Index => FillBy::Index,
            },
            max_velocity: self.max_velocity.clone(),
            max_acceleration: self.max_acceleration.clone(),
            max_jerk: self.max_jerk.clone(),
            position_range: self.position_range.clone(),
            velocity_scale: self.velocity_scale,
            acceleration_scale: self.acceleration_scale,
            jerk_scale: self.jerk_scale,
            ..LimitsSpec::default()
        };
        spec.source =
            match (&self.limits, default) {
                (Some(spec), _) => Some(load::from_spec(spec)?),
                (None, _) if spec.has_overrides() => None,
                (None, Some(preset)) => Some(Limits::preset(preset)?.into()),
                (None, None) => return Err(CliError(
                    "no limits given: name them with --limits PRESET|FILE (panda, ur5e, iiwa14, a \
                 .json/.yaml limits file, a MoveIt joint_limits.yaml or a .urdf) or give them \
                 with --max-velocity, --max-acceleration, --max-jerk and --position-range"
                        .to_string(),
                )),
            };
        if let Some(p) = &self.joint_limits {
            spec.joint_limits = Some(TextFile {
                text: trajkit::io::read_text(p)?,
                name: p.display().to_string(),
            });
        }
        if let Some(from) = &self.fill_from {
            spec.fill_from = Some(load::from_spec(from)?);
        }
        spec.resolve(what, names, dof).map_err(|e| {
            let err = &e.error;
            CliError(match e.step {
                SpecStep::FillFrom => {
                    let from = self.fill_from.as_deref().unwrap_or_default();
                    match err {
                        trajkit::Error::JointNames { .. } => format!(
                            "--fill-from {from}: {err} (--fill-by index pairs them by position)"
                        ),
                        _ => format!("--fill-from {from}: {err}"),
                    }
                }
                SpecStep::JointCount => match err {
                    trajkit::Error::DimensionMismatch { found, .. } => format!(
                        "the limits have {found} joints, the {what}s {dof}{}",
                        if names.is_some() {
                            ""
                        } else {
                            " (unnamed columns pair with the limits by position)"
                        }
                    ),
                    _ => err.to_string(),
                },
                SpecStep::Override(order) => format!("--max-{}: {err}", order.name()),
                SpecStep::PositionRange => format!("--position-range: {err}"),
                _ => err.to_string(),
            })
        })
    }
}

/// Completes resolved limits with what an operation needs; a missing one is one line naming
/// the joint, the field and the flags that supply it.
pub fn complete(l: &PartialLimits, needs: Needs) -> CliResult<Limits> {
    l.complete(needs).map_err(|e| match &e {
        trajkit::Error::MissingLimit { field, .. } => {
            let how = match *field {
                "velocity" => "--max-velocity V or a limits file with it",
                "acceleration" => {
                    "--max-acceleration A, a limits file with it, or --fill-from PRESET|FILE"
                }
                "jerk" => {
                    "--max-jerk J ('inf': unlimited), a limits file, or --fill-from PRESET|FILE"
                }
                _ => "--position-range LO:HI ('-inf:inf': unbounded) or a limits file with it",
            };
            CliError(format!("{e}: give {how}"))
        }
        _ => CliError(e.to_string()),
    })
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

/// Files to write at the very end, all or nothing. Every file is first written to a temporary
/// sibling; only when all of them are written are they renamed into place, each existing
/// target first kept aside under a hard link (a copy where links are not possible). If any
/// step fails, every target is put back as it was (byte-identical; files this run would have
/// created are removed) and the temporaries are deleted. Targets that exist and are not
/// regular files (`/dev/null`, a FIFO, a terminal) are written in place, after the renames.
#[derive(Default)]
pub struct Outputs {
    files: Vec<(PathBuf, String)>,
    stdout: Option<String>,
}

/// One target during [`Outputs::commit`].
struct Staged {
    target: PathBuf,
    tmp: PathBuf,
    /// The target's previous content, kept aside while the run commits.
    backup: Option<PathBuf>,
    renamed: bool,
}

/// A sibling of `path` named `.name.trajkit-<what>-<pid>-<k>`.
fn sibling(path: &Path, what: &str, k: usize) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.trajkit-{what}-{}-{k}", std::process::id()))
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

    /// Writes everything queued (see the type documentation).
    pub fn commit(self) -> CliResult<()> {
        let err = |p: &Path, e: std::io::Error| CliError(format!("{}: {e}", p.display()));
        let is_special = |p: &Path| std::fs::metadata(p).is_ok_and(|m| !m.is_file());
        for (k, (path, _)) in self.files.iter().enumerate() {
            if self.files[..k].iter().any(|(p, _)| p == path) {
                return Err(CliError(format!(
                    "{}: given for two outputs of one run",
                    path.display()
                )));
            }
        }
        // 1. Every regular target's content to a temporary; nothing else is touched yet.
        let mut staged: Vec<Staged> = Vec::new();
        let mut special: Vec<(&Path, &str)> = Vec::new();
        for (k, (path, content)) in self.files.iter().enumerate() {
            if is_special(path) {
                special.push((path, content));
                continue;
            }
            let tmp = sibling(path, "tmp", k);
            if let Err(e) = std::fs::write(&tmp, content) {
                let _ = std::fs::remove_file(&tmp);
                rollback(&staged);
                return Err(err(path, e));
            }
            staged.push(Staged {
                target: path.clone(),
                tmp,
                backup: None,
                renamed: false,
            });
        }
        // 2. Keep every existing target aside, then rename the temporaries into place.
        for k in 0..staged.len() {
            if staged[k].target.exists() {
                let b = sibling(&staged[k].target, "bak", k);
                let kept = std::fs::hard_link(&staged[k].target, &b)
                    .or_else(|_| std::fs::copy(&staged[k].target, &b).map(|_| ()));
                if let Err(e) = kept {
                    let _ = std::fs::remove_file(&b);
                    let target = staged[k].target.clone();
                    rollback(&staged);
                    return Err(err(&target, e));
                }
                staged[k].backup = Some(b);
            }
        }
        for k in 0..staged.len() {
            if let Err(e) = std::fs::rename(&staged[k].tmp, &staged[k].target) {
                let target = staged[k].target.clone();
                rollback(&staged);
                return Err(err(&target, e));
            }
            staged[k].renamed = true;
        }
        // 3. Devices, in place.
        for (path, content) in special {
            if let Err(e) = std::fs::write(path, content) {
                rollback(&staged);
                return Err(err(path, e));
            }
        }
        for s in &staged {
            if let Some(b) = &s.backup {
                let _ = std::fs::remove_file(b);
            }
        }
        if let Some(s) = self.stdout {
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            // A reader that went away (`| head`) is not an error, as for any Unix filter.
            match out.write_all(s.as_bytes()).and_then(|()| out.flush()) {
                Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                    return Err(CliError(format!("<stdout>: {e}")));
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// Puts every target of a failed commit back as it was and removes the temporaries.
fn rollback(staged: &[Staged]) {
    for s in staged {
        if s.renamed {
            match &s.backup {
                Some(b) => {
                    let _ = std::fs::rename(b, &s.target);
                }
                None => {
                    let _ = std::fs::remove_file(&s.target);
                }
            }
        } else {
            let _ = std::fs::remove_file(&s.tmp);
            if let Some(b) = &s.backup {
                let _ = std::fs::remove_file(b);
            }
        }
    }
}

/// Joint names for people: the given ones, `qJ` (1-based) where a name is empty.
pub fn display_names(names: &[String]) -> Vec<String> {
    names
        .iter()
        .enumerate()
        .map(|(j, n)| {
            if n.is_empty() {
                format!("q{}", j + 1)
            } else {
                n.clone()
            }
        })
        .collect()
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
        say(format_args!("{summary}\n"));
    }
}

/// Writes `text` to standard output. A reader that went away (`trajkit plan | head`) ends the
/// process quietly with status 0, as a Unix filter does, instead of a panic; any other write
/// error is reported on stderr once and ends it with status 1.
pub fn say(text: fmt::Arguments<'_>) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(text).and_then(|()| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("trajkit: cannot write to standard output: {e}");
        std::process::exit(1);
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
