//! The replay page: one self-contained HTML file (`template.html` with `replay.css`,
//! `replay.js`, the arena as `usar render` draws it, the page's metadata as JSON and the
//! recording as base64), which plays the trial in a browser without network or server.

use std::path::Path;

use base64::Engine;
use base64::engine::general_purpose::STANDARD as BASE64;
use plotters::style::RGBColor;
use serde::Serialize;
use usar_sim::mission::RoundRecord;
use usar_sim::scenario::{Locomotion, Scenario};

use super::channels::{Channel, PHASE_NAMES, RescueeCode, StateFlags};
use super::encoding::{compress, encode_recording};
use super::error::ReplayError;
use super::marks::MarkKind;
use super::recording::Recording;
use crate::render::{
    MAX_LABELLED_ROBOTS, MapFrame, RESCUEE_COLOR, kind_color, render_map_svg, task_color,
    task_strong_color,
};
use usar_sweep::atomic::write_atomic;

const TEMPLATE: &str = include_str!("template.html");
const CSS: &str = include_str!("replay.css");
const JS: &str = include_str!("replay.js");

/// Version of the page's data layout ([`PageMeta::format`]).
pub const PAGE_FORMAT: u32 = 1;

/// Names of the needs vector's entries (paper, Eqs. 19-21), in order.
const NEEDS_NAMES: [&str; 7] = ["hp", "v", "sen", "eng", "res", "cap", "obs"];

/// A robot kind as the page draws it.
#[derive(Debug, Clone, Serialize)]
pub struct KindMeta {
    /// The kind's name.
    pub name: String,
    /// `Carrier`, `Supplier` or `Observer`.
    pub role: String,
    /// Whether it flies (drawn ringed).
    pub aerial: bool,
    /// Body radius, metres.
    pub radius_m: f64,
    /// Its colour in `usar render` (by role), `#rrggbb`.
    pub color: String,
}

/// A task as the page draws it.
#[derive(Debug, Clone, Serialize)]
pub struct TaskMeta {
    /// The task's name.
    pub name: String,
    /// Its search area's colour in `usar render`, `#rrggbb`.
    pub area_color: String,
    /// The colour of its group's robots, `#rrggbb`.
    pub color: String,
    /// Its rescuees' positions, metres (to the centimetre), in index order.
    pub rescuees: Vec<[f64; 2]>,
}

/// A round of the trial.
#[derive(Debug, Clone, Serialize)]
pub struct RoundMeta {
    /// Start, seconds.
    pub start_s: f64,
    /// End, seconds.
    pub end_s: f64,
    /// Whether every grouped robot got back before the time limit.
    pub completed: bool,
    /// Robot ids of each task's group.
    pub groups: Vec<Vec<usize>>,
    /// Rescuees delivered per task in the round.
    pub rescued: Vec<u32>,
}

/// A mark on the timeline: time (s), kind (row), task (`None` for none), value, robots.
#[derive(Debug, Clone, Serialize)]
pub struct MarkMeta {
    /// Time, seconds.
    pub t: f64,
    /// Kind, as [`MarkKind`]'s number.
    pub k: u8,
    /// Task id, if any.
    pub task: Option<usize>,
    /// Value (see [`MarkKind`]).
    pub v: u32,
    /// Robots concerned.
    pub robots: Vec<usize>,
}

/// A mark kind's row on the timeline.
#[derive(Debug, Clone, Serialize)]
pub struct MarkKindMeta {
    /// Row label.
    pub label: String,
    /// Colour, `#rrggbb`.
    pub color: String,
}

/// A channel of the data stream: its name and the value of one integer step.
#[derive(Debug, Clone, Serialize)]
pub struct ChannelMeta {
    /// Name ([`Channel::name`]).
    pub name: String,
    /// Quantum ([`Channel::quantum`]).
    pub quantum: f64,
}

