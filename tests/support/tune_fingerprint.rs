//! A short tuning run reduced to exact text, shared by `tests/tune_golden.rs` (native) and
//! `tests/web_tune.rs` (wasm in Chromium): every float is written with `{:?}`, the shortest text
//! that reads back to the same bits, so equal fingerprints mean bit-identical runs.

use flockpath::tune::TuneSetup;
use serde::{Deserialize, Serialize};

/// The stored result of a short run (`tests/data/tune-short.json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TuneFingerprint {
    /// What was run.
    pub setup: TuneSetup,
    /// Per generation: `"best_gsum mean_gsum evaluations"`.
    pub generations: Vec<String>,
    /// The best weights s1…s5.
    pub best_weights: Vec<String>,
    /// The best Gsum.
    pub best_gsum: String,
    /// The scene with the best weights as a URL fragment value (what the Tune page applies).
    pub best_scene: String,
}

/// Runs `setup` to the end with the core's tuner.
pub fn fingerprint(setup: &TuneSetup) -> TuneFingerprint {
    let mut tuner = setup.tuner().expect("the stored setup is valid");
    let best = tuner.run(|_| {}).expect("the run scored something");
    TuneFingerprint {
        setup: setup.clone(),
        generations: tuner
            .history()
            .iter()
            .map(|s| format!("{:?} {:?} {}", s.best_gsum, s.mean_gsum, s.evaluations))
            .collect(),
        best_weights: best.weights.iter().map(|w| format!("{w:?}")).collect(),
        best_gsum: format!("{:?}", best.gsum),
        best_scene: flockpath::scene_to_fragment(&tuner.task().scene_with(best.weights)),
    }
}

/// The stored fingerprint.
pub fn stored() -> TuneFingerprint {
    serde_json::from_str(include_str!("../data/tune-short.json")).expect("tests/data/tune-short.json parses")
}
