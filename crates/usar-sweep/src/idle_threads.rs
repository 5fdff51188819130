//! Threads a batch of trials leaves idle at its tail: once every trial of a batch has started
//! on a pool of one thread per trial, the threads whose trials have ended have nothing left to
//! take, and the trials still running may spread their per-robot phases over them.
//!
//! Not in the paper: only a choice of speed. A trial's results are bit-identical whether its
//! per-robot phases run on one thread or several (`usar_sim::mission::Simulation::set_parallel`),
//! so lending the idle threads changes no number of a sweep.

use std::sync::atomic::{AtomicUsize, Ordering};

/// Counts a batch's trials not yet started and running, on a pool of `threads` threads; a
/// running trial asks [`IdleThreads::lend`] whether to spread its per-robot phases.
///
/// The rule: once no trial is left to start, a running trial spreads its phases when the
/// running trials are at most half the threads (one trial on two threads, two on four...), so
/// each has about two threads or more. Before then a thread waiting for a phase's chunks
/// could take a whole trial not yet started from the pool's queue and hold the phase up for
/// it, and with more trials running than that, two trials spreading their phases over the same
/// threads get less done than each on its own thread (`docs/scaling.md`, "One trial on all
/// cores"). A sweep asks it only for a team of at least
/// [`usar_sim::world::PARALLEL_MIN_ROBOTS`] robots, the floor of a trial run alone; a smaller
/// team keeps to its thread.
#[derive(Debug)]
pub struct IdleThreads {
    unstarted: AtomicUsize,
    running: AtomicUsize,
    threads: usize,
}

impl IdleThreads {
    /// A batch of `trials` trials, none started, on a pool of `threads` threads (`>= 1`; `0`
    /// counts as one).
    pub fn new(trials: usize, threads: usize) -> Self {
        Self {
            unstarted: AtomicUsize::new(trials),
            running: AtomicUsize::new(0),
            threads: threads.max(1),
        }
    }

    /// Counts one trial of the batch as taken off the queue: started, or skipped (a stopped
    /// sweep). Call once per trial, first thing; it saturates at zero.
    pub fn take(&self) {
        // An `Err` only when already zero: more calls than trials, nothing to count.
        let _ = self
            .unstarted
            .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |n| n.checked_sub(1));
    }

    /// Counts one trial as running until the returned guard drops (at its end, or as a panic
    /// unwinds).
    pub fn running(&self) -> Running<'_> {
        self.running.fetch_add(1, Ordering::SeqCst);
        Running(self)
    }

    /// Whether a running trial should spread its per-robot phases over the pool's threads
    /// now (the rule of [`IdleThreads`]). Once `true` it stays `true` for the batch: no trial
    /// starts after the last, and the running ones only end.
    pub fn lend(&self) -> bool {
        let running = self.running.load(Ordering::SeqCst);
        self.threads > 1
            && self.unstarted.load(Ordering::SeqCst) == 0
            && running > 0
            && running * 2 <= self.threads
    }
}

/// A trial counted running by [`IdleThreads::running`] until this drops.
#[derive(Debug)]
pub struct Running<'a>(&'a IdleThreads);

impl Drop for Running<'_> {
    fn drop(&mut self) {
        self.0.running.fetch_sub(1, Ordering::SeqCst);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_are_lent_only_once_every_trial_started_and_half_the_threads_are_idle() {
        let idle = IdleThreads::new(3, 2);
        idle.take();
        let a = idle.running();
        idle.take();
        let b = idle.running();
        assert!(!idle.lend(), "two running on two threads");
        drop(a);
        assert!(!idle.lend(), "a trial is still to start");
        idle.take();
        let c = idle.running();
        assert!(!idle.lend(), "two running again");
        drop(b);
        assert!(idle.lend(), "the last trial alone on two threads");
        drop(c);
        assert!(!idle.lend(), "nothing running");
    }

    #[test]
    fn four_threads_lend_to_two_trials_and_one_thread_never_lends() {
        let idle = IdleThreads::new(3, 4);
        for _ in 0..3 {
            idle.take();
        }
        let (a, _b) = (idle.running(), idle.running());
        let c = idle.running();
        assert!(!idle.lend(), "three on four threads");
        drop(c);
        assert!(idle.lend(), "two on four threads");
        drop(a);
        assert!(idle.lend());
        let one = IdleThreads::new(1, 1);
        one.take();
        let _r = one.running();
        assert!(!one.lend());
    }

    #[test]
    fn taking_more_trials_than_the_batch_holds_saturates() {
        let idle = IdleThreads::new(1, 2);
        idle.take();
        idle.take();
        let _r = idle.running();
        assert!(idle.lend());
    }
}
