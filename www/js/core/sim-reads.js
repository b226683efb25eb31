// Which calls of a wasm simulation handle only read, per handle kind (`Sim`: the playground, the
// element, the tune preview; `CompareSim`: the compare page's panes), shared by the simulation
// worker (core/sim-worker.js) and the page's proxy of it (core/sim-proxy.js): the page keeps a
// mirror of the reads below, refreshed with every frame and every reply, so code that only reads
// the state (the metrics panel, the timeline, the page API's `metrics()`) stays synchronous.

const SIM = {
  /** Reads refreshed with every frame and every reply: they change as the run steps. */
  frame: [
    'steps',
    'metrics_json',
    'digest',
    'planning_progress',
    'can_cancel_planning',
    'timeline_json',
    'goals_json',
    'stuck_agents',
    'inspected',
    'explanation_json',
    'activity_report_json',
    'capacity_notices_json',
    'history_json',
    'recording_json',
    // Fitted by the renderer: read after each render (a resize, a new scene size).
    'view',
    'view_zoom',
    'width',
    'height',
  ],
  /** Reads refreshed after a call that may change the scene (not after a step). */
  scene: ['scene_json', 'scene_string', 'seed', 'theme', 'overlays_json', 'activity_json'],
  /**
   * Reads with arguments (or too big for every frame) the page may subscribe to: the first read
   * asks for them, every later frame brings them while they are read.
   */
  subscribable: ['history_steps', 'history_series'],
  /** Further calls that change nothing: no render, no scene refresh after them. */
  pure: [
    'pick',
    'agent_at',
    'pick_waypoint',
    'group_path_json',
    'positions_json',
    'export_paths_csv',
    'export_paths_json',
    'export_maya_mel',
    'export_blender_py',
    'export_trails_svg',
    'export_pedpy_text',
    'export_jupedsim_script',
    'history_csv',
    'recorded_digest',
  ],
  /** Calls that change the run's state but never the scene (no scene refresh after them). */
  sceneKeeping: [
    'step', 'reset', 'clear_trails', 'inspect', 'set_selection', 'render', 'advance_planning',
    // Zoom and pan change the view only (src/web/zoom.rs).
    'zoom_view', 'pan_view', 'fit_view',
  ],
};

const COMPARE_SIM = {
  frame: [
    'steps',
    'pane_steps_json',
    'metrics_json',
    'series_json',
    'summary_json',
    'digests_json',
    'activity_report_json',
    'width',
    'height',
  ],
  scene: ['panes_json', 'pane_count', 'max_panes', 'scene_json', 'scene_string', 'spec_string'],
  subscribable: [],
  pure: ['summary_csv'],
  sceneKeeping: ['step', 'reset'],
};

/** The sets of one handle kind: `frame`, `scene`, `mirrored`, `subscribable`, `pure`, `sceneKeeping`. */
function setsOf({ frame, scene, subscribable, pure, sceneKeeping }) {
  const mirrored = new Set([...frame, ...scene]);
  return Object.freeze({
    frame: Object.freeze([...frame]),
    scene: Object.freeze([...scene]),
    mirrored,
    subscribable: new Set(subscribable),
    pure: new Set([...mirrored, ...subscribable, ...pure]),
    sceneKeeping: new Set(sceneKeeping),
  });
}

/** The read tables by handle kind (the wasm class's name). */
export const READS = Object.freeze({ Sim: setsOf(SIM), CompareSim: setsOf(COMPARE_SIM) });
