//! Rasterises a running [`World`] into one reusable RGBA frame: a cached static base, an
//! incremental trail layer, then goals, spawn regions, agents (pre-rendered sprites) and the
//! selection.
//!
//! Costs drive the shape. tiny-skia spends microseconds per anti-aliased shape, so it only draws
//! what is rare: the base layer (rebuilt when the obstacles or the size change), goals, spawn
//! regions, the selection, and a small set of agent sprites (one per group and heading bucket).
//! What scales with the agent count is written directly: each frame's new trail segments (Wu
//! lines onto the persistent trail layer), the agents (sprites copied with a premultiplied-over
//! byte loop, or single pixels when they are smaller than two device pixels), and the fading
//! (a byte loop over a stripe of rows). Every layer is opaque, so the premultiplied bytes are
//! also the straight-alpha bytes `ImageData` wants.
//!
//! Layer: render. Uses `model`, `spatial`, `planners` (explanations, planned paths) and `sim`.

mod overlay;
mod paint;
mod sprite;

pub use overlay::{Overlays, ARROW_COLORS};
use paint::{color, draw_wide_segment, paint, stroke_scene_path};
pub use paint::{Style, Theme, ViewTransform, PROJECTOR, STANDARD};
use sprite::{agent_sprite, blit_over, Sprite};

use crate::model::edit::ItemRef;
use crate::model::geometry::Obstacle;
use crate::model::params::PlannerConfig;
use crate::model::scene::{parse_color, Hill, Scene};
use crate::sim::world::World;
use glam::Vec2;
use std::f32::consts::TAU;
use tiny_skia::{FillRule, Path, PathBuilder, PixmapMut, Rect, Stroke, Transform};

/// Fill colour of obstacles (RGB, standard theme). Tests and page checks look for it at an
/// obstacle's centre.
pub const OBSTACLE_COLOR: [u8; 3] = STANDARD.obstacle;
/// Outline colour of obstacles (RGB, standard theme), darker than the fill.
pub const OBSTACLE_OUTLINE_COLOR: [u8; 3] = STANDARD.obstacle_outline;
/// Background of the scene rectangle (RGB, standard theme).
pub const BACKGROUND_COLOR: [u8; 3] = STANDARD.background;
/// Canvas area outside the scene rectangle when the aspect ratios differ (RGB, standard theme).
pub const LETTERBOX_COLOR: [u8; 3] = STANDARD.letterbox;
/// Faint grid lines (RGB, standard theme; the projector theme has none).
pub const GRID_COLOR: [u8; 3] = match STANDARD.grid {
    Some(rgb) => rgb,
    None => STANDARD.background,
};
/// Goals no group heads for (RGB); goals in use take their first group's colour.
pub const GOAL_COLOR: [u8; 3] = [0x3a, 0x8a, 0x4f];
/// Path segments that cross an obstacle (RGB): an edited IGSA path the user should fix.
pub const CROSSING_COLOR: [u8; 3] = [0xe0, 0x1a, 0x1a];
/// Radius of a draggable waypoint handle (device px).
pub const WAYPOINT_HANDLE_PX: f32 = 5.0;
/// Outline of the selected item (RGB).
pub const SELECTION_COLOR: [u8; 3] = [0xff, 0x8c, 0x00];
/// Colour of hill shading (earth brown).
pub const HILL_COLOR: [u8; 3] = [0x8a, 0x6a, 0x3c];
/// Default share of a trail's visibility lost per fade tick ([`FADE_STEPS`] steps).
pub const DEFAULT_TRAIL_FADE: f32 = 0.01;
/// Steps per fade tick: trails fade with the steps simulated, by `trail_fade` every this many
/// steps (a frame at the page's default speed, so scenes look as they did when trails faded per
/// frame), never by a frame drawn again without a step (a print, a resize, a paused redraw).
pub const FADE_STEPS: u32 = 2;
/// Number of pre-rendered headings per group: 32 steps of 11.25°.
pub const HEADING_BUCKETS: usize = 32;
/// Largest canvas side in device px; larger requests are clamped (and smaller than 1 become 1).
pub const MAX_CANVAS_SIDE: u32 = 8192;
/// Deepest zoom, as a multiple of the fitted scale: close enough to watch a few agents pass a
/// gap, while a group's 32 heading sprites stay small (an agent of 5 scene px on a 1366 px
/// canvas is ~70 device px in radius at 8×, ~2.4 MB of sprites; at 32× it would be ~40 MB).
pub const MAX_ZOOM: f32 = 8.0;

/// Grid spacing in scene px.
const GRID_SPACING: f32 = 50.0;
/// The grid is left out when its lines would be closer than this (device px).
const MIN_GRID_SPACING_PX: f32 = 6.0;
/// A trail segment is drawn once an agent has moved its body radius (clamped to this range,
/// device px) from its last drawn point: the open end stays hidden under the agent, stationary
/// agents cost nothing, and fewer, longer segments are cheaper and do not darken at the joins.
const TRAIL_SEGMENT_PX: (f32, f32) = (1.0, 4.0);
/// Between frames (steps of a multi-step advance, a rebuilt trail) a segment spans at least this
/// many device px: half the segments of small agents, and a 2 px chord cannot cut through
/// anything the agent went round. A frame after a single step draws exactly as before: what the
/// step did not trace, the frame does with [`TRAIL_SEGMENT_PX`].
const TRACED_SEGMENT_MIN_PX: f32 = 2.0;
/// Agents are drawn in bands of 2^this device rows, top to bottom, so that consecutive sprites
/// touch nearby frame memory (10,000 agents in id order hit the cache far less well).
const BAND_SHIFT: u32 = 3;
/// Fading is spread over this many ticks: each tick fades every n-th row by n ticks' worth (an
/// eighth of a full pass per tick; neighbouring rows differ by at most 7 ticks' fade). A frame
/// after many ticks fades each row once by all of its ticks, so a frame costs at most one pass.
const FADE_ROW_PERIOD: u32 = 8;
/// Agents whose body radius is below this (device px) are drawn as single pixels.
const DOT_RADIUS_PX: f32 = 1.0;
/// Trail segments traced between two frames wait in a buffer so that they are drawn after the
/// frame's fade (a single step per frame then draws exactly what it always drew); past this many
/// (about 400 kB) they are drawn at once, so `step(5000)` never holds more than one buffer.
const PENDING_SEGMENTS_MAX: usize = 16_384;
/// A timeline jump redraws the trails of at most this many recorded agent-steps before the new
/// step (50 steps of 10,000 agents, 625 of the 80 in `pillars`): about 125,000 segments,
/// tens of milliseconds, so scrubbing stays fluid.
const TRAIL_REBUILD_AGENT_STEPS: usize = 500_000;

/// What the base layer was drawn from: it is rebuilt when any of this changes.
#[derive(Clone, Debug, PartialEq)]
struct BaseKey {
    width: f32,
    height: f32,
    obstacles: Vec<Obstacle>,
    hills: Vec<Hill>,
}

impl BaseKey {
    fn matches(&self, scene: &Scene) -> bool {
        self.width == scene.width
            && self.height == scene.height
            && self.obstacles == scene.obstacles
            && self.hills == scene.hills
    }
}

/// A zoomed-in view: the scene point at the canvas centre and the scale as a multiple of the
/// fitted one. Only the view changes: the run, its digest and the scene are the same at any zoom.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Zoom {
    /// Scene point drawn at the canvas centre (scene px), kept inside the scene.
    center: Vec2,
    /// Scale over the fitted scale, in (1, [`MAX_ZOOM`]].
    factor: f32,
}

/// An agent ready to draw: its pixel, group and heading bucket.
#[derive(Clone, Copy, Debug, Default)]
struct Placed {
    x: i32,
    y: i32,
    group: u32,
    heading: u8,
}

/// A trail segment traced but not drawn yet: canvas endpoints, colour and opacity.
#[derive(Clone, Copy, Debug)]
struct Segment {
    from: Vec2,
    to: Vec2,
    rgb: [u8; 3],
    alpha: u8,
    /// The fade tick it was traced at: drawn later, it is drawn as faded as the ticks since.
    tick: u32,
}

/// The sprites of one group, valid for one colour and one device radius.
#[derive(Clone, Debug)]
struct GroupSprites {
    color: [u8; 3],
    radius_px: f32,
    /// Empty when the agents are drawn as dots.
    headings: Vec<Sprite>,
}

