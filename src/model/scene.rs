//! The scene a user draws: bounds, obstacles, goals, groups of agents, seed; and its validation.

use crate::model::activity::Activity;
use crate::model::geometry::{v, Obstacle};
use crate::model::params::spec::number_text;
use crate::model::params::PlannerConfig;
use crate::model::refusal::{Arg, Code, Message, Refusal};
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Seconds per step: the fixed time step (JS owns the frame loop, Rust owns time).
pub const DT: f32 = 1.0 / 60.0;
/// Largest decompressed scene accepted from a URL (bytes): a guard against deflate bombs.
pub const MAX_SCENE_BYTES: usize = 4 << 20;
/// Largest scene text accepted (a file, a link, a JSON string; the codec checks it) from a URL or file (bytes).
pub const MAX_INPUT_BYTES: usize = 8 << 20;
/// Longest scene string (the `s=` value of a link, `flockpath url`'s output) a scene may have,
/// in characters. Chromium keeps at most 2 MiB (2,097,152 characters) of address: a longer
/// link loses its fragment on reload or when opened, and the page then shows its default
/// scene without a word. The page's own address and the classroom options need the rest. A
/// scene is checked against it when loaded (`crate::model::codec`), so every scene that loads
/// has a link that opens it again.
pub const MAX_LINK_CHARS: usize = 2_000_000;
/// Longest name (the scene's, a group's), in characters: one line in the legend, the metrics
/// panel and the exports' headers. Before this limit a 7 MiB name loaded from JSON, and its
/// link was too long to open.
pub const MAX_NAME_CHARS: usize = 100;

/// Most agents a scene may hold in total (keeps a typo from freezing the page).
pub const MAX_AGENTS: u32 = 200_000;
/// Largest scene side in px.
pub const MAX_SIDE: f32 = 20_000.0;
/// Most obstacles a scene may hold.
pub const MAX_OBSTACLES: usize = 5_000;
/// Most vertices a polygon obstacle may have.
pub const MAX_POLYGON_POINTS: usize = 1_000;

/// A whole scene. Units: px for lengths, steps for time (one step is [`crate::DT`] seconds);
/// `px_per_metre` relates px to metres ([`Scale`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Display name.
    #[serde(default)]
    pub name: String,
    /// Width of the world in px.
    pub width: f32,
    /// Height of the world in px.
    pub height: f32,
    /// Seed of the one random generator: same scene + same seed = same run.
    #[serde(default)]
    pub seed: u32,
    /// Static obstacles.
    #[serde(default)]
    pub obstacles: Vec<Obstacle>,
    /// Goals that groups head for.
    #[serde(default)]
    pub goals: Vec<Goal>,
    /// Groups of agents.
    #[serde(default)]
    pub groups: Vec<Group>,
    /// How the page shows the run (trails); carried in shared links, no effect on the simulation.
    #[serde(default)]
    pub view: ViewOptions,
    /// Drawn paths that groups may follow (Boids path following, parameter `path`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub paths: Vec<PathSpec>,
    /// Hills of the ground (a height field of Gaussian bumps): drawn as shading, a cost for PSO.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hills: Vec<Hill>,
    /// How many px make one metre ([`Scale`]); default [`DEFAULT_PX_PER_METRE`]. Left out of the
    /// JSON and the link while it holds the default, so scenes saved before it existed keep
    /// their exact text. Only metrics and metre-based settings read it: the simulation runs in px.
    #[serde(default = "default_px_per_metre", skip_serializing_if = "is_default_px_per_metre")]
    pub px_per_metre: f32,
    /// A classroom activity (prompt, prediction, goal checked on the metrics); absent in most
    /// scenes and then left out of the JSON and the link, so older scenes keep their exact text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub activity: Option<Activity>,
}

/// Pixels per metre of a scene that does not say (20 px = 1 m: a 4 px body radius is 0.2 m,
/// about a pedestrian's shoulder half-width).
pub const DEFAULT_PX_PER_METRE: f32 = 20.0;
/// Smallest scale a scene may state (px per metre).
pub const MIN_PX_PER_METRE: f32 = 1.0;
/// Largest scale a scene may state (px per metre).
pub const MAX_PX_PER_METRE: f32 = 1000.0;

fn default_px_per_metre() -> f32 {
    DEFAULT_PX_PER_METRE
}

fn is_default_px_per_metre(x: &f32) -> bool {
    x.to_bits() == DEFAULT_PX_PER_METRE.to_bits()
}

/// A scene's length scale: converts px ↔ metres and px/step ↔ m/s (one step is [`DT`] s, the
/// f32 nearest 1/60, as the metrics' `time_s` counts it).
///
/// The simulation works in px and steps; this is the one place where metres come in. Build one
/// with [`Scene::scale`] (or [`Scale::new`] for a stated number), then convert:
///
/// ```
/// use flockpath::model::scene::{Scale, Scene};
/// let scale = Scene::empty(800.0, 600.0).scale(); // 20 px = 1 m by default
/// assert_eq!(scale.metres(40.0), 2.0);
/// assert_eq!(scale.px(1.5), 30.0);
/// // 1.34 m/s, a pedestrian's mean free walking speed, in px per step (≈ 0.447) and back:
/// let v = scale.px_per_step(1.34);
/// assert!((v - 1.34 * 20.0 / 60.0).abs() < 1e-6);
/// assert!((scale.m_s(v) - 1.34).abs() < 1e-12);
/// // 2 persons on 10 000 px² = 25 m²:
/// assert_eq!(2.0 / scale.square_metres(10_000.0), 0.08);
/// ```
///
/// Everything is in f64: measurements are summed in f64, and a planner setting converted from
/// metres is cast to f32 once (`scale.px_per_step(1.34) as f32`). The scale is not checked here;
/// [`Scene::validate`] refuses a scene whose `px_per_metre` is outside
/// [`MIN_PX_PER_METRE`]…[`MAX_PX_PER_METRE`] or not a number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    px_per_metre: f64,
}

impl Default for Scale {
    fn default() -> Self {
        Self::new(DEFAULT_PX_PER_METRE)
    }
}

impl Scale {
    /// A scale of `px_per_metre` pixels per metre.
    pub fn new(px_per_metre: f32) -> Self {
        Self { px_per_metre: f64::from(px_per_metre) }
    }

    /// Pixels per metre.
    pub fn px_per_metre(self) -> f64 {
        self.px_per_metre
    }

    /// A length in px, in metres.
    pub fn metres(self, px: f64) -> f64 {
        px / self.px_per_metre
    }

    /// A length in metres, in px.
    pub fn px(self, metres: f64) -> f64 {
        metres * self.px_per_metre
    }

    /// An area in px², in m².
    pub fn square_metres(self, px2: f64) -> f64 {
        px2 / (self.px_per_metre * self.px_per_metre)
    }

    /// A speed in px/step, in m/s.
    pub fn m_s(self, px_per_step: f64) -> f64 {
        px_per_step / self.px_per_metre / f64::from(DT)
    }

    /// A speed in m/s, in px/step.
    pub fn px_per_step(self, m_s: f64) -> f64 {
        m_s * self.px_per_metre * f64::from(DT)
    }
}

