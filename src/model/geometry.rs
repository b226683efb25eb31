//! Obstacle shapes and the queries the planners need: containment, nearest surface, ray casts.

use glam::Vec2;
use serde::{Deserialize, Serialize};

/// A static obstacle in scene coordinates (pixels, y down).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum Obstacle {
    /// A disc.
    Circle {
        /// Centre `[x, y]` in px.
        center: [f32; 2],
        /// Radius in px, > 0.
        radius: f32,
    },
    /// An axis-aligned rectangle.
    Rect {
        /// Top-left corner `[x, y]` in px.
        min: [f32; 2],
        /// Bottom-right corner `[x, y]` in px.
        max: [f32; 2],
    },
    /// A simple polygon (at least three points, either winding).
    Polygon {
        /// Vertices `[x, y]` in px, closed implicitly.
        points: Vec<[f32; 2]>,
    },
}

/// The nearest point of an obstacle's boundary to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Nearest boundary point.
    pub point: Vec2,
    /// Unit normal pointing out of the obstacle at that point.
    pub normal: Vec2,
    /// Distance from the query point to the boundary: negative when the point is inside.
    pub signed_distance: f32,
}

/// Where a segment first meets an obstacle's boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Fraction along the segment, in [0, 1].
    pub t: f32,
    /// Unit outward normal at the hit.
    pub normal: Vec2,
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec2,
    /// Largest corner.
    pub max: Vec2,
}

impl Aabb {
    /// Grows the box by `margin` on every side.
    pub fn inflate(self, margin: f32) -> Self {
        Self { min: self.min - Vec2::splat(margin), max: self.max + Vec2::splat(margin) }
    }

    /// Whether the point lies in the box (borders included).
    pub fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// Whether two boxes overlap.
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.x <= other.max.x
            && self.max.x >= other.min.x
            && self.min.y <= other.max.y
            && self.max.y >= other.min.y
    }
}

/// Converts a JSON pair into a vector.
#[inline]
pub fn v(p: [f32; 2]) -> Vec2 {
    Vec2::new(p[0], p[1])
}

fn closest_on_segment(p: Vec2, a: Vec2, b: Vec2) -> Vec2 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 <= f32::EPSILON {
        return a;
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    a + ab * t
}

/// Intersection of segment p→p+d with segment a→b: the fraction along p→p+d.
fn segment_hit(p: Vec2, d: Vec2, a: Vec2, b: Vec2) -> Option<f32> {
    let e = b - a;
    let denom = d.perp_dot(e);
    if denom.abs() <= f32::EPSILON {
        return None;
    }
    let ap = a - p;
    let t = ap.perp_dot(e) / denom;
    let u = ap.perp_dot(d) / denom;
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some(t)
}

/// `v.length()` with the hardware square root. glam's `length` goes through libm (its `libm`
/// feature keeps sines and cosines the same on every platform), whose `sqrtf` is a software
/// loop in wasm on stable Rust; a square root is correctly rounded either way, so this gives
/// the same bits, several times faster in the browser. Use it in per-agent code.
#[inline]
pub fn length(v: Vec2) -> f32 {
    v.dot(v).sqrt()
}

/// `a.distance(b)` with the hardware square root (see [`length`]).
#[inline]
pub fn distance(a: Vec2, b: Vec2) -> f32 {
    length(a - b)
}

/// A unit vector, or `fallback` when `d` has no usable length.
#[inline]
pub fn unit_or(d: Vec2, fallback: Vec2) -> Vec2 {
    let len = length(d);
    if len > 1e-6 {
        d / len
    } else {
        fallback
    }
}

