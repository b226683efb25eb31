//! The scene a user draws: bounds, obstacles, goals, groups of agents, seed; and its validation.

use crate::geometry::{v, Obstacle};
use crate::planners::PlannerConfig;
use glam::Vec2;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Most agents a scene may hold in total (keeps a typo from freezing the page).
pub const MAX_AGENTS: u32 = 200_000;
/// Largest scene side in px.
pub const MAX_SIDE: f32 = 20_000.0;
/// Most obstacles a scene may hold.
pub const MAX_OBSTACLES: usize = 5_000;
/// Most vertices a polygon obstacle may have.
pub const MAX_POLYGON_POINTS: usize = 1_000;

/// A whole scene. Units: px for lengths, steps for time (one step is [`crate::DT`] seconds).
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
    /// Share of a trail's visibility lost per frame: 0 = permanent, 1 = one frame. Default 0.01.
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

    fn validate(&self, name: &dyn Fn() -> String) -> Result<(), SceneError> {
        match self {
            GoalMotion::Circle { center, radius, period_steps } => {
                finite(name, &[center[0], center[1], *radius, *period_steps])?;
                if *radius < 0.0 || *radius > MAX_SIDE || *period_steps < 1.0 {
                    return Err(SceneError::OutOfRange(format!(
                        "{} circle needs radius 0…{MAX_SIDE} px and a period of at least 1 step",
                        name()
                    )));
                }
            }
            GoalMotion::Polyline { points, speed } => {
                let flat: Vec<f32> = points.iter().flat_map(|p| [p[0], p[1]]).chain([*speed]).collect();
                finite(name, &flat)?;
                if points.is_empty() || points.len() > MAX_PATH_POINTS || *speed < 0.0 || *speed > MAX_SIDE {
                    return Err(SceneError::OutOfRange(format!(
                        "{} path needs 1…{MAX_PATH_POINTS} points and a speed ≥ 0 px/step",
                        name()
                    )));
                }
            }
        }
        Ok(())
    }
}

impl Goal {
    /// A goal that stays at `position`.
    pub fn fixed(position: [f32; 2], radius: f32) -> Self {
        Self { position, radius, motion: None }
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
    "#2f6fdf".to_string()
}

fn default_agent_radius() -> f32 {
    4.0
}

/// Why a scene was refused. Each message names the offending item.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneError {
    /// The text is not a scene (bad JSON, bad encoding, unknown version).
    Parse(String),
    /// A number is NaN or infinite.
    NotFinite(String),
    /// A value is outside its allowed range.
    OutOfRange(String),
    /// Something refers to an item that does not exist.
    BadReference(String),
    /// The geometry makes the scene unusable (goal inside an obstacle, no room to spawn).
    Blocked(String),
    /// One step of the scene would cost more than the stated limit ([`crate::cost`]).
    TooCostly(String),
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Parse(m) => write!(f, "cannot read the scene: {m}"),
            SceneError::NotFinite(m) => write!(f, "{m} is not a finite number"),
            SceneError::OutOfRange(m)
            | SceneError::BadReference(m)
            | SceneError::Blocked(m)
            | SceneError::TooCostly(m) => {
                write!(f, "{m}")
            }
        }
    }
}

impl std::error::Error for SceneError {}

