-- Idempotency keys of POST /v1/jobs and the job listing (issue 32). A key names one job while
-- that job is kept; the hash of the request it came with tells a retry from a different
-- request under the same key.

ALTER TABLE jobs ADD COLUMN idempotency_key text;  -- the client's Idempotency-Key
ALTER TABLE jobs ADD COLUMN request_sha256 text;   -- of the analysis and the input, compact JSON
CREATE UNIQUE INDEX jobs_idempotency ON jobs (idempotency_key) WHERE idempotency_key IS NOT NULL;
-- GET /v1/jobs?analysis=...: newest first.
CREATE INDEX jobs_by_analysis ON jobs (analysis, id);