impl Obstacle {
    /// The obstacle's bounding box.
    pub fn aabb(&self) -> Aabb {
        match self {
            Obstacle::Circle { center, radius } => {
                Aabb { min: v(*center) - Vec2::splat(*radius), max: v(*center) + Vec2::splat(*radius) }
            }
            Obstacle::Rect { min, max } => Aabb { min: v(*min), max: v(*max) },
            Obstacle::Polygon { points } => {
                let mut b = Aabb { min: Vec2::splat(f32::INFINITY), max: Vec2::splat(f32::NEG_INFINITY) };
                for p in points {
                    b.min = b.min.min(v(*p));
                    b.max = b.max.max(v(*p));
                }
                b
            }
        }
    }

    /// Whether `p` lies strictly inside the obstacle.
    pub fn contains(&self, p: Vec2) -> bool {
        match self {
            Obstacle::Circle { center, radius } => p.distance_squared(v(*center)) < radius * radius,
            Obstacle::Rect { min, max } => p.x > min[0] && p.x < max[0] && p.y > min[1] && p.y < max[1],
            Obstacle::Polygon { points } => {
                // Even-odd rule: count edge crossings of a ray towards +x.
                let mut inside = false;
                let n = points.len();
                for i in 0..n {
                    let a = v(points[i]);
                    let b = v(points[(i + n - 1) % n]);
                    if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
                        inside = !inside;
                    }
                }
                inside
            }
        }
    }

    /// The nearest boundary point to `p`, with the outward normal there.
    pub fn surface(&self, p: Vec2) -> SurfacePoint {
        match self {
            Obstacle::Circle { center, radius } => {
                let c = v(*center);
                let normal = unit_or(p - c, Vec2::X);
                SurfacePoint { point: c + normal * *radius, normal, signed_distance: distance(p, c) - radius }
            }
            Obstacle::Rect { min, max } => {
                let (lo, hi) = (v(*min), v(*max));
                if self.contains(p) {
                    // Exit through the nearest side.
                    let exits = [
                        (p.x - lo.x, Vec2::NEG_X, Vec2::new(lo.x, p.y)),
                        (hi.x - p.x, Vec2::X, Vec2::new(hi.x, p.y)),
                        (p.y - lo.y, Vec2::NEG_Y, Vec2::new(p.x, lo.y)),
                        (hi.y - p.y, Vec2::Y, Vec2::new(p.x, hi.y)),
                    ];
                    let mut best = exits[0];
                    for e in exits.iter().skip(1) {
                        if e.0 < best.0 {
                            best = *e;
                        }
                    }
                    SurfacePoint { point: best.2, normal: best.1, signed_distance: -best.0 }
                } else {
                    let q = p.clamp(lo, hi);
                    let d = p - q;
                    SurfacePoint { point: q, normal: unit_or(d, Vec2::X), signed_distance: length(d) }
                }
            }
            Obstacle::Polygon { points } => {
                let n = points.len();
                let mut best = SurfacePoint { point: p, normal: Vec2::X, signed_distance: f32::INFINITY };
                let mut best_edge = (Vec2::ZERO, Vec2::ZERO);
                for i in 0..n {
                    let a = v(points[i]);
                    let b = v(points[(i + 1) % n]);
                    let q = closest_on_segment(p, a, b);
                    let d = distance(p, q);
                    if d < best.signed_distance {
                        best.point = q;
                        best.signed_distance = d;
                        best_edge = (a, b);
                    }
                }
                let inside = self.contains(p);
                let away = p - best.point;
                best.normal = if away.length_squared() > 1e-10 {
                    let n = away.normalize();
                    if inside {
                        -n
                    } else {
                        n
                    }
                } else {
                    // On the boundary: use the edge normal that points out.
                    let e = best_edge.1 - best_edge.0;
                    let cand = unit_or(Vec2::new(e.y, -e.x), Vec2::X);
                    let probe = best.point + cand * 1e-3;
                    if self.contains(probe) {
                        -cand
                    } else {
                        cand
                    }
                };
                if inside {
                    best.signed_distance = -best.signed_distance;
                }
                best
            }
        }
    }

    /// First intersection of the segment `from → from + d` with the boundary, if any.
    pub fn ray_cast(&self, from: Vec2, d: Vec2) -> Option<RayHit> {
        match self {
            Obstacle::Circle { center, radius } => {
                let c = v(*center);
                let f = from - c;
                let a = d.length_squared();
                if a <= f32::EPSILON {
                    return None;
                }
                let b = f.dot(d);
                let cc = f.length_squared() - radius * radius;
                if cc < 0.0 {
                    // Starting inside: the hit is where we are.
                    return Some(RayHit { t: 0.0, normal: unit_or(f, -d.normalize()) });
                }
                let disc = b * b - a * cc;
                if disc < 0.0 {
                    return None;
                }
                let t = (-b - disc.sqrt()) / a;
                (0.0..=1.0).contains(&t).then(|| RayHit { t, normal: unit_or(f + d * t, Vec2::X) })
            }
            Obstacle::Rect { min, max } => {
                let (lo, hi) = (v(*min), v(*max));
                let corners = [lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)];
                polygon_ray_cast(self, &corners, from, d)
            }
            Obstacle::Polygon { points } => {
                let pts: Vec<Vec2> = points.iter().map(|p| v(*p)).collect();
                polygon_ray_cast(self, &pts, from, d)
            }
        }
    }
}