/// Everything the page knows besides the recorded stream, as JSON in the page.
#[derive(Debug, Clone, Serialize)]
pub struct PageMeta {
    /// Data layout version ([`PAGE_FORMAT`]).
    pub format: u32,
    /// Scenario name.
    pub scenario: String,
    /// Scenario description.
    pub description: String,
    /// Method (display name).
    pub method: String,
    /// Trial index.
    pub trial: u32,
    /// Seed of the starting team, as a decimal string (JavaScript numbers hold 53 bits).
    pub seed: String,
    /// Step, seconds.
    pub dt_s: f64,
    /// Steps between samples.
    pub every_steps: u64,
    /// Steps of the trial.
    pub total_steps: u64,
    /// Samples in the stream.
    pub samples: usize,
    /// Sampling rate used, samples per simulated second.
    pub hz: f64,
    /// The arena picture's frame.
    pub map: MapFrame,
    /// Robot kinds.
    pub kinds: Vec<KindMeta>,
    /// Kind index of each robot.
    pub robots: Vec<usize>,
    /// Tasks, by id.
    pub tasks: Vec<TaskMeta>,
    /// The colour of robots in no group, `#rrggbb`.
    pub no_group_color: String,
    /// The colour of rescuees, `#rrggbb`.
    pub rescuee_color: String,
    /// Whether robots get id labels (teams of up to `MAX_LABELLED_ROBOTS`).
    pub labels: bool,
    /// Channels of the stream, in order.
    pub channels: Vec<ChannelMeta>,
    /// Phase names by code.
    pub phases: Vec<String>,
    /// Flag bits: leaving, picking, claim, held, blocked, in_list.
    pub flags: [i32; 6],
    /// Rescuee code names by code.
    pub rescuee_codes: Vec<String>,
    /// Needs entry names.
    pub needs: Vec<String>,
    /// Mark kinds by number.
    pub mark_kinds: Vec<MarkKindMeta>,
    /// Marks in time order.
    pub marks: Vec<MarkMeta>,
    /// Rounds.
    pub rounds: Vec<RoundMeta>,
}

impl KindMeta {
    /// Kind `i` of `s`.
    fn of(s: &Scenario, i: usize) -> Self {
        let k = &s.kinds()[i];
        Self {
            name: k.name.clone(),
            role: format!("{:?}", k.role),
            aerial: k.locomotion == Locomotion::Aerial,
            radius_m: k.body_radius_m,
            color: hex(kind_color(s, i)),
        }
    }
}

impl TaskMeta {
    /// Task `t` of `s`, rescuee positions to the centimetre.
    fn of(s: &Scenario, t: usize) -> Self {
        let task = &s.tasks()[t];
        let cm = |v: f64| (v * 100.0).round() / 100.0;
        Self {
            name: task.name.clone(),
            area_color: hex(task_color(s, t)),
            color: hex(task_strong_color(s, t)),
            rescuees: task.rescuees.iter().map(|p| [cm(p.x), cm(p.y)]).collect(),
        }
    }
}

fn hex(c: RGBColor) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

impl PageMeta {
    /// The page's metadata for `rec`, a recording of a trial of `scenario`, drawn in `map`.
    pub fn new(scenario: &Scenario, rec: &Recording, map: MapFrame) -> Self {
        let s = scenario;
        Self {
            format: PAGE_FORMAT,
            scenario: s.name().to_owned(),
            description: s.description().to_owned(),
            method: rec.method.clone(),
            trial: rec.trial,
            seed: rec.seed.to_string(),
            dt_s: rec.dt_s,
            every_steps: rec.clock.every_steps,
            total_steps: rec.clock.total_steps,
            samples: rec.samples,
            hz: rec.clock.actual_hz(rec.dt_s),
            map,
            kinds: (0..s.kinds().len()).map(|i| KindMeta::of(s, i)).collect(),
            robots: s.robots().iter().map(|r| r.kind).collect(),
            tasks: (0..s.tasks().len()).map(|t| TaskMeta::of(s, t)).collect(),
            no_group_color: "#9e9e9e".into(),
            rescuee_color: hex(RESCUEE_COLOR),
            labels: s.robots().len() <= MAX_LABELLED_ROBOTS,
            channels: Channel::ALL
                .iter()
                .map(|c| ChannelMeta {
                    name: c.name(),
                    quantum: c.quantum(),
                })
                .collect(),
            phases: PHASE_NAMES.iter().map(|p| p.to_string()).collect(),
            flags: [
                StateFlags::LEAVING,
                StateFlags::PICKING,
                StateFlags::CLAIM,
                StateFlags::HELD,
                StateFlags::BLOCKED,
                StateFlags::IN_LIST,
            ],
            rescuee_codes: RescueeCode::NAMES.iter().map(|p| p.to_string()).collect(),
            needs: NEEDS_NAMES.iter().map(|p| p.to_string()).collect(),
            mark_kinds: MarkKind::ALL
                .iter()
                .map(|k| MarkKindMeta {
                    label: k.label().into(),
                    color: k.color().into(),
                })
                .collect(),
            marks: rec
                .marks
                .iter()
                .map(|m| MarkMeta {
                    t: m.time_s,
                    k: m.kind as u8,
                    task: m.task,
                    v: m.value,
                    robots: m.robots.clone(),
                })
                .collect(),
            rounds: rec.rounds.iter().map(round_meta).collect(),
        }
    }
}

