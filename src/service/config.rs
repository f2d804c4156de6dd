//! Settings, from the environment, each with a default that works on a laptop. [`SETTINGS`]
//! is the one list: parsing, `whirl --help` and the README's table come from it.

use std::time::Duration;

use crate::model::Limits;

/// Service settings. Every field has an environment variable (see [`SETTINGS`]).
#[derive(Debug, Clone)]
pub struct Config {
    pub host: String,
    pub port: u16,
    /// Long analyses running at once.
    pub workers: usize,
    /// Analyses waiting for a worker before new ones get 503.
    pub queue: usize,
    pub max_body_bytes: usize,
    pub max_speeds: usize,
    pub max_dofs: usize,
    pub max_sparse_dofs: usize,
    pub max_states: usize,
    pub max_samples: usize,
    pub max_steps: usize,
    pub max_response_bytes: u64,
    /// Heap all running analyses may hold together, by their estimates.
    pub memory_budget: u64,
    /// Longest a synchronous analysis may run.
    pub request_time_limit: Duration,
    pub job_retention: Duration,
    pub max_finished_jobs: usize,
    /// Most samples of one study.
    pub max_study_samples: usize,
    /// Most samples of all studies waiting in the shared queue.
    pub study_queue: usize,
    /// Compressed bytes of finished jobs' results kept.
    pub job_result_bytes: u64,
    pub job_time_limit: Duration,
    pub shutdown_grace: Duration,
    /// Time to receive a request's headers, and the longest idle keep-alive.
    pub header_timeout: Duration,
    /// Time to receive a request's whole body.
    pub body_timeout: Duration,
    /// Longest a response write may make no progress.
    pub write_timeout: Duration,
    pub max_connections: usize,
    /// Open connections from one client address.
    pub max_connections_per_client: usize,
    pub log_json: bool,
    /// Directory of the embedded job store (SQLite), when there is no `database_url`.
    pub data_dir: std::path::PathBuf,
    /// A PostgreSQL URL: the job store shared by replicas.
    pub database_url: Option<String>,
    /// How long a running job's lease lasts without a heartbeat.
    pub job_lease: Duration,
    /// Browser origins that may call the API (CORS); none by default.
    pub cors_origins: super::cors::Origins,
    /// The URL clients reach the service at, for absolute problem types; `None`: the request's.
    pub public_url: Option<String>,
    /// The bearer token every request but the probes and the docs needs, if set.
    pub api_token: Option<super::guard::ApiToken>,
}

/// One setting: its variable, its default (as text; `None`: computed) and what it means.
pub struct Setting {
    pub var: &'static str,
    pub default: &'static str,
    pub meaning: &'static str,
}

