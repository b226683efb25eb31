//! Checks a scene's activity goal ([`crate::model::activity::Check`]) on a run's metrics, step
//! by step: "met" at the first step where every condition holds, "missed" at the step limit.
//!
//! An "arrives before" condition that can no longer hold (the second reached the share first)
//! decides the check as missed at that step.
//!
//! The page steps in frames of several steps; the watch is fed after every single step (by
//! [`crate::sim::run::Run`] and [`crate::sim::compare::Comparison`], which the page and the
//! command line drive alike), so the deciding step and the values shown with it are the same on every machine (the same run, the
//! same check). While a check is open each step costs one metrics summary (O(agents), what the
//! page's readout polls every 250 ms); once decided, nothing.
//!
//! On the playground the subjects are the run and its groups. On the compare page they are the
//! panes (a condition without `pane` must hold in every pane), and a group is pane A's group. A
//! condition that names a pane means nothing on the playground (nor a pane the comparison does
//! not show): it is reported as not applying, and the check as "unavailable" on that page.

use crate::model::activity::{BeforeCondition, Check, Condition, MetricCondition, Subject};
use crate::model::scene::Scene;
use crate::sim::metrics::{GroupMetrics, Metrics};
use crate::sim::world::World;
use serde::Serialize;

/// Where a check stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Not decided yet.
    Running,
    /// Every condition held at `step`.
    Met,
    /// The step limit came first, or an "arrives before" was lost.
    Missed,
    /// A condition does not apply on this page (a compare-only check on the playground).
    Unavailable,
}

/// One measured value of a condition: whose, and what.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measured {
    /// The group (from 0), when the value is a group's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub group: Option<u32>,
    /// The pane (from 0), on the compare page.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pane: Option<u32>,
    /// The value (null when the metric has none yet, as `mean_time_to_goal` before anyone arrives).
    pub value: Option<f64>,
    /// For an "arrives before" condition: the first step at which the share was reached.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reached_step: Option<u32>,
}

/// A condition with what was measured for it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConditionReport {
    /// The condition as the activity states it.
    pub condition: Condition,
    /// Whether it applies on this page.
    pub applies: bool,
    /// Whether it holds at `step`.
    pub holds: bool,
    /// The values behind it, one per subject.
    pub measured: Vec<Measured>,
}

/// The state of a check: what the page shows on the activity card.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// Running, met, missed or unavailable.
    pub status: Status,
    /// The step of the values: the deciding step once decided, else the last one watched.
    pub step: u32,
    /// The check's step limit.
    pub limit: u32,
    /// The first step watched: 1 for a run watched from its start; later after a jump on the
    /// timeline or a scene edit mid-run (then "before" conditions only know what came after).
    pub from_step: u32,
    /// Each condition, in the activity's order.
    pub conditions: Vec<ConditionReport>,
}

/// Where the subjects' metrics come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Page {
    /// One run (the playground, `<flock-path>`, the command line).
    Run,
    /// The compare page's panes.
    Compare,
}

/// A check in progress.
#[derive(Clone, Debug)]
struct Progress {
    check: Check,
    last_step: u32,
    report: Report,
}

/// Follows one run's (or one comparison's) activity check, fed after every step.
#[derive(Clone, Debug)]
pub struct ActivityWatch {
    page: Page,
    progress: Option<Progress>,
}

impl ActivityWatch {
    /// A watch for `page`.
    pub fn new(page: Page) -> Self {
        Self { page, progress: None }
    }

    /// Notes the run of `world` after a step (the playground).
    pub fn observe_world(&mut self, world: &World) {
        self.observe(world.scene(), world.step_count(), || vec![world.metrics()]);
    }

