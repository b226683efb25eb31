//! The playground's path-editing bindings: an IGSA group's planned path, picking and moving its
//! waypoints. Conversion only; the core plans, validates and flags crossings.

use super::{no_group, refused, scene_error, to_json, Sim};
use crate::model::params::PlannerConfig;
use crate::model::refusal::{Code, Message};
use glam::Vec2;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl Sim {
    /// The path group `group` (0-based) follows, as JSON `{points, crossing, source, length,
    /// max_turn_deg, mean_turn_deg, fitness, evaluations}`, or `"null"` for a group whose
    /// planner plans no path or whose path is still being planned ([`Sim::planning_progress`]).
    pub fn group_path_json(&self, group: u32) -> Result<String, JsError> {
        to_json(&self.run.world().planned_path(group as usize))
    }

    /// The draggable waypoint within `tolerance` scene px of `(x, y)`: JSON `{group, index}` or
    /// `"null"`.
    pub fn pick_waypoint(&self, x: f32, y: f32, tolerance: f32) -> Result<String, JsError> {
        let hit = crate::sim::diagnose::pick_waypoint(self.run.world(), Vec2::new(x, y), tolerance)
            .map(|(group, index)| serde_json::json!({ "group": group, "index": index }));
        to_json(&hit)
    }

    /// Replaces the waypoints of an IGSA group (JSON `[[x, y], …]`; `[]` plans them again) and
    /// lets the group follow the new path without restarting the run. A path that crosses an
    /// obstacle is accepted; the returned path JSON flags the crossing segments (`"null"` after
    /// `[]`: the path is planned in slices, see [`Sim::advance_planning`]).
    pub fn set_group_waypoints(&mut self, group: u32, points_json: &str) -> Result<String, JsValue> {
        let points: Vec<[f32; 2]> = serde_json::from_str(points_json)
            .map_err(|e| refused(Message::new(Code::WaypointsNotList).with("reason", e.to_string())))?;
        let g = group as usize;
        let mut config =
            self.run.world().scene().groups.get(g).ok_or_else(|| no_group(group))?.planner.clone();
        let PlannerConfig::Igsa(params) = &mut config else {
            return Err(refused(Message::new(Code::WaypointsNotIgsa).with("group", u64::from(group) + 1)));
        };
        params.waypoints = points;
        self.run.set_group_planner(g, config).map_err(scene_error)?;
        Ok(self.group_path_json(group)?)
    }
}
