//! `whirl`: the service binary.
//!
//! - `whirl` serves HTTP on `HOST:PORT` (defaults `0.0.0.0:8080`), settings from the environment;
//! - `whirl openapi` prints the OpenAPI document (the committed `openapi/openapi.json`);
//! - `whirl healthcheck` asks `GET /healthz` on `127.0.0.1:PORT` (exit 0 if 200): the container's
//!   HEALTHCHECK, which needs no curl in the image;
//! - `whirl --help`, `whirl --version`.

use std::io::{IsTerminal, Read, Write};
use std::process::ExitCode;
use std::time::Duration;

use whirl::service::config::SETTINGS;
use whirl::service::server::{ServerLimits, serve as serve_http};
use whirl::service::{self, Config};

/// Writes to stdout; a closed pipe (`whirl openapi | head`) ends quietly, not in a panic.
fn print(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("whirl: {e}");
            ExitCode::FAILURE
        }
    }
}

fn help() -> String {
    let mut s = format!(
        "whirl {} - rotordynamics computation service\n\n\
         usage: whirl [serve|openapi|healthcheck|--help|--version]\n\n\
         \x20 serve (default)  serve HTTP on HOST:PORT\n\
         \x20 openapi          print the OpenAPI document\n\
         \x20 healthcheck      exit 0 if GET /healthz on 127.0.0.1:PORT answers 200\n\n\
         settings (environment variables, default in brackets):\n",
        env!("CARGO_PKG_VERSION")
    );
    for set in SETTINGS {
        s.push_str(&format!(
            "  {} [{}]\n      {}\n",
            set.var, set.default, set.meaning
        ));
    }
    s
}

fn main() -> ExitCode {
    let arg = std::env::args().nth(1);
    match arg.as_deref() {
        None | Some("serve") => serve(),
        Some("openapi") => match serde_json::to_string_pretty(&service::openapi_document()) {
            Ok(s) => print(&(s + "\n")),
            Err(e) => {
                eprintln!("whirl: {e}");
                ExitCode::FAILURE
            }
        },
        Some("healthcheck") => healthcheck(),
        Some("-h" | "--help" | "help") => print(&help()),
        Some("-V" | "--version" | "version") => {
            print(&format!("whirl {}\n", env!("CARGO_PKG_VERSION")))
        }
        Some(other) => {
            eprintln!("whirl: unknown command {other:?} (try --help)");
            ExitCode::from(2)
        }
    }
}

fn serve() -> ExitCode {
    let config = match Config::from_env() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("whirl: bad setting: {e}");
            return ExitCode::from(2);
        }
    };
    init_tracing(config.log_json);
    raise_file_limit(config.max_connections + whirl::service::server::PROBE_CONNECTIONS);
    fixed_mmap_threshold();
    let rt = match tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
    {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("whirl: cannot start the runtime: {e}");
            return ExitCode::FAILURE;
        }
    };
    let code = match rt.block_on(run(config)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            tracing::error!("{e}");
            eprintln!("whirl: {e}");
            ExitCode::FAILURE
        }
    };
    // Analyses still running on blocking threads were cancelled; do not wait for them.
    rt.shutdown_timeout(Duration::from_secs(1));
    code
}

