//! One degree of freedom's problem: boundary states, limits and the profile order.
//!
//! The solver works on [`Dof1`]: the state to start from, the state to reach and the limits of
//! one joint. Limits follow trajkit's convention (an infinite value means unlimited; minima are
//! negative). The order of the profiles follows from which limits are finite: an infinite
//! acceleration limit gives first-order (velocity-limited) profiles, an infinite jerk limit with
//! a finite acceleration limit gives second-order (trapezoidal) profiles, and otherwise
//! third-order (jerk-limited, 7-phase S-curve) profiles.

/// Which derivative the profile's piecewise-constant input is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ProfileOrder {
    /// Piecewise-constant velocity (velocity limit only).
    First,
    /// Piecewise-constant acceleration (trapezoidal velocity, infinite jerk).
    Second,
    /// Piecewise-constant jerk (7-phase S-curve).
    Third,
}

/// What the target prescribes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ControlInterface {
    /// Reach the target position, velocity and acceleration.
    #[default]
    Position,
    /// Reach the target velocity and acceleration; the final position is free.
    Velocity,
}

/// The problem for one degree of freedom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dof1 {
    /// Current position.
    pub p0: f64,
    /// Current velocity.
    pub v0: f64,
    /// Current acceleration.
    pub a0: f64,
    /// Target position.
    pub pf: f64,
    /// Target velocity.
    pub vf: f64,
    /// Target acceleration.
    pub af: f64,
    /// Largest velocity (> 0, may be infinite).
    pub vmax: f64,
    /// Smallest velocity (< 0, may be −infinite).
    pub vmin: f64,
    /// Largest acceleration (> 0, may be infinite).
    pub amax: f64,
    /// Smallest acceleration (< 0, may be −infinite).
    pub amin: f64,
    /// Jerk limit (> 0, may be infinite), the same in both directions.
    pub jmax: f64,
    /// Position or velocity target.
    pub interface: ControlInterface,
}

impl Dof1 {
    /// A rest-to-rest problem with symmetric limits.
    pub(crate) fn rest_to_rest(p0: f64, pf: f64, vmax: f64, amax: f64, jmax: f64) -> Dof1 {
        Dof1 {
            p0,
            v0: 0.0,
            a0: 0.0,
            pf,
            vf: 0.0,
            af: 0.0,
            vmax,
            vmin: -vmax,
            amax,
            amin: -amax,
            jmax,
            interface: ControlInterface::Position,
        }
    }

    /// The order of the profiles this problem gets.
    pub(crate) fn order(&self) -> ProfileOrder {
        if self.amax.is_infinite() || self.amin.is_infinite() {
            ProfileOrder::First
        } else if self.jmax.is_infinite() {
            ProfileOrder::Second
        } else {
            ProfileOrder::Third
        }
    }

    /// The mirrored problem (all states negated, limits swapped).
    pub(crate) fn mirrored(&self) -> Dof1 {
        Dof1 {
            p0: -self.p0,
            v0: -self.v0,
            a0: -self.a0,
            pf: -self.pf,
            vf: -self.vf,
            af: -self.af,
            vmax: -self.vmin,
            vmin: -self.vmax,
            amax: -self.amin,
            amin: -self.amax,
            jmax: self.jmax,
            interface: self.interface,
        }
    }
}
