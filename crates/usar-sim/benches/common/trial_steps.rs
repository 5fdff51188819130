//! Stepping a trial by blocks and comparing two trials' robots, for the benches that time the
//! same trial two ways (`stepping_thread`, and `scale`'s one-against-several threads).

use usar_sim::mission::Simulation;

/// Steps `sim` `len` times. Errors (one line): a step fails, named by its number in the trial
/// (from 1).
pub fn steps_of(sim: &mut Simulation, len: u64) -> Result<(), String> {
    for _ in 0..len {
        sim.step()
            .map_err(|e| format!("step {}: {e}", sim.progress().0 + 1))?;
    }
    Ok(())
}

/// Whether two trials' robots stand in the same places, bit for bit.
pub fn same_positions(a: &Simulation, b: &Simulation) -> bool {
    let (a, b) = (a.world().robots(), b.world().robots());
    a.iter().zip(b).all(|(x, y)| x.position == y.position)
}
