//! The page's diagnosis and metrics-plot bindings on [`Sim`]: agent picking, the inspector's
//! explanation, overlay switches, stuck flags and the metrics time series. Conversion only; the
//! work is done by [`crate::sim::diagnose`], [`crate::sim::run`] (the metric series) and the renderer.

use super::{refused, to_json, Sim};
use crate::model::refusal::{Code, Message};
use crate::render::{Overlays, ARROW_COLORS};
use crate::sim::diagnose;
use crate::sim::metric_series::SERIES;
use glam::Vec2;
use wasm_bindgen::prelude::*;

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

#[wasm_bindgen]
impl Sim {
    /// The agent under scene point `(x, y)` within `tolerance` px of its body (the nearest), or -1.
    pub fn agent_at(&self, x: f32, y: f32, tolerance: f32) -> i32 {
        diagnose::agent_at(self.run.world(), Vec2::new(x, y), tolerance).map_or(-1, |id| id as i32)
    }

    /// Inspects agent `agent` (its explanation is drawn and returned by
    /// [`Sim::explanation_json`]); a negative id inspects nobody.
    pub fn inspect(&mut self, agent: i32) {
        self.renderer.set_inspected(u32::try_from(agent).ok());
    }

    /// The inspected agent, or -1.
    pub fn inspected(&self) -> i32 {
        self.renderer.inspected().map_or(-1, |id| id as i32)
    }

    /// The inspected agent's explanation as JSON (`null` when nobody is inspected or the id is
    /// gone): position, velocity, speed, state, stuck, neighbours, vectors (with the colour of
    /// their arrow), points, applied, values.
    pub fn explanation_json(&self) -> Result<String, JsError> {
        let Some(e) = self.renderer.inspected().and_then(|id| diagnose::explain(self.run.world(), id)) else {
            return Ok("null".into());
        };
        let mut json = e.to_json();
        if let Some(vectors) = json.get_mut("vectors").and_then(|v| v.as_array_mut()) {
            for (k, v) in vectors.iter_mut().enumerate() {
                v["color"] = hex(ARROW_COLORS[k % ARROW_COLORS.len()]).into();
            }
        }
        to_json(&json)
    }

    /// Switches the overlays: stuck rings, the inspected agent's explanation, its cost landscape
    /// (PSO), firefly feelers and brightness.
    pub fn set_overlays(&mut self, stuck: bool, explanation: bool, landscape: bool, fireflies: bool) {
        self.renderer.set_overlays(Overlays { stuck, explanation, landscape, fireflies });
    }

    /// The overlays that are on, as JSON `{stuck, explanation, landscape, fireflies}`.
    pub fn overlays_json(&self) -> Result<String, JsError> {
        let o = self.renderer.overlays();
        to_json(&serde_json::json!({
            "stuck": o.stuck, "explanation": o.explanation, "landscape": o.landscape, "fireflies": o.fireflies,
        }))
    }

    /// Ids of the agents stuck now.
    pub fn stuck_agents(&self) -> Vec<u32> {
        diagnose::stuck_agents(self.run.world())
    }

    /// What the metrics history holds, as JSON: `{every, thinned, samples, series: [{key, label,
    /// unit}], groups: [{name, color}]}`.
    pub fn history_json(&mut self) -> Result<String, JsError> {
        let h = self.run.metric_series();
        let series: Vec<_> = SERIES
            .iter()
            .map(|s| serde_json::json!({"key": s.key, "label": s.label, "unit": s.unit}))
            .collect();
        let groups: Vec<_> = self
            .run
            .world()
            .scene()
            .groups
            .iter()
            .map(|g| serde_json::json!({"name": g.name, "color": g.color}))
            .collect();
        to_json(&serde_json::json!({
            "every": h.every(), "thinned": h.thinned(), "samples": h.steps().len(),
            "series": series, "groups": groups,
        }))
    }

    /// The sampled step numbers of the metrics history.
    pub fn history_steps(&mut self) -> Vec<u32> {
        self.run.metric_series().steps().to_vec()
    }

    /// One series of the metrics history (`key` from `history_json`), for `group` (-1: the
    /// whole run); NaN marks a missing value. Throws for an unknown key or group.
    pub fn history_series(&mut self, key: &str, group: i32) -> Result<Vec<f32>, JsValue> {
        let group = usize::try_from(group).ok();
        if self.run.metric_series().steps().is_empty() {
            return Ok(Vec::new());
        }
        self.run.metric_series().series(key, group).ok_or_else(|| {
            let group = group.map_or_else(|| "None".to_string(), |g| format!("Some({g})"));
            refused(Message::new(Code::NoSeries).with("key", key).with("group", group))
        })
    }

    /// The metrics history as CSV (`step,time_s,group,<series…>`).
    pub fn history_csv(&mut self) -> String {
        let names: Vec<String> = self.run.world().scene().groups.iter().map(|g| g.name.clone()).collect();
        self.run.metric_series().to_csv(&names)
    }
}