/// Most paths a scene may hold.
pub const MAX_PATHS: usize = 64;
/// Most hills a scene may hold.
pub const MAX_HILLS: usize = 256;
/// Highest hill allowed (px: heights share the unit of the ground plane, as the 3-D exports do).
pub const MAX_HILL_HEIGHT: f32 = 10_000.0;

/// A polyline path with a radius: Reynolds' path following keeps agents within `radius` of it
/// while they travel from its first point to its last.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PathSpec {
    /// Vertices `[x, y]` in px, in travel order (at least two).
    pub points: Vec<[f32; 2]>,
    /// Half-width of the corridor around the polyline, px. Default 30.
    #[serde(default = "default_path_radius")]
    pub radius: f32,
}

/// Default corridor half-width of a drawn path (px).
pub const DEFAULT_PATH_RADIUS: f32 = 30.0;

fn default_path_radius() -> f32 {
    DEFAULT_PATH_RADIUS
}

impl PathSpec {
    /// The closest point of the polyline to `p`, with the index of its segment and its
    /// distance along the whole path (px). `None` for a path without points.
    pub fn closest_point(&self, p: Vec2) -> Option<PathPoint> {
        self.closest_point_in(p, 0..self.points.len().saturating_sub(1))
    }

    /// [`Self::closest_point`] over segments `segments` only (segment `k` joins points `k` and
    /// `k + 1`); a single-point path yields that point.
    pub fn closest_point_in(&self, p: Vec2, segments: std::ops::Range<usize>) -> Option<PathPoint> {
        let first = v(*self.points.first()?);
        if self.points.len() == 1 {
            return Some(PathPoint { point: first, segment: 0, along: 0.0, direction: Vec2::ZERO });
        }
        let mut along_start = 0.0f32;
        let mut best: Option<(f32, PathPoint)> = None;
        for (k, pair) in self.points.windows(2).enumerate() {
            let (a, b) = (v(pair[0]), v(pair[1]));
            let ab = b - a;
            let length = ab.length();
            if segments.contains(&k) {
                let t =
                    if length > 0.0 { ((p - a).dot(ab) / (length * length)).clamp(0.0, 1.0) } else { 0.0 };
                let q = a + ab * t;
                let d2 = p.distance_squared(q);
                if best.as_ref().is_none_or(|(bd, _)| d2 < *bd) {
                    let direction = if length > 0.0 { ab / length } else { Vec2::ZERO };
                    best = Some((
                        d2,
                        PathPoint { point: q, segment: k, along: along_start + t * length, direction },
                    ));
                }
            }
            along_start += length;
        }
        best.map(|(_, q)| q)
    }

    /// Total length of the polyline (px).
    pub fn length(&self) -> f32 {
        self.points.windows(2).map(|w| v(w[0]).distance(v(w[1]))).sum()
    }

    /// The point at distance `along` from the start, clamped to the path's ends.
    pub fn point_at(&self, along: f32) -> Vec2 {
        let Some(first) = self.points.first() else { return Vec2::ZERO };
        let mut left = along.max(0.0);
        let mut at = v(*first);
        for next in self.points.iter().skip(1).map(|q| v(*q)) {
            let length = at.distance(next);
            if left <= length {
                return if length > 0.0 { at + (next - at) * (left / length) } else { at };
            }
            left -= length;
            at = next;
        }
        at
    }
}

/// A point on a path, as found by [`PathSpec::closest_point`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint {
    /// The point (px).
    pub point: Vec2,
    /// Index of its segment.
    pub segment: usize,
    /// Distance from the path's start along the polyline (px).
    pub along: f32,
    /// Unit direction of its segment (zero for a degenerate one).
    pub direction: Vec2,
}

/// A hill: a Gaussian bump `height · exp(−|p − center|² / radius²)` of the ground.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hill {
    /// Top of the hill `[x, y]` in px.
    pub center: [f32; 2],
    /// Distance (px) at which the height has fallen to 1/e of the top.
    pub radius: f32,
    /// Height of the top (px, the unit of the ground plane), ≥ 0.
    pub height: f32,
}

impl Hill {
    /// Height of this hill's ground at `p` (px); zero beyond four radii, where it is below
    /// 10⁻⁷ of the top.
    pub fn height_at(&self, p: Vec2) -> f32 {
        let d2 = p.distance_squared(v(self.center));
        let r2 = self.radius * self.radius;
        if d2 >= 16.0 * r2 {
            return 0.0;
        }
        self.height * libm::expf(-d2 / r2)
    }
}

/// Height of the ground at `p`: the sum of the hills (px).
pub fn ground_height(hills: &[Hill], p: Vec2) -> f32 {
    hills.iter().map(|h| h.height_at(p)).sum()
}

/// Display options saved with a scene so a shared link looks the same. They never change a run.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ViewOptions {
    /// Whether agents leave trails. Default on.
    pub trails: bool,
    /// Share of a trail's visibility lost every two steps (a frame at the page's default speed;
    /// trails fade with the steps, not with redraws): 0 = permanent, 1 = the newest segments
    /// only. Default 0.01.
    pub trail_fade: f32,
}

impl Default for ViewOptions {
    fn default() -> Self {
        Self { trails: true, trail_fade: 0.01 }
    }
}

/// A goal: agents inside its radius count as arrived.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Goal {
    /// Centre `[x, y]` in px.
    pub position: [f32; 2],
    /// Arrival radius in px.
    #[serde(default = "default_goal_radius")]
    pub radius: f32,
    /// How the goal moves; `None` (the default, and every scene saved before motions existed)
    /// keeps it fixed at `position`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<GoalMotion>,
    /// What agents do on reaching the goal: gather in it (the default, also for every scene
    /// saved before the option existed) or leave the scene through it.
    #[serde(default, skip_serializing_if = "OnArrival::is_gather")]
    pub on_arrival: OnArrival,
}

/// What agents do once they reach their goal (DESIGN §4, "Goals and arrival").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnArrival {
    /// The goal is a place that fills, like a waiting area: each arriving agent walks to a free
    /// place inside it and stops there; when none is left the others wait outside, packed.
    #[default]
    Gather,
    /// The goal is an exit: an agent whose centre enters it leaves the scene (an evacuation,
    /// the RiMEA tests).
    Exit,
}

impl OnArrival {
    /// Whether this is [`OnArrival::Gather`] (left out of JSON, the default).
    pub fn is_gather(&self) -> bool {
        *self == OnArrival::Gather
    }

    /// The name used in JSON and links.
    pub fn name(self) -> &'static str {
        match self {
            OnArrival::Gather => "gather",
            OnArrival::Exit => "exit",
        }
    }
}

/// Most points a goal's polyline path may have.
pub const MAX_PATH_POINTS: usize = 1_000;

/// How a goal moves over time (step `t` counts from the start of the run).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum GoalMotion {
    /// Uniform motion on a circle, starting at the point of the circle nearest to the goal's
    /// `position` and turning clockwise on screen (y down) as the step count grows.
    Circle {
        /// Centre `[x, y]` in px.
        center: [f32; 2],
        /// Radius in px, ≥ 0.
        radius: f32,
        /// Steps per full turn, > 0.
        period_steps: f32,
    },
    /// Along a polyline at a constant speed from its first point; it stays at the last point.
    Polyline {
        /// Vertices `[x, y]` in px (at least one).
        points: Vec<[f32; 2]>,
        /// Speed along the path in px/step, ≥ 0.
        speed: f32,
    },
}

