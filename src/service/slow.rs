//! Slow readers: a connection's writes must keep a minimum rate.
//!
//! A write that cannot go on (the client's socket buffer is full) starts the clock. Over every
//! `WHIRL_WRITE_TIMEOUT` spent waiting on such writes, at least [`MIN_WRITE_RATE`] bytes a
//! second of that time must have gone out, else the connection is dropped. A client that stops
//! reading is dropped after the timeout (nothing went out), and so is one that trickles (a
//! reader of 4 KB/s holds a large answer for minutes otherwise, since every byte it takes would
//! restart a plain no-progress timer). Time the server itself spends producing is not counted:
//! only waits on a full socket are.
//!
//! One wait of a whole timeout (nothing at all went out) drops the connection too, whatever its
//! window wrote before: a client that stops reading after a fast start is dropped a timeout
//! after its last read, not a window later.
//!
//! A window counts the bytes written from its first wait on: what went out before (into the
//! socket's empty buffer, on loopback megabytes at once) says nothing of the client's pace, and
//! counted it would let a trickling reader through its first window. A wait that comes a
//! timeout or more after the last one ended opens a fresh window (the client kept up meanwhile).
//!
//! A dropped connection is reset ([`Reset`]: `SO_LINGER` 0, as nginx's
//! `reset_timedout_connection`), not closed: a plain close leaves what the kernel still holds
//! for the client (megabytes of socket buffer) to trickle out after the drop, for minutes, and
//! the client sees its answer end only then.

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
    /// Since when the current write has been waiting, and up to when that wait is in `waited`.
    wait: Option<(Instant, Instant)>,
    /// When the last wait ended.
    last_wait: Option<Instant>,
    /// Fires at the end of the window or of a timeout of this wait, whichever comes first.
    timer: Option<Pin<Box<Sleep>>>,
}

/// A connection that can be reset: dropped with nothing more sent (see the module docs).
pub trait Reset {
    /// Makes the coming close a reset, discarding what the kernel still holds to send.
    fn reset(&self);
}

impl Reset for tokio::net::TcpStream {
    fn reset(&self) {
        if let Err(e) = self.set_zero_linger() {
            tracing::debug!(error = %e, "could not set SO_LINGER 0 on a slow reader's socket");
        }
    }
}

fn timed_out(what: String) -> io::Error {
    io::Error::new(io::ErrorKind::TimedOut, what)
}

impl<T> WriteTimeout<T> {
    pub fn new(inner: T, timeout: Duration) -> Self {
        WriteTimeout {
            inner,
            timeout,
            waited: Duration::ZERO,
            written: 0,
            wait: None,
            last_wait: None,
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
            return Err(timed_out(format!(
                "the client read {} bytes in {:.1} s of waiting, slower than {} bytes/s \
                 (WHIRL_WRITE_TIMEOUT)",
                self.written,
                self.waited.as_secs_f64(),
                MIN_WRITE_RATE
            )));
        }
        self.waited = Duration::ZERO;
        self.written = 0;
        Ok(())
    }

    /// A write went through (`n` bytes).
    fn progress(&mut self, n: usize) -> io::Result<()> {
        self.written += n as u64;
        if let Some((_, counted)) = self.wait.take() {
            let now = Instant::now();
            self.waited += now.saturating_duration_since(counted);
            self.last_wait = Some(now);
            self.timer = None;
        }
        self.close_window()
    }

