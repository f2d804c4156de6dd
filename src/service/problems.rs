//! Problem types (RFC 9457) as absolute URIs that resolve: every problem's `type` is
//! `<base>/problems/<kind>`, and `GET /problems/<kind>` serves a page describing that problem.
//!
//! `base` is `WHIRL_PUBLIC_URL` when set (a server behind a proxy or under another name), else
//! the scheme and `Host` of the request (`X-Forwarded-Proto` for the scheme). The errors keep
//! relative types (`/problems/<kind>`, as a failed job stores them); [`absolute_types`] makes
//! them absolute in every problem+json answer, and [`Base::job`] in a job's `error`.

use axum::body::{Body, to_bytes};
use axum::extract::{FromRequestParts, Path, Request, State};
use axum::http::request::Parts;
use axum::http::{HeaderMap, HeaderValue, header};
use axum::middleware::Next;
use axum::response::{Html, IntoResponse, Response};

use super::error::ApiError;
use crate::model::api::{JobInfo, Problem};

/// One kind of problem: what its page says.
pub struct Kind {
    pub kind: &'static str,
    pub status: u16,
    pub title: &'static str,
    pub meaning: &'static str,
    pub remedy: &'static str,
}

/// Every problem the service answers (a test checks it against [`ApiError`]).
pub const KINDS: &[Kind] = &[
    Kind {
        kind: "malformed-json",
        status: 400,
        title: "Malformed JSON",
        meaning: "The request body is not JSON (a syntax error, or it ends early).",
        remedy: "Send a JSON document; `detail` gives the line and column of the error.",
    },
    Kind {
        kind: "malformed-toml",
        status: 400,
        title: "Malformed TOML",
        meaning: "The body of `POST /v1/convert/ross` is not TOML (a syntax error, a key given \
            twice, or it is not UTF-8).",
        remedy: "Send the file ROSS's `Rotor.save` wrote, unchanged; `detail` gives the line and \
            column of the error.",
    },
    Kind {
        kind: "invalid-model",
        status: 422,
        title: "Invalid model",
        meaning: "The body is JSON but does not describe a valid request: a field is missing, \
            unknown, of the wrong type, out of its range, or a size exceeds a limit. For \
            `POST /v1/convert/ross`: the ROSS file holds an element a Whirl rotor cannot hold, \
            or a bad value.",
        remedy: "`errors` lists every bad field with its JSON path (`rotor.mass`, \
            `speeds[3]`), or its TOML table and key with its line, and what is wrong with it; \
            fix those and send it again.",
    },
    Kind {
        kind: "unsolvable-model",
        status: 422,
        title: "Model cannot be analysed",
        meaning: "The request is valid, but this analysis cannot be carried out on this model \
            (for example a rotor that floats, or the hysteretic model in the time domain).",
        remedy: "`detail` says why; change the model or the analysis.",
    },
    Kind {
        kind: "payload-too-large",
        status: 413,
        title: "Request body too large",
        meaning: "The body is larger than WHIRL_MAX_BODY_BYTES; it was refused from its \
            Content-Length, before it was read.",
        remedy: "Send a smaller model, or raise the server's limit.",
    },
    Kind {
        kind: "busy",
        status: 503,
        title: "Service busy",
        meaning: "Every worker is busy and the queue is full (WHIRL_QUEUE), the memory budget \
            (WHIRL_MEMORY_BUDGET) cannot hold a synchronous answer beside the analyses running \
            and the answers still being sent to their clients, or the server is shutting down.",
        remedy: "Retry after the seconds in `Retry-After`.",
    },
    Kind {
        kind: "store-unavailable",
        status: 503,
        title: "Job store unavailable",
        meaning: "The job store (SQLite or PostgreSQL) did not answer.",
        remedy: "Retry after the seconds in `Retry-After`; `GET /readyz` says when it is back.",
    },
    Kind {
        kind: "not-found",
        status: 404,
        title: "Not found",
        meaning: "No such endpoint, or no such job: unknown, or finished and forgotten after \
            WHIRL_JOB_RETENTION.",
        remedy: "Check the path against `GET /openapi.json`; fetch a job's result within its \
            retention.",
    },
    Kind {
        kind: "not-acceptable",
        status: 406,
        title: "Not acceptable",
        meaning: "No representation the `Accept` header takes exists for this answer (a plot of \
            an analysis that has none, for example).",
        remedy: "Accept application/json, or a format `detail` lists.",
    },
    Kind {
        kind: "internal",
        status: 500,
        title: "Internal error",
        meaning: "A bug in the service; the server keeps serving, and the error is in its log \
            under the response's `x-request-id`.",
        remedy: "Report it with the request and its `x-request-id`.",
    },
    Kind {
        kind: "cancelled",
        status: 409,
        title: "Cancelled",
        meaning: "The analysis was cancelled before it finished.",
        remedy: "Submit it again if you still need it.",
    },
    Kind {
        kind: "stopped",
        status: 409,
        title: "Job stopped",
        meaning: "The job was stopped: cancelled by a client, past WHIRL_JOB_TIME_LIMIT, or its \
            replica died twice while running it; `detail` says which.",
        remedy: "Submit it again, with a smaller sweep if it ran out of time.",
    },
    Kind {
        kind: "conflict",
        status: 409,
        title: "Conflict",
        meaning: "The job is not in a state for this request: its result before it has \
            succeeded, or a cancel after it has finished.",
        remedy: "Poll `GET /v1/jobs/{id}` until its status is `succeeded`.",
    },
    Kind {
        kind: "unsupported-media-type",
        status: 415,
        title: "Unsupported media type",
        meaning: "The body is not declared as JSON.",
        remedy: "Send `Content-Type: application/json` (curl's `--json` does).",
    },
    Kind {
        kind: "method-not-allowed",
        status: 405,
        title: "Method not allowed",
        meaning: "The path exists but does not answer this method.",
        remedy: "Use one of the methods in the `Allow` header.",
    },
    Kind {
        kind: "request-timeout",
        status: 408,
        title: "Request timeout",
        meaning: "The body did not arrive within WHIRL_BODY_TIMEOUT.",
        remedy: "Send the body at once, or over a faster link.",
    },
    Kind {
        kind: "time-limit",
        status: 503,
        title: "Analysis time limit",
        meaning: "A synchronous analysis ran past WHIRL_REQUEST_TIME_LIMIT and was stopped.",
        remedy: "Submit it as a job (`POST /v1/jobs`), which may run longer and can be polled.",
    },
    Kind {
        kind: "idempotency-key-reused",
        status: 422,
        title: "Idempotency key reused",
        meaning: "The `Idempotency-Key` of this `POST /v1/jobs` already names a job that was \
            submitted with a different request. A key names one job, and a retry must send the \
            same request.",
        remedy: "Use a new key for a new job; `detail` names the job the key belongs to.",
    },
];

