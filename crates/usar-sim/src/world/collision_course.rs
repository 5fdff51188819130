//! The "about to collide" test of two moving discs.
//!
//! Rules 1, 3 and 5 of the collision resolver ([`super::resolver`]) all ask it.

use parry2d::math::Vector as Vec2;

/// Whether two discs moving with relative position `r = p_j - p_i` and relative velocity
/// `v = v_j - v_i` approach each other and come closer than `clear` within `horizon` seconds.
pub fn about_to_collide(r: Vec2, v: Vec2, clear: f32, horizon: f32) -> bool {
    let rv = r.dot(v);
    if rv >= 0.0 {
        return false;
    }
    let t = (-rv / v.length_squared()).min(horizon);
    (r + v * t).length_squared() < clear * clear
}
