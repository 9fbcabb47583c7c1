//! `[output] vtk` / `--vtk`: the deformed chain for ParaView through `flexwing_io::vtk` — a
//! `.vtu` per output time (`flexwing dynamic`, the node file's times), load step (`static`) or
//! mode (`modes`), and a `.pvd` collection per model, in `vtk/` of the output folder. The 3-D
//! chain's frames carry the section rotation vector and the section axes `t`, `n`, `c` as point
//! vectors beside the displacement.

use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::chain3d::{Analysis3d, Chain3dOutcome, Chain3dPlan, Shape3dData};
use flexwing::analysis::dynamics::Snapshot;
use flexwing::model::chain3d::rotation_matrix;
use flexwing_io::vtk::{self, Frame};

use super::{dynamic, View};

/// The folder of the VTK files in the output folder `dir`.
pub fn folder(dir: &Path) -> PathBuf {
    dir.join("vtk")
}

/// The frames of one model's snapshots at the node file's output times.
fn snapshot_frames(shots: &[Snapshot], written: &[usize], reference: &[[f64; 3]]) -> Vec<Frame> {
    shots
        .iter()
        .filter(|s| written.binary_search(&s.index).is_ok())
        .map(|s| vtk::planar_frame(s.t, &s.shape.x, &s.shape.y, &s.shape.twist, reference))
        .collect()
}

/// The load steps' times in the collection: the sweep's scales if they increase, else 1, 2, ….
fn step_times(scales: &[f64]) -> Vec<f64> {
    if scales.windows(2).all(|w| w[0] < w[1]) {
        scales.to_vec()
    } else {
        (1..=scales.len()).map(|k| k as f64).collect()
    }
}

/// Write the VTK files of `view` (nothing for the analyses without node shapes: flutter, the
/// planar static aeroelastic run, linearize, turbulence); the `.pvd` paths.
pub fn files(ctx: &super::Context, view: &View, dir: &Path) -> Result<Vec<PathBuf>> {
    let out = folder(dir);
    let mut written = Vec::new();
    match view {
        View::Modes(_, o) => {
            let frames: Vec<Frame> = o
                .modes
                .iter()
                .map(|m| {
                    let s = &m.shape;
                    let reference = vtk::straight(&s.x);
                    vtk::planar_mode_frame(m.mode as f64, &s.dx, &s.dy, &s.twist, &reference)
                })
                .collect();
            written.push(vtk::write_series(&out, "modes", &frames)?);
        }
        View::Static(p, o) => {
            let reference = vtk::straight(p.model.beam().nodes());
            for r in &o.runs {
                let scales: Vec<f64> = r.points.iter().map(|q| q.scale).collect();
                let frames: Vec<Frame> = r
                    .points
                    .iter()
                    .zip(step_times(&scales))
                    .map(|(q, t)| {
                        let s = &q.shape;
                        vtk::planar_frame(t, &s.x, &s.y, &s.twist, &reference)
                    })
                    .collect();
                let stem = format!("static_{}", r.kind.label());
                written.push(vtk::write_series(&out, &stem, &frames)?);
            }
        }
        View::Dynamic(p, o) => {
            let reference = vtk::straight(p.model.beam().nodes());
            let times = dynamic::node_indices(&ctx.case.output, p.output_times.len());
            for r in &o.runs {
                let frames = snapshot_frames(&r.snapshots, &times, &reference);
                let stem = format!("dynamic_{}", r.kind.label());
                written.push(vtk::write_series(&out, &stem, &frames)?);
            }
        }
        View::AeroDynamic(p, o) => {
            let s = &p.structure;
            let reference = vtk::straight(s.model.beam().nodes());
            let times = dynamic::node_indices(&ctx.case.output, s.output_times.len());
            for r in &o.runs {
                let frames = snapshot_frames(&r.snapshots, &times, &reference);
                let stem = format!("dynamic_{}", r.kind.label());
                written.push(vtk::write_series(&out, &stem, &frames)?);
            }
        }
        View::Chain3d(p, o) => written.extend(chain3d_files(ctx, p, o, &out)?),
        View::AeroStatic(..)
        | View::Flutter(..)
        | View::GustFamily(..)
        | View::Linearize(..)
        | View::Turbulence(..) => {}
    }
    Ok(written)
}

