//! The collector of step 1's candidates: builds them in place, verifies them, keeps the
//! fastest and records the candidate durations.

use super::super::problem::Dof1;
use super::super::profile::{Profile, State1};
use super::verify::{verify, TOL_POSITION};
use super::MAX_CANDIDATES;

/// Collects verified candidates and keeps the fastest.
///
/// Candidates are built in place in a spare buffer ([`Collector::scratch`], then
/// [`Collector::submit`]); the fastest valid one stays in the other buffer, so no profile is
/// copied while the families are enumerated. One of the two buffers is the caller's (where
/// the result is wanted), the other the collector's own; the second is created only when a
/// second candidate is built while a valid one is kept (most rest-to-rest problems never need
/// it, and so never pay for initialising it).
pub(crate) struct Collector<'a> {
    dof: &'a Dof1,
    /// Buffer 0.
    out: &'a mut Profile,
    /// Buffer 1, created on first use.
    own: &'a mut Option<Profile>,
    /// Which buffer holds the fastest valid candidate so far.
    best: Option<usize>,
    /// Only the fastest candidate is wanted: candidates that cannot beat it are neither
    /// verified nor recorded.
    pub(super) fastest_only: bool,
    pub cand: [f64; MAX_CANDIDATES],
    pub ncand: usize,
}

impl<'a> Collector<'a> {
    pub fn new(
        dof: &'a Dof1,
        out: &'a mut Profile,
        own: &'a mut Option<Profile>,
        fastest_only: bool,
    ) -> Self {
        Collector {
            dof,
            out,
            own,
            best: None,
            fastest_only,
            cand: [0.0; MAX_CANDIDATES],
            ncand: 0,
        }
    }

    #[inline]
    fn buf(&self, k: usize) -> &Profile {
        match (k, self.own.as_ref()) {
            (1, Some(own)) => own,
            // Buffer 1 is created (by `buf_mut`) before it is first read: only k = 0 gets here.
            _ => self.out,
        }
    }

    #[inline]
    fn buf_mut(&mut self, k: usize) -> &mut Profile {
        if k == 0 {
            self.out
        } else {
            self.own.get_or_insert_with(Profile::default)
        }
    }

    /// The fastest valid candidate so far.
    #[inline]
    pub fn best(&self) -> Option<&Profile> {
        self.best.map(|k| self.buf(k))
    }

    /// Which buffer holds the fastest valid candidate (0: the caller's).
    pub fn best_index(&self) -> Option<usize> {
        self.best
    }

    /// Leaves the fastest valid candidate in the caller's buffer.
    pub fn settle(&mut self) {
        if let (Some(1), Some(own)) = (self.best, self.own.as_ref()) {
            *self.out = *own;
            self.best = Some(0);
        }
    }

    #[inline]
    fn spare(&self) -> usize {
        match self.best {
            Some(0) => 1,
            _ => 0,
        }
    }

    /// Whether every valid candidate matters (the target moves, so every valid duration
    /// bounds a blocked interval, and all candidates are wanted).
    #[inline]
    fn wants_all(&self) -> bool {
        !self.fastest_only && (self.dof.vf != 0.0 || self.dof.af != 0.0)
    }

    /// Whether a candidate of duration `t` can still matter: it could be the fastest, or
    /// every candidate is wanted.
    #[inline]
    pub fn wants(&self, t: f64) -> bool {
        self.wants_all() || self.best().is_none_or(|b| t < b.duration())
    }

    /// Whether a family whose profiles keep their velocity within `[v_low, v_high]` (with a
    /// margin of 1e-9 relative) can be skipped for displacement `d`: covering `d` (to the
    /// position tolerance) takes at least |d|/|v| at the velocity bound v on its side. It is
    /// skipped when no valid profile can cover `d` (both modes: nothing valid is lost), or, in
    /// fastest-only mode, when covering it takes longer than the fastest so far.
    #[inline]
    pub fn cannot_cover(&self, d: f64, v_low: f64, v_high: f64) -> bool {
        let need = d.abs() - TOL_POSITION;
        if need.is_nan() || need <= 0.0 {
            return false;
        }
        let slack = 1e-9 * (v_low.abs().min(1e300) + v_high.abs().min(1e300));
        let v = if d > 0.0 {
            v_high + slack
        } else {
            slack - v_low
        };
        if v.is_nan() {
            return false;
        }
        if v <= 0.0 {
            return true;
        }
        match self.best() {
            Some(b) if self.fastest_only => need / v > b.duration() * (1.0 + 1e-9),
            _ => false,
        }
    }

    /// The spare buffer, emptied and starting at `s`, to build a candidate in.
    #[inline]
    pub fn scratch(&mut self, s: State1) -> &mut Profile {
        let k = self.spare();
        let b = self.buf_mut(k);
        b.reset(s);
        b
    }

    /// Offers the candidate built in the spare buffer; returns whether it was valid.
    pub fn submit(&mut self) -> bool {
        let k = self.spare();
        let t = self.buf(k).duration();
        if !self.wants(t) || !verify(self.dof, self.buf(k)) {
            return false;
        }
        self.record(t);
        if self.best().is_none_or(|b| t < b.duration()) {
            self.best = Some(k);
        }
        true
    }

    /// Offers a main profile (starting after the brake); returns whether it was valid.
    pub fn offer(&mut self, main: &Profile) -> bool {
        if !self.wants(main.duration()) || !verify(self.dof, main) {
            return false;
        }
        let t = main.duration();
        self.record(t);
        if self.best().is_none_or(|b| t < b.duration()) {
            let k = self.spare();
            *self.buf_mut(k) = *main;
            self.best = Some(k);
        }
        true
    }

    #[inline]
    fn record(&mut self, t: f64) {
        if !self.fastest_only
            && self.ncand < MAX_CANDIDATES
            && !self.cand[..self.ncand].contains(&t)
        {
            self.cand[self.ncand] = t;
            self.ncand += 1;
        }
    }
}
