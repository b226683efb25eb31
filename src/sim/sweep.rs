//! Moves that cannot tunnel: phase 2 of a step for one agent, checked over the whole move and
//! not only where it ends.
//!
//! An agent moves to `previous + velocity` and is pushed out of any obstacle its disc overlaps
//! there. Alone, that lets a move longer than a wall is thick jump over it: the end lies beyond
//! the wall, or inside it nearer the far side, and is pushed out there (issue 24: 39 of 50
//! Boids at `max_speed` 20 crossed a 1 px wall). So the centre's way from where the step began
//! to where it ends — a straight segment, two in a periodic band where it wraps — must not pass
//! through any obstacle's interior. When it would, the agent stops a body radius short of where
//! its intended move first enters an obstacle, without the part of its velocity into that
//! surface, and is pushed out from there; should even that cross (pushes between obstacles
//! packed closer than a body), it stays where it was.
//!
//! Cost: nothing beyond the push-out in the usual case. When the push-out's last round found no
//! obstacle within a body radius of the end and the move is no longer than that radius, the
//! whole segment lies in a disc that holds no obstacle, so it crosses none; only a longer move,
//! a clamp at the border, a wrap, or an end the push-out could not clear asks the obstacle index
//! about the segment's box.
//!
//! The metrics count a centre whose way passed through an obstacle as a penetration, with
//! [`path_enters`], so a crossing that happened would show.

use crate::model::geometry::{distance, Aabb, Obstacle, RayHit};
use crate::sim::spawn::centre_bounds;
use crate::spatial::ObstacleIndex;
use glam::Vec2;

/// How far outside a surface a pushed-out agent is placed (px).
pub(crate) const PUSH_EPSILON: f32 = 0.01;

/// Where the world is, for moving one agent: its obstacles, its size and its periodic band.
#[derive(Clone, Copy)]
pub(crate) struct Terrain<'a> {
    /// The scene's obstacles.
    pub obstacles: &'a ObstacleIndex,
    /// World size (px): centres are clamped inside it.
    pub bounds: Vec2,
    /// The periodic band in x (the world's `set_periodic_x`), if any.
    pub periodic_x: Option<(f32, f32)>,
}

impl Terrain<'_> {
    /// Phase 2 for one agent: the centre at `previous` moves by `velocity`, wraps in the
    /// periodic band, is pushed out of obstacles (when `solid`) and kept inside the world.
    /// Returns its new centre and velocity. A solid agent never ends inside an obstacle and its
    /// way never passes through one it was not already in (see the module docs).
    #[inline]
    pub fn move_agent(&self, previous: Vec2, velocity: Vec2, radius: f32, solid: bool) -> (Vec2, Vec2) {
        let mut v = velocity;
        let intended = previous + velocity;
        let mut p = wrap(previous, intended, self.periodic_x);
        let wrapped = p != intended;
        let mut clear = true;
        if solid {
            clear = push_out(self.obstacles, &mut p, &mut v, radius);
        }
        let clamped = self.clamp(&mut p, &mut v, radius);
        if !solid {
            return (p, v);
        }
        if self.obstacles.contains(p) {
            // Pushing out failed (overlapping obstacles, or the border pushed it back in):
            // stay where it was, inside the world and outside the obstacles.
            return (previous, Vec2::ZERO);
        }
        let short = clear && !clamped && !wrapped && previous.distance_squared(p) <= radius * radius;
        if short || self.obstacles.is_empty() || !path_enters(self.obstacles, previous, p, self.periodic_x) {
            return (p, v);
        }
        self.stop_before_entry(previous, velocity, radius)
    }

    /// The move from `previous` by `velocity` went through an obstacle: stop a body radius
    /// short of where the intended move first enters one (or where it began, if it enters
    /// within a radius), drop the velocity's part into that surface, and push out from there;
    /// if the way still crosses an obstacle, stay at `previous`.
    fn stop_before_entry(&self, previous: Vec2, velocity: Vec2, radius: f32) -> (Vec2, Vec2) {
        let stay = (previous, Vec2::ZERO);
        let pieces = pieces(previous, previous + velocity, self.periodic_x);
        let Some((from, to, hit)) = pieces
            .into_iter()
            .flatten()
            .find_map(|(a, b)| first_entry(self.obstacles, a, b).map(|h| (a, b, h)))
        else {
            // The intended move enters nothing: the push-out or the border made the crossing.
            return stay;
        };
        let length = distance(from, to);
        let before = (hit.t * length - radius).max(0.0);
        let mut p = from + (to - from) * (before / length);
        let mut v = velocity;
        let into = v.dot(hit.normal);
        if into < 0.0 {
            v -= hit.normal * into;
        }
        push_out(self.obstacles, &mut p, &mut v, radius);
        self.clamp(&mut p, &mut v, radius);
        if self.obstacles.contains(p) || path_enters(self.obstacles, previous, p, self.periodic_x) {
            return stay;
        }
        (p, v)
    }

    /// Keeps the centre inside the world (a world narrower than the body holds it on the middle
    /// line), also when an obstacle touches the border; a clamped axis loses its velocity.
    /// Returns whether it clamped.
    #[inline]
    fn clamp(&self, p: &mut Vec2, v: &mut Vec2, radius: f32) -> bool {
        let (lo, hi) = centre_bounds(radius, self.bounds);
        let clamped = p.clamp(lo, hi);
        if clamped.x != p.x {
            v.x = 0.0;
        }
        if clamped.y != p.y {
            v.y = 0.0;
        }
        let moved = clamped != *p;
        *p = clamped;
        moved
    }
}

