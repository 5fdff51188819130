//! Validating the rest stations: at least one, at most [`MAX_REST_STATIONS`], each circle
//! wholly inside the arena, with the field path messages give it.

use super::context::{Ctx, R};
use super::limits::MAX_REST_STATIONS;
use super::model::Circle;
use super::params::Arena;
use super::spec::RestStationsSpec;

/// The rest stations with their field paths (`rest_station` for one circle,
/// `rest_station[i]` in a list): at least one, at most [`MAX_REST_STATIONS`], each inside the
/// arena.
pub(crate) fn rest_stations(
    ctx: &Ctx<'_>,
    spec: &RestStationsSpec,
    arena: &Arena,
) -> R<Vec<(String, Circle)>> {
    let circles = spec.circles();
    if circles.is_empty() {
        return Err(ctx.err(
            "rest_station",
            "an empty list: give at least one rest station".to_owned(),
        ));
    }
    if circles.len() > MAX_REST_STATIONS {
        return Err(ctx.err(
            "rest_station",
            format!(
                "{} rest stations, more than the limit of {MAX_REST_STATIONS}",
                circles.len()
            ),
        ));
    }
    circles
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let field = match spec {
                RestStationsSpec::One(_) => "rest_station".to_owned(),
                RestStationsSpec::Many(_) => format!("rest_station[{i}]"),
            };
            let circle = ctx.circle_in_arena(&field, c, arena)?;
            Ok((field, circle))
        })
        .collect()
}
