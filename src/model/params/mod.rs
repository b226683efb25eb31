//! Each group's planner choice and its parameters as plain data: the closed set of planners
//! ([`PlannerKind`]), a planner with its parameters ([`PlannerConfig`]), one parameter struct
//! per planner (units and the papers' defaults) and the tables ([`ParamSpec`]) that the panel,
//! the codec and validation read. Building a running planner from these is `crate::planners`.

pub mod boids;
pub mod collision_free_speed;
pub mod firefly;
pub mod forces;
pub mod guidance;
pub mod igsa;
pub mod orca;
pub mod pso;
pub mod social_force;
pub mod spec;

use crate::model::refusal::{Arg, Code, Message, Refusal};
pub use boids::{Arbitration, BoidsParams, FlowGuide, Leader, Role};
pub use collision_free_speed::CollisionFreeSpeedParams;
pub use firefly::FireflyParams;
pub use forces::ForcesParams;
pub use guidance::Guidance;
pub use igsa::{IgsaParams, PathOptimizer, WaypointError};
pub use orca::OrcaParams;
pub use pso::PsoParams;
use serde::{Deserialize, Serialize};
pub use social_force::{Ellipse, SocialForceParams};
use spec::check_params;
pub use spec::{ParamError, ParamSpec};

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
    /// ORCA, optimal reciprocal collision avoidance (van den Berg et al. 2011): a baseline.
    Orca,
    /// Social force model (Helbing & Molnár 1995; Helbing, Farkas & Vicsek 2000): a baseline.
    SocialForce,
    /// Collision-free speed model (Tordeux, Chraibi & Seyfried 2016; JuPedSim's default): a
    /// first-order baseline whose speed falls with the spacing ahead.
    CollisionFreeSpeed,
}

impl PlannerKind {
    /// Every planner, in menu order.
    pub const ALL: &'static [PlannerKind] = &[
        PlannerKind::Boids,
        PlannerKind::Pso,
        PlannerKind::Firefly,
        PlannerKind::Forces,
        PlannerKind::Igsa,
        PlannerKind::Orca,
        PlannerKind::SocialForce,
        PlannerKind::CollisionFreeSpeed,
    ];

    /// The CLI / URL name.
    pub fn name(self) -> &'static str {
        match self {
            PlannerKind::Boids => "boids",
            PlannerKind::Pso => "pso",
            PlannerKind::Firefly => "firefly",
            PlannerKind::Forces => "forces",
            PlannerKind::Igsa => "igsa",
            PlannerKind::Orca => "orca",
            PlannerKind::SocialForce => "social_force",
            PlannerKind::CollisionFreeSpeed => "collision_free_speed",
        }
    }

    /// Looks a planner up by its CLI name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|k| k.name() == name)
    }

    /// [`Self::from_name`] for user input: an unknown name is refused with the known ones.
    pub fn parse(name: &str) -> Result<Self, UnknownPlanner> {
        Self::from_name(name).ok_or_else(|| UnknownPlanner::new(name))
    }

    /// The label as a term of the page's strings table (`planner.<name>`), for messages.
    pub fn label_term(self) -> Arg {
        Arg::term(format!("planner.{}", self.name()), self.label())
    }

    /// Human-readable label.
    pub fn label(self) -> &'static str {
        match self {
            PlannerKind::Boids => "Boids steering",
            PlannerKind::Pso => "PSO crowd (Chen & Lin 2009)",
            PlannerKind::Firefly => "Firefly crowd (Zhang et al. 2017)",
            PlannerKind::Forces => "Virtual forces (GA-tuned)",
            PlannerKind::Igsa => "IGSA group path (Liu & Liu 2022)",
            PlannerKind::Orca => "ORCA (van den Berg et al. 2011)",
            PlannerKind::SocialForce => "Social force (Helbing & Molnár 1995)",
            PlannerKind::CollisionFreeSpeed => "Collision-free speed (Tordeux et al. 2016)",
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
            PlannerKind::Orca => PlannerConfig::Orca(OrcaParams::default()),
            PlannerKind::SocialForce => PlannerConfig::SocialForce(SocialForceParams::default()),
            PlannerKind::CollisionFreeSpeed => {
                PlannerConfig::CollisionFreeSpeed(CollisionFreeSpeedParams::default())
            }
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
            PlannerKind::Orca => OrcaParams::SPECS,
            PlannerKind::SocialForce => SocialForceParams::SPECS,
            PlannerKind::CollisionFreeSpeed => CollisionFreeSpeedParams::SPECS,
        }
    }
}

/// A planner name that names no planner. Every front-end words it the same way:
/// `unknown planner "teleport"; known: boids, pso, firefly, forces, igsa`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown planner {name:?}; known: {}", self.known().join(", "))]
pub struct UnknownPlanner {
    /// The name given (at most 40 characters of it).
    pub name: String,
    /// Other words the caller accepts in the same place, listed first (the comparison's
    /// `scene`).
    pub also: &'static [&'static str],
}

