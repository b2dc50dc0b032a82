//! The HTTP side: one thread taking requests from `tiny_http` in turn and routing them to the
//! page, the images, the scene text and the JSON handlers of [`crate::api`]. Bodies over
//! [`MAX_BODY`] bytes, unknown paths and wrong methods are refused with one line, and so are
//! edits posted by pages of other sites (`Origin` not the `Host`); nothing a request sends can
//! stop the server or the render.
use crate::api::{self, Refusal};
use crate::encode;
use crate::state::Shared;
use std::io::Read;
use std::sync::atomic::Ordering;
use std::sync::Arc;
use tiny_http::{Header, Method, Request, Response, Server};

/// The largest request body accepted (bytes).
pub const MAX_BODY: usize = 64 * 1024;

/// The page, with its script and style.
const PAGE: &str = include_str!("page.html");

/// A response: status, content type, bytes.
struct Reply {
    status: u16,
    content_type: &'static str,
    body: Vec<u8>,
    extra: Vec<(&'static str, String)>,
}

impl Reply {
    fn ok(content_type: &'static str, body: Vec<u8>) -> Reply {
        Reply {
            status: 200,
            content_type,
            body,
            extra: Vec::new(),
        }
    }
    fn json(v: serde_json::Value) -> Reply {
        Reply::ok("application/json", v.to_string().into_bytes())
    }
    fn refused((status, msg): Refusal) -> Reply {
        let mut body = msg.replace('\n', " ");
        body.push('\n');
        Reply {
            status,
            content_type: "text/plain; charset=utf-8",
            body: body.into_bytes(),
            extra: Vec::new(),
        }
    }
}

/// Serves until shutdown.
pub fn run(server: Arc<Server>, shared: Arc<Shared>) {
    while !shared.shutdown.load(Ordering::SeqCst) {
        let mut req = match server.recv() {
            Ok(r) => r,
            Err(_) => break, // unblocked (shutdown) or the socket failed
        };
        let reply = match cross_origin(&req).map_or_else(|| read_body(&mut req), Err) {
            Ok(body) => route(&shared, req.method(), req.url(), &body),
            Err(r) => Reply::refused(r),
        };
        let mut resp = Response::from_data(reply.body).with_status_code(reply.status);
        let mut headers = vec![
            ("Content-Type", reply.content_type.to_string()),
            ("Cache-Control", "no-store".to_string()),
        ];
        headers.extend(reply.extra);
        for (k, v) in headers {
            if let Ok(h) = Header::from_bytes(k.as_bytes(), v.as_bytes()) {
                resp.add_header(h);
            }
        }
        let _ = req.respond(resp); // a client that went away is its own business
    }
}

/// A POST sent by a page of another site (its `Origin` names another host than the request's
/// `Host`): browsers send those without asking, so they are refused here.
fn cross_origin(req: &Request) -> Option<Refusal> {
    if *req.method() != Method::Post {
        return None;
    }
    let header = |name: &'static str| {
        req.headers()
            .iter()
            .find(|h| h.field.equiv(name))
            .map(|h| h.value.as_str().to_string())
    };
    let origin = header("Origin")?;
    let host = header("Host").unwrap_or_default();
    let origin_host = origin.split_once("://").map_or(origin.as_str(), |(_, h)| h);
    (origin_host != host).then(|| (403, format!("cross-origin request from {origin} refused")))
}

fn read_body(req: &mut Request) -> Result<String, Refusal> {
    if req.body_length().is_some_and(|n| n > MAX_BODY) {
        return Err((400, format!("request body over {MAX_BODY} bytes")));
    }
    let mut buf = Vec::new();
    req.as_reader()
        .take(MAX_BODY as u64 + 1)
        .read_to_end(&mut buf)
        .map_err(|e| (400, format!("cannot read the request body: {e}")))?;
    if buf.len() > MAX_BODY {
        return Err((400, format!("request body over {MAX_BODY} bytes")));
    }
    String::from_utf8(buf).map_err(|_| (400, "the request body is not UTF-8".to_string()))
}

fn route(shared: &Shared, method: &Method, url: &str, body: &str) -> Reply {
    let (path, query) = url.split_once('?').unwrap_or((url, ""));
    let get = *method == Method::Get || *method == Method::Head;
    let post = *method == Method::Post;
    let result = match path {
        "/" | "/index.html" if get => Ok(Reply::ok("text/html; charset=utf-8", PAGE.into())),
        "/api/state" if get => Ok(Reply::json(api::state(shared))),
        "/api/image.png" if get => image_png(shared, query),
        "/api/image.exr" if get => image_exr(shared),
        "/api/scene.xml" if get => {
            let text = shared.lock().text.clone();
            Ok(Reply::ok(
                "application/xml; charset=utf-8",
                text.into_bytes(),
            ))
        }
        "/api/camera" if post => api::camera(shared, body).map(Reply::json),
        "/api/material" if post => api::material(shared, body).map(Reply::json),
        "/api/integrator" if post => api::integrator(shared, body).map(Reply::json),
        "/" | "/index.html" | "/api/state" | "/api/image.png" | "/api/image.exr"
        | "/api/scene.xml" => Err((400, format!("{path} takes GET, not {method}"))),
        "/api/camera" | "/api/material" | "/api/integrator" => {
            Err((400, format!("{path} takes POST, not {method}")))
        }
        _ => Err((404, format!("no such path: {path}"))),
    };
    result.unwrap_or_else(Reply::refused)
}

/// The query parameter `name`, if given.
fn query_param<'a>(query: &'a str, name: &str) -> Option<&'a str> {
    query
        .split('&')
        .filter_map(|kv| kv.split_once('='))
        .find(|(k, _)| *k == name)
        .map(|(_, v)| v)
}

fn frame_headers(frame: &crate::state::Frame) -> Vec<(&'static str, String)> {
    vec![
        ("X-Tessera-Spp", frame.spp.to_string()),
        ("X-Tessera-Generation", frame.generation.to_string()),
        ("X-Tessera-Preview", frame.preview.to_string()),
    ]
}

fn current_frame(shared: &Shared) -> Result<Arc<crate::state::Frame>, Refusal> {
    let inner = shared.lock();
    inner
        .frame
        .clone()
        .ok_or((404, "no frame yet: the first pass is rendering".to_string()))
}

fn image_png(shared: &Shared, query: &str) -> Result<Reply, Refusal> {
    let exposure = match query_param(query, "exposure") {
        None => 0.0,
        Some(s) => s
            .parse::<f64>()
            .ok()
            .filter(|e| e.is_finite() && e.abs() <= encode::EXPOSURE_RANGE)
            .ok_or_else(|| {
                (
                    400,
                    format!(
                        "exposure must be a number of stops in [-{0}, {0}], found \"{s}\"",
                        encode::EXPOSURE_RANGE
                    ),
                )
            })?,
    };
    let frame = current_frame(shared)?;
    let png = encode::png(&frame, exposure).map_err(|e| (500, e))?;
    let mut r = Reply::ok("image/png", png);
    r.extra = frame_headers(&frame);
    Ok(r)
}

fn image_exr(shared: &Shared) -> Result<Reply, Refusal> {
    let frame = current_frame(shared)?;
    let exr = encode::exr(&frame).map_err(|e| (500, e))?;
    let mut r = Reply::ok("image/x-exr", exr);
    r.extra = frame_headers(&frame);
    Ok(r)
}