/// Renders worlds into one reusable RGBA frame of `width × height` device px.
pub struct Renderer {
    width: u32,
    height: u32,
    /// The frame JS shows: opaque RGBA.
    frame: Vec<u8>,
    /// Background, grid and obstacles.
    base: Vec<u8>,
    /// Base plus the trails drawn so far.
    trails: Vec<u8>,
    base_key: Option<BaseKey>,
    view: ViewTransform,
    /// The part of the scene shown when zoomed in (`None`: the whole scene, fitted).
    zoom: Option<Zoom>,
    /// The scene size the view was last fitted to (scene px; zero before the first frame).
    scene_size: Vec2,
    /// What the current theme draws.
    style: Style,
    theme: Theme,
    trails_on: bool,
    trail_fade: f32,
    /// Set when the trail layer must restart from the base at the next frame.
    trails_stale: bool,
    /// Device position of each agent where its trail was last drawn to.
    last_drawn: Vec<Vec2>,
    /// Segments traced since the last frame (see [`PENDING_SEGMENTS_MAX`]).
    pending: Vec<Segment>,
    /// Per group, reused: trail colour and the distance (device px) that makes a new segment.
    trail_groups: Vec<([u8; 3], f32)>,
    /// Step count of the world at the last frame (a smaller one means the run was reset).
    last_step: u32,
    /// Heading bucket of each agent, kept while it stands still.
    heading: Vec<u8>,
    /// The fade tick (step / [`FADE_STEPS`]) the trail layer has been faded up to.
    faded_tick: u32,
    sprites: Vec<GroupSprites>,
    selection: Option<ItemRef>,
    /// Diagnosis overlays that are on, and the agent being inspected.
    overlays: Overlays,
    inspected: Option<u32>,
    /// Reused per frame: agents placed on the canvas, their drawing order, band counts.
    placed: Vec<Placed>,
    drawing_order: Vec<u32>,
    band_counts: Vec<u32>,
    /// Stuck-ring sprites by radius (see `overlay::Target::rings`).
    rings: Vec<(u32, Sprite)>,
}

impl Renderer {
    /// A renderer for a canvas of `width × height` device px (clamped to 1…[`MAX_CANVAS_SIDE`]).
    pub fn new(width: u32, height: u32) -> Self {
        let mut r = Self {
            width: 0,
            height: 0,
            frame: Vec::new(),
            base: Vec::new(),
            trails: Vec::new(),
            base_key: None,
            view: ViewTransform { scale: 1.0, offset_x: 0.0, offset_y: 0.0 },
            zoom: None,
            scene_size: Vec2::ZERO,
            style: STANDARD,
            theme: Theme::Standard,
            trails_on: true,
            trail_fade: DEFAULT_TRAIL_FADE,
            trails_stale: true,
            last_drawn: Vec::new(),
            pending: Vec::new(),
            trail_groups: Vec::new(),
            last_step: 0,
            heading: Vec::new(),
            faded_tick: 0,
            sprites: Vec::new(),
            selection: None,
            overlays: Overlays::default(),
            inspected: None,
            placed: Vec::new(),
            drawing_order: Vec::new(),
            band_counts: Vec::new(),
            rings: Vec::new(),
        };
        r.resize(width, height);
        r
    }

    /// Changes the canvas size (device px, clamped like [`Renderer::new`]). The next frame
    /// rebuilds the base layer for the new size; trails restart.
    pub fn resize(&mut self, width: u32, height: u32) {
        let width = width.clamp(1, MAX_CANVAS_SIDE);
        let height = height.clamp(1, MAX_CANVAS_SIDE);
        if width == self.width && height == self.height {
            return;
        }
        self.width = width;
        self.height = height;
        let len = width as usize * height as usize * 4;
        for layer in [&mut self.frame, &mut self.base, &mut self.trails] {
            layer.clear();
            layer.resize(len, 255);
        }
        self.base_key = None;
        self.trails_stale = true;
        self.sprites.clear();
    }

    /// Frame width in device px.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Frame height in device px.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The last rendered frame: `width × height` RGBA pixels, row-major, every alpha 255 (so
    /// premultiplied and straight alpha agree).
    pub fn pixels(&self) -> &[u8] {
        &self.frame
    }

    /// The scene → canvas mapping used by the last frame.
    pub fn view(&self) -> ViewTransform {
        self.view
    }

    /// Draws in `theme` from the next frame on (the base layer, the sprites and the trails are
    /// redrawn in it; trails restart).
    pub fn set_theme(&mut self, theme: Theme) {
        if theme == self.theme {
            return;
        }
        self.theme = theme;
        self.style = theme.style();
        self.base_key = None;
        self.trails_stale = true;
        self.sprites.clear();
    }

    /// The current theme.
    pub fn theme(&self) -> Theme {
        self.theme
    }

    /// Turns trails on or off. Turning them on starts from a clean layer.
    pub fn set_trails(&mut self, on: bool) {
        if on && !self.trails_on {
            self.trails_stale = true;
        }
        self.trails_on = on;
    }

    /// Whether trails are drawn.
    pub fn trails(&self) -> bool {
        self.trails_on
    }

    /// Share of a trail's visibility lost every [`FADE_STEPS`] steps: 0 keeps trails forever, 1
    /// shows only the newest segments. Values outside 0…1 are clamped; NaN is ignored.
    pub fn set_trail_fade(&mut self, fade: f32) {
        if !fade.is_nan() {
            self.trail_fade = fade.clamp(0.0, 1.0);
        }
    }

    /// The current trail fade per [`FADE_STEPS`] steps.
    pub fn trail_fade(&self) -> f32 {
        self.trail_fade
    }

    /// Erases all trails; they restart from the agents' positions at the next frame. Call it
    /// when a different run is shown: a reset or a new agent count is noticed by itself, but a
    /// new scene with as many agents, still at step 0, would otherwise draw jumps.
    pub fn clear_trails(&mut self) {
        self.trails_stale = true;
    }

    /// Outlines an item of the scene (or nothing). An index that does not exist draws nothing.
    pub fn set_selection(&mut self, item: Option<ItemRef>) {
        self.selection = item;
    }

    /// Chooses the diagnosis overlays (see [`Overlays`]).
    pub fn set_overlays(&mut self, overlays: Overlays) {
        self.overlays = overlays;
    }

    /// The diagnosis overlays that are on.
    pub fn overlays(&self) -> Overlays {
        self.overlays
    }

    /// Inspects an agent (its explanation and cost landscape are drawn) or none. An id that does
    /// not exist draws nothing.
    pub fn set_inspected(&mut self, agent: Option<u32>) {
        self.inspected = agent;
    }

    /// The inspected agent.
    pub fn inspected(&self) -> Option<u32> {
        self.inspected
    }

    /// Adds the trail of the step `world` just took. Call it after every step of a multi-step
    /// advance: without it the next frame joins the old and new positions by a straight chord,
    /// through whatever the agents went round. An agent adds a segment only once it has moved
    /// a body radius (1–4 device px) from its last one, so the cost is a comparison per agent and
    /// step plus the segments, and memory does not grow with the steps. Does nothing with trails
    /// off. After a new run, a reset or a resize the trails start here, so a script that loads a
    /// scene and steps it before any frame still gets the whole trail.
    pub fn trace_step(&mut self, world: &World) {
        if !self.trails_on {
            return;
        }
        let n = world.agent_count();
        if self.trails_stale || self.last_drawn.len() != n || world.step_count() < self.last_step {
            self.fit_scene(world.scene());
            self.restart_trails(world);
        } else {
            let positions = world.positions();
            let alpha = self.style.trail_alpha;
            let tick = world.step_count() / FADE_STEPS;
            self.trace(world.scene(), positions, world.group_of(), TRACED_SEGMENT_MIN_PX, alpha, tick);
            if self.pending.len() >= PENDING_SEGMENTS_MAX {
                self.fade_to(world.step_count());
                self.draw_pending(tick);
            }
        }
        self.last_step = world.step_count();
    }

    /// The first step whose recorded positions [`Renderer::rebuild_trails`] draws for `world`:
    /// at most [`TRAIL_REBUILD_AGENT_STEPS`] agent-steps back, and no further back than the fade
    /// leaves visible.
    pub fn trail_rebuild_start(&self, world: &World) -> u32 {
        let by_cost = TRAIL_REBUILD_AGENT_STEPS / world.agent_count().max(1);
        let keep = 1.0 - self.trail_fade;
        let by_fade = if keep >= 1.0 {
            usize::MAX
        } else {
            // Fade ticks until the segment's opacity drops below half a level.
            let ticks = libm::logf(0.5 / f32::from(self.style.trail_alpha)) / libm::logf(keep);
            (ticks * FADE_STEPS as f32).max(0.0) as usize
        };
        let back = u32::try_from(by_cost.min(by_fade)).unwrap_or(u32::MAX);
        world.step_count().saturating_sub(back)
    }

    /// Redraws the trails after a jump to `world`'s step from the recorded positions before it
    /// (`(step, positions)` in increasing step order; steps after `world`'s, or with another
    /// agent count, are skipped), instead of erasing them. Each segment is drawn faded by its
    /// age as the steps would have faded it. Pass the frames from
    /// [`Renderer::trail_rebuild_start`] on: older ones cost time and add nothing visible.
    pub fn rebuild_trails(&mut self, world: &World, history: impl IntoIterator<Item = (u32, Vec<Vec2>)>) {
        self.fit_scene(world.scene());
        self.restart_trails(world);
        self.last_step = world.step_count();
        if !self.trails_on {
            return;
        }
        let now = world.step_count();
        let tick = now / FADE_STEPS;
        let keep = 1.0 - self.trail_fade;
        let mut started = false;
        for (step, positions) in history {
            if step > now || positions.len() != world.agent_count() {
                continue;
            }
            if !started {
                let view = self.view;
                self.last_drawn.clear();
                self.last_drawn.extend(positions.iter().map(|&p| view.to_canvas(p)));
                started = true;
                continue;
            }
            let ticks_ago = (now - step) as f32 / FADE_STEPS as f32;
            let alpha = (f32::from(self.style.trail_alpha) * libm::powf(keep, ticks_ago)).round() as u8;
            self.trace(world.scene(), &positions, world.group_of(), TRACED_SEGMENT_MIN_PX, alpha, tick);
            if self.pending.len() >= PENDING_SEGMENTS_MAX {
                self.draw_pending(tick);
            }
        }
        self.draw_pending(tick);
    }