impl UnknownPlanner {
    /// The refusal of `name` (cut to 40 characters: a pasted paragraph is not repeated back).
    pub fn new(name: &str) -> Self {
        Self { name: name.chars().take(40).collect(), also: &[] }
    }

    /// The same refusal where `also` are accepted too (listed before the planners).
    pub fn also_accepting(self, also: &'static [&'static str]) -> Self {
        Self { also, ..self }
    }

    /// Every accepted word, in the order the message lists them.
    pub fn known(&self) -> Vec<&'static str> {
        self.also.iter().copied().chain(PlannerKind::ALL.iter().map(|k| k.name())).collect()
    }
}

/// Why [`PlannerConfig::set_param`] refused a value; the planner is left unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SetParamError {
    /// The planner's table has no such key.
    #[error("{} has no parameter {key:?}", planner.label())]
    UnknownKey {
        /// The planner.
        planner: PlannerKind,
        /// The key asked for.
        key: String,
    },
    /// The value has the wrong JSON type for the parameter (a string for a number, …).
    #[error("{label}: {problem}")]
    WrongType {
        /// The planner.
        planner: PlannerKind,
        /// The parameter's key.
        key: &'static str,
        /// The parameter's label on its slider.
        label: &'static str,
        /// The JSON reader's words.
        problem: String,
    },
    /// The value is outside the table's range or choices.
    #[error(transparent)]
    Refused(#[from] ParamError),
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
    /// ORCA.
    Orca(OrcaParams),
    /// Social force model.
    SocialForce(SocialForceParams),
    /// Collision-free speed model.
    CollisionFreeSpeed(CollisionFreeSpeedParams),
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
            PlannerConfig::Orca(_) => PlannerKind::Orca,
            PlannerConfig::SocialForce(_) => PlannerKind::SocialForce,
            PlannerConfig::CollisionFreeSpeed(_) => PlannerKind::CollisionFreeSpeed,
        }
    }

    /// Whether the world gathers this planner's agents in a goal that gathers (DESIGN §4): an
    /// agent that reaches it walks to a free place inside and stops there for good. False for
    /// the planners that keep their own arrival (PSO, firefly, ORCA, social force, the
    /// collision-free speed model: their
    /// avoidance does not see the world's walkers) and for Boids prey, who must go on fleeing;
    /// theirs count as arrived while their centre is inside. The world and the scene check's
    /// capacity notice both ask this.
    pub fn gathers_at_goal(&self) -> bool {
        match self {
            PlannerConfig::Boids(p) => p.role != boids::Role::Prey,
            PlannerConfig::Forces(_) | PlannerConfig::Igsa(_) => true,
            PlannerConfig::Pso(_)
            | PlannerConfig::Firefly(_)
            | PlannerConfig::Orca(_)
            | PlannerConfig::SocialForce(_)
            | PlannerConfig::CollisionFreeSpeed(_) => false,
        }
    }

    /// Whether this planner steers its group down the goal's flow field (one field per distinct
    /// goal point and body radius, `spatial::flow_field`) in a scene with or without
    /// obstacles: Boids with `flow_field: goal` always, ORCA, social force and the
    /// collision-free speed model with flow-field guidance among obstacles (without any their
    /// way is straight).
    pub fn keeps_flow_field(&self, has_obstacles: bool) -> bool {
        match self {
            PlannerConfig::Boids(p) => p.flow_field == FlowGuide::Goal,
            PlannerConfig::Orca(p) => has_obstacles && p.guidance == guidance::Guidance::FlowField,
            PlannerConfig::SocialForce(p) => has_obstacles && p.guidance == guidance::Guidance::FlowField,
            PlannerConfig::CollisionFreeSpeed(p) => {
                has_obstacles && p.guidance == guidance::Guidance::FlowField
            }
            PlannerConfig::Pso(_)
            | PlannerConfig::Firefly(_)
            | PlannerConfig::Forces(_)
            | PlannerConfig::Igsa(_) => false,
        }
    }

    /// Checks every parameter against its table range (and IGSA's edited waypoints); a refusal
    /// names the parameter by its key, value and range.
    pub fn check(&self) -> Result<(), ParamError> {
        check_params(self.kind().name(), self.kind().param_specs(), &self.params_json())?;
        match self {
            PlannerConfig::Igsa(p) => p.check_waypoints().map_err(|problem| ParamError {
                planner: PlannerKind::Igsa.name(),
                key: "waypoints".into(),
                label: "Waypoints",
                value: problem.message().into(),
                allowed: "finite points".into(),
            }),
            _ => Ok(()),
        }
    }

    /// This planner's parameters as the JSON object a scene holds (`{"max_speed": 2, …}`).
    pub fn params_json(&self) -> serde_json::Map<String, serde_json::Value> {
        // Serialising a parameter struct cannot fail: derived `Serialize`, string keys only, and
        // serde_json writes a non-finite float as null (which check_params then refuses).
        match serde_json::to_value(self).expect("planner parameters always serialise") {
            serde_json::Value::Object(mut tagged) => match tagged.remove("params") {
                Some(serde_json::Value::Object(params)) => params,
                _ => serde_json::Map::new(),
            },
            _ => serde_json::Map::new(),
        }
    }

    /// Sets one parameter by its table key from a JSON value; checks the range. On an error
    /// nothing changes.
    pub fn set_param(&mut self, key: &str, value: serde_json::Value) -> Result<(), SetParamError> {
        let kind = self.kind();
        let spec = kind
            .param_specs()
            .iter()
            .find(|s| s.key == key)
            .ok_or_else(|| SetParamError::UnknownKey { planner: kind, key: key.to_string() })?;
        let mut params = self.params_json();
        params.insert(spec.key.to_string(), value);
        let tagged = serde_json::json!({ "kind": kind.name(), "params": params });
        let updated: PlannerConfig =
            serde_json::from_value(tagged).map_err(|e| SetParamError::WrongType {
                planner: kind,
                key: spec.key,
                label: spec.label,
                problem: e.to_string(),
            })?;
        updated.check()?;
        *self = updated;
        Ok(())
    }
}