    /// Notes step `step` of a run of `scene`; `metrics` gives the subjects' metrics (one per pane,
    /// or the run's), called only while the check is open. A step that does not follow the last
    /// one watched (a reset, a new scene, a jump on the timeline) or a changed check starts over.
    pub fn observe(&mut self, scene: &Scene, step: u32, metrics: impl FnOnce() -> Vec<Metrics>) {
        let Some(check) = scene.activity.as_ref().and_then(|a| a.check.as_ref()) else {
            self.progress = None;
            return;
        };
        let fresh = self
            .progress
            .as_ref()
            .is_none_or(|p| &p.check != check || p.last_step.checked_add(1) != Some(step));
        if fresh {
            let report = initial_report(check, self.page, step);
            self.progress = Some(Progress { check: check.clone(), last_step: step, report });
        }
        let Some(p) = self.progress.as_mut() else { return };
        p.last_step = step;
        if p.report.status != Status::Running {
            return;
        }
        let panes = metrics();
        update(&mut p.report, self.page, step, &panes);
    }

    /// The check's state for the run of `scene` at `step` (null without a check): a fresh
    /// report when the watch has not seen this run up to `step` (step 0, just reset).
    pub fn report(&self, scene: &Scene, step: u32) -> Option<Report> {
        let check = scene.activity.as_ref()?.check.as_ref()?;
        match &self.progress {
            Some(p) if &p.check == check && p.last_step == step && step > 0 => Some(p.report.clone()),
            _ => Some(initial_report(check, self.page, step)),
        }
    }
}

/// Whether `condition` can be measured on `page` (`panes` is the compare page's pane count).
fn applies(condition: &Condition, page: Page, panes: Option<u32>) -> bool {
    let subject_ok = |s: Subject| match (s, page) {
        (Subject::Group(_), _) => true,
        (Subject::Pane(p), Page::Compare) => panes.is_none_or(|n| p < n),
        (Subject::Pane(_), Page::Run) => false,
    };
    match condition {
        Condition::Metric(m) => match m.pane {
            None => true,
            Some(p) => subject_ok(Subject::Pane(p)),
        },
        Condition::Before(b) => b.before.iter().all(|&s| subject_ok(s)),
    }
}

fn initial_report(check: &Check, page: Page, step: u32) -> Report {
    let conditions: Vec<ConditionReport> = check
        .conditions
        .iter()
        .map(|c| ConditionReport {
            condition: c.clone(),
            applies: applies(c, page, None),
            holds: false,
            measured: Vec::new(),
        })
        .collect();
    let status = if conditions.iter().all(|c| c.applies) { Status::Running } else { Status::Unavailable };
    Report { status, step, limit: check.steps, from_step: step.max(1), conditions }
}

/// The value of metrics key `key` in `m` (the keys of [`crate::model::activity::METRIC_KEYS`]).
pub fn metric_value(m: &GroupMetrics, key: &str) -> Option<f64> {
    Some(match key {
        "arrived_share" => m.arrived_share,
        "mean_time_to_goal" => m.mean_time_to_goal?,
        "mean_time_to_goal_s" => m.mean_time_to_goal_s?,
        "collisions_agent_agent" => m.collisions_agent_agent as f64,
        "collisions_moving" => m.collisions_moving as f64,
        "penetrations_agent_obstacle" => m.penetrations_agent_obstacle as f64,
        "mean_speed" => m.mean_speed,
        "mean_speed_m_s" => m.mean_speed_m_s,
        "mean_speed_near_obstacles" => m.mean_speed_near_obstacles?,
        "mean_path_length" => m.mean_path_length,
        "mean_path_length_m" => m.mean_path_length_m,
        "mean_turn_deg" => m.mean_turn_deg,
        "max_turn_deg" => m.max_turn_deg,
        "stuck_agents" => f64::from(m.stuck_agents),
        "queue_order" => m.queue_order?,
        _ => return None,
    })
}

/// The metrics of `group` (or the whole run) in `metrics`.
fn of_group(metrics: &Metrics, group: Option<u32>) -> Option<&GroupMetrics> {
    match group {
        None => Some(&metrics.overall),
        Some(g) => metrics.groups.get(g as usize),
    }
}

/// The metrics of a subject: a pane's whole run, or a group (pane A's on the compare page).
fn of_subject(panes: &[Metrics], s: Subject) -> Option<&GroupMetrics> {
    match s {
        Subject::Pane(p) => panes.get(p as usize).map(|m| &m.overall),
        Subject::Group(g) => panes.first().and_then(|m| m.groups.get(g as usize)),
    }
}

