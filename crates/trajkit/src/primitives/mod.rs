//! Movement primitives learned from demonstration: DMP, ProMP and KMP.
//!
//! - [`basis`]: normalized Gaussian basis functions over a phase, with exact derivatives.
//! - [`bounded_dmp`]: DMPs whose rollouts stay inside joint position limits ([`BoundedDmp`]).
//! - [`cartesian_dmp`]: orientation DMPs with unit quaternions ([`QuaternionDmp`]).
//! - [`dmp`]: discrete dynamic movement primitives ([`Dmp`], rollouts as [`DmpRollout`]).
//! - [`gmm`]: Gaussian mixture (EM) and regression on time, for KMP references.
//! - [`kmp`]: kernelized movement primitives ([`Kmp`]) with via points.
//! - [`rhythmic`]: rhythmic (periodic) DMPs ([`RhythmicDmp`]).
//! - [`promp`]: probabilistic movement primitives ([`ProMp`]): fit, conditioning, sampling.
//!
//! Every primitive yields a [`crate::Trajectory`] (a DMP rollout, a ProMP mean or sample, a KMP
//! mean), so it can be sampled, limit-checked, plotted and time-rescaled like any other
//! trajectory. Each module states its precision contract.

pub mod basis;
pub mod bounded_dmp;
pub mod cartesian_dmp;
pub mod dmp;
pub mod gmm;
pub mod kmp;
mod kmp_cov;
mod kmp_lowrank;
pub mod promp;
pub mod rhythmic;

pub use basis::{GaussianBasis, MAX_BASIS};
pub use bounded_dmp::{BoundedDmp, BoundedRollout};
pub use cartesian_dmp::{quat_exp, quat_log, quat_mul, QuaternionDmp, QuaternionRollout};
pub use dmp::{
    ActualPosition, Coupling, CouplingTerm, Dmp, DmpConfig, DmpRollout, ForcingScaling, GoalChange,
    ObstacleAvoidance, PhaseStop, RolloutOptions,
};
pub use gmm::{Gmm, GmmConfig};
pub use kmp::{Kmp, KmpConfig, KmpReference, KmpVia};
pub use promp::{Demo, ProMp, ProMpConfig, ProMpSampler, ViaPoint, WeightTrajectory};
pub use rhythmic::RhythmicDmp;
