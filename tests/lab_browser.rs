//! The lab in a real browser: `rasterlab lab` is started, headless
//! Chromium opens its page, and the test drives it through the DevTools
//! protocol as a student would, with the mouse: it drags a vertex and
//! checks that the grid, the trace and the URL follow, hovers a pixel and
//! checks that the trace highlights its lines. The server's answers to bad
//! requests (4xx, never a panic) are checked over plain HTTP.
//!
//! Chromium is found as for the report's browser test; without one this
//! test passes with a message unless `RASTERLAB_REQUIRE_BROWSER` is set.

mod common;

use common::{chromium, HEADLESS};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running `rasterlab lab`, stopped when dropped.
struct Lab {
    child: Child,
    address: String,
}

impl Lab {
    fn start() -> Lab {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(["lab", "--port", "0"])
            .stdout(Stdio::piped())
            .spawn()
            .expect("the lab starts");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .expect("the lab prints its address");
        let address = url
            .trim_start_matches("http://")
            .trim_end_matches('/')
            .to_string();
        assert!(
            address.starts_with("127.0.0.1:"),
            "the lab binds the loopback address only: {line}"
        );
        Lab { child, address }
    }

    /// A raw HTTP request; returns the status code and body.
    fn http(&self, method: &str, path: &str, body: &[u8]) -> (u16, String) {
        let mut stream = TcpStream::connect(&self.address).unwrap();
        write!(
            stream,
            "{method} {path} HTTP/1.1\r\nHost: {}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
            self.address,
            body.len()
        )
        .unwrap();
        stream.write_all(body).unwrap();
        let mut text = String::new();
        stream.read_to_string(&mut text).unwrap();
        let status = text
            .split_whitespace()
            .nth(1)
            .and_then(|s| s.parse().ok())
            .unwrap_or(0);
        let body = text
            .split_once("\r\n\r\n")
            .map(|(_, b)| b.to_string())
            .unwrap_or_default();
        (status, body)
    }
}

impl Drop for Lab {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

#[test]
fn bad_requests_get_4xx_answers_with_a_message() {
    let lab = Lab::start();
    let (status, page) = lab.http("GET", "/", b"");
    assert_eq!(status, 200);
    assert!(page.contains("<title>rasterlab lab</title>"));
    // The page loads nothing from elsewhere (the SVG namespace is a name,
    // not a fetch).
    for outside in [
        "src=\"http",
        "href=\"http",
        "fetch(\"http",
        "url(http",
        "import ",
    ] {
        assert!(!page.contains(outside), "the page fetches `{outside}`");
    }
    let good = br#"{"width":8,"height":8,"kind":"triangles","triangles":[[[0.5,0.5],[6.5,1.5],[2.5,6.5]]],"backends":["bbox","scanline"]}"#;
    let (status, body) = lab.http("POST", "/api/draw", good);
    assert_eq!(status, 200, "{body}");
    let v: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["backends"][0]["fragments"], v["backends"][1]["fragments"]);
    let many = format!(
        r#"{{"width":8,"height":8,"kind":"triangles","triangles":[{}]}}"#,
        vec!["[[0,0],[1,0],[0,1]]"; 1000].join(",")
    );
    let long = vec![b' '; 70_000];
    for (body, status, message) in [
        (&b"{not json"[..], 400, "malformed request"),
        (
            br#"{"width":100000,"height":8,"kind":"triangles"}"#,
            400,
            "each side must be 1 to 128",
        ),
        (
            br#"{"width":8,"height":8,"kind":"triangles","triangles":[[[NaN,0],[1,0],[0,1]]]}"#,
            400,
            "malformed",
        ),
        (
            br#"{"width":8,"height":8,"kind":"triangles","triangles":[[[1e300,0],[1,0],[0,1]]]}"#,
            400,
            "not a finite number within",
        ),
        (many.as_bytes(), 400, "at most 16"),
        (
            br#"{"width":8,"height":8,"kind":"triangles","backends":["nope"]}"#,
            400,
            "unknown",
        ),
        (
            br#"{"width":8,"height":8,"kind":"triangles","depths":[2]}"#,
            400,
            "one depth per triangle",
        ),
        (&long[..], 413, "larger than"),
    ] {
        let (got, text) = lab.http("POST", "/api/draw", body);
        assert_eq!(got, status, "{text}");
        let v: Value = serde_json::from_str(&text).unwrap();
        assert!(v["error"].as_str().unwrap().contains(message), "{text}");
    }
    assert_eq!(lab.http("GET", "/api/draw", b"").0, 405);
    assert_eq!(lab.http("GET", "/etc/passwd", b"").0, 404);
    // Still serving after all that.
    assert_eq!(lab.http("POST", "/api/draw", good).0, 200);
}