/// The centre at `intended` after a move from `previous`: only a centre leaving the periodic
/// band wraps (one outside it stays outside).
#[inline]
fn wrap(previous: Vec2, intended: Vec2, band: Option<(f32, f32)>) -> Vec2 {
    let mut p = intended;
    if let Some((start, end)) = band {
        if p.x >= end && previous.x < end {
            p.x -= end - start;
        } else if p.x < start && previous.x >= start {
            p.x += end - start;
        }
    }
    p
}

/// The straight pieces of a centre's way from `from` to `to`: one segment, or, where the way
/// left the periodic band and wrapped (`to` is then the wrapped centre or the unwrapped one),
/// the part up to the band's edge and the part from the other edge.
fn pieces(from: Vec2, to: Vec2, band: Option<(f32, f32)>) -> [Option<(Vec2, Vec2)>; 2] {
    let Some((start, end)) = band else {
        return [Some((from, to)), None];
    };
    let width = end - start;
    let inside = |x: f32| (start..end).contains(&x);
    // Unwrap: a centre in the band that moved more than half the band's width in x wrapped.
    let unwrapped = if inside(from.x) && to.x - from.x > 0.5 * width && inside(to.x) {
        Vec2::new(to.x - width, to.y)
    } else if inside(from.x) && from.x - to.x > 0.5 * width && inside(to.x) {
        Vec2::new(to.x + width, to.y)
    } else {
        to
    };
    let (edge, shift) = if inside(from.x) && unwrapped.x >= end {
        (end, -width)
    } else if inside(from.x) && unwrapped.x < start {
        (start, width)
    } else {
        return [Some((from, to)), None];
    };
    let t = (edge - from.x) / (unwrapped.x - from.x);
    let at_edge = from + (unwrapped - from) * t;
    let shifted = |p: Vec2| Vec2::new(p.x + shift, p.y);
    [Some((from, at_edge)), Some((shifted(at_edge), shifted(unwrapped)))]
}

/// Whether a centre's way from `from` to `to` passes into the interior of an obstacle it did
/// not start in: enters one and leaves it again, or ends inside it. In the periodic band
/// `band`, a centre that moved more than half the band's width in x wrapped: its way is the
/// part up to the band's edge and the part from the other edge.
pub fn path_enters(obstacles: &ObstacleIndex, from: Vec2, to: Vec2, band: Option<(f32, f32)>) -> bool {
    pieces(from, to, band).into_iter().flatten().any(|(a, b)| first_entry(obstacles, a, b).is_some())
}

/// Where the segment `from → to` first enters an obstacle's interior (see
/// [`Obstacle::segment_entry`]), among the obstacles whose boxes meet the segment's box.
fn first_entry(obstacles: &ObstacleIndex, from: Vec2, to: Vec2) -> Option<RayHit> {
    let query = Aabb { min: from.min(to), max: from.max(to) };
    let mut first: Option<RayHit> = None;
    obstacles.for_each_near(query, |_, o: &Obstacle| {
        if let Some(hit) = o.segment_entry(from, to) {
            if first.is_none_or(|f| hit.t < f.t) {
                first = Some(hit);
            }
        }
    });
    first
}

