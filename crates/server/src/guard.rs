//! Closed doors and a memory budget, as middleware in front of every route.
//!
//! - **Host** (DNS rebinding): a browser always names the site it thinks it talks to in
//!   `Host`. A page on `evil.example` whose name was re-pointed to 127.0.0.1 sends
//!   `Host: evil.example`, so only loopback names, the address the connection was accepted
//!   on and the names given with `--allow-host` are served (403 otherwise). A request
//!   without `Host` (HTTP/1.0, in-process tests) comes from no browser and passes. An
//!   absolute-form target (`GET http://evil.example/`) names its host in the target, which
//!   then counts as the request's host (RFC 9112, 3.2.2) and is checked the same way; two
//!   `Host` headers are a 400 (which one counts would be a guess).
//! - **Origin** (cross-site requests): a multipart POST is a "simple" CORS request that a
//!   browser sends from any page without asking. A state-changing request (any method but
//!   GET, HEAD, OPTIONS) whose `Origin` is neither this server's own (same scheme-less
//!   authority as `Host`) nor one given with `--cors` is refused with 403; so is one that
//!   carries no `Origin` but a `Sec-Fetch-Site` saying it comes from another site.
//! - **Upload budget**: every request with a body holds, while it is served, permits for
//!   its announced length (or its route's body limit when it announces none) from a budget
//!   of [`super::Config::upload_budget`] bytes, so concurrent uploads wait instead of
//!   multiplying the memory they take; after a large one, freed memory goes back to the OS.
//!   A body announced over its route's own limit (uploads to `/api/analyze`: the body
//!   limit; the JSON routes: the JSON limit) is refused at once, holding nothing. Answers
//!   count too: an answer of 64 KiB or more holds permits for its length until it is
//!   written or its connection dropped, and an answer whose size is known beforehand (an
//!   interpolation's, a sample list's) is reserved before it is built.
//! - **A fair budget**: the budget is two pools. Bodies and answers of at most
//!   [`SMALL_REQUEST`] (1 MiB) take from a pool of their own (an eighth of the budget), so a
//!   small request never waits behind large ones; larger ones share the rest. Whatever holds
//!   a pool must not hold it idle while others wait for it: a body must keep the pace that
//!   finishes it within the request time-out (its length over the time-out, at least
//!   [`MIN_BODY_RATE`]), and while anyone waits for its pool its grace is
//!   [`CROWDED_GRACE`]; an answer its client does not read for [`CROWDED_GRACE`] while
//!   anyone waits for its pool is dropped with its connection ([`AnswerWatch`], checked by
//!   the socket). A connection thus holds at most one body and one answer, and only while
//!   it uses them.
//! - **Body rate**: a body must keep arriving. After a grace of the header time-out (of
//!   [`CROWDED_GRACE`] while nearly every connection slot is taken, or its pool is waited
//!   for), it must have come at its pace on average, or the read fails (408) and the
//!   connection, its budget share and its worker are freed: a client trickling a body
//!   cannot hold them for the whole request time-out, and trickling connections cannot keep
//!   new clients out.
//!
//! ```
//! use close_server::guard::host_name;
//! assert_eq!(host_name("LocalHost:8080"), "localhost");
//! assert_eq!(host_name("[::1]:80"), "::1");
//! ```

use std::future::Future;
use std::net::{IpAddr, SocketAddr};
use std::pin::Pin;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll};
use std::time::Duration;

