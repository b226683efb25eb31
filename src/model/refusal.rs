//! Errors as data: every refusal a user can meet is a [`Message`], a stable [`Code`] with named,
//! typed [`Arg`]s. Its English text (the `Display` of every core error, what the CLI prints and
//! scripts read) is rendered from the code's English template ([`Code::english`]); the pages
//! word the same code from their own template in the reader's language
//! (`www/js/core/messages/<lang>.js`), so no front-end ever reads an English sentence to make
//! another one. Codes and argument names are a contract with those files: add freely, never
//! rename (a test checks every code has a template in every language with the same arguments).
//!
//! Template syntax: `{name}` is an argument; `{name:?}` is a text argument in double quotes
//! (Rust's `{:?}`); `{name:and}` / `{name:or}` are lists joined with "and" / "or"; a brace not
//! followed by a name and `}` or `:` is literal text (`{…}`).
//!
//! Layer: model (plain data about the model's own errors; higher layers add their codes here).

use std::fmt;

/// A refusal with a stable code and typed arguments beside its English message.
pub trait Refusal: fmt::Display {
    /// The refusal as data: its code and arguments.
    fn message(&self) -> Message;

    /// The stable name of this kind of refusal (`scene.field`, `lab.unknown_algorithm`, …).
    fn code(&self) -> &'static str {
        self.message().code.as_str()
    }
}

/// One argument of a message.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// Text shown as it is: a name, a field path, a value as the user wrote it.
    Text(String),
    /// A whole number (counts, indices counted from 1, limits).
    Int(i64),
    /// A number (a limit, a coordinate): the page formats it by its language's rules.
    Num(f64),
    /// Names (known presets, planners): joined by the template's `:and` / `:or`, or by commas.
    List(Vec<String>),
    /// A word the page has in its strings table (`planner.boids`, `unit.px/step`), with its
    /// English: planner and parameter labels, units. Boxed to keep every error small.
    Term(Box<Term>),
    /// A message inside a message (the reason a scene could not be read, what a field allows).
    Message(Box<Message>),
}

impl Arg {
    /// An `f32` as the number its shortest decimal text spells (`0.1`, not `0.100000001…`).
    pub fn f32(x: f32) -> Arg {
        Arg::Num(x.to_string().parse().unwrap_or(f64::from(x)))
    }

    /// A term of the strings table ([`Arg::Term`]).
    pub fn term(key: impl Into<String>, english: impl Into<String>) -> Arg {
        Arg::Term(Box::new(Term { key: key.into(), english: english.into() }))
    }

    fn render(&self, spec: &str, out: &mut String) {
        match self {
            Arg::Text(t) if spec == "?" => out.push_str(&format!("{t:?}")),
            Arg::Text(t) => out.push_str(t),
            Arg::Int(n) => out.push_str(&n.to_string()),
            Arg::Num(x) => out.push_str(&x.to_string()),
            Arg::List(items) => {
                let items: Vec<String> = if spec == "?" {
                    items.iter().map(|i| format!("{i:?}")).collect()
                } else {
                    items.clone()
                };
                let joined = match (spec, items.split_last()) {
                    ("and" | "or", Some((last, rest))) if !rest.is_empty() => {
                        format!("{} {spec} {last}", rest.join(", "))
                    }
                    _ => items.join(", "),
                };
                out.push_str(&joined);
            }
            Arg::Term(term) => out.push_str(&term.english),
            Arg::Message(m) => out.push_str(&m.to_string()),
        }
    }
}

/// A word of the page's strings table ([`Arg::Term`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    /// The strings table key.
    pub key: String,
    /// Its English words.
    pub english: String,
}

impl Arg {
    /// The text of a [`Arg::Text`].
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Arg::Text(t) => Some(t),
            _ => None,
        }
    }
}

/// As the English message shows it.
impl fmt::Display for Arg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        self.render("", &mut out);
        f.write_str(&out)
    }
}

/// A text argument equals its text (a value as written: `f.value == "NaN"`).
impl PartialEq<&str> for Arg {
    fn eq(&self, other: &&str) -> bool {
        self.as_text() == Some(*other)
    }
}

impl From<String> for Arg {
    fn from(s: String) -> Self {
        Arg::Text(s)
    }
}

