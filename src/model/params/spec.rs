//! The parameter table of a planner: one row per parameter ([`ParamSpec`]: label, unit, range,
//! default, help) that drives a slider, the range check and the docs, and the refusal a row
//! gives ([`ParamError`]).

use crate::model::refusal::{Code, Message};
use serde::Serialize;

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
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{label} ({key}) is {value}; allowed: {allowed}")]
pub struct ParamError {
    /// The name of the planner whose table refused it (`boids`).
    pub planner: &'static str,
    /// The parameter's key in the planner's params (`max_speed`).
    pub key: String,
    /// Its label on the slider (`Max speed`).
    pub label: &'static str,
    /// The refused value as written (text), or in words (a `value.*` message).
    pub value: crate::model::refusal::Arg,
    /// What is allowed, with the unit (`a number in 0.1…20 px/step`).
    pub allowed: String,
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

pub(super) fn check_params(
    planner: &'static str,
    specs: &[ParamSpec],
    params: &serde_json::Map<String, serde_json::Value>,
) -> Result<(), ParamError> {
    for spec in specs {
        let Some(value) = params.get(spec.key) else { continue };
        let refuse = |shown: crate::model::refusal::Arg| ParamError {
            planner,
            key: spec.key.to_string(),
            label: spec.label,
            value: shown,
            allowed: spec.allowed(),
        };
        if spec.choices.is_empty() {
            // JSON cannot hold NaN or infinity: serialising the f32 parameters turned them (and
            // numbers past f32's range, which became infinite) into null.
            if value.is_null() {
                return Err(refuse(Message::new(Code::ValueNotFinite).into()));
            }
            // Compared as f32, the parameters' type: 0.01 stored as f32 is below 0.01 as f64, and
            // a slider at its minimum must be accepted.
            let x = value.as_f64().ok_or_else(|| refuse(value.to_string().into()))? as f32;
            if !x.is_finite() || x < spec.min as f32 || x > spec.max as f32 {
                return Err(refuse(number_text(x).into()));
            }
        } else {
            let s = value.as_str().unwrap_or_default();
            if !spec.choices.contains(&s) {
                return Err(refuse(value.to_string().into()));
            }
        }
    }
    Ok(())
}

/// A number as a person writes it: `1e30` rather than thirty-one digits, `NaN`, `infinite`.
pub fn number_text(x: f32) -> String {
    if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        if x > 0.0 { "infinite (too large a number)" } else { "-infinite (too large a number)" }.into()
    } else if x != 0.0 && (x.abs() >= 1e7 || x.abs() < 1e-4) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}
