//! Property tests of the file readers (limits JSON/YAML/MoveIt/URDF, waypoints CSV/JSON,
//! sample tables CSV/JSON), with shrinking: a failure comes back as a minimal input.
//!
//! - No reader panics on any text, and every refusal is a typed error naming the source.
//! - Round trips: waypoints and tables written as text read back to the same numbers; a limits
//!   file written from generated values reads back to them.
//! - A bad value in a limits file is refused with an error naming its field.

use proptest::prelude::*;
use trajkit::io::{self, Waypoints};
use trajkit::limits::load;
use trajkit::{Error, Order, SampleTable};

/// Runs every reader on `text`; each must return (not panic), and a parse error must name
/// the source it was given.
fn read_all(text: &str) {
    let check = |r: Result<(), Error>, src: &str| {
        if let Err(Error::Parse { location, .. }) = r {
            assert_eq!(location.source, src);
        }
    };
    check(load::from_json_str(text, "l.json").map(|_| ()), "l.json");
    check(load::from_yaml_str(text, "l.yaml").map(|_| ()), "l.yaml");
    check(
        load::moveit_joint_limits_from_str(text, "m.yaml", None).map(|_| ()),
        "m.yaml",
    );
    check(load::from_urdf_str(text, "r.urdf").map(|_| ()), "r.urdf");
    check(Waypoints::from_csv(text, "w.csv").map(|_| ()), "w.csv");
    check(Waypoints::from_json(text, "w.json").map(|_| ()), "w.json");
    check(io::table_from_csv(text, "t.csv").map(|_| ()), "t.csv");
    check(io::table_from_json(text, "t.json").map(|_| ()), "t.json");
}

/// Text that looks like the formats: pieces of JSON, YAML, XML and CSV glued together, so
/// that the readers get past their first token more often than with random characters.
fn format_like() -> impl Strategy<Value = String> {
    let piece = prop_oneof![
        Just("{".to_string()),
        Just("}".to_string()),
        Just("[".to_string()),
        Just("]".to_string()),
        Just(",".to_string()),
        Just(":".to_string()),
        Just("\n".to_string()),
        Just("  - ".to_string()),
        Just("\"joints\"".to_string()),
        Just("joints:".to_string()),
        Just("\"waypoints\"".to_string()),
        Just("\"t\"".to_string()),
        Just("\"q\"".to_string()),
        Just("joint_limits:".to_string()),
        Just("has_velocity_limits: true".to_string()),
        Just("max_velocity:".to_string()),
        Just("\"velocity\"".to_string()),
        Just("\"position\"".to_string()),
        Just("\"preset\": \"panda\"".to_string()),
        Just("<robot name=\"r\">".to_string()),
        Just("</robot>".to_string()),
        Just("<joint name=\"j\" type=\"revolute\">".to_string()),
        Just("</joint>".to_string()),
        Just("<limit lower=\"-1\" upper=\"1\" velocity=\"2\" effort=\"3\"/>".to_string()),
        Just("t,q1,q2\n".to_string()),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("null".to_string()),
        Just("1e308".to_string()),
        any::<f64>().prop_map(|x| x.to_string()),
        "[a-z_]{1,8}",
    ];
    prop::collection::vec(piece, 0..40).prop_map(|v| v.concat())
}

