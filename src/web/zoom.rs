//! The playground's zoom and pan: the renderer draws the scene through a view (the whole scene
//! fitted, or a zoomed part of it); the page only maps wheel, pinch, keys and drags to these
//! calls. A view changes pixels only: the run, its digest and the scene are untouched, and every
//! pointer position the editor maps through `view()` lands on the scene point under it.

use super::Sim;
use glam::Vec2;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
impl Sim {
    /// Zooms by `factor` (above 1 in, below 1 out) about the canvas point `(x, y)` (device px),
    /// which keeps the scene point under it; between the whole scene and
    /// [`crate::render::MAX_ZOOM`] times closer. Trails are redrawn for the new view.
    pub fn zoom_view(&mut self, x: f32, y: f32, factor: f32) {
        let before = self.renderer.view();
        self.renderer.zoom_about(Vec2::new(x, y), factor);
        self.redraw_after_view_change(before);
    }

    /// Moves a zoomed view by `(dx, dy)` device px, the scene following the pointer.
    pub fn pan_view(&mut self, dx: f32, dy: f32) {
        let before = self.renderer.view();
        self.renderer.pan_by(Vec2::new(dx, dy));
        self.redraw_after_view_change(before);
    }

    /// Shows the whole scene again.
    pub fn fit_view(&mut self) {
        let before = self.renderer.view();
        self.renderer.fit_view();
        self.redraw_after_view_change(before);
    }

    /// The zoom over the fitted view (1: the whole scene shows).
    pub fn view_zoom(&self) -> f32 {
        self.renderer.zoom()
    }
}

impl Sim {
    /// Redraws the trails in the new view, when the view changed.
    fn redraw_after_view_change(&mut self, before: crate::render::ViewTransform) {
        self.renderer.render(self.run.world());
        if self.renderer.view() != before {
            self.redraw_trails();
        }
    }

    /// Redraws the trails from the recorded positions before the current step (the timeline's
    /// quantised frames, every `frame_every`-th step once thinned): after a jump, or a view
    /// change that moved every pixel (a zoom or a pan).
    pub(super) fn redraw_trails(&mut self) {
        let world = self.run.world();
        let from = self.renderer.trail_rebuild_start(world);
        let now = world.step_count();
        let frames = self.run.replay().map_or(&[][..], |r| r.frame_steps());
        let recorded = frames.iter().copied().skip_while(|&s| s < from).take_while(|&s| s <= now);
        let history = recorded.map_while(|s| Some((s, self.run.replay()?.positions_at(s)?)));
        self.renderer.rebuild_trails(world, history);
    }
}
