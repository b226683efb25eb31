//! The playground's activity bindings: the check's report, and setting or clearing the scene's
//! activity (the Share dialog's authoring form). Conversion and errors only: the data and its
//! limits are `crate::model::activity`'s, the check `crate::sim::activity_check`'s.

use super::{scene_error, to_json, Sim};
use crate::model::activity::Activity;
use crate::model::refusal::{Code, Message};
use crate::model::scene::SceneError;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl Sim {
    /// The scene's activity as JSON, or `null`.
    pub fn activity_json(&self) -> Result<String, JsError> {
        to_json(&self.run.world().scene().activity)
    }

    /// The activity check as JSON (`crate::sim::activity_check::Report`: status, step, limit,
    /// conditions with their measured values), or `null` when the scene has no check.
    pub fn activity_report_json(&self) -> Result<String, JsError> {
        to_json(&self.run.activity_report())
    }

    /// Sets the scene's activity from JSON (empty text or `null` removes it), without restarting
    /// the run. Throws with the refused field's path and limit; on error nothing changes.
    pub fn set_activity(&mut self, activity_json: &str) -> Result<(), JsValue> {
        let text = activity_json.trim();
        let activity: Option<Activity> = if text.is_empty() {
            None
        } else {
            serde_json::from_str(text).map_err(|e| {
                scene_error(SceneError::parse(
                    Message::new(Code::SceneBadActivity).with("reason", e.to_string()),
                ))
            })?
        };
        let mut scene = self.run.world().scene().clone();
        scene.activity = activity;
        self.run.edit_scene(scene).map_err(scene_error)
    }
}
