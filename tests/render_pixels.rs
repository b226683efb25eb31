//! Pixel checks of the rendered frame: the picture shows what the simulation holds.
//!
//! - The goal ring is drawn round the goal's position at the step shown. Regression: a moving
//!   goal was drawn where it started (`draw_goals` drew `goal.position`), so in
//!   `pso-circle-target` and the three forces presets the crowd chased an empty ring-less spot
//!   while the ring stayed behind (250 px away at step 600 of `pso-circle-target`).
//! - Every agent is drawn at its position, in its group's colour.
//! - Trails never cross an obstacle's interior, however many steps run between frames.

use flockpath::model::scene::parse_color;
use flockpath::render::{Renderer, Theme, PROJECTOR, STANDARD};
use flockpath::{presets, Scene, World};
use glam::Vec2;

/// A preset's scene builder.
type Preset = fn() -> Scene;

/// Device px per scene px of the test canvases: a page canvas on a 2× screen.
const SCALE: f32 = 1.5;

fn renderer_for(scene: &Scene, theme: Theme) -> Renderer {
    let mut r = Renderer::new((scene.width * SCALE) as u32, (scene.height * SCALE) as u32);
    r.set_theme(theme);
    r
}

fn pixel(r: &Renderer, x: i32, y: i32) -> Option<[u8; 3]> {
    if x < 0 || y < 0 || x >= r.width() as i32 || y >= r.height() as i32 {
        return None;
    }
    let at = (y as usize * r.width() as usize + x as usize) * 4;
    let p = r.pixels();
    Some([p[at], p[at + 1], p[at + 2]])
}

fn distance(a: [u8; 3], b: [u8; 3]) -> f32 {
    a.iter().zip(b).map(|(&x, y)| (f32::from(x) - f32::from(y)).powi(2)).sum::<f32>().sqrt()
}

/// Share of 96 points evenly spaced on the circle of `radius` scene px round `centre` where the
/// frame shows `ink`: some pixel of the point's 3×3 neighbourhood (the ring's anti-aliased
/// stroke) is nearer to `ink` than a third of the way from `ink` to the field's colour.
fn ring_share(r: &Renderer, centre: Vec2, radius: f32, ink: [u8; 3], field: [u8; 3]) -> f32 {
    const SAMPLES: usize = 96;
    let near = distance(ink, field) / 3.0;
    let inked = (0..SAMPLES)
        .filter(|&k| {
            let angle = k as f32 / SAMPLES as f32 * std::f32::consts::TAU;
            let c = r.view().to_canvas(centre + Vec2::new(angle.cos(), angle.sin()) * radius);
            let (x, y) = (c.x.round() as i32, c.y.round() as i32);
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| pixel(r, x + dx, y + dy).is_some_and(|p| distance(p, ink) < near))
            })
        })
        .count();
    inked as f32 / SAMPLES as f32
}

/// `(share inked round where the goal is now, share inked round where it started, how far it
/// moved in scene px)` for goal 0 of `scene` after `steps` steps, trails off.
fn goal_ring_shares(scene: Scene, steps: u32, theme: Theme) -> (f32, f32, f32) {
    let field = match theme {
        Theme::Standard => STANDARD.background,
        Theme::Projector => PROJECTOR.background,
    };
    let goal = scene.goals[0].clone();
    let ink = scene.groups.iter().find(|g| g.goal == Some(0)).map(|g| parse_color(&g.color)).expect("a user");
    let mut r = renderer_for(&scene, theme);
    r.set_trails(false);
    let mut world = World::new(scene).expect("valid preset");
    world.step_n(steps);
    r.render(&world);
    let now = goal.position_at(steps);
    let start = Vec2::from(goal.position);
    (
        ring_share(&r, now, goal.radius, ink, field),
        ring_share(&r, start, goal.radius, ink, field),
        now.distance(start),
    )
}

#[test]
fn the_goal_ring_is_drawn_round_where_the_goal_is_at_the_step_shown() {
    let cases = [
        (presets::pso_circle_target as Preset, 600, Theme::Standard),
        (presets::pso_circle_target, 1800, Theme::Projector),
        (presets::forces_e1_open, 300, Theme::Standard),
        (presets::forces_e2_narrow, 400, Theme::Standard),
        (presets::forces_e3_cluttered, 250, Theme::Projector),
        (presets::pillars, 300, Theme::Standard),
    ];
    for (build, steps, theme) in cases {
        let scene = build();
        let name = scene.name.clone();
        let (now, start, moved) = goal_ring_shares(scene, steps, theme);
        println!("{name} step {steps} {theme:?}: goal moved {moved:.1} px; ring inked {now:.2} round it now, {start:.2} round its start");
        assert!(
            now >= 0.9,
            "{name} at step {steps}: only {now:.2} of the ring round the goal's position is drawn"
        );
        if moved > 3.0 * 30.0 {
            assert!(start <= 0.1, "{name} at step {steps}: {start:.2} of a ring is drawn where the goal started, {moved:.0} px away");
        }
    }
}

