//! End-to-end in a real headless Chromium (driven over WebDriver by fantoccini), as a new
//! user would use the app, at 1400 px and 420 px: browse (URLs, Back/Forward, titles,
//! filter, categories, per-step pictures, full-resolution view, low-confidence flag, stale
//! answers, readable errors), upload (keyboard-reachable input, file names everywhere,
//! mismatched frames), interpolate (layers filled, one disk colour scale per motion, any
//! step or the whole sequence, keyboard handles, exact fold boxes), plan (controls above the
//! results on a phone). axe-core (vendored in `tests/fixtures/axe/`) checks every view: no
//! serious or critical violation. The browser's console stays clean: after every part, no
//! error or warning was logged but the refusals the part asks for on purpose, each named.
//! Issue 45: two cloths of other vertex counts are compared without asking for A − B, and a
//! cloth the server does not have (a gone upload, an unknown sample) is said to be gone in
//! every view, which asks nothing more of it. Screenshots of every view at both widths go to
//! `target/e2e-screenshots/` for a person to look at.
//!
//! Needs Debian's `chromium` and `chromium-driver` (or `CLOSE_CHROMIUM` / `CLOSE_CHROMEDRIVER`
//! pointing at them), so it is ignored by default: `cargo test --test it browser:: -- --ignored`.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use axum::routing::get;
use fantoccini::{Client, ClientBuilder, Locator};
use serde_json::{json, Value};

use close::server::{app, AppState};

const TIMEOUT: Duration = Duration::from_secs(60);
/// WebDriver key codes.
const ARROW_RIGHT: &str = "\u{E014}";

/// chromedriver, stopped when the test ends however it ends.
struct Driver(Child);

