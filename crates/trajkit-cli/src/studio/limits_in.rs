//! Limits in a request: a robot preset or an uploaded file (URDF, MoveIt `joint_limits.yaml`,
//! trajkit JSON/YAML), then the same adjustments as the CLI's flags (MoveIt overrides,
//! completion from a preset, per-joint overrides, scaling), all through `trajkit::limits`.

use super::caps;
use super::error::{ApiError, ApiResult};
use serde::Deserialize;
use serde_json::json;
use trajkit::limits::load;
use trajkit::limits::{FillBy, LimitsSpec, Needs, PartialLimits, SpecStep, TextFile};
use trajkit::{Limits, Order};

/// An uploaded text file: its name (the extension tells the format) and its content.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileIn {
    /// File name, e.g. `robot.urdf`.
    pub name: String,
    /// Content.
    pub text: String,
}

/// The format of a limits file.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LimitsFormat {
    /// URDF `<limit>` tags (no acceleration or jerk: complete them).
    Urdf,
    /// MoveIt `joint_limits.yaml`.
    Moveit,
    /// trajkit's JSON limits format.
    Json,
    /// trajkit's YAML limits format.
    Yaml,
}

/// `limits` of a plan request. Exactly one of `preset` and `file`.
#[derive(Debug, Clone, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct LimitsIn {
    /// A robot preset: `panda`, `ur5e`, `iiwa14`.
    pub preset: Option<String>,
    /// A limits file.
    pub file: Option<FileIn>,
    /// The file's format (default: from the extension: `.urdf`/`.xml` URDF, `.json` trajkit
    /// JSON, `.yaml`/`.yml` MoveIt when a line starts with `joint_limits:`, else trajkit YAML).
    pub format: Option<LimitsFormat>,
    /// A MoveIt `joint_limits.yaml` whose joints override these limits by name.
    pub joint_limits: Option<FileIn>,
    /// Complete absent acceleration and jerk limits (e.g. of a URDF) from this preset.
    pub fill_from: Option<String>,
    /// Override every joint's maximum velocity (one value, or one per joint).
    pub max_velocity: Option<Vec<f64>>,
    /// Override maximum accelerations.
    pub max_acceleration: Option<Vec<f64>>,
    /// Override maximum jerks.
    pub max_jerk: Option<Vec<f64>>,
    /// Scale every velocity limit (default 1).
    pub velocity_scale: Option<f64>,
    /// Scale every acceleration limit (default 1).
    pub acceleration_scale: Option<f64>,
    /// Scale every jerk limit (default 1).
    pub jerk_scale: Option<f64>,
    /// Position ranges `[lo, hi]` (one for every joint, or one per joint; `null` for an
    /// unbounded end), for sources without them (a MoveIt file alone, a trajkit file without
    /// `position`).
    pub position_range: Option<Vec<[Option<f64>; 2]>>,
}

/// The format of `file`, from `format` or the file name.
fn format_of(file: &FileIn, format: Option<LimitsFormat>) -> ApiResult<LimitsFormat> {
    if let Some(f) = format {
        return Ok(f);
    }
    let ext = std::path::Path::new(&file.name)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match ext.as_str() {
        "urdf" | "xml" => Ok(LimitsFormat::Urdf),
        "json" => Ok(LimitsFormat::Json),
        "yaml" | "yml" => {
            let moveit = file.text.lines().any(|l| l.starts_with("joint_limits:"));
            Ok(if moveit {
                LimitsFormat::Moveit
            } else {
                LimitsFormat::Yaml
            })
        }
        _ => Err(ApiError::bad(
            "limits.file.name",
            json!(file.name),
            "has no known limits extension (.urdf, .xml, .json, .yaml, .yml): set limits.format",
        )),
    }
}

impl LimitsIn {
    /// The limits of `preset` or `file` (exactly one), before any adjustment.
    fn source(&self) -> ApiResult<PartialLimits> {
        let lib = |field: &'static str| move |e| ApiError::from_lib(field, e);
        Ok(match (&self.preset, &self.file) {
            (Some(p), None) => Limits::preset(p).map_err(lib("limits.preset"))?.into(),
            (None, Some(f)) => {
                caps::count(
                    "limits.file.text (bytes)",
                    f.text.len(),
                    1,
                    caps::MAX_BODY_BYTES,
                )?;
                match format_of(f, self.format)? {
                    LimitsFormat::Urdf => load::from_urdf_str(&f.text, &f.name),
                    LimitsFormat::Moveit => {
                        load::moveit_joint_limits_from_str(&f.text, &f.name, None)
                    }
                    LimitsFormat::Json => load::from_json_str(&f.text, &f.name),
                    LimitsFormat::Yaml => load::from_yaml_str(&f.text, &f.name),
                }
                .map_err(lib("limits.file"))?
            }
            _ => {
                return Err(ApiError::bad(
                    "limits",
                    json!(if self.preset.is_some() {
                        "preset and file"
                    } else {
                        "neither preset nor file"
                    }),
                    "is not allowed: give exactly one of limits.preset and limits.file",
                ))
            }
        })
    }

