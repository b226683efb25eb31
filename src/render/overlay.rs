//! Diagnosis overlays drawn over the agents: stuck rings, the inspected agent's explanation
//! (neighbours, force arrows, the points its planner looks at), the PSO cost landscape it sees as
//! a heat map, and the firefly feelers and brightness display.
//!
//! Each overlay is skipped by one test when off, so a frame without overlays costs what it did.
//! The inspected agent's explanation and cost grid are recomputed per frame from the world (only
//! for that one agent), never stored during a step.

use super::paint::{draw_segment, stroke_scene_path, ViewTransform};
use super::sprite::{blit_over, ring_sprite, Sprite};
use crate::model::params::PlannerConfig;
use crate::planners::explain::Explanation;
use crate::sim::diagnose;
use crate::sim::world::World;
use glam::Vec2;
use tiny_skia::{PathBuilder, PixmapMut};

/// Which overlays are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overlays {
    /// A red ring around every stuck agent (default on).
    pub stuck: bool,
    /// The inspected agent's explanation: highlight, neighbours, arrows, points (default on).
    pub explanation: bool,
    /// The cost landscape the inspected agent sees, as a heat map (PSO only; default off).
    pub landscape: bool,
    /// Firefly feelers and per-agent brightness (default off).
    pub fireflies: bool,
}

impl Default for Overlays {
    fn default() -> Self {
        Self { stuck: true, explanation: true, landscape: false, fireflies: false }
    }
}

/// Colours of the explanation's arrows, by index (the inspector shows the same).
pub const ARROW_COLORS: [[u8; 3]; 8] = [
    [0xd6, 0x27, 0x28],
    [0x1f, 0x77, 0xb4],
    [0x2c, 0xa0, 0x2c],
    [0x94, 0x67, 0xbd],
    [0xff, 0x7f, 0x0e],
    [0x17, 0xbe, 0xcf],
    [0x8c, 0x56, 0x4b],
    [0xe3, 0x77, 0xc2],
];
/// Ring around a stuck agent (RGB).
pub const STUCK_COLOR: [u8; 3] = [0xe0, 0x10, 0x10];
/// Highlight ring of the inspected agent (RGB).
pub const INSPECTED_COLOR: [u8; 3] = [0xff, 0x8c, 0x00];
/// Scene px on each side of the inspected agent the heat map covers.
pub const LANDSCAPE_HALF_SIZE: f32 = 160.0;
/// Heat-map cells per side.
pub const LANDSCAPE_CELLS: u32 = 48;
/// Opacity of the heat map (out of 255).
const LANDSCAPE_ALPHA: u32 = 120;
/// Most neighbour links drawn for the inspected agent.
const MAX_NEIGHBOUR_LINKS: usize = 64;
/// Gap between a stuck agent's body and its ring (device px), and the ring's width.
const STUCK_RING_GAP_PX: f32 = 4.0;
const STUCK_RING_WIDTH_PX: f32 = 2.0;
/// Ring radii are rounded to this fraction of a device px to share sprites.
const RING_RADIUS_STEPS_PER_PX: f32 = 8.0;
/// Most ring sprites kept (one per distinct radius; a scene has one radius per group).
const MAX_RING_SPRITES: usize = 32;

/// Everything an overlay pass needs from the renderer.
pub(super) struct Target<'a> {
    pub frame: &'a mut [u8],
    pub width: u32,
    pub height: u32,
    pub view: ViewTransform,
    /// Stuck rings drawn so far, by radius (device px × [`RING_RADIUS_STEPS_PER_PX`]): kept by
    /// the renderer from frame to frame.
    pub rings: &'a mut Vec<(u32, Sprite)>,
}

/// Draws the overlays that are on.
pub(super) fn draw(mut target: Target, world: &World, overlays: Overlays, inspected: Option<u32>) {
    let inspected = inspected.filter(|&id| (id as usize) < world.agent_count());
    if overlays.landscape {
        if let Some(id) = inspected {
            draw_landscape(&mut target, world, id);
        }
    }
    let Target { frame, width, height, view, rings } = target;
    if overlays.fireflies {
        draw_fireflies(frame, width, height, view, world);
    }
    if overlays.stuck {
        draw_stuck_rings(frame, width, height, view, world, rings);
    }
    let Some(mut pixmap) = PixmapMut::from_bytes(frame, width, height) else { return };
    if overlays.explanation {
        if let Some(e) = inspected.and_then(|id| diagnose::explain(world, id)) {
            draw_explanation(&mut pixmap, view, world, &e);
        }
    }
}

