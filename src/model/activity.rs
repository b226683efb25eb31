//! A short classroom activity a scene may carry: a prompt, optionally a prediction question asked
//! before the run starts, and a goal checked on the run's metrics (`crate::sim::activity_check`).
//!
//! Plain data and its limits only. Every text is plain text: the pages show it as text, never as
//! markup. The metric keys are the metrics JSON's own (DESIGN §4), so an activity reads like the
//! numbers the page shows:
//!
//! ```
//! use flockpath::model::activity::Activity;
//! let json = r#"{
//!   "prompt": "Will the flock get past the pillars?",
//!   "prediction": {"question": "How many arrive?", "choices": ["under half", "most", "all"]},
//!   "check": {"steps": 1500, "conditions": [
//!     {"metric": "arrived_share", "op": ">=", "value": 0.9},
//!     {"metric": "penetrations_agent_obstacle", "op": "=", "value": 0}
//!   ]}
//! }"#;
//! let activity: Activity = serde_json::from_str(json).expect("an activity");
//! assert_eq!(activity.validate(1), Ok(()));
//! ```

use crate::model::refusal::{Arg, Code, Message};
use serde::{Deserialize, Serialize};

/// Longest prompt (characters).
pub const MAX_PROMPT_CHARS: usize = 1_000;
/// Longest prediction question (characters).
pub const MAX_QUESTION_CHARS: usize = 300;
/// Longest prediction choice (characters).
pub const MAX_CHOICE_CHARS: usize = 120;
/// Fewest and most prediction choices.
pub const MIN_CHOICES: usize = 2;
/// Most prediction choices.
pub const MAX_CHOICES: usize = 6;
/// Most conditions a check may have.
pub const MAX_CONDITIONS: usize = 8;
/// Largest step limit of a check (a bit over 4.6 hours of simulated time at 60 steps/s).
pub const MAX_CHECK_STEPS: u32 = 1_000_000;
/// Panes a comparison may name (the compare page shows at most four: A…D).
pub const MAX_PANES: u32 = 4;

/// The metrics keys a condition may test (DESIGN §4 and `src/sim/metrics.rs`), each a number
/// both for the whole run and per group.
pub const METRIC_KEYS: &[&str] = &[
    "arrived_share",
    "mean_time_to_goal",
    "mean_time_to_goal_s",
    "collisions_agent_agent",
    "collisions_moving",
    "penetrations_agent_obstacle",
    "mean_speed",
    "mean_speed_m_s",
    "mean_speed_near_obstacles",
    "mean_path_length",
    "mean_path_length_m",
    "mean_turn_deg",
    "max_turn_deg",
    "stuck_agents",
    "queue_order",
];

/// A scene's activity: what to think about, what to predict, what counts as success.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Activity {
    /// What the student is asked to do or think about (plain text; line breaks kept).
    pub prompt: String,
    /// A multiple-choice question answered before the first Play.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub prediction: Option<Prediction>,
    /// The goal, checked on the metrics while the run goes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check: Option<Check>,
}

/// A prediction question with its choices.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prediction {
    /// The question (plain text).
    pub question: String,
    /// The answers to choose from, in order.
    pub choices: Vec<String>,
    /// Index (from 0) of the answer the author expects, shown with the result; none for an
    /// open question.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expected: Option<u32>,
}

/// The goal: every condition holds at some step up to `steps` ("met" at the first such step),
/// else the run is "missed" at step `steps`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Check {
    /// The step limit: the check ends here if the goal was not met before.
    pub steps: u32,
    /// What must hold, all at the same step.
    pub conditions: Vec<Condition>,
}

/// One condition of a check.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Condition {
    /// A metric compared with a number: `{"metric": "arrived_share", "op": ">=", "value": 0.9}`,
    /// for the whole run or one group (`"group": 0`) or, on the compare page, one pane
    /// (`"pane": 1`; without it, every pane).
    Metric(MetricCondition),
    /// Who reaches an arrived share first: `{"before": [{"pane": 1}, {"pane": 0}], "share": 0.9}`
    /// ("pane B arrives before pane A"). Holds once the first has reached `share` and the second
    /// has not reached it at the same step or earlier.
    Before(BeforeCondition),
}

