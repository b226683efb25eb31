//! The playground's timeline bindings: jump to any recorded step and describe the recording.
//! The history itself (checkpoints, quantised positions, thinning) is `crate::sim::replay`.

use super::{js_error, to_json, Sim};
use wasm_bindgen::prelude::*;

impl Sim {
    /// Keeps the timeline's history in step with a change made while the run goes on
    /// (a parameter, a planner, an obstacle): the future after this step is dropped and the
    /// changed world is checkpointed here, so a later jump replays the change where it happened.
    pub(super) fn note_live_edit(&mut self) {
        self.replay.note_edit(&self.world);
        self.recording.truncate_after(self.world.step_count());
    }
}

#[wasm_bindgen]
impl Sim {
    /// Moves the run to `step` (clamped to the recorded history) by restoring the nearest
    /// checkpoint and re-simulating from it: bit-identical to the original run at that step.
    /// Playing on continues from there. Returns the number of steps re-simulated.
    pub fn seek(&mut self, step: u32) -> Result<u32, JsError> {
        // View options (trails, fade) are not history: a jump keeps the ones shown now.
        let view = self.world.scene().view;
        let resimulated = self.replay.seek(step, &mut self.world);
        if self.world.scene().view != view {
            let mut scene = self.world.scene().clone();
            scene.view = view;
            self.world.edit_scene(scene).map_err(js_error)?;
        }
        // Redraw the trails from the recorded positions before the new step (the timeline's
        // quantised frames, every `frame_every`-th step once thinned), not a chord of the jump.
        let from = self.renderer.trail_rebuild_start(&self.world);
        let replay = &self.replay;
        let now = self.world.step_count();
        let recorded =
            replay.frame_steps().iter().copied().skip_while(|&s| s < from).take_while(|&s| s <= now);
        let history = recorded.map_while(|s| Some((s, replay.positions_at(s)?)));
        self.renderer.rebuild_trails(&self.world, history);
        Ok(resimulated)
    }

    /// The timeline's state as JSON (`crate::sim::replay::ReplayInfo` plus `step`, the current step):
    /// `{step, first_step, end_step, frame_every, frames, frame_bytes, frame_budget_bytes,
    /// capacity_steps, frames_thinned, checkpoint_every, checkpoints, checkpoint_bytes,
    /// checkpoint_budget_bytes, checkpoints_thinned, diverged, edits, note}`.
    pub fn timeline_json(&self) -> Result<String, JsError> {
        let mut info = serde_json::to_value(self.replay.info()).map_err(js_error)?;
        if let Some(object) = info.as_object_mut() {
            object.insert("step".into(), self.world.step_count().into());
        }
        to_json(&info)
    }

    /// The recorded digest at `step` as 16 hex digits, or an empty string when that step has
    /// no checkpoint: what a jump to `step` must reproduce.
    pub fn recorded_digest(&self, step: u32) -> String {
        self.replay.digest_at(step).map(|d| format!("{d:016x}")).unwrap_or_default()
    }
}
