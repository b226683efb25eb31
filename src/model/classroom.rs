//! Teacher-locked scenes: which controls students get, which parts of the scene they may edit
//! through the page, and which panels are hidden. Parsed from the link options (`controls=`,
//! `lock=`, `hide=`) and `<flock-path>` attributes of the same names, and written back for the
//! Share dialog; the page only applies the result to its DOM.
//!
//! These are page options beside the scene, like `autoplay` and `theme`, not part of the scene:
//! a run, its digest and the CLI ignore them, and a student loading another scene keeps the
//! teacher's options. Every option is a list of names: a link without an option allows
//! everything (every link written before the options existed), and each name, once released, is
//! read with the same meaning by every later build (names are added, never renamed or removed;
//! `tests/data/classroom/` pins the released ones). A name this build does not know is
//! refused with a message naming the option and the allowed names, never read as something else.

use crate::model::edit::{Edit, ItemRef};
use crate::model::refusal::{Arg, Code, Message, Refusal};
use serde::Serialize;
use std::collections::BTreeSet;

/// A closed set of names released in links.
pub trait Named: Copy + Ord + 'static {
    /// Every value, in the order links write them.
    const ALL: &'static [Self];
    /// Its name in links and attributes.
    fn name(self) -> &'static str;
}

/// A control students may be given (`controls=`). Controls not listed are not shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Control {
    /// Play / pause (button and Space).
    Play,
    /// Single step (button and S).
    Step,
    /// Reset to step 0 (button and R).
    Reset,
    /// Steps per frame (playground slider).
    Speed,
    /// The planner menu (playground), the planner's name (iframe and element).
    Planner,
    /// The planner's parameter sliders and Defaults (playground).
    Params,
    /// The seed field and New seed (playground).
    Seed,
    /// Trails on/off, fade and Clear trails (playground).
    Trails,
    /// The Scene menu of presets (playground).
    Presets,
    /// Undo and redo (buttons and Ctrl+Z).
    Undo,
    /// Share… (playground).
    Share,
    /// Export… (playground).
    Export,
    /// Links to the other views: Compare, Tune, Optimizer lab, Validation (playground).
    Views,
    /// Full screen (iframe and element).
    Fullscreen,
}

impl Named for Control {
    const ALL: &'static [Self] = &[
        Self::Play,
        Self::Step,
        Self::Reset,
        Self::Speed,
        Self::Planner,
        Self::Params,
        Self::Seed,
        Self::Trails,
        Self::Presets,
        Self::Undo,
        Self::Share,
        Self::Export,
        Self::Views,
        Self::Fullscreen,
    ];

    fn name(self) -> &'static str {
        match self {
            Self::Play => "play",
            Self::Step => "step",
            Self::Reset => "reset",
            Self::Speed => "speed",
            Self::Planner => "planner",
            Self::Params => "params",
            Self::Seed => "seed",
            Self::Trails => "trails",
            Self::Presets => "presets",
            Self::Undo => "undo",
            Self::Share => "share",
            Self::Export => "export",
            Self::Views => "views",
            Self::Fullscreen => "fullscreen",
        }
    }
}

/// A part of the scene the page may lock (`lock=`): its editor tools are withdrawn, dragging
/// or deleting such an item does nothing, and its panel fields are read-only.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Part {
    /// Obstacles of every shape.
    Obstacles,
    /// Goals.
    Goals,
    /// Groups: spawn regions and their settings in the Groups panel.
    Groups,
    /// Paths (the Boids path tool) and the waypoints of IGSA groups' planned paths.
    Paths,
}

impl Named for Part {
    const ALL: &'static [Self] = &[Self::Obstacles, Self::Goals, Self::Groups, Self::Paths];

    fn name(self) -> &'static str {
        match self {
            Self::Obstacles => "obstacles",
            Self::Goals => "goals",
            Self::Groups => "groups",
            Self::Paths => "paths",
        }
    }
}

impl Part {
    /// The playground's editor tools that add this part.
    pub fn tools(self) -> &'static [&'static str] {
        match self {
            Self::Obstacles => &["circle", "rect", "polygon"],
            Self::Goals => &["goal"],
            Self::Groups => &["group"],
            Self::Paths => &["path"],
        }
    }

    /// The part an item of the scene belongs to.
    pub fn of(item: ItemRef) -> Self {
        match item {
            ItemRef::Obstacle(_) => Self::Obstacles,
            ItemRef::Goal(_) => Self::Goals,
            ItemRef::Group(_) => Self::Groups,
            ItemRef::Path(_) => Self::Paths,
        }
    }
}

