//! A run as a front-end drives it: a [`World`] with its recording (for the exports), its replay
//! (the timeline: seek to any step) and its metric series (the plots), kept in step. The page
//! (`web::Sim`, which adds a renderer) and `flockpath run` both drive a `Run`, so the session
//! logic is the same in both and is tested natively (`tests/run.rs`).
//!
//! What "in step" means:
//! - every new step is recorded by all three; a step replayed after a jump back on the timeline
//!   is not recorded again (the recording and the series keep the run's history), and the first
//!   new step after a jump drops the old future from all three;
//! - a new run (a restart at step 0: load, reset, another seed, an edit that respawns the
//!   agents) starts a new recording and timeline; the metric series drops its old future at its
//!   next sample, and forgets samples of a scene with other groups at once;
//! - a live edit (a planner, its parameters or waypoints, an obstacle or goal while the agents
//!   go on) is noted on the timeline at its step, so a jump replays it where it happened;
//! - view options (trails, fade) are not history: changing them or jumping keeps the ones shown.
//!
//! The scene activity's check (`crate::sim::activity_check`) is fed after every step here, so
//! the page and `flockpath run` decide it at the same step; [`Run::activity_report`] reads it.
//!
//! Planning ahead (IGSA paths) may be done in slices ([`RunOptions::sliced_planning`], the page)
//! so a frame never waits for it; [`Run::cancel_planning`] goes back to the world shown before.

use crate::model::params::{PlannerConfig, PlannerKind};
use crate::model::scene::{Scene, SceneError, ViewOptions};
use crate::sim::activity_check::{ActivityWatch, Page, Report};
use crate::sim::limits;
use crate::sim::metric_series::MetricSeries;
use crate::sim::recording::Recording;
use crate::sim::replay::{Replay, ReplayBudget};
use crate::sim::world::World;

/// What a run keeps besides its world, and how it plans ahead.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// Leave planning ahead (IGSA paths) to [`Run::advance_planning`] instead of planning at
    /// once when a world is built; a step finishes what is left.
    pub sliced_planning: bool,
    /// Memory budget of the recording for the exports; `None`: no recording.
    pub recording_budget_bytes: Option<usize>,
    /// Budget of the timeline; `None`: no timeline, [`Run::seek`] does not move.
    pub replay: Option<ReplayBudget>,
    /// Metric sampling: steps between samples at the start and the most samples kept; `None`:
    /// no metric series.
    pub metric_series: Option<(u32, usize)>,
}

impl RunOptions {
    /// The playground's run: planning in slices, a recording within
    /// [`limits::PAGE_RECORDING_BUDGET_BYTES`], the timeline and the plots' metric series.
    pub fn page() -> Self {
        Self {
            sliced_planning: true,
            recording_budget_bytes: Some(limits::PAGE_RECORDING_BUDGET_BYTES),
            replay: Some(ReplayBudget::default()),
            metric_series: Some((limits::METRIC_SERIES_EVERY, limits::PAGE_METRIC_SERIES_CAP)),
        }
    }

    /// `flockpath run`'s run: no timeline; a recording within
    /// [`limits::CLI_RECORDING_BUDGET_BYTES`] when files are to be exported and a metric series
    /// of [`limits::CLI_METRIC_SERIES_CAP`] samples when one is to be written.
    pub fn command_line(recording: bool, metric_series: bool) -> Self {
        Self {
            sliced_planning: false,
            recording_budget_bytes: recording.then_some(limits::CLI_RECORDING_BUDGET_BYTES),
            replay: None,
            metric_series: metric_series
                .then_some((limits::METRIC_SERIES_EVERY, limits::CLI_METRIC_SERIES_CAP)),
        }
    }
}

/// A world with its recording, replay and metric series, kept in step (see the module docs).
#[derive(Clone)]
pub struct Run {
    options: RunOptions,
    world: World,
    /// Empty (a budget of 0 bytes) when the options ask for none.
    recording: Recording,
    replay: Option<Replay>,
    /// Empty when the options ask for none.
    metrics: MetricSeries,
    /// The world shown before the current one started planning ahead, which
    /// [`Run::cancel_planning`] goes back to; `None` when nothing is being planned.
    before_planning: Option<World>,
    /// The scene activity's check, fed after every step (kept across restarts: it starts over
    /// by itself when the steps it sees do not follow on).
    activity: ActivityWatch,
}

impl Run {
    /// Starts a run of `scene`; errors when the world refuses it (validation, density, cost).
    pub fn new(scene: Scene, options: RunOptions) -> Result<Self, SceneError> {
        let world = build(scene, options)?;
        Ok(Self::of_world(world, options))
    }

