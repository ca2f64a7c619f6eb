//! The socket under hyper: a write time-out, and JSON bodies for hyper's own error answers.
//!
//! - **Write time-out**: a write (or flush) that makes no progress for
//!   [`super::Config::write_timeout`] fails, and hyper drops the connection with the answer
//!   it held. A client that asks and never reads cannot keep an answer in memory longer;
//!   while others wait for the budget the answer holds ([`AnswerWatch`]), not longer than
//!   [`CROWDED_GRACE`].
//! - **hyper's answers**: a request head that hyper cannot parse (a head over its buffer,
//!   431; a target over 65 534 bytes, 414; a bad method, target, version or header, such as
//!   two different `Content-Length` values, 400) is answered by hyper itself, before any
//!   service sees a request, with an empty body; hyper 1.x has no hook to change it. That
//!   answer is the only 4xx head without a `Content-Type` and with `content-length: 0` the
//!   server writes (every answer of the app carries its `{"error": …}` body), so it is
//!   recognised here, on its way out, and given the same JSON body as every other error.

use std::future::Future;
use std::io;
use std::pin::Pin;
use std::task::{ready, Context, Poll};
use std::time::Duration;

use axum::http::StatusCode;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::time::Instant;

use super::guard::{AnswerWatch, CROWDED_GRACE};

/// The largest request head hyper reads, in bytes (its read buffer, hyper's default size):
/// a longer head is 431. It holds a target of hyper's longest, so that one is 414.
pub const MAX_HEAD: usize = 8192 + 4096 * 100;
/// The most header lines of a request: more are 431.
pub const MAX_HEADERS: usize = 100;
/// The longest request target hyper takes (its own limit): a longer one is 414.
const MAX_TARGET: usize = u16::MAX as usize - 1;

/// A connection's stream with a write time-out and hyper's error answers made JSON.
pub struct Socket<S> {
    inner: S,
    write_timeout: Duration,
    /// Whether the answer being written holds budget others wait for.
    watch: AnswerWatch,
    /// Since when writes are stuck, and the next time to check; `None` while they progress.
    stalled: Option<(Instant, Pin<Box<tokio::time::Sleep>>)>,
    /// A rewritten error answer not yet all written, and how much of it was.
    pending: Vec<u8>,
    sent: usize,
}

impl<S> Socket<S> {
    pub fn new(inner: S, write_timeout: Duration, watch: AnswerWatch) -> Socket<S> {
        Socket { inner, write_timeout, watch, stalled: None, pending: Vec::new(), sent: 0 }
    }

    /// How long writes may stall now: the write time-out, or [`CROWDED_GRACE`] while the
    /// answer holds budget others wait for.
    fn stall_limit(&self) -> Duration {
        if self.watch.crowded() {
            CROWDED_GRACE.min(self.write_timeout)
        } else {
            self.write_timeout
        }
    }

