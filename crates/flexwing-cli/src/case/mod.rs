//! The case file (TOML): its schema (`spec`), number-or-table properties (`property`), and the
//! conversion into library types (`convert`). Every error is one line that names the file, the
//! place in it and the problem.

mod convert;
mod dynamic;
mod loads;
mod property;
mod spec;
mod statics;

use std::path::Path;

pub use spec::Case;

impl Case {
    /// Read and parse the case file at `path`.
    ///
    /// # Errors
    /// One-line messages: `PATH: cannot read the case file: …`, or
    /// `PATH line L, column C: KEY.PATH: problem` for TOML and schema errors.
    pub fn load(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("{}: cannot read the case file: {e}", path.display()))?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Parse a case from TOML text; `name` is the file name used in messages.
    pub fn parse(text: &str, name: &str) -> Result<Self, String> {
        toml::from_str(text).map_err(|e| toml_error_line(name, text, &e))
    }
}

/// One line for a TOML or schema error: `NAME line L, column C: KEY.PATH: message`.
///
/// `toml`'s own `Display` is a multi-line report with a source snippet; this keeps the message,
/// turns the span into a 1-based line and column (in characters), and puts the dotted path of the
/// offending key in front when toml knows it.
pub fn toml_error_line(name: &str, source: &str, error: &toml::de::Error) -> String {
    let message = one_line(error.message());
    let keys = error_keys(error).map(|k| match error.span() {
        Some(span) => with_table_index(&k, source, span.start),
        None => k,
    });
    let place = match error.span() {
        Some(span) => {
            let (line, column) = line_column(source, span.start);
            format!("{name} line {line}, column {column}")
        }
        None => name.to_string(),
    };
    match keys {
        Some(keys) if !message.starts_with(&keys) => format!("{place}: {keys}: {message}"),
        _ => format!("{place}: {message}"),
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

    fn error_of(text: &str) -> String {
        Case::parse(text, "x.toml").unwrap_err()
    }

    const BEAM: &str =
        "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\nmass_per_length = 0.2\n";

    #[test]
    fn unknown_key_is_one_line_with_line_column_and_path() {
        let msg = error_of(&format!("{BEAM}foo = 1\n"));
        assert_eq!(
            msg.lines().count(),
            1,
            "message spans several lines: {msg:?}"
        );
        assert!(
            msg.starts_with("x.toml line 8, column 1: beam.section: unknown field `foo`"),
            "{msg}"
        );
        assert!(msg.contains("expected one of"), "{msg}");
    }

    #[test]
    fn type_error_names_the_key() {
        let msg = error_of(&BEAM.replace("EI = 50", "EI = \"50\""));
        assert!(
            msg.starts_with("x.toml line 6, column 6: beam.section.EI: invalid type: string"),
            "{msg}"
        );
        assert!(msg.contains("a number, or a table"), "{msg}");
    }

    #[test]
    fn syntax_error_is_one_line() {
        let msg = error_of("[beam\nlength = 1\n");
        assert_eq!(msg.lines().count(), 1, "{msg:?}");
        assert!(msg.starts_with("x.toml line 1, column "), "{msg}");
    }

    #[test]
    fn malformed_table_says_what_is_missing() {
        let msg = error_of(&BEAM.replace("EI = 50", "EI = { x = [0.0, 1.0] }"));
        assert!(msg.contains("beam.section.EI"), "{msg}");
        assert!(msg.contains("missing `value`"), "{msg}");
    }

    #[test]
    fn integers_are_accepted_for_floats() {
        let case = Case::parse(BEAM, "x.toml").unwrap();
        let beam = case.to_beam().unwrap();
        assert_eq!(beam.n_elements(), 4);
    }

    #[test]
    fn keys_in_arrays_of_tables_get_their_index() {
        let load = "\n[[loads]]\ntype = \"gravity\"\n";
        let msg = error_of(&format!(
            "{BEAM}{load}{load}{}",
            load.replace("gravity", "gravitas")
        ));
        assert!(
            msg.starts_with("x.toml line 16, column 8: loads[2].type: unknown variant"),
            "{msg}"
        );
        let msg = error_of(&format!("{BEAM}{load}bogus = 1\n"));
        assert!(msg.contains(": loads[0]: unknown field `bogus`"), "{msg}");
        assert_eq!(
            with_table_index("beam.section", "[beam]", 3),
            "beam.section"
        );
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        assert_eq!(line_column("a\nωω = 1", 6), (2, 3));
        assert_eq!(line_column("abc", 99), (1, 4));
    }
}
