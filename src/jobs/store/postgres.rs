//! The store on PostgreSQL, shared by replicas: claims with `FOR UPDATE SKIP LOCKED`, leases on
//! the database's clock, admission under an advisory lock. Statements as in `sqlite.rs`.

use std::str::FromStr;
use std::time::Duration;

use sqlx::Row;
use sqlx::migrate::Migrator;
use sqlx::postgres::{PgConnectOptions, PgPool, PgPoolOptions, PgRow};

use super::{
    CHUNK, Claimed, Ending, Filter, Inserted, JobRow, NewJob, Reaped, Retention, Room, Stats,
    StoreError, ending_parts, key_taken, lane_text, ms, parse_lane, parse_problem, parse_status,
    status_text,
};

/// Connections per replica.
const CONNECTIONS: u32 = 8;
/// Serialises admission over all replicas (an arbitrary key: "whirl" in ASCII).
const ADMISSION_LOCK: i64 = 0x0077_6869_726c;

/// The columns of a [`JobRow`], times in ms since the epoch.
const ROW: &str = "id, analysis, status, progress, \
    (extract(epoch FROM created_at) * 1000)::int8 AS created, \
    (extract(epoch FROM started_at) * 1000)::int8 AS started, \
    (extract(epoch FROM finished_at) * 1000)::int8 AS finished, \
    error::text AS error, attempts::int8 AS attempts, result_bytes, \
    result_chunks::int8 AS result_chunks";

pub struct Postgres {
    pub(super) pool: PgPool,
    pub(super) retention: Retention,
}

/// The URL without its password.
pub fn describe(url: &str) -> String {
    match PgConnectOptions::from_str(url) {
        Ok(o) => format!(
            "postgres://{}@{}:{}/{}",
            o.get_username(),
            o.get_host(),
            o.get_port(),
            o.get_database().unwrap_or("")
        ),
        Err(_) => "postgres (unparsable URL)".into(),
    }
}

fn row(r: &PgRow) -> Result<JobRow, sqlx::Error> {
    Ok(JobRow {
        id: r.try_get("id")?,
        analysis: r.try_get("analysis")?,
        status: parse_status(r.try_get("status")?)?,
        progress: r.try_get("progress")?,
        created_ms: r.try_get("created")?,
        started_ms: r.try_get("started")?,
        finished_ms: r.try_get("finished")?,
        error: parse_problem(r.try_get("error")?),
        attempts: r.try_get("attempts")?,
        result_bytes: r.try_get("result_bytes")?,
        result_chunks: r.try_get("result_chunks")?,
    })
}

/// The jobs queued (single jobs, or study samples), counted under the admission lock that the
/// transaction `tx` then holds: replicas admitting at once count each other's inserts.
pub(super) async fn queued_admitting(
    tx: &mut sqlx::Transaction<'_, sqlx::Postgres>,
    samples: bool,
) -> Result<i64, sqlx::Error> {
    sqlx::query("SELECT pg_advisory_xact_lock($1)")
        .bind(ADMISSION_LOCK)
        .execute(&mut **tx)
        .await?;
    let kind = if samples { "IS NOT NULL" } else { "IS NULL" };
    sqlx::query_scalar(&format!(
        "SELECT count(*) FROM jobs WHERE status = 'queued' AND study_id {kind}"
    ))
    .fetch_one(&mut **tx)
    .await
}

impl Postgres {
    pub async fn connect(
        url: &str,
        retention: Retention,
        migrator: &Migrator,
    ) -> Result<Self, StoreError> {
        let options = PgConnectOptions::from_str(url)
            .map_err(|e| StoreError(format!("WHIRL_DATABASE_URL: {e}")))?
            .application_name("whirl");
        let pool = PgPoolOptions::new()
            .max_connections(CONNECTIONS)
            .acquire_timeout(Duration::from_secs(3))
            .connect_with(options)
            .await?;
        // Takes an advisory lock: replicas starting together migrate once.
        migrator.run(&pool).await?;
        Ok(Postgres { pool, retention })
    }

    pub async fn ping(&self) -> Result<(), sqlx::Error> {
        sqlx::query("SELECT 1")
            .execute(&self.pool)
            .await
            .map(|_| ())
    }

    pub async fn submit(&self, job: &NewJob<'_>, queue: usize) -> Result<Inserted, sqlx::Error> {
        let mut tx = self.pool.begin().await?;
        if queued_admitting(&mut tx, false).await? >= queue as i64 {
            return Ok(Inserted::Full);
        }
        let r = sqlx::query(&format!(
            "INSERT INTO jobs (id, analysis, input, lane, memory_mib, status, idempotency_key, \
             request_sha256) VALUES ($1, $2, $3, $4, $5, 'queued', $6, $7) RETURNING {ROW}"
        ))
        .bind(job.id)
        .bind(job.analysis)
        .bind(job.input)
        .bind(lane_text(job.lane))
        .bind(job.memory_mib as i64)
        .bind(job.key.map(|k| k.0))
        .bind(job.key.map(|k| k.1))
        .fetch_one(&mut *tx)
        .await;
        let r = match r {
            Ok(r) => r,
            Err(e) if key_taken(&e) => return Ok(Inserted::KeyTaken),
            Err(e) => return Err(e),
        };
        tx.commit().await?;
        row(&r).map(|r| Inserted::Row(Box::new(r)))
    }

