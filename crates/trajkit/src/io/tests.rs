//! Tests of the waypoint and table readers and writers.

use super::*;
use crate::traj::Order;

#[test]
fn waypoints_csv_with_and_without_header() {
    let w = Waypoints::from_csv("a,b\n# comment\n0,1\n\n2,3\n", "w.csv").unwrap();
    assert_eq!(w.dof(), 2);
    assert_eq!(w.len(), 2);
    assert_eq!(w.names(), ["a", "b"]);
    assert_eq!(w.point(1), [2.0, 3.0]);
    let w = Waypoints::from_csv("0;1;2\n3;4;5", "w.csv").unwrap();
    assert_eq!((w.dof(), w.len()), (3, 2));
    assert_eq!(w.names()[2], "q3");
}

#[test]
fn waypoints_csv_errors_name_line_and_field() {
    let e = Waypoints::from_csv("a,b\n0,1\n2,x\n", "w.csv")
        .unwrap_err()
        .to_string();
    assert_eq!(e, "w.csv:3 field 'b': 'x' is not a number");
    let e = Waypoints::from_csv("0,1\n2,nan\n", "w.csv")
        .unwrap_err()
        .to_string();
    assert_eq!(e, "w.csv:2 field 'q2': NaN is not a finite number");
    let e = Waypoints::from_csv("0,1\n2,inf\n", "w.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("inf is not a finite number"), "{e}");
    let e = Waypoints::from_csv("0,1\n2,3,4\n", "w.csv")
        .unwrap_err()
        .to_string();
    assert_eq!(e, "w.csv:2: 3 columns, expected 2");
    assert!(Waypoints::from_csv("", "w.csv").is_err());
    assert!(Waypoints::from_csv("a,b\n", "w.csv").is_err());
}

#[cfg(feature = "serde")]
#[test]
fn waypoints_json_both_shapes() {
    let w = Waypoints::from_json("[[0,1],[2,3.5]]", "w.json").unwrap();
    assert_eq!(w.point(1), [2.0, 3.5]);
    let w = Waypoints::from_json(
        r#"{"joint_names":["x","y"],"waypoints":[[0,1],[2,3]]}"#,
        "w.json",
    )
    .unwrap();
    assert_eq!(w.names(), ["x", "y"]);
    let e = Waypoints::from_json("[[0,1],[2]]", "w.json")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("waypoints[1]") && e.contains("1 values, expected 2"),
        "{e}"
    );
    let e = Waypoints::from_json("[[0,\"a\"]]", "w.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("waypoints[0][1]"), "{e}");
    let e = Waypoints::from_json("[[0,1]\n,", "w.json")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("w.json:2"), "{e}");
}

#[test]
fn names_are_given_or_not_and_json_is_strict() {
    let w = Waypoints::from_csv("a,b\n0,1\n", "w.csv").unwrap();
    assert!(w.has_names());
    assert_eq!(w.given_names().unwrap(), ["a", "b"]);
    let w = Waypoints::from_csv("0,1\n2,3\n", "w.csv").unwrap();
    assert!(!w.has_names() && w.given_names().is_none());
    assert_eq!(w.names(), ["q1", "q2"]);
    let e = Waypoints::from_csv("a,a\n0,1\n", "w.csv").unwrap_err();
    assert!(e.to_string().contains("'a' (column 2)"), "{e}");
    #[cfg(feature = "serde")]
    {
        let e = Waypoints::from_json(r#"{"waypionts": [[0, 1]]}"#, "w.json")
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "w.json field 'waypionts': unknown field (did you mean 'waypoints'? known: joint_names, waypoints)"
        );
        let e = Waypoints::from_json(r#"{"waypoints": [[0, 1]], "units": "deg"}"#, "w.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("'units': unknown field (known:"), "{e}");
    }
}

/// Two joints, two samples, positions and velocities.
fn small_table() -> SampleTable {
    SampleTable::new(
        2,
        vec![0.0, 0.5],
        [
            Some(vec![1.0, 2.0, 3.0, 4.0]),
            Some(vec![0.1, 0.2, 0.3, 0.4]),
            None,
            None,
        ],
    )
    .unwrap()
}

#[test]
fn named_tables_round_trip() {
    let t = small_table()
        .with_names(vec!["elbow".into(), "wrist_1".into()])
        .unwrap();
    let csv = table_to_csv(&t);
    assert!(
        csv.starts_with("t,q_elbow,q_wrist_1,qd_elbow,qd_wrist_1\n"),
        "{csv}"
    );
    let back = table_from_csv(&csv, "n.csv").unwrap();
    assert_eq!(back, t);
    // Columns in any order are paired by name.
    let shuffled = "t,qd_wrist_1,q_elbow,qd_elbow,q_wrist_1\n0,0.2,1,0.1,2\n";
    let b = table_from_csv(shuffled, "s.csv").unwrap();
    assert_eq!(b.names(), ["elbow", "wrist_1"]);
    assert_eq!(b.row(Order::Velocity, 0).unwrap(), [0.1, 0.2]);
    for bad in [
        "t,q_a,qd_b\n0,1,2\n",
        "t,q_a,q_a\n0,1,2\n",
        "t,q_a,q2\n0,1,2\n",
        "t,q_a,x\n0,1,2\n",
    ] {
        assert!(table_from_csv(bad, "b.csv").is_err(), "{bad}");
    }
    // A name that cannot be a header: indices instead.
    let t = t.with_names(vec!["a,b".into(), "c".into()]).unwrap();
    assert!(table_to_csv(&t).starts_with("t,q1,q2,"));
}

#[test]
fn dedup_removes_consecutive_repeats() {
    let mut w = Waypoints::new(
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0],
        2,
        vec![],
    )
    .unwrap();
    assert_eq!(w.dedup(0.0), 2);
    assert_eq!(w.len(), 3);
}

#[test]
fn table_round_trips() {
    let t = small_table();
    let csv = table_to_csv(&t);
    assert!(csv.starts_with("t,q1,q2,qd1,qd2\n"));
    assert_eq!(table_from_csv(&csv, "x.csv").unwrap(), t);
    #[cfg(feature = "serde")]
    {
        let json = table_to_json(&t);
        let back = table_from_json(&json, "x.json").unwrap();
        assert_eq!(back.times(), t.times());
        assert_eq!(back.row(Order::Velocity, 1), t.row(Order::Velocity, 1));
    }
    // Foreign table: time + positions only, other names.
    let f = table_from_csv("time,j1,j2\n0,0,0\n0.1,0.01,0.02\n", "f.csv").unwrap();
    assert_eq!(f.dof(), 2);
    assert!(!f.has(Order::Velocity));
    let e = table_from_csv("t,q1\n0,0\n0.1,x\n", "f.csv")
        .unwrap_err()
        .to_string();
    assert_eq!(e, "f.csv:3 field 'q1': 'x' is not a number");
    let e = table_from_csv("q1,q2\n0,0\n", "f.csv")
        .unwrap_err()
        .to_string();
    assert!(e.contains("no 't'"), "{e}");
}
