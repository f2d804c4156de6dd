//! `whirl`: the service binary.
//!
//! - `whirl` serves HTTP on `HOST:PORT` (defaults `0.0.0.0:8080`), settings from the environment;
//! - `whirl openapi` prints the OpenAPI document (the committed `openapi/openapi.json`);
//! - `whirl healthcheck` asks `GET /healthz` on `127.0.0.1:PORT` (exit 0 if 200): the container's
//!   HEALTHCHECK, which needs no curl in the image.

use std::io::{Read, Write};
use std::process::ExitCode;
use std::time::Duration;

use whirl::service::{self, Config};

fn main() -> ExitCode {
    let arg = std::env::args().nth(1);
    match arg.as_deref() {
        None | Some("serve") => serve(),
        Some("openapi") => {
            match service::openapi_document().to_pretty_json() {
                Ok(s) => println!("{s}"),
                Err(e) => {
                    eprintln!("whirl: {e}");
                    return ExitCode::FAILURE;
                }
            }
            ExitCode::SUCCESS
        }
        Some("healthcheck") => healthcheck(),
        Some("-h" | "--help" | "help") => {
            println!(
                "whirl [serve|openapi|healthcheck]\n\n\
                 serve (default)  serve HTTP on HOST:PORT (0.0.0.0:8080)\n\
                 openapi          print the OpenAPI document\n\
                 healthcheck      exit 0 if GET /healthz on 127.0.0.1:PORT answers 200\n\n\
                 Environment: HOST, PORT, WHIRL_WORKERS, WHIRL_QUEUE, WHIRL_MAX_BODY_BYTES,\n\
                 WHIRL_MAX_SPEEDS, WHIRL_LOG_FORMAT (text|json), RUST_LOG (e.g. info)."
            );
            ExitCode::SUCCESS
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
    match rt.block_on(run(config)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            tracing::error!("{e}");
            eprintln!("whirl: {e}");
            ExitCode::FAILURE
        }
    }
}

async fn run(config: Config) -> Result<(), String> {
    let addr = format!("{}:{}", config.host, config.port);
    let listener = tokio::net::TcpListener::bind(&addr)
        .await
        .map_err(|e| format!("cannot listen on {addr}: {e}"))?;
    tracing::info!(
        %addr,
        workers = config.workers,
        queue = config.queue,
        "whirl listening (docs at /docs, OpenAPI at /openapi.json)"
    );
    let grace = Duration::from_secs(config.shutdown_grace);
    let (app, state) = service::app_with_state(config);
    axum::serve(listener, app)
        .with_graceful_shutdown(shutdown_signal())
        .await
        .map_err(|e| e.to_string())?;
    // No new connections now; jobs get the grace period, then are cancelled with the reason.
    state.jobs.shutdown(grace).await;
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
    tracing::info!("shutting down: no new connections, finishing requests in flight");
}

fn init_tracing(json: bool) {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info,tower_http=info"));
    let builder = tracing_subscriber::fmt().with_env_filter(filter);
    if json {
        builder.json().init();
    } else {
        builder.init();
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
