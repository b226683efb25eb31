//! The classroom options' bindings (teacher-locked scenes): parse a link or `<flock-path>`
//! attributes, tell the page what to show, check an editor edit against the locks, and write the
//! Share dialog's ticks back as link options and attributes. Conversion only; the rules are
//! `model::classroom`'s.

use super::{coded, js_error, refused};
use crate::model::classroom::{self, ClassroomError, Named, Options};
use crate::model::codec;
use crate::model::edit::Edit;
use crate::model::refusal::{Code, Message};
use wasm_bindgen::prelude::*;

/// A refused option as a JS `Error` whose message is the core's, with `field` (the option),
/// `name` (the unknown name, when that was the fault) and `allowed` (its names, comma-separated)
/// for a translated message.
fn option_error(e: &ClassroomError) -> JsValue {
    let error = js_sys::Error::new(&e.to_string());
    let set = |key: &str, value: &str| {
        // Setting a property on a fresh Error object cannot fail.
        let _ = js_sys::Reflect::set(&error, &JsValue::from_str(key), &JsValue::from_str(value));
    };
    set("field", e.field().key());
    set("allowed", &e.field().names().join(", "));
    if let ClassroomError::UnknownName { name, .. } = e {
        set("name", name);
    }
    error.into()
}

/// The options a page applies, with the refusals met while reading them.
#[wasm_bindgen]
pub struct Classroom {
    inner: classroom::Classroom,
    errors: Vec<ClassroomError>,
}

#[wasm_bindgen]
impl Classroom {
    /// Reads `controls`, `lock` and `hide` values (`undefined`/`null`: option absent), as
    /// `<flock-path>` attributes or the Share dialog's ticks carry them. A refused option is
    /// left allowing everything and listed by [`Classroom::errors`].
    #[wasm_bindgen(constructor)]
    pub fn new(controls: Option<String>, lock: Option<String>, hide: Option<String>) -> Classroom {
        let (inner, errors) = classroom::Classroom::from_options_lenient(Options {
            controls: controls.as_deref(),
            lock: lock.as_deref(),
            hide: hide.as_deref(),
        });
        Classroom { inner, errors }
    }

    /// Reads the options of a link: a URL, a `#…` fragment or its text.
    pub fn from_link(link: &str) -> Classroom {
        let (inner, errors) = codec::classroom_from_link_lenient(link);
        Classroom { inner, errors }
    }

    /// The refused options, each a JS `Error` (see the module docs); empty when all parsed.
    pub fn errors(&self) -> Vec<JsValue> {
        self.errors.iter().map(option_error).collect()
    }

    /// The page's view as JSON: `{controls, lock, hide, locked_tools, can_load, open,
    /// fragment, attributes}` (names shown, locked, hidden; tools withdrawn; whether a scene may
    /// be loaded through the page; the texts to write back).
    pub fn view_json(&self) -> Result<String, JsError> {
        serde_json::to_string(&self.inner.view()).map_err(js_error)
    }

    /// The edit the editor may send for `edit_json` (perhaps without its group link), as JSON;
    /// throws an `Error` with `part` (the locked part's name) when a lock refuses it.
    pub fn check_edit(&self, edit_json: &str) -> Result<String, JsValue> {
        let edit: Edit = serde_json::from_str(edit_json)
            .map_err(|e| refused(Message::new(Code::NotAnEdit).with("reason", e.to_string())))?;
        match self.inner.check_edit(&edit) {
            Ok(allowed) => serde_json::to_string(&allowed).map_err(|e| js_error(e).into()),
            Err(locked) => {
                let error = coded(&locked);
                let _ = js_sys::Reflect::set(
                    &error,
                    &JsValue::from_str("part"),
                    &JsValue::from_str(locked.part.name()),
                );
                Err(error.into())
            }
        }
    }
}

/// The names each option accepts, as JSON `{controls: [...], lock: [...], hide: [...]}`.
#[wasm_bindgen]
pub fn classroom_vocabulary_json() -> String {
    classroom::vocabulary().to_string()
}

/// A classroom from the Share dialog's ticks: lists of names (an unknown name throws the
/// refusal, as a link would).
#[wasm_bindgen]
pub fn classroom_from_ticks(
    controls: Vec<String>,
    lock: Vec<String>,
    hide: Vec<String>,
) -> Result<Classroom, JsValue> {
    let list = |names: &[String]| if names.is_empty() { "none".to_string() } else { names.join(",") };
    let (controls, lock, hide) = (list(&controls), list(&lock), list(&hide));
    let parsed = classroom::Classroom::from_options(Options {
        controls: Some(&controls),
        lock: Some(&lock),
        hide: Some(&hide),
    })
    .map_err(|e| option_error(&e))?;
    Ok(Classroom { inner: parsed, errors: Vec::new() })
}
