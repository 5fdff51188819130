//! The integration tests of `usar-study`, one test binary (each file a module): a calibration
//! and a multiverse run as library calls, with their hooks (progress, stop flag, own grouping
//! methods). The `usar` commands over them are tested in `experiments`.

mod calibrate;
mod multiverse;
