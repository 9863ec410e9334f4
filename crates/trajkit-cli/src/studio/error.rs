//! The one error type of the studio's API and its JSON form.
//!
//! Every refused request gets a status and a body
//! `{"error": {"message": "...", "field": "...", "value": ...}}`: `message` is one line, like
//! the CLI's (it names the field and the value); `field` is the request field at fault when
//! known (a JSON path such as `limits.velocity_scale` or `waypoints[3][1]`), else `null`;
//! `value` is the offending value when there is one (a number, or a string such as `"NaN"`).
//! Statuses: 400 bad input, 404 unknown path, 405 wrong method, 413 body too large, 415 not
//! JSON, 422 valid input without a solution (an infeasible plan, limits exceeded), 503 every
//! worker busy for too long, 500 a bug (never expected).

use axum::http::StatusCode;
use serde_json::{json, Value};

/// A refused request: status, message, and the field and value at fault when known.
#[derive(Debug, Clone, PartialEq)]
pub struct ApiError {
    /// HTTP status.
    pub status: StatusCode,
    /// One line naming the field and the value.
    pub message: String,
    /// The request field at fault (a JSON path), when known.
    pub field: Option<String>,
    /// The offending value, when there is one.
    pub value: Option<Value>,
}

/// Shorthand.
pub type ApiResult<T> = Result<T, ApiError>;

/// A number as a JSON value: finite numbers stay numbers, NaN and infinities become strings.
pub fn number(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else if v.is_nan() {
        json!("NaN")
    } else if v > 0.0 {
        json!("inf")
    } else {
        json!("-inf")
    }
}

impl ApiError {
    /// 400: `field` = `value` is refused, because `reason`.
    pub fn bad(field: &str, value: Value, reason: impl std::fmt::Display) -> Self {
        let shown = match &value {
            Value::String(s) => format!("'{s}'"),
            other => other.to_string(),
        };
        ApiError {
            status: StatusCode::BAD_REQUEST,
            message: format!("{field} = {shown} {reason}"),
            field: Some(field.to_string()),
            value: Some(value),
        }
    }

    /// A status with a message and no field.
    pub fn plain(status: StatusCode, message: impl Into<String>) -> Self {
        ApiError {
            status,
            message: message.into(),
            field: None,
            value: None,
        }
    }

    /// A library error met while handling request field `field` (e.g. `"limits.file"`); the
    /// library's message already names its own field and value. Infeasible problems are 422,
    /// everything else 400.
    pub fn from_lib(field: &str, e: trajkit::Error) -> Self {
        use trajkit::Error as E;
        let value = match &e {
            E::InvalidValue { value, .. } => Some(number(*value)),
            E::DimensionMismatch { found, .. } | E::TooFewWaypoints { found, .. } => {
                Some(json!(found))
            }
            E::DuplicateWaypoint { index } => Some(json!(index)),
            E::UnknownPreset { name, .. } => Some(json!(name)),
            _ => None,
        };
        let status = match e {
            E::Infeasible(_) => StatusCode::UNPROCESSABLE_ENTITY,
            E::Io { .. } => StatusCode::INTERNAL_SERVER_ERROR,
            _ => StatusCode::BAD_REQUEST,
        };
        let message = if field.is_empty() {
            e.to_string()
        } else {
            format!("{field}: {e}")
        };
        ApiError {
            status,
            message,
            field: (!field.is_empty()).then(|| field.to_string()),
            value,
        }
    }

    /// Returns a copy naming `field` as the field at fault.
    pub fn field(mut self, field: &str) -> Self {
        self.field = Some(field.to_string());
        self
    }

    /// The JSON body.
    pub fn body(&self) -> Value {
        json!({"error": {
            "message": self.message,
            "field": self.field,
            "value": self.value,
        }})
    }
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {}", self.status.as_u16(), self.message)
    }
}

/// Parses a JSON request body into `T`; a failure names the JSON path of the field at fault
/// (serde's message quotes the value or the unknown field).
pub fn parse_json<T: serde::de::DeserializeOwned>(body: &[u8]) -> ApiResult<T> {
    let de = &mut serde_json::Deserializer::from_slice(body);
    match serde_path_to_error::deserialize::<_, T>(de) {
        Ok(v) => Ok(v),
        Err(e) => {
            let path = e.path().to_string();
            let inner = e.into_inner();
            let field = (path != ".").then_some(path);
            let message = match &field {
                Some(p) => format!("{p}: {inner}"),
                None => format!("request body: {inner}"),
            };
            Err(ApiError {
                status: StatusCode::BAD_REQUEST,
                message,
                field,
                value: None,
            })
        }
    }
}
