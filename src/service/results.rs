//! A succeeded job's result, served from the store one chunk at a time.
//!
//! The store keeps the result as gzipped JSON in chunks (see `store`). A client that takes
//! gzipped JSON gets those bytes as they are, with `Content-Encoding: gzip` and their length;
//! one that takes JSON but not gzip gets it decompressed chunk by chunk. Either way the server
//! holds one chunk of a result at a time, however large it is and however many are kept. A
//! table or a plot is rendered from the whole output, as the synchronous endpoint does.
//!
//! A result never changes once stored, so it is cacheable for good: a weak `ETag` names the
//! job and the representation (the formats `Accept` ranked, which decide the one served; weak
//! because gzip and identity codings share it), with `Cache-Control: private, max-age=31536000,
//! immutable`, and `If-None-Match` with a current tag answers 304 before the store's chunks
//! are read or anything is rendered.

use std::io::Write;
use std::sync::Arc;

use axum::body::{Body, Bytes};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use futures_util::stream::{self, Stream};

use super::error::ApiError;
use crate::jobs::Stored;
use crate::jobs::store::{JobRow, Store};
use crate::render::{Format, render};

type Chunk = Result<Bytes, std::io::Error>;

/// `private`: a result may be one client's (an authenticated service); a year, as for any
/// immutable resource.
const IMMUTABLE: &str = "private, max-age=31536000, immutable";

/// The tag of job `id`'s result in the first of `formats` it has.
pub fn etag(id: &str, formats: &[Format]) -> String {
    let names: Vec<String> = formats
        .iter()
        .map(|f| format!("{f:?}").to_ascii_lowercase())
        .collect();
    format!("W/\"{id}.{}\"", names.join("+"))
}

/// Whether `If-None-Match` names `tag` (weak comparison, RFC 9110 13.1.2), or is `*`.
pub fn matches(headers: &HeaderMap, tag: &str) -> bool {
    let opaque = |t: &str| t.trim().trim_start_matches("W/").to_string();
    let ours = opaque(tag);
    headers
        .get_all(header::IF_NONE_MATCH)
        .iter()
        .filter_map(|v| v.to_str().ok())
        .flat_map(|v| v.split(','))
        .any(|t| t.trim() == "*" || opaque(t) == ours)
}

/// 304 for a current copy: its tag and caching, no body.
pub fn not_modified(tag: &str) -> Response {
    let mut resp = StatusCode::NOT_MODIFIED.into_response();
    immutable(&mut resp, tag);
    resp
}

/// The caching headers of a result.
pub fn immutable(resp: &mut Response, tag: &str) {
    let h = resp.headers_mut();
    if let Ok(v) = HeaderValue::from_str(tag) {
        h.insert(header::ETAG, v);
    }
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static(IMMUTABLE));
    h.insert(
        header::VARY,
        HeaderValue::from_static("accept, accept-encoding"),
    );
}

/// The result of a succeeded job (`row`) in the first acceptable format.
pub async fn respond(
    store: Arc<Store>,
    row: JobRow,
    formats: Vec<Format>,
    gzip_ok: bool,
) -> Result<Response, ApiError> {
    let id = row.id.clone();
    let first = store
        .chunk(&id, 0)
        .await?
        .ok_or_else(|| ApiError::NotFound(format!("no job {id} (finished and forgotten)")))?;
    let chunks = row.result_chunks.max(1);
    let mut resp = if formats.first() == Some(&Format::Json) {
        let raw = raw(store, id, first, chunks);
        let mut resp = if gzip_ok {
            let mut r = Body::from_stream(raw).into_response();
            let h = r.headers_mut();
            h.insert(header::CONTENT_ENCODING, HeaderValue::from_static("gzip"));
            h.insert(header::CONTENT_LENGTH, HeaderValue::from(row.result_bytes));
            r
        } else {
            Body::from_stream(gunzip(raw)).into_response()
        };
        resp.headers_mut().insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static(Format::Json.media()),
        );
        resp
    } else {
        let mut gzip = first;
        for seq in 1..chunks {
            let c = store.chunk(&id, seq).await?.ok_or_else(|| {
                ApiError::NotFound(format!("no job {id} (finished and forgotten)"))
            })?;
            gzip.extend_from_slice(&c);
        }
        // Decompressing and rendering a large result is work: off the runtime.
        let analysis = row.analysis.clone();
        tokio::task::spawn_blocking(move || {
            let out = Stored::output(&analysis, &gzip)?;
            render(&out, &formats)
        })
        .await
        .map_err(|e| ApiError::Internal(e.to_string()))??
        .into_response()
    };
    resp.headers_mut().insert(
        header::VARY,
        HeaderValue::from_static("accept, accept-encoding"),
    );
    Ok(resp)
}

/// The stored chunks as they are, `first` (chunk 0) already read.
fn raw(
    store: Arc<Store>,
    id: String,
    first: Vec<u8>,
    chunks: i64,
) -> impl Stream<Item = Chunk> + Send + 'static {
    stream::unfold((Some(first), 1i64), move |(first, seq)| {
        let store = store.clone();
        let id = id.clone();
        async move {
            if let Some(f) = first {
                return Some((Ok(Bytes::from(f)), (None, seq)));
            }
            if seq >= chunks {
                return None;
            }
            let item = match store.chunk(&id, seq).await {
                Ok(Some(c)) => Ok(Bytes::from(c)),
                Ok(None) => Err(std::io::Error::other(
                    "the result was forgotten while it was sent",
                )),
                Err(e) => Err(std::io::Error::other(e.0)),
            };
            // After an error the stream ends (the connection is closed mid-body).
            let next = if item.is_ok() { seq + 1 } else { chunks };
            Some((item, (None, next)))
        }
    })
}

/// Gzipped chunks decompressed one by one (on the blocking pool).
fn gunzip(
    chunks: impl Stream<Item = Chunk> + Send + 'static,
) -> impl Stream<Item = Chunk> + Send + 'static {
    use futures_util::StreamExt;
    let decoder = flate2::write::GzDecoder::new(Vec::new());
    let chunks = Box::pin(chunks);
    stream::unfold(Some((decoder, chunks)), |state| async move {
        let (mut decoder, mut chunks) = state?;
        match chunks.next().await {
            Some(Ok(gz)) => {
                let r = tokio::task::spawn_blocking(move || {
                    decoder.write_all(&gz)?;
                    let out = std::mem::take(decoder.get_mut());
                    Ok::<_, std::io::Error>((decoder, out))
                })
                .await
                .map_err(std::io::Error::other)
                .and_then(|r| r);
                match r {
                    Ok((decoder, out)) => Some((Ok(Bytes::from(out)), Some((decoder, chunks)))),
                    Err(e) => Some((Err(e), None)),
                }
            }
            Some(Err(e)) => Some((Err(e), None)),
            None => match decoder.try_finish() {
                Ok(()) => {
                    let rest = std::mem::take(decoder.get_mut());
                    if rest.is_empty() {
                        None
                    } else {
                        Some((Ok(Bytes::from(rest)), None))
                    }
                }
                Err(e) => Some((Err(e), None)),
            },
        }
    })
}
