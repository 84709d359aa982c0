//! Issue 16, item 5: the long commands draw progress bars on standard error only when it is a
//! terminal. With standard error piped (CI logs, `2> file`) it carries no bar, no escape code
//! and no carriage return: checked here for `lut` (every kind, with its error points), `fit`
//! and `bake --compare`, and for `report`, `models`, `plan`, `bake` and `render-gerard` by
//! `common::hairmath`, which every run of tests/cli_report.rs, cli_models.rs, cli_plan.rs
//! and cli_strands.rs goes through. On a terminal (a pseudo-terminal made by util-linux's
//! `script`), the bar is drawn.

#[allow(dead_code)] // its JSON helpers serve the other command-line tests
mod common;

use common::{assert_no_progress, hairmath};
use std::path::PathBuf;
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("hairmath-progress-{}-{name}", std::process::id()))
}

#[test]
fn piped_stderr_carries_no_progress_bar() {
    let dir = scratch("lut");
    let dir_arg = dir.to_string_lossy().into_owned();
    for (kind, size) in [
        ("nguyen-m", "64,64"),
        ("nguyen-n", "64,64"),
        ("gerard", "64,32"),
        ("far-field", "16,8,4"),
    ] {
        // `hairmath` asserts success and no progress on the piped stderr.
        let printed = hairmath(&["lut", "--kind", kind, "--size", size, "--out", &dir_arg]);
        assert!(printed.contains("lookup vs direct"), "{printed}");
    }
    hairmath(&["fit"]);
    let hair = scratch("groom.hair");
    let hair_arg = hair.to_string_lossy().into_owned();
    hairmath(&[
        "groom",
        "--kind",
        "curly",
        "--strands",
        "20",
        "--points",
        "8",
        "--out",
        &hair_arg,
    ]);
    let bake_dir = scratch("bake");
    let printed = hairmath(&[
        "bake",
        &hair_arg,
        "--compare",
        "--directions",
        "256",
        "--first-strands",
        "4",
        "--out",
        &bake_dir.to_string_lossy(),
    ]);
    assert!(printed.contains("against the exact baker"), "{printed}");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&bake_dir);
    let _ = std::fs::remove_file(&hair);
}

/// The check itself finds a bar: what a terminal receives fails it.
#[test]
fn the_check_finds_a_drawn_bar() {
    let drawn = "\r\x1b[2Kbaking (samples) [=====>     ] 2048/4096, 0s (eta 0s)";
    let caught = std::panic::catch_unwind(|| assert_no_progress(&["lut"], drawn));
    assert!(caught.is_err());
    assert_no_progress(
        &["lut"],
        "hairmath: error: invalid parameters: eta = 0.5 ...\n",
    );
}

/// On a terminal the bar is drawn: `lut` run by `script` in a pseudo-terminal (standard output
/// to a file, so that what the terminal receives is standard error). Skipped where `script`
/// (util-linux) does not run.
#[test]
fn a_terminal_gets_the_bar() {
    let dir = scratch("tty");
    std::fs::create_dir_all(&dir).unwrap();
    let command = format!(
        "{} lut --kind far-field --size 16,8,8 --error-points 0 --out '{}' > '{}'",
        env!("CARGO_BIN_EXE_hairmath"),
        dir.display(),
        dir.join("stdout.txt").display()
    );
    let Ok(o) = Command::new("script")
        .args(["-qec", &command, "/dev/null"])
        .output()
    else {
        eprintln!("skipped: util-linux's `script` is not available");
        return;
    };
    let terminal = String::from_utf8_lossy(&o.stdout);
    if !o.status.success() {
        // `script` without a pseudo-terminal to make fails before running the command.
        assert!(!terminal.contains("hairmath"), "{terminal:?}");
        eprintln!(
            "skipped: `script` failed: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        return;
    }
    assert!(
        terminal.contains("baking (samples) [") && terminal.contains("/1024"),
        "{terminal:?}"
    );
    let printed = std::fs::read_to_string(dir.join("stdout.txt")).unwrap();
    assert!(printed.starts_with("wrote "), "{printed:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
