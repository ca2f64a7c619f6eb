//! End-to-end in a real headless Chromium (driven over WebDriver by fantoccini): load the
//! app, open a sample, upload a file, move the interpolation slider (the drawing and the
//! disk follow), plan a fold. Screenshots go to
//! `target/e2e-screenshots/` for a person to look at.
//!
//! Needs Debian's `chromium` and `chromium-driver` (or `CLOSE_CHROMIUM` / `CLOSE_CHROMEDRIVER`
//! pointing at them), so it is ignored by default: `cargo test -- --ignored` runs it, and
//! `.ci/run` installs both and does.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use fantoccini::{elements::Element, Client, ClientBuilder, Locator};
use serde_json::{json, Value};

use close::server::{app, AppState};

const TIMEOUT: Duration = Duration::from_secs(30);

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
    std::env::split_paths(&path).flat_map(|dir| names.iter().map(move |n| dir.join(n))).find(|p| p.is_file())
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0").and_then(|l| l.local_addr()).map(|a| a.port()).expect("a free port")
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

async fn screenshot(client: &Client, dir: &Path, name: &str) {
    let png = client.screenshot().await.expect("screenshot");
    std::fs::write(dir.join(name), png).expect("write screenshot");
}

/// Every image under `selector` has loaded with a real picture.
async fn images_loaded(client: &Client, selector: &str) -> usize {
    let script = format!("return [...document.querySelectorAll({selector:?})].map(i => i.complete ? i.naturalWidth : 0)");
    wait_for(&format!("images of {selector}"), async || {
        let widths: Vec<u64> = serde_json::from_value(js(client, &script).await).unwrap_or_default();
        (!widths.is_empty() && widths.iter().all(|&w| w > 0)).then_some(widths.len())
    })
    .await
}

async fn text_of(client: &Client, css: &str) -> String {
    wait_for(&format!("text in {css}"), async || {
        let el: Element = client.find(Locator::Css(css)).await.ok()?;
        let text = el.text().await.ok()?;
        (!text.trim().is_empty()).then_some(text)
    })
    .await
}

/// A digest of the interpolation canvas's pixels (short enough for an assertion message).
async fn canvas(client: &Client) -> u64 {
    use std::hash::{Hash, Hasher};
    let url = js(client, "return document.getElementById('interp-canvas').toDataURL()").await;
    let mut h = std::hash::DefaultHasher::new();
    url.as_str().unwrap_or_default().hash(&mut h);
    h.finish()
}

/// A Wavefront OBJ of one mesh frame.
fn obj(vertices: &[[f64; 3]], faces: &[Vec<usize>]) -> String {
    let v = vertices.iter().map(|p| format!("v {} {} {}\n", p[0], p[1], p[2]));
    let f = faces.iter().map(|f| format!("f {}\n", f.iter().map(|k| (k + 1).to_string()).collect::<Vec<_>>().join(" ")));
    v.chain(f).collect()
}

/// A digest of the disk picture of the interpolation, once it shows the current state.
async fn disk_picture(client: &Client) -> u64 {
    use std::hash::{Hash, Hasher};
    let script = "const img = document.getElementById('interp-disk'); \
                  if (!img.complete || !img.naturalWidth || img.dataset.key !== window.closeApp.interp.diskKey()) return null; \
                  const c = document.createElement('canvas'); c.width = img.naturalWidth; c.height = img.naturalHeight; \
                  c.getContext('2d').drawImage(img, 0, 0); return c.toDataURL();";
    let url = wait_for("the disk of the current state", async || js(client, script).await.as_str().map(str::to_string)).await;
    let mut h = std::hash::DefaultHasher::new();
    url.hash(&mut h);
    h.finish()
}

/// The texts of the plan view's cards, once there are some.
async fn plan_steps(client: &Client) -> Vec<String> {
    wait_for("plan steps", async || {
        let texts: Vec<String> = serde_json::from_value(js(client, "return [...document.querySelectorAll('#plan-list .plan-step')].map(li => li.innerText)").await).ok()?;
        (!texts.is_empty()).then_some(texts)
    })
    .await
}