fn finite(what: impl Fn() -> String, values: &[f32]) -> Result<(), SceneError> {
    if values.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(SceneError::NotFinite(what()))
    }
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
        }
    }

    /// Total number of agents over all groups.
    pub fn agent_count(&self) -> u64 {
        self.groups.iter().map(|g| u64::from(g.count)).sum()
    }

    /// Checks every value; the first problem found is returned with a message naming it.
    pub fn validate(&self) -> Result<(), SceneError> {
        finite(|| "scene width/height".into(), &[self.width, self.height])?;
        if !(10.0..=MAX_SIDE).contains(&self.width) || !(10.0..=MAX_SIDE).contains(&self.height) {
            return Err(SceneError::OutOfRange(format!(
                "scene size {}×{} px is outside 10…{MAX_SIDE} px",
                self.width, self.height
            )));
        }
        if self.obstacles.len() > MAX_OBSTACLES {
            return Err(SceneError::OutOfRange(format!(
                "{} obstacles is more than the {MAX_OBSTACLES} allowed",
                self.obstacles.len()
            )));
        }
        for (i, o) in self.obstacles.iter().enumerate() {
            validate_obstacle(i, o)?;
        }
        for (i, g) in self.goals.iter().enumerate() {
            finite(|| format!("goal {}", i + 1), &[g.position[0], g.position[1], g.radius])?;
            if g.radius <= 0.0 || g.radius > MAX_SIDE {
                return Err(SceneError::OutOfRange(format!(
                    "goal {} radius {} must be > 0",
                    i + 1,
                    g.radius
                )));
            }
            if !self.in_bounds(v(g.position)) {
                return Err(SceneError::OutOfRange(format!("goal {} lies outside the scene", i + 1)));
            }
            if let Some(k) = self.obstacles.iter().position(|o| o.contains(v(g.position))) {
                return Err(SceneError::Blocked(format!("goal {} is inside obstacle {}", i + 1, k + 1)));
            }
            if let Some(m) = &g.motion {
                m.validate(&|| format!("goal {} motion", i + 1))?;
                if let GoalMotion::Circle { center, radius, .. } = m {
                    let reach = Vec2::splat(*radius);
                    if !self.in_bounds(v(*center) - reach) || !self.in_bounds(v(*center) + reach) {
                        return Err(SceneError::OutOfRange(format!(
                            "goal {} circle (radius {radius} px) must stay inside the scene",
                            i + 1
                        )));
                    }
                }
            }
        }
        let total = self.agent_count();
        if total > u64::from(MAX_AGENTS) {
            return Err(SceneError::OutOfRange(format!(
                "{total} agents is more than the {MAX_AGENTS} allowed"
            )));
        }
        for (i, g) in self.groups.iter().enumerate() {
            self.validate_group(i, g)?;
        }
        if self.paths.len() > MAX_PATHS {
            return Err(SceneError::OutOfRange(format!(
                "{} paths is more than the {MAX_PATHS} allowed",
                self.paths.len()
            )));
        }
        for (i, path) in self.paths.iter().enumerate() {
            let flat: Vec<f32> = path.points.iter().flat_map(|p| [p[0], p[1]]).chain([path.radius]).collect();
            finite(|| format!("path {}", i + 1), &flat)?;
            if path.points.len() < 2 || path.points.len() > MAX_PATH_POINTS {
                return Err(SceneError::OutOfRange(format!(
                    "path {} needs 2…{MAX_PATH_POINTS} points, has {}",
                    i + 1,
                    path.points.len()
                )));
            }
            if path.radius <= 0.0 || path.radius > MAX_SIDE {
                return Err(SceneError::OutOfRange(format!(
                    "path {} radius {} must be > 0",
                    i + 1,
                    path.radius
                )));
            }
            if let Some(k) = path.points.iter().position(|&p| !self.in_bounds(v(p))) {
                return Err(SceneError::OutOfRange(format!(
                    "path {} point {} lies outside the scene",
                    i + 1,
                    k + 1
                )));
            }
        }
        if self.hills.len() > MAX_HILLS {
            return Err(SceneError::OutOfRange(format!(
                "{} hills is more than the {MAX_HILLS} allowed",
                self.hills.len()
            )));
        }
        for (i, h) in self.hills.iter().enumerate() {
            finite(|| format!("hill {}", i + 1), &[h.center[0], h.center[1], h.radius, h.height])?;
            if h.radius <= 0.0 || h.radius > MAX_SIDE || !(0.0..=MAX_HILL_HEIGHT).contains(&h.height) {
                return Err(SceneError::OutOfRange(format!(
                    "hill {} needs a radius in 0…{MAX_SIDE} px and a height in 0…{MAX_HILL_HEIGHT} px",
                    i + 1
                )));
            }
        }
        let fade = self.view.trail_fade;
        finite(|| "view trail fade".into(), &[fade])?;
        if !(0.0..=1.0).contains(&fade) {
            return Err(SceneError::OutOfRange(format!("view trail fade {fade} is outside 0…1")));
        }
        Ok(())
    }

    fn validate_group(&self, i: usize, g: &Group) -> Result<(), SceneError> {
        let name = || format!("group {} ({})", i + 1, g.name);
        let s = g.spawn;
        finite(|| format!("{} spawn region", name()), &[s.min[0], s.min[1], s.max[0], s.max[1]])?;
        finite(|| format!("{} agent radius", name()), &[g.agent_radius])?;
        if !(0.5..=100.0).contains(&g.agent_radius) {
            return Err(SceneError::OutOfRange(format!(
                "{} agent radius {} px is outside 0.5…100",
                name(),
                g.agent_radius
            )));
        }
        if s.min[0] > s.max[0] || s.min[1] > s.max[1] {
            return Err(SceneError::OutOfRange(format!("{} spawn region has min > max", name())));
        }
        if !self.in_bounds(v(s.min)) || !self.in_bounds(v(s.max)) {
            return Err(SceneError::OutOfRange(format!("{} spawn region leaves the scene", name())));
        }
        if let Some(goal) = g.goal {
            if goal as usize >= self.goals.len() {
                return Err(SceneError::BadReference(format!(
                    "{} heads for goal {} but the scene has {} goal(s)",
                    name(),
                    goal + 1,
                    self.goals.len()
                )));
            }
        }
        if !is_hex_color(&g.color) {
            return Err(SceneError::OutOfRange(format!("{} colour {:?} is not #rrggbb", name(), g.color)));
        }
        g.planner.validate().map_err(|m| SceneError::OutOfRange(format!("{}: {m}", name())))
    }

    /// Whether a point lies within the scene rectangle.
    pub fn in_bounds(&self, p: Vec2) -> bool {
        p.x >= 0.0 && p.y >= 0.0 && p.x <= self.width && p.y <= self.height
    }
}

