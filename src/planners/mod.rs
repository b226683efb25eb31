//! Crowd planners: one file each behind the [`Planner`] trait, chosen by [`PlannerKind`].

pub mod boids;
pub mod firefly;
pub mod forces;
pub mod igsa;
mod lanes;
pub mod pso;

use crate::diagnose::Explanation;
use crate::geometry::Obstacle;
use crate::rng::Rng;
use crate::scene::Scene;
use crate::spatial::{ObstacleIndex, SpatialGrid};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::ops::Range;

pub use boids::{Arbitration, Boids, BoidsParams};
pub use firefly::{Firefly, FireflyParams};
pub use forces::{Forces, ForcesParams};
pub use igsa::{GroupPath, IgsaParams, IgsaPlanner};
pub use pso::{Pso, PsoParams};

/// Read-only view of the world at the start of a step: planners read it, never write it,
/// so the new velocities do not depend on the order agents are planned in.
pub struct StepContext<'a> {
    /// Positions of all agents (px).
    pub positions: &'a [Vec2],
    /// Velocities of all agents (px/step).
    pub velocities: &'a [Vec2],
    /// Body radius of every agent (px).
    pub radii: &'a [f32],
    /// All agents bucketed for neighbour queries.
    pub grid: &'a SpatialGrid,
    /// Static obstacles with a spatial index.
    pub obstacles: &'a ObstacleIndex,
    /// World size (px).
    pub bounds: Vec2,
    /// Steps simulated so far.
    pub step: u32,
    /// The scene being run: its paths, hills and every group's planner settings (roles).
    pub scene: &'a Scene,
    /// Group index of every agent.
    pub group_of: &'a [u32],
}

/// What a planner knows about the group it steers.
#[derive(Clone, Debug)]
pub struct GroupView {
    /// Global ids of the group's agents (groups own contiguous id ranges).
    pub agents: Range<u32>,
    /// Current goal position and arrival radius, if the group has a goal.
    pub goal: Option<(Vec2, f32)>,
}

/// Copies a boxed planner with all its internal state (replay checkpoints clone the world).
/// Implemented for every `Clone` planner, so a planner only has to derive `Clone`.
pub trait PlannerClone {
    /// A boxed deep copy of this planner.
    fn clone_box(&self) -> Box<dyn Planner>;
}

impl<T: Planner + Clone + 'static> PlannerClone for T {
    fn clone_box(&self) -> Box<dyn Planner> {
        Box::new(self.clone())
    }
}

impl Clone for Box<dyn Planner> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// A crowd planner: computes every new velocity of its group from the old state.
pub trait Planner: PlannerClone {
    /// Largest radius (px) the planner queries neighbours in; sizes the spatial grid.
    fn interaction_radius(&self) -> f32;
    /// Speed limit (px/step); the world checks it after every step.
    fn max_speed(&self) -> f32;
    /// Writes the new velocity of agent `group.agents.start + k` to `new_velocities[k]`.
    fn plan(&mut self, ctx: &StepContext, group: GroupView, rng: &mut Rng, new_velocities: &mut [Vec2]);
    /// Whether the world should let this group's agents move into obstacles instead of pushing
    /// them out. Only for showing a planner's own failure (the original PSO penetrating).
    fn passes_through_obstacles(&self) -> bool {
        false
    }
    /// The path the group follows, for planners that plan one (IGSA group path control).
    fn planned_path(&self) -> Option<&GroupPath> {
        None
    }
    /// Whether the world must rebuild this planner when obstacles or goals are edited during a
    /// run (a planner that planned on the old geometry).
    fn replans_on_edit(&self) -> bool {
        false
    }
    /// Share of the planning ahead done, 0…1 (IGSA plans its path in slices); 1 for planners
    /// that plan nothing ahead. The world does not step a group before it reaches 1.
    fn planning_progress(&self) -> f64 {
        1.0
    }
    /// Runs up to `iterations` more iterations of the planning ahead; returns the share done.
    fn advance_planning(&mut self, iterations: u32) -> f64 {
        let _ = iterations;
        1.0
    }
    /// Why `agent` would move as it does at the next step: the terms of its step recomputed from
    /// `ctx` (forces per component, points looked at, neighbours). Called only for a selected
    /// agent, so it costs nothing per step. The default explains nothing.
    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let _ = (ctx, group, agent);
        Explanation::default()
    }
    /// The objective `agent` minimises at point `p`, for planners that have one (PSO's cost
    /// landscape); `None` otherwise.
    fn cost_at(&self, ctx: &StepContext, group: &GroupView, agent: u32, p: Vec2) -> Option<f32> {
        let _ = (ctx, group, agent, p);
        None
    }
}

