//! `voussoir serve`: the arch explorer in the browser (src/serve/, docs/web.md).

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::sync::Arc;
use voussoir::error::{AnalysisError, Error};
use voussoir::scene::Scene;
use voussoir::serve::{self, Limits, ServerState};

#[derive(clap::Args)]
pub struct Args {
    /// Scene the page opens with (default: the bundled semicircular arch)
    scene: Option<PathBuf>,
    /// Override a value of the scene, e.g. --set arch.thickness=0.2 (repeatable)
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
    /// Port on 127.0.0.1 (0: any free port, printed on the first line)
    #[arg(long, default_value_t = serve::DEFAULT_ADDR.port())]
    port: u16,
    /// Largest arch.voussoirs (and pier courses) a request may ask for
    #[arg(long, default_value_t = Limits::default().max_voussoirs)]
    max_voussoirs: usize,
}

fn other(message: String) -> Error {
    Error::Analysis(AnalysisError::Other(message))
}

pub fn run(args: Args) -> Result<String, Error> {
    let limits = Limits {
        max_voussoirs: args.max_voussoirs,
        ..Limits::default()
    };
    let scene = match &args.scene {
        Some(path) => Scene::from_file_with_overrides(path, &args.set)?,
        None => Scene::from_toml_str(serve::parameters::DEFAULT_SCENE, serve::DEFAULT_ORIGIN)?
            .with_overrides(&args.set)?,
    };
    let state = ServerState::new(scene, limits);
    let grace = state.timeouts.shutdown_grace;
    // Loopback only: the page is for the person at this machine.
    let addr = SocketAddr::new(IpAddr::V4(Ipv4Addr::LOCALHOST), args.port);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| other(format!("cannot start the server's runtime: {e}")))?;
    let stopped: Result<serve::Stopped, Error> = runtime.block_on(async move {
        let listener = tokio::net::TcpListener::bind(addr).await.map_err(|e| {
            other(format!(
                "cannot listen on {addr}: {e} (is another server on that port? try --port 0)"
            ))
        })?;
        let local = listener
            .local_addr()
            .map_err(|e| other(format!("cannot read the listening address: {e}")))?;
        {
            use std::io::Write;
            let mut out = std::io::stdout().lock();
            // The first line is read by scripts and the end-to-end tests: keep its form.
            let _ = writeln!(out, "voussoir serve: listening on http://{local}/");
            let _ = writeln!(out, "open it in a browser; Ctrl-C stops the server");
            let _ = out.flush();
        }
        Ok(serve::serve(listener, Arc::new(state)).await)
    });
    // A request still running past the grace (a long sweep's case) is not waited for: its
    // blocking thread ends with the process.
    runtime.shutdown_background();
    Ok(match stopped? {
        serve::Stopped::Clean => "voussoir serve: stopped".into(),
        serve::Stopped::GraceExpired { open } => format!(
            "voussoir serve: stopped ({open} connection{} still open after {} s were closed)",
            if open == 1 { "" } else { "s" },
            grace.as_secs_f64()
        ),
    })
}