/// Every setting, in the order `--help` lists them.
pub const SETTINGS: &[Setting] = &[
    Setting {
        var: "HOST",
        default: "0.0.0.0",
        meaning: "listen address",
    },
    Setting {
        var: "PORT",
        default: "8080",
        meaning: "listen port",
    },
    Setting {
        var: "WHIRL_WORKERS",
        default: "number of cores",
        meaning: "long analyses running at once (short ones have their own lane)",
    },
    Setting {
        var: "WHIRL_QUEUE",
        default: "64",
        meaning: "jobs waiting in the shared queue (all replicas), and synchronous analyses waiting for a worker of this server; beyond this, 503 with Retry-After",
    },
    Setting {
        var: "WHIRL_MAX_BODY_BYTES",
        default: "8388608",
        meaning: "largest request body; beyond it, 413 (from Content-Length, before reading)",
    },
    Setting {
        var: "WHIRL_MAX_SPEEDS",
        default: "2000",
        meaning: "most speeds in one sweep",
    },
    Setting {
        var: "WHIRL_MAX_DOFS",
        default: "1000",
        meaning: "most complex degrees of freedom of an assembled rotor (before reduction) whose analysis holds it dense",
    },
    Setting {
        var: "WHIRL_MAX_SPARSE_DOFS",
        default: "200000",
        meaning: "most complex degrees of freedom of a rotor held sparse: a beam rotor past 600 coordinates (no Guyan reduction) in a bounded Campbell diagram, modal analysis and stability threshold (`max_frequency`), the unbalance and frequency responses, Level I and II, the report and the time responses (on a checked modal reduction) under every damping model (the equivalent and nonviscous models with their dampers on the lowest modes), the static analysis of any beam rotor and the critical speed map (at most 100 modes); the memory budget bounds it too (about 11 kB per coordinate for the Campbell, 4 kB for the statics and for each harmonic solve running)",
    },
    Setting {
        var: "WHIRL_MAX_STATES",
        default: "2000",
        meaning: "largest first-order eigenproblem, internal coordinates included (2000: the nonviscous model of a 100-element rotor, 1616 states, and a rotor at WHIRL_MAX_DOFS)",
    },
    Setting {
        var: "WHIRL_MAX_SAMPLES",
        default: "2000000",
        meaning: "most output values of a time response (samples x nodes)",
    },
    Setting {
        var: "WHIRL_MAX_STEPS",
        default: "500000",
        meaning: "most steps of the implicit integrator",
    },
    Setting {
        var: "WHIRL_MAX_RESPONSE_BYTES",
        default: "134217728",
        meaning: "largest answer (estimated before the analysis runs)",
    },
    Setting {
        var: "WHIRL_MEMORY_BUDGET",
        default: "half the memory (cgroup limit or RAM)",
        meaning: "bytes all running analyses may hold by their estimates, with the synchronous answers not yet sent; beyond it long analyses wait and short synchronous ones are refused (503), and one that can never fit is refused (422); accepts K, M, G suffixes",
    },
    Setting {
        var: "WHIRL_REQUEST_TIME_LIMIT",
        default: "60",
        meaning: "seconds a synchronous analysis may run before 503 (submit a job instead)",
    },
    Setting {
        var: "WHIRL_JOB_TIME_LIMIT",
        default: "600",
        meaning: "seconds a job may run before it is stopped",
    },
    Setting {
        var: "WHIRL_JOB_RETENTION",
        default: "3600",
        meaning: "seconds a finished job is kept",
    },
    Setting {
        var: "WHIRL_MAX_FINISHED_JOBS",
        default: "1000",
        meaning: "most finished jobs kept",
    },
    Setting {
        var: "WHIRL_MAX_STUDY_SAMPLES",
        default: "5000",
        meaning: "most samples of one study (POST /v1/studies); their inputs and estimated results together must also fit WHIRL_JOB_RESULT_BYTES",
    },
    Setting {
        var: "WHIRL_STUDY_QUEUE",
        default: "20000",
        meaning: "samples of all studies waiting in the shared queue (all replicas); a study that would take it past this waits: 503 with Retry-After (one larger than it: 422)",
    },
    Setting {
        var: "WHIRL_JOB_RESULT_BYTES",
        default: "268435456",
        meaning: "compressed bytes of finished results kept (oldest forgotten first)",
    },
    Setting {
        var: "WHIRL_DATA_DIR",
        default: "./data",
        meaning: "directory of the embedded job store (SQLite file whirl.sqlite), used when WHIRL_DATABASE_URL is not set",
    },
    Setting {
        var: "WHIRL_DATABASE_URL",
        default: "none",
        meaning: "postgres://user:password@host:port/database: the job store shared by several replicas (instead of WHIRL_DATA_DIR)",
    },
    Setting {
        var: "WHIRL_JOB_LEASE",
        default: "15",
        meaning: "seconds a running job stays claimed without a heartbeat (sent every 0.25 s); after that it is re-queued once, then failed (after a store outage, only once the store has answered for a lease: the workers renew first)",
    },
    Setting {
        var: "WHIRL_SHUTDOWN_GRACE",
        default: "30",
        meaning: "seconds running work gets on SIGTERM; jobs still running then go back to the queue; the process ends a few seconds later whatever the clients do",
    },
    Setting {
        var: "WHIRL_HEADER_TIMEOUT",
        default: "10",
        meaning: "seconds to receive a request's headers; also the longest idle keep-alive",
    },
    Setting {
        var: "WHIRL_BODY_TIMEOUT",
        default: "30",
        meaning: "seconds to receive a request's body (408 after)",
    },
    Setting {
        var: "WHIRL_WRITE_TIMEOUT",
        default: "30",
        meaning: "seconds of waiting on a client that does not read its answer, or reads slower than 32 KiB/s over that time, before the connection is dropped",
    },
    Setting {
        var: "WHIRL_MAX_CONNECTIONS",
        default: "1024",
        meaning: "open connections; beyond it (and beyond the client's share) new ones get 503 and are closed, but for 16 kept for /healthz and /readyz (headers within 1 s)",
    },
    Setting {
        var: "WHIRL_MAX_CONNECTIONS_PER_CLIENT",
        default: "256",
        meaning: "open connections from one client address (behind a proxy, set it to WHIRL_MAX_CONNECTIONS)",
    },
    Setting {
        var: "WHIRL_API_TOKEN",
        default: "none",
        meaning: "a secret of at least 16 visible characters: every request but /healthz, /readyz, /docs and /openapi.json then needs `Authorization: Bearer <token>` (401 otherwise); /metrics included",
    },
    Setting {
        var: "WHIRL_CORS_ORIGINS",
        default: "none",
        meaning: "browser origins that may call the API (CORS), comma-separated (https://app.example.com,http://localhost:5173), or * for any; with none, no CORS headers and OPTIONS is 405",
    },
    Setting {
        var: "WHIRL_PUBLIC_URL",
        default: "the request's scheme and Host",
        meaning: "URL clients reach the service at (https://whirl.example.com), the base of the absolute problem type URIs",
    },
    Setting {
        var: "WHIRL_LOG_FORMAT",
        default: "text",
        meaning: "`json` for structured logs (stderr; colours only on a terminal)",
    },
    Setting {
        var: "RUST_LOG",
        default: "info",
        meaning: "log filter",
    },
];

