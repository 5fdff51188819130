//! Rule 1's search for the pairs about to collide, robot by robot, in parallel for a large
//! team: each robot's pairs with its neighbours of higher id go to its chunk's list, and the
//! resolver unites them in robot order (the lists in chunk order are the pairs of a serial
//! scan, in its order).
//!
//! Not in the paper.

use rayon::prelude::*;

use super::per_robot::CHUNK_ROBOTS;

/// Fills `out` with one list per chunk of [`CHUNK_ROBOTS`] robots (of `n`): the pairs `(i,
/// j)` for which `pairs_of(i, push)` calls `push(j)`, robot `i` ascending, `j` in the order it
/// was pushed; on a rayon pool when `parallel`. `pairs_of` only reads, so the lists are the
/// same on any number of threads. `out` keeps its lists' memory between calls.
pub(super) fn pairs_by_chunk(
    n: usize,
    parallel: bool,
    out: &mut Vec<Vec<(usize, usize)>>,
    pairs_of: impl Fn(usize, &mut dyn FnMut(usize)) + Sync,
) {
    let chunks = n.div_ceil(CHUNK_ROBOTS);
    if out.len() < chunks {
        out.resize_with(chunks, Vec::new);
    }
    let fill = |(c, list): (usize, &mut Vec<(usize, usize)>)| {
        list.clear();
        for i in c * CHUNK_ROBOTS..((c + 1) * CHUNK_ROBOTS).min(n) {
            pairs_of(i, &mut |j| list.push((i, j)));
        }
    };
    let lists = &mut out[..chunks];
    if parallel {
        lists
            .par_iter_mut()
            .enumerate()
            .with_max_len(1)
            .for_each(fill);
    } else {
        lists.iter_mut().enumerate().for_each(fill);
    }
    out.truncate(chunks);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Serial and parallel give the same lists, in robot order, over several chunks.
    #[test]
    fn the_same_pairs_in_robot_order_either_way() {
        let n = 3 * CHUNK_ROBOTS + 7;
        let pairs_of = |i: usize, push: &mut dyn FnMut(usize)| {
            for j in (i + 1..n)
                .filter(|j| (i * 7 + j * 3).is_multiple_of(11))
                .take(3)
            {
                push(j);
            }
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        pairs_by_chunk(n, false, &mut a, pairs_of);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| pairs_by_chunk(n, true, &mut b, pairs_of));
        assert_eq!(a, b);
        let flat: Vec<_> = a.iter().flatten().copied().collect();
        assert!(flat.windows(2).all(|w| w[0].0 <= w[1].0), "robot order");
        assert!(flat.len() > n / 4, "pairs found: {}", flat.len());
    }
}
