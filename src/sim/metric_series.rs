//! A bounded time series of a run's metrics, overall and per group, for the page's plots and
//! `flockpath run --metrics-history` ("metric series": in the page's JS, "history" is the undo
//! stack).
//!
//! A sample is taken every `every` steps. When the series holds its cap of samples it keeps
//! every other one and samples half as often from then on (thinning, a
//! [`crate::sim::series::BoundedSeries`]), so a long run always fits and always spans its whole
//! length. Counts
//! that accumulate (collisions, penetrations) are stored as totals and turned into per-step rates
//! between neighbouring kept samples when read, so thinning loses no events.

use crate::csv;
use crate::model::params::PlannerKind;
use crate::sim::limits;
use crate::sim::metrics::{GroupMetrics, Metrics};
use crate::sim::series::BoundedSeries;
use crate::sim::world::World;

/// One plotted series: key, label, unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SeriesSpec {
    /// Stable key (page API, CSV column).
    pub key: &'static str,
    /// Label shown above the plot.
    pub label: &'static str,
    /// Unit shown after values.
    pub unit: &'static str,
}

const fn spec(key: &'static str, label: &'static str, unit: &'static str) -> SeriesSpec {
    SeriesSpec { key, label, unit }
}

/// Every series, in plot order. Values that do not exist yet (time to goal before the first
/// arrival, queue order without a goal or of a group that is not firefly) are NaN: a gap in the
/// plot.
pub const SERIES: &[SeriesSpec] = &[
    spec("arrived_share", "Arrived", "share"),
    spec("mean_time_to_goal_s", "Time to goal", "s"),
    spec("collisions_per_step", "Agent–agent collisions", "pairs/step"),
    spec("penetrations_per_step", "Obstacle penetrations", "agents/step"),
    spec("mean_path_length", "Mean path length", "px"),
    spec("mean_turn_deg", "Mean turn", "°/step"),
    spec("max_turn_deg", "Max turn", "°/step"),
    spec("mean_speed_near_obstacles", "Speed near obstacles", "px/step"),
    spec("queue_order", "Queue order (firefly)", "share"),
    spec("stuck_agents", "Stuck agents", "agents"),
    spec("mean_speed", "Mean speed", "px/step"),
];

/// Raw values stored per sample and row: the series, with the two rates stored as totals.
const RAW: usize = 11;
const COLLISIONS: usize = 2;
const PENETRATIONS: usize = 3;

/// The sampled metrics of one run.
#[derive(Clone, Debug)]
pub struct MetricSeries {
    /// Steps between samples at the start (and after going back to the start).
    start_every: u32,
    /// Rows per sample: overall, then one per group; a sample is `rows × RAW` values,
    /// `values[r * RAW + k]` of its row.
    rows: usize,
    samples: BoundedSeries<f32>,
}

impl Default for MetricSeries {
    fn default() -> Self {
        Self::new(limits::METRIC_SERIES_EVERY, limits::PAGE_METRIC_SERIES_CAP)
    }
}

impl MetricSeries {
    /// An empty series sampling every `every` steps (at least 1), keeping at most `cap` samples
    /// (at least 2).
    pub fn new(every: u32, cap: usize) -> Self {
        let every = every.max(1);
        Self { start_every: every, rows: 0, samples: BoundedSeries::new(0, cap.max(2), every) }
    }

    /// Forgets every sample (a new run); the sampling interval returns to the start's.
    pub fn clear(&mut self) {
        *self = Self::new(self.start_every, self.samples.cap());
    }

    /// Samples `world` if its step count falls on the sampling interval (call after every new
    /// step). A run that went back (a restart, or a change after a jump back on the timeline)
    /// drops the samples from its step on, since they belonged to the old future.
    pub fn sample(&mut self, world: &World) {
        let step = world.step_count();
        if self.samples.steps().last().is_some_and(|&last| step <= last) {
            self.truncate_before(step);
        }
        if !self.samples.due(step) {
            return;
        }
        self.push(&plot_metrics(world));
    }

