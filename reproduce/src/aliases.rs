//! The flags of earlier versions, kept as documented aliases of the subcommands:
//! `reproduce --check --paper kong2019` is `reproduce check --paper kong2019`,
//! `reproduce --infer jia2019:T2` is `reproduce infer jia2019:T2`, `--list --shard 2/4` is
//! `list --shard 2/4`. [`to_subcommand`] turns the one mode flag of an argument list into its
//! subcommand before clap parses it; the flag's values stay where they are and become the
//! subcommand's arguments. Two modes at once are refused ([`TwoModes`]), never silently one.
//! The aliases are deprecated: each one used is said on stderr ([`Alias::deprecation`]), and
//! they go in a later version.

use std::ffi::OsString;

/// An old mode flag and the subcommand it stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Alias {
    /// The old flag (`--check`).
    pub flag: &'static str,
    /// Its subcommand (`check`).
    pub subcommand: &'static str,
}

impl Alias {
    /// The line said on stderr when the old flag is used.
    pub fn deprecation(&self) -> String {
        format!(
            "warning: `{}` is deprecated and will be removed: write `reproduce {}` instead",
            self.flag, self.subcommand
        )
    }
}

/// (old flag, the subcommand it stands for).
const ALIASES: &[(&str, &str)] = &[
    ("--list", "list"),
    ("--check", "check"),
    ("--report-only", "report"),
    ("--explain-only", "explain"),
    ("--infer", "infer"),
    ("--shard", "shard"),
    ("--merge", "merge"),
    ("--robots", "robots"),
    ("--dof-cost", "cost"),
    ("--score", "score"),
];

/// The subcommand names (the modes of [`crate::options::Mode`]).
pub const SUBCOMMANDS: &[&str] = &[
    "run", "check", "report", "explain", "infer", "shard", "merge", "list", "robots", "cost",
    "score",
];

/// Two modes asked for at once (two old mode flags, or a subcommand and an old mode flag).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{first} and {second} are two modes: give one (`reproduce --help` lists them)")]
pub struct TwoModes {
    pub first: String,
    pub second: String,
}

/// Where in `args` (after the program, before a `--`) the old flag `flag` stands, alone or
/// as `flag=value`. An argument that is not UTF-8 is no flag.
fn position(args: &[OsString], flag: &str) -> Option<usize> {
    args.iter()
        .take_while(|a| *a != "--")
        .position(|a| {
            a.to_str().is_some_and(|a| {
                a == flag || a.strip_prefix(flag).is_some_and(|v| v.starts_with('='))
            })
        })
        .filter(|&i| i > 0)
}

/// The global options that take a value (`--root DIR`, ...) and the global flags: what may
/// stand before a subcommand (`crate::options::GlobalOptions`).
const GLOBAL_VALUED: [&str; 4] = ["--root", "--experiments-dir", "--results-dir", "--threads"];
const GLOBAL_FLAGS: [&str; 2] = ["--accept-edited", "--prune"];

/// Where the subcommand of `args` stands, past the global options before it (`reproduce
/// --root DIR list`), if one is given.
fn subcommand_at(args: &[OsString]) -> Option<usize> {
    let mut i = 1;
    while let Some(a) = args.get(i).and_then(|a| a.to_str()) {
        let name = a.split_once('=').map_or(a, |(name, _)| name);
        if GLOBAL_VALUED.contains(&a) {
            i += 2;
        } else if GLOBAL_VALUED.contains(&name) || GLOBAL_FLAGS.contains(&a) {
            i += 1;
        } else {
            return SUBCOMMANDS.contains(&a).then_some(i);
        }
    }
    None
}

/// The arguments with an old mode flag replaced by its subcommand, written first (`args[0]` is
/// the program), and the alias used if one was. `--shard` beside `--list` or the `list`
/// subcommand is the list's option (`list --shard 2/4`, `--root DIR list --shard 2/4`,
/// `--list --shard 2/4`), not the shard mode.
pub fn to_subcommand(mut args: Vec<OsString>) -> Result<(Vec<OsString>, Option<Alias>), TwoModes> {
    let given = subcommand_at(&args);
    let listing = position(&args, "--list").is_some() || given.is_some_and(|i| args[i] == "list");
    let found: Vec<(usize, &str, &str)> = ALIASES
        .iter()
        .filter_map(|(flag, sub)| position(&args, flag).map(|i| (i, *flag, *sub)))
        .filter(|(_, flag, _)| !(*flag == "--shard" && listing))
        .collect();
    let Some(&(at, flag, sub)) = found.first() else {
        return Ok((args, None));
    };
    if let Some((_, second, _)) = found.get(1) {
        return Err(TwoModes {
            first: flag.to_string(),
            second: second.to_string(),
        });
    }
    if let Some(given) = given {
        return Err(TwoModes {
            first: args[given].to_string_lossy().into_owned(),
            second: flag.to_string(),
        });
    }
    // `position` matched the flag, so the argument is UTF-8.
    match args[at].to_str().and_then(|a| a.split_once('=')) {
        Some((_, value)) => args[at] = value.into(),
        None => {
            args.remove(at);
        }
    }
    args.insert(1, sub.into());
    Ok((
        args,
        Some(Alias {
            flag,
            subcommand: sub,
        }),
    ))
}

