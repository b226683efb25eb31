//! Scene edits from the editor: add, move, delete and replace items, and picking items under
//! the pointer. Every edit yields a new validated scene or an error; the old scene is untouched.

use crate::model::geometry::Obstacle;
use crate::model::params::PlannerConfig;
use crate::model::refusal::{Code, Message};
use crate::model::scene::{Goal, GoalMotion, Group, PathSpec, Scene, SceneError, DEFAULT_PATH_RADIUS};

/// A path is picked within this many px of its polyline (or the pick tolerance, if larger).
const PATH_PICK_PX: f32 = 6.0;
use glam::Vec2;
use serde::{Deserialize, Serialize};

/// A reference to one item of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "index", rename_all = "snake_case")]
pub enum ItemRef {
    /// `scene.obstacles[i]`.
    Obstacle(u32),
    /// `scene.goals[i]`.
    Goal(u32),
    /// `scene.groups[i]` (picked by its spawn region).
    Group(u32),
    /// `scene.paths[i]` (picked near its polyline).
    Path(u32),
}

/// One editing operation, as sent by the page.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "op", rename_all = "snake_case")]
pub enum Edit {
    /// Adds an obstacle on top.
    AddObstacle {
        /// The new obstacle.
        obstacle: Obstacle,
    },
    /// Adds a goal; with `group`, that group now heads for it.
    AddGoal {
        /// Centre in px.
        position: [f32; 2],
        /// Arrival radius in px (default 20).
        #[serde(default)]
        radius: Option<f32>,
        /// Group whose goal this becomes.
        #[serde(default)]
        group: Option<u32>,
    },
    /// Adds a group.
    AddGroup {
        /// The new group.
        group: Group,
    },
    /// Translates an item by `(dx, dy)` px.
    Move {
        /// What to move.
        item: ItemRef,
        /// Shift along x (px).
        dx: f32,
        /// Shift along y (px).
        dy: f32,
    },
    /// Removes an item; groups heading for a removed goal wander.
    Delete {
        /// What to remove.
        item: ItemRef,
    },
    /// Adds a path; with `group` (a Boids group), that group now follows it.
    AddPath {
        /// Vertices in px, in travel order (at least two).
        points: Vec<[f32; 2]>,
        /// Corridor half-width in px (default 30).
        #[serde(default)]
        radius: Option<f32>,
        /// Group that follows it.
        #[serde(default)]
        group: Option<u32>,
    },
    /// Replaces a group's settings (count, colour, goal, radius, planner, …).
    SetGroup {
        /// Which group.
        index: u32,
        /// Its new settings.
        group: Group,
    },
}

fn missing(item: ItemRef) -> SceneError {
    let (what, i) = match item {
        ItemRef::Obstacle(i) => ("obstacle", i),
        ItemRef::Goal(i) => ("goal", i),
        ItemRef::Group(i) => ("group", i),
        ItemRef::Path(i) => ("path", i),
    };
    SceneError::no_such_item(what, u64::from(i) + 1)
}

fn translate(o: &mut Obstacle, d: Vec2) {
    let shift = |p: &mut [f32; 2]| {
        p[0] += d.x;
        p[1] += d.y;
    };
    match o {
        Obstacle::Circle { center, .. } => shift(center),
        Obstacle::Rect { min, max } => {
            shift(min);
            shift(max);
        }
        Obstacle::Polygon { points } => points.iter_mut().for_each(shift),
    }
}

