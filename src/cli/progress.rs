//! Progress bars on stderr (hidden when stderr is not a terminal, with `-q` or `--no-progress`).

use super::GlobalArgs;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar counting to `total`.
pub fn bar(global: &GlobalArgs, total: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(total);
    if global.quiet > 0 || global.no_progress {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    bar.set_style(
        ProgressStyle::with_template("{msg} {wide_bar} {pos}/{len} [{elapsed_precise}, ETA {eta}]")
            .expect("the template is valid"),
    );
    bar.set_message(what.to_string());
    bar
}