impl Refusal for UnknownPlanner {
    fn message(&self) -> Message {
        Message::new(Code::PlannerUnknown).with("name", self.name.clone()).with("known", self.known())
    }
}

/// A parameter's label as a term of the page's strings table (`param.<planner>.<key>`).
fn param_label(planner: &str, key: &str, label: &str) -> Arg {
    Arg::term(format!("param.{planner}.{key}"), label)
}

impl Refusal for ParamError {
    fn message(&self) -> Message {
        Message::new(Code::ParamRange)
            .with("label", param_label(self.planner, &self.key, self.label))
            .with("key", self.key.clone())
            .with("value", self.value.clone())
            .with("allowed", self.allowed.clone())
    }
}

impl Refusal for SetParamError {
    fn message(&self) -> Message {
        match self {
            SetParamError::UnknownKey { planner, key } => Message::new(Code::ParamUnknown)
                .with("planner", planner.label_term())
                .with("key", key.clone()),
            SetParamError::WrongType { planner, key, label, problem } => Message::new(Code::ParamType)
                .with("label", param_label(planner.name(), key, label))
                .with("problem", problem.clone()),
            SetParamError::Refused(e) => e.message(),
        }
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
            assert_eq!(kind.default_config().check(), Ok(()));
        }
    }

    #[test]
    fn unknown_planners_are_refused_in_one_wording() {
        assert_eq!(PlannerKind::parse("pso"), Ok(PlannerKind::Pso));
        let names: Vec<&str> = PlannerKind::ALL.iter().map(|k| k.name()).collect();
        let e = PlannerKind::parse("teleport").expect_err("no such planner");
        assert_eq!(e.to_string(), format!("unknown planner \"teleport\"; known: {}", names.join(", ")));
        let e = e.also_accepting(&["scene"]);
        assert_eq!(
            e.to_string(),
            format!("unknown planner \"teleport\"; known: scene, {}", names.join(", "))
        );
        let long = "x".repeat(500);
        assert_eq!(PlannerKind::parse(&long).expect_err("long").name.len(), 40, "a pasted paragraph is cut");
    }

    #[test]
    fn set_param_checks_range_and_key() {
        let mut c = PlannerConfig::default();
        assert!(c.set_param("max_speed", serde_json::json!(3.0)).is_ok());
        assert!(matches!(&c, PlannerConfig::Boids(p) if p.max_speed == 3.0));
        let refused = c.set_param("max_speed", serde_json::json!(1e9)).expect_err("out of range");
        assert!(matches!(&refused, SetParamError::Refused(e) if e.key == "max_speed"), "{refused:?}");
        assert_eq!(
            c.set_param("nope", serde_json::json!(1)),
            Err(SetParamError::UnknownKey { planner: PlannerKind::Boids, key: "nope".into() })
        );
        let wrong = c.set_param("max_speed", serde_json::json!("fast")).expect_err("a string");
        assert!(matches!(&wrong, SetParamError::WrongType { label: "Max speed", .. }), "{wrong:?}");
        assert!(c.set_param("arbitration", serde_json::json!("priority")).is_ok());
        assert!(c.set_param("arbitration", serde_json::json!("chaos")).is_err());
        assert!(matches!(&c, PlannerConfig::Boids(p) if p.max_speed == 3.0));
    }
}
