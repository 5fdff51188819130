//! Scoring the splits of one kind by their between-RNE `J(A, B) = T(A||B) + T(B||A)`
//! (Eq. 17): exactly, as [`HierarchicalRne::between_rne`] does, for the enumeration; and from
//! running column sums in `O(j)` per candidate for the heuristic.
//!
//! [`HierarchicalRne::between_rne`]: crate::grouping::HierarchicalRne::between_rne

use nalgebra::DVector;

use crate::distribution::{Alignment, Smoothing, group_distribution_from_sums, needs_scale};
use crate::error::{Result, RneError};
use crate::needs::NeedsVector;
use crate::rne::TrustModel;

/// The members of one kind (`n` needs vectors of length `j`) and a trust model, ready to
/// score splits of the members into two subgroups.
pub(crate) struct SplitScorer<'a> {
    model: &'a TrustModel,
    members: &'a [&'a NeedsVector],
    j: usize,
    /// `n x j`, row-major: member `r`'s weighted needs `n_rk w_k`, or with no or relative
    /// smoothing, when their total is not a normal `f64`, `(n_rk / max n) (w_k / max w)`
    /// (as the distributions scale them: the same shares, computable near `f64::MAX`).
    weighted: Vec<f64>,
    /// Relative smoothing epsilon `e` (0 unless `Smoothing::Relative`).
    eps_rel: f64,
    /// Absolute smoothing epsilon (0 unless `Smoothing::Absolute`).
    eps_abs: f64,
    sorted: bool,
    ln_base: f64,
}

/// Work space of [`SplitScorer::score`] and its gradients: six vectors of length `j`.
pub(crate) struct Scratch {
    p: Vec<f64>,
    q: Vec<f64>,
    ps: Vec<f64>,
    qs: Vec<f64>,
    sa: Vec<f64>,
    sb: Vec<f64>,
    /// Swaps scored so far ([`SplitScorer::swap_score`] calls).
    swaps_scored: u64,
}

impl Scratch {
    /// How many swaps [`SplitScorer::swap_score`] has scored with this work space.
    pub(crate) fn swaps_scored(&self) -> u64 {
        self.swaps_scored
    }
}

