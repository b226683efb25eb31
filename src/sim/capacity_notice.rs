//! The scene check's notice that a goal is too small for the crowd heading for it (issue 23,
//! DESIGN §4 "Goals and arrival"): said up front, when a scene is loaded or edited, so a
//! reader who sees agents waiting outside a full goal knows why before the run shows it. A
//! notice, not a refusal: a goal that fills and leaves a queue outside is a scene worth
//! running (a waiting area, a bottleneck).
//!
//! Read from the scene alone, as the world lays out its places ([`crate::sim::world`]): a goal
//! that gathers and comes to rest, the groups heading for it whose planner gathers, bodies of
//! the largest radius among them. Its capacity is [`capacity`], the lattice of places without
//! obstacles or the world's border, hence "about".

use crate::model::scene::{OnArrival, Scene};
use crate::sim::gather::capacity;
use serde::Serialize;

/// A goal that holds fewer bodies than the groups heading for it bring.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CapacityNotice {
    /// Index of the goal in the scene (from 0, as the scene's JSON and the page's labels count).
    pub goal: u32,
    /// About how many bodies the goal holds ([`capacity`]).
    pub capacity: u64,
    /// Radius of the bodies it was counted for (px): the largest among the groups heading there.
    pub body_radius: f32,
    /// The groups heading there whose planner gathers, in scene order.
    pub groups: Vec<HeadingGroup>,
    /// Agents of those groups together.
    pub agents: u64,
    /// How many of them will wait outside once the goal is full (`agents − capacity`).
    pub waiting: u64,
}

/// One group heading for a goal that is too small.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HeadingGroup {
    /// Index of the group in the scene (from 0): the page names an unnamed group by it.
    pub group: u32,
    /// The group's name as the scene gives it (may be empty).
    pub name: String,
    /// Its number of agents.
    pub count: u32,
}

