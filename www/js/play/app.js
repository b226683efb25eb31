// The shell's shared state: the simulation (a `Sim` handle in a worker, reached through
// core/sim-proxy.js), what the UI shows, and the one door every call goes through (so every thrown
// error reaches the banner and a panic reaches the panel). A call that changes the simulation
// returns a Promise settled once the worker answered; reads answer from the mirror at once.

import { History } from './history.js';
import { SimHost, after } from '../core/sim-host.js';

/** Colours handed to new groups, in order: Okabe–Ito, colour-blind safe (src/model/palette.rs). */
export const PALETTE = ['#0072b2', '#d55e00', '#009e73', '#cc79a7', '#e69f00', '#56b4e9', '#000000', '#f0e442'];

export class App extends SimHost {
  /**
   * @param {object} wasm   the instance exports returned by `init()` (for `memory`)
   * @param {object} module the JS bindings (`presets_json`, `preset_scene_json`, …)
   * @param {object} remote the RemoteSim whose `handle` stands for the `Sim`
   */
  constructor(wasm, module, remote) {
    super(wasm, module, remote.handle);
    this.remote = remote;
    this.history = new History(200);
    this.activeGroup = 0;
    this.selection = null;
    this.trails = true;
    this.trailFade = 0.01;
    this.scene = JSON.parse(this.sim.scene_json());
  }

  /**
   * Runs a scene-changing call (`edit`, `load`, `set_group_param`, …) through `guard`, records the
   * scene before it for undo, and tells the UI. `record: false` skips the undo entry (undo itself,
   * a slider drag whose entry is recorded once at the end).
   */
  change(fn, { rethrow = false, record = true, clearSelection = true } = {}) {
    const before = this.crashed ? null : this.sim.scene_json();
    return after(this.guard(fn, { rethrow }), (result) => {
      if (!result.ok) return;
      if (record && before !== null) {
        this.history.record(before);
        this.dispatchEvent(new Event('history'));
      }
      if (clearSelection) this.select(null);
      this.sceneChanged();
    });
  }

  /** Loads scene text (JSON or fragment) as one undoable change; a Promise of the result. */
  load(text, options = {}) {
    return after(this.change((sim) => sim.load(text), options), (result) => {
      if (result.ok) this.afterLoad();
    });
  }

  /**
   * Clears stale state after a new scene arrived. A loaded scene brings its own view options
   * (trails, fade: they travel in shared links); with `keepView` (undo/redo) the current ones
   * are kept instead.
   */
  afterLoad({ keepView = false } = {}) {
    const result = this.guard((sim) => {
      if (keepView) {
        sim.set_trails(this.trails);
        sim.set_trail_fade(this.trailFade);
      }
      // A different run with as many agents would otherwise draw jumps from the old positions.
      sim.clear_trails();
    });
    // Told at once (the scene the mirror holds) and again once the view options are applied.
    this.sceneChanged();
    return after(result, () => this.sceneChanged());
  }

  /** Changes the view options (saved in the scene, so the link keeps them; not an undo step). */
  setView({ trails = this.trails, trailFade = this.trailFade } = {}) {
    const result = this.guard((sim) => {
      sim.set_trails(trails);
      sim.set_trail_fade(trailFade);
    });
    return after(result, () => this.sceneChanged());
  }

  /** Refreshes the cached scene and tells the panels. */
  sceneChanged() {
    if (this.crashed) return;
    const result = this.guard((sim) => JSON.parse(sim.scene_json()));
    if (result.ok) {
      this.scene = result.value;
      if (this.scene.view) {
        this.trails = this.scene.view.trails;
        this.trailFade = this.scene.view.trail_fade;
      }
    }
    const groups = this.scene.groups?.length ?? 0;
    if (this.activeGroup >= groups) this.activeGroup = Math.max(0, groups - 1);
    this.dirty = true;
    this.dispatchEvent(new Event('scene'));
  }

  /** Marks a group as the one the panel edits and new goals attach to. */
  setActiveGroup(index) {
    this.activeGroup = index;
    this.dispatchEvent(new Event('scene'));
  }

  /** Sets (or clears, with null) the highlighted item. */
  select(item) {
    this.selection = item;
    this.guard((sim) => sim.set_selection(item ? JSON.stringify(item) : 'null'));
    this.dirty = true;
    this.dispatchEvent(new Event('selection'));
  }

  /** Steps back to the scene before the last change. */
  undo() {
    this.travel(this.history.undoStack, this.history.redoStack);
  }

  /** Re-applies the last undone change. */
  redo() {
    this.travel(this.history.redoStack, this.history.undoStack);
  }

  travel(from, to) {
    if (from.length === 0 || this.crashed) return undefined;
    const target = from.pop();
    const current = this.sim.scene_json();
    return after(this.change((sim) => sim.load(target), { record: false }), (result) => {
      if (result.ok) {
        to.push(current);
        this.afterLoad({ keepView: true });
      } else {
        from.push(target);
      }
      this.dispatchEvent(new Event('history'));
    });
  }

  /** The next palette colour no group uses yet. */
  nextColor() {
    const used = new Set((this.scene.groups ?? []).map((g) => g.color.toLowerCase()));
    return PALETTE.find((c) => !used.has(c)) ?? PALETTE[(this.scene.groups?.length ?? 0) % PALETTE.length];
  }

  /** The spec list of a planner by name. */
  plannerSpec(name) {
    return this.planners.find((p) => p.name === name);
  }

  /** A planner config with every parameter at its default (from the params table). */
  defaultPlanner(name = this.planners[0]?.name) {
    const spec = this.plannerSpec(name);
    const params = {};
    for (const p of spec?.params ?? []) {
      params[p.key] = p.choices && p.choices.length ? p.choices[p.default] : p.default;
    }
    return { kind: name, params };
  }
}
