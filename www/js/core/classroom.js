// The classroom options (teacher-locked scenes: `controls=`, `lock=`, `hide=` beside the scene in
// a link, attributes of the same names on <flock-path>) as every page reads them. Rust parses
// and validates them (the wasm `Classroom` handle, src/model/classroom.rs); this module only turns
// its answer into plain data and its refusals into messages in the page's language.

import { t } from './i18n.js';

/** A refused option's message in the page's language (the core's words when it has no key). */
export function classroomMessage(error) {
  if (error && typeof error.field === 'string' && typeof error.name === 'string') {
    return t('classroom.unknownName', { field: error.field, name: error.name, allowed: error.allowed });
  }
  return error instanceof Error ? error.message : String(error);
}

/**
 * Reads a wasm `Classroom` handle: `{ handle, view, errors }` where `view` is
 * `{controls, lock, hide, locked_tools, can_load, open, fragment, attributes}` and `errors` the
 * messages of the refused options (each left allowing everything).
 */
export function readClassroom(handle) {
  const view = JSON.parse(handle.view_json());
  const errors = handle.errors().map(classroomMessage);
  return { handle, view, errors };
}