impl Drop for Driver {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn find_program(env: &str, names: &[&str]) -> Option<PathBuf> {
    if let Ok(p) = std::env::var(env) {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| names.iter().map(move |n| dir.join(n)))
        .find(|p| p.is_file())
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

/// Poll `check` until it gives `Some`, or fail naming `what`.
async fn wait_for<T>(what: &str, mut check: impl AsyncFnMut() -> Option<T>) -> T {
    let start = Instant::now();
    loop {
        if let Some(v) = check().await {
            return v;
        }
        assert!(start.elapsed() < TIMEOUT, "timed out waiting for {what}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

async fn js(client: &Client, script: &str) -> Value {
    client.execute(script, vec![]).await.unwrap_or_else(|e| panic!("script failed ({e}): {script}"))
}

/// Wait until `script` (an expression) is truthy; gives its value.
async fn until(client: &Client, what: &str, expression: &str) -> Value {
    let script = format!("try {{ return ({expression}) || null; }} catch (e) {{ return null; }}");
    wait_for(what, async || Some(js(client, &script).await).filter(|v| !v.is_null())).await
}

async fn text(client: &Client, expression: &str) -> String {
    js(client, &format!("return String({expression})"))
        .await
        .as_str()
        .unwrap_or_default()
        .to_string()
}

/// A Chrome DevTools command, sent through chromedriver.
#[derive(Debug)]
struct DevTools(&'static str, Value);

impl fantoccini::wd::WebDriverCompatibleCommand for DevTools {
    fn endpoint(
        &self,
        base: &url::Url,
        session: Option<&str>,
    ) -> Result<url::Url, url::ParseError> {
        base.join(&format!("session/{}/goog/cdp/execute", session.unwrap_or_default()))
    }

    fn method_and_body(&self, _: &url::Url) -> (http::Method, Option<String>) {
        (http::Method::POST, Some(json!({ "cmd": self.0, "params": self.1 }).to_string()))
    }
}

/// The browser's log (its console and its network errors), read through chromedriver, which
/// empties it.
#[derive(Debug)]
struct BrowserLog;

impl fantoccini::wd::WebDriverCompatibleCommand for BrowserLog {
    fn endpoint(
        &self,
        base: &url::Url,
        session: Option<&str>,
    ) -> Result<url::Url, url::ParseError> {
        base.join(&format!("session/{}/se/log", session.unwrap_or_default()))
    }

    fn method_and_body(&self, _: &url::Url) -> (http::Method, Option<String>) {
        (http::Method::POST, Some(json!({ "type": "browser" }).to_string()))
    }
}

/// Asserts that since the log was last read, the browser logged no error and no warning
/// during `part` but the ones `expected` names (each a piece of the message: a request
/// refused on purpose, such as "/api/samples - Failed to load resource: the server responded
/// with a status of 503"), and each of those at least once.
async fn console_clean(client: &Client, part: &str, expected: &[&str]) {
    let log = client.issue_cmd(BrowserLog).await.expect("the browser's log");
    let entries: Vec<String> = log
        .as_array()
        .into_iter()
        .flatten()
        .filter(|e| matches!(e["level"].as_str(), Some("SEVERE" | "WARNING")))
        .map(|e| format!("{} {}: {}", e["level"], e["source"], e["message"]))
        .collect();
    let unexpected: Vec<&String> =
        entries.iter().filter(|e| !expected.iter().any(|x| e.contains(x))).collect();
    assert!(unexpected.is_empty(), "{part}: the console logged {unexpected:#?}");
    for x in expected {
        assert!(entries.iter().any(|e| e.contains(x)), "{part}: no {x:?} logged: {entries:#?}");
    }
}

/// A screenshot of the whole page, so a person sees every part of the view, not just its
/// top: captured beyond the window, the page laid out for the window as it is (a stretched
/// window would stretch the parts sized in `vh` with it, and its height counts the browser's
/// bars). Fails if the picture is shorter than the page.
async fn screenshot(client: &Client, dir: &Path, name: &str) {
    use base64::Engine as _;
    // Lazy images far below the window would be captured blank.
    until(client, "every picture loaded", "[...document.images].every(i => (i.loading = 'eager', !i.getAttribute('src') || i.complete))").await;
    let size = || {
        js(client, "window.scrollTo(0, 0); return [window.innerWidth, document.documentElement.scrollHeight]")
    };
    let mut page = size().await;
    // A picture that loads while the page is captured can make it taller: capture again.
    let mut png = Vec::new();
    for _ in 0..3 {
        let clip = json!({ "x": 0, "y": 0, "width": page[0], "height": page[1], "scale": 1 });
        let shot = client
            .issue_cmd(DevTools(
                "Page.captureScreenshot",
                json!({ "captureBeyondViewport": true, "clip": clip }),
            ))
            .await
            .expect("screenshot");
        png = base64::engine::general_purpose::STANDARD
            .decode(shot["data"].as_str().unwrap_or_default())
            .expect("a base64 PNG");
        let now = size().await;
        if now == page {
            break;
        }
        page = now;
    }
    std::fs::write(dir.join(name), &png).expect("write screenshot");
    // The PNG's height, from its header (one device pixel per CSS px).
    let shot = png.get(20..24).map_or(0, |h| u32::from_be_bytes(h.try_into().unwrap_or_default()));
    assert!(
        u64::from(shot) >= page[1].as_u64().unwrap_or(u64::MAX),
        "{name}: the screenshot is {shot} px tall, the page {} px",
        page[1]
    );
}

/// Every image under `selector` has loaded with a real picture; gives how many.
async fn images_loaded(client: &Client, selector: &str) -> usize {
    let script = format!("return [...document.querySelectorAll({selector:?})].map(i => i.complete ? i.naturalWidth : 0)");
    wait_for(&format!("images of {selector}"), async || {
        let widths: Vec<u64> =
            serde_json::from_value(js(client, &script).await).unwrap_or_default();
        (!widths.is_empty() && widths.iter().all(|&w| w > 0)).then_some(widths.len())
    })
    .await
}

async fn goto_view(client: &Client, base: &str, hash: &str) {
    client.goto(&format!("{base}/{hash}")).await.expect("load the app");
}

/// Open a hash route in the running page (a history entry, as a click on a link).
async fn route(client: &Client, hash: &str) {
    js(client, &format!("location.hash = {hash:?}")).await;
}

/// The result shown in the Browse view names `name` and is no longer loading.
async fn shows_sample(client: &Client, name: &str) {
    until(
        client,
        &format!("sample {name} shown"),
        &format!("document.querySelector('#browse-result .result-name')?.textContent === {name:?} && !document.querySelector('#browse-result.loading')"),
    )
    .await;
}

/// Run axe-core on the page; the serious and critical violations, described.
async fn axe_violations(client: &Client, axe: &str) -> Vec<String> {
    js(client, axe).await;
    let script = "const done = arguments[arguments.length - 1]; \
                  axe.run(document, { resultTypes: ['violations'] }).then(r => done(r.violations \
                  .filter(v => v.impact === 'serious' || v.impact === 'critical') \
                  .map(v => `${v.id} (${v.impact}): ${v.help} — ${v.nodes.slice(0, 3).map(n => n.target.join(' ')).join(', ')}`)), \
                  e => done(['axe failed: ' + e]));";
    let found = client.execute_async(script, vec![]).await.expect("axe run");
    serde_json::from_value(found).unwrap_or_else(|_| vec!["axe gave no list".into()])
}

/// Pixels of a canvas that are not (nearly) white, as a share.
async fn canvas_ink(client: &Client, id: &str) -> f64 {
    let script = format!(
        "const c = document.getElementById({id:?}); const d = {COPY}(c).getImageData(0, 0, c.width, c.height).data; \
         let ink = 0; for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0 && (d[i] < 235 || d[i + 1] < 235 || d[i + 2] < 235)) ink++; \
         return ink / (c.width * c.height);"
    );
    js(client, &script).await.as_f64().unwrap_or(0.0)
}

/// Every picture on screen under `scope` is looked at pixel by pixel (issue 28 item 1): each
/// image and each canvas drawn as a picture (`role=img`) has ink on over 1 % of its area and
/// more than one colour; an overlay canvas (a cell or edge mark) paints no background over
/// the picture beneath it. Gives how many pictures were looked at; fails naming the blank.
async fn pictures_have_ink(client: &Client, scope: &str) -> usize {
    until(
        client,
        &format!("the pictures of {scope} loaded"),
        &format!("[...document.querySelectorAll('{scope} img')].every(i => (i.loading = 'eager', i.complete && i.naturalWidth > 0))"),
    )
    .await;
    let script = format!(
        "const blank = [], scope = document.querySelector({scope:?}); let looked = 0; \
         const judge = (name, picture, w, h) => {{ looked++; const c = document.createElement('canvas'); c.width = w; c.height = h; \
           const g = c.getContext('2d'); g.drawImage(picture, 0, 0); const d = g.getImageData(0, 0, w, h).data; \
           let ink = 0; const colours = new Set(); \
           for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0 && (d[i] < 235 || d[i + 1] < 235 || d[i + 2] < 235)) {{ ink++; if (colours.size < 2) colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]); }} \
           if (!(ink > 0.01 * w * h) || colours.size < 2) blank.push(`${{name}}: ${{(100 * ink / (w * h)).toFixed(2)}} % inked, ${{colours.size}} colour(s)`); }}; \
         for (const i of scope.querySelectorAll('img')) if (i.checkVisibility()) judge(i.alt || i.src, i, i.naturalWidth, i.naturalHeight); \
         for (const c of scope.querySelectorAll('canvas')) if (c.checkVisibility()) {{ \
           if (c.getAttribute('role') === 'img') judge(c.id || c.getAttribute('aria-label'), c, c.width, c.height); \
           else {{ const bg = getComputedStyle(c).backgroundColor; if (bg !== 'rgba(0, 0, 0, 0)' && bg !== 'transparent') blank.push(`overlay ${{c.className}} paints ${{bg}} over its picture`); }} }} \
         return [looked, blank];"
    );
    let found = js(client, &script).await;
    assert_eq!(found[1], json!([]), "{scope}: pictures that show nothing");
    let looked = found[0].as_u64().unwrap_or(0) as usize;
    assert!(looked > 0, "{scope}: no picture on screen");
    looked
}

/// The interpolation disk picture, once it shows the current state: its colour bar and
/// tick labels (the right part of the picture) as a data URL, and the whole picture.
async fn disk_picture(client: &Client) -> (String, String) {
    let script = "const img = document.getElementById('interp-disk'); \
                  if (!img.complete || !img.naturalWidth || img.dataset.key !== window.closeApp.diskKey()) return null; \
                  const w = img.naturalWidth, h = img.naturalHeight, c = document.createElement('canvas'); c.width = w; c.height = h; \
                  c.getContext('2d').drawImage(img, 0, 0); const bar = document.createElement('canvas'); bar.width = Math.round(0.2 * w); bar.height = Math.round(0.6 * h); \
                  bar.getContext('2d').drawImage(c, w - bar.width, Math.round(0.15 * h), bar.width, bar.height, 0, 0, bar.width, bar.height); \
                  return [bar.toDataURL(), c.toDataURL()];";
    let v = wait_for("the disk of the current state", async || {
        Some(js(client, script).await).filter(|v| v.is_array())
    })
    .await;
    (v[0].as_str().unwrap_or_default().to_string(), v[1].as_str().unwrap_or_default().to_string())
}

/// Nothing is wider than the window.
async fn assert_no_overflow(client: &Client, view: &str) {
    let widths =
        js(client, "return [document.documentElement.scrollWidth, window.innerWidth]").await;
    let (scroll, inner) = (widths[0].as_u64().unwrap_or(0), widths[1].as_u64().unwrap_or(0));
    assert!(scroll <= inner, "{view}: the page is {scroll} px wide in a {inner} px window");
}

/// Press the right arrow on handle `id` ("to:0", "from:1") of the Interpolate circle; gives
/// the folds `which` ("to", "from") before and after, once it moved.
async fn arrow_on_handle(client: &Client, id: &str, which: &str) -> (Value, Value) {
    let before = js(client, &format!("return window.closeApp.interpolate.state().{which}")).await;
    js(
        client,
        &format!("document.querySelector('#fold-circle .handle[data-id=\"{id}\"]').focus()"),
    )
    .await;
    client
        .active_element()
        .await
        .expect("the focused handle")
        .send_keys(ARROW_RIGHT)
        .await
        .expect("arrow key");
    let after = until(client, "the handle to move", &format!("(s => JSON.stringify(s.{which}) !== {:?} && s.{which})(window.closeApp.interpolate.state())", before.to_string())).await;
    (before, after)
}

/// How far (degrees, anticlockwise) angle `k` turned from `before` to `after`.
fn turned(before: &Value, after: &Value, k: usize) -> f64 {
    (after[k].as_f64().unwrap_or(f64::NAN) - before[k].as_f64().unwrap_or(f64::NAN))
        .rem_euclid(std::f64::consts::TAU)
        .to_degrees()
}

/// The handles of the fold circle `svg` that another handle covers (the element on top at
/// the centre of its dot is not its own), after scrolling the circle into view.
async fn covered_handles(client: &Client, svg: &str) -> Value {
    js(client, &format!("const svg = document.getElementById({svg:?}); svg.scrollIntoView({{ block: 'center' }}); \
                         return [...svg.querySelectorAll('.handle')].filter(h => {{ const r = h.querySelector('circle').getBoundingClientRect(); \
                         return document.elementFromPoint(r.x + r.width / 2, r.y + r.height / 2)?.closest('.handle') !== h; }}).map(h => h.dataset.id)")).await
}

/// The names of the fold boxes (`.fold-inputs` labels) on screen that wrap onto two lines.
async fn wrapped_box_names(client: &Client) -> Value {
    js(client, "return [...document.querySelectorAll('.fold-inputs label')].filter(l => l.checkVisibility()).flatMap(l => [...l.childNodes] \
                .filter(t => t.nodeType === 3 && t.textContent.trim() && (r => (r.selectNodeContents(t), r.getClientRects().length > 1))(document.createRange())) \
                .map(t => t.textContent.trim()))").await
}

/// Plan's step pictures whose corner labels are shown smaller than 11 CSS px.
async fn small_plan_labels(client: &Client) -> Value {
    js(client, "return [...document.querySelectorAll('#plan-list canvas')].map(c => parseFloat(c.getContext('2d').font) * c.getBoundingClientRect().width / c.width).filter(px => !(px >= 11))").await
}

/// Once a two-fold sequence has played: its last state drawn is the second fold's, turned
/// all the way, and lies on the analysis's predicted end of `sample`.
async fn ends_on_the_prediction(client: &Client, sample: &close::Sample) {
    until(
        client,
        "the last state drawn",
        "(f => f && f.t === 1 && f.now.fold === 2)(window.closeApp.interpolate.state().frame)",
    )
    .await;
    let drawn: Vec<[f64; 3]> = serde_json::from_value(
        js(client, "return window.closeApp.interpolate.state().drawn").await,
    )
    .expect("the drawn border");
    let predicted = close::analyze(&sample.border_frames().expect("frames"), Default::default())
        .expect("analysis")
        .predicted_end;
    let off = drawn
        .iter()
        .zip(&predicted)
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max);
    assert!(
        drawn.len() == predicted.len() && off < 1e-9,
        "{}: the sequence ends {off} away from the predicted end",
        sample.name
    );
}

/// Choose `paths` in the upload input.
async fn choose_files(client: &Client, paths: &[PathBuf]) {
    choose_files_in(client, "#upload-input", paths).await;
}

/// Choose `paths` in the file input `selector`.
async fn choose_files_in(client: &Client, selector: &str, paths: &[PathBuf]) {
    js(client, &format!("document.querySelector({selector:?}).value = ''")).await;
    let list: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
    client
        .find(Locator::Css(selector))
        .await
        .expect("file input")
        .send_keys(&list.join("\n"))
        .await
        .expect("choose files");
}

fn write(dir: &Path, name: &str, body: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, body).expect("write a test file");
    path
}

/// A text frame: one `x,y,z` per line.
fn text_frame(points: &[[f64; 3]]) -> String {
    points.iter().map(|p| format!("{},{},{}\n", p[0], p[1], p[2])).collect()
}

/// A server on a free port; gives its base URL.
async fn serve(router: axum::Router) -> String {
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.expect("bind");
    let base = format!("http://{}", listener.local_addr().expect("address"));
    tokio::spawn(async move { axum::serve(listener, router).await });
    base
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs chromium and chromedriver (apt-get install chromium chromium-driver); run with `cargo test --test it browser:: -- --ignored`"]
async fn the_app_works_in_a_real_browser() {
    let dataset = close::dataset::Dataset::builtin();
    let (chromium, chromedriver) = (
        find_program("CLOSE_CHROMIUM", &["chromium", "chromium-browser"]),
        find_program("CLOSE_CHROMEDRIVER", &["chromedriver"]),
    );
    let (Some(chromium), Some(chromedriver)) = (chromium, chromedriver) else {
        panic!(
            "the browser test needs chromium and chromedriver: apt-get install -y --no-install-recommends chromium chromium-driver \
             (or set CLOSE_CHROMIUM / CLOSE_CHROMEDRIVER)"
        );
    };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let shots = root.join("target/e2e-screenshots");
    std::fs::create_dir_all(&shots).expect("screenshot folder");
    let axe = std::fs::read_to_string(root.join("tests/fixtures/axe/axe.min.js"))
        .expect("the vendored axe-core");
    let scratch = std::env::temp_dir().join(format!("close-e2e-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("scratch folder");

    let state = AppState::new();
    let base = serve(app(state.clone())).await;
    // A second server whose sample list fails with a proxy's HTML page.
    let broken = serve(
        axum::Router::new()
            .route(
                "/api/samples",
                get(|| async { (axum::http::StatusCode::SERVICE_UNAVAILABLE, axum::response::Html("<html><body><h1>503 Service Unavailable</h1><p>upstream down</p></body></html>")) }),
            )
            .fallback_service(app(state.clone())),
    )
    .await;
    // A third whose list holds five thousand samples (as `close serve --dataset` may).
    let many_list: Vec<Value> = (0..5000)
        .map(|k| {
            let (real, category) = (&dataset.entries()[k % 3], ["a", "b", "c"][k % 3]);
            json!({ "id": real.id, "name": format!("user {k}"), "category": category, "n": 4, "frames": 2, "mesh": false,
                    "thumbnail": format!("/api/images/sample:{}/thumbnail.png?size=160", real.id) })
        })
        .collect();
    let many_body = json!({ "samples": many_list }).to_string();
    let many = serve(
        axum::Router::new()
            .route(
                "/api/samples",
                get(move || {
                    std::future::ready((
                        [(axum::http::header::CONTENT_TYPE, "application/json")],
                        many_body.clone(),
                    ))
                }),
            )
            .fallback_service(app(state)),
    )
    .await;

    // A fourth with the user's own dataset: copies of two physics samples with their truth.
    let own = scratch.join("own-dataset");
    std::fs::create_dir_all(&own).expect("dataset folder");
    for file in ["h1_half_left_onto_right_31x31.json", "q3_napkin_half_then_quarter_31x31.json"] {
        std::fs::copy(root.join("tests/fixtures/physics").join(file), own.join(file))
            .expect("copy a fixture");
    }
    let with_dataset = serve(app(AppState::with_config(close::server::Config {
        datasets: vec![own.clone()],
        ..Default::default()
    })))
    .await;

    let port = free_port();
    let _driver = Driver(
        Command::new(&chromedriver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromedriver"),
    );
    let mut caps = serde_json::Map::new();
    // Every console and network message, for `console_clean`.
    caps.insert("goog:loggingPrefs".into(), json!({ "browser": "ALL" }));
    caps.insert(
        "goog:chromeOptions".into(),
        json!({
            "binary": chromium,
            "args": ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
                     "--disable-component-update", "--disable-sync", "--window-size=1400,1000",
                     format!("--user-data-dir={}", scratch.join("profile").display())],
        }),
    );
    let webdriver = format!("http://127.0.0.1:{port}");
    let client = wait_for("chromedriver to start a session", async || {
        ClientBuilder::new(hyper_util::client::legacy::connect::HttpConnector::new())
            .capabilities(caps.clone())
            .connect(&webdriver)
            .await
            .ok()
    })
    .await;
    client.set_window_size(1400, 1000).await.expect("window size");
    let mut violations: Vec<String> = Vec::new();

    // ---- Browse: the bare URL opens the first sample under its own URL.
    goto_view(&client, &base, "").await;
    let first = &dataset.entries()[0];
    until(
        &client,
        "the first sample's URL",
        &format!("location.hash === '#/samples/{}'", first.id),
    )
    .await;
    shows_sample(&client, &first.sample.name).await;
    assert!(
        text(&client, "document.title").await.contains(&first.sample.name),
        "the title names the open sample"
    );
    // The favicon is declared and served (no 404 on load).
    let favicon =
        until(&client, "the favicon", "document.querySelector('link[rel=icon]')?.href").await;
    let status = client
        .execute_async(
            "fetch(arguments[0]).then(r => arguments[1](r.status))",
            vec![favicon.clone()],
        )
        .await
        .expect("fetch favicon");
    assert_eq!(status, json!(200), "favicon {favicon}");
    // Thumbnails are mini drawings that load.
    images_loaded(&client, "#sample-list .category:first-of-type .sample-card:nth-child(-n+3) img")
        .await;
    // Names are whole and wrap only after an underscore: no word of a name spans two lines.
    let split = js(&client, "return [...document.querySelectorAll('.sample-card .card-name')].flatMap(n => [...n.childNodes] \
                             .filter(t => t.nodeType === 3 && (r => (r.selectNodeContents(t), r.getClientRects().length > 1))(document.createRange())) \
                             .map(t => n.textContent))").await;
    assert_eq!(split, json!([]), "names broken mid-word");

    // A click on a card: its URL, its title, its pictures.
    let twice = dataset.get("napkin__half_then_half").expect("a second-fold sample");
    client
        .find(Locator::Css(&format!(".sample-card[data-id={:?}]", twice.id)))
        .await
        .expect("its card")
        .click()
        .await
        .expect("click");
    shows_sample(&client, &twice.sample.name).await;
    assert_eq!(
        client.current_url().await.expect("url").fragment(),
        Some(&*format!("/samples/{}", twice.id))
    );
    assert!(text(&client, "document.title").await.contains(&twice.sample.name));
    // Per-step pictures: step 1 first, step 2 on demand (frame 1's disks), the whole run.
    assert_eq!(images_loaded(&client, "#browse-result figure img").await, 6);
    let steps = js(&client, "return [...document.querySelectorAll('#browse-result .segmented input')].map(i => i.nextElementSibling.textContent)").await;
    assert_eq!(steps.as_array().map(Vec::len), Some(3), "all frames, step 1, step 2: {steps}");
    js(
        &client,
        "document.querySelector('#browse-result .segmented input[data-step=\"2\"]').click()",
    )
    .await;
    until(&client, "step 2's pictures", "[...document.querySelectorAll('#browse-result .step-pictures img')].every(i => i.src.includes('step=2'))").await;
    assert_eq!(images_loaded(&client, "#browse-result .step-pictures img").await, 4);
    // One timeline (issue 28 item 5): the step drives the border plot and the fold circle too.
    until(&client, "step 2's border plot and fold circle", "(p => p.length === 2 && p.every(i => i.src.includes('step=2')))([...document.querySelectorAll('#browse-result .instrument-plot img')])").await;
    assert!(pictures_have_ink(&client, "#browse-result").await >= 6);
    // The evidence is shown, and this exact fold is not flagged.
    let evidence =
        text(&client, "document.querySelector('#browse-result .evidence-table').innerText").await;
    assert!(
        evidence.contains("same/cross")
            && evidence.contains("cut residual")
            && evidence.contains("flip scores"),
        "{evidence}"
    );
    assert!(js(&client, "return document.querySelector('#browse-result .confidence').hidden")
        .await
        .as_bool()
        .unwrap_or(false));
    screenshot(&client, &shots, "1400-01-browse-second-fold.png").await;
    violations
        .extend(axe_violations(&client, &axe).await.into_iter().map(|v| format!("browse: {v}")));

    // Click to enlarge: the full-resolution picture in a dialog; Escape closes it.
    js(&client, "document.querySelector('#browse-result .step-pictures .zoom').click()").await;
    until(&client, "the full-resolution picture", "document.getElementById('lightbox').open && document.querySelector('#lightbox img').naturalWidth >= 1400").await;
    // The wheel zooms in about the pointer, up to more than the fitted size (item 6).
    let zoomed = js(&client, "const f = document.querySelector('#lightbox .lightbox-frame'), r = f.getBoundingClientRect(); \
                              f.dispatchEvent(new WheelEvent('wheel', { deltaY: -600, clientX: r.x + r.width / 2, clientY: r.y + r.height / 2, bubbles: true, cancelable: true })); \
                              const img = document.querySelector('#lightbox img'); return img.getBoundingClientRect().width / f.getBoundingClientRect().width").await;
    assert!(zoomed.as_f64().is_some_and(|z| z > 5.0), "the picture did not zoom: {zoomed}");
    // The large disk downloads, and reads its cells as the small one does (issue 28 item 15).
    let save = js(&client, "const a = document.querySelector('#lightbox .lightbox-download'); return [a.href === document.querySelector('#lightbox img').src, a.download]").await;
    assert!(
        save[0] == json!(true)
            && save[1].as_str().is_some_and(|f| f.ends_with("_disk_start_step2.png")),
        "the dialog's download: {save}"
    );
    js(&client, "const f = document.querySelector('#lightbox .lightbox-frame'); f.dispatchEvent(new WheelEvent('wheel', { deltaY: 6000, bubbles: true, cancelable: true })); \
                 const s = document.querySelector('#lightbox .lightbox-stage'), r = s.getBoundingClientRect(); \
                 s.dispatchEvent(new PointerEvent('pointermove', { pointerType: 'mouse', clientX: r.x + 0.42 * r.width, clientY: r.y + 0.3 * r.height, bubbles: true }))").await;
    let read = until(
        &client,
        "the large disk's readout",
        "document.querySelector('#lightbox .lightbox-readout .cell-readout')?.textContent || null",
    )
    .await;
    assert!(
        read.as_str().is_some_and(|r| r.starts_with("edges i =")),
        "the large disk reads: {read}"
    );
    screenshot(&client, &shots, "1400-02-full-resolution.png").await;
    violations
        .extend(axe_violations(&client, &axe).await.into_iter().map(|v| format!("lightbox: {v}")));
    client.active_element().await.expect("focus").send_keys("\u{E00C}").await.expect("Escape");
    until(&client, "the dialog to close", "!document.getElementById('lightbox').open").await;

    // A well-supported second fold is not flagged (the doubtful case is an upload below).
    route(&client, "#/samples/trousers__legs_up_then_half").await;
    shows_sample(&client, &dataset.get("trousers__legs_up_then_half").expect("sample").sample.name)
        .await;
    let verdict =
        text(&client, "document.querySelector('#browse-result .confidence').textContent").await;
    assert!(!verdict.contains("Low confidence"), "{verdict}");

    // Back and Forward move between samples.
    client.back().await.expect("back");
    shows_sample(&client, &twice.sample.name).await;
    client.forward().await.expect("forward");
    until(&client, "forward", "location.hash === '#/samples/trousers__legs_up_then_half'").await;

    // Stale answers: A's answer is held back past B's (and past any abort); B is shown and
    // highlighted, and a loading note shows while B loads.
    let (a, b) = ("tshirt__sleeve_left", "towel__half_long_then_half");
    js(&client, &format!(
        "window.realFetch = window.fetch; const sleep = ms => new Promise(r => setTimeout(r, ms)); \
         window.fetch = (url, o) => String(url).endsWith('/api/samples/{a}') ? window.realFetch(url).then(r => sleep(1500).then(() => r)) \
         : String(url).endsWith('/api/samples/{b}') ? sleep(600).then(() => window.realFetch(url, o)) : window.realFetch(url, o); \
         location.hash = '#/samples/{a}'; setTimeout(() => location.hash = '#/samples/{b}', 50)"
    ))
    .await;
    until(&client, "the loading state", &format!("document.getElementById('browse-result').classList.contains('loading') && document.querySelector('.loading-note').textContent.includes('{b}')")).await;
    let b_name = dataset.get(b).expect("sample").sample.name.clone();
    shows_sample(&client, &b_name).await;
    tokio::time::sleep(Duration::from_millis(2500)).await;
    js(&client, "window.fetch = window.realFetch").await;
    assert_eq!(
        text(&client, "document.querySelector('#browse-result .result-name').textContent").await,
        b_name,
        "a late answer replaced the newer one"
    );
    let active = js(
        &client,
        "return [...document.querySelectorAll('.sample-card.active')].map(c => c.dataset.id)",
    )
    .await;
    assert_eq!(active, json!([b]));

    // Filter by name and category; collapse a category.
    js(&client, "const f = document.getElementById('sample-filter'); f.value = 'tshirt sleeve'; f.dispatchEvent(new Event('input'))").await;
    let ids = until(&client, "filtered cards", "(() => { const ids = [...document.querySelectorAll('.sample-card')].map(c => c.dataset.id); return ids.every(i => i.includes('tshirt') && i.includes('sleeve')) && ids.length ? ids : null })()").await;
    assert!(ids.as_array().is_some_and(|a| !a.is_empty()));
    js(&client, "const f = document.getElementById('sample-filter'); f.value = ''; f.dispatchEvent(new Event('input')); \
                 const c = document.getElementById('sample-category'); c.value = 'towel'; c.dispatchEvent(new Event('change'))").await;
    until(&client, "one category", "[...document.querySelectorAll('.category summary')].length === 1 && document.querySelector('.category summary').textContent.startsWith('towel')").await;
    js(&client, "document.querySelector('.category summary').click()").await;
    until(&client, "a closed category", "!document.querySelector('.category').open && !document.querySelector('.sample-card').checkVisibility()").await;
    js(&client, "document.querySelector('.category summary').click()").await;
    until(&client, "the category open again", "document.querySelector('.category').open").await;
    js(&client, "const c = document.getElementById('sample-category'); c.value = ''; c.dispatchEvent(new Event('change'))").await;

    // Readable errors: an HTML error page, then a network failure; the failed sample's
    // card is highlighted over its own error, never over the old result.
    js(&client, "window.realFetch = window.fetch; window.fetch = (url, o) => String(url).includes('/api/samples/napkin__diagonal') \
                 ? Promise.resolve(new Response('<html><body><h1>503 Service Unavailable</h1></body></html>', { status: 503, headers: { 'content-type': 'text/html' } })) \
                 : window.realFetch(url, o)").await;
    route(&client, "#/samples/napkin__diagonal").await;
    let error =
        until(&client, "the 503 message", "document.getElementById('error').textContent").await;
    let error = error.as_str().unwrap_or_default();
    assert!(
        error.contains("503 Service Unavailable") && !error.contains('<'),
        "error shown: {error}"
    );
    assert!(text(&client, "document.getElementById('browse-result').textContent")
        .await
        .contains("could not be shown"));
    js(&client, "window.fetch = (url, o) => String(url).includes('/api/samples/napkin__corner') ? Promise.reject(new TypeError('Failed to fetch')) : window.realFetch(url, o)").await;
    route(&client, "#/samples/napkin__corner").await;
    let error = until(&client, "the network message", "document.getElementById('error').textContent.includes('Could not reach') && document.getElementById('error').textContent").await;
    assert!(!error.as_str().unwrap_or_default().starts_with("Failed to fetch"), "{error}");
    js(&client, "window.fetch = window.realFetch").await;

    console_clean(&client, "browse", &[]).await;

    // ---- Upload: keyboard-reachable input; results named by file names everywhere.
    route(&client, "#/upload").await;
    until(&client, "the upload view", "!document.getElementById('view-upload').hidden").await;
    let reachable = js(&client, "const i = document.getElementById('upload-input'); i.focus(); return getComputedStyle(i).display !== 'none' && document.activeElement === i").await;
    assert_eq!(reachable, json!(true), "the file input cannot be focused");
    let entry = dataset.get("napkin__half_vertical").expect("a folded sample");
    let good =
        write(&scratch, "my-napkin.json", &serde_json::to_vec(&entry.sample).expect("sample JSON"));
    choose_files(&client, &[good]).await;
    until(
        &client,
        "the upload's result",
        "document.querySelector('#upload-result .result-name')?.textContent === 'my-napkin.json'",
    )
    .await;
    assert_eq!(images_loaded(&client, "#upload-result img").await, 6);
    assert!(pictures_have_ink(&client, "#upload-result").await >= 6);
    assert!(text(&client, "document.title").await.contains("my-napkin.json"));
    screenshot(&client, &shots, "1400-03-upload.png").await;
    violations
        .extend(axe_violations(&client, &axe).await.into_iter().map(|v| format!("upload: {v}")));
    // A doubtful fold says so: the same napkin, its folded flap then slid half a side away,
    // so no fold of the start explains the end frame.
    let mut slid = entry.sample.clone();
    let (start, end) = (slid.frames[0].clone(), slid.frames.last_mut().expect("an end frame"));
    let side = start.iter().map(|p| p[0]).fold(f64::MIN, f64::max)
        - start.iter().map(|p| p[0]).fold(f64::MAX, f64::min);
    for (p, q) in end.iter_mut().zip(&start) {
        if (p[0] - q[0]).hypot(p[1] - q[1]) > 1e-9 {
            p[0] += 0.5 * side;
        }
    }
    let doubtful =
        write(&scratch, "slid-napkin.json", &serde_json::to_vec(&slid).expect("sample JSON"));
    choose_files(&client, &[doubtful]).await;
    until(
        &client,
        "the doubtful upload",
        "document.querySelector('#upload-result .result-name')?.textContent === 'slid-napkin.json'",
    )
    .await;
    let verdict =
        text(&client, "document.querySelector('#upload-result .confidence').textContent").await;
    assert!(
        verdict.contains("Low confidence"),
        "a fold that does not explain the end frame is not flagged: {verdict}"
    );
    // An uploaded Sample JSON keeps its truth (issue 19, item 4).
    choose_files(&client, &[own.join("h1_half_left_onto_right_31x31.json")]).await;
    until(&client, "the upload with a truth", "document.querySelector('#upload-result .result-name')?.textContent === 'h1_half_left_onto_right_31x31.json'").await;
    let facts =
        text(&client, "document.querySelector('#upload-result .close-table').innerText").await;
    assert!(facts.contains("true fold 1"), "the upload's truth is not shown: {facts}");
    // A multi-arc fold is compared with its truth by its line and folded set (issue 28 item
    // 2): the border plot of step 2 of the MuJoCo trousers, in the legend of its SVG.
    let trousers =
        root.join("tests/fixtures/physics-mujoco/border/trousers_q1_leg_over_leg_then_half.json");
    choose_files(&client, &[trousers]).await;
    until(&client, "the multi-arc upload", "document.querySelector('#upload-result .result-name')?.textContent === 'trousers_q1_leg_over_leg_then_half.json'").await;
    js(
        &client,
        "document.querySelector('#upload-result .segmented input[data-step=\"2\"]').click()",
    )
    .await;
    let legend = client.execute_async("const done = arguments[0], wait = () => { const i = [...document.querySelectorAll('#upload-result figure img')].find(i => i.dataset.picture === 'borders'); \
                                       if (!i || !i.src.includes('step=2')) return setTimeout(wait, 50); \
                                       fetch(i.closest('figure').querySelector('a.download[data-format=svg]').href).then(r => r.text()).then(t => done([...t.matchAll(/<text[^>]*>([^<]*)</g)].map(m => m[1]).join(' '))).catch(e => done(String(e))); }; wait();", vec![]).await.expect("the border plot's SVG");
    let legend = legend.as_str().unwrap_or_default().to_string();
    assert!(
        legend.contains("fold 2 (true: line") && legend.contains("folded vertices shared"),
        "the multi-arc fold is not compared by its line and folded set: {legend}"
    );
    assert!(text(&client, "document.querySelector('#upload-result .result-meta').textContent")
        .await
        .starts_with("your upload"));
    // A change with no fold is flagged (item 13): the napkin crumpled on the table (each
    // vertex moved at random, a quarter of the side at most) has no fold, and no rigid
    // motion brings it back onto the start frame (a napkin only moved would be unchanged).
    let mut crumpled = entry.sample.clone();
    let start = crumpled.frames[0].clone();
    let mut rng = close::rng::SplitMix64::new(11);
    let mut noise = |scale: f64| (rng.uniform() - 0.5) * scale * side;
    crumpled.frames[1] =
        start.iter().map(|p| [p[0] + noise(0.5), p[1] + noise(0.5), p[2] + noise(0.05)]).collect();
    choose_files(
        &client,
        &[write(
            &scratch,
            "crumpled-napkin.json",
            &serde_json::to_vec(&crumpled).expect("sample JSON"),
        )],
    )
    .await;
    until(&client, "the crumpled upload", "document.querySelector('#upload-result .result-name')?.textContent === 'crumpled-napkin.json'").await;
    let label =
        text(&client, "document.querySelector('#upload-result .result-label').textContent").await;
    let verdict =
        text(&client, "document.querySelector('#upload-result .confidence').textContent").await;
    assert!(
        label.contains("changed, but no fold found")
            && verdict.contains("changed, but no fold found"),
        "{label} / {verdict}"
    );
    // A failed upload leaves no old name in the title.
    choose_files(&client, &[write(&scratch, "broken.json", b"{")]).await;
    until(&client, "the failed upload", "!document.getElementById('error').hidden").await;
    assert!(
        !text(&client, "document.title").await.contains("crumpled-napkin"),
        "the title names the previous upload"
    );
    // Mismatched frames name their files.
    let frames = entry.sample.frames.clone();
    let short =
        write(&scratch, "b-end.txt", text_frame(&frames[1][..frames[1].len() - 3]).as_bytes());
    let long = write(&scratch, "a-start.txt", text_frame(&frames[0]).as_bytes());
    choose_files(&client, &[short, long]).await;
    let error = until(
        &client,
        "the mismatch message",
        "(t => !t.includes('broken.json') && t)(document.getElementById('error').textContent)",
    )
    .await;
    let error = error.as_str().unwrap_or_default();
    assert!(
        error.contains("a-start.txt") && error.contains("b-end.txt"),
        "the files are not named: {error}"
    );
    screenshot(&client, &shots, "1400-04-upload-error.png").await;
    // A sample of two text files: its snippets send both files (issue 28 item 9).
    let start = write(&scratch, "c-start.txt", text_frame(&frames[0]).as_bytes());
    let end = write(&scratch, "d-end.txt", text_frame(&frames[frames.len() - 1]).as_bytes());
    choose_files(&client, &[start, end]).await;
    until(&client, "the two-file upload", "document.querySelector('#upload-result .result-name')?.textContent === 'c-start.txt … d-end.txt (2 files)'").await;
    let label =
        text(&client, "document.querySelector('#upload-result .result-label').textContent").await;
    run_snippets(&client, "#upload-result", &scratch, &label).await;

    // The broken file and the mismatched frames, refused by the server.
    console_clean(&client, "upload", &["/api/analyze - Failed to load resource"]).await;

    // Upload → Interpolate: the upload, by its file name, with its fold.
    choose_files(&client, &[scratch.join("my-napkin.json")]).await;
    until(&client, "the upload again", "document.querySelector('#upload-result .result-name')?.textContent === 'my-napkin.json' && document.getElementById('error').hidden").await;
    js(&client, "document.querySelector('#upload-result .interp-this').click()").await;
    until(&client, "the interpolate view", "location.hash.startsWith('#/interpolate') && !document.getElementById('view-interpolate').hidden").await;
    let chosen = until(&client, "the upload chosen", "document.getElementById('interp-sample').selectedOptions[0]?.textContent.includes('my-napkin.json') && document.getElementById('interp-sample').selectedOptions[0].textContent").await;
    assert!(chosen.as_str().unwrap_or_default().starts_with("upload"), "{chosen}");
    assert!(text(&client, "document.title").await.contains("my-napkin.json"));

    // ---- Interpolate: the layers are filled; one colour scale all the way through.
    let (bar0, disk0) = disk_picture(&client).await;
    js(&client, "window.closeApp.interpolate.setTau(1)").await;
    let (bar1, disk1) = disk_picture(&client).await;
    assert_ne!(disk0, disk1, "the disk did not follow the fold");
    assert_eq!(bar0, bar1, "the colour bar changed during the motion");
    // At t = 1 the folded napkin is two layers on half the cloth: filled, not a hole.
    let ink = canvas_ink(&client, "interp-canvas").await;
    assert!(ink > 0.15, "the folded cloth is not filled: {ink:.3} of the canvas inked");
    assert!(pictures_have_ink(&client, "#view-interpolate").await >= 2);
    screenshot(&client, &shots, "1400-05-interpolate.png").await;
    violations.extend(
        axe_violations(&client, &axe).await.into_iter().map(|v| format!("interpolate: {v}")),
    );
    assert_eq!(wrapped_box_names(&client).await, json!([]), "fold box names wrap");

    // The fold starts flat: both "from" handles at one angle, each still in sight and on top
    // at its own dot (none hidden under the other), and each moved by its own arrow keys.
    let from = js(&client, "return window.closeApp.interpolate.state().from").await;
    assert_eq!(from[0], from[1], "the fold does not start flat");
    assert_eq!(
        covered_handles(&client, "fold-circle").await,
        json!([]),
        "handles hidden under others"
    );
    let (before, after) = arrow_on_handle(&client, "from:1", "from").await;
    assert!(
        (turned(&before, &after, 1) - 1.0).abs() < 1e-9 && after[0] == before[0],
        "the second 'from' handle: {before} → {after}"
    );

    // The disk opens at full resolution in the motion's colour scale: the request for it is
    // the state shown, with the scale the small pictures use.
    js(&client, "window.diskAsked = []; window.realFetch = window.fetch; \
                 window.fetch = (url, o) => (String(url).endsWith('/api/disk') && window.diskAsked.push(JSON.parse(o.body)), window.realFetch(url, o)); \
                 window.closeApp.interpolate.setTau(0.5)").await;
    disk_picture(&client).await;
    js(&client, "document.getElementById('interp-disk-zoom').click()").await;
    until(&client, "the disk at full resolution", "document.getElementById('lightbox').open && document.querySelector('#lightbox img').naturalWidth >= 1400").await;
    let asked = js(
        &client,
        "window.fetch = window.realFetch; return window.diskAsked.filter(r => r.size >= 480)",
    )
    .await;
    let (small, large) = (
        &asked[asked.as_array().map_or(0, |a| a.len().saturating_sub(2))],
        asked.as_array().and_then(|a| a.last()).unwrap_or(&Value::Null),
    );
    assert!(large["size"].as_u64() >= Some(1400) && small["size"] == json!(480), "{asked}");
    assert!(
        large["scale"].is_object()
            && large["scale"] == small["scale"]
            && large["border"] == small["border"],
        "the enlarged disk is not the state shown in its scale: {small} / {large}"
    );
    screenshot(&client, &shots, "1400-05b-interpolate-full-resolution.png").await;
    violations.extend(
        axe_violations(&client, &axe)
            .await
            .into_iter()
            .map(|v| format!("interpolate lightbox: {v}")),
    );
    client.active_element().await.expect("focus").send_keys("\u{E00C}").await.expect("Escape");
    until(&client, "the dialog to close", "!document.getElementById('lightbox').open").await;
    js(&client, "window.closeApp.interpolate.setTau(1)").await;

    // Keyboard: a handle takes focus and moves by a degree per arrow key; the fold boxes
    // keep the other folds exact and report what is not a number.
    let (before, after) = arrow_on_handle(&client, "to:0", "to").await;
    let moved = turned(&before, &after, 0);
    assert!((moved - 1.0).abs() < 1e-9, "one arrow key moved the handle {moved}°");
    assert_eq!(after[1], before[1], "the other end moved");
    js(&client, "const i = document.getElementById('to-2'); i.value = 'abc'; i.dispatchEvent(new Event('change'))").await;
    assert_eq!(
        js(&client, "return document.getElementById('to-2').getAttribute('aria-invalid')").await,
        json!("true")
    );
    assert!(text(&client, "document.getElementById('fold-input-status').textContent")
        .await
        .contains("not a number"));
    js(&client, "const i = document.getElementById('to-2'); i.value = '200'; i.dispatchEvent(new Event('change'))").await;
    let exact = js(&client, "return window.closeApp.interpolate.state().to").await;
    assert_eq!(exact[0], after[0], "editing g₂ re-read g₁ from its rounded box");
    assert!((exact[1].as_f64().unwrap_or(0.0).to_degrees() - 200.0).abs() < 1e-9);

    // A towel folded twice, uploaded flat and folded only (issue 26): the step's sequence
    // is listed, and the whole sequence plays fold by fold to the predicted end.
    let towel: close::Sample = close::formats::json::parse_sample(
        &std::fs::read(root.join("tests/fixtures/physics/q5_towel_half_then_half_26x41.json"))
            .expect("the towel fixture"),
    )
    .expect("the towel");
    let ends = close::Sample {
        frames: vec![towel.frames[0].clone(), towel.frames[towel.frames.len() - 1].clone()],
        ..towel.clone()
    };
    let ends_file = write(
        &scratch,
        "towel-flat-and-folded.json",
        close::formats::json::to_json(&ends).as_bytes(),
    );
    route(&client, "#/upload").await;
    choose_files(&client, &[ends_file]).await;
    until(&client, "the flat-and-folded upload", "document.querySelector('#upload-result .result-name')?.textContent === 'towel-flat-and-folded.json' && document.getElementById('error').hidden").await;
    let evidence =
        text(&client, "document.querySelector('#upload-result .evidence-table').textContent").await;
    assert!(evidence.contains("2 folds:"), "the sequence is not listed: {evidence}");
    js(&client, "document.querySelector('#upload-result .interp-this').click()").await;
    until(&client, "the whole sequence chosen", "document.getElementById('interp-step').value === 'all' && [...document.getElementById('interp-step').options].some(o => o.textContent.includes('2 folds'))").await;
    client.find(Locator::Id("interp-play")).await.expect("play").click().await.expect("play");
    ends_on_the_prediction(&client, &ends).await;
    screenshot(&client, &shots, "1400-06b-interpolate-flat-and-folded.png").await;

    // A second-fold sample: pick the step, or animate the whole sequence.
    route(&client, &format!("#/samples/{}", twice.id)).await;
    shows_sample(&client, &twice.sample.name).await;
    js(&client, "document.querySelector('#browse-result .interp-this').click()").await;
    until(&client, "the step choice", "document.getElementById('interp-step').options.length === 4 && document.getElementById('interp-sample').value.endsWith('napkin__half_then_half')").await;
    js(&client, "const s = document.getElementById('interp-step'); s.value = 'all'; s.dispatchEvent(new Event('change'))").await;
    client.find(Locator::Id("interp-play")).await.expect("play").click().await.expect("play");
    until(
        &client,
        "the sequence to end",
        "document.getElementById('interp-slider').value === '1000'",
    )
    .await;
    // The second fold, through two stacked layers, is made along the line the analysis
    // reports, not through its two (coinciding) fold points.
    ends_on_the_prediction(&client, &twice.sample).await;
    let readout = text(&client, "document.getElementById('interp-readout').textContent").await;
    assert!(readout.contains("fold 2 of 2"), "{readout}");
    disk_picture(&client).await;
    screenshot(&client, &shots, "1400-06-interpolate-sequence.png").await;

    console_clean(&client, "interpolate", &[]).await;

    // ---- Plan from the interpolation's goal; each step drawn and said.
    js(&client, "const s = document.getElementById('interp-step'); s.value = '1'; s.dispatchEvent(new Event('change'))").await;
    // An arrow key steps a degree from the exact angle (49.737…°), not from its rounding.
    let (before, after) = arrow_on_handle(&client, "to:0", "to").await;
    let moved = turned(&before, &after, 0);
    assert!(
        (moved - 1.0).abs() < 1e-9,
        "one arrow key moved the handle {moved}° from {}",
        before[0]
    );
    client.find(Locator::Id("plan-goal")).await.expect("plan button").click().await.expect("click");
    until(
        &client,
        "the plan view",
        "location.hash.startsWith('#/plan') && !document.getElementById('view-plan').hidden",
    )
    .await;
    js(&client, "for (const [id, v] of [['goal-1', 10], ['goal-2', 150]]) { const i = document.getElementById(id); i.value = v; i.dispatchEvent(new Event('change')); }").await;
    client.find(Locator::Id("plan-run")).await.expect("plan").click().await.expect("click");
    until(
        &client,
        "a plan",
        "document.getElementById('plan-case').textContent.includes('unfold first')",
    )
    .await;
    let steps: Vec<String> = serde_json::from_value(js(&client, "return [...document.querySelectorAll('#plan-list .plan-step')].map(li => li.innerText)").await).unwrap_or_default();
    assert!(steps.first().is_some_and(|s| s.starts_with("Now")), "{steps:?}");
    assert_eq!(steps.iter().filter(|s| s.contains("· Unfold")).count(), 2, "{steps:?}");
    assert!(steps.last().is_some_and(|s| s.contains("· Fold") && s.contains("10.0°")), "{steps:?}");
    assert!(
        steps.iter().skip(1).all(|s| s.contains("(x, y in the sample's units)")),
        "coordinates without units: {steps:?}"
    );
    assert!(text(&client, "document.title").await.contains("half_then_half"));
    // The goal is previewed on the flat cloth (issue 28 item 3), drawn by the server.
    until(&client, "the goal's preview", "document.getElementById('plan-preview').getAttribute('aria-label').includes('(10.0°, 150.0°)')").await;
    assert!(pictures_have_ink(&client, "#view-plan").await >= 5);
    screenshot(&client, &shots, "1400-07-plan.png").await;
    assert_eq!(wrapped_box_names(&client).await, json!([]), "goal box names wrap");
    assert_eq!(
        small_plan_labels(&client).await,
        json!([]),
        "plan pictures' corner labels below 11 CSS px"
    );
    // Corner labels keep off one another and off the dots: on a strip narrower than a label,
    // corners 1 and 2 (and 3 and 4) get their labels on either side.
    let overlaps = client
        .execute_async(
            "const done = arguments[arguments.length - 1]; import('/assets/draw.js').then(d => { \
             const c = document.createElement('canvas'); c.width = 520; c.height = 420; const size = 25, r = size / 3; \
             const pts = [[100, 380], [130, 380], [130, 60], [100, 60]]; \
             const boxes = d.labelCorners(c.getContext('2d'), { X: p => p[0], Y: p => p[1] }, pts, [0, 1, 2, 3], size); \
             const all = [...boxes, ...pts.map(([x, y]) => ({ x: x - r, y: y - r, w: 2 * r, h: 2 * r }))]; \
             const hit = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h; \
             done(boxes.length === 4 ? boxes.flatMap((b, i) => all.filter((o, j) => j !== i && hit(b, o)).map(o => `label ${i + 1} over ${JSON.stringify(o)}`)) : ['no boxes']); \
             }).catch(e => done([String(e)]))",
            vec![],
        )
        .await
        .expect("label corners");
    assert_eq!(overlaps, json!([]), "corner labels overlap");
    violations
        .extend(axe_violations(&client, &axe).await.into_iter().map(|v| format!("plan: {v}")));
    // The goal the cloth is already in: nothing to do.
    js(&client, "document.getElementById('plan-sample').value = 'upload:' + window.closeApp.store.get().uploads.find(u => u.name === 'my-napkin.json').key; document.getElementById('plan-sample').dispatchEvent(new Event('change'))").await;
    until(
        &client,
        "the upload's state",
        "document.getElementById('plan-now').textContent.includes('my-napkin.json')",
    )
    .await;
    js(&client, "for (const [id, v] of [['goal-1', 45], ['goal-2', 225]]) { const i = document.getElementById(id); i.value = v; i.dispatchEvent(new Event('change')); }").await;
    client.find(Locator::Id("plan-run")).await.expect("plan").click().await.expect("click");
    until(
        &client,
        "already there",
        "document.getElementById('plan-case').textContent.includes('already folded')",
    )
    .await;
    assert_eq!(
        js(&client, "return document.querySelectorAll('#plan-list .plan-step').length").await,
        json!(1),
        "only the current state is drawn"
    );
    // The upload is listed by its file name.
    let options = text(
        &client,
        "[...document.getElementById('plan-sample').options].map(o => o.textContent).join('|')",
    )
    .await;
    assert!(options.contains("upload · my-napkin.json"), "{options}");
    // The plan downloads as JSON (issue 19, item 9).
    let plan_json = client.execute_async("const a = document.getElementById('plan-json'); fetch(a.href).then(r => r.json()).then(j => arguments[0]([a.hidden, a.download, j.steps.length])).catch(e => arguments[0](String(e)))", vec![]).await.expect("plan JSON");
    assert!(
        plan_json[0] == json!(false)
            && plan_json[1].as_str().is_some_and(|d| d.ends_with(".json"))
            && plan_json[2] == json!(0),
        "the plan shown (already there: no step) is the one downloaded: {plan_json}"
    );
    // A concave cloth (issue 28 item 3): the T-shirt planned to its default goal, each step
    // drawn whole inside its picture — nothing of the cloth, a fold line or an arrow in the
    // picture's outer frame.
    route(&client, "#/plan?cloth=sample:tshirt__sleeve_left").await;
    until(
        &client,
        "the T-shirt in Plan",
        "document.getElementById('plan-now').textContent.includes('sleeve_left')",
    )
    .await;
    client.find(Locator::Id("plan-run")).await.expect("plan").click().await.expect("click");
    until(
        &client,
        "the T-shirt's plan",
        "document.querySelectorAll('#plan-list .plan-step').length >= 2",
    )
    .await;
    let spilled = js(&client, "return [...document.querySelectorAll('#plan-list canvas')].flatMap((c, k) => { \
                               const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data, frame = 2, out = []; \
                               for (let y = 0; y < c.height; y++) for (let x = 0; x < c.width; x++) { \
                                 if (x >= frame && x < c.width - frame && y >= frame && y < c.height - frame) continue; \
                                 const i = 4 * (y * c.width + x); if (d[i + 3] > 0 && Math.max(d[i], d[i + 1], d[i + 2]) - Math.min(d[i], d[i + 1], d[i + 2]) > 40) out.push(`(${x}, ${y}) rgba(${d.slice(i, i + 4)})`); } \
                               return out.length ? [`picture ${k}: ${out.length} coloured pixels on its edge: ${out.slice(0, 4).join(', ')}`] : []; })").await;
    screenshot(&client, &shots, "1400-07b-plan-tshirt.png").await;
    assert_eq!(spilled, json!([]), "a plan step of the T-shirt spills off its picture");
    // Its default goal folds it in half along its axis: from the hem's middle to the neck's.
    let last =
        text(&client, "[...document.querySelectorAll('#plan-list .plan-step')].pop().innerText")
            .await;
    assert!(last.contains("Fold along (0.0°, 180.0°)"), "the T-shirt's default goal: {last}");
    // The preview follows the goal as it moves, before any plan is asked for.
    let shown = until(&client, "the T-shirt's goal previewed", "document.getElementById('plan-preview').getAttribute('aria-label').includes('(0.0°, 180.0°)') && document.getElementById('plan-preview').toDataURL()").await;
    js(&client, "const i = document.getElementById('goal-1'); i.value = 90; i.dispatchEvent(new Event('change'))").await;
    let moved = until(&client, "the moved goal previewed", "document.getElementById('plan-preview').getAttribute('aria-label').includes('(90.0°, 180.0°)') && document.getElementById('plan-preview').toDataURL()").await;
    assert_ne!(shown, moved, "the preview did not follow the goal");
    assert!(pictures_have_ink(&client, "#view-plan").await >= 2);

    console_clean(&client, "plan", &[]).await;

    // ---- Every picture downloads as PNG and SVG, the analysis as JSON; "use from code"
    // gives calls that return the same analysis (items 9 and 11).
    route(&client, &format!("#/samples/{}", twice.id)).await;
    shows_sample(&client, &twice.sample.name).await;
    let fetched = |selector: &str| {
        format!("const a = document.querySelector({selector:?}); fetch(a.href).then(r => r.text().then(t => arguments[0]([r.headers.get('content-type'), t.slice(0, 5), a.download]))).catch(e => arguments[0](String(e)))")
    };
    for (selector, kind, head) in [
        ("#browse-result a.download[data-format=svg]", "image/svg+xml", "<svg "),
        ("#browse-result a.download[data-format=png]", "image/png", "\u{fffd}PNG\r"),
    ] {
        let got = client.execute_async(&fetched(selector), vec![]).await.expect("a download");
        assert_eq!(got[0], json!(kind), "{selector}: {got}");
        assert!(got[2].as_str().is_some_and(|d| d.ends_with(&kind[6..9])), "{selector}: {got}");
        if kind.ends_with("xml") {
            assert_eq!(got[1], json!(head));
        }
    }
    let links = js(&client, "return [...document.querySelectorAll('#browse-result figure')].map(f => f.querySelectorAll('a.download').length)").await;
    assert!(
        links.as_array().is_some_and(|l| l.len() == 6 && l.iter().all(|n| n == 3)),
        "every picture has screen PNG, print PNG and SVG links: {links}"
    );
    // Item 10: the print PNG states its resolution (pHYs: 300 dpi is 11811 pixels per metre),
    // and the border plot's SVG is vector through and through (no embedded raster).
    let print = client.execute_async("const a = document.querySelector('#browse-result a.download[data-format=png-print]'); fetch(a.href).then(r => r.arrayBuffer()).then(b => { const d = new DataView(b); const at = new Uint8Array(b).findIndex((c, i, u) => u[i] === 0x70 && u[i+1] === 0x48 && u[i+2] === 0x59 && u[i+3] === 0x73); arguments[0]([d.getUint32(16), at < 0 ? null : d.getUint32(at + 4)]); }).catch(e => arguments[0](String(e)))", vec![]).await.expect("the print PNG");
    assert_eq!(print, json!([2048, 11811]), "print PNG: [width, pixels per metre]");
    let borders_svg = client.execute_async("const a = [...document.querySelectorAll('#browse-result figure img')].find(i => i.dataset.picture === 'borders').closest('figure').querySelector('a.download[data-format=svg]'); fetch(a.href).then(r => r.text()).then(t => arguments[0]([t.includes('<image'), (t.match(/<text/g) || []).length, t.includes('>-0.0<') || t.includes('>-0<')])).catch(e => arguments[0](String(e)))", vec![]).await.expect("the border plot's SVG");
    assert_eq!(
        borders_svg[0],
        json!(false),
        "the border plot's SVG embeds no raster: {borders_svg}"
    );
    assert!(
        borders_svg[1].as_u64().is_some_and(|n| n >= 8),
        "its ticks and legend are text: {borders_svg}"
    );
    assert_eq!(borders_svg[2], json!(false), "no tick reads -0: {borders_svg}");
    let label_shown =
        text(&client, "document.querySelector('#browse-result .result-label').textContent").await;
    let analysis = client.execute_async("fetch(document.querySelector('#browse-result a.download-analysis').href).then(r => r.json()).then(j => arguments[0](j.label.text))", vec![]).await.expect("analysis JSON");
    assert_eq!(analysis, json!(label_shown));
    // Issue 28 item 9: every snippet shown runs, from a shell and from Python.
    run_snippets(&client, "#browse-result", &scratch, &label_shown).await;

    console_clean(&client, "downloads and snippets", &[]).await;

    // ---- State in the URL (item 10): the step, Interpolate's cloth, step, folds and t,
    // Plan's goal; a reload shows the same.
    js(
        &client,
        "document.querySelector('#browse-result .segmented input[data-step=\"2\"]').click()",
    )
    .await;
    until(&client, "the step in the URL", "location.hash.endsWith('?step=2')").await;
    client.refresh().await.expect("reload");
    shows_sample(&client, &twice.sample.name).await;
    until(
        &client,
        "step 2 after the reload",
        "document.querySelector('#browse-result .segmented input:checked')?.dataset.step === '2'",
    )
    .await;
    route(&client, "#/interpolate?cloth=sample:tshirt__sleeve_left&step=1&t=0.400").await;
    until(&client, "the linked cloth", "document.getElementById('interp-sample').value === 'sample:tshirt__sleeve_left' && Math.abs(window.closeApp.interpolate.state().tau - 0.4) < 1e-9").await;
    js(&client, "window.closeApp.interpolate.setTau(0.25)").await;
    until(&client, "t in the URL", "location.hash.includes('t=0.250') && location.hash.includes('cloth=sample%3Atshirt__sleeve_left')").await;
    let folds = js(&client, "return window.closeApp.interpolate.state().to").await;
    client.refresh().await.expect("reload");
    until(&client, "the same state after a reload", "document.getElementById('interp-sample').value === 'sample:tshirt__sleeve_left' && Math.abs(window.closeApp.interpolate.state().tau - 0.25) < 1e-9").await;
    let again = js(&client, "return window.closeApp.interpolate.state().to").await;
    let close_to = |a: &Value, b: &Value| {
        (0..2).all(|k| {
            (a[k].as_f64().unwrap_or(f64::NAN) - b[k].as_f64().unwrap_or(0.0)).abs() < 1e-5
        })
    };
    assert!(close_to(&folds, &again), "{folds} → {again}");
    // A fold from flat turns its flap about its line (issue 28 item 4): over the whole
    // motion, no frame moves a vertex more than twice the mean of the frames' largest moves.
    route(&client, "#/interpolate?cloth=sample:trousers__legs_up_then_half&step=1&t=0").await;
    until(&client, "the trousers from flat", "document.getElementById('interp-sample').value === 'sample:trousers__legs_up_then_half' && window.closeApp.interpolate.state().frame?.t === 0").await;
    let mut frames: Vec<Vec<Vec<f64>>> = Vec::new();
    for k in 0..=50 {
        let t = f64::from(k) / 50.0;
        js(&client, &format!("window.closeApp.interpolate.setTau({t})")).await;
        let drawn = until(&client, &format!("the state at t = {t}"), &format!("(s => s.frame && Math.abs(s.frame.t - {t}) < 1e-12 && s.drawn)(window.closeApp.interpolate.state())")).await;
        frames.push(serde_json::from_value(drawn).expect("a drawn border"));
    }
    let moves: Vec<f64> = frames
        .windows(2)
        .map(|w| {
            w[0].iter()
                .zip(&w[1])
                .map(|(p, q)| p.iter().zip(q).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt())
                .fold(0.0, f64::max)
        })
        .collect();
    let mean = moves.iter().sum::<f64>() / moves.len() as f64;
    let largest = moves.iter().copied().fold(0.0, f64::max);
    assert!(
        mean > 0.0 && largest <= 2.0 * mean,
        "a vertex jumps: largest move per frame {largest:.4}, mean {mean:.4} ({moves:.4?})"
    );
    // Back from Interpolate to a sample: the title names the sample again.
    route(&client, &format!("#/samples/{}", twice.id)).await;
    shows_sample(&client, &twice.sample.name).await;
    route(&client, "#/interpolate").await;
    until(&client, "interpolate", "!document.getElementById('view-interpolate').hidden").await;
    client.back().await.expect("back");
    shows_sample(&client, &twice.sample.name).await;
    tokio::time::sleep(Duration::from_millis(800)).await;
    let title = text(&client, "document.title").await;
    assert!(title.contains(&twice.sample.name) && !title.contains("Interpolate"), "{title}");
    route(&client, "#/plan?cloth=sample:napkin__half_vertical&goal=0.500000,3.600000").await;
    until(&client, "the linked goal", "document.getElementById('plan-sample').value === 'sample:napkin__half_vertical' && Math.abs(parseFloat(document.getElementById('goal-1').value) - 28.65) < 0.1").await;

    console_clean(&client, "state in the URL", &[]).await;

    // ---- Compare (item 15): two states on one colour scale, and a frame scrubber.
    route(&client, &format!("#/compare/{0}@1/{0}", twice.id)).await;
    until(
        &client,
        "the compared states",
        "document.querySelectorAll('#compare-result .compare-panels img').length === 6 && document.querySelector('#compare-result .compare-borders')",
    )
    .await;
    images_loaded(&client, "#compare-result img").await;
    let scales = js(&client, "return [...document.querySelectorAll('#compare-result .compare-panels')].map(p => [...p.querySelectorAll('img[data-picture=disk]')].map(i => i.dataset.scale))").await;
    let shared = |k: usize| {
        scales[k].as_array().is_some_and(|s| {
            s.iter().all(|v| v == &s[0] && v.as_str().is_some_and(|t| !t.is_empty()))
        })
    };
    assert!(shared(0) && shared(1), "the panels do not share one colour scale: {scales}");
    assert!(pictures_have_ink(&client, "#compare-result").await >= 7);
    let captions = text(&client, "[...document.querySelectorAll('#compare-result figcaption')].map(f => f.textContent).join('|')").await;
    assert!(
        captions.contains("after step 1 of 2")
            && captions.contains("after step 2 of 2")
            && captions.contains("predicted frame 1"),
        "{captions}"
    );
    assert!(text(&client, "document.title").await.contains("Compare"));
    screenshot(&client, &shots, "1400-09-compare.png").await;
    violations
        .extend(axe_violations(&client, &axe).await.into_iter().map(|v| format!("compare: {v}")));
    violations.extend(disk_readout(&client, &base, &shots, &axe).await);

    console_clean(&client, "compare and the disk readout", &[]).await;

    // ---- The user's own dataset (items 1–3): listed with thumbnails and provenance, second
    // folds filed as such, opened, planned like a built-in sample.
    let q3 = "d0-q3_napkin_half_then_quarter_31x31";
    goto_view(&client, &with_dataset, &format!("#/samples/{q3}")).await;
    shows_sample(&client, "q3_napkin_half_then_quarter_31x31").await;
    let meta =
        text(&client, "document.querySelector('#browse-result .result-meta').textContent").await;
    assert!(
        meta.starts_with(&format!("dataset {}", own.display()))
            && meta.contains("napkin_second_fold"),
        "{meta}"
    );
    assert!(text(&client, "document.querySelector('#browse-result .close-table').innerText")
        .await
        .contains("true fold 2"));
    // The whole span of a sequence draws no curve and says so.
    js(
        &client,
        "document.querySelector('#browse-result .segmented input[data-step=\"0\"]').click()",
    )
    .await;
    until(&client, "the whole span's caption", "[...document.querySelectorAll('#browse-result figcaption')].some(f => f.textContent.startsWith('|diff| (the fold curves: see each step)'))").await;
    let card = until(&client, "the dataset card in its category", &format!("document.querySelector('.sample-card[data-id=\"{q3}\"]')?.closest('details').querySelector('summary').textContent")).await;
    assert!(card.as_str().unwrap_or_default().starts_with("napkin_second_fold"), "{card}");
    until(&client, "the open card in view", &format!("(r => r.top >= 0 && r.bottom <= window.innerHeight)(document.querySelector('.sample-card[data-id=\"{q3}\"]').getBoundingClientRect())")).await;
    images_loaded(&client, &format!(".sample-card[data-id=\"{q3}\"] img")).await;
    // Every dataset card's thumbnail is a picture (the ones out of sight load lazily).
    let statuses = client.execute_async("Promise.all([...document.querySelectorAll('.sample-card[data-source]:not([data-source=builtin]) img')].map(i => fetch(i.src).then(r => r.status + ' ' + r.headers.get('content-type')))).then(arguments[0])", vec![]).await.expect("thumbnails");
    assert_eq!(statuses, json!(["200 image/png", "200 image/png"]));
    let missing = js(&client, "return performance.getEntriesByType('resource').map(r => r.name).filter(n => n.includes('undefined'))").await;
    assert_eq!(missing, json!([]), "requests for missing pictures");
    assert!(text(&client, "document.querySelector('.sample-card[data-source]:not([data-source=builtin]) .card-meta').textContent").await.contains("dataset own-dataset"));
    screenshot(&client, &shots, "1400-10-own-dataset.png").await;
    violations.extend(
        axe_violations(&client, &axe).await.into_iter().map(|v| format!("own dataset: {v}")),
    );
    js(&client, "document.querySelector('#browse-result .plan-this').click()").await;
    until(&client, "the plan view", "location.hash.startsWith('#/plan') && document.getElementById('plan-sample').value === 'sample:d0-q3_napkin_half_then_quarter_31x31'").await;
    until(&client, "its state", "document.getElementById('plan-now').textContent.includes('now')")
        .await;
    client.find(Locator::Id("plan-run")).await.expect("plan").click().await.expect("click");
    until(
        &client,
        "a plan for the dataset sample",
        "/\\d+ steps? ·/.test(document.getElementById('plan-case').textContent)",
    )
    .await;
    assert!(
        js(&client, "return document.getElementById('error').hidden")
            .await
            .as_bool()
            .unwrap_or(false),
        "{}",
        text(&client, "document.getElementById('error').textContent").await
    );
    goto_view(&client, &base, &format!("#/samples/{}", twice.id)).await;
    shows_sample(&client, &twice.sample.name).await;

    console_clean(&client, "the user's own dataset", &[]).await;

    // Keyboard (issue 28 item 12): the first Tab reaches the skip link, which takes the focus
    // to the view; the list comes before the result, a few Tabs from the top.
    // From a fresh page: the focus starts at its top.
    let fresh = async || {
        client.refresh().await.expect("reload");
        shows_sample(&client, &twice.sample.name).await;
    };
    let tabs_to_a_card = async || {
        fresh().await;
        let mut tabs = 0;
        loop {
            client.active_element().await.expect("focus").send_keys("\u{E004}").await.expect("Tab");
            tabs += 1;
            let on_card =
                js(&client, "return document.activeElement?.classList.contains('sample-card')")
                    .await;
            if on_card == json!(true) || tabs >= 60 {
                return tabs;
            }
        }
    };
    let tabs = tabs_to_a_card().await;
    assert!(tabs <= 12, "{tabs} Tabs to the first sample card");
    fresh().await;
    client.active_element().await.expect("focus").send_keys("\u{E004}").await.expect("Tab");
    assert_eq!(js(&client, "return document.activeElement?.className").await, json!("skip-link"));
    client.active_element().await.expect("focus").send_keys("\u{E007}").await.expect("Enter");
    let focused = js(&client, "return document.activeElement?.id").await;
    assert_eq!(focused, json!("sample-filter"), "the skip link leads to the view's first control");

    console_clean(&client, "keyboard", &[]).await;

    // ---- Phone width: no overflow, the list first in a box of its own and the result right
    // under it, the plan's controls above its results.
    client.set_window_size(420, 900).await.expect("phone size");
    until(&client, "a narrow window", "window.innerWidth <= 420").await;
    route(&client, "#/samples/napkin__half_then_half").await;
    shows_sample(&client, &twice.sample.name).await;
    let order = js(&client, "window.scrollTo(0, 0); const [list, result] = [document.querySelector('.sample-panel'), document.getElementById('browse-result')].map(e => e.getBoundingClientRect()); \
                             return [list.top < result.top, result.top + window.scrollY, window.innerHeight]").await;
    assert_eq!(order[0], json!(true), "the list is not above the result");
    assert!(
        order[1].as_f64().unwrap_or(f64::MAX) < order[2].as_f64().unwrap_or(0.0),
        "the result starts {} px down a {} px window",
        order[1],
        order[2]
    );
    let tabs = tabs_to_a_card().await;
    assert!(tabs <= 12, "420 px: {tabs} Tabs to the first sample card");
    assert_no_overflow(&client, "browse").await;
    screenshot(&client, &shots, "420-01-browse.png").await;
    violations.extend(
        axe_violations(&client, &axe).await.into_iter().map(|v| format!("browse 420: {v}")),
    );
    // Tapping a card far down brings its result into view.
    js(
        &client,
        "document.querySelector('.sample-card[data-id=\"towel__half_long\"]').scrollIntoView()",
    )
    .await;
    client
        .find(Locator::Css(".sample-card[data-id=\"towel__half_long\"]"))
        .await
        .expect("a card")
        .click()
        .await
        .expect("tap");
    shows_sample(&client, &dataset.get("towel__half_long").expect("sample").sample.name).await;
    let top = until(&client, "the result in view", "(t => t > -50 && t < 300 && t + 1)(document.getElementById('browse-result').getBoundingClientRect().top)").await;
    assert!(top.as_f64().is_some(), "result at {top}");
    for (hash, name) in
        [("#/upload", "upload"), ("#/interpolate", "interpolate"), ("#/plan", "plan")]
    {
        route(&client, hash).await;
        until(&client, name, &format!("!document.getElementById('view-{name}').hidden")).await;
        tokio::time::sleep(Duration::from_millis(500)).await;
        assert_no_overflow(&client, name).await;
        if name == "interpolate" {
            disk_picture(&client).await;
            // The canvas is shrunk to the phone's width: its labels are sized for that.
            let shown = js(&client, "const c = document.getElementById('interp-canvas'); return parseFloat(c.getContext('2d').font) * c.getBoundingClientRect().width / c.width").await;
            assert!(
                shown.as_f64().is_some_and(|px| px >= 11.0),
                "corner labels {shown} CSS px tall"
            );
        }
        assert_eq!(wrapped_box_names(&client).await, json!([]), "{name} 420: fold box names wrap");
        if name == "plan" {
            assert_eq!(
                small_plan_labels(&client).await,
                json!([]),
                "plan 420: corner labels below 11 CSS px"
            );
        }
        screenshot(
            &client,
            &shots,
            &format!(
                "420-0{}-{name}.png",
                2 + ["upload", "interpolate", "plan"].iter().position(|n| *n == name).unwrap_or(0)
            ),
        )
        .await;
        violations.extend(
            axe_violations(&client, &axe).await.into_iter().map(|v| format!("{name} 420: {v}")),
        );
    }
    let order = js(&client, "return document.querySelector('.plan-side').getBoundingClientRect().top < document.querySelector('.plan-main').getBoundingClientRect().top").await;
    assert_eq!(order, json!(true), "the plan's controls are below its results");
    route(&client, &format!("#/compare/{0}@1/{0}", twice.id)).await;
    until(
        &client,
        "the compared states",
        "document.querySelectorAll('#compare-result .compare-panels img').length === 6 && document.querySelector('#compare-result .compare-borders')",
    )
    .await;
    images_loaded(&client, "#compare-result img").await;
    assert_no_overflow(&client, "compare").await;
    screenshot(&client, &shots, "420-05-compare.png").await;
    violations.extend(
        axe_violations(&client, &axe).await.into_iter().map(|v| format!("compare 420: {v}")),
    );

    console_clean(&client, "phone width", &[]).await;

    // ---- Five thousand samples: the list stays paged, the filter finds any of them.
    goto_view(&client, &many, "").await;
    until(
        &client,
        "the long list",
        "document.getElementById('sample-count').textContent.startsWith('5000 of 5000')",
    )
    .await;
    let cards = js(&client, "return document.querySelectorAll('.sample-card').length")
        .await
        .as_u64()
        .unwrap_or(0);
    assert!(cards > 0 && cards <= 3 * 24, "{cards} cards drawn for 5000 samples");
    js(&client, "document.querySelector('.category .more').click()").await;
    until(
        &client,
        "more cards",
        &format!("document.querySelectorAll('.sample-card').length > {cards}"),
    )
    .await;
    js(&client, "const f = document.getElementById('sample-filter'); f.value = 'user 4321'; f.dispatchEvent(new Event('input'))").await;
    until(&client, "one match", "document.getElementById('sample-count').textContent.startsWith('1 of 5000') && document.querySelectorAll('.sample-card').length === 1").await;

    console_clean(&client, "five thousand samples", &[]).await;

    // ---- The sample list fails: a readable message that survives a change of view.
    client.set_window_size(1400, 1000).await.expect("wide again");
    goto_view(&client, &broken, "").await;
    let error = until(&client, "the list's error", "document.getElementById('sample-list').textContent.includes('could not be loaded') && document.getElementById('sample-list').textContent").await;
    let error = error.as_str().unwrap_or_default();
    assert!(
        error.contains("503 Service Unavailable upstream down") && !error.contains("<h1>"),
        "{error}"
    );
    route(&client, "#/interpolate").await;
    let error = until(
        &client,
        "the message in Interpolate",
        "!document.getElementById('error').hidden && document.getElementById('error').textContent",
    )
    .await;
    assert!(error.as_str().unwrap_or_default().contains("could not be loaded"), "{error}");
    screenshot(&client, &shots, "1400-08-samples-failed.png").await;
    console_clean(
        &client,
        "the sample list fails",
        &["/api/samples - Failed to load resource: the server responded with a status of 503"],
    )
    .await;

    mesh_picture_shows_and_pictures_are_legible(&client, &base, &shots).await;
    console_clean(&client, "mesh picture", &[]).await;
    drag_follows_the_pointer(&client, &base, &scratch, &shots).await;
    console_clean(&client, "drag", &[]).await;
    unequal_cloths_compare_without_asking(&client, &base, &shots).await;
    violations.extend(missing_cloths_are_said(&client, &base, &scratch, &shots, &axe).await);
    uploads_outlive_a_reload_and_a_restart(&client, &scratch).await;

    client.close().await.expect("end the session");
    let _ = std::fs::remove_dir_all(&scratch);
    assert!(
        violations.is_empty(),
        "axe-core found serious or critical violations:\n{}",
        violations.join("\n")
    );
}

/// The picture pixel (480 px picture) at the middle of disk cell (i, j), and the cell the
/// server paints there: (ring d, first edge a), by its own rule (`sector_at`).
fn cell_pixel(n: usize, (i, j): (usize, usize)) -> ((f64, f64), (usize, usize)) {
    let layout = close::render::disk_picture::Layout::of(480, 480);
    let cell = close::disk::position(n, i, j);
    let (x, y) = layout.pixel(cell.radius - 0.5 / (n / 2) as f64, cell.angle);
    let (dx, dy) = (x + 0.5 - layout.cx, layout.cy - (y + 0.5));
    let painted = close::render::disk_picture::sector_at(
        n,
        dx.hypot(dy) / layout.radius,
        dy.atan2(dx).rem_euclid(std::f64::consts::TAU),
    );
    ((x, y), painted)
}

/// The pair of the largest |value| of `values` (condensed, pairs i < j row-major).
fn largest_pair(n: usize, values: impl Fn(usize, usize) -> f64) -> (usize, usize) {
    let pairs = (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j)));
    pairs.max_by(|a, b| values(a.0, a.1).abs().total_cmp(&values(b.0, b.1).abs())).unwrap_or((0, 1))
}

/// Move the mouse (or tap, with `touch`) over picture pixel `at` of the 480 px picture
/// `selector`, scrolled into the middle of the window first.
async fn point_at(client: &Client, selector: &str, (x, y): (f64, f64), touch: bool) {
    use fantoccini::actions::{
        InputSource, MouseActions, PointerAction, TouchActions, MOUSE_BUTTON_LEFT,
    };
    let rect = js(client, &format!("const i = document.querySelector({selector:?}); i.scrollIntoView({{ block: 'center' }}); const r = i.getBoundingClientRect(); return [r.left, r.top, r.width, r.height]")).await;
    let f = |k: usize| rect[k].as_f64().unwrap_or(0.0);
    let (cx, cy) =
        ((f(0) + (x + 0.5) * f(2) / 480.0).round(), (f(1) + (y + 0.5) * f(3) / 480.0).round());
    let to = PointerAction::MoveTo { duration: None, x: cx, y: cy };
    if touch {
        let tap = TouchActions::new("finger".into())
            .then(to)
            .then(PointerAction::Down { button: MOUSE_BUTTON_LEFT })
            .then(PointerAction::Up { button: MOUSE_BUTTON_LEFT });
        client.perform_actions(tap).await.expect("tap");
    } else {
        client
            .perform_actions(MouseActions::new("mouse".into()).then(to))
            .await
            .expect("move the mouse");
    }
}

/// The readout under a disk picture once it names cell (a, a + d): its text and its value.
async fn readout_of(
    client: &Client,
    figure: &str,
    n: usize,
    (d, a): (usize, usize),
) -> (String, f64) {
    let want = format!("edges i = {a}, j = {} · d = {d} ·", (a + d) % n);
    let got = until(client, &format!("the readout of {want}"), &format!("(o => o.textContent.startsWith({want:?}) && [o.textContent, Number(o.dataset.value)])(document.querySelector({:?}))", format!("{figure} .cell-readout"))).await;
    (got[0].as_str().unwrap_or_default().to_string(), got[1].as_f64().unwrap_or(f64::NAN))
}

/// Whether pixel (x, y) of the canvas `selector` has ink (alpha > 0).
async fn inked(client: &Client, selector: &str, (x, y): (f64, f64)) -> bool {
    js(client, &format!("return {COPY}(document.querySelector({selector:?})).getImageData({}, {}, 1, 1).data[3] > 0", x.round(), y.round())).await.as_bool().unwrap_or(false)
}

/// A function of a canvas giving a 2D context on a copy of it, to read its pixels: a canvas
/// of the app read back again and again would make the browser warn about it.
const COPY: &str = "(c => { const t = document.createElement('canvas'); t.width = c.width; t.height = c.height; \
                    const g = t.getContext('2d', { willReadFrequently: true }); g.drawImage(c, 0, 0); return g; })";

/// Issue 19, item 5: hovering, tapping or arrowing over a disk cell (Browse and
/// Interpolate) names its edges i and j, their distance d and the value the analysis has
/// there (for a diff also its start and end), outlines it, and marks the two edges on the
/// border plot; item 15: Compare's predicted frame is the analysis's own; Plan's arrows
/// stand off the cloth's edges. Screenshots at 1400 and 420 px. Gives axe's serious or
/// critical violations.
async fn disk_readout(client: &Client, base: &str, shots: &Path, axe: &str) -> Vec<String> {
    let mut violations = Vec::new();
    let (entry, analysis) = crate::common::builtin().analysed("napkin__half_then_half");
    let n = analysis.n;
    // Step 2: analysed frames 1 → 2; the cell that changed most.
    let (before, after) = (analysis.disk(1).expect("frame 1"), analysis.disk(2).expect("frame 2"));
    let delta = |i: usize, j: usize| after.get(i, j) - before.get(i, j);
    let ((x, y), (d, a)) = cell_pixel(n, largest_pair(n, delta));
    let b = (a + d) % n;
    goto_view(client, base, &format!("#/samples/{}?step=2", entry.id)).await;
    shows_sample(client, &entry.sample.name).await;
    until(client, "step 2's pictures", "[...document.querySelectorAll('#browse-result .step-pictures img')].every(i => i.src.includes('step=2'))").await;
    images_loaded(client, "#browse-result .step-pictures img").await;
    let signed = "#browse-result .step-pictures figure:nth-child(4)";
    point_at(client, &format!("{signed} img"), (x, y), false).await;
    let (text, value) = readout_of(client, signed, n, (d, a)).await;
    assert!(
        (value - delta(a, b)).abs() <= 1e-5 * delta(a, b).abs().max(1e-3),
        "{text}: the analysis has Δ = {}",
        delta(a, b)
    );
    assert!(
        text.contains("start") && text.contains("end"),
        "a diff's readout gives its start and end values: {text}"
    );
    // The cell is outlined: ink on its outer arc's middle.
    let layout = close::render::disk_picture::Layout::of(480, 480);
    let l = (n / 2) as f64;
    let theta = std::f64::consts::PI * (2 * a + d + 1) as f64 / n as f64;
    assert!(
        inked(
            client,
            &format!("{signed} canvas.cell-mark"),
            layout.pixel((l - d as f64 + 1.0) / l, theta)
        )
        .await,
        "the cell is not outlined"
    );
    // Its two edges are marked on the border plot of step 2 (issue 28 item 5: it follows the
    // step), on that step's start and end borders, and nowhere else.
    let truth =
        entry.sample.truth.as_ref().map(close::render::truth::Truth::of).unwrap_or_default();
    let plot = close::render::readout::PlotTransform::of_borders(analysis, &truth, Some(2), 480)
        .expect("the plot's map");
    let mid = |border: &[close::border::Point], e: usize| {
        let (p, q) = (border[e], border[(e + 1) % n]);
        (plot.x[0] * (p.x + q.x) / 2.0 + plot.x[1], plot.y[0] * (p.y + q.y) / 2.0 + plot.y[1])
    };
    until(
        client,
        "the plot of step 2",
        "document.querySelector('#browse-result .instrument-borders img').src.includes('step=2')",
    )
    .await;
    for border in [&analysis.frames[1], &analysis.frames[2]] {
        for e in [a, b] {
            assert!(
                inked(client, "#browse-result canvas.edge-mark", mid(border, e)).await,
                "edge {e} is not marked at {:?}",
                mid(border, e)
            );
        }
    }
    assert!(
        !inked(client, "#browse-result canvas.edge-mark", (2.0, 2.0)).await,
        "the plot's corner is marked"
    );
    // The arrow keys move the cell: left turns anticlockwise (edge a + 1), down goes inwards.
    js(client, &format!("document.querySelector({:?}).focus()", format!("{signed} .zoom"))).await;
    let keys = client.active_element().await.expect("the focused picture");
    keys.send_keys("\u{E012}").await.expect("arrow left");
    let (_, value) = readout_of(client, signed, n, (d, (a + 1) % n)).await;
    let want = delta((a + 1) % n, (a + 1 + d) % n);
    assert!(
        (value - want).abs() <= 1e-5 * want.abs().max(1e-3),
        "after ArrowLeft: {value}, the analysis has {want}"
    );
    keys.send_keys("\u{E015}").await.expect("arrow down");
    readout_of(client, signed, n, ((d + 1).min(n / 2), (a + 1) % n)).await;
    keys.send_keys("\u{E013}").await.expect("arrow up");
    readout_of(client, signed, n, (d, (a + 1) % n)).await;
    screenshot(client, shots, "1400-11-disk-readout.png").await;
    violations.extend(
        axe_violations(client, axe).await.into_iter().map(|v| format!("disk readout: {v}")),
    );
    // A tap on the start disk reads its value; it does not open the full-resolution view.
    let start_fig = "#browse-result .step-pictures figure:nth-child(1)";
    let ((x, y), (d1, a1)) = cell_pixel(n, largest_pair(n, |i, j| before.get(i, j)));
    point_at(client, &format!("{start_fig} img"), (x, y), true).await;
    let (text, value) = readout_of(client, start_fig, n, (d1, a1)).await;
    let want = before.get(a1, (a1 + d1) % n);
    assert!(
        (value - want).abs() <= 1e-5 * want.abs().max(1e-3) && !text.contains("start"),
        "{text}: the analysis has {want}"
    );
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!(
        js(client, "return document.getElementById('lightbox').open").await,
        json!(false),
        "a tap on a cell opened the lightbox"
    );

    // Interpolate: the disk of the state drawn, its cells' edges marked on the cloth.
    route(client, &format!("#/interpolate?cloth=sample:{}&step=1&t=1.000", entry.id)).await;
    until(client, "the cloth", &format!("document.getElementById('interp-sample').value === 'sample:{}' && window.closeApp.interpolate.state().tau === 1", entry.id)).await;
    disk_picture(client).await;
    // The disk is of the state drawn with its layers at their heights (the server's), as sent for its disk.
    let drawn: Vec<[f64; 3]> =
        serde_json::from_value(js(client, "return window.closeApp.interpolate.state().disk").await)
            .expect("the drawn border");
    let flat: Vec<[f64; 3]> = analysis.start_border().iter().map(close::border::to_xyz).collect();
    let state = close::disk::of_state(drawn, Some(flat), &close::budget::Deadline::default())
        .expect("the state's disk");
    let ((x, y), (d, a)) = cell_pixel(n, largest_pair(n, |i, j| state.get(i, j)));
    point_at(client, "#interp-disk", (x, y), false).await;
    let (_, value) = readout_of(client, ".interp-disk", n, (d, a)).await;
    let want = state.get(a, (a + d) % n);
    assert!(
        (value - want).abs() <= 1e-5 * want.abs().max(1e-3),
        "the state's disk has {want}, the readout {value}"
    );
    let cell = js(client, "return window.closeApp.interpolate.state().cell").await;
    assert_eq!(
        (cell["i"].as_u64(), cell["j"].as_u64()),
        (Some(a as u64), Some(((a + d) % n) as u64))
    );
    let marked = js(client, &format!("const c = document.getElementById('interp-canvas'), d = {COPY}(c).getImageData(0, 0, c.width, c.height).data; let k = 0; \
                             for (let p = 0; p < d.length; p += 4) if (Math.abs(d[p] - 0xd8) < 8 && Math.abs(d[p + 1] - 0x1b) < 8 && Math.abs(d[p + 2] - 0x60) < 8) k++; return k")).await;
    assert!(marked.as_u64().unwrap_or(0) > 20, "edge i is not marked on the cloth ({marked} px)");

    // Compare's scrubber: the predicted frame k is the analysis's prediction for step k.
    js(client, "window.diskBodies = []; window.realFetch = window.fetch; window.fetch = (u, o) => { \
                if (String(u).endsWith('/api/disk') && o && o.body) window.diskBodies.push(JSON.parse(o.body)); return window.realFetch(u, o); }").await;
    // The earlier comparison's panels go first: the ones waited for are this one's.
    js(client, "document.getElementById('compare-result').replaceChildren()").await;
    route(client, &format!("#/compare/{0}@1/{0}", entry.id)).await;
    until(client, "the scrubber", "document.querySelectorAll('#compare-result .scrubber img').length === 3 && document.querySelector('#compare-result .scrubber input')").await;
    js(client, "const s = document.querySelector('#compare-result .scrubber input'); s.value = 2; s.dispatchEvent(new Event('input'))").await;
    until(client, "step 2 in the scrubber", "document.querySelector('#compare-result .scrubber figcaption:last-of-type') && [...document.querySelectorAll('#compare-result .scrubber figcaption')].some(f => f.textContent.startsWith('predicted frame 2'))").await;
    let bodies = js(client, "return window.diskBodies.map(b => b.border)").await;
    js(client, "window.fetch = window.realFetch").await;
    let sent: Vec<Vec<[f64; 3]>> = serde_json::from_value(bodies).expect("borders sent");
    for step in &analysis.steps {
        assert!(
            sent.iter().any(|b| b == &step.predicted),
            "the predicted frame {} drawn is not the analysis's",
            step.to_frame
        );
    }

    // Plan: the unfold arrows (a corner put back along the cloth's own edge) bow off it.
    route(client, &format!("#/plan?cloth=sample:{}&goal=0.174533,2.617994", entry.id)).await;
    until(client, "the linked goal", &format!("document.getElementById('plan-sample').value === 'sample:{}' && document.getElementById('plan-now').textContent.includes('now')", entry.id)).await;
    client.find(Locator::Id("plan-run")).await.expect("plan").click().await.expect("click");
    until(
        client,
        "a plan",
        "document.getElementById('plan-case').textContent.includes('unfold first')",
    )
    .await;
    // At each arrow's middle, within two pixels, its colour (#2f855a); its middle off the straight chord.
    let arrows = js(client, &format!("return [...document.querySelectorAll('#plan-list canvas[data-arrows]')].flatMap(c => {{ const g = {COPY}(c); return JSON.parse(c.dataset.arrows).map(a => {{ \
                             const p = g.getImageData(Math.round(a.mid[0]) - 2, Math.round(a.mid[1]) - 2, 5, 5).data; let green = false; \
                             for (let k = 0; k < p.length; k += 4) green ||= Math.abs(p[k] - 47) + Math.abs(p[k + 1] - 133) + Math.abs(p[k + 2] - 90) < 30; \
                             const chord = [(a.from[0] + a.to[0]) / 2, (a.from[1] + a.to[1]) / 2]; \
                             return {{ off: Math.hypot(a.mid[0] - chord[0], a.mid[1] - chord[1]), green, at: a.mid }}; }}); }})")).await;
    let arrows = arrows.as_array().cloned().unwrap_or_default();
    assert!(arrows.len() >= 2, "{arrows:?}");
    assert!(
        arrows
            .iter()
            .all(|a| a["off"].as_f64().is_some_and(|o| o >= 13.9) && a["green"] == json!(true)),
        "arrows on the edges: {arrows:?}"
    );

    // A phone: the readout by tap, under the picture.
    client.set_window_size(420, 900).await.expect("phone size");
    until(client, "a narrow window", "window.innerWidth <= 420").await;
    route(client, &format!("#/samples/{}?step=2", entry.id)).await;
    shows_sample(client, &entry.sample.name).await;
    until(client, "step 2's pictures", "[...document.querySelectorAll('#browse-result .step-pictures img')].every(i => i.src.includes('step=2'))").await;
    images_loaded(client, "#browse-result .step-pictures img").await;
    let ((x, y), (d, a)) = cell_pixel(n, largest_pair(n, delta));
    point_at(client, &format!("{signed} img"), (x, y), true).await;
    readout_of(client, signed, n, (d, a)).await;
    assert_no_overflow(client, "browse readout").await;
    screenshot(client, shots, "420-06-disk-readout.png").await;
    violations.extend(
        axe_violations(client, axe).await.into_iter().map(|v| format!("disk readout 420: {v}")),
    );
    client.set_window_size(1400, 1000).await.expect("wide again");
    until(client, "a wide window", "window.innerWidth > 1000").await;
    violations
}

/// A mesh sample shows its mesh picture (the mesh from above under its border loop), and
/// every picture of a result is shown at least `SHOWN_WIDTH` CSS px wide, the width its text
/// is sized for (at least 12 CSS px there), at 1400 and at 420 px; the whole-analysis
/// pictures (borders, fold circle, mesh) are captured at both widths.
async fn mesh_picture_shows_and_pictures_are_legible(client: &Client, base: &str, shots: &Path) {
    use base64::Engine as _;
    let dataset = close::dataset::Dataset::builtin();
    let mesh = &dataset
        .entries()
        .iter()
        .find(|e| e.sample.mesh.is_some())
        .expect("a built-in mesh sample")
        .id;
    for (width, height) in [(1400, 1000), (420, 900)] {
        client.set_window_size(width, height).await.expect("window size");
        until(client, "the window size", &format!("window.innerWidth <= {width}")).await;
        goto_view(client, base, &format!("#/samples/{mesh}")).await;
        until(client, "the mesh picture", "document.querySelector('#browse-result .images.whole img[data-picture=mesh]') !== null").await;
        let whole = images_loaded(
            client,
            "#browse-result .images.whole img, #browse-result .instrument-plot img",
        )
        .await;
        assert_eq!(whole, 3, "{width} px: borders, fold circle and mesh");
        // Issue 28 item 5: on a wide screen the border plot sits beside the disks, so the
        // edges a hover on a disk marks are in view; on a narrow one it follows them.
        let beside = js(client, "const d = document.querySelector('#browse-result .step-pictures .images').getBoundingClientRect(); \
                                 const b = document.querySelector('#browse-result .instrument-borders').getBoundingClientRect(); \
                                 return [b.left >= d.right, b.top < d.bottom]").await;
        let wide = width >= 1380;
        assert_eq!(beside, json!([wide, wide]), "{width} px: the border plot beside the disks");
        let shown: Vec<(String, f64)> = serde_json::from_value(js(client, "return [...document.querySelectorAll('#browse-result figure img')].map(i => [i.dataset.picture, i.getBoundingClientRect().width])").await).expect("widths");
        assert!(shown.len() >= 7, "{width} px: {shown:?}");
        for (picture, css) in &shown {
            assert!(
                *css >= close::render::SHOWN_WIDTH,
                "{width} px: {picture} shown {css} CSS px wide, under the {} its text is sized for",
                close::render::SHOWN_WIDTH
            );
        }
        // The mesh picture is drawn: mostly not paper (its PNG, decoded in the page).
        let inked = js(client, "const i = document.querySelector('#browse-result img[data-picture=mesh]'); const c = document.createElement('canvas'); \
                                c.width = i.naturalWidth; c.height = i.naturalHeight; const g = c.getContext('2d'); g.drawImage(i, 0, 0); \
                                const d = g.getImageData(0, 0, c.width, c.height).data; let n = 0; \
                                for (let k = 0; k < d.length; k += 4) if (d[k] + d[k + 1] + d[k + 2] < 600) n++; return n / (c.width * c.height)").await;
        assert!(
            inked.as_f64().unwrap_or(0.0) > 0.1,
            "{width} px: the mesh picture is nearly blank ({inked})"
        );
        // The disks, the border plot and the whole-analysis pictures, as shown.
        let rect = js(client, "const e = document.querySelector('#browse-result .images-slot'); e.scrollIntoView(); const r = e.getBoundingClientRect(); \
                               const m = 16; return { x: Math.max(0, r.left + window.scrollX - m), y: Math.max(0, r.top + window.scrollY - m), width: r.width + 2 * m, height: r.height + 2 * m, scale: 1 }").await;
        let shot = client
            .issue_cmd(DevTools(
                "Page.captureScreenshot",
                json!({ "captureBeyondViewport": true, "clip": rect }),
            ))
            .await
            .expect("screenshot");
        let png = base64::engine::general_purpose::STANDARD
            .decode(shot["data"].as_str().unwrap_or_default())
            .expect("a base64 PNG");
        std::fs::write(shots.join(format!("{width}-11-mesh-circle-borders.png")), png)
            .expect("write screenshot");
    }
    client.set_window_size(1400, 1000).await.expect("wide again");
}

/// Issue 25 item 4: the states Interpolate draws are the server's, asked one at a time as a
/// handle moves; dragging a handle round the circle on a cloth of N = 200 still follows the
/// pointer. Measured, not asserted against a clock: how many states were drawn per second of
/// drag and how long each waited, written to `target/e2e-screenshots/drag.txt`. Asserted:
/// states were drawn during the drag, and once the pointer stops the state drawn is the
/// one last asked for.
async fn drag_follows_the_pointer(client: &Client, base: &str, scratch: &Path, shots: &Path) {
    use fantoccini::actions::{InputSource, MouseActions, PointerAction, MOUSE_BUTTON_LEFT};
    client.set_window_size(1400, 1000).await.expect("window size");
    // A square napkin of 200 vertices, its right half folded over.
    let per_side = 50;
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let flat: Vec<[f64; 3]> = (0..4 * per_side)
        .map(|k| {
            let (a, b) = (corners[k / per_side], corners[(k / per_side + 1) % 4]);
            let t = (k % per_side) as f64 / per_side as f64;
            [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0.0]
        })
        .collect();
    let folded: Vec<[f64; 3]> =
        flat.iter().map(|p| if p[0] > 0.5 { [1.0 - p[0], p[1], 0.01] } else { *p }).collect();
    let sample = json!({ "name": "napkin-200", "category": "napkin", "frames": [flat, folded] });
    let file = write(scratch, "napkin-200.json", sample.to_string().as_bytes());
    goto_view(client, base, "#/upload").await;
    choose_files(client, &[file]).await;
    until(
        client,
        "the N = 200 upload",
        "document.querySelector('#upload-result .result-name')?.textContent === 'napkin-200.json'",
    )
    .await;
    js(client, "document.querySelector('#upload-result .interp-this').click()").await;
    until(
        client,
        "its first state",
        "(f => f.drawn && f.drawn === f.wanted)(window.closeApp.interpolate.following())",
    )
    .await;
    js(client, "window.closeApp.interpolate.setTau(0.5)").await;
    until(
        client,
        "the state at t = 0.5",
        "(f => f.drawn && f.drawn === f.wanted)(window.closeApp.interpolate.following())",
    )
    .await;
    // A quarter turn of the second "to" handle, in 120 pointer moves of 16 ms.
    let path = js(client, "const svg = document.getElementById('fold-circle'); svg.scrollIntoView({ block: 'center' }); \
                           const h = svg.querySelector('.handle[data-id=\"to:1\"]'); const a = Number(h.dataset.angle); const m = svg.getScreenCTM(); \
                           const r = 132; return Array.from({ length: 121 }, (_, k) => { const t = a + (k / 120) * Math.PI / 2; \
                           const [x, y] = [r * Math.cos(t), -r * Math.sin(t)]; return [m.a * x + m.c * y + m.e, m.b * x + m.d * y + m.f]; })").await;
    let path: Vec<[f64; 2]> = serde_json::from_value(path).expect("the drag's path");
    js(client, "window.closeApp.interpolate.following(true)").await;
    let mut drag = MouseActions::new("drag".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x: path[0][0].round(),
            y: path[0][1].round(),
        })
        .then(PointerAction::Down { button: MOUSE_BUTTON_LEFT });
    for p in &path[1..] {
        drag = drag.then(PointerAction::MoveTo {
            duration: Some(Duration::from_millis(16)),
            x: p[0].round(),
            y: p[1].round(),
        });
    }
    let started = Instant::now();
    client
        .perform_actions(drag.then(PointerAction::Up { button: MOUSE_BUTTON_LEFT }))
        .await
        .expect("drag");
    let seconds = started.elapsed().as_secs_f64();
    let during = js(client, "return window.closeApp.interpolate.following()").await;
    let last = until(
        client,
        "the last state asked for, drawn",
        "(f => f.drawn && f.drawn === f.wanted && f)(window.closeApp.interpolate.following())",
    )
    .await;
    let turned = js(client, "return window.closeApp.interpolate.state().to[1] - Number(document.querySelector('#fold-circle .handle[data-id=\"to:1\"]').dataset.angle)").await;
    assert!(
        turned.as_f64().is_some_and(|d| d.abs() < 1e-9),
        "the handle is where the fold is: {turned}"
    );
    let drawn = during["shown"].as_u64().unwrap_or(0);
    let mut waits: Vec<f64> = serde_json::from_value(last["waits"].clone()).unwrap_or_default();
    waits.sort_by(f64::total_cmp);
    let at = |q: f64| {
        waits.get(((waits.len() as f64 - 1.0) * q).round() as usize).copied().unwrap_or(f64::NAN)
    };
    let report = format!(
        "drag of a handle, N = 200, {} pointer moves in {seconds:.2} s: {} states asked, {drawn} drawn during the drag ({:.1} per second); wait per state drawn: median {:.0} ms, 90th percentile {:.0} ms, largest {:.0} ms\n",
        path.len() - 1,
        during["asked"],
        drawn as f64 / seconds,
        at(0.5),
        at(0.9),
        waits.last().copied().unwrap_or(f64::NAN)
    );
    println!("{report}");
    std::fs::write(shots.join("drag.txt"), &report).expect("write the drag's numbers");
    assert!(drawn > 0, "no state was drawn while the handle moved: {report}");
}

/// Run the "Use from code" snippets shown under `scope` (curl in `sh`, Python with python3)
/// in `dir`: each succeeds; the analysis they print carries `label`; the plan, the
/// interpolation and the pictures come.
async fn run_snippets(client: &Client, scope: &str, dir: &Path, label: &str) {
    let snippet = |lang: &str| {
        format!("document.querySelector('{scope} .use-code .code-{lang}').textContent")
    };
    let (curl, python) =
        (text(client, &snippet("curl")).await, text(client, &snippet("python")).await);
    for file in ["diff.png", "diff.svg"] {
        let _ = std::fs::remove_file(dir.join(file));
    }
    let shell = Command::new("sh").arg("-ec").arg(&curl).current_dir(dir).output().expect("run sh");
    let out = String::from_utf8_lossy(&shell.stdout);
    assert!(shell.status.success(), "{curl}\n{}", String::from_utf8_lossy(&shell.stderr));
    // The analysis (its label, JSON-escaped as serde writes it) and then the plan.
    let escaped = serde_json::to_string(label).expect("a JSON string");
    assert!(out.contains(escaped.trim_matches('"')) && out.contains("\"case\""), "{curl}\n{out}");
    let png = std::fs::read(dir.join("diff.png")).expect("the PNG the shell wrote");
    let svg = std::fs::read_to_string(dir.join("diff.svg")).expect("the SVG the shell wrote");
    assert!(png.starts_with(b"\x89PNG") && svg.starts_with("<svg"), "{curl}");
    let run = Command::new("python3")
        .arg("-c")
        .arg(&python)
        .current_dir(dir)
        .output()
        .expect("run python3");
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{python}\n{}", String::from_utf8_lossy(&run.stderr));
    assert!(out.contains(label) && out.contains("steps"), "{python}\n{out}");
    assert!(std::fs::read(dir.join("diff.png")).is_ok_and(|p| p.starts_with(b"\x89PNG")));
}

/// The API paths the page requested (its resource timing entries), but the sample list and
/// the cards' thumbnails.
async fn asked(client: &Client) -> Value {
    js(client, "return performance.getEntriesByType('resource').map(r => new URL(r.name).pathname) \
                .filter(p => p.startsWith('/api/') && p !== '/api/samples' && !p.endsWith('/thumbnail.png'))").await
}

/// Open `hash` of `base` in a new page (a goto that changes the hash alone keeps the page).
async fn fresh_page(client: &Client, base: &str, hash: &str) {
    client.goto(&format!("{base}/{hash}")).await.expect("a link");
    client.refresh().await.expect("a new page");
}

/// Issue 45 item 1: two cloths of other vertex counts compared. Both disks (on one colour
/// scale) and both borders are drawn; in the difference's place, what A − B needs, and no
/// request is made for it (it could only be refused); the console stays clean.
async fn unequal_cloths_compare_without_asking(client: &Client, base: &str, shots: &Path) {
    let (a, b) = ("napkin__half_vertical", "tshirt__sleeve_left");
    let builtin = crate::common::builtin();
    let (na, nb) = (builtin.analysed(a).1.n, builtin.analysed(b).1.n);
    assert_ne!(na, nb, "the two cloths have as many vertices");
    fresh_page(client, base, "#/compare").await;
    until(client, "the sample list", "window.closeApp.store.get().samples").await;
    js(client, &format!("window.realFetch = window.fetch; window.differences = 0; \
                        window.fetch = (url, o) => (String(url).endsWith('/api/disk') && JSON.parse(o.body).minus && window.differences++, window.realFetch(url, o)); \
                        location.hash = '#/compare/{a}/{b}'")).await;
    let said = until(
        client,
        "what A − B needs",
        "document.querySelector('#compare-result [data-picture=no-difference]')?.textContent",
    )
    .await;
    assert_eq!(
        said,
        json!(format!("A − B needs two cloths with as many border vertices: {na} and {nb}."))
    );
    until(client, "both disks and the borders", "document.querySelectorAll('#compare-result .compare-panels img[data-picture=disk]').length >= 2 && document.querySelector('#compare-result .compare-borders')").await;
    assert!(pictures_have_ink(client, "#compare-result").await >= 3);
    screenshot(client, shots, "1400-12-compare-unequal.png").await;
    let differences =
        js(client, "window.fetch = window.realFetch; return window.differences").await;
    assert_eq!(differences, json!(0), "A − B was asked for");
    assert!(
        asked(client).await.as_array().is_some_and(|a| a.iter().any(|p| p == "/api/disk")),
        "the page's requests are not seen"
    );
    console_clean(client, "compare of unequal cloths", &[]).await;
}

/// Issue 45 item 2: links to a cloth this server does not have. In a fresh page, each view
/// says so in a notice that stays on screen (with an upload control where another cloth can
/// take its place), draws nothing, and asks nothing more of that cloth: the one request that
/// learns an upload is gone is the only one refused, an unknown sample is known from the list
/// without a request, and a gone upload is not asked for again. The notice's upload control
/// brings a cloth that the view then draws. Gives axe-core's serious findings.
async fn missing_cloths_are_said(
    client: &Client,
    base: &str,
    scratch: &Path,
    shots: &Path,
    axe: &str,
) -> Vec<String> {
    let mut violations = Vec::new();
    let gone = "00000000000000000000000000000000";
    let refused = format!(
        "/api/analyses/{gone} - Failed to load resource: the server responded with a status of 404"
    );
    // Interpolate.
    fresh_page(client, base, &format!("#/interpolate?cloth=upload:{gone}&step=1")).await;
    let said = until(
        client,
        "the gone upload's notice",
        "document.querySelector('#interp-missing .missing-text')?.textContent",
    )
    .await;
    assert_eq!(said, json!("That upload is no longer on this server: upload it again."));
    // It stays, and nothing is drawn.
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let shown = js(client, "return [!document.getElementById('interp-missing').hidden, !!document.querySelector('#interp-missing input[type=file]'), \
                            document.querySelector('#view-interpolate .stage-pictures').checkVisibility(), document.querySelector('#view-interpolate .player').checkVisibility(), \
                            window.closeApp.interpolate.state().frame, document.getElementById('interp-sample').selectedOptions[0]?.textContent, \
                            document.getElementById('error').hidden]").await;
    assert_eq!(
        shown,
        json!([true, true, false, false, null, format!("upload {gone} (not on this server)"), true]),
        "[notice, its upload control, pictures shown, player shown, frame drawn, cloth box, error box hidden]"
    );
    assert_eq!(asked(client).await, json!([format!("/api/analyses/{gone}")]));
    screenshot(client, shots, "1400-13-interpolate-upload-gone.png").await;
    violations
        .extend(axe_violations(client, axe).await.into_iter().map(|v| format!("upload gone: {v}")));
    console_clean(client, "Interpolate of a gone upload", &[&refused]).await;
    // Plan and Upload, in the same page: said again, not asked again.
    route(client, &format!("#/plan?cloth=upload:{gone}&goal=0.500000,3.600000")).await;
    let said = until(
        client,
        "Plan's notice",
        "!document.getElementById('view-plan').hidden && document.querySelector('#plan-missing .missing-text')?.textContent",
    )
    .await;
    assert_eq!(said, json!("That upload is no longer on this server: upload it again."));
    tokio::time::sleep(Duration::from_millis(800)).await;
    let plan = js(client, "return [document.getElementById('plan-run').disabled, !!document.querySelector('#plan-missing input[type=file]'), document.querySelectorAll('#plan-list li').length]").await;
    assert_eq!(plan, json!([true, true, 0]), "[Plan disabled, upload control, steps drawn]");
    screenshot(client, shots, "1400-14-plan-upload-gone.png").await;
    route(client, &format!("#/upload?key={gone}")).await;
    until(client, "Upload's notice", "document.querySelector('#upload-result .missing-text')?.textContent.includes('no longer on this server')").await;
    assert_eq!(asked(client).await, json!([format!("/api/analyses/{gone}")]), "asked again");
    console_clean(client, "Plan and Upload of a gone upload", &[]).await;
    // The notice's upload control: the cloth chosen is drawn in its place.
    route(client, &format!("#/interpolate?cloth=upload:{gone}&step=1")).await;
    until(client, "the notice again", "!document.getElementById('interp-missing').hidden").await;
    let file = write(
        scratch,
        "brought-again.json",
        &serde_json::to_vec(
            &close::dataset::Dataset::builtin()
                .get("napkin__half_vertical")
                .expect("a sample")
                .sample,
        )
        .expect("sample JSON"),
    );
    choose_files_in(client, "#interp-missing input[type=file]", &[file]).await;
    until(
        client,
        "the new upload drawn",
        "document.getElementById('interp-missing').hidden && (f => f.drawn && f.drawn === f.wanted)(window.closeApp.interpolate.following())",
    )
    .await;
    let chosen =
        text(client, "document.getElementById('interp-sample').selectedOptions[0].textContent")
            .await;
    assert_eq!(chosen, "upload · brought-again.json");
    console_clean(client, "an upload from the notice", &[]).await;

    // An unknown sample: known from the list, never asked for.
    let unknown = "no-such-sample";
    fresh_page(client, base, &format!("#/samples/{unknown}")).await;
    let said = until(
        client,
        "Browse's notice",
        "document.querySelector('#browse-result .missing-text')?.textContent",
    )
    .await;
    assert_eq!(
        said,
        json!(format!("There is no sample “{unknown}” on this server: pick one from the list."))
    );
    assert!(
        js(client, "return !!document.querySelector('#browse-result .missing input[type=file]')")
            .await
            == json!(true),
        "no upload control"
    );
    screenshot(client, shots, "1400-15-browse-unknown-sample.png").await;
    violations.extend(
        axe_violations(client, axe).await.into_iter().map(|v| format!("unknown sample: {v}")),
    );
    route(client, &format!("#/plan?cloth=sample:{unknown}")).await;
    until(client, "Plan's notice of the sample", "document.querySelector('#plan-missing .missing-text')?.textContent.includes('no-such-sample')").await;
    route(client, &format!("#/compare/{unknown}/napkin__half_vertical")).await;
    until(client, "Compare's notice", "document.querySelector('#compare-result .missing-text')?.textContent.includes('no-such-sample')").await;
    screenshot(client, shots, "1400-16-compare-unknown-sample.png").await;
    let unknown_asked = js(
        client,
        &format!("return performance.getEntriesByType('resource').filter(r => r.name.includes('{unknown}')).length"),
    )
    .await;
    assert_eq!(unknown_asked, json!(0), "the unknown sample was asked for");
    console_clean(client, "an unknown sample", &[]).await;
    violations
}

/// A server on `addr` that stops when `stop` is sent.
async fn serve_at(
    addr: std::net::SocketAddr,
    router: axum::Router,
) -> tokio::sync::oneshot::Sender<()> {
    let listener = tokio::net::TcpListener::bind(addr).await.expect("bind");
    let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
    tokio::spawn(async move {
        axum::serve(listener, router)
            .with_graceful_shutdown(async move {
                stopped.await.ok();
            })
            .await
    });
    stop
}

/// Issue 28 item 8: with a data folder, an upload's links (the upload itself, Interpolate,
/// Plan) work after a reload of the page and after a restart of the server; a link to an
/// upload the server no longer has says so.
async fn uploads_outlive_a_reload_and_a_restart(client: &Client, scratch: &Path) {
    let data = scratch.join("data");
    let config = || close::server::Config { data_dir: Some(data.clone()), ..Default::default() };
    let addr: std::net::SocketAddr =
        format!("127.0.0.1:{}", free_port()).parse().expect("an address");
    let base = format!("http://{addr}");
    let stop = serve_at(addr, app(AppState::with_config(config()))).await;
    let entry =
        close::dataset::Dataset::builtin().get("napkin__half_vertical").expect("a sample").clone();
    let file = write(
        scratch,
        "kept-napkin.json",
        &serde_json::to_vec(&entry.sample).expect("sample JSON"),
    );
    goto_view(client, &base, "#/upload").await;
    choose_files(client, &[file]).await;
    let hash = until(client, "the upload's own URL", "location.hash.startsWith('#/upload?key=') && document.querySelector('#upload-result .result-name')?.textContent === 'kept-napkin.json' && location.hash").await;
    let hash = hash.as_str().unwrap_or_default().to_string();
    let key = hash.trim_start_matches("#/upload?key=").to_string();
    // A new page each time (a goto that changes the hash alone would keep the old one).
    let open = async |url: &str| {
        client.goto(url).await.expect("a link");
        client.refresh().await.expect("a new page");
    };
    let shows_upload = async || {
        until(client, "the upload after a reload", "document.querySelector('#upload-result .result-label')?.textContent && document.getElementById('error').hidden").await;
    };
    client.refresh().await.expect("reload");
    shows_upload().await;
    // Its Interpolate link, in a page that never saw the upload.
    let interpolate = format!("{base}/#/interpolate?cloth=upload:{key}&step=1&t=1.000");
    open(&interpolate).await;
    until(
        client,
        "the upload's fold drawn",
        "(f => f.drawn && f.drawn === f.wanted)(window.closeApp.interpolate.following())",
    )
    .await;
    // A restart: a new server on the same address, over the same folder (the page left
    // first, as below).
    client.goto("about:blank").await.expect("leave the page");
    stop.send(()).ok();
    tokio::time::sleep(Duration::from_millis(300)).await;
    let stop = serve_at(addr, app(AppState::with_config(config()))).await;
    open(&format!("{base}/{hash}")).await;
    shows_upload().await;
    open(&interpolate).await;
    until(
        client,
        "the upload's fold drawn after a restart",
        "(f => f.drawn && f.drawn === f.wanted)(window.closeApp.interpolate.following())",
    )
    .await;
    client
        .goto(&format!("{base}/#/plan?cloth=upload:{key}&goal=0.500000,3.600000"))
        .await
        .expect("the Plan link");
    until(
        client,
        "a plan for the upload",
        "/\\d+ steps? ·|already folded/.test(document.getElementById('plan-case').textContent)",
    )
    .await;
    // Gone: the folder emptied behind the server's back. The page is left first, so that
    // none of its pictures is still asked of the server while it is down.
    client.goto("about:blank").await.expect("leave the page");
    stop.send(()).ok();
    tokio::time::sleep(Duration::from_millis(300)).await;
    std::fs::remove_dir_all(&data).expect("empty the data folder");
    let _stop = serve_at(addr, app(AppState::with_config(config()))).await;
    open(&format!("{base}/{hash}")).await;
    let said = until(
        client,
        "the notice that the upload is gone",
        "document.querySelector('#upload-result .missing')?.textContent",
    )
    .await;
    assert!(
        said.as_str().is_some_and(|e| e.contains("no longer on this server")
            && e.contains("is gone")
            && e.contains("Upload the sample again")),
        "{said}"
    );
    console_clean(
        client,
        "an upload kept, then gone",
        &[&format!("/api/analyses/{key} - Failed to load resource: the server responded with a status of 404")],
    )
    .await;
}