pub fn kind(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.kind == name)
}

/// Where problem types point: `<base>/problems/<kind>`.
#[derive(Debug, Clone, Default)]
pub struct Base(Option<String>);

impl Base {
    /// `public` (`WHIRL_PUBLIC_URL`), else the request's scheme and host.
    pub fn of(public: Option<&str>, headers: &HeaderMap) -> Self {
        if let Some(p) = public {
            return Base(Some(p.trim_end_matches('/').to_string()));
        }
        let host = headers
            .get(header::HOST)
            .and_then(|h| h.to_str().ok())
            .filter(|h| valid_authority(h));
        let scheme = match headers
            .get("x-forwarded-proto")
            .and_then(|v| v.to_str().ok())
            .map(|v| v.trim().to_ascii_lowercase())
        {
            Some(s) if s == "https" => "https",
            _ => "http",
        };
        Base(host.map(|h| format!("{scheme}://{h}")))
    }

    /// A relative type made absolute (an absolute one, or no known base, as it is).
    pub fn absolute(&self, kind: &str) -> String {
        match &self.0 {
            Some(base) if kind.starts_with('/') => format!("{base}{kind}"),
            _ => kind.to_string(),
        }
    }

    pub fn problem(&self, p: &mut Problem) {
        p.kind = self.absolute(&p.kind);
    }

