//! Tests of the limits loaders.

use super::value::strip_position;
use super::*;
use crate::limits::presets;

fn parse_err(e: Error) -> (String, usize, String, String) {
    let shown = e.to_string();
    match e {
        Error::Parse { location, message } => {
            (location.source, location.line, location.field, message)
        }
        other => panic!("expected a parse error, got {other:?} ({shown})"),
    }
}

const YAML: &str = "\
# Panda-like limits
joints:
  - name: a1
    position: [-2.8973, 2.8973]
    velocity: 2.175
    acceleration: 15
    jerk: 7500
    min_velocity: -1.0
    effort: 87
  - name: a2
    position_min: -1.7628
    position_max: 1.7628
    velocity: 2.175
    acceleration: 7.5
    jerk: 3750
  - name: a3
    velocity: null
    acceleration: .inf
";

#[test]
fn yaml_round_trip() {
    let l = from_yaml_str(YAML, "robot.yaml").unwrap();
    assert_eq!(l.dof(), 3);
    // Written fields are given (null and .inf as "unlimited"); the others are absent.
    let g = l.given();
    assert!(g[0].velocity && g[0].position_min && g[1].position_max);
    assert!(g[2].velocity && g[2].acceleration && !g[2].jerk && !g[2].position_min);
    assert_eq!(
        l.missing(crate::limits::Needs::ALL),
        vec![(2, "jerk"), (2, "position range")]
    );
    let j = l.joint(0);
    assert_eq!(j.name, "a1");
    assert_eq!((j.position_min, j.position_max), (-2.8973, 2.8973));
    assert_eq!((j.velocity, j.acceleration, j.jerk), (2.175, 15.0, 7500.0));
    assert_eq!(j.min_velocity, Some(-1.0));
    assert_eq!(j.min_acceleration, None);
    assert_eq!(j.effort, Some(87.0));
    assert_eq!(l.joint(1).position_max, 1.7628);
    let j = l.joint(2);
    assert!(j.velocity.is_infinite() && j.acceleration.is_infinite() && j.jerk.is_infinite());
    assert!(j.position_min.is_infinite());
}

#[test]
fn json_round_trip_and_preset_override() {
    let json = serde_json::json!({
        "joints": [
            {"name": "x", "position": [-1, 1], "velocity": 1, "acceleration": 2, "jerk": 3},
            {"velocity": 4, "min_acceleration": -0.5, "acceleration": 1}
        ]
    })
    .to_string();
    let l = from_json_str(&json, "l.json").unwrap();
    assert_eq!(l.dof(), 2);
    assert_eq!(l.joint(0).jerk, 3.0);
    assert_eq!(l.joint(1).min_acceleration, Some(-0.5));
    assert_eq!(l.joint(1).name, "");

    let text = r#"{"preset": "panda", "joints": [
            {"name": "panda_joint3", "velocity": 1.5, "min_velocity": -1.0},
            {"jerk": null}
        ]}"#;
    let l = from_json_str(text, "p.json").unwrap();
    let panda = presets::panda();
    assert_eq!(l.dof(), 7);
    assert_eq!(l.joint(2).velocity, 1.5);
    assert_eq!(l.joint(2).min_velocity, Some(-1.0));
    assert_eq!(l.joint(2).acceleration, panda.joint(2).acceleration);
    assert!(l.joint(1).jerk.is_infinite()); // by index, null = unlimited
    assert_eq!(l.joint(1).velocity, panda.joint(1).velocity);
    assert_eq!(l.joint(0).velocity, panda.joint(0).velocity);
    // Only a preset.
    assert_eq!(
        from_yaml_str("preset: ur5e\n", "u.yaml").unwrap(),
        presets::ur5e().into()
    );
}

