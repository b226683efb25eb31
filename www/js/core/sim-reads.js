// Which calls of the wasm `Sim` handle only read, shared by the simulation worker
// (core/sim-worker.js) and the page's proxy of it (core/sim-proxy.js): the page keeps a mirror of
// the reads below, refreshed with every frame and every reply, so code that only reads the state
// (the metrics panel, the timeline, the page API's `metrics()`) stays synchronous.

/** Reads refreshed with every frame and every reply: they change as the run steps. */
export const FRAME_READS = Object.freeze([
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
  'width',
  'height',
]);

/** Reads refreshed after a call that may change the scene or the view (not after a step). */
export const SCENE_READS = Object.freeze([
  'scene_json',
  'scene_string',
  'seed',
  'theme',
  'overlays_json',
  'activity_json',
]);

/** The mirrored reads: the page answers them from its mirror, without asking the worker. */
export const MIRRORED = new Set([...FRAME_READS, ...SCENE_READS]);

/**
 * Reads with arguments (or too big for every frame) the page may subscribe to: the first read
 * asks for them, every later frame brings them while they are read.
 */
export const SUBSCRIBABLE = new Set(['history_steps', 'history_series']);

/** Every call that changes nothing: no render, no scene refresh after it. */
export const PURE_READS = new Set([
  ...MIRRORED,
  ...SUBSCRIBABLE,
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
  'history_csv',
  'recorded_digest',
]);

/** Calls that change the run's state but never the scene (no scene refresh after them). */
export const SCENE_KEEPING = new Set(['step', 'reset', 'clear_trails', 'inspect', 'set_selection', 'render', 'advance_planning']);
