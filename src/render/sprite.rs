//! Pre-rendered images copied onto the frame per agent: tiny-skia draws each shape once (an
//! agent's triangle per heading bucket, a stuck agent's ring per radius), and a byte loop blends
//! the copies. A sprite keeps only its runs of visible pixels, so a ring costs its outline, not
//! its box.

use glam::Vec2;
use tiny_skia::{FillRule, PathBuilder, Pixmap, Stroke, Transform};

use super::paint::paint;

/// A run of visible pixels on one row of a sprite: columns `start..end` of row `row`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Run {
    row: u16,
    start: u16,
    end: u16,
}

/// A pre-rendered image: premultiplied RGBA, cropped to its visible pixels.
#[derive(Clone, Debug, Default)]
pub(super) struct Sprite {
    /// Offset of the image's top-left pixel from the pixel it is centred on.
    left: i32,
    top: i32,
    width: usize,
    height: usize,
    data: Vec<u8>,
    /// The runs of visible pixels, row by row (a triangle leaves half of its box empty, a ring
    /// all of its inside).
    runs: Vec<Run>,
}

/// Draws `sprite` centred on pixel `(x, y)` of an opaque `w × h` RGBA frame with
/// premultiplied source-over, clipped to the frame.
pub(super) fn blit_over(frame: &mut [u8], w: i32, h: i32, sprite: &Sprite, x: i32, y: i32) {
    let left = x + sprite.left;
    let top = y + sprite.top;
    let x0 = left.max(0);
    let x1 = (left + sprite.width as i32).min(w);
    let y0 = top.max(0);
    let y1 = (top + sprite.height as i32).min(h);
    if x0 >= x1 || y0 >= y1 {
        return;
    }
    for run in &sprite.runs {
        let row = top + i32::from(run.row);
        if row < y0 || row >= y1 {
            continue;
        }
        // The run's columns in frame coordinates, clipped to the frame.
        let from = (left + i32::from(run.start)).max(x0);
        let to = (left + i32::from(run.end)).min(x1);
        if from >= to {
            continue;
        }
        let span = (to - from) as usize * 4;
        let src_at = (usize::from(run.row) * sprite.width + (from - left) as usize) * 4;
        let dst_at = (row as usize * w as usize + from as usize) * 4;
        let src = &sprite.data[src_at..src_at + span];
        let dst = &mut frame[dst_at..dst_at + span];
        for (d, s) in dst.chunks_exact_mut(4).zip(src.chunks_exact(4)) {
            let alpha = s[3];
            if alpha == 0 {
                continue;
            }
            if alpha == 255 {
                d[..3].copy_from_slice(&s[..3]);
                continue;
            }
            let inverse = 255 - u32::from(alpha);
            for k in 0..3 {
                d[k] = s[k].saturating_add(div255(u32::from(d[k]) * inverse));
            }
        }
    }
}

/// `x / 255` rounded, for `x ≤ 255 · 255`.
#[inline]
fn div255(x: u32) -> u8 {
    let x = x + 128;
    ((x + (x >> 8)) >> 8) as u8
}

/// A square pixmap of `2·half + 1` px whose pixel `(half, half)` is the one a sprite is
/// centred on.
fn canvas(reach: f32) -> Option<(Pixmap, i32)> {
    let half = (reach + 2.0).ceil() as i32;
    let side = (2 * half + 1) as u32;
    Pixmap::new(side, side).map(|p| (p, half))
}

/// An agent: an oriented, notched triangle for heading `angle` (radians), `radius_px` device px
/// in body radius, outlined in a darker shade from 3 px up.
pub(super) fn agent_sprite(rgb: [u8; 3], radius_px: f32, angle: f32) -> Sprite {
    let reach = 1.5 * radius_px;
    let Some((mut pixmap, half)) = canvas(reach) else {
        return Sprite::default();
    };
    let (sin, cos) = (libm::sinf(angle), libm::cosf(angle));
    // Pixel (half, half) is the agent's pixel; its centre is at half + 0.5.
    let centre = Vec2::splat(half as f32 + 0.5);
    let corner = |forward: f32, side: f32| {
        let p = centre + Vec2::new(cos, sin) * forward + Vec2::new(-sin, cos) * side;
        (p.x, p.y)
    };
    let mut pb = PathBuilder::new();
    let tip = corner(reach, 0.0);
    let left = corner(-radius_px, 0.9 * radius_px);
    let notch = corner(-0.5 * radius_px, 0.0);
    let right = corner(-radius_px, -0.9 * radius_px);
    pb.move_to(tip.0, tip.1);
    pb.line_to(left.0, left.1);
    pb.line_to(notch.0, notch.1);
    pb.line_to(right.0, right.1);
    pb.close();
    if let Some(path) = pb.finish() {
        pixmap.fill_path(&path, &paint(rgb, 255), FillRule::Winding, Transform::identity(), None);
        if radius_px >= 3.0 {
            let dark = rgb.map(|c| (u16::from(c) * 3 / 5) as u8);
            let stroke = Stroke { width: (0.12 * radius_px).clamp(1.0, 2.0), ..Stroke::default() };
            pixmap.stroke_path(&path, &paint(dark, 230), &stroke, Transform::identity(), None);
        }
    }
    crop(&pixmap, half)
}

