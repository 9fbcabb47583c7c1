//! The one error of the case layer: where in which file, under which key, and why.

use std::fmt;

use flexwing::InputError;

/// A case that cannot be read, parsed or turned into a plan. Displayed as one line:
/// `FILE line L, column C: KEY: reason`, each part present when known.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CaseError {
    /// The file (as given by the caller), if the case came from one.
    pub file: Option<String>,
    /// 1-based line of the offending text (syntax and schema errors).
    pub line: Option<usize>,
    /// 1-based column, in characters (syntax and schema errors).
    pub column: Option<usize>,
    /// The dotted key of the offending value, e.g. `loads[2].time.t`.
    pub key: Option<String>,
    /// What is wrong.
    pub reason: String,
}

impl CaseError {
    /// An error with only a reason.
    pub fn new(reason: impl Into<String>) -> Self {
        Self {
            file: None,
            line: None,
            column: None,
            key: None,
            reason: reason.into(),
        }
    }

    /// The error of a value the library or the case layer rejected, in `file`.
    pub fn input(e: InputError, file: Option<&str>) -> Self {
        Self {
            file: file.map(str::to_string),
            key: Some(e.field),
            ..Self::new(e.reason)
        }
    }

    /// A TOML syntax or schema error of `source`, read from `file`.
    ///
    /// `toml`'s own `Display` is a multi-line report with a source snippet; this keeps the
    /// message, turns the span into a 1-based line and column (in characters), and keeps the
    /// dotted path of the offending key when toml knows it.
    pub(crate) fn toml(e: &toml::de::Error, source: &str, file: Option<&str>) -> Self {
        let mut message = crate::words::in_user_terms(&one_line(e.message()));
        // toml says only "duplicate key"; its span is the key as written.
        if message == "duplicate key" {
            if let Some(k) = e.span().and_then(|s| source.get(s)) {
                message = format!("the key {} is given twice", one_line(k));
            }
        }
        let key = error_keys(e).map(|k| match e.span() {
            Some(span) => with_table_index(&k, source, span.start),
            None => k,
        });
        let (line, column) = match e.span() {
            Some(span) => {
                let (l, c) = line_column(source, span.start);
                (Some(l), Some(c))
            }
            None => (None, None),
        };
        Self {
            file: file.map(str::to_string),
            line,
            column,
            // toml sometimes puts the key at the start of its message already.
            key: key.filter(|k| !message.starts_with(k.as_str())),
            reason: message,
        }
    }
}

impl fmt::Display for CaseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut place = self.file.clone().unwrap_or_default();
        if let (Some(line), Some(column)) = (self.line, self.column) {
            if !place.is_empty() {
                place.push(' ');
            }
            place.push_str(&format!("line {line}, column {column}"));
        }
        let mut parts: Vec<&str> = Vec::new();
        if !place.is_empty() {
            parts.push(&place);
        }
        if let Some(key) = &self.key {
            parts.push(key);
        }
        parts.push(&self.reason);
        write!(f, "{}", parts.join(": "))
    }
}

impl std::error::Error for CaseError {}

impl From<InputError> for CaseError {
    fn from(e: InputError) -> Self {
        Self::input(e, None)
    }
}

/// The dotted key path toml recorded for the error. toml 1.x keeps it private and only prints it
/// (as a trailing "in `a.b`" line) when the error carries no source text, so ask for that form.
fn error_keys(error: &toml::de::Error) -> Option<String> {
    let mut bare = error.clone();
    bare.set_input(None);
    let text = bare.to_string();
    let rest = text.strip_prefix(error.message())?.trim();
    let keys = rest.strip_prefix("in `")?.strip_suffix('`')?;
    (!keys.is_empty()).then(|| keys.to_string())
}

/// toml names a key inside an array of tables without its index (`loads.type`); count the
/// `[[loads]]` headers before `offset` to put it back (`loads[1].type`). Arrays written inline
/// keep toml's path.
fn with_table_index(keys: &str, source: &str, offset: usize) -> String {
    let (head, rest) = keys.split_once('.').unwrap_or((keys, ""));
    let header = format!("[[{head}]]");
    let mut end = offset.min(source.len());
    while !source.is_char_boundary(end) {
        end -= 1;
    }
    let count = source[..end]
        .lines()
        .filter(|l| l.replace([' ', '\t'], "").starts_with(&header))
        .count();
    match (count, rest) {
        (0, _) => keys.to_string(),
        (n, "") => format!("{head}[{}]", n - 1),
        (n, rest) => format!("{head}[{}].{rest}", n - 1),
    }
}

/// 1-based line and column (in characters) of the byte offset `offset` of `source`.
fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(source.len());
    while !source.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &source[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = before.matches('\n').count() + 1;
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

/// Collapse line breaks and runs of blanks so a message fits on one line.
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_joins_the_known_parts() {
        let mut e = CaseError::new("must be positive");
        assert_eq!(e.to_string(), "must be positive");
        e.key = Some("beam.length".into());
        assert_eq!(e.to_string(), "beam.length: must be positive");
        e.file = Some("x.toml".into());
        assert_eq!(e.to_string(), "x.toml: beam.length: must be positive");
        e.line = Some(3);
        e.column = Some(10);
        assert_eq!(
            e.to_string(),
            "x.toml line 3, column 10: beam.length: must be positive"
        );
        e.file = None;
        assert_eq!(
            e.to_string(),
            "line 3, column 10: beam.length: must be positive"
        );
    }

    #[test]
    fn a_duplicate_key_is_named() {
        let src = "[beam]\nlength = 1.0\nlength = 2.0\n";
        let e = toml::from_str::<toml::Table>(src).unwrap_err();
        let e = CaseError::toml(&e, src, None);
        assert_eq!(e.reason, "the key length is given twice");
        assert_eq!((e.line, e.column), (Some(3), Some(1)));
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        assert_eq!(line_column("a\nωω = 1", 6), (2, 3));
        assert_eq!(line_column("abc", 99), (1, 4));
        assert_eq!(
            with_table_index("beam.section", "[beam]", 3),
            "beam.section"
        );
    }
}
