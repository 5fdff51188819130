//! End-to-end tests of `usar render` (runs the built binary).

use crate::common;

use std::path::{Path, PathBuf};

use common::{PAPER, stderr, text, usar};

/// Checks that `svg` looks like one complete SVG document.
fn assert_svg(svg: &str) {
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(200)]);
    assert!(svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<svg").count(), 1);
    assert_eq!(svg.matches("<text").count(), svg.matches("</text>").count());
}

#[test]
fn renders_the_paper_arena() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("pictures/arena.svg");
    let o = usar(["render", PAPER, "--out", text(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("12 robots"));
    let svg = std::fs::read_to_string(&out).expect("SVG written");
    assert_svg(&svg);
    for label in [
        "hard search area (240 rescuees)",
        "easy search area (240 rescuees)",
        "hard drop-off",
        "easy drop-off",
        "rest station",
        "carrier x6 (ground)",
        "supplier x4 (ground)",
        "observer x2 (aerial)",
        "radiation, dose x1.5",
    ] {
        assert!(svg.contains(label), "missing {label:?}");
    }
    // Every robot is labelled by its id at its start (ids 0..=11).
    let ids = (0..12)
        .filter(|id| svg.contains(&format!(">\n{id}\n</text>")))
        .count();
    assert_eq!(ids, 12);
    // No trace without --trace.
    assert!(!svg.contains("where it ended"));
    // Nothing half-written is left beside the picture.
    let names: Vec<_> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["arena.svg"]);
}

#[test]
fn trace_draws_paths_of_a_short_trial() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("trace.svg");
    let o = usar([
        "render",
        PAPER,
        "--out",
        text(&out),
        "--trace",
        "--method",
        "dis",
        "--trial",
        "1",
        "--duration",
        "5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    // 5 s sampled every 0.5 s, plus the start: 11 samples per robot.
    assert!(
        stdout.contains("trial 1 with dis over 5.0 s, 11 samples"),
        "{stdout}"
    );
    let svg = std::fs::read_to_string(&out).expect("SVG written");
    assert_svg(&svg);
    assert!(svg.contains("where it ended"));
    // One path per robot (and one polyline in the legend).
    assert!(svg.matches("<polyline").count() >= 12);
}

#[test]
fn a_missing_scenario_fails_with_its_path() {
    let dir = tempfile::tempdir().expect("temp dir");
    let missing = dir.path().join("no-such.ron");
    let out = dir.path().join("x.svg");
    let o = usar(["render", text(&missing), "--out", text(&out)]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.starts_with("error: ") && e.contains("no-such.ron: cannot read scenario file"),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn a_broken_scenario_prints_the_loaders_message() {
    let dir = tempfile::tempdir().expect("temp dir");
    let src = std::fs::read_to_string(PAPER).expect("paper.ron");
    let broken = src.replacen("duration_s: 600.0", "duration_s: -1.0", 1);
    assert_ne!(src, broken, "paper.ron sets mission.duration_s");
    let path = dir.path().join("broken.ron");
    std::fs::write(&path, broken).unwrap();
    let o = usar([
        "render",
        text(&path),
        "--out",
        text(&dir.path().join("x.svg")),
    ]);
    assert!(!o.status.success());
    let e = stderr(&o);
    // file:line:col: field: message
    let line = src
        .lines()
        .position(|l| l.contains("duration_s: 600.0"))
        .unwrap()
        + 1;
    assert!(e.contains(&format!("broken.ron:{line}:")), "{e}");
    assert!(e.contains("mission.duration_s"), "{e}");
}

#[test]
fn bad_options_are_reported() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("x.svg");
    let o = usar([
        "render",
        PAPER,
        "--out",
        text(&out),
        "--trace",
        "--method",
        "nope",
    ]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("--method") && e.contains("rne"), "{e}");
    // Trial options need --trace.
    let o = usar(["render", PAPER, "--out", text(&out), "--trial", "2"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--trace"), "{}", stderr(&o));
    assert!(!out.exists());
}

/// The `width` attribute of SVG document `svg`, pixels.
fn svg_width_px(svg: &str) -> f64 {
    let rest = &svg[svg.find("width=\"").expect("width") + 7..];
    rest[..rest.find('"').expect("closing quote")]
        .parse()
        .expect("a number")
}

#[test]
fn walls_kilometres_thick_do_not_shrink_the_arena_in_the_picture() {
    let dir = tempfile::tempdir().expect("temp dir");
    let src = std::fs::read_to_string(PAPER).expect("paper.ron");
    let thick = src.replacen("wall_thickness_m: 1.0", "wall_thickness_m: 10000.0", 1);
    assert_ne!(src, thick, "paper.ron's wall line moved");
    let thick_ron = dir.path().join("thick.ron");
    std::fs::write(&thick_ron, thick).expect("write");
    let mut widths = Vec::new();
    for (ron, svg) in [
        (PathBuf::from(PAPER), "paper.svg"),
        (thick_ron, "thick.svg"),
    ] {
        let out = dir.path().join(svg);
        let o = usar(["render", text(&ron), "--out", text(&out)]);
        assert!(o.status.success(), "{}", stderr(&o));
        let svg = std::fs::read_to_string(&out).expect("SVG written");
        assert_svg(&svg);
        widths.push(svg_width_px(&svg));
    }
    // The walls are drawn at most 8 m thick (a tenth of 80 m): the picture keeps its size.
    assert!(
        (widths[1] / widths[0] - 1.0).abs() < 0.2,
        "{} px against {} px",
        widths[1],
        widths[0]
    );
}

/// A full device: the error names its flag and the file once, on one line (it said "writing
/// /dev/full: writing /dev/full: ..."), for `render` and `replay` alike.
#[cfg(target_os = "linux")]
#[test]
fn a_full_device_is_named_once() {
    let full = Path::new("/dev/full");
    if !full.exists() {
        return;
    }
    for cmd in ["render", "replay"] {
        let o = usar([cmd, PAPER, "--out", "/dev/full"]);
        let err = stderr(&o);
        assert!(!o.status.success(), "{cmd}");
        assert_eq!(err.matches("/dev/full").count(), 1, "{cmd}: {err}");
        assert!(
            err.starts_with("error: --out: writing /dev/full: "),
            "{cmd}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{cmd}: {err}");
    }
}
