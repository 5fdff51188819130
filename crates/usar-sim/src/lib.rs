//! The USAR mission world of Yang & Parasuraman (SMC 2021), stepped with Rapier 2D.
//!
//! Three layers, each using only the ones before it:
//! - [`scenario`]: a mission as data. [`scenario::load`] a RON file or [`scenario::from_str`]
//!   a text, build one in code with [`scenario::ScenarioSpec::builder`], or change a loaded
//!   one with [`scenario::Scenario::edit`]; each validates once into a read-only
//!   [`scenario::Scenario`], so a trial never gets an invalid one (`docs/scenario-format.md`).
//! - [`world`]: the bodies, debris, paths and collisions of one trial, stepped with Rapier.
//! - [`mission`]: needs, rounds, grouping by any `rne_core::grouping::GroupingMethod`,
//!   rescuing and metrics. [`mission::Simulation::builder`] runs one trial, deterministic
//!   from the scenario, the method and the trial index.
//!
//! ```
//! use usar_sim::mission::Simulation;
//! use usar_sim::scenario;
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
//! let paper = scenario::load(path)?;
//! let quick = paper.edit(|spec| spec.sim.seed = 7)?;
//! let result = Simulation::builder(&quick)
//!     .method_named("rne")
//!     .trial(0)
//!     .duration_s(20.0)
//!     .build()?
//!     .run_to_end()?;
//! assert_eq!(result.rescued.len(), 2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod mission;
pub mod scenario;
pub mod world;