    /// A write must wait: start or check the clocks.
    fn stall(&mut self, cx: &mut Context<'_>) -> Poll<io::Error> {
        if self.wait.is_none() {
            let now = Instant::now();
            if self
                .last_wait
                .is_none_or(|t| now.saturating_duration_since(t) >= self.timeout)
            {
                // The first wait, or the first after a timeout of none: a fresh window,
                // which counts nothing written before it.
                self.waited = Duration::ZERO;
                self.written = 0;
            }
            self.wait = Some((now, now));
        }
        loop {
            let Some((since, counted)) = self.wait else {
                unreachable!("set above")
            };
            // The window ends when its waiting reaches the timeout; this wait ends the
            // connection when it alone reaches the timeout, whatever the window wrote before.
            let end =
                (counted + self.timeout.saturating_sub(self.waited)).min(since + self.timeout);
            let timer = self
                .timer
                .get_or_insert_with(|| Box::pin(tokio::time::sleep_until(end)));
            if timer.as_mut().poll(cx).is_pending() {
                return Poll::Pending;
            }
            self.timer = None;
            let now = Instant::now();
            if now >= since + self.timeout {
                return Poll::Ready(timed_out(format!(
                    "the client read nothing for {:.1} s (WHIRL_WRITE_TIMEOUT)",
                    now.saturating_duration_since(since).as_secs_f64()
                )));
            }
            // The window's waiting time is spent while this write still waits.
            self.waited = (self.waited + now.saturating_duration_since(counted)).max(self.timeout);
            self.wait = Some((since, now));
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
    ) -> Poll<io::Result<R>>
    where
        T: Reset,
    {
        let r = match r {
            Poll::Ready(Ok(v)) => Poll::Ready(self.progress(written(&v)).map(|()| v)),
            Poll::Ready(Err(e)) => return Poll::Ready(Err(e)),
            Poll::Pending => self.stall(cx).map(Err),
        };
        if matches!(&r, Poll::Ready(Err(e)) if e.kind() == io::ErrorKind::TimedOut) {
            self.inner.reset();
        }
        r
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

impl<T: AsyncWrite + Reset + Unpin> AsyncWrite for WriteTimeout<T> {
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

#[cfg(test)]
mod tests {
    //! On an in-memory pipe (`tokio::io::duplex`) of a small buffer, in real time: a writer of
    //! `total` bytes through a [`WriteTimeout`], and a reader taking a few bytes at a time.

    use super::*;
    use tokio::io::{AsyncReadExt, AsyncWriteExt, DuplexStream};

    impl Reset for DuplexStream {
        fn reset(&self) {}
    }

    const TIMEOUT: Duration = Duration::from_millis(1000);

    /// How a writer fared.
    struct Run {
        /// Bytes the writer got through.
        written: usize,
        /// Bytes the reader took.
        read: usize,
        /// The error that stopped the writer, and when (from the first write).
        stopped: Option<(io::Error, Duration)>,
    }

    /// Writes `total` bytes in writes of 16 KiB (each after `produce`, the server's own time)
    /// into a pipe of `buffer` bytes whose reader takes up to `take` bytes every `every`
    /// (never, if `take` is 0).
    async fn run(
        buffer: usize,
        total: usize,
        produce: Duration,
        take: usize,
        every: Duration,
    ) -> Run {
        let (a, mut b) = tokio::io::duplex(buffer);
        let read = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let r = read.clone();
        let reader = tokio::spawn(async move {
            let mut buf = vec![0u8; take.max(1)];
            loop {
                tokio::time::sleep(every).await;
                if take == 0 {
                    continue;
                }
                match b.read(&mut buf).await {
                    Ok(0) | Err(_) => return,
                    Ok(n) => r.fetch_add(n, std::sync::atomic::Ordering::SeqCst),
                };
            }
        });
        let mut w = WriteTimeout::new(a, TIMEOUT);
        let chunk = vec![7u8; 16 << 10];
        let (mut written, mut stopped) = (0, None);
        let t0 = Instant::now();
        while written < total {
            if !produce.is_zero() {
                tokio::time::sleep(produce).await;
            }
            let n = chunk.len().min(total - written);
            match w.write(&chunk[..n]).await {
                Ok(n) => written += n,
                Err(e) => {
                    stopped = Some((e, t0.elapsed()));
                    break;
                }
            }
        }
        drop(w);
        if stopped.is_some() || take == 0 {
            // What the reader took until the writer was stopped (the pipe keeps the rest).
            reader.abort();
        } else {
            reader.await.unwrap();
        }
        let read = read.load(std::sync::atomic::Ordering::SeqCst);
        Run {
            written,
            read,
            stopped,
        }
    }

    /// The time a writer was stopped at, checked to be a timeout.
    fn stopped_at(r: &Run) -> Duration {
        let (e, at) = r.stopped.as_ref().expect("the writer was stopped");
        assert_eq!(e.kind(), io::ErrorKind::TimedOut, "{e}");
        *at
    }

    #[tokio::test]
    async fn a_reader_that_stops_reading_is_dropped_after_the_timeout() {
        let r = run(4096, 10 << 20, Duration::ZERO, 0, Duration::ZERO).await;
        let at = stopped_at(&r);
        eprintln!(
            "stalled reader: dropped after {at:?} and {} bytes",
            r.written
        );
        assert!(
            at >= TIMEOUT && at < TIMEOUT + Duration::from_millis(400),
            "{at:?}"
        );
        assert_eq!(r.written, 4096, "what the pipe holds");
    }

    #[tokio::test]
    async fn a_reader_that_trickles_is_dropped_within_one_window() {
        // 4 KB/s against 32 KiB/s: 400 bytes every 100 ms, always some progress. The pipe's
        // 256 KiB, written before any wait (a kernel's socket buffer on loopback holds
        // megabytes), is more than a window's minimum of 32 KiB and must not count.
        let r = run(
            256 << 10,
            10 << 20,
            Duration::ZERO,
            400,
            Duration::from_millis(100),
        )
        .await;
        let at = stopped_at(&r);
        eprintln!(
            "trickling reader: dropped after {at:?}, {} bytes written, {} read",
            r.written, r.read
        );
        assert!(at >= TIMEOUT && at < TIMEOUT * 3 / 2, "{at:?}");
        assert!(r.read > 0 && r.read < 8 << 10, "{} bytes read", r.read);
    }

    #[tokio::test]
    async fn a_reader_faster_than_the_minimum_is_never_dropped() {
        // 64 KiB/s (twice the minimum) in reads of 3.2 KiB, for 3.5 windows, on a 4 KiB pipe:
        // the writer waits nearly all the time.
        let total = 224 << 10;
        let r = run(4096, total, Duration::ZERO, 3277, Duration::from_millis(50)).await;
        assert!(r.stopped.is_none(), "dropped: {:?}", r.stopped);
        assert_eq!((r.written, r.read), (total, total));
    }

    #[tokio::test]
    async fn time_the_writer_does_not_wait_is_not_counted() {
        // The server produces 16 KiB every 0.6 s (27 KiB/s, under the minimum) for 3 windows
        // and the reader takes everything at once: the writer never waits on the client.
        let total = 80 << 10;
        let t0 = Instant::now();
        let r = run(
            64 << 10,
            total,
            Duration::from_millis(600),
            64 << 10,
            Duration::from_millis(10),
        )
        .await;
        assert!(r.stopped.is_none(), "dropped: {:?}", r.stopped);
        assert_eq!((r.written, r.read), (total, total));
        assert!(t0.elapsed() >= TIMEOUT * 3, "{:?}", t0.elapsed());
    }

    #[tokio::test]
    async fn a_window_of_keeping_up_does_not_excuse_a_stall_after_it() {
        // Fast for a while (many windows' minimum written), then the reader stops: dropped a
        // timeout after its last read, not later.
        let (a, mut b) = tokio::io::duplex(4096);
        let mut w = WriteTimeout::new(a, TIMEOUT);
        let fast = 1 << 20;
        let reader = tokio::spawn(async move {
            let mut buf = vec![0u8; 64 << 10];
            let mut read = 0;
            while read < fast {
                read += b.read(&mut buf).await.unwrap();
            }
            let last = Instant::now();
            tokio::time::sleep(TIMEOUT * 3).await;
            (b, last)
        });
        let chunk = vec![7u8; 16 << 10];
        let err = loop {
            if let Err(e) = w.write(&chunk).await {
                break e;
            }
        };
        let dropped = Instant::now();
        let (_b, last) = reader.await.unwrap();
        assert_eq!(err.kind(), io::ErrorKind::TimedOut, "{err}");
        let after = dropped - last;
        eprintln!("stalled after 1 MiB: dropped {after:?} after the last read");
        assert!(after >= TIMEOUT && after < TIMEOUT * 3 / 2, "{after:?}");
    }
}
