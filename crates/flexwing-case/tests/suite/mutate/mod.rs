//! Mutations of a case file's text, with a fixed seed: shared by the fuzz test of the case-file
//! layer (`fuzz_case_files.rs`) and the fuzz test of runs (`crates/flexwing-cli/tests/
//! fuzz_runs.rs`, which includes this file by path).

#![allow(dead_code)]

/// Replacements for a value: zero, negative, extreme, tiny, non-finite, huge integers, the wrong
/// type, and the edges of the accepted range of magnitudes (`flexwing::magnitude`).
pub const VALUES: &[&str] = &[
    "0",
    "-1",
    "1e300",
    "-1e300",
    "1e-300",
    "nan",
    "inf",
    "-inf",
    "4611686018427387904",
    "1e9",
    "\"x\"",
    "true",
    "[]",
    "{}",
    "[1e308, -1e308]",
    "0.5",
    "1e30",
    "-1e-30",
    "2e30",
    "5e-31",
];

/// What a mutation did, for the counts a fuzz test reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Class {
    /// A `key = value` line deleted.
    Deleted,
    /// A `key = value` line doubled (a duplicate key).
    Doubled,
    /// A value replaced by one of [`VALUES`].
    Replaced,
}

/// A fixed-seed linear congruential generator (Knuth's MMIX constants).
pub struct Lcg(pub u64);

impl Lcg {
    /// A number in `0..n`.
    pub fn next(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 33) % n as u64) as usize
    }
}

/// One mutation of a `key = value` line of `text` (comments and headers are kept).
pub fn mutate(text: &str, rng: &mut Lcg) -> (String, Class) {
    let lines: Vec<&str> = text.lines().collect();
    let candidates: Vec<usize> = (0..lines.len())
        .filter(|&i| {
            let l = lines[i].trim_start();
            !l.starts_with('#') && l.contains(" = ")
        })
        .collect();
    if candidates.is_empty() {
        return (text.to_string(), Class::Replaced);
    }
    let i = candidates[rng.next(candidates.len())];
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    let class = match rng.next(10) {
        0 => {
            out.remove(i);
            Class::Deleted
        }
        1 => {
            let l = out[i].clone();
            out.insert(i, l);
            Class::Doubled
        }
        _ => {
            let line = &out[i];
            let eq = line.find(" = ").unwrap();
            let key = &line[..eq];
            out[i] = format!("{key} = {}", VALUES[rng.next(VALUES.len())]);
            Class::Replaced
        }
    };
    (out.join("\n"), class)
}
