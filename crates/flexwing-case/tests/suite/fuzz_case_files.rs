//! A fuzz test of the case-file layer (issue 9): the example case files, mutated with a fixed
//! seed — a value replaced by an extreme, non-finite, wrong-typed or huge one, a line deleted or
//! doubled — are parsed and turned into every plan. Asserted: no panic, every error one line
//! (naming where it is), in the user's terms (none of serde's phrases of
//! `flexwing_case::JARGON`, no number written out in hundreds of digits), every plan either an
//! error or built. This is the input layer, where the "found" cases of issue 9 (capacity
//! overflow, `expected usize`) lived; `fuzz_runs.rs` runs what it accepts.

use flexwing_case::Case;
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::mutate::{mutate, Lcg};

#[test]
fn mutated_example_case_files_give_plans_or_one_line_errors() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "examples: {files:?}");
    let mut rng = Lcg(20261130);
    let (mut accepted, mut refused, mut jargon_seen) = (0, 0, 0);
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        for _ in 0..400 {
            let (mut mutated, _) = mutate(&text, &mut rng);
            if rng.next(3) == 0 {
                mutated = mutate(&mutated, &mut rng).0;
            }
            let outcome = catch_unwind(AssertUnwindSafe(|| {
                let case = match Case::from_toml_str(&mutated) {
                    Ok(c) => c,
                    Err(e) => return vec![Err(e.to_string())],
                };
                let mut results = vec![
                    case.modes_plan().map(|_| ()).map_err(|e| e.to_string()),
                    case.static_plan().map(|_| ()).map_err(|e| e.to_string()),
                    case.dynamic_plan().map(|_| ()).map_err(|e| e.to_string()),
                ];
                if case.is_aeroelastic() {
                    results.push(case.flutter_plan().map(|_| ()).map_err(|e| e.to_string()));
                    results.push(
                        case.aero_static_plan()
                            .map(|_| ())
                            .map_err(|e| e.to_string()),
                    );
                    results.push(
                        case.aero_dynamic_plan()
                            .map(|_| ())
                            .map_err(|e| e.to_string()),
                    );
                    results.push(
                        case.gust_family_plan()
                            .map(|_| ())
                            .map_err(|e| e.to_string()),
                    );
                    results.push(
                        case.turbulence_plan()
                            .map(|_| ())
                            .map_err(|e| e.to_string()),
                    );
                }
                results
            }));
            let results = outcome
                .unwrap_or_else(|_| panic!("{}: a mutation panicked:\n{mutated}", path.display()));
            for r in results {
                match r {
                    Ok(()) => accepted += 1,
                    Err(e) => {
                        refused += 1;
                        assert_eq!(e.lines().count(), 1, "{}: {e}", path.display());
                        assert!(!e.contains("panicked"), "{e}");
                        // Numbers in messages in exponent form, not hundreds of digits (a whole number
                        // as typed, up to 2^64 = 20 digits, is fine).
                        let digits = e.chars().fold((0, 0), |(run, most), c| {
                            let run = if c.is_ascii_digit() { run + 1 } else { 0 };
                            (run, most.max(run))
                        });
                        assert!(digits.1 <= 20, "a number written out in full: {e}");
                        for jargon in flexwing_case::JARGON {
                            if e.contains(jargon) {
                                jargon_seen += 1;
                                eprintln!("not in the user's terms: {e}");
                            }
                        }
                    }
                }
            }
        }
    }
    eprintln!(
        "{} files × 400 mutations: {accepted} plans built, {refused} refused, {jargon_seen} \
         of them in serde's terms rather than the user's",
        files.len()
    );
    assert!(refused > 0 && accepted > 0);
    // Every schema error is put into words (flexwing_case::in_user_terms): none may keep
    // serde's phrasing (flexwing_case::JARGON lists the phrases).
    assert_eq!(jargon_seen, 0, "messages in serde's terms (printed above)");
}
