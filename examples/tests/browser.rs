//! The megakernel in a browser: the page of `web/` (built into `target/web`
//! by scripts/web.sh) served from here to headless Chromium, whose WebGPU
//! adapter (SwiftShader's Vulkan on a machine without a GPU) runs the
//! `normal` and `cornell` examples through `Context::launch_async`. The
//! page POSTs what each canvas shows back; each picture must meet the
//! golden rule against the tour's golden image (at least 99.9% of the
//! 8-bit channels within 2/255, none beyond 16/255). The page then turns
//! its denoise toggle on and POSTs the Cornell box's samples denoised by
//! the runtime's denoiser stage on its device, and what its caption says:
//! that picture must differ from the raw one, be nearer a render of many
//! more samples than the raw one is, and be the CPU backend's denoised
//! picture of the same samples, within the golden rule.
//!
//! Without the built page or Chromium the test passes with a note, unless
//! `RT_REQUIRE_BROWSER=1` (scripts/test.sh sets it after building the page
//! and installing Chromium): then it fails, naming what is missing.

use examples::denoised::Denoiser;
use examples::{Image, Settings};
use rt_runtime::Backend;
use std::collections::HashMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The size and launches the golden images were made with
/// (examples/tests/golden.rs).
const W: u32 = 64;
const H: u32 = 48;
const SPP: u32 = 4;

/// The samples of the reference the denoised picture is measured against.
const REFERENCE_SPP: u32 = 64;

/// How long the page may take: a cold SwiftShader compiles two megakernels.
const PAGE_TIME: Duration = Duration::from_secs(600);

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Passes with a note, or fails when the browser test is required.
fn missing(what: &str) {
    assert!(std::env::var("RT_REQUIRE_BROWSER").as_deref() != Ok("1"), "RT_REQUIRE_BROWSER=1 but {what}");
    eprintln!("skipped: {what}");
}

fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("RT_CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .flat_map(|name| std::env::split_paths(&path).map(move |d| d.join(name)))
        .find(|p| p.is_file())
}

/// What the page POSTed: `(path, body)`.
type Posted = (String, Vec<u8>);

/// Serves `dir` (GET) and forwards every POST to `posted`, on a port of
/// the loopback interface; returns the port.
fn serve(dir: PathBuf, posted: mpsc::Sender<Posted>) -> u16 {
    let listener = TcpListener::bind("127.0.0.1:0").expect("a loopback port");
    let port = listener.local_addr().unwrap().port();
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let (dir, posted) = (dir.clone(), posted.clone());
            std::thread::spawn(move || answer(stream, &dir, &posted));
        }
    });
    port
}

/// One HTTP/1.1 request: a file of `dir`, or a POST forwarded.
fn answer(stream: TcpStream, dir: &Path, posted: &mpsc::Sender<Posted>) {
    let mut reader = BufReader::new(stream);
    let mut line = String::new();
    if reader.read_line(&mut line).is_err() {
        return;
    }
    let mut parts = line.split_whitespace();
    let (method, target) = (parts.next().unwrap_or(""), parts.next().unwrap_or("/").to_string());
    let mut length = 0usize;
    loop {
        let mut header = String::new();
        if reader.read_line(&mut header).is_err() || header.trim().is_empty() {
            break;
        }
        if let Some((name, value)) = header.split_once(':')
            && name.eq_ignore_ascii_case("content-length")
        {
            length = value.trim().parse().unwrap_or(0);
        }
    }
    let path = target.split('?').next().unwrap_or("/").to_string();
    let (status, kind, body) = if method == "POST" {
        let mut body = vec![0; length];
        let _ = reader.read_exact(&mut body);
        let _ = posted.send((path, body));
        ("200 OK", "text/plain", Vec::new())
    } else {
        let file = dir.join(path.trim_start_matches('/'));
        let kind = match file.extension().and_then(|e| e.to_str()) {
            Some("html") => "text/html",
            Some("js") => "text/javascript",
            Some("wasm") => "application/wasm",
            _ => "application/octet-stream",
        };
        match std::fs::read(&file) {
            Ok(bytes) if !path.contains("..") => ("200 OK", kind, bytes),
            _ => ("404 Not Found", "text/plain", Vec::new()),
        }
    };
    let mut stream = reader.into_inner();
    let head = format!(
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nAccess-Control-Allow-Origin: *\r\nConnection: close\r\n\r\n",
        body.len()
    );
    let _ = stream.write_all(head.as_bytes()).and_then(|()| stream.write_all(&body));
}

/// Kills the browser when the test ends, however it ends.
struct Browser(Child);

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The golden rule, or what breaks it.
fn compare(name: &str, golden: &[u8], got: &[u8]) -> Result<String, String> {
    if golden.len() != got.len() {
        return Err(format!("{name}: {} bytes from the page, {} in the golden", got.len(), golden.len()));
    }
    let diffs: Vec<u8> = golden.iter().zip(got).map(|(a, b)| a.abs_diff(*b)).collect();
    let beyond_2 = diffs.iter().filter(|d| **d > 2).count();
    let max = diffs.iter().copied().max().unwrap_or(0);
    let figures = format!("{name}: max difference {max}/255, {beyond_2} of {} channels beyond 2/255", diffs.len());
    if beyond_2 * 1000 <= diffs.len() && max <= 16 { Ok(figures) } else { Err(figures) }
}

/// 8-bit RGBA of `image`, display values, top row first.
fn rgba8(image: &Image) -> Vec<u8> {
    rt_runtime::image_out::to_rgba8(image.width, image.height, &image.pixels).into_raw()
}