use axum::body::HttpBody;
use axum::extract::{Request, State};
use axum::http::{header, HeaderMap, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use tokio::sync::{OwnedSemaphorePermit, Semaphore};

use super::error::{ApiError, BodyTooSlow};

/// The local address a connection was accepted on, put on each request by the accept loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ServedAt(pub SocketAddr);

/// Who may reach the server: extra host names and cross-origin callers.
#[derive(Debug, Clone, Default)]
pub struct Doors {
    /// Host names served besides loopback and the accepting address (lower case).
    pub hosts: Vec<String>,
    /// Origins allowed to make state-changing requests (`--cors`).
    pub origins: Vec<String>,
}

/// The host part of a `Host` value or authority, lower case, without port, brackets or a
/// trailing dot.
pub fn host_name(authority: &str) -> String {
    let authority = authority.trim();
    let host = match authority.strip_prefix('[') {
        Some(v6) => v6.split(']').next().unwrap_or(v6),
        None => authority.rsplit_once(':').map_or(authority, |(h, _)| h),
    };
    host.trim_end_matches('.').to_ascii_lowercase()
}

/// `authority` with the default port of plain HTTP made explicit, for comparing.
fn with_port(authority: &str) -> String {
    let authority = authority.trim().to_ascii_lowercase();
    let has_port = authority.rsplit_once(':').is_some_and(|(h, p)| {
        !p.is_empty()
            && p.bytes().all(|b| b.is_ascii_digit())
            && (!h.starts_with('[') || h.ends_with(']'))
    });
    if has_port {
        authority
    } else {
        format!("{authority}:80")
    }
}

impl Doors {
    fn host_allowed(&self, host: &str, served_at: Option<ServedAt>) -> bool {
        let name = host_name(host);
        let ip = name.parse::<IpAddr>().ok();
        name == "localhost"
            || name.ends_with(".localhost")
            || ip.is_some_and(|ip| ip.is_loopback())
            || served_at
                .is_some_and(|ServedAt(at)| !at.ip().is_unspecified() && ip == Some(at.ip()))
            || self.hosts.iter().any(|h| host_name(h) == name)
    }

    /// Same origin: `http://` plus exactly the authority the request was sent to.
    fn origin_allowed(&self, origin: &str, host: Option<&str>) -> bool {
        if self.origins.iter().any(|o| o.trim_end_matches('/').eq_ignore_ascii_case(origin)) {
            return true;
        }
        match (origin.strip_prefix("http://"), host) {
            (Some(authority), Some(host)) => with_port(authority) == with_port(host),
            _ => false,
        }
    }

    /// Why `request` may not pass, if it may not.
    fn refuse(
        &self,
        method: &Method,
        headers: &HeaderMap,
        served_at: Option<ServedAt>,
    ) -> Option<String> {
        let host = headers.get(header::HOST).map(|h| h.to_str().unwrap_or("(not text)"));
        if let Some(host) = host.filter(|h| !self.host_allowed(h, served_at)) {
            return Some(format!(
                "this server does not answer to the host name {host:?}: start it with --allow-host {} to allow it",
                host_name(host)
            ));
        }
        if matches!(*method, Method::GET | Method::HEAD | Method::OPTIONS) {
            return None;
        }
        match headers.get(header::ORIGIN).map(|o| o.to_str().unwrap_or("(not text)")) {
            Some(origin) if !self.origin_allowed(origin, host) => Some(format!(
                "a {method} from the page at {origin:?} is refused: only this server's own pages may send it (or start the server with --cors {origin})"
            )),
            Some(_) => None,
            None => headers
                .get("sec-fetch-site")
                .filter(|site| matches!(site.as_bytes(), b"cross-site" | b"same-site"))
                .map(|_| format!("a {method} from another site is refused")),
        }
    }
}

/// Middleware: 400 for two `Host` headers; 403 for a foreign `Host` or target authority, or
/// a cross-origin state-changing request.
pub async fn doors(State(doors): State<Arc<Doors>>, request: Request, next: Next) -> Response {
    let served_at = request.extensions().get::<ServedAt>().copied();
    if request.headers().get_all(header::HOST).iter().nth(1).is_some() {
        return ApiError::Rejected(
            StatusCode::BAD_REQUEST,
            "the request has more than one Host header".into(),
        )
        .into_response();
    }
    let target = request.uri().authority().map(|a| a.as_str().to_string());
    let foreign_target = target.filter(|t| !doors.host_allowed(t, served_at)).map(|t| {
        format!("this server does not answer to the host name {t:?} of the request target: start it with --allow-host {} to allow it", host_name(&t))
    });
    match foreign_target.or_else(|| doors.refuse(request.method(), request.headers(), served_at)) {
        Some(why) => ApiError::Rejected(StatusCode::FORBIDDEN, why).into_response(),
        None => next.run(request).await,
    }
}

/// Bodies and answers of at most this many bytes take from the small requests' pool.
pub const SMALL_REQUEST: usize = 1 << 20;

/// One pool of the budget: KiB permits, and how many wait for them now.
#[derive(Debug)]
pub struct Pool {
    permits: Arc<Semaphore>,
    /// All its permits: no single request asks for more.
    total_kib: u32,
    waiting: AtomicUsize,
}

/// Counts a wait for a pool while it lasts (a wait given up when its request is dropped too).
struct Waiting<'a>(&'a AtomicUsize);

