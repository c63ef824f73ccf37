//! The command line: clap parses it into the global options and one [`Mode`] with its options
//! ([`crate::options`]); the old mode flags are aliases of the subcommands
//! ([`crate::aliases`]). Nothing here runs: [`crate::run`](fn@crate::run) takes what [`Cli`]
//! parsed.

use crate::aliases;
use crate::options::{GlobalOptions, Mode, RunOptions};
use clap::error::ErrorKind;
use clap::{CommandFactory, FromArgMatches, Parser};

/// Regenerates the tables and error data of the papers on drift-free redundancy resolution
/// in papers/ (jia2019, zhang2018, zhong2021, kong2019, robio2018, and any paper added as
/// data), solving every scheme's QP exactly along every run and scoring each paper's neural
/// or numerical solver against that optimum.
///
/// With no subcommand (or `run`): runs every experiment in experiments/*.toml (in parallel),
/// writes results/runs.csv (one row per run) and results/traces/, the explanation layer and
/// report/, and prints a summary table. The global options go before or after the subcommand.
#[derive(Parser, Debug)]
#[command(
    name = "reproduce",
    version = concat!(env!("CARGO_PKG_VERSION"), " (revision ", env!("DRIFTBENCH_REVISION"), ")"),
    about,
    long_about
)]
pub struct Cli {
    #[command(flatten)]
    pub global: GlobalOptions,
    /// The mode; none is `run`, with the options given here.
    #[command(subcommand)]
    pub mode: Option<Mode>,
    /// The options of `run` written without the subcommand.
    #[command(flatten)]
    pub run: RunOptions,
}

impl Cli {
    /// Parses the program's arguments (`args[0]` is the program), the old mode flags read as
    /// their subcommands. A clap error (an unknown option, two modes, `--help`, `--version`)
    /// is returned for the caller to print and exit with.
    pub fn parse_from_args(args: Vec<String>) -> Result<Self, clap::Error> {
        let mut command = Self::command().after_help(aliases::help());
        let args = aliases::to_subcommand(args)
            .map_err(|e| command.error(ErrorKind::ArgumentConflict, e.to_string()))?;
        let matches = command.try_get_matches_from_mut(args)?;
        let cli = Self::from_arg_matches(&matches).map_err(|e| e.format(&mut command))?;
        match (&cli.mode, &cli.run) {
            (Some(_), run) if *run != RunOptions::default() => {
                let name = matches.subcommand_name().unwrap_or("the subcommand");
                Err(command.error(
                    ErrorKind::ArgumentConflict,
                    format!(
                        "a mode's own options go after its subcommand: write `reproduce {name} \
                         [OPTIONS]` (only --root, --experiments-dir, --results-dir, --threads, \
                         --accept-edited and --prune go anywhere)"
                    ),
                ))
            }
            _ => Ok(cli),
        }
    }

    /// The global options and the mode (`run` with the top-level options when none was named).
    pub fn into_parts(self) -> (GlobalOptions, Mode) {
        (self.global, self.mode.unwrap_or(Mode::Run(self.run)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::{CheckOptions, InferOptions, ScoreOptions, SelectionOptions};
    use std::path::PathBuf;

    fn parse(line: &str) -> Result<(GlobalOptions, Mode), clap::Error> {
        Cli::parse_from_args(line.split_whitespace().map(String::from).collect())
            .map(Cli::into_parts)
    }

    #[test]
    fn a_subcommand_and_its_old_flag_parse_alike() {
        let check = Mode::Check(CheckOptions {
            selection: SelectionOptions {
                paper: Some("kong2019".into()),
                experiment: vec![],
                exact_only: true,
            },
            baseline: None,
        });
        for line in [
            "reproduce check --paper kong2019 --exact-only",
            "reproduce --check --paper kong2019 --exact-only",
            "reproduce --paper kong2019 --exact-only --check",
        ] {
            assert_eq!(parse(line).unwrap().1, check, "{line}");
        }
        assert_eq!(
            parse("reproduce infer jia2019:T2").unwrap().1,
            Mode::Infer(InferOptions {
                table: "jia2019:T2".into(),
                dry_run: false
            })
        );
        assert!(matches!(parse("reproduce shard").unwrap().1, Mode::Shard(s) if s.shard == "auto"));
        assert!(
            matches!(parse("reproduce --paper x").unwrap().1, Mode::Run(r) if r.selection.paper.as_deref() == Some("x"))
        );
    }

    #[test]
    fn global_options_go_before_or_after_the_subcommand() {
        let score = |line: &str| parse(line).unwrap();
        let want = (
            GlobalOptions {
                root: Some(PathBuf::from("/p")),
                threads: Some(2),
                ..GlobalOptions::default()
            },
            Mode::Score(ScoreOptions {
                file: PathBuf::from("f.csv"),
                task: "e/v".into(),
                columns: None,
                out: PathBuf::from("scores"),
            }),
        );
        assert_eq!(
            score("reproduce --root /p --threads 2 score f.csv --task e/v"),
            want
        );
        assert_eq!(
            score("reproduce score f.csv --task e/v --root /p --threads 2"),
            want
        );
        assert_eq!(
            score("reproduce --root /p score --threads 2 f.csv --task e/v"),
            want
        );
        for line in ["reproduce --root /p check", "reproduce --root /p list"] {
            assert_eq!(
                parse(line).unwrap().0.root,
                Some(PathBuf::from("/p")),
                "{line}"
            );
        }
    }

    #[test]
    fn wrong_and_incomplete_options_are_refused_by_kind() {
        let kind = |line: &str| parse(line).err().map(|e| e.kind());
        assert_eq!(
            kind("reproduce report --paper jia2019"),
            Some(ErrorKind::UnknownArgument)
        );
        assert_eq!(
            kind("reproduce merge a --check"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(
            kind("reproduce --list --robots"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(kind("reproduce cost 1/2"), Some(ErrorKind::UnknownArgument));
        assert_eq!(
            kind("reproduce --skip-explain --explain-only"),
            Some(ErrorKind::UnknownArgument)
        );
        assert_eq!(
            kind("reproduce --baseline b.csv"),
            Some(ErrorKind::UnknownArgument)
        );
        assert_eq!(
            kind("reproduce score f.csv"),
            Some(ErrorKind::MissingRequiredArgument)
        );
        assert_eq!(
            kind("reproduce merge"),
            Some(ErrorKind::MissingRequiredArgument)
        );
        assert_eq!(
            kind("reproduce --threads 0"),
            Some(ErrorKind::ValueValidation)
        );
        assert_eq!(
            kind("reproduce --paper x check"),
            Some(ErrorKind::ArgumentConflict)
        );
        assert_eq!(kind("reproduce check --baseline b.csv"), None);
    }
}
