//! The page's wasm-bindgen API: converts JS values to core calls and core errors to JS `Error`s
//! carrying the core's message. No simulation logic lives here.
//!
//! The frame crosses as a pointer and a length into wasm memory ([`Sim::frame_ptr`],
//! [`Sim::frame_len`]); JS wraps it in a `Uint8ClampedArray` after every call, because the view
//! dies when memory grows.
//!
//! Layer: web (wasm32 only). Uses every layer below; converts and reports errors, no simulation logic.

mod activity;
mod diagnose;

use crate::experiments::validation::{jupedsim, pedpy};
use crate::export::{self, ExportOptions};
use crate::model::codec;
use crate::model::edit::{self, Edit, ItemRef};
use crate::model::params::PlannerKind;
use crate::model::presets;
use crate::model::refusal::{Arg, Code, Message, Refusal};
use crate::model::scene::ViewOptions;
use crate::render::{Renderer, Theme};
use crate::sim::run::{Run, RunOptions};
use glam::Vec2;
use std::fmt::Display;
use wasm_bindgen::prelude::*;

pub mod classroom;
mod compare;
pub mod lab;
mod paths;
mod scorm;
mod seed;
mod timeline;
pub mod tune;
pub mod validation;
mod zoom;

/// Installs the panic hook so a Rust panic shows its message in the console (runs on load).
#[wasm_bindgen(start)]
pub fn init() {
    console_error_panic_hook::set_once();
}

