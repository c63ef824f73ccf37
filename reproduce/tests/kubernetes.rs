//! The Kubernetes recipe of docs/kubernetes/ against the rules of the Kubernetes API it relies on
//! (the API server's validation of batch/v1 Job, pkg/apis/batch/validation, and of v1
//! PersistentVolumeClaim, pkg/apis/core/validation) and the project's own: the shards' Job (N
//! written twice must agree; threads from the CPU request; the memory request the docs state),
//! the volume (ReadWriteMany), the Job that fills it with a clone at a revision, the merge Job
//! (N a third time), every pod mounting the volume's claim at the root it runs in, and the
//! minimum Kubernetes version the docs state (the newest of the fields' versions). The manifest is read by a small parser of the YAML subset it is written in (block
//! mappings and sequences, flow sequences and mappings of scalars, quoted and plain scalars,
//! comments); anything else in it is a test failure, not a guess.

use crate::common;

use std::collections::HashSet;

#[derive(Clone, Debug, PartialEq)]
enum Yaml {
    Map(Vec<(String, Yaml)>),
    Seq(Vec<Yaml>),
    Str(String),
}

impl Yaml {
    /// The value at a dotted path of mapping keys.
    fn at(&self, path: &str) -> Option<&Yaml> {
        path.split('.').try_fold(self, |node, key| match node {
            Yaml::Map(entries) => entries.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        })
    }

    fn str_at(&self, path: &str) -> Option<&str> {
        match self.at(path)? {
            Yaml::Str(s) => Some(s),
            _ => None,
        }
    }

    fn seq_at(&self, path: &str) -> &[Yaml] {
        match self.at(path) {
            Some(Yaml::Seq(items)) => items,
            _ => &[],
        }
    }

    fn int_at(&self, path: &str) -> Option<i64> {
        self.str_at(path)?.parse().ok()
    }
}

/// `text` without its comment (a `#` outside quotes, at the start or after a space).
fn strip_comment(text: &str) -> &str {
    let (mut quote, mut prev) = (None, ' ');
    for (i, c) in text.char_indices() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c == '#' && prev.is_whitespace() => return &text[..i],
            None => {}
        }
        prev = c;
    }
    text
}

/// Splits `text` at `sep` outside quotes.
fn split_outside_quotes(text: &str, sep: char) -> Vec<&str> {
    let (mut quote, mut start, mut out) = (None, 0, Vec::new());
    for (i, c) in text.char_indices() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => {}
            None if c == '"' || c == '\'' => quote = Some(c),
            None if c == sep => {
                out.push(&text[start..i]);
                start = i + 1;
            }
            None => {}
        }
    }
    out.push(&text[start..]);
    out
}

/// `key: value` (or `key:`) outside quotes, or `None`.
fn split_key(text: &str) -> Option<(String, &str)> {
    let parts = split_outside_quotes(text, ':');
    let key = parts.first()?.trim();
    if parts.len() < 2 || key.is_empty() || key.contains([' ', '"', '\'', '{', '[']) {
        return None;
    }
    let value = &text[parts[0].len() + 1..];
    (value.is_empty() || value.starts_with(' ')).then(|| (key.to_string(), value.trim()))
}

fn scalar(text: &str, line: usize) -> Yaml {
    let text = text.trim();
    let inner = |open: char, close: char| {
        text.strip_prefix(open)
            .and_then(|t| t.strip_suffix(close))
            .map(str::trim)
    };
    if let Some(items) = inner('[', ']') {
        let items = split_outside_quotes(items, ',');
        return Yaml::Seq(
            items
                .iter()
                .filter(|i| !i.trim().is_empty())
                .map(|i| scalar(i, line))
                .collect(),
        );
    }
    if let Some(entries) = inner('{', '}') {
        return Yaml::Map(
            split_outside_quotes(entries, ',')
                .iter()
                .map(|e| {
                    let (k, v) = split_key(e.trim())
                        .unwrap_or_else(|| panic!("line {line}: not `key: value`: {e}"));
                    (k, scalar(v, line))
                })
                .collect(),
        );
    }
    assert!(
        !text.starts_with(['[', '{', '&', '*', '|', '>', '!']),
        "line {line}: YAML this parser does not read: {text}"
    );
    let unquoted = inner('"', '"').or_else(|| inner('\'', '\''));
    Yaml::Str(unquoted.unwrap_or(text).to_string())
}

