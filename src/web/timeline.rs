//! The playground's timeline bindings: jump to any recorded step and describe the recording.
//! The history itself (checkpoints, quantised positions, thinning) is `crate::sim::replay`, kept
//! in step with the run by `crate::sim::run::Run`.

use super::{js_error, refused, scene_error, to_json, Sim};
use crate::model::refusal::{Code, Message};
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl Sim {
    /// Moves the run to `step` (clamped to the recorded history) by restoring the nearest
    /// checkpoint and re-simulating from it: bit-identical to the original run at that step.
    /// Playing on continues from there. Returns the number of steps re-simulated.
    pub fn seek(&mut self, step: u32) -> Result<u32, JsValue> {
        self.seek_toward(step, u32::MAX)
    }

    /// [`Sim::seek`] re-simulating at most `max_steps`; called again with the same `step` it
    /// goes on where it stopped (the simulation worker slices a long jump this way, so a scene
    /// whose steps take a second shows its progress and answers in between). Returns the steps
    /// re-simulated; the jump is done once `steps()` equals [`Sim::seek_target`].
    pub fn seek_toward(&mut self, step: u32, max_steps: u32) -> Result<u32, JsValue> {
        let resimulated = self.run.seek_toward(step, max_steps).map_err(scene_error)?;
        if self.run.world().step_count() != self.seek_target(step) {
            // A slice on the way: the trails are redrawn once, when the jump arrives.
            return Ok(resimulated);
        }
        // Redraw the trails from the recorded positions before the new step, not a chord of the jump.
        self.redraw_trails();
        Ok(resimulated)
    }

    /// The step a jump to `step` ends on: `step` clamped to the recorded history (the current
    /// step without a timeline).
    pub fn seek_target(&self, step: u32) -> u32 {
        self.run.replay().map_or(self.run.world().step_count(), |r| r.seek_target(step))
    }

    /// The timeline's state as JSON (`crate::sim::replay::ReplayInfo` plus `step`, the current step):
    /// `{step, first_step, end_step, frame_every, frames, frame_bytes, frame_budget_bytes,
    /// capacity_steps, frames_thinned, checkpoint_every, checkpoints, checkpoint_bytes,
    /// checkpoint_budget_bytes, checkpoints_thinned, diverged, edits, note}`.
    pub fn timeline_json(&self) -> Result<String, JsValue> {
        let replay = self.run.replay().ok_or_else(|| refused(Message::new(Code::NoTimeline)))?;
        let mut info = serde_json::to_value(replay.info()).map_err(js_error)?;
        if let Some(object) = info.as_object_mut() {
            object.insert("step".into(), self.run.world().step_count().into());
        }
        Ok(to_json(&info)?)
    }

    /// The recorded digest at `step` as 16 hex digits, or an empty string when that step has
    /// no checkpoint: what a jump to `step` must reproduce.
    pub fn recorded_digest(&self, step: u32) -> String {
        self.run.replay().and_then(|r| r.digest_at(step)).map(|d| format!("{d:016x}")).unwrap_or_default()
    }
}