/// A panel the page may hide (`hide=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Panel {
    /// The live metrics card.
    Metrics,
    /// Plots over time.
    Plots,
    /// Diagnose: overlays and the agent inspector.
    Diagnose,
    /// The timeline bar.
    Timeline,
    /// The Groups card.
    Groups,
    /// The keyboard help card.
    Keys,
}

impl Named for Panel {
    const ALL: &'static [Self] =
        &[Self::Metrics, Self::Plots, Self::Diagnose, Self::Timeline, Self::Groups, Self::Keys];

    fn name(self) -> &'static str {
        match self {
            Self::Metrics => "metrics",
            Self::Plots => "plots",
            Self::Diagnose => "diagnose",
            Self::Timeline => "timeline",
            Self::Groups => "groups",
            Self::Keys => "keys",
        }
    }
}

/// The three options, by the key links and attributes use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `controls=`: the controls shown.
    Controls,
    /// `lock=`: the parts students cannot edit.
    Lock,
    /// `hide=`: the panels hidden.
    Hide,
}

impl Field {
    /// Every field, in the order links write them.
    pub const ALL: [Field; 3] = [Field::Controls, Field::Lock, Field::Hide];

    /// Its key in links and its attribute name.
    pub fn key(self) -> &'static str {
        match self {
            Self::Controls => "controls",
            Self::Lock => "lock",
            Self::Hide => "hide",
        }
    }

    /// The names it accepts, in order.
    pub fn names(self) -> Vec<&'static str> {
        match self {
            Self::Controls => names_of::<Control>(),
            Self::Lock => names_of::<Part>(),
            Self::Hide => names_of::<Panel>(),
        }
    }
}

fn names_of<T: Named>() -> Vec<&'static str> {
    T::ALL.iter().map(|v| v.name()).collect()
}

/// Longest option value read (bytes): every name of a field, repeated, is far shorter.
pub const MAX_OPTION_BYTES: usize = 1_000;

/// A refused option: the field, what was wrong and what is allowed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ClassroomError {
    /// A name the field does not know.
    #[error("{}: unknown name {name:?}; allowed: {} (or all, none)", field.key(), field.names().join(", "))]
    UnknownName {
        /// The option.
        field: Field,
        /// The name as written (at most 40 characters of it).
        name: String,
    },
    /// A value longer than [`MAX_OPTION_BYTES`].
    #[error("{}: the value is {bytes} bytes long; at most {MAX_OPTION_BYTES}", field.key())]
    TooLong {
        /// The option.
        field: Field,
        /// Its length.
        bytes: usize,
    },
}

impl ClassroomError {
    /// The option refused.
    pub fn field(&self) -> Field {
        match self {
            Self::UnknownName { field, .. } | Self::TooLong { field, .. } => *field,
        }
    }
}

/// An edit refused because its part is locked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the {} are locked in this scene: the page cannot add, move, change or delete them", part.name())]
pub struct Locked {
    /// The locked part the edit would change.
    pub part: Part,
}

/// What students get: the controls shown, the parts locked, the panels hidden. The default
/// allows everything.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Classroom {
    controls: BTreeSet<Control>,
    locked: BTreeSet<Part>,
    hidden: BTreeSet<Panel>,
}

impl Default for Classroom {
    fn default() -> Self {
        Self {
            controls: Control::ALL.iter().copied().collect(),
            locked: BTreeSet::new(),
            hidden: BTreeSet::new(),
        }
    }
}

/// The options' raw values, as a link or an element carries them (`None`: option absent).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options<'a> {
    /// `controls=`.
    pub controls: Option<&'a str>,
    /// `lock=`.
    pub lock: Option<&'a str>,
    /// `hide=`.
    pub hide: Option<&'a str>,
}

/// What a value stands for before its names are looked up.
enum Whole {
    All,
    None,
    List,
}

fn whole(field: Field, text: &str) -> Whole {
    match text {
        // An empty value is a bare attribute (`<flock-path controls>`): the option is on.
        "" | "all" => Whole::All,
        "none" => Whole::None,
        // The iframe's spellings from before the lists (`embed.html#…&controls=0`).
        "1" | "true" if field == Field::Controls => Whole::All,
        "0" | "false" if field == Field::Controls => Whole::None,
        _ => Whole::List,
    }
}

