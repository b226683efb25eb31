// The side panel: the group list and editor, the planner picker and the parameter sliders, all
// generated from `planners_json()` (the Rust params table), so a new planner needs no JS.

import { paramControl, paramHelp, paramLabel, paramReadout } from '../core/params-form.js';
import { onLanguageChange, t, tOr } from '../core/i18n.js';
import { messageOf } from '../core/errors.js';

/** The group form's field of each group key. */
const FIELD_OF = { name: 'name', count: 'count', color: 'color', goal: 'goal', agent_radius: 'radius' };

const el = (tag, props = {}, children = []) => {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(props)) {
    if (key === 'dataset') Object.assign(node.dataset, value);
    else if (key in node) node[key] = value;
    else node.setAttribute(key, value);
  }
  node.append(...children);
  return node;
};

export class Panel {
  constructor(app) {
    this.app = app;
    this.list = document.getElementById('group-list');
    this.groupForm = document.getElementById('group-editor');
    this.plannerSelect = document.getElementById('planner');
    this.params = document.getElementById('params');
    this.defaults = document.getElementById('params-defaults');
    /** Key of the generated controls: rebuilt only when it changes, so a slider being dragged survives. */
    this.builtFor = '';
    /** Scene before a slider gesture started; recorded for undo when the gesture ends. */
    this.pendingUndo = null;
    for (const planner of app.planners) {
      this.plannerSelect.append(el('option', { value: planner.name, textContent: tOr(`planner.${planner.name}`, planner.label) }));
    }
    // A language switch rebuilds the generated controls in the new words.
    onLanguageChange(() => {
      for (const option of this.plannerSelect.options) {
        const spec = app.plannerSpec(option.value);
        if (spec) option.textContent = tOr(`planner.${spec.name}`, spec.label);
      }
      this.builtFor = '';
      this.render();
    });
    this.plannerSelect.addEventListener('change', () => {
      const index = this.app.activeGroup;
      const name = this.plannerSelect.value;
      // A new planner restarts the run from the seed, as any other group edit does: agents that
      // had already arrived would otherwise show nothing of it until Reset.
      Promise.resolve(this.app.change((sim) => {
        sim.set_group_planner(index, name);
        sim.reset();
      }, { clearSelection: false })).then((result) => {
        if (result.ok) this.app.dispatchEvent(new Event('stepped'));
      });
    });
    this.defaults.addEventListener('click', () => this.resetParams());
    app.addEventListener('scene', () => this.render());
    this.render();
  }

  group() {
    return this.app.scene.groups?.[this.app.activeGroup] ?? null;
  }

  render() {
    const scene = this.app.scene;
    const group = this.group();
    const key = JSON.stringify([
      this.app.activeGroup,
      (scene.groups ?? []).map((g) => [g.name, g.color]),
      (scene.goals ?? []).length,
      (scene.paths ?? []).length,
      group?.planner?.kind,
    ]);
    if (key !== this.builtFor) {
      this.builtFor = key;
      this.buildList();
      this.buildGroupForm();
      this.buildParams();
    }
    this.fillValues();
  }

  buildList() {
    const groups = this.app.scene.groups ?? [];
    this.list.replaceChildren(
      ...groups.map((g, i) => {
        const button = el('button', {
          type: 'button',
          role: 'option',
          title: t('groups.edit', { n: i + 1 }),
          'aria-selected': String(i === this.app.activeGroup),
        }, [el('span', { className: 'swatch' }), g.name || t('groups.default_name', { n: i + 1 })]);
        button.querySelector('.swatch').style.background = g.color;
        button.addEventListener('click', () => {
          this.app.setActiveGroup(i);
          this.app.select({ kind: 'group', index: i });
        });
        return button;
      }),
    );
  }