impl From<&str> for Arg {
    fn from(s: &str) -> Self {
        Arg::Text(s.to_string())
    }
}

impl From<Message> for Arg {
    fn from(m: Message) -> Self {
        Arg::Message(Box::new(m))
    }
}

impl From<Vec<String>> for Arg {
    fn from(items: Vec<String>) -> Self {
        Arg::List(items)
    }
}

impl From<Vec<&str>> for Arg {
    fn from(items: Vec<&str>) -> Self {
        Arg::List(items.into_iter().map(str::to_string).collect())
    }
}

impl From<f64> for Arg {
    fn from(x: f64) -> Self {
        Arg::Num(x)
    }
}

impl From<f32> for Arg {
    fn from(x: f32) -> Self {
        Arg::f32(x)
    }
}

macro_rules! whole_numbers {
    ($($t:ty),*) => {$(
        impl From<$t> for Arg {
            fn from(n: $t) -> Self {
                Arg::Int(i64::try_from(n).unwrap_or(i64::MAX))
            }
        }
    )*};
}
whole_numbers!(u8, u16, u32, u64, usize, i32, i64);

/// A code with its arguments: what every front-end words.
#[derive(Clone, Debug, PartialEq)]
pub struct Message {
    /// What kind of message this is.
    pub code: Code,
    /// Its arguments by name, in the order given.
    pub args: Vec<(&'static str, Arg)>,
}

impl Message {
    /// A message of `code` without arguments (add them with [`Message::with`]).
    pub fn new(code: Code) -> Self {
        Message { code, args: Vec::new() }
    }

    /// The message with one more argument.
    pub fn with(mut self, name: &'static str, value: impl Into<Arg>) -> Self {
        // The templates of every language name the same arguments: one the template lacks
        // would be lost in every language.
        debug_assert!(self.code.arg_names().contains(&name), "{} has no argument {name}", self.code.as_str());
        self.args.push((name, value.into()));
        self
    }

    /// The argument `name`, if given.
    pub fn arg(&self, name: &str) -> Option<&Arg> {
        self.args.iter().find(|(n, _)| *n == name).map(|(_, a)| a)
    }

    /// The argument `name` as text (a text's own words, a number's digits, a message's English).
    pub fn arg_text(&self, name: &str) -> Option<String> {
        self.arg(name).map(|a| {
            let mut out = String::new();
            a.render("", &mut out);
            out
        })
    }
}

impl fmt::Display for Message {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = String::new();
        for piece in pieces(self.code.english()) {
            match piece {
                Piece::Text(t) => out.push_str(t),
                Piece::Arg(name, spec) => match self.arg(name) {
                    Some(arg) => arg.render(spec, &mut out),
                    // A missing argument shows as its placeholder (a test guards against it).
                    None => out.push_str(&format!("{{{name}}}")),
                },
            }
        }
        f.write_str(&out)
    }
}

impl Refusal for Message {
    fn message(&self) -> Message {
        self.clone()
    }
}

impl serde::Serialize for Arg {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        match self {
            Arg::Text(t) => s.serialize_str(t),
            Arg::Int(n) => s.serialize_i64(*n),
            Arg::Num(x) => s.serialize_f64(*x),
            Arg::List(items) => items.serialize(s),
            Arg::Term(term) => {
                let mut map = s.serialize_map(Some(2))?;
                map.serialize_entry("term", &term.key)?;
                map.serialize_entry("english", &term.english)?;
                map.end()
            }
            Arg::Message(m) => m.serialize(s),
        }
    }
}

/// `{code, args, message}`: the shape every error crosses the wasm boundary in.
impl serde::Serialize for Message {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        struct Args<'a>(&'a [(&'static str, Arg)]);
        impl serde::Serialize for Args<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut map = s.serialize_map(Some(self.0.len()))?;
                for (name, arg) in self.0 {
                    map.serialize_entry(name, arg)?;
                }
                map.end()
            }
        }
        let mut map = s.serialize_map(Some(3))?;
        map.serialize_entry("code", self.code.as_str())?;
        map.serialize_entry("args", &Args(&self.args))?;
        map.serialize_entry("message", &self.to_string())?;
        map.end()
    }
}

