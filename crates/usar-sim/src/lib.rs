//! The USAR mission world of Yang & Parasuraman (SMC 2021), stepped with Rapier 2D.

pub mod mission;
pub mod scenario;
pub mod world;
