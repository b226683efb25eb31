//! A short tuning run (B2 in E2, population 12, 4 generations of 60 frames, seed 3) must give the
//! fingerprint stored in `tests/data/tune-short.json`: every generation's best and mean Gsum, the
//! best weights and the scene the Tune page would apply. `tests/web_tune.rs` checks the same
//! file in Chromium, so the page's worker tunes exactly as `flockpath tune` does.
//!
//! When the result changes on purpose (the forces, the measures or the GA changed by design),
//! regenerate the file with `FLOCKPATH_BLESS=1 cargo test --test tune_golden` and say why in the
//! commit. When it changes by accident, find the cause: that is what this test is for.

#[path = "support/tune_fingerprint.rs"]
mod support;

use support::{fingerprint, stored, TuneFingerprint};

#[test]
fn the_short_run_matches_the_stored_fingerprint() {
    let expected = stored();
    let actual = fingerprint(&expected.setup);
    if std::env::var_os("FLOCKPATH_BLESS").is_some() {
        let text = serde_json::to_string_pretty(&actual).expect("serialises") + "\n";
        std::fs::write(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/tune-short.json"), text)
            .expect("writes the fingerprint");
        return;
    }
    assert_eq!(
        actual,
        expected,
        "the short tuning run changed; now:\n{}",
        serde_json::to_string_pretty(&actual).unwrap_or_default()
    );
}

#[test]
fn the_stored_run_is_a_real_tuning_run() {
    let f: TuneFingerprint = stored();
    assert_eq!((f.setup.population, f.setup.generations, f.setup.frames), (12, 4, 60));
    assert!(!f.generations.is_empty() && f.generations.len() <= 4);
    let best: f64 = f.best_gsum.parse().expect("a number");
    let first: f64 = f.generations[0].split(' ').next().and_then(|x| x.parse().ok()).expect("a number");
    assert!(best >= first, "the best so far never falls below generation 0's best");
    assert_eq!(f.best_weights.len(), 5);
    assert!(f.best_scene.starts_with("2."), "a v2 fragment: {}", &f.best_scene[..8.min(f.best_scene.len())]);
}
