//! Planner output as it comes (in progress).
