//! Slow readers: a connection's writes must keep a minimum rate.
//!
//! A write that cannot go on (the client's socket buffer is full) starts the clock. Over every
//! `WHIRL_WRITE_TIMEOUT` spent waiting on such writes, at least [`MIN_WRITE_RATE`] bytes a
//! second of that time must have gone out, else the connection is dropped. A client that stops
//! reading is dropped after the timeout (nothing went out), and so is one that trickles (a
//! reader of 4 KB/s holds a large answer for minutes otherwise, since every byte it takes would
//! restart a plain no-progress timer). Time the server itself spends producing is not counted:
//! only waits on a full socket are.

use std::future::Future;
use std::io;
use std::pin::Pin;
use std::task::{Context, Poll};
use std::time::Duration;

use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::time::{Instant, Sleep};

/// The slowest reader kept, bytes a second of waiting (32 KiB/s: a 256 kbit/s link).
pub const MIN_WRITE_RATE: u64 = 32 << 10;

/// A stream whose writes fail when the client reads too slowly (see the module docs).
pub struct WriteTimeout<T> {
    pub(super) inner: T,
    timeout: Duration,
    /// Waiting on writes in the current window.
    waited: Duration,
    /// Bytes written in the current window.
    written: u64,
    /// Since when the current write has been waiting.
    since: Option<Instant>,
    /// Fires at the end of the window, if the wait goes on until then.
    timer: Option<Pin<Box<Sleep>>>,
}

impl<T> WriteTimeout<T> {
    pub fn new(inner: T, timeout: Duration) -> Self {
        WriteTimeout {
            inner,
            timeout,
            waited: Duration::ZERO,
            written: 0,
            since: None,
            timer: None,
        }
    }

    /// The least a window of waiting must have written.
    fn least(&self) -> u64 {
        (MIN_WRITE_RATE as f64 * self.timeout.as_secs_f64()).ceil() as u64
    }

    /// Ends the window if its waiting time is spent: an error if it wrote too little.
    fn close_window(&mut self) -> io::Result<()> {
        if self.waited < self.timeout {
            return Ok(());
        }
        if self.written < self.least() {
            return Err(io::Error::new(
                io::ErrorKind::TimedOut,
                format!(
                    "the client read {} bytes in {:.1} s of waiting, slower than {} bytes/s \
                     (WHIRL_WRITE_TIMEOUT)",
                    self.written,
                    self.waited.as_secs_f64(),
                    MIN_WRITE_RATE
                ),
            ));
        }
        self.waited = Duration::ZERO;
        self.written = 0;
        Ok(())
    }

    /// A write went through (`n` bytes).
    fn progress(&mut self, n: usize) -> io::Result<()> {
        self.written += n as u64;
        if let Some(since) = self.since.take() {
            self.waited += since.elapsed();
            self.timer = None;
        }
        self.close_window()
    }

    /// A write must wait: start or check the window's clock.
    fn stall(&mut self, cx: &mut Context<'_>) -> Poll<io::Error> {
        loop {
            let now = Instant::now();
            let since = *self.since.get_or_insert(now);
            let left = self.timeout.saturating_sub(self.waited);
            let timer = self
                .timer
                .get_or_insert_with(|| Box::pin(tokio::time::sleep_until(since + left)));
            if timer.as_mut().poll(cx).is_pending() {
                return Poll::Pending;
            }
            // The window's waiting time is spent while this write still waits.
            self.waited += now.saturating_duration_since(since);
            self.since = None;
            self.timer = None;
            self.waited = self.waited.max(self.timeout);
            if let Err(e) = self.close_window() {
                return Poll::Ready(e);
            }
        }
    }

    fn outcome<R>(
        &mut self,
        r: Poll<io::Result<R>>,
        cx: &mut Context<'_>,
        written: impl Fn(&R) -> usize,
    ) -> Poll<io::Result<R>> {
        match r {
            Poll::Ready(Ok(v)) => Poll::Ready(self.progress(written(&v)).map(|()| v)),
            Poll::Ready(Err(e)) => Poll::Ready(Err(e)),
            Poll::Pending => self.stall(cx).map(Err),
        }
    }
}

impl<T: AsyncRead + Unpin> AsyncRead for WriteTimeout<T> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_read(cx, buf)
    }
}

impl<T: AsyncWrite + Unpin> AsyncWrite for WriteTimeout<T> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        let r = Pin::new(&mut self.inner).poll_write(cx, buf);
        self.outcome(r, cx, |n| *n)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let r = Pin::new(&mut self.inner).poll_flush(cx);
        self.outcome(r, cx, |_| 0)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let r = Pin::new(&mut self.inner).poll_shutdown(cx);
        self.outcome(r, cx, |_| 0)
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        let r = Pin::new(&mut self.inner).poll_write_vectored(cx, bufs);
        self.outcome(r, cx, |n| *n)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }
}
