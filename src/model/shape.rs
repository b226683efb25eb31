//! Why a JSON value does not fit a type, as data: the scene's types are read from a
//! `serde_json::Value` through [`check`], whose error ([`ShapeError`]) keeps what serde's
//! derived code reports through `serde::de::Error`'s typed constructors (an unknown key and the
//! keys allowed, a missing key, a value of the wrong kind, a list of the wrong length) and what
//! kind of value the type asked for ([`Expected`], from the `deserialize_*` method it called).
//! The codec words a refusal from these, never from a parser's English, so its messages do not
//! change when serde or serde_json reword theirs.
//!
//! Layer: model (reads the model's own types).

use serde::de::value::{MapAccessDeserializer, MapDeserializer, SeqDeserializer};
use serde::de::{self, Deserializer, IntoDeserializer, Unexpected, Visitor};
use serde_json::Value;
use std::fmt;

/// What a type reported about the value it was given.
#[derive(Clone, Debug, PartialEq)]
pub enum Fault {
    /// A value of another kind (text where a number belongs).
    WrongKind,
    /// A value of the right kind outside what the type holds (`-1` for a whole number); `key` is
    /// the text when the value was text (a tagged planner's unknown key arrives this way).
    BadValue {
        /// The refused text, when the value was text.
        text: Option<String>,
    },
    /// A list of `len` items where another length belongs.
    Length {
        /// Items given.
        len: usize,
    },
    /// A name that names no choice.
    UnknownVariant {
        /// The name given.
        name: String,
        /// Every choice.
        known: &'static [&'static str],
    },
    /// A key the object does not have.
    UnknownKey {
        /// The key given.
        name: String,
        /// The keys it has.
        known: &'static [&'static str],
    },
    /// A key the object needs.
    MissingKey {
        /// The key.
        name: &'static str,
    },
    /// A key given twice.
    DuplicateKey {
        /// The key.
        name: &'static str,
    },
    /// A value that fits none of the shapes a field takes (an untagged choice: a compact
    /// obstacle that is neither circle, rectangle nor polygon), or that a field's own reader
    /// refused.
    NoShapeFits,
}

/// The kind of value a type asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Expected {
    /// A number (`f32`, `f64`).
    Number,
    /// A whole number from 0 to `max` (`u32`: 0…4294967295).
    Whole {
        /// The largest value.
        max: u64,
    },
    /// A signed whole number.
    Integer,
    /// Text.
    Text,
    /// `true` or `false`.
    Bool,
    /// A list of any length.
    List,
    /// A list of exactly this many items (`[f32; 2]`).
    ListOf(usize),
    /// An object with these keys (empty: any keys).
    Object(&'static [&'static str]),
    /// One of these names.
    OneOf(&'static [&'static str]),
    /// `null`.
    Unit,
}

/// A value that does not fit: what was wrong, and what the type asked for (`None` where it
/// asked for any value and judged it itself: untagged and internally tagged choices).
#[derive(Clone, Debug, PartialEq)]
pub struct ShapeError {
    /// What was wrong.
    pub fault: Fault,
    /// What kind of value belonged there.
    pub expected: Option<Expected>,
    /// Whether the value that failed already said what it expected (perhaps nothing): the
    /// lists and objects around it must not.
    settled: bool,
}

impl ShapeError {
    fn new(fault: Fault) -> Self {
        ShapeError { fault, expected: None, settled: false }
    }

    /// The error with `expected` set unless the value that failed (deeper down) settled it.
    fn expecting(mut self, expected: Option<Expected>) -> Self {
        if !self.settled {
            self.expected = expected;
            self.settled = true;
        }
        self
    }
}

/// For `serde::de::Error`'s bound only; refusals are worded by the codec from the fields.
impl fmt::Display for ShapeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?} (expected {:?})", self.fault, self.expected)
    }
}

impl std::error::Error for ShapeError {}

impl de::Error for ShapeError {
    /// Untagged choices and hand-written readers: their words are not read.
    fn custom<T: fmt::Display>(_: T) -> Self {
        ShapeError::new(Fault::NoShapeFits)
    }