/// A finite number that prints and parses back exactly (any finite f64 does).
fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..1e3f64,
        any::<f64>().prop_filter("finite", |x| x.is_finite())
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn no_reader_panics_on_any_text(text in ".{0,200}") {
        read_all(&text);
    }

    #[test]
    fn no_reader_panics_on_format_like_text(text in format_like()) {
        read_all(&text);
    }

    #[test]
    fn waypoints_csv_round_trip(
        dof in 1usize..6,
        rows in 1usize..8,
        values in prop::collection::vec(finite(), 48),
    ) {
        let points: Vec<f64> = values[..dof * rows].to_vec();
        let names: Vec<String> = (0..dof).map(|j| format!("j{j}")).collect();
        let mut text = names.join(",");
        for r in points.chunks(dof) {
            text.push('\n');
            text.push_str(&r.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(","));
        }
        let w = Waypoints::from_csv(&text, "w.csv").unwrap();
        prop_assert_eq!(w.points(), &points[..]);
        prop_assert_eq!(w.names(), &names[..]);
        let json = format!(
            "{{\"joint_names\": {:?}, \"waypoints\": [{}]}}",
            names,
            points
                .chunks(dof)
                .map(|r| format!("[{}]", r.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>().join(",")))
                .collect::<Vec<_>>()
                .join(",")
        );
        let w = Waypoints::from_json(&json, "w.json").unwrap();
        prop_assert_eq!(w.points(), &points[..]);
    }

    #[test]
    fn tables_round_trip_through_csv_and_json(
        dof in 1usize..4,
        len in 1usize..6,
        values in prop::collection::vec(finite(), 4 * 3 * 5),
        with_derivatives in any::<bool>(),
        named in any::<bool>(),
    ) {
        let t: Vec<f64> = (0..len).map(|i| i as f64 * 0.01).collect();
        let n = dof * len;
        let block = |k: usize| Some(values[k * n..(k + 1) * n].to_vec());
        let data = if with_derivatives {
            [block(0), block(1), block(2), block(3)]
        } else {
            [block(0), None, None, None]
        };
        let mut table = SampleTable::new(dof, t, data).unwrap();
        if named {
            table = table
                .with_names((0..dof).map(|j| format!("joint_{j}")).collect())
                .unwrap();
        }
        for (text, back) in [
            (io::table_to_csv(&table), io::table_from_csv(&io::table_to_csv(&table), "t.csv")),
            (io::table_to_json(&table), io::table_from_json(&io::table_to_json(&table), "t.json")),
        ] {
            let back = back.unwrap();
            prop_assert_eq!(back.times(), table.times(), "{}", text);
            for o in Order::ALL {
                prop_assert_eq!(back.matrix(o), table.matrix(o), "{:?}", o);
            }
            if named {
                prop_assert_eq!(back.names(), table.names());
            }
        }
    }

    #[test]
    fn limits_json_and_yaml_read_back_what_was_written(
        joints in prop::collection::vec((0.01..1e3f64, 0.01..1e4f64, 0.01..1e5f64, 0.0..4.0f64), 1..6),
    ) {
        let entries: Vec<String> = joints
            .iter()
            .enumerate()
            .map(|(i, (v, a, j, r))| {
                format!(
                    "{{\"name\": \"j{i}\", \"position\": [{}, {r}], \"velocity\": {v}, \
                     \"acceleration\": {a}, \"jerk\": {j}}}",
                    -r - 0.1
                )
            })
            .collect();
        let json = format!("{{\"joints\": [{}]}}", entries.join(", "));
        // JSON is YAML (flow style), so the YAML reader must agree.
        for l in [load::from_json_str(&json, "l.json").unwrap(), load::from_yaml_str(&json, "l.yaml").unwrap()] {
            prop_assert_eq!(l.dof(), joints.len());
            for (k, (v, a, j, r)) in joints.iter().enumerate() {
                let jl = l.joint(k);
                prop_assert_eq!(&jl.name, &format!("j{k}"));
                prop_assert_eq!((jl.velocity, jl.acceleration, jl.jerk), (*v, *a, *j));
                prop_assert_eq!((jl.position_min, jl.position_max), (-r - 0.1, *r));
            }
        }
    }

    #[test]
    fn a_bad_limit_value_is_refused_naming_its_field(
        dof in 1usize..5,
        bad_joint in 0usize..5,
        field in prop::sample::select(vec!["velocity", "acceleration", "jerk"]),
        bad in prop_oneof![Just("-1".to_string()), Just("0".to_string()), Just("\"fast\"".to_string()), Just("[1, 2]".to_string())],
    ) {
        let bad_joint = bad_joint % dof;
        let entries: Vec<String> = (0..dof)
            .map(|i| {
                let mut fields = vec![
                    ("velocity", "1".to_string()),
                    ("acceleration", "2".to_string()),
                    ("jerk", "3".to_string()),
                ];
                if i == bad_joint {
                    for f in &mut fields {
                        if f.0 == field {
                            f.1 = bad.clone();
                        }
                    }
                }
                let body: Vec<String> = fields.iter().map(|(k, v)| format!("\"{k}\": {v}")).collect();
                format!("{{\"name\": \"j{i}\", {}}}", body.join(", "))
            })
            .collect();
        let json = format!("{{\"joints\": [{}]}}", entries.join(",\n"));
        let want = format!("joints[{bad_joint}].{field}");
        for e in [load::from_json_str(&json, "l.json").unwrap_err(), load::from_yaml_str(&json, "l.yaml").unwrap_err()] {
            let shown = e.to_string();
            match e {
                Error::Parse { location, .. } => prop_assert_eq!(&location.field, &want, "{}", shown),
                other => prop_assert!(false, "not a parse error: {:?}", other),
            }
        }
    }

    #[test]
    fn urdf_limits_read_back_what_was_written(
        joints in prop::collection::vec((0.01..1e3f64, 0.01..1e3f64, 0.0..4.0f64), 1..6),
    ) {
        let mut text = String::from("<robot name=\"r\">\n");
        for (i, (v, e, r)) in joints.iter().enumerate() {
            text.push_str(&format!(
                "<joint name=\"j{i}\" type=\"revolute\"><limit lower=\"{}\" upper=\"{r}\" \
                 velocity=\"{v}\" effort=\"{e}\"/></joint>\n",
                -r - 0.1
            ));
        }
        text.push_str("</robot>\n");
        let l = load::from_urdf_str(&text, "r.urdf").unwrap();
        prop_assert_eq!(l.dof(), joints.len());
        for (k, (v, e, r)) in joints.iter().enumerate() {
            let jl = l.joint(k);
            prop_assert_eq!(jl.velocity, *v);
            prop_assert_eq!(jl.effort, Some(*e));
            prop_assert_eq!((jl.position_min, jl.position_max), (-r - 0.1, *r));
            prop_assert!(!l.given()[k].acceleration);
        }
    }
}