#[test]
fn errors_name_file_line_field_value() {
    let bad = YAML.replace(
        "velocity: 2.175\n    acceleration: 7.5",
        "velocity: -3\n    acceleration: 7.5",
    );
    let (src, line, field, msg) = parse_err(from_yaml_str(&bad, "robot.yaml").unwrap_err());
    assert_eq!(
        (src.as_str(), line, field.as_str()),
        ("robot.yaml", 13, "joints[1].velocity")
    );
    assert!(
        msg.contains("-3") && msg.contains("not a positive"),
        "{msg}"
    );

    let e = from_yaml_str(&bad, "robot.yaml").unwrap_err().to_string();
    assert!(
        e.starts_with("robot.yaml:13 field 'joints[1].velocity': -3"),
        "{e}"
    );

    // NaN-like strings and YAML NaN.
    let bad = YAML.replace("jerk: 3750", "jerk: \"NaN\"");
    let (_, line, field, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
    assert_eq!((line, field.as_str()), (15, "joints[1].jerk"));
    assert!(msg.contains("'NaN' is not a number"), "{msg}");
    let bad = YAML.replace("jerk: 3750", "jerk: .nan");
    let (_, _, field, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
    assert_eq!(field, "joints[1].jerk");
    assert!(msg.contains("NaN is not a number"), "{msg}");

    // Unknown field (a typo) with its line.
    let bad = YAML.replace("    jerk: 7500", "    jerck: 7500");
    let (_, line, field, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
    assert_eq!((line, field.as_str()), (7, "joints[0].jerck"));
    assert!(
        msg.starts_with("unknown field (did you mean 'jerk'?"),
        "{msg}"
    );
    let e = from_json_str(r#"{"joints": [], "jionts": 1}"#, "j.json").unwrap_err();
    let (_, line, field, msg) = parse_err(e);
    assert_eq!((line, field.as_str()), (1, "jionts"));
    assert!(
        msg.starts_with("unknown field (did you mean 'joints'?"),
        "{msg}"
    );
    // MoveIt keys too.
    let bad = MOVEIT.replace("max_velocity: 2.0", "max_velocityy: 2.0");
    let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err();
    let (_, _, field, msg) = parse_err(e);
    assert_eq!(field, "joint_limits.panda_joint1.max_velocityy");
    assert!(msg.contains("did you mean 'max_velocity'?"), "{msg}");
    // A field that resembles nothing: the known ones, no guess.
    let bad = YAML.replace("    jerk: 7500", "    colour: 7500");
    let (_, _, _, msg) = parse_err(from_yaml_str(&bad, "r.yaml").unwrap_err());
    assert!(msg.starts_with("unknown field (known: name,"), "{msg}");

    // Zero and positive-minimum limits.
    let e = from_json_str(
        "{\"joints\": [\n {\"velocity\": 1},\n {\"acceleration\": 0}\n]}",
        "z.json",
    )
    .unwrap_err();
    let (_, line, field, msg) = parse_err(e);
    assert_eq!((line, field.as_str()), (3, "joints[1].acceleration"));
    assert!(msg.starts_with("0 is not a positive number"), "{msg}");
    let e = from_json_str(r#"{"joints": [{"min_velocity": 0.5}]}"#, "z.json").unwrap_err();
    assert!(
        e.to_string().contains("0.5 is not a negative number"),
        "{e}"
    );
    // Wrong type and inverted range.
    let e = from_json_str(r#"{"joints": [{"position": [1, -1]}]}"#, "z.json").unwrap_err();
    assert!(e.to_string().contains("joints[0].position"), "{e}");
    let e = from_json_str(r#"{"joints": [{"velocity": true}]}"#, "z.json").unwrap_err();
    assert!(e.to_string().contains("true is not a number"), "{e}");
    // Syntax errors carry the line.
    let (_, line, _, _) = parse_err(from_json_str("{\n\"joints\": [\n}", "s.json").unwrap_err());
    assert_eq!(line, 3);
    let (_, line, _, _) =
        parse_err(from_yaml_str("joints:\n  - velocity: [1\n", "s.yaml").unwrap_err());
    assert!(line >= 2, "{line}");
    assert_eq!(
        strip_position("bad node at line 2 column 1, while parsing at line x"),
        "bad node, while parsing at line x"
    );
    // Empty and trailing content.
    assert!(from_json_str("{}", "e.json")
        .unwrap_err()
        .to_string()
        .contains("no joints"));
    assert!(from_json_str(r#"{"preset": "ur5e"} x"#, "e.json").is_err());
    assert!(from_yaml_str("", "e.yaml").is_err());
    assert!(from_yaml_str("- 1\n- 2\n", "e.yaml").is_err());
}

#[test]
fn preset_errors() {
    let e = from_yaml_str("preset: pandaa\n", "p.yaml").unwrap_err();
    let (src, line, field, msg) = parse_err(e);
    assert_eq!(
        (src.as_str(), line, field.as_str()),
        ("p.yaml", 1, "preset")
    );
    assert!(msg.contains("unknown robot preset 'pandaa'"), "{msg}");
    let e = from_yaml_str(
        "preset: panda\njoints:\n  - name: elbow\n    velocity: 1\n",
        "p.yaml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("joints[0].name") && e.contains("'elbow' is not a joint of preset panda"),
        "{e}"
    );
    let many = format!("preset: ur5e\njoints:\n{}", "  - velocity: 1\n".repeat(7));
    assert!(from_yaml_str(&many, "p.yaml")
        .unwrap_err()
        .to_string()
        .contains("joints[6]"));
    // Override that breaks validation after merging is reported with the file.
    let e = from_yaml_str("preset: panda\njoints:\n  - position_max: -3\n", "p.yaml")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("p.yaml") && e.contains("panda_joint1"), "{e}");
    assert!(matches!(
        from_spec("no_such_robot"),
        Err(Error::UnknownPreset { .. })
    ));
    assert_eq!(from_spec("PANDA").unwrap(), presets::panda().into());
    let e = from_spec("/nonexistent/limits.yaml").unwrap_err();
    assert!(matches!(e, Error::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/limits.yaml"));
}

const MOVEIT: &str = "\
default_velocity_scaling_factor: 0.1
default_acceleration_scaling_factor: 0.1
joint_limits:
  panda_joint1:
    has_velocity_limits: true
    max_velocity: 2.0
    has_acceleration_limits: true
    max_acceleration: 3.75
    has_jerk_limits: false
    max_jerk: 0
  panda_joint2:
    has_velocity_limits: false
    max_velocity: 0
    has_acceleration_limits: true
    max_acceleration: 1.875
    has_position_limits: true
    min_position: -1.5
    max_position: 1.5
    has_effort_limits: true
    max_effort: 80
    has_deceleration_limits: false
    max_deceleration: 0
  panda_finger_joint1:
    has_velocity_limits: true
    max_velocity: 0.2
";

#[test]
fn moveit_apply_and_standalone() {
    let panda = presets::panda();
    let l = apply_moveit_joint_limits(&panda.clone().into(), MOVEIT, "joint_limits.yaml").unwrap();
    assert_eq!(l.dof(), 7);
    assert_eq!(l.joint(0).velocity, 2.0);
    assert_eq!(l.joint(0).acceleration, 3.75);
    assert_eq!(l.joint(0).jerk, panda.joint(0).jerk); // has_jerk_limits: false
    assert_eq!(l.joint(1).velocity, panda.joint(1).velocity);
    assert_eq!(
        (l.joint(1).position_min, l.joint(1).position_max),
        (-1.5, 1.5)
    );
    assert_eq!(l.joint(1).effort, Some(80.0));
    assert_eq!(l.joint(2), panda.joint(2));

    let s = moveit_joint_limits_from_str(MOVEIT, "jl.yaml", None).unwrap();
    assert_eq!(s.dof(), 3);
    assert_eq!(s.joint(2).name, "panda_finger_joint1");
    assert!(s.joint(0).jerk.is_infinite() && s.joint(1).velocity.is_infinite());
    // has_jerk_limits: false and a missing has_velocity_limits leave them absent.
    assert!(!s.given()[0].jerk && !s.given()[1].velocity && s.given()[0].velocity);
    let order = ["panda_joint2", "panda_joint1"];
    let s = moveit_joint_limits_from_str(MOVEIT, "jl.yaml", Some(&order)).unwrap();
    assert_eq!(s.joint(0).name, "panda_joint2");
    let e = moveit_joint_limits_from_str(MOVEIT, "jl.yaml", Some(&["elbow"])).unwrap_err();
    assert!(e.to_string().contains("jl.yaml") && e.to_string().contains("'elbow'"));

    // No joint in common.
    let ur = presets::ur5e();
    let e = apply_moveit_joint_limits(&ur.into(), MOVEIT, "jl.yaml")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("jl.yaml") && e.contains("no joint"), "{e}");
}

#[test]
fn moveit_errors() {
    let bad = MOVEIT.replace("max_velocity: 2.0", "max_velocity: -2.0");
    let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err();
    let (_, line, field, msg) = parse_err(e);
    assert_eq!(field, "joint_limits.panda_joint1.max_velocity");
    assert!((4..=6).contains(&line), "{line}");
    assert!(msg.contains("-2"), "{msg}");
    let bad = MOVEIT.replace("max_acceleration: 3.75", "max_acceleration: fast");
    let (_, line, field, msg) =
        parse_err(moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err());
    assert_eq!(
        (line, field.as_str()),
        (8, "joint_limits.panda_joint1.max_acceleration")
    );
    assert!(msg.contains("'fast' is not a number"), "{msg}");
    let bad = MOVEIT.replace("has_jerk_limits", "has_jerk_limit");
    let (_, line, field, _) =
        parse_err(moveit_joint_limits_from_str(&bad, "jl.yaml", None).unwrap_err());
    assert_eq!(
        (line, field.as_str()),
        (9, "joint_limits.panda_joint1.has_jerk_limit")
    );
    let bad = MOVEIT.replace("has_jerk_limits: false", "has_jerk_limits: true");
    let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("max_jerk") && e.contains("0 is not a positive"),
        "{e}"
    );
    let bad = MOVEIT.replace("    max_velocity: 0.2\n", "");
    let e = moveit_joint_limits_from_str(&bad, "jl.yaml", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("panda_finger_joint1.max_velocity") && e.contains("missing"),
        "{e}"
    );
    let e = moveit_joint_limits_from_str("joint_limits: {}\n", "jl.yaml", None).unwrap_err();
    assert!(e.to_string().contains("no joints"));
}

fn panda_urdf() -> String {
    let p = presets::panda();
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<robot name=\"panda\">\n  <link name=\"panda_link0\"/>\n",
    );
    for (i, j) in p.joints().iter().enumerate() {
        s.push_str(&format!(
                "  <joint name=\"{}\" type=\"revolute\">\n    <parent link=\"panda_link{}\"/>\n    <child link=\"panda_link{}\"/>\n    <axis xyz=\"0 0 1\"/>\n    <limit effort=\"{}\" lower=\"{}\" upper=\"{}\" velocity=\"{}\"/>\n  </joint>\n",
                j.name, i, i + 1, j.effort.unwrap(), j.position_min, j.position_max, j.velocity
            ));
    }
    s.push_str(
            "  <joint name=\"panda_joint8\" type=\"fixed\"><parent link=\"panda_link7\"/><child link=\"panda_link8\"/></joint>\n\
             <joint name=\"panda_finger_joint1\" type=\"prismatic\">\n    <limit effort=\"20\" lower=\"0.0\" upper=\"0.04\" velocity=\"0.2\"/>\n  </joint>\n\
             <joint name=\"panda_finger_joint2\" type=\"prismatic\"><limit effort=\"20\" lower=\"0.0\" upper=\"0.04\" velocity=\"0.2\"/><mimic joint=\"panda_finger_joint1\"/></joint>\n\
             <transmission name=\"t1\"><joint name=\"panda_joint1\"/></transmission>\n</robot>\n",
        );
    s
}

#[test]
fn urdf_round_trip_and_fill() {
    let text = panda_urdf();
    let l = from_urdf_str(&text, "panda.urdf").unwrap();
    let p = presets::panda();
    assert_eq!(l.dof(), 8);
    for j in 0..7 {
        assert_eq!(l.joint(j).name, p.joint(j).name);
        assert_eq!(l.joint(j).velocity, p.joint(j).velocity);
        assert_eq!(l.joint(j).position_min, p.joint(j).position_min);
        assert_eq!(l.joint(j).position_max, p.joint(j).position_max);
        assert_eq!(l.joint(j).effort, p.joint(j).effort);
        assert!(l.joint(j).acceleration.is_infinite() && l.joint(j).jerk.is_infinite());
    }
    assert_eq!(l.joint(7).name, "panda_finger_joint1");
    assert_eq!(l.joint(7).position_max, 0.04);

    // Acceleration and jerk are absent, not unlimited; filled by name from the preset
    // the seven arm joints are complete, the finger joint still lacks them.
    assert!(!l.given()[0].acceleration && !l.given()[0].jerk && l.given()[0].velocity);
    let filled = l
        .fill_from(&p.clone().into(), crate::limits::FillBy::Name)
        .unwrap();
    let arm = filled.select(&[0, 1, 2, 3, 4, 5, 6]).unwrap();
    assert_eq!(arm.complete(crate::limits::Needs::ALL).unwrap(), p);
    let e = filled.complete(crate::limits::Needs::ALL).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("joint 8 (panda_finger_joint1) has no acceleration limit"),
        "{e}"
    );

    let c = from_urdf_str(
            "<robot name=\"r\"><joint name=\"wheel\" type=\"continuous\"><limit lower=\"-1\" upper=\"1\" effort=\"0\" velocity=\"3\"/></joint><joint name=\"spin\" type=\"continuous\"/></robot>",
            "c.urdf",
        )
        .unwrap();
    assert_eq!(c.dof(), 2);
    assert!(c.joint(0).position_min.is_infinite() && c.joint(0).effort.is_none());
    assert_eq!(c.joint(0).velocity, 3.0);
    assert!(c.joint(1).velocity.is_infinite());
    // Continuous joints: unbounded by definition; a velocity only where written.
    assert!(c.given()[0].position_min && c.given()[1].position_max);
    assert!(c.given()[0].velocity && !c.given()[1].velocity);
}

#[test]
fn urdf_errors() {
    let text = panda_urdf();
    // Joint k's (0-based) <limit> is on line 8 + 6 k.
    let bad = text.replacen("velocity=\"2.175\"", "velocity=\"-1\"", 3);
    let (src, line, field, msg) = parse_err(from_urdf_str(&bad, "panda.urdf").unwrap_err());
    assert_eq!((src.as_str(), line), ("panda.urdf", 8));
    assert_eq!(field, "joint 'panda_joint1' <limit velocity>");
    assert!(msg.contains("-1 is not a positive number"), "{msg}");
    let bad = text.replacen("velocity=\"2.175\"", "velocity=\"0\"", 1);
    let e = from_urdf_str(&bad, "panda.urdf").unwrap_err().to_string();
    assert!(
        e.starts_with(
            "panda.urdf:8 field 'joint 'panda_joint1' <limit velocity>': 0 is not a positive"
        ),
        "{e}"
    );
    let bad = text.replacen("upper=\"1.7628\"", "upper=\"NaN\"", 1);
    let (_, line, field, msg) = parse_err(from_urdf_str(&bad, "panda.urdf").unwrap_err());
    assert_eq!(
        (line, field.as_str()),
        (14, "joint 'panda_joint2' <limit upper>")
    );
    assert!(msg.contains("'NaN' is not a finite number"), "{msg}");
    let bad = text.replacen("effort=\"87\"", "effort=\"lots\"", 1);
    let e = from_urdf_str(&bad, "panda.urdf").unwrap_err().to_string();
    assert!(
        e.contains("<limit effort>") && e.contains("'lots' is not a number"),
        "{e}"
    );
    let bad = text.replacen(
        "lower=\"-2.8973\" upper=\"2.8973\"",
        "lower=\"1\" upper=\"0\"",
        1,
    );
    let e = from_urdf_str(&bad, "panda.urdf").unwrap_err().to_string();
    assert!(
        e.contains("<limit upper>") && e.contains("0 is not above lower = 1"),
        "{e}"
    );
    let e = from_urdf_str(
        "<robot name=\"r\"><joint name=\"j\" type=\"revolute\"/></robot>",
        "x.urdf",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("needs a <limit>"), "{e}");
    let e = from_urdf_str(
        "<robot name=\"r\"><joint name=\"j\" type=\"fixed\"/></robot>",
        "x.urdf",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("x.urdf") && e.contains("no movable joint"),
        "{e}"
    );
    let (_, line, _, _) =
        parse_err(from_urdf_str("<robot>\n<joint>\n</robot>", "x.urdf").unwrap_err());
    assert_eq!(line, 3);
    assert!(from_urdf_str("<sdf/>", "x.urdf").is_err());
    let e = from_urdf_str(
        "<robot><joint name=\"j\" type=\"hinge\"/></robot>",
        "x.urdf",
    )
    .unwrap_err();
    assert!(e.to_string().contains("'hinge'"));
}

#[test]
fn files_by_extension() {
    let dir = std::env::temp_dir().join(format!("trajkit-load-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let y = write("l.yaml", YAML);
    assert_eq!(from_file(&y).unwrap().dof(), 3);
    let m = write("joint_limits.yml", MOVEIT);
    assert_eq!(from_file(&m).unwrap().dof(), 3);
    let j = write("l.JSON", r#"{"preset": "iiwa14"}"#);
    assert_eq!(from_file(&j).unwrap(), presets::iiwa14().into());
    let u = write("r.urdf", &panda_urdf());
    assert_eq!(from_spec(u.to_str().unwrap()).unwrap().dof(), 8);
    let t = write("l.txt", "");
    assert!(from_file(&t).unwrap_err().to_string().contains("extension"));
    let missing = dir.join("missing.yaml");
    let e = from_file(&missing).unwrap_err();
    assert!(matches!(&e, Error::Io { path, .. } if path.contains("missing.yaml")));
    let _ = std::fs::remove_dir_all(&dir);
}
