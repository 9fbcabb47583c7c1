//! Table 8 of `flexwing reproduce` alone: case (b) at n = 20, every model's counters, its CPU time
//! (median, min, max over the samples) and the reduced/full ratio of the medians, as the report
//! prints it. Run: `cargo run --release -p flexwing-paper --example table8 [-- SAMPLES]`.

fn main() -> anyhow::Result<()> {
    let samples = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let study = flexwing_paper::sine::run(samples)?;
    println!("| model | steps | rhs | Jacobians | LU | Newton | CPU median (min–max) | ratio |");
    println!("|---|---|---|---|---|---|---|---|");
    for m in &study.models {
        let s = &m.stats;
        println!(
            "| {} | {} | {} | {} | {} | {} | {:.1} µs ({:.1}–{:.1}) | {:.3} |",
            m.kind.label(),
            s.steps,
            s.rhs_evaluations,
            s.jacobian_evaluations,
            s.factorizations,
            s.newton_iterations,
            1e6 * m.timing.median,
            1e6 * m.timing.min,
            1e6 * m.timing.max,
            study.ratio(m)
        );
    }
    Ok(())
}