impl GoalMotion {
    /// Position at step `step` of a goal that starts at `start`. Computed with libm (and the
    /// turn fraction in f64) so every platform agrees and long runs stay accurate.
    pub fn position_at(&self, start: Vec2, step: u32) -> Vec2 {
        match self {
            GoalMotion::Circle { center, radius, period_steps } => {
                let c = v(*center);
                let from = start - c;
                let phase0 = if from.length_squared() > 0.0 { libm::atan2f(from.y, from.x) } else { 0.0 };
                let turns = (f64::from(step) / f64::from(period_steps.max(f32::MIN_POSITIVE))).fract();
                let angle = phase0 + (turns * std::f64::consts::TAU) as f32;
                c + Vec2::new(libm::cosf(angle), libm::sinf(angle)) * *radius
            }
            GoalMotion::Polyline { points, speed } => {
                let mut left = *speed * step as f32;
                let Some(first) = points.first() else { return Vec2::ZERO };
                let mut at = v(*first);
                for next in points.iter().skip(1).map(|p| v(*p)) {
                    let length = at.distance(next);
                    if left <= length {
                        return if length > 0.0 { at + (next - at) * (left / length) } else { at };
                    }
                    left -= length;
                    at = next;
                }
                at
            }
        }
    }

    /// Checks the motion of the goal at `path` (`goals[0].motion`) in `scene`.
    fn validate(&self, path: &str, scene: &Scene) -> Result<(), SceneError> {
        match self {
            GoalMotion::Circle { center, radius, period_steps } => {
                for (k, &c) in center.iter().enumerate() {
                    finite_at(|| format!("{path}.center[{k}]"), c)?;
                }
                number_in(|| format!("{path}.radius"), *radius, 0.0, false, MAX_SIDE)?;
                number_in(|| format!("{path}.period_steps"), *period_steps, 1.0, false, f32::MAX)?;
                let reach = Vec2::splat(*radius);
                if !scene.in_bounds(v(*center) - reach) || !scene.in_bounds(v(*center) + reach) {
                    return Err(SceneError::field(
                        format!("{path}.radius"),
                        num(*radius),
                        format!(
                            "a circle around ({}, {}) that stays inside the {}×{} px world",
                            num(center[0]),
                            num(center[1]),
                            num(scene.width),
                            num(scene.height)
                        ),
                    ));
                }
            }
            GoalMotion::Polyline { points, speed } => {
                count_in(|| format!("{path}.points"), points.len(), 1, MAX_PATH_POINTS)?;
                for (k, p) in points.iter().enumerate() {
                    scene.point_near(|| format!("{path}.points[{k}]"), *p)?;
                }
                number_in(|| format!("{path}.speed"), *speed, 0.0, false, MAX_SIDE)?;
            }
        }
        Ok(())
    }
}

impl Goal {
    /// A goal that stays at `position`.
    pub fn fixed(position: [f32; 2], radius: f32) -> Self {
        Self { position, radius, motion: None, on_arrival: OnArrival::Gather }
    }

    /// The same goal as an exit ([`OnArrival::Exit`]).
    pub fn exit(self) -> Self {
        Self { on_arrival: OnArrival::Exit, ..self }
    }

    /// The first step from which the goal stays where it is: 0 for a fixed goal, the step a
    /// polyline motion reaches its last point, `None` for a goal that never stops (a circle).
    pub fn rest_step(&self) -> Option<u32> {
        match &self.motion {
            None => Some(0),
            Some(GoalMotion::Circle { .. }) => None,
            Some(GoalMotion::Polyline { points, speed }) => {
                let length: f32 = points.windows(2).map(|w| v(w[0]).distance(v(w[1]))).sum();
                if length <= 0.0 {
                    Some(0)
                } else if *speed <= 0.0 {
                    // It never leaves its first point.
                    Some(0)
                } else {
                    let steps = (f64::from(length) / f64::from(*speed)).ceil();
                    // One more: the motion's f32 arithmetic may reach the end a step late.
                    Some(if steps >= f64::from(u32::MAX - 1) { u32::MAX } else { steps as u32 + 1 })
                }
            }
        }
    }

    /// Where the goal is at step `step`: `position` for a fixed goal, else along its motion.
    pub fn position_at(&self, step: u32) -> Vec2 {
        match &self.motion {
            None => v(self.position),
            Some(m) => m.position_at(v(self.position), step),
        }
    }
}

fn default_goal_radius() -> f32 {
    20.0
}

/// A rectangular region agents are spawned in.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Region {
    /// Top-left corner `[x, y]` in px.
    pub min: [f32; 2],
    /// Bottom-right corner `[x, y]` in px.
    pub max: [f32; 2],
}

/// A group of agents sharing a spawn region, a goal, a colour and a planner.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Group {
    /// Display name.
    #[serde(default)]
    pub name: String,
    /// Colour as `#rrggbb`.
    #[serde(default = "default_color")]
    pub color: String,
    /// Number of agents.
    pub count: u32,
    /// Spawn region.
    pub spawn: Region,
    /// Index into [`Scene::goals`]; `None` lets the group wander.
    #[serde(default)]
    pub goal: Option<u32>,
    /// Body radius in px (collisions are overlapping discs of this radius).
    #[serde(default = "default_agent_radius")]
    pub agent_radius: f32,
    /// The planner steering this group, with its parameters.
    #[serde(default)]
    pub planner: PlannerConfig,
}

fn default_color() -> String {
    crate::model::palette::BLUE.to_string()
}

fn default_agent_radius() -> f32 {
    4.0
}

/// Why a scene was refused. Each message names the offending item; each is a coded
/// [`Message`] (see [`crate::model::refusal`]), its English the `Display`.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneError {
    /// The text is not a scene (bad JSON, bad encoding, unknown version): why, inside.
    Parse(Message),
    /// A number is NaN or infinite.
    NotFinite(Message),
    /// A value is outside its allowed range.
    OutOfRange(Message),
    /// Something refers to an item that does not exist.
    BadReference(Message),
    /// The geometry makes the scene unusable (goal inside an obstacle, no room to spawn).
    Blocked(Message),
    /// The scene asks for more work than the stated limit: IGSA path planning over its
    /// segment checks ([`crate::sim::cost`]).
    TooCostly(Message),
    /// One field's value is refused (wrong type, not a finite number, outside its limit, an
    /// unknown key, a missing one): the message names the field by its path, the value and what
    /// is allowed.
    Field(Box<FieldError>),
    /// The input is larger than a stated limit.
    TooLarge {
        /// What was too large ([`Code::WhatSceneText`], [`Code::WhatUnpackedScene`],
        /// [`Code::WhatSceneLink`]).
        what: Code,
        /// Its size in bytes, when known (unpacking stops at the limit).
        bytes: Option<usize>,
        /// The limit in bytes.
        limit: usize,
    },
    /// The groups' flow fields would keep more memory than the stated limit
    /// (`crate::sim::cost::MAX_FLOW_FIELD_BYTES`): each distinct goal point and body radius among
    /// the groups guided by a field keeps one field of `cells` cells.
    FlowFieldMemory {
        /// The group whose field crosses the limit, as the scene JSON spells it (`groups[499]`).
        path: String,
        /// Distinct fields the scene's groups would keep.
        fields: u64,
        /// Cells of each field (set by the world's size).
        cells: u64,
        /// Bytes the fields would keep.
        bytes: u64,
        /// The limit in bytes.
        limit: u64,
    },
    /// A bare name that names no preset.
    UnknownPreset {
        /// The name given.
        name: String,
        /// Every preset name, in menu order.
        known: Vec<&'static str>,
    },
}