    /// Zooms by `factor` (above 1 in, below 1 out) about `canvas_point` (device px): the scene
    /// point under it stays there, unless the zoom reaches its limits (the whole scene fitted,
    /// [`MAX_ZOOM`]) or the view would leave the scene. A factor that is not finite and
    /// positive, or a call before the first frame, does nothing. Trails restart (a caller with
    /// the run's history redraws them, as the playground does).
    pub fn zoom_about(&mut self, canvas_point: Vec2, factor: f32) {
        if !(factor.is_finite() && factor > 0.0 && canvas_point.is_finite()) || self.scene_size == Vec2::ZERO
        {
            return;
        }
        let fitted = self.fitted_view();
        let old = self.zoom.map_or(1.0, |z| z.factor);
        let wanted = (old * factor).clamp(1.0, MAX_ZOOM);
        if wanted <= 1.0 {
            self.fit_view();
            return;
        }
        // The scene point under the pointer now, and where the centre must be to keep it there.
        let anchor = self.view.to_scene(canvas_point);
        let scale = fitted.scale * wanted;
        let canvas_centre = 0.5 * Vec2::new(self.width as f32, self.height as f32);
        let center = anchor + (canvas_centre - canvas_point) / scale;
        self.set_zoom(Some(Zoom { center, factor: wanted }));
    }

    /// Moves a zoomed view by `canvas_delta` device px (the scene follows the pointer: a drag
    /// to the right shows more of the scene's left). Does nothing at the fitted view.
    pub fn pan_by(&mut self, canvas_delta: Vec2) {
        let Some(zoom) = self.zoom else { return };
        if !canvas_delta.is_finite() {
            return;
        }
        let scale = self.fitted_view().scale * zoom.factor;
        self.set_zoom(Some(Zoom { center: zoom.center - canvas_delta / scale, ..zoom }));
    }

    /// Shows the whole scene again, fitted and centred.
    pub fn fit_view(&mut self) {
        self.set_zoom(None);
    }

    /// The zoom over the fitted view: 1 shows the whole scene, up to [`MAX_ZOOM`].
    pub fn zoom(&self) -> f32 {
        self.zoom.map_or(1.0, |z| z.factor)
    }

    /// Stores a zoom (its centre kept inside the scene) and redraws the base at the next frame.
    fn set_zoom(&mut self, zoom: Option<Zoom>) {
        let size = self.scene_size;
        let zoom = zoom.map(|z| Zoom { center: z.center.clamp(Vec2::ZERO, size), ..z });
        if zoom == self.zoom {
            return;
        }
        self.zoom = zoom;
        self.base_key = None;
        self.trails_stale = true;
    }

    /// The whole scene fitted into the canvas.
    fn fitted_view(&self) -> ViewTransform {
        ViewTransform::fit(self.scene_size.x, self.scene_size.y, self.width, self.height)
    }

    /// The view to draw with: the fitted one, or the zoomed part of the scene.
    fn wanted_view(&self) -> ViewTransform {
        let fitted = self.fitted_view();
        let Some(zoom) = self.zoom else { return fitted };
        let scale = fitted.scale * zoom.factor;
        let offset = 0.5 * Vec2::new(self.width as f32, self.height as f32) - zoom.center * scale;
        ViewTransform { scale, offset_x: offset.x, offset_y: offset.y }
    }

    /// Rebuilds the base layer and the view when the scene's size, obstacles or hills, or the
    /// zoom changed (the trails then restart). A scene of another size shows whole again.
    fn fit_scene(&mut self, scene: &Scene) {
        if !self.base_key.as_ref().is_some_and(|k| k.matches(scene)) {
            let size = Vec2::new(scene.width, scene.height);
            if size != self.scene_size {
                self.scene_size = size;
                self.zoom = None;
            }
            self.view = self.wanted_view();
            self.draw_base(scene);
            self.base_key = Some(BaseKey {
                width: scene.width,
                height: scene.height,
                obstacles: scene.obstacles.clone(),
                hills: scene.hills.clone(),
            });
            self.trails_stale = true;
        }
    }

    /// Draws `world` into the frame.
    pub fn render(&mut self, world: &World) {
        let scene = world.scene();
        self.fit_scene(scene);
        let n = world.agent_count();
        if self.last_drawn.len() != n || world.step_count() < self.last_step {
            self.trails_stale = true;
        }
        if self.trails_stale {
            self.restart_trails(world);
        }
        if self.trails_on {
            // Faded by the steps since the last frame (none when the same step is drawn again).
            self.fade_to(world.step_count());
            // The segments traced by the steps since the last frame, then those from the last
            // traced points to where the agents are now (all of them when nothing was traced).
            let tick = world.step_count() / FADE_STEPS;
            self.trace(scene, world.positions(), world.group_of(), 0.0, self.style.trail_alpha, tick);
            self.draw_pending(tick);
            self.frame.copy_from_slice(&self.trails);
        } else {
            self.frame.copy_from_slice(&self.base);
        }
        self.last_step = world.step_count();

        let view = self.view;
        if let Some(mut pixmap) = PixmapMut::from_bytes(&mut self.frame, self.width, self.height) {
            draw_spawn_regions(&mut pixmap, scene, view);
            draw_paths(&mut pixmap, scene, view);
            draw_goals(&mut pixmap, scene, world.step_count(), view);
            draw_planned_paths(&mut pixmap, world, view);
        }
        self.update_sprites(scene);
        self.draw_agents(world);
        let target = overlay::Target {
            frame: &mut self.frame,
            width: self.width,
            height: self.height,
            view: self.view,
            rings: &mut self.rings,
        };
        overlay::draw(target, world, self.overlays, self.inspected);
        if let Some(item) = self.selection {
            if let Some(mut pixmap) = PixmapMut::from_bytes(&mut self.frame, self.width, self.height) {
                draw_selection(&mut pixmap, scene, world.step_count(), view, item);
            }
        }
    }

    fn draw_base(&mut self, scene: &Scene) {
        let view = self.view;
        let Some(mut pixmap) = PixmapMut::from_bytes(&mut self.base, self.width, self.height) else {
            return;
        };
        let style = self.style;
        pixmap.fill(color(style.letterbox, 255));
        let scene_rect = Rect::from_xywh(0.0, 0.0, scene.width, scene.height);
        if let Some(rect) = scene_rect.and_then(|r| r.transform(view.transform())) {
            pixmap.fill_rect(rect, &paint(style.background, 255), Transform::identity(), None);
        }
        if let Some(grid) = style.grid.filter(|_| GRID_SPACING * view.scale >= MIN_GRID_SPACING_PX) {
            let mut pb = PathBuilder::new();
            let mut x = GRID_SPACING;
            while x < scene.width {
                pb.move_to(x, 0.0);
                pb.line_to(x, scene.height);
                x += GRID_SPACING;
            }
            let mut y = GRID_SPACING;
            while y < scene.height {
                pb.move_to(0.0, y);
                pb.line_to(scene.width, y);
                y += GRID_SPACING;
            }
            stroke_scene_path(&mut pixmap, pb, view, grid, 255, 0.0, None);
        }
        draw_hills(&mut pixmap, scene, view);
        let fill = paint(style.obstacle, 255);
        let outline_width = (1.5 * view.scale).clamp(1.0, 3.0);
        for obstacle in &scene.obstacles {
            let Some(path) = obstacle_path(obstacle).and_then(|p| p.transform(view.transform())) else {
                continue;
            };
            pixmap.fill_path(&path, &fill, FillRule::Winding, Transform::identity(), None);
            let stroke = Stroke { width: outline_width, ..Stroke::default() };
            pixmap.stroke_path(
                &path,
                &paint(style.obstacle_outline, 255),
                &stroke,
                Transform::identity(),
                None,
            );
        }
    }

    fn restart_trails(&mut self, world: &World) {
        self.trails.copy_from_slice(&self.base);
        self.pending.clear();
        let view = self.view;
        self.last_drawn.clear();
        self.last_drawn.extend(world.positions().iter().map(|&p| view.to_canvas(p)));
        self.heading.clear();
        self.heading.extend(world.velocities().iter().map(|&v| heading_bucket(v).unwrap_or(0)));
        self.faded_tick = world.step_count() / FADE_STEPS;
        self.trails_stale = false;
    }