    /// A job's status with the type of its `error` absolute.
    pub fn job(&self, mut info: JobInfo) -> JobInfo {
        if let Some(p) = info.error.as_mut() {
            self.problem(p);
        }
        info
    }
}

/// A host and port as `Host` carries them (no user info, path or spaces).
fn valid_authority(h: &str) -> bool {
    !h.is_empty()
        && h.len() <= 255
        && h.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b".-:[]_".contains(&b))
}

impl<S: Send + Sync> FromRequestParts<S> for Base {
    type Rejection = std::convert::Infallible;

    async fn from_request_parts(parts: &mut Parts, _: &S) -> Result<Self, Self::Rejection> {
        let public = parts
            .extensions
            .get::<PublicUrl>()
            .and_then(|p| p.0.clone());
        Ok(Base::of(public.as_deref(), &parts.headers))
    }
}

/// `WHIRL_PUBLIC_URL`, for the handlers (a request extension set by [`absolute_types`]).
#[derive(Debug, Clone, Default)]
pub struct PublicUrl(pub Option<String>);

/// Largest problem body rewritten (a 422 lists at most 32 fields).
const MAX_PROBLEM_BYTES: usize = 256 * 1024;

/// Middleware: the `type` of every problem+json answer made absolute.
pub async fn absolute_types(
    State(public): State<PublicUrl>,
    mut req: Request,
    next: Next,
) -> Response {
    let base = Base::of(public.0.as_deref(), req.headers());
    req.extensions_mut().insert(public);
    let resp = next.run(req).await;
    let is_problem = resp
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"application/problem+json"));
    if !is_problem || base.0.is_none() {
        return resp;
    }
    let (mut parts, body) = resp.into_parts();
    let Ok(bytes) = to_bytes(body, MAX_PROBLEM_BYTES).await else {
        return ApiError::Internal("a problem body could not be read".into()).into_response();
    };
    let out = match serde_json::from_slice::<Problem>(&bytes) {
        Ok(mut p) => {
            base.problem(&mut p);
            serde_json::to_vec(&p)
                .map(Body::from)
                .unwrap_or(Body::from(bytes))
        }
        Err(_) => Body::from(bytes),
    };
    parts.headers.remove(header::CONTENT_LENGTH);
    Response::from_parts(parts, out)
}

/// A page describing a problem type.
#[utoipa::path(get, path = "/problems/{kind}", tag = "operations",
    params(("kind" = String, Path, description = "The problem's kind: the last segment of its `type`")),
    responses(
        (status = 200, description = "What the problem means and what to do", body = String, content_type = "text/html"),
        (status = 404, description = "No such problem type", body = Problem, content_type = "application/problem+json")))]
pub async fn page(Path(name): Path<String>) -> Result<Response, ApiError> {
    let k = kind(&name).ok_or_else(|| ApiError::NotFound(format!("no problem type {name:?}")))?;
    let mut resp = Html(html(k)).into_response();
    resp.headers_mut().insert(
        header::CACHE_CONTROL,
        HeaderValue::from_static("public, max-age=86400"),
    );
    Ok(resp)
}