fn round_meta(r: &RoundRecord) -> RoundMeta {
    RoundMeta {
        start_s: r.start_s,
        end_s: r.end_s,
        completed: r.completed,
        groups: r.groups.clone(),
        rescued: r.rescued.clone(),
    }
}

/// Escapes text for HTML element content and attribute values.
fn escape_html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The replay page of `rec`, a recording of a trial of `scenario`, as HTML text.
///
/// # Errors
/// [`ReplayError::Draw`] if the arena cannot be drawn, [`ReplayError::Encode`] if the data
/// cannot be serialised or compressed.
pub fn replay_html(scenario: &Scenario, rec: &Recording) -> Result<String, ReplayError> {
    let (svg, map) =
        render_map_svg(scenario).map_err(|e| ReplayError::Draw(rne_core::error_line(&e)))?;
    let meta = PageMeta::new(scenario, rec, map);
    // In a script element, `</script` ends it and `<!--` starts a comment that can swallow
    // the rest of the page: with every `<` written `\u003c` (JSON reads it back as `<`; a `<`
    // occurs only inside strings), no scenario text can do either.
    let json = serde_json::to_string(&meta)
        .map_err(|e| ReplayError::Encode(e.to_string()))?
        .replace('<', "\\u003c");
    let data = BASE64.encode(compress(&encode_recording(rec))?);
    let title = format!(
        "{} - {} trial {} - replay",
        scenario.name(),
        rec.method,
        rec.trial
    );
    let mut html = String::with_capacity(TEMPLATE.len() + json.len() + data.len() + svg.len() * 2);
    // One pass over the template, so no inserted text is searched for placeholders again.
    let mut rest = TEMPLATE;
    while let Some(i) = rest.find("{{") {
        html.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let Some(j) = after.find("}}") else {
            html.push_str(&rest[i..]);
            rest = "";
            break;
        };
        match &after[..j] {
            "TITLE" => html.push_str(&escape_html(&title)),
            "CSS" => html.push_str(CSS),
            "JS" => html.push_str(JS),
            "META" => html.push_str(&json),
            "DATA" => html.push_str(&data),
            "MAP" => html.push_str(&BASE64.encode(svg.as_bytes())),
            other => {
                return Err(ReplayError::Encode(format!(
                    "template placeholder {{{{{other}}}}} unknown"
                )));
            }
        }
        rest = &after[j + 2..];
    }
    html.push_str(rest);
    Ok(html)
}

/// Writes the replay page of `rec` (see [`replay_html`]) to `out` with [`write_atomic`] and
/// returns its size, bytes.
///
/// # Errors
/// As [`replay_html`], and [`ReplayError::Write`] if the file cannot be written.
pub fn write_replay(scenario: &Scenario, rec: &Recording, out: &Path) -> Result<u64, ReplayError> {
    let html = replay_html(scenario, rec)?;
    write_atomic(out, html.as_bytes())?;
    Ok(html.len() as u64)
}

#[cfg(test)]
mod tests {
    use usar_sim::mission::Simulation;
    use usar_sim::scenario;

    use super::*;
    use crate::replay::{decode_recording, decompress, record_trial};

