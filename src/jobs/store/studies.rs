//! Studies in the store: a `studies` row and its samples, jobs that name it (`study_id`,
//! `sample`, `parameters`). The samples are inserted with the study in one transaction, so a
//! study is whole or absent; they are claimed like any job, after every single job queued
//! (the claim orders by `study_id IS NOT NULL`), are not counted against the admission queue,
//! are not listed by `GET /v1/jobs`, and leave with their study (`ON DELETE CASCADE`) once
//! every sample has been finished longer than the retention.

use std::time::Duration;

use super::{Engine, REQUEST_WAIT, Store, StoreError, breaker, problem_json};
use crate::jobs::pool::Lane;
use crate::model::api::{JobStatus, Problem};

/// Samples inserted per statement.
pub(super) const BATCH: usize = 200;

pub struct NewStudy<'a> {
    pub id: &'a str,
    pub analysis: &'a str,
    /// The study request (JSON), with its seed.
    pub request: &'a str,
}

/// A sample to queue.
pub struct NewSample {
    pub id: String,
    pub input: String,
    /// Its parameter values (JSON array).
    pub parameters: String,
    pub lane: Lane,
    pub memory_mib: u64,
}

/// A study and its samples by status.
#[derive(Debug, Clone)]
pub struct StudyRow {
    pub id: String,
    pub analysis: String,
    pub request: String,
    pub samples: i64,
    pub created_ms: i64,
    pub cancelled: bool,
    pub error: Option<Problem>,
    pub counts: Vec<(JobStatus, i64)>,
}

impl StudyRow {
    pub fn count(&self, s: JobStatus) -> i64 {
        self.counts
            .iter()
            .filter(|(k, _)| *k == s)
            .map(|(_, n)| n)
            .sum()
    }
}

/// A sample as the result needs it.
#[derive(Debug, Clone)]
pub struct SampleRow {
    pub sample: i64,
    pub status: JobStatus,
    pub worker: Option<String>,
    pub error: Option<Problem>,
    pub parameters: String,
    /// Its result's gzipped JSON (empty unless it succeeded).
    pub gzip: Vec<u8>,
}

impl Store {
    /// Inserts a study and its samples (queued), all or nothing; `false` (nothing inserted)
    /// when the samples of all studies waiting would then be more than `queue`.
    pub async fn submit_study(
        &self,
        study: &NewStudy<'_>,
        samples: &[NewSample],
        queue: usize,
    ) -> Result<bool, StoreError> {
        on_engine!(self, request, e => e.submit_study(study, samples, queue))
    }

    /// A study with its counts, unless unknown or purged.
    pub async fn study(&self, id: &str) -> Result<Option<StudyRow>, StoreError> {
        on_engine!(self, request, e => e.study(id))
    }

    /// The samples `from..from + count` of a study, by index (a page: their results are
    /// held in memory).
    pub async fn study_samples(
        &self,
        id: &str,
        from: i64,
        count: i64,
    ) -> Result<Vec<SampleRow>, StoreError> {
        on_engine!(self, request, e => e.study_samples(id, from, count))
    }

    /// Records a study as cancelled with `error` and cancels its queued and running samples;
    /// returns the samples cancelled (`None`: no such study).
    pub async fn cancel_study(
        &self,
        id: &str,
        error: &Problem,
    ) -> Result<Option<Vec<String>>, StoreError> {
        on_engine!(self, request, e => e.cancel_study(id, &problem_json(error)))
    }
}
