//! values.csv as other people write it: the numbers that contradict their own paper are marked
//! and warned with file and line (robio2018 prints three such: a norm below its own entry, a
//! negative norm), and numbers that cannot be compared are refused before anything runs.

use analysis::papers::Papers;
use inputs::Scratch;

/// A scratch `papers/` with one paper `demo` whose values.csv is `values` (removed when dropped).
fn papers_dir(name: &str, values: &str) -> Scratch {
    let dir = Scratch::dir(&format!("paper-values-{name}"));
    let paper = dir.join("demo");
    std::fs::create_dir_all(&paper).unwrap();
    std::fs::write(
        paper.join("paper.toml"),
        "paper = \"demo\"\ntitle = \"Demo\"\n\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"A\"\nrun = \"demo-e / v / exact\"\n",
    )
    .unwrap();
    std::fs::write(paper.join("values.csv"), values).unwrap();
    dir
}

const HEADER: &str = "paper,table,experiment,column,metric,value,note\n";

#[test]
fn contradictions_are_marked_with_their_line_and_not_used() {
    let values = format!(
        "{HEADER}demo,T1,e,A,drift_1,3e-6,\ndemo,T1,e,A,drift_2,5.6e-6,\ndemo,T1,e,A,drift_norm,2.45e-6,\n\
         demo,T1,e,B,drift_1,1e-6,\ndemo,T1,e,B,drift_norm,-2.5e-5,\n\
         demo,T2,e,A,compute_time_s,1.0,\n\
         demo,T1,e,C,drift_1,1e-6,\ndemo,T1,e,C,drift_norm,2e-6,\n"
    );
    let dir = papers_dir("marks", &values);
    let papers = Papers::load(&dir).unwrap();
    let lines: Vec<usize> = papers.warnings.iter().map(|w| w.line).collect();
    assert_eq!(lines, vec![4, 6], "{:?}", papers.warnings);
    assert!(papers.warnings[0].message.contains("below its own drift_2"));
    assert!(papers.warnings[1].message.contains("negative"));
    assert!(papers.warnings[0].to_string().contains("values.csv:4"));
    // The column's norm falls back to the norm of its printed joints.
    let m = &papers.mappings[0];
    let (norm, derived) = papers.published(m, "drift_norm").unwrap();
    assert!(derived && (norm - (3e-6f64.powi(2) + 5.6e-6f64.powi(2)).sqrt()).abs() < 1e-18);
    assert_eq!(papers.published(m, "sim_s"), Some((1.0, false)));
    assert_eq!(
        papers.inconsistent(m, "drift_norm").map(|v| v.0),
        Some(2.45e-6)
    );
    // A consistent column is left alone.
    assert!(papers
        .values
        .iter()
        .filter(|v| v.column == "C")
        .all(|v| v.inconsistent.is_none()));
}

#[test]
fn non_finite_values_and_unknown_metrics_are_refused_naming_the_line() {
    for (bad, expect) in [
        (
            "demo,T1,e,A,drift_1,NaN,\n",
            "line 3: value NaN is not a finite number",
        ),
        ("demo,T1,e,A,drift_1,inf,\n", "line 3: value inf"),
        (
            "demo,T1,e,A,max_pos_error,1e-3,\n",
            "unknown metric \"max_pos_error\" (valid: drift_1",
        ),
        (
            "demo,T1,e,A,drift_2,2e-6,\n",
            "line 3: the drift_2 of e / A in table T1 is given already on line 2",
        ),
    ] {
        let dir = papers_dir(
            "refused",
            &format!("{HEADER}demo,T1,e,A,drift_2,1e-6,\n{bad}"),
        );
        let err = Papers::load(&dir).unwrap_err().to_string();
        assert!(err.contains(expect) && err.contains("values.csv"), "{err}");
    }
}

/// A mapping's companions name a variant (the mapped solver) or a variant and a solver, in the
/// mapping's experiment; anything else is refused naming the field.
#[test]
fn companions_name_variants_or_runs() {
    let dir = papers_dir("companions", HEADER);
    let toml = |companions: &str| {
        format!(
            "paper = \"demo\"\ntitle = \"Demo\"\n\n[[mapping]]\npublished_experiment = \"e\"\npublished_column = \"A\"\nrun = \"demo-e / v / m3\"\ncompanions = {companions}\n"
        )
    };
    let paper_toml = dir.join("demo").join("paper.toml");
    std::fs::write(&paper_toml, toml(r#"["w", "x / m3-tol-1e-6"]"#)).unwrap();
    let papers = Papers::load(&dir).unwrap();
    let shown: Vec<String> = papers.mappings[0]
        .companions
        .iter()
        .map(|k| k.to_string())
        .collect();
    assert_eq!(shown, ["demo-e / w / m3", "demo-e / x / m3-tol-1e-6"]);
    for bad in [r#"["x / "]"#, r#"["a / b / c"]"#, r#"["../x"]"#, r#"[""]"#] {
        std::fs::write(&paper_toml, toml(bad)).unwrap();
        let err = Papers::load(&dir).expect_err(bad).to_string();
        assert!(err.contains("companions"), "{bad}: {err}");
    }
}

/// A published compute time is set beside the first run of its solver in its experiment (by
/// key, whatever the variant the mapping names), the run the report shows and the timing pass
/// times alone; an experiment without such a run shows none.
#[test]
fn a_published_time_is_compared_with_the_first_run_of_its_solver() {
    use records::index::Runs;
    use records::RunRow;
    use spec::SolverKind;
    let dir = papers_dir(
        "timed",
        &format!("{HEADER}demo,T1,e,A,drift_1,1e-6,\ndemo,T2,e,A,compute_time_s,2.5,\n"),
    );
    let papers = Papers::load(&dir).unwrap();
    let blank = |variant: &str, solver: &str| {
        RunRow::blank(
            &spec::RunKey::from_ids("demo-e", variant, solver).unwrap(),
            SolverKind::Exact,
        )
    };
    let runs = Runs::new(vec![
        blank("w", "exact"),
        blank("v", "m3"),
        blank("u", "exact"),
        RunRow::blank(
            &spec::RunKey::from_ids("other", "a", "exact").unwrap(),
            SolverKind::Exact,
        ),
    ]);
    let timed: Vec<_> = papers.timed_runs(&runs).collect();
    assert_eq!(timed.len(), 1);
    assert_eq!(
        (timed[0].experiment, timed[0].solver, timed[0].published_s),
        ("demo-e", "exact", 2.5)
    );
    assert_eq!(
        timed[0].run.map(RunRow::key),
        Some(blank("u", "exact").key())
    );
    let none = Runs::new(vec![blank("v", "m3")]);
    assert_eq!(papers.timed_runs(&none).next().unwrap().run, None);
}
