//! Each group's planner choice and its parameters as plain data: the closed set of planners
//! ([`PlannerKind`]), a planner with its parameters ([`PlannerConfig`]), one parameter struct
//! per planner (units and the papers' defaults) and the tables ([`ParamSpec`]) that the panel,
//! the codec and validation read. Building a running planner from these is `crate::planners`.

pub mod boids;
pub mod firefly;
pub mod forces;
pub mod igsa;
pub mod pso;

pub use boids::{Arbitration, BoidsParams, FlowGuide, Leader, Role};
pub use firefly::FireflyParams;
pub use forces::ForcesParams;
pub use igsa::{IgsaParams, PathOptimizer};
pub use pso::PsoParams;
use serde::{Deserialize, Serialize};

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
                return Err(refuse(crate::model::scene::number_text(x)));
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