/// Applies `edit` to a copy of `scene` and validates the result.
pub fn apply(scene: &Scene, edit: &Edit) -> Result<Scene, SceneError> {
    let mut s = scene.clone();
    match edit {
        Edit::AddObstacle { obstacle } => s.obstacles.push(obstacle.clone()),
        Edit::AddGoal { position, radius, group } => {
            s.goals.push(Goal::fixed(*position, radius.unwrap_or(20.0)));
            if let Some(g) = group {
                let index = (s.goals.len() - 1) as u32;
                s.groups.get_mut(*g as usize).ok_or_else(|| missing(ItemRef::Group(*g)))?.goal = Some(index);
            }
        }
        Edit::AddGroup { group } => s.groups.push(group.clone()),
        Edit::AddPath { points, radius, group } => {
            s.paths.push(PathSpec { points: points.clone(), radius: radius.unwrap_or(DEFAULT_PATH_RADIUS) });
            if let Some(g) = group {
                let number = s.paths.len() as u32;
                let target = s.groups.get_mut(*g as usize).ok_or_else(|| missing(ItemRef::Group(*g)))?;
                match &mut target.planner {
                    PlannerConfig::Boids(p) => p.path = number,
                    other => {
                        return Err(SceneError::OutOfRange(
                            Message::new(Code::ScenePathNeedsBoids)
                                .with("group", g + 1)
                                .with("planner", other.kind().label_term()),
                        ))
                    }
                }
            }
        }
        Edit::Move { item, dx, dy } => {
            if !dx.is_finite() || !dy.is_finite() {
                return Err(SceneError::NotFinite(Message::new(Code::SceneMoveNotFinite)));
            }
            let d = Vec2::new(*dx, *dy);
            match *item {
                ItemRef::Obstacle(i) => {
                    translate(s.obstacles.get_mut(i as usize).ok_or_else(|| missing(*item))?, d)
                }
                ItemRef::Goal(i) => {
                    let g = s.goals.get_mut(i as usize).ok_or_else(|| missing(*item))?;
                    g.position = [g.position[0] + d.x, g.position[1] + d.y];
                    // A moving goal is dragged where it is seen (at the step shown): its whole
                    // route moves with it, so it stays under the pointer at every step.
                    match &mut g.motion {
                        Some(GoalMotion::Circle { center, .. }) => {
                            *center = [center[0] + d.x, center[1] + d.y]
                        }
                        Some(GoalMotion::Polyline { points, .. }) => {
                            for p in points {
                                *p = [p[0] + d.x, p[1] + d.y];
                            }
                        }
                        None => {}
                    }
                }
                ItemRef::Group(i) => {
                    let g = s.groups.get_mut(i as usize).ok_or_else(|| missing(*item))?;
                    g.spawn.min = [g.spawn.min[0] + d.x, g.spawn.min[1] + d.y];
                    g.spawn.max = [g.spawn.max[0] + d.x, g.spawn.max[1] + d.y];
                }
                ItemRef::Path(i) => {
                    let path = s.paths.get_mut(i as usize).ok_or_else(|| missing(*item))?;
                    for p in &mut path.points {
                        *p = [p[0] + d.x, p[1] + d.y];
                    }
                }
            }
        }
        Edit::Delete { item } => match *item {
            ItemRef::Obstacle(i) => {
                if i as usize >= s.obstacles.len() {
                    return Err(missing(*item));
                }
                s.obstacles.remove(i as usize);
            }
            ItemRef::Goal(i) => {
                if i as usize >= s.goals.len() {
                    return Err(missing(*item));
                }
                s.goals.remove(i as usize);
                for g in &mut s.groups {
                    g.goal = match g.goal {
                        Some(k) if k == i => None,
                        Some(k) if k > i => Some(k - 1),
                        other => other,
                    };
                }
            }
            ItemRef::Group(i) => {
                if i as usize >= s.groups.len() {
                    return Err(missing(*item));
                }
                s.groups.remove(i as usize);
            }
            ItemRef::Path(i) => {
                if i as usize >= s.paths.len() {
                    return Err(missing(*item));
                }
                s.paths.remove(i as usize);
                // Groups name paths by 1-based number: the followers of the removed one stop
                // following, later numbers shift down.
                let number = i + 1;
                for g in &mut s.groups {
                    if let PlannerConfig::Boids(p) = &mut g.planner {
                        p.path = match p.path {
                            k if k == number => 0,
                            k if k > number => k - 1,
                            k => k,
                        };
                    }
                }
            }
        },
        Edit::SetGroup { index, group } => {
            *s.groups.get_mut(*index as usize).ok_or_else(|| missing(ItemRef::Group(*index)))? =
                group.clone();
        }
    }
    s.validate()?;
    Ok(s)
}