/// A child process killed when dropped, so a failing test leaves no
/// browser behind.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A DevTools protocol session on one page.
struct DevTools {
    socket: tungstenite::WebSocket<tungstenite::stream::MaybeTlsStream<TcpStream>>,
    session: String,
    next_id: u64,
}

impl DevTools {
    fn call(&mut self, method: &str, params: Value, session: bool) -> Value {
        self.next_id += 1;
        let mut message = json!({ "id": self.next_id, "method": method, "params": params });
        if session {
            message["sessionId"] = json!(self.session);
        }
        self.socket
            .send(tungstenite::Message::Text(message.to_string().into()))
            .unwrap();
        loop {
            let reply = self.socket.read().unwrap();
            let Ok(text) = reply.to_text() else { continue };
            let v: Value = serde_json::from_str(text).unwrap_or(Value::Null);
            if v["id"] == json!(self.next_id) {
                assert!(v.get("error").is_none(), "{method}: {v}");
                return v["result"].clone();
            }
        }
    }

    /// Opens `url` in a new page, attaches this session to it, and waits
    /// for the lab's first update to draw fragments.
    fn open(&mut self, url: &str) {
        let target = self.call("Target.createTarget", json!({ "url": url }), false);
        let attached = self.call(
            "Target.attachToTarget",
            json!({ "targetId": target["targetId"], "flatten": true }),
            false,
        );
        self.session = attached["sessionId"].as_str().unwrap().to_string();
        self.wait_for("Number(document.body.dataset.updates || 0) >= 1 && document.querySelectorAll('#grid rect.fragment').length > 0");
    }