impl<'a> SplitScorer<'a> {
    /// # Errors
    /// [`RneError::LengthMismatch`] if the members' needs vectors differ in length, or differ
    /// from the model's weights (the errors [`HierarchicalRne::between_rne`] would give).
    ///
    /// [`HierarchicalRne::between_rne`]: crate::grouping::HierarchicalRne::between_rne
    pub(crate) fn new(model: &'a TrustModel, members: &'a [&'a NeedsVector]) -> Result<Self> {
        let w = model.weights().as_slice();
        let j = members.first().map_or(w.len(), |m| m.len());
        if let Some(bad) = members.iter().find(|m| m.len() != j) {
            return Err(RneError::LengthMismatch {
                what: "group member needs vector",
                expected: j,
                actual: bad.len(),
            });
        }
        if j != w.len() {
            return Err(RneError::LengthMismatch {
                what: "group needs matrix",
                expected: w.len(),
                actual: j,
            });
        }
        let opts = model.options();
        let weighted = weighted_rows(members, w, opts.smoothing);
        let (eps_rel, eps_abs) = match opts.smoothing {
            Smoothing::None => (0.0, 0.0),
            Smoothing::Relative(e) => (e, 0.0),
            Smoothing::Absolute(e) => (0.0, e),
        };
        Ok(Self {
            model,
            members,
            j,
            weighted,
            eps_rel,
            eps_abs,
            sorted: opts.alignment == Alignment::Sorted,
            ln_base: opts.log_base.value().ln(),
        })
    }

    /// Number of members `n`.
    pub(crate) fn n(&self) -> usize {
        self.members.len()
    }

    /// Number of needs categories `j`.
    pub(crate) fn j(&self) -> usize {
        self.j
    }

    /// A fresh work space.
    pub(crate) fn scratch(&self) -> Scratch {
        let v = || vec![0.0; self.j];
        Scratch {
            p: v(),
            q: v(),
            ps: v(),
            qs: v(),
            sa: v(),
            sb: v(),
            swaps_scored: 0,
        }
    }

    /// Member `r`'s weighted needs (length `j`).
    pub(crate) fn row(&self, r: usize) -> &[f64] {
        &self.weighted[r * self.j..(r + 1) * self.j]
    }

    /// The exact `J` of the split `(first, second)` (member indices, each in the order the
    /// group's needs matrix would have), bit-identical to
    /// [`HierarchicalRne::between_rne`](crate::grouping::HierarchicalRne::between_rne) on the
    /// same members; 0 if a side is empty. `O(n j)`.
    ///
    /// # Errors
    /// As [`TrustModel::group_group`] (e.g. [`RneError::ZeroTotal`]).
    pub(crate) fn exact(&self, first: &[usize], second: &[usize]) -> Result<f64> {
        if first.is_empty() || second.is_empty() {
            return Ok(0.0);
        }
        let opts = self.model.options().distribution();
        let da = group_distribution_from_sums(self.raw_sums(first), self.model.weights(), &opts)?;
        let db = group_distribution_from_sums(self.raw_sums(second), self.model.weights(), &opts)?;
        Ok(self.model.rne(&da, &db)? + self.model.rne(&db, &da)?)
    }

    /// Column sums of the raw needs of `idx`, accumulated from `0.0` in the order of `idx`
    /// (as `nalgebra` sums a needs matrix's columns).
    fn raw_sums(&self, idx: &[usize]) -> DVector<f64> {
        let mut sums = DVector::zeros(self.j);
        for &r in idx {
            for (s, n) in sums.iter_mut().zip(self.members[r].as_slice()) {
                *s += n;
            }
        }
        sums
    }

    /// Weighted column sums `(s_A, s_B)` of the two sides of a split given as membership
    /// flags (`in_first[r]`). `O(n j)`.
    pub(crate) fn sums_of(&self, in_first: &[bool]) -> (Vec<f64>, Vec<f64>) {
        let (mut sa, mut sb) = (vec![0.0; self.j], vec![0.0; self.j]);
        for (r, &first) in in_first.iter().enumerate() {
            let side = if first { &mut sa } else { &mut sb };
            for (s, v) in side.iter_mut().zip(self.row(r)) {
                *s += v;
            }
        }
        (sa, sb)
    }

    /// The smoothed distribution of weighted sums `s` into `out` (unsorted); its normaliser
    /// `Z` (infinite for the uniform distribution relative smoothing gives zero sums), or
    /// `None` if the total is not positive (the distribution is undefined).
    fn distribution(&self, s: &[f64], out: &mut [f64]) -> Option<f64> {
        let total: f64 = s.iter().sum();
        if total == 0.0 && self.eps_rel > 0.0 {
            // Uniform by convention (`Smoothing::Relative`); an infinite normaliser gives
            // this side no gradient, as the convention has none.
            out.fill(1.0 / self.j as f64);
            return Some(f64::INFINITY);
        }
        let eps = self.eps_abs + self.eps_rel * total;
        let z = total + eps * self.j as f64;
        if !(z > 0.0 && z.is_finite()) {
            return None;
        }
        for (o, v) in out.iter_mut().zip(s) {
            *o = (v + eps) / z;
        }
        Some(z)
    }

    /// `J` of the sides with weighted sums `sa` and `sb` (both non-empty), in the model's log
    /// base; `-inf` if a side's distribution is undefined (all needs zero, no smoothing to
    /// save it), `+inf` possible without smoothing. Leaves the unsorted distributions in
    /// `w.p` and `w.q`. `O(j)` (`O(j log j)` with sorted alignment).
    pub(crate) fn score(&self, sa: &[f64], sb: &[f64], w: &mut Scratch) -> f64 {
        if self.distribution(sa, &mut w.p).is_none() || self.distribution(sb, &mut w.q).is_none() {
            return f64::NEG_INFINITY;
        }
        let (p, q) = if self.sorted {
            w.ps.copy_from_slice(&w.p);
            w.qs.copy_from_slice(&w.q);
            w.ps.sort_by(f64::total_cmp);
            w.qs.sort_by(f64::total_cmp);
            (&w.ps, &w.qs)
        } else {
            (&w.p, &w.q)
        };
        (kl(p, q).max(0.0) + kl(q, p).max(0.0)) / self.ln_base
    }

    /// `J` after swapping member `a` (first side) with member `b` (second side), from the
    /// current sums `sa`, `sb`. `O(j)`.
    pub(crate) fn swap_score(
        &self,
        sa: &[f64],
        sb: &[f64],
        a: usize,
        b: usize,
        w: &mut Scratch,
    ) -> f64 {
        w.swaps_scored += 1;
        let (va, vb) = (self.row(a), self.row(b));
        let mut na = std::mem::take(&mut w.sa);
        let mut nb = std::mem::take(&mut w.sb);
        for k in 0..self.j {
            na[k] = sa[k] - va[k] + vb[k];
            nb[k] = sb[k] + va[k] - vb[k];
        }
        let score = self.score(&na, &nb, w);
        (w.sa, w.sb) = (na, nb);
        score
    }

    /// First-order gain of moving each member from the first side to the second:
    /// `out[r] = <dJ/ds_B - dJ/ds_A, v_r>` at the sums `(sa, sb)`, where `v_r` is member `r`'s
    /// weighted needs. A swap of `a` (first side) and `b` (second) gains about
    /// `out[a] - out[b]`. Components whose derivative is not finite (a zero share without
    /// smoothing) count as 0. `O(n j)`.
    pub(crate) fn move_gains(&self, sa: &[f64], sb: &[f64], w: &mut Scratch, out: &mut [f64]) {
        let (Some(za), Some(zb)) = (
            self.distribution(sa, &mut w.p),
            self.distribution(sb, &mut w.q),
        ) else {
            out.fill(0.0);
            return;
        };
        // dJ/dp and dJ/dq per category (in w.ps, w.qs), then through the normalisation.
        self.share_gradients(w);
        let grad_a = self.sum_gradient(&w.ps, &w.p, za);
        let grad_b = self.sum_gradient(&w.qs, &w.q, zb);
        let diff: Vec<f64> = grad_b.iter().zip(&grad_a).map(|(b, a)| b - a).collect();
        for (r, o) in out.iter_mut().enumerate() {
            *o = self.row(r).iter().zip(&diff).map(|(v, d)| v * d).sum();
        }
    }

    /// `dJ/dp_k` into `w.ps` and `dJ/dq_k` into `w.qs` for the distributions in `w.p`, `w.q`
    /// (pairing the `i`-th smallest shares with sorted alignment).
    fn share_gradients(&self, w: &mut Scratch) {
        let d = |x: f64, y: f64| {
            let g = (x / y).ln() + 1.0 - y / x;
            if g.is_finite() { g } else { 0.0 }
        };
        if self.sorted {
            let argsort = |v: &[f64]| {
                let mut idx: Vec<usize> = (0..v.len()).collect();
                idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
                idx
            };
            let (op, oq) = (argsort(&w.p), argsort(&w.q));
            for i in 0..self.j {
                let (x, y) = (w.p[op[i]], w.q[oq[i]]);
                w.ps[op[i]] = d(x, y);
                w.qs[oq[i]] = d(y, x);
            }
        } else {
            for k in 0..self.j {
                w.ps[k] = d(w.p[k], w.q[k]);
                w.qs[k] = d(w.q[k], w.p[k]);
            }
        }
    }

    /// `dJ/ds_i = (G_i + c sum_k G_k - (1 + j c) <G, p>) / Z` for share gradient `G`,
    /// distribution `p`, normaliser `Z` and relative smoothing `c`.
    fn sum_gradient(&self, g: &[f64], p: &[f64], z: f64) -> Vec<f64> {
        let c = self.eps_rel;
        let sum_g: f64 = g.iter().sum();
        let dot: f64 = g.iter().zip(p).map(|(g, p)| g * p).sum();
        let shift = c * sum_g - (1.0 + self.j as f64 * c) * dot;
        g.iter().map(|gi| (gi + shift) / z).collect()
    }
}

/// The members' weighted needs, row-major, scaled by [`needs_scale`]'s rule (as the
/// distributions are) applied to the whole kind, whose total bounds every side's sums.
fn weighted_rows(members: &[&NeedsVector], w: &[f64], smoothing: Smoothing) -> Vec<f64> {
    let plain: Vec<f64> = members
        .iter()
        .flat_map(|m| m.as_slice().iter().zip(w).map(|(n, w)| n * w))
        .collect();
    let n_max = members
        .iter()
        .flat_map(|m| m.as_slice())
        .fold(0.0_f64, |a, &b| a.max(b));
    let w_max = w.iter().fold(0.0_f64, |a, &b| a.max(b));
    match needs_scale(plain.iter().sum(), n_max, w_max, smoothing) {
        None => plain,
        Some((n_max, w_max)) => members
            .iter()
            .flat_map(|m| {
                m.as_slice()
                    .iter()
                    .zip(w)
                    .map(|(n, w)| (n / n_max) * (w / w_max))
            })
            .collect(),
    }
}

/// `sum_k p_k ln(p_k / q_k)` with `0 ln(0/q) = 0` and `p ln(p/0) = +inf`.
fn kl(p: &[f64], q: &[f64]) -> f64 {
    p.iter()
        .zip(q)
        .map(|(&pk, &qk)| match (pk, qk) {
            (0.0, _) => 0.0,
            (_, 0.0) => f64::INFINITY,
            _ => pk * (pk.ln() - qk.ln()),
        })
        .sum()
}