/// A red ring around every stuck agent, copied from a sprite per ring radius: in a jammed crowd
/// thousands of agents are stuck, and a path of that many circles costs tiny-skia hundreds of
/// milliseconds (10,000 rings: 380 ms natively), a sprite copy a fraction of a microsecond each.
fn draw_stuck_rings(
    frame: &mut [u8],
    width: u32,
    height: u32,
    view: ViewTransform,
    world: &World,
    rings: &mut Vec<(u32, Sprite)>,
) {
    let (w, h) = (width as i32, height as i32);
    // Placed top to bottom (rows of 8 px), so that consecutive rings touch nearby memory.
    let mut placed: Vec<(i32, i32, u32)> = diagnose::stuck_agents(world)
        .into_iter()
        .filter_map(|id| {
            let c = view.to_canvas(*world.positions().get(id as usize)?);
            let radius_px = world.radii().get(id as usize)? * view.scale + STUCK_RING_GAP_PX;
            if !c.is_finite() || !radius_px.is_finite() {
                return None;
            }
            let key = (radius_px * RING_RADIUS_STEPS_PER_PX).round().clamp(0.0, 1e6) as u32;
            Some((c.x.round() as i32, c.y.round() as i32, key))
        })
        .collect();
    placed.sort_unstable_by_key(|&(x, y, _)| (y >> 3, x));
    for (x, y, key) in placed {
        let at = match rings.iter().position(|(k, _)| *k == key) {
            Some(at) => at,
            None => {
                if rings.len() >= MAX_RING_SPRITES {
                    rings.clear();
                }
                let radius = key as f32 / RING_RADIUS_STEPS_PER_PX;
                rings.push((key, ring_sprite(STUCK_COLOR, 230, radius, STUCK_RING_WIDTH_PX)));
                rings.len() - 1
            }
        };
        blit_over(frame, w, h, &rings[at].1, x, y);
    }
}

/// Neighbour links, the highlight ring, force arrows and the planner's points.
fn draw_explanation(pixmap: &mut PixmapMut, view: ViewTransform, world: &World, e: &Explanation) {
    let p = e.position;
    let px = 1.0 / view.scale.max(1e-3);
    let radius = world.radii().get(e.agent as usize).copied().unwrap_or(4.0);
    let mut links = PathBuilder::new();
    for &n in e.neighbours.iter().take(MAX_NEIGHBOUR_LINKS) {
        let Some(&q) = world.positions().get(n as usize) else { continue };
        links.move_to(p.x, p.y);
        links.line_to(q.x, q.y);
        links.push_circle(q.x, q.y, radius + 2.0 * px);
    }
    stroke_scene_path(pixmap, links, view, [0x55, 0x55, 0x55], 110, 1.0, None);
    let mut ring = PathBuilder::new();
    ring.push_circle(p.x, p.y, radius + 6.0 * px);
    stroke_scene_path(pixmap, ring, view, INSPECTED_COLOR, 255, 3.0, None);

    for (k, v) in e.vectors.iter().enumerate() {
        let rgb = ARROW_COLORS[k % ARROW_COLORS.len()];
        let d = if v.in_px { v.vector } else { v.vector * e.scale };
        if !d.is_finite() || d.length() < 0.5 * px {
            continue;
        }
        let dash = v.in_px.then_some([6.0, 4.0]);
        stroke_scene_path(pixmap, arrow(p, p + d, 7.0 * px), view, rgb, 240, 2.0, dash);
    }
    if e.applied.is_finite() && e.applied != Vec2::ZERO {
        let tip = p + e.applied * e.scale;
        stroke_scene_path(pixmap, arrow(p, tip, 8.0 * px), view, [0x10, 0x10, 0x10], 255, 1.0, None);
    }
    for point in &e.points {
        let q = point.point;
        let mut pb = PathBuilder::new();
        let (rgb, width) = match point.name.as_str() {
            "pbest" => {
                pb.push_rect_centered(q, 5.0 * px);
                ([0x2c, 0xa0, 0x2c], 2.0)
            }
            "gbest" => {
                pb.push_circle(q.x, q.y, 6.0 * px);
                pb.push_circle(q.x, q.y, 2.0 * px);
                ([0xc0, 0x90, 0x00], 2.5)
            }
            "rejected candidate" => {
                let s = 3.0 * px;
                pb.move_to(q.x - s, q.y - s);
                pb.line_to(q.x + s, q.y + s);
                pb.move_to(q.x - s, q.y + s);
                pb.line_to(q.x + s, q.y - s);
                (STUCK_COLOR, 1.5)
            }
            "candidate" => {
                pb.push_circle(q.x, q.y, 2.5 * px);
                ([0x2c, 0xa0, 0x2c], 1.5)
            }
            _ => {
                // A firefly followed or at the feeler tip: a ring and a link.
                pb.push_circle(q.x, q.y, radius + 4.0 * px);
                pb.move_to(p.x, p.y);
                pb.line_to(q.x, q.y);
                ([0xc0, 0x90, 0x00], 2.0)
            }
        };
        stroke_scene_path(pixmap, pb, view, rgb, 255, width, None);
    }
}

