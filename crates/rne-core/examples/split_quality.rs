//! Quality of the heuristic kind split (used beyond `HierarchicalRne::exact_split_limit`)
//! against the exact optimum (Algorithm 1 step 1 by full enumeration, Algorithm 2).
//!
//! For `TEAMS` random kinds of 2 to 20 robots (7 needs, uniform weights, a random first-side
//! size `1..n-1`), in three regimes that take turns (the paper's needs ratios with random HP
//! and energy levels; uniform random needs; needs from `{0, 1, 5, 10}` with many ties), it
//! prints the ratio of the heuristic's between-RNE `J` to the exact optimum: mean, worst, and
//! how often it is optimal. Deterministic.
//!
//! ```sh
//! cargo run --release -p rne-core --example split_quality -- [TEAMS]
//! ```

use std::time::Instant;

use rne_core::grouping::HierarchicalRne;
use rne_core::{NeedsVector, TrustModel, Weights};

#[path = "../benches/support/large_team.rs"]
mod large_team;

/// A deterministic random stream (SplitMix64).
struct Rng(u64);

impl Rng {
    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        large_team::unit(&mut self.0)
    }
    /// Uniform in `0..n`.
    fn below(&mut self, n: usize) -> usize {
        ((self.unit() * n as f64) as usize).min(n - 1)
    }
}

/// One robot's needs in regime `regime` (0 paper-like, 1 uniform, 2 tied values).
fn needs(rng: &mut Rng, regime: usize, kind: usize) -> Vec<f64> {
    match regime {
        0 => {
            let hp = (0.9 + 0.1 * (rng.unit() - 0.5) * 3.4).clamp(0.05, 1.0);
            let energy = (0.8 + 0.2 * (rng.unit() - 0.5) * 3.4).clamp(0.05, 1.0);
            large_team::paper_needs(kind, hp, energy)
        }
        1 => (0..7).map(|_| 100.0 * rng.unit()).collect(),
        _ => (0..7)
            .map(|_| [0.0, 1.0, 5.0, 10.0][rng.below(4)])
            .collect(),
    }
}

fn main() {
    let teams: usize = std::env::args()
        .nth(1)
        .map_or(1000, |a| a.parse().expect("TEAMS must be a number"));
    let model = TrustModel::with_weights(Weights::uniform(7).expect("weights"));
    let method = HierarchicalRne::new(model);
    let mut rng = Rng(2021);
    let (mut sum, mut worst, mut optimal, mut counted) = (0.0, f64::INFINITY, 0usize, 0usize);
    let (mut t_exact, mut t_heur) = (0.0, 0.0);
    let mut worst_case = String::new();
    for team in 0..teams {
        let regime = team % 3;
        let n = 2 + rng.below(19);
        let m = 1 + rng.below(n - 1);
        let kind = rng.below(3);
        let members: Vec<NeedsVector> = (0..n)
            .map(|_| NeedsVector::new(needs(&mut rng, regime, kind)).expect("needs"))
            .collect();
        let refs: Vec<&NeedsVector> = members.iter().collect();
        let t0 = Instant::now();
        let Ok((_, exact)) = method.best_split_exact(&refs, m) else {
            continue; // without smoothing an all-zero subgroup has no distribution
        };
        let t1 = Instant::now();
        let (_, heur) = method.best_split_heuristic(&refs, m).expect("heuristic");
        t_exact += (t1 - t0).as_secs_f64();
        t_heur += t1.elapsed().as_secs_f64();
        let ratio = if exact > 0.0 { heur / exact } else { 1.0 };
        counted += 1;
        sum += ratio;
        if ratio >= 1.0 - 1e-9 {
            optimal += 1;
        }
        if ratio < worst {
            worst = ratio;
            worst_case = format!("team {team}: regime {regime}, n = {n}, m = {m}");
        }
    }
    println!(
        "kinds compared: {counted} (of {teams}; the rest had an all-zero subgroup and no smoothing)"
    );
    println!(
        "heuristic J / exact optimum: mean {:.6}, worst {worst:.6} ({worst_case})",
        sum / counted as f64
    );
    println!("optimal (ratio >= 1 - 1e-9): {optimal} / {counted}");
    println!("time: exact {t_exact:.2} s, heuristic {t_heur:.3} s in total");
}