    pub async fn keyed(&self, key: &str) -> Result<Option<(JobRow, Option<String>)>, sqlx::Error> {
        sqlx::query(&format!(
            "SELECT {ROW}, request_sha256 FROM jobs WHERE idempotency_key = $1"
        ))
        .bind(key)
        .fetch_optional(&self.pool)
        .await?
        .map(|r| Ok((row(&r)?, r.try_get("request_sha256")?)))
        .transpose()
    }

    pub async fn list(&self, f: &Filter) -> Result<Vec<JobRow>, sqlx::Error> {
        sqlx::query(&format!(
            "SELECT {ROW} FROM jobs WHERE ($1::text IS NULL OR status = $1) \
             AND ($2::text IS NULL OR analysis = $2) AND ($3::text IS NULL OR id < $3) \
             AND (finished_at IS NULL \
                  OR finished_at > now() - $4::float8 * interval '1 millisecond') \
             AND study_id IS NULL ORDER BY id DESC LIMIT $5"
        ))
        .bind(f.status.map(status_text))
        .bind(f.analysis.as_deref())
        .bind(f.before.as_deref())
        .bind(ms(self.retention.age))
        .bind(i64::from(f.limit))
        .fetch_all(&self.pool)
        .await?
        .iter()
        .map(row)
        .collect()
    }

    pub async fn get(&self, id: &str) -> Result<Option<JobRow>, sqlx::Error> {
        sqlx::query(&format!(
            "SELECT {ROW} FROM jobs WHERE id = $1 \
             AND (finished_at IS NULL OR finished_at > now() - $2::float8 * interval '1 millisecond')"
        ))
        .bind(id)
        .bind(ms(self.retention.age))
        .fetch_optional(&self.pool)
        .await?
        .as_ref()
        .map(row)
        .transpose()
    }

    pub async fn cancel(&self, id: &str, error: &str) -> Result<Option<JobRow>, sqlx::Error> {
        sqlx::query(&format!(
            "UPDATE jobs SET status = 'cancelled', finished_at = now(), error = $2::jsonb, \
             lease_until = NULL WHERE id = $1 AND status IN ('queued', 'running') RETURNING {ROW}"
        ))
        .bind(id)
        .bind(error)
        .fetch_optional(&self.pool)
        .await?
        .as_ref()
        .map(row)
        .transpose()
    }

    pub async fn claim(
        &self,
        worker: &str,
        room: Room,
        lease: Duration,
    ) -> Result<Option<Claimed>, sqlx::Error> {
        let r = sqlx::query(
            "UPDATE jobs SET status = 'running', worker = $1, attempts = attempts + 1, \
               started_at = now(), progress = 0, \
               lease_until = now() + $2::float8 * interval '1 millisecond' \
             WHERE id = ( \
               SELECT id FROM jobs WHERE status = 'queued' \
                 AND ((lane = 'short' AND $3) OR (lane = 'long' AND $4 AND memory_mib <= $5)) \
               ORDER BY (study_id IS NOT NULL), id LIMIT 1 FOR UPDATE SKIP LOCKED) \
             RETURNING id, analysis, input, lane, memory_mib, \
               (extract(epoch FROM now() - created_at) * 1000)::int8 AS waited",
        )
        .bind(worker)
        .bind(ms(lease))
        .bind(room.short)
        .bind(room.long)
        .bind(room.memory_mib as i64)
        .fetch_optional(&self.pool)
        .await?;
        let Some(r) = r else { return Ok(None) };
        Ok(Some(Claimed {
            id: r.try_get("id")?,
            analysis: r.try_get("analysis")?,
            input: r.try_get("input")?,
            lane: parse_lane(r.try_get("lane")?),
            memory_mib: r.try_get::<i64, _>("memory_mib")?.max(0) as u64,
            waited: Duration::from_millis(r.try_get::<i64, _>("waited")?.max(0) as u64),
        }))
    }

    pub async fn heartbeat(
        &self,
        id: &str,
        worker: &str,
        progress: f64,
        lease: Duration,
    ) -> Result<bool, sqlx::Error> {
        let r = sqlx::query(
            "UPDATE jobs SET progress = $3, lease_until = now() + $4::float8 * interval '1 millisecond' \
             WHERE id = $1 AND worker = $2 AND status = 'running'",
        )
        .bind(id)
        .bind(worker)
        .bind(progress)
        .bind(ms(lease))
        .execute(&self.pool)
        .await?;
        Ok(r.rows_affected() == 1)
    }

