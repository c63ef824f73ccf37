//! The experiment files: every committed file loads, every experiment of docs/experiments.md is
//! there, and a malformed file is rejected with an error naming the file and the field.

use catalog::PaperFile;
use std::path::PathBuf;

fn experiments_dir() -> PathBuf {
    catalog::root_from_current_dir()
        .unwrap()
        .join("experiments")
}

#[test]
fn every_experiment_of_the_spec_is_in_the_files() {
    let files =
        reproduce::load_experiments(&experiments_dir()).expect("committed experiment files load");
    let ids: Vec<String> = files
        .iter()
        .flat_map(|f| f.experiments.iter().map(|e| e.id.clone()))
        .collect();
    for id in [
        "jia2019-clover",
        "jia2019-star",
        "jia2019-ping",
        "zhang2018-butterfly-scheme",
        "zhang2018-cardioid-scheme",
        "zhang2018-butterfly-robust",
        "zhang2018-cardioid-robust",
        "zhong2021-clover-a",
        "zhong2021-clover-b",
        "zhong2021-dai",
        "kong2019-triangle",
        "kong2019-circle",
    ] {
        assert!(
            ids.iter().any(|i| i == id),
            "experiment {id} missing from experiments/"
        );
    }
    let papers: Vec<&str> = files.iter().map(|f| f.paper.as_str()).collect();
    for p in ["jia2019", "zhang2018", "zhong2021", "kong2019"] {
        assert!(papers.contains(&p), "no experiment file for {p}");
    }
}

/// Writes `text` to a fresh file, alone in its directory (removed on return), and loads it as
/// the orchestrator loads a directory of them.
fn load_text(name: &str, text: &str) -> Result<PaperFile, String> {
    let dir = inputs::Scratch::dir(&format!("test-{name}"));
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    reproduce::load_experiments(&dir)
        .map(|mut files| files.remove(0))
        .map_err(|e| e.to_string())
}

const GOOD: &str = r#"
paper = "jia2019"
title = "t"
[[experiment]]
id = "jia2019-x"
paper_output = "-"
robot = "jaco2-pen"
path = { name = "four-leaf-clover", duration = 5.0 }
theta0 = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95]
[[experiment.variant]]
label = "VLTCO"
scheme = { kind = "jia2019", phi = 0.2, tau = 0.4, kappa = 20.0, lambda = 20.0 }
solvers = [{ kind = "lvi-pdnn", gamma = 1e7 }]
"#;

fn assert_rejected(name: &str, text: &str, must_mention: &[&str]) {
    let err = load_text(name, text).expect_err("malformed file must be rejected");
    assert!(
        err.contains(&format!("{name}.toml")),
        "error does not name the file: {err}"
    );
    for m in must_mention {
        assert!(err.contains(m), "error does not mention `{m}`: {err}");
    }
}

#[test]
fn a_good_file_loads_and_expands_into_runs() {
    let f = load_text("good", GOOD).unwrap();
    let jobs = f.jobs().unwrap();
    assert_eq!(jobs.len(), 2, "exact column + one neural solver");
    assert_eq!(
        jobs[0].theta_ref, jobs[0].theta0,
        "theta_ref defaults to theta0"
    );
}

#[test]
fn malformed_files_name_the_file_and_the_field() {
    assert_rejected(
        "missing_theta0",
        &GOOD.replace("theta0 = [1.675, 2.79, -3.216, 4.187, -1.71, -2.95]\n", ""),
        &["theta0"],
    );
    assert_rejected(
        "short_theta0",
        &GOOD.replace("-1.71, -2.95]", "-1.71]"),
        &["theta0", "5 entries"],
    );
    assert_rejected(
        "unknown_robot",
        &GOOD.replace("jaco2-pen", "jaco3"),
        &["robot", "jaco3"],
    );
    assert_rejected(
        "unknown_field",
        &GOOD.replace("paper_output", "paper_outptu"),
        &["paper_outptu"],
    );
    assert_rejected(
        "bad_scheme_kind",
        &GOOD.replace("kind = \"jia2019\"", "kind = \"jia2020\""),
        &["jia2020"],
    );
    assert_rejected(
        "bad_solver_field",
        &GOOD.replace("gamma = 1e7", "gama = 1e7"),
        &["gama"],
    );
    assert_rejected("bad_id", &GOOD.replace("jia2019-x", "zhong2021-x"), &["id"]);
    assert_rejected(
        "bad_tolerance",
        &GOOD
            .replace("solvers = [", "exact = true\nsolvers = [")
            .replace(
                "theta0 = [",
                "integrator = { method = \"bdf\", rtol = -1.0, atol = 1e-8 }\ntheta0 = [",
            ),
        &["integrator"],
    );
}