/// A refused field: where it is, what it holds, what is allowed.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldError {
    /// Path to the field as the scene JSON spells it: `groups[2].planner.params.max_speed`
    /// (indices count from 0, like the JSON arrays they index).
    pub path: String,
    /// The refused value as written (`"abc"`, `NaN`, `1e30`: text), or in words (a `value.*`
    /// message: `missing`, `an unknown key`, `a list of 3`).
    pub value: Arg,
    /// What the field accepts, with its unit and limit (`a number in 0.1…20 px/step`).
    pub allowed: String,
    /// The parser's own words and position, for a "details" disclosure; not part of the message.
    pub detail: Option<String>,
}

impl SceneError {
    /// A refused field (see [`FieldError`]).
    pub fn field(path: impl Into<String>, value: impl Into<Arg>, allowed: impl Into<String>) -> Self {
        SceneError::Field(Box::new(FieldError {
            path: path.into(),
            value: value.into(),
            allowed: allowed.into(),
            detail: None,
        }))
    }

    /// A scene text that could not be read, for `reason`.
    pub fn parse(reason: Message) -> Self {
        SceneError::Parse(reason)
    }

    /// "there is no `item` `number`" (`number` counted from 1; `item` a word of the strings
    /// table's `item.*`: obstacle, goal, group, path, hill).
    pub fn no_such_item(item: &str, number: u64) -> Self {
        SceneError::BadReference(
            Message::new(Code::SceneNoSuchItem)
                .with("item", Arg::term(format!("item.{item}"), item))
                .with("number", number),
        )
    }

    /// The parser's raw message and position behind this error, if it came from one.
    pub fn detail(&self) -> Option<&str> {
        match self {
            SceneError::Field(f) => f.detail.as_deref(),
            _ => None,
        }
    }
}

impl Refusal for SceneError {
    fn message(&self) -> Message {
        match self {
            SceneError::Parse(m) => Message::new(Code::SceneParse).with("reason", m.clone()),
            SceneError::NotFinite(m)
            | SceneError::OutOfRange(m)
            | SceneError::BadReference(m)
            | SceneError::Blocked(m)
            | SceneError::TooCostly(m) => m.clone(),
            SceneError::Field(e) => Message::new(Code::SceneField)
                .with("path", e.path.clone())
                .with("value", e.value.clone())
                .with("allowed", e.allowed.clone()),
            SceneError::TooLarge { what, bytes: Some(bytes), limit } => {
                Message::new(Code::SceneTooLargeBytes)
                    .with("what", Message::new(*what))
                    .with("bytes", *bytes)
                    .with("limit", *limit)
            }
            SceneError::TooLarge { what, bytes: None, limit } => {
                Message::new(Code::SceneTooLarge).with("what", Message::new(*what)).with("limit", *limit)
            }
            SceneError::FlowFieldMemory { path, fields, cells, bytes, limit } => {
                Message::new(Code::SceneFlowFieldMemory)
                    .with("path", path.clone())
                    .with("fields", *fields)
                    .with("cells", *cells)
                    .with("mb", bytes.div_ceil(1 << 20))
                    .with("limit_mb", limit / (1 << 20))
            }
            SceneError::UnknownPreset { name, known } => {
                Message::new(Code::SceneUnknownPreset).with("name", name.clone()).with("known", known.clone())
            }
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.message().fmt(f)
    }
}

impl std::error::Error for SceneError {}

fn num(x: f32) -> String {
    number_text(x)
}

/// How far (px) obstacles, hills and moving goals may reach beyond the world's edges: room for a
/// wall drawn across the border, and a bound that keeps squared distances far from overflow.
pub const WORLD_MARGIN: f32 = MAX_SIDE;
/// Most polygon vertices a scene may hold over all its polygons: the check that edges do not
/// cross compares pairs of edges within each polygon.
pub const MAX_POLYGON_POINTS_TOTAL: usize = 50_000;

/// One row of the limits table: a field pattern (`[]` for any index), what it accepts, why.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldLimit {
    /// The field, as a path with `[]` for any index (`groups[].agent_radius`).
    pub field: &'static str,
    /// What is allowed, with the unit.
    pub allowed: String,
    /// Why the limit exists.
    pub why: &'static str,
}

