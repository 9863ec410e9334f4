//! The HTTP side: routes, the embedded page, request bodies, and the bounded pool that runs
//! every computation off the async executor.
//!
//! Each API request is answered in three steps: the executor checks the method, the content
//! type and the body size (cheap, never blocks); the request then waits (at most the queue
//! timeout, `--queue-timeout`, 20 s by default) for one of `workers` permits of its class;
//! with a permit, `spawn_blocking` parses the JSON, calls the lesson's function and serializes
//! the answer on tokio's blocking pool. A slow request therefore holds one worker and no
//! executor thread: static files, refusals and the other workers keep going. There are two
//! classes with `workers` permits each: plans (`/api/plan`, up to about a second each) and
//! everything else (milliseconds), so that the lessons' dragging stays responsive while plans
//! are computed. When every worker of a class stays busy past the queue timeout, the request
//! is refused with 503 instead of queueing forever.

use super::assets;
use super::caps::MAX_BODY_BYTES;
use super::error::{parse_json, ApiError, ApiResult};
use super::{lessons, otg, plan};
use axum::body::Bytes;
use axum::extract::rejection::{BytesRejection, QueryRejection};
use axum::extract::{Path, Query, Request, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post, MethodRouter};
use axum::{extract::DefaultBodyLimit, Router};
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::json;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::Semaphore;

/// Shared by every request.
#[derive(Clone)]
pub struct AppState {
    /// Permits of the plans.
    heavy: Arc<Semaphore>,
    /// Permits of every other computation.
    light: Arc<Semaphore>,
    workers: usize,
    queue_wait: Duration,
    /// `host:port` names accepted in the Host header (DNS-rebinding guard) when listening on
    /// loopback; empty when any host is accepted.
    hosts: Arc<Vec<String>>,
}

impl AppState {
    /// `workers` computations at once per class, each request waiting at most `queue_wait`
    /// for one; `hosts` as in the field's documentation.
    pub fn new(workers: usize, queue_wait: Duration, hosts: Vec<String>) -> Self {
        AppState {
            heavy: Arc::new(Semaphore::new(workers)),
            light: Arc::new(Semaphore::new(workers)),
            workers,
            queue_wait,
            hosts: Arc::new(hosts),
        }
    }
}

/// A computed answer: status, content type, body, and a download name.
pub struct Reply {
    status: StatusCode,
    content_type: &'static str,
    body: Vec<u8>,
    attachment: Option<&'static str>,
}

impl Reply {
    fn json<T: Serialize>(r: ApiResult<T>) -> Reply {
        match r.and_then(|v| {
            serde_json::to_vec(&v)
                .map_err(|e| ApiError::plain(StatusCode::INTERNAL_SERVER_ERROR, e.to_string()))
        }) {
            Ok(body) => Reply {
                status: StatusCode::OK,
                content_type: "application/json",
                body,
                attachment: None,
            },
            Err(e) => Reply::error(&e),
        }
    }

    fn error(e: &ApiError) -> Reply {
        Reply {
            status: e.status,
            content_type: "application/json",
            body: e.body().to_string().into_bytes(),
            attachment: None,
        }
    }
}

impl IntoResponse for Reply {
    fn into_response(self) -> Response {
        let mut r = (self.status, self.body).into_response();
        let h = r.headers_mut();
        h.insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static(self.content_type),
        );
        h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
        if let Some(name) = self.attachment {
            h.insert(header::CONTENT_DISPOSITION, HeaderValue::from_static(name));
        }
        r
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        Reply::error(&self).into_response()
    }
}

/// Runs `job` on the blocking pool once a worker of `pool` is free (see the module
/// documentation); the refusal when none is free in time (503) or the job failed (500).
async fn compute<F, T>(st: &AppState, pool: &Arc<Semaphore>, job: F) -> Result<T, Reply>
where
    F: FnOnce() -> T + Send + 'static,
    T: Send + 'static,
{
    let permit = match tokio::time::timeout(st.queue_wait, pool.clone().acquire_owned()).await {
        Ok(Ok(p)) => p,
        _ => {
            return Err(Reply::error(&ApiError::plain(
                StatusCode::SERVICE_UNAVAILABLE,
                format!(
                    "busy: all {} workers of this kind of request stayed busy for {} s; try again",
                    st.workers,
                    st.queue_wait.as_secs_f64()
                ),
            )))
        }
    };
    match tokio::task::spawn_blocking(move || {
        let _permit = permit;
        job()
    })
    .await
    {
        Ok(v) => Ok(v),
        Err(e) => Err(Reply::error(&ApiError::plain(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("internal error (a bug in trajkit, please report it): {e}"),
        ))),
    }
}

