//! The playground's "new seed": a fresh seed drawn in Rust from the browser's
//! `crypto.getRandomValues` (getrandom's `wasm_js` backend), so the page holds no randomness of
//! its own. The seed then enters the scene like a typed one: the run stays reproducible.

use super::refusal;
use wasm_bindgen::prelude::*;

/// A fresh seed in 0…4294967295 for the "new seed" button; throws if the browser has no random
/// source.
#[wasm_bindgen]
pub fn fresh_seed() -> Result<u32, JsValue> {
    crate::rng::fresh_seed().map_err(refusal)
}
