//! Side-by-side comparison: one scene and seed in up to four panes, each with its own planners,
//! stepped in lockstep, with per-pane metrics, overlaid time series and a summary table.
//!
//! Random streams: every pane builds its own [`World`] from the scene with the scene's seed
//! unchanged, so each pane owns its generators (spawn stream and planning stream, see
//! `world.rs`) and no generator is shared between panes. Consequences, both tested: all panes
//! start from the same spawn positions (a fair comparison: common random numbers), a pane whose
//! planners equal the scene's runs exactly as the playground does, and a pane's run does not
//! depend on which other panes are shown.
//!
//! The comparison travels in the URL as `compare.html#s=<scene>&c=<spec>`; the spec string is
//! `1.` followed by the panes separated by `~`. A pane is `scene` (the scene's own planners) or
//! `;`-separated assignments `[group=]planner[(v1,v2,…)]`: without a group the planner is for
//! every group, `2=pso` is for group 2 (1-based). The values are the planner's parameters by
//! table position (choices by name); missing trailing values take their defaults. Writing lists
//! every value, so a link replays the same runs after a default changes (as the scene codec does).
//! Example: `1.scene~pso~firefly(2,0.2)` or `1.boids~1=pso;2=firefly`.

use crate::csv;
use crate::model::link;
use crate::model::params::{PlannerConfig, PlannerKind};
use crate::model::refusal::{Arg, Code, Message, Refusal};
use crate::model::scene::{Scene, SceneError};
use crate::sim::activity_check::{ActivityWatch, Page, Report};
use crate::sim::limits;
use crate::sim::metrics::Metrics;
use crate::sim::series::BoundedSeries;
use crate::sim::world::World;
use serde::Serialize;
use std::fmt::Write as _;

/// The spec version written today.
pub const SPEC_VERSION: &str = "1";
/// Most panes a comparison shows.
pub const MAX_PANES: usize = 4;
/// Steps between time-series samples at the start (doubles when the series thins).
pub const SERIES_EVERY: u32 = limits::COMPARE_SERIES_EVERY;
/// Most samples kept per series; beyond it every other sample goes and the interval doubles.
pub const MAX_SERIES_SAMPLES: usize = limits::COMPARE_SERIES_CAP;
/// Pane names and colours (plots and table headers), in pane order.
pub const PANE_NAMES: [&str; MAX_PANES] = ["A", "B", "C", "D"];
/// One colour per pane for the overlaid plots.
pub const PANE_COLORS: [&str; MAX_PANES] = ["#2f6fdf", "#df4f2f", "#2f9f5f", "#9f4fdf"];
/// The time-series keys, in plot order.
pub const SERIES_KEYS: [&str; 5] =
    ["arrived_share", "collisions_agent_agent", "penetrations_agent_obstacle", "speed", "stuck_agents"];
/// Longest spec string accepted (bytes).
const MAX_SPEC_BYTES: usize = 16 << 10;

/// Why a comparison spec was refused; the message names the problem.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecError(pub Message);

impl Refusal for SpecError {
    fn message(&self) -> Message {
        Message::new(Code::Compare).with("reason", self.0.clone())
    }
}

impl std::fmt::Display for SpecError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.message().fmt(f)
    }
}

impl std::error::Error for SpecError {}

impl From<SceneError> for SpecError {
    fn from(e: SceneError) -> Self {
        SpecError(e.message())
    }
}

fn err<T>(message: Message) -> Result<T, SpecError> {
    Err(SpecError(message))
}

/// The planners of one pane.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PaneSpec {
    /// A planner for every group, or `None` to keep each group's own.
    pub all: Option<PlannerConfig>,
    /// Per-group planners (0-based group index), applied after `all`.
    pub groups: Vec<(u32, PlannerConfig)>,
}

impl PaneSpec {
    /// A pane that runs the scene as it is.
    pub fn scene() -> Self {
        Self::default()
    }

    /// A pane with `kind` (default parameters) for every group.
    pub fn every_group(kind: PlannerKind) -> Self {
        Self { all: Some(kind.default_config()), groups: Vec::new() }
    }

    /// The scene with this pane's planners; errors name a group the scene does not have.
    pub fn apply(&self, scene: &Scene) -> Result<Scene, SpecError> {
        let mut scene = scene.clone();
        if let Some(all) = &self.all {
            for g in &mut scene.groups {
                g.planner = all.clone();
            }
        }
        for (g, config) in &self.groups {
            let count = scene.groups.len();
            let group = scene.groups.get_mut(*g as usize).ok_or_else(|| {
                SpecError(
                    Message::new(Code::ComparePaneGroupMissing).with("group", g + 1).with("count", count),
                )
            })?;
            group.planner = config.clone();
        }
        Ok(scene)
    }

