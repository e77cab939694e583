//! `shade-sim`: parse the command line, run the command, map the outcome to an exit code
//! (0 ok, 1 found something, e.g. violations; 2 error with one line `error: <file>: <what>`).

use std::process::ExitCode;

fn main() -> ExitCode {
    shade_sim::tune_allocator_for_tensors();
    let cli = cli::parse_args();
    cli::init_logging(&cli.global);
    cli::quiet_panics();
    // Batch commands name the input a panic came from; this catches any other.
    let outcome = std::panic::catch_unwind(|| cli::run(cli)).unwrap_or_else(|payload| {
        Err(anyhow::anyhow!(
            "internal error: {} (a bug: please report it with the input)",
            cli::panic_message(payload.as_ref())
        ))
    });
    match outcome {
        Ok(status) => status.into(),
        Err(e) => {
            eprintln!("error: {}", cli::one_line(&e));
            cli::ExitStatus::Error.into()
        }
    }
}

mod cli;