struct Parser {
    /// (1-based line number, indent, text without indent and comment).
    lines: Vec<(usize, usize, String)>,
    i: usize,
}

fn is_item(text: &str) -> bool {
    text == "-" || text.starts_with("- ")
}

impl Parser {
    fn new(text: &str) -> Self {
        let lines = text
            .lines()
            .enumerate()
            .filter_map(|(n, l)| {
                assert!(!l.contains('\t'), "line {}: a tab", n + 1);
                let l = strip_comment(l).trim_end();
                let body = l.trim_start();
                (!body.is_empty() && body != "---")
                    .then(|| (n + 1, l.len() - body.len(), body.to_string()))
            })
            .collect();
        Self { lines, i: 0 }
    }

    fn parse(mut self) -> Yaml {
        let doc = self.block(0);
        if let Some((n, _, text)) = self.lines.get(self.i) {
            panic!("line {n}: not read: {text}");
        }
        doc
    }

    fn block(&mut self, indent: usize) -> Yaml {
        if is_item(&self.lines[self.i].2) {
            self.seq(indent)
        } else {
            self.map(indent)
        }
    }

    fn next_indent(&self, than: usize) -> Option<usize> {
        self.lines
            .get(self.i)
            .map(|l| l.1)
            .filter(|&indent| indent > than)
    }

    fn seq(&mut self, indent: usize) -> Yaml {
        let mut items = Vec::new();
        while let Some((n, at, text)) = self.lines.get(self.i).cloned() {
            if at != indent || !is_item(&text) {
                break;
            }
            let rest = text[1..].trim_start().to_string();
            if rest.is_empty() {
                self.i += 1;
                let inner = self
                    .next_indent(indent)
                    .unwrap_or_else(|| panic!("line {n}: an empty item"));
                items.push(self.block(inner));
            } else if split_key(&rest).is_some() {
                // `- key: value`: a mapping whose entries line up after the dash.
                let inner = indent + text.len() - rest.len();
                self.lines[self.i] = (n, inner, rest);
                items.push(self.map(inner));
            } else {
                items.push(scalar(&rest, n));
                self.i += 1;
            }
        }
        Yaml::Seq(items)
    }

    fn map(&mut self, indent: usize) -> Yaml {
        let mut entries: Vec<(String, Yaml)> = Vec::new();
        while let Some((n, at, text)) = self.lines.get(self.i).cloned() {
            if at < indent || is_item(&text) && at == indent {
                break;
            }
            assert_eq!(at, indent, "line {n}: unexpected indentation");
            let (key, value) =
                split_key(&text).unwrap_or_else(|| panic!("line {n}: not `key: value`: {text}"));
            assert!(
                entries.iter().all(|(k, _)| *k != key),
                "line {n}: the key {key} twice"
            );
            self.i += 1;
            let node = if !value.is_empty() {
                scalar(value, n)
            } else if let Some(inner) = self.next_indent(indent) {
                self.block(inner)
            } else {
                Yaml::Str(String::new())
            };
            entries.push((key, node));
        }
        Yaml::Map(entries)
    }
}

/// Whether `s` is a DNS-1123 label (what a pod's host name must be).
fn dns_label(s: &str) -> bool {
    let ok = |c: u8| c.is_ascii_lowercase() || c.is_ascii_digit();
    !s.is_empty()
        && s.len() <= 63
        && s.bytes().all(|c| ok(c) || c == b'-')
        && ok(s.as_bytes()[0])
        && ok(s.as_bytes()[s.len() - 1])
}

/// Adds `what` to `out` unless `ok`.
fn need(out: &mut Vec<String>, ok: bool, what: &str) {
    if !ok {
        out.push(what.to_string());
    }
}

/// Every rule of the Job API and of the project the shards' Job breaks, one line each.
fn problems(job: &Yaml, cluster_md: &str) -> Vec<String> {
    let mut out = job_api_problems(job);
    need(
        &mut out,
        job.str_at("spec.completionMode") == Some("Indexed"),
        "spec.completionMode: Indexed (shards are indexes)",
    );
    out.extend(shard_problems(job, cluster_md));
    out
}