    fn paper() -> Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
        scenario::load(path).expect("paper.ron loads")
    }

    fn recorded(s: &Scenario, duration_s: f64) -> Recording {
        let sim = Simulation::builder(s)
            .method_named("rne")
            .duration_s(duration_s)
            .build()
            .expect("trial builds");
        record_trial(sim, 10.0, None).expect("records").recording
    }

    /// The text between `<script ... id="ID">` and `</script>`.
    fn script<'a>(html: &'a str, id: &str) -> &'a str {
        let open = format!("id=\"{id}\">");
        let start = html.find(&open).expect("script element") + open.len();
        &html[start..start + html[start..].find("</script>").expect("end")]
    }

    /// The page holds everything (no placeholder left, nothing fetched from elsewhere), its
    /// metadata parses, and its data decode back to the recording.
    #[test]
    fn the_page_is_self_contained_and_its_data_decode_to_the_recording() {
        let s = paper();
        let rec = recorded(&s, 30.0);
        let html = replay_html(&s, &rec).expect("page");
        assert!(!html.contains("{{"), "a placeholder is left");
        for remote in ["src=\"http", "href=\"http", "<link", "fetch(", "import("] {
            assert!(!html.contains(remote), "the page refers to {remote}");
        }
        let meta: serde_json::Value =
            serde_json::from_str(script(&html, "meta")).expect("metadata is JSON");
        assert_eq!(meta["samples"], 301);
        assert_eq!(meta["robots"].as_array().map(Vec::len), Some(12));
        assert_eq!(meta["seed"], rec.seed.to_string());
        assert_eq!(
            meta["marks"].as_array().map(Vec::len),
            Some(rec.marks.len())
        );
        let packed = BASE64.decode(script(&html, "data").trim()).expect("base64");
        let back =
            decode_recording(&decompress(&packed).expect("inflates"), 301, 12).expect("decodes");
        assert_eq!(back.channels, rec.channels);
        assert_eq!(back.rescuee_changes, rec.rescuee_changes);
        let svg = BASE64
            .decode(
                html.split("base64,")
                    .nth(1)
                    .and_then(|t| t.split('"').next())
                    .expect("map"),
            )
            .expect("map base64");
        assert!(
            String::from_utf8(svg)
                .expect("svg text")
                .contains("hard drop-off")
        );
    }

    /// The paper's whole 600 s trial at 10 Hz stays far under the 5 MB budget.
    #[test]
    fn the_papers_whole_trial_fits_in_well_under_five_megabytes() {
        let s = paper();
        let rec = recorded(&s, 600.0);
        assert_eq!(rec.samples, 6_001);
        let dir = tempfile::tempdir().expect("temp dir");
        let out = dir.path().join("replay.html");
        let bytes = write_replay(&s, &rec, &out).expect("writes");
        assert_eq!(std::fs::metadata(&out).expect("file").len(), bytes);
        let per_robot_sample = bytes as f64 / (6_001.0 * 12.0);
        assert!(bytes < 5_000_000, "{bytes} bytes");
        assert!(
            per_robot_sample < 4.0,
            "{per_robot_sample:.2} bytes per robot and sample"
        );
    }

    #[test]
    fn no_scenario_text_can_end_or_comment_out_the_metadata_script() {
        // A name is one line (validation refuses `\u{2028}`); a description need not be.
        let name = "a <!--<script> b </script> c";
        let text = "a <!--<script> b </script> c \u{2028} d";
        let s = paper()
            .edit(|s| {
                s.description = text.to_string();
                s.name = name.to_string();
            })
            .expect("a valid edit");
        let rec = recorded(&s, 2.0);
        let html = replay_html(&s, &rec).expect("page");
        let meta = script(&html, "meta");
        assert!(!meta.contains('<'), "{meta}");
        let meta: serde_json::Value = serde_json::from_str(meta).expect("metadata is JSON");
        assert_eq!(meta["description"], text);
        assert_eq!(meta["scenario"], name);
    }

    #[test]
    fn titles_are_escaped() {
        assert_eq!(
            escape_html("a<b & \"c\">"),
            "a&lt;b &amp; &quot;c&quot;&gt;"
        );
    }
}