    fn parse(text: &str) -> Result<Self, SpecError> {
        let mut pane = PaneSpec::default();
        if text == "scene" {
            return Ok(pane);
        }
        if text.is_empty() {
            return err(Message::new(Code::ComparePaneEmpty));
        }
        for assignment in text.split(';') {
            let (group, planner) = match assignment.split_once('=') {
                Some((g, p)) => {
                    let n: u32 = g
                        .parse()
                        .map_err(|_| SpecError(Message::new(Code::ComparePaneNotGroup).with("text", g)))?;
                    if n == 0 {
                        return err(Message::new(Code::ComparePaneGroupZero));
                    }
                    (Some(n - 1), p)
                }
                None => (None, assignment),
            };
            let config = parse_planner(planner)?;
            match group {
                None if pane.all.is_some() => return err(Message::new(Code::ComparePaneAllTwice)),
                None => pane.all = Some(config),
                Some(g) if pane.groups.iter().any(|(h, _)| *h == g) => {
                    return err(Message::new(Code::ComparePaneGroupTwice).with("group", g + 1))
                }
                Some(g) => pane.groups.push((g, config)),
            }
        }
        Ok(pane)
    }

    fn write(&self, out: &mut String) {
        if self.all.is_none() && self.groups.is_empty() {
            out.push_str("scene");
            return;
        }
        let mut first = true;
        if let Some(all) = &self.all {
            write_planner(all, out);
            first = false;
        }
        for (g, config) in &self.groups {
            if !first {
                out.push(';');
            }
            first = false;
            let _ = write!(out, "{}=", g + 1);
            write_planner(config, out);
        }
    }

