//! A digest of TOPP-RA's exact output (every gridpoint and path velocity, bit for bit) on the
//! fixture problems and seeded random Panda paths, for changes that must not move a single
//! bit: run it before and after and compare the printed digests.
//!
//! `cargo test -p trajkit --test topp_digest -- --ignored --nocapture`

mod topp_common;

use topp_common::*;
use trajkit::rng::SplitMix64;
use trajkit::topp::{
    messy, Discretization, Gridpoints, JointAcceleration, JointVelocity, PhaseProfile, Toppra,
    ToppraOptions,
};
use trajkit::Limits;

/// FNV-1a over 64-bit words.
struct Digest(u64);

impl Digest {
    fn add(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x100_0000_01b3);
        }
    }
    fn profile(&mut self, p: &PhaseProfile) {
        self.add(p.gridpoints().len() as u64);
        for v in p.gridpoints().iter().chain(p.velocities()) {
            self.add(v.to_bits());
        }
    }
}

fn fixture_profile(p: &serde_json::Value, options: ToppraOptions) -> Option<PhaseProfile> {
    let vmax = floats(&p["vmax"]);
    let vmin: Vec<f64> = vmax.iter().map(|v| -v).collect();
    Toppra::new(fixture_path(p))
        .constraint(JointVelocity::new(&vmin, &vmax).ok()?)
        .ok()?
        .constraint(JointAcceleration::new(&floats(&p["amin"]), &floats(&p["amax"])).ok()?)
        .ok()?
        .options(ToppraOptions {
            start_velocity: p["sd_start"].as_f64().unwrap(),
            end_velocity: p["sd_end"].as_f64().unwrap(),
            ..options
        })
        .solve_profile()
        .ok()
}

#[test]
#[ignore = "prints a digest to compare across builds"]
fn print_digest() {
    let mut total = Digest(0xcbf2_9ce4_8422_2325);
    let grids = [
        ("auto", Gridpoints::Auto { tolerance: 1e-4 }, true, false),
        ("n300", Gridpoints::Uniform(300), true, false),
        ("n300-colloc", Gridpoints::Uniform(300), true, true),
        ("n300-raw", Gridpoints::Uniform(300), false, false),
    ];
    for p in fixtures() {
        for (g, grid, refine, colloc) in &grids {
            let options = ToppraOptions {
                gridpoints: grid.clone(),
                refine: *refine,
                discretization: if *colloc {
                    Discretization::Collocation
                } else {
                    Discretization::Interpolation
                },
                ..ToppraOptions::default()
            };
            let mut d = Digest(0xcbf2_9ce4_8422_2325);
            match fixture_profile(&p, options) {
                Some(profile) => d.profile(&profile),
                None => d.add(1),
            }
            total.add(d.0);
            println!("{:32} {g:12} {:016x}", p["name"].as_str().unwrap(), d.0);
        }
    }
    let limits = Limits::preset("panda").unwrap();
    let mo = messy::PlanOptions::default();
    let mut cases = vec![(
        "std7".to_string(),
        fixture_waypoints("standard_7wp_natural_N1000"),
    )];
    let mut rng = SplitMix64::new(2026);
    for k in 0..16 {
        let n = 2 + (k % 9);
        let mut wp = Vec::new();
        for _ in 0..n {
            for j in limits.joints() {
                wp.push(rng.uniform(j.position_min + 0.1, j.position_max - 0.1));
            }
        }
        cases.push((format!("random_{k}_{n}wp"), wp));
    }
    for (name, wp) in &cases {
        let mut d = Digest(0xcbf2_9ce4_8422_2325);
        let paths = messy::piece_paths(wp, 7, &limits, &mo).unwrap();
        match messy::time_pieces(paths, &limits, &mo, &mut |_, _| {}) {
            Ok(seq) => {
                for piece in seq.pieces() {
                    d.profile(piece.law());
                }
            }
            Err(e) => {
                for b in e.to_string().bytes() {
                    d.add(b as u64);
                }
            }
        }
        total.add(d.0);
        println!("{name:32} {:12} {:016x}", "plan", d.0);
    }
    println!("total {:016x}", total.0);
}
