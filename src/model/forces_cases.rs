//! The behaviours (B1–B3) and environments (E1–E3) of the GA-tuned virtual-force paper's
//! experiment (DESIGN §3.5) as plain data: presets build their scenes, `sim::fitness` gives each
//! behaviour its measures' parameters and weights.

use crate::model::refusal::{Code, Message, Refusal};
use serde::{Deserialize, Serialize};

/// A behaviour or environment code that names none of the paper's cases.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum UnknownCase {
    /// Not `b1`, `b2` or `b3`.
    #[error("unknown behaviour {0:?}; known: b1, b2, b3")]
    Behaviour(String),
    /// Not `e1`, `e2` or `e3`.
    #[error("unknown environment {0:?}; known: e1, e2, e3")]
    Environment(String),
}

/// The behaviours of the paper's experiment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Behaviour {
    /// B1: the group moves to a goal keeping a given spacing.
    GroupMoving,
    /// B2: the group follows a moving goal as closely as it can.
    Following,
    /// B3: the group surrounds (guards) a moving goal.
    Guarding,
}

/// The environments of the paper's experiment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Environment {
    /// E1: open space.
    Open,
    /// E2: a wall with a narrow passage.
    Narrow,
    /// E3: cluttered with small obstacles.
    Cluttered,
}

impl Behaviour {
    /// All three, in the paper's order.
    pub const ALL: [Behaviour; 3] = [Behaviour::GroupMoving, Behaviour::Following, Behaviour::Guarding];

    /// `b1`, `b2`, `b3`.
    pub fn code(self) -> &'static str {
        match self {
            Behaviour::GroupMoving => "b1",
            Behaviour::Following => "b2",
            Behaviour::Guarding => "b3",
        }
    }

    /// Looks a behaviour up by `b1`…`b3` (or its name).
    pub fn from_code(code: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|b| b.code().eq_ignore_ascii_case(code) || b.label() == code)
    }

    /// [`Self::from_code`] for user input: an unknown code is refused with the known ones.
    pub fn parse(code: &str) -> Result<Self, UnknownCase> {
        Self::from_code(code).ok_or_else(|| UnknownCase::Behaviour(code.chars().take(40).collect()))
    }

    /// Readable name.
    pub fn label(self) -> &'static str {
        match self {
            Behaviour::GroupMoving => "group moving",
            Behaviour::Following => "following",
            Behaviour::Guarding => "guarding",
        }
    }
}

impl Environment {
    /// All three, in the paper's order.
    pub const ALL: [Environment; 3] = [Environment::Open, Environment::Narrow, Environment::Cluttered];

    /// `e1`, `e2`, `e3`.
    pub fn code(self) -> &'static str {
        match self {
            Environment::Open => "e1",
            Environment::Narrow => "e2",
            Environment::Cluttered => "e3",
        }
    }

    /// Looks an environment up by `e1`…`e3`.
    pub fn from_code(code: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.code().eq_ignore_ascii_case(code))
    }

    /// [`Self::from_code`] for user input: an unknown code is refused with the known ones.
    pub fn parse(code: &str) -> Result<Self, UnknownCase> {
        Self::from_code(code).ok_or_else(|| UnknownCase::Environment(code.chars().take(40).collect()))
    }

    /// Readable name.
    pub fn label(self) -> &'static str {
        match self {
            Environment::Open => "open",
            Environment::Narrow => "narrow passage",
            Environment::Cluttered => "cluttered",
        }
    }
}

impl Refusal for UnknownCase {
    fn message(&self) -> Message {
        match self {
            UnknownCase::Behaviour(name) => {
                Message::new(Code::TuneUnknownBehaviour).with("name", name.clone())
            }
            UnknownCase::Environment(name) => {
                Message::new(Code::TuneUnknownEnvironment).with("name", name.clone())
            }
        }
    }
}