impl Drop for Waiting<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::Relaxed);
    }
}

impl Pool {
    fn new(kib: u32) -> Pool {
        let kib = kib.clamp(1, Semaphore::MAX_PERMITS as u32);
        Pool { permits: Arc::new(Semaphore::new(kib as usize)), total_kib: kib, waiting: 0.into() }
    }

    /// KiB permits for `bytes`: at least one, at most all.
    fn kib(&self, bytes: usize) -> u32 {
        u32::try_from(bytes.div_ceil(1024)).unwrap_or(u32::MAX).clamp(1, self.total_kib)
    }

    /// Take `kib` permits, after those who wait already; counted as waiting meanwhile.
    async fn take(&self, kib: u32) -> Result<OwnedSemaphorePermit, ApiError> {
        if let Ok(permits) = self.permits.clone().try_acquire_many_owned(kib) {
            return Ok(permits);
        }
        self.waiting.fetch_add(1, Ordering::Relaxed);
        let _waiting = Waiting(&self.waiting);
        self.permits.clone().acquire_many_owned(kib).await.map_err(|_| closed())
    }

    /// Whether anyone waits for this pool now: what holds it must then use it or let go.
    pub fn crowded(&self) -> bool {
        self.waiting.load(Ordering::Relaxed) > 0
    }
}

/// Bytes of request bodies and answers that may be held at once, counted in KiB permits,
/// in two pools: small requests' and large ones'.
#[derive(Debug)]
pub struct UploadBudget {
    small: Arc<Pool>,
    large: Arc<Pool>,
    /// What an upload to `/api/analyze` may hold.
    body_limit: usize,
    /// What the body of any other route may hold.
    json_body_limit: usize,
}

/// The one route that takes uploads up to the body limit; the others take small JSON.
const UPLOAD_ROUTE: &str = "/api/analyze";

impl UploadBudget {
    /// A budget of `bytes`: an eighth (at least [`SMALL_REQUEST`], at most half) for small
    /// requests, the rest for large ones.
    pub fn new(bytes: usize, body_limit: usize, json_body_limit: usize) -> Self {
        let total_kib = u32::try_from(bytes.div_ceil(1024)).unwrap_or(u32::MAX).max(2);
        let small_kib = (total_kib / 8).max((SMALL_REQUEST / 1024) as u32).min(total_kib / 2);
        UploadBudget {
            small: Arc::new(Pool::new(small_kib)),
            large: Arc::new(Pool::new(total_kib - small_kib)),
            body_limit,
            json_body_limit,
        }
    }

    /// The largest body the route at `path` takes.
    fn limit_of(&self, path: &str) -> usize {
        if path == UPLOAD_ROUTE {
            self.body_limit
        } else {
            self.json_body_limit
        }
    }

    /// The pool a body or answer of `bytes` takes from.
    fn pool(&self, bytes: usize) -> &Arc<Pool> {
        if bytes <= SMALL_REQUEST {
            &self.small
        } else {
            &self.large
        }
    }

    /// Bytes of the budget not held by a request now.
    pub fn available(&self) -> usize {
        (self.small.permits.available_permits() + self.large.permits.available_permits()) * 1024
    }
}

/// What a body holds of the budget, for the pace it must keep ([`BodyRate`]): put in the
/// request's extensions by [`upload_budget`].
#[derive(Clone, Debug)]
pub struct Pace {
    /// Bytes held for it.
    bytes: usize,
    pool: Arc<Pool>,
}

/// Middleware: hold the request's share of the budget until its answer is ready, then the
/// answer's own share until it is written (`hold_answer`).
pub async fn upload_budget(
    State(budget): State<Arc<UploadBudget>>,
    request: Request,
    next: Next,
) -> Response {
    let watch = request.extensions().get::<AnswerWatch>().cloned();
    let response = if matches!(*request.method(), Method::GET | Method::HEAD | Method::OPTIONS) {
        next.run(request).await
    } else {
        match hold_request(&budget, request, next).await {
            Ok(response) | Err(response) => response,
        }
    };
    hold_answer(&budget, response, watch).await
}

