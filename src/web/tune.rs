//! The Tune page's wasm API: a GA tuning run of the virtual-force weights (DESIGN §3.5) that a Web
//! Worker advances one generation per call, so the page never waits on it. Converts and calls
//! the core's [`Tuner`]; no tuning logic lives here.

use super::{refusal, scene_error, to_json};
use crate::model::codec;
use crate::tune::{TuneError, TuneSetup, Tuner};
use wasm_bindgen::prelude::*;

/// A refused setup as a JS `Error`: a refused scene with its `details`, anything else coded
/// by the core ([`super::coded`]).
fn tune_error(e: TuneError) -> JsValue {
    match e {
        TuneError::Scene(e) => scene_error(e),
        other => refusal(other),
    }
}

/// A tuning run, built from a [`TuneSetup`] in JSON.
#[wasm_bindgen]
pub struct TuneRun {
    tuner: Tuner,
}

#[wasm_bindgen]
impl TuneRun {
    /// Starts a run from JSON `{behaviour, environment, scene, seed, population, generations,
    /// frames}` (every field optional; the paper's settings by default). Throws with the reason
    /// for an unknown behaviour or environment, a bad scene or out-of-range settings.
    #[wasm_bindgen(constructor)]
    pub fn new(setup_json: &str) -> Result<TuneRun, JsValue> {
        console_error_panic_hook::set_once();
        let setup = TuneSetup::from_json(setup_json).map_err(tune_error)?;
        Ok(TuneRun { tuner: setup.tuner().map_err(tune_error)? })
    }

    /// Evaluates one generation and breeds the next: JSON of `GenerationStats` (`generation`,
    /// `best_gsum`, `mean_gsum`, `best: {weights, measures, gsum}`, `evaluations`, `unchanged`,
    /// `finished`), or `"null"` once the run has finished.
    pub fn generation(&mut self) -> Result<String, JsError> {
        to_json(&self.tuner.generation())
    }

    /// Whether the run has stopped (generation limit, or the best unchanged for 5 generations).
    pub fn finished(&self) -> bool {
        self.tuner.is_finished()
    }

    /// Chromosomes per generation.
    pub fn population(&self) -> u32 {
        self.tuner.population().len() as u32
    }

    /// Steps simulated per evaluation.
    pub fn frames(&self) -> u32 {
        self.tuner.task().frames
    }

    /// Agents in the scene being tuned.
    pub fn agents(&self) -> u32 {
        u32::try_from(self.tuner.task().scene.agent_count()).unwrap_or(u32::MAX)
    }

    /// The scene tuned in with the best weights so far (before the first generation: with
    /// the scene's own weights), as a URL fragment value: `index.html#s=<value>` opens it.
    pub fn best_scene_string(&self) -> String {
        let task = self.tuner.task();
        let scene = match self.tuner.best() {
            Some(best) => task.scene_with(best.weights),
            None => task.scene.clone(),
        };
        codec::scene_to_fragment(&scene)
    }

    /// Every generation so far as a JSON array of `GenerationStats`.
    pub fn history_json(&self) -> Result<String, JsError> {
        to_json(&self.tuner.history())
    }
}