/// Parses one option's value: a comma-separated list of names (case and spaces around names do
/// not matter, empty items are skipped), or `all` / `none` (an empty value means `all`).
pub fn parse_list<T: Named>(field: Field, text: &str) -> Result<BTreeSet<T>, ClassroomError> {
    if text.len() > MAX_OPTION_BYTES {
        return Err(ClassroomError::TooLong { field, bytes: text.len() });
    }
    let text = text.trim();
    let lower = text.to_ascii_lowercase();
    match whole(field, &lower) {
        Whole::All => return Ok(T::ALL.iter().copied().collect()),
        Whole::None => return Ok(BTreeSet::new()),
        Whole::List => {}
    }
    let mut set = BTreeSet::new();
    for (raw, name) in text.split(',').zip(lower.split(',')) {
        let name = name.trim();
        if name.is_empty() {
            continue;
        }
        let value = T::ALL.iter().copied().find(|v| v.name() == name).ok_or_else(|| {
            ClassroomError::UnknownName { field, name: raw.trim().chars().take(40).collect() }
        })?;
        set.insert(value);
    }
    Ok(set)
}

/// `a,b,c` in table order.
fn join<T: Named>(set: &BTreeSet<T>) -> String {
    T::ALL.iter().filter(|v| set.contains(v)).map(|v| v.name()).collect::<Vec<_>>().join(",")
}

/// The page's view of a [`Classroom`], as JSON for the shell.
#[derive(Debug, Serialize)]
pub struct ClassroomView {
    /// The controls shown, by name.
    pub controls: Vec<&'static str>,
    /// The parts locked, by name.
    pub lock: Vec<&'static str>,
    /// The panels hidden, by name.
    pub hide: Vec<&'static str>,
    /// The playground's editor tools withdrawn (they add a locked part).
    pub locked_tools: Vec<&'static str>,
    /// Whether the page may replace the scene (presets, a scene file): not when a part is locked.
    pub can_load: bool,
    /// Whether everything is allowed (the options are all absent).
    pub open: bool,
    /// The link options (`controls=…&lock=…&hide=…`, empty when everything is allowed).
    pub fragment: String,
    /// The `<flock-path>` attributes (` controls="…" lock="…"`, with a leading space each).
    pub attributes: String,
}

impl Classroom {
    /// Reads the three options; every refused one is reported and left at its default
    /// (everything allowed), while the others apply. The page uses this: a typo in `hide=`
    /// should not drop the teacher's locks.
    pub fn from_options_lenient(options: Options<'_>) -> (Classroom, Vec<ClassroomError>) {
        let mut classroom = Classroom::default();
        let mut errors = Vec::new();
        if let Some(text) = options.controls {
            match parse_list(Field::Controls, text) {
                Ok(set) => classroom.controls = set,
                Err(e) => errors.push(e),
            }
        }
        if let Some(text) = options.lock {
            match parse_list(Field::Lock, text) {
                Ok(set) => classroom.locked = set,
                Err(e) => errors.push(e),
            }
        }
        if let Some(text) = options.hide {
            match parse_list(Field::Hide, text) {
                Ok(set) => classroom.hidden = set,
                Err(e) => errors.push(e),
            }
        }
        (classroom, errors)
    }

    /// Reads the three options; the first refused one is the error.
    pub fn from_options(options: Options<'_>) -> Result<Classroom, ClassroomError> {
        let (classroom, errors) = Self::from_options_lenient(options);
        match errors.into_iter().next() {
            Some(e) => Err(e),
            None => Ok(classroom),
        }
    }

    /// A classroom from sets of names (the Share dialog's ticks).
    pub fn new(
        controls: impl IntoIterator<Item = Control>,
        locked: impl IntoIterator<Item = Part>,
        hidden: impl IntoIterator<Item = Panel>,
    ) -> Classroom {
        Classroom {
            controls: controls.into_iter().collect(),
            locked: locked.into_iter().collect(),
            hidden: hidden.into_iter().collect(),
        }
    }

    /// Whether everything is allowed.
    pub fn is_open(&self) -> bool {
        self == &Classroom::default()
    }

    /// Whether `control` is shown.
    pub fn allows(&self, control: Control) -> bool {
        self.controls.contains(&control)
    }

    /// Whether `part` is locked.
    pub fn is_locked(&self, part: Part) -> bool {
        self.locked.contains(&part)
    }

