//! How far a robot's rules can reach this step: each layer's bounds (largest sensing range,
//! body radius and intended speed) and the radius the resolver's neighbour lists must cover.

use super::resolver_input::{ResolverInput, layer_slot};

/// Relative and absolute slack (dimensionless, metres) added to a robot's query radius so that
/// `f32` rounding in the exact tests never puts a pair beyond the radius it was searched in.
const REACH_SLACK: f32 = 1e-4;

/// The largest sensing range, body radius and intended speed of one layer's robots this step
/// (metres, metres, metres per second).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct LayerBounds {
    sensing: f32,
    radius: f32,
    speed: f32,
}

impl LayerBounds {
    /// The layers' bounds (ground, aerial) among `inputs`; zero for a layer with no robot.
    pub(super) fn measure(inputs: &[ResolverInput]) -> [LayerBounds; 2] {
        let mut bounds = [LayerBounds::default(); 2];
        for a in inputs {
            let b = &mut bounds[layer_slot(a.layer)];
            b.sensing = b.sensing.max(a.sensing);
            b.radius = b.radius.max(a.radius);
            b.speed = b.speed.max(a.intent.length());
        }
        bounds
    }
}

/// The radius around robot `a` beyond which no robot of its layer can take part in one of
/// the rules with it this step, metres: `min(S, r_a + R + m + (|v_a| + V) h)` with `S` the
/// larger of its and the layer's largest sensing range, `R` and `V` the layer's largest
/// body radius and intended speed this step, `m` the margin `margin_m` and `h` the look-ahead
/// `lookahead_s` (two discs closer than `c` within `h` were at most `c + |v| h` apart), plus
/// [`REACH_SLACK`].
pub(super) fn reach(
    bounds: &[LayerBounds; 2],
    margin_m: f32,
    lookahead_s: f32,
    a: &ResolverInput,
) -> f32 {
    let b = bounds[layer_slot(a.layer)];
    let sensed = a.sensing.max(b.sensing);
    let closing = a.radius + b.radius + margin_m + (a.intent.length() + b.speed) * lookahead_s;
    sensed.min(closing) * (1.0 + REACH_SLACK) + REACH_SLACK
}
