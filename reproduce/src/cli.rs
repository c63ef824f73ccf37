//! The command line: clap parses it into the global options and one [`Mode`] with its options
//! ([`crate::options`]), every id, shard and table typed at this boundary (a malformed one is
//! clap's usage error, exit 2). Nothing here runs: [`crate::run`](fn@crate::run) takes what
//! [`Cli`] parsed.

use crate::options::{GlobalOptions, Mode, RunOptions};
use clap::error::ErrorKind;
use clap::{CommandFactory, FromArgMatches, Parser};
use std::ffi::OsString;

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
    long_about,
    after_help = OLD_FLAGS
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

/// The line of `--help` after the options: where the mode flags of earlier versions went.
const OLD_FLAGS: &str = "The subcommands replaced the mode flags of earlier versions: \
`--check` is `reproduce check`, `--list` `list`, `--report-only` `report`, `--explain-only` \
`explain`, `--infer` `infer`, `--shard` `shard`, `--merge` `merge`, `--robots` `robots`, \
`--dof-cost` `cost` and `--score` `score`.";

impl Cli {
    /// Parses the program's arguments (`args[0]` is the program; `std::env::args_os`). An
    /// argument that is not UTF-8 is taken where a path is expected and refused elsewhere. A
    /// clap error (an unknown option such as an old mode flag, a malformed id, a value that is
    /// not UTF-8, `--help`, `--version`) is returned for the caller to print and exit with.
    pub fn parse_from_args(args: Vec<OsString>) -> Result<Self, clap::Error> {
        let mut command = Self::command();
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

    /// A clap error of [`Cli::parse_from_args`] as the program prints it (`--help` and
    /// `--version` aside, which clap prints itself): clap quotes the argument at fault as it was
    /// given (in single quotes, its escape sequences taken out, its line breaks and other
    /// control characters left in), so each argument it quotes is shown as every error shows a
    /// text instead ([`settings::shown`]: escaped, cut), and any other control or format
    /// character is escaped; clap's own lines are kept, without its colours.
    pub fn shown_error(e: &clap::Error) -> String {
        use clap::builder::StyledStr;
        use clap::error::ContextValue;
        // Plain text: clap's styles and the escape sequences of the arguments taken out.
        let mut text = e.render().to_string();
        for (_, value) in e.context() {
            let given: Vec<&str> = match value {
                ContextValue::String(s) => vec![s.as_str()],
                ContextValue::Strings(v) => v.iter().map(String::as_str).collect(),
                _ => Vec::new(),
            };
            for raw in given {
                let shown = settings::shown(raw).to_string();
                if raw.is_empty() || shown == format!("\"{raw}\"") {
                    continue;
                }
                // The argument as the plain text quotes it.
                let plain = StyledStr::from(raw.to_owned()).to_string();
                text = text.replace(&format!("'{plain}'"), &shown);
            }
        }
        text.chars()
            .map(|c| match c {
                '\n' => c.to_string(),
                c if settings::is_control_or_format(c) => c.escape_debug().collect(),
                c => c.to_string(),
            })
            .collect()
    }

    /// The global options and the mode (`run` with the top-level options when none was named).
    pub fn into_parts(self) -> (GlobalOptions, Mode) {
        (self.global, self.mode.unwrap_or(Mode::Run(self.run)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::{CheckOptions, InferOptions, ScoreOptions, SelectionOptions, ShardSpec};
    use std::path::PathBuf;

    fn parse(line: &str) -> Result<(GlobalOptions, Mode), clap::Error> {
        Cli::parse_from_args(line.split_whitespace().map(OsString::from).collect())
            .map(Cli::into_parts)
    }

    #[test]
    fn subcommands_parse_into_their_modes() {
        assert_eq!(
            parse("reproduce check --paper kong2019 --exact-only")
                .unwrap()
                .1,
            Mode::Check(CheckOptions {
                selection: SelectionOptions {
                    paper: Some("kong2019".parse().unwrap()),
                    experiment: vec![],
                    exact_only: true,
                },
                baseline: None,
            })
        );
        assert_eq!(
            parse("reproduce infer jia2019:T2").unwrap().1,
            Mode::Infer(InferOptions {
                table: "jia2019:T2".parse().unwrap(),
                dry_run: false
            })
        );
        assert!(
            matches!(parse("reproduce shard").unwrap().1, Mode::Shard(s) if s.shard == ShardSpec::Auto)
        );
        // A merge renders the report unless told not to (either spelling).
        for (line, no_report) in [
            ("reproduce merge a b", false),
            ("reproduce merge a b --no-report", true),
            ("reproduce merge --skip-report a b", true),
        ] {
            let Mode::Merge(m) = parse(line).unwrap().1 else {
                panic!("{line}: not a merge");
            };
            assert_eq!((m.dirs.len(), m.no_report), (2, no_report), "{line}");
        }
        assert!(
            matches!(parse("reproduce --paper x").unwrap().1, Mode::Run(r) if r.selection.paper.as_deref() == Some("x"))
        );
    }

    #[test]
    fn the_old_mode_flags_are_unknown_and_help_names_their_subcommands() {
        for flag in [
            "--check",
            "--list",
            "--report-only",
            "--explain-only",
            "--infer",
            "--shard",
            "--merge",
            "--robots",
            "--dof-cost",
            "--score",
        ] {
            let line = format!("reproduce {flag} x");
            let err = parse(&line).unwrap_err();
            assert_eq!(err.kind(), ErrorKind::UnknownArgument, "{line}");
            assert!(OLD_FLAGS.contains(&format!("`{flag}`")), "{flag}");
        }
        let help = Cli::command().render_long_help().to_string();
        assert!(
            help.contains("The subcommands replaced the mode flags of earlier versions"),
            "{help}"
        );
        // `--shard K/N` is still an option of `list`.
        assert!(parse("reproduce list --shard 1/2").is_ok());
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
                task: spec::TaskKey::parse("e/v").unwrap(),
                columns: None,
                name: "trajectory".into(),
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
            kind("reproduce merge a --dry-run"),
            Some(ErrorKind::UnknownArgument)
        );
        assert_eq!(
            kind("reproduce list robots"),
            Some(ErrorKind::UnknownArgument)
        );
        assert_eq!(kind("reproduce cost 1/2"), Some(ErrorKind::UnknownArgument));
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

    #[test]
    fn ids_are_parsed_at_the_command_line_naming_the_valid_form() {
        let refused = |line: &str| {
            let e = parse(line).unwrap_err();
            (e.kind(), e.to_string())
        };
        let (kind, msg) = refused("reproduce --paper Kong2019");
        assert_eq!(kind, ErrorKind::ValueValidation);
        assert!(
            msg.contains("paper id \"Kong2019\" is not a slug") && msg.contains("\"kong2019\""),
            "{msg}"
        );
        let (kind, msg) = refused("reproduce list --experiment ../x");
        assert_eq!(kind, ErrorKind::ValueValidation);
        assert!(msg.contains("experiment id \"../x\""), "{msg}");
        let (kind, msg) = refused("reproduce shard 3/2");
        assert_eq!(kind, ErrorKind::ValueValidation);
        assert!(
            msg.contains("K must be in 1..=2") && msg.contains("or `auto`"),
            "{msg}"
        );
        let (kind, msg) = refused("reproduce list --shard x");
        assert_eq!(kind, ErrorKind::ValueValidation);
        assert!(
            msg.contains("expected K/N") && msg.contains("or `auto`"),
            "{msg}"
        );
        let (kind, msg) = refused("reproduce score f.csv --task just-one");
        assert_eq!(kind, ErrorKind::ValueValidation);
        assert!(msg.contains("just-one"), "{msg}");
        for (line, want) in [
            (
                "reproduce infer Jia2019",
                "paper id \"Jia2019\" is not a slug",
            ),
            ("reproduce infer jia2019:", "expected `all`, a paper"),
            ("reproduce infer all,,x", "expected `all`, a paper"),
            ("reproduce infer ../x:T2", "paper id \"../x\""),
        ] {
            let (kind, msg) = refused(line);
            assert_eq!(kind, ErrorKind::ValueValidation, "{line}");
            assert!(msg.contains(want), "{line}: {msg}");
        }
        let Mode::Infer(o) = parse("reproduce infer jia2019:T2,kong2019,all").unwrap().1 else {
            panic!("not infer");
        };
        assert_eq!(o.table.to_string(), "jia2019:T2,kong2019,all");
        assert!(matches!(
            parse("reproduce list --shard 2/4").unwrap().1,
            Mode::List(l) if l.shard == Some(ShardSpec::Given(store::shard::Shard::new(2, 4).unwrap()))
        ));
    }
}