fn either(r: Result<Reply, Reply>) -> Reply {
    r.unwrap_or_else(|e| e)
}

/// The body of a JSON request, or the refusal: 413 beyond the cap, 415 without a JSON
/// content type.
fn body(headers: &HeaderMap, body: Result<Bytes, BytesRejection>) -> ApiResult<Bytes> {
    let json = headers
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.trim_start().starts_with("application/json"));
    if !json {
        return Err(ApiError::plain(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "the request body must be JSON, sent with 'Content-Type: application/json'",
        ));
    }
    body.map_err(|e| {
        let status = e.status();
        if status == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::plain(
                status,
                format!("the request body exceeds the cap of {MAX_BODY_BYTES} bytes"),
            )
        } else {
            ApiError::plain(status, format!("request body: {}", e.body_text()))
        }
    })
}

/// A `POST` endpoint whose answer is `f` of the parsed JSON body.
fn endpoint<Req, Resp>(f: fn(Req) -> ApiResult<Resp>) -> MethodRouter<AppState>
where
    Req: DeserializeOwned + Send + 'static,
    Resp: Serialize + 'static,
{
    post(
        move |State(st): State<AppState>,
              headers: HeaderMap,
              raw: Result<Bytes, BytesRejection>| async move {
            let bytes = match body(&headers, raw) {
                Ok(b) => b,
                Err(e) => return Reply::error(&e),
            };
            either(
                compute(&st, &st.light, move || {
                    Reply::json(parse_json::<Req>(&bytes).and_then(f))
                })
                .await,
            )
        },
    )
}

async fn plan_endpoint(
    State(st): State<AppState>,
    query: Result<Query<plan::Query>, QueryRejection>,
    headers: HeaderMap,
    raw: Result<Bytes, BytesRejection>,
) -> Reply {
    let format = match query {
        Ok(Query(q)) => q.format,
        Err(e) => {
            return Reply::error(
                &ApiError::plain(StatusCode::BAD_REQUEST, format!("query: {}", e.body_text()))
                    .field("format"),
            )
        }
    };
    let bytes = match body(&headers, raw) {
        Ok(b) => b,
        Err(e) => return Reply::error(&e),
    };
    // Read and check on a light worker (bad requests are refused at once), plan on a heavy one.
    let prepared = match compute(&st, &st.light, move || {
        parse_json::<plan::Request>(&bytes).and_then(plan::prepare)
    })
    .await
    {
        Ok(Ok(p)) => p,
        Ok(Err(e)) => return Reply::error(&e),
        Err(reply) => return reply,
    };
    either(
        compute(&st, &st.heavy, move || match plan::run(prepared, format) {
            Ok(plan::Output::Summary(r)) => Reply::json(Ok(r)),
            Ok(plan::Output::Table(content_type, text)) => Reply {
                status: StatusCode::OK,
                content_type,
                body: text.into_bytes(),
                attachment: Some(if content_type == "text/csv" {
                    "attachment; filename=\"trajectory.csv\""
                } else {
                    "attachment; filename=\"trajectory.json\""
                }),
            },
            Err(e) => Reply::error(&e),
        })
        .await,
    )
}

async fn otg_endpoint(
    State(st): State<AppState>,
    headers: HeaderMap,
    raw: Result<Bytes, BytesRejection>,
) -> Reply {
    let bytes = match body(&headers, raw) {
        Ok(b) => b,
        Err(e) => return Reply::error(&e),
    };
    either(
        compute(&st, &st.light, move || {
            Reply::json(otg::otg_request(&bytes))
        })
        .await,
    )
}

fn static_file(name: &str) -> Response {
    match assets::find(name) {
        Some((content_type, bytes)) => {
            let mut r = (StatusCode::OK, bytes).into_response();
            let h = r.headers_mut();
            h.insert(header::CONTENT_TYPE, HeaderValue::from_static(content_type));
            h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
            h.insert(
                header::X_CONTENT_TYPE_OPTIONS,
                HeaderValue::from_static("nosniff"),
            );
            // Everything the page loads comes from this server: no CDN, works offline.
            h.insert(
                header::CONTENT_SECURITY_POLICY,
                HeaderValue::from_static(
                    "default-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:",
                ),
            );
            r
        }
        None => (StatusCode::NOT_FOUND, "not found\n").into_response(),
    }
}