impl Default for Config {
    fn default() -> Self {
        let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
        Config {
            host: "0.0.0.0".into(),
            port: 8080,
            workers: cores,
            queue: 64,
            max_body_bytes: 8 * 1024 * 1024,
            max_speeds: 2000,
            max_dofs: 1000,
            max_sparse_dofs: Limits::default().max_sparse_dofs,
            max_states: 2000,
            max_samples: 2_000_000,
            max_steps: 500_000,
            max_response_bytes: 128 << 20,
            memory_budget: default_memory_budget(),
            request_time_limit: Duration::from_secs(60),
            job_retention: Duration::from_secs(3600),
            max_finished_jobs: 1000,
            max_study_samples: 5000,
            study_queue: 20000,
            job_result_bytes: 256 << 20,
            job_time_limit: Duration::from_secs(600),
            shutdown_grace: Duration::from_secs(30),
            header_timeout: Duration::from_secs(10),
            body_timeout: Duration::from_secs(30),
            write_timeout: Duration::from_secs(30),
            max_connections: 1024,
            max_connections_per_client: 256,
            log_json: false,
            // A fresh directory per configuration built in code (tests, embedding); the binary
            // reads WHIRL_DATA_DIR, `./data` by default (see `from_lookup`).
            data_dir: scratch_dir(),
            database_url: None,
            job_lease: Duration::from_secs(15),
            cors_origins: super::cors::Origins::None,
            public_url: None,
            api_token: None,
        }
    }
}

/// A directory of its own under the system's temporary directory.
fn scratch_dir() -> std::path::PathBuf {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    std::env::temp_dir().join(format!("whirl-{}-{n}", std::process::id()))
}