    fn invalid_type(_: Unexpected<'_>, _: &dyn de::Expected) -> Self {
        ShapeError::new(Fault::WrongKind)
    }

    fn invalid_value(found: Unexpected<'_>, _: &dyn de::Expected) -> Self {
        let text = match found {
            Unexpected::Str(s) => Some(s.to_string()),
            _ => None,
        };
        ShapeError::new(Fault::BadValue { text })
    }

    fn invalid_length(len: usize, _: &dyn de::Expected) -> Self {
        ShapeError::new(Fault::Length { len })
    }

    fn unknown_variant(name: &str, known: &'static [&'static str]) -> Self {
        ShapeError::new(Fault::UnknownVariant { name: name.to_string(), known })
    }

    fn unknown_field(name: &str, known: &'static [&'static str]) -> Self {
        ShapeError::new(Fault::UnknownKey { name: name.to_string(), known })
    }

    fn missing_field(name: &'static str) -> Self {
        ShapeError::new(Fault::MissingKey { name })
    }

    fn duplicate_field(name: &'static str) -> Self {
        ShapeError::new(Fault::DuplicateKey { name })
    }
}

/// A path segment as `serde_path_to_error` names it.
pub use serde_path_to_error::Segment;

/// `json` read as a `T`, or where and why it does not fit.
pub fn check<T: de::DeserializeOwned>(json: &Value) -> Result<T, (Vec<Segment>, ShapeError)> {
    serde_path_to_error::deserialize(ValueReader(json)).map_err(|e| {
        let path = e.path().iter().cloned().collect();
        (path, e.into_inner())
    })
}

/// A `serde_json::Value` as a deserializer whose error is a [`ShapeError`].
#[derive(Clone, Copy)]
struct ValueReader<'a>(&'a Value);

impl<'de> IntoDeserializer<'de, ShapeError> for ValueReader<'de> {
    type Deserializer = Self;

    fn into_deserializer(self) -> Self {
        self
    }
}

/// Methods that read any value and, when it does not fit, record what they asked for.
macro_rules! expecting {
    ($($method:ident => $expected:expr,)*) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
            self.read_any(visitor).map_err(|e| e.expecting(Some($expected)))
        }
    )*};
}

impl<'de> ValueReader<'de> {
    /// The value handed to `visitor` as what it is.
    fn read_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        match self.0 {
            Value::Null => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(*b),
            Value::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
                (Some(u), _, _) => visitor.visit_u64(u),
                (None, Some(i), _) => visitor.visit_i64(i),
                (None, None, Some(x)) => visitor.visit_f64(x),
                (None, None, None) => Err(ShapeError::new(Fault::WrongKind)),
            },
            Value::String(s) => visitor.visit_borrowed_str(s),
            Value::Array(items) => {
                let mut seq = SeqDeserializer::new(items.iter().map(ValueReader));
                let read = visitor.visit_seq(&mut seq)?;
                seq.end()?;
                Ok(read)
            }
            Value::Object(entries) => {
                let mut map = MapDeserializer::new(entries.iter().map(|(k, v)| (k.as_str(), ValueReader(v))));
                let read = visitor.visit_map(&mut map)?;
                map.end()?;
                Ok(read)
            }
        }
    }
}