    pub async fn finish(
        &self,
        id: &str,
        worker: &str,
        ending: &Ending,
    ) -> Result<bool, sqlx::Error> {
        let (status, error, gzip) = ending_parts(ending);
        let mut tx = self.pool.begin().await?;
        // The chunks first, without holding the job's row: a cancel meanwhile wins, and the
        // update below then matches nothing and the whole is rolled back.
        let mut chunks = 0i64;
        for (seq, data) in gzip.chunks(CHUNK).enumerate() {
            sqlx::query("INSERT INTO job_chunks (job_id, seq, data) VALUES ($1, $2, $3)")
                .bind(id)
                .bind(seq as i32)
                .bind(data)
                .execute(&mut *tx)
                .await?;
            chunks += 1;
        }
        let r = sqlx::query(
            "UPDATE jobs SET status = $3, error = $4::jsonb, finished_at = now(), \
               lease_until = NULL, result_bytes = $5, result_chunks = $6, \
               progress = CASE WHEN $3 = 'succeeded' THEN 1 ELSE progress END \
             WHERE id = $1 AND worker = $2 AND status = 'running'",
        )
        .bind(id)
        .bind(worker)
        .bind(status)
        .bind(error)
        .bind(gzip.len() as i64)
        .bind(chunks as i32)
        .execute(&mut *tx)
        .await?;
        if r.rows_affected() != 1 {
            tx.rollback().await?;
            return Ok(false);
        }
        tx.commit().await?;
        Ok(true)
    }

    pub async fn release(&self, id: &str, worker: &str) -> Result<bool, sqlx::Error> {
        let r = sqlx::query(
            "UPDATE jobs SET status = 'queued', worker = NULL, lease_until = NULL, \
               started_at = NULL, progress = 0 \
             WHERE id = $1 AND worker = $2 AND status = 'running'",
        )
        .bind(id)
        .bind(worker)
        .execute(&self.pool)
        .await?;
        Ok(r.rows_affected() == 1)
    }

    pub async fn reap(&self, error: &str) -> Result<Vec<Reaped>, sqlx::Error> {
        let rows = sqlx::query(
            "UPDATE jobs SET \
               status = CASE WHEN expiries = 0 THEN 'queued' ELSE 'failed' END, \
               error = CASE WHEN expiries = 0 THEN NULL ELSE $1::jsonb END, \
               finished_at = CASE WHEN expiries = 0 THEN NULL ELSE now() END, \
               started_at = CASE WHEN expiries = 0 THEN NULL ELSE started_at END, \
               progress = CASE WHEN expiries = 0 THEN 0 ELSE progress END, \
               worker = NULL, lease_until = NULL, expiries = expiries + 1 \
             WHERE status = 'running' AND lease_until < now() \
             RETURNING id, status",
        )
        .bind(error)
        .fetch_all(&self.pool)
        .await?;
        rows.iter()
            .map(|r| {
                Ok(Reaped {
                    id: r.try_get("id")?,
                    requeued: r.try_get::<&str, _>("status")? == "queued",
                })
            })
            .collect()
    }

    pub async fn purge(&self) -> Result<u64, sqlx::Error> {
        let mut conn = self.pool.acquire().await?;
        let old = sqlx::query(
            "DELETE FROM jobs WHERE study_id IS NULL \
             AND finished_at < now() - $1::float8 * interval '1 millisecond'",
        )
        .bind(ms(self.retention.age))
        .execute(&mut *conn)
        .await?
        .rows_affected();
        let beyond = sqlx::query(
            "DELETE FROM jobs WHERE id IN (SELECT id FROM ( \
               SELECT id, row_number() OVER w AS n, sum(result_bytes) OVER w AS bytes \
               FROM jobs WHERE finished_at IS NOT NULL AND study_id IS NULL \
               WINDOW w AS (ORDER BY finished_at DESC, id DESC)) t \
             WHERE n > $1 OR bytes > $2)",
        )
        .bind(self.retention.max_finished as i64)
        .bind(self.retention.max_bytes.min(i64::MAX as u64) as i64)
        .execute(&mut *conn)
        .await?
        .rows_affected();
        // Studies whose samples have all finished longer ago than the retention.
        Ok(old + beyond + self.purge_studies().await?)
    }

    pub async fn chunk(&self, id: &str, seq: i64) -> Result<Option<Vec<u8>>, sqlx::Error> {
        sqlx::query_scalar("SELECT data FROM job_chunks WHERE job_id = $1 AND seq = $2")
            .bind(id)
            .bind(seq as i32)
            .fetch_optional(&self.pool)
            .await
    }

    pub async fn queued(&self) -> Result<i64, sqlx::Error> {
        sqlx::query_scalar("SELECT count(*) FROM jobs WHERE status = 'queued' AND study_id IS NULL")
            .fetch_one(&self.pool)
            .await
    }

    pub async fn stats(&self) -> Result<Stats, sqlx::Error> {
        let rows = sqlx::query(
            "SELECT status, count(*) AS n, coalesce(sum(result_bytes), 0)::int8 AS bytes \
             FROM jobs GROUP BY status",
        )
        .fetch_all(&self.pool)
        .await?;
        let mut s = Stats::default();
        for r in &rows {
            s.counts
                .push((parse_status(r.try_get("status")?)?, r.try_get("n")?));
            s.result_bytes += r.try_get::<i64, _>("bytes")?;
        }
        Ok(s)
    }
}