/// Serve `request` holding permits for its announced length (its route's limit when it
/// announces none); `Err` when it is refused, over the limit, or the budget is closed.
async fn hold_request(
    budget: &UploadBudget,
    mut request: Request,
    next: Next,
) -> Result<Response, Response> {
    let announced = request
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|l| l.to_str().ok()?.parse::<usize>().ok());
    let limit = budget.limit_of(request.uri().path());
    if let Some(bytes) = announced.filter(|&bytes| bytes > limit) {
        return Err(ApiError::Rejected(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!("the body announces {bytes} bytes; this route takes at most {limit}"),
        )
        .into_response());
    }
    let bytes = announced.unwrap_or(limit);
    let pool = budget.pool(bytes);
    let kib = pool.kib(bytes);
    let held = pool.take(kib).await.map_err(IntoResponse::into_response)?;
    request.extensions_mut().insert(Pace { bytes, pool: pool.clone() });
    let response = next.run(request).await;
    drop(held);
    if kib >= RELEASE_AFTER_KIB {
        release_memory();
    }
    Ok(response)
}

fn closed() -> ApiError {
    ApiError::Internal("the memory budget is closed".into())
}

/// Answers from this size on are counted in the budget until written; smaller ones go
/// into the socket's buffers at once.
const COUNTED_ANSWER: usize = 64 * 1024;

/// Permits a handler took for the answer it is about to build ([`UploadBudget::reserve`]),
/// put in the answer's extensions: `hold_answer` keeps them, resized to the answer's
/// length, until the answer is written.
#[derive(Clone)]
pub struct Reserved(Arc<Mutex<Option<Hold>>>);

/// Permits held, and the pool they are of.
type Hold = (OwnedSemaphorePermit, Arc<Pool>);

impl Reserved {
    fn take(&self) -> Option<Hold> {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).take()
    }
}

impl UploadBudget {
    /// Take `bytes` of the budget for the answer a JSON route is about to build, waiting
    /// until they are free: an answer whose size is known beforehand (an interpolation's)
    /// is then never built while the budget is spent. At most its pool less the largest
    /// JSON body of that pool is taken, which the request may hold itself while it waits.
    pub async fn reserve(&self, bytes: usize) -> Result<Reserved, ApiError> {
        let pool = self.pool(bytes);
        let body = pool.kib(self.json_body_limit.min(if bytes <= SMALL_REQUEST {
            SMALL_REQUEST
        } else {
            usize::MAX
        }));
        let most = pool.total_kib.saturating_sub(body).max(1);
        let permits = pool.take(pool.kib(bytes).min(most)).await?;
        Ok(Reserved(Arc::new(Mutex::new(Some((permits, pool.clone()))))))
    }
}

/// Which pool a connection's answer holds while it is written, if any: shared by the
/// answer's body (`Held`) and the connection's socket, which drops a stalled answer
/// early when others wait for that pool ([`AnswerWatch::crowded`]).
#[derive(Clone, Debug, Default)]
pub struct AnswerWatch(Arc<Mutex<Option<Arc<Pool>>>>);

impl AnswerWatch {
    fn set(&self, pool: Option<Arc<Pool>>) {
        *self.0.lock().unwrap_or_else(|e| e.into_inner()) = pool;
    }

    /// Whether the answer being written holds a pool that someone waits for.
    pub fn crowded(&self) -> bool {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).as_ref().is_some_and(|p| p.crowded())
    }
}

/// Hold the answer's length in the budget until its body is written (or the connection
/// is dropped, e.g. at the write time-out): with permits the handler reserved, resized to
/// the length, or with permits waited for now. Answers nobody reads thus hold at most the
/// budget, and further requests wait, instead of each keeping its answer in memory.
async fn hold_answer(
    budget: &UploadBudget,
    mut response: Response,
    watch: Option<AnswerWatch>,
) -> Response {
    let reserved = response.extensions_mut().remove::<Reserved>().and_then(|r| r.take());
    let Some(bytes) = response.body().size_hint().exact().and_then(|b| usize::try_from(b).ok())
    else {
        return match reserved {
            Some((permits, pool)) => {
                response.map(|body| axum::body::Body::new(Held::new(body, permits, pool, watch)))
            }
            None => response,
        };
    };
    if bytes < COUNTED_ANSWER && reserved.is_none() {
        return response;
    }
    let (permits, pool) = match reserved {
        Some((mut permits, pool)) => {
            let kib = pool.kib(bytes) as usize;
            if permits.num_permits() >= kib {
                drop(permits.split(permits.num_permits() - kib));
                (Ok(permits), pool)
            } else {
                let more = pool.take((kib - permits.num_permits()) as u32).await;
                (
                    more.map(|more| {
                        permits.merge(more);
                        permits
                    }),
                    pool,
                )
            }
        }
        None => {
            let pool = budget.pool(bytes).clone();
            (pool.take(pool.kib(bytes)).await, pool)
        }
    };
    match permits {
        Ok(permits) => {
            response.map(|body| axum::body::Body::new(Held::new(body, permits, pool, watch)))
        }
        Err(e) => e.into_response(),
    }
}

