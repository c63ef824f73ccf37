//! `cargo run --release -p driftbench-benches --bin telemetry`: renders `benches/REPORT.md`,
//! the suite's measurements of itself, from `benches/results/`
//! (`driftbench_benches::telemetry`). Exit code 2 on a file it cannot read or write.

use std::process::ExitCode;

fn main() -> ExitCode {
    let root = match catalog::root_from_current_dir() {
        Ok(root) => root,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    match driftbench_benches::telemetry::page::write(&root) {
        Ok(path) => {
            eprintln!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
