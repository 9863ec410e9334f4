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
//!
//! # Implementation notes
//!
//! `primitives/` — one file per model. `basis.rs`: normalized Gaussian basis over a phase with
//! exact derivatives (its own vectorizable `exp`, relative error < 5e-16). `dmp.rs`: ridge fit of
//! the forcing term — design rows are streamed into `RidgeAccumulator` (blocked rank-32 updates
//! of ΦᵀΦ and ΦᵀF, no rows × basis matrix; ProMP, rhythmic and quaternion DMPs use it through
//! `ridge_fit`), rollout by an exponential integrator when uncoupled (exact `e^{Mh}` propagation, forcing integrated as a quintic interpolant of grid values; `ExpStep`), else RK4 with the forcing term at each stage's own time, dense
//! quintic-Hermite output (`DmpRollout` is a `Trajectory`); `bounded_dmp.rs`, `rhythmic.rs`,
//! `cartesian_dmp.rs` reuse it. `promp.rs`: per-demo ridge fit, weight mean/covariance,
//! conditioning by one small Cholesky solve. `gmm.rs` (EM + GMR) builds `kmp.rs` references;
//! `Kmp::fit` caches the mean weights, so a mean query is O(N·d); `kmp_lowrank.rs` solves both KMP systems without an (N·d)³ factorization when the time kernel has a low numerical rank (pivoted Cholesky of `K_t` + Woodbury with the block-diagonal λΣ, as CG preconditioner and for one refinement step guarded by an a-priori contraction bound; the Cholesky of `K + λ_c Σ` is the fallback, built lazily for `covariance_exact`); `kmp_cov.rs` is the
//! covariance's Chebyshev expansion in time (its matrices `Bᵀ A⁻¹ B` from the low-rank refinement or from the factor) (degree from an a-priori bound, matrices cached at
//! fit, so a covariance query is d(d+1)/2 small quadratic forms; exact per-query substitution
//! for spans of many kernel widths). `linalg.rs` (Cholesky with reported regularization, LU) is
//! the crate's dense algebra, on row-major slices.

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