/// The aliases, for `--help`.
pub fn help() -> String {
    let mut out = String::from(
        "Old flags, still accepted but deprecated (each stands for its subcommand):\n",
    );
    for (flag, sub) in ALIASES {
        out.push_str(&format!("  {flag:<15} {sub}\n"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<OsString> {
        s.split_whitespace().map(OsString::from).collect()
    }

    #[test]
    fn old_flags_become_their_subcommands_wherever_they_stand() {
        let to = |s: &str| to_subcommand(args(s)).unwrap().0;
        assert_eq!(to("r --check --paper x"), args("r check --paper x"));
        assert_eq!(to("r --paper x --check"), args("r check --paper x"));
        assert_eq!(to("r --infer jia2019:T2"), args("r infer jia2019:T2"));
        assert_eq!(to("r --infer=jia2019:T2"), args("r infer jia2019:T2"));
        assert_eq!(to("r --shard"), args("r shard"));
        assert_eq!(to("r --root p --shard 2/4"), args("r shard --root p 2/4"));
        assert_eq!(to("r --list --shard 2/4"), args("r list --shard 2/4"));
        assert_eq!(to("r list --shard 2/4"), args("r list --shard 2/4"));
        assert_eq!(to("r list --shard=2/4"), args("r list --shard=2/4"));
        assert_eq!(
            to("r --root p --threads=2 list --shard 2/4"),
            args("r --root p --threads=2 list --shard 2/4")
        );
        assert_eq!(
            to("r --score f.csv --task e/v"),
            args("r score f.csv --task e/v")
        );
        assert_eq!(to("r --merge a b"), args("r merge a b"));
        assert_eq!(to("r check --paper x"), args("r check --paper x"));
        assert_eq!(to("r"), args("r"));
        // A value that spells a subcommand is left alone, and so is what follows `--`.
        assert_eq!(to("r --paper list"), args("r --paper list"));
        assert_eq!(to("r -- --check"), args("r -- --check"));
    }

    #[test]
    fn two_modes_are_refused_naming_both() {
        let err = to_subcommand(args("r --list --robots")).unwrap_err();
        assert_eq!(
            (err.first.as_str(), err.second.as_str()),
            ("--list", "--robots")
        );
        let err = to_subcommand(args("r merge a --check")).unwrap_err();
        assert_eq!(
            (err.first.as_str(), err.second.as_str()),
            ("merge", "--check")
        );
        let err = to_subcommand(args("r --root p merge a --check")).unwrap_err();
        assert_eq!(
            (err.first.as_str(), err.second.as_str()),
            ("merge", "--check")
        );
        assert!(help().contains("--dof-cost") && help().contains("cost"));
    }

    #[test]
    fn the_alias_used_is_named_for_its_deprecation_line() {
        let (_, alias) = to_subcommand(args("r --paper x --check")).unwrap();
        let alias = alias.unwrap();
        assert_eq!((alias.flag, alias.subcommand), ("--check", "check"));
        assert_eq!(
            alias.deprecation(),
            "warning: `--check` is deprecated and will be removed: write `reproduce check` instead"
        );
        assert_eq!(to_subcommand(args("r check --paper x")).unwrap().1, None);
        // `--shard` beside `--list` is the list's own option, not an alias.
        let (_, alias) = to_subcommand(args("r --list --shard 2/4")).unwrap();
        assert_eq!(alias.map(|a| a.flag), Some("--list"));
    }

    #[test]
    fn an_argument_that_is_not_utf8_passes_through_untouched() {
        use std::os::unix::ffi::OsStringExt;
        let odd = OsString::from_vec(vec![b'-', b'-', 0xff]);
        let given = vec!["r".into(), "--check".into(), odd.clone()];
        let (out, _) = to_subcommand(given).unwrap();
        assert_eq!(out, vec![OsString::from("r"), "check".into(), odd]);
    }
}