/// Type a goal fold (degrees) into the plan view.
async fn set_goal(client: &Client, g1: u32, g2: u32) {
    let script = format!(
        "for (const [id, v] of [['goal-1', {g1}], ['goal-2', {g2}]]) {{ const i = document.getElementById(id); i.value = v; i.dispatchEvent(new Event('change')); }}"
    );
    js(client, &script).await;
}

/// Pixels of the pick → place arrows' green in the plan's step pictures.
async fn arrow_pixels(client: &Client) -> u64 {
    let script = "let n = 0; for (const c of document.querySelectorAll('#plan-list canvas')) { \
                  const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data; \
                  for (let i = 0; i < d.length; i += 4) if (d[i] === 47 && d[i + 1] === 133 && d[i + 2] === 90) n++; } return n;";
    js(client, script).await.as_u64().unwrap_or(0)
}

async fn slider_value(client: &Client) -> String {
    js(client, "return document.getElementById('interp-slider').value").await.as_str().unwrap_or_default().to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs chromium and chromedriver (apt-get install chromium chromium-driver); run with `cargo test -- --ignored`"]
async fn the_app_works_in_a_real_browser() {
    let (chromium, chromedriver) = (find_program("CLOSE_CHROMIUM", &["chromium", "chromium-browser"]), find_program("CLOSE_CHROMEDRIVER", &["chromedriver"]));
    let (Some(chromium), Some(chromedriver)) = (chromium, chromedriver) else {
        panic!(
            "the browser test needs chromium and chromedriver: apt-get install -y --no-install-recommends chromium chromium-driver \
             (or set CLOSE_CHROMIUM / CLOSE_CHROMEDRIVER)"
        );
    };
    let shots = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/e2e-screenshots");
    std::fs::create_dir_all(&shots).expect("screenshot folder");
    let scratch = std::env::temp_dir().join(format!("close-e2e-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).expect("scratch folder");

    // The server, on a free port.
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.expect("bind");
    let base = format!("http://{}", listener.local_addr().expect("address"));
    tokio::spawn(async move { axum::serve(listener, app(AppState::new())).await });

    // chromedriver and a session.
    let port = free_port();
    let _driver = Driver(
        Command::new(&chromedriver).arg(format!("--port={port}")).stdout(Stdio::null()).stderr(Stdio::null()).spawn().expect("start chromedriver"),
    );
    let mut caps = serde_json::Map::new();
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
        ClientBuilder::new(hyper_util::client::legacy::connect::HttpConnector::new()).capabilities(caps.clone()).connect(&webdriver).await.ok()
    })
    .await;

    // 1. Browse: open a sample; its pictures load and its label shows.
    client.goto(&format!("{base}/")).await.expect("load the app");
    let cards = wait_for("sample cards", async || client.find_all(Locator::Css(".sample-card")).await.ok().filter(|c| !c.is_empty())).await;
    // Thumbnails load lazily: check the first ones, which are on screen.
    images_loaded(&client, "#sample-list .cards:first-of-type .sample-card:nth-child(-n+2) img").await;
    cards[0].click().await.expect("open a sample");
    let label = text_of(&client, "#browse-result .result-label").await;
    assert!(label.contains("corner"), "label: {label}");
    assert_eq!(images_loaded(&client, "#browse-result .images img").await, 6);
    // The Rerun download is offered exactly when the server can write recordings.
    let offered = js(&client, "return !document.querySelector('#browse-result .recording').hidden").await;
    assert_eq!(offered.as_bool(), Some(cfg!(feature = "rerun")), "recording link shown: {offered}");
    screenshot(&client, &shots, "01-sample.png").await;
    // A built-in mesh sample is listed, and its view says where its border came from.
    let dataset = close::dataset::Dataset::builtin();
    let mesh_entry = dataset.entries().iter().find(|e| e.sample.mesh.is_some()).expect("a built-in mesh sample");
    let card = client.find(Locator::Css(&format!(".sample-card[data-id={:?}]", mesh_entry.id))).await.expect("the mesh sample's card");
    card.click().await.expect("open the mesh sample");
    wait_for("the mesh sample's view", async || {
        let meta = client.find(Locator::Css("#browse-result .result-meta")).await.ok()?.text().await.ok()?;
        meta.contains("mesh boundary loop").then_some(())
    })
    .await;
    assert_eq!(images_loaded(&client, "#browse-result .images img").await, 6);
    screenshot(&client, &shots, "01b-mesh-sample.png").await;

    // 2. Upload a Sample JSON; then a broken file shows the server's error.
    client.find(Locator::Id("tab-upload")).await.expect("upload tab").click().await.expect("click");
    let entry = dataset.entries().iter().find(|e| e.sample.frames.len() >= 2).expect("a folded sample");
    let mut sample = entry.sample.clone();
    sample.name = "e2e upload".into();
    let good = scratch.join("e2e-upload.json");
    std::fs::write(&good, serde_json::to_vec(&sample).expect("sample JSON")).expect("write upload");
    js(&client, "document.getElementById('upload-input').style.display = 'block'").await;
    let input = client.find(Locator::Id("upload-input")).await.expect("file input");
    input.send_keys(&good.display().to_string()).await.expect("choose the file");
    assert_eq!(text_of(&client, "#upload-result .result-name").await, "e2e upload");
    assert!(text_of(&client, "#upload-result .result-label").await.contains("corner"));
    assert_eq!(images_loaded(&client, "#upload-result .images img").await, 6);
    screenshot(&client, &shots, "02-upload.png").await;

    // Two OBJ frames of a mesh (chosen together, in reverse order): the border is the mesh's
    // boundary loop, and the page says so.
    let mesh = mesh_entry.sample.mesh.as_ref().expect("mesh");
    let objs: Vec<PathBuf> = mesh
        .frames
        .iter()
        .enumerate()
        .map(|(k, frame)| {
            let path = scratch.join(format!("cloth-frame{k}.obj"));
            std::fs::write(&path, obj(frame, &mesh.faces)).expect("write an OBJ frame");
            path
        })
        .rev()
        .collect();
    js(&client, "document.getElementById('upload-input').value = ''").await;
    let paths: Vec<String> = objs.iter().map(|p| p.display().to_string()).collect();
    client.find(Locator::Id("upload-input")).await.expect("file input").send_keys(&paths.join("\n")).await.expect("choose the OBJ files");
    wait_for("the mesh analysis", async || {
        let meta = client.find(Locator::Css("#upload-result .result-meta")).await.ok()?.text().await.ok()?;
        meta.contains("mesh boundary loop").then_some(())
    })
    .await;
    assert_eq!(text_of(&client, "#upload-result .result-name").await, "cloth-frame0.obj", "frames in file-name order");
    assert!(text_of(&client, "#upload-result .close-table").await.contains("fold 1"), "the mesh's fold is found");
    screenshot(&client, &shots, "02b-upload-mesh.png").await;

    let bad = scratch.join("broken.json");
    std::fs::write(&bad, b"{\"frames\": [[[0, 0, 0], [1, 0").expect("write broken file");
    js(&client, "document.getElementById('upload-input').value = ''").await;
    client.find(Locator::Id("upload-input")).await.expect("file input").send_keys(&bad.display().to_string()).await.expect("choose");
    let error = text_of(&client, "#error").await;
    assert!(error.contains("could not parse") && error.contains("400"), "error shown: {error}");
    screenshot(&client, &shots, "03-upload-error.png").await;

    // 3. Interpolate: moving the slider redraws the folded border.
    client.find(Locator::Id("tab-interpolate")).await.expect("interpolate tab").click().await.expect("click");
    wait_for("the interpolation readout", async || {
        let t = client.find(Locator::Id("interp-readout")).await.ok()?.text().await.ok()?;
        t.contains("fold").then_some(())
    })
    .await;
    let before = canvas(&client).await;
    let disk_before = disk_picture(&client).await;
    screenshot(&client, &shots, "04-interpolate-start.png").await;
    // A mouse click on the middle of the slider's track moves it there.
    client.find(Locator::Id("interp-slider")).await.expect("slider").click().await.expect("click the slider");
    let moved: f64 = slider_value(&client).await.parse().unwrap_or(0.0);
    assert!((400.0..=600.0).contains(&moved), "the slider is at {moved} after a click on its middle");
    let halfway = canvas(&client).await;
    assert_ne!(before, halfway, "moving the slider did not change the drawing");
    let readout = client.find(Locator::Id("interp-readout")).await.expect("readout").text().await.expect("text");
    assert!(!readout.contains("t = 0.000"), "the readout did not follow the slider: {readout}");
    assert_ne!(disk_before, disk_picture(&client).await, "the disk did not follow the slider");
    screenshot(&client, &shots, "05-interpolate-half.png").await;
    // The play button runs the motion to its end.
    client.find(Locator::Id("interp-play")).await.expect("play").click().await.expect("play");
    wait_for("the motion to end", async || (slider_value(&client).await == "1000").then_some(())).await;
    assert_ne!(halfway, canvas(&client).await, "playing did not change the drawing");
    disk_picture(&client).await;
    screenshot(&client, &shots, "06-interpolate-end.png").await;

    // The same motion from the server agrees.
    client.find(Locator::Id("check-server")).await.expect("check button").click().await.expect("click");
    let check = text_of(&client, "#interp-check").await;
    assert!(check.contains("agree"), "parity display: {check}");

    // 4. Plan: the interpolation's goal opens the plan view; each step is drawn with its
    // pick → place arrows and said in words.
    client.find(Locator::Id("plan-goal")).await.expect("plan button").click().await.expect("click");
    wait_for("the plan view", async || js(&client, "return !document.getElementById('view-plan').hidden").await.as_bool().filter(|&v| v)).await;
    // A goal folding the same corners as the sample's half fold: one direct step.
    set_goal(&client, 60, 240).await;
    client.find(Locator::Id("plan-run")).await.expect("plan run").click().await.expect("click");
    wait_for("the plan", async || {
        let case = client.find(Locator::Id("plan-case")).await.ok()?.text().await.ok()?;
        case.contains("straight").then_some(())
    })
    .await;
    let steps = plan_steps(&client).await;
    assert!(steps.len() >= 2, "the current state and at least one step: {steps:?}");
    assert!(steps[0].starts_with("Now"), "{steps:?}");
    assert!(steps[1..].iter().all(|s| s.contains("Step") && s.contains("along")), "{steps:?}");
    assert!(steps[1..].iter().any(|s| s.contains("grasp corner")), "no corner grasped: {steps:?}");
    assert!(arrow_pixels(&client).await > 50, "no pick → place arrow drawn");
    screenshot(&client, &shots, "07-plan.png").await;

    // A sample folded twice, a goal typed in: unfold both folds, then fold.
    let twice = dataset.entries().iter().find(|e| e.sample.frames.len() == 3).expect("a second-fold sample");
    js(&client, &format!("const s = document.getElementById('plan-sample'); s.value = {:?}; s.dispatchEvent(new Event('change'))", twice.id)).await;
    wait_for("the sample's state", async || {
        let now = client.find(Locator::Id("plan-now")).await.ok()?.text().await.ok()?;
        now.contains(" then ").then_some(())
    })
    .await;
    set_goal(&client, 10, 150).await;
    client.find(Locator::Id("plan-run")).await.expect("plan run").click().await.expect("click");
    wait_for("a new plan", async || {
        let case = client.find(Locator::Id("plan-case")).await.ok()?.text().await.ok()?;
        case.contains("unfold first").then_some(())
    })
    .await;
    let steps = plan_steps(&client).await;
    assert_eq!(steps.iter().filter(|s| s.contains("· Unfold")).count(), 2, "{steps:?}");
    assert!(steps.last().is_some_and(|s| s.contains("· Fold") && s.contains("10.0°")), "{steps:?}");
    screenshot(&client, &shots, "08-plan-unfold.png").await;

    client.close().await.expect("end the session");
    let _ = std::fs::remove_dir_all(&scratch);
}
