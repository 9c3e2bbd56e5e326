//! `voussoir serve`: the arch explorer in the browser and the JSON API behind it.
//!
//! One page (three embedded files, [`assets`]) and four JSON endpoints ([`api`]), all on the
//! same analysis layer as the CLI: `POST /api/analyze` returns exactly the object
//! `voussoir analyze --json` prints, plus the drawing `analyze --svg` writes; `POST
//! /api/sweep` runs [`crate::sweep::Sweep`], as `voussoir sweep` does. The server holds no
//! policy of its own beyond its [`Limits`]: scenes are validated by [`crate::scene`], and the
//! slider ranges the page shows come from [`parameters`].
//!
//! Safety: the server binds to loopback ([`DEFAULT_ADDR`]) and answers only requests that say
//! they are for this machine and come from its own page ([`api::same_machine_only`]: the
//! `Host`, the `Origin`, and JSON bodies, so that no other web site open in the user's browser
//! can use it); request bodies, block counts and sweep sizes are limited, and sweeps run a few
//! at a time and stop when their client has gone; no client is waited for without end
//! ([`Timeouts`]: a request's head and body must arrive in time, an idle connection is closed,
//! and Ctrl-C waits a bounded grace for the requests in flight, [`serve_until`]); a request
//! that cannot be analysed is answered with a 400 and the message (naming the scene key when
//! there is one), and a panic in an analysis is caught and answered with a 500, never a
//! crash. The server reads no files on request: a scene's
//! `blocks.file` is accepted only when it is the file of the scene the server was started
//! with.

pub mod api;
pub mod assets;
pub mod parameters;

use crate::scene::Scene;
use std::future::Future;
use std::net::{Ipv4Addr, SocketAddr};
use std::sync::Arc;
use std::time::Duration;

/// Where `voussoir serve` listens unless told otherwise: loopback only, port 8080.
pub const DEFAULT_ADDR: SocketAddr =
    SocketAddr::new(std::net::IpAddr::V4(Ipv4Addr::LOCALHOST), 8080);

/// What one request may ask for. The defaults keep every answer fast on a laptop (the page's
/// update target is 50 ms for n <= 200); the CLI takes larger scenes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Largest request body (bytes); a larger one is answered with 413.
    pub max_body_bytes: usize,
    /// Largest `arch.voussoirs`, and largest number of pier courses on each side.
    pub max_voussoirs: usize,
    /// Largest number of the user's blocks (`blocks.polygons`).
    pub max_blocks: usize,
    /// Largest number of cases in one `/api/sweep`.
    pub max_sweep_points: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_body_bytes: 64 * 1024,
            max_voussoirs: 1000,
            max_blocks: 1000,
            max_sweep_points: 101,
        }
    }
}

/// How long the server waits for a client, and for itself when asked to stop. Without
/// them one client that sends half a request and stays holds its connection for ever, and
/// Ctrl-C (which waits for open requests) never stops the server.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Timeouts {
    /// Time a client has to send a request's head (request line and headers), counted from
    /// when the connection is ready for one: from its opening, and on a kept-alive
    /// connection from the end of the previous answer. So it is also the idle (keep-alive)
    /// timeout: a connection that sends nothing for this long is closed.
    pub header_read: Duration,
    /// Time a client has to send a request's body, counted from its head.
    pub body_read: Duration,
    /// After Ctrl-C: how long requests in flight may take to finish (no new connection is
    /// taken meanwhile) before the server stops without them.
    pub shutdown_grace: Duration,
}

impl Default for Timeouts {
    fn default() -> Self {
        Timeouts {
            header_read: Duration::from_secs(20),
            body_read: Duration::from_secs(20),
            shutdown_grace: Duration::from_secs(5),
        }
    }
}

/// What the server knows: the scene it was started with, its limits and its timeouts.
#[derive(Debug)]
pub struct ServerState {
    /// The scene the page opens with (`GET /api/scene`). Request scenes are read relative
    /// to its directory.
    pub scene: Scene,
    pub limits: Limits,
    pub timeouts: Timeouts,
    /// Sweeps running at once (each is parallel already): more wait their turn.
    pub(crate) sweeps: tokio::sync::Semaphore,
}

/// How the bundled start scene is named (`GET /api/scene`'s `origin`, and in messages).
pub const DEFAULT_ORIGIN: &str = "bundled semicircular arch";

/// Sweeps that may run at once.
const CONCURRENT_SWEEPS: usize = 2;

impl ServerState {
    /// The state of a server opening with `scene`.
    pub fn new(scene: Scene, limits: Limits) -> Self {
        ServerState {
            scene,
            limits,
            timeouts: Timeouts::default(),
            sweeps: tokio::sync::Semaphore::new(CONCURRENT_SWEEPS),
        }
    }

