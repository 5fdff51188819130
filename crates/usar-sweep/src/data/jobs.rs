//! The jobs of a sweep: one per (grid cell, method, trial), and their canonical order.

/// One job of the sweep: indices of its cell and method, and its trial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct JobId {
    /// Grid cell index.
    pub cell: usize,
    /// Index of the method in the sweep's method order.
    pub method: usize,
    /// Trial index.
    pub trial: u32,
}

/// Every job of a sweep of `cells` x `methods` x `trials`, in the canonical order jobs are
/// started in: trial-major, then cell, then method, so a partial sweep has every cell and
/// method on its first trials. [`crate::shard::Shard::jobs`] splits this list into shards.
pub fn job_list(cells: usize, methods: usize, trials: u32) -> Vec<JobId> {
    let mut jobs = Vec::with_capacity(cells * methods * trials as usize);
    for trial in 0..trials {
        for cell in 0..cells {
            for method in 0..methods {
                jobs.push(JobId {
                    cell,
                    method,
                    trial,
                });
            }
        }
    }
    jobs
}