fn validate_obstacle(i: usize, o: &Obstacle) -> Result<(), SceneError> {
    let name = || format!("obstacle {}", i + 1);
    match o {
        Obstacle::Circle { center, radius } => {
            finite(name, &[center[0], center[1], *radius])?;
            if *radius <= 0.0 || *radius > MAX_SIDE {
                return Err(SceneError::OutOfRange(format!("{} radius {radius} must be > 0", name())));
            }
        }
        Obstacle::Rect { min, max } => {
            finite(name, &[min[0], min[1], max[0], max[1]])?;
            if min[0] >= max[0] || min[1] >= max[1] {
                return Err(SceneError::OutOfRange(format!("{} rectangle has no area", name())));
            }
        }
        Obstacle::Polygon { points } => {
            if points.len() < 3 || points.len() > MAX_POLYGON_POINTS {
                return Err(SceneError::OutOfRange(format!(
                    "{} polygon needs 3…{MAX_POLYGON_POINTS} points, has {}",
                    name(),
                    points.len()
                )));
            }
            let flat: Vec<f32> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
            finite(name, &flat)?;
        }
    }
    Ok(())
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
        assert!(matches!(e, SceneError::NotFinite(_)));
        assert!(e.to_string().contains("goal 1"), "{e}");
    }

    #[test]
    fn an_obstacle_over_the_goal_is_refused() {
        let mut s = scene();
        s.obstacles.push(Obstacle::Circle { center: [350.0, 150.0], radius: 30.0 });
        let e = s.validate().expect_err("blocked");
        assert_eq!(e, SceneError::Blocked("goal 1 is inside obstacle 1".into()));
    }

    #[test]
    fn ten_million_agents_are_refused() {
        let mut s = scene();
        s.groups[0].count = 10_000_000;
        assert!(matches!(s.validate(), Err(SceneError::OutOfRange(m)) if m.contains("10000000 agents")));
    }

    #[test]
    fn a_missing_goal_is_a_bad_reference() {
        let mut s = scene();
        s.groups[0].goal = Some(3);
        assert!(matches!(s.validate(), Err(SceneError::BadReference(_))));
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
        assert!(matches!(s.validate(), Err(SceneError::OutOfRange(_))));
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
        assert!(matches!(s.validate(), Err(SceneError::OutOfRange(m)) if m.contains("goal 1 motion")));
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