    fn eval(&mut self, expression: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "returnByValue": true }),
            true,
        );
        r["result"]["value"].clone()
    }

    /// Waits until `expression` is true, for up to ten seconds.
    fn wait_for(&mut self, expression: &str) {
        let start = Instant::now();
        while self.eval(expression) != json!(true) {
            assert!(
                start.elapsed() < Duration::from_secs(10),
                "timed out waiting for {expression}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn mouse(&mut self, kind: &str, x: f64, y: f64, buttons: u32) {
        self.call(
            "Input.dispatchMouseEvent",
            json!({ "type": kind, "x": x, "y": y, "button": if buttons > 0 || kind != "mouseMoved" { "left" } else { "none" }, "buttons": buttons, "clickCount": 1 }),
            true,
        );
    }
}

#[test]
fn a_dragged_vertex_updates_the_grid_the_trace_and_the_url() {
    let Some(browser) = chromium() else {
        common::part_missing(
            "the lab's browser test",
            "chromium (Debian's package `chromium`)",
            "RASTERLAB_REQUIRE_BROWSER",
        );
        return;
    };
    let lab = Lab::start();
    let profile =
        std::env::temp_dir().join(format!("rasterlab-lab-chromium-{}", std::process::id()));
    let mut chrome = Killed(
        Command::new(browser)
            .args(HEADLESS)
            .args(["--remote-debugging-port=0", "--window-size=1400,1000"])
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("chromium starts"),
    );
    let mut lines = BufReader::new(chrome.0.stderr.take().unwrap()).lines();
    let ws = loop {
        let line = lines
            .next()
            .expect("chromium prints its DevTools address")
            .unwrap();
        if let Some(at) = line.find("ws://") {
            break line[at..].trim().to_string();
        }
    };
    // Keep reading Chromium's messages so it never blocks on a full pipe.
    std::thread::spawn(move || for _ in lines {});
    let (socket, _) = tungstenite::connect(ws.as_str()).expect("DevTools connects");
    let mut dev = DevTools {
        socket,
        session: String::new(),
        next_id: 0,
    };
    dev.open(&format!("http://{}/", lab.address));

    let fragments = |dev: &mut DevTools| {
        dev.eval("document.querySelectorAll('#grid rect.fragment').length")
            .as_u64()
            .unwrap()
    };
    let before = fragments(&mut dev);
    let first_line = "document.getElementById('trace').firstChild.textContent";
    let trace_before = dev.eval(first_line).as_str().unwrap().to_string();
    assert!(
        trace_before.starts_with("scanline, top-left rule"),
        "{trace_before}"
    );
    let smalls = dev
        .eval("document.querySelectorAll('#side svg.small').length")
        .as_u64()
        .unwrap();
    assert_eq!(
        smalls,
        rasterlab::triangle_backends().len() as u64,
        "every triangle back-end side by side"
    );
    let same = dev.eval(
        "[...document.querySelectorAll('#side svg.small')].map(s => s.querySelectorAll('rect.fragment').length).every((n, _, a) => n === a[0])",
    );
    assert_eq!(same, json!(true), "every back-end draws the same fragments");

    // Drag the triangle's third vertex four cells left and up.
    let handle = dev.eval(
        "(() => { const r = document.querySelectorAll('.handle')[2].getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2, +document.getElementById('grid').dataset.cell]; })()",
    );
    let (x, y, cell) = (
        handle[0].as_f64().unwrap(),
        handle[1].as_f64().unwrap(),
        handle[2].as_f64().unwrap(),
    );
    let updates = dev
        .eval("Number(document.body.dataset.updates)")
        .as_u64()
        .unwrap();
    dev.mouse("mousePressed", x, y, 1);
    for step in 1..=4 {
        let t = f64::from(step) / 4.0;
        dev.mouse("mouseMoved", x + t * 4.0 * cell, y - t * 4.0 * cell, 1);
    }
    dev.mouse("mouseReleased", x + 4.0 * cell, y - 4.0 * cell, 0);
    // Several moves may each have sent a request: wait for the page to
    // settle on the answer to the last one.
    dev.wait_for(&format!(
        "Number(document.body.dataset.updates) > {updates} && document.body.dataset.busy === '0' && document.getElementById('trace').firstChild.textContent !== {}",
        json!(trace_before)
    ));
    dev.wait_for("document.querySelectorAll('#grid rect.fragment').length > 0");
    let after = fragments(&mut dev);
    assert_ne!(before, after, "the grid follows the drag");
    let trace_after = dev.eval(first_line).as_str().unwrap().to_string();
    assert_ne!(trace_before, trace_after);
    let hash = dev
        .eval("decodeURIComponent(location.hash)")
        .as_str()
        .unwrap()
        .to_string();
    let state: Value = serde_json::from_str(hash.trim_start_matches('#')).unwrap();
    let moved = &state["triangles"][0][2];
    assert_ne!(
        moved,
        &json!([4.25, 13.5]),
        "the URL holds the new vertex: {hash}"
    );
    assert_eq!(
        dev.eval("document.getElementById('error').textContent"),
        json!("")
    );

    // Hovering a pixel of the triangle highlights its row in the trace.
    let cell_of = |dev: &mut DevTools| {
        dev.eval("(() => { const f = document.querySelector('#grid rect.fragment'); const r = f.getBoundingClientRect(); return [r.x + r.width / 2, r.y + r.height / 2]; })()")
    };
    let p = cell_of(&mut dev);
    dev.mouse(
        "mouseMoved",
        p[0].as_f64().unwrap(),
        p[1].as_f64().unwrap(),
        0,
    );
    dev.wait_for("document.querySelectorAll('#trace .hl').length > 0");

    // A shared link restores the same state in a fresh page.
    let shared = dev.eval("location.href").as_str().unwrap().to_string();
    dev.open(&shared);
    assert_eq!(
        fragments(&mut dev),
        after,
        "the link restores the dragged triangle"
    );
    assert_eq!(dev.eval(first_line).as_str().unwrap(), trace_after);

    let _ = dev.call("Browser.close", json!({}), false);
    let _ = chrome.0.wait();
    let _ = std::fs::remove_dir_all(&profile);
}
