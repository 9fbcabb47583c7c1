//! The named signals of a linear aeroelastic model (docs/control.md): its inputs, its outputs and
//! the choice of its structural states, each with a name a case file or a Python call spells and
//! an SI unit. Numbering follows the case file: nodes `0 … n` (node 0 the clamp), elements and
//! their strips `1 … n` (element `k` between nodes `k − 1` and `k`), joints `1 … n` (joint `k`
//! at the inboard node of element `k`).

use crate::error::InputError;
use crate::model::aero::ControlSurface;

/// A control surface a signal belongs to: its index among `[[aero.surfaces]]` (0-based) and its
/// name (the signal's name carries it: `delta[aileron]`).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Surface {
    /// Index of the surface (0-based, in the order of the surfaces).
    pub index: usize,
    /// Its name.
    pub name: String,
}

/// An input of the linear model: a perturbation about the equilibrium's value.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Input {
    /// `root_angle` (rad): the root angle of attack, a nose-up rotation of the free stream (and
    /// of gravity) in the wing's frame, as `FlightHistory`'s root angle.
    RootAngle,
    /// `speed` (m/s): the free-stream speed.
    Speed,
    /// `gust` (m/s): a vertical gust velocity (up, ground frame), uniform over the span.
    Gust,
    /// `gust[k]` (m/s): the vertical gust velocity at the strip of element `k` (1-based) only.
    StripGust(usize),
    /// `gust_rate` (m/s²): the rate `d(gust)/dt` of the uniform gust, for its apparent mass
    /// `πρb² v̇_g` at mid-chord (the non-linear strips' uniform penetration; none with steady
    /// aerodynamics). Feed it with `gust`; zero gives the quasi-static gust.
    GustRate,
    /// `force[k]` (N): a dead vertical force (along the wing frame's `y`, up) at node `k`
    /// (`1 … n`).
    Force(usize),
    /// `torque[k]` (N·m): a torque about the span axis (nose-up) on the element inboard of node
    /// `k` (`1 … n`).
    Torque(usize),
    /// `delta[NAME]` (rad): the deflection `δ` of the surface `NAME`, trailing edge down (it
    /// raises the lift): its circulatory upwash `V T10 δ/π` (lagged) and the moment
    /// `−ρb²(T4 + T10)V²δ` (docs/aeroelastic-model.md §3b).
    Deflection(Surface),
    /// `delta_rate[NAME]` (rad/s): the rate `δ̇`, for the upwash `b T11 δ̇/(2π)` and the
    /// non-circulatory terms; feed it with `delta[NAME]` (`iω δ` in the frequency domain). None
    /// with steady aerodynamics.
    DeflectionRate(Surface),
    /// `delta_acceleration[NAME]` (rad/s²): the acceleration `δ̈`, for the apparent-mass terms
    /// (`−ρb³T1 δ̈` normal force); `−ω² δ` in the frequency domain. None with steady
    /// aerodynamics.
    DeflectionAcceleration(Surface),
}

/// An output of the linear model: a perturbation about the equilibrium's value.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Output {
    /// `tip_x` (m): the tip node's spanwise position.
    TipX,
    /// `tip_y` (m): the tip node's vertical position (wing frame).
    TipY,
    /// `tip_z` (m): the tip node's chordwise position (toward the leading edge; the 3-D chain's
    /// lag displacement).
    TipZ,
    /// `tip_twist` (rad): the twist of the tip element, nose-up.
    TipTwist,
    /// `x[k]` (m): node `k`'s spanwise position.
    X(usize),
    /// `y[k]` (m): node `k`'s vertical position.
    Y(usize),
    /// `z[k]` (m): node `k`'s chordwise position (the 3-D chain).
    Z(usize),
    /// `twist[k]` (rad): the twist of the element inboard of node `k`.
    Twist(usize),
    /// `root_bending_moment` (N·m): the clamp spring's moment `K_θ,1 q_1`.
    RootBendingMoment,
    /// `root_shear` (N): the force the wing exerts on the clamp along the wing frame's `y` (up):
    /// the external forces on the wing (aerodynamic, gravity, applied, input forces) less the
    /// rate of change of its momentum (structure and fluid).
    RootShear,
    /// `root_torque` (N·m): the clamp's torsion spring moment `K_ψ,1 q_{n+1}`.
    RootTorque,
    /// `root_lag_moment` (N·m): the 3-D chain's clamp moment about the root element's section
    /// normal `n`, `(K_0 φ_0)_n` (positive in the sense of a lag rotation: tip toward the
    /// trailing edge).
    RootLagMoment,
    /// `lift` (N): the total aerodynamic force along the ground's vertical (the circulatory and
    /// non-circulatory velocity terms; the apparent-mass terms are in the mass matrix), as the
    /// `lift` of a response.
    Lift,
    /// `tip_acceleration` (m/s²): the tip node's vertical acceleration.
    TipAcceleration,
    /// `acceleration[k]` (m/s²): node `k`'s vertical acceleration.
    Acceleration(usize),
    /// `hinge_moment[NAME]` (N·m): the hinge moment of the surface `NAME`, positive in the sense
    /// of `δ` (trailing edge down): Theodorsen's deflection, flap-rate and circulatory terms over
    /// the covered span (the terms in the structure's own rates and accelerations are not
    /// included, docs/aeroelastic-model.md §3b).
    HingeMoment(Surface),
}