    /// Fades the trail layer up to the fade tick of `step`: tick `t` moves the stripe of rows
    /// `t mod` [`FADE_ROW_PERIOD`] (every [`FADE_ROW_PERIOD`]-th row) towards the base by
    /// [`FADE_ROW_PERIOD`] ticks' worth, an even, small cost per tick; a stripe due several times
    /// since the last call is faded once by all of them, so a call costs at most one pass.
    fn fade_to(&mut self, step: u32) {
        let target = step / FADE_STEPS;
        if target <= self.faded_tick {
            return;
        }
        let from = self.faded_tick;
        self.faded_tick = target;
        if self.trail_fade <= 0.0 {
            return;
        }
        if self.trail_fade >= 1.0 {
            self.trails.copy_from_slice(&self.base);
            return;
        }
        let ticks = target - from;
        let period = FADE_ROW_PERIOD;
        let row = self.width as usize * 4;
        for phase in 0..period {
            // Ticks from + 1 ..= target whose stripe is `phase`.
            let first = (from + 1) % period;
            let extra = u32::from((phase + period - first) % period < ticks % period);
            let due = ticks / period + extra;
            if due == 0 {
                continue;
            }
            let keep = libm::powf(1.0 - self.trail_fade, (period * due.min(1 << 16)) as f32);
            let amount = (((1.0 - keep) * 128.0).round() as i16).clamp(1, 128);
            for (trail_row, base_row) in self
                .trails
                .chunks_exact_mut(row)
                .zip(self.base.chunks_exact(row))
                .skip(phase as usize)
                .step_by(period as usize)
            {
                fade_row(trail_row, base_row, amount);
            }
        }
    }

    /// Queues the segment from each agent's last traced point to `positions` (scene px) when it
    /// has moved its group's [`TRAIL_SEGMENT_PX`] and at least `min_px` (device px), with
    /// opacity `alpha`, as traced at fade tick `tick`.
    #[allow(clippy::too_many_arguments, reason = "the plain inputs of a per-agent loop")]
    fn trace(
        &mut self,
        scene: &Scene,
        positions: &[Vec2],
        group_of: &[u32],
        min_px: f32,
        alpha: u8,
        tick: u32,
    ) {
        let view = self.view;
        let style = self.style;
        let (lo, hi) = TRAIL_SEGMENT_PX;
        let lo = lo.max(min_px);
        let hi = hi.max(lo);
        self.trail_groups.clear();
        self.trail_groups.extend(scene.groups.iter().map(|g| {
            (style.trail_color(parse_color(&g.color)), (g.agent_radius * view.scale).clamp(lo, hi))
        }));
        for ((&p, &g), last) in positions.iter().zip(group_of).zip(self.last_drawn.iter_mut()) {
            let Some(&(rgb, min_step)) = self.trail_groups.get(g as usize) else { continue };
            let now = view.to_canvas(p);
            if now.distance(*last) < min_step {
                continue;
            }
            self.pending.push(Segment { from: *last, to: now, rgb, alpha, tick });
            *last = now;
        }
    }

    /// Draws the queued segments onto the trail layer.
    ///
    /// The segments are rasterised here with Wu's anti-aliased lines rather than as one
    /// tiny-skia path per group: tiny-skia's hairline costs 0.6–0.8 µs per 3 px segment on this
    /// machine (its pipeline runs once per one- or two-pixel span), which at 10,000 agents is the
    /// whole frame budget; the direct loop costs a few blends per pixel column.
    ///
    /// A segment traced at an earlier fade tick than `tick` (a multi-step advance that filled
    /// the buffer) is drawn as faded as those ticks would have faded it.
    fn draw_pending(&mut self, tick: u32) {
        let (w, h) = (self.width as usize, self.height as usize);
        let width = self.style.trail_width_px;
        let keep = 1.0 - self.trail_fade;
        // Segments come in tick order: the faded opacity is recomputed when the tick changes.
        let mut faded: Option<(u32, u8, u8)> = None;
        for s in self.pending.drain(..) {
            let alpha = if s.tick >= tick {
                s.alpha
            } else {
                match faded {
                    Some((t, a, out)) if t == s.tick && a == s.alpha => out,
                    _ => {
                        let out =
                            (f32::from(s.alpha) * libm::powf(keep, (tick - s.tick) as f32)).round() as u8;
                        faded = Some((s.tick, s.alpha, out));
                        out
                    }
                }
            };
            if alpha > 0 {
                draw_wide_segment(&mut self.trails, w, h, s.from, s.to, s.rgb, alpha, width);
            }
        }
    }

    /// Rebuilds the sprites of groups whose colour or device size changed.
    fn update_sprites(&mut self, scene: &Scene) {
        self.sprites.truncate(scene.groups.len());
        for (i, group) in scene.groups.iter().enumerate() {
            let rgb = parse_color(&group.color);
            let radius_px = (group.agent_radius * self.view.scale * self.style.agent_scale)
                .max(self.style.min_agent_radius_px);
            let fresh = self.sprites.get(i).is_some_and(|s| s.color == rgb && s.radius_px == radius_px);
            if fresh {
                continue;
            }
            let headings = if radius_px < DOT_RADIUS_PX {
                Vec::new()
            } else {
                (0..HEADING_BUCKETS)
                    .map(|b| agent_sprite(rgb, radius_px, b as f32 * TAU / HEADING_BUCKETS as f32))
                    .collect()
            };
            let sprites = GroupSprites { color: rgb, radius_px, headings };
            if i < self.sprites.len() {
                self.sprites[i] = sprites;
            } else {
                self.sprites.push(sprites);
            }
        }
    }

    /// Places every agent on the canvas, orders them top to bottom by band (a counting sort),
    /// then blits each one's sprite or writes its dot.
    fn draw_agents(&mut self, world: &World) {
        let view = self.view;
        let (w, h) = (self.width as i32, self.height as i32);
        self.heading.resize(world.agent_count(), 0);
        self.placed.clear();
        let agents = world.positions().iter().zip(world.velocities()).zip(world.group_of());
        let arrivals = world.arrivals();
        for (i, (((&p, &v), &group), heading)) in agents.zip(self.heading.iter_mut()).enumerate() {
            if arrivals.get(i) == Some(&crate::sim::gather::Arrival::Exited) {
                // Left the scene through its exit: not drawn.
                continue;
            }
            // Dots have no heading: no arctangent per agent for a crowd too small to show one
            // (100,000 agents on a page canvas).
            let dots = self.sprites.get(group as usize).is_none_or(|s| s.headings.is_empty());
            if !dots {
                if let Some(b) = heading_bucket(v) {
                    *heading = b;
                }
            }
            let c = view.to_canvas(p);
            if c.is_finite() {
                let (x, y) = (c.x.round() as i32, c.y.round() as i32);
                self.placed.push(Placed { x, y, group, heading: *heading });
            }
        }

        let bands = (h as usize >> BAND_SHIFT) + 1;
        let band_of = |p: &Placed| (p.y.clamp(0, h - 1) as usize) >> BAND_SHIFT;
        self.band_counts.clear();
        self.band_counts.resize(bands + 1, 0);
        for p in &self.placed {
            self.band_counts[band_of(p) + 1] += 1;
        }
        for b in 1..=bands {
            self.band_counts[b] += self.band_counts[b - 1];
        }
        self.drawing_order.clear();
        self.drawing_order.resize(self.placed.len(), 0);
        for (i, p) in self.placed.iter().enumerate() {
            let slot = &mut self.band_counts[band_of(p)];
            self.drawing_order[*slot as usize] = i as u32;
            *slot += 1;
        }

        for &i in &self.drawing_order {
            let p = self.placed[i as usize];
            let Some(sprites) = self.sprites.get(p.group as usize) else { continue };
            match sprites.headings.get(p.heading as usize) {
                Some(sprite) => blit_over(&mut self.frame, w, h, sprite, p.x, p.y),
                None => {
                    if (0..w).contains(&p.x) && (0..h).contains(&p.y) {
                        let at = (p.y as usize * w as usize + p.x as usize) * 4;
                        self.frame[at..at + 3].copy_from_slice(&sprites.color);
                    }
                }
            }
        }
    }
}

/// The heading bucket of a velocity, or `None` when it is too slow to have a direction.
fn heading_bucket(v: Vec2) -> Option<u8> {
    let speed2 = v.length_squared();
    if speed2.is_nan() || speed2 <= 1e-8 {
        return None;
    }
    let turns = libm::atan2f(v.y, v.x) / TAU;
    let bucket = (turns * HEADING_BUCKETS as f32).round() as i32;
    Some(bucket.rem_euclid(HEADING_BUCKETS as i32) as u8)
}

/// Moves each byte of `trail` towards `base` by `amount / 128` of the gap (`amount` in
/// 1…128), at least one step, so faded trails reach the base exactly instead of leaving a residue.
/// 16-bit lanes (|gap · amount| ≤ 255 · 128 fits) let the loop vectorise eight bytes at a time.
fn fade_row(trail: &mut [u8], base: &[u8], amount: i16) {
    for (t, &b) in trail.iter_mut().zip(base) {
        let gap = i16::from(b) - i16::from(*t);
        // Arithmetic shift floors: rounding up for positive gaps makes both directions round
        // away from zero.
        let step = (gap * amount + if gap > 0 { 127 } else { 0 }) >> 7;
        *t = (i16::from(*t) + step) as u8;
    }
}

