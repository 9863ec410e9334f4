//! Loaders for limits files (trajkit JSON/YAML, MoveIt joint_limits.yaml) and URDF.