    /// Starts a run from a world as it is (its step may be past 0: recording starts there).
    pub fn of_world(world: World, options: RunOptions) -> Self {
        let metrics =
            options.metric_series.map_or_else(|| MetricSeries::new(1, 2), |(e, c)| MetricSeries::new(e, c));
        let recording = Recording::new(0, 0);
        let activity = ActivityWatch::new(Page::Run);
        let mut run =
            Self { options, world, recording, replay: None, metrics, before_planning: None, activity };
        run.start_recording();
        run
    }

    /// The options the run was started with.
    pub fn options(&self) -> RunOptions {
        self.options
    }

    /// The world now.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The recording for the exports (empty when the options keep none).
    pub fn recording(&self) -> &Recording {
        &self.recording
    }

    /// The timeline, if the options keep one.
    pub fn replay(&self) -> Option<&Replay> {
        self.replay.as_ref()
    }

    /// The metrics over time (empty when the options sample none).
    pub fn metric_series(&self) -> &MetricSeries {
        &self.metrics
    }

    /// The activity check's state at the step shown (`None` when the scene has no check).
    pub fn activity_report(&self) -> Option<Report> {
        self.activity.report(self.world.scene(), self.world.step_count())
    }

    /// Advances `n` steps, recording each.
    pub fn step(&mut self, n: u32) {
        let o = &self.options;
        let keeps_nothing =
            o.recording_budget_bytes.is_none() && o.replay.is_none() && o.metric_series.is_none();
        let checks = self.world.scene().activity.as_ref().is_some_and(|a| a.check.is_some());
        if keeps_nothing && !checks {
            self.world.step_n(n);
        } else {
            self.step_each(n, |_| {});
        }
    }

    /// Advances `n` steps, recording each, calling `each` with the world after every step (the
    /// page traces trails) and feeding the activity check.
    pub fn step_each(&mut self, n: u32, mut each: impl FnMut(&World)) {
        for _ in 0..n {
            self.world.step();
            each(&self.world);
            self.activity.observe_world(&self.world);
            let new_step = self.replay.as_mut().is_none_or(|r| r.record(&self.world));
            if new_step {
                // A new step (not one replayed after a jump back): the recording and the metric
                // series keep the same history as the timeline.
                self.recording.truncate_after(self.world.step_count().saturating_sub(1));
                self.recording.capture_world(&self.world);
                if self.options.metric_series.is_some() {
                    self.metrics.sample(&self.world);
                }
            }
        }
    }

    /// Replaces the scene (a new run at step 0); on error the run goes on unchanged.
    pub fn load(&mut self, scene: Scene) -> Result<(), SceneError> {
        let world = build(scene, self.options)?;
        self.replace_world(world);
        Ok(())
    }

    /// Restarts the scene from step 0 with the same seed.
    pub fn reset(&mut self) -> Result<(), SceneError> {
        self.load(self.world.scene().clone())
    }

    /// Changes the seed and restarts; on error the run goes on unchanged.
    pub fn set_seed(&mut self, seed: u32) -> Result<(), SceneError> {
        let mut scene = self.world.scene().clone();
        scene.seed = seed;
        self.load(scene)
    }

    /// Gives group `group` (0-based) another planner or other parameters (waypoints included)
    /// while the run goes on: a live edit, noted on the timeline at this step. On error nothing
    /// changes.
    pub fn set_group_planner(&mut self, group: usize, config: PlannerConfig) -> Result<(), SceneError> {
        let before = (config.kind() == PlannerKind::Igsa || plans_ahead(self.world.scene()))
            .then(|| self.world.clone());
        self.world.set_group_planner(group, config)?;
        self.keep_for_cancel(before);
        self.note_live_edit();
        Ok(())
    }

    /// Switches to an edited scene: obstacles and goals change live (noted on the timeline);
    /// a change to the groups or the seed restarts the run. On error nothing changes.
    pub fn edit_scene(&mut self, scene: Scene) -> Result<(), SceneError> {
        // An edit may not grow the scene past a link that opens it, as a load may not (the
        // page keeps the link in its address bar).
        crate::model::codec::check_link_fits(&scene)?;
        let before = plans_ahead(self.world.scene()).then(|| self.world.clone());
        self.world.edit_scene(scene)?;
        self.keep_for_cancel(before);
        self.restart_recording_if_new_run();
        Ok(())
    }

    /// Stores new view options in the scene: not history, no restart, nothing noted.
    pub fn set_view(&mut self, view: ViewOptions) -> Result<(), SceneError> {
        let mut scene = self.world.scene().clone();
        scene.view = view;
        self.world.edit_scene(scene)
    }