/// A line from `a` to `b` with a two-stroke head of length `head` (scene px).
fn arrow(a: Vec2, b: Vec2, head: f32) -> PathBuilder {
    let mut pb = PathBuilder::new();
    pb.move_to(a.x, a.y);
    pb.line_to(b.x, b.y);
    let d = b - a;
    let len = d.length();
    if len > 1e-6 {
        let back = d / len * -head.min(0.5 * len).max(head * 0.5);
        for angle in [0.45f32, -0.45] {
            let w = Vec2::from_angle(angle).rotate(back);
            pb.move_to(b.x, b.y);
            pb.line_to(b.x + w.x, b.y + w.y);
        }
    }
    pb
}

trait PushRectCentered {
    fn push_rect_centered(&mut self, c: Vec2, half: f32);
}

impl PushRectCentered for PathBuilder {
    fn push_rect_centered(&mut self, c: Vec2, half: f32) {
        if let Some(r) = tiny_skia::Rect::from_ltrb(c.x - half, c.y - half, c.x + half, c.y + half) {
            self.push_rect(r);
        }
    }
}

/// The inspected agent's cost landscape: each cell blended over the frame, coloured by the log
/// of the cost from blue (cheapest in view) through yellow to red (dearest).
fn draw_landscape(target: &mut Target, world: &World, id: u32) {
    let Some(grid) = diagnose::cost_grid(world, id, LANDSCAPE_HALF_SIZE, LANDSCAPE_CELLS) else { return };
    let logs: Vec<f32> = grid.costs.iter().map(|c| libm::logf(c.max(1e-6))).collect();
    let lo = logs.iter().copied().fold(f32::INFINITY, f32::min);
    let hi = logs.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let span = (hi - lo).max(1e-6);
    let view = target.view;
    let (w, h) = (target.width as i32, target.height as i32);
    let mut cells = Vec::with_capacity(logs.len());
    for (k, &l) in logs.iter().enumerate() {
        let (row, col) = (k as u32 / grid.cells, k as u32 % grid.cells);
        let a = view.to_canvas(grid.origin + Vec2::new(col as f32, row as f32) * grid.cell);
        let b = view.to_canvas(grid.origin + Vec2::new(col as f32 + 1.0, row as f32 + 1.0) * grid.cell);
        cells.push((a, b, heat((l - lo) / span)));
    }
    let frame = &mut *target.frame;
    for (a, b, rgb) in cells {
        let (x0, y0) = ((a.x.round() as i32).clamp(0, w), (a.y.round() as i32).clamp(0, h));
        let (x1, y1) = ((b.x.round() as i32).clamp(0, w), (b.y.round() as i32).clamp(0, h));
        for y in y0..y1 {
            let row = y as usize * w as usize * 4;
            for x in x0..x1 {
                let at = row + x as usize * 4;
                for c in 0..3 {
                    let under = u32::from(frame[at + c]);
                    let over = u32::from(rgb[c]);
                    frame[at + c] =
                        ((over * LANDSCAPE_ALPHA + under * (255 - LANDSCAPE_ALPHA) + 127) / 255) as u8;
                }
            }
        }
    }
}

/// Blue → cyan → yellow → red for `t` in 0…1.
fn heat(t: f32) -> [u8; 3] {
    // NaN (a cost the planner could not evaluate) shows as the cheapest colour.
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let stops: [[f32; 3]; 4] =
        [[40.0, 70.0, 200.0], [40.0, 190.0, 210.0], [250.0, 220.0, 40.0], [220.0, 30.0, 30.0]];
    let x = t * 3.0;
    let i = (x.floor() as usize).min(2);
    let f = x - i as f32;
    let (a, b) = (stops[i], stops[i + 1]);
    [0, 1, 2].map(|c| (a[c] + (b[c] - a[c]) * f).round() as u8)
}