    /// Drops the samples at `step` and later; an emptied series samples at the start rate again.
    pub fn truncate_before(&mut self, step: u32) {
        self.samples.truncate_before(step);
        if self.samples.is_empty() {
            self.clear();
        }
    }

    /// Appends the metrics of one step (thinning first when full). Metrics with another number
    /// of groups than the samples held start the series again.
    pub fn push(&mut self, m: &Metrics) {
        let rows = 1 + m.groups.len();
        if rows != self.rows {
            self.rows = rows;
            self.samples.clear_samples(rows * RAW);
        }
        let mut values = Vec::with_capacity(rows * RAW);
        push_row(&mut values, &m.overall);
        for g in &m.groups {
            push_row(&mut values, g);
        }
        self.samples.push(m.steps, values);
    }

    /// The sampled step numbers, increasing.
    pub fn steps(&self) -> &[u32] {
        self.samples.steps()
    }

    /// Steps between samples now.
    pub fn every(&self) -> u32 {
        self.samples.every()
    }

    /// How many times the series was thinned.
    pub fn thinned(&self) -> u32 {
        self.samples.thinned()
    }

    /// Number of groups the samples have rows for.
    pub fn groups(&self) -> usize {
        self.rows.saturating_sub(1)
    }

    /// The series `key` (see [`SERIES`]) for `group` (`None`: overall), one value per sample;
    /// `None` for an unknown key or group. Rates are per step between neighbouring samples; the
    /// first sample's rate covers the steps since the start.
    pub fn series(&self, key: &str, group: Option<usize>) -> Option<Vec<f32>> {
        let k = SERIES.iter().position(|s| s.key == key)?;
        let row = match group {
            None => 0,
            Some(g) if g + 1 < self.rows => g + 1,
            Some(_) => return None,
        };
        let steps = self.samples.steps();
        let at = |s: usize| self.samples.row(s).get(row * RAW + k).copied().unwrap_or(f32::NAN);
        let mut out = Vec::with_capacity(steps.len());
        for s in 0..steps.len() {
            if k == COLLISIONS || k == PENETRATIONS {
                let (before, since) = if s == 0 { (0.0, 0) } else { (at(s - 1), steps[s - 1]) };
                let span = steps[s].saturating_sub(since).max(1) as f32;
                out.push((at(s) - before) / span);
            } else {
                out.push(at(s));
            }
        }
        Some(out)
    }

    /// The series as CSV: `step,time_s,group,<series…>`, one row per sample for the whole run
    /// (group `all`) and one per group (its index from 1), empty cells for missing values.
    pub fn to_csv(&self, group_names: &[String]) -> String {
        let mut out = String::from("step,time_s,group");
        for s in SERIES {
            out.push(',');
            out.push_str(s.key);
        }
        out.push('\n');
        let columns: Vec<Vec<Vec<f32>>> = (0..self.rows)
            .map(|row| {
                let group = row.checked_sub(1);
                SERIES.iter().map(|s| self.series(s.key, group).unwrap_or_default()).collect()
            })
            .collect();
        let dt = f64::from(crate::model::scene::DT);
        for (i, &step) in self.samples.steps().iter().enumerate() {
            for (row, series) in columns.iter().enumerate() {
                let name = match row {
                    0 => "all".to_string(),
                    r => group_names.get(r - 1).cloned().unwrap_or_else(|| r.to_string()),
                };
                out.push_str(&format!("{step},{:.4},{}", f64::from(step) * dt, csv::field(&name)));
                for values in series {
                    out.push(',');
                    if let Some(v) = values.get(i).filter(|v| v.is_finite()) {
                        out.push_str(&format!("{v}"));
                    }
                }
                out.push('\n');
            }
        }
        out
    }
}