/// Every rule of the Job API (batch/v1) `job` breaks, one line each.
fn job_api_problems(job: &Yaml) -> Vec<String> {
    let mut out = Vec::new();
    need(
        &mut out,
        job.str_at("apiVersion") == Some("batch/v1"),
        "apiVersion: batch/v1",
    );
    need(&mut out, job.str_at("kind") == Some("Job"), "kind: Job");
    let indexed = job.str_at("spec.completionMode") == Some("Indexed");
    need(
        &mut out,
        job.str_at("spec.completionMode")
            .is_none_or(|m| m == "Indexed" || m == "NonIndexed"),
        "spec.completionMode: Indexed or NonIndexed",
    );
    let completions = job.int_at("spec.completions").unwrap_or(1);
    need(&mut out, completions >= 1, "spec.completions: N >= 1");
    need(
        &mut out,
        job.at("spec.backoffLimit")
            .is_none_or(|_| job.int_at("spec.backoffLimit").is_some_and(|b| b >= 0)),
        "spec.backoffLimit: a whole number >= 0",
    );
    let parallelism = job.int_at("spec.parallelism").unwrap_or(1);
    need(
        &mut out,
        (0..=100_000).contains(&parallelism),
        "spec.parallelism: at most 100000 for an Indexed Job",
    );
    let name = job.str_at("metadata.name").unwrap_or("");
    need(
        &mut out,
        dns_label(name) && (!indexed || dns_label(&format!("{name}-{}", completions - 1))),
        "metadata.name: a DNS-1123 label, and so <name>-<last index> of an Indexed Job",
    );
    let restart = job.str_at("spec.template.spec.restartPolicy").unwrap_or("");
    need(
        &mut out,
        restart == "OnFailure" || restart == "Never",
        "spec.template.spec.restartPolicy: OnFailure or Never",
    );
    let per_index = job.at("spec.backoffLimitPerIndex").is_some();
    if per_index {
        need(
            &mut out,
            job.int_at("spec.backoffLimitPerIndex")
                .is_some_and(|b| b >= 0),
            "spec.backoffLimitPerIndex: a whole number >= 0",
        );
        need(
            &mut out,
            indexed,
            "spec.backoffLimitPerIndex requires completionMode: Indexed",
        );
        need(
            &mut out,
            restart == "Never",
            "spec.backoffLimitPerIndex requires restartPolicy: Never",
        );
    }
    if let Some(max) = job
        .at("spec.maxFailedIndexes")
        .map(|_| job.int_at("spec.maxFailedIndexes"))
    {
        need(
            &mut out,
            per_index,
            "spec.maxFailedIndexes requires backoffLimitPerIndex",
        );
        need(
            &mut out,
            max.is_some_and(|m| (0..=completions).contains(&m)),
            "spec.maxFailedIndexes: 0 ..= completions",
        );
    }
    let containers = job.seq_at("spec.template.spec.containers");
    let names: HashSet<&str> = containers.iter().filter_map(|c| c.str_at("name")).collect();
    if job.at("spec.podFailurePolicy").is_some() {
        need(
            &mut out,
            restart == "Never",
            "spec.podFailurePolicy requires restartPolicy: Never",
        );
        let rules = job.seq_at("spec.podFailurePolicy.rules");
        need(
            &mut out,
            rules.len() <= 20,
            "spec.podFailurePolicy.rules: at most 20",
        );
        for (i, rule) in rules.iter().enumerate() {
            let at = format!("spec.podFailurePolicy.rules[{i}]");
            let action = rule.str_at("action").unwrap_or("");
            need(
                &mut out,
                ["Count", "FailIndex", "FailJob", "Ignore"].contains(&action),
                &format!("{at}.action: Count, FailIndex, FailJob or Ignore"),
            );
            if action == "FailIndex" {
                need(
                    &mut out,
                    per_index,
                    &format!("{at}: FailIndex requires backoffLimitPerIndex"),
                );
            }
            let (codes, conditions) = (rule.at("onExitCodes"), rule.at("onPodConditions"));
            need(
                &mut out,
                codes.is_some() != conditions.is_some(),
                &format!("{at}: exactly one of onExitCodes and onPodConditions"),
            );
            if let Some(codes) = codes {
                let op = codes.str_at("operator").unwrap_or("");
                need(
                    &mut out,
                    op == "In" || op == "NotIn",
                    &format!("{at}.onExitCodes.operator: In or NotIn"),
                );
                if let Some(c) = codes.str_at("containerName") {
                    need(
                        &mut out,
                        names.contains(c),
                        &format!("{at}.onExitCodes.containerName: a container of the pod"),
                    );
                }
                let values: Vec<Option<i32>> = codes
                    .seq_at("values")
                    .iter()
                    .map(|v| match v {
                        Yaml::Str(s) => s.parse().ok(),
                        _ => None,
                    })
                    .collect();
                need(
                    &mut out,
                    (1..=255).contains(&values.len()) && values.iter().all(Option::is_some),
                    &format!("{at}.onExitCodes.values: 1 to 255 whole numbers"),
                );
                let values: Vec<i32> = values.into_iter().flatten().collect();
                need(
                    &mut out,
                    op != "In" || !values.contains(&0),
                    &format!("{at}.onExitCodes.values: not 0 with In"),
                );
                need(
                    &mut out,
                    values.windows(2).all(|w| w[0] < w[1]),
                    &format!("{at}.onExitCodes.values: ordered, without duplicates"),
                );
            }
            if let Some(Yaml::Seq(patterns)) = conditions {
                for p in patterns {
                    need(
                        &mut out,
                        p.str_at("type").is_some_and(|t| !t.is_empty()),
                        &format!("{at}.onPodConditions[].type: required"),
                    );
                    need(
                        &mut out,
                        ["True", "False", "Unknown"].contains(&p.str_at("status").unwrap_or("")),
                        &format!("{at}.onPodConditions[].status: True, False or Unknown"),
                    );
                }
            }
        }
    }
    need(&mut out, containers.len() == 1, "one container");
    let volumes: HashSet<&str> = job
        .seq_at("spec.template.spec.volumes")
        .iter()
        .filter_map(|v| v.str_at("name"))
        .collect();
    for c in containers {
        for m in c.seq_at("volumeMounts") {
            need(
                &mut out,
                m.str_at("name").is_some_and(|n| volumes.contains(n)),
                "volumeMounts[].name: a volume of the pod",
            );
            need(
                &mut out,
                m.str_at("mountPath").is_some_and(|p| p.starts_with('/')),
                "volumeMounts[].mountPath: an absolute path",
            );
        }
        // $(NAME) in a command is the kubelet's expansion: it must name an env variable of
        // the container, else it stays literal.
        let env: HashSet<&str> = c
            .seq_at("env")
            .iter()
            .filter_map(|e| e.str_at("name"))
            .collect();
        for arg in c.seq_at("command").iter().chain(c.seq_at("args")) {
            let Yaml::Str(arg) = arg else { continue };
            for reference in arg.split("$(").skip(1) {
                let name = reference.split(')').next().unwrap_or("");
                need(
                    &mut out,
                    env.contains(name),
                    &format!("$({name}) in the command names an env variable of the container (else it stays literal)"),
                );
            }
        }
    }
    out
}