/// The outline of an obstacle in scene px.
fn obstacle_path(obstacle: &Obstacle) -> Option<Path> {
    match obstacle {
        Obstacle::Circle { center, radius } => PathBuilder::from_circle(center[0], center[1], *radius),
        Obstacle::Rect { min, max } => {
            Rect::from_ltrb(min[0], min[1], max[0], max[1]).map(PathBuilder::from_rect)
        }
        Obstacle::Polygon { points } => {
            let mut pb = PathBuilder::new();
            let (first, rest) = points.split_first()?;
            pb.move_to(first[0], first[1]);
            for p in rest {
                pb.line_to(p[0], p[1]);
            }
            pb.close();
            pb.finish()
        }
    }
}

fn push_rect(pb: &mut PathBuilder, min: [f32; 2], max: [f32; 2]) {
    if let Some(r) = Rect::from_ltrb(min[0], min[1], max[0], max[1]) {
        pb.push_rect(r);
    }
}

/// Each group's spawn region as a faint dashed rectangle in its colour.
fn draw_spawn_regions(pixmap: &mut PixmapMut, scene: &Scene, view: ViewTransform) {
    for group in &scene.groups {
        let mut pb = PathBuilder::new();
        push_rect(&mut pb, group.spawn.min, group.spawn.max);
        stroke_scene_path(pixmap, pb, view, parse_color(&group.color), 110, 1.0, Some([5.0, 4.0]));
    }
}