/// A metric compared with a number.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MetricCondition {
    /// One of [`METRIC_KEYS`].
    pub metric: String,
    /// The comparison.
    pub op: Op,
    /// The number compared with (shares 0…1, counts, px/step …, in the metric's unit).
    pub value: f64,
    /// A group (from 0) instead of the whole run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<u32>,
    /// A pane of the compare page (from 0: A = 0) instead of every pane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pane: Option<u32>,
}

/// "`before[0]` reaches `share` arrived before `before[1]` does".
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeforeCondition {
    /// The one that should arrive first, and the other.
    pub before: [Subject; 2],
    /// The arrived share that counts as "arrived" (0 excluded … 1). Default 0.9.
    #[serde(default = "default_share")]
    pub share: f64,
}

fn default_share() -> f64 {
    0.9
}

/// Whose metrics: a group of the scene, or a pane of the compare page (on the compare page a
/// group is pane A's group).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Subject {
    /// A group, from 0.
    Group(u32),
    /// A pane, from 0 (A = 0).
    Pane(u32),
}

/// A comparison of a measured value with a condition's number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Op {
    /// At least.
    #[serde(rename = ">=")]
    AtLeast,
    /// At most.
    #[serde(rename = "<=")]
    AtMost,
    /// More than.
    #[serde(rename = ">")]
    Above,
    /// Less than.
    #[serde(rename = "<")]
    Below,
    /// Equal to.
    #[serde(rename = "=")]
    Equal,
}

impl Op {
    /// Whether `measured` compares with `value` this way.
    pub fn holds(self, measured: f64, value: f64) -> bool {
        match self {
            Op::AtLeast => measured >= value,
            Op::AtMost => measured <= value,
            Op::Above => measured > value,
            Op::Below => measured < value,
            Op::Equal => measured == value,
        }
    }
}

/// A refused activity field: its path in the scene JSON (`activity.prediction.choices[2]`), the
/// value as shown, and what is allowed. The scene turns it into a field refusal.
#[derive(Clone, Debug, PartialEq)]
pub struct ActivityFault {
    /// Path from the scene's root.
    pub path: String,
    /// The refused value, shortened (text as written, or a `value.*` message).
    pub value: Arg,
    /// What the field accepts.
    pub allowed: String,
}

fn fault<T>(
    path: impl Into<String>,
    value: impl Into<Arg>,
    allowed: impl Into<String>,
) -> Result<T, ActivityFault> {
    Err(ActivityFault { path: path.into(), value: value.into(), allowed: allowed.into() })
}

/// A text's description as a refused value: its length, and its start (a name or prompt of
/// megabytes is not repeated in the message).
pub(crate) fn text_value(text: &str) -> Message {
    let n = text.chars().count();
    let start: String = text.chars().take(24).collect();
    Message::new(Code::ValueTextOf)
        .with("count", n)
        .with("start", start)
        .with("more", if n > 24 { "…" } else { "" })
}

/// Refuses `text` at `path` unless it has 1…`max` characters, not only spaces, and no control
/// character other than a line break or tab (`multiline`) or none at all.
fn text_in(path: &str, text: &str, max: usize, multiline: bool) -> Result<(), ActivityFault> {
    let n = text.chars().count();
    let allowed = || {
        format!(
            "text of 1…{max} characters{}",
            if multiline { " (line breaks allowed)" } else { " on one line" }
        )
    };
    if text.trim().is_empty() || n > max {
        return fault(path, text_value(text), allowed());
    }
    if let Some(c) = text.chars().find(|&c| c.is_control() && !(multiline && (c == '\n' || c == '\t'))) {
        let character = format!("U+{:04X}", u32::from(c));
        return fault(path, Message::new(Code::ValueTextControl).with("character", character), allowed());
    }
    Ok(())
}

