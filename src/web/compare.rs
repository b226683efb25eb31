//! The compare page's bindings: an opaque handle over `crate::sim::compare::Comparison` with one
//! renderer per pane. Conversion and errors only; the panes, series and summary are the core's.

use super::{js_error, refusal, refused, scene_error, to_json};
use crate::model::codec;
use crate::model::params::PlannerKind;
use crate::model::refusal::{Code, Message};
use crate::model::scene::Scene;
use crate::render::Renderer;
use crate::sim::compare::{Comparison, ComparisonSpec, MAX_PANES, PANE_COLORS, PANE_NAMES, SERIES_KEYS};
use wasm_bindgen::prelude::*;

/// A comparison with its pane renderers: the handle the compare page keeps.
#[wasm_bindgen]
pub struct CompareSim {
    comparison: Comparison,
    renderers: Vec<Renderer>,
    width: u32,
    height: u32,
}

/// The spec a link's `c=` value asks for: empty for the default (the scene's planners against
/// another).
fn spec_for(scene: &Scene, spec_text: &str) -> Result<ComparisonSpec, JsValue> {
    if spec_text.trim().is_empty() {
        Ok(ComparisonSpec::default_for(scene))
    } else {
        ComparisonSpec::parse(spec_text).map_err(refusal)
    }
}

/// A pane's planner by name: `None` for `"scene"` (the scene's own planners).
fn pane_planner(name: &str) -> Result<Option<PlannerKind>, JsValue> {
    if name == "scene" {
        return Ok(None);
    }
    PlannerKind::parse(name).map(Some).map_err(|e| refusal(e.also_accepting(&["scene"])))
}

#[wasm_bindgen]
impl CompareSim {
    /// Starts a comparison of a scene (JSON, fragment value or URL) with a spec string (`1.…`;
    /// empty for the default: the scene's planners against another), each pane rendered at
    /// `width × height` device px.
    #[wasm_bindgen(constructor)]
    pub fn new(scene_text: &str, spec_text: &str, width: u32, height: u32) -> Result<CompareSim, JsValue> {
        console_error_panic_hook::set_once();
        let scene = codec::scene_from_any(scene_text).map_err(scene_error)?;
        let spec = spec_for(&scene, spec_text)?;
        let comparison = Comparison::new(scene, spec).map_err(refusal)?;
        let mut sim = CompareSim { comparison, renderers: Vec::new(), width, height };
        sim.fit_renderers();
        Ok(sim)
    }

    /// One renderer per pane at the current size, with the scene's view options.
    fn fit_renderers(&mut self) {
        let view = self.comparison.scene().view;
        let panes = self.comparison.panes().len();
        self.renderers.truncate(panes);
        while self.renderers.len() < panes {
            self.renderers.push(Renderer::new(self.width, self.height));
        }
        for r in &mut self.renderers {
            r.set_trails(view.trails);
            r.set_trail_fade(view.trail_fade);
            r.clear_trails();
        }
    }

    /// Number of panes.
    pub fn pane_count(&self) -> u32 {
        self.comparison.panes().len() as u32
    }

    /// Most panes a comparison may have.
    pub fn max_panes(&self) -> u32 {
        MAX_PANES as u32
    }

    /// Steps simulated (every pane has the same).
    pub fn steps(&self) -> u32 {
        self.comparison.step_count()
    }

    /// Every pane's step count as JSON `[n, …]` (for checking the lockstep).
    pub fn pane_steps_json(&self) -> Result<String, JsError> {
        let steps: Vec<u32> = self.comparison.panes().iter().map(|p| p.world().step_count()).collect();
        to_json(&steps)
    }

    /// Advances every pane `n` steps, tracing each step's trail.
    pub fn step(&mut self, n: u32) {
        for _ in 0..n {
            self.comparison.step_n(1);
            for (r, p) in self.renderers.iter_mut().zip(self.comparison.panes()) {
                r.trace_step(p.world());
            }
        }
    }

