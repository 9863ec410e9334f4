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
//!
//! # Implementation notes
//!
//! `primitives/` — one file per model. `basis.rs`: normalized Gaussian basis over a phase with
//! exact derivatives (its own vectorizable `exp`, relative error < 5e-16). `ridge.rs`: ridge fit of
//! the forcing term — design rows are streamed into `RidgeAccumulator` (blocked rank-32 updates
//! of ΦᵀΦ and ΦᵀF, no rows × basis matrix; ProMP, rhythmic and quaternion DMPs use it through
//! `ridge_fit`), rollout by an exponential integrator when uncoupled (exact `e^{Mh}` propagation, forcing integrated as a quintic interpolant of grid values; `ExpStep`), else RK4 with the forcing term at each stage's own time (`dmp/`), dense
//! quintic-Hermite output (`DmpRollout` is a `Trajectory`); `bounded_dmp.rs`, `rhythmic.rs`,
//! `cartesian_dmp.rs` reuse it. `promp.rs`: per-demo ridge fit, weight mean/covariance,
//! conditioning by one small Cholesky solve. `gmm.rs` (EM + GMR) builds `kmp.rs` references;
//! `Kmp::fit` caches the mean weights, so a mean query is O(N·d); `kmp_lowrank.rs` solves both KMP systems without an (N·d)³ factorization when the time kernel has a low numerical rank (pivoted Cholesky of `K_t` + Woodbury with the block-diagonal λΣ, as CG preconditioner and for one refinement step guarded by an a-priori contraction bound; the Cholesky of `K + λ_c Σ` is the fallback, built lazily for `covariance_exact`); `kmp_cov.rs` is the
//! covariance's Chebyshev expansion in time (its matrices `Bᵀ A⁻¹ B` from the low-rank refinement or from the factor) (degree from an a-priori bound, matrices cached at
//! fit, so a covariance query is d(d+1)/2 small quadratic forms; exact per-query substitution
//! for spans of many kernel widths). `linalg.rs` (Cholesky with reported regularization, LU) is
//! the crate's dense algebra, on row-major slices.

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
