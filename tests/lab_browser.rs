//! The lab in a real browser: `rasterlab lab` is started, headless
//! Chromium opens its page, and the test drives it through the DevTools
//! protocol as a student would, with the mouse: it drags a vertex and
//! checks that the grid, the trace and the URL follow, hovers a pixel and
//! checks that the trace highlights its lines. It checks that the page
//! draws with the one palette and shows its legend, that the grid has row
//! and column numbers and the trace pane its scanline `span` column at
//! 1400 px, that the course's depth-buffer example shows kept and hidden
//! fragments (not double draws) with the depth buffer's trace, and that a
//! student's program (`--exec`) gets a legend entry and a count of wrong
//! pixels. The server's answers to bad requests (4xx, never a panic) are
//! checked over plain HTTP.
//!
//! Chromium is found as for the report's browser test; without one this
//! test passes with a message unless `RASTERLAB_REQUIRE_BROWSER` is set.

mod common;

use common::{chromium, HEADLESS};
use rasterlab::geometry::Scene2D;
use rasterlab::raster::FillRule;
use rasterlab::teaching::{
    colour_hex, triangle_colour, triangle_mark, DepthCells, Mark, Role, LEVEL_COLOURS,
};
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
        Lab::start_with(&[])
    }

    /// `rasterlab lab` with more arguments (`--exec ...`).
    fn start_with(args: &[&str]) -> Lab {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(["lab", "--port", "0"])
            .args(args)
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

/// Headless Chromium, 1400 x 1000 px, and a DevTools session on it;
/// closed and its profile removed when dropped.
struct Browser {
    chrome: Killed,
    dev: DevTools,
    /// Chromium's profile folder, removed when the browser is dropped
    /// (after Chromium has exited).
    _profile: tempfile::TempDir,
}

impl Browser {
    /// Starts Chromium, or says `test` did not run and returns `None`
    /// when there is none.
    fn start(test: &str) -> Option<Browser> {
        let Some(browser) = chromium() else {
            common::part_missing(
                test,
                "chromium (Debian's package `chromium`)",
                "RASTERLAB_REQUIRE_BROWSER",
            );
            return None;
        };
        let profile = tempfile::Builder::new()
            .prefix("rasterlab-lab-chromium-")
            .tempdir()
            .unwrap();
        let mut chrome = Killed(
            Command::new(browser)
                .args(HEADLESS)
                .args(["--remote-debugging-port=0", "--window-size=1400,1000"])
                .arg(format!("--user-data-dir={}", profile.path().display()))
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
        let dev = DevTools {
            socket,
            session: String::new(),
            next_id: 0,
        };
        Some(Browser {
            chrome,
            dev,
            _profile: profile,
        })
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.dev.call("Browser.close", json!({}), false);
        let _ = self.chrome.0.wait();
    }
}

/// The keys of the legend's entries under `#legend`, after checking that
/// it is the one palette's legend, that every role's swatch has the
/// role's colour and draws it (the swatch's SVG uses the colour), and
/// that each triangle's has its colour and line pattern.
fn legend(dev: &mut DevTools) -> Vec<String> {
    let entries = dev.eval(
        "[...document.querySelectorAll('#legend .legend[data-palette=\"okabe-ito\"] .entry')].map(e => [e.dataset.role, e.dataset.colour, e.textContent, e.dataset.mark, e.querySelector('svg.swatch').innerHTML])",
    );
    let entries = entries.as_array().expect("a legend under the grid");
    let mut keys = Vec::new();
    for e in entries {
        let (key, colour, label, mark, swatch) = (
            e[0].as_str().unwrap(),
            e[1].as_str().unwrap(),
            e[2].as_str().unwrap(),
            e[3].as_str().unwrap(),
            e[4].as_str().unwrap(),
        );
        assert!(swatch.contains(colour), "{key}: {swatch}");
        if let Some(role) = Role::ALL.iter().find(|r| r.key() == key) {
            assert_eq!(colour, role.hex(), "{key}");
            assert!(label.contains(role.label()), "{key}: {label}");
        } else if let Some(level) = key.strip_prefix("level-") {
            let level: usize = level.parse().unwrap();
            assert_eq!(colour, colour_hex(LEVEL_COLOURS[level]), "{key}");
            assert_eq!(mark, Mark::Fill.key(), "{key}");
        } else if key == "helper" {
            assert_eq!(colour, Role::Geometry.hex(), "{key}");
            assert_eq!(mark, Mark::Cross.key(), "{key}");
        } else {
            let i: usize = key.strip_prefix("triangle-").expect(key).parse().unwrap();
            assert_eq!(colour, colour_hex(triangle_colour(i)), "{key}");
            assert_eq!(mark, triangle_mark(i).key(), "{key}");
        }
        keys.push(key.to_string());
    }
    keys
}

/// Waits for the page to settle on the answer to its latest state.
fn settle(dev: &mut DevTools, updates: u64) {
    dev.wait_for(&format!(
        "Number(document.body.dataset.updates) > {updates} && document.body.dataset.busy === '0'"
    ));
}

fn updates(dev: &mut DevTools) -> u64 {
    dev.eval("Number(document.body.dataset.updates)")
        .as_u64()
        .unwrap()
}

#[test]
fn a_dragged_vertex_updates_the_grid_the_trace_and_the_url() {
    let Some(mut browser) = Browser::start("the lab's browser test") else {
        return;
    };
    let lab = Lab::start();
    let dev = &mut browser.dev;
    dev.open(&format!("http://{}/", lab.address));

    // The one palette's legend, for what the grid shows: fragments,
    // samples tested outside, the true edges, the pixel centres.
    let keys = legend(dev);
    for role in [
        Role::Drawn,
        Role::TestedOutside,
        Role::Geometry,
        Role::PixelCentre,
    ] {
        assert!(keys.iter().any(|k| k == role.key()), "{role:?} in {keys:?}");
    }
    // Row and column numbers, 16 of each.
    assert_eq!(
        dev.eval("[document.querySelectorAll('#grid .axes .column').length, document.querySelectorAll('#grid .axes .row').length]"),
        json!([16, 16])
    );
    // At 1400 px every scanline row shows its span, on one line, inside
    // the trace pane.
    let spans = dev.eval(
        "(() => { const t = document.getElementById('trace'), box = t.getBoundingClientRect(); const spans = [...t.querySelectorAll('tr')].map(tr => tr.lastElementChild).filter(d => / px\\)$/.test(d.textContent)); return [spans.length, spans.filter(d => { const b = d.getBoundingClientRect(); return b.right <= box.right - 4 && b.height < 20; }).length, window.innerWidth]; })()",
    );
    assert_eq!(spans[2], json!(1400));
    assert!(spans[0].as_u64().unwrap() > 5, "{spans}");
    assert_eq!(spans[0], spans[1], "rows whose span is cut off: {spans}");

    let fragments = |dev: &mut DevTools| {
        dev.eval("document.querySelectorAll('#grid rect.fragment').length")
            .as_u64()
            .unwrap()
    };
    let before = fragments(dev);
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
        rasterlab::raster::triangle_backends().len() as u64,
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
    let after = fragments(dev);
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
    let p = cell_of(dev);
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
        fragments(dev),
        after,
        "the link restores the dragged triangle"
    );
    assert_eq!(dev.eval(first_line).as_str().unwrap(), trace_after);
}

#[test]
fn the_depth_view_shows_kept_and_hidden_fragments_not_double_draws() {
    let Some(mut browser) = Browser::start("the lab's depth-view browser test") else {
        return;
    };
    let lab = Lab::start();
    let dev = &mut browser.dev;
    dev.open(&format!("http://{}/", lab.address));
    let before = updates(dev);
    dev.eval("(() => { const p = document.getElementById('preset'); p.value = 'depth'; p.onchange(); })()");
    settle(dev, before);
    dev.wait_for("document.getElementById('depth-summary') !== null");
    // What the depth test did, as the library counts it.
    let cells = DepthCells::of_scene(
        &Scene2D::depth_example(true),
        rasterlab::raster::triangle_backend("bbox").unwrap(),
        FillRule::TopLeft,
    )
    .unwrap();
    let kept: usize = cells.kept.iter().map(Vec::len).sum();
    let hidden: usize = cells.hidden.iter().map(Vec::len).sum();
    assert_eq!(hidden, 4, "the course's example hides 4 fragments");
    let summary = dev.eval(
        "(() => { const s = document.getElementById('depth-summary'); return [Number(s.dataset.kept), Number(s.dataset.hidden), s.textContent]; })()",
    );
    assert_eq!(
        (summary[0].clone(), summary[1].clone()),
        (json!(kept), json!(hidden)),
        "{summary}"
    );
    assert!(
        summary[2].as_str().unwrap().contains("4 hidden"),
        "{summary}"
    );
    // Hidden fragments are marked where the library hid them; nothing is
    // called a double draw.
    assert_eq!(
        dev.eval("document.querySelectorAll('#grid .hidden').length"),
        json!(cells.hidden.iter().filter(|h| !h.is_empty()).count())
    );
    assert_eq!(
        dev.eval("document.querySelectorAll('#grid .double, #grid .gap').length"),
        json!(0)
    );
    assert_eq!(
        dev.eval("document.getElementById('overlay').disabled"),
        json!(true),
        "the heat map cannot be switched on in the depth view"
    );
    let keys = legend(dev);
    assert!(keys.iter().any(|k| k == Role::Hidden.key()), "{keys:?}");
    // The triangles told apart by their edges, as the legend draws them:
    // colour, dash pattern and name.
    let edges = dev.eval(
        "[...document.querySelectorAll('#grid polygon.outline')].map(p => [p.getAttribute('stroke'), p.getAttribute('stroke-dasharray')])",
    );
    for i in 0..2 {
        let dash = triangle_mark(i).dasharray().unwrap_or("none");
        assert_eq!(
            edges[i],
            json!([colour_hex(triangle_colour(i)), dash]),
            "{edges}"
        );
    }
    assert_eq!(
        dev.eval(
            "[...document.querySelectorAll('#grid text.triangle-label')].map(t => t.textContent)"
        ),
        json!(["T1", "T2"])
    );
    assert!(keys.iter().any(|k| k == "triangle-0") && keys.iter().any(|k| k == "triangle-1"));
    assert!(
        !keys.iter().any(|k| k == Role::DoubleDraw.key()),
        "{keys:?}"
    );
    // The stored depth in every cell, and no pixel centre on a number.
    let labels = dev.eval(
        "(() => { const texts = [...document.querySelectorAll('#grid text.depth')]; const dots = [...document.querySelectorAll('#grid circle.centre')].map(d => d.getBoundingClientRect()); const overlaps = texts.filter(t => { const a = t.getBoundingClientRect(); return dots.some(b => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom); }).length; return [texts.length, overlaps, texts.map(t => t.textContent).join(' ')]; })()",
    );
    assert_eq!(labels[0], json!(14 * 9));
    assert_eq!(labels[1], json!(0), "pixel centres on the printed depths");
    let printed: Vec<String> = cells.depth.iter().map(|z| format!("{z:.1}")).collect();
    assert_eq!(labels[2], json!(printed.join(" ")));
    // The depth buffer's trace, every triangle, not one back-end's.
    let trace = dev
        .eval("document.getElementById('trace').textContent")
        .as_str()
        .unwrap()
        .to_string();
    assert!(trace.starts_with("depth buffer, 14 x 9"), "{trace}");
    assert!(trace.contains("triangle 1 (z = 0.5") && trace.contains("triangle 2 (z = 0.8"));
    assert!(trace.contains(&format!("{hidden} hidden")), "{trace}");
    // Pointing at a pixel highlights its row in each of the three
    // matrices (before, after triangle 1, after triangle 2), by the rows'
    // pixels.
    let p = dev.eval(
        "(() => { const g = document.getElementById('grid'), r = g.getBoundingClientRect(), c = +g.dataset.cell; return [r.left + +g.dataset.left + 5.5 * c, r.top + +g.dataset.top + 4.5 * c]; })()",
    );
    dev.mouse(
        "mouseMoved",
        p[0].as_f64().unwrap(),
        p[1].as_f64().unwrap(),
        0,
    );
    dev.wait_for("document.querySelectorAll('#trace .hl').length > 0");
    let lit = dev.eval("[...document.querySelectorAll('#trace .hl')].map(r => r.children.length)");
    assert_eq!(lit, json!([14, 14, 14]), "the row y = 4 of each matrix");
}

#[test]
fn a_students_program_gets_a_legend_entry_and_a_count_of_wrong_pixels() {
    let Some(mut browser) = Browser::start("the lab's --exec browser test") else {
        return;
    };
    // A "rasterizer" that draws pixel (0, 0) whatever it is given.
    let lab = Lab::start_with(&["--exec", "echo 0 0 0; : {input}"]);
    let dev = &mut browser.dev;
    dev.open(&format!("http://{}/", lab.address));
    dev.wait_for("!document.getElementById('student-box').hidden");
    let answer = dev
        .eval("document.querySelectorAll('#grid rect.fragment').length")
        .as_u64()
        .unwrap();
    let before = updates(dev);
    dev.eval("(() => { const b = document.getElementById('student'); b.checked = true; b.onchange(); })()");
    settle(dev, before);
    dev.wait_for("document.getElementById('student-summary') !== null");
    // Every pixel of the answer is missing, and (0, 0) is extra.
    let summary = dev.eval(
        "(() => { const s = document.getElementById('student-summary'); return [Number(s.dataset.wrong), s.textContent, document.querySelectorAll('#grid .missing').length, document.querySelectorAll('#grid .extra').length]; })()",
    );
    assert_eq!(summary[0], json!(answer + 1), "{summary}");
    assert!(
        summary[1]
            .as_str()
            .unwrap()
            .contains(&format!("{} wrong pixels", answer + 1)),
        "{summary}"
    );
    assert_eq!(
        (summary[2].clone(), summary[3].clone()),
        (json!(answer), json!(1))
    );
    let keys = legend(dev);
    for role in [Role::Missing, Role::Extra] {
        assert!(keys.iter().any(|k| k == role.key()), "{role:?} in {keys:?}");
    }
}

/// The MSAA control: at 4 samples the main grid marks every sample of
/// the default triangle's grid, the dots exactly where the library's
/// masks have bits, the resolve is drawn beside it, and the legend
/// names both marks; switched off, they go.
#[test]
fn the_msaa_control_shows_samples_and_the_resolve() {
    let Some(mut browser) = Browser::start("the lab's MSAA browser test") else {
        return;
    };
    let lab = Lab::start();
    let dev = &mut browser.dev;
    dev.open(&format!("http://{}/", lab.address));
    let before = updates(dev);
    dev.eval(
        "(() => { const m = document.getElementById('msaa'); m.value = '4'; m.onchange(); })()",
    );
    settle(dev, before);
    dev.wait_for("document.getElementById('samples-summary') !== null");
    // What the library covers for the page's own request.
    let request: String = dev
        .eval("JSON.stringify(request())")
        .as_str()
        .unwrap()
        .to_string();
    let request = rasterlab::lab::LabRequest::parse(&request).unwrap();
    let (w, h) = (request.width, request.height);
    let answer = rasterlab::lab::answer(&request, None).unwrap();
    let samples = answer.samples.expect("samples under msaa 4");
    let covered = samples.points.iter().filter(|p| p[2] == 1.0).count();
    assert!(covered > 0);
    assert_eq!(
        dev.eval("document.querySelectorAll('#grid circle.sample').length"),
        json!(4 * w * h)
    );
    assert_eq!(
        dev.eval("document.querySelectorAll('#grid circle.sample.covered').length"),
        json!(covered)
    );
    assert_eq!(
        dev.eval("document.querySelectorAll('#resolved rect.resolved').length"),
        json!(samples.resolved.len())
    );
    let keys = legend(dev);
    for role in [Role::SampleCovered, Role::SampleOutside] {
        assert!(keys.iter().any(|k| k == role.key()), "{keys:?}");
    }
    let before = updates(dev);
    dev.eval(
        "(() => { const m = document.getElementById('msaa'); m.value = '1'; m.onchange(); })()",
    );
    settle(dev, before);
    assert_eq!(
        dev.eval("document.querySelectorAll('#grid circle.sample, #resolved').length"),
        json!(0)
    );
    let keys = legend(dev);
    assert!(
        !keys.iter().any(|k| k == Role::SampleCovered.key()),
        "{keys:?}"
    );
}

/// The compositing controls: the transparent preset composites its three
/// triangles through the stage, the page paints exactly the library's
/// pixels, and sorting back to front changes the pixel all three cover.
#[test]
fn the_compositing_controls_show_the_blended_triangles() {
    let Some(mut browser) = Browser::start("the lab's compositing browser test") else {
        return;
    };
    let lab = Lab::start();
    let dev = &mut browser.dev;
    dev.open(&format!("http://{}/", lab.address));
    let before = updates(dev);
    dev.eval("(() => { const p = document.getElementById('preset'); p.value = 'transparent'; p.onchange(); })()");
    settle(dev, before);
    dev.wait_for("document.getElementById('composited') !== null");
    let painted = |dev: &mut DevTools| -> Vec<String> {
        let v = dev.eval("[...document.querySelectorAll('#composited rect.composited')].map((r) => r.getAttribute('fill'))");
        v.as_array()
            .unwrap()
            .iter()
            .map(|f| f.as_str().unwrap().to_string())
            .collect()
    };
    let expected = |dev: &mut DevTools| -> Vec<String> {
        let request = dev.eval("JSON.stringify(request())");
        let request = rasterlab::lab::LabRequest::parse(request.as_str().unwrap()).unwrap();
        let composite = rasterlab::lab::answer(&request, None)
            .unwrap()
            .composite
            .unwrap();
        composite
            .pixels
            .iter()
            .map(|[r, g, b, _]| format!("rgb({r},{g},{b})"))
            .collect()
    };
    let listed = painted(dev);
    assert_eq!(listed, expected(dev));
    let before = updates(dev);
    dev.eval(
        "(() => { const s = document.getElementById('sort'); s.checked = true; s.onchange(); })()",
    );
    settle(dev, before);
    let sorted = painted(dev);
    assert_eq!(sorted, expected(dev));
    assert_ne!(listed, sorted, "sorting back to front changes the overlap");
    let before = updates(dev);
    dev.eval(
        "(() => { const b = document.getElementById('blend'); b.value = ''; b.onchange(); })()",
    );
    settle(dev, before);
    assert_eq!(
        dev.eval("document.querySelectorAll('#composited').length"),
        json!(0)
    );
}

/// The texture controls: the textured preset draws the triangle through
/// the mipmapped shader, the page paints exactly the library's pixels
/// and levels, crosses each quad's helper pixels under quad derivatives
/// (none under analytic), and lists the levels in the legend.
#[test]
fn the_texture_controls_show_the_textured_triangle_and_its_levels() {
    let Some(mut browser) = Browser::start("the lab's texture browser test") else {
        return;
    };
    let lab = Lab::start();
    let dev = &mut browser.dev;
    dev.open(&format!("http://{}/", lab.address));
    let before = updates(dev);
    dev.eval("(() => { const p = document.getElementById('preset'); p.value = 'textured'; p.onchange(); })()");
    settle(dev, before);
    dev.wait_for("document.getElementById('textured') !== null");
    let answer = |dev: &mut DevTools| {
        let request = dev.eval("JSON.stringify(request())");
        let request = rasterlab::lab::LabRequest::parse(request.as_str().unwrap()).unwrap();
        rasterlab::lab::answer(&request, None)
            .unwrap()
            .textured
            .unwrap()
    };
    let view = answer(dev);
    let painted = dev.eval(
        "[...document.querySelectorAll('#textured rect.texel')].map((r) => r.getAttribute('fill'))",
    );
    let expected: Vec<String> = view
        .pixels
        .iter()
        .map(|[r, g, b, _]| format!("rgb({r},{g},{b})"))
        .collect();
    assert_eq!(painted, json!(expected));
    assert_eq!(
        dev.eval("document.querySelectorAll('#level-map rect.level').length"),
        json!(view.lookups.len())
    );
    // The preset recedes: more than one level is read.
    let mut levels: Vec<usize> = view.lookups.iter().map(|l| l.fine).collect();
    levels.sort_unstable();
    levels.dedup();
    assert!(levels.len() > 1, "{levels:?}");
    assert_eq!(
        dev.eval("document.querySelectorAll('#level-map line.helper').length"),
        json!(view.helpers.len())
    );
    assert!(!view.helpers.is_empty());
    let keys = legend(dev);
    assert!(keys.iter().any(|k| k == "helper"), "{keys:?}");
    assert_eq!(
        keys.iter().filter(|k| k.starts_with("level-")).count(),
        levels.len(),
        "{keys:?}"
    );
    let before = updates(dev);
    dev.eval("(() => { const d = document.getElementById('tex-derivatives'); d.value = 'analytic'; d.onchange(); })()");
    settle(dev, before);
    assert_eq!(
        dev.eval("document.querySelectorAll('#level-map line.helper').length"),
        json!(0)
    );
    assert!(!legend(dev).iter().any(|k| k == "helper"));
    let before = updates(dev);
    dev.eval("(() => { const f = document.getElementById('tex-filter'); f.value = ''; f.onchange(); })()");
    settle(dev, before);
    assert_eq!(
        dev.eval("document.querySelectorAll('#textured').length"),
        json!(0)
    );
}
