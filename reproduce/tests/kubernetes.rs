//! docs/kubernetes/driftbench-job.yaml against the rules of the Kubernetes Job API it relies on
//! (the API server's validation of batch/v1 Job: pkg/apis/batch/validation) and the project's
//! own (N written twice must agree; threads from the CPU request; the memory request the docs
//! state). The manifest is read by a small parser of the YAML subset it is written in (block
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

/// Every rule of the Job API and of the project the manifest breaks, one line each.
fn problems(job: &Yaml, cluster_md: &str) -> Vec<String> {
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
        indexed,
        "spec.completionMode: Indexed (shards are indexes)",
    );
    let completions = job.int_at("spec.completions").unwrap_or(0);
    need(&mut out, completions >= 1, "spec.completions: N >= 1");
    let parallelism = job.int_at("spec.parallelism").unwrap_or(1);
    need(
        &mut out,
        (0..=100_000).contains(&parallelism),
        "spec.parallelism: at most 100000 for an Indexed Job",
    );
    let name = job.str_at("metadata.name").unwrap_or("");
    need(
        &mut out,
        dns_label(&format!("{name}-{}", completions - 1)),
        "metadata.name: <name>-<last index> must be a DNS-1123 label",
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
    // The project's rules: one reproduce container, K from the index, N twice and equal,
    // threads from the CPU request, the memory request the docs state.
    need(&mut out, containers.len() == 1, "one container");
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
        command.windows(2).any(|w| w == ["--shard", "auto"]),
        "the command runs `--shard auto`",
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
    for arg in &command {
        for reference in arg.split("$(").skip(1) {
            let name = reference.split(')').next().unwrap_or("");
            need(
                &mut out,
                var(name).is_some(),
                &format!("$({name}) in the command names an env variable of the container (else it stays literal)"),
            );
        }
    }
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

fn read(rel: &str) -> String {
    std::fs::read_to_string(common::repo_root().join(rel)).unwrap()
}

#[test]
fn the_job_manifest_passes_the_job_api_rules_it_relies_on() {
    let job = Parser::new(&read("docs/kubernetes/driftbench-job.yaml")).parse();
    let found = problems(&job, &read("docs/cluster.md"));
    assert!(found.is_empty(), "{found:#?}");
    assert!(common::repo_root()
        .join("docs/kubernetes/Containerfile")
        .is_file());
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
          command: ["reproduce", "--root", "/driftbench", "--shard", "auto"]
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
