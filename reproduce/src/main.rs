//! `cargo run --release -p reproduce`: runs driftbench's experiments and writes `results/`.
//! Wiring only: the logic is the library (`reproduce::run`); the exit code is the outcome's
//! (`reproduce::Exit`, docs/reference/exit-codes.md).

use clap::error::ErrorKind;
use reproduce::Cli;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match Cli::parse_from_args(std::env::args_os().collect()) {
        Ok(cli) => cli,
        Err(e) => match e.kind() {
            ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => e.exit(),
            _ => {
                eprint!("{}", Cli::shown_error(&e));
                std::process::exit(e.exit_code())
            }
        },
    };
    let (global, mode) = cli.into_parts();
    match reproduce::run(&global, mode) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit().into()
        }
    }
}