impl Obstacle {
    /// Where the segment `from → to` first enters the obstacle's interior, with the outward
    /// normal of the side it enters through; `None` when it stays outside (touching the boundary,
    /// or running along it, is not entering) or starts inside (leaving is not entering). A
    /// centre's move that enters an obstacle and leaves it again went through it: the move
    /// tunnelled (the world stops such a move, and the metrics count it as a penetration).
    ///
    /// Unlike [`Obstacle::ray_cast`], a hit on the boundary alone is no entry, and a polygon is
    /// not copied. Cost: a circle or rectangle O(1); a polygon O(n) for the edges plus O(k · n)
    /// for the k edges the segment meets, each followed by a containment test.
    pub fn segment_entry(&self, from: Vec2, to: Vec2) -> Option<RayHit> {
        let d = to - from;
        if d.length_squared() <= f32::EPSILON * f32::EPSILON {
            return None;
        }
        match self {
            Obstacle::Circle { center, radius } => {
                let f = from - v(*center);
                let a = d.length_squared();
                let b = f.dot(d);
                let c = f.length_squared() - radius * radius;
                if c < 0.0 {
                    return None;
                }
                let disc = b * b - a * c;
                if disc <= 0.0 {
                    // Missed, or touched at one point.
                    return None;
                }
                let root = disc.sqrt();
                let (t0, t1) = ((-b - root) / a, (-b + root) / a);
                if t0 >= 1.0 || t1 <= 0.0 {
                    return None;
                }
                let t = t0.max(0.0);
                Some(RayHit { t, normal: unit_or(f + d * t, -d.normalize_or_zero()) })
            }
            Obstacle::Rect { min, max } => {
                // The open box between the slabs: entered after the last slab is entered.
                let (lo, hi) = (v(*min), v(*max));
                let (mut enter, mut exit) = (f32::NEG_INFINITY, f32::INFINITY);
                let mut normal = Vec2::ZERO;
                for (a, dd, l, h, axis) in
                    [(from.x, d.x, lo.x, hi.x, Vec2::X), (from.y, d.y, lo.y, hi.y, Vec2::Y)]
                {
                    if dd == 0.0 {
                        if a <= l || a >= h {
                            return None;
                        }
                        continue;
                    }
                    let (t_lo, t_hi) = ((l - a) / dd, (h - a) / dd);
                    let (near, far) = if dd > 0.0 { (t_lo, t_hi) } else { (t_hi, t_lo) };
                    if near > enter {
                        enter = near;
                        normal = if dd > 0.0 { -axis } else { axis };
                    }
                    exit = exit.min(far);
                }
                // Inside from the start (enter < 0 < exit) is leaving, not entering.
                (enter < exit && (0.0..1.0).contains(&enter)).then_some(RayHit { t: enter, normal })
            }
            Obstacle::Polygon { points } => {
                if self.contains(from) {
                    return None;
                }
                let n = points.len();
                let edge = |i: usize| (v(points[i]), v(points[(i + 1) % n]));
                // The segment is outside up to its first meeting with an edge; after each
                // meeting, the piece up to the next one is inside or outside as a whole.
                let mut at = f32::NEG_INFINITY;
                loop {
                    let mut next: Option<(f32, usize)> = None;
                    for i in 0..n {
                        let (a, b) = edge(i);
                        if let Some(t) = segment_hit(from, d, a, b) {
                            if t > at && next.is_none_or(|(nt, _)| t < nt) {
                                next = Some((t, i));
                            }
                        }
                    }
                    let (t, i) = next?;
                    let after = (0..n)
                        .filter_map(|j| {
                            let (a, b) = edge(j);
                            segment_hit(from, d, a, b)
                        })
                        .filter(|&u| u > t)
                        .fold(1.0f32, f32::min);
                    if after > t && self.contains(from + d * (0.5 * (t + after))) {
                        let (a, b) = edge(i);
                        let e = b - a;
                        let mut normal = unit_or(Vec2::new(e.y, -e.x), Vec2::X);
                        if normal.dot(d) > 0.0 {
                            normal = -normal;
                        }
                        return Some(RayHit { t, normal });
                    }
                    at = t;
                }
            }
        }
    }
}