impl<'de> Deserializer<'de> for ValueReader<'de> {
    type Error = ShapeError;

    /// A type that takes any value (untagged and internally tagged choices) judges it itself:
    /// it expected no one kind.
    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        self.read_any(visitor).map_err(|e| e.expecting(None))
    }

    expecting! {
        deserialize_f32 => Expected::Number,
        deserialize_f64 => Expected::Number,
        deserialize_u8 => Expected::Whole { max: u8::MAX.into() },
        deserialize_u16 => Expected::Whole { max: u16::MAX.into() },
        deserialize_u32 => Expected::Whole { max: u32::MAX.into() },
        deserialize_u64 => Expected::Whole { max: u64::MAX },
        deserialize_i8 => Expected::Integer,
        deserialize_i16 => Expected::Integer,
        deserialize_i32 => Expected::Integer,
        deserialize_i64 => Expected::Integer,
        deserialize_bool => Expected::Bool,
        deserialize_char => Expected::Text,
        deserialize_str => Expected::Text,
        deserialize_string => Expected::Text,
        deserialize_seq => Expected::List,
        deserialize_map => Expected::Object(&[]),
        deserialize_unit => Expected::Unit,
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        match self.0 {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, ShapeError> {
        self.deserialize_unit(visitor)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, ShapeError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_tuple<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, ShapeError> {
        self.read_any(visitor).map_err(|e| e.expecting(Some(Expected::ListOf(len))))
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _len: usize,
        visitor: V,
    ) -> Result<V::Value, ShapeError> {
        self.read_any(visitor).map_err(|e| e.expecting(Some(Expected::List)))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ShapeError> {
        self.read_any(visitor).map_err(|e| e.expecting(Some(Expected::Object(fields))))
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, ShapeError> {
        let read = match self.0 {
            Value::String(s) => visitor.visit_enum(s.as_str().into_deserializer()),
            Value::Object(entries) if entries.len() == 1 => visitor.visit_enum(MapAccessDeserializer::new(
                MapDeserializer::new(entries.iter().map(|(k, v)| (k.as_str(), ValueReader(v)))),
            )),
            _ => self.read_any(visitor),
        };
        read.map_err(|e| e.expecting(Some(Expected::OneOf(variants))))
    }

    fn deserialize_bytes<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        self.deserialize_any(visitor)
    }

    fn deserialize_byte_buf<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        self.deserialize_any(visitor)
    }

    fn deserialize_identifier<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        self.deserialize_any(visitor)
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, ShapeError> {
        visitor.visit_unit()
    }
}

/// The path of the value at byte `offset` of JSON `text` (`groups`, `2`, `name`), read from the
/// text's brackets, keys and commas: where a text that is no JSON stops (`NaN`, a broken
/// string), so its refusal can name the field.
pub fn path_at(text: &str, offset: usize) -> Vec<Segment> {
    enum Frame {
        Object { key: Option<String>, expecting_key: bool },
        List { index: usize },
    }
    let bytes = text.as_bytes();
    let mut frames: Vec<Frame> = Vec::new();
    let mut i = 0;
    while i < bytes.len().min(offset) {
        match bytes[i] {
            b'{' => frames.push(Frame::Object { key: None, expecting_key: true }),
            b'[' => frames.push(Frame::List { index: 0 }),
            b'}' | b']' => {
                frames.pop();
            }
            b',' => match frames.last_mut() {
                Some(Frame::List { index }) => *index += 1,
                Some(Frame::Object { expecting_key, .. }) => *expecting_key = true,
                None => {}
            },
            b'"' => {
                let start = i + 1;
                let mut end = start;
                while end < bytes.len() && bytes[end] != b'"' {
                    end += if bytes[end] == b'\\' { 2 } else { 1 };
                }
                if end >= offset {
                    // The value at `offset` is this string.
                    break;
                }
                if let Some(Frame::Object { key, expecting_key: expecting @ true }) = frames.last_mut() {
                    *key = text.get(start..end).map(str::to_string);
                    *expecting = false;
                }
                i = end;
            }
            _ => {}
        }
        i += 1;
    }
    frames
        .into_iter()
        .filter_map(|frame| match frame {
            Frame::Object { key: Some(key), expecting_key: false } => Some(Segment::Map { key }),
            Frame::List { index } => Some(Segment::Seq { index }),
            Frame::Object { .. } => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_is_read_from_brackets_keys_and_commas() {
        let text = r#"{"a": [1, {"b": "x,]", "c": NaN}], "d": 2}"#;
        let at = text.find("NaN").expect("NaN");
        let path: Vec<String> = path_at(text, at).iter().map(ToString::to_string).collect();
        assert_eq!(path, ["a", "[1]", "c"]);
        assert!(path_at(text, 0).is_empty());
    }
}
