-- Studies (issue 33): a parametric sweep or Monte Carlo over one job request. The study is a
-- row here; each sample is a job in the shared queue (any replica claims it) that names its
-- study, so the study's state is its jobs' and survives restarts and dead replicas.

CREATE TABLE studies (
    id           text PRIMARY KEY,          -- UUIDv7
    analysis     text NOT NULL,
    request      text NOT NULL,             -- the study request as received (JSON)
    samples      integer NOT NULL,
    created_at   timestamptz NOT NULL DEFAULT now(),
    cancelled_at timestamptz,
    error        jsonb                      -- problem+json of a cancelled study
);

-- A study's samples go with it (and their results with them).
ALTER TABLE jobs ADD COLUMN study_id text REFERENCES studies (id) ON DELETE CASCADE;
ALTER TABLE jobs ADD COLUMN sample integer;      -- its index in the study
ALTER TABLE jobs ADD COLUMN parameters text;     -- the values substituted (JSON array)
CREATE INDEX jobs_study ON jobs (study_id, sample) WHERE study_id IS NOT NULL;
-- Claims: single jobs before the samples of studies, each oldest first.
CREATE INDEX jobs_queue ON jobs ((study_id IS NOT NULL), id) WHERE status = 'queued';
