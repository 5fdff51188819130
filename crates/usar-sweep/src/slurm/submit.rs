//! Submitting the scripts of [`crate::slurm::script`] with `sbatch`: the job array, then the
//! merge with `--dependency=afterok:<array job id>` (what `submit.sh` does, for `usar slurm
//! --submit`).

use std::path::Path;
use std::process::Command;

use usar_sim::scenario::path_text;

use crate::slurm::SlurmFiles;
use crate::slurm::error::SlurmError;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, SlurmError>;

/// The job ids Slurm gave.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Submitted {
    /// The job array's id (its tasks are `<id>_0`, `<id>_1`, ...).
    pub array_job: String,
    /// The merge job's id.
    pub merge_job: String,
}

/// The job id in the output of `sbatch --parsable`: `<id>` or `<id>;<cluster>` on one line.
///
/// # Errors
/// Output that does not start with a job id (digits).
pub fn parse_job_id(stdout: &str) -> Result<String> {
    let line = stdout.lines().map(str::trim).find(|l| !l.is_empty());
    let id = line.map(|l| l.split(';').next().unwrap_or(l).trim());
    match id {
        Some(id) if !id.is_empty() && id.chars().all(|c| c.is_ascii_digit()) => Ok(id.to_string()),
        _ => Err(SlurmError::NoJobId {
            stdout: stdout.to_owned(),
        }),
    }
}

/// Runs `sbatch --parsable [extra] script` and returns the job id.
fn sbatch(sbatch: &Path, extra: &[String], script: &Path) -> Result<String> {
    let out = Command::new(sbatch)
        .arg("--parsable")
        .args(extra)
        .arg(script)
        .output()
        .map_err(|source| SlurmError::Run {
            program: path_text(sbatch),
            source,
        })?;
    if !out.status.success() {
        return Err(SlurmError::Refused {
            script: path_text(script),
            status: out.status.to_string(),
            message: one_line(&String::from_utf8_lossy(&out.stderr)),
        });
    }
    parse_job_id(&String::from_utf8_lossy(&out.stdout))
}

/// A program's message on one line: its non-empty lines, trimmed, joined by ` / `
/// (sbatch prints one `sbatch: error: ...` line per failed step).
fn one_line(message: &str) -> String {
    let lines: Vec<&str> = message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    if lines.is_empty() {
        "(it printed nothing)".to_string()
    } else {
        lines.join(" / ")
    }
}

/// Submits the array of `files`, then its merge chained with `--dependency=afterok`, with the
/// `sbatch` program `sbatch_program` (usually `sbatch`, found on the `PATH`).
///
/// # Errors
/// `sbatch` cannot be run (not on the `PATH`), refuses a script (its message is given), or
/// prints no job id. When the merge is refused, the message names the array job that was
/// submitted.
pub fn submit(files: &SlurmFiles, sbatch_program: &Path) -> Result<Submitted> {
    let array_job = sbatch(sbatch_program, &[], &files.array)?;
    let merge_job = sbatch(
        sbatch_program,
        &[format!("--dependency=afterok:{array_job}")],
        &files.merge,
    )
    .map_err(|e| SlurmError::MergeNotSubmitted {
        array_job: array_job.clone(),
        merge_script: path_text(&files.merge),
        source: Box::new(e),
    })?;
    Ok(Submitted {
        array_job,
        merge_job,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn job_ids_are_read_with_or_without_a_cluster() {
        assert_eq!(parse_job_id("1234\n").ok(), Some("1234".into()));
        assert_eq!(parse_job_id("77;cluster-a\n").ok(), Some("77".into()));
        assert!(parse_job_id("Submitted batch job 12\n").is_err());
        assert!(parse_job_id("").is_err());
    }

    #[test]
    fn sbatchs_message_is_given_on_one_line() {
        let stderr = "sbatch: error: resolve_ctls_from_dns_srv: res_nsearch error: Unknown host\n\
                      sbatch: error: fetch_config: DNS SRV lookup failed\n\n";
        assert_eq!(
            one_line(stderr),
            "sbatch: error: resolve_ctls_from_dns_srv: res_nsearch error: Unknown host / \
             sbatch: error: fetch_config: DNS SRV lookup failed"
        );
        assert_eq!(one_line(" \n"), "(it printed nothing)");
    }

    /// A fake `sbatch` that fails with two lines: the error `submit` gives is one line.
    #[cfg(unix)]
    #[test]
    fn a_refused_submission_is_one_line() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let fake = dir.path().join("sbatch");
        std::fs::write(
            &fake,
            "#!/bin/sh\necho 'sbatch: error: one' >&2\necho 'sbatch: error: two' >&2\nexit 1\n",
        )
        .unwrap();
        std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
        let files = SlurmFiles::under(dir.path());
        let e = format!("{:#}", submit(&files, &fake).unwrap_err());
        assert!(!e.contains('\n'), "{e}");
        assert!(
            e.ends_with("sbatch: error: one / sbatch: error: two"),
            "{e}"
        );
    }
}