/// The project's rules of the shards' Job: one reproduce container, K from the index, N twice
/// and equal, threads from the CPU request, the memory request the docs state.
fn shard_problems(job: &Yaml, cluster_md: &str) -> Vec<String> {
    let mut out = Vec::new();
    let completions = job.int_at("spec.completions").unwrap_or(1);
    let containers = job.seq_at("spec.template.spec.containers");
    let Some(c) = containers.first() else {
        return out;
    };
    let command: Vec<&str> = c
        .seq_at("command")
        .iter()
        .chain(c.seq_at("args"))
        .filter_map(|a| match a {
            Yaml::Str(s) => Some(s.as_str()),
            _ => None,
        })
        .collect();
    need(
        &mut out,
        command.windows(2).any(|w| w == ["shard", "auto"]),
        "the command runs `shard auto`",
    );
    let env: Vec<(&str, &Yaml)> = c
        .seq_at("env")
        .iter()
        .filter_map(|e| Some((e.str_at("name")?, e)))
        .collect();
    let var = |name: &str| env.iter().find(|(n, _)| *n == name).map(|(_, e)| *e);
    need(
        &mut out,
        var("DRIFTBENCH_SHARDS").and_then(|e| e.str_at("value")) == Some(&completions.to_string()),
        "env DRIFTBENCH_SHARDS equals spec.completions",
    );
    let cpu = c.str_at("resources.requests.cpu").unwrap_or("");
    need(
        &mut out,
        cpu.parse::<u32>().is_ok_and(|n| n >= 1),
        "resources.requests.cpu: whole cores",
    );
    let threads = command
        .windows(2)
        .find(|w| w[0] == "--threads")
        .map(|w| w[1]);
    let from_request = |e: &Yaml| {
        e.str_at("valueFrom.resourceFieldRef.resource") == Some("requests.cpu")
            && e.str_at("valueFrom.resourceFieldRef.containerName")
                .is_none_or(|n| Some(n) == c.str_at("name"))
    };
    need(
        &mut out,
        match threads {
            Some(t) => match t.strip_prefix("$(").and_then(|t| t.strip_suffix(')')) {
                Some(name) => var(name).is_some_and(from_request),
                None => t == cpu,
            },
            None => false,
        },
        "--threads from the CPU request (a resourceFieldRef of requests.cpu, or the same number)",
    );
    let memory = c.str_at("resources.requests.memory").unwrap_or("");
    need(
        &mut out,
        !memory.is_empty() && cluster_md.contains(&format!("memory request, `{memory}`")),
        "resources.requests.memory: the value docs/cluster.md states (\"memory request, `<value>`\")",
    );
    out
}

