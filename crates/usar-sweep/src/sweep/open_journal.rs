//! The journal a sweep opens: created, resumed or reused, or refused with what to do instead.

use std::path::Path;

use usar_sim::scenario::path_text;

use crate::atomic::FileError;
use crate::data::config::SweepConfig;
use crate::data::outcome::JournalUse;
use crate::data::shard_folders::shard_folders;
use crate::error::SweepError;
use crate::journal::{
    Journal, JournalContents, RejectedRecord, SweepHeader, TrialRecord, header_diff, holds_no_line,
    other_sweeps, read_header, something_at,
};
use crate::journal_error::JournalError;
use crate::settings::Setting;
use crate::stale_outputs::remove_previous_outputs;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, SweepError>;

/// A journal opened for a sweep, with what it already held.
pub(crate) struct OpenJournal {
    /// The journal, open for appending.
    pub(crate) journal: Journal,
    /// Records that verify, in file order.
    pub(crate) records: Vec<TrialRecord>,
    /// Record lines that do not verify.
    pub(crate) rejected: Vec<RejectedRecord>,
    /// How the journal was come by.
    pub(crate) how: JournalUse,
}

impl OpenJournal {
    fn new(journal: Journal) -> Self {
        Self {
            journal,
            records: Vec::new(),
            rejected: Vec::new(),
            how: JournalUse::Created,
        }
    }

    fn continued((journal, contents): (Journal, JournalContents), how: JournalUse) -> Self {
        Self {
            journal,
            records: contents.records,
            rejected: contents.rejected,
            how,
        }
    }
}

/// Creates, resumes or reuses the journal in `dir`, with the records it holds.
pub(crate) fn open_journal(
    cfg: &SweepConfig,
    dir: &Path,
    header: &SweepHeader,
) -> Result<OpenJournal> {
    let path = Journal::path_in(dir);
    if holds_no_line(&path) {
        // An empty file, or a header cut short, holds no trial: nothing to resume or lose.
        std::fs::remove_file(&path)
            .map_err(FileError::io(format!("removing {}", path_text(&path))))?;
    }
    if cfg.overwrite && !cfg.resume {
        // A folder in the journal's place is the user's to remove: nothing goes.
        if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_dir()) {
            return Err(JournalError::Folder {
                path: path_text(&path),
            }
            .into());
        }
        // The earlier sweep's tables, figures and grid cells go with its journal.
        remove_previous_outputs(dir, &path)?;
        if something_at(&path) {
            std::fs::remove_file(&path)
                .map_err(FileError::io(format!("removing {}", path_text(&path))))?;
        }
        return Ok(OpenJournal::new(Journal::create(dir, header)?));
    }
    if !something_at(&path) {
        if cfg.shard.is_none() {
            refuse_other_sweeps_shards(dir, header)?;
        }
        return Ok(OpenJournal::new(Journal::create(dir, header)?));
    }
    if cfg.resume {
        let resumed = Journal::open_resume(dir, header)?;
        return Ok(OpenJournal::continued(resumed, JournalUse::Resumed));
    }
    let why = match read_header(&path) {
        Ok(found) if &found == header => {
            let resumed = Journal::open_resume(dir, header)?;
            return Ok(OpenJournal::continued(resumed, JournalUse::Reused));
        }
        Ok(found) if found.build != header.build => {
            return Err(SweepError::JournalExists {
                path: path_text(&path),
                why: header_diff(&found, header),
                advice: format!(
                    "its trials cannot be continued by this build; pass {} to start afresh \
                     (or choose another {}, or run the build that wrote it)",
                    Setting::Overwrite,
                    Setting::Out
                ),
            });
        }
        Ok(found) => format!(
            "it was written with other parameters: {}",
            header_diff(&found, header)
        ),
        // It cannot be continued: its own message says how to start afresh.
        Err(e) => return Err(e.into()),
    };
    // --resume with these parameters would be refused too: say what works.
    Err(SweepError::JournalExists {
        path: path_text(&path),
        why,
        advice: format!(
            "to continue that sweep, run it with its own parameters (and {}); to start \
             afresh with these, pass {}, or choose another {}",
            Setting::Resume,
            Setting::Overwrite,
            Setting::Out
        ),
    })
}

/// Refuses to start a sweep in `dir` when a journal of its shards (`dir/shards/`, see
/// [`crate::shard`]) was written by another sweep: `usar merge` writes that sweep's files into
/// `dir`, and the two would mix. `--overwrite` removes those files instead
/// ([`remove_previous_outputs`]).
fn refuse_other_sweeps_shards(dir: &Path, header: &SweepHeader) -> Result<()> {
    for (_, shard) in shard_folders(dir)? {
        let path = Journal::path_in(&shard);
        if let Some(why) = other_sweeps(&path, header) {
            return Err(SweepError::OtherSweepsShard {
                path: path_text(&path),
                why,
                dir: path_text(dir),
            });
        }
    }
    Ok(())
}