/// The Cornell box at `spp` on the CPU backend: its picture, and its
/// samples denoised and shown as its camera shows them (as the page's
/// `denoised` does).
fn cornell_on_cpu(spp: u32) -> (Vec<u8>, Vec<u8>) {
    let settings = Settings { spp, backend: Backend::Cpu, ..Settings::new(W, H) };
    let mut scene = examples::cornell::scene(&settings).expect("the Cornell box builds");
    let rendered = scene.render(&mut |_| {}).expect("the Cornell box renders on the CPU");
    let denoiser = Denoiser::new(&mut scene).expect("a denoiser").expect("the Cornell box writes guides");
    let mut denoised = denoiser.run(&mut scene).expect("the denoiser runs on the CPU");
    for p in &mut denoised.pixels {
        *p = examples::cornell::tonemap(p.truncate(), examples::cornell::EXPOSURE).extend(1.0);
    }
    (rgba8(&rendered.image), rgba8(&denoised))
}

/// The mean squared difference of two pictures' colour channels, in
/// 8-bit steps.
fn mse(a: &[u8], b: &[u8]) -> f64 {
    let colour = |(i, _): &(usize, _)| i % 4 != 3;
    let squares = a.iter().zip(b).enumerate().filter(colour).map(|(_, (x, y))| (*x as f64 - *y as f64).powi(2));
    squares.sum::<f64>() / (a.len() / 4 * 3) as f64
}

#[test]
fn the_page_renders_normal_and_cornell_as_the_goldens_and_denoises_cornell() {
    let page = root().join("target/web");
    if !page.join("pkg/rt_web_bg.wasm").is_file() {
        return missing(&format!("{} holds no built page (run scripts/web.sh)", page.display()));
    }
    let Some(chromium) = chromium() else {
        return missing("no Chromium on PATH (apt-get install chromium, or set RT_CHROMIUM)");
    };
    let (tx, rx) = mpsc::channel();
    let port = serve(page, tx);
    let origin = format!("http://127.0.0.1:{port}");
    let url = format!("{origin}/index.html?width={W}&height={H}&spp={SPP}&report={origin}");
    let profile = std::env::temp_dir().join(format!("rt-browser-{}-{port}", std::process::id()));
    let flags = ["--headless=new", "--no-sandbox", "--enable-unsafe-webgpu", "--disable-dev-shm-usage"];
    let child = Command::new(&chromium)
        .args(flags)
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(&url)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {}: {e}", chromium.display()));
    let _browser = Browser(child);
    let start = Instant::now();
    let mut posted: HashMap<String, Vec<u8>> = HashMap::new();
    while !posted.contains_key("/done") {
        let left = PAGE_TIME.saturating_sub(start.elapsed());
        match rx.recv_timeout(left) {
            Ok((path, body)) => {
                posted.insert(path, body);
            }
            Err(_) => panic!("the page did not finish in {PAGE_TIME:?}; it said: {:?}", posted.keys()),
        }
    }
    let _ = std::fs::remove_dir_all(&profile);
    let text = |path: &str| posted.get(path).map(|b| String::from_utf8_lossy(b).into_owned());
    eprintln!(
        "browser: {} with WebGPU adapter `{}`, {:.1} s",
        chromium.display(),
        text("/adapter").unwrap_or_default(),
        start.elapsed().as_secs_f64()
    );
    if let Some(e) = text("/error/page") {
        panic!("the page failed: {e}");
    }
    for name in ["normal", "cornell"] {
        if let Some(e) = text(&format!("/error/{name}")) {
            panic!("{e}");
        }
        let got = posted.get(&format!("/picture/{name}")).unwrap_or_else(|| panic!("no picture of {name}"));
        let golden_path = root().join(format!("examples/tests/golden/{name}.png"));
        let golden = image::open(&golden_path).unwrap_or_else(|e| panic!("{}: {e}", golden_path.display())).to_rgba8();
        match compare(name, golden.as_raw(), got) {
            Ok(figures) => eprintln!("browser: {figures}"),
            Err(figures) => panic!("the page's picture breaks the golden rule: {figures}"),
        }
    }
    if let Some(e) = text("/error/cornell-denoised") {
        panic!("the denoise toggle failed: {e}");
    }
    let raw = &posted["/picture/cornell"];
    let denoised = posted.get("/picture/cornell-denoised").expect("no denoised picture of cornell");
    assert_eq!(
        text("/mode").as_deref(),
        Some(format!("cornell, {SPP} spp: denoised").as_str()),
        "what the page says it shows"
    );
    let (_, cpu_denoised) = cornell_on_cpu(SPP);
    let (reference, _) = cornell_on_cpu(REFERENCE_SPP);
    let (raw_error, denoised_error) = (mse(raw, &reference), mse(denoised, &reference));
    eprintln!(
        "browser: cornell at {SPP} spp against {REFERENCE_SPP} spp: mean squared error {raw_error:.1} raw, {denoised_error:.1} denoised, {:.1} between them",
        mse(raw, denoised)
    );
    assert!(mse(raw, denoised) > 4.0, "the denoised picture is the raw one: {:.2}", mse(raw, denoised));
    assert!(
        denoised_error < raw_error / 2.0,
        "denoising did not bring the picture nearer {REFERENCE_SPP} spp: {raw_error:.1} raw, {denoised_error:.1} denoised"
    );
    match compare("cornell denoised", &cpu_denoised, denoised) {
        Ok(figures) => eprintln!("browser: against the CPU's denoised: {figures}"),
        Err(figures) => panic!("the page's denoised picture is not the CPU backend's: {figures}"),
    }
}
