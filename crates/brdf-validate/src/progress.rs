//! Progress bar: shown on a terminal, hidden when `CI=true` or stderr is not a TTY.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar of `len` steps with a message; hidden in CI or when not on a terminal.
pub fn bar(len: u64, msg: &str) -> ProgressBar {
    let hidden = std::env::var("CI").map(|v| v == "true").unwrap_or(false)
        || !std::io::stderr().is_terminal();
    let pb = ProgressBar::with_draw_target(
        Some(len),
        if hidden {
            ProgressDrawTarget::hidden()
        } else {
            ProgressDrawTarget::stderr()
        },
    );
    if let Ok(style) =
        ProgressStyle::with_template("{msg:28} [{bar:40}] {pos}/{len} ({elapsed}, eta {eta})")
    {
        pb.set_style(style.progress_chars("=> "));
    }
    pb.set_message(msg.to_string());
    pb
}