/// The world's metrics with the queue order measured for firefly groups only: it is the
/// firefly measure, and in a dense crowd it costs more than a step (10,000 Boids agents: 6.9 ms
/// against 0.13 ms for the rest), so plotting it for every planner would slow the run down.
fn plot_metrics(world: &World) -> Metrics {
    let scene = world.scene();
    let planners: Vec<&str> = scene.groups.iter().map(|g| g.planner.kind().name()).collect();
    let firefly = |g: usize| scene.groups.get(g).is_some_and(|g| g.planner.kind() == PlannerKind::Firefly);
    world.metrics_recorder().summary_with_queue(scene, &planners, world.step_count(), firefly)
}

fn push_row(values: &mut Vec<f32>, g: &GroupMetrics) {
    let opt = |x: Option<f64>| x.map_or(f32::NAN, |v| v as f32);
    let row: [f32; RAW] = [
        g.arrived_share as f32,
        opt(g.mean_time_to_goal_s),
        g.collisions_agent_agent as f32,
        g.penetrations_agent_obstacle as f32,
        g.mean_path_length as f32,
        g.mean_turn_deg as f32,
        g.max_turn_deg as f32,
        opt(g.mean_speed_near_obstacles),
        opt(g.queue_order),
        g.stuck_agents as f32,
        g.mean_speed as f32,
    ];
    values.extend_from_slice(&row);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;

    #[test]
    fn thinning_keeps_the_cap_spans_the_run_and_keeps_rates_exact() {
        let mut world = World::new(presets::two_groups_swap()).expect("valid");
        let mut h = MetricSeries::new(1, 20);
        for _ in 0..200 {
            world.step();
            h.sample(&world);
            assert!(h.steps().len() <= 20);
        }
        assert!(h.thinned() >= 3, "thinned {}", h.thinned());
        assert!(h.steps().windows(2).all(|w| w[1] - w[0] == h.every()));
        assert!(*h.steps().last().expect("samples") > 180);
        assert_eq!(h.groups(), 2);
        // Per-step rates times the spans add up to the last total.
        let rates = h.series("collisions_per_step", None).expect("series");
        let mut total = 0.0f64;
        let mut since = 0;
        for (r, &s) in rates.iter().zip(h.steps()) {
            total += f64::from(*r) * f64::from(s - since);
            since = s;
        }
        // …to the total at the last sample, replayed in a fresh run of the same scene.
        let last = *h.steps().last().expect("samples");
        let mut replay = World::new(presets::two_groups_swap()).expect("valid");
        replay.step_n(last);
        let expected = replay.metrics().overall.collisions_agent_agent as f64;
        assert!((total - expected).abs() <= 1e-3 * expected.max(1.0), "{total} vs {expected}");
        assert!(h.series("nope", None).is_none());
        assert!(h.series("arrived_share", Some(2)).is_none());
    }

    #[test]
    fn a_run_that_goes_back_drops_the_old_future_and_csv_has_a_row_per_group() {
        let mut world = World::new(presets::open_field()).expect("valid");
        let mut h = MetricSeries::new(limits::METRIC_SERIES_EVERY, limits::PAGE_METRIC_SERIES_CAP);
        world.step_n(20);
        h.sample(&world);
        world = World::new(presets::open_field()).expect("valid");
        world.step_n(limits::METRIC_SERIES_EVERY);
        h.sample(&world);
        assert_eq!(h.steps(), &[limits::METRIC_SERIES_EVERY]);
        let csv = h.to_csv(&["flock".to_string()]);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3, "{csv}");
        assert!(lines[0].starts_with("step,time_s,group,arrived_share"));
        assert!(lines[2].contains(",flock,"));
        assert_eq!(lines[1].split(',').count(), 3 + SERIES.len());
        // Going back to step 55 (a change after a jump back) keeps the samples before it.
        for _ in 0..100 {
            world.step();
            h.sample(&world);
        }
        let mut back = World::new(presets::open_field()).expect("valid");
        back.step_n(55);
        h.sample(&back);
        assert_eq!(h.steps().last(), Some(&55));
        assert_eq!(h.steps().len(), 11, "{:?}", h.steps());
    }
}