/// Feelers (one Wu line each, no path per agent) and a brightness
/// glow for every firefly: brighter (nearer the target) is a larger, more opaque yellow dot.
fn draw_fireflies(frame: &mut [u8], width: u32, height: u32, view: ViewTransform, world: &World) {
    let (w, h) = (width as usize, height as usize);
    for (g, group) in world.scene().groups.iter().enumerate() {
        let PlannerConfig::Firefly(params) = &group.planner else { continue };
        let Some(view_of_group) = world.group_view(g) else { continue };
        let range = view_of_group.agents.start as usize..view_of_group.agents.end as usize;
        let positions = &world.positions()[range.clone()];
        let velocities = &world.velocities()[range];
        let target = view_of_group.goal.map(|(t, _)| t);
        let far = target.map_or(1.0, |t| positions.iter().map(|p| p.distance(t)).fold(1.0f32, f32::max));
        for (&p, &v) in positions.iter().zip(velocities) {
            let heading =
                crate::model::geometry::unit_or(v, target.map_or(Vec2::X, |t| (t - p).normalize_or_zero()));
            let a = view.to_canvas(p);
            let b = view.to_canvas(p + heading * params.feeler_length);
            draw_segment(frame, w, h, a, b, [0x90, 0x60, 0x00], 150);
            let brightness = target.map_or(0.5, |t| 1.0 - p.distance(t) / far);
            glow(frame, w, h, a, brightness);
        }
    }
}

/// A square glow of radius 2…6 device px, yellow, opacity rising with `brightness` (0…1).
fn glow(frame: &mut [u8], w: usize, h: usize, c: Vec2, brightness: f32) {
    if !c.is_finite() {
        return;
    }
    let b = brightness.clamp(0.0, 1.0);
    let r = (2.0 + 4.0 * b).round() as i32;
    let alpha = (60.0 + 180.0 * b) as u32;
    let (cx, cy) = (c.x.round() as i32, c.y.round() as i32);
    let rgb = [255u32, 220, 40];
    for y in (cy - r).max(0)..(cy + r + 1).min(h as i32) {
        for x in (cx - r).max(0)..(cx + r + 1).min(w as i32) {
            let d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            if d2 > r * r {
                continue;
            }
            let at = (y as usize * w + x as usize) * 4;
            for k in 0..3 {
                let under = u32::from(frame[at + k]);
                frame[at + k] = ((rgb[k] * alpha + under * (255 - alpha) + 127) / 255) as u8;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;
    use crate::render::Renderer;

    fn frame(world: &World, overlays: Overlays, inspected: Option<u32>) -> Vec<u8> {
        let mut r = Renderer::new(450, 300);
        r.set_trails(false);
        r.set_overlays(overlays);
        r.set_inspected(inspected);
        r.render(world);
        r.pixels().to_vec()
    }

    fn differing_pixels(a: &[u8], b: &[u8]) -> usize {
        a.chunks(4).zip(b.chunks(4)).filter(|(x, y)| x != y).count()
    }

    const OFF: Overlays = Overlays { stuck: false, explanation: false, landscape: false, fireflies: false };

    #[test]
    fn each_overlay_changes_pixels_and_off_changes_none() {
        let mut world = World::new(presets::u_trap()).expect("valid");
        world.step_n(60);
        let plain = frame(&world, OFF, None);
        // Defaults with nothing inspected and nobody stuck yet draw nothing extra.
        assert_eq!(differing_pixels(&plain, &frame(&world, Overlays::default(), None)), 0);
        assert_eq!(differing_pixels(&plain, &frame(&world, OFF, Some(0))), 0);
        let explained = frame(&world, Overlays { explanation: true, ..OFF }, Some(0));
        assert!(differing_pixels(&plain, &explained) > 50);
        let landscape = frame(&world, Overlays { landscape: true, ..OFF }, Some(0));
        let covered = differing_pixels(&plain, &landscape);
        // 320 scene px at half scale is a 160-px square, minus what lies outside the frame.
        assert!(covered > 5_000, "heat map covers {covered} px");
        // Boids (agent 40) have no cost landscape: nothing drawn.
        assert_eq!(
            differing_pixels(&plain, &frame(&world, Overlays { landscape: true, ..OFF }, Some(40))),
            0
        );
        let fireflies = frame(&world, Overlays { fireflies: true, ..OFF }, None);
        assert!(differing_pixels(&plain, &fireflies) > 200);
    }

    #[test]
    fn stuck_agents_get_rings() {
        let mut world = World::new(presets::u_trap()).expect("valid");
        world.step_n(900);
        assert!(!diagnose::stuck_agents(&world).is_empty());
        let plain = frame(&world, OFF, None);
        let rings = frame(&world, Overlays { stuck: true, ..OFF }, None);
        let red = rings.chunks(4).filter(|p| p[0] > 180 && p[1] < 90 && p[2] < 90).count();
        assert!(differing_pixels(&plain, &rings) > 100 && red > 20, "red px {red}");
    }

    #[test]
    fn heat_runs_from_blue_to_red() {
        assert!(heat(0.0)[2] > heat(0.0)[0]);
        assert!(heat(1.0)[0] > heat(1.0)[2]);
        assert_eq!(heat(f32::NAN), heat(0.0));
    }
}
