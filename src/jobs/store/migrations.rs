//! The schema's migrations, compiled into the binary and applied at connection (the same
//! versions on both engines).

use std::borrow::Cow;

use sqlx::error::BoxDynError;
use sqlx::migrate::{Migration, MigrationSource, MigrationType, Migrator};

use super::StoreError;

/// Migrations compiled into the binary: (version, description, SQL).
#[derive(Debug)]
struct Embedded(&'static [(i64, &'static str, &'static str)]);

impl MigrationSource<'static> for Embedded {
    fn resolve(
        self,
    ) -> futures_util::future::BoxFuture<'static, Result<Vec<Migration>, BoxDynError>> {
        Box::pin(async move {
            Ok(self
                .0
                .iter()
                .map(|(v, d, sql)| {
                    Migration::new(
                        *v,
                        Cow::Borrowed(*d),
                        MigrationType::Simple,
                        Cow::Borrowed(*sql),
                        false,
                    )
                })
                .collect())
        })
    }
}

const POSTGRES_MIGRATIONS: Embedded = Embedded(&[
    (
        1,
        "jobs",
        include_str!("../../../migrations/postgres/0001_jobs.sql"),
    ),
    (
        3,
        "job keys",
        include_str!("../../../migrations/postgres/0003_job_keys.sql"),
    ),
    (
        4,
        "studies",
        include_str!("../../../migrations/postgres/0004_studies.sql"),
    ),
]);
const SQLITE_MIGRATIONS: Embedded = Embedded(&[
    (
        1,
        "jobs",
        include_str!("../../../migrations/sqlite/0001_jobs.sql"),
    ),
    (
        3,
        "job keys",
        include_str!("../../../migrations/sqlite/0003_job_keys.sql"),
    ),
    (
        4,
        "studies",
        include_str!("../../../migrations/sqlite/0004_studies.sql"),
    ),
]);

pub(super) async fn postgres() -> Result<Migrator, StoreError> {
    Ok(Migrator::new(POSTGRES_MIGRATIONS).await?)
}

pub(super) async fn sqlite() -> Result<Migrator, StoreError> {
    Ok(Migrator::new(SQLITE_MIGRATIONS).await?)
}