/// Every limit a scene field has, in the words of the refusal messages (the README's table is
/// checked against it). Planner parameters are listed by their own table
/// ([`crate::model::params::ParamSpec`]).
pub fn field_limits() -> Vec<FieldLimit> {
    let row = |field, allowed: String, why| FieldLimit { field, allowed, why };
    let side = format!("a number in 10…{MAX_SIDE} px");
    let inside = "a number inside the world (0…width, 0…height px)".to_string();
    let near = format!(
        "a number within {WORLD_MARGIN} px of the world (−{WORLD_MARGIN}…width/height + {WORLD_MARGIN} px)"
    );
    let length = format!("a number above 0 and at most {MAX_SIDE} px");
    let mut rows = vec![
        row("name", name_text(), "one line in the legend, the metrics and the exports; a link holds it"),
        row("width", side.clone(), "a world from a dot to a large poster; bigger worlds cost memory per grid cell"),
        row("height", side, "as width"),
        row(
            "px_per_metre",
            format!("a number in {MIN_PX_PER_METRE}…{MAX_PX_PER_METRE} px per metre (default {DEFAULT_PX_PER_METRE})"),
            "the scale of metres and m/s in metrics and metre-based settings; the run itself is in px",
        ),
        row("seed", "a whole number 0…4294967295".into(), "a 32-bit seed: same scene + same seed = same run"),
        row("obstacles", format!("a list of at most {MAX_OBSTACLES} obstacles"), "every step tests agents against nearby obstacles"),
        row("obstacles[].shape", "\"circle\", \"rect\" or \"polygon\"".into(), "the shapes the geometry knows"),
        row("obstacles[].center[]", near.clone(), "far-off coordinates only cost precision"),
        row("obstacles[].radius", length.clone(), "a circle larger than the largest world is a typo"),
        row("obstacles[].min[]", format!("{near}, below max"), "a rectangle needs an area"),
        row("obstacles[].max[]", format!("{near}, above min"), "a rectangle needs an area"),
        row(
            "obstacles[].points",
            format!("3…{MAX_POLYGON_POINTS} points of a simple polygon (edges meet only at shared corners, non-zero area); at most {MAX_POLYGON_POINTS_TOTAL} polygon points in all"),
            "inside/outside tests need a simple polygon; the crossing check compares pairs of edges",
        ),
        row("obstacles[].points[][]", near.clone(), "as obstacle centres"),
        row("goals[].position[]", format!("{inside}, outside every obstacle"), "a goal must be reachable"),
        row("goals[].radius", length.clone(), "the arrival disc"),
        row("goals[].motion.kind", "\"circle\" or \"polyline\"".into(), "the motions goals know"),
        row("goals[].motion.center[]", "a number; the whole circle inside the world".into(), "the goal must stay reachable"),
        row("goals[].motion.radius", format!("a number in 0…{MAX_SIDE} px"), "as obstacle radii"),
        row("goals[].motion.period_steps", "a number of at least 1 step".into(), "a turn takes at least one step"),
        row("goals[].motion.points", format!("1…{MAX_PATH_POINTS} points, each {near}"), "a goal's route"),
        row("goals[].motion.speed", format!("a number in 0…{MAX_SIDE} px/step"), "as obstacle radii"),
        row("groups[].count", format!("a whole number 0…{MAX_AGENTS}; all groups together at most {MAX_AGENTS} agents; 0 is an empty group that spawns nothing"), "keeps a typo from freezing the page"),
        row("groups[].name", name_text(), "as the scene's name"),
        row("groups[].color", "a colour \"#rrggbb\"".into(), "what the renderer draws"),
        row("groups[].spawn.min[]", format!("{inside}, at most max"), "agents start inside the world"),
        row("groups[].spawn.max[]", format!("{inside}, at least min"), "agents start inside the world"),
        row("groups[].goal", "null (wander) or the index of one of the scene's goals, counting from 0".into(), "a group heads for a goal that exists"),
        row("groups[].agent_radius", "a number in 0.5…100 px".into(), "bodies from a dot to a large disc"),
        row("groups[].planner.kind", planner_names(), "the planners flockpath has"),
        row("groups[].planner.params.path", "0 (none) or the number of one of the scene's paths, counting from 1".into(), "a Boids group follows a path that exists"),
        row("paths", format!("a list of at most {MAX_PATHS} paths"), "paths are drawn and followed every step"),
        row("paths[].points", format!("2…{MAX_PATH_POINTS} points, each inside the world"), "a path runs inside the world"),
        row("paths[].radius", length.clone(), "the corridor half-width"),
        row("hills", format!("a list of at most {MAX_HILLS} hills"), "every hill adds to each ground-height lookup"),
        row("hills[].center[]", near, "as obstacle centres"),
        row("hills[].radius", length, "as obstacle radii"),
        row("hills[].height", format!("a number in 0…{MAX_HILL_HEIGHT} px"), "hills, not pits; tall enough for any scene"),
        row("view.trail_fade", "a number in 0…1".into(), "the share of a trail lost every two steps"),
        row("(any object)", "only the keys listed here and in the planner tables; an unknown key is refused".into(), "a misspelt key would otherwise be ignored without a word"),
        row("(scene text)", format!("at most {} bytes", MAX_INPUT_BYTES), "a file or link larger than any real scene"),
        row("(unpacked scene string)", format!("at most {} bytes", MAX_SCENE_BYTES), "a guard against deflate bombs"),
        row(
            "(the scene's link)",
            format!("at most {MAX_LINK_CHARS} characters, unpacking to at most {MAX_SCENE_BYTES} bytes"),
            "every scene that loads has a link that opens it again; Chromium drops addresses over 2 MiB",
        ),
    ];
    rows.extend(
        crate::model::activity::limits().into_iter().map(|(field, allowed, why)| row(field, allowed, why)),
    );
    rows
}

/// What a name may hold, in the refusal's words.
fn name_text() -> String {
    format!("text of at most {MAX_NAME_CHARS} characters on one line")
}

/// Refuses the name at `path` if longer than [`MAX_NAME_CHARS`] or holding a control character
/// (a line break would split the exports' header lines).
fn name_in(path: impl Fn() -> String, name: &str) -> Result<(), SceneError> {
    if name.chars().count() > MAX_NAME_CHARS {
        return Err(SceneError::field(path(), crate::model::activity::text_value(name), name_text()));
    }
    if let Some(c) = name.chars().find(|c| c.is_control()) {
        let value = Message::new(Code::ValueTextControl).with("character", format!("U+{:04X}", u32::from(c)));
        return Err(SceneError::field(path(), value, name_text()));
    }
    Ok(())
}

/// What `path` accepts, from [`field_limits`] (indices in the path may be any number).
pub fn allowed_for(path: &str) -> Option<String> {
    let pattern = index_free(path);
    field_limits().into_iter().find(|l| l.field == pattern).map(|l| l.allowed)
}

/// `groups[2].spawn.min[0]` → `groups[].spawn.min[]`.
pub fn index_free(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut in_index = false;
    for c in path.chars() {
        match c {
            '[' => {
                in_index = true;
                out.push('[');
            }
            ']' => {
                in_index = false;
                out.push(']');
            }
            _ if in_index => {}
            _ => out.push(c),
        }
    }
    out
}

/// The allowed text of `path`, or `fallback` when the table has no row for it.
fn allowed(path: &str, fallback: &str) -> String {
    allowed_for(path).unwrap_or_else(|| fallback.to_string())
}

/// Refuses a non-finite number at `path`.
fn finite_at(path: impl Fn() -> String, x: f32) -> Result<(), SceneError> {
    if x.is_finite() {
        Ok(())
    } else {
        let path = path();
        let allowed = allowed(&path, "a finite number");
        Err(SceneError::field(path, num(x), allowed))
    }
}

/// Refuses `x` at `path` unless finite and within `lo…hi` (`above_lo`: strictly above `lo`).
fn number_in(path: impl Fn() -> String, x: f32, lo: f32, above_lo: bool, hi: f32) -> Result<(), SceneError> {
    finite_at(&path, x)?;
    if (above_lo && x <= lo) || (!above_lo && x < lo) || x > hi {
        let path = path();
        let allowed = allowed(&path, &format!("a number in {lo}…{hi}"));
        return Err(SceneError::field(path, num(x), allowed));
    }
    Ok(())
}

impl Scene {
    /// An empty scene of the given size.
    pub fn empty(width: f32, height: f32) -> Self {
        Self {
            name: String::new(),
            width,
            height,
            seed: 1,
            obstacles: vec![],
            goals: vec![],
            groups: vec![],
            view: ViewOptions::default(),
            paths: vec![],
            hills: vec![],
            px_per_metre: DEFAULT_PX_PER_METRE,
            activity: None,
        }
    }

    /// The scene's length scale ([`Scale`]): px ↔ m, px/step ↔ m/s.
    pub fn scale(&self) -> Scale {
        Scale::new(self.px_per_metre)
    }

    /// Total number of agents over all groups.
    pub fn agent_count(&self) -> u64 {
        self.groups.iter().map(|g| u64::from(g.count)).sum()
    }