fn polygon_ray_cast(shape: &Obstacle, pts: &[Vec2], from: Vec2, d: Vec2) -> Option<RayHit> {
    if shape.contains(from) {
        let s = shape.surface(from);
        return Some(RayHit { t: 0.0, normal: s.normal });
    }
    let n = pts.len();
    let mut best: Option<(f32, Vec2, Vec2)> = None;
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        if let Some(t) = segment_hit(from, d, a, b) {
            if best.is_none_or(|(bt, _, _)| t < bt) {
                best = Some((t, a, b));
            }
        }
    }
    best.map(|(t, a, b)| {
        let e = b - a;
        let mut normal = unit_or(Vec2::new(e.y, -e.x), Vec2::X);
        // Face the normal against the ray: it points out of the side the ray came from.
        if normal.dot(d) > 0.0 {
            normal = -normal;
        }
        RayHit { t, normal }
    })
}

/// Scales `v` down to length `max` if longer.
#[inline]
pub fn limit(v: Vec2, max: f32) -> Vec2 {
    let len2 = v.length_squared();
    if len2 > max * max && len2 > 0.0 {
        v * (max / len2.sqrt())
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Obstacle {
        Obstacle::Polygon { points: vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]] }
    }

    #[test]
    fn polygon_and_rect_agree_on_a_square() {
        let rect = Obstacle::Rect { min: [0.0, 0.0], max: [10.0, 10.0] };
        let poly = square();
        for &(x, y) in &[(5.0, 3.0), (1.0, 8.0), (-1.0, 5.0), (12.0, 3.0), (5.0, 11.0)] {
            let p = Vec2::new(x, y);
            assert_eq!(rect.contains(p), poly.contains(p), "{p}");
            let (a, b) = (rect.surface(p), poly.surface(p));
            assert!((a.signed_distance - b.signed_distance).abs() < 1e-4, "{p}: {a:?} {b:?}");
            assert!(a.normal.distance(b.normal) < 1e-4, "{p}: {a:?} {b:?}");
        }
    }

    #[test]
    fn circle_surface_and_ray() {
        let c = Obstacle::Circle { center: [0.0, 0.0], radius: 5.0 };
        let s = c.surface(Vec2::new(10.0, 0.0));
        assert_eq!(s.signed_distance, 5.0);
        assert_eq!(s.normal, Vec2::X);
        let hit = c.ray_cast(Vec2::new(-10.0, 0.0), Vec2::new(20.0, 0.0)).expect("hits");
        assert!((hit.t - 0.25).abs() < 1e-6);
        assert_eq!(hit.normal, Vec2::NEG_X);
        assert!(c.ray_cast(Vec2::new(-10.0, 6.0), Vec2::new(20.0, 0.0)).is_none());
    }

    #[test]
    fn a_segment_enters_an_interior_not_a_boundary() {
        let wall = Obstacle::Rect { min: [0.0, 10.0], max: [100.0, 11.0] };
        let (above, below) = (Vec2::new(50.0, 0.0), Vec2::new(50.0, 20.0));
        let hit = wall.segment_entry(above, below).expect("through the 1 px wall");
        assert_eq!((hit.t, hit.normal), (0.5, Vec2::NEG_Y));
        assert_eq!(wall.segment_entry(below, above).map(|h| h.normal), Some(Vec2::Y));
        // Touching the face, running along it, stopping short, starting inside: no entry.
        assert!(wall.segment_entry(above, Vec2::new(50.0, 10.0)).is_none());
        assert!(wall.segment_entry(Vec2::new(-5.0, 10.0), Vec2::new(120.0, 10.0)).is_none());
        assert!(wall.segment_entry(above, Vec2::new(50.0, 9.5)).is_none());
        assert!(wall.segment_entry(Vec2::new(50.0, 10.5), below).is_none());
        // Clipping a corner.
        assert!(wall.segment_entry(Vec2::new(94.0, 0.0), Vec2::new(104.0, 20.0)).is_some());
        assert!(wall.segment_entry(Vec2::new(99.0, 0.0), Vec2::new(111.0, 20.0)).is_none());

        let disc = Obstacle::Circle { center: [0.0, 0.0], radius: 1.0 };
        let hit = disc.segment_entry(Vec2::new(-3.0, 0.0), Vec2::new(3.0, 0.0)).expect("through");
        assert!((hit.t - 2.0 / 6.0).abs() < 1e-6 && hit.normal == Vec2::NEG_X, "{hit:?}");
        assert!(disc.segment_entry(Vec2::new(-3.0, 1.0), Vec2::new(3.0, 1.0)).is_none(), "tangent");
        assert!(disc.segment_entry(Vec2::new(0.5, 0.0), Vec2::new(3.0, 0.0)).is_none(), "leaving");
        assert!(disc.segment_entry(Vec2::new(-3.0, 0.0), Vec2::new(-1.5, 0.0)).is_none(), "short");

        // A U open at the top: a segment across the mouth enters nothing; one across the
        // arms enters the left arm first.
        let u = Obstacle::Polygon {
            points: vec![
                [0.0, 0.0],
                [2.0, 0.0],
                [2.0, 8.0],
                [8.0, 8.0],
                [8.0, 0.0],
                [10.0, 0.0],
                [10.0, 10.0],
                [0.0, 10.0],
            ],
        };
        assert!(u.segment_entry(Vec2::new(3.0, 4.0), Vec2::new(7.0, 4.0)).is_none());
        let hit = u.segment_entry(Vec2::new(-2.0, 4.0), Vec2::new(12.0, 4.0)).expect("the left arm");
        assert!((hit.t - 2.0 / 14.0).abs() < 1e-6 && hit.normal == Vec2::NEG_X, "{hit:?}");
        let hit = u.segment_entry(Vec2::new(5.0, 4.0), Vec2::new(12.0, 4.0)).expect("the right arm");
        assert!((hit.t - 3.0 / 7.0).abs() < 1e-6, "{hit:?}");
        assert!(u.segment_entry(Vec2::new(5.0, 4.0), Vec2::new(5.0, -3.0)).is_none(), "out of the mouth");
    }

    #[test]
    fn polygon_ray_hits_nearest_edge() {
        let hit = square().ray_cast(Vec2::new(-5.0, 5.0), Vec2::new(30.0, 0.0)).expect("hits");
        assert!((hit.t - 5.0 / 30.0).abs() < 1e-6);
        assert_eq!(hit.normal, Vec2::NEG_X);
    }
}