/// A ring of radius `radius_px` (device px, to the stroke's middle), stroked `width` px wide.
pub(super) fn ring_sprite(rgb: [u8; 3], alpha: u8, radius_px: f32, width: f32) -> Sprite {
    let Some((mut pixmap, half)) = canvas(radius_px + 0.5 * width) else {
        return Sprite::default();
    };
    let c = half as f32 + 0.5;
    if let Some(path) = PathBuilder::from_circle(c, c, radius_px.max(0.5)) {
        let stroke = Stroke { width, ..Stroke::default() };
        pixmap.stroke_path(&path, &paint(rgb, alpha), &stroke, Transform::identity(), None);
    }
    crop(&pixmap, half)
}

/// The smallest sub-image holding every non-transparent pixel of `pixmap`, with its runs.
fn crop(pixmap: &Pixmap, half: i32) -> Sprite {
    let (w, h) = (pixmap.width() as usize, pixmap.height() as usize);
    let data = pixmap.data();
    let visible = |x: usize, y: usize| data[(y * w + x) * 4 + 3] != 0;
    let rows: Vec<usize> = (0..h).filter(|&y| (0..w).any(|x| visible(x, y))).collect();
    let cols: Vec<usize> = (0..w).filter(|&x| (0..h).any(|y| visible(x, y))).collect();
    let (Some(&y0), Some(&y1), Some(&x0), Some(&x1)) = (rows.first(), rows.last(), cols.first(), cols.last())
    else {
        return Sprite::default();
    };
    let (width, height) = (x1 - x0 + 1, y1 - y0 + 1);
    let mut out = Vec::with_capacity(width * height * 4);
    let mut runs = Vec::new();
    for y in y0..=y1 {
        out.extend_from_slice(&data[(y * w + x0) * 4..(y * w + x1 + 1) * 4]);
        let mut x = x0;
        while x <= x1 {
            if !visible(x, y) {
                x += 1;
                continue;
            }
            let start = x;
            while x <= x1 && visible(x, y) {
                x += 1;
            }
            runs.push(Run { row: (y - y0) as u16, start: (start - x0) as u16, end: (x - x0) as u16 });
        }
    }
    Sprite { left: x0 as i32 - half, top: y0 as i32 - half, width, height, data: out, runs }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The opaque `w × h` frame with `sprite` blitted at `(x, y)` over grey.
    fn blitted(sprite: &Sprite, w: i32, h: i32, x: i32, y: i32) -> Vec<u8> {
        let mut frame = vec![128u8; (w * h * 4) as usize];
        blit_over(&mut frame, w, h, sprite, x, y);
        frame
    }

    #[test]
    fn a_ring_keeps_only_its_outline_and_leaves_its_inside_alone() {
        let ring = ring_sprite([0xe0, 0x10, 0x10], 230, 8.0, 2.0);
        let visible: usize = ring.runs.iter().map(|r| usize::from(r.end - r.start)).sum();
        assert!(visible < ring.width * ring.height / 2, "{visible} of {}×{}", ring.width, ring.height);
        let frame = blitted(&ring, 40, 40, 20, 20);
        let at = |x: usize, y: usize| &frame[(y * 40 + x) * 4..(y * 40 + x) * 4 + 4];
        assert_eq!(at(20, 20), [128, 128, 128, 128], "the centre is untouched");
        assert!(at(28, 20)[0] > 180 && at(28, 20)[1] < 90, "on the ring: {:?}", at(28, 20));
    }

    #[test]
    fn sprites_clip_at_every_edge() {
        let ring = ring_sprite([0, 0, 0], 255, 6.0, 2.0);
        for (x, y) in [(-3, 5), (5, -3), (12, 5), (5, 12), (-50, -50), (60, 60)] {
            let frame = blitted(&ring, 10, 10, x, y);
            assert_eq!(frame.len(), 400, "({x}, {y})");
        }
        let inside = blitted(&ring, 10, 10, 5, 5);
        assert!(inside.chunks(4).any(|p| p[0] == 0), "a ring centred in the frame shows");
    }
}
