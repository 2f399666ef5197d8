//! The lab's HTTP server: the page, and one JSON endpoint per update.
//!
//! | request | answer |
//! |---|---|
//! | `GET /` | the page ([`super::page`]) |
//! | `GET /api/info` | `{"exec": true}` when a student's program is attached |
//! | `POST /api/draw` | a [`super::LabRequest`] in, a [`super::LabResponse`] out; 400 with `{"error": ...}` for a bad request |
//! | anything else | 404 |
//!
//! Requests are served one at a time on the calling thread, so the work
//! in flight is one bounded update.

use super::{answer, LabRequest, MAX_REQUEST_BYTES};
use crate::check::Program;
use crate::error::{Error, Result};
use std::io::Read;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;
use tiny_http::{Header, Method, Request, Response, Server};

/// The lab's server, listening on 127.0.0.1 only.
pub struct LabServer {
    server: Server,
    port: u16,
}

impl LabServer {
    /// Listens on 127.0.0.1:`port` (0: any free port).
    pub fn bind(port: u16) -> Result<LabServer> {
        let server = Server::http(("127.0.0.1", port)).map_err(|e| {
            Error::InvalidArgument(format!("cannot listen on 127.0.0.1:{port}: {e}"))
        })?;
        let port = server.server_addr().to_ip().map_or(port, |a| a.port());
        Ok(LabServer { server, port })
    }

    /// The port it listens on.
    pub fn port(&self) -> u16 {
        self.port
    }

    /// Serves until `stop` is set (checked a few times a second), with
    /// `program` (a student's rasterizer) overlaid when given.
    pub fn serve(&self, mut program: Option<Program>, stop: &AtomicBool) {
        while !stop.load(Ordering::Relaxed) {
            match self.server.recv_timeout(Duration::from_millis(200)) {
                Ok(Some(request)) => handle(request, program.as_mut()),
                Ok(None) => {}
                Err(_) => break,
            }
        }
    }
}

fn header(value: &str) -> Header {
    Header::from_bytes(&b"Content-Type"[..], value.as_bytes()).expect("a valid header")
}

fn json(status: u16, body: String) -> Response<std::io::Cursor<Vec<u8>>> {
    Response::from_string(body)
        .with_status_code(status)
        .with_header(header("application/json"))
}

fn error(status: u16, message: &str) -> Response<std::io::Cursor<Vec<u8>>> {
    json(status, serde_json::json!({ "error": message }).to_string())
}

/// Answers one request; a client that went away is not an error.
fn handle(mut request: Request, program: Option<&mut Program>) {
    let response = match (request.method(), request.url()) {
        (Method::Get, "/") | (Method::Get, "/index.html") => {
            Response::from_string(super::page()).with_header(header("text/html; charset=utf-8"))
        }
        (Method::Get, "/api/info") => json(
            200,
            serde_json::json!({ "exec": program.is_some() }).to_string(),
        ),
        (Method::Post, "/api/draw") => {
            let mut body = String::new();
            let read = request
                .as_reader()
                .take(MAX_REQUEST_BYTES as u64 + 1)
                .read_to_string(&mut body);
            match read {
                Err(_) => error(400, "the request body is not UTF-8 text"),
                Ok(_) if body.len() > MAX_REQUEST_BYTES => error(
                    413,
                    &format!("the request is larger than {MAX_REQUEST_BYTES} bytes"),
                ),
                Ok(_) => match LabRequest::parse(&body).and_then(|r| answer(&r, program)) {
                    Ok(answer) => json(200, serde_json::to_string(&answer).unwrap_or_default()),
                    Err(e) => error(400, &e.to_string()),
                },
            }
        }
        (_, "/api/draw") => error(405, "use POST"),
        _ => error(404, "no such page"),
    };
    let _ = request.respond(response);
}