/// Slices an answer is handed to hyper in: hyper asks for the next one only once it has
/// written most of the last, so the body (and its permits) is dropped only when nearly all
/// of it is out.
const ANSWER_SLICE: usize = 64 * 1024;

/// An answer's body holding its share of the budget until it is dropped, and telling its
/// connection's socket so meanwhile ([`AnswerWatch`]).
struct Held {
    inner: axum::body::Body,
    /// The rest of a data frame larger than [`ANSWER_SLICE`].
    rest: axum::body::Bytes,
    permits: OwnedSemaphorePermit,
    watch: Option<AnswerWatch>,
}

impl Held {
    fn new(
        inner: axum::body::Body,
        permits: OwnedSemaphorePermit,
        pool: Arc<Pool>,
        watch: Option<AnswerWatch>,
    ) -> Held {
        if let Some(watch) = &watch {
            watch.set(Some(pool));
        }
        Held { inner, rest: axum::body::Bytes::new(), permits, watch }
    }

    /// The next slice of `rest`.
    fn slice(&mut self) -> hyper::body::Frame<axum::body::Bytes> {
        let k = ANSWER_SLICE.min(self.rest.len());
        hyper::body::Frame::data(self.rest.split_to(k))
    }
}

impl hyper::body::Body for Held {
    type Data = axum::body::Bytes;
    type Error = axum::Error;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<hyper::body::Frame<Self::Data>, Self::Error>>> {
        let this = &mut *self;
        if !this.rest.is_empty() {
            return Poll::Ready(Some(Ok(this.slice())));
        }
        match Pin::new(&mut this.inner).poll_frame(cx) {
            Poll::Ready(Some(Ok(frame))) => match frame.into_data() {
                Ok(data) => {
                    this.rest = data;
                    Poll::Ready(Some(Ok(this.slice())))
                }
                Err(frame) => Poll::Ready(Some(Ok(frame))),
            },
            other => other,
        }
    }

    fn is_end_stream(&self) -> bool {
        self.rest.is_empty() && self.inner.is_end_stream()
    }

    fn size_hint(&self) -> hyper::body::SizeHint {
        let (inner, rest) = (self.inner.size_hint(), self.rest.len() as u64);
        let mut hint = hyper::body::SizeHint::new();
        if let Some(upper) = inner.upper() {
            hint.set_upper(upper + rest);
        }
        hint.set_lower(inner.lower() + rest);
        hint
    }
}

impl Drop for Held {
    fn drop(&mut self) {
        if let Some(watch) = &self.watch {
            watch.set(None);
        }
        if self.permits.num_permits() >= RELEASE_AFTER_KIB as usize {
            release_memory();
        }
    }
}

/// Slowest average a request body may arrive at, after the grace: 16 KiB/s, so a 64 MiB
/// upload may take about an hour (as far as its request time-out allows), and a trickle of
/// a byte now and then is cut.
pub const MIN_BODY_RATE: u64 = 16 * 1024;

/// The grace of a body while the server is crowded (fewer than an eighth of the connection slots free) or its pool is
/// waited for, and how long an answer may go unread while its pool is waited for: trickled
/// bodies and unread answers that hold what others need are then cut within a second or
/// two, so new clients (a `/healthz`, a normal analysis) get in instead of waiting.
pub const CROWDED_GRACE: Duration = Duration::from_secs(1);

/// What the body rate is checked against: the grace of a body, the connection slots whose
/// crowding shortens it, and the request time-out that sets a body's pace.
#[derive(Clone)]
pub struct BodyRate {
    /// The grace while the server is not crowded (the header time-out).
    pub grace: Duration,
    /// The connection slots ([`super::Config::max_connections`] permits; a connection holds one).
    pub connections: Arc<Semaphore>,
    pub max_connections: usize,
    /// The request time-out: a body must come fast enough to finish within it.
    pub timeout: Duration,
}

impl BodyRate {
    /// Fewer than an eighth of the connection slots are free.
    fn crowded(&self) -> bool {
        self.connections.available_permits().saturating_mul(8) < self.max_connections
    }
}