/// A kong2019-style file on the 5-joint Katana (kinematics only).
const KATANA: &str = r#"
paper = "kong2019"
title = "t"
[[experiment]]
id = "kong2019-x"
paper_output = "-"
robot = "katana6m180"
path = { name = "circle", duration = 9.0 }
theta0 = [1.2566, 1.5708, 0.0, -0.5236, 1.0472]
[[experiment.variant]]
label = "ZNN (eq. 22)"
scheme = { kind = "kong2019-znn", mu = 1.0, k_p = 1.0 }
solvers = [{ kind = "znn", gamma = 1.0 }]
"#;

/// A zhang2018-style file (acceleration level, Jaco2 with dynamics).
const ZHANG: &str = r#"
paper = "zhang2018"
title = "t"
[[experiment]]
id = "zhang2018-x"
paper_output = "-"
robot = "jaco2-pen"
path = { name = "butterfly", duration = 8.0 }
theta0 = [1.68, 2.81, -3.22, 4.19, -1.71, -2.65]
[[experiment.variant]]
label = "HL-JDF"
scheme = { kind = "zhang2018", zeta = 0.6, alpha = 20.0, beta = 20.0, rho_v = 20.0, rho_p = 20.0 }
solvers = [{ kind = "fp-cdnn", gamma = 200.0 }]
"#;

