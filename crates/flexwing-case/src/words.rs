//! Schema errors in the user's terms (issue 9): serde and toml describe a wrong value in Rust's
//! terms ("invalid type: map, expected usize", "wanted string or table"); a case file's author
//! needs to read what the value must be ("must be a whole number ≥ 0, got a table").
//!
//! Two parts: [`word_enum!`] gives the case file's keyword enums a `Deserialize` that accepts
//! exactly their words and, for anything else, expects `one of "dead", "follower"` (toml's own
//! enum path would say "wanted string or table"); [`in_user_terms`] rewrites the remaining serde
//! phrasings of a message — the type names and the `invalid type`/`invalid value`/`missing
//! field`/`unknown field` forms — into words.

/// Implement `Deserialize` for a keyword enum: `word_enum!(Type { Variant = "word", … })`.
/// Accepts exactly the listed strings; any other value is an error that expects
/// `one of "word", …`.
macro_rules! word_enum {
    ($ty:ident { $($variant:ident = $word:literal),+ $(,)? }) => {
        impl<'de> serde::Deserialize<'de> for $ty {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct Words;
                impl<'de> serde::de::Visitor<'de> for Words {
                    type Value = $ty;
                    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                        f.write_str(&$crate::words::one_of(&[$($word),+]))
                    }
                    fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<$ty, E> {
                        match s {
                            $($word => Ok($ty::$variant),)+
                            _ => Err(E::invalid_value(serde::de::Unexpected::Str(s), &self)),
                        }
                    }
                }
                d.deserialize_str(Words)
            }
        }
    };
}
pub(crate) use word_enum;

/// `one of "a", "b"` (or `"a"` for a single word).
pub(crate) fn one_of(words: &[&str]) -> String {
    let quoted: Vec<String> = words.iter().map(|w| format!("\"{w}\"")).collect();
    match quoted.len() {
        1 => quoted[0].clone(),
        _ => format!("one of {}", quoted.join(", ")),
    }
}

/// Rewrite a serde/toml message into the case file's terms; a message in none of serde's forms
/// is returned unchanged.
pub fn in_user_terms(message: &str) -> String {
    let m = message.trim();
    for prefix in ["invalid type: ", "invalid value: "] {
        if let Some(rest) = m.strip_prefix(prefix) {
            if let Some((got, expected)) = split_expected(rest) {
                return format!(
                    "must be {}, got {}",
                    expected_words(expected),
                    got_words(got)
                );
            }
        }
    }
    if let Some(rest) = m.strip_prefix("invalid length ") {
        if let Some((got, expected)) = split_expected(rest) {
            return format!("must have {}, got {got} values", expected_words(expected));
        }
    }
    if let Some(rest) = m.strip_prefix("missing field ") {
        return format!("the key {rest} is missing here");
    }
    if let Some(rest) = m.strip_prefix("unknown field ") {
        return match rest.split_once(", expected ") {
            Some((key, keys)) => format!(
                "unknown key {key}; the keys here are {}",
                keys.trim_start_matches("one of ")
            ),
            None => format!("unknown key {rest}"),
        };
    }
    if let Some(rest) = m.strip_prefix("unknown variant ") {
        if let Some((got, expected)) = rest.split_once(", expected ") {
            let expected = expected.trim_start_matches("one of ").replace('`', "\"");
            return format!("must be one of {expected}, got {}", got.replace('`', "\""));
        }
    }
    if m == "wanted string or table" {
        return "must be a word in quotes (the words each key takes are in docs/case-file.md)"
            .into();
    }
    m.to_string()
}

/// `GOT, expected EXPECTED` → (`GOT`, `EXPECTED`). The unexpected part may itself hold commas
/// (a string value), so split at the last `, expected `.
fn split_expected(rest: &str) -> Option<(&str, &str)> {
    rest.rsplit_once(", expected ")
}

/// serde's names of what was expected, in words.
fn expected_words(expected: &str) -> String {
    let e = expected.trim();
    match e {
        "f64" | "f32" => "a number".into(),
        "usize" | "u64" | "u32" | "u16" | "u8" => "a whole number ≥ 0".into(),
        "i64" | "i32" | "i16" | "i8" | "isize" => "a whole number".into(),
        "a string" | "string" => "a text in quotes".into(),
        "a boolean" | "bool" => "true or false".into(),
        "a sequence" | "a list" => "a list [...]".into(),
        "a map" => "a table".into(),
        _ if e.starts_with("struct ") => "a table".into(),
        _ if e.starts_with("a sequence") || e.starts_with("sequence") => "a list [...]".into(),
        _ if e.starts_with("an array of length ") || e.starts_with("a tuple of size ") => {
            format!("a list of {} values", e.rsplit(' ').next().unwrap_or("?"))
        }
        _ => e.to_string(),
    }
}

