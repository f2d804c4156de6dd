-- Whirl's job store on PostgreSQL: the queue all replicas share, and the results.
-- The design is in src/service/store/mod.rs. Give Whirl a database of its own.

CREATE TABLE jobs (
    id            text PRIMARY KEY,         -- UUIDv7: its order is the order of submission
    analysis      text NOT NULL,            -- modal, campbell, ... (POST /v1/<analysis>)
    input         text NOT NULL,            -- the job's JSON input: any replica parses it again
    lane          text NOT NULL CHECK (lane IN ('short', 'long')),
    memory_mib    bigint NOT NULL,          -- estimated peak heap: a replica claims what fits
    status        text NOT NULL
                  CHECK (status IN ('queued', 'running', 'succeeded', 'failed', 'cancelled')),
    progress      double precision NOT NULL DEFAULT 0,
    created_at    timestamptz NOT NULL DEFAULT now(),
    started_at    timestamptz,
    finished_at   timestamptz,
    error         jsonb,                    -- problem+json of a failed or cancelled job
    worker        text,                     -- the replica that claimed it
    lease_until   timestamptz,              -- renewed by that replica's heartbeat
    attempts      integer NOT NULL DEFAULT 0,  -- claims: executions started
    expiries      integer NOT NULL DEFAULT 0,  -- leases that ran out (a replica died)
    result_bytes  bigint NOT NULL DEFAULT 0,   -- gzipped JSON of the result, in job_chunks
    result_chunks integer NOT NULL DEFAULT 0
) WITH (fillfactor = 80);  -- room for heartbeats to update in place (no indexed column changes)

-- The queue and the running jobs: a few rows, whatever the number of finished jobs kept.
CREATE INDEX jobs_active ON jobs (status, id) WHERE status IN ('queued', 'running');
-- Retention: oldest finished first.
CREATE INDEX jobs_finished ON jobs (finished_at) WHERE finished_at IS NOT NULL;

CREATE TABLE job_chunks (
    job_id text NOT NULL REFERENCES jobs (id) ON DELETE CASCADE,
    seq    integer NOT NULL,
    data   bytea NOT NULL,
    PRIMARY KEY (job_id, seq)
);
-- gzip does not compress again: store it out of line, as it is.
ALTER TABLE job_chunks ALTER COLUMN data SET STORAGE EXTERNAL;