/// Half of what this process may use: the cgroup's memory limit if it has one (a container),
/// else the machine's RAM; 4 GiB if neither can be read.
pub fn default_memory_budget() -> u64 {
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    let ram = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
        s.lines()
            .find(|l| l.starts_with("MemTotal:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|kb| kb.parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let total = match (cgroup, ram) {
        (Some(c), Some(r)) => c.min(r),
        (Some(c), None) => c,
        (None, Some(r)) => r,
        (None, None) => 8 << 30,
    };
    total / 2
}

impl Config {
    /// Compute threads one analysis uses.
    pub fn threads(&self) -> usize {
        std::thread::available_parallelism().map_or(2, |n| n.get())
    }

    /// Where the jobs are kept.
    pub fn store_target(&self) -> crate::jobs::store::Target {
        match &self.database_url {
            Some(url) => crate::jobs::store::Target::Postgres(url.clone()),
            None => crate::jobs::store::Target::Sqlite(self.data_dir.clone()),
        }
    }

    /// What the job runner takes of the settings.
    pub fn runner(&self) -> crate::jobs::runner::Settings {
        crate::jobs::runner::Settings {
            limits: self.limits(),
            max_response_bytes: self.max_response_bytes,
            job_time_limit: self.job_time_limit,
            job_result_bytes: self.job_result_bytes,
            job_lease: self.job_lease,
        }
    }

    /// The limits requests are parsed with.
    pub fn limits(&self) -> Limits {
        Limits {
            max_dofs: self.max_dofs,
            max_sparse_dofs: self.max_sparse_dofs,
            dofs_setting: Limits::default().dofs_setting,
            max_states: self.max_states,
            max_speeds: self.max_speeds,
            max_samples: self.max_samples,
            max_steps: self.max_steps,
            max_response_bytes: self.max_response_bytes,
            threads: self.threads(),
        }
    }

    /// Reads the environment; a set but unparsable variable is an error, not a silent default.
    pub fn from_env() -> Result<Self, String> {
        Self::from_lookup(|k| std::env::var(k).ok())
    }

    pub fn from_lookup(get: impl Fn(&str) -> Option<String>) -> Result<Self, String> {
        let d = Config::default();
        fn num<T>(
            get: &impl Fn(&str) -> Option<String>,
            key: &str,
            default: T,
            min: T,
        ) -> Result<T, String>
        where
            T: std::str::FromStr + PartialOrd + std::fmt::Display,
        {
            match get(key) {
                None => Ok(default),
                Some(v) => match v.trim().parse::<T>() {
                    Ok(x) if x >= min => Ok(x),
                    _ => Err(format!("{key}={v:?}: expected a whole number >= {min}")),
                },
            }
        }
        fn seconds(
            get: &impl Fn(&str) -> Option<String>,
            key: &str,
            default: Duration,
            min: f64,
        ) -> Result<Duration, String> {
            match get(key) {
                None => Ok(default),
                Some(v) => match v.trim().parse::<f64>() {
                    Ok(x) if x.is_finite() && x >= min && x < 1e9 => Ok(Duration::from_secs_f64(x)),
                    _ => Err(format!("{key}={v:?}: expected seconds >= {min}")),
                },
            }
        }
        let bytes = |key: &str, default: u64| -> Result<u64, String> {
            let Some(v) = get(key) else {
                return Ok(default);
            };
            let t = v.trim();
            let (digits, unit) = match t.char_indices().last() {
                Some((i, c)) if c.is_ascii_alphabetic() => (&t[..i], c.to_ascii_uppercase()),
                _ => (t, 'B'),
            };
            let shift = match unit {
                'B' => 0,
                'K' => 10,
                'M' => 20,
                'G' => 30,
                'T' => 40,
                _ => return Err(format!("{key}={v:?}: expected bytes, e.g. 4G")),
            };
            digits
                .trim()
                .parse::<u64>()
                .ok()
                .and_then(|n| n.checked_mul(1 << shift))
                .filter(|&n| n >= 1 << 20)
                .ok_or_else(|| format!("{key}={v:?}: expected bytes >= 1M, e.g. 4G"))
        };
        let log_json = match get("WHIRL_LOG_FORMAT").as_deref() {
            None | Some("text") => false,
            Some("json") => true,
            Some(other) => {
                return Err(format!("WHIRL_LOG_FORMAT={other:?}: expected text or json"));
            }
        };
        let database_url = match get("WHIRL_DATABASE_URL").filter(|v| !v.trim().is_empty()) {
            None => None,
            Some(url) if url.starts_with("postgres://") || url.starts_with("postgresql://") => {
                Some(url)
            }
            Some(_) => {
                return Err(
                    "WHIRL_DATABASE_URL: expected postgres://user:password@host:port/database"
                        .into(),
                );
            }
        };
        let cors_origins = match get("WHIRL_CORS_ORIGINS") {
            None => d.cors_origins,
            Some(v) => super::cors::Origins::parse(&v)?,
        };
        let public_url = match get("WHIRL_PUBLIC_URL").filter(|v| !v.trim().is_empty()) {
            None => None,
            Some(u) => {
                let u = u.trim().trim_end_matches('/');
                let ok = (u.starts_with("https://") || u.starts_with("http://"))
                    && !u.contains(['?', '#', ' '])
                    && axum::http::Uri::try_from(u).is_ok();
                if !ok {
                    return Err(format!(
                        "WHIRL_PUBLIC_URL={u:?}: expected an http(s) URL, e.g. https://whirl.example.com"
                    ));
                }
                Some(u.to_string())
            }
        };
        Ok(Config {
            host: get("HOST").unwrap_or(d.host),
            port: num(&get, "PORT", d.port, 0)?,
            workers: num(&get, "WHIRL_WORKERS", d.workers, 1)?,
            queue: num(&get, "WHIRL_QUEUE", d.queue, 0)?,
            max_body_bytes: num(&get, "WHIRL_MAX_BODY_BYTES", d.max_body_bytes, 1024)?,
            max_speeds: num(&get, "WHIRL_MAX_SPEEDS", d.max_speeds, 2)?,
            max_dofs: num(&get, "WHIRL_MAX_DOFS", d.max_dofs, 2)?,
            max_sparse_dofs: num(&get, "WHIRL_MAX_SPARSE_DOFS", d.max_sparse_dofs, 2)?,
            max_states: num(&get, "WHIRL_MAX_STATES", d.max_states, 2)?,
            max_samples: num(&get, "WHIRL_MAX_SAMPLES", d.max_samples, 2)?,
            max_steps: num(&get, "WHIRL_MAX_STEPS", d.max_steps, 10)?,
            max_response_bytes: bytes("WHIRL_MAX_RESPONSE_BYTES", d.max_response_bytes)?,
            memory_budget: bytes("WHIRL_MEMORY_BUDGET", d.memory_budget)?,
            request_time_limit: seconds(
                &get,
                "WHIRL_REQUEST_TIME_LIMIT",
                d.request_time_limit,
                0.1,
            )?,
            job_retention: seconds(&get, "WHIRL_JOB_RETENTION", d.job_retention, 1.0)?,
            max_finished_jobs: num(&get, "WHIRL_MAX_FINISHED_JOBS", d.max_finished_jobs, 1)?,
            max_study_samples: num(&get, "WHIRL_MAX_STUDY_SAMPLES", d.max_study_samples, 1)?,
            study_queue: num(&get, "WHIRL_STUDY_QUEUE", d.study_queue, 1)?,
            job_result_bytes: bytes("WHIRL_JOB_RESULT_BYTES", d.job_result_bytes)?,
            job_time_limit: seconds(&get, "WHIRL_JOB_TIME_LIMIT", d.job_time_limit, 0.1)?,
            shutdown_grace: seconds(&get, "WHIRL_SHUTDOWN_GRACE", d.shutdown_grace, 0.0)?,
            header_timeout: seconds(&get, "WHIRL_HEADER_TIMEOUT", d.header_timeout, 0.1)?,
            body_timeout: seconds(&get, "WHIRL_BODY_TIMEOUT", d.body_timeout, 0.1)?,
            write_timeout: seconds(&get, "WHIRL_WRITE_TIMEOUT", d.write_timeout, 0.1)?,
            max_connections: num(&get, "WHIRL_MAX_CONNECTIONS", d.max_connections, 1)?,
            max_connections_per_client: num(
                &get,
                "WHIRL_MAX_CONNECTIONS_PER_CLIENT",
                d.max_connections_per_client,
                1,
            )?,
            log_json,
            data_dir: get("WHIRL_DATA_DIR").map_or_else(|| "./data".into(), Into::into),
            database_url,
            job_lease: seconds(&get, "WHIRL_JOB_LEASE", d.job_lease, 1.0)?,
            cors_origins,
            public_url,
            api_token: match get("WHIRL_API_TOKEN").filter(|t| !t.is_empty()) {
                None => None,
                Some(t) => Some(super::guard::ApiToken::new(&t)?),
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_and_overrides() {
        let c = Config::from_lookup(|_| None).unwrap();
        assert_eq!((c.host.as_str(), c.port), ("0.0.0.0", 8080));
        let c = Config::from_lookup(|k| (k == "PORT").then(|| "9000".to_string())).unwrap();
        assert_eq!(c.port, 9000);
        assert!(Config::from_lookup(|k| (k == "WHIRL_WORKERS").then(|| "0".into())).is_err());
        assert!(Config::from_lookup(|k| (k == "PORT").then(|| "http".into())).is_err());
        let c = Config::from_lookup(|k| (k == "WHIRL_MEMORY_BUDGET").then(|| "3G".into())).unwrap();
        assert_eq!(c.memory_budget, 3 << 30);
        let c =
            Config::from_lookup(|k| (k == "WHIRL_HEADER_TIMEOUT").then(|| "0.5".into())).unwrap();
        assert_eq!(c.header_timeout, Duration::from_millis(500));
        assert!(
            Config::from_lookup(|k| (k == "WHIRL_MEMORY_BUDGET").then(|| "lots".into())).is_err()
        );
        assert!(
            Config::from_lookup(|k| (k == "WHIRL_DATABASE_URL").then(|| "mysql://x".into()))
                .is_err()
        );
        let url = "postgres://postgres@127.0.0.1/test";
        let c = Config::from_lookup(|k| (k == "WHIRL_DATABASE_URL").then(|| url.into())).unwrap();
        assert_eq!(c.database_url.as_deref(), Some(url));
        assert!(Config::from_lookup(|k| (k == "WHIRL_JOB_LEASE").then(|| "0.1".into())).is_err());
    }

    #[test]
    fn every_field_has_a_setting() {
        // The variables parsed above, each listed once for --help.
        let vars: Vec<&str> = SETTINGS.iter().map(|s| s.var).collect();
        for v in [
            "WHIRL_MEMORY_BUDGET",
            "WHIRL_REQUEST_TIME_LIMIT",
            "WHIRL_HEADER_TIMEOUT",
            "WHIRL_MAX_CONNECTIONS",
            "WHIRL_JOB_RESULT_BYTES",
            "WHIRL_DATA_DIR",
            "WHIRL_DATABASE_URL",
            "WHIRL_JOB_LEASE",
            "WHIRL_CORS_ORIGINS",
            "WHIRL_PUBLIC_URL",
            "WHIRL_API_TOKEN",
            "WHIRL_MAX_CONNECTIONS_PER_CLIENT",
            "WHIRL_MAX_STUDY_SAMPLES",
            "WHIRL_STUDY_QUEUE",
            "WHIRL_MAX_SPARSE_DOFS",
        ] {
            assert_eq!(vars.iter().filter(|x| **x == v).count(), 1, "{v}");
        }
        assert_eq!(vars.len(), 34);
    }
}