#[test]
fn every_agent_is_drawn_at_its_position_in_its_groups_colour() {
    for (build, steps) in [
        (presets::pillars as Preset, 240),
        (presets::two_groups_swap, 200),
        (presets::pso_circle_target, 600),
        (presets::u_trap, 400),
    ] {
        let scene = build();
        let name = scene.name.clone();
        let colours: Vec<[u8; 3]> = scene.groups.iter().map(|g| parse_color(&g.color)).collect();
        let mut r = renderer_for(&scene, Theme::Standard);
        let mut world = World::new(scene).expect("valid preset");
        world.step_n(steps);
        r.render(&world);
        // A sprite reaches 1.5 body radii from its centre (the triangle's tip): an agent with no
        // other agent that close has nothing drawn over its centre pixel.
        let reach_of = |g: u32| 1.5 * world.scene().groups[g as usize].agent_radius;
        let positions = world.positions();
        let (mut isolated, mut misses) = (0, Vec::new());
        for (i, (&p, &g)) in positions.iter().zip(world.group_of()).enumerate() {
            let c = r.view().to_canvas(p);
            let (x, y) = (c.x.round() as i32, c.y.round() as i32);
            let own = colours[g as usize];
            let alone = positions
                .iter()
                .zip(world.group_of())
                .enumerate()
                .all(|(j, (&q, &h))| j == i || q.distance(p) > reach_of(h) + 1.0 / SCALE);
            let shown = if alone {
                isolated += 1;
                pixel(&r, x, y) == Some(own)
            } else {
                // A neighbour is drawn over part of it: its own colour still shows within its
                // body radius.
                let reach = (world.scene().groups[g as usize].agent_radius * SCALE).ceil() as i32;
                (-reach..=reach).any(|dy| (-reach..=reach).any(|dx| pixel(&r, x + dx, y + dy) == Some(own)))
            };
            if !shown {
                misses.push((i, p, alone));
            }
        }
        let n = world.agent_count();
        println!("{name} step {steps}: {n} agents drawn where they are; {isolated} on their own, each with its group's colour at its centre pixel");
        assert!(
            misses.is_empty(),
            "{name}: agents not drawn where they are (id, position, alone): {misses:?}"
        );
        assert!(
            isolated * 4 >= n,
            "{name}: only {isolated} of {n} agents stand apart, so the centre check proves little"
        );
    }
}

/// Pixels strictly inside an obstacle (at least 2 device px from its outline, whose stroke is
/// anti-aliased) where the frame with trails differs from the frame without, at the same step:
/// trail ink inside the obstacle. Agents are drawn the same in both frames, so they cancel.
fn trail_pixels_inside_obstacles(with: &Renderer, without: &Renderer, scene: &Scene) -> (usize, usize) {
    let (mut inside, mut checked) = (0, 0);
    let view = with.view();
    for y in 0..with.height() as i32 {
        for x in 0..with.width() as i32 {
            let p = view.to_scene(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            let deep = scene.obstacles.iter().any(|o| o.surface(p).signed_distance < -2.0 / view.scale);
            if !deep {
                continue;
            }
            checked += 1;
            inside += usize::from(pixel(with, x, y) != pixel(without, x, y));
        }
    }
    (inside, checked)
}

#[test]
fn trails_never_cross_an_obstacles_interior() {
    for (build, steps, steps_per_frame) in [
        (presets::pillars as Preset, 600, 1),
        (presets::pillars, 600, 50),
        (presets::corridor, 600, 20),
        (presets::forces_e3_cluttered, 500, 10),
        (presets::u_trap, 600, 100),
    ] {
        let scene = build();
        let name = scene.name.clone();
        let mut with = renderer_for(&scene, Theme::Standard);
        with.set_trail_fade(0.0);
        let mut without = renderer_for(&scene, Theme::Standard);
        without.set_trails(false);
        let mut world = World::new(scene.clone()).expect("valid preset");
        with.render(&world);
        for _ in 0..steps / steps_per_frame {
            for _ in 0..steps_per_frame {
                world.step();
                with.trace_step(&world);
            }
            with.render(&world);
        }
        without.render(&world);
        let penetrations = world.metrics().overall.penetrations_agent_obstacle;
        let (inside, checked) = trail_pixels_inside_obstacles(&with, &without, &scene);
        let ink = with
            .pixels()
            .chunks_exact(4)
            .zip(without.pixels().chunks_exact(4))
            .filter(|(a, b)| a != b)
            .count();
        println!("{name}, {steps} steps at {steps_per_frame} per frame: {inside} trail pixels inside obstacles of {checked} checked; {ink} trail pixels in all; {penetrations} agent-steps with a centre inside an obstacle");
        assert!(ink > 1000, "{name}: {ink} trail pixels: the trails were not drawn, so this proves nothing");
        assert_eq!(penetrations, 0, "{name}: agents entered obstacles, so their trails honestly do too");
        assert_eq!(inside, 0, "{name}: {inside} trail pixels inside obstacles");
    }
}