fn html(k: &Kind) -> String {
    // Backticks in the texts are code.
    let code = |s: &str| {
        s.split('`')
            .enumerate()
            .map(|(i, part)| {
                if i % 2 == 1 {
                    format!("<code>{part}</code>")
                } else {
                    part.to_string()
                }
            })
            .collect::<String>()
    };
    format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>{title} ({status}) - Whirl</title>\
         <style>body{{font:16px/1.5 system-ui,sans-serif;max-width:42em;margin:2em auto;padding:0 1em}}\
         code{{background:#f3f3f3;padding:0 .2em}}</style></head>\n<body>\
         <h1>{title}</h1>\n<p>HTTP status <strong>{status}</strong>, problem type \
         <code>/problems/{kind}</code> (<code>application/problem+json</code>, RFC 9457).</p>\n\
         <h2>What it means</h2>\n<p>{meaning}</p>\n<h2>What to do</h2>\n<p>{remedy}</p>\n\
         <p>Every problem carries <code>type</code>, <code>title</code>, <code>status</code> and \
         <code>detail</code>; a 422 also <code>errors</code>, one per bad field. The API is \
         described at <a href=\"/docs\">/docs</a>.</p>\n</body></html>\n",
        title = k.title,
        status = k.status,
        kind = k.kind,
        meaning = code(k.meaning),
        remedy = code(k.remedy),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One of each error (a new variant fails to compile here until it is listed).
    fn every_error() -> Vec<ApiError> {
        let all = vec![
            ApiError::Malformed(String::new()),
            ApiError::MalformedToml(String::new()),
            ApiError::Invalid(crate::model::Invalid::one("x", "y")),
            ApiError::Unsolvable(String::new()),
            ApiError::TooLarge(1),
            ApiError::Busy,
            ApiError::NotFound(String::new()),
            ApiError::NotAcceptable(String::new()),
            ApiError::Internal(String::new()),
            ApiError::Cancelled,
            ApiError::Stopped(String::new()),
            ApiError::Conflict(String::new()),
            ApiError::UnsupportedMediaType(String::new()),
            ApiError::MethodNotAllowed(String::new()),
            ApiError::RequestTimeout(std::time::Duration::ZERO),
            ApiError::TimeLimit(std::time::Duration::ZERO),
            ApiError::Unavailable(String::new()),
            ApiError::KeyReused(String::new()),
        ];
        for e in &all {
            match e {
                ApiError::Malformed(_)
                | ApiError::MalformedToml(_)
                | ApiError::Invalid(_)
                | ApiError::Unsolvable(_)
                | ApiError::TooLarge(_)
                | ApiError::Busy
                | ApiError::NotFound(_)
                | ApiError::NotAcceptable(_)
                | ApiError::Internal(_)
                | ApiError::Cancelled
                | ApiError::Stopped(_)
                | ApiError::Conflict(_)
                | ApiError::UnsupportedMediaType(_)
                | ApiError::MethodNotAllowed(_)
                | ApiError::RequestTimeout(_)
                | ApiError::TimeLimit(_)
                | ApiError::Unavailable(_)
                | ApiError::KeyReused(_) => {}
            }
        }
        all
    }

    #[test]
    fn every_problem_has_its_page() {
        let errors = every_error();
        for e in &errors {
            let p = e.problem();
            let name = p.kind.strip_prefix("/problems/").expect("relative type");
            let k = kind(name).unwrap_or_else(|| panic!("no page for {name}"));
            assert_eq!((k.status, k.title), (p.status, p.title.as_str()), "{name}");
        }
        // And no page for a problem that does not exist.
        assert_eq!(KINDS.len(), errors.len());
    }

    #[test]
    fn bases() {
        let mut h = HeaderMap::new();
        h.insert(
            header::HOST,
            HeaderValue::from_static("whirl.internal:8080"),
        );
        assert_eq!(
            Base::of(None, &h).absolute("/problems/busy"),
            "http://whirl.internal:8080/problems/busy"
        );
        h.insert("x-forwarded-proto", HeaderValue::from_static("https"));
        assert_eq!(
            Base::of(None, &h).absolute("/problems/busy"),
            "https://whirl.internal:8080/problems/busy"
        );
        let public = Base::of(Some("https://api.example.com/whirl/"), &h);
        assert_eq!(
            public.absolute("/problems/busy"),
            "https://api.example.com/whirl/problems/busy"
        );
        // A Host that is not a host is not copied into a URI.
        h.insert(header::HOST, HeaderValue::from_static("evil.com/x?y"));
        h.remove("x-forwarded-proto");
        assert_eq!(
            Base::of(None, &h).absolute("/problems/busy"),
            "/problems/busy"
        );
    }
}
