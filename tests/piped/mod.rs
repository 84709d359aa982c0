//! Running the `hairmath` binary with a standard input (the tests of the commands that read
//! CSV from it: `eval`, `check`).

use std::io::Write;
use std::process::{Command, Output, Stdio};

/// Runs `hairmath` with `args`, writes `stdin` to its standard input and waits for it.
pub fn hairmath_piped(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let mut input = child.stdin.take().expect("stdin is piped");
    // The tool may exit before reading everything (argument errors): ignore a broken pipe.
    let _ = input.write_all(stdin.as_bytes());
    drop(input);
    child.wait_with_output().expect("the binary runs")
}