    /// Checks every value; the first problem found is returned with a message naming the field
    /// by its path (`groups[2].agent_radius`), the value and what is allowed ([`field_limits`]).
    ///
    /// Empty is fine: a scene without obstacles, goals or groups is an empty canvas to draw on,
    /// and a group with `count: 0` spawns nothing (the editor keeps its settings).
    pub fn validate(&self) -> Result<(), SceneError> {
        name_in(|| "name".into(), &self.name)?;
        number_in(|| "width".into(), self.width, 10.0, false, MAX_SIDE)?;
        number_in(|| "height".into(), self.height, 10.0, false, MAX_SIDE)?;
        number_in(|| "px_per_metre".into(), self.px_per_metre, MIN_PX_PER_METRE, false, MAX_PX_PER_METRE)?;
        count_in(|| "obstacles".into(), self.obstacles.len(), 0, MAX_OBSTACLES)?;
        let polygon_points: usize = self
            .obstacles
            .iter()
            .map(|o| if let Obstacle::Polygon { points } = o { points.len() } else { 0 })
            .sum();
        if polygon_points > MAX_POLYGON_POINTS_TOTAL {
            return Err(SceneError::field(
                "obstacles",
                Message::new(Code::ValuePolygonPoints).with("count", polygon_points),
                format!("at most {MAX_POLYGON_POINTS_TOTAL} polygon points over all polygons"),
            ));
        }
        for (i, o) in self.obstacles.iter().enumerate() {
            self.validate_obstacle(i, o)?;
        }
        for (i, g) in self.goals.iter().enumerate() {
            self.point_inside(|| format!("goals[{i}].position"), g.position)?;
            number_in(|| format!("goals[{i}].radius"), g.radius, 0.0, true, MAX_SIDE)?;
            if let Some(k) = self.obstacles.iter().position(|o| o.contains(v(g.position))) {
                return Err(SceneError::Blocked(
                    Message::new(Code::SceneGoalInObstacle)
                        .with("goal", i)
                        .with("x", num(g.position[0]))
                        .with("y", num(g.position[1]))
                        .with("obstacle", k),
                ));
            }
            if let Some(m) = &g.motion {
                m.validate(&format!("goals[{i}].motion"), self)?;
            }
        }
        let total = self.agent_count();
        if total > u64::from(MAX_AGENTS) {
            let path = if self.groups.len() == 1 { "groups[0].count" } else { "groups" };
            return Err(SceneError::field(
                path,
                Message::new(Code::ValueAgentsInAll).with("count", total),
                format!("at most {MAX_AGENTS} agents over all groups"),
            ));
        }
        for (i, g) in self.groups.iter().enumerate() {
            self.validate_group(i, g)?;
        }
        count_in(|| "paths".into(), self.paths.len(), 0, MAX_PATHS)?;
        for (i, path) in self.paths.iter().enumerate() {
            count_in(|| format!("paths[{i}].points"), path.points.len(), 2, MAX_PATH_POINTS)?;
            for (k, p) in path.points.iter().enumerate() {
                self.point_inside(|| format!("paths[{i}].points[{k}]"), *p)?;
            }
            number_in(|| format!("paths[{i}].radius"), path.radius, 0.0, true, MAX_SIDE)?;
        }
        count_in(|| "hills".into(), self.hills.len(), 0, MAX_HILLS)?;
        for (i, h) in self.hills.iter().enumerate() {
            self.point_near(|| format!("hills[{i}].center"), h.center)?;
            number_in(|| format!("hills[{i}].radius"), h.radius, 0.0, true, MAX_SIDE)?;
            number_in(|| format!("hills[{i}].height"), h.height, 0.0, false, MAX_HILL_HEIGHT)?;
        }
        number_in(|| "view.trail_fade".into(), self.view.trail_fade, 0.0, false, 1.0)?;
        match &self.activity {
            Some(a) => {
                a.validate(self.groups.len()).map_err(|f| SceneError::field(f.path, f.value, f.allowed))
            }
            None => Ok(()),
        }
    }

    fn validate_group(&self, i: usize, g: &Group) -> Result<(), SceneError> {
        name_in(|| format!("groups[{i}].name"), &g.name)?;
        let s = g.spawn;
        for (corner, p) in [("min", s.min), ("max", s.max)] {
            self.point_inside(|| format!("groups[{i}].spawn.{corner}"), p)?;
        }
        for k in 0..2 {
            if s.min[k] > s.max[k] {
                return Err(SceneError::field(
                    format!("groups[{i}].spawn.min[{k}]"),
                    num(s.min[k]),
                    format!("at most spawn.max[{k}] ({})", num(s.max[k])),
                ));
            }
        }
        number_in(|| format!("groups[{i}].agent_radius"), g.agent_radius, 0.5, false, 100.0)?;
        if let Some(goal) = g.goal {
            if goal as usize >= self.goals.len() {
                return Err(SceneError::field(
                    format!("groups[{i}].goal"),
                    goal.to_string(),
                    match self.goals.len() {
                        0 => "null: the scene has no goals".to_string(),
                        n => format!("null or a goal index 0…{} (the scene has {n} goal(s))", n - 1),
                    },
                ));
            }
        }
        if !is_hex_color(&g.color) {
            return Err(SceneError::field(
                format!("groups[{i}].color"),
                format!("{:?}", g.color.chars().take(40).collect::<String>()),
                allowed(&format!("groups[{i}].color"), "#rrggbb"),
            ));
        }
        self.validate_planner(i, &g.planner)
    }

    /// Checks the planner settings of group `i` against their table and against this scene (a
    /// Boids group follows a path that exists). The world checks a live planner change with it.
    pub fn validate_planner(&self, i: usize, planner: &PlannerConfig) -> Result<(), SceneError> {
        planner.check().map_err(|e| {
            SceneError::field(format!("groups[{i}].planner.params.{}", e.key), e.value, e.allowed)
        })?;
        if let PlannerConfig::Boids(p) = planner {
            if p.path as usize > self.paths.len() {
                return Err(SceneError::field(
                    format!("groups[{i}].planner.params.path"),
                    p.path.to_string(),
                    match self.paths.len() {
                        0 => "0 (none): the scene has no paths".to_string(),
                        n => format!("0 (none) or a path number 1…{n} (the scene has {n} path(s))"),
                    },
                ));
            }
        }
        Ok(())
    }

    /// Whether a point lies within the scene rectangle.
    pub fn in_bounds(&self, p: Vec2) -> bool {
        p.x >= 0.0 && p.y >= 0.0 && p.x <= self.width && p.y <= self.height
    }

    /// Refuses coordinate `axis` (0 = x, 1 = y) at `path` unless it lies inside the world.
    fn coordinate_inside(&self, path: impl Fn() -> String, x: f32, axis: usize) -> Result<(), SceneError> {
        let side = if axis == 0 { self.width } else { self.height };
        finite_at(&path, x)?;
        if !(0.0..=side).contains(&x) {
            let what = if axis == 0 { "width" } else { "height" };
            return Err(SceneError::field(
                path(),
                num(x),
                format!("a number in 0…{} px (inside the world's {what})", num(side)),
            ));
        }
        Ok(())
    }

    /// Refuses point `p` at `path` unless it lies inside the world.
    fn point_inside(&self, path: impl Fn() -> String, p: [f32; 2]) -> Result<(), SceneError> {
        for (axis, x) in p.into_iter().enumerate() {
            self.coordinate_inside(|| format!("{}[{axis}]", path()), x, axis)?;
        }
        Ok(())
    }

