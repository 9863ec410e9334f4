//! Movement primitives learned from demonstration: DMP, ProMP and KMP.
//!
//! - [`basis`]: normalized Gaussian basis functions over a phase, with exact derivatives.
//! - [`dmp`]: discrete dynamic movement primitives ([`Dmp`], rollouts as [`DmpRollout`]).
//! - [`promp`]: probabilistic movement primitives ([`ProMp`]): fit, conditioning, sampling.
//!
//! Every primitive yields a [`crate::Trajectory`] (a DMP rollout, a ProMP mean or sample, a KMP
//! mean), so it can be sampled, limit-checked, plotted and time-rescaled like any other
//! trajectory. Each module states its precision contract.

pub mod basis;
pub mod dmp;
pub mod promp;

pub use basis::GaussianBasis;
pub use dmp::{Coupling, Dmp, DmpConfig, DmpRollout, ForcingScaling, GoalChange, RolloutOptions};
pub use promp::{Demo, ProMp, ProMpConfig, ProMpSampler, ViaPoint, WeightTrajectory};