/// The closed set of planners, for the URL, the UI and the CLI.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlannerKind {
    /// Reynolds steering (lecture, DESIGN §3.1).
    Boids,
    /// PSO crowd (Chen & Lin 2009, DESIGN §3.2).
    Pso,
    /// Firefly crowd (Zhang, Wei & Chen 2017, DESIGN §3.3).
    Firefly,
    /// Five GA-tunable virtual forces (DESIGN §3.5).
    Forces,
    /// IGSA group path control (Liu & Liu 2022, DESIGN §3.4).
    Igsa,
}

impl PlannerKind {
    /// Every planner, in menu order.
    pub const ALL: &'static [PlannerKind] =
        &[PlannerKind::Boids, PlannerKind::Pso, PlannerKind::Firefly, PlannerKind::Forces, PlannerKind::Igsa];

    /// The CLI / URL name.
    pub fn name(self) -> &'static str {
        match self {
            PlannerKind::Boids => "boids",
            PlannerKind::Pso => "pso",
            PlannerKind::Firefly => "firefly",
            PlannerKind::Forces => "forces",
            PlannerKind::Igsa => "igsa",
        }
    }

    /// Looks a planner up by its CLI name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|k| k.name() == name)
    }

    /// Human-readable label.
    pub fn label(self) -> &'static str {
        match self {
            PlannerKind::Boids => "Boids steering",
            PlannerKind::Pso => "PSO crowd (Chen & Lin 2009)",
            PlannerKind::Firefly => "Firefly crowd (Zhang et al. 2017)",
            PlannerKind::Forces => "Virtual forces (GA-tuned)",
            PlannerKind::Igsa => "IGSA group path (Liu & Liu 2022)",
        }
    }

    /// The default configuration of this planner (its paper's parameters).
    pub fn default_config(self) -> PlannerConfig {
        match self {
            PlannerKind::Boids => PlannerConfig::Boids(BoidsParams::default()),
            PlannerKind::Pso => PlannerConfig::Pso(PsoParams::default()),
            PlannerKind::Firefly => PlannerConfig::Firefly(FireflyParams::default()),
            PlannerKind::Forces => PlannerConfig::Forces(ForcesParams::default()),
            PlannerKind::Igsa => PlannerConfig::Igsa(IgsaParams::default()),
        }
    }

    /// The parameter table that drives the sliders and the docs.
    pub fn param_specs(self) -> &'static [ParamSpec] {
        match self {
            PlannerKind::Boids => BoidsParams::SPECS,
            PlannerKind::Pso => PsoParams::SPECS,
            PlannerKind::Firefly => FireflyParams::SPECS,
            PlannerKind::Forces => ForcesParams::SPECS,
            PlannerKind::Igsa => IgsaParams::SPECS,
        }
    }
}

/// A planner with its parameters, as stored in a scene's group.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "params", rename_all = "snake_case", deny_unknown_fields)]
pub enum PlannerConfig {
    /// Boids steering.
    Boids(BoidsParams),
    /// PSO crowd.
    Pso(PsoParams),
    /// Firefly crowd.
    Firefly(FireflyParams),
    /// Virtual forces.
    Forces(ForcesParams),
    /// IGSA group path control.
    Igsa(IgsaParams),
}

impl Default for PlannerConfig {
    fn default() -> Self {
        PlannerConfig::Boids(BoidsParams::default())
    }
}

impl PlannerConfig {
    /// Which planner this is.
    pub fn kind(&self) -> PlannerKind {
        match self {
            PlannerConfig::Boids(_) => PlannerKind::Boids,
            PlannerConfig::Pso(_) => PlannerKind::Pso,
            PlannerConfig::Firefly(_) => PlannerKind::Firefly,
            PlannerConfig::Forces(_) => PlannerKind::Forces,
            PlannerConfig::Igsa(_) => PlannerKind::Igsa,
        }
    }

    /// Checks every parameter against its table range.
    pub fn validate(&self) -> Result<(), String> {
        self.check().map_err(|e| e.to_string())
    }

    /// [`Self::validate`] with the refused parameter named by its key, value and range.
    pub fn check(&self) -> Result<(), ParamError> {
        let value = serde_json::to_value(self).map_err(|e| ParamError {
            key: String::new(),
            label: "parameters",
            value: e.to_string(),
            allowed: "values that can be written as JSON".into(),
        })?;
        let params = value.get("params").cloned().unwrap_or_default();
        check_params(self.kind().param_specs(), &params)?;
        match self {
            PlannerConfig::Igsa(p) => p.check_waypoints().map_err(|problem| ParamError {
                key: "waypoints".into(),
                label: "Waypoints",
                value: problem,
                allowed: "finite points".into(),
            }),
            _ => Ok(()),
        }
    }

