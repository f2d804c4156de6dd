//! Settings, from the environment, each with a default that works on a laptop.

/// Service settings. Every field has an environment variable (see the README).
#[derive(Debug, Clone)]
pub struct Config {
    /// `HOST` (default `0.0.0.0`).
    pub host: String,
    /// `PORT` (default 8080).
    pub port: u16,
    /// `WHIRL_WORKERS`: analyses running at once (default: the number of cores).
    pub workers: usize,
    /// `WHIRL_QUEUE`: analyses waiting for a worker before new ones get 503 (default 64).
    pub queue: usize,
    /// `WHIRL_MAX_BODY_BYTES`: largest request body (default 8 MiB); larger gets 413.
    pub max_body_bytes: usize,
    /// `WHIRL_MAX_SPEEDS`: most spin speeds in one sweep (default 2000).
    pub max_speeds: usize,
    /// `WHIRL_MAX_DOFS`: most complex degrees of freedom of an assembled rotor (default 1000).
    pub max_dofs: usize,
    /// `WHIRL_MAX_STATES`: largest first-order eigenproblem, internal coordinates included
    /// (default 1500).
    pub max_states: usize,
    /// `WHIRL_MAX_SAMPLES`: most output values of a time response, samples times nodes
    /// (default 2 000 000).
    pub max_samples: usize,
    /// `WHIRL_MAX_STEPS`: most steps of the implicit integrator (default 500 000).
    pub max_steps: usize,
    /// `WHIRL_JOB_RETENTION`: seconds a finished job is kept (default 3600).
    pub job_retention: u64,
    /// `WHIRL_MAX_FINISHED_JOBS`: most finished jobs kept (default 1000).
    pub max_finished_jobs: usize,
    /// `WHIRL_JOB_TIME_LIMIT`: seconds a job may run before it is stopped (default 600).
    pub job_time_limit: u64,
    /// `WHIRL_SHUTDOWN_GRACE`: seconds running jobs get to finish on SIGTERM (default 30).
    pub shutdown_grace: u64,
    /// `WHIRL_LOG_FORMAT`: `text` (default) or `json`.
    pub log_json: bool,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            host: "0.0.0.0".into(),
            port: 8080,
            workers: std::thread::available_parallelism().map_or(2, |n| n.get()),
            queue: 64,
            max_body_bytes: 8 * 1024 * 1024,
            max_speeds: 2000,
            max_dofs: 1000,
            max_states: 1500,
            max_samples: 2_000_000,
            max_steps: 500_000,
            job_retention: 3600,
            max_finished_jobs: 1000,
            job_time_limit: 600,
            shutdown_grace: 30,
            log_json: false,
        }
    }
}

impl Config {
    /// The model-size limits validation enforces.
    pub fn limits(&self) -> crate::model::rotor::Limits {
        crate::model::rotor::Limits {
            max_dofs: self.max_dofs,
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
        let log_json = match get("WHIRL_LOG_FORMAT").as_deref() {
            None | Some("text") => false,
            Some("json") => true,
            Some(other) => {
                return Err(format!("WHIRL_LOG_FORMAT={other:?}: expected text or json"));
            }
        };
        Ok(Config {
            host: get("HOST").unwrap_or(d.host),
            port: num(&get, "PORT", d.port, 0)?,
            workers: num(&get, "WHIRL_WORKERS", d.workers, 1)?,
            queue: num(&get, "WHIRL_QUEUE", d.queue, 0)?,
            max_body_bytes: num(&get, "WHIRL_MAX_BODY_BYTES", d.max_body_bytes, 1024)?,
            max_speeds: num(&get, "WHIRL_MAX_SPEEDS", d.max_speeds, 2)?,
            max_dofs: num(&get, "WHIRL_MAX_DOFS", d.max_dofs, 1)?,
            max_states: num(&get, "WHIRL_MAX_STATES", d.max_states, 2)?,
            max_samples: num(&get, "WHIRL_MAX_SAMPLES", d.max_samples, 2)?,
            max_steps: num(&get, "WHIRL_MAX_STEPS", d.max_steps, 10)?,
            job_retention: num(&get, "WHIRL_JOB_RETENTION", d.job_retention, 1)?,
            max_finished_jobs: num(&get, "WHIRL_MAX_FINISHED_JOBS", d.max_finished_jobs, 1)?,
            job_time_limit: num(&get, "WHIRL_JOB_TIME_LIMIT", d.job_time_limit, 1)?,
            shutdown_grace: num(&get, "WHIRL_SHUTDOWN_GRACE", d.shutdown_grace, 0)?,
            log_json,
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
    }
}