    /// Moves the run to `step` (clamped to the recorded history) by restoring the nearest
    /// checkpoint and re-simulating from it: bit-identical to the original run at that step.
    /// Playing on continues from there. Returns the number of steps re-simulated (0 without a
    /// timeline).
    pub fn seek(&mut self, step: u32) -> Result<u32, SceneError> {
        self.seek_toward(step, u32::MAX)
    }

    /// [`Run::seek`] re-simulating at most `max_steps` (see [`Replay::seek_toward`]): called
    /// again with the same `step` it goes on where it stopped, and ends on the same world.
    pub fn seek_toward(&mut self, step: u32, max_steps: u32) -> Result<u32, SceneError> {
        let Some(replay) = self.replay.as_ref() else { return Ok(0) };
        let view = self.world.scene().view;
        let resimulated = replay.seek_toward(step, max_steps, &mut self.world);
        if self.world.scene().view != view {
            self.set_view(view)?;
        }
        Ok(resimulated)
    }

    /// Runs up to `evaluations` more objective evaluations of the planning (`u32::MAX`: all);
    /// returns the share done (0…1). The path is the same whatever the slices.
    pub fn advance_planning(&mut self, evaluations: u32) -> f64 {
        let progress = self.world.advance_planning(evaluations);
        if progress >= 1.0 {
            self.before_planning = None;
            if self.world.step_count() == 0 {
                // The timeline's first checkpoint should hold the planned path.
                self.restart_recording_if_new_run();
            }
        }
        progress
    }

    /// Whether [`Run::cancel_planning`] has a world to go back to.
    pub fn can_cancel_planning(&self) -> bool {
        self.before_planning.is_some() && self.world.planning_progress() < 1.0
    }

    /// Abandons the planning and goes back to the world shown before it began, with a new
    /// recording, timeline and metric series; returns false (and changes nothing) when there is
    /// none.
    pub fn cancel_planning(&mut self) -> bool {
        if !self.can_cancel_planning() {
            return false;
        }
        let Some(before) = self.before_planning.take() else { return false };
        self.world = before;
        self.start_recording();
        true
    }

    /// Makes `world` the run's (a new run) and keeps the old one to cancel planning.
    fn replace_world(&mut self, world: World) {
        let before = std::mem::replace(&mut self.world, world);
        self.keep_for_cancel(Some(before));
        self.restart_recording_if_new_run();
    }

    /// A new recording and timeline from the world as it is now.
    fn start_recording(&mut self) {
        let budget = self.options.recording_budget_bytes.unwrap_or(0);
        self.recording = Recording::of_world(&self.world, budget);
        self.replay = self.options.replay.map(|b| Replay::with_budget(&self.world, b));
        // The old run's samples would be plotted beside the new run's step 0 until it steps.
        self.metrics.clear();
    }

    /// Starts a new recording when the run restarted (step 0) or its agents changed; otherwise
    /// the change was live.
    fn restart_recording_if_new_run(&mut self) {
        let agents = self.world.agent_count();
        let agents_changed =
            self.recording.agents() != agents || self.replay.as_ref().is_some_and(|r| r.agents() != agents);
        if self.world.step_count() == 0 || agents_changed {
            self.start_recording();
        } else {
            self.note_live_edit();
        }
    }

    /// Keeps the timeline in step with a change made while the run goes on: the future after
    /// this step is dropped and the changed world is checkpointed here, so a later jump replays
    /// the change where it happened.
    fn note_live_edit(&mut self) {
        if let Some(replay) = self.replay.as_mut() {
            replay.note_edit(&self.world);
        }
        self.recording.truncate_after(self.world.step_count());
    }

    /// Keeps `before` to go back to if the world now plans ahead (the oldest such world wins:
    /// edits during planning start it again, cancelling goes back to before the first).
    fn keep_for_cancel(&mut self, before: Option<World>) {
        if self.world.planning_progress() >= 1.0 {
            self.before_planning = None;
        } else if self.before_planning.is_none() {
            self.before_planning = before.filter(|w| w.planning_progress() >= 1.0);
        }
    }
}

/// A world for `scene`, planning ahead as the options say.
fn build(scene: Scene, options: RunOptions) -> Result<World, SceneError> {
    if options.sliced_planning {
        World::new_sliced(scene)
    } else {
        World::new(scene)
    }
}

/// Whether a group of `scene` plans ahead (IGSA): a change may start planning that can be
/// cancelled.
fn plans_ahead(scene: &Scene) -> bool {
    scene.groups.iter().any(|g| g.planner.kind() == PlannerKind::Igsa)
}