/// A request body that fails once it falls behind its pace: by the grace after it started
/// plus the time its bytes so far were due at that pace. The pace is the body's held length
/// over the request time-out (a body slower than that could not be read in time anyway),
/// at least [`MIN_BODY_RATE`]. The grace is the one that applies when the body is checked
/// ([`CROWDED_GRACE`] while the server is crowded or the body's pool is waited for), and a
/// body behind is checked at least every [`CROWDED_GRACE`], so crowding that comes later
/// shortens it too.
struct MinRate {
    inner: axum::body::Body,
    check: Pin<Box<tokio::time::Sleep>>,
    started: tokio::time::Instant,
    rate: BodyRate,
    /// Bytes a second it must keep on average.
    pace: f64,
    /// The pool its budget comes from.
    pool: Option<Arc<Pool>>,
    received: u64,
}

impl MinRate {
    fn new(inner: axum::body::Body, rate: BodyRate, held: Option<Pace>) -> MinRate {
        let started = tokio::time::Instant::now();
        let timeout = rate.timeout.as_secs_f64().max(1.0);
        let pace =
            held.as_ref().map_or(0.0, |h| h.bytes as f64 / timeout).max(MIN_BODY_RATE as f64);
        let mut body = MinRate {
            inner,
            check: Box::pin(tokio::time::sleep_until(started)),
            started,
            rate,
            pace,
            pool: held.map(|h| h.pool),
            received: 0,
        };
        let first = body.next_check(started);
        body.check.as_mut().reset(first);
        body
    }

    /// The grace that applies now.
    fn grace(&self) -> Duration {
        if self.rate.crowded() || self.pool.as_ref().is_some_and(|p| p.crowded()) {
            CROWDED_GRACE.min(self.rate.grace)
        } else {
            self.rate.grace
        }
    }

    /// When the body must have arrived so far, with the grace that applies now.
    fn due(&self) -> tokio::time::Instant {
        self.started + self.grace() + Duration::from_secs_f64(self.received as f64 / self.pace)
    }

    /// When to check next, from `now`: at the due time, or sooner to notice crowding.
    fn next_check(&self, now: tokio::time::Instant) -> tokio::time::Instant {
        self.due().min(now + CROWDED_GRACE)
    }
}