    /// Loads and adjusts the limits for data whose joints are `names` (matched by name when
    /// both sides name their joints, as `trajkit plan` does; overrides then apply per data
    /// column), keeping track of what was given ([`PartialLimits::complete`] refuses what a
    /// method needs and no source gave). Returns the limits and the limit joints left out.
    pub fn load(&self, names: Option<&[String]>) -> ApiResult<(PartialLimits, Vec<String>)> {
        let lib = |field: &'static str| move |e| ApiError::from_lib(field, e);
        let source = self.source()?;
        caps::count("limits (joint count)", source.dof(), 1, caps::MAX_JOINTS)?;
        for (values, field) in [
            (&self.max_velocity, "limits.max_velocity"),
            (&self.max_acceleration, "limits.max_acceleration"),
            (&self.max_jerk, "limits.max_jerk"),
        ] {
            for (j, &x) in values.iter().flatten().enumerate() {
                caps::positive(&format!("{field}[{j}]"), x)?;
            }
        }
        let scale = |v: Option<f64>, field: &str| -> ApiResult<f64> {
            v.map_or(Ok(1.0), |x| caps::positive(field, x))
        };
        let fill_from = match &self.fill_from {
            Some(p) => Some(Limits::preset(p).map_err(lib("limits.fill_from"))?.into()),
            None => None,
        };
        let dof = names.map_or(source.dof(), <[String]>::len);
        let spec = LimitsSpec {
            source: Some(source),
            joint_limits: self.joint_limits.as_ref().map(|f| TextFile {
                name: f.name.clone(),
                text: f.text.clone(),
            }),
            fill_from,
            fill_by: FillBy::Name,
            max_velocity: self.max_velocity.clone(),
            max_acceleration: self.max_acceleration.clone(),
            max_jerk: self.max_jerk.clone(),
            position_range: self.position_range.as_ref().map(|r| {
                r.iter()
                    .map(|[lo, hi]| (lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY)))
                    .collect()
            }),
            velocity_scale: scale(self.velocity_scale, "limits.velocity_scale")?,
            acceleration_scale: scale(self.acceleration_scale, "limits.acceleration_scale")?,
            jerk_scale: scale(self.jerk_scale, "limits.jerk_scale")?,
        };
        let r = spec.resolve("waypoint", names, dof).map_err(|e| {
            let field = match e.step {
                SpecStep::JointLimits => "limits.joint_limits",
                SpecStep::FillFrom => "limits.fill_from",
                SpecStep::Override(Order::Velocity) => "limits.max_velocity",
                SpecStep::Override(Order::Acceleration) => "limits.max_acceleration",
                SpecStep::Override(_) => "limits.max_jerk",
                SpecStep::PositionRange => "limits.position_range",
                _ => "limits",
            };
            ApiError::from_lib(field, e.error)
        })?;
        Ok((r.limits, r.unused))
    }
}

/// Completes `limits` with what `needs` asks for; a missing limit is a 400 naming the joint
/// and the field, and saying how a request supplies it.
pub fn complete(limits: &PartialLimits, needs: Needs) -> ApiResult<Limits> {
    limits.complete(needs).map_err(|e| match &e {
        trajkit::Error::MissingLimit { joint, name, field } => {
            let how = match *field {
                "velocity" => "limits.max_velocity or a file that has it",
                "acceleration" => "limits.max_acceleration, limits.fill_from or a file that has it",
                "jerk" => {
                    "limits.max_jerk, limits.fill_from, a file that has it, or jerk_limit false"
                }
                _ => "a limits file or preset with position ranges",
            };
            ApiError::bad(
                &format!("limits (joint {} {name} {field})", joint + 1),
                json!(null),
                format!("is missing: {e}; give {how}"),
            )
        }
        _ => ApiError::from_lib("limits", e),
    })
}
