//! Movement primitives learned from demonstration: DMP, ProMP and KMP.
//!
//! Every primitive yields a [`crate::Trajectory`] (a DMP rollout, a ProMP mean or sample, a KMP
//! mean), so it can be sampled, limit-checked, plotted and time-rescaled like any other
//! trajectory. Demonstrations are plain slices: times, and positions row-major
//! `samples × joints`.
//!
//! # Map
//! - [`Dmp`] (dmp/): discrete dynamic movement primitive, [`Dmp::fit`] from one
//!   demonstration ([`DmpConfig`], [`ForcingScaling`]), [`Dmp::rollout`] with
//!   [`RolloutOptions`] (new start, goal, τ, [`GoalChange`]s, goal filter, a [`CouplingTerm`]
//!   such as [`ObstacleAvoidance`], [`PhaseStop`]) into a [`DmpRollout`]. The files follow the
//!   jobs: the model (`mod.rs`), the fit (`fit.rs`), the rollout options (`options.rs`), the
//!   integrators (`rollout.rs`: checks and RK4; `exact.rs`: the exponential integrator) and
//!   the dense output (`dense.rs`).
//! - [`BoundedDmp`] (bounded_dmp.rs): a DMP in `atanh` coordinates whose rollouts
//!   ([`BoundedRollout`]) stay strictly inside joint position limits.
//! - [`RhythmicDmp`] (rhythmic.rs): periodic DMPs from one period.
//! - [`QuaternionDmp`] (cartesian_dmp.rs): orientation DMPs on unit quaternions
//!   ([`crate::spline::Quat`]), rollouts as [`QuaternionRollout`].
//! - [`ProMp`] (promp.rs): a Gaussian distribution over trajectories from several
//!   [`Demo`]s ([`ProMpConfig`]); conditioning on [`ViaPoint`]s, sampling
//!   ([`ProMpSampler`]), the mean or a sample as a [`WeightTrajectory`].
//! - [`Kmp`] (kmp.rs, with kmp_lowrank.rs and kmp_cov.rs): kernelized movement primitives
//!   from a [`KmpReference`] ([`KmpConfig`]), via points ([`KmpVia`]); the reference from a
//!   [`Gmm`] (gmm.rs, [`GmmConfig`]), a ProMP or aligned samples.
//! - [`GaussianBasis`] (basis.rs): normalized Gaussian basis functions over a phase with exact
//!   derivatives, shared by DMPs and ProMPs.
//! - Shared plumbing: ridge.rs (the ridge regression of the weights, streamed through a
//!   blocked accumulator: no `samples × basis` matrix), demo.rs (demonstration checks and
//!   finite-difference derivatives).
//!
//! Size limits checked before anything is allocated: [`MAX_BASIS`] basis functions,
//! [`MAX_WEIGHTS`] ProMP weights, [`MAX_UNKNOWNS`] KMP unknowns; [`MAX_REACH`] bounds how far
//! a DMP rollout's start or goal may lie from the demonstrated one.
//!
//! # Precision contract
//! Each model's file states it in full next to the code; in short (all checked by the tests
//! under `tests/primitives_*.rs`):
//! - **DMP**: uncoupled rollouts by an exponential integrator (exact homogeneous part, quintic
//!   interpolant of the forcing), coupled ones by RK4; refining the default step 16-fold
//!   changes the rollout by < 1e-9 of the range. Dense output is the quintic Hermite
//!   interpolant of `(y, ẏ, ÿ)`: position to jerk consistent, continuous to acceleration. A
//!   smooth 7-joint demonstration at 1 kHz with 50 basis functions is reproduced within RMS
//!   1e-4 of each joint's range.
//! - **Bounded DMP**: `lo < y(t) < hi` at every `t` (up to the rounding of `tanh` at
//!   `|ξ| > 19`); derivatives by the exact chain rule.
//! - **Rhythmic DMP**: RK4 as above (2000 steps per period), reproduction RMS ≤ 1e-3 of the
//!   range, period after period.
//! - **Orientation DMP**: Runge–Kutta–Munthe-Kaas of order 4 on the unit quaternions;
//!   halving the step changes the rollout by < 1e-10 rad; reproduction RMS ≤ 1e-4 rad.
//! - **ProMP**: conditioning with zero via-point covariance passes through the via point to
//!   the accuracy of the small solve (1e-9 in the tests); a singular innovation matrix is
//!   regularized by the smallest sufficient multiple of the identity
//!   ([`ProMp::last_jitter`]).
//! - **KMP**: covariance queries equal the direct formula to rounding (1e-9 relative
//!   asserted, 4e-13 to 6.6e-11 measured); factorization regularization is reported by
//!   [`Kmp::jitter`].
//! - **GMM**: EM with log-sum-exp responsibilities; the log-likelihood never decreases by more
//!   than roundoff.
//! - Evaluation (rollouts, means, KMP covariance with its expansion) allocates nothing; time
//!   is clamped to the trajectory's interval.

mod basis;
mod bounded_dmp;
mod cartesian_dmp;
mod demo;
mod dmp;
mod gmm;
mod kmp;
mod kmp_cov;
mod kmp_lowrank;
mod promp;
mod rhythmic;
mod ridge;

pub use basis::{GaussianBasis, MAX_BASIS};
pub use bounded_dmp::{BoundedDmp, BoundedRollout};
pub use cartesian_dmp::{QuaternionDmp, QuaternionRollout};
pub use dmp::{
    ActualPosition, Coupling, CouplingTerm, Dmp, DmpConfig, DmpRollout, ForcingScaling, GoalChange,
    ObstacleAvoidance, PhaseStop, RolloutOptions, MAX_REACH,
};
pub use gmm::{Gmm, GmmConfig};
pub use kmp::{Kmp, KmpConfig, KmpReference, KmpVia, MAX_UNKNOWNS};
pub use promp::{Demo, ProMp, ProMpConfig, ProMpSampler, ViaPoint, WeightTrajectory, MAX_WEIGHTS};
pub use rhythmic::RhythmicDmp;