/// The topmost item at `p` (scene px), within `tolerance` px: goals first (where they are at
/// `step`, as the renderer draws them, so a moving goal is picked where it is seen), then
/// obstacles (last drawn on top), then paths (near their polyline), then group spawn regions.
pub fn pick(scene: &Scene, step: u32, p: Vec2, tolerance: f32) -> Option<ItemRef> {
    let tolerance = if tolerance.is_finite() { tolerance.max(0.0) } else { 0.0 };
    if !p.is_finite() {
        return None;
    }
    let goal = scene
        .goals
        .iter()
        .enumerate()
        .rev()
        .find(|(_, g)| p.distance(g.position_at(step)) <= g.radius.max(6.0) + tolerance);
    if let Some((i, _)) = goal {
        return Some(ItemRef::Goal(i as u32));
    }
    let obstacle =
        scene.obstacles.iter().enumerate().rev().find(|(_, o)| o.surface(p).signed_distance <= tolerance);
    if let Some((i, _)) = obstacle {
        return Some(ItemRef::Obstacle(i as u32));
    }
    let path = scene.paths.iter().enumerate().rev().find(|(_, path)| {
        path.closest_point(p).is_some_and(|q| q.point.distance(p) <= tolerance.max(PATH_PICK_PX))
    });
    if let Some((i, _)) = path {
        return Some(ItemRef::Path(i as u32));
    }
    scene
        .groups
        .iter()
        .enumerate()
        .rev()
        .find(|(_, g)| {
            p.x >= g.spawn.min[0] - tolerance
                && p.x <= g.spawn.max[0] + tolerance
                && p.y >= g.spawn.min[1] - tolerance
                && p.y <= g.spawn.max[1] + tolerance
        })
        .map(|(i, _)| ItemRef::Group(i as u32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::v;
    use crate::model::presets;

    #[test]
    fn add_move_delete_round() {
        let s = presets::open_field();
        let circle = Obstacle::Circle { center: [400.0, 100.0], radius: 30.0 };
        let s1 = apply(&s, &Edit::AddObstacle { obstacle: circle }).expect("adds");
        assert_eq!(pick(&s1, 0, Vec2::new(410.0, 100.0), 0.0), Some(ItemRef::Obstacle(0)));
        let s2 = apply(&s1, &Edit::Move { item: ItemRef::Obstacle(0), dx: 10.0, dy: 5.0 }).expect("moves");
        assert_eq!(s2.obstacles[0], Obstacle::Circle { center: [410.0, 105.0], radius: 30.0 });
        let s3 = apply(&s2, &Edit::Delete { item: ItemRef::Obstacle(0) }).expect("deletes");
        assert_eq!(s3, s);
    }

    #[test]
    fn a_moving_goal_is_picked_and_dragged_where_it_is_at_the_step_shown() {
        let s = presets::pso_circle_target();
        let start = v(s.goals[0].position);
        let now = s.goals[0].position_at(600);
        assert!(start.distance(now) > 100.0, "the goal should have moved ({start} → {now})");
        assert_eq!(pick(&s, 600, now, 0.0), Some(ItemRef::Goal(0)));
        assert_ne!(pick(&s, 600, start, 0.0), Some(ItemRef::Goal(0)), "picked where it started");
        let moved = apply(&s, &Edit::Move { item: ItemRef::Goal(0), dx: 10.0, dy: -5.0 }).expect("moves");
        for step in [0, 150, 600, 1234] {
            let d = moved.goals[0].position_at(step) - s.goals[0].position_at(step);
            assert!(d.distance(Vec2::new(10.0, -5.0)) < 1e-3, "step {step}: moved by {d}");
        }
    }

    #[test]
    fn a_new_goal_can_retarget_a_group_and_deleting_it_unlinks() {
        let s = presets::open_field();
        let s1 = apply(&s, &Edit::AddGoal { position: [400.0, 400.0], radius: None, group: Some(0) })
            .expect("adds");
        assert_eq!(s1.groups[0].goal, Some(1));
        let s2 = apply(&s1, &Edit::Delete { item: ItemRef::Goal(0) }).expect("deletes");
        assert_eq!(s2.groups[0].goal, Some(0));
        assert_eq!(s2.goals[0].position, [400.0, 400.0]);
    }

    #[test]
    fn a_drawn_path_is_followed_moved_and_deleted_with_its_followers_renumbered() {
        let mut s = presets::two_groups_swap();
        let first =
            Edit::AddPath { points: vec![[100.0, 100.0], [300.0, 120.0]], radius: None, group: Some(0) };
        s = apply(&s, &first).expect("adds");
        let second = Edit::AddPath {
            points: vec![[100.0, 400.0], [300.0, 420.0]],
            radius: Some(20.0),
            group: Some(1),
        };
        s = apply(&s, &second).expect("adds");
        let path_of = |s: &Scene, g: usize| match &s.groups[g].planner {
            PlannerConfig::Boids(p) => p.path,
            _ => u32::MAX,
        };
        assert_eq!((path_of(&s, 0), path_of(&s, 1)), (1, 2));
        assert_eq!(s.paths[0].radius, DEFAULT_PATH_RADIUS);
        assert_eq!(pick(&s, 0, Vec2::new(200.0, 112.0), 0.0), Some(ItemRef::Path(0)));
        let moved = apply(&s, &Edit::Move { item: ItemRef::Path(1), dx: 5.0, dy: -5.0 }).expect("moves");
        assert_eq!(moved.paths[1].points[0], [105.0, 395.0]);
        let deleted = apply(&s, &Edit::Delete { item: ItemRef::Path(0) }).expect("deletes");
        assert_eq!((path_of(&deleted, 0), path_of(&deleted, 1)), (0, 1));
        assert_eq!(deleted.paths.len(), 1);
        let one_point = Edit::AddPath { points: vec![[1.0, 1.0]], radius: None, group: None };
        assert!(matches!(apply(&s, &one_point), Err(SceneError::Field(f)) if f.path == "paths[2].points"));
        let mut pso = s.clone();
        pso.groups[0].planner = crate::model::params::PlannerKind::Pso.default_config();
        let e = apply(&pso, &first).expect_err("PSO does not follow paths");
        assert!(e.to_string().contains("Boids"), "{e}");
        let json = r#"{"op":"add_path","points":[[10,10],[50,50]],"group":0}"#;
        assert!(apply(&presets::open_field(), &serde_json::from_str(json).expect("parses")).is_ok());
    }

    #[test]
    fn invalid_edits_are_refused_with_messages() {
        let s = presets::open_field();
        let over_goal = Obstacle::Circle { center: [700.0, 250.0], radius: 10.0 };
        assert!(matches!(apply(&s, &Edit::AddObstacle { obstacle: over_goal }), Err(SceneError::Blocked(_))));
        assert!(apply(&s, &Edit::Delete { item: ItemRef::Group(5) }).is_err());
        assert!(apply(&s, &Edit::Move { item: ItemRef::Goal(0), dx: f32::NAN, dy: 0.0 }).is_err());
        let json = r#"{"op":"move","item":{"kind":"group","index":0},"dx":5,"dy":0}"#;
        let e: Edit = serde_json::from_str(json).expect("parses");
        assert!(apply(&s, &e).is_ok());
    }
}