    /// Refuses point `p` at `path` unless both coordinates are finite and within
    /// [`WORLD_MARGIN`] of the world.
    fn point_near(&self, path: impl Fn() -> String, p: [f32; 2]) -> Result<(), SceneError> {
        for (k, side) in [self.width, self.height].into_iter().enumerate() {
            let at = || format!("{}[{k}]", path());
            finite_at(at, p[k])?;
            if p[k] < -WORLD_MARGIN || p[k] > side + WORLD_MARGIN {
                return Err(SceneError::field(
                    at(),
                    num(p[k]),
                    format!(
                        "a number in −{WORLD_MARGIN}…{} px (within {WORLD_MARGIN} px of the world)",
                        num(side + WORLD_MARGIN)
                    ),
                ));
            }
        }
        Ok(())
    }

    fn validate_obstacle(&self, i: usize, o: &Obstacle) -> Result<(), SceneError> {
        match o {
            Obstacle::Circle { center, radius } => {
                self.point_near(|| format!("obstacles[{i}].center"), *center)?;
                number_in(|| format!("obstacles[{i}].radius"), *radius, 0.0, true, MAX_SIDE)?;
            }
            Obstacle::Rect { min, max } => {
                self.point_near(|| format!("obstacles[{i}].min"), *min)?;
                self.point_near(|| format!("obstacles[{i}].max"), *max)?;
                for k in 0..2 {
                    if min[k] >= max[k] {
                        return Err(SceneError::field(
                            format!("obstacles[{i}].min[{k}]"),
                            num(min[k]),
                            format!("below max[{k}] ({}): a rectangle needs an area", num(max[k])),
                        ));
                    }
                }
            }
            Obstacle::Polygon { points } => {
                count_in(|| format!("obstacles[{i}].points"), points.len(), 3, MAX_POLYGON_POINTS)?;
                for (k, p) in points.iter().enumerate() {
                    self.point_near(|| format!("obstacles[{i}].points[{k}]"), *p)?;
                }
                check_simple_polygon(points).map_err(|problem| {
                    SceneError::field(
                        format!("obstacles[{i}].points"),
                        problem.message(),
                        "a simple polygon: edges meet only at shared corners, non-zero area",
                    )
                })?;
            }
        }
        Ok(())
    }
}

/// Refuses a list at `path` of `n` items unless `lo ≤ n ≤ hi`.
fn count_in(path: impl Fn() -> String, n: usize, lo: usize, hi: usize) -> Result<(), SceneError> {
    if n < lo || n > hi {
        let path = path();
        let fallback = if lo == 0 { format!("at most {hi} items") } else { format!("{lo}…{hi} items") };
        let allowed = allowed(&path, &fallback);
        return Err(SceneError::field(path, Message::new(Code::ValueListOf).with("count", n), allowed));
    }
    Ok(())
}

/// Checks that `points` form a simple polygon: not all on one line, and no two edges meet except
/// neighbours at their shared corner (which also rules out zero area). Repeated consecutive points count once (an editor's
/// double click). Edges are swept in order of their left end, so only edges whose x ranges
/// overlap are compared. The problem names the points (from 0).
fn check_simple_polygon(points: &[[f32; 2]]) -> Result<(), PolygonFault> {
    let mut corners: Vec<(usize, [f64; 2])> = Vec::with_capacity(points.len());
    for (k, p) in points.iter().enumerate() {
        let q = [f64::from(p[0]), f64::from(p[1])];
        if corners.last().is_none_or(|(_, last)| *last != q) {
            corners.push((k, q));
        }
    }
    while corners.len() > 1 && corners.first().map(|c| c.1) == corners.last().map(|c| c.1) {
        corners.pop();
    }
    let n = corners.len();
    if n < 3 {
        return Err(PolygonFault::TooFewPoints(n));
    }
    if corners.iter().all(|c| orientation(corners[0].1, corners[1].1, c.1) == 0.0) {
        return Err(PolygonFault::NoArea);
    }
    let edge = |k: usize| (corners[k].1, corners[(k + 1) % n].1);
    let mut order: Vec<usize> = (0..n).collect();
    let min_x = |k: usize| edge(k).0[0].min(edge(k).1[0]);
    order.sort_by(|&a, &b| min_x(a).total_cmp(&min_x(b)));
    for (slot, &a) in order.iter().enumerate() {
        let (a0, a1) = edge(a);
        let max_x = a0[0].max(a1[0]);
        for &b in &order[slot + 1..] {
            if min_x(b) > max_x {
                break;
            }
            let (b0, b1) = edge(b);
            let neighbours = (a + 1) % n == b || (b + 1) % n == a;
            let crossing = if neighbours {
                // Neighbours share one corner; they may only touch there (no folding back).
                let (shared, a_far, b_far) = if (a + 1) % n == b { (a1, a0, b1) } else { (a0, a1, b0) };
                orientation(a_far, shared, b_far) == 0.0 && dot(a_far, shared, b_far) > 0.0
            } else {
                segments_meet(a0, a1, b0, b1)
            };
            if crossing {
                let (first, second) = (a.min(b), a.max(b));
                let edge = |k: usize| [corners[k].0, corners[(k + 1) % n].0];
                return Err(if neighbours {
                    PolygonFault::FoldsBack(edge(first), edge(second))
                } else {
                    PolygonFault::EdgesCross(edge(first), edge(second))
                });
            }
        }
    }
    Ok(())
}

/// Why points do not form a simple polygon; shown as the refused value of `obstacles[i].points`.
/// Edges are named by their end points' indices (from 0): `[2, 3]` is the edge 2→3.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PolygonFault {
    /// Fewer than three distinct points (repeats counted once).
    TooFewPoints(usize),
    /// Every point lies on one line.
    NoArea,
    /// Two neighbouring edges fold back onto each other.
    FoldsBack([usize; 2], [usize; 2]),
    /// Two edges that are not neighbours cross or touch.
    EdgesCross([usize; 2], [usize; 2]),
}

impl PolygonFault {
    /// The fault as the refused value's words.
    fn message(self) -> Message {
        let edge = |e: [usize; 2]| format!("{}→{}", e[0], e[1]);
        match self {
            PolygonFault::TooFewPoints(n) => Message::new(Code::ValuePolygonFew).with("count", n),
            PolygonFault::NoArea => Message::new(Code::ValuePolygonNoArea),
            PolygonFault::FoldsBack(a, b) => {
                Message::new(Code::ValuePolygonFolds).with("a", edge(a)).with("b", edge(b))
            }
            PolygonFault::EdgesCross(a, b) => {
                Message::new(Code::ValuePolygonCross).with("a", edge(a)).with("b", edge(b))
            }
        }
    }
}

