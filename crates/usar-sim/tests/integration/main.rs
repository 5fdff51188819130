//! The integration tests of `usar-sim`, one test binary (each file a module): scenario files
//! loaded and refused, and the world's physics, paths and determinism, with the helpers they
//! share in `common`.

mod common;
mod proptest_floats;
mod scenario_limits;
mod scenario_load;
mod world_control_period;
mod world_corridor;
mod world_debris;
mod world_determinism;
mod world_shared_paths;
mod world_step_beside;