  /**
   * Whole-group edit: every field change sends the full group through `edit` `set_group`. A
   * refused value does not stay in its field: the field shows the scene's value again, with the
   * refusal beside it (until the field's next accepted change), so what is shown is what runs.
   */
  updateGroup(patch) {
    const index = this.app.activeGroup;
    const group = this.group();
    if (!group) return;
    const field = this.fields?.[FIELD_OF[Object.keys(patch)[0]]] ?? null;
    const op = { op: 'set_group', index, group: { ...group, ...patch } };
    Promise.resolve(this.app.change((sim) => sim.edit(JSON.stringify(op)), { clearSelection: false })).then((result) => {
      if (result.pending) return;
      this.showRefusal(field, result.ok ? null : messageOf(result.error));
      if (!result.ok) this.fillValues({ even: field });
    });
  }

  /** Shows `message` beside `field` (null clears it), tied to the field for screen readers. */
  showRefusal(field, message) {
    if (!field) return;
    const row = field.closest('.row');
    let note = row?.nextElementSibling?.classList.contains('field-error') ? row.nextElementSibling : null;
    if (message === null) {
      note?.remove();
      field.removeAttribute('aria-invalid');
      field.removeAttribute('aria-describedby');
      return;
    }
    if (!note) {
      note = el('p', { className: 'field-error', id: `${field.name}-refused` });
      row?.after(note);
    }
    note.textContent = message;
    field.setAttribute('aria-invalid', 'true');
    field.setAttribute('aria-describedby', note.id);
  }

  buildGroupForm() {
    const group = this.group();
    if (!group) {
      this.groupForm.replaceChildren();
      return;
    }
    const goals = this.app.scene.goals ?? [];
    const row = (label, input) => el('label', { className: 'row' }, [el('span', { className: 'label', textContent: label }), input]);
    const name = el('input', { type: 'text', name: 'name', maxLength: 40 });
    name.addEventListener('change', () => this.updateGroup({ name: name.value }));
    const count = el('input', { type: 'number', name: 'count', min: 0, max: 200000, step: 1, title: t('groups.agents_title') });
    count.addEventListener('change', () => this.updateGroup({ count: Number(count.value) }));
    const color = el('input', { type: 'color', name: 'color', title: t('groups.colour_title') });
    color.addEventListener('change', () => this.updateGroup({ color: color.value }));
    const goal = el('select', { name: 'goal', title: t('groups.goal_title') }, [
      el('option', { value: '', textContent: t('groups.goal_none') }),
      ...goals.map((_, i) => el('option', { value: String(i), textContent: t('groups.goal_n', { n: i + 1 }) })),
    ]);
    goal.addEventListener('change', () => this.updateGroup({ goal: goal.value === '' ? null : Number(goal.value) }));
    const radius = el('input', { type: 'number', name: 'agent_radius', min: 0.5, max: 100, step: 0.5, title: t('groups.radius_title') });
    radius.addEventListener('change', () => this.updateGroup({ agent_radius: Number(radius.value) }));
    const remove = el('button', { type: 'button', className: 'small ghost', textContent: t('groups.delete'), title: t('groups.delete_title') });
    remove.addEventListener('click', () => {
      const item = { kind: 'group', index: this.app.activeGroup };
      this.app.change((sim) => sim.edit(JSON.stringify({ op: 'delete', item })));
    });
    this.groupForm.replaceChildren(
      row(t('groups.name'), name),
      row(t('groups.agents'), count),
      row(t('groups.colour'), color),
      row(t('groups.goal'), goal),
      row(t('groups.radius'), radius),
      remove,
    );
    this.fields = { name, count, color, goal, radius };
  }