    /// `poll` (a write or a flush), failing once it has not progressed for the stall limit
    /// (checked at least every [`CROWDED_GRACE`], so crowding that comes later counts).
    fn timed<T>(
        &mut self,
        cx: &mut Context<'_>,
        poll: impl FnOnce(Pin<&mut S>, &mut Context<'_>) -> Poll<io::Result<T>>,
    ) -> Poll<io::Result<T>>
    where
        S: Unpin,
    {
        match poll(Pin::new(&mut self.inner), cx) {
            Poll::Pending => loop {
                let limit = self.stall_limit();
                let now = Instant::now();
                let (since, check) = self.stalled.get_or_insert_with(|| {
                    (now, Box::pin(tokio::time::sleep_until(now + limit.min(CROWDED_GRACE))))
                });
                if check.as_mut().poll(cx).is_pending() {
                    return Poll::Pending;
                }
                if now >= *since + limit {
                    let stalled = now - *since;
                    return Poll::Ready(Err(io::Error::new(
                        io::ErrorKind::TimedOut,
                        format!("the client read nothing of its answer for {stalled:?}"),
                    )));
                }
                let next = (*since + limit).min(now + CROWDED_GRACE);
                check.as_mut().reset(next);
            },
            ready => {
                self.stalled = None;
                ready
            }
        }
    }

    /// Write what is left of a rewritten error answer.
    fn poll_pending(&mut self, cx: &mut Context<'_>) -> Poll<io::Result<()>>
    where
        S: AsyncWrite + Unpin,
    {
        while self.sent < self.pending.len() {
            let (pending, sent) = (std::mem::take(&mut self.pending), self.sent);
            let wrote = self.timed(cx, |inner, cx| inner.poll_write(cx, &pending[sent..]));
            self.pending = pending;
            match ready!(wrote)? {
                0 => return Poll::Ready(Err(io::ErrorKind::WriteZero.into())),
                k => self.sent += k,
            }
        }
        Poll::Ready(Ok(()))
    }

    /// Take `buf` as written when it is hyper's empty error answer: its JSON version is
    /// sent instead.
    fn rewrite(&mut self, buf: &[u8]) -> bool {
        match json_answer(buf) {
            Some(answer) => {
                (self.pending, self.sent) = (answer, 0);
                true
            }
            None => false,
        }
    }
}

/// The message of hyper's answer `status` to a head it could not parse.
fn message(status: StatusCode) -> String {
    match status {
        StatusCode::URI_TOO_LONG => format!("the request target is too long: at most {MAX_TARGET} bytes"),
        StatusCode::REQUEST_HEADER_FIELDS_TOO_LARGE => {
            format!("the request head is too large: at most {MAX_HEAD} bytes and {MAX_HEADERS} headers")
        }
        StatusCode::BAD_REQUEST => {
            "the request head cannot be read: a bad method, target, version or header (e.g. two different Content-Length values)".into()
        }
        other => other.canonical_reason().unwrap_or("the request cannot be read").to_lowercase(),
    }
}

/// The JSON answer that replaces `buf` when `buf` is exactly hyper's head of a 4xx answer
/// without a content type or a body; `None` for anything else.
fn json_answer(buf: &[u8]) -> Option<Vec<u8>> {
    let head = std::str::from_utf8(buf.strip_suffix(b"\r\n\r\n")?).ok()?;
    let mut lines = head.split("\r\n");
    let status_line = lines.next()?;
    let code = status_line
        .strip_prefix("HTTP/1.1 ")
        .or_else(|| status_line.strip_prefix("HTTP/1.0 "))?
        .get(..3)?;
    let status =
        StatusCode::from_bytes(code.as_bytes()).ok().filter(StatusCode::is_client_error)?;
    let headers: Vec<&str> = lines.collect();
    let named = |name: &str| {
        headers
            .iter()
            .any(|h| h.split(':').next().is_some_and(|n| n.trim().eq_ignore_ascii_case(name)))
    };
    let empty = headers.iter().any(|h| {
        h.split_once(':').is_some_and(|(n, v)| {
            n.trim().eq_ignore_ascii_case("content-length") && v.trim() == "0"
        })
    });
    if !empty || named("content-type") {
        return None;
    }
    let body = serde_json::to_string(&crate::answer::ErrorBody { error: message(status) })
        .unwrap_or_default();
    let kept = headers.iter().filter(|h| {
        !h.split(':').next().is_some_and(|n| n.trim().eq_ignore_ascii_case("content-length"))
    });
    let mut answer = format!("{status_line}\r\n");
    for h in kept {
        answer.push_str(h);
        answer.push_str("\r\n");
    }
    answer.push_str(&format!(
        "content-type: application/json\r\ncontent-length: {}\r\n\r\n{body}",
        body.len()
    ));
    Some(answer.into_bytes())
}

impl<S: AsyncRead + Unpin> AsyncRead for Socket<S> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<io::Result<()>> {
        Pin::new(&mut self.inner).poll_read(cx, buf)
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for Socket<S> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<io::Result<usize>> {
        ready!(self.poll_pending(cx))?;
        if self.rewrite(buf) {
            // Sent by the next flush at the latest.
            return match self.poll_pending(cx) {
                Poll::Ready(Err(e)) => Poll::Ready(Err(e)),
                _ => Poll::Ready(Ok(buf.len())),
            };
        }
        self.timed(cx, |inner, cx| inner.poll_write(cx, buf))
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[io::IoSlice<'_>],
    ) -> Poll<io::Result<usize>> {
        ready!(self.poll_pending(cx))?;
        // hyper's error answer is a head alone: one buffer.
        if let Some(first) = bufs.iter().find(|b| !b.is_empty()) {
            if self.rewrite(first) {
                return match self.poll_pending(cx) {
                    Poll::Ready(Err(e)) => Poll::Ready(Err(e)),
                    _ => Poll::Ready(Ok(first.len())),
                };
            }
        }
        self.timed(cx, |inner, cx| inner.poll_write_vectored(cx, bufs))
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        ready!(self.poll_pending(cx))?;
        self.timed(cx, |inner, cx| inner.poll_flush(cx))
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        ready!(self.poll_pending(cx))?;
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_an_empty_4xx_head_without_a_type_is_rewritten() {
        let hyper = b"HTTP/1.1 431 Request Header Fields Too Large\r\ncontent-length: 0\r\ndate: Wed, 02 Dec 2026 07:00:00 GMT\r\n\r\n";
        let answer = String::from_utf8(json_answer(hyper).expect("rewritten")).unwrap();
        let (head, body) = answer.split_once("\r\n\r\n").unwrap();
        assert!(head.starts_with("HTTP/1.1 431 Request Header Fields Too Large\r\n"), "{head}");
        assert!(
            head.contains("date: Wed") && head.contains("content-type: application/json"),
            "{head}"
        );
        assert!(head.contains(&format!("content-length: {}", body.len())), "{head}");
        let json: serde_json::Value = serde_json::from_str(body).unwrap();
        assert!(json["error"].as_str().unwrap().contains("head is too large"));
        for kept in [
            &b"HTTP/1.1 200 OK\r\ncontent-length: 0\r\n\r\n"[..],
            b"HTTP/1.1 404 Not Found\r\ncontent-type: application/json\r\ncontent-length: 0\r\n\r\n",
            b"HTTP/1.1 400 Bad Request\r\ncontent-length: 12\r\n\r\n",
            b"HTTP/1.1 400 Bad Request\r\ncontent-length: 0\r\n\r\nmore",
            b"HTTP/1.1 400 Bad Request\r\ncontent-length: 0\r\n",
        ] {
            assert!(json_answer(kept).is_none(), "{}", String::from_utf8_lossy(kept));
        }
    }
}