    /// Whether `panel` is hidden.
    pub fn hides(&self, panel: Panel) -> bool {
        self.hidden.contains(&panel)
    }

    /// Whether the page may replace the whole scene (a preset, a scene file): that would change
    /// locked parts, so not while any part is locked. The page API may, always.
    pub fn can_load(&self) -> bool {
        self.locked.is_empty()
    }

    /// The options that differ from "everything allowed", as `(key, value)` in link order.
    /// Lists are written name by name (never `all`), so a link keeps its meaning when later
    /// builds add names.
    pub fn options(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        if self.controls.len() != Control::ALL.len() {
            let list = join(&self.controls);
            out.push((Field::Controls.key(), if list.is_empty() { "none".to_string() } else { list }));
        }
        if !self.locked.is_empty() {
            out.push((Field::Lock.key(), join(&self.locked)));
        }
        if !self.hidden.is_empty() {
            out.push((Field::Hide.key(), join(&self.hidden)));
        }
        out
    }

    /// The link options: `controls=play,step&lock=obstacles`, empty when everything is allowed.
    pub fn fragment(&self) -> String {
        self.options().iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join("&")
    }

    /// The `<flock-path>` attributes, each with a leading space. The element shows no control
    /// bar without `controls`, so every control is a bare ` controls`, none is no attribute.
    pub fn attributes(&self) -> String {
        let mut out = String::new();
        if self.controls.len() == Control::ALL.len() {
            out.push_str(" controls");
        } else if !self.controls.is_empty() {
            out.push_str(&format!(" controls=\"{}\"", join(&self.controls)));
        }
        if !self.locked.is_empty() {
            out.push_str(&format!(" lock=\"{}\"", join(&self.locked)));
        }
        if !self.hidden.is_empty() {
            out.push_str(&format!(" hide=\"{}\"", join(&self.hidden)));
        }
        out
    }

    /// The editor tools withdrawn because they add a locked part.
    pub fn locked_tools(&self) -> Vec<&'static str> {
        self.locked.iter().flat_map(|p| p.tools().iter().copied()).collect()
    }

    /// The page's view: names, withdrawn tools, and the texts to write back.
    pub fn view(&self) -> ClassroomView {
        let names = |set: Vec<&'static str>| set;
        ClassroomView {
            controls: names(Control::ALL.iter().filter(|c| self.allows(**c)).map(|c| c.name()).collect()),
            lock: names(Part::ALL.iter().filter(|p| self.is_locked(**p)).map(|p| p.name()).collect()),
            hide: names(Panel::ALL.iter().filter(|p| self.hides(**p)).map(|p| p.name()).collect()),
            locked_tools: self.locked_tools(),
            can_load: self.can_load(),
            open: self.is_open(),
            fragment: self.fragment(),
            attributes: self.attributes(),
        }
    }

    /// The edit the page may send for `edit`, or the locked part it would change. Adding a goal
    /// or a path for a group also changes that group: with groups locked the new item is still
    /// added, without the link to the group (the groups keep their settings).
    pub fn check_edit(&self, edit: &Edit) -> Result<Edit, Locked> {
        let refuse = |part: Part| if self.is_locked(part) { Err(Locked { part }) } else { Ok(()) };
        let mut allowed = edit.clone();
        match &mut allowed {
            Edit::AddObstacle { .. } => refuse(Part::Obstacles)?,
            Edit::AddGoal { group, .. } => {
                refuse(Part::Goals)?;
                if self.is_locked(Part::Groups) {
                    *group = None;
                }
            }
            Edit::AddPath { group, .. } => {
                refuse(Part::Paths)?;
                if self.is_locked(Part::Groups) {
                    *group = None;
                }
            }
            Edit::AddGroup { .. } | Edit::SetGroup { .. } => refuse(Part::Groups)?,
            Edit::Move { item, .. } | Edit::Delete { item } => refuse(Part::of(*item))?,
        }
        Ok(allowed)
    }
}

/// Every field's names as JSON `{controls: [...], lock: [...], hide: [...]}`: what the Share
/// dialog offers to tick.
pub fn vocabulary() -> serde_json::Value {
    serde_json::json!({
        "controls": Field::Controls.names(),
        "lock": Field::Lock.names(),
        "hide": Field::Hide.names(),
    })
}

