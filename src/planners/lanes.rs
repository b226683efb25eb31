//! Four agents at a time: 2-D vectors with one `Vec4` per axis, for planner passes that apply
//! the same steering arithmetic to every agent.
//!
//! Every operation here is the lane-wise copy of the scalar `Vec2` code it replaces, one
//! correctly rounded IEEE operation per lane in the same order, so a lane computes bit for bit
//! what the scalar code computes (tests check it). Branches become masks: both sides are
//! computed and [`Vec4::select`] keeps one, so a discarded side may hold NaN or infinity.

use glam::{BVec4A, Vec2, Vec4};

/// The number of agents in a [`Lanes2`].
pub const LANES: usize = 4;

/// Four 2-D vectors, lane `j` of `x` and `y` being vector `j`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes2 {
    /// The x coordinates.
    pub x: Vec4,
    /// The y coordinates.
    pub y: Vec4,
}

impl Lanes2 {
    /// Four zero vectors.
    pub const ZERO: Self = Self { x: Vec4::ZERO, y: Vec4::ZERO };

    /// The same vector in every lane.
    #[inline]
    pub fn splat(v: Vec2) -> Self {
        Self { x: Vec4::splat(v.x), y: Vec4::splat(v.y) }
    }

    /// Lane `j` from `f(j)`.
    #[inline]
    pub fn from_fn(mut f: impl FnMut(usize) -> Vec2) -> Self {
        let v: [Vec2; LANES] = std::array::from_fn(&mut f);
        Self { x: Vec4::new(v[0].x, v[1].x, v[2].x, v[3].x), y: Vec4::new(v[0].y, v[1].y, v[2].y, v[3].y) }
    }

    /// Vector `j`.
    #[inline]
    pub fn lane(self, j: usize) -> Vec2 {
        Vec2::new(self.x[j], self.y[j])
    }

    /// `Vec2::length_squared` per lane.
    #[inline]
    pub fn length_squared(self) -> Vec4 {
        self.x * self.x + self.y * self.y
    }

    /// `Vec2::length` per lane (the hardware square root: see [`crate::model::geometry::length`]).
    #[inline]
    pub fn length(self) -> Vec4 {
        sqrt(self.length_squared())
    }

    /// `v * s` per lane.
    #[inline]
    pub fn scale(self, s: Vec4) -> Self {
        Self { x: self.x * s, y: self.y * s }
    }

    /// `if mask { a } else { b }` per lane.
    #[inline]
    pub fn select(mask: BVec4A, a: Self, b: Self) -> Self {
        Self { x: Vec4::select(mask, a.x, b.x), y: Vec4::select(mask, a.y, b.y) }
    }

    /// [`super::limit`] per lane.
    #[inline]
    pub fn limit(self, max: f32) -> Self {
        let len2 = self.length_squared();
        let over = len2.cmpgt(Vec4::splat(max * max)) & len2.cmpgt(Vec4::ZERO);
        Self::select(over, self.scale(Vec4::splat(max) / sqrt(len2)), self)
    }
}

impl std::ops::Add for Lanes2 {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self { x: self.x + rhs.x, y: self.y + rhs.y }
    }
}

impl std::ops::Sub for Lanes2 {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self { x: self.x - rhs.x, y: self.y - rhs.y }
    }
}

/// The square root per lane, in hardware (glam's `Vec4::sqrt` goes through libm: see
/// [`crate::model::geometry::length`]).
#[inline]
pub fn sqrt(x: Vec4) -> Vec4 {
    Vec4::from_array(x.to_array().map(f32::sqrt))
}

/// `x.clamp(min, max)` per lane (`f32::clamp`: below `min` → `min`, then above `max` → `max`).
#[inline]
pub fn clamp(x: Vec4, min: f32, max: f32) -> Vec4 {
    let (min, max) = (Vec4::splat(min), Vec4::splat(max));
    let x = Vec4::select(x.cmplt(min), min, x);
    Vec4::select(x.cmpgt(max), max, x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::limit;

    #[test]
    fn lanes_compute_what_the_scalar_code_computes() {
        let samples = [
            Vec2::new(3.0, -4.0),
            Vec2::new(1e-20, 0.0),
            Vec2::ZERO,
            Vec2::new(-0.7, 0.3),
            Vec2::new(123.456, 7.89e-3),
            Vec2::new(-5.5, -0.0),
            Vec2::new(0.1, 0.2),
            Vec2::new(2.0, 2.0),
        ];
        for window in samples.windows(LANES) {
            let v = Lanes2::from_fn(|j| window[j]);
            let limited = v.limit(1.5);
            let lengths = v.length();
            for (j, &s) in window.iter().enumerate() {
                assert_eq!(
                    limited.lane(j).to_array().map(f32::to_bits),
                    limit(s, 1.5).to_array().map(f32::to_bits)
                );
                assert_eq!(lengths[j].to_bits(), s.length().to_bits());
                assert_eq!(clamp(Vec4::splat(s.x), 0.1, 1.0)[j].to_bits(), s.x.clamp(0.1, 1.0).to_bits());
            }
        }
    }
}