    /// Restarts every pane from step 0.
    pub fn reset(&mut self) -> Result<(), JsValue> {
        self.comparison.reset().map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Replaces the scene, keeping the panes' planners; on error nothing changes.
    pub fn load(&mut self, scene_text: &str) -> Result<(), JsValue> {
        let scene = codec::scene_from_any(scene_text).map_err(scene_error)?;
        self.comparison.set_scene(scene).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Replaces the scene and the panes together (a link that changes both): each is checked
    /// against the other, not against the one it replaces, so a one-group scene may replace a
    /// two-group one whose spec set group 2. On error nothing changes.
    pub fn load_with_spec(&mut self, scene_text: &str, spec_text: &str) -> Result<(), JsValue> {
        let scene = codec::scene_from_any(scene_text).map_err(scene_error)?;
        let spec = spec_for(&scene, spec_text)?;
        self.comparison = Comparison::new(scene, spec).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Replaces the panes by a spec string (restarts); on error nothing changes.
    pub fn set_spec(&mut self, spec_text: &str) -> Result<(), JsValue> {
        let spec = ComparisonSpec::parse(spec_text).map_err(refusal)?;
        self.comparison.set_spec(spec).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Sets pane `pane`'s planner for every group (`"scene"` for the scene's own planners), with
    /// that planner's defaults; restarts every pane.
    pub fn set_pane_planner(&mut self, pane: u32, planner_name: &str) -> Result<(), JsValue> {
        let kind = pane_planner(planner_name)?;
        self.comparison.set_pane_planner(pane as usize, kind).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Sets one parameter of pane `pane`'s every-group planner from a JSON value; restarts.
    pub fn set_pane_param(&mut self, pane: u32, key: &str, value_json: &str) -> Result<(), JsValue> {
        let value: serde_json::Value = serde_json::from_str(value_json).map_err(|e| {
            refused(Message::new(Code::ValueNotJson).with("key", key).with("reason", e.to_string()))
        })?;
        self.comparison.set_pane_param(pane as usize, key, value).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Adds a pane running `planner_name` (or `"scene"`); restarts. Throws past the limit.
    pub fn add_pane(&mut self, planner_name: &str) -> Result<(), JsValue> {
        let kind = pane_planner(planner_name)?;
        self.comparison.add_pane(kind).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Removes pane `pane`; restarts. Throws for the last pane.
    pub fn remove_pane(&mut self, pane: u32) -> Result<(), JsValue> {
        self.comparison.remove_pane(pane as usize).map_err(refusal)?;
        self.fit_renderers();
        Ok(())
    }

    /// Sets every pane's canvas size in device px.
    pub fn resize(&mut self, width: u32, height: u32) {
        self.width = width;
        self.height = height;
        for r in &mut self.renderers {
            r.resize(width, height);
        }
    }

    /// Draws pane `pane` into its frame (no-op for a missing pane).
    pub fn render(&mut self, pane: u32) {
        if let (Some(r), Some(p)) =
            (self.renderers.get_mut(pane as usize), self.comparison.panes().get(pane as usize))
        {
            r.render(p.world());
        }
    }

    /// Address of pane `pane`'s RGBA frame in wasm memory (0 for a missing pane).
    pub fn frame_ptr(&self, pane: u32) -> u32 {
        self.renderers.get(pane as usize).map_or(0, |r| r.pixels().as_ptr() as u32)
    }

    /// Length of pane `pane`'s RGBA frame in bytes (0 for a missing pane).
    pub fn frame_len(&self, pane: u32) -> u32 {
        self.renderers.get(pane as usize).map_or(0, |r| r.pixels().len() as u32)
    }

    /// Frame width in device px.
    pub fn width(&self) -> u32 {
        self.renderers.first().map_or(self.width, Renderer::width)
    }

    /// Frame height in device px.
    pub fn height(&self) -> u32 {
        self.renderers.first().map_or(self.height, Renderer::height)
    }

    /// The panes as JSON `[{pane, label, color, planner, per_group, groups, params, spec}]`:
    /// `planner` is the every-group planner's name or `"scene"`, `params` its parameters (or
    /// null), `groups` every group's `{name, planner, params}` as the pane runs it, `spec` the
    /// pane's part of the spec string.
    pub fn panes_json(&self) -> Result<String, JsError> {
        let list: Vec<serde_json::Value> = self
            .comparison
            .panes()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let (planner, params) = match &p.spec().all {
                    Some(c) => (c.kind().name(), serde_json::Value::Object(c.params_json())),
                    None => ("scene", serde_json::Value::Null),
                };
                let one = ComparisonSpec { panes: vec![p.spec().clone()] }.to_spec_string();
                // Every group's planner as this pane runs it, for the page to word a per-group
                // pane's label in the reader's language.
                let groups: Vec<serde_json::Value> = p
                    .world()
                    .scene()
                    .groups
                    .iter()
                    .map(|g| {
                        serde_json::json!({
                            "name": g.name,
                            "planner": g.planner.kind().name(),
                            "params": serde_json::Value::Object(g.planner.params_json()),
                        })
                    })
                    .collect();
                serde_json::json!({
                    "pane": PANE_NAMES.get(i).copied().unwrap_or_default(),
                    "label": p.label(),
                    "color": PANE_COLORS.get(i).copied().unwrap_or_default(),
                    "planner": planner,
                    "per_group": !p.spec().groups.is_empty(),
                    "groups": groups,
                    "params": params,
                    "spec": one.split_once('.').map(|(_, body)| body).unwrap_or_default(),
                })
            })
            .collect();
        to_json(&list)
    }

    /// Every pane's metrics as JSON `[Metrics…]` (DESIGN §4 keys), in pane order.
    pub fn metrics_json(&self) -> Result<String, JsError> {
        to_json(&self.comparison.metrics())
    }

    /// The time series of every pane as JSON `{keys, panes: [{pane, label, color, every, steps,
    /// arrived_share, collisions_agent_agent, penetrations_agent_obstacle, speed, stuck_agents}]}`.
    pub fn series_json(&self) -> Result<String, JsError> {
        let panes: Vec<serde_json::Value> = self
            .comparison
            .panes()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut v = serde_json::to_value(p.series()).map_err(js_error)?;
                if let Some(o) = v.as_object_mut() {
                    o.insert("pane".into(), PANE_NAMES.get(i).copied().unwrap_or_default().into());
                    o.insert("label".into(), p.label().into());
                    o.insert("color".into(), PANE_COLORS.get(i).copied().unwrap_or_default().into());
                }
                Ok(v)
            })
            .collect::<Result<_, JsError>>()?;
        to_json(&serde_json::json!({ "keys": SERIES_KEYS, "panes": panes }))
    }

    /// The summary table as JSON `[{pane, label, steps, agents, arrived_share, …}]`.
    pub fn summary_json(&self) -> Result<String, JsError> {
        to_json(&self.comparison.summary())
    }

    /// The summary table as CSV (one row per pane).
    pub fn summary_csv(&self) -> String {
        self.comparison.summary_csv()
    }

    /// The comparison spec string (`1.…`): `compare.html#s=<scene>&c=<this>` reopens it.
    pub fn spec_string(&self) -> String {
        self.comparison.spec().to_spec_string()
    }

    /// The scene's URL fragment value.
    pub fn scene_string(&self) -> String {
        codec::scene_to_fragment(self.comparison.scene())
    }

    /// The scene as pretty JSON.
    pub fn scene_json(&self) -> String {
        codec::scene_to_json(self.comparison.scene())
    }

    /// The activity check over the panes as JSON (`crate::sim::activity_check::Report`), or
    /// `null` when the scene has no check.
    pub fn activity_report_json(&self) -> Result<String, JsError> {
        to_json(&self.comparison.activity_report())
    }

    /// Every pane's digest as JSON `["16 hex digits", …]`.
    pub fn digests_json(&self) -> Result<String, JsError> {
        let list: Vec<String> = self.comparison.digests().iter().map(|d| format!("{d:016x}")).collect();
        to_json(&list)
    }
}

/// Checks a comparison spec string; returns it in canonical form (every value written) or
/// throws with the reason.
#[wasm_bindgen]
pub fn compare_spec_check(spec_text: &str) -> Result<String, JsValue> {
    ComparisonSpec::parse(spec_text).map(|s| s.to_spec_string()).map_err(refusal)
}
