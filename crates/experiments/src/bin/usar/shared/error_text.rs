//! An error of `usar` as the line it prints: the libraries' typed errors about a setting in
//! the command line's words (the field that holds the setting becomes the flag that sets it),
//! every other cause as it says itself, joined by `: ` as anyhow's `{:#}` joins them.

use usar_study::refused_setting::RefusedSetting;

/// `e` and its causes on one line, each refused setting named by its flag.
pub fn error_line(e: &anyhow::Error) -> String {
    e.chain()
        .map(|cause| setting_line(cause).unwrap_or_else(|| cause.to_string()))
        .collect::<Vec<_>>()
        .join(": ")
}

/// `cause` in `usar`'s words when it is a refused setting (of a sweep, a calibration or a
/// multiverse): the flag, then the problem (`--max-evals must be at least 1`).
fn setting_line(cause: &(dyn std::error::Error + 'static)) -> Option<String> {
    RefusedSetting::of(cause).map(|refused| refused.line(flag))
}

/// The flag that sets the field named `field`: `--` and the name with `-` for `_`, but
/// `--duration` for `duration_s` and `--max-time` for `max_time_s`.
fn flag(field: &str) -> String {
    match field {
        "duration_s" => "--duration".into(),
        "max_time_s" => "--max-time".into(),
        f => format!("--{}", f.replace('_', "-")),
    }
}

#[cfg(test)]
mod tests {
    use usar_study::calibrate::SetupError;
    use usar_study::multiverse::MultiverseError;
    use usar_sweep::sweep::{ConfigError, SettingError};

    use super::*;

    #[test]
    fn a_refused_setting_names_its_flag_inside_the_chain() {
        let e = anyhow::Error::new(ConfigError::TrialLength {
            reason: "too long".into(),
        })
        .context("cell 2");
        assert_eq!(error_line(&e), "cell 2: --duration: too long");
        assert_eq!(
            error_line(&anyhow::Error::new(ConfigError::NoTrials)),
            "--trials must be at least 1"
        );
        let setting = SettingError::new("max_evals", " must be at least 1");
        assert_eq!(
            error_line(&anyhow::Error::new(SetupError::from(setting.clone()))),
            "--max-evals must be at least 1"
        );
        let calibration = MultiverseError::Calibration(SetupError::from(setting));
        assert_eq!(
            error_line(&anyhow::Error::new(calibration)),
            "--max-evals must be at least 1"
        );
        assert_eq!(
            error_line(&anyhow::anyhow!("plain").context("outer")),
            "outer: plain"
        );
    }

    #[test]
    fn fields_become_flags() {
        for (field, flag_text) in [
            ("duration_s", "--duration"),
            ("max_time_s", "--max-time"),
            ("calibration_trials", "--calibration-trials"),
            ("vary", "--vary"),
        ] {
            assert_eq!(flag(field), flag_text);
        }
    }
}
