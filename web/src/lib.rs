//! The megakernel in a browser. `index.html` beside this crate loads the
//! wasm module that `wasm-bindgen --target web` makes of it (scripts/web.sh
//! builds both into `target/web/`) and renders the `normal` and `cornell`
//! examples through the page's WebGPU: the same programs, scenes and
//! kernels as the tour's, launched with `Context::launch_async`, since a
//! page's one thread may not block on the GPU. examples/tests/browser.rs
//! serves the page to headless Chromium and compares what its canvases
//! show with the tour's golden images.
//!
//! The page's denoise toggle shows the Cornell box's samples denoised
//! (`denoised`): the runtime's denoiser stage over the render's guides
//! (`examples::Aovs`), a command list run with
//! `CommandList::execute_async`, on the same device, no sample taken
//! again.
//!
//! Natively the crate is empty.

#![cfg(target_arch = "wasm32")]

use examples::denoised::Denoiser;
use examples::{Scene, Settings};
use rt_runtime::{Backend, Traversal};
use std::cell::RefCell;
use wasm_bindgen::prelude::*;

thread_local! {
    /// The last Cornell box [`render`] rendered, for [`denoised`].
    static CORNELL: RefCell<Option<Scene>> = const { RefCell::new(None) };
}

/// The Cornell box's files, built in: a page has no files to read.
const CORNELL_OBJ: &str = include_str!("../../../shared/scenes/cornell_box.obj");
const CORNELL_MTL: &str = include_str!("../../../shared/scenes/cornell_box.mtl");

/// Renders example `name` (`normal` or `cornell`) at `width` x `height`,
/// `spp` launches for the progressive Cornell box, on the page's WebGPU
/// adapter: the picture as 8-bit RGBA, top row first (as the tour's PNGs
/// hold it). Errors (no WebGPU, a failed launch, an exception raised) come
/// back as the promise's rejection, one line. The Cornell box is kept for
/// [`denoised`].
#[wasm_bindgen]
pub async fn render(name: String, width: u32, height: u32, spp: u32) -> Result<Vec<u8>, JsValue> {
    say_panics();
    let fail = |e: String| JsValue::from_str(&format!("{name}: {e}"));
    let settings =
        Settings { spp, backend: Backend::Wgpu, traversal: Traversal::Compute, ..Settings::new(width, height) };
    let scene = match name.as_str() {
        "normal" => examples::normal::scene(&settings),
        "cornell" => examples::cornell::scene_from_text(&settings, CORNELL_OBJ, CORNELL_MTL),
        other => return Err(fail(format!("no example `{other}` in this page (normal, cornell)"))),
    };
    let mut scene = scene.map_err(|e| fail(e.to_string()))?;
    let rendered = scene.render_async().await.map_err(|e| fail(e.to_string()))?;
    if let Some(first) = rendered.exceptions.first() {
        return Err(fail(format!("{} exceptions raised, the first {first:?}", rendered.exceptions.len())));
    }
    let image = &rendered.image;
    let rgba = rt_runtime::image_out::to_rgba8(image.width, image.height, &image.pixels).into_raw();
    if name == "cornell" {
        CORNELL.with(|c| *c.borrow_mut() = Some(scene));
    }
    Ok(rgba)
}

/// The last Cornell box [`render`] rendered, its mean radiance denoised by
/// the runtime's denoiser stage (guided by the render's albedo, normal and
/// variance) and shown as its camera shows the raw mean (exposure,
/// filmic shoulder, gamma: `examples::cornell::tonemap`): 8-bit RGBA, top
/// row first. Errors come back as the promise's rejection, one line.
#[wasm_bindgen]
pub async fn denoised() -> Result<Vec<u8>, JsValue> {
    say_panics();
    let fail = |e: String| JsValue::from_str(&format!("cornell denoised: {e}"));
    let Some(mut scene) = CORNELL.with(|c| c.borrow_mut().take()) else {
        return Err(fail("the Cornell box is not rendered yet".into()));
    };
    let image = denoise(&mut scene).await;
    CORNELL.with(|c| *c.borrow_mut() = Some(scene));
    let image = image.map_err(fail)?;
    let shown: Vec<_> = image
        .pixels
        .iter()
        .map(|p| examples::cornell::tonemap(p.truncate(), examples::cornell::EXPOSURE).extend(1.0))
        .collect();
    Ok(rt_runtime::image_out::to_rgba8(image.width, image.height, &shown).into_raw())
}

/// `scene`'s last render's radiance through the denoiser stage, awaited.
async fn denoise(scene: &mut Scene) -> Result<examples::Image, String> {
    let denoiser = Denoiser::new(scene).map_err(|e| e.to_string())?.ok_or("the scene writes no guides")?;
    denoiser.run_async(scene).await.map_err(|e| e.to_string())
}

#[wasm_bindgen]
extern "C" {
    #[wasm_bindgen(js_namespace = console)]
    fn error(line: &str);
}

/// A panic in wasm aborts with "unreachable": print its message and place
/// on the console first.
fn say_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| std::panic::set_hook(Box::new(|info| error(&format!("rt-web panicked: {info}")))));
}
