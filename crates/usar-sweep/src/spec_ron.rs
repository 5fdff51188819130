//! A scenario spec written back as a RON scenario file: what `usar check --print` prints and
//! each grid cell's `scenario.ron` holds.
//!
//! The text lists every field (defaults included), floats in their shortest round-trip form,
//! so [`usar_sim::scenario::parse_spec`] reads it back to an equal spec and `usar check`
//! validates it to the same scenario (same scenario hash).

use ron::ser::PrettyConfig;
use usar_sim::scenario::ScenarioSpec;

/// `spec` as the text of a scenario file, `Scenario( ... )`, after `comments` (one `// `
/// line each; line breaks inside a comment, `\n`, `\r\n` or a bare `\r`, start a new comment
/// line).
///
/// # Errors
/// A serialisation error from ron (not expected for a spec).
pub fn spec_to_ron(spec: &ScenarioSpec, comments: &[String]) -> Result<String, ron::Error> {
    let config = PrettyConfig::new()
        .indentor("    ")
        .struct_names(false)
        .separate_tuple_members(false);
    let body = ron::ser::to_string_pretty(spec, config)?;
    let mut text = String::new();
    // The loader ends a line at a bare `\r` too (old Mac endings): such a comment would
    // leave its tail outside the comment.
    for line in comments
        .iter()
        .flat_map(|c| c.lines())
        .flat_map(|l| l.split('\r'))
    {
        text.push_str("// ");
        text.push_str(line);
        text.push('\n');
    }
    // Without struct names the top level is written `( ... )`; name it as files do.
    text.push_str("Scenario");
    text.push_str(&body);
    text.push('\n');
    Ok(text)
}

#[cfg(test)]
mod tests {
    use usar_sim::scenario::{from_str, parse_spec};

    use super::*;

    const PAPER: &str = include_str!("../../../scenarios/paper.ron");

    #[test]
    fn round_trips_every_shipped_scenario() {
        for (name, src) in [
            ("paper.ron", PAPER),
            (
                "corridor.ron",
                include_str!("../../../scenarios/corridor.ron"),
            ),
            (
                "debris-crossing.ron",
                include_str!("../../../scenarios/debris-crossing.ron"),
            ),
        ] {
            let spec = parse_spec(src, name).unwrap();
            let text = spec_to_ron(&spec, &["first\nsecond".into()]).unwrap();
            assert!(
                text.starts_with("// first\n// second\nScenario(\n"),
                "{text}"
            );
            let back = parse_spec(&text, "back.ron").unwrap();
            assert_eq!(back, spec, "{name}");
            assert_eq!(
                from_str(&text, "back.ron").unwrap(),
                from_str(src, name).unwrap()
            );
        }
    }

    #[test]
    fn a_bare_carriage_return_in_a_comment_stays_in_the_comment() {
        // A cell's comment holds the scenario's path, which may hold any character.
        let spec = parse_spec(PAPER, "paper.ron").unwrap();
        let text = spec_to_ron(&spec, &["Cell 0 of a\rb.ron: x\r\ny".into()]).unwrap();
        assert!(
            text.starts_with("// Cell 0 of a\n// b.ron: x\n// y\nScenario(\n"),
            "{text}"
        );
        assert_eq!(parse_spec(&text, "back.ron").unwrap(), spec);
    }

    #[test]
    fn awkward_floats_survive() {
        let mut spec = parse_spec(PAPER, "paper.ron").unwrap();
        spec.mission.hp_pct_per_step_in_radiation = (0.1 + 0.2).try_into().unwrap();
        spec.mission.energy_pct_per_moving_step = 1e-300.try_into().unwrap();
        spec.arena.width_m = (1.0 / 3.0).try_into().unwrap();
        let back = parse_spec(&spec_to_ron(&spec, &[]).unwrap(), "x").unwrap();
        assert_eq!(back, spec);
    }
}
