//! Loader and data-plumbing benchmarks: limits files (trajkit JSON/YAML, MoveIt, URDF), the
//! URDF dynamics model, waypoints and sample tables (CSV/JSON, both directions), the limit
//! checker and the SVG plot. Run: `cargo bench -p trajkit --bench loaders`.
//!
//! Inputs: the UR5e of `examples/robots/ur5e/` (URDF, MoveIt `joint_limits.yaml`), a trajkit
//! limits file for the Panda's 7 joints, 1000 waypoints and a 1000-sample table of 7 joints
//! (positions to jerks) from a seeded sine.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use trajkit::dynamics::SerialChain;
use trajkit::io::Waypoints;
use trajkit::limits::load;
use trajkit::InverseDynamics;
use trajkit::{Limits, SampleTable};

const UR5E_URDF: &str = include_str!("../../../examples/robots/ur5e/ur5e.urdf");
const UR5E_MOVEIT: &str = include_str!("../../../examples/robots/ur5e/joint_limits.yaml");

/// The Panda preset written as a trajkit limits file (YAML; JSON is the same text in JSON).
fn panda_limits_yaml() -> (String, String) {
    let p = Limits::preset("panda").unwrap();
    let mut y = String::from("joints:\n");
    let mut j = Vec::new();
    for jl in p.joints() {
        y.push_str(&format!(
            "  - name: {}\n    position: [{}, {}]\n    velocity: {}\n    acceleration: {}\n    jerk: {}\n    effort: {}\n",
            jl.name, jl.position_min, jl.position_max, jl.velocity, jl.acceleration, jl.jerk,
            jl.effort.unwrap()
        ));
        j.push(format!(
            "{{\"name\": \"{}\", \"position\": [{}, {}], \"velocity\": {}, \"acceleration\": {}, \"jerk\": {}, \"effort\": {}}}",
            jl.name, jl.position_min, jl.position_max, jl.velocity, jl.acceleration, jl.jerk,
            jl.effort.unwrap()
        ));
    }
    (y, format!("{{\"joints\": [{}]}}", j.join(", ")))
}

/// 1000 samples of 7 joints, positions to jerks of q_j = sin(t + j).
fn table() -> SampleTable {
    let (n, dof) = (1000, 7);
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 1e-3).collect();
    let mut data: [Option<Vec<f64>>; 4] = Default::default();
    for (k, d) in data.iter_mut().enumerate() {
        let mut v = Vec::with_capacity(n * dof);
        for &ti in &t {
            for j in 0..dof {
                let x = ti + j as f64;
                v.push(match k {
                    0 => x.sin(),
                    1 => x.cos(),
                    2 => -x.sin(),
                    _ => -x.cos(),
                });
            }
        }
        *d = Some(v);
    }
    SampleTable::new(dof, t, data).unwrap()
}

fn limits_files(c: &mut Criterion) {
    let (yaml, json) = panda_limits_yaml();
    let mut g = c.benchmark_group("limits_load");
    g.bench_function("trajkit_json_panda", |b| {
        b.iter(|| load::from_json_str(black_box(&json), "l.json").unwrap())
    });
    g.bench_function("trajkit_yaml_panda", |b| {
        b.iter(|| load::from_yaml_str(black_box(&yaml), "l.yaml").unwrap())
    });
    g.bench_function("moveit_ur5e", |b| {
        b.iter(|| {
            load::moveit_joint_limits_from_str(black_box(UR5E_MOVEIT), "jl.yaml", None).unwrap()
        })
    });
    g.bench_function("urdf_ur5e", |b| {
        b.iter(|| load::from_urdf_str(black_box(UR5E_URDF), "ur5e.urdf").unwrap())
    });
    g.finish();
}

fn dynamics(c: &mut Criterion) {
    let mut g = c.benchmark_group("dynamics");
    g.bench_function("serial_chain_from_urdf_ur5e", |b| {
        b.iter(|| SerialChain::from_urdf_str(black_box(UR5E_URDF), "ur5e.urdf").unwrap())
    });
    let chain = SerialChain::from_urdf_str(UR5E_URDF, "ur5e.urdf").unwrap();
    let (q, qd, qdd) = ([0.1, -1.2, 1.4, -0.3, 0.8, 0.2], [0.5; 6], [-1.0; 6]);
    let mut tau = [0.0; 6];
    g.bench_function("torque_ur5e", |b| {
        b.iter(|| {
            chain.torque(black_box(&q), black_box(&qd), black_box(&qdd), &mut tau);
            black_box(&tau);
        })
    });
    g.finish();
}

fn tables(c: &mut Criterion) {
    let t = table();
    let csv = trajkit::io::table_to_csv(&t);
    let json = trajkit::io::table_to_json(&t);
    let wp_csv = {
        let mut s = String::from("a,b,c,d,e,f,g\n");
        for i in 0..1000 {
            let row: Vec<String> = (0..7)
                .map(|j| format!("{}", (i as f64 * 0.01 + j as f64).sin()))
                .collect();
            s.push_str(&row.join(","));
            s.push('\n');
        }
        s
    };
    let wp = Waypoints::from_csv(&wp_csv, "w.csv").unwrap();
    let wp_json = {
        let rows: Vec<String> = (0..wp.len())
            .map(|i| {
                format!(
                    "[{}]",
                    wp.point(i)
                        .iter()
                        .map(|x| x.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })
            .collect();
        format!(
            "{{\"joint_names\": [\"a\",\"b\",\"c\",\"d\",\"e\",\"f\",\"g\"], \"waypoints\": [{}]}}",
            rows.join(", ")
        )
    };
    let mut g = c.benchmark_group("io");
    g.sample_size(30);
    g.bench_function("waypoints_csv_1000x7", |b| {
        b.iter(|| Waypoints::from_csv(black_box(&wp_csv), "w.csv").unwrap())
    });
    g.bench_function("waypoints_json_1000x7", |b| {
        b.iter(|| Waypoints::from_json(black_box(&wp_json), "w.json").unwrap())
    });
    g.bench_function("table_to_csv_1000x7x4", |b| {
        b.iter(|| trajkit::io::table_to_csv(black_box(&t)))
    });
    g.bench_function("table_from_csv_1000x7x4", |b| {
        b.iter(|| trajkit::io::table_from_csv(black_box(&csv), "t.csv").unwrap())
    });
    g.bench_function("table_to_json_1000x7x4", |b| {
        b.iter(|| trajkit::io::table_to_json(black_box(&t)))
    });
    g.bench_function("table_from_json_1000x7x4", |b| {
        b.iter(|| trajkit::io::table_from_json(black_box(&json), "t.json").unwrap())
    });
    let limits = Limits::uniform(7, 2.0, 10.0, 100.0).unwrap();
    g.bench_function("check_samples_1000x7", |b| {
        b.iter(|| trajkit::check::check_samples(black_box(&t), &limits).unwrap())
    });
    g.bench_function("plot_svg_1000x7", |b| {
        b.iter(|| trajkit::plot::svg(black_box(&t), Some(&limits), &Default::default()).unwrap())
    });
    g.finish();
}

criterion_group!(benches, limits_files, dynamics, tables);
criterion_main!(benches);
