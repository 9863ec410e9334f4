//! `trajkit studio`: the specification's interactive lessons as a local web app, served by the
//! `trajkit` binary on the library itself.
//!
//! The page draws; the library computes. Every number on the page comes from a JSON endpoint
//! whose handler translates the request into one library call and the result back
//! (`lessons/`, [`plan`], [`otg`]); no algorithm is written in JavaScript. The page's files are
//! embedded in the binary ([`assets`]), so it works offline.
//!
//! - [`server`]: routes, bodies (JSON only, size-capped), the bounded worker pools (plans,
//!   everything else) that keep computations off the async executor, 503 when every worker
//!   stays busy.
//! - [`error`]: the API's error type and its JSON form (status, message, field, value).
//! - [`caps`]: the work one request may ask for (waypoints, gridpoints, samples, ...).
//! - [`lessons`]: one module per lesson (polynomials, Catmull-Rom, B-spline/NURBS, trapezoid vs
//!   S-curve, movement primitives); [`plan`] (+ [`limits_in`], [`phase`]) is the planning
//!   lesson and `POST /api/plan`; [`otg`] is `POST /api/otg`.
//!
//! The server binds 127.0.0.1 unless told otherwise; on a loopback address it also refuses
//! requests whose Host header names another host (DNS rebinding).

pub mod assets;
pub mod caps;
pub mod error;
pub mod lessons;
pub mod limits_in;
pub mod otg;
pub mod phase;
pub mod plan;
pub mod server;

use crate::cmd::common::{CliError, CliResult};
use clap::Args;
use std::io::Write;
use std::net::SocketAddr;

/// Arguments of `trajkit studio`.
#[derive(Args, Debug)]
#[command(
    after_help = "Examples:\n  trajkit studio                      # http://127.0.0.1:8765/\n  trajkit studio --addr 127.0.0.1:0   # any free port (printed)\n\nThe API is documented in README.md (\"Studio\"); GET /api lists the endpoints."
)]
pub struct StudioArgs {
    /// Address to listen on. Anything but a loopback address makes the studio reachable from
    /// other machines.
    #[arg(long, value_name = "IP:PORT", default_value = "127.0.0.1:8765")]
    pub addr: SocketAddr,
    /// Computations run at the same time, per class (plans; everything else), each on its
    /// own thread; further requests wait (see --queue-timeout).
    #[arg(long, value_name = "N", default_value_t = default_workers(), value_parser = clap::value_parser!(u16).range(1..=64))]
    pub workers: u16,
    /// Longest wait in seconds for a free worker before a request is refused with 503
    /// (0.01 to 3600).
    #[arg(long, value_name = "SECONDS", default_value_t = 20.0, value_parser = parse_wait)]
    pub queue_timeout: f64,
}

/// Parses `--queue-timeout`.
fn parse_wait(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (0.01..=3600.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "'{s}' is not a number of seconds from 0.01 to 3600"
        )),
    }
}

fn default_workers() -> u16 {
    std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .clamp(2, 16) as u16
}

/// Runs the server until Ctrl-C.
pub fn run(a: &StudioArgs) -> CliResult<u8> {
    let workers = usize::from(a.workers);
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .max_blocking_threads(2 * workers + 2)
        .enable_all()
        .build()
        .map_err(|e| CliError(format!("studio: cannot start the runtime: {e}")))?;
    rt.block_on(async {
        let listener = tokio::net::TcpListener::bind(a.addr)
            .await
            .map_err(|e| CliError(format!("--addr {}: {e}", a.addr)))?;
        let local = listener
            .local_addr()
            .map_err(|e| CliError(format!("--addr {}: {e}", a.addr)))?;
        let hosts = if local.ip().is_loopback() {
            let port = local.port();
            let mut hosts = vec![
                format!("127.0.0.1:{port}"),
                format!("localhost:{port}"),
                format!("[::1]:{port}"),
            ];
            if !hosts.contains(&local.to_string()) {
                hosts.push(local.to_string());
            }
            hosts
        } else {
            eprintln!(
                "trajkit studio: listening on {local}: reachable from other machines, without authentication"
            );
            Vec::new()
        };
        println!("trajkit studio: http://{local}/ (Ctrl-C to stop)");
        let _ = std::io::stdout().flush();
        let wait = std::time::Duration::from_secs_f64(a.queue_timeout);
        let app = server::router(server::AppState::new(workers, wait, hosts));
        axum::serve(listener, app)
            .with_graceful_shutdown(async {
                let _ = tokio::signal::ctrl_c().await;
            })
            .await
            .map_err(|e| CliError(format!("studio: {e}")))
    })?;
    Ok(0)
}