    /// A fresh planner for a group of `count` agents.
    pub fn build(&self, count: usize, obstacles: &[Obstacle]) -> Box<dyn Planner> {
        let _ = count;
        match self {
            PlannerConfig::Boids(p) => Box::new(Boids::new(p.clone())),
            PlannerConfig::Pso(p) => Box::new(Pso::new(p.clone(), obstacles)),
            PlannerConfig::Firefly(p) => Box::new(Firefly::new(p.clone())),
            PlannerConfig::Forces(p) => Box::new(Forces::new(p.clone())),
            // Without its scene the IGSA planner has no path to plan: use `build_for_group`.
            PlannerConfig::Igsa(p) => Box::new(IgsaPlanner::new(p.clone(), &Scene::empty(10.0, 10.0), 0)),
        }
    }

    /// A fresh planner for group `group` of `scene`. Planners that plan ahead (IGSA) read the
    /// scene's geometry and seed here and plan when [`Planner::advance_planning`] is called
    /// (the world does); the others are [`PlannerConfig::build`].
    pub fn build_for_group(&self, scene: &Scene, group: usize) -> Box<dyn Planner> {
        match self {
            PlannerConfig::Igsa(p) => Box::new(IgsaPlanner::planning(p.clone(), scene, group)),
            _ => {
                let count = scene.groups.get(group).map_or(0, |g| g.count as usize);
                self.build(count, &scene.obstacles)
            }
        }
    }

    /// Sets one parameter by its table key from a JSON value; checks the range.
    pub fn set_param(&mut self, key: &str, value: serde_json::Value) -> Result<(), String> {
        let kind = self.kind();
        let spec = kind
            .param_specs()
            .iter()
            .find(|s| s.key == key)
            .ok_or_else(|| format!("{} has no parameter {key:?}", kind.label()))?;
        let mut json = serde_json::to_value(&*self).map_err(|e| e.to_string())?;
        let params = json
            .get_mut("params")
            .and_then(|p| p.as_object_mut())
            .ok_or_else(|| "planner parameters are not an object".to_string())?;
        params.insert(spec.key.to_string(), value);
        let updated: PlannerConfig =
            serde_json::from_value(json).map_err(|e| format!("{}: {e}", spec.label))?;
        updated.validate()?;
        *self = updated;
        Ok(())
    }
}

/// One row of a planner's parameter table: drives a slider, the range check and the docs.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ParamSpec {
    /// JSON key in the planner's params.
    pub key: &'static str,
    /// Label shown next to the slider.
    pub label: &'static str,
    /// Unit shown after the value ("px", "px/step", "" for weights).
    pub unit: &'static str,
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value.
    pub max: f64,
    /// Slider step.
    pub step: f64,
    /// Default (the paper's value where it gives one).
    pub default: f64,
    /// For a choice parameter, its options (the value is one of these strings).
    pub choices: &'static [&'static str],
    /// One-line help.
    pub help: &'static str,
    /// Links may leave this parameter out while it and every later one hold their defaults (see
    /// [`ParamSpec::omitted_at_default`]).
    pub omit_default: bool,
}

impl ParamSpec {
    /// A numeric parameter.
    pub const fn number(
        key: &'static str,
        label: &'static str,
        unit: &'static str,
        range: (f64, f64, f64),
        default: f64,
        help: &'static str,
    ) -> Self {
        Self {
            key,
            label,
            unit,
            min: range.0,
            max: range.1,
            step: range.2,
            default,
            choices: &[],
            help,
            omit_default: false,
        }
    }

    /// A choice among named options; `default` indexes `choices`.
    pub const fn choice(
        key: &'static str,
        label: &'static str,
        choices: &'static [&'static str],
        default: usize,
        help: &'static str,
    ) -> Self {
        Self {
            key,
            label,
            unit: "",
            min: 0.0,
            max: 0.0,
            step: 0.0,
            default: default as f64,
            choices,
            help,
            omit_default: false,
        }
    }

    /// Marks a parameter appended after links existed: while it and every later parameter hold
    /// their defaults, links leave them out, so older links and their fixtures keep their exact
    /// text. Only for parameters whose feature is off by default and sits before its switch in
    /// the table (a feature's settings first, its on/off choice last), so a value left out never
    /// changes a run: when the switch is on, it and everything before it is written.
    pub const fn omitted_at_default(self) -> Self {
        Self { omit_default: true, ..self }
    }

    /// Whether `value` (as the params JSON holds it) is this parameter's default.
    pub fn is_default(&self, value: &serde_json::Value) -> bool {
        if self.choices.is_empty() {
            value.as_f64().is_some_and(|x| x as f32 == self.default as f32)
        } else {
            value.as_str().is_some_and(|s| self.choices.get(self.default as usize) == Some(&s))
        }
    }
}