/// The structural states of the model: velocities `(x, ẋ, a)` or momenta `(x, p, a)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum StateBasis {
    /// Coordinates, their rates and the lag states (the usual plant form).
    #[default]
    Velocities,
    /// Coordinates, the momenta `p = M(x) ẋ` (of the structure and the fluid's inertia) and the
    /// lag states: the integrators' own state, whose Jacobian `A` is.
    Momenta,
}

impl StateBasis {
    /// `velocities` or `momenta`.
    pub fn name(self) -> &'static str {
        match self {
            StateBasis::Velocities => "velocities",
            StateBasis::Momenta => "momenta",
        }
    }

    /// The basis called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        [StateBasis::Velocities, StateBasis::Momenta]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

/// A named signal (state, input or output) with its SI unit.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Signal {
    /// Its name (`tip_y`, `gust[3]`, `theta[1]`, …).
    pub name: String,
    /// Its unit (`m`, `rad`, `N·m`, `m/s`, …; `1` for none).
    pub unit: &'static str,
}

/// `name` as `base[index]`, or `None`.
fn indexed(name: &str) -> Option<(&str, &str)> {
    let open = name.find('[')?;
    let inner = name[open + 1..].strip_suffix(']')?;
    Some((&name[..open], inner))
}

/// The index of `what` in `inner` within `range`.
fn index_in(inner: &str, what: &str, lo: usize, hi: usize) -> Result<usize, String> {
    let k: usize = inner
        .parse()
        .map_err(|_| format!("{inner:?} is not a {what} number"))?;
    if !(lo..=hi).contains(&k) {
        return Err(format!("{what} {k} is out of range: {lo} to {hi}"));
    }
    Ok(k)
}

/// Every name an input takes, for messages.
pub const INPUT_NAMES: &str =
    "root_angle, speed, gust, gust[k] (strip of element k), gust_rate, force[k] and torque[k] \
     (node k), delta[NAME], delta_rate[NAME], delta_acceleration[NAME] (surface NAME)";

/// Every name an output takes, for messages.
pub const OUTPUT_NAMES: &str = "tip_x, tip_y, tip_twist, x[k], y[k], twist[k] (node k), \
                                root_bending_moment, root_shear, root_torque, lift, \
                                tip_acceleration, acceleration[k], hinge_moment[NAME] (surface \
                                NAME); on the 3-D chain also tip_z, z[k], root_lag_moment";

