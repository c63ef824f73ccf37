//! Subcommands: `reproduce run | check | report | explain | infer | shard | merge | list | robots
//! | cost | score`, each the name of one mode of the binary.
//!
//! A subcommand is the flag of its mode written first (`reproduce check --paper kong2019` is
//! `reproduce --check --paper kong2019`; `reproduce infer jia2019:T2` is
//! `reproduce --infer jia2019:T2`). [`to_flags`] rewrites the arguments once, before they are
//! parsed, so every check of the flags (conflicts, required values) applies to both spellings,
//! and the flags of earlier versions keep working.

/// (subcommand, the flag it stands for, what it does).
pub const COMMANDS: &[(&str, Option<&str>, &str)] = &[
    (
        "run",
        None,
        "run the selected experiments, the explanation layer and the report (the default)",
    ),
    (
        "check",
        Some("--check"),
        "the regression gate against git HEAD's results/runs.csv (or --baseline)",
    ),
    (
        "report",
        Some("--report-only"),
        "re-render report/ from the stored results",
    ),
    (
        "explain",
        Some("--explain-only"),
        "only the tolerance ladders and drift attribution of the selection",
    ),
    (
        "infer",
        Some("--infer"),
        "setup inference of TABLE: `all`, a paper or PAPER:T2",
    ),
    (
        "shard",
        Some("--shard"),
        "run shard K/N of the selection (`auto`: from Slurm or Kubernetes)",
    ),
    (
        "merge",
        Some("--merge"),
        "merge finished shard directories DIR... into results/",
    ),
    (
        "list",
        Some("--list"),
        "list the experiments and their runs (keys and labels)",
    ),
    (
        "robots",
        Some("--robots"),
        "list the robots with their check values",
    ),
    (
        "cost",
        Some("--dof-cost"),
        "cost against the number of joints (results/dof-cost.csv)",
    ),
    (
        "score",
        Some("--score"),
        "score a trajectory FILE (CSV or MAT) on --task EXPERIMENT/VARIANT",
    ),
];

/// The arguments with a leading subcommand replaced by its flag (`args[0]` is the program).
pub fn to_flags(mut args: Vec<String>) -> Vec<String> {
    let Some(first) = args.get(1) else {
        return args;
    };
    if let Some((_, flag, _)) = COMMANDS.iter().find(|(name, _, _)| name == first) {
        match flag {
            Some(flag) => args[1] = flag.to_string(),
            None => {
                args.remove(1);
            }
        }
    }
    args
}

/// The subcommands, for `--help`.
pub fn help() -> String {
    let mut out = String::from("Commands (each is the flag of its mode written first):\n");
    for (name, flag, what) in COMMANDS {
        let alias = flag.map_or(String::new(), |f| format!(" [{f}]"));
        out.push_str(&format!("  {name:<8} {what}{alias}\n"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn subcommands_become_their_flags_and_flags_stay() {
        assert_eq!(
            to_flags(args("r check --paper x")),
            args("r --check --paper x")
        );
        assert_eq!(
            to_flags(args("r infer jia2019:T2")),
            args("r --infer jia2019:T2")
        );
        assert_eq!(to_flags(args("r shard")), args("r --shard"));
        assert_eq!(to_flags(args("r run --paper x")), args("r --paper x"));
        assert_eq!(
            to_flags(args("r score f.csv --task e/v")),
            args("r --score f.csv --task e/v")
        );
        assert_eq!(to_flags(args("r --check")), args("r --check"));
        assert_eq!(to_flags(args("r")), args("r"));
        // Only the first argument is a subcommand: a value that spells one is left alone.
        assert_eq!(to_flags(args("r --paper list")), args("r --paper list"));
        assert!(help().contains("check") && help().contains("[--dof-cost]"));
    }
}
