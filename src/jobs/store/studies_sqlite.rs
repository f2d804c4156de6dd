//! Studies on SQLite (see `studies.rs`); statements as in `studies_pg.rs`.

use sqlx::{QueryBuilder, Row};

use super::sqlite::Sqlite;
use super::studies::{BATCH, NewSample, NewStudy, SampleRow, StudyRow};
use super::{lane_text, ms, now_ms, parse_problem, parse_status};

impl Sqlite {
    pub async fn submit_study(
        &self,
        study: &NewStudy<'_>,
        samples: &[NewSample],
        queue: usize,
    ) -> Result<bool, sqlx::Error> {
        let now = now_ms();
        let mut tx = self.pool.begin().await?;
        sqlx::query(
            "INSERT INTO studies (id, analysis, request, samples, created_at) \
             VALUES (?1, ?2, ?3, ?4, ?5)",
        )
        .bind(study.id)
        .bind(study.analysis)
        .bind(study.request)
        .bind(samples.len() as i64)
        .bind(now)
        .execute(&mut *tx)
        .await?;
        // Counted after the first write: the transaction then holds the write lock, so nothing
        // comes between the count and the inserts (a read first would have to upgrade its lock,
        // which SQLite refuses at once when another connection wrote). Too many: rolled back.
        let waiting: i64 = sqlx::query_scalar(
            "SELECT count(*) FROM jobs WHERE status = 'queued' AND study_id IS NOT NULL",
        )
        .fetch_one(&mut *tx)
        .await?;
        if waiting + samples.len() as i64 > queue as i64 {
            return Ok(false);
        }
        for (b, batch) in samples.chunks(BATCH).enumerate() {
            let mut q = QueryBuilder::<sqlx::Sqlite>::new(
                "INSERT INTO jobs (id, analysis, input, lane, memory_mib, status, created_at, \
                 study_id, sample, parameters) ",
            );
            q.push_values(batch.iter().enumerate(), |mut r, (i, s)| {
                r.push_bind(&s.id)
                    .push_bind(study.analysis)
                    .push_bind(&s.input)
                    .push_bind(lane_text(s.lane))
                    .push_bind(s.memory_mib as i64)
                    .push_bind("queued")
                    .push_bind(now)
                    .push_bind(study.id)
                    .push_bind((b * BATCH + i) as i64)
                    .push_bind(&s.parameters);
            });
            q.build().execute(&mut *tx).await?;
        }
        tx.commit().await?;
        Ok(true)
    }

    pub async fn study(&self, id: &str) -> Result<Option<StudyRow>, sqlx::Error> {
        let Some(r) = sqlx::query(
            "SELECT id, analysis, request, samples, created_at, \
               cancelled_at IS NOT NULL AS cancelled, error FROM studies WHERE id = ?1",
        )
        .bind(id)
        .fetch_optional(&self.pool)
        .await?
        else {
            return Ok(None);
        };
        let counts = sqlx::query(
            "SELECT status, count(*) AS n FROM jobs WHERE study_id = ?1 GROUP BY status",
        )
        .bind(id)
        .fetch_all(&self.pool)
        .await?
        .iter()
        .map(|c| Ok((parse_status(c.try_get("status")?)?, c.try_get("n")?)))
        .collect::<Result<_, sqlx::Error>>()?;
        Ok(Some(StudyRow {
            id: r.try_get("id")?,
            analysis: r.try_get("analysis")?,
            request: r.try_get("request")?,
            samples: r.try_get("samples")?,
            created_ms: r.try_get("created_at")?,
            cancelled: r.try_get("cancelled")?,
            error: parse_problem(r.try_get("error")?),
            counts,
        }))
    }

    pub async fn study_samples(
        &self,
        id: &str,
        from: i64,
        count: i64,
    ) -> Result<Vec<SampleRow>, sqlx::Error> {
        let rows = sqlx::query(
            "SELECT j.sample, j.status, j.worker, j.error, j.parameters, c.data \
             FROM jobs j LEFT JOIN job_chunks c ON c.job_id = j.id AND j.status = 'succeeded' \
             WHERE j.study_id = ?1 AND j.sample >= ?2 AND j.sample < ?2 + ?3 \
             ORDER BY j.sample, c.seq",
        )
        .bind(id)
        .bind(from)
        .bind(count)
        .fetch_all(&self.pool)
        .await?;
        let mut out: Vec<SampleRow> = vec![];
        for r in &rows {
            let sample: i64 = r.try_get("sample")?;
            let data: Option<Vec<u8>> = r.try_get("data")?;
            if let Some(last) = out.last_mut().filter(|l| l.sample == sample) {
                last.gzip.extend(data.unwrap_or_default());
                continue;
            }
            out.push(SampleRow {
                sample,
                status: parse_status(r.try_get("status")?)?,
                worker: r.try_get("worker")?,
                error: parse_problem(r.try_get("error")?),
                parameters: r
                    .try_get::<Option<String>, _>("parameters")?
                    .unwrap_or_default(),
                gzip: data.unwrap_or_default(),
            });
        }
        Ok(out)
    }

    pub async fn cancel_study(
        &self,
        id: &str,
        error: &str,
    ) -> Result<Option<Vec<String>>, sqlx::Error> {
        let now = now_ms();
        let mut tx = self.pool.begin().await?;
        let found = sqlx::query(
            "UPDATE studies SET cancelled_at = coalesce(cancelled_at, ?2), \
               error = coalesce(error, ?3) WHERE id = ?1",
        )
        .bind(id)
        .bind(now)
        .bind(error)
        .execute(&mut *tx)
        .await?
        .rows_affected();
        if found == 0 {
            return Ok(None);
        }
        let ids = sqlx::query_scalar(
            "UPDATE jobs SET status = 'cancelled', finished_at = ?2, error = ?3, \
               lease_until = NULL \
             WHERE study_id = ?1 AND status IN ('queued', 'running') RETURNING id",
        )
        .bind(id)
        .bind(now)
        .bind(error)
        .fetch_all(&mut *tx)
        .await?;
        tx.commit().await?;
        Ok(Some(ids))
    }

    /// Deletes the studies (and their samples) whose samples have all finished longer ago than
    /// the retention.
    pub(super) async fn purge_studies(&self) -> Result<u64, sqlx::Error> {
        let cutoff = now_ms() - ms(self.retention.age);
        Ok(sqlx::query(
            "DELETE FROM studies WHERE created_at < ?1 \
               AND NOT EXISTS (SELECT 1 FROM jobs j WHERE j.study_id = studies.id \
                 AND (j.finished_at IS NULL OR j.finished_at > ?1))",
        )
        .bind(cutoff)
        .execute(&self.pool)
        .await?
        .rows_affected())
    }
}