/// Every rule of the PersistentVolumeClaim API (v1) and of the recipe `pvc` breaks.
fn volume_problems(pvc: &Yaml) -> Vec<String> {
    let mut out = Vec::new();
    need(
        &mut out,
        pvc.str_at("apiVersion") == Some("v1"),
        "apiVersion: v1",
    );
    need(
        &mut out,
        pvc.str_at("kind") == Some("PersistentVolumeClaim"),
        "kind: PersistentVolumeClaim",
    );
    need(
        &mut out,
        pvc.str_at("metadata.name").is_some_and(dns_label),
        "metadata.name: a DNS-1123 label",
    );
    let modes: Vec<&str> = pvc
        .seq_at("spec.accessModes")
        .iter()
        .filter_map(|m| match m {
            Yaml::Str(s) => Some(s.as_str()),
            _ => None,
        })
        .collect();
    need(
        &mut out,
        !modes.is_empty()
            && modes.iter().all(|m| {
                ["ReadWriteOnce", "ReadOnlyMany", "ReadWriteMany", "ReadWriteOncePod"].contains(m)
            }),
        "spec.accessModes: one or more of ReadWriteOnce, ReadOnlyMany, ReadWriteMany, ReadWriteOncePod",
    );
    need(
        &mut out,
        modes.contains(&"ReadWriteMany"),
        "spec.accessModes: ReadWriteMany (the shards' pods write at once, on several nodes)",
    );
    need(
        &mut out,
        pvc.str_at("spec.volumeMode")
            .is_none_or(|m| m == "Filesystem" || m == "Block"),
        "spec.volumeMode: Filesystem or Block",
    );
    let storage = pvc.str_at("spec.resources.requests.storage").unwrap_or("");
    let digits = storage.trim_end_matches(|c: char| c.is_ascii_alphabetic());
    let suffix = &storage[digits.len()..];
    need(
        &mut out,
        digits.parse::<u64>().is_ok_and(|n| n > 0)
            && ["", "Ki", "Mi", "Gi", "Ti", "Pi", "k", "M", "G", "T", "P"].contains(&suffix),
        "spec.resources.requests.storage: a positive quantity (e.g. 20Gi)",
    );
    out
}

/// Where `job`'s first container mounts the claim `claim` (its mountPath), if it does.
fn mount_of<'a>(job: &'a Yaml, claim: &str) -> Option<&'a str> {
    let volume = job
        .seq_at("spec.template.spec.volumes")
        .iter()
        .find(|v| v.str_at("persistentVolumeClaim.claimName") == Some(claim))?
        .str_at("name")?;
    job.seq_at("spec.template.spec.containers")
        .first()?
        .seq_at("volumeMounts")
        .iter()
        .find(|m| m.str_at("name") == Some(volume))?
        .str_at("mountPath")
}