/// serde's `Unexpected` display, in words; numbers in their shortest form (`1e300`, not three
/// hundred digits).
fn got_words(got: &str) -> String {
    let g = got.trim();
    let number = |s: &str| -> Option<String> {
        let inner = s.strip_prefix('`')?.strip_suffix('`')?;
        let v: f64 = inner.parse().ok()?;
        Some(flexwing::text::short(v))
    };
    for prefix in ["floating point ", "integer "] {
        if let Some(rest) = g.strip_prefix(prefix) {
            if let Some(n) = number(rest) {
                return n;
            }
        }
    }
    if let Some(rest) = g.strip_prefix("boolean ") {
        return rest.trim_matches('`').to_string();
    }
    if let Some(rest) = g.strip_prefix("string ") {
        return format!("the text {rest}");
    }
    match g {
        "sequence" => "a list".into(),
        "map" => "a table".into(),
        "unit value" => "nothing".into(),
        "newtype struct" | "newtype variant" | "unit variant" | "tuple variant"
        | "struct variant" | "enum" => "a keyword".into(),
        "" => "nothing".into(),
        _ => g.to_string(),
    }
}

/// Phrases that are serde's or toml's, not the user's: a message holding one of them has not
/// been put into words (the fuzz test fails on them).
pub const JARGON: &[&str] = &[
    "invalid type",
    "invalid value",
    "invalid length",
    "expected usize",
    "expected u64",
    "expected u32",
    "expected f64",
    "expected i64",
    "expected a sequence",
    "expected a map",
    "expected struct",
    "expected a string",
    "wanted string or table",
    "unknown variant",
    "missing field",
    "unknown field",
    "did not match any variant",
    "floating point `",
    "integer `",
];

/// The keys of the table `T` (a serde struct of the schema): the names `T` deserializes, as
/// the case file spells them. Front ends that take a table's keys as arguments (Python's
/// `Beam(length=…, EI=…)`) check them against this list instead of one of their own.
pub fn keys<'de, T: serde::Deserialize<'de>>() -> &'static [&'static str] {
    use serde::de::{self, Visitor};
    struct Probe(Option<&'static [&'static str]>);
    #[derive(Debug)]
    struct Found;
    impl std::fmt::Display for Found {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("probe")
        }
    }
    impl std::error::Error for Found {}
    impl de::Error for Found {
        fn custom<M: std::fmt::Display>(_: M) -> Self {
            Found
        }
    }
    impl<'de> de::Deserializer<'de> for &mut Probe {
        type Error = Found;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Found> {
            Err(Found)
        }
        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _: &'static str,
            fields: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Found> {
            self.0 = Some(fields);
            Err(Found)
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
            identifier ignored_any
        }
    }
    let mut probe = Probe(None);
    let _ = T::deserialize(&mut probe);
    probe.0.unwrap_or(&[])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serde_phrasings_become_words() {
        let cases = [
            (
                "invalid type: map, expected usize",
                "must be a whole number ≥ 0, got a table",
            ),
            (
                "invalid value: integer `-1`, expected usize",
                "must be a whole number ≥ 0, got -1",
            ),
            (
                "invalid type: floating point `1000000000000000000000000000000.0`, expected usize",
                "must be a whole number ≥ 0, got 1e30",
            ),
            (
                "invalid type: string \"x, y\", expected f64",
                "must be a number, got the text \"x, y\"",
            ),
            (
                "invalid type: sequence, expected a number, or a table { x = [...], value = [...] }",
                "must be a number, or a table { x = [...], value = [...] }, got a list",
            ),
            (
                "invalid type: boolean `true`, expected struct SectionSpec",
                "must be a table, got true",
            ),
            (
                "invalid type: integer `0`, expected one of \"dead\", \"follower\"",
                "must be one of \"dead\", \"follower\", got 0",
            ),
            ("missing field `EI`", "the key `EI` is missing here"),
            (
                "unknown field `Ei`, expected one of `EI`, `GJ`",
                "unknown key `Ei`; the keys here are `EI`, `GJ`",
            ),
            (
                "unknown variant `rk4`, expected one of `auto`, `radau`",
                "must be one of \"auto\", \"radau\", got \"rk4\"",
            ),
            ("must be positive", "must be positive"),
        ];
        for (serde, words) in cases {
            let w = in_user_terms(serde);
            assert_eq!(w, words);
            assert!(!JARGON.iter().any(|j| w.contains(j)), "{w}");
        }
    }
}
