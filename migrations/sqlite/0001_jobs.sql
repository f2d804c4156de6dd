-- Whirl's embedded job store (SQLite, one server): the same schema as migrations/postgres,
-- with times in milliseconds since the Unix epoch. The design is in src/service/store/mod.rs.

CREATE TABLE jobs (
    id            TEXT PRIMARY KEY,
    analysis      TEXT NOT NULL,
    input         TEXT NOT NULL,
    lane          TEXT NOT NULL CHECK (lane IN ('short', 'long')),
    memory_mib    INTEGER NOT NULL,
    status        TEXT NOT NULL
                  CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'cancelled')),
    progress      REAL NOT NULL DEFAULT 0,
    created_at    INTEGER NOT NULL,
    started_at    INTEGER,
    finished_at   INTEGER,
    error         TEXT,
    worker        TEXT,
    lease_until   INTEGER,
    attempts      INTEGER NOT NULL DEFAULT 0,
    expiries      INTEGER NOT NULL DEFAULT 0,
    result_bytes  INTEGER NOT NULL DEFAULT 0,
    result_chunks INTEGER NOT NULL DEFAULT 0
);

CREATE INDEX jobs_active ON jobs (status, id) WHERE status IN ('queued', 'running');
CREATE INDEX jobs_finished ON jobs (finished_at) WHERE finished_at IS NOT NULL;

CREATE TABLE job_chunks (
    job_id TEXT NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    seq    INTEGER NOT NULL,
    data   BLOB NOT NULL,
    PRIMARY KEY (job_id, seq)
);