/// Every goal of `scene` that gathers and will be full before all its agents arrive, in goal
/// order; empty when every crowd fits. Goals that are exits, or that never stop moving (a
/// circle), hold nobody and are left out. Work: one pass over the goals and groups, and
/// [`capacity`] per goal (bounded for huge goals).
pub fn capacity_notices(scene: &Scene) -> Vec<CapacityNotice> {
    let mut notices = Vec::new();
    for (k, goal) in scene.goals.iter().enumerate() {
        if goal.on_arrival != OnArrival::Gather || goal.rest_step().is_none() {
            continue;
        }
        let heading: Vec<(usize, &crate::model::scene::Group)> = scene
            .groups
            .iter()
            .enumerate()
            .filter(|(_, g)| g.goal == Some(k as u32) && g.count > 0 && g.planner.gathers_at_goal())
            .collect();
        if heading.is_empty() {
            continue;
        }
        let body_radius = heading.iter().map(|(_, g)| g.agent_radius).fold(0.0, f32::max);
        let agents: u64 = heading.iter().map(|(_, g)| u64::from(g.count)).sum();
        let holds = capacity(goal.radius, body_radius);
        if agents <= holds {
            continue;
        }
        notices.push(CapacityNotice {
            goal: k as u32,
            capacity: holds,
            body_radius,
            groups: heading
                .iter()
                .map(|&(g, group)| HeadingGroup {
                    group: g as u32,
                    name: group.name.clone(),
                    count: group.count,
                })
                .collect(),
            agents,
            waiting: agents - holds,
        });
    }
    notices
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::PlannerKind;
    use crate::model::presets;
    use crate::model::scene::Goal;

    #[test]
    fn a_goal_too_small_names_its_goal_capacity_groups_and_the_waiting() {
        let mut scene = presets::open_field();
        scene.goals[0].radius = 20.0;
        let notices = capacity_notices(&scene);
        assert_eq!(notices.len(), 1, "{notices:?}");
        let n = &notices[0];
        let holds = capacity(20.0, 4.0);
        assert!(holds > 1 && holds < 60, "a 20 px goal holds {holds} bodies of radius 4 px");
        assert_eq!((n.goal, n.capacity, n.body_radius, n.agents), (0, holds, 4.0, 60));
        assert_eq!(n.waiting, 60 - holds);
        assert_eq!(n.groups, vec![HeadingGroup { group: 0, name: "flock".into(), count: 60 }]);
    }

    #[test]
    fn a_goal_that_holds_its_crowd_gives_no_notice() {
        let mut scene = presets::open_field();
        assert_eq!(capacity_notices(&scene), vec![], "the preset's goal holds its flock");
        // Exactly full is not too small.
        let holds = capacity(20.0, 4.0);
        scene.goals[0].radius = 20.0;
        scene.groups[0].count = holds as u32;
        assert_eq!(capacity_notices(&scene), vec![]);
        scene.groups[0].count += 1;
        assert_eq!(capacity_notices(&scene).first().map(|n| n.waiting), Some(1));
    }

    #[test]
    fn groups_sharing_a_goal_count_together_with_the_largest_body() {
        let mut scene = presets::two_groups_swap();
        // Send both groups to one small goal; the second has larger bodies.
        scene.goals.truncate(1);
        scene.goals[0].radius = 30.0;
        for g in &mut scene.groups {
            g.goal = Some(0);
        }
        scene.groups[1].agent_radius = 6.0;
        let notices = capacity_notices(&scene);
        assert_eq!(notices.len(), 1, "{notices:?}");
        let n = &notices[0];
        assert_eq!(n.body_radius, 6.0);
        assert_eq!(n.capacity, capacity(30.0, 6.0));
        let total: u64 = scene.groups.iter().map(|g| u64::from(g.count)).sum();
        assert_eq!(n.agents, total);
        assert_eq!(n.waiting, total - n.capacity);
        assert_eq!(n.groups.iter().map(|g| g.group).collect::<Vec<_>>(), vec![0, 1]);
    }

    #[test]
    fn exits_circling_goals_and_non_gathering_planners_give_no_notice() {
        let mut small = presets::open_field();
        small.goals[0].radius = 20.0;
        assert_eq!(capacity_notices(&small).len(), 1);

        let mut exit = small.clone();
        exit.goals[0] = exit.goals[0].clone().exit();
        assert_eq!(capacity_notices(&exit), vec![], "an exit holds nobody");

        let mut circling = small.clone();
        circling.goals[0].motion = Some(crate::model::scene::GoalMotion::Circle {
            center: [400.0, 250.0],
            radius: 100.0,
            period_steps: 600.0,
        });
        assert_eq!(capacity_notices(&circling), vec![], "a goal that never stops is never filled");

        let mut pso = small.clone();
        pso.groups[0].planner = PlannerKind::Pso.default_config();
        assert_eq!(capacity_notices(&pso), vec![], "PSO keeps its own gathering");

        let mut wander = small;
        wander.groups[0].goal = None;
        assert_eq!(capacity_notices(&wander), vec![]);
    }

    #[test]
    fn every_preset_goal_holds_the_groups_heading_there() {
        for preset in presets::ALL {
            assert_eq!(capacity_notices(&(preset.build)()), vec![], "preset {}", preset.name);
        }
    }

    #[test]
    fn a_huge_crowd_is_checked_without_laying_out_places() {
        let mut scene = presets::open_field();
        scene.width = 20_000.0;
        scene.height = 20_000.0;
        scene.goals[0] = Goal::fixed([10_000.0, 10_000.0], 9_000.0);
        scene.groups[0].count = 200_000;
        scene.groups[0].agent_radius = 0.5;
        // Checked from the lattice's area (no places laid out): the answer, not its time, is
        // what a test can hold; the time belongs in a benchmark.
        let notices = capacity_notices(&scene);
        assert_eq!(notices, vec![], "a 9,000 px goal holds 200,000 bodies of radius 0.5 px");
    }
}
