//! Step 1 never misses a profile of one of its own families.
//!
//! Seeded property test of the mechanism behind the `step1_property` reproducer (a none-family
//! root whose second acceleration level lay next to zero, ill-conditioned in the family's
//! parameter, missed the target by 1.7e-8 and was dropped, so step 1 returned a profile 0.3 %
//! slower than Ruckig's). Each case builds a profile of a step-1 family (none, acc0, acc1,
//! acc0_acc1, cruise at the velocity limit) forward from a random state with random levels and
//! plateau durations inside the limits, often next to each other or to zero, where the valid
//! parameter ranges are narrow. Its end state becomes the target: the minimum duration that
//! step 1 finds must not exceed the constructed profile's (× (1 + 1e-9)). Half the problems
//! are mirrored (the negative direction).
//!
//! Not yet met everywhere: 2 of the default run's ~16 800 cases are still missed
//! ([`KNOWN_MISSES`], pinned so that any change shows), and 52 of the long run's 251 940 (77
//! before the plateau families' window ends took the displacement's rounding and the none
//! family's window-end levels were polished; none new); in each of them Ruckig 0.19.4 is as
//! long or longer (`tools/otg_step1_misses.py` classifies a
//! long run's misses against the wheel). Before the none family's rescue (window-end
//! candidates, the solve in the middle ramp's duration, `step1/closed.rs`) and the plateau
//! families' polish, the long run missed 333 cases: 45 where Ruckig was shorter and reached
//! the target within the tolerance (in 6 of them, all 1e-9 to 2e-6 longer, the solver then
//! given Ruckig's own final position as the target was as fast as Ruckig), 288 where Ruckig
//! was as long or longer. Of those 45, 44 are now at most Ruckig's duration and are in
//! `fixtures/otg/regressions.jsonl` (category `step1_property`); the other, case 126400, is
//! now the exact constructed profile (below).
//!
//! Ruckig shorter by its own error (in the fixture with the end position Ruckig reached, which
//! trajkit then reaches as fast: see tests/otg_regressions.rs): case 15540 of the default run (none family, a
//! motion of 4.07e-7 in 3.78e-7 s at 1.08 m/s): trajkit 3.77733754e-7 s, the constructed
//! duration to 1e-9; Ruckig 3.77731502e-7 s, 6.0e-6 shorter, ending 2.4e-12 before the target
//! (0.59 of the scale-relative tolerance of 4.1e-12, so within it), and 2.4e-12 at 1.08 m/s is
//! the 2.25e-12 s it saves. Case 126400 of the long run likewise: trajkit 1.21954210e-5 s (the
//! constructed duration), Ruckig 4.95e-6 shorter, ending 3.5e-12 short (0.49 of the
//! tolerance) at 0.06 m/s, worth 5.9e-11 s, the difference. In both, trajkit given Ruckig's
//! final position as the target is as fast as Ruckig; the sweep counts such results as
//! `longer_by_ruckig_error`, apart from `longer` (`tools/otg_sweep.py`).

mod otg_common;
use otg_common::{step1_property, FAMILIES};
use trajkit::otg::Otg;
use trajkit::rng::SplitMix64;

/// Runs `count` cases from `seed`; returns the misses (case number, one line each) and the
/// number tried.
fn sweep(seed: u64, count: usize) -> (Vec<(usize, String)>, usize) {
    let otg = Otg::<1>::new(0.001);
    let mut r = SplitMix64::new(seed);
    let (mut missed, mut tried) = (Vec::new(), 0);
    for case in 0..count {
        let kind = case % FAMILIES.len();
        let Some((inp, t)) = step1_property(&mut r, kind) else {
            continue;
        };
        tried += 1;
        match otg.calculate(&inp) {
            Ok(tr) if tr.duration() <= t * (1.0 + 1e-9) => {}
            Ok(tr) => missed.push((
                case,
                format!(
                    "case {case} ({}): {} > {t}: {inp:?}",
                    FAMILIES[kind],
                    tr.duration()
                ),
            )),
            Err(e) => missed.push((
                case,
                format!("case {case} ({}): {e}: {inp:?}", FAMILIES[kind]),
            )),
        }
    }
    (missed, tried)
}

/// The cases of the default run that step 1 still misses (see the module docs), so that a
/// new miss fails the test and so does a fixed one (the list then shrinks; it was 22 cases
/// before the none family's rescue, all of them fixed but these; 12022, 18987 and 19982
/// since the plateau families' window ends and the polished window-end levels of the none
/// family). By class, Ruckig 0.19.4 as long or longer in each:
/// - at most 8e-9 longer on a duration below 2.5e-6 s, Ruckig's duration within 1e-9 or
///   longer: 3960;
/// - far longer (a slower family chosen: 16.7 s for 2.8e-7 s), Ruckig returning the same
///   longer duration: 15425.
const KNOWN_MISSES: [usize; 2] = [3960, 15425];

#[test]
fn step1_finds_its_families_profiles() {
    let (missed, tried) = sweep(20261126, 20000);
    let cases: Vec<usize> = missed.iter().map(|m| m.0).collect();
    for (case, m) in &missed {
        if !KNOWN_MISSES.contains(case) {
            eprintln!("{m}");
        }
    }
    assert_eq!(cases, KNOWN_MISSES, "missed cases changed ({tried} tried)");
    assert!(tried >= 12000, "{tried}");
}

/// The long run (`cargo test -p trajkit --release --test otg_step1_shapes -- --ignored`):
/// every miss printed; it fails while the classes of [`KNOWN_MISSES`] remain.
#[test]
#[ignore]
fn step1_finds_its_families_profiles_long() {
    let (missed, tried) = sweep(20261127, 300_000);
    for (_, m) in &missed {
        eprintln!("{m}");
    }
    assert!(missed.is_empty(), "{} missed of {tried}", missed.len());
}
