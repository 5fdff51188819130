//! The default output folder of a sweep (`results/<scenario name>/`), of a calibration and of
//! a multiverse (`results/calibrate-<scenario name>/`, `results/multiverse-<scenario name>/`),
//! always one folder inside `results/`.

use std::path::{Path, PathBuf};

use usar_sim::scenario::Scenario;

/// Default output folder for a scenario: `results/<scenario name>/`, always one folder inside
/// `results/`: in the name, path separators (`/`, `\`), `:` and control characters become
/// `_`, surrounding white space is dropped, and a name left empty or made only of dots (`.`,
/// `..`) becomes `scenario`. So a scenario file cannot direct output elsewhere (`name:
/// "../../x"` writes to `results/.._.._x/`). A name longer than [`MAX_FOLDER_NAME_BYTES`]
/// is cut there (at a character boundary) and ends with `~` and the first 8 hex digits of
/// the FNV-1a hash of the whole name, so that the folder can be created (most file systems
/// allow 255 bytes) and two long names stay apart.
pub fn default_out_dir(scenario: &Scenario) -> PathBuf {
    Path::new("results").join(folder_name(scenario.name()))
}

/// Default output folder of a run of kind `kind` (`"calibrate"`, `"multiverse"`) on a
/// scenario: `results/<kind>-<scenario name>/`, the name made one folder as for
/// [`default_out_dir`] (so `kind` must hold no path separator).
pub fn default_out_dir_of(kind: &str, scenario: &Scenario) -> PathBuf {
    Path::new("results").join(format!("{kind}-{}", folder_name(scenario.name())))
}

/// The scenario name as one folder name (see [`default_out_dir`]).
fn folder_name(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| {
            if matches!(c, '/' | '\\' | ':') || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    let clean = clean.trim();
    if clean.chars().all(|c| c == '.') {
        return "scenario".to_string();
    }
    if clean.len() <= MAX_FOLDER_NAME_BYTES {
        return clean.to_string();
    }
    let hash = crate::fingerprint::fnv1a64_hex(name.as_bytes());
    let keep = MAX_FOLDER_NAME_BYTES - 9;
    let cut = (0..=keep)
        .rev()
        .find(|&i| clean.is_char_boundary(i))
        .unwrap_or(0);
    format!("{}~{}", clean[..cut].trim_end(), &hash[..8])
}

/// The longest default output folder name, bytes (see [`default_out_dir`]); 100.
pub const MAX_FOLDER_NAME_BYTES: usize = 100;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_out_dirs_stay_one_folder_inside_results() {
        for (name, folder) in [
            ("paper", "paper"),
            ("swarm-1000 v2", "swarm-1000 v2"),
            ("/etc", "_etc"),
            ("../../escaped", ".._.._escaped"),
            ("a/../b", "a_.._b"),
            ("..", "scenario"),
            (" . ", "scenario"),
            ("C:\\tmp", "C__tmp"),
            ("line\nbreak", "line_break"),
            (&"x".repeat(100), &"x".repeat(100)),
        ] {
            assert_eq!(folder_name(name), folder, "{name:?}");
            let dir = Path::new("results").join(folder_name(name));
            let parts: Vec<_> = dir.components().collect();
            assert_eq!(parts.len(), 2, "{name:?} gives {}", dir.display());
            assert!(
                matches!(parts[1], std::path::Component::Normal(_)),
                "{name:?}"
            );
        }
    }

    /// A calibration's and a multiverse's folders are the sweep's folder name after their
    /// kind, one folder inside `results/` whatever the scenario's name.
    #[test]
    fn a_run_kind_prefixes_the_safe_folder_name() {
        let paper = include_str!("../../../../scenarios/paper.ron");
        let mut spec = usar_sim::scenario::parse_spec(paper, "paper.ron").unwrap();
        for (name, calibrate) in [
            ("paper", "results/calibrate-paper"),
            ("../../escaped", "results/calibrate-.._.._escaped"),
        ] {
            spec.name = name.into();
            let scenario = spec.validate("paper.ron").unwrap();
            assert_eq!(
                default_out_dir_of("calibrate", &scenario),
                Path::new(calibrate)
            );
            let multiverse = default_out_dir_of("multiverse", &scenario);
            assert_eq!(
                multiverse.components().count(),
                2,
                "{}",
                multiverse.display()
            );
        }
    }

    /// A name too long for a file name (300 x "x", 90 CJK characters of 3 bytes) is cut
    /// with a hash of the whole name: `usar sweep` without `--out` failed with "File name too
    /// long (os error 36)".
    #[test]
    fn long_names_are_cut_with_a_hash() {
        let dir = tempfile::tempdir().unwrap();
        let long = "x".repeat(300);
        let cjk = "漢".repeat(90);
        let mut seen = Vec::new();
        for name in [long.clone(), format!("{long}y"), cjk] {
            let folder = folder_name(&name);
            assert!(folder.len() <= MAX_FOLDER_NAME_BYTES, "{folder}");
            assert!(folder.len() > MAX_FOLDER_NAME_BYTES - 12, "{folder}");
            assert_eq!(folder.as_bytes()[folder.len() - 9], b'~', "{folder}");
            std::fs::create_dir(dir.path().join(&folder)).expect("a valid folder name");
            seen.push(folder);
        }
        assert_ne!(seen[0], seen[1]);
    }
}
