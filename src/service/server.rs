//! The HTTP server loop: what no client may hold forever.
//!
//! - at most `max_connections` open connections, and at most `max_connections_per_client`
//!   from one address, so one client cannot take them all;
//! - beyond those, [`PROBE_CONNECTIONS`] more are reserved for the probes: such a connection
//!   must send its headers within [`PROBE_HEADER_TIMEOUT`], and only `/healthz` and `/readyz`
//!   are answered on it (anything else gets 503 with `Retry-After`), so a flood of connections
//!   that never finish their headers cannot make an orchestrator restart a healthy server;
//!   past the reserve too, a connection is answered 503 and closed at once;
//! - a request's headers must arrive within `header_timeout`, which also bounds how long an
//!   idle keep-alive connection is kept (hyper starts that timer whenever it waits for a
//!   request);
//! - a client that stops reading, or reads slower than [`super::slow::MIN_WRITE_RATE`] over
//!   `write_timeout` of waiting, is dropped (see [`super::slow`]);
//! - the body's own deadline is the JSON extractor's (`WHIRL_BODY_TIMEOUT`);
//! - on shutdown the listener closes at once, connections finish their requests within
//!   `drain`, and then the server returns whatever is left open.

use std::collections::HashMap;
use std::future::Future;
use std::net::IpAddr;
use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use axum::response::IntoResponse;
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::io::AsyncWriteExt;
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::Semaphore;
use tower::Service;

use super::slow::WriteTimeout;

/// Connections kept for the probes beyond the limits.
pub const PROBE_CONNECTIONS: usize = 16;
/// Time a connection in the probes' reserve has to send its headers.
pub const PROBE_HEADER_TIMEOUT: Duration = Duration::from_secs(1);

/// Connection limits of the server.
#[derive(Debug, Clone, Copy)]
pub struct ServerLimits {
    pub max_connections: usize,
    pub max_connections_per_client: usize,
    pub header_timeout: Duration,
    pub write_timeout: Duration,
}

impl ServerLimits {
    pub fn of(c: &super::Config) -> Self {
        ServerLimits {
            max_connections: c.max_connections,
            max_connections_per_client: c.max_connections_per_client,
            header_timeout: c.header_timeout,
            write_timeout: c.write_timeout,
        }
    }
}

/// Open connections per client address.
#[derive(Default)]
struct Clients(std::sync::Mutex<HashMap<IpAddr, usize>>);

/// One connection of a client, counted while it lives.
struct ClientSlot {
    clients: Arc<Clients>,
    ip: IpAddr,
}

impl Clients {
    /// A place for one more connection of `ip`, if it has fewer than `cap`.
    fn take(self: &Arc<Self>, ip: IpAddr, cap: usize) -> Option<ClientSlot> {
        let mut map = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let n = map.entry(ip).or_insert(0);
        if *n >= cap {
            return None;
        }
        *n += 1;
        Some(ClientSlot {
            clients: self.clone(),
            ip,
        })
    }
}

impl Drop for ClientSlot {
    fn drop(&mut self) {
        let mut map = self.clients.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(n) = map.get_mut(&self.ip) {
            *n -= 1;
            if *n == 0 {
                map.remove(&self.ip);
            }
        }
    }
}

/// Whether a request is a probe (answered on a reserved connection).
fn is_probe<B>(req: &hyper::Request<B>) -> bool {
    matches!(req.uri().path(), "/healthz" | "/readyz")
        && matches!(*req.method(), hyper::Method::GET | hyper::Method::HEAD)
}

/// The answer to a connection over the limit.
async fn refuse(mut stream: TcpStream) {
    let body = serde_json::to_vec(&super::ApiError::Busy.problem()).unwrap_or_default();
    let head = format!(
        "HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/problem+json\r\n\
         retry-after: 1\r\nconnection: close\r\ncontent-length: {}\r\n\r\n",
        body.len()
    );
    let write = async {
        stream.write_all(head.as_bytes()).await?;
        stream.write_all(&body).await?;
        stream.shutdown().await
    };
    let _ = tokio::time::timeout(Duration::from_secs(1), write).await;
}

/// Serves `app` on `listener` until `shutdown` resolves, then lets open connections finish
/// their requests for at most `drain` and returns.
pub async fn serve(
    listener: TcpListener,
    app: Router,
    limits: ServerLimits,
    shutdown: impl Future<Output = ()>,
    drain: Duration,
) {
    let connections = Arc::new(Semaphore::new(limits.max_connections));
    let reserve = Arc::new(Semaphore::new(PROBE_CONNECTIONS));
    let clients = Arc::new(Clients::default());
    let graceful = hyper_util::server::graceful::GracefulShutdown::new();
    let mut http = hyper::server::conn::http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(limits.header_timeout)
        .keep_alive(true);
    let mut probe_http = hyper::server::conn::http1::Builder::new();
    probe_http
        .timer(TokioTimer::new())
        .header_read_timeout(limits.header_timeout.min(PROBE_HEADER_TIMEOUT))
        .keep_alive(false);
    tokio::pin!(shutdown);
    loop {
        let accepted = tokio::select! {
            r = listener.accept() => r,
            () = &mut shutdown => break,
        };
        let (stream, peer) = match accepted {
            Ok(a) => a,
            Err(e) => {
                // Out of file descriptors or a transient error: back off, keep serving.
                tracing::warn!(error = %e, "accept failed");
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        let _ = stream.set_nodelay(true);
        let io = TokioIo::new(WriteTimeout::new(stream, limits.write_timeout));
        let tower = app.clone();
        let general = clients
            .take(peer.ip(), limits.max_connections_per_client)
            .and_then(|slot| Some((slot, connections.clone().try_acquire_owned().ok()?)));
        if let Some(held) = general {
            let service = hyper::service::service_fn(move |req: hyper::Request<Incoming>| {
                tower.clone().call(req)
            });
            let conn = graceful.watch(http.serve_connection(io, service));
            tokio::spawn(async move {
                let _held = held;
                if let Err(e) = conn.await {
                    tracing::debug!(error = %e, "connection ended with an error");
                }
            });
            continue;
        }
        let Ok(permit) = reserve.clone().try_acquire_owned() else {
            tracing::warn!(
                limit = limits.max_connections,
                per_client = limits.max_connections_per_client,
                client = %peer.ip(),
                "connection limit reached (WHIRL_MAX_CONNECTIONS, \
                 WHIRL_MAX_CONNECTIONS_PER_CLIENT): refused with 503"
            );
            tokio::spawn(refuse(io.into_inner().inner));
            continue;
        };
        // The probes' reserve: headers at once, probes only, one request.
        let service = hyper::service::service_fn(move |req: hyper::Request<Incoming>| {
            let tower = tower.clone();
            async move {
                if is_probe(&req) {
                    tower.clone().call(req).await
                } else {
                    Ok(super::ApiError::Busy.into_response())
                }
            }
        });
        let conn = graceful.watch(probe_http.serve_connection(io, service));
        tokio::spawn(async move {
            let _permit = permit;
            if let Err(e) = conn.await {
                tracing::debug!(error = %e, "probe connection ended with an error");
            }
        });
    }
    drop(listener);
    tracing::info!("no longer accepting connections; draining open ones");
    tokio::select! {
        () = graceful.shutdown() => tracing::info!("connections drained"),
        () = tokio::time::sleep(drain) => {
            tracing::warn!(drain_s = drain.as_secs_f64(), "connections still open after the drain time: closing them");
        }
    }
}
