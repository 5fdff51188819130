//! Replays: one trial recorded while it runs and written as one self-contained HTML page that
//! plays it in a browser (`usar replay`, `usar sweep --replay`). See `docs/replay.md`.
//!
//! - [`SampleClock`] (`sampling.rs`): which steps are sampled (10 Hz by default).
//! - [`Channel`], [`RescueeCode`] (`channels.rs`): what is recorded per robot and rescuee, and
//!   how it is quantised.
//! - [`Mark`], [`MarkKind`] (`marks.rs`): the timeline's marks, from the mission's events
//!   ([`usar_sim::mission::MissionEvent`]) and the resolver's deadlock counters.
//! - [`Recording`] (`recording.rs`) and [`ReplayRecorder`] (`recorder.rs`), the
//!   [`usar_sim::mission::StepObserver`] that fills it.
//! - [`encode_recording`], [`decode_recording`] (`encoding.rs`): delta-coded, zigzag varints,
//!   raw deflate, base64.
//! - [`replay_html`], [`write_replay`] (`page.rs`): the page, from `template.html`,
//!   `replay.css` and `replay.js` beside this file.
//! - [`record_trial`] (`trial.rs`): run one trial and record it.
//! - [`ReplayRequest`], [`SweepReplays`] (`sweep_replays.rs`): replays of chosen trials of a sweep.

mod channels;
mod encoding;
mod error;
mod marks;
mod page;
mod recorder;
mod recording;
mod sampling;
mod sweep_replays;
mod trial;

pub use channels::{
    Channel, NEEDS_ENTRIES, PHASE_NAMES, RescueeCode, StateFlags, phase_code, quantise,
};
pub use encoding::{
    DecodedRecording, compress, decode_recording, decompress, encode_recording, read_varint,
    unzigzag, write_varint, zigzag,
};
pub use error::ReplayError;
pub use marks::{Mark, MarkKind};
pub use page::{
    ChannelMeta, KindMeta, MarkKindMeta, MarkMeta, PAGE_FORMAT, PageMeta, RoundMeta, TaskMeta,
    replay_html, write_replay,
};
pub use recorder::ReplayRecorder;
pub use recording::{Recording, RescueeChange};
pub use sampling::{DEFAULT_HZ, DEFAULT_MAX_ROBOT_SAMPLES, SampleClock, default_hz};
pub use sweep_replays::{ReplayRequest, SweepReplays, WrittenReplay, parse_replay_list};
pub use trial::{ReplayTrial, record_trial};
