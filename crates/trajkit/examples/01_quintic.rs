//! 01 — A quintic (minimum-jerk) move of one joint, and the seed's peak-coefficient table.
//!
//! Run: `cargo run -p trajkit --example 01_quintic`

use trajkit::poly::{peak_coefficients, Degree, PolyMove};
use trajkit::{Order, Trajectory};

fn main() -> Result<(), trajkit::Error> {
    // q: 0 -> 1 rad in 2 s, at rest at both ends.
    let mv = PolyMove::rest_to_rest(Degree::Quintic, &[0.0], &[1.0], 2.0)?;
    let mut buf = [0.0];
    println!("   t      q        q̇        q̈        q⃛");
    for i in 0..=8 {
        let t = 0.25 * i as f64;
        let mut row = [0.0; 4];
        for o in Order::ALL {
            mv.eval(t, o, &mut buf);
            row[o.index()] = buf[0];
        }
        println!(
            "{t:5.2} {:8.4} {:8.4} {:8.4} {:9.4}",
            row[0], row[1], row[2], row[3]
        );
    }
    // Peak coefficients: peak |q̇|·T/Δq, |q̈|·T²/Δq, |q⃛|·T³/Δq, computed from the polynomials.
    for d in Degree::ALL {
        let c = peak_coefficients(d);
        println!("{:8} {:.4} / {:.4} / {:.4}", d.name(), c[0], c[1], c[2]);
    }
    Ok(())
}