    /// The same state with other timeouts.
    pub fn with_timeouts(mut self, timeouts: Timeouts) -> Self {
        self.timeouts = timeouts;
        self
    }

    /// The start scene's `blocks.file`, as written in it, when it has one: the only file a
    /// request may name (resolved against the start scene's directory).
    pub(crate) fn blocks_file(&self) -> Option<&str> {
        self.scene.table().get("blocks")?.get("file")?.as_str()
    }

    /// The state of a server opening with the bundled semicircular arch.
    pub fn with_default_scene(limits: Limits) -> Result<Self, crate::error::SceneError> {
        let scene = Scene::from_toml_str(parameters::DEFAULT_SCENE, DEFAULT_ORIGIN)?;
        Ok(ServerState::new(scene, limits))
    }
}

/// The router: the page's three files and the API.
pub fn router(state: Arc<ServerState>) -> axum::Router {
    use axum::routing::{get, post};
    let limit = state.limits.max_body_bytes;
    axum::Router::new()
        .route("/", get(assets::index))
        .route("/app.js", get(assets::script))
        .route("/style.css", get(assets::style))
        .route("/api/scene", get(api::scene))
        .route("/api/parameters", get(api::parameters))
        .route("/api/analyze", post(api::analyze))
        .route("/api/sweep", post(api::sweep))
        .route("/api/report", post(api::report))
        .fallback(api::not_found)
        .method_not_allowed_fallback(api::method_not_allowed)
        .layer(axum::middleware::from_fn_with_state(
            state.timeouts.body_read,
            api::body_deadline,
        ))
        .layer(axum::middleware::from_fn(api::same_machine_only))
        .layer(axum::extract::DefaultBodyLimit::max(limit))
        .with_state(state)
}

/// Serve `state` on `listener` until Ctrl-C (then as [`serve_until`]).
pub async fn serve(listener: tokio::net::TcpListener, state: Arc<ServerState>) -> Stopped {
    serve_until(listener, state, async {
        // An error here means no signal handler could be installed: then the server runs
        // until it is killed, which is what Ctrl-C would have done.
        if tokio::signal::ctrl_c().await.is_err() {
            std::future::pending::<()>().await;
        }
    })
    .await
}

/// How the server stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stopped {
    /// Every request in flight was answered.
    Clean,
    /// This many connections were still open (a request being answered, or one whose
    /// client had not finished sending it) when the shutdown grace ran out: they were closed.
    GraceExpired { open: usize },
}

/// Serve `state` on `listener` until `shutdown` completes; then take no new connection, let
/// the requests in flight finish for at most [`Timeouts::shutdown_grace`], and return.
///
/// The connection loop is hyper's own, not `axum::serve`: that one sets no timer, so hyper's
/// header-read timeout never runs and a client that sends half a request (or opens a
/// connection and says nothing) keeps it open for ever, and with it the graceful shutdown.
/// HTTP/1 only (the page is on loopback).
pub async fn serve_until(
    listener: tokio::net::TcpListener,
    state: Arc<ServerState>,
    shutdown: impl Future<Output = ()>,
) -> Stopped {
    use hyper_util::rt::{TokioIo, TokioTimer};
    let timeouts = state.timeouts;
    let app = router(state);
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(timeouts.header_read)
        .keep_alive(true);
    let graceful = hyper_util::server::graceful::GracefulShutdown::new();
    // One clone per open connection: how many are left when the grace runs out.
    let open = Arc::new(());
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let stream = tokio::select! {
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => stream,
                Err(e) => {
                    // A connection that failed before it was taken (reset, aborted) is the
                    // client's affair; anything else (out of file descriptors) passes
                    // with time, so wait a little rather than spin or stop serving.
                    use std::io::ErrorKind::*;
                    if !matches!(e.kind(), ConnectionAborted | ConnectionReset | ConnectionRefused) {
                        eprintln!("voussoir serve: cannot take a connection: {e}");
                        tokio::time::sleep(Duration::from_millis(200)).await;
                    }
                    continue;
                }
            },
            () = &mut shutdown => break,
        };
        let service = hyper_util::service::TowerToHyperService::new(app.clone());
        let connection = graceful.watch(http.serve_connection(TokioIo::new(stream), service));
        let token = open.clone();
        tokio::spawn(async move {
            // A connection's error (a client gone, a head not sent in time) ends that
            // connection only.
            let _ = connection.await;
            drop(token);
        });
    }
    drop(listener);
    match tokio::time::timeout(timeouts.shutdown_grace, graceful.shutdown()).await {
        Ok(()) => Stopped::Clean,
        Err(_) => Stopped::GraceExpired {
            open: Arc::strong_count(&open).saturating_sub(1),
        },
    }
}