    /// A short description: the planner (with parameters that differ from its defaults) or,
    /// per group, `group: planner`.
    pub fn describe(&self, scene: &Scene) -> String {
        let Ok(applied) = self.apply(scene) else { return "(invalid)".into() };
        let configs: Vec<&PlannerConfig> = applied.groups.iter().map(|g| &g.planner).collect();
        if configs.windows(2).all(|w| w[0] == w[1]) {
            if let Some(c) = configs.first() {
                return describe_config(c);
            }
            return "no groups".into();
        }
        applied
            .groups
            .iter()
            .map(|g| format!("{}: {}", g.name, describe_config(&g.planner)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The planner's label and up to two parameters that differ from its defaults.
fn describe_config(config: &PlannerConfig) -> String {
    let kind = config.kind();
    let values = param_values(config);
    let defaults = param_values(&kind.default_config());
    let changed: Vec<String> = kind
        .param_specs()
        .iter()
        .zip(values.iter().zip(&defaults))
        .filter(|(_, (v, d))| v != d)
        .map(|(spec, (v, _))| format!("{} {v}", spec.label.to_lowercase()))
        .collect();
    let name = kind.label().split(" (").next().unwrap_or_default().to_string();
    match changed.len() {
        0 => name,
        1 | 2 => format!("{name}, {}", changed.join(", ")),
        n => format!("{name}, {} and {} more", changed[..2].join(", "), n - 2),
    }
}

/// The planner's parameter values as spec text, by table position.
fn param_values(config: &PlannerConfig) -> Vec<String> {
    let params = config.params_json();
    config
        .kind()
        .param_specs()
        .iter()
        .map(|spec| match params.get(spec.key) {
            Some(serde_json::Value::String(s)) => s.clone(),
            Some(serde_json::Value::Bool(b)) => if *b { "on" } else { "off" }.to_string(),
            Some(serde_json::Value::Number(n)) => format_number(n.as_f64().unwrap_or_default()),
            _ => format_number(spec.default),
        })
        .collect()
}

/// The shortest text that reads back as the same parameter (most parameters are `f32`).
fn format_number(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else if f64::from(x as f32) == x {
        format!("{}", x as f32)
    } else {
        format!("{x}")
    }
}

fn write_planner(config: &PlannerConfig, out: &mut String) {
    out.push_str(config.kind().name());
    out.push('(');
    out.push_str(&param_values(config).join(","));
    out.push(')');
}

/// A parameter's label as a term of the page's strings table.
fn label(kind: PlannerKind, spec: &crate::model::params::ParamSpec) -> Arg {
    Arg::term(format!("param.{}.{}", kind.name(), spec.key), spec.label)
}

fn parse_planner(text: &str) -> Result<PlannerConfig, SpecError> {
    let (name, values) = match text.split_once('(') {
        Some((name, rest)) => {
            let inner = rest
                .strip_suffix(')')
                .ok_or_else(|| SpecError(Message::new(Code::ComparePaneNoParen).with("text", text)))?;
            (name, inner)
        }
        None => (text, ""),
    };
    let kind = PlannerKind::parse(name).map_err(|e| SpecError(e.also_accepting(&["scene"]).message()))?;
    let specs = kind.param_specs();
    let mut params = serde_json::Map::new();
    let values: Vec<&str> = if values.is_empty() { Vec::new() } else { values.split(',').collect() };
    if values.len() > specs.len() {
        return err(Message::new(Code::ComparePaneParamCount)
            .with("planner", kind.name())
            .with("count", specs.len())
            .with("given", values.len()));
    }
    for (spec, value) in specs.iter().zip(values) {
        let json = if spec.choices.is_empty() {
            let x: f64 = value.parse().map_err(|_| {
                SpecError(
                    Message::new(Code::ComparePaneParamNumber)
                        .with("label", label(kind, spec))
                        .with("planner", kind.name())
                        .with("value", value),
                )
            })?;
            if !(spec.min..=spec.max).contains(&x) {
                let unit = if spec.unit.is_empty() {
                    Arg::from("")
                } else {
                    Arg::term(format!("unit.{}", spec.unit), spec.unit)
                };
                return err(Message::new(Code::ComparePaneParamRange)
                    .with("label", label(kind, spec))
                    .with("planner", kind.name())
                    .with("value", value)
                    .with("min", spec.min)
                    .with("max", spec.max)
                    .with("unit", unit));
            }
            if value.bytes().all(|b| b.is_ascii_digit() || b == b'-') {
                serde_json::Value::from(x as i64)
            } else {
                serde_json::Number::from_f64(x).map(serde_json::Value::Number).ok_or_else(|| {
                    SpecError(
                        Message::new(Code::ComparePaneParamFinite)
                            .with("label", label(kind, spec))
                            .with("planner", kind.name()),
                    )
                })?
            }
        } else if spec.choices.contains(&value) {
            serde_json::Value::from(value)
        } else {
            return err(Message::new(Code::ComparePaneParamChoice)
                .with("label", label(kind, spec))
                .with("planner", kind.name())
                .with("choices", spec.choices.to_vec())
                .with("value", value));
        };
        params.insert(spec.key.to_string(), json);
    }
    let config: PlannerConfig = serde_json::from_value(
        serde_json::json!({ "kind": kind.name(), "params": params }),
    )
    .map_err(|e| {
        SpecError(
            Message::new(Code::ComparePanePlanner).with("planner", kind.name()).with("reason", e.to_string()),
        )
    })?;
    config.check().map_err(|e| {
        SpecError(
            Message::new(Code::ComparePanePlanner).with("planner", kind.name()).with("reason", e.message()),
        )
    })?;
    Ok(config)
}

/// What each pane runs.
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonSpec {
    /// One to [`MAX_PANES`] panes.
    pub panes: Vec<PaneSpec>,
}

impl ComparisonSpec {
    /// The comparison a scene opens with when the link has none: the scene's own planners
    /// against PSO (or against Boids when the scene already uses PSO everywhere).
    pub fn default_for(scene: &Scene) -> Self {
        let all_pso =
            !scene.groups.is_empty() && scene.groups.iter().all(|g| g.planner.kind() == PlannerKind::Pso);
        let other = if all_pso { PlannerKind::Boids } else { PlannerKind::Pso };
        Self { panes: vec![PaneSpec::scene(), PaneSpec::every_group(other)] }
    }

    /// Reads a spec string (`1.…`, or a URL / fragment holding `c=1.…`).
    pub fn parse(input: &str) -> Result<Self, SpecError> {
        let value = link::option_or_fragment(input.trim(), "c");
        if value.len() > MAX_SPEC_BYTES {
            return err(Message::new(Code::CompareSpecTooLarge)
                .with("bytes", value.len())
                .with("limit", MAX_SPEC_BYTES));
        }
        if value.is_empty() {
            return err(Message::new(Code::CompareSpecEmpty));
        }
        let (version, body) = value.split_once('.').ok_or_else(|| {
            SpecError(Message::new(Code::CompareSpecNoVersion).with("expected", SPEC_VERSION))
        })?;
        if version != SPEC_VERSION {
            return err(Message::new(Code::CompareSpecVersion)
                .with("version", version.chars().take(12).collect::<String>())
                .with("readable", SPEC_VERSION));
        }
        let panes = body.split('~').map(PaneSpec::parse).collect::<Result<Vec<_>, _>>()?;
        if panes.len() > MAX_PANES {
            return err(Message::new(Code::ComparePanesTooMany)
                .with("count", panes.len())
                .with("most", MAX_PANES));
        }
        Ok(Self { panes })
    }

    /// The spec string (`1.…`), listing every parameter value.
    pub fn to_spec_string(&self) -> String {
        let mut out = format!("{SPEC_VERSION}.");
        for (i, pane) in self.panes.iter().enumerate() {
            if i > 0 {
                out.push('~');
            }
            pane.write(&mut out);
        }
        out
    }
}

/// Sampled time series of one pane (every `every` steps), as the compare page reads it: one
/// list per key. Held as a [`BoundedSeries`] of rows, halved when full.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Series {
    /// Steps between samples now.
    pub every: u32,
    /// Step of each sample.
    pub steps: Vec<u32>,
    /// Share of agents inside their goal.
    pub arrived_share: Vec<f64>,
    /// Agent–agent collisions so far (cumulative).
    pub collisions_agent_agent: Vec<f64>,
    /// Agent–obstacle penetrations so far (cumulative).
    pub penetrations_agent_obstacle: Vec<f64>,
    /// Mean speed of the agents at that step (px/step).
    pub speed: Vec<f64>,
    /// Agents stuck at that step.
    pub stuck_agents: Vec<f64>,
}

/// The values of one sample, in [`SERIES_KEYS`] order.
type PaneSample = [f64; 5];

/// A pane's bounded series (see [`Series`] for what it holds).
fn pane_series() -> BoundedSeries<PaneSample> {
    BoundedSeries::new(1, MAX_SERIES_SAMPLES, SERIES_EVERY)
}

/// Samples `world` into `series` when its step falls on the interval.
fn sample(series: &mut BoundedSeries<PaneSample>, world: &World) {
    if !series.due(world.step_count()) {
        return;
    }
    let m = world.metrics();
    let n = world.velocities().len().max(1) as f64;
    let speed = world.velocities().iter().map(|v| f64::from(v.length())).sum::<f64>() / n;
    let o = &m.overall;
    let row = [
        o.arrived_share,
        o.collisions_agent_agent as f64,
        o.penetrations_agent_obstacle as f64,
        speed,
        f64::from(o.stuck_agents),
    ];
    series.push(m.steps, [row]);
}

impl Series {
    fn of(series: &BoundedSeries<PaneSample>) -> Self {
        let column = |k: usize| series.values().iter().map(|row| row[k]).collect();
        Self {
            every: series.every(),
            steps: series.steps().to_vec(),
            arrived_share: column(0),
            collisions_agent_agent: column(1),
            penetrations_agent_obstacle: column(2),
            speed: column(3),
            stuck_agents: column(4),
        }
    }
}

/// One pane: its planners, its world and its series.
pub struct Pane {
    spec: PaneSpec,
    label: String,
    world: World,
    series: BoundedSeries<PaneSample>,
}

impl Pane {
    fn new(scene: &Scene, spec: PaneSpec) -> Result<Self, SpecError> {
        let applied = spec.apply(scene)?;
        let world = World::new(applied)?;
        let label = spec.describe(scene);
        let mut series = pane_series();
        sample(&mut series, &world);
        Ok(Self { spec, label, world, series })
    }

    /// What this pane runs.
    pub fn spec(&self) -> &PaneSpec {
        &self.spec
    }

    /// A short description of the pane's planners.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// The pane's world.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The pane's time series.
    pub fn series(&self) -> Series {
        Series::of(&self.series)
    }
}

/// A pane's row of the summary table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PaneSummary {
    /// Pane name (A, B, …).
    pub pane: String,
    /// The pane's planners.
    pub label: String,
    /// Steps simulated.
    pub steps: u32,
    /// Agents.
    pub agents: u32,
    /// Share of agents that reached their goal.
    pub arrived_share: f64,
    /// Mean time to the goal over arrived agents (s), if any arrived.
    pub mean_time_to_goal_s: Option<f64>,
    /// Agent–agent collisions (pairs × steps).
    pub collisions_agent_agent: u64,
    /// Agent–obstacle penetrations (agents × steps).
    pub penetrations_agent_obstacle: u64,
    /// Mean path length per agent (px).
    pub mean_path_length: f64,
    /// Mean turning angle per step (degrees): lower is smoother.
    pub mean_turn_deg: f64,
    /// Largest turn in one step (degrees).
    pub max_turn_deg: f64,
    /// Agents stuck at the last step.
    pub stuck_agents: u32,
}

/// The panes of a comparison, stepped in lockstep, with the scene activity's check over them.
pub struct Comparison {
    scene: Scene,
    panes: Vec<Pane>,
    /// Fed after every step of the panes (a restart builds a new comparison, and a new check).
    activity: ActivityWatch,
}

impl Comparison {
    /// Builds every pane from `scene` (the same seed in every pane).
    pub fn new(scene: Scene, spec: ComparisonSpec) -> Result<Self, SpecError> {
        if spec.panes.is_empty() || spec.panes.len() > MAX_PANES {
            return err(Message::new(Code::ComparePanesCount)
                .with("count", spec.panes.len())
                .with("most", MAX_PANES));
        }
        scene.validate()?;
        let panes = spec.panes.into_iter().map(|p| Pane::new(&scene, p)).collect::<Result<Vec<_>, _>>()?;
        Ok(Self { scene, panes, activity: ActivityWatch::new(Page::Compare) })
    }

    /// The scene every pane runs (with the pane's planners applied on top).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The panes, in order.
    pub fn panes(&self) -> &[Pane] {
        &self.panes
    }

    /// The spec of the panes as they are now.
    pub fn spec(&self) -> ComparisonSpec {
        ComparisonSpec { panes: self.panes.iter().map(|p| p.spec.clone()).collect() }
    }

    /// Steps simulated (the same in every pane).
    pub fn step_count(&self) -> u32 {
        step_count(&self.panes)
    }

    /// Advances every pane `n` steps, one step of every pane at a time (the panes are
    /// independent: the order changes nothing but when the activity check sees them).
    pub fn step_n(&mut self, n: u32) {
        for _ in 0..n {
            for pane in &mut self.panes {
                pane.world.step();
                sample(&mut pane.series, &pane.world);
            }
            let (panes, scene) = (&self.panes, &self.scene);
            self.activity.observe(scene, step_count(panes), || metrics(panes));
        }
    }

    /// The activity check over the panes at the step shown (`None` when the scene has no check).
    pub fn activity_report(&self) -> Option<Report> {
        self.activity.report(&self.scene, self.step_count())
    }

    /// Restarts every pane from step 0.
    pub fn reset(&mut self) -> Result<(), SpecError> {
        let spec = self.spec();
        *self = Self::new(self.scene.clone(), spec)?;
        Ok(())
    }

    /// Replaces the spec (restarts every pane); on error nothing changes.
    pub fn set_spec(&mut self, spec: ComparisonSpec) -> Result<(), SpecError> {
        *self = Self::new(self.scene.clone(), spec)?;
        Ok(())
    }

    /// Gives pane `pane` `kind` for every group with its defaults, or the scene's own planners
    /// for `None`; restarts every pane. On error nothing changes.
    pub fn set_pane_planner(&mut self, pane: usize, kind: Option<PlannerKind>) -> Result<(), SpecError> {
        let mut spec = self.spec();
        *pane_slot(&mut spec, pane)? = kind.map_or_else(PaneSpec::scene, PaneSpec::every_group);
        self.set_spec(spec)
    }

    /// Sets one parameter of pane `pane`'s every-group planner; restarts every pane. On error
    /// (no such pane, a pane running the scene's planners, a value out of range) nothing changes.
    pub fn set_pane_param(
        &mut self,
        pane: usize,
        key: &str,
        value: serde_json::Value,
    ) -> Result<(), SpecError> {
        let mut spec = self.spec();
        let config = pane_slot(&mut spec, pane)?
            .all
            .as_mut()
            .ok_or_else(|| SpecError(Message::new(Code::ComparePaneSceneParam)))?;
        config.set_param(key, value).map_err(|e| SpecError(e.message()))?;
        self.set_spec(spec)
    }

    /// Adds a pane running `kind` for every group (`None`: the scene's planners); restarts.
    /// Errors past [`MAX_PANES`].
    pub fn add_pane(&mut self, kind: Option<PlannerKind>) -> Result<(), SpecError> {
        let mut spec = self.spec();
        spec.panes.push(kind.map_or_else(PaneSpec::scene, PaneSpec::every_group));
        self.set_spec(spec)
    }

    /// Removes pane `pane`; restarts. Errors for a missing pane or the last one.
    pub fn remove_pane(&mut self, pane: usize) -> Result<(), SpecError> {
        let mut spec = self.spec();
        pane_slot(&mut spec, pane)?;
        spec.panes.remove(pane);
        self.set_spec(spec)
    }

    /// Replaces the scene, keeping the spec (restarts); on error nothing changes.
    pub fn set_scene(&mut self, scene: Scene) -> Result<(), SpecError> {
        *self = Self::new(scene, self.spec())?;
        Ok(())
    }

    /// The metrics of every pane.
    pub fn metrics(&self) -> Vec<Metrics> {
        metrics(&self.panes)
    }

    /// The summary row of every pane.
    pub fn summary(&self) -> Vec<PaneSummary> {
        self.panes
            .iter()
            .zip(PANE_NAMES)
            .map(|(p, name)| {
                let m = p.world.metrics();
                PaneSummary {
                    pane: name.to_string(),
                    label: p.label.clone(),
                    steps: m.steps,
                    agents: m.overall.agents,
                    arrived_share: m.overall.arrived_share,
                    mean_time_to_goal_s: m.overall.mean_time_to_goal_s,
                    collisions_agent_agent: m.overall.collisions_agent_agent,
                    penetrations_agent_obstacle: m.overall.penetrations_agent_obstacle,
                    mean_path_length: m.overall.mean_path_length,
                    mean_turn_deg: m.overall.mean_turn_deg,
                    max_turn_deg: m.overall.max_turn_deg,
                    stuck_agents: m.overall.stuck_agents,
                }
            })
            .collect()
    }

    /// The summary as CSV with a header row (one row per pane; empty cell for "none arrived").
    pub fn summary_csv(&self) -> String {
        let mut out = String::from(
            "pane,planners,steps,agents,arrived_share,mean_time_to_goal_s,collisions_agent_agent,\
             penetrations_agent_obstacle,mean_path_length_px,mean_turn_deg,max_turn_deg,stuck_agents\n",
        );
        for r in self.summary() {
            let time = r.mean_time_to_goal_s.map(|t| format!("{t:.3}")).unwrap_or_default();
            let _ = writeln!(
                out,
                "{},{},{},{},{:.4},{},{},{},{:.2},{:.3},{:.3},{}",
                r.pane,
                csv::field(&r.label),
                r.steps,
                r.agents,
                r.arrived_share,
                time,
                r.collisions_agent_agent,
                r.penetrations_agent_obstacle,
                r.mean_path_length,
                r.mean_turn_deg,
                r.max_turn_deg,
                r.stuck_agents
            );
        }
        out
    }

    /// Every pane's digest (equal digests: bit-identical runs).
    pub fn digests(&self) -> Vec<u64> {
        self.panes.iter().map(|p| p.world.digest()).collect()
    }
}

/// Pane `pane` of `spec`, or an error naming it (counted from 1).
fn pane_slot(spec: &mut ComparisonSpec, pane: usize) -> Result<&mut PaneSpec, SpecError> {
    spec.panes
        .get_mut(pane)
        .ok_or_else(|| SpecError(Message::new(Code::CompareNoPane).with("number", pane as u64 + 1)))
}

/// Steps simulated by `panes` (the same in every pane; 0 without panes).
fn step_count(panes: &[Pane]) -> u32 {
    panes.first().map_or(0, |p| p.world.step_count())
}

/// The metrics of every pane of `panes`.
fn metrics(panes: &[Pane]) -> Vec<Metrics> {
    panes.iter().map(|p| p.world.metrics()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;

    #[test]
    fn number_formatting_reads_back_exactly() {
        for x in [0.1f32, 1.5, 14.0, 0.15, 1e-3, 123.456] {
            let text = format_number(f64::from(x));
            assert_eq!(text.parse::<f32>().expect("number"), x, "{text}");
        }
        assert_eq!(format_number(3.0), "3");
    }

    #[test]
    fn describe_names_changed_parameters() {
        let scene = (presets::find("open-field").expect("preset").build)();
        let mut config = PlannerKind::Boids.default_config();
        config.set_param("max_speed", serde_json::json!(3.0)).expect("in range");
        let pane = PaneSpec { all: Some(config), groups: Vec::new() };
        assert!(pane.describe(&scene).contains('3'), "{}", pane.describe(&scene));
        assert_eq!(PaneSpec::every_group(PlannerKind::Pso).describe(&scene), "PSO crowd");
    }
}