/// A JS `Error` with the core's message, for what no user can cause (a value that does not
/// serialise): a bug, not a refusal.
fn js_error(e: impl Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A refusal as a JS `Error` in the one shape every error crosses in: `message` is the core's
/// English text; `code` (a [`Code`] name) and `args` (its typed arguments: strings, numbers,
/// lists, `{term, english}` words of the strings table and nested `{code, args, message}`)
/// let the page word it from its template in the reader's language.
fn coded(e: &impl Refusal) -> js_sys::Error {
    let message = e.message();
    let error = js_sys::Error::new(&message.to_string());
    // The message serialises to JSON by construction (strings, numbers, maps).
    let shape = serde_json::to_string(&message).ok().and_then(|json| js_sys::JSON::parse(&json).ok());
    let args = shape
        .and_then(|shape| js_sys::Reflect::get(&shape, &JsValue::from_str("args")).ok())
        .unwrap_or_else(|| js_sys::Object::new().into());
    // Setting a property on a fresh Error object cannot fail.
    let _ =
        js_sys::Reflect::set(&error, &JsValue::from_str("code"), &JsValue::from_str(message.code.as_str()));
    let _ = js_sys::Reflect::set(&error, &JsValue::from_str("args"), &args);
    error
}

/// A coded refusal ([`coded`]) as a JS value, for `map_err`.
fn refusal(e: impl Refusal) -> JsValue {
    coded(&e).into()
}

/// A message of `code` with `args` as a refused JS value ([`coded`]).
fn refused(message: Message) -> JsValue {
    refusal(message)
}

/// JSON from the page that does not read as the call's input (an edit with a negative count):
/// `cannot read the <what>: <the reader's words>`.
fn unreadable(what: &'static str, reason: impl Display) -> JsValue {
    refused(
        Message::new(Code::PageUnreadable)
            .with("what", Arg::term(format!("what.{what}"), what))
            .with("reason", reason.to_string()),
    )
}

/// A refused scene as a JS `Error` ([`coded`]), and its `details` property (when the parser had
/// its own words and position) what the page shows behind "details".
fn scene_error(e: crate::model::scene::SceneError) -> JsValue {
    let error = coded(&e);
    if let Some(detail) = e.detail() {
        // Setting a property on a fresh Error object cannot fail.
        let _ = js_sys::Reflect::set(&error, &JsValue::from_str("details"), &JsValue::from_str(detail));
    }
    error.into()
}

/// "there is no group n" (`group` counts from 0, the message from 1).
fn no_group(group: u32) -> JsValue {
    scene_error(crate::model::scene::SceneError::no_such_item("group", u64::from(group) + 1))
}

fn to_json<T: serde::Serialize>(value: &T) -> Result<String, JsError> {
    serde_json::to_string(value).map_err(js_error)
}

/// A run with its renderer: the handle the page keeps. The session logic (recording, timeline,
/// metric series, live edits, planning ahead) is [`Run`]'s; this converts and draws.
#[wasm_bindgen]
pub struct Sim {
    run: Run,
    renderer: Renderer,
}

#[wasm_bindgen]
impl Sim {
    /// Starts a scene from JSON, a fragment value or a URL, rendered at `width × height` device px.
    #[wasm_bindgen(constructor)]
    pub fn new(scene_text: &str, width: u32, height: u32) -> Result<Sim, JsValue> {
        console_error_panic_hook::set_once();
        let scene = codec::scene_from_any(scene_text).map_err(scene_error)?;
        let run = Run::new(scene, RunOptions::page()).map_err(scene_error)?;
        let mut sim = Sim { run, renderer: Renderer::new(width, height) };
        sim.show_scene_view();
        Ok(sim)
    }

    /// Gives the renderer the scene's view options.
    fn show_scene_view(&mut self) {
        let view = self.run.world().scene().view;
        self.renderer.set_trails(view.trails);
        self.renderer.set_trail_fade(view.trail_fade);
    }

    /// Stores new view options in the scene (no restart) and shows them.
    fn set_view(&mut self, view: ViewOptions) -> Result<(), JsValue> {
        self.run.set_view(view).map_err(scene_error)?;
        self.show_scene_view();
        Ok(())
    }

    /// Replaces the scene; on error the current scene keeps running unchanged.
    pub fn load(&mut self, scene_text: &str) -> Result<(), JsValue> {
        let scene = codec::scene_from_any(scene_text).map_err(scene_error)?;
        self.run.load(scene).map_err(scene_error)?;
        self.renderer.set_selection(None);
        self.renderer.clear_trails();
        // A new scene shows whole (an edit of the same scene keeps the zoom).
        self.renderer.fit_view();
        self.show_scene_view();
        Ok(())
    }

    /// Restarts the current scene from step 0 with the same seed.
    pub fn reset(&mut self) -> Result<(), JsValue> {
        self.run.reset().map_err(scene_error)?;
        self.renderer.clear_trails();
        Ok(())
    }

    /// Advances `n` fixed steps, recording each and tracing its trail.
    pub fn step(&mut self, n: u32) {
        // Every step leaves its trail, however many run before the next frame.
        let renderer = &mut self.renderer;
        self.run.step_each(n, |world| renderer.trace_step(world));
    }

    /// Steps simulated since the start.
    pub fn steps(&self) -> u32 {
        self.run.world().step_count()
    }

    /// Sets the canvas backing-store size in device px. The trails are redrawn at the new size
    /// from the recorded positions (entering Present mode mid-run keeps them).
    pub fn resize(&mut self, width: u32, height: u32) {
        let before = (self.renderer.width(), self.renderer.height());
        self.renderer.resize(width, height);
        if (self.renderer.width(), self.renderer.height()) != before {
            self.renderer.render(self.run.world());
            self.redraw_trails();
        }
    }

    /// Draws the current state into the frame.
    pub fn render(&mut self) {
        self.renderer.render(self.run.world());
    }

    /// Address of the RGBA frame in wasm memory.
    pub fn frame_ptr(&self) -> u32 {
        self.renderer.pixels().as_ptr() as u32
    }

    /// Length of the RGBA frame in bytes (`width * height * 4`).
    pub fn frame_len(&self) -> u32 {
        self.renderer.pixels().len() as u32
    }

    /// Frame width in device px.
    pub fn width(&self) -> u32 {
        self.renderer.width()
    }

    /// Frame height in device px.
    pub fn height(&self) -> u32 {
        self.renderer.height()
    }

    /// `[scale, offset_x, offset_y]`: canvas px = scene px · scale + offset.
    pub fn view(&self) -> Vec<f32> {
        let v = self.renderer.view();
        vec![v.scale, v.offset_x, v.offset_y]
    }

    /// The metrics of the run so far as JSON (DESIGN §4 keys).
    pub fn metrics_json(&self) -> Result<String, JsError> {
        to_json(&self.run.world().metrics())
    }

    /// Agent positions as a flat JSON array `[x0, y0, x1, y1, …]` in scene px.
    pub fn positions_json(&self) -> Result<String, JsError> {
        let flat: Vec<f32> = self.run.world().positions().iter().flat_map(|p| [p.x, p.y]).collect();
        to_json(&flat)
    }

    /// The current scene as pretty JSON.
    pub fn scene_json(&self) -> String {
        codec::scene_to_json(self.run.world().scene())
    }

    /// The current scene as a URL fragment value (`2.…`).
    pub fn scene_string(&self) -> String {
        codec::scene_to_fragment(self.run.world().scene())
    }

    /// The scene's seed.
    pub fn seed(&self) -> u32 {
        self.run.world().scene().seed
    }

    /// Changes the seed and restarts the run; on error the current run continues.
    pub fn set_seed(&mut self, seed: u32) -> Result<(), JsValue> {
        self.run.set_seed(seed).map_err(scene_error)?;
        self.renderer.clear_trails();
        Ok(())
    }

    /// Sets one planner parameter of a group (0-based) from a JSON value, live, without a reset.
    pub fn set_group_param(&mut self, group: u32, key: &str, value_json: &str) -> Result<(), JsValue> {
        let value: serde_json::Value = serde_json::from_str(value_json).map_err(|e| {
            refused(Message::new(Code::ValueNotJson).with("key", key).with("reason", e.to_string()))
        })?;
        let mut config = self
            .run
            .world()
            .scene()
            .groups
            .get(group as usize)
            .ok_or_else(|| no_group(group))?
            .planner
            .clone();
        config.set_param(key, value).map_err(refusal)?;
        self.run.set_group_planner(group as usize, config).map_err(scene_error)
    }

    /// Switches a group (0-based) to another planner with that planner's default parameters.
    pub fn set_group_planner(&mut self, group: u32, planner_name: &str) -> Result<(), JsValue> {
        let kind = PlannerKind::parse(planner_name).map_err(refusal)?;
        self.run.set_group_planner(group as usize, kind.default_config()).map_err(scene_error)
    }

    /// Applies an editor operation (JSON of `crate::model::edit::Edit`); on error nothing changes.
    pub fn edit(&mut self, edit_json: &str) -> Result<(), JsValue> {
        let edit: Edit = serde_json::from_str(edit_json).map_err(|e| unreadable("edit", e))?;
        let scene = edit::apply(self.run.world().scene(), &edit).map_err(scene_error)?;
        self.run.edit_scene(scene).map_err(scene_error)?;
        if self.run.world().step_count() == 0 {
            // The agents may have been respawned elsewhere: do not draw the jump as a trail.
            self.renderer.clear_trails();
        }
        Ok(())
    }

    /// The topmost item at scene point `(x, y)` within `tolerance` px: JSON of an item
    /// reference, or `"null"`.
    pub fn pick(&self, x: f32, y: f32, tolerance: f32) -> Result<String, JsError> {
        let world = self.run.world();
        to_json(&edit::pick(world.scene(), world.step_count(), Vec2::new(x, y), tolerance))
    }

    /// Where each goal is at the step shown, as the frame draws it: JSON `[{x, y, radius}]` in
    /// scene px, in the scene's goal order (a moving goal's `position` in the scene is only where
    /// it starts).
    pub fn goals_json(&self) -> Result<String, JsError> {
        let world = self.run.world();
        let goals: Vec<serde_json::Value> = world
            .scene()
            .goals
            .iter()
            .map(|g| {
                let at = g.position_at(world.step_count());
                serde_json::json!({ "x": at.x, "y": at.y, "radius": g.radius })
            })
            .collect();
        to_json(&goals)
    }

    /// The scene check's notices that a goal is too small for the groups heading for it, as JSON
    /// (`[]` when every crowd fits; fields of [`crate::sim::capacity_notice::CapacityNotice`]):
    /// the page words them in the reader's language.
    pub fn capacity_notices_json(&self) -> Result<String, JsError> {
        to_json(&crate::sim::capacity_notice::capacity_notices(self.run.world().scene()))
    }

    /// Outlines an item (JSON item reference) or nothing (`"null"`).
    pub fn set_selection(&mut self, item_json: &str) -> Result<(), JsValue> {
        let item: Option<ItemRef> = serde_json::from_str(item_json)
            .map_err(|e| refused(Message::new(Code::BadSelection).with("reason", e.to_string())))?;
        self.renderer.set_selection(item);
        Ok(())
    }

    /// Turns trails on or off (saved in the scene's view options, so shared links keep it).
    pub fn set_trails(&mut self, on: bool) -> Result<(), JsValue> {
        self.set_view(ViewOptions { trails: on, ..self.run.world().scene().view })
    }

    /// Share of a trail's visibility lost every two steps (0 = permanent, 1 = the newest segments
    /// only); saved in the scene's view options. Throws outside 0…1.
    pub fn set_trail_fade(&mut self, fade: f32) -> Result<(), JsValue> {
        self.set_view(ViewOptions { trail_fade: fade, ..self.run.world().scene().view })
    }

    /// Draws in the render theme `name` ("standard" or "projector") from the next frame on: a
    /// page option, not part of the scene (links and runs do not change). Throws on another name.
    pub fn set_theme(&mut self, name: &str) -> Result<(), JsValue> {
        let theme = Theme::from_name(name).ok_or_else(|| {
            let known: Vec<&str> = Theme::ALL.iter().map(|t| t.name()).collect();
            refused(Message::new(Code::ThemeUnknown).with("name", name).with("known", known))
        })?;
        self.renderer.set_theme(theme);
        Ok(())
    }

    /// The render theme's name.
    pub fn theme(&self) -> String {
        self.renderer.theme().name().to_string()
    }

    /// The recording of the current run as JSON: `{frames, first_step, last_step, every,
    /// thinned, bytes, budget_bytes, capacity_steps, agents}`.
    pub fn recording_json(&self) -> Result<String, JsError> {
        let r = self.run.recording();
        to_json(&serde_json::json!({
            "frames": r.steps().len(),
            "first_step": r.steps().first(),
            "last_step": r.steps().last(),
            "every": r.every(),
            "thinned": r.thinned(),
            "bytes": r.bytes(),
            "budget_bytes": r.budget_bytes(),
            "capacity_steps": r.capacity_steps(),
            "agents": r.agents(),
        }))
    }

    /// The recorded paths as CSV `agent,group,step,time,x,y,vx,vy`.
    pub fn export_paths_csv(&self) -> String {
        export::paths_csv(self.run.world().scene(), self.run.recording())
    }

    /// The recorded paths as JSON.
    pub fn export_paths_json(&self) -> String {
        export::paths_json(self.run.world().scene(), self.run.recording())
    }

    /// A Maya MEL script keyframing one locator per agent at `fps`, scene px × `scale`.
    pub fn export_maya_mel(&self, fps: f32, scale: f32) -> Result<String, JsValue> {
        let options = ExportOptions::checked(fps, scale).map_err(refusal)?;
        Ok(export::maya_mel(self.run.world().scene(), self.run.recording(), options))
    }

    /// A Blender Python script keyframing one empty per agent at `fps`, scene px × `scale`.
    pub fn export_blender_py(&self, fps: f32, scale: f32) -> Result<String, JsValue> {
        let options = ExportOptions::checked(fps, scale).map_err(refusal)?;
        Ok(export::blender_py(self.run.world().scene(), self.run.recording(), options))
    }

    /// The recorded trails as SVG.
    pub fn export_trails_svg(&self) -> String {
        export::trails_svg(self.run.world().scene(), self.run.recording())
    }

    /// The recorded paths as PedPy text (`id frame x y z` in metres), as `flockpath run --pedpy`
    /// writes them.
    pub fn export_pedpy_text(&self) -> String {
        pedpy::recording_text(self.run.world().scene(), self.run.recording())
    }

    /// A Python script that runs the scene in JuPedSim from the recording's starts, as
    /// `flockpath run --jupedsim` writes it.
    pub fn export_jupedsim_script(&self) -> String {
        jupedsim::recording_script(self.run.world().scene(), self.run.recording())
    }

    /// Erases the trails.
    pub fn clear_trails(&mut self) {
        self.renderer.clear_trails();
    }

    /// Share of the planning ahead done (IGSA paths), 0…1. Below 1 the page calls
    /// [`Sim::advance_planning`] within its frame budget instead of stepping (a step would
    /// finish the planning at once: what a script calling `step` wants).
    pub fn planning_progress(&self) -> f64 {
        self.run.world().planning_progress()
    }

    /// Runs up to `evaluations` more objective evaluations of the planning (each is a path's
    /// fitness: at most a few milliseconds even among thousands of obstacles, so the worker
    /// calls this in a loop until its time budget is spent); returns the share done. The path
    /// is the same whatever the slices.
    pub fn advance_planning(&mut self, evaluations: u32) -> f64 {
        self.run.advance_planning(evaluations)
    }

    /// Whether [`Sim::cancel_planning`] has a scene to go back to.
    pub fn can_cancel_planning(&self) -> bool {
        self.run.can_cancel_planning()
    }

    /// Abandons the planning and goes back to the scene shown before it began; returns false
    /// (and changes nothing) when there is none.
    pub fn cancel_planning(&mut self) -> bool {
        if !self.run.cancel_planning() {
            return false;
        }
        self.renderer.set_selection(None);
        self.renderer.clear_trails();
        self.show_scene_view();
        true
    }

    /// The run's digest as 16 hex digits: equal digests mean bit-identical runs.
    pub fn digest(&self) -> String {
        format!("{:016x}", self.run.world().digest())
    }
}

/// The presets as JSON `[{name, description}]`, in menu order.
#[wasm_bindgen]
pub fn presets_json() -> Result<String, JsError> {
    let list: Vec<serde_json::Value> = presets::ALL
        .iter()
        .map(|p| serde_json::json!({ "name": p.name, "description": p.description }))
        .collect();
    to_json(&list)
}

/// The scene JSON of a preset; throws for an unknown name.
#[wasm_bindgen]
pub fn preset_scene_json(name: &str) -> Result<String, JsValue> {
    let preset = presets::lookup(name).map_err(scene_error)?;
    Ok(codec::scene_to_json(&(preset.build)()))
}

/// The planners as JSON `[{name, label, params: [ParamSpec…]}]`, in menu order.
#[wasm_bindgen]
pub fn planners_json() -> Result<String, JsError> {
    let list: Vec<serde_json::Value> = PlannerKind::ALL
        .iter()
        .map(|k| serde_json::json!({ "name": k.name(), "label": k.label(), "params": k.param_specs() }))
        .collect();
    to_json(&list)
}

/// Validates a scene given as JSON, a fragment value or a URL and returns it as JSON; throws with
/// the reason otherwise.
#[wasm_bindgen]
pub fn scene_from_text(text: &str) -> Result<String, JsValue> {
    codec::scene_from_any(text).map(|s| codec::scene_to_json(&s)).map_err(scene_error)
}
