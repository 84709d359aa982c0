//! Progress bars on standard error for the long commands, in one style, drawn only when
//! standard error is a terminal: redirected to a file, a pipe or a CI log, standard error
//! carries nothing but errors and notes. The library reports `done of total` through plain
//! callbacks (`&(dyn Fn(usize, usize) + Sync)`) and knows nothing of this module: it computes,
//! the command line draws.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::borrow::Cow;
use std::io::IsTerminal;

/// The template of every bar: what is being done, the bar, how far, the time taken and left.
const TEMPLATE: &str = "{msg} [{wide_bar}] {pos}/{len}, {elapsed} (eta {eta})";

/// Where bars draw: standard error when `terminal` (standard error is a terminal), else
/// nowhere.
pub fn draw_target(terminal: bool) -> ProgressDrawTarget {
    if terminal {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    }
}

/// A bar saying `message`, of length 0 until [`update`] (or the caller) sets it, drawn on
/// standard error only if it is a terminal ([`draw_target`]). End it with
/// `finish_and_clear`.
pub fn bar(message: impl Into<Cow<'static, str>>) -> ProgressBar {
    // Styled while hidden, so that nothing is drawn before the first update gives a length.
    let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template(TEMPLATE)
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(message);
    bar.set_draw_target(draw_target(std::io::stderr().is_terminal()));
    bar
}

/// Moves `bar` to `done` of `total`. Callbacks the library calls from several threads may
/// arrive out of order: the bar never moves back.
pub fn update(bar: &ProgressBar, done: usize, total: usize) {
    bar.set_length(total as u64);
    if done as u64 > bar.position() {
        bar.set_position(done as u64);
    }
}

/// The `done of total` callback of `bar`, for the library's progress hooks ([`update`]).
pub fn callback(bar: &ProgressBar) -> impl Fn(usize, usize) + Sync + '_ {
    move |done, total| update(bar, done, total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_are_hidden_off_a_terminal() {
        assert!(draw_target(false).is_hidden());
        let bar = ProgressBar::with_draw_target(Some(10), draw_target(false));
        assert!(bar.is_hidden());
    }

    #[test]
    fn update_sets_the_length_and_never_moves_back() {
        let bar = ProgressBar::with_draw_target(Some(0), draw_target(false));
        let progress = callback(&bar);
        progress(3, 10);
        assert_eq!((bar.position(), bar.length()), (3, Some(10)));
        progress(2, 10);
        assert_eq!(bar.position(), 3);
        progress(10, 10);
        assert_eq!(bar.position(), 10);
    }
}