impl hyper::body::Body for MinRate {
    type Data = axum::body::Bytes;
    type Error = axum::Error;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<hyper::body::Frame<Self::Data>, Self::Error>>> {
        let this = &mut *self;
        match Pin::new(&mut this.inner).poll_frame(cx) {
            Poll::Ready(Some(Ok(frame))) => {
                this.received += frame.data_ref().map_or(0, |d| d.len() as u64);
                let next = this.next_check(tokio::time::Instant::now());
                this.check.as_mut().reset(next);
                Poll::Ready(Some(Ok(frame)))
            }
            Poll::Pending => loop {
                if this.check.as_mut().poll(cx).is_pending() {
                    return Poll::Pending;
                }
                let now = tokio::time::Instant::now();
                if now >= this.due() {
                    let pace = this.pace as u64;
                    return Poll::Ready(Some(Err(axum::Error::new(BodyTooSlow(pace)))));
                }
                let next = this.next_check(now);
                this.check.as_mut().reset(next);
            },
            other => other,
        }
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> hyper::body::SizeHint {
        self.inner.size_hint()
    }
}

/// Middleware: read every request body through `MinRate`, at the pace of what it holds
/// of the budget ([`Pace`]).
pub async fn body_rate(State(rate): State<BodyRate>, request: Request, next: Next) -> Response {
    let held = request.extensions().get::<Pace>().cloned();
    let request = request.map(|body| axum::body::Body::new(MinRate::new(body, rate, held)));
    next.run(request).await
}

/// Requests and answers holding this much of the budget give their freed memory back when
/// done.
const RELEASE_AFTER_KIB: u32 = 16 * 1024;

/// Hand the heap pages freed by a large request or answer back to the OS. glibc keeps them
/// in its arenas otherwise: a burst of large uploads would stay resident as hundreds of MB.
fn release_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if let Ok(runtime) = tokio::runtime::Handle::try_current() {
        runtime.spawn_blocking(|| {
            // SAFETY: malloc_trim takes no pointer; it walks glibc's own arenas under their locks.
            unsafe { libc::malloc_trim(0) };
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn headers(pairs: &[(&'static str, &'static str)]) -> HeaderMap {
        pairs
            .iter()
            .map(|(k, v)| (header::HeaderName::from_static(k), header::HeaderValue::from_static(v)))
            .collect()
    }

    #[test]
    fn hosts_are_loopback_the_served_address_or_allowed() {
        let doors = Doors { hosts: vec!["Cloth.Lan".into()], origins: vec![] };
        let at = Some(ServedAt("192.168.1.5:8080".parse().unwrap()));
        for ok in [
            "localhost:8080",
            "127.0.0.1",
            "127.3.4.5:1",
            "[::1]:8080",
            "app.localhost",
            "cloth.lan:80",
            "192.168.1.5:8080",
        ] {
            assert!(doors.refuse(&Method::GET, &headers(&[("host", ok)]), at).is_none(), "{ok}");
        }
        for bad in [
            "evil.example",
            "evil.example:8080",
            "localhost.evil.example",
            "10.0.0.1",
            "192.168.1.5",
        ] {
            let why = doors.refuse(&Method::GET, &headers(&[("host", bad)]), None).expect(bad);
            assert!(why.contains("--allow-host"), "{why}");
        }
        // A server on every interface does not answer to every address by itself.
        let any = Some(ServedAt("0.0.0.0:8080".parse().unwrap()));
        assert!(doors.refuse(&Method::GET, &headers(&[("host", "0.0.0.0:8080")]), any).is_some());
    }

    #[test]
    fn state_changing_requests_need_our_origin() {
        let doors = Doors { hosts: vec![], origins: vec!["https://tool.example".into()] };
        let post =
            |h: &[(&'static str, &'static str)]| doors.refuse(&Method::POST, &headers(h), None);
        assert!(post(&[("host", "localhost:8080"), ("origin", "http://localhost:8080")]).is_none());
        assert!(post(&[("host", "localhost"), ("origin", "http://localhost:80")]).is_none());
        assert!(
            post(&[("host", "localhost:8080")]).is_none(),
            "no Origin: not a browser's cross-site request"
        );
        assert!(
            post(&[("host", "localhost:8080"), ("origin", "https://tool.example")]).is_none(),
            "--cors"
        );
        for evil in
            ["https://evil.example", "http://localhost:9999", "null", "https://localhost:8080"]
        {
            let mut h = headers(&[("host", "localhost:8080")]);
            h.insert(header::ORIGIN, evil.parse().unwrap());
            assert!(
                doors.refuse(&Method::POST, &h, None).is_some_and(|w| w.contains(evil)),
                "{evil}"
            );
        }
        assert!(post(&[("host", "localhost:8080"), ("sec-fetch-site", "cross-site")]).is_some());
        // Reading is not refused for the origin (CORS decides whether the page may see it).
        assert!(doors
            .refuse(
                &Method::GET,
                &headers(&[("host", "localhost"), ("origin", "https://evil.example")]),
                None
            )
            .is_none());
    }

    #[test]
    fn the_upload_budget_counts_kib_in_two_pools() {
        let b = UploadBudget::new(10 * 1024, 64 * 1024, 8 * 1024);
        assert_eq!((b.small.total_kib, b.large.total_kib, b.available()), (5, 5, 10 * 1024));
        assert_eq!((b.limit_of("/api/analyze"), b.limit_of("/api/plan")), (64 * 1024, 8 * 1024));
        let b = UploadBudget::new(256 << 20, 64 << 20, 8 << 20);
        assert_eq!((b.small.total_kib, b.large.total_kib), (32 << 10, 224 << 10));
        assert!(Arc::ptr_eq(b.pool(SMALL_REQUEST), &b.small));
        assert!(Arc::ptr_eq(b.pool(SMALL_REQUEST + 1), &b.large));
    }

    #[tokio::test]
    async fn a_pool_is_crowded_while_someone_waits_for_it() {
        let pool = Arc::new(Pool::new(4));
        let all = pool.take(4).await.unwrap();
        assert!(!pool.crowded());
        let waiter = tokio::spawn({
            let pool = pool.clone();
            async move { pool.take(1).await.map(drop) }
        });
        while !pool.crowded() {
            tokio::task::yield_now().await;
        }
        // A wait given up is no longer counted.
        waiter.abort();
        let _ = waiter.await;
        assert!(!pool.crowded());
        drop(all);
        assert_eq!(pool.permits.available_permits(), 4);
    }
}
