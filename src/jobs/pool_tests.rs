//! The worker pool's lanes, admission and memory budget.

use super::*;
use crate::model::limits::Size;

fn cost(work: f64, bytes: u64) -> Cost {
    let size = Size {
        assembled: 1,
        dofs: 1,
        internal: 0,
        problems: 1,
        points: 1,
    };
    let mut c = Cost::new(size, 0, 0, 0, 0).with_work(work);
    c.peak_bytes = bytes;
    c
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_panic_fails_the_request_not_the_pool() {
    let pool = WorkerPool::new(1, 0, 1, 1 << 30);
    let c = cost(1.0, 1);
    let a = pool.admit(&c, "rotor").unwrap();
    let r: Result<(), ApiError> = pool.run(a, || {}, || panic!("boom")).await;
    assert!(matches!(r, Err(ApiError::Internal(_))));
    let a = pool.admit(&c, "rotor").unwrap();
    assert_eq!(pool.run(a, || {}, || 7).await.unwrap(), 7);
    assert_eq!(pool.in_flight(), 0);
}

#[test]
fn lanes_and_the_budget() {
    assert_eq!(Lane::of(&cost(1e6, 1 << 20)), Lane::Short);
    assert_eq!(Lane::of(&cost(1e12, 1 << 20)), Lane::Long);
    assert_eq!(Lane::of(&cost(1e6, 1 << 30)), Lane::Long);
    let pool = WorkerPool::new(2, 2, 2, 2 << 30);
    assert!(matches!(
        pool.admit(&cost(1e12, 8 << 30), "rotor"),
        Err(ApiError::Invalid(_))
    ));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_full_queue_refuses_at_once() {
    let test = async {
        let pool = Arc::new(WorkerPool::new(1, 1, 1, 1 << 30));
        let long = cost(1e12, 1 << 20);
        let (tx, rx) = std::sync::mpsc::channel::<()>();
        let p = pool.clone();
        let a = pool.admit(&long, "rotor").unwrap();
        let running = tokio::spawn(async move {
            p.run(
                a,
                || {},
                move || {
                    rx.recv().ok();
                },
            )
            .await
        });
        // The first analysis holds the only worker before the second one queues.
        while pool.long.available_permits() > 0 {
            tokio::time::sleep(std::time::Duration::from_millis(1)).await;
        }
        let p = pool.clone();
        let a = pool.admit(&long, "rotor").unwrap();
        let waiting = tokio::spawn(async move { p.run(a, || {}, || ()).await });
        assert!(!pool.ready());
        assert!(matches!(pool.admit(&long, "rotor"), Err(ApiError::Busy)));
        tx.send(()).unwrap();
        running.await.unwrap().unwrap();
        waiting.await.unwrap().unwrap();
        assert!(pool.ready());
        assert_eq!(pool.in_flight(), 0);
    };
    tokio::time::timeout(std::time::Duration::from_secs(20), test)
        .await
        .expect("the pool test must not hang");
}

#[test]
fn a_full_long_queue_still_admits_short_analyses() {
    // 1 worker and 1 waiting place: two long sweeps fill the long lane.
    let pool = WorkerPool::new(1, 1, 2, 1 << 30);
    let long = cost(1e12, 1 << 20);
    let short = cost(1e6, 1 << 20);
    let held: Vec<Admission> = (0..2)
        .map(|_| pool.admit(&long, "rotor").unwrap())
        .collect();
    assert!(matches!(pool.admit(&long, "rotor"), Err(ApiError::Busy)));
    // The short lane has its own count: 2 per core x 2 threads running + 1 waiting.
    let shorts: Vec<Admission> = (0..5)
        .map(|_| pool.admit(&short, "rotor").unwrap())
        .collect();
    assert!(matches!(pool.admit(&short, "rotor"), Err(ApiError::Busy)));
    assert_eq!(pool.in_flight(), 7);
    drop(shorts);
    drop(held);
    assert_eq!(pool.in_flight(), 0);
    assert!(pool.admit(&short, "rotor").is_ok());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn long_analyses_wait_for_memory() {
    let pool = Arc::new(WorkerPool::new(4, 4, 1, 1 << 30));
    let budget = pool.memory_budget();
    let big = cost(1e12, budget * 3 / 4);
    let (tx, rx) = std::sync::mpsc::channel::<()>();
    let a = pool.admit(&big, "rotor").unwrap();
    let p = pool.clone();
    let first = tokio::spawn(async move {
        p.run(
            a,
            || {},
            move || {
                rx.recv().ok();
            },
        )
        .await
    });
    while pool.memory_in_use() == 0 {
        tokio::time::sleep(std::time::Duration::from_millis(1)).await;
    }
    // A second one does not fit beside the first: it waits, then runs.
    let a = pool.admit(&big, "rotor").unwrap();
    let p = pool.clone();
    let started = Arc::new(std::sync::atomic::AtomicBool::new(false));
    let s = started.clone();
    let second = tokio::spawn(async move {
        p.run(a, move || s.store(true, Ordering::SeqCst), || ())
            .await
    });
    tokio::time::sleep(std::time::Duration::from_millis(100)).await;
    assert!(!started.load(Ordering::SeqCst));
    tx.send(()).unwrap();
    first.await.unwrap().unwrap();
    second.await.unwrap().unwrap();
    assert!(started.load(Ordering::SeqCst));
    assert_eq!(pool.memory_in_use(), 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_short_answer_holds_its_share_before_it_runs_or_is_refused_at_once() {
    // 64 MiB: too small to set the short lane's worst case (2 x 64 MiB) aside, so a short
    // analysis answering synchronously takes its whole estimate from the budget.
    let pool = Arc::new(WorkerPool::new(1, 4, 1, 64 << 20));
    assert_eq!((pool.memory_budget(), pool.short_aside_mib), (64 << 20, 0));
    let mut c = cost(1e6, 40 << 20);
    c.response_bytes = 16 << 20;
    assert_eq!(Lane::of(&c), Lane::Short);
    let (tx, rx) = std::sync::mpsc::channel::<()>();
    let a = pool.admit(&c, "rotor").unwrap();
    let p = pool.clone();
    let first = tokio::spawn(async move {
        p.run_answer(a, move || {
            rx.recv().ok();
            ((), 10 << 20)
        })
        .await
    });
    while pool.memory_in_use() == 0 {
        tokio::time::sleep(std::time::Duration::from_millis(1)).await;
    }
    assert_eq!(pool.memory_in_use(), 40 << 20);
    // A second one does not fit beside it: refused before it runs.
    let ran = Arc::new(std::sync::atomic::AtomicBool::new(false));
    let r = ran.clone();
    let a = pool.admit(&c, "rotor").unwrap();
    let second = pool
        .run_answer(a, move || {
            r.store(true, Ordering::SeqCst);
            ((), 1)
        })
        .await;
    assert!(matches!(second, Err(ApiError::Busy)));
    assert!(!ran.load(Ordering::SeqCst));
    assert_eq!(pool.memory_in_use(), 40 << 20);
    // The answer keeps its own size until it is dropped (sent).
    tx.send(()).unwrap();
    let ((), hold) = first.await.unwrap().unwrap();
    assert_eq!(hold.bytes(), 10 << 20);
    assert_eq!(pool.memory_in_use(), 10 << 20);
    drop(hold);
    assert_eq!(pool.memory_in_use(), 0);
}

#[test]
fn with_the_short_lane_set_aside_a_short_answer_takes_its_answer_from_the_budget() {
    // 1 GiB: 2 x 64 MiB set aside for the short lane's heaps, the rest for the long lane and
    // the answers.
    let pool = WorkerPool::new(1, 4, 1, 1 << 30);
    assert_eq!((pool.budget_mib, pool.short_aside_mib), (896, 64));
    let mut c = cost(1e6, 40 << 20);
    c.response_bytes = 16 << 20;
    assert_eq!(pool.admit(&c, "rotor").unwrap().answer_mib, 16);
    // And a long one its whole estimate, as while it runs.
    let mut c = cost(1e12, 40 << 20);
    c.response_bytes = 16 << 20;
    let a = pool.admit(&c, "rotor").unwrap();
    assert_eq!((a.mib, a.answer_mib), (40, 40));
}