/// Twice the signed area of triangle `a, b, c`, in f64 (scene coordinates are f32).
fn orientation(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// `(a − at) · (c − at)`: positive when `a` and `c` lie on the same side of `at`.
fn dot(a: [f64; 2], at: [f64; 2], c: [f64; 2]) -> f64 {
    (a[0] - at[0]) * (c[0] - at[0]) + (a[1] - at[1]) * (c[1] - at[1])
}

/// Whether closed segments `a0a1` and `b0b1` share a point.
fn segments_meet(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> bool {
    let on = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        // r lies on segment pq, given that p, q, r are collinear.
        r[0] >= p[0].min(q[0]) && r[0] <= p[0].max(q[0]) && r[1] >= p[1].min(q[1]) && r[1] <= p[1].max(q[1])
    };
    let (d1, d2) = (orientation(b0, b1, a0), orientation(b0, b1, a1));
    let (d3, d4) = (orientation(a0, a1, b0), orientation(a0, a1, b1));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on(b0, b1, a0))
        || (d2 == 0.0 && on(b0, b1, a1))
        || (d3 == 0.0 && on(a0, a1, b0))
        || (d4 == 0.0 && on(a0, a1, b1))
}

/// Whether `s` is a `#rrggbb` colour.
pub fn is_hex_color(s: &str) -> bool {
    s.len() == 7 && s.starts_with('#') && s[1..].chars().all(|c| c.is_ascii_hexdigit())
}

/// Parses a `#rrggbb` colour into bytes (grey when malformed; validation refuses those first).
pub fn parse_color(s: &str) -> [u8; 3] {
    let byte = |i: usize| s.get(i..i + 2).and_then(|h| u8::from_str_radix(h, 16).ok()).unwrap_or(128);
    if is_hex_color(s) {
        [byte(1), byte(3), byte(5)]
    } else {
        [128, 128, 128]
    }
}

/// The planner names as the limits table words them: `"a", "b" or "c"`.
fn planner_names() -> String {
    let quoted: Vec<String> =
        crate::model::params::PlannerKind::ALL.iter().map(|k| format!("\"{}\"", k.name())).collect();
    match quoted.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        let mut s = Scene::empty(400.0, 300.0);
        s.goals.push(Goal::fixed([350.0, 150.0], 20.0));
        s.groups.push(Group {
            name: "a".into(),
            color: "#ff0000".into(),
            count: 10,
            spawn: Region { min: [10.0, 10.0], max: [60.0, 60.0] },
            goal: Some(0),
            agent_radius: 4.0,
            planner: PlannerConfig::default(),
        });
        s
    }

    #[test]
    fn a_good_scene_validates() {
        assert_eq!(scene().validate(), Ok(()));
    }

    #[test]
    fn nan_is_refused_with_its_name() {
        let mut s = scene();
        s.goals[0].position[0] = f32::NAN;
        let e = s.validate().expect_err("NaN");
        assert!(
            matches!(&e, SceneError::Field(f) if f.path == "goals[0].position[0]" && f.value == "NaN"),
            "{e}"
        );
    }

    #[test]
    fn an_obstacle_over_the_goal_is_refused() {
        let mut s = scene();
        s.obstacles.push(Obstacle::Circle { center: [350.0, 150.0], radius: 30.0 });
        let e = s.validate().expect_err("blocked");
        assert_eq!(
            e,
            SceneError::Blocked(
                Message::new(Code::SceneGoalInObstacle)
                    .with("goal", 0u32)
                    .with("x", "350")
                    .with("y", "150")
                    .with("obstacle", 0u32)
            )
        );
        assert_eq!(
            e.to_string(),
            "goals[0] at (350, 150) is inside obstacles[0]; a goal must lie outside every obstacle"
        );
    }

    #[test]
    fn ten_million_agents_are_refused() {
        let mut s = scene();
        s.groups[0].count = 10_000_000;
        let e = s.validate().expect_err("too many").to_string();
        assert!(e.contains("groups[0].count is 10000000 agents") && e.contains("at most 200000"), "{e}");
    }

    #[test]
    fn a_missing_goal_is_a_bad_reference() {
        let mut s = scene();
        s.groups[0].goal = Some(3);
        let e = s.validate().expect_err("no goal 3").to_string();
        assert_eq!(e, "groups[0].goal is 3; allowed: null or a goal index 0…0 (the scene has 1 goal(s))");
    }

    #[test]
    fn a_circling_goal_moves_on_its_circle_and_old_scenes_still_load() {
        let mut goal = Goal::fixed([300.0, 150.0], 20.0);
        goal.motion = Some(GoalMotion::Circle { center: [200.0, 150.0], radius: 100.0, period_steps: 400.0 });
        assert!(goal.position_at(0).distance(Vec2::new(300.0, 150.0)) < 1e-3);
        assert!(goal.position_at(100).distance(Vec2::new(200.0, 250.0)) < 1e-3);
        assert!(goal.position_at(400).distance(goal.position_at(0)) < 1e-3);
        let mut s = scene();
        s.goals[0] = goal;
        assert_eq!(s.validate(), Ok(()));
        let old: Goal = serde_json::from_str(r#"{"position":[1,2],"radius":3}"#).expect("old goal");
        assert_eq!(old, Goal::fixed([1.0, 2.0], 3.0));
        assert!(!serde_json::to_string(&old).expect("json").contains("motion"));
        if let Some(GoalMotion::Circle { radius, .. }) = &mut s.goals[0].motion {
            *radius = 1000.0;
        }
        assert!(matches!(s.validate(), Err(SceneError::Field(f)) if f.path == "goals[0].motion.radius"));
    }

    #[test]
    fn moving_goals_follow_their_paths() {
        let line = GoalMotion::Polyline { points: vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]], speed: 2.0 };
        assert_eq!(line.position_at(Vec2::ZERO, 0), Vec2::new(0.0, 0.0));
        assert_eq!(line.position_at(Vec2::ZERO, 3), Vec2::new(6.0, 0.0));
        assert_eq!(line.position_at(Vec2::ZERO, 7), Vec2::new(10.0, 4.0));
        assert_eq!(line.position_at(Vec2::ZERO, 100), Vec2::new(10.0, 10.0));
        let circle = GoalMotion::Circle { center: [100.0, 100.0], radius: 10.0, period_steps: 40.0 };
        assert!(circle.position_at(Vec2::new(110.0, 100.0), 0).distance(Vec2::new(110.0, 100.0)) < 1e-4);
        assert!(circle.position_at(Vec2::new(110.0, 100.0), 10).distance(Vec2::new(100.0, 110.0)) < 1e-4);
        assert!(circle.position_at(Vec2::ZERO, 40).distance(circle.position_at(Vec2::ZERO, 0)) < 1e-4);
        let mut s = scene();
        s.goals[0].motion = Some(GoalMotion::Polyline { points: vec![], speed: 1.0 });
        assert!(matches!(s.validate(), Err(SceneError::Field(f)) if f.path == "goals[0].motion.points"));
        s.goals[0].motion = Some(circle);
        assert_eq!(s.validate(), Ok(()));
        let json = serde_json::to_string(&s.goals[0]).expect("serialises");
        assert!(json.contains(r#""kind":"circle""#), "{json}");
        assert_eq!(serde_json::from_str::<Goal>(&json).expect("parses"), s.goals[0]);
        assert!(!serde_json::to_string(&Goal::fixed([1.0, 2.0], 3.0)).expect("ok").contains("motion"));
    }

    #[test]
    fn colours_parse() {
        assert_eq!(parse_color("#ff8000"), [255, 128, 0]);
        assert_eq!(parse_color("red"), [128, 128, 128]);
    }
}