  buildParams() {
    const group = this.group();
    this.plannerSelect.disabled = !group;
    this.defaults.disabled = !group;
    this.params.replaceChildren();
    this.sliders = new Map();
    if (!group) return;
    const planner = this.app.plannerSpec(group.planner.kind);
    if (!planner) return;
    for (const spec of planner.params) {
      const id = `param-${spec.key}`;
      const output = el('output', { htmlFor: id });
      let input;
      if (spec.key === 'path') {
        // A scene path by number, not a slider: "none" or one of the drawn paths.
        const paths = this.app.scene.paths ?? [];
        input = el('select', { id, name: spec.key, title: paramHelp(planner.name, spec) }, [
          el('option', { value: '0', textContent: t('planner.path_none') }),
          ...paths.map((_, i) => el('option', { value: String(i + 1), textContent: t('planner.path_n', { n: i + 1 }) })),
        ]);
        input.addEventListener('change', () => this.setParam(spec, Number(input.value), true));
      } else {
        input = paramControl(spec, {
          id,
          planner: planner.name,
          onInput: (value) => this.setParam(spec, value, false),
          onChange: (value) => this.setParam(spec, value, true),
        });
      }
      const label = el('label', { className: 'label', htmlFor: id, textContent: paramLabel(planner.name, spec), title: paramHelp(planner.name, spec) });
      this.params.append(el('div', { className: 'param', dataset: { key: spec.key } }, [label, output, input]));
      this.sliders.set(spec.key, { spec, input, output });
    }
  }

  /**
   * Applies one parameter live. A drag sends many `input` events; the scene before the first is
   * kept and recorded for undo once, when the gesture ends (`change`).
   */
  setParam(spec, value, endOfGesture) {
    const index = this.app.activeGroup;
    if (this.pendingUndo === null) this.pendingUndo = this.app.sim.scene_json();
    const pending = this.app.change((sim) => sim.set_group_param(index, spec.key, JSON.stringify(value)), {
      record: false,
      clearSelection: false,
    });
    // The simulation worker answers in order: the gesture's end sees every value it sent applied.
    Promise.resolve(pending).then((result) => {
      if (endOfGesture || !result.ok) {
        if (result.ok && this.pendingUndo !== null && this.pendingUndo !== this.app.sim.scene_json()) {
          this.app.history.record(this.pendingUndo);
          this.app.dispatchEvent(new Event('history'));
        }
        this.pendingUndo = null;
      }
      this.showParam(spec.key);
    });
  }

  /** Puts every parameter of the active group back to its table default (one undo step). */
  resetParams() {
    const group = this.group();
    if (!group) return;
    const defaults = this.app.defaultPlanner(group.planner.kind);
    const index = this.app.activeGroup;
    this.app.change((sim) => {
      for (const [key, value] of Object.entries(defaults.params)) {
        sim.set_group_param(index, key, JSON.stringify(value));
      }
    }, { clearSelection: false });
  }

  showParam(key) {
    const entry = this.sliders?.get(key);
    const value = this.group()?.planner?.params?.[key];
    if (!entry || value === undefined) return;
    const { spec, input, output } = entry;
    if (document.activeElement !== input || input.tagName === 'SELECT') input.value = String(value);
    output.textContent = input.tagName === 'SELECT' ? '' : paramReadout(spec, value);
  }

  /** Shows the active group's values; `even`: a field refilled although it has the focus. */
  fillValues({ even = null } = {}) {
    // By position, not by searching the list for each button (5,000 groups: 17 s of the page's thread).
    [...this.list.children].forEach((button, index) => {
      const selected = String(index === this.app.activeGroup);
      if (button.getAttribute('aria-selected') !== selected) button.setAttribute('aria-selected', selected);
    });
    const group = this.group();
    if (!group) return;
    this.plannerSelect.value = group.planner.kind;
    const f = this.fields;
    const set = (input, value) => {
      if (document.activeElement !== input || input === even) input.value = value;
    };
    set(f.name, group.name ?? '');
    set(f.count, String(group.count));
    set(f.color, group.color);
    set(f.goal, group.goal === null || group.goal === undefined ? '' : String(group.goal));
    set(f.radius, String(group.agent_radius));
    for (const key of this.sliders.keys()) this.showParam(key);
  }
}
