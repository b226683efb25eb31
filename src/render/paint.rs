//! Drawing primitives shared by the layers and the overlays: the scene → canvas transform, a
//! trail segment written straight into a pixel buffer, and a stroked scene path.

use glam::Vec2;
use tiny_skia::{Color, Paint, PathBuilder, PixmapMut, Stroke, StrokeDash, Transform};

/// How scene px map to canvas px: `canvas = scene * scale + offset`. The scene is fitted into the
/// canvas keeping its aspect ratio, centred, with letterbox bands on the spare sides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewTransform {
    /// Device px per scene px.
    pub scale: f32,
    /// Canvas x of scene x = 0 (device px).
    pub offset_x: f32,
    /// Canvas y of scene y = 0 (device px).
    pub offset_y: f32,
}

impl ViewTransform {
    /// The transform fitting a `scene_width × scene_height` scene into a canvas, centred.
    pub fn fit(scene_width: f32, scene_height: f32, canvas_width: u32, canvas_height: u32) -> Self {
        let (cw, ch) = (canvas_width as f32, canvas_height as f32);
        if !(scene_width > 0.0 && scene_height > 0.0) {
            return Self { scale: 1.0, offset_x: 0.0, offset_y: 0.0 };
        }
        let scale = (cw / scene_width).min(ch / scene_height);
        Self {
            scale,
            offset_x: 0.5 * (cw - scene_width * scale),
            offset_y: 0.5 * (ch - scene_height * scale),
        }
    }

    /// Scene px → canvas px.
    pub fn to_canvas(&self, p: Vec2) -> Vec2 {
        p * self.scale + Vec2::new(self.offset_x, self.offset_y)
    }

    /// Canvas px → scene px (for pointer input).
    pub fn to_scene(&self, p: Vec2) -> Vec2 {
        (p - Vec2::new(self.offset_x, self.offset_y)) / self.scale
    }

    pub(super) fn transform(&self) -> Transform {
        Transform::from_row(self.scale, 0.0, 0.0, self.scale, self.offset_x, self.offset_y)
    }
}

/// Blends a one-pixel anti-aliased line (Xiaolin Wu's algorithm) from `a` to `b` (canvas px)
/// into an opaque `w × h` RGBA layer with opacity `alpha`. The pixel column or row of `b` is
/// left out: the agent's next segment starts there, and drawing it twice would darken every join.
pub(super) fn draw_segment(layer: &mut [u8], w: usize, h: usize, a: Vec2, b: Vec2, rgb: [u8; 3], alpha: u8) {
    // Pixel (i, j) covers [i, i + 1) × [j, j + 1): shift so that pixel centres are integers.
    let (a, b) = (a - Vec2::splat(0.5), b - Vec2::splat(0.5));
    let d = b - a;
    if !d.is_finite() || d.abs().max_element() > (w + h) as f32 {
        return;
    }
    let steep = d.y.abs() > d.x.abs();
    // Work along the major axis `u`, with `v` the minor one.
    let (au, av, bu, bv) = if steep { (a.y, a.x, b.y, b.x) } else { (a.x, a.y, b.x, b.y) };
    let slope = if bu != au { (bv - av) / (bu - au) } else { 0.0 };
    let (first, last) = (au.round() as i64, bu.round() as i64);
    let range = if first <= last { first..last } else { last + 1..first + 1 };
    let mut plot = |u: i64, v: i64, coverage: f32| {
        let (x, y) = if steep { (v, u) } else { (u, v) };
        if x < 0 || y < 0 || x >= w as i64 || y >= h as i64 {
            return;
        }
        let k = (coverage * f32::from(alpha)) as u32;
        let at = (y as usize * w + x as usize) * 4;
        for (c, &s) in layer[at..at + 3].iter_mut().zip(&rgb) {
            *c = ((u32::from(*c) * (255 - k) + u32::from(s) * k + 127) / 255) as u8;
        }
    };
    for u in range {
        let v = av + slope * (u as f32 - au);
        let base = v.floor();
        let frac = v - base;
        plot(u, base as i64, 1.0 - frac);
        plot(u, base as i64 + 1, frac);
    }
}

/// Strokes a path given in scene px with a width and dash pattern in device px (width 0 is a
/// one-pixel hairline).
pub(super) fn stroke_scene_path(
    pixmap: &mut PixmapMut,
    pb: PathBuilder,
    view: ViewTransform,
    rgb: [u8; 3],
    alpha: u8,
    width: f32,
    dash: Option<[f32; 2]>,
) {
    let Some(path) = pb.finish().and_then(|p| p.transform(view.transform())) else { return };
    let dash = dash.and_then(|[on, off]| StrokeDash::new(vec![on, off], 0.0));
    let stroke = Stroke { width, dash, ..Stroke::default() };
    pixmap.stroke_path(&path, &paint(rgb, alpha), &stroke, Transform::identity(), None);
}

pub(super) fn color(rgb: [u8; 3], alpha: u8) -> Color {
    Color::from_rgba8(rgb[0], rgb[1], rgb[2], alpha)
}

pub(super) fn paint(rgb: [u8; 3], alpha: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(color(rgb, alpha));
    p.anti_alias = true;
    p
}