/// Pushes a disc of `radius` at `p` out of any obstacle it overlaps and removes the velocity
/// component into the surface (agents slide along walls). A few rounds handle corners. Returns
/// whether the last round found no obstacle within `radius` of `p` (false when the rounds ran
/// out while still pushing).
#[inline]
fn push_out(obstacles: &ObstacleIndex, p: &mut Vec2, v: &mut Vec2, radius: f32) -> bool {
    if obstacles.is_empty() {
        return true;
    }
    for _ in 0..3 {
        let query = Aabb { min: *p - Vec2::splat(radius), max: *p + Vec2::splat(radius) };
        let here = *p;
        let mut push = None;
        obstacles.for_each_near(query, |_, o: &Obstacle| {
            if push.is_some() {
                return;
            }
            let s = o.surface(here);
            if s.signed_distance < radius {
                push = Some(s);
            }
        });
        let Some(s) = push else {
            return true;
        };
        *p = s.point + s.normal * (radius + PUSH_EPSILON);
        let into = v.dot(s.normal);
        if into < 0.0 {
            *v -= s.normal * into;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    const W: f32 = 300.0;
    const H: f32 = 300.0;

    fn index(obstacles: Vec<Obstacle>) -> ObstacleIndex {
        ObstacleIndex::new(obstacles, W, H)
    }

    fn terrain(obstacles: &ObstacleIndex) -> Terrain<'_> {
        Terrain { obstacles, bounds: Vec2::new(W, H), periodic_x: None }
    }

    /// A thin obstacle somewhere in the world: a wall 0.5…3 px thick (either way), a small
    /// circle, a thin triangle or an L-shaped polygon (not convex).
    fn thin_obstacle(rng: &mut Rng) -> Obstacle {
        let (x, y) = (rng.range(0.0, W), rng.range(0.0, H));
        let (long, thin) = (rng.range(10.0, 200.0), rng.range(0.5, 3.0));
        match rng.below(4) {
            0 => Obstacle::Rect { min: [x, y], max: [x + long, y + thin] },
            1 => Obstacle::Rect { min: [x, y], max: [x + thin, y + long] },
            2 => Obstacle::Circle { center: [x, y], radius: rng.range(0.5, 20.0) },
            _ if rng.below(2) == 0 => Obstacle::Polygon {
                points: vec![
                    [x, y],
                    [x + long, y + rng.range(-40.0, 40.0)],
                    [x + long * 0.5, y + thin * 4.0],
                ],
            },
            _ => Obstacle::Polygon {
                points: vec![
                    [x, y],
                    [x + long, y],
                    [x + long, y + thin],
                    [x + thin, y + thin],
                    [x + thin, y + long],
                    [x, y + long],
                ],
            },
        }
    }

    /// Whether any of `samples` evenly spaced points of `a → b` lies in an obstacle that does
    /// not hold `a`: the crossing test made by sampling, apart from `segment_entry`.
    fn sampled_crossing(obstacles: &[Obstacle], a: Vec2, b: Vec2, samples: u32) -> Option<usize> {
        obstacles.iter().position(|o| {
            !o.contains(a) && (1..=samples).any(|k| o.contains(a.lerp(b, k as f32 / samples as f32)))
        })
    }

    #[test]
    fn no_move_passes_through_a_thin_obstacle_at_any_speed() {
        let mut rng = Rng::new(24, 2);
        let mut stopped = 0;
        for case in 0..3000 {
            let list: Vec<Obstacle> = (0..2 + rng.below(7)).map(|_| thin_obstacle(&mut rng)).collect();
            let obstacles = index(list.clone());
            let radius = if rng.below(2) == 0 { rng.range(0.5, 2.0) } else { rng.range(2.0, 12.0) };
            let previous = Vec2::new(rng.range(0.0, W), rng.range(0.0, H));
            let speed =
                [rng.range(0.0, 2.0), rng.range(2.0, 30.0), rng.range(30.0, 300.0)][rng.below(3) as usize];
            let angle = rng.range(0.0, std::f32::consts::TAU);
            let velocity = Vec2::new(angle.cos(), angle.sin()) * speed;
            let (p, v) = terrain(&obstacles).move_agent(previous, velocity, radius, true);
            let what = format!("case {case}: {previous} by {velocity} (radius {radius}) to {p}, {list:?}");
            assert!(p.is_finite() && v.is_finite(), "{what}");
            assert!(p.x >= 0.0 && p.x <= W && p.y >= 0.0 && p.y <= H, "left the world: {what}");
            assert!(!obstacles.contains(p) || p == previous, "ended inside: {what}");
            // 0.5 px is the thinnest obstacle; 300 px / 2,000 samples = 0.15 px apart.
            assert_eq!(sampled_crossing(&list, previous, p, 2000), None, "crossed: {what}");
            stopped += usize::from(sampled_crossing(&list, previous, previous + velocity, 500).is_some());
        }
        // The cases are not all easy: many intended moves went through an obstacle.
        assert!(stopped > 200, "only {stopped} of 3000 intended moves crossed an obstacle");
    }

    #[test]
    fn a_short_move_clear_of_obstacles_is_not_changed() {
        // The push-out and clamp alone decide a move that cannot cross: the same floats as a
        // plain `previous + velocity`.
        let obstacles = index(vec![Obstacle::Rect { min: [100.0, 100.0], max: [101.0, 200.0] }]);
        let (p, v) = terrain(&obstacles).move_agent(Vec2::new(90.0, 150.0), Vec2::new(1.5, 0.25), 4.0, true);
        assert_eq!((p, v), (Vec2::new(91.5, 150.25), Vec2::new(1.5, 0.25)));
        // Sliding along the wall's face: the push-out's result, unchanged.
        let (p, v) = terrain(&obstacles).move_agent(Vec2::new(95.0, 150.0), Vec2::new(3.0, 2.0), 4.0, true);
        assert!((p.x - (100.0 - 4.0 - PUSH_EPSILON)).abs() < 1e-4 && p.y == 152.0, "{p}");
        assert_eq!(v, Vec2::new(0.0, 2.0));
    }

    #[test]
    fn a_fast_move_stops_before_the_wall_and_slides_along_it() {
        let obstacles = index(vec![Obstacle::Rect { min: [0.0, 150.0], max: [W, 151.0] }]);
        let t = terrain(&obstacles);
        let (p, v) = t.move_agent(Vec2::new(100.0, 100.0), Vec2::new(30.0, 100.0), 4.0, true);
        assert!(p.y < 150.0 - 4.0 + 1e-3, "on the near side, clear of the wall: {p}");
        assert_eq!(v, Vec2::new(30.0, 0.0), "the part into the wall is gone");
        // A passing planner (`solid` false) goes through, as its design says.
        let (p, _) = t.move_agent(Vec2::new(100.0, 100.0), Vec2::new(30.0, 100.0), 4.0, false);
        assert_eq!(p, Vec2::new(130.0, 200.0));
    }

    #[test]
    fn a_wrap_across_the_seam_is_no_crossing_but_a_wall_past_it_still_stops() {
        let band = Some((0.0, 200.0));
        // A wall beyond the band's end (x ≥ 200) is never on the way of a centre that wraps.
        let beyond = index(vec![Obstacle::Rect { min: [205.0, 0.0], max: [206.0, H] }]);
        let t = Terrain { periodic_x: band, ..terrain(&beyond) };
        let (p, _) = t.move_agent(Vec2::new(195.0, 100.0), Vec2::new(20.0, 0.0), 2.0, true);
        assert!((p.x - 15.0).abs() < 1e-4, "wrapped to the band's start: {p}");
        assert!(!path_enters(&beyond, Vec2::new(195.0, 100.0), p, band));
        // A wall just past the band's start is on the way after the wrap.
        let after = index(vec![Obstacle::Rect { min: [5.0, 0.0], max: [6.0, H] }]);
        let t = Terrain { periodic_x: band, ..terrain(&after) };
        let (p, _) = t.move_agent(Vec2::new(195.0, 100.0), Vec2::new(20.0, 0.0), 2.0, true);
        assert!(p.x > 150.0 || p.x < 5.0, "not past the wall at x 5…6: {p}");
        assert!(path_enters(&after, Vec2::new(195.0, 100.0), Vec2::new(15.0, 100.0), band));
        assert!(!path_enters(&after, Vec2::new(195.0, 100.0), p, band));
    }
}