impl Refusal for ClassroomError {
    fn message(&self) -> Message {
        match self {
            ClassroomError::UnknownName { field, name } => Message::new(Code::ClassroomUnknownName)
                .with("field", field.key())
                .with("name", name.clone())
                .with("known", field.names()),
            ClassroomError::TooLong { field, bytes } => Message::new(Code::ClassroomTooLong)
                .with("field", field.key())
                .with("bytes", *bytes)
                .with("most", MAX_OPTION_BYTES),
        }
    }
}

impl Refusal for Locked {
    fn message(&self) -> Message {
        let part = self.part.name();
        Message::new(Code::ClassroomLocked).with("part", Arg::term(format!("classroom.part.{part}"), part))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::geometry::Obstacle;

    fn parse(
        controls: Option<&str>,
        lock: Option<&str>,
        hide: Option<&str>,
    ) -> Result<Classroom, ClassroomError> {
        Classroom::from_options(Options { controls, lock, hide })
    }

    #[test]
    fn absent_options_allow_everything() {
        let c = parse(None, None, None).expect("no options");
        assert!(c.is_open());
        assert!(Control::ALL.iter().all(|k| c.allows(*k)));
        assert!(Part::ALL.iter().all(|p| !c.is_locked(*p)));
        assert!(c.can_load());
        assert_eq!(c.fragment(), "");
        assert_eq!(c.attributes(), " controls");
    }

    #[test]
    fn lists_choose_exactly_their_names() {
        let c = parse(Some("play, Step,,reset,planner"), Some("obstacles,goals"), Some("metrics"))
            .expect("valid");
        let shown: Vec<_> = Control::ALL.iter().filter(|k| c.allows(**k)).map(|k| k.name()).collect();
        assert_eq!(shown, ["play", "step", "reset", "planner"]);
        assert!(c.is_locked(Part::Obstacles) && c.is_locked(Part::Goals));
        assert!(!c.is_locked(Part::Groups) && !c.is_locked(Part::Paths));
        assert!(c.hides(Panel::Metrics) && !c.hides(Panel::Plots));
        assert!(!c.can_load());
        assert_eq!(c.locked_tools(), ["circle", "rect", "polygon", "goal"]);
        assert_eq!(c.fragment(), "controls=play,step,reset,planner&lock=obstacles,goals&hide=metrics");
        assert_eq!(
            c.attributes(),
            " controls=\"play,step,reset,planner\" lock=\"obstacles,goals\" hide=\"metrics\""
        );
    }

    #[test]
    fn whole_values_and_the_iframes_old_spellings() {
        let none = parse(Some("none"), None, None).expect("none");
        assert!(Control::ALL.iter().all(|k| !none.allows(*k)));
        assert_eq!(none.fragment(), "controls=none");
        assert_eq!(none.attributes(), "", "no controls: the element shows no bar");
        assert_eq!(parse(Some("0"), None, None), Ok(none.clone()));
        assert_eq!(parse(Some("false"), None, None), Ok(none));
        for all in ["1", "true", "all", "", " ALL "] {
            assert!(parse(Some(all), None, None).expect("all").is_open(), "{all:?}");
        }
        let locked = parse(None, Some("all"), Some("")).expect("all");
        assert!(Part::ALL.iter().all(|p| locked.is_locked(*p)));
        assert!(Panel::ALL.iter().all(|p| locked.hides(*p)));
        assert_eq!(
            locked.fragment(),
            "lock=obstacles,goals,groups,paths&hide=metrics,plots,diagnose,timeline,groups,keys"
        );
        // 0 and 1 are the controls option's old spellings only.
        assert!(parse(None, Some("1"), None).is_err());
    }

    #[test]
    fn unknown_names_are_refused_naming_the_field_and_the_allowed_names() {
        let e = parse(None, Some("obstacles,walls"), None).expect_err("walls");
        assert_eq!(e, ClassroomError::UnknownName { field: Field::Lock, name: "walls".into() });
        assert_eq!(
            e.to_string(),
            "lock: unknown name \"walls\"; allowed: obstacles, goals, groups, paths (or all, none)"
        );
        let e = parse(Some("play,pause"), None, None).expect_err("pause");
        assert!(
            e.to_string().starts_with("controls: unknown name \"pause\"; allowed: play, step, reset, speed,"),
            "{e}"
        );
        let e = parse(None, None, Some("metric")).expect_err("metric");
        assert_eq!(e.field(), Field::Hide);
        assert!(e.to_string().contains("allowed: metrics, plots, diagnose, timeline, groups, keys"), "{e}");
        // A long name is cut in the message; a long value is refused outright.
        let long = "x".repeat(200);
        let ClassroomError::UnknownName { name, .. } = parse(None, Some(&long), None).expect_err("long")
        else {
            panic!("an unknown name")
        };
        assert_eq!(name.len(), 40);
        let huge = "play,".repeat(300);
        assert_eq!(
            parse(Some(&huge), None, None),
            Err(ClassroomError::TooLong { field: Field::Controls, bytes: huge.len() })
        );
    }

    #[test]
    fn the_lenient_reading_keeps_the_fields_that_parse() {
        let (c, errors) = Classroom::from_options_lenient(Options {
            controls: Some("play"),
            lock: Some("goals"),
            hide: Some("bogus"),
        });
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0].field(), Field::Hide);
        assert!(c.allows(Control::Play) && !c.allows(Control::Step));
        assert!(c.is_locked(Part::Goals));
        assert!(Panel::ALL.iter().all(|p| !c.hides(*p)), "the refused field stays at its default");
    }

    #[test]
    fn written_options_read_back_the_same() {
        let c = Classroom::new(
            [Control::Step, Control::Fullscreen],
            [Part::Paths, Part::Groups],
            [Panel::Timeline],
        );
        let options = c.options();
        let get = |key: &str| options.iter().find(|(k, _)| *k == key).map(|(_, v)| v.as_str());
        let back = parse(get("controls"), get("lock"), get("hide")).expect("round trip");
        assert_eq!(back, c);
        assert_eq!(c.fragment(), "controls=step,fullscreen&lock=groups,paths&hide=timeline");
    }

    #[test]
    fn locked_parts_refuse_their_edits_and_others_pass() {
        let c = parse(None, Some("obstacles,goals"), None).expect("valid");
        let circle = Obstacle::Circle { center: [10.0, 10.0], radius: 5.0 };
        let refused = |e: Edit| c.check_edit(&e).map_err(|l| l.part);
        assert_eq!(refused(Edit::AddObstacle { obstacle: circle }), Err(Part::Obstacles));
        assert_eq!(
            refused(Edit::Move { item: ItemRef::Obstacle(0), dx: 1.0, dy: 0.0 }),
            Err(Part::Obstacles)
        );
        assert_eq!(refused(Edit::Delete { item: ItemRef::Obstacle(0) }), Err(Part::Obstacles));
        assert_eq!(refused(Edit::Move { item: ItemRef::Goal(0), dx: 1.0, dy: 0.0 }), Err(Part::Goals));
        assert_eq!(
            refused(Edit::AddGoal { position: [1.0, 1.0], radius: None, group: Some(0) }),
            Err(Part::Goals)
        );
        let moved = Edit::Move { item: ItemRef::Group(0), dx: 1.0, dy: 0.0 };
        assert_eq!(c.check_edit(&moved), Ok(moved.clone()));
        let path = Edit::AddPath { points: vec![[0.0, 0.0], [1.0, 1.0]], radius: None, group: Some(0) };
        assert_eq!(c.check_edit(&path), Ok(path.clone()));
        assert_eq!(
            Locked { part: Part::Obstacles }.to_string(),
            "the obstacles are locked in this scene: the page cannot add, move, change or delete them"
        );
    }

    #[test]
    fn with_groups_locked_a_new_goal_is_added_without_retargeting_a_group() {
        let c = parse(None, Some("groups"), None).expect("valid");
        let goal = Edit::AddGoal { position: [1.0, 1.0], radius: None, group: Some(0) };
        assert_eq!(
            c.check_edit(&goal),
            Ok(Edit::AddGoal { position: [1.0, 1.0], radius: None, group: None })
        );
        let path = Edit::AddPath { points: vec![[0.0, 0.0], [1.0, 1.0]], radius: None, group: Some(1) };
        assert!(matches!(c.check_edit(&path), Ok(Edit::AddPath { group: None, .. })));
        assert!(c.check_edit(&Edit::Delete { item: ItemRef::Group(0) }).is_err());
    }

    #[test]
    fn every_field_lists_its_names_once() {
        for field in Field::ALL {
            let names = field.names();
            let unique: BTreeSet<_> = names.iter().collect();
            assert_eq!(unique.len(), names.len(), "{field:?}");
            assert!(!names.contains(&"all") && !names.contains(&"none"), "whole values are not names");
        }
        assert_eq!(vocabulary()["lock"], serde_json::json!(["obstacles", "goals", "groups", "paths"]));
    }
}