/// The API's own index: every endpoint with a one-line description.
fn api_index() -> serde_json::Value {
    json!({
        "name": "trajkit studio",
        "version": env!("CARGO_PKG_VERSION"),
        "endpoints": [
            {"method": "GET", "path": "/api/health", "does": "liveness"},
            {"method": "POST", "path": "/api/polynomials", "does": "cubic/quintic/septic profiles, peak coefficients, limits"},
            {"method": "POST", "path": "/api/catmull-rom", "does": "Catmull-Rom curves (uniform, centripetal, chordal)"},
            {"method": "POST", "path": "/api/bspline", "does": "B-spline/NURBS curve, degree comparison, basis functions, supports"},
            {"method": "POST", "path": "/api/profiles", "does": "trapezoid vs S-curve for D, v_max, a_max, j_max"},
            {"method": "POST", "path": "/api/plan", "does": "waypoints + limits + method -> trajectory, check, phase plane (?format=csv|json for the table)"},
            {"method": "GET", "path": "/api/plan/defaults", "does": "the default path and the robot presets"},
            {"method": "POST", "path": "/api/otg", "does": "the JSON of trajkit otg in, the JSON it writes out"},
            {"method": "POST", "path": "/api/dmp", "does": "DMP from a demonstration, rollout to a new goal"},
            {"method": "POST", "path": "/api/promp", "does": "ProMP from demonstrations, mean and band, via points"},
        ],
    })
}

/// Refuses requests whose Host header is not one of this server's loopback names (a web page
/// elsewhere cannot reach the API through a rebound DNS name).
async fn host_guard(State(st): State<AppState>, req: Request, next: Next) -> Response {
    if !st.hosts.is_empty() {
        let host = req
            .headers()
            .get(header::HOST)
            .and_then(|h| h.to_str().ok())
            .unwrap_or("");
        if !st.hosts.iter().any(|h| h == host) {
            return ApiError::plain(
                StatusCode::FORBIDDEN,
                format!(
                    "Host '{host}' is not this server (expected {})",
                    st.hosts.join(" or ")
                ),
            )
            .into_response();
        }
    }
    next.run(req).await
}

/// The whole application.
pub fn router(state: AppState) -> Router {
    Router::new()
        .route("/", get(|| async { static_file("index.html") }))
        .route(
            "/assets/{*path}",
            get(|Path(p): Path<String>| async move { static_file(&p) }),
        )
        .route("/api", get(|| async { axum::Json(api_index()) }))
        .route(
            "/api/health",
            get(|| async { axum::Json(json!({"status": "ok"})) }),
        )
        .route("/api/polynomials", endpoint(lessons::polynomials::handle))
        .route("/api/catmull-rom", endpoint(lessons::catmull_rom::handle))
        .route("/api/bspline", endpoint(lessons::bspline::handle))
        .route("/api/profiles", endpoint(lessons::profiles::handle))
        .route("/api/dmp", endpoint(lessons::primitives::dmp))
        .route("/api/promp", endpoint(lessons::primitives::promp))
        .route("/api/plan", post(plan_endpoint))
        .route(
            "/api/plan/defaults",
            get(|| async { axum::Json(plan::defaults()) }),
        )
        .route("/api/otg", post(otg_endpoint))
        .fallback(|req: Request| async move {
            let path = req.uri().path().to_string();
            if path.starts_with("/api") {
                ApiError::plain(
                    StatusCode::NOT_FOUND,
                    format!("no endpoint {path} (see GET /api)"),
                )
                .field("path")
                .into_response()
            } else {
                (StatusCode::NOT_FOUND, "not found\n").into_response()
            }
        })
        .method_not_allowed_fallback(|req: Request| async move {
            ApiError::plain(
                StatusCode::METHOD_NOT_ALLOWED,
                format!(
                    "{} is not allowed on {} (see GET /api)",
                    req.method(),
                    req.uri().path()
                ),
            )
            .into_response()
        })
        .layer(DefaultBodyLimit::max(MAX_BODY_BYTES))
        .layer(middleware::from_fn_with_state(state.clone(), host_guard))
        .with_state(state)
}