/// The surface called `inner` among `surfaces`.
fn surface_in(inner: &str, surfaces: &[ControlSurface]) -> Result<Surface, String> {
    match surfaces.iter().position(|s| s.name == inner) {
        Some(index) => Ok(Surface {
            index,
            name: inner.to_string(),
        }),
        None if surfaces.is_empty() => Err(format!(
            "there is no control surface {inner:?}: the case has no [[aero.surfaces]]"
        )),
        None => Err(format!(
            "there is no control surface {inner:?}; the surfaces are {}",
            surfaces
                .iter()
                .map(|s| s.name.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

impl Input {
    /// The input called `name` on a chain of `n` elements (`torsion`: with twist) with the
    /// control surfaces `surfaces`; errors name `field`.
    ///
    /// # Errors
    /// An unknown name, an index out of range, a torque on a bending-only beam, a surface the
    /// wing does not have.
    pub fn parse(
        name: &str,
        n: usize,
        torsion: bool,
        surfaces: &[ControlSurface],
        field: &str,
    ) -> Result<Self, InputError> {
        let error = |reason: String| InputError::new(field, reason);
        let surface = |i: &str| surface_in(i, surfaces).map_err(error);
        let input = match (name, indexed(name)) {
            ("root_angle", _) => Input::RootAngle,
            ("speed", _) => Input::Speed,
            ("gust", _) => Input::Gust,
            ("gust_rate", _) => Input::GustRate,
            (_, Some(("gust", i))) => {
                Input::StripGust(index_in(i, "element", 1, n).map_err(error)?)
            }
            (_, Some(("force", i))) => Input::Force(index_in(i, "node", 1, n).map_err(error)?),
            (_, Some(("torque", i))) => Input::Torque(index_in(i, "node", 1, n).map_err(error)?),
            (_, Some(("delta", i))) => Input::Deflection(surface(i)?),
            (_, Some(("delta_rate", i))) => Input::DeflectionRate(surface(i)?),
            (_, Some(("delta_acceleration", i))) => Input::DeflectionAcceleration(surface(i)?),
            _ => {
                return Err(error(format!(
                    "unknown input {name:?}; the inputs are {INPUT_NAMES}"
                )))
            }
        };
        if matches!(input, Input::Torque(_)) && !torsion {
            return Err(error(
                "a torque input needs torsion (the beam has no GJ)".to_string(),
            ));
        }
        Ok(input)
    }

    /// The input's name.
    pub fn name(&self) -> String {
        match self {
            Input::RootAngle => "root_angle".into(),
            Input::Speed => "speed".into(),
            Input::Gust => "gust".into(),
            Input::StripGust(k) => format!("gust[{k}]"),
            Input::GustRate => "gust_rate".into(),
            Input::Force(k) => format!("force[{k}]"),
            Input::Torque(k) => format!("torque[{k}]"),
            Input::Deflection(s) => format!("delta[{}]", s.name),
            Input::DeflectionRate(s) => format!("delta_rate[{}]", s.name),
            Input::DeflectionAcceleration(s) => format!("delta_acceleration[{}]", s.name),
        }
    }

    /// The input's unit.
    pub fn unit(&self) -> &'static str {
        match self {
            Input::RootAngle => "rad",
            Input::Speed | Input::Gust | Input::StripGust(_) => "m/s",
            Input::GustRate => "m/s²",
            Input::Force(_) => "N",
            Input::Torque(_) => "N·m",
            Input::Deflection(_) => "rad",
            Input::DeflectionRate(_) => "rad/s",
            Input::DeflectionAcceleration(_) => "rad/s²",
        }
    }

    /// What the input is, in one sentence (the FMU's variable descriptions).
    pub fn description(&self) -> String {
        match self {
            Input::RootAngle => "root angle of attack (nose-up rotation of the free stream)".into(),
            Input::Speed => "free-stream speed".into(),
            Input::Gust => "vertical gust velocity (up), uniform over the span".into(),
            Input::GustRate => "rate of the uniform vertical gust velocity".into(),
            Input::StripGust(k) => {
                format!("vertical gust velocity (up) at the strip of element {k}")
            }
            Input::Force(k) => format!("dead vertical force (up) at node {k}"),
            Input::Torque(k) => {
                format!("torque about the span axis (nose-up) on the element inboard of node {k}")
            }
            Input::Deflection(s) => {
                format!(
                    "deflection of control surface {} (trailing edge down)",
                    s.name
                )
            }
            Input::DeflectionRate(s) => format!("rate of deflection of control surface {}", s.name),
            Input::DeflectionAcceleration(s) => {
                format!("acceleration of deflection of control surface {}", s.name)
            }
        }
    }

    /// The input as a named signal.
    pub fn signal(&self) -> Signal {
        Signal {
            name: self.name(),
            unit: self.unit(),
        }
    }
}

impl Output {
    /// The output called `name` on a chain of `n` elements (`torsion`: with twist) with the
    /// control surfaces `surfaces`; errors name `field`.
    ///
    /// # Errors
    /// An unknown name, an index out of range, a twist or torque of a bending-only beam, a
    /// surface the wing does not have.
    pub fn parse(
        name: &str,
        n: usize,
        torsion: bool,
        surfaces: &[ControlSurface],
        field: &str,
    ) -> Result<Self, InputError> {
        let error = |reason: String| InputError::new(field, reason);
        let node = |i: &str| index_in(i, "node", 0, n).map_err(error);
        let output = match (name, indexed(name)) {
            ("tip_x", _) => Output::TipX,
            ("tip_y", _) => Output::TipY,
            ("tip_z", _) => Output::TipZ,
            ("tip_twist", _) => Output::TipTwist,
            ("root_bending_moment", _) => Output::RootBendingMoment,
            ("root_shear", _) => Output::RootShear,
            ("root_torque", _) => Output::RootTorque,
            ("root_lag_moment", _) => Output::RootLagMoment,
            ("lift", _) => Output::Lift,
            ("tip_acceleration", _) => Output::TipAcceleration,
            (_, Some(("x", i))) => Output::X(node(i)?),
            (_, Some(("y", i))) => Output::Y(node(i)?),
            (_, Some(("z", i))) => Output::Z(node(i)?),
            (_, Some(("twist", i))) => Output::Twist(node(i)?),
            (_, Some(("acceleration", i))) => Output::Acceleration(node(i)?),
            (_, Some(("hinge_moment", i))) => {
                Output::HingeMoment(surface_in(i, surfaces).map_err(error)?)
            }
            _ => {
                return Err(error(format!(
                    "unknown output {name:?}; the outputs are {OUTPUT_NAMES}"
                )))
            }
        };
        if matches!(
            output,
            Output::TipTwist | Output::Twist(_) | Output::RootTorque
        ) && !torsion
        {
            return Err(error(format!("{name} needs torsion (the beam has no GJ)")));
        }
        Ok(output)
    }

    /// Whether the output exists on the 3-D chain only (`tip_z`, `z[k]`, `root_lag_moment`:
    /// the planar chain has no lag).
    pub fn is_spatial(&self) -> bool {
        matches!(self, Output::TipZ | Output::Z(_) | Output::RootLagMoment)
    }

    /// The error of a 3-D output asked of the planar chain, naming `field`; `None` otherwise.
    pub fn planar_error(&self, field: &str) -> Option<InputError> {
        self.is_spatial().then(|| {
            InputError::new(
                field,
                format!(
                    "{} is an output of the 3-D chain (beam.model = \"chain3d\"): the planar \
                     chain has no lag",
                    self.name()
                ),
            )
        })
    }

    /// The output's name.
    pub fn name(&self) -> String {
        match self {
            Output::TipX => "tip_x".into(),
            Output::TipY => "tip_y".into(),
            Output::TipZ => "tip_z".into(),
            Output::TipTwist => "tip_twist".into(),
            Output::X(k) => format!("x[{k}]"),
            Output::Y(k) => format!("y[{k}]"),
            Output::Z(k) => format!("z[{k}]"),
            Output::Twist(k) => format!("twist[{k}]"),
            Output::RootBendingMoment => "root_bending_moment".into(),
            Output::RootShear => "root_shear".into(),
            Output::RootTorque => "root_torque".into(),
            Output::RootLagMoment => "root_lag_moment".into(),
            Output::Lift => "lift".into(),
            Output::TipAcceleration => "tip_acceleration".into(),
            Output::Acceleration(k) => format!("acceleration[{k}]"),
            Output::HingeMoment(s) => format!("hinge_moment[{}]", s.name),
        }
    }

    /// The output's unit.
    pub fn unit(&self) -> &'static str {
        match self {
            Output::TipX
            | Output::TipY
            | Output::TipZ
            | Output::X(_)
            | Output::Y(_)
            | Output::Z(_) => "m",
            Output::TipTwist | Output::Twist(_) => "rad",
            Output::RootBendingMoment
            | Output::RootTorque
            | Output::RootLagMoment
            | Output::HingeMoment(_) => "N·m",
            Output::RootShear | Output::Lift => "N",
            Output::TipAcceleration | Output::Acceleration(_) => "m/s²",
        }
    }

    /// What the output is, in one sentence (the FMU's variable descriptions).
    pub fn description(&self) -> String {
        match self {
            Output::TipX => "tip node's spanwise position".into(),
            Output::TipY => "tip node's vertical position (wing frame)".into(),
            Output::TipZ => "tip node's chordwise position (toward the leading edge)".into(),
            Output::TipTwist => "twist of the tip element (nose-up)".into(),
            Output::X(k) => format!("node {k}'s spanwise position"),
            Output::Y(k) => format!("node {k}'s vertical position (wing frame)"),
            Output::Z(k) => format!("node {k}'s chordwise position (toward the leading edge)"),
            Output::Twist(k) => format!("twist of the element inboard of node {k} (nose-up)"),
            Output::RootBendingMoment => "root bending moment (the clamp spring's)".into(),
            Output::RootShear => "force of the wing on the clamp (up, wing frame)".into(),
            Output::RootTorque => "root torque (the clamp's torsion spring)".into(),
            Output::RootLagMoment => "root lag bending moment (the clamp's, about n)".into(),
            Output::Lift => "total aerodynamic force along the ground's vertical".into(),
            Output::TipAcceleration => "tip node's vertical acceleration".into(),
            Output::Acceleration(k) => format!("node {k}'s vertical acceleration"),
            Output::HingeMoment(s) => {
                format!(
                    "hinge moment of control surface {} (trailing edge down)",
                    s.name
                )
            }
        }
    }

    /// The output as a named signal.
    pub fn signal(&self) -> Signal {
        Signal {
            name: self.name(),
            unit: self.unit(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_errors_name_the_field() {
        let surfaces = [
            ControlSurface::new("flap", 0.0, 1.0, 0.8),
            ControlSurface::new("aileron", 1.0, 2.0, 0.75),
        ];
        for name in [
            "root_angle",
            "speed",
            "gust",
            "gust[3]",
            "gust_rate",
            "force[4]",
            "torque[1]",
            "delta[aileron]",
            "delta_rate[flap]",
            "delta_acceleration[aileron]",
        ] {
            let input = Input::parse(name, 4, true, &surfaces, "i").unwrap();
            assert_eq!(input.name(), name);
        }
        for name in [
            "tip_x",
            "tip_y",
            "tip_twist",
            "x[0]",
            "y[4]",
            "twist[2]",
            "root_bending_moment",
            "root_shear",
            "root_torque",
            "lift",
            "tip_acceleration",
            "acceleration[3]",
            "hinge_moment[flap]",
            "tip_z",
            "z[2]",
            "root_lag_moment",
        ] {
            let output = Output::parse(name, 4, true, &surfaces, "o").unwrap();
            assert_eq!(output.name(), name);
        }
        let cases = [
            (
                Input::parse("gusts", 4, true, &[], "linearize.inputs[1]").unwrap_err(),
                "linearize.inputs[1]: unknown input \"gusts\"; the inputs are root_angle",
            ),
            (
                Input::parse("force[5]", 4, true, &[], "i").unwrap_err(),
                "i: node 5 is out of range: 1 to 4",
            ),
            (
                Input::parse("gust[0]", 4, true, &[], "i").unwrap_err(),
                "i: element 0 is out of range: 1 to 4",
            ),
            (
                Input::parse("torque[2]", 4, false, &[], "i").unwrap_err(),
                "i: a torque input needs torsion",
            ),
            (
                Output::parse("y[x]", 4, true, &[], "o").unwrap_err(),
                "o: \"x\" is not a node number",
            ),
            (
                Output::parse("tip_twist", 4, false, &[], "o").unwrap_err(),
                "o: tip_twist needs torsion",
            ),
            (
                Input::parse("delta[rudder]", 4, true, &surfaces, "i").unwrap_err(),
                "i: there is no control surface \"rudder\"; the surfaces are flap, aileron",
            ),
            (
                Output::parse("hinge_moment[flap]", 4, true, &[], "o").unwrap_err(),
                "o: there is no control surface \"flap\": the case has no [[aero.surfaces]]",
            ),
        ];
        for (e, expected) in cases {
            assert!(e.to_string().starts_with(expected), "{e}");
        }
        assert_eq!(StateBasis::from_name("momenta"), Some(StateBasis::Momenta));
        assert_eq!(StateBasis::from_name("x"), None);
    }
}
