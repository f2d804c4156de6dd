//! A real server on a loopback port, stopped when dropped.

use std::time::Duration;

use whirl::service::server::{ServerLimits, serve};
use whirl::service::{AppState, Config, app_with_state};

pub struct Server {
    pub addr: std::net::SocketAddr,
    pub state: AppState,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
}

impl Drop for Server {
    fn drop(&mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
    }
}

/// Serves `config` on 127.0.0.1 at a free port (shutdown grace 1 s).
pub async fn start(config: Config) -> Server {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let limits = ServerLimits::of(&config);
    let (app, state) = app_with_state(config);
    let (tx, rx) = tokio::sync::oneshot::channel::<()>();
    tokio::spawn(serve(
        listener,
        app,
        limits,
        async {
            let _ = rx.await;
        },
        Duration::from_secs(1),
    ));
    Server {
        addr,
        state,
        stop: Some(tx),
    }
}