/// The first container's command and args, one string.
fn command_line(job: &Yaml) -> String {
    let Some(c) = job.seq_at("spec.template.spec.containers").first() else {
        return String::new();
    };
    c.seq_at("command")
        .iter()
        .chain(c.seq_at("args"))
        .filter_map(|a| match a {
            Yaml::Str(s) => Some(s.as_str()),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The value of the first container's env variable `name`.
fn env_value<'a>(job: &'a Yaml, name: &str) -> Option<&'a str> {
    job.seq_at("spec.template.spec.containers")
        .first()?
        .seq_at("env")
        .iter()
        .find(|e| e.str_at("name") == Some(name))?
        .str_at("value")
}

/// The recipe's own rules across its four objects: every pod mounts the volume's claim, the
/// fill clones into the root the shards and the merge run in, at a revision; the merge reads
/// the N shard directories of the shards' Job with its image.
fn recipe_problems(pvc: &Yaml, fill: &Yaml, job: &Yaml, merge: &Yaml) -> Vec<String> {
    let mut out = Vec::new();
    let claim = pvc.str_at("metadata.name").unwrap_or("");
    let root = mount_of(job, claim);
    for (what, j) in [
        ("the fill Job", fill),
        ("the shards' Job", job),
        ("the merge Job", merge),
    ] {
        need(
            &mut out,
            mount_of(j, claim).is_some() && mount_of(j, claim) == root,
            &format!("{what} mounts the volume's claim ({claim}) where the shards' Job does"),
        );
    }
    let root = root.unwrap_or("");
    let (fill_cmd, job_cmd, merge_cmd) =
        (command_line(fill), command_line(job), command_line(merge));
    need(
        &mut out,
        job_cmd.contains(&format!("--root {root} ")),
        "the shards run with --root at the volume's mount",
    );
    for step in [
        format!("cd {root};"),
        "git fetch".to_string(),
        "$DRIFTBENCH_REPO $DRIFTBENCH_REVISION".to_string(),
        "git checkout".to_string(),
    ] {
        need(
            &mut out,
            fill_cmd.contains(&step),
            &format!("the fill Job's command: {step}"),
        );
    }
    for var in ["DRIFTBENCH_REPO", "DRIFTBENCH_REVISION"] {
        need(
            &mut out,
            env_value(fill, var).is_some_and(|v| !v.is_empty()),
            &format!("the fill Job sets {var}"),
        );
    }
    need(
        &mut out,
        merge_cmd.contains(&format!(
            "reproduce merge --root {root} {root}/results-shard-*-of-$(DRIFTBENCH_SHARDS)"
        )),
        "the merge Job runs `reproduce merge --root <mount> <mount>/results-shard-*-of-$(DRIFTBENCH_SHARDS)`",
    );
    need(
        &mut out,
        env_value(merge, "DRIFTBENCH_SHARDS").is_some()
            && env_value(merge, "DRIFTBENCH_SHARDS") == env_value(job, "DRIFTBENCH_SHARDS"),
        "the merge Job's DRIFTBENCH_SHARDS equals the shards' Job's",
    );
    let image = |j: &Yaml| {
        j.seq_at("spec.template.spec.containers")
            .first()
            .and_then(|c| c.str_at("image"))
            .map(str::to_string)
    };
    need(
        &mut out,
        image(merge).is_some() && image(merge) == image(job),
        "the merge Job runs the shards' image",
    );
    need(
        &mut out,
        merge.str_at("spec.template.spec.restartPolicy") == Some("Never")
            && merge.int_at("spec.backoffLimit") == Some(0),
        "the merge Job is not retried (restartPolicy: Never, backoffLimit: 0): a retry finds the same",
    );
    out
}

/// The Kubernetes minor version (1.x) from which each Job field the recipe may use is served
/// and on by default (beta or GA): Indexed completion 1.22 (GA 1.24), podFailurePolicy 1.26
/// (GA 1.31), backoffLimitPerIndex and maxFailedIndexes 1.29 (GA 1.33; alpha, off, in 1.28).
const FIELD_SINCE: [(&str, u32); 4] = [
    ("spec.completionMode", 22),
    ("spec.podFailurePolicy", 26),
    ("spec.backoffLimitPerIndex", 29),
    ("spec.maxFailedIndexes", 29),
];

/// The oldest Kubernetes 1.x that serves every field the Jobs use.
fn minimum_minor(jobs: &[&Yaml]) -> u32 {
    jobs.iter()
        .flat_map(|j| FIELD_SINCE.iter().filter(|(f, _)| j.at(f).is_some()))
        .map(|(_, v)| *v)
        .max()
        .unwrap_or(21)
}

/// The four files of the recipe, parsed: volume, fill, shards' Job, merge.
fn recipe(files: [&str; 4]) -> [Yaml; 4] {
    files.map(|text| Parser::new(text).parse())
}

const RECIPE: [&str; 4] = [
    "docs/kubernetes/driftbench-volume.yaml",
    "docs/kubernetes/driftbench-fill.yaml",
    "docs/kubernetes/driftbench-job.yaml",
    "docs/kubernetes/driftbench-merge.yaml",
];

/// Everything the recipe breaks: each object's API rules, the shards' Job's and the recipe's
/// own rules, and the minimum version (`cluster_md` and every file must state it).
fn recipe_all_problems(texts: [&str; 4], cluster_md: &str) -> Vec<String> {
    let [pvc, fill, job, merge] = recipe(texts);
    let mut out = volume_problems(&pvc);
    out.extend(
        job_api_problems(&fill)
            .into_iter()
            .map(|p| format!("fill: {p}")),
    );
    out.extend(problems(&job, cluster_md));
    out.extend(
        job_api_problems(&merge)
            .into_iter()
            .map(|p| format!("merge: {p}")),
    );
    out.extend(recipe_problems(&pvc, &fill, &job, &merge));
    let stated = format!(
        "Kubernetes 1.{} or later",
        minimum_minor(&[&fill, &job, &merge])
    );
    need(
        &mut out,
        cluster_md.contains(&stated),
        &format!("docs/cluster.md states the minimum version: {stated}"),
    );
    for (file, text) in RECIPE.iter().zip(texts) {
        need(
            &mut out,
            text.contains(&stated),
            &format!("{file} states the minimum version: {stated}"),
        );
    }
    out
}

#[test]
fn the_whole_recipe_volume_fill_shards_merge_passes_the_api_and_recipe_rules() {
    let texts = RECIPE.map(read);
    let found = recipe_all_problems(
        texts.each_ref().map(String::as_str),
        &read("docs/cluster.md"),
    );
    assert!(found.is_empty(), "{found:#?}");
    assert!(common::repo_root()
        .join("docs/kubernetes/Containerfile")
        .is_file());
}

/// A broken rule in any file of the recipe is found.
#[test]
fn broken_recipes_are_found() {
    let texts = RECIPE.map(read);
    let docs = read("docs/cluster.md");
    for (file, from, to, want) in [
        (
            0,
            "accessModes: [ReadWriteMany]",
            "accessModes: [ReadWriteOnce]",
            "ReadWriteMany (the shards",
        ),
        (0, "storage: 20Gi", "storage: lots", "a positive quantity"),
        (
            0,
            "name: driftbench-project",
            "name: other-project",
            "mounts the volume's claim",
        ),
        (
            1,
            "mountPath: /driftbench",
            "mountPath: /elsewhere",
            "the fill Job mounts",
        ),
        (1, "git checkout", "git switch", "git checkout"),
        (
            1,
            "restartPolicy: Never",
            "restartPolicy: Always",
            "fill: spec.template.spec.restartPolicy",
        ),
        (
            2,
            "  backoffLimitPerIndex: 3\n",
            "  backoffLimitPerIndex: 3\n  maxFailedIndexes: 99\n",
            "0 ..= completions",
        ),
        (
            3,
            "value: \"16\"",
            "value: \"8\"",
            "DRIFTBENCH_SHARDS equals the shards' Job's",
        ),
        (3, "backoffLimit: 0", "backoffLimit: 2", "is not retried"),
        (
            3,
            "claimName: driftbench-project",
            "claimName: other",
            "the merge Job mounts",
        ),
        (
            3,
            "-of-$(DRIFTBENCH_SHARDS)",
            "-of-$(SHARDS)",
            "names an env variable",
        ),
    ] {
        let mut broken = texts.clone();
        assert!(broken[file].contains(from), "{}: {from}", RECIPE[file]);
        broken[file] = broken[file].replacen(from, to, 1);
        let found = recipe_all_problems(broken.each_ref().map(String::as_str), &docs);
        assert!(
            found.iter().any(|p| p.contains(want)),
            "{to}: {want}: {found:#?}"
        );
    }
    // Without backoffLimitPerIndex (and its FailIndex rule) the recipe would need 1.26 only:
    // the version the docs state must then follow, so the statement is checked, not copied.
    let job = Parser::new(&texts[2]).parse();
    assert_eq!(minimum_minor(&[&job]), 29);
    let older = Parser::new("spec:\n  podFailurePolicy:\n    rules: []\n").parse();
    assert_eq!(minimum_minor(&[&older]), 26);
    let stated = docs.replace("Kubernetes 1.29 or later", "Kubernetes 1.27 or later");
    let found = recipe_all_problems(texts.each_ref().map(String::as_str), &stated);
    assert!(
        found
            .iter()
            .any(|p| p.contains("docs/cluster.md states the minimum version")),
        "{found:#?}"
    );
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(common::repo_root().join(rel)).unwrap()
}

/// The manifest before issue 30 (`restartPolicy: OnFailure` beside `backoffLimitPerIndex`,
/// no `--threads`) and single broken rules are each found.
#[test]
fn broken_manifests_are_found() {
    const OLD: &str = r#"apiVersion: batch/v1
kind: Job
metadata:
  name: driftbench
spec:
  completionMode: Indexed
  completions: 16
  parallelism: 16
  backoffLimitPerIndex: 3
  template:
    spec:
      restartPolicy: OnFailure
      containers:
        - name: reproduce
          image: registry.example.org/driftbench:latest # built from a clean clone
          command: ["reproduce", "--root", "/driftbench", "shard", "auto"]
          env:
            - name: DRIFTBENCH_SHARDS
              value: "16"
          resources:
            requests: { cpu: "4", memory: "4Gi" }
            limits: { cpu: "4", memory: "4Gi" }
"#;
    let docs = read("docs/cluster.md");
    let old = problems(&Parser::new(OLD).parse(), &docs);
    for want in [
        "requires restartPolicy: Never",
        "--threads from the CPU request",
    ] {
        assert!(old.iter().any(|p| p.contains(want)), "{want}: {old:#?}");
    }
    let current = read("docs/kubernetes/driftbench-job.yaml");
    for (from, to, want) in [
        ("values: [1, 2]", "values: [2, 1]", "ordered"),
        ("values: [1, 2]", "values: [0, 2]", "not 0 with In"),
        (
            "containerName: reproduce\n          operator",
            "containerName: other\n          operator",
            "a container of the pod",
        ),
        (
            "  backoffLimitPerIndex: 3\n",
            "",
            "FailIndex requires backoffLimitPerIndex",
        ),
        (
            "completions: 16",
            "completions: 8",
            "DRIFTBENCH_SHARDS equals spec.completions",
        ),
        (
            "resource: requests.cpu",
            "resource: limits.memory",
            "--threads from the CPU request",
        ),
        (
            "$(DRIFTBENCH_THREADS)",
            "$(THREADS)",
            "names an env variable",
        ),
        (
            "status: \"True\"",
            "status: \"Yes\"",
            "True, False or Unknown",
        ),
        (
            "memory: \"4Gi\" }\n            limits",
            "memory: \"1Gi\" }\n            limits",
            "docs/cluster.md states",
        ),
    ] {
        assert!(current.contains(from), "{from}");
        let broken = Parser::new(&current.replacen(from, to, 1)).parse();
        let found = problems(&broken, &docs);
        assert!(
            found.iter().any(|p| p.contains(want)),
            "{to}: {want}: {found:#?}"
        );
    }
}

#[test]
fn the_parser_reads_the_subset_and_refuses_the_rest() {
    let doc = Parser::new(
        "a: 1 # note\nb:\n  - x\n  - k: \"v # not a comment\"\n    l: [1, 2]\nc: { d: e }\n",
    )
    .parse();
    assert_eq!(doc.str_at("a"), Some("1"));
    assert_eq!(doc.seq_at("b")[0], Yaml::Str("x".into()));
    assert_eq!(doc.seq_at("b")[1].str_at("k"), Some("v # not a comment"));
    assert_eq!(doc.seq_at("b")[1].seq_at("l").len(), 2);
    assert_eq!(doc.str_at("c.d"), Some("e"));
    for bad in [
        "a: &x 1\n",
        "a: |\n  text\n",
        "a: 1\n   b: 2\n",
        "a: 1\na: 2\n",
    ] {
        assert!(
            std::panic::catch_unwind(|| Parser::new(bad).parse()).is_err(),
            "{bad}"
        );
    }
}
