//! Drawing primitives shared by the layers and the overlays: the scene → canvas transform, the
//! render themes (what a theme changes: field colours, trail width and shade, agent size), a
//! trail segment written straight into a pixel buffer, and a stroked scene path. The default
//! group colours (Okabe–Ito) are scene data: `model::palette`.

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

/// A render theme: how the same scene is drawn. The page chooses it (URL option `theme=`, a
/// toggle); it is not part of the scene, so links and runs are the same in every theme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Theme {
    /// The everyday look: a warm light field, two-pixel trails in the group colour darkened to
    /// 47 % (every Okabe–Ito colour, yellow included, at ≥ 3:1 against the field, so trails
    /// stay visible on a washed-out projector), agents at their size.
    #[default]
    Standard,
    /// For a projector or a screen seen from the back of a room: a white field, darker
    /// obstacles, thick dark trails, agents drawn larger, no grid.
    Projector,
}

impl Theme {
    /// Every theme, in the order the page offers them.
    pub const ALL: [Theme; 2] = [Theme::Standard, Theme::Projector];

    /// The name in URLs and the wasm API.
    pub fn name(self) -> &'static str {
        match self {
            Theme::Standard => "standard",
            Theme::Projector => "projector",
        }
    }

    /// The theme called `name` (as [`Theme::name`] spells it), or `None`.
    pub fn from_name(name: &str) -> Option<Theme> {
        Theme::ALL.into_iter().find(|t| t.name() == name)
    }

    /// What this theme draws.
    pub fn style(self) -> Style {
        match self {
            Theme::Standard => STANDARD,
            Theme::Projector => PROJECTOR,
        }
    }
}

/// The colours and sizes a [`Theme`] sets (colours RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    /// The scene rectangle.
    pub background: [u8; 3],
    /// The canvas outside the scene rectangle.
    pub letterbox: [u8; 3],
    /// Grid lines; `None` leaves the grid out.
    pub grid: Option<[u8; 3]>,
    /// Obstacle fill.
    pub obstacle: [u8; 3],
    /// Obstacle outline.
    pub obstacle_outline: [u8; 3],
    /// Width of a trail (whole device px, ≥ 1).
    pub trail_width_px: u32,
    /// Opacity of a fresh trail segment (out of 255).
    pub trail_alpha: u8,
    /// How much of the group colour a trail keeps (out of 255); the rest is black.
    pub trail_keep: u8,
    /// Agents are drawn this many times their body radius.
    pub agent_scale: f32,
    /// ... and at least this radius (device px).
    pub min_agent_radius_px: f32,
}

/// The [`Theme::Standard`] style. Its trails were 1 px at 35 % opacity in the full group colour
/// (1.1–1.7:1 against the field: gone on a projector, issue 27); now 2 px at 86 % opacity at
/// 47 % brightness: 3.8:1 (yellow) to 8:1 (blue) where a fresh trail covers a pixel fully
/// (tests/e2e/trail-contrast.test.mjs measures the page's screenshot).
pub const STANDARD: Style = Style {
    background: [0xf6, 0xf5, 0xf0],
    letterbox: [0xd8, 0xd8, 0xd3],
    grid: Some([0xe4, 0xe2, 0xda]),
    obstacle: [0x5b, 0x63, 0x70],
    obstacle_outline: [0x2c, 0x31, 0x38],
    trail_width_px: 2,
    trail_alpha: 220,
    trail_keep: 120,
    agent_scale: 1.0,
    min_agent_radius_px: 0.0,
};

/// The [`Theme::Projector`] style: trails three px wide at 80 % opacity in the group colour at
/// half brightness, agents 1.6 times as large and at least 4 px in radius.
pub const PROJECTOR: Style = Style {
    background: [0xff, 0xff, 0xff],
    letterbox: [0xc8, 0xc8, 0xc8],
    grid: None,
    obstacle: [0x33, 0x33, 0x33],
    obstacle_outline: [0x00, 0x00, 0x00],
    trail_width_px: 3,
    trail_alpha: 205,
    trail_keep: 128,
    agent_scale: 1.6,
    min_agent_radius_px: 4.0,
};

impl Style {
    /// The trail colour of a group drawn in `rgb`.
    pub fn trail_color(&self, rgb: [u8; 3]) -> [u8; 3] {
        rgb.map(|c| ((u16::from(c) * u16::from(self.trail_keep) + 127) / 255) as u8)
    }
}

/// [`draw_segment`] `width` px wide: that many one-pixel lines side by side along the minor axis
/// (Wu lines one pixel apart tile: their coverages add up to one between them).
#[allow(clippy::too_many_arguments, reason = "a pixel loop's plain inputs")]
pub(super) fn draw_wide_segment(
    layer: &mut [u8],
    w: usize,
    h: usize,
    a: Vec2,
    b: Vec2,
    rgb: [u8; 3],
    alpha: u8,
    width: u32,
) {
    if width <= 1 {
        draw_segment(layer, w, h, a, b, rgb, alpha);
        return;
    }
    let d = b - a;
    let across = if d.y.abs() > d.x.abs() { Vec2::X } else { Vec2::Y };
    let first = -0.5 * (width - 1) as f32;
    for k in 0..width {
        let offset = across * (first + k as f32);
        draw_segment(layer, w, h, a + offset, b + offset, rgb, alpha);
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