async fn run(config: Config) -> Result<(), String> {
    let addr = format!("{}:{}", config.host, config.port);
    let listener = tokio::net::TcpListener::bind(&addr)
        .await
        .map_err(|e| format!("cannot listen on {addr}: {e}"))?;
    // The address bound (PORT=0 picks a free port; tests read it here).
    let bound = listener
        .local_addr()
        .map_or(addr.clone(), |a| a.to_string());
    tracing::info!(
        addr = %bound,
        workers = config.workers,
        queue = config.queue,
        memory_budget_mb = config.memory_budget >> 20,
        "whirl listening (docs at /docs, OpenAPI at /openapi.json)"
    );
    let grace = config.shutdown_grace;
    let limits = ServerLimits::of(&config);
    let (app, state) = service::app_with_state(config);
    // One server per data directory: a second one stops here (its jobs would be run twice).
    state.jobs.store.claim_dir().map_err(|e| e.to_string())?;
    // Connect the job store now (and until it answers): the runner claims jobs from then on.
    let jobs = state.jobs.clone();
    tokio::spawn(async move {
        let store = jobs.store.describe();
        loop {
            match jobs.store.ping().await {
                Ok(()) => {
                    tracing::info!(%store, worker = %jobs.runner.worker, "job store ready");
                    break;
                }
                Err(e) => tracing::error!(
                    %store, error = %e,
                    "job store unreachable: jobs get 503 and /readyz fails until it answers"
                ),
            }
            tokio::time::sleep(Duration::from_secs(2)).await;
        }
    });
    let (stop_tx, stop_rx) = tokio::sync::watch::channel(false);
    tokio::spawn(async move {
        shutdown_signal().await;
        let _ = stop_tx.send(true);
    });
    let stopped = |mut rx: tokio::sync::watch::Receiver<bool>| async move {
        let _ = rx.wait_for(|s| *s).await;
    };
    // On the signal, the connections drain and the jobs get their grace at the same time:
    // both are bounded by `grace`, whatever the clients do.
    let server = serve_http(listener, app, limits, stopped(stop_rx.clone()), grace);
    let jobs = async {
        stopped(stop_rx).await;
        state.jobs.shutdown(grace).await;
    };
    tokio::join!(server, jobs);
    tracing::info!("stopped");
    Ok(())
}

async fn shutdown_signal() {
    let ctrl_c = async {
        tokio::signal::ctrl_c().await.ok();
    };
    #[cfg(unix)]
    let term = async {
        if let Ok(mut s) = tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate())
        {
            s.recv().await;
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! { _ = ctrl_c => {}, _ = term => {} }
    tracing::info!("shutting down: no new connections; requests and jobs get the grace period");
}

/// Logs go to stderr, coloured only on a terminal.
fn init_tracing(json: bool) {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info"));
    let builder = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::stderr().is_terminal());
    if json {
        builder.json().init();
    } else {
        builder.init();
    }
}

/// Large blocks (256 KiB and up: matrices, results, result chunks) are mapped and unmapped
/// by glibc on their own, so the server's resident size follows what it holds. glibc's
/// default raises this threshold after each large free (up to 32 MiB) and then keeps such
/// blocks in its arenas: the resident size then creeps up to the peaks of past analyses
/// (measured: +65 MB after 80 large job results, against +6 MB with the fixed threshold).
fn fixed_mmap_threshold() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets an allocator parameter; called before other threads start.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 256 << 10);
    }
}

/// Raises the open-file limit to its hard maximum, and warns when the connection limit does
/// not leave room for the rest (the listener, logs, blocking threads).
fn raise_file_limit(connections: usize) {
    #[cfg(unix)]
    // SAFETY: getrlimit/setrlimit write and read only the struct passed.
    unsafe {
        let mut lim = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        if libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) == 0 {
            if lim.rlim_cur < lim.rlim_max {
                lim.rlim_cur = lim.rlim_max;
                libc::setrlimit(libc::RLIMIT_NOFILE, &lim);
            }
            if (connections as u64).saturating_add(64) > lim.rlim_cur {
                tracing::warn!(
                    connections,
                    open_files = lim.rlim_cur,
                    "WHIRL_MAX_CONNECTIONS is close to the open-file limit"
                );
            }
        }
    }
}

fn healthcheck() -> ExitCode {
    let port = std::env::var("PORT").unwrap_or_else(|_| "8080".into());
    let addr = format!("127.0.0.1:{port}");
    let ok = (|| -> std::io::Result<bool> {
        let sock = addr
            .parse()
            .map_err(|_| std::io::Error::other("bad PORT"))?;
        let mut s = std::net::TcpStream::connect_timeout(&sock, Duration::from_secs(2))?;
        s.set_read_timeout(Some(Duration::from_secs(2)))?;
        s.write_all(b"GET /healthz HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n")?;
        let mut buf = String::new();
        s.read_to_string(&mut buf)?;
        Ok(buf.starts_with("HTTP/1.1 200"))
    })()
    .unwrap_or(false);
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