fn measure_metric(m: &MetricCondition, page: Page, panes: &[Metrics]) -> (bool, Vec<Measured>) {
    let which: Vec<u32> = match (page, m.pane) {
        (Page::Run, _) => vec![0],
        (Page::Compare, Some(p)) => vec![p],
        (Page::Compare, None) => (0..panes.len() as u32).collect(),
    };
    let measured: Vec<Measured> = which
        .iter()
        .map(|&p| Measured {
            group: m.group,
            pane: (page == Page::Compare).then_some(p),
            value: panes
                .get(p as usize)
                .and_then(|metrics| of_group(metrics, m.group))
                .and_then(|g| metric_value(g, &m.metric)),
            reached_step: None,
        })
        .collect();
    let holds =
        !measured.is_empty() && measured.iter().all(|x| x.value.is_some_and(|v| m.op.holds(v, m.value)));
    (holds, measured)
}

fn measure_before(
    b: &BeforeCondition,
    step: u32,
    panes: &[Metrics],
    before: &[Measured],
) -> (bool, Vec<Measured>) {
    let measured: Vec<Measured> = b
        .before
        .iter()
        .enumerate()
        .map(|(k, &s)| {
            let value = of_subject(panes, s).map(|g| g.arrived_share);
            let earlier = before.get(k).and_then(|x| x.reached_step);
            let reached_step = earlier.or_else(|| value.filter(|&v| v >= b.share).map(|_| step));
            let (group, pane) = match s {
                Subject::Group(g) => (Some(g), None),
                Subject::Pane(p) => (None, Some(p)),
            };
            Measured { group, pane, value, reached_step }
        })
        .collect();
    let holds = match (measured[0].reached_step, measured[1].reached_step) {
        (Some(first), None) => first <= step,
        (Some(first), Some(second)) => first < second,
        _ => false,
    };
    (holds, measured)
}

fn update(report: &mut Report, page: Page, step: u32, panes: &[Metrics]) {
    let pane_count = (page == Page::Compare).then_some(panes.len() as u32);
    for c in &mut report.conditions {
        c.applies = applies(&c.condition, page, pane_count);
        if !c.applies {
            c.holds = false;
            c.measured.clear();
            continue;
        }
        let (holds, measured) = match &c.condition {
            Condition::Metric(m) => measure_metric(m, page, panes),
            Condition::Before(b) => measure_before(b, step, panes, &c.measured),
        };
        c.holds = holds;
        c.measured = measured;
    }
    report.step = step;
    // An "arrives before" whose second reached the share first can never hold again.
    let lost = report.conditions.iter().any(|c| {
        matches!(c.condition, Condition::Before(_))
            && match (
                c.measured.first().and_then(|m| m.reached_step),
                c.measured.get(1).and_then(|m| m.reached_step),
            ) {
                (first, Some(second)) => first.is_none_or(|f| f >= second),
                _ => false,
            }
    });
    report.status = if report.conditions.iter().any(|c| !c.applies) {
        Status::Unavailable
    } else if report.conditions.iter().all(|c| c.holds) {
        Status::Met
    } else if lost || step >= report.limit {
        Status::Missed
    } else {
        Status::Running
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::activity::METRIC_KEYS;

    #[test]
    fn every_metric_key_reads_the_metrics_json_value() {
        let m = GroupMetrics {
            arrived_share: 0.25,
            mean_time_to_goal: Some(120.0),
            mean_time_to_goal_s: Some(2.0),
            collisions_agent_agent: 3,
            collisions_moving: 2,
            penetrations_agent_obstacle: 1,
            mean_speed: 1.5,
            mean_speed_m_s: 4.5,
            mean_speed_near_obstacles: Some(0.75),
            mean_path_length: 80.0,
            mean_path_length_m: 4.0,
            mean_turn_deg: 3.5,
            max_turn_deg: 40.0,
            stuck_agents: 4,
            queue_order: Some(0.5),
            ..GroupMetrics::default()
        };
        let json = serde_json::to_value(&m).expect("serialises");
        for key in METRIC_KEYS {
            assert_eq!(metric_value(&m, key), json[key].as_f64(), "{key}");
            assert!(metric_value(&m, key).is_some(), "{key}");
        }
    }
}