#[test]
fn the_templates_load() {
    for (name, text) in [("good_t", GOOD), ("katana_t", KATANA), ("zhang_t", ZHANG)] {
        load_text(name, text).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn paths_are_checked_at_load() {
    assert_rejected(
        "unknown_path",
        &GOOD.replace("four-leaf-clover", "four-leaf-clovr"),
        &[
            "field `path`",
            "four-leaf-clovr",
            "valid names",
            "five-point-star",
        ],
    );
    for (name, bad) in [("zero_duration", "0.0"), ("negative_duration", "-5.0")] {
        assert_rejected(
            name,
            &GOOD.replace("duration = 5.0", &format!("duration = {bad}")),
            &["jia2019-x", "field `path`", "duration"],
        );
    }
    assert_rejected(
        "inf_duration",
        &GOOD.replace("duration = 5.0", "duration = inf"),
        &["duration"],
    );
    assert_rejected(
        "zero_scale",
        &GOOD.replace("duration = 5.0", "duration = 5.0, scale = 0.0"),
        &["scale"],
    );
    assert_rejected(
        "nan_rotation",
        &GOOD.replace("duration = 5.0", "duration = 5.0, rotation = nan"),
        &["rotation"],
    );
    assert_rejected(
        "inf_tilt",
        &GOOD.replace("duration = 5.0", "duration = 5.0, tilt_y = -inf"),
        &["tilt_y"],
    );
    assert_rejected(
        "phase_one",
        &GOOD.replace("duration = 5.0", "duration = 5.0, phase = 1.0"),
        &["phase", "[0, 1)"],
    );
    // Phase is defined for the closed curves only, not for the stroke paths.
    load_text(
        "phase_clover",
        &GOOD.replace("duration = 5.0", "duration = 5.0, phase = 0.25"),
    )
    .unwrap();
    assert_rejected(
        "phase_triangle",
        &KATANA
            .replace("\"circle\"", "\"triangle\"")
            .replace("duration = 9.0", "duration = 9.0, phase = 0.5"),
        &["phase", "triangle"],
    );
    // A variant's own path names the variant.
    assert_rejected(
        "variant_path",
        &GOOD.replace(
            "solvers = [",
            "path = { name = \"ping\", duration = -1.0 }\nsolvers = [",
        ),
        &["variant[0] (\"VLTCO\") field `path`", "duration"],
    );
}

#[test]
fn gains_are_checked_at_load() {
    for bad in ["0.0", "-1.0", "inf", "nan"] {
        assert_rejected(
            "solver_gain",
            &GOOD.replace("gamma = 1e7", &format!("gamma = {bad}")),
            &["variant[0] (\"VLTCO\")", "field `solvers[0]`", "gamma"],
        );
        assert_rejected(
            "scheme_gain",
            &GOOD.replace("kappa = 20.0", &format!("kappa = {bad}")),
            &["field `scheme`", "kappa"],
        );
        assert_rejected(
            "zhang_gain",
            &ZHANG.replace("alpha = 20.0", &format!("alpha = {bad}")),
            &["field `scheme`", "alpha"],
        );
        // mu = 0 (no repetitive term) is a scheme the mathematics allows.
        if bad != "0.0" {
            assert_rejected(
                "kong_gain",
                &KATANA.replace("mu = 1.0", &format!("mu = {bad}")),
                &["field `scheme`", "mu"],
            );
        }
    }
    load_text("kong_mu_0", &KATANA.replace("mu = 1.0", "mu = 0.0"))
        .expect("mu = 0 is allowed: the scheme without its repetitive term");
    assert_rejected(
        "vp_rnn_pf_sigma",
        &GOOD.replace(
            "{ kind = \"lvi-pdnn\", gamma = 1e7 }",
            "{ kind = \"lvi-pdnn\", gamma = 1e7 }, { kind = \"vp-rnn-pf\", p = 1e-4, sigma = 0.0, gamma = 2.0 }",
        ),
        &["field `solvers[1]`", "sigma"],
    );
    assert_rejected(
        "ftnn_alpha",
        &KATANA.replace(
            "{ kind = \"znn\", gamma = 1.0 }",
            "{ kind = \"finite-time\", beta = 1.0, alpha = 1.5 }",
        ),
        &["solvers[0]", "alpha"],
    );
}

#[test]
fn integrator_tolerances_are_checked_at_load() {
    let with = |integrator: &str| {
        GOOD.replace(
            "theta0 = [",
            &format!("integrator = {{ {integrator} }}\ntheta0 = ["),
        )
    };
    for rtol in ["inf", "1e300", "0.0", "1.0", "nan", "-1e-6"] {
        assert_rejected(
            "rtol",
            &with(&format!("method = \"bdf\", rtol = {rtol}, atol = 1e-8")),
            &["field `integrator`", "rtol"],
        );
    }
    for atol in ["inf", "0.0", "nan"] {
        assert_rejected(
            "atol",
            &with(&format!("method = \"bdf\", rtol = 1e-6, atol = {atol}")),
            &["field `integrator`", "atol"],
        );
    }
    assert_rejected(
        "max_steps",
        &with("method = \"bdf\", rtol = 1e-6, atol = 1e-8, max_steps = 0"),
        &["field `integrator`", "max_steps"],
    );
    for h in ["0.0", "inf", "-0.05"] {
        assert_rejected(
            "max_step",
            &with(&format!(
                "method = \"bdf\", rtol = 1e-6, atol = 1e-8, max_step = {h}"
            )),
            &["max_step"],
        );
    }
    assert_rejected(
        "exact_rtol",
        &GOOD.replace(
            "theta0 = [",
            "exact_integrator = { method = \"dopri5\", rtol = 1e300, atol = 1e-10 }\ntheta0 = [",
        ),
        &["field `exact_integrator`", "rtol"],
    );
    assert_rejected(
        "variant_integrator",
        &GOOD.replace(
            "solvers = [",
            "integrator = { method = \"bdf\", rtol = 1e-6, atol = 1e-8, max_steps = 0 }\nsolvers = [",
        ),
        &["variant[0] (\"VLTCO\") field `integrator`", "max_steps"],
    );
}

#[test]
fn scheme_robot_and_solver_must_fit_together() {
    // zhang2018 is acceleration level and needs the arm's dynamics: not the Katana.
    let katana_zhang = KATANA.replace(
        "scheme = { kind = \"kong2019-znn\", mu = 1.0, k_p = 1.0 }\nsolvers = [{ kind = \"znn\", gamma = 1.0 }]",
        "scheme = { kind = \"zhang2018\", zeta = 0.6, alpha = 20.0, beta = 20.0, rho_v = 20.0, rho_p = 20.0 }",
    );
    assert_rejected(
        "zhang_on_katana",
        &katana_zhang,
        &["field `scheme`", "dynamics", "katana6m180", "jaco2-pen"],
    );
    // The zeroing networks solve equality-constrained QPs only; jia2019's QP has inequalities.
    assert_rejected(
        "cdnn_on_jia",
        &GOOD.replace(
            "{ kind = \"lvi-pdnn\", gamma = 1e7 }",
            "{ kind = \"fp-cdnn\", gamma = 200.0 }",
        ),
        &["field `solvers[0]`", "FP-CDNN", "inequality"],
    );
    // A network that solves the equality part only is refused on a scheme with bounds (robio2018's
    // bound conversion, `upsilon`), naming both; without the bounds the same network loads.
    let rmp = |upsilon: &str| {
        GOOD.replace(
            "{ kind = \"jia2019\", phi = 0.2, tau = 0.4, kappa = 20.0, lambda = 20.0 }",
            &format!("{{ kind = \"velocity-rmp\", lambda = 4.0{upsilon} }}"),
        )
        .replace(
            "{ kind = \"lvi-pdnn\", gamma = 1e7 }",
            "{ kind = \"vp-cdnn\", gamma = 200.0 }",
        )
    };
    assert_rejected(
        "cdnn_on_bounds",
        &rmp(", upsilon = 2.0"),
        &[
            "field `solvers[0]`",
            "VP-CDNN",
            "equality-constrained QPs only",
            "(field `scheme`)",
            "finite bounds",
        ],
    );
    load_text("cdnn_without_bounds", &rmp("")).unwrap();
    // The same holds for a point of the zeroing vocabulary; a point of the projection family
    // (which honours bounds) loads on the bounded scheme, and a misplaced part of its error
    // form is refused naming its line, the field and the valid choices.
    let on_bounds = |solver: &str| {
        rmp(", upsilon = 2.0").replace("{ kind = \"vp-cdnn\", gamma = 200.0 }", solver)
    };
    assert_rejected(
        "zeroing_point_on_bounds",
        &on_bounds("{ kind = \"zeroing\", gain = { law = \"power\", gamma = 1.0, p = 2.0 } }"),
        &[
            "field `solvers[0]`",
            "equality-constrained QPs only",
            "finite bounds",
        ],
    );
    load_text(
        "projection_point_on_bounds",
        &on_bounds("{ kind = \"projection\", error = { form = \"lvi\", scaling = \"identity\" }, gain = { law = \"power\", gamma = 1e3, p = 2.0 } }"),
    )
    .unwrap();
    assert_rejected(
        "projection_point_misplaced",
        &on_bounds("{ kind = \"projection\", error = { form = \"lvi\", p = 1.0 }, gain = { law = \"constant\", gamma = 1.0 } }"),
        &["line 13", "unknown field `p`", "expected `scaling`"],
    );
    // The reference perturbation is 9-dimensional (6 joints + 3): not for the 5-joint Katana.
    assert_rejected(
        "perturbation_on_katana",
        &KATANA.replace(
            "{ kind = \"znn\", gamma = 1.0 }",
            "{ kind = \"fp-cdnn\", gamma = 200.0, perturbation = { a_d = 1.0, a_s = 1.5, task_duration = 9.0 } }",
        ),
        &["solvers[0]", "perturbation"],
    );
    // The networks are QP solvers and do not depend on the level: a velocity-level paper's
    // network on zhang2018's acceleration-level QP (equality-only, unbounded) is a valid run.
    load_text(
        "lvi_on_zhang",
        &ZHANG.replace(
            "{ kind = \"fp-cdnn\", gamma = 200.0 }",
            "{ kind = \"lvi-pdnn\", gamma = 1e7 }",
        ),
    )
    .unwrap();
    // theta_ref must fit the robot too.
    assert_rejected(
        "theta_ref_len",
        &GOOD.replace("theta0 = [", "theta_ref = [0.0, 0.0]\ntheta0 = ["),
        &["field `theta_ref`", "2 entries", "6 joints"],
    );
    assert_rejected(
        "variant_theta0_len",
        &GOOD.replace("solvers = [", "theta0 = [1.0]\nsolvers = ["),
        &["variant[0] (\"VLTCO\") field `theta0`", "1 entries"],
    );
}

/// A second experiment `id` with one variant `label`.
fn second_experiment(id: &str, label: &str) -> String {
    let start = GOOD.find("[[experiment]]").unwrap();
    GOOD[start..]
        .replace("jia2019-x", id)
        .replace("label = \"VLTCO\"", &format!("label = \"{label}\""))
}

#[test]
fn names_must_be_unique_and_file_safe() {
    assert_rejected(
        "dup_id",
        &format!("{GOOD}{}", second_experiment("jia2019-x", "VLTCO")),
        &["experiment[1] (id \"jia2019-x\") field `id`", "used twice"],
    );
    assert_rejected(
        "id_slug_collision",
        &format!("{GOOD}{}", second_experiment("jia2019-X", "VLTCO")),
        &[
            "field `id`",
            "\"jia2019-X\" is not an id",
            "(e.g. \"jia2019-x\")",
        ],
    );
    let mut two_variants = GOOD.to_string();
    two_variants.push_str(&GOOD[GOOD.find("[[experiment.variant]]").unwrap()..]);
    assert_rejected(
        "dup_label",
        &two_variants,
        &["variant[1] (\"VLTCO\") field `label`", "two variants"],
    );
    assert_rejected(
        "label_slug_collision",
        &two_variants.replacen("label = \"VLTCO\"", "label = \"vltco\"", 1),
        &[
            "field `id`",
            "both have the id \"vltco\"",
            "derived from the label",
        ],
    );
    assert_rejected(
        "id_not_a_slug",
        &GOOD.replace("label = \"VLTCO\"", "id = \"VLTCO x\"\nlabel = \"VLTCO\""),
        &["field `id`", "is not an id", "\"vltco-x\""],
    );
    assert_rejected(
        "expected_failure_of_no_solver",
        &GOOD.replace(
            "label = \"VLTCO\"",
            "label = \"VLTCO\"\nexpected_failure = { why = \"w\", solvers = [\"LVI-PDNN\"] }",
        ),
        &[
            "field `expected_failure`",
            "not a solver kind",
            "exact, lvi-pdnn",
        ],
    );
    assert_rejected(
        "dup_run_key",
        &GOOD.replace(
            "solvers = [{ kind = \"lvi-pdnn\", gamma = 1e7 }]",
            "solvers = [{ kind = \"lvi-pdnn\", gamma = 1e7 }, { kind = \"lvi-pdnn\", gamma = 1e6 }]",
        ),
        &["jia2019-x / vltco / lvi-pdnn", "listed twice"],
    );
    assert_rejected(
        "escaping_id",
        &GOOD.replace("id = \"jia2019-x\"", "id = \"jia2019-/../../etc\""),
        &["field `id`", "must not contain"],
    );
    assert_rejected(
        "escaping_label",
        &GOOD.replace("label = \"VLTCO\"", "label = \"..\\\\x\""),
        &["field `label`", "must not contain"],
    );
    // A label is shown as it is in the report's tables: no HTML, no Markdown link.
    assert_rejected(
        "html_label",
        &GOOD.replace(
            "label = \"VLTCO\"",
            "label = \"VLTCO <img src=x onerror=alert(1)>\"",
        ),
        &["field `label`", "must not contain HTML", "report/"],
    );
    assert_rejected(
        "link_label",
        &GOOD.replace("label = \"VLTCO\"", "label = \"[VLTCO](javascript:x)\""),
        &["field `label`", "a Markdown link (`](`)"],
    );
    assert_rejected(
        "empty_slug_label",
        &GOOD.replace("label = \"VLTCO\"", "label = \" () \""),
        &["field `label`", "letter or digit"],
    );
}

#[test]
fn experiment_ids_are_unique_across_files() {
    let dir = inputs::Scratch::dir("test-dupdir");
    std::fs::write(dir.join("a.toml"), GOOD).unwrap();
    std::fs::write(
        dir.join("b.toml"),
        GOOD.replace("label = \"VLTCO\"", "label = \"other\""),
    )
    .unwrap();
    let err = reproduce::load_experiments(&dir)
        .expect_err("an id defined in two files")
        .to_string();
    assert!(err.contains("b.toml") && err.contains("a.toml"), "{err}");
    assert!(
        err.contains("jia2019-x") && err.contains("also defined"),
        "{err}"
    );
    // An id that is not a slug (it would share a file name with its slug) is refused.
    std::fs::write(
        dir.join("b.toml"),
        GOOD.replace("id = \"jia2019-x\"", "id = \"jia2019-X\""),
    )
    .unwrap();
    let err = reproduce::load_experiments(&dir)
        .expect_err("an id that is not a slug")
        .to_string();
    assert!(
        err.contains("is not an id") && err.contains("b.toml"),
        "{err}"
    );
    std::fs::remove_file(dir.join("b.toml")).unwrap();
    assert_eq!(reproduce::load_experiments(&dir).unwrap().len(), 1);
}

/// The red team's file (`/tmp/redteam/cases`): the Katana on the circle, ZNN-RMP, one ZNN run,
/// with `path` and `sweep` of its variant replaced.
fn red_team_file(path: &str, sweep: &str) -> String {
    format!(
        r#"paper = "rt"
title = "redteam"
[[experiment]]
id = "rt-a"
paper_output = "none"
robot = "katana6m180"
path = {path}
theta0 = [1.2566370614359172, 1.5707963267948966, 0.0, -0.5235987755982988, 1.5471975511965976]

[[experiment.variant]]
id = "v"
label = "V"
scheme = {{ kind = "znn-rmp", mu = 1.0, k_p = 1.0 }}
solvers = [{{ kind = "znn", gamma = 1.0 }}]
{sweep}
"#
    )
}

/// The red team's inputs that hung a run inside one BDF step for minutes (a path of 1e-300 s,
/// or 1e308 m) and its sweeps whose keys set one field twice (labels gamma=0.1 and gamma=0.2
/// both ran gamma = 5): the binary refuses each at load with exit 2, naming the file, the field
/// and the range, or the experiment, the variant and both keys.
#[test]
fn hanging_paths_and_sweeps_that_set_one_field_twice_exit_2() {
    let circle = r#"{ name = "circle", duration = 0.1 }"#;
    let cases: [(&str, String, &[&str]); 7] = [
        (
            "hang-dur-tiny",
            red_team_file(r#"{ name = "circle", duration = 1e-300 }"#, ""),
            &[
                "field `path`",
                "path `duration` must be within [0.001, 100000] s, got 1e-300",
            ],
        ),
        (
            "dur-long",
            red_team_file(r#"{ name = "circle", duration = 1e6 }"#, ""),
            &["field `path`", "[0.001, 100000] s"],
        ),
        (
            "hang-scale-huge",
            red_team_file(r#"{ name = "circle", duration = 0.1, scale = 1e308 }"#, ""),
            &["field `path`", "path `scale`", "(0, 10] m, got 1e308"],
        ),
        (
            "sweep-samefield",
            red_team_file(
                circle,
                r#"sweep = { "solvers.0.gamma" = [0.1, 0.2], "solvers.*.gamma" = [5.0] }"#,
            ),
            &[
                "experiment[0] (id \"rt-a\") variant[0] (\"V\")",
                "keys \"solvers.0.gamma\" and \"solvers.*.gamma\" both set \"solvers.0.gamma\"",
            ],
        ),
        (
            "sweep-zipdup",
            red_team_file(
                circle,
                r#"sweep = { "solvers.0.gamma, solvers.0.gamma" = [[1.0, 2.0], [3.0, 4.0]] }"#,
            ),
            &[
                "variant[0] (\"V\")",
                "its paths \"solvers.0.gamma\" and \"solvers.0.gamma\" both set",
            ],
        ),
        (
            "sweep-star",
            red_team_file(
                circle,
                r#"sweep = { "solvers.*.gamma" = [0.1, 0.2], "solvers.*.gamma " = [1] }"#,
            ),
            &["variant[0] (\"V\")", "key \"solvers.*.gamma \": whitespace"],
        ),
        (
            "sweep-prefix",
            red_team_file(
                circle,
                r#"sweep = { "scheme" = [{ kind = "znn-rmp", mu = 2.0, k_p = 1.0 }], "scheme.mu" = [0.5, 1.0] }"#,
            ),
            &[
                "variant[0] (\"V\")",
                "keys \"scheme\" and \"scheme.mu\" both set \"scheme.mu\"",
            ],
        ),
    ];
    for (name, text, must) in cases {
        let dir = inputs::Scratch::dir(&format!("red-team-{name}"));
        std::fs::write(dir.join("rt.toml"), text).unwrap();
        let out = crate::common::reproduce()
            .args(["list", "--experiments-dir"])
            .arg(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains("rt.toml"), "{name}: no file named: {err}");
        for m in must {
            assert!(err.contains(m), "{name}: does not mention `{m}`: {err}");
        }
    }
}
