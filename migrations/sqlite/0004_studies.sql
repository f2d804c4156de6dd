-- Studies (issue 33): a parametric sweep or Monte Carlo over one job request; each sample is
-- a job naming its study. Same schema as migrations/postgres/0004, times in ms.

CREATE TABLE studies (
    id           TEXT PRIMARY KEY,
    analysis     TEXT NOT NULL,
    request      TEXT NOT NULL,
    samples      INTEGER NOT NULL,
    created_at   INTEGER NOT NULL,
    cancelled_at INTEGER,
    error        TEXT
);

ALTER TABLE jobs ADD COLUMN study_id TEXT REFERENCES studies (id) ON DELETE CASCADE;
ALTER TABLE jobs ADD COLUMN sample INTEGER;
ALTER TABLE jobs ADD COLUMN parameters TEXT;
CREATE INDEX jobs_study ON jobs (study_id, sample) WHERE study_id IS NOT NULL;
CREATE INDEX jobs_queue ON jobs ((study_id IS NOT NULL), id) WHERE status = 'queued';