/// Hills as shading: nested discs at the contours of 20, 40, 60 and 80 % of each top, darker
/// for higher hills (the tallest hill of the scene at full strength).
fn draw_hills(pixmap: &mut PixmapMut, scene: &Scene, view: ViewTransform) {
    let tallest = scene.hills.iter().map(|h| h.height).fold(0.0f32, f32::max);
    if tallest <= 0.0 {
        return;
    }
    for hill in &scene.hills {
        let strength = hill.height / tallest;
        for level in [0.2f32, 0.4, 0.6, 0.8] {
            // exp(−d²/r²) = level at d = r·√(ln 1/level).
            let d = hill.radius * libm::sqrtf(libm::logf(1.0 / level));
            let mut pb = PathBuilder::new();
            pb.push_circle(hill.center[0], hill.center[1], d);
            let Some(path) = pb.finish().and_then(|p| p.transform(view.transform())) else { continue };
            let alpha = (strength * 34.0) as u8;
            pixmap.fill_path(
                &path,
                &paint(HILL_COLOR, alpha),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }
}

fn push_polyline(pb: &mut PathBuilder, points: &[[f32; 2]]) {
    if let Some((first, rest)) = points.split_first() {
        pb.move_to(first[0], first[1]);
        for p in rest {
            pb.line_to(p[0], p[1]);
        }
    }
}

/// Each path as a faint corridor (its radius) with a dashed centre line in the colour of the
/// first group following it (grey if none).
fn draw_paths(pixmap: &mut PixmapMut, scene: &Scene, view: ViewTransform) {
    for (i, path) in scene.paths.iter().enumerate() {
        let number = i as u32 + 1;
        let follower =
            scene.groups.iter().find(|g| matches!(&g.planner, PlannerConfig::Boids(p) if p.path == number));
        let rgb = follower.map_or(OBSTACLE_COLOR, |g| parse_color(&g.color));
        let mut corridor = PathBuilder::new();
        push_polyline(&mut corridor, &path.points);
        let Some(line) = corridor.finish().and_then(|p| p.transform(view.transform())) else { continue };
        let wide = Stroke {
            width: 2.0 * path.radius * view.scale,
            line_cap: tiny_skia::LineCap::Round,
            line_join: tiny_skia::LineJoin::Round,
            ..Stroke::default()
        };
        pixmap.stroke_path(&line, &paint(rgb, 28), &wide, Transform::identity(), None);
        let mut centre = PathBuilder::new();
        push_polyline(&mut centre, &path.points);
        stroke_scene_path(pixmap, centre, view, rgb, 200, 1.5, Some([8.0, 5.0]));
    }
}

/// Each goal as a ring (its arrival radius) and a centre dot where it is at `step` (a moving goal
/// is drawn where the agents are heading now, not where it started); goals no group uses are
/// dimmer.
fn draw_goals(pixmap: &mut PixmapMut, scene: &Scene, step: u32, view: ViewTransform) {
    for (i, goal) in scene.goals.iter().enumerate() {
        let user = scene.groups.iter().find(|g| g.goal == Some(i as u32));
        let (rgb, alpha) = match user {
            Some(g) => (parse_color(&g.color), 230),
            None => (GOAL_COLOR, 90),
        };
        let at = goal.position_at(step);
        let mut ring = PathBuilder::new();
        ring.push_circle(at.x, at.y, goal.radius);
        stroke_scene_path(pixmap, ring, view, rgb, alpha, 2.0, None);
        let c = view.to_canvas(at);
        if let Some(dot) = PathBuilder::from_circle(c.x, c.y, 3.0) {
            pixmap.fill_path(&dot, &paint(rgb, alpha), FillRule::Winding, Transform::identity(), None);
        }
    }
}

/// The path each IGSA group follows: a dashed line in the group's colour, segments that cross an
/// obstacle solid red, and a handle (white disc, coloured ring) on every draggable waypoint.
fn draw_planned_paths(pixmap: &mut PixmapMut, world: &World, view: ViewTransform) {
    for (g, group) in world.scene().groups.iter().enumerate() {
        let Some(path) = world.planned_path(g) else { continue };
        let rgb = parse_color(&group.color);
        for (k, w) in path.points.windows(2).enumerate() {
            let mut pb = PathBuilder::new();
            pb.move_to(w[0][0], w[0][1]);
            pb.line_to(w[1][0], w[1][1]);
            if path.crossing.get(k).copied().unwrap_or(false) {
                stroke_scene_path(pixmap, pb, view, CROSSING_COLOR, 255, 3.0, None);
            } else {
                stroke_scene_path(pixmap, pb, view, rgb, 220, 2.0, Some([7.0, 4.0]));
            }
        }
        let inner = path.points.len().saturating_sub(1);
        for p in path.points.iter().take(inner).skip(1) {
            let c = view.to_canvas(Vec2::new(p[0], p[1]));
            if let Some(dot) = PathBuilder::from_circle(c.x, c.y, WAYPOINT_HANDLE_PX) {
                pixmap.fill_path(
                    &dot,
                    &paint([255, 255, 255], 255),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
                let stroke = Stroke { width: 2.0, ..Stroke::default() };
                pixmap.stroke_path(&dot, &paint(rgb, 255), &stroke, Transform::identity(), None);
            }
        }
    }
}

/// An orange outline around the selected item (a goal where it is at `step`, as
/// [`draw_goals`] draws it); a stale index draws nothing.
fn draw_selection(pixmap: &mut PixmapMut, scene: &Scene, step: u32, view: ViewTransform, item: ItemRef) {
    let mut pb = PathBuilder::new();
    match item {
        ItemRef::Obstacle(i) => {
            let Some(path) = scene.obstacles.get(i as usize).and_then(obstacle_path) else { return };
            pb.push_path(&path);
        }
        ItemRef::Goal(i) => {
            let Some(goal) = scene.goals.get(i as usize) else { return };
            let at = goal.position_at(step);
            pb.push_circle(at.x, at.y, goal.radius.max(6.0) + 4.0 / view.scale);
        }
        ItemRef::Group(i) => {
            let Some(group) = scene.groups.get(i as usize) else { return };
            push_rect(&mut pb, group.spawn.min, group.spawn.max);
        }
        ItemRef::Path(i) => {
            let Some(path) = scene.paths.get(i as usize) else { return };
            push_polyline(&mut pb, &path.points);
        }
    }
    stroke_scene_path(pixmap, pb, view, SELECTION_COLOR, 255, 2.5, None);
}

#[cfg(test)]
mod tests {
    use super::paint::draw_segment;
    use super::*;
    use crate::model::params::PlannerConfig;
    use crate::model::presets;
    use crate::model::scene::{Goal, Group, Region};

    fn pixel(r: &Renderer, x: u32, y: u32) -> [u8; 4] {
        let at = (y as usize * r.width() as usize + x as usize) * 4;
        let p = r.pixels();
        [p[at], p[at + 1], p[at + 2], p[at + 3]]
    }

    fn canvas_of(r: &Renderer, scene_point: Vec2) -> (u32, u32) {
        let c = r.view().to_canvas(scene_point);
        (c.x as u32, c.y as u32)
    }

    /// One red agent heading right across an empty field.
    fn lone_agent() -> Scene {
        let mut s = Scene::empty(400.0, 200.0);
        s.goals.push(Goal::fixed([380.0, 100.0], 10.0));
        s.groups.push(Group {
            name: "solo".into(),
            color: "#ff0000".into(),
            count: 1,
            spawn: Region { min: [40.0, 95.0], max: [45.0, 105.0] },
            goal: Some(0),
            agent_radius: 5.0,
            planner: PlannerConfig::default(),
        });
        s
    }

    #[test]
    fn obstacle_centres_have_the_obstacle_colour() {
        let world = World::new(presets::pillars()).expect("valid");
        let mut r = Renderer::new(900, 560);
        r.render(&world);
        for o in &world.scene().obstacles {
            let Obstacle::Circle { center, .. } = o else { panic!("pillars are circles") };
            let (x, y) = canvas_of(&r, Vec2::from(*center));
            let [cr, cg, cb] = OBSTACLE_COLOR;
            assert_eq!(pixel(&r, x, y), [cr, cg, cb, 255], "pillar at {center:?}");
        }
        let corridor = World::new(presets::corridor()).expect("valid");
        r.render(&corridor);
        let (x, y) = canvas_of(&r, Vec2::new(450.0, 100.0));
        assert_eq!(pixel(&r, x, y)[..3], OBSTACLE_COLOR, "rectangle wall");
    }

    #[test]
    fn hills_shade_the_ground_darker_towards_the_top_and_paths_show_their_followers_colour() {
        let mut world = World::new(presets::pso_hills()).expect("valid");
        let mut r = Renderer::new(1000, 700);
        r.render(&world);
        let brightness = |r: &Renderer, p: Vec2| {
            let (x, y) = canvas_of(r, p);
            pixel(r, x, y)[..3].iter().map(|&c| u32::from(c)).sum::<u32>()
        };
        let open = brightness(&r, Vec2::new(450.0, 40.0));
        let flank = brightness(&r, Vec2::new(450.0, 350.0 + 80.0));
        let top = brightness(&r, Vec2::new(450.0, 350.0));
        assert!(top < flank && flank < open, "top {top}, flank {flank}, open {open}");
        let mut scene = presets::boids_path();
        scene.groups[0].count = 1;
        world = World::new(scene).expect("valid");
        r.render(&world);
        // Halfway along the first segment, on the dashed centre line or its faint corridor.
        let (x, y) = canvas_of(&r, Vec2::new(195.0, 505.0));
        let [pr, pg, pb, _] = pixel(&r, x, y);
        assert!(pg > pr && pg > pb, "path pixel {:?} is not the group's green", (pr, pg, pb));
    }

    #[test]
    fn every_pixel_is_opaque() {
        let mut world = World::new(presets::two_groups_swap()).expect("valid");
        let mut r = Renderer::new(333, 217);
        for _ in 0..5 {
            world.step_n(10);
            r.render(&world);
        }
        assert_eq!(r.pixels().len(), 333 * 217 * 4);
        assert!(r.pixels().chunks_exact(4).all(|p| p[3] == 255));
    }

    #[test]
    fn an_agent_shows_its_group_colour_near_its_position() {
        let mut world = World::new(lone_agent()).expect("valid");
        world.step_n(20);
        let mut r = Renderer::new(800, 400);
        r.set_trails(false);
        r.render(&world);
        let (x, y) = canvas_of(&r, world.positions()[0]);
        let red = (x.saturating_sub(3)..x + 4)
            .flat_map(|px| (y.saturating_sub(3)..y + 4).map(move |py| (px, py)))
            .filter(|&(px, py)| pixel(&r, px, py) == [255, 0, 0, 255])
            .count();
        assert!(red >= 4, "only {red} pure red pixels around the agent at ({x}, {y})");
        // Far from the agent there is no red.
        assert_ne!(pixel(&r, x + 100, y)[..3], [255, 0, 0]);
    }

    #[test]
    fn tiny_agents_become_dots_in_their_colour() {
        let mut world = World::new(lone_agent()).expect("valid");
        world.step_n(5);
        // 0.1 device px per scene px: the 5 px agent is half a pixel across.
        let mut r = Renderer::new(40, 20);
        r.render(&world);
        // A dot is written to the pixel nearest the centre (rounded, not truncated).
        let c = r.view().to_canvas(world.positions()[0]);
        assert_eq!(pixel(&r, c.x.round() as u32, c.y.round() as u32), [255, 0, 0, 255]);
    }

    /// The lone agent drawn at 800 × 400 in `theme` with unfading trails, before and after 60
    /// steps: the world and renderer after the second frame and the agent's canvas positions at
    /// both frames.
    fn lone_agent_track(theme: Theme) -> (World, Renderer, Vec2, Vec2) {
        let mut world = World::new(lone_agent()).expect("valid");
        let mut r = Renderer::new(800, 400);
        r.set_theme(theme);
        r.set_trail_fade(0.0);
        r.render(&world);
        let start = r.view().to_canvas(world.positions()[0]);
        world.step_n(60);
        r.render(&world);
        let end = r.view().to_canvas(world.positions()[0]);
        (world, r, start, end)
    }

    #[test]
    fn trails_mark_the_path_between_frames_and_fade_away() {
        let (world, mut r, start, end) = lone_agent_track(Theme::Standard);
        assert!(start.distance(end) > 20.0, "the agent should have moved: {start} → {end}");
        let mid = (start + end) * 0.5;
        let at = (mid.y as usize * 800 + mid.x as usize) * 4;
        let (trail, base) = (&r.trails[at..at + 3], &r.base[at..at + 3]);
        assert_ne!(trail, base, "no trail at {mid}");
        assert!(trail[0] > trail[1] && trail[0] > trail[2], "trail is not reddish: {trail:?}");
        assert_eq!(r.pixels()[at..at + 3], *trail, "the frame shows the trail");

        // Frames drawn again without a step change nothing, whatever the fade.
        r.set_trail_fade(0.5);
        let shown = r.pixels().to_vec();
        for _ in 0..40 {
            r.render(&world);
        }
        assert!(r.pixels() == &shown[..], "drawing the same step again faded the trails");

        // Steps fade it: it returns exactly to the base.
        let mut later = world.clone();
        for _ in 0..80 {
            later.step();
            r.render(&later);
        }
        assert_eq!(&r.trails[at..at + 3], &r.base[at..at + 3]);

        // A reset (step count going back) restarts the trails rather than drawing a jump.
        r.set_trail_fade(0.0);
        let reset = World::new(lone_agent()).expect("valid");
        r.render(&reset);
        assert_eq!(r.trails, r.base);
    }

    /// Pixels of the trail layer that differ from the base inside a pillar, at least `inset`
    /// device px from its border (the outline is anti-aliased).
    fn trail_pixels_inside_pillars(r: &Renderer, scene: &Scene, inset: f32) -> usize {
        let (w, h) = (r.width() as usize, r.height() as usize);
        let mut inside = 0;
        for o in &scene.obstacles {
            let Obstacle::Circle { center, radius } = o else { panic!("pillars are circles") };
            let c = r.view().to_canvas(Vec2::from(*center));
            let reach = radius * r.view().scale - inset;
            for y in (c.y - reach).floor() as usize..=(c.y + reach).ceil() as usize {
                for x in (c.x - reach).floor() as usize..=(c.x + reach).ceil() as usize {
                    let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                    if x >= w || y >= h || centre.distance(c) > reach {
                        continue;
                    }
                    let at = (y * w + x) * 4;
                    inside += usize::from(r.trails[at..at + 3] != r.base[at..at + 3]);
                }
            }
        }
        inside
    }

    #[test]
    fn traced_steps_go_round_the_pillars_where_one_chord_per_frame_crosses_them() {
        let mut scene = presets::pillars();
        scene.view.trail_fade = 0.0;
        let mut world = World::new(scene).expect("valid");
        let (mut traced, mut chords) = (Renderer::new(900, 560), Renderer::new(900, 560));
        for r in [&mut traced, &mut chords] {
            r.set_trail_fade(0.0);
        }
        // The chords start at the first frame; the traced trails at the first step, with no
        // frame before it (a script stepping a scene it just loaded).
        chords.render(&world);
        let agents = world.agent_count();
        for _ in 0..2000 {
            world.step();
            traced.trace_step(&world);
            assert!(traced.pending.len() <= PENDING_SEGMENTS_MAX + agents, "the buffer stays bounded");
        }
        traced.render(&world);
        chords.render(&world);
        assert!(traced.pending.is_empty());
        let scene = world.scene();
        assert_eq!(trail_pixels_inside_pillars(&traced, scene, 2.0), 0, "a traced trail entered a pillar");
        assert!(
            trail_pixels_inside_pillars(&chords, scene, 2.0) > 100,
            "one chord per 2000 steps should cross the pillars (else this test proves nothing)"
        );
    }

    #[test]
    fn a_frame_depends_on_the_steps_not_on_how_often_it_is_drawn() {
        let mut world = World::new(presets::two_groups_swap()).expect("valid");
        let (mut once, mut often) = (Renderer::new(640, 360), Renderer::new(640, 360));
        for r in [&mut once, &mut often] {
            r.set_trail_fade(0.05);
        }
        for step in 0..150 {
            world.step();
            once.trace_step(&world);
            often.trace_step(&world);
            once.render(&world);
            // A print, a resize check, a paused redraw: the same step drawn again.
            for _ in 0..1 + step % 3 {
                often.render(&world);
            }
            assert!(once.pixels() == often.pixels(), "step {step} differs");
        }
    }

    /// Mean |trail − base| over the trail layer's colour bytes.
    fn trail_ink(r: &Renderer) -> f64 {
        let total: u64 = r
            .trails
            .iter()
            .zip(&r.base)
            .enumerate()
            .filter(|(k, _)| k % 4 != 3)
            .map(|(_, (&t, &b))| u64::from(t.abs_diff(b)))
            .sum();
        total as f64 / (r.trails.len() as f64 * 0.75)
    }

    #[test]
    fn trails_fade_with_the_steps_whether_drawn_every_step_or_after_many() {
        let mut world = World::new(presets::pillars()).expect("valid");
        world.step_n(20);
        let mut history = vec![world.positions().to_vec()];
        let (mut every, mut once) = (Renderer::new(900, 560), Renderer::new(900, 560));
        for r in [&mut every, &mut once] {
            r.set_trail_fade(0.1);
            r.render(&world);
        }
        // 400 steps drawn after each step, or traced and drawn in one frame at the end.
        for _ in 0..400 {
            world.step();
            history.push(world.positions().to_vec());
            every.trace_step(&world);
            every.render(&world);
            once.trace_step(&world);
        }
        once.render(&world);
        let (a, b) = (trail_ink(&every), trail_ink(&once));
        assert!(a > 0.05, "the trails show: {a}");
        assert!((a - b).abs() < 0.25 * a, "ink drawn every step {a:.3}, after 400 steps {b:.3}");
        // Fade 0.1 per 2 steps leaves about 100 steps visible: where the agents were 300 steps
        // ago shows no trail, where they were 20 steps ago does.
        let near = |r: &Renderer, p: Vec2| {
            let c = r.view().to_canvas(p);
            let w = r.width() as usize;
            (c.y as usize - 1..=c.y as usize + 1)
                .flat_map(|y| (c.x as usize - 1..=c.x as usize + 1).map(move |x| (y * w + x) * 4))
                .any(|at| r.trails[at..at + 3] != r.base[at..at + 3])
        };
        let moved =
            |k: usize| history[k].iter().zip(&history[k + 1]).filter(|(p, q)| p.distance(**q) > 0.5).count();
        assert!(moved(100) > 20 && moved(379) > 20, "the crowd still moves");
        for r in [&every, &once] {
            let old = history[100].iter().filter(|&&p| near(r, p)).count();
            let recent = history[380].iter().filter(|&&p| near(r, p)).count();
            assert!(recent > 20 && old * 4 < recent, "trails near old positions {old}, recent {recent}");
        }
    }

    #[test]
    fn tracing_single_steps_draws_the_same_frames_as_before() {
        let mut world = World::new(presets::two_groups_swap()).expect("valid");
        let (mut traced, mut plain) = (Renderer::new(640, 360), Renderer::new(640, 360));
        for frame in 0..120 {
            world.step();
            traced.trace_step(&world);
            traced.render(&world);
            plain.render(&world);
            assert!(traced.pixels() == plain.pixels(), "frame {frame} differs");
        }
    }

    #[test]
    fn a_jump_rebuilds_the_trails_from_the_recorded_positions() {
        let mut world = World::new(presets::pillars()).expect("valid");
        let mut history = vec![(0, world.positions().to_vec())];
        let mut earlier = world.clone();
        for _ in 0..400 {
            world.step();
            history.push((world.step_count(), world.positions().to_vec()));
            if world.step_count() == 300 {
                earlier = world.clone();
            }
        }
        let mut r = Renderer::new(900, 560);
        r.set_trail_fade(0.0);
        r.render(&world);
        let start = r.trail_rebuild_start(&world);
        assert_eq!(start, 0, "80 agents × 400 steps are within the rebuild budget");
        r.rebuild_trails(&world, history.iter().cloned());
        r.render(&world);
        let (w, scene) = (r.width() as usize, world.scene().clone());
        let trail_near = |r: &Renderer, p: Vec2| {
            let c = r.view().to_canvas(p);
            let (x, y) = (c.x as usize, c.y as usize);
            (y - 2..=y + 2)
                .flat_map(|y| (x - 2..=x + 2).map(move |x| (y * w + x) * 4))
                .any(|at| r.trails[at..at + 3] != r.base[at..at + 3])
        };
        // A trail grows by a segment once its agent has moved a body radius (`trace`), so an
        // agent that stopped less than that past its last segment, as one that parks in the
        // goal after creeping in, ends up to a radius (4 px) from its trail.
        let within_a_radius = |r: &Renderer, p: Vec2| {
            let c = r.view().to_canvas(p);
            let (x, y) = (c.x as usize, c.y as usize);
            (y - 4..=y + 4)
                .flat_map(|y| (x - 4..=x + 4).map(move |x| (y * w + x) * 4))
                .any(|at| r.trails[at..at + 3] != r.base[at..at + 3])
        };
        for &(step, ref positions) in history.iter().skip(20).step_by(60) {
            let missing = positions.iter().filter(|&&p| !within_a_radius(&r, p)).count();
            assert!(
                missing <= positions.len() / 20,
                "step {step}: {missing} agents have no trail where they were"
            );
        }
        assert_eq!(trail_pixels_inside_pillars(&r, &scene, 2.0), 0);

        // Faded trails: only the recent part is rebuilt, old positions show nothing.
        r.set_trail_fade(0.05);
        let start = r.trail_rebuild_start(&world);
        // 220 · 0.95^k < 0.5 after k = 118.7 fade ticks of 2 steps.
        assert_eq!(400 - start, 237, "fade 0.05 keeps the last 237 steps");
        r.rebuild_trails(&world, history.iter().filter(|h| h.0 >= start).cloned());
        let (_, early) = &history[40];
        assert!(early.iter().all(|&p| !trail_near(&r, p)), "trails long faded are not redrawn");
        let (_, recent) = &history[395];
        let shown = recent.iter().filter(|&&p| trail_near(&r, p)).count();
        assert!(shown >= recent.len() * 9 / 10, "{shown} recent positions have a trail");
        // A jump back: the rebuild does not count as a reset (the step went back), the next
        // frame keeps it.
        r.render(&world);
        r.rebuild_trails(&earlier, history.iter().cloned());
        let rebuilt = r.trails.clone();
        assert!(rebuilt != r.base);
        r.render(&earlier);
        let kept = r.trails.chunks_exact(4).zip(rebuilt.chunks_exact(4)).filter(|(a, b)| a == b).count();
        assert!(kept > r.trails.len() / 4 * 9 / 10, "only {kept} pixels kept after one frame");
        let (_, last) = &history[295];
        assert!(last.iter().filter(|&&p| trail_near(&r, p)).count() >= last.len() * 9 / 10);
        // Recorded steps after the jump's are left out.
        let mut upto = Renderer::new(900, 560);
        upto.set_trail_fade(0.05);
        upto.render(&earlier);
        upto.rebuild_trails(&earlier, history.iter().take(301).cloned());
        assert!(upto.trails == rebuilt, "steps after 300 changed the rebuilt trails");
    }

    #[test]
    fn resize_keeps_rendering_the_same_scene() {
        let world = World::new(presets::pillars()).expect("valid");
        let mut r = Renderer::new(200, 100);
        r.render(&world);
        r.resize(300, 400);
        r.render(&world);
        assert_eq!((r.width(), r.height()), (300, 400));
        assert_eq!(r.pixels().len(), 300 * 400 * 4);
        let (x, y) = canvas_of(&r, Vec2::new(300.0, 110.0));
        assert_eq!(pixel(&r, x, y)[..3], OBSTACLE_COLOR);
        r.resize(0, 0);
        r.render(&world);
        assert_eq!(r.pixels().len(), 4, "a zero size is clamped to one pixel");
    }

    #[test]
    fn the_view_fits_the_scene_centred() {
        let scene = presets::pillars();
        for (w, h) in [(900, 560), (1000, 300), (300, 1000), (1, 1)] {
            let view = ViewTransform::fit(scene.width, scene.height, w, h);
            let a = view.to_canvas(Vec2::ZERO);
            let b = view.to_canvas(Vec2::new(scene.width, scene.height));
            let eps = 1e-3;
            assert!(a.x >= -eps && a.y >= -eps, "{w}×{h}: {a}");
            assert!(b.x <= w as f32 + eps && b.y <= h as f32 + eps, "{w}×{h}: {b}");
            // Letterboxed on one axis only, equally on both sides.
            assert!((a.x - (w as f32 - b.x)).abs() < eps && (a.y - (h as f32 - b.y)).abs() < eps);
            assert!(a.x.min(a.y).abs() < eps, "{w}×{h}: the scene touches two edges");
            let back = view.to_scene(Vec2::new(123.0, 45.0));
            assert!(view.to_canvas(back).distance(Vec2::new(123.0, 45.0)) < 1e-3);
        }
    }

    #[test]
    fn zooming_keeps_the_point_under_the_pointer_and_fit_shows_the_whole_scene() {
        let world = World::new(presets::pillars()).expect("valid");
        let mut r = Renderer::new(900, 560);
        r.zoom_about(Vec2::new(300.0, 200.0), 2.0);
        assert_eq!(r.zoom(), 1.0, "before the first frame there is no scene to zoom into");
        r.render(&world);
        let fitted = r.view();
        let fitted_frame = r.pixels().to_vec();
        let pointer = Vec2::new(300.0, 200.0);
        let under = fitted.to_scene(pointer);
        r.zoom_about(pointer, 2.5);
        r.render(&world);
        assert_eq!(r.zoom(), 2.5);
        assert!((r.view().scale - 2.5 * fitted.scale).abs() < 1e-4);
        assert!(r.view().to_canvas(under).distance(pointer) < 1e-2, "the pointed-at point stays put");
        assert!(r.pixels() != fitted_frame.as_slice(), "the zoomed frame differs");
        // Panning moves the scene with the pointer.
        r.pan_by(Vec2::new(40.0, -10.0));
        r.render(&world);
        assert!(r.view().to_canvas(under).distance(pointer + Vec2::new(40.0, -10.0)) < 1e-2);
        // Limits: never below the fitted view, never past MAX_ZOOM; bad factors do nothing.
        r.zoom_about(pointer, 1000.0);
        assert_eq!(r.zoom(), MAX_ZOOM);
        r.zoom_about(pointer, f32::NAN);
        r.zoom_about(pointer, -1.0);
        assert_eq!(r.zoom(), MAX_ZOOM);
        r.zoom_about(pointer, 1e-6);
        r.render(&world);
        assert_eq!(r.zoom(), 1.0);
        assert_eq!(r.view(), fitted);
        r.zoom_about(pointer, 3.0);
        r.fit_view();
        r.render(&world);
        assert_eq!(r.view(), fitted);
        assert!(r.pixels() == fitted_frame.as_slice(), "Fit draws the fitted frame again");
        // The fitted view does not pan.
        r.pan_by(Vec2::new(50.0, 50.0));
        r.render(&world);
        assert_eq!(r.view(), fitted);
    }

    #[test]
    fn a_zoomed_view_stays_over_the_scene() {
        let world = World::new(presets::pillars()).expect("valid");
        let mut r = Renderer::new(900, 560);
        r.render(&world);
        r.zoom_about(Vec2::new(450.0, 280.0), 4.0);
        r.pan_by(Vec2::new(1e7, 1e7));
        r.render(&world);
        let centre = r.view().to_scene(Vec2::new(450.0, 280.0));
        assert!(centre.abs_diff_eq(Vec2::ZERO, 1e-2), "panned to the scene's corner, no further: {centre}");
    }

    #[test]
    fn the_selection_is_outlined() {
        let world = World::new(presets::pillars()).expect("valid");
        let mut r = Renderer::new(900, 560);
        r.render(&world);
        let before = r.pixels().to_vec();
        r.set_selection(Some(ItemRef::Obstacle(0)));
        r.render(&world);
        let orange = r.pixels().chunks_exact(4).filter(|p| p[..3] == SELECTION_COLOR).count();
        assert!(orange > 50, "{orange} selection pixels");
        r.set_selection(Some(ItemRef::Obstacle(999)));
        r.render(&world);
        assert_eq!(r.pixels(), &before[..], "a stale selection draws nothing");
    }

    #[test]
    fn segments_cover_their_path_leave_their_end_and_clip() {
        let (w, h) = (20usize, 10usize);
        let mut layer = vec![255u8; w * h * 4];
        draw_segment(&mut layer, w, h, Vec2::new(2.5, 4.5), Vec2::new(12.5, 4.5), [0, 0, 0], 255);
        let at = |layer: &[u8], x: usize, y: usize| layer[(y * w + x) * 4];
        for x in 2..12 {
            assert_eq!(at(&layer, x, 4), 0, "column {x}");
        }
        assert_eq!(at(&layer, 12, 4), 255, "the end column is left for the next segment");
        assert_eq!(at(&layer, 6, 3), 255);
        let before = layer.clone();
        draw_segment(&mut layer, w, h, Vec2::new(-50.0, -50.0), Vec2::new(100.0, 80.0), [0, 0, 0], 255);
        draw_segment(&mut layer, w, h, Vec2::new(f32::NAN, 1.0), Vec2::new(3.0, 3.0), [0, 0, 0], 255);
        draw_segment(&mut layer, w, h, Vec2::new(30.0, 3.0), Vec2::new(25.0, 3.0), [0, 0, 0], 255);
        assert_eq!(layer, before, "jumps, NaN and off-canvas segments draw nothing");
        draw_segment(&mut layer, w, h, Vec2::new(5.5, 9.5), Vec2::new(5.5, 0.5), [0, 0, 0], 255);
        assert_eq!(at(&layer, 5, 9), 0, "a steep segment going up covers its start");
        assert_eq!(at(&layer, 5, 0), 255, "and leaves its end");
    }

    #[test]
    fn an_igsa_path_is_drawn_with_handles_and_its_crossing_segment_in_red() {
        let mut scene = presets::igsa_path_2();
        if let PlannerConfig::Igsa(p) = &mut scene.groups[0].planner {
            // Through the wall (x 380…425 from y 150 down), then to the goal.
            p.waypoints = vec![[300.0, 420.0], [500.0, 420.0]];
        }
        let world = World::new(scene).expect("valid");
        let mut r = Renderer::new(800, 500);
        r.render(&world);
        let (hx, hy) = canvas_of(&r, Vec2::new(300.0, 420.0));
        assert_eq!(pixel(&r, hx, hy), [255, 255, 255, 255], "handle centre");
        // Middle of the crossing segment, left of the wall (inside it the wall is drawn first).
        let (cx, cy) = canvas_of(&r, Vec2::new(350.0, 420.0));
        let p = pixel(&r, cx, cy);
        assert!(p[0] > 200 && p[1] < 80 && p[2] < 80, "crossing segment is red: {p:?}");
    }

    #[test]
    fn fading_rounds_towards_the_base_in_both_directions() {
        let mut trail = vec![0u8, 255, 100, 101];
        let base = vec![255u8, 0, 100, 100];
        for _ in 0..300 {
            fade_row(&mut trail, &base, 3);
        }
        assert_eq!(trail, base);
    }

    /// Rows of the trail layer that differ from the base in the column halfway along the lone
    /// agent's track, and the agent's pixels that are not background, for a theme.
    fn trail_rows_and_agent_pixels(theme: Theme) -> (usize, usize, Renderer, usize) {
        let (world, mut r, start, end) = lone_agent_track(theme);
        let x = ((start.x + end.x) * 0.5) as usize;
        let rows = (0..400usize)
            .filter(|&y| {
                let at = (y * 800 + x) * 4;
                r.trails[at..at + 3] != r.base[at..at + 3]
            })
            .count();
        r.set_trails(false);
        r.render(&world);
        let (cx, cy) = (end.x as i64, end.y as i64);
        let agent = (cx - 30..cx + 30)
            .flat_map(|px| (cy - 30..cy + 30).map(move |py| (px as usize, py as usize)))
            .filter(|&(px, py)| {
                let at = (py * 800 + px) * 4;
                r.pixels()[at..at + 3] != r.base[at..at + 3]
            })
            .count();
        (rows, agent, r, x)
    }

    #[test]
    fn the_projector_theme_draws_a_white_field_dark_obstacles_thick_trails_and_larger_agents() {
        assert_eq!(Theme::from_name("projector"), Some(Theme::Projector));
        assert_eq!(Theme::from_name("standard"), Some(Theme::Standard));
        assert_eq!(Theme::from_name("neon"), None);
        let (thin, small, standard, _) = trail_rows_and_agent_pixels(Theme::Standard);
        let (thick, large, projector, x) = trail_rows_and_agent_pixels(Theme::Projector);
        // Standard trails are 2 px (3 rows where the Wu lines straddle a pixel), projector ones 3 px.
        assert!(thin <= 3 && thick > thin, "trail rows: standard {thin}, projector {thick}");
        assert!(large as f32 > 1.8 * small as f32, "agent pixels: standard {small}, projector {large}");
        assert_eq!(pixel(&standard, 5, 5)[..3], BACKGROUND_COLOR);
        assert_eq!(pixel(&projector, 5, 5)[..3], PROJECTOR.background);
        // Projector trails are dark (red at half brightness, mostly opaque: white is 765).
        let darkest = (0..400usize)
            .map(|y| {
                let at = (y * 800 + x) * 4;
                projector.trails[at..at + 3].iter().map(|&c| u32::from(c)).sum::<u32>()
            })
            .min();
        assert!(darkest.is_some_and(|sum| sum < 400), "no dark trail pixel: {darkest:?}");

        let world = World::new(presets::pillars()).expect("valid");
        let mut r = Renderer::new(900, 560);
        r.set_theme(Theme::Projector);
        r.render(&world);
        let Obstacle::Circle { center, .. } = world.scene().obstacles[0] else {
            panic!("pillars are circles")
        };
        let (x, y) = canvas_of(&r, Vec2::from(center));
        assert_eq!(pixel(&r, x, y)[..3], PROJECTOR.obstacle);
    }

    #[test]
    fn switching_back_to_the_standard_theme_draws_what_a_fresh_renderer_draws() {
        let mut world = World::new(presets::pillars()).expect("valid");
        let mut fresh = Renderer::new(450, 280);
        let mut switched = Renderer::new(450, 280);
        switched.set_theme(Theme::Projector);
        switched.render(&world);
        assert_ne!(switched.pixels(), fresh.pixels());
        world.step_n(30);
        switched.set_theme(Theme::Standard);
        assert_eq!(switched.theme(), Theme::Standard);
        fresh.render(&world);
        switched.render(&world);
        assert!(fresh.pixels() == switched.pixels(), "the standard theme is drawn as before");
    }
}