impl Activity {
    /// Checks every field against its limit ([`limits`]); `groups` is the scene's group count
    /// (conditions may name a group). The first problem found is returned.
    pub fn validate(&self, groups: usize) -> Result<(), ActivityFault> {
        text_in("activity.prompt", &self.prompt, MAX_PROMPT_CHARS, true)?;
        if let Some(p) = &self.prediction {
            text_in("activity.prediction.question", &p.question, MAX_QUESTION_CHARS, false)?;
            let n = p.choices.len();
            if !(MIN_CHOICES..=MAX_CHOICES).contains(&n) {
                return fault(
                    "activity.prediction.choices",
                    Message::new(Code::ValueListOf).with("count", n),
                    format!("{MIN_CHOICES}…{MAX_CHOICES} choices"),
                );
            }
            for (k, c) in p.choices.iter().enumerate() {
                text_in(&format!("activity.prediction.choices[{k}]"), c, MAX_CHOICE_CHARS, false)?;
            }
            if let Some(e) = p.expected {
                if e as usize >= n {
                    return fault(
                        "activity.prediction.expected",
                        e.to_string(),
                        format!("the index of one of the {n} choices, 0…{}", n - 1),
                    );
                }
            }
        }
        if let Some(c) = &self.check {
            c.validate(groups)?;
        }
        Ok(())
    }
}

