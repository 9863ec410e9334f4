//! Differential tests against rsruckig (Ruckig's Rust port): where Ruckig succeeds, trajkit's
//! duration must agree within 1e-9 relative.

mod otg_common;
use otg_common::*;
use trajkit::otg::Otg;
use trajkit::rng::SplitMix64;

fn compare<const N: usize>(cat: Cat, n: usize, seed: u64, verbose: bool) -> (usize, usize, usize, usize) {
    let mut r = SplitMix64::new(seed);
    let otg = Otg::<N>::new(0.001);
    let (mut agree, mut ruckig_failed, mut mismatch, mut ours_failed) = (0, 0, 0, 0);
    for k in 0..n {
        let inp = problem::<N>(&mut r, cat);
        let ours = otg.calculate(&inp);
        let theirs = ruckig_duration(&inp, 0.001);
        match (ours, theirs) {
            (Ok(tr), Some(t)) => {
                let w = check(&inp, &tr);
                assert!(within_contract(&w), "{cat:?} case {k}: {w:?}\n{inp:?}");
                if (tr.duration() - t).abs() <= 1e-9 * t.max(1.0) {
                    agree += 1;
                } else {
                    mismatch += 1;
                    if verbose && mismatch < 4 {
                        eprintln!("{cat:?} case {k}: ours {} ruckig {t}\n{inp:?}", tr.duration());
                    }
                }
            }
            (Ok(tr), None) => {
                let w = check(&inp, &tr);
                assert!(within_contract(&w), "{cat:?} case {k}: {w:?}\n{inp:?}");
                ruckig_failed += 1;
            }
            (Err(e), Some(t)) => {
                ours_failed += 1;
                if verbose && ours_failed < 4 {
                    eprintln!("{cat:?} case {k}: ours failed ({e}), ruckig {t}\n{inp:?}");
                }
            }
            (Err(_), None) => ruckig_failed += 1,
        }
    }
    (agree, mismatch, ours_failed, ruckig_failed)
}

#[test]
#[ignore]
fn survey() {
    let only = std::env::var("OTG_CAT").ok();
    for cat in ALL {
        if only.as_ref().is_some_and(|o| *o != format!("{cat:?}")) {
            continue;
        }
        let s1 = compare::<1>(cat, 2000, 1, true);
        let s3 = compare::<3>(cat, 1000, 2, true);
        eprintln!("{cat:?}: 1 DOF (agree, mismatch, ours failed, ruckig failed) {s1:?}; 3 DOF {s3:?}");
    }
}