/// A part of a template.
#[derive(Debug, PartialEq)]
enum Piece<'a> {
    Text(&'a str),
    /// An argument's name and its format (`""`, `"?"`, `"and"`, `"or"`).
    Arg(&'a str, &'a str),
}

/// The pieces of `template` (see the module's syntax).
fn pieces(template: &str) -> Vec<Piece<'_>> {
    let mut out = Vec::new();
    let mut rest = template;
    while let Some(open) = rest.find('{') {
        let after = &rest[open + 1..];
        let name_len = after.find(|c: char| !(c.is_ascii_lowercase() || c == '_')).unwrap_or(after.len());
        let placeholder = (name_len > 0)
            .then(|| {
                let tail = &after[name_len..];
                if let Some(close) = tail.strip_prefix('}') {
                    Some((&after[..name_len], "", close))
                } else {
                    let spec_and_more = tail.strip_prefix(':')?;
                    let end = spec_and_more.find('}')?;
                    Some((&after[..name_len], &spec_and_more[..end], &spec_and_more[end + 1..]))
                }
            })
            .flatten();
        match placeholder {
            Some((name, spec, close)) => {
                if open > 0 {
                    out.push(Piece::Text(&rest[..open]));
                }
                out.push(Piece::Arg(name, spec));
                rest = close;
            }
            None => {
                out.push(Piece::Text(&rest[..open + 1]));
                rest = after;
            }
        }
    }
    if !rest.is_empty() {
        out.push(Piece::Text(rest));
    }
    out
}

macro_rules! codes {
    ($( #[doc = $doc:literal] $variant:ident = $code:literal => $english:literal, )*) => {
        /// Every kind of message the core can produce, with its English template.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Code {
            $( #[doc = $doc] $variant, )*
        }

        impl Code {
            /// Every code, in declaration order: what the template tests walk.
            pub const ALL: &'static [Code] = &[ $( Code::$variant, )* ];

            /// The stable dotted name (`scene.field`).
            pub fn as_str(self) -> &'static str {
                match self { $( Code::$variant => $code, )* }
            }

            /// The English template (see the module's syntax).
            pub fn english(self) -> &'static str {
                match self { $( Code::$variant => $english, )* }
            }
        }
    };
}

impl Code {
    /// The template's argument names, in order of first use.
    pub fn arg_names(self) -> Vec<&'static str> {
        let mut names = Vec::new();
        for piece in pieces(self.english()) {
            if let Piece::Arg(name, _) = piece {
                if !names.contains(&name) {
                    names.push(name);
                }
            }
        }
        names
    }

    /// The code named `name`, if any.
    pub fn from_name(name: &str) -> Option<Code> {
        Code::ALL.iter().copied().find(|c| c.as_str() == name)
    }
}