impl Check {
    fn validate(&self, groups: usize) -> Result<(), ActivityFault> {
        if self.steps == 0 || self.steps > MAX_CHECK_STEPS {
            return fault(
                "activity.check.steps",
                self.steps.to_string(),
                format!("a whole number 1…{MAX_CHECK_STEPS}"),
            );
        }
        let n = self.conditions.len();
        if n == 0 || n > MAX_CONDITIONS {
            return fault(
                "activity.check.conditions",
                Message::new(Code::ValueListOf).with("count", n),
                format!("1…{MAX_CONDITIONS} conditions"),
            );
        }
        let group_in = |path: String, g: u32| match groups {
            _ if (g as usize) < groups => Ok(()),
            0 => fault(path, g.to_string(), "no group: the scene has no groups"),
            n => {
                fault(path, g.to_string(), format!("a group index 0…{} (the scene has {n} group(s))", n - 1))
            }
        };
        let pane_in = |path: String, p: u32| {
            if p < MAX_PANES {
                Ok(())
            } else {
                fault(path, p.to_string(), format!("a pane index 0…{} (A…D)", MAX_PANES - 1))
            }
        };
        for (k, condition) in self.conditions.iter().enumerate() {
            let at = format!("activity.check.conditions[{k}]");
            match condition {
                Condition::Metric(m) => {
                    if !METRIC_KEYS.contains(&m.metric.as_str()) {
                        return fault(
                            format!("{at}.metric"),
                            format!("{:?}", m.metric.chars().take(40).collect::<String>()),
                            format!("one of the metrics keys {}", METRIC_KEYS.join(", ")),
                        );
                    }
                    if !m.value.is_finite() {
                        return fault(format!("{at}.value"), m.value.to_string(), "a finite number");
                    }
                    if let Some(g) = m.group {
                        group_in(format!("{at}.group"), g)?;
                    }
                    if let Some(p) = m.pane {
                        pane_in(format!("{at}.pane"), p)?;
                    }
                }
                Condition::Before(b) => {
                    if !(b.share > 0.0 && b.share <= 1.0) {
                        return fault(
                            format!("{at}.share"),
                            b.share.to_string(),
                            "a share above 0 and at most 1",
                        );
                    }
                    if b.before[0] == b.before[1] {
                        return fault(
                            format!("{at}.before"),
                            "the same one twice",
                            "two different groups or panes",
                        );
                    }
                    for (i, s) in b.before.iter().enumerate() {
                        match *s {
                            Subject::Group(g) => group_in(format!("{at}.before[{i}].group"), g)?,
                            Subject::Pane(p) => pane_in(format!("{at}.before[{i}].pane"), p)?,
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// The activity's rows of the scene's limits table: `(field, allowed, why)`.
pub fn limits() -> Vec<(&'static str, String, &'static str)> {
    vec![
        (
            "activity.prompt",
            format!("text of 1…{MAX_PROMPT_CHARS} characters (line breaks allowed)"),
            "a short task, shown as plain text on a card",
        ),
        (
            "activity.prediction.question",
            format!("text of 1…{MAX_QUESTION_CHARS} characters on one line"),
            "one question asked before the first Play",
        ),
        ("activity.prediction.choices", format!("{MIN_CHOICES}…{MAX_CHOICES} choices"), "a multiple-choice question"),
        (
            "activity.prediction.choices[]",
            format!("text of 1…{MAX_CHOICE_CHARS} characters on one line"),
            "one answer, a button's worth of text",
        ),
        ("activity.prediction.expected", "the index of one of the choices, from 0".into(), "the author's answer"),
        (
            "activity.check.steps",
            format!("a whole number 1…{MAX_CHECK_STEPS}"),
            "the step limit where the check ends if the goal was not met before",
        ),
        ("activity.check.conditions", format!("1…{MAX_CONDITIONS} conditions"), "a goal that fits on a card"),
        (
            "activity.check.conditions[].metric",
            "one of the metrics keys arrived_share, mean_time_to_goal, collisions_agent_agent, penetrations_agent_obstacle, stuck_agents, mean_speed, … (README)".into(),
            "the numbers the page measures",
        ),
        ("activity.check.conditions[].op", "\">=\", \"<=\", \">\", \"<\" or \"=\"".into(), "a comparison"),
        (
            "activity.check.conditions[].pane",
            format!("a pane index 0…{} (A…D)", MAX_PANES - 1),
            "the compare page shows at most four panes",
        ),
        ("activity.check.conditions[].share", "a share above 0 and at most 1 (default 0.9)".into(), "what counts as arrived"),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn activity() -> Activity {
        serde_json::from_str(
            r#"{"prompt": "Watch.", "prediction": {"question": "Q?", "choices": ["a", "b"], "expected": 1},
                "check": {"steps": 100, "conditions": [
                  {"metric": "arrived_share", "op": ">=", "value": 0.9, "group": 0},
                  {"before": [{"group": 0}, {"pane": 1}], "share": 0.5}]}}"#,
        )
        .expect("parses")
    }

    #[test]
    fn conditions_parse_by_shape_and_write_back_the_same() {
        let a = activity();
        let Some(check) = &a.check else { panic!("has a check") };
        assert!(
            matches!(&check.conditions[0], Condition::Metric(m) if m.op == Op::AtLeast && m.group == Some(0))
        );
        assert!(matches!(&check.conditions[1],
            Condition::Before(b) if b.before == [Subject::Group(0), Subject::Pane(1)] && b.share == 0.5));
        let json = serde_json::to_string(&a).expect("writes");
        assert_eq!(serde_json::from_str::<Activity>(&json).expect("reads"), a);
        assert!(!json.contains("\"pane\":null"), "{json}");
    }

    #[test]
    fn limits_name_the_field() {
        let mut a = activity();
        assert_eq!(a.validate(1), Ok(()));
        assert_eq!(a.validate(0).map_err(|f| f.path), Err("activity.check.conditions[0].group".into()));
        a.prompt = "x".repeat(MAX_PROMPT_CHARS + 1);
        let f = a.validate(1).expect_err("too long");
        assert_eq!(f.path, "activity.prompt");
        assert!(f.value.to_string().contains("1001 character"), "{}", f.value);
        assert!(f.allowed.contains("1…1000"), "{}", f.allowed);
        a.prompt = "ok".into();
        if let Some(p) = &mut a.prediction {
            p.choices = (0..7).map(|k| k.to_string()).collect();
        }
        assert_eq!(a.validate(1).map_err(|f| f.path), Err("activity.prediction.choices".into()));
        if let Some(p) = &mut a.prediction {
            p.choices = vec!["a".into(), "b\u{0}".into()];
        }
        let f = a.validate(1).expect_err("control character");
        assert_eq!(
            (f.path.as_str(), f.value.to_string().contains("U+0000")),
            ("activity.prediction.choices[1]", true)
        );
    }
}