/// A frame of the 3-D chain's `shape`, displaced from `reference`.
fn spatial_frame(time: f64, shape: &Shape3dData, reference: &[[f64; 3]]) -> Frame {
    let frames: Vec<[[f64; 3]; 3]> = shape.rotation.iter().map(|&r| rotation_matrix(r)).collect();
    vtk::spatial_frame(time, &shape.position, &shape.rotation, &frames, reference)
}

/// The 3-D chain's series: its modes, static points, static aeroelastic equilibria or dynamic
/// snapshots (nothing for flutter and the study).
fn chain3d_files(
    ctx: &super::Context,
    plan: &Chain3dPlan,
    outcome: &Chain3dOutcome,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let reference = plan.model.node_positions(&vec![0.0; plan.model.n_dofs()]);
    let mut written = Vec::new();
    match (outcome, &plan.analysis) {
        (Chain3dOutcome::Modes { modes, .. }, _) => {
            let frames: Vec<Frame> = modes
                .iter()
                .map(|m| {
                    vtk::spatial_mode_frame(m.mode as f64, &m.displacement, &m.rotation, &reference)
                })
                .collect();
            written.push(vtk::write_series(out, "modes", &frames)?);
        }
        (Chain3dOutcome::Static(o), _) => {
            let scales: Vec<f64> = o.points.iter().map(|q| q.scale).collect();
            let frames: Vec<Frame> = o
                .points
                .iter()
                .zip(step_times(&scales))
                .map(|(q, t)| spatial_frame(t, &q.shape, &reference))
                .collect();
            written.push(vtk::write_series(out, "static_full", &frames)?);
        }
        (Chain3dOutcome::AeroStatic(o), _) => {
            // One frame per equilibrium, its time the speed (m/s).
            let speeds: Vec<f64> = o.equilibria.iter().map(|e| e.speed).collect();
            let frames: Vec<Frame> = o
                .equilibria
                .iter()
                .zip(step_times(&speeds))
                .map(|(e, t)| spatial_frame(t, &e.shape, &reference))
                .collect();
            written.push(vtk::write_series(out, "static_aero", &frames)?);
        }
        (Chain3dOutcome::Dynamic(o), Analysis3d::Dynamic(d)) => {
            let times = dynamic::node_indices(&ctx.case.output, d.output_times.len());
            for r in &o.runs {
                let frames: Vec<Frame> = r
                    .snapshots
                    .iter()
                    .filter(|s| times.binary_search(&s.index).is_ok())
                    .map(|s| spatial_frame(s.t, &s.shape, &reference))
                    .collect();
                let stem = format!("dynamic_{}", r.label);
                written.push(vtk::write_series(out, &stem, &frames)?);
            }
        }
        _ => {}
    }
    Ok(written)
}

/// Remove a previous run's VTK files (`vtk/*.vtu`, `vtk/*.pvd`) from the output folder `dir`.
pub fn remove_previous(dir: &Path) -> Result<()> {
    let Ok(entries) = std::fs::read_dir(folder(dir)) else {
        return Ok(());
    };
    for entry in entries {
        let path = entry?.path();
        if matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("vtu" | "pvd")
        ) {
            std::fs::remove_file(&path)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_steps_are_timed_by_increasing_scales_else_numbered() {
        assert_eq!(step_times(&[0.5, 1.0]), [0.5, 1.0]);
        assert_eq!(step_times(&[1.0, 0.5, 0.5]), [1.0, 2.0, 3.0]);
    }
}