/// A planner parameter refused by its table.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// The parameter's key in the planner's params (`max_speed`).
    pub key: String,
    /// Its label on the slider (`Max speed`).
    pub label: &'static str,
    /// The refused value as written.
    pub value: String,
    /// What is allowed, with the unit (`a number in 0.1…20 px/step`).
    pub allowed: String,
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} ({}) is {}; allowed: {}", self.label, self.key, self.value, self.allowed)
    }
}

impl ParamSpec {
    /// What this parameter accepts, in words: `a number in 0.1…20 px/step`, `"on" or "off"`.
    pub fn allowed(&self) -> String {
        if self.choices.is_empty() {
            let unit = if self.unit.is_empty() || self.unit == "#" {
                String::new()
            } else {
                format!(" {}", self.unit)
            };
            format!("a number in {}…{}{unit}", self.min, self.max)
        } else {
            let quoted: Vec<String> = self.choices.iter().map(|c| format!("\"{c}\"")).collect();
            format!("one of {}", quoted.join(", "))
        }
    }
}

fn check_params(specs: &[ParamSpec], params: &serde_json::Value) -> Result<(), ParamError> {
    for spec in specs {
        let Some(value) = params.get(spec.key) else { continue };
        let refuse = |shown: String| ParamError {
            key: spec.key.to_string(),
            label: spec.label,
            value: shown,
            allowed: spec.allowed(),
        };
        if spec.choices.is_empty() {
            // JSON cannot hold NaN or infinity: serialising the f32 parameters turned them (and
            // numbers past f32's range, which became infinite) into null.
            if value.is_null() {
                return Err(refuse("not a finite number (too large, infinite or NaN)".into()));
            }
            // Compared as f32, the parameters' type: 0.01 stored as f32 is below 0.01 as f64, and
            // a slider at its minimum must be accepted.
            let x = value.as_f64().ok_or_else(|| refuse(value.to_string()))? as f32;
            if !x.is_finite() || x < spec.min as f32 || x > spec.max as f32 {
                return Err(refuse(crate::scene::number_text(x)));
            }
        } else {
            let s = value.as_str().unwrap_or_default();
            if !spec.choices.contains(&s) {
                return Err(refuse(value.to_string()));
            }
        }
    }
    Ok(())
}

/// Scales `v` down to length `max` if longer.
#[inline]
pub fn limit(v: Vec2, max: f32) -> Vec2 {
    let len2 = v.length_squared();
    if len2 > max * max && len2 > 0.0 {
        v * (max / len2.sqrt())
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_spec_default_matches_the_params_default() {
        for &kind in PlannerKind::ALL {
            let json = serde_json::to_value(kind.default_config()).expect("serialises");
            let params = &json["params"];
            for spec in kind.param_specs() {
                let value = &params[spec.key];
                if spec.choices.is_empty() {
                    let x = value.as_f64().expect("number");
                    assert!(
                        (x - spec.default).abs() < 1e-6,
                        "{}.{}: {x} vs {}",
                        kind.name(),
                        spec.key,
                        spec.default
                    );
                    assert!(
                        spec.min <= x && x <= spec.max,
                        "{}.{} default out of range",
                        kind.name(),
                        spec.key
                    );
                } else {
                    assert_eq!(value.as_str(), Some(spec.choices[spec.default as usize]), "{}", spec.key);
                }
            }
            assert_eq!(kind.default_config().validate(), Ok(()));
        }
    }

    #[test]
    fn set_param_checks_range_and_key() {
        let mut c = PlannerConfig::default();
        assert!(c.set_param("max_speed", serde_json::json!(3.0)).is_ok());
        assert!(matches!(&c, PlannerConfig::Boids(p) if p.max_speed == 3.0));
        assert!(c.set_param("max_speed", serde_json::json!(1e9)).is_err());
        assert!(c.set_param("nope", serde_json::json!(1)).is_err());
        assert!(c.set_param("arbitration", serde_json::json!("priority")).is_ok());
        assert!(c.set_param("arbitration", serde_json::json!("chaos")).is_err());
        assert!(matches!(&c, PlannerConfig::Boids(p) if p.max_speed == 3.0));
    }
}
