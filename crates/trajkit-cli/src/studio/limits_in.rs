//! Limits in a request: a robot preset or an uploaded file (URDF, MoveIt `joint_limits.yaml`,
//! trajkit JSON/YAML), then the same adjustments as the CLI's flags (MoveIt overrides,
//! completion from a preset, per-joint overrides, scaling), all through `trajkit::limits`.

use super::caps;
use super::error::{ApiError, ApiResult};
use serde::Deserialize;
use serde_json::json;
use trajkit::limits::load;
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
    /// Loads and adjusts the limits.
    pub fn load(&self) -> ApiResult<Limits> {
        let lib = |field: &'static str| move |e| ApiError::from_lib(field, e);
        let mut l = match (&self.preset, &self.file) {
            (Some(p), None) => Limits::preset(p).map_err(lib("limits.preset"))?,
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
        };
        caps::count("limits (joint count)", l.dof(), 1, caps::MAX_JOINTS)?;
        if let Some(f) = &self.joint_limits {
            l = load::apply_moveit_joint_limits(&l, &f.text, &f.name)
                .map_err(lib("limits.joint_limits"))?;
        }
        if let Some(p) = &self.fill_from {
            let from = Limits::preset(p).map_err(lib("limits.fill_from"))?;
            l = load::fill_missing(&l, &from).map_err(lib("limits.fill_from"))?;
        }
        for (order, values, field) in [
            (Order::Velocity, &self.max_velocity, "limits.max_velocity"),
            (
                Order::Acceleration,
                &self.max_acceleration,
                "limits.max_acceleration",
            ),
            (Order::Jerk, &self.max_jerk, "limits.max_jerk"),
        ] {
            if let Some(v) = values {
                for (j, &x) in v.iter().enumerate() {
                    caps::positive(&format!("{field}[{j}]"), x)?;
                }
                l = l.with_override(order, v).map_err(lib(field))?;
            }
        }
        let scale = |v: Option<f64>, field: &str| -> ApiResult<f64> {
            v.map_or(Ok(1.0), |x| caps::positive(field, x))
        };
        let (sv, sa, sj) = (
            scale(self.velocity_scale, "limits.velocity_scale")?,
            scale(self.acceleration_scale, "limits.acceleration_scale")?,
            scale(self.jerk_scale, "limits.jerk_scale")?,
        );
        if (sv, sa, sj) != (1.0, 1.0, 1.0) {
            l = l.scaled(sv, sa, sj).map_err(lib("limits"))?;
        }
        Ok(l)
    }
}

/// Refuses limits that do not bound `order` for some joint: a missing limit is an error, not
/// "unlimited". The message says how to supply it.
pub fn require(limits: &Limits, order: Order, why: &str) -> ApiResult<()> {
    for (j, jl) in limits.joints().iter().enumerate() {
        let (lo, hi) = jl.range(order);
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(ApiError::bad(
                &format!("limits (joint {} {} {})", j + 1, jl.name, order.name()),
                json!("inf"),
                format!(
                    "is missing: {why} needs every joint's {0} limit; give limits.fill_from, limits.max_{0} or a file that has it",
                    order.name()
                ),
            ));
        }
    }
    Ok(())
}
