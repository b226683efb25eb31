//! Browser tests of the Tune page's wasm API in headless Chromium (`bash scripts/test-wasm.sh`):
//! the short tuning run of `tests/data/tune-short.json` (computed natively by
//! `tests/tune_golden.rs`) gives the same Gsum bit for bit in wasm, through the core's tuner and
//! through the `TuneRun` handle the page's worker uses, and bad settings become JS errors.
#![cfg(target_arch = "wasm32")]

#[path = "support/tune_fingerprint.rs"]
mod support;

use flockpath::web::tune::TuneRun;
use support::{fingerprint, stored};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::{wasm_bindgen_test, wasm_bindgen_test_configure};

wasm_bindgen_test_configure!(run_in_browser);

/// The message of the JS `Error` a call threw.
fn message(e: JsValue) -> String {
    let error: &js_sys::Error = e.dyn_ref().expect("a JS Error");
    String::from(error.message())
}

/// The `code` a refusal carries for the page to word it in the reader's language.
fn code(e: &JsValue) -> String {
    js_sys::Reflect::get(e, &JsValue::from_str("code")).ok().and_then(|c| c.as_string()).unwrap_or_default()
}

#[wasm_bindgen_test]
fn the_core_tuner_reproduces_the_native_run_bit_for_bit() {
    let expected = stored();
    assert_eq!(fingerprint(&expected.setup), expected);
}

#[wasm_bindgen_test]
fn the_page_handle_runs_the_same_tuning() {
    let expected = stored();
    let setup = serde_json::to_string(&expected.setup).expect("serialises");
    let mut run = TuneRun::new(&setup).expect("valid setup");
    assert_eq!(run.population(), expected.setup.population);
    assert_eq!(run.frames(), expected.setup.frames);
    let mut gsums = Vec::new();
    loop {
        let text = run.generation().expect("a generation");
        let stats: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        if stats.is_null() {
            break;
        }
        let best_so_far = stats["best"]["gsum"].as_f64().expect("a number");
        gsums.push(best_so_far);
        assert_eq!(stats["finished"].as_bool(), Some(run.finished()));
    }
    assert_eq!(gsums.len(), expected.generations.len());
    // The scene the page applies carries exactly the natively tuned weights.
    assert_eq!(run.best_scene_string(), expected.best_scene);
    let best: f64 = expected.best_gsum.parse().expect("a number");
    let last = gsums.last().copied().unwrap_or_default();
    assert!((last - best).abs() <= 1e-12 * best, "{last} vs {best}");
    let history: serde_json::Value = serde_json::from_str(&run.history_json().expect("JSON")).expect("JSON");
    assert_eq!(history.as_array().map(Vec::len), Some(expected.generations.len()));
}

#[wasm_bindgen_test]
fn bad_settings_throw_readable_errors() {
    let refused = TuneRun::new(r#"{"behaviour": "b9"}"#).err();
    assert_eq!(
        refused.as_ref().map(code).as_deref(),
        Some("tune.unknown_behaviour"),
        "coded for the page's words"
    );
    let unknown = refused.map(message).unwrap_or_default();
    assert!(unknown.contains("unknown behaviour"), "{unknown}");
    let population = TuneRun::new(r#"{"population": 1}"#).err().map(message).unwrap_or_default();
    assert!(population.contains("population"), "{population}");
    let refused = TuneRun::new(r#"{"scene": "2.not-a-scene"}"#).err();
    assert_eq!(
        refused.as_ref().map(code).as_deref(),
        Some("scene.parse"),
        "a refused scene keeps its own code"
    );
    let scene = refused.map(message).unwrap_or_default();
    assert!(scene.contains("scene"), "{scene}");
    let typo = TuneRun::new(r#"{"populaton": 20}"#).err().map(message).unwrap_or_default();
    assert!(typo.contains("populaton"), "{typo}");
}