codes! {
    /// A scene text or string that could not be read.
    SceneParse = "scene.parse" => "cannot read the scene: {reason}",
    /// A scene string without `2.`.
    SceneNoVersion = "scene.no_version" => "the scene string has no version prefix (expected \"{expected}.…\")",
    /// A scene string of a version this build does not read.
    SceneUnknownVersion = "scene.unknown_version" => "unknown scene format version {version:?}; this flockpath reads versions {readable:and}",
    /// A scene string whose base64 does not decode.
    SceneBadBase64 = "scene.bad_base64" => "the scene string is not valid base64 ({reason}); was it cut short?",
    /// base64: a byte that is no base64 symbol.
    Base64InvalidSymbol = "base64.invalid_symbol" => "Invalid symbol {symbol}, offset {offset}.",
    /// base64: the last symbol has bits set past the data.
    Base64InvalidLastSymbol = "base64.invalid_last_symbol" => "Invalid last symbol {symbol}, offset {offset}.",
    /// base64: a length no encoding gives.
    Base64InvalidLength = "base64.invalid_length" => "Invalid input length: {length}",
    /// base64: padding where none belongs.
    Base64InvalidPadding = "base64.invalid_padding" => "Invalid padding",
    /// A scene string whose deflate data is broken.
    SceneDamaged = "scene.damaged" => "the scene string is damaged or truncated: was it cut short when copied?",
    /// A scene string that unpacks to bytes that are not UTF-8.
    SceneNotText = "scene.not_text" => "the scene string does not hold text",
    /// Nothing to read.
    SceneEmpty = "scene.empty" => "the scene text is empty",
    /// JSON that ends in the middle.
    SceneCutShort = "scene.cut_short" => "the scene text ends too early (line {line}, column {column}): was it cut short?",
    /// Text that is not JSON.
    SceneNotJson = "scene.not_json" => "the scene text is not valid JSON: {reason} (line {line}, column {column}, in {path})",
    /// JSON that is not a scene object.
    SceneNotObject = "scene.not_object" => "the text is not a scene object ({reason}, line {line}, column {column})",
    /// A scene string that does not hold a version 2 scene.
    SceneNotV2 = "scene.not_v2" => "the scene string does not hold a version 2 scene ({reason})",
    /// More text after the scene's JSON.
    SceneTrailingText = "scene.trailing_text" => "unexpected text after the end of the scene (line {line}, column {column})",
    /// A refused field: its path, its value and what is allowed.
    SceneField = "scene.field" => "{path} is {value}; allowed: {allowed}",
    /// Input over a size limit, size unknown.
    SceneTooLarge = "scene.too_large" => "{what} is too large (limit {limit} bytes)",
    /// Input over a size limit.
    SceneTooLargeBytes = "scene.too_large_bytes" => "{what} is too large ({bytes} bytes; limit {limit} bytes)",
    /// What was too large: the scene text.
    WhatSceneText = "what.scene_text" => "the scene text",
    /// What was too large: the unpacked scene string.
    WhatUnpackedScene = "what.unpacked_scene" => "the unpacked scene string",
    /// What was too large: the scene's link.
    WhatSceneLink = "what.scene_link" => "the scene's link",
    /// A bare name that names no preset.
    SceneUnknownPreset = "scene.unknown_preset" => "unknown preset '{name}' (known: {known})",
    /// A goal inside an obstacle.
    SceneGoalInObstacle = "scene.goal_in_obstacle" => "goals[{goal}] at ({x}, {y}) is inside obstacles[{obstacle}]; a goal must lie outside every obstacle",
    /// A group's crowd does not fit its spawn region.
    SceneDensity = "scene.density" => "group {group} ({name}): {count} agents of radius {radius} px do not fit in its spawn region ({width}×{height} px): it holds at most {most} apart from each other, the obstacles and the other groups (the density limit)",
    /// The groups' flow fields over their memory limit.
    SceneFlowFieldMemory = "scene.flow_field_memory" => "{path}: the groups' {fields} distinct flow fields ({cells} cells each: one per goal and body radius among the groups guided by a field) would keep {mb} MB, over the {limit_mb} MB limit; let groups share a goal or steer straight at it (guidance: goal)",
    /// IGSA planning over its limit.
    ScenePlanningCost = "scene.planning_cost" => "group {group} ({name}): igsa path planning of all groups would check {checks} path segments (population × iterations × (waypoints + 1), this group {this}), over the limit of {limit}: lower the population or the iterations",
    /// An edit or call names an item that does not exist.
    SceneNoSuchItem = "scene.no_such_item" => "there is no {item} {number}",
    /// A path given to a group whose planner does not follow paths.
    ScenePathNeedsBoids = "scene.path_needs_boids" => "group {group} uses {planner}; path following is part of Boids steering",
    /// A move by a distance that is not a number.
    SceneMoveNotFinite = "scene.move_not_finite" => "the move distance is not a finite number",
    /// Start positions that do not match the agents.
    SceneStartPositions = "scene.start_positions" => "{given} start positions for {total} agents",
    /// An activity the page sent that does not read.
    SceneBadActivity = "scene.bad_activity" => "the activity is not valid: {reason}",
    /// A planner name that names no planner.
    PlannerUnknown = "planner.unknown" => "unknown planner {name:?}; known: {known}",
    /// A planner parameter outside its table's range.
    ParamRange = "param.range" => "{label} ({key}) is {value}; allowed: {allowed}",
    /// A parameter key the planner does not have.
    ParamUnknown = "param.unknown" => "{planner} has no parameter {key:?}",
    /// A parameter value of the wrong JSON type.
    ParamType = "param.type" => "{label}: {problem}",
    /// Too many edited IGSA waypoints.
    WaypointsTooMany = "waypoints.too_many" => "an edited path holds at most {most} waypoints, this one {count}",
    /// An edited IGSA waypoint that is not a finite point.
    WaypointNotFinite = "waypoints.not_finite" => "waypoint {number} is not a finite point",
    /// Edited waypoints that are not a list of points.
    WaypointsNotList = "waypoints.not_list" => "the waypoints are not a list of [x, y] points: {reason}",
    /// Waypoints for a group that does not plan a path.
    WaypointsNotIgsa = "waypoints.not_igsa" => "group {group} does not follow a planned path (its planner is not igsa)",
    /// A parameter value the page sent that is not JSON.
    ValueNotJson = "page.value_not_json" => "the value for {key:?} is not JSON: {reason}",
    /// JSON from the page that does not read as the call's input.
    PageUnreadable = "page.unreadable" => "cannot read the {what}: {reason}",
    /// A theme name that names no theme.
    ThemeUnknown = "theme.unknown" => "unknown theme {name:?}; known: {known}",
    /// An export's frame rate outside 1…240.
    ExportFrameRate = "export.frame_rate" => "the frame rate must be 1…240 fps, not {value}",
    /// An export's scale that is not a number above 0.
    ExportScale = "export.scale" => "the scale must be a number > 0, not {value}",
    /// A comparison refused: the reason inside.
    Compare = "compare.refused" => "comparison: {reason}",
    /// A comparison spec over its size limit.
    CompareSpecTooLarge = "compare.spec_too_large" => "the spec is {bytes} bytes, over the {limit}-byte limit",
    /// An empty comparison spec.
    CompareSpecEmpty = "compare.spec_empty" => "the spec is empty",
    /// A spec without `1.`.
    CompareSpecNoVersion = "compare.spec_no_version" => "the spec has no version prefix (expected \"{expected}.…\")",
    /// A spec of another version.
    CompareSpecVersion = "compare.spec_version" => "unknown spec version {version:?}; this flockpath reads version {readable}",
    /// Too many panes.
    ComparePanesTooMany = "compare.panes_too_many" => "{count} panes; at most {most}",
    /// Panes outside 1…max.
    ComparePanesCount = "compare.panes_count" => "{count} panes; a comparison has 1 to {most}",
    /// A pane number that names no pane.
    CompareNoPane = "compare.no_pane" => "there is no pane {number}",
    /// A pane setting a group the scene does not have.
    ComparePaneGroupMissing = "compare.pane_group_missing" => "the pane sets group {group} but the scene has {count} group(s)",
    /// A group that is not a number.
    ComparePaneNotGroup = "compare.pane_not_group" => "{text:?} is not a group number (groups count from 1)",
    /// Group 0.
    ComparePaneGroupZero = "compare.pane_group_zero" => "groups count from 1, not 0",
    /// An empty pane.
    ComparePaneEmpty = "compare.pane_empty" => "a pane is empty (write `scene` for the scene's own planners)",
    /// A pane's every-group planner given twice.
    ComparePaneAllTwice = "compare.pane_all_twice" => "a pane sets the planner for every group twice",
    /// A pane setting one group twice.
    ComparePaneGroupTwice = "compare.pane_group_twice" => "a pane sets group {group} twice",
    /// A parameter list without `)`.
    ComparePaneNoParen = "compare.pane_no_paren" => "{text:?}: the parameter list has no closing `)`",
    /// More parameter values than the planner has.
    ComparePaneParamCount = "compare.pane_param_count" => "{planner} takes {count} parameters, the pane gives {given}",
    /// A parameter value that is not a number.
    ComparePaneParamNumber = "compare.pane_param_number" => "{label} ({planner}) must be a number, not {value:?}",
    /// A parameter value outside its range.
    ComparePaneParamRange = "compare.pane_param_range" => "{label} ({planner}) = {value} is outside {min}…{max} {unit}",
    /// A parameter value that is not finite.
    ComparePaneParamFinite = "compare.pane_param_finite" => "{label} ({planner}) is not a finite number",
    /// A choice parameter given another word.
    ComparePaneParamChoice = "compare.pane_param_choice" => "{label} ({planner}) must be one of [{choices:?}], not {value:?}",
    /// A planner refused inside a pane: its name and the reason.
    ComparePanePlanner = "compare.pane_planner" => "{planner}: {reason}",
    /// A parameter set on a pane that runs the scene's planners.
    ComparePaneSceneParam = "compare.pane_scene_param" => "this pane runs the scene's own planners: pick a planner for it first",
    /// A refused value: none given.
    ValueMissing = "value.missing" => "missing",
    /// A refused value: a key the object does not have.
    ValueUnknownKey = "value.unknown_key" => "an unknown key",
    /// A refused value: a number JSON could not hold.
    ValueNotFinite = "value.not_finite" => "not a finite number (too large, infinite or NaN)",
    /// A refused value the reader could not show.
    ValueRefused = "value.refused" => "refused",
    /// A refused list, by its length.
    ValueListOf = "value.list_of" => "a list of {count}",
    /// A refused list of parameter values, by its length.
    ValueListOfValues = "value.list_of_values" => "a list of {count} values",
    /// Polygon points over the scene's limit.
    ValuePolygonPoints = "value.polygon_points" => "{count} polygon points in all",
    /// Agents over the scene's limit.
    ValueAgentsInAll = "value.agents_in_all" => "{count} agents in all",
    /// A polygon of too few distinct points.
    ValuePolygonFew = "value.polygon_few" => "a polygon of {count} distinct point(s)",
    /// A polygon without area.
    ValuePolygonNoArea = "value.polygon_no_area" => "a polygon with no area (its points lie on one line)",
    /// A polygon folding back on itself (edges as `2→3`).
    ValuePolygonFolds = "value.polygon_folds" => "a polygon whose edges {a} and {b} fold back onto each other",
    /// A polygon whose edges cross.
    ValuePolygonCross = "value.polygon_cross" => "a polygon whose edges {a} and {b} cross or touch",
    /// A JSON string with a lone surrogate escape.
    ValueLoneSurrogate = "value.lone_surrogate" => "an invalid string (the lone surrogate {escape})",
    /// A JSON string with an unknown escape.
    ValueBadEscape = "value.bad_escape" => "an invalid string (the escape {escape})",
    /// A JSON string with a raw control character.
    ValueRawControl = "value.raw_control" => "an invalid string (the control character {character} written as it is)",
    /// A text by its length and start (`start` quoted; `more` is `…` when cut).
    ValueTextOf = "value.text_of" => "text of {count} character(s) ({start:?}{more})",
    /// A text holding a control character (`U+000A`).
    ValueTextControl = "value.text_control" => "text holding the control character {character}",
    /// An optimizer name that names no optimizer.
    LabUnknownAlgorithm = "lab.unknown_algorithm" => "unknown algorithm {name:?}; known: {known}",
    /// A benchmark function name that names none.
    LabUnknownFunction = "lab.unknown_function" => "unknown function {name:?}; known: {known}",
    /// A lab size outside the page's limits.
    LabOutOfRange = "lab.out_of_range" => "{setting} {value} is outside {min}…{max}",
    /// The lab's dimension.
    LabDimension = "lab.dimension" => "dimension",
    /// The lab's population.
    LabPopulation = "lab.population" => "population",
    /// The lab's iterations.
    LabIterations = "lab.iterations" => "iterations",
    /// Tuning settings that do not read.
    TuneSettings = "tune.settings" => "cannot read the tuning settings: {reason}",
    /// An unknown behaviour code.
    TuneUnknownBehaviour = "tune.unknown_behaviour" => "unknown behaviour {name:?}; known: b1, b2, b3",
    /// An unknown environment code.
    TuneUnknownEnvironment = "tune.unknown_environment" => "unknown environment {name:?}; known: e1, e2, e3",
    /// Frames per evaluation out of range.
    TuneFrames = "tune.frames" => "frames {value} is outside 1…{most}",
    /// Generations out of range.
    TuneGenerations = "tune.generations" => "generations {value} is outside 1…{most}",
    /// Population out of range.
    TunePopulation = "tune.population" => "population {value} is outside 2…{most}",
    /// Sample interval out of range.
    TuneSampleEvery = "tune.sample_every" => "sample interval {every} is outside 1…{frames} (the frames per evaluation)",
    /// Rates outside 0…1.
    TuneRates = "tune.rates" => "crossover and mutation rates must be in 0…1",
    /// A scene without agents to tune.
    TuneNoAgents = "tune.no_agents" => "the scene has no agents to tune",
    /// A run that evaluated nothing.
    TuneNothing = "tune.nothing" => "the run evaluated nothing",
    /// An unknown validation test.
    ValidationUnknownTest = "validation.unknown_test" => "unknown test {name:?}",
    /// An unknown planner name in the validation page.
    ValidationUnknownPlanner = "validation.unknown_planner" => "unknown planner {name:?}",
    /// An unknown reference curve.
    ValidationUnknownCurve = "validation.unknown_curve" => "unknown reference curve {name:?}; known: {known}",
    /// A planner without a speed parameter for the validation suite.
    ValidationNoSpeed = "validation.no_speed_param" => "{planner} has no speed parameter to set",
    /// A classroom option naming an unknown name.
    ClassroomUnknownName = "classroom.unknown_name" => "{field}: unknown name {name:?}; allowed: {known} (or all, none)",
    /// A classroom option too long.
    ClassroomTooLong = "classroom.too_long" => "{field}: the value is {bytes} bytes long; at most {most}",
    /// An edit of a locked part.
    ClassroomLocked = "classroom.locked" => "the {part} are locked in this scene: the page cannot add, move, change or delete them",
    /// The system's random source failed.
    Entropy = "seed.entropy" => "cannot draw a fresh seed: the system's random source failed ({reason})",
    /// The optimizer experiments had nothing to run.
    OptimizeNothing = "optimize.nothing" => "optimize: nothing to run (no algorithm, function or run)",
    /// A metrics series the run does not have.
    NoSeries = "page.no_series" => "no metrics series {key:?} for group {group}",
    /// A timeline call on a run without one.
    NoTimeline = "page.no_timeline" => "this run keeps no timeline",
    /// A selected item the page sent that does not read.
    BadSelection = "page.bad_selection" => "cannot read the selected item: {reason}",
    /// A classroom edit the page sent that does not read.
    NotAnEdit = "page.not_an_edit" => "not an edit: {reason}",
    /// A zip entry name that is empty, absolute or climbs out of the archive's folder.
    ZipBadName = "zip.bad_name" => "cannot put {name:?} in a zip: a file name must be a relative path without \"..\" or empty parts",
    /// The same zip entry name twice.
    ZipDuplicate = "zip.duplicate" => "the zip already has a file {name:?}",
    /// A zip past the format's limits without zip64.
    ZipTooLarge = "zip.too_large" => "the zip would be larger than {bytes} bytes or {entries} files",
    /// A link for an LMS package without an activity.
    ScormNoActivity = "scorm.no_activity" => "this scene has no activity: an LMS package grades an activity's check (add one with Share… → Activity)",
    /// An activity without a check in an LMS package.
    ScormNoCheck = "scorm.no_check" => "this activity has no check: an LMS package scores the check, so give it one (Share… → Activity)",
    /// A check that only the compare page can decide.
    ScormCompareOnly = "scorm.compare_only" => "this activity's check names panes of the compare page: an LMS package runs one scene, so its check must not name a pane",
    /// A page file the package needs but was not given.
    ScormMissingFile = "scorm.missing_file" => "the LMS package needs the page file {name:?}, which was not found (build the wasm first: bash scripts/build-wasm.sh)",
}

impl Refusal for crate::rng::EntropyError {
    fn message(&self) -> Message {
        Message::new(Code::Entropy).with("reason", self.source_text())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_dotted() {
        let mut seen = std::collections::HashSet::new();
        for code in Code::ALL {
            assert!(seen.insert(code.as_str()), "{} twice", code.as_str());
            assert!(code.as_str().contains('.'), "{}", code.as_str());
            assert_eq!(Code::from_name(code.as_str()), Some(*code));
        }
    }

    #[test]
    fn templates_render_their_arguments() {
        let m = Message::new(Code::SceneUnknownVersion).with("version", "9").with("readable", vec!["1", "2"]);
        assert_eq!(
            m.to_string(),
            "unknown scene format version \"9\"; this flockpath reads versions 1 and 2"
        );
        assert_eq!(Code::SceneUnknownVersion.arg_names(), ["version", "readable"]);
        // A brace without a name is text.
        assert_eq!(pieces("a {…} b"), [Piece::Text("a {"), Piece::Text("…} b")]);
    }
}
