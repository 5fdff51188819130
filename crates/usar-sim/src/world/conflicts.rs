//! The conflict graph of one resolver step: which robots are about to collide with which
//! (rule 1 of [`super::resolver`]), kept as adjacency lists for the `Yield` hold rule
//! ([`crate::scenario::HoldRule::Yield`]).

/// Undirected pairs collected during a step, then compressed into adjacency lists
/// (compressed sparse rows, built by a counting sort: `O(n + pairs)`, no allocation once the
/// buffers have grown).
#[derive(Debug, Clone, Default)]
pub struct ConflictGraph {
    pairs: Vec<(u32, u32)>,
    /// `adj[start[i]..start[i + 1]]` are robot `i`'s neighbours, in no particular order.
    start: Vec<u32>,
    adj: Vec<u32>,
}

impl ConflictGraph {
    /// Forgets the previous step's pairs.
    pub fn clear(&mut self) {
        self.pairs.clear();
    }

    /// Records that robots `i` and `j` (`i != j`) conflict.
    pub fn push(&mut self, i: usize, j: usize) {
        self.pairs.push((i as u32, j as u32));
    }

    /// Builds the adjacency lists of robots `0..n` from the pairs pushed since
    /// [`ConflictGraph::clear`]. A list's order depends on the push order (the resolver's
    /// neighbour candidates come in any order), so readers must not depend on it: the `Yield`
    /// rule only asks whether any neighbour qualifies.
    pub fn build(&mut self, n: usize) {
        self.start.clear();
        self.start.resize(n + 1, 0);
        for &(i, j) in &self.pairs {
            self.start[i as usize + 1] += 1;
            self.start[j as usize + 1] += 1;
        }
        for k in 0..n {
            self.start[k + 1] += self.start[k];
        }
        self.adj.resize(self.start[n] as usize, 0);
        // `start[i]` runs ahead as robot i's list fills, then is shifted back.
        for &(i, j) in &self.pairs {
            for (a, b) in [(i, j), (j, i)] {
                let slot = &mut self.start[a as usize];
                self.adj[*slot as usize] = b;
                *slot += 1;
            }
        }
        for k in (1..=n).rev() {
            self.start[k] = self.start[k - 1];
        }
        self.start[0] = 0;
    }

    /// Robot `i`'s neighbours (after [`ConflictGraph::build`]).
    pub fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        let (a, b) = (self.start[i] as usize, self.start[i + 1] as usize);
        self.adj[a..b].iter().map(|&j| j as usize)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #[test]
        fn adjacency_lists_hold_every_pair_both_ways(
            n in 1usize..30,
            raw in prop::collection::vec((0usize..30, 0usize..30), 0..80),
        ) {
            let pairs: Vec<(usize, usize)> =
                raw.into_iter().map(|(a, b)| (a % n, b % n)).filter(|(a, b)| a != b).collect();
            let mut g = ConflictGraph::default();
            g.push(0, 1.min(n - 1)); // stale pair, must be forgotten
            g.clear();
            for &(a, b) in &pairs {
                g.push(a, b);
            }
            g.build(n);
            for i in 0..n {
                let mut got: Vec<usize> = g.neighbours(i).collect();
                let mut want: Vec<usize> = pairs
                    .iter()
                    .filter_map(|&(a, b)| if a == i { Some(b) } else if b == i { Some(a) } else { None })
                    .collect();
                got.sort_unstable();
                want.sort_unstable();
                prop_assert_eq!(got, want);
            }
        }
    }
}
