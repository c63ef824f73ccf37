//! Task cards: one Markdown page per task, rendered from a typed model ([`TaskCard`]) that the
//! orchestrator builds from the experiment files and the suite's own models
//! (`reproduce::task_card`: the robot's kinematics and limits, the path's values at a few
//! instants, the start, the scheme's QP at t = 0). This module computes nothing: it formats
//! the numbers it is handed, to full precision (Rust's shortest round-trip form), and the
//! schemes' QPs as formulas (jia2019 (2.17)-(2.20), zhong2021 (2.16)-(2.18), zhang2018
//! (2.5)-(2.6), kong2019 (14) and (22)).
//!
//! [`render`] gives every card and the index ([`INDEX`]) by file name.

use spec::Level;
use spec::PathSample;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The index page's file name.
pub const INDEX: &str = "README.md";

/// One task's card.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskCard {
    /// `<experiment> / <variant>`.
    pub task: String,
    /// The card's file name (`<experiment>--<variant slug>.md`).
    pub file_name: String,
    /// The paper id (the experiment file's name).
    pub paper: String,
    /// Whether the task is one of the cross experiment's (the leaderboard's standard task set
    /// is drawn from them).
    pub cross: bool,
    /// Every run on the task, in the experiment file's order.
    pub runs: Vec<CardRun>,
    /// The robot.
    pub robot: RobotCard,
    /// The start.
    pub start: StartCard,
    /// The path.
    pub path: PathCard,
    /// The scheme.
    pub scheme: SchemeCard,
}

/// One run on a task: its solver's label and settings.
#[derive(Clone, Debug, PartialEq)]
pub struct CardRun {
    /// The solver's label.
    pub label: String,
    /// Its settings.
    pub settings: RunSettings,
}

/// A run's settings, as the experiment file writes them (TOML values).
#[derive(Clone, Debug, PartialEq)]
pub enum RunSettings {
    /// The exact optimum, integrated by `integrator`.
    Exact { integrator: toml::Value },
    /// A network `spec`, integrated by `integrator`.
    Neural {
        spec: toml::Value,
        integrator: toml::Value,
    },
    /// A numerical method in a fixed-step loop, its settings with the defaults filled in.
    Numerical { settings: toml::Value },
}

/// The name of a scheme's level on the card.
fn level_label(level: Level) -> &'static str {
    match level {
        Level::Velocity => "velocity",
        Level::Acceleration => "acceleration",
    }
}

/// The robot: its name, kinematics, mount and limits.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotCard {
    /// The robot's registry name.
    pub name: String,
    /// The joint count n.
    pub joints: usize,
    /// Its kinematics.
    pub kinematics: Kinematics,
    /// The experiment's mount, when it mounts the robot.
    pub mount: Option<MountCard>,
    /// theta- per joint (rad; infinite where unlimited).
    pub theta_min: Vec<f64>,
    /// theta+ per joint (rad).
    pub theta_max: Vec<f64>,
    /// thetadot- per joint (rad/s).
    pub thetadot_min: Vec<f64>,
    /// thetadot+ per joint (rad/s).
    pub thetadot_max: Vec<f64>,
}

/// An experiment's mount of the robot.
#[derive(Clone, Debug, PartialEq)]
pub struct MountCard {
    /// The tool offset in the tool frame (m).
    pub tool: [f64; 3],
    /// The base's translation (m).
    pub base_origin: [f64; 3],
    /// The base's rotation, row by row (9 entries).
    pub base_rotation_rows: Vec<f64>,
}

/// A robot's kinematics.
#[derive(Clone, Debug, PartialEq)]
pub enum Kinematics {
    /// Classical DH: link i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i).
    Dh {
        /// The robot file declaring it, if any.
        file: Option<String>,
        /// (a_i, alpha_i, d_i) per link.
        links: Vec<[f64; 3]>,
        /// The base's rotation (world from DH frame 0), by rows.
        base_rotation: Vec<Vec<f64>>,
        /// The base frame's origin (m).
        base_origin: [f64; 3],
        /// The joint offsets (rad).
        offsets: Vec<f64>,
        /// The DH frame holding the task point (the chain's joint count).
        frame: usize,
        /// The task point in that frame (m).
        tool: [f64; 3],
    },
    /// kong2019 (2): the Katana's closed form, link lengths l1..l5 (m).
    Katana { l: [f64; 5] },
    /// A URDF chain declared by a robot file.
    Urdf {
        file: String,
        urdf: String,
        base: String,
        tip: String,
    },
    /// The synthetic n-link arm.
    NLink(usize),
}

/// The task's start.
#[derive(Clone, Debug, PartialEq)]
pub struct StartCard {
    /// theta0 (rad).
    pub theta0: Vec<f64>,
    /// theta_ref, the scheme's theta*0, where the path starts (rad).
    pub theta_ref: Vec<f64>,
    /// f(theta0) (m).
    pub position0: [f64; 3],
    /// J(theta0), by rows.
    pub jacobian0: Vec<Vec<f64>>,
}

/// The task's path.
#[derive(Clone, Debug, PartialEq)]
pub struct PathCard {
    /// The path's name.
    pub name: String,
    /// Its parameters as in the experiment file.
    pub params: toml::Value,
    /// Its size (m), given or the path's default; none for paths without one.
    pub size: Option<f64>,
    /// The duration T (s).
    pub duration: f64,
    /// r_start = f(theta_ref) (m).
    pub start: [f64; 3],
    /// r*, rdot*, rddot* at a few instants.
    pub samples: Vec<PathSample>,
}

/// The task's scheme.
#[derive(Clone, Debug, PartialEq)]
pub struct SchemeCard {
    /// Its display name.
    pub name: String,
    /// Its level.
    pub level: Level,
    /// Its parameters as in the experiment file.
    pub params: toml::Value,
    /// Which formula states its QP.
    pub form: SchemeForm,
    /// Its terms, one line each, in the order they write the QP.
    pub terms: Vec<String>,
    /// Its QP at t = 0.
    pub qp0: QpCard,
}

/// The scheme whose QP the card states as formulas.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchemeForm {
    /// jia2019's VLTCO.
    Vltco,
    /// zhong2021's CMCO.
    Cmco,
    /// zhang2018's HL-JDF.
    HlJdf,
    /// kong2019 (14).
    FiniteTimeRmp,
    /// kong2019 (22).
    ZnnRmp,
    /// A scheme stated by its terms alone.
    Terms,
}

/// A QP `min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,  lower <= x <= upper`, matrices by rows.
#[derive(Clone, Debug, PartialEq)]
pub struct QpCard {
    pub p: Vec<Vec<f64>>,
    pub a: Vec<Vec<f64>>,
    pub g: Vec<Vec<f64>>,
    pub q: Vec<f64>,
    pub b: Vec<f64>,
    pub h: Vec<f64>,
    pub lower: Vec<f64>,
    pub upper: Vec<f64>,
}

/// Every card of `cards` by its file name, and the index ([`INDEX`]).
pub fn render(cards: &[TaskCard]) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut index = String::from(
        "# Task cards\n\nGenerated by the reproduction from `experiments/*.toml` \
         (`reproduce::task_card`); do not edit. One card per task (experiment / variant): the \
         robot's kinematics and limits, the path, the start, and the scheme's QP with its \
         numbers, so that the task can be set up in other code and its trajectory scored here \
         with `reproduce score FILE --task \"<experiment> / <variant>\"` (velocity-level \
         tasks). The leaderboard's standard task set is drawn from the cross experiment's tasks \
         (those whose exact column completed).\n\n\
         | task | paper | robot | path | T (s) | scheme | level | card |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for c in cards {
        let name = &c.file_name;
        let _ = writeln!(
            index,
            "| {} | {} | `{}` | `{}` | {} | {} | {} | [{name}]({name}) |",
            c.task,
            c.paper,
            c.robot.name,
            c.path.name,
            c.path.duration,
            c.scheme.name,
            level_label(c.scheme.level),
        );
        out.insert(name.clone(), card(c));
    }
    out.insert(INDEX.to_string(), index);
    out
}

/// One task's card: the runs on it, the robot, the start, the path and the scheme.
fn card(c: &TaskCard) -> String {
    let mut s = runs_section(c);
    s.push_str(&robot_section(&c.robot));
    s.push_str(&start_section(&c.start));
    s.push_str(&path_section(&c.path));
    s.push_str(&scheme_section(&c.scheme));
    s
}

/// The card's title and what it is, then the task's paper, duration and every run on it (its
/// solver's and integrator's settings), and how to score a trajectory of it.
fn runs_section(c: &TaskCard) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# {}\n", c.task);
    let _ = writeln!(
        s,
        "Task card generated from `experiments/{}.toml` by the reproduction; do not edit. \
         Numbers are printed to full precision (Rust's shortest round-trip form: `1.0`, `1e-10`).\n",
        c.paper
    );
    let _ = writeln!(s, "- paper: {}", c.paper);
    let _ = writeln!(s, "- duration T = {} s", c.path.duration);
    let _ = writeln!(s, "- runs on this task:");
    for run in &c.runs {
        let label = &run.label;
        match &run.settings {
            RunSettings::Exact { integrator } => {
                let _ = writeln!(s, "  - {label}: integrator `{}`", inline(integrator));
            }
            RunSettings::Neural { spec, integrator } => {
                let _ = writeln!(
                    s,
                    "  - {label}: `{}`, integrator `{}`",
                    inline(spec),
                    inline(integrator)
                );
            }
            RunSettings::Numerical { settings } => {
                let _ = writeln!(
                    s,
                    "  - {label}: `{}`, a fixed-step loop (spec::numerical)",
                    inline(settings)
                );
            }
        }
    }
    if c.cross {
        let _ = writeln!(
            s,
            "- a task of the cross experiment: in the leaderboard's standard task set when its exact column completed"
        );
    }
    if c.scheme.level == Level::Velocity {
        let _ = writeln!(
            s,
            "- score a trajectory of it: `reproduce score FILE --task \"{}\"`",
            c.task
        );
    }
    s
}

/// `## Robot`: its kinematics and limits.
fn robot_section(r: &RobotCard) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Robot `{}` ({} joints)\n", r.name, r.joints);
    s.push_str(&kinematics(&r.kinematics));
    if let Some(m) = &r.mount {
        let _ = writeln!(
            s,
            "\nMounted by the experiment (`tool`, `base`; docs/robots.md): tool offset {} m in \
             the tool frame; base: translation {} m, rotation row by row {}.",
            vector(&m.tool),
            vector(&m.base_origin),
            vector(&m.base_rotation_rows),
        );
    }
    s.push_str("\nLimits (rad, rad/s; inf: none):\n\n| joint | theta- | theta+ | thetadot- | thetadot+ |\n|---|---|---|---|---|\n");
    for i in 0..r.joints {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            i + 1,
            r.theta_min[i],
            r.theta_max[i],
            r.thetadot_min[i],
            r.thetadot_max[i]
        );
    }
    s
}

/// `## Start`: theta0, theta_ref, the task point and the Jacobian at theta0.
fn start_section(st: &StartCard) -> String {
    let mut s = String::from("\n## Start\n\n");
    let _ = writeln!(s, "- theta0 = {} rad", vector(&st.theta0));
    let _ = writeln!(
        s,
        "- theta_ref (the scheme's theta*0, where the path starts) = {} rad",
        vector(&st.theta_ref)
    );
    let _ = writeln!(s, "- f(theta0) = {} m", vector(&st.position0));
    let _ = writeln!(s, "- J(theta0) =\n\n```text\n{}```", matrix(&st.jacobian0));
    s
}

/// `## Path`: its parameters and size, the formula, and r* and its derivatives at sampled t.
fn path_section(p: &PathCard) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Path `{}`\n", p.name);
    let _ = writeln!(
        s,
        "Parameters (as in the experiment file): `{}`; size: {}.\n",
        inline(&p.params),
        p.size.map_or_else(|| "-".to_string(), |v| format!("{v} m")),
    );
    let _ = writeln!(
        s,
        "r*(t) = r_start + dr(phi(t)), r_start = f(theta_ref) = {} m, with the rest-to-rest time law \
         phi(t) = 2 pi sin^2(pi t / (2T)) (stroke paths: per stroke); dr, the shape of `{}`, is in \
         docs/paths.md (code: `schemes/src/paths/`). Then rotated by `rotation`, tilted by \
         `tilt_x`, `tilt_y`, started at `phase`, reversed by `reverse` where given.\n",
        vector(&p.start),
        p.name
    );
    s.push_str("| t (s) | r* (m) | rdot* (m/s) | rddot* (m/s^2) |\n|---|---|---|---|\n");
    for x in &p.samples {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} |",
            x.t,
            vector(&x.r),
            vector(&x.rdot),
            vector(&x.rddot)
        );
    }
    s
}

/// `## Scheme`: its parameters and formula, and its QP at t = 0.
fn scheme_section(sc: &SchemeCard) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "\n## Scheme: {} ({} level)\n\nParameters: `{}`\n\n```text\n{}```\n",
        sc.name,
        level_label(sc.level),
        inline(&sc.params),
        formula(sc.form)
    );
    let _ = writeln!(
        s,
        "Its terms, in the order they write the QP (`schemes/src/terms/`):\n\n```text\n{}\n```\n",
        sc.terms.join("\n")
    );
    let _ = writeln!(
        s,
        "The QP `min x'Px/2 + q'x  s.t.  A x = b,  G x <= h,  lower <= x <= upper` at t = 0, \
         theta = theta0{}:\n\n```text\n{}```",
        if sc.level == Level::Acceleration {
            ", thetadot = 0"
        } else {
            ""
        },
        qp(&sc.qp0)
    );
    s
}

/// The robot's kinematics: the DH table and tool, or the closed form.
fn kinematics(k: &Kinematics) -> String {
    let mut s = String::new();
    match k {
        Kinematics::Dh {
            file,
            links,
            base_rotation,
            base_origin,
            offsets,
            frame,
            tool,
        } => {
            if let Some(file) = file {
                let _ = writeln!(
                    s,
                    "Declared by the robot file `{file}` (its `source` gives the numbers' origin).\n"
                );
            }
            s.push_str("Classical DH, link i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i):\n\n| i | a_i (m) | alpha_i (rad) | d_i (m) |\n|---|---|---|---|\n");
            for (i, [a, alpha, d]) in links.iter().enumerate() {
                let _ = writeln!(s, "| {} | {a} | {alpha} | {d} |", i + 1);
            }
            let _ = writeln!(
                s,
                "\nBase (world from DH frame 0): rotation\n\n```text\n{}```",
                matrix(base_rotation)
            );
            let _ = writeln!(
                s,
                "Base frame origin {} m; joint offsets {} rad; task point in DH frame {frame}: {} m.",
                vector(base_origin),
                vector(offsets),
                vector(tool)
            );
        }
        Kinematics::Katana {
            l: [l1, l2, l3, l4, l5],
        } => {
            let _ = writeln!(
                s,
                "kong2019 (2), in the paper's joint convention (Cij = cos(theta_i + theta_j), ...):\n\n\
                 ```text\n\
                 h    = l2 C2 + l3 C23 + L S234\n\
                 f(θ) = [ C1 h,  S1 h,  l1 - L C234 + l2 S2 + l3 S23 ]\n\
                 l1 = {l1}, l2 = {l2}, l3 = {l3}, L = l4 + l5 = {l4} + {l5} m\n\
                 ```\n\nJoint 5 (the wrist roll) does not move the task point."
            );
        }
        Kinematics::Urdf {
            file,
            urdf,
            base,
            tip,
        } => {
            let _ = writeln!(
                s,
                "Declared by the robot file `{file}` (its `source` gives the numbers' origin): the \
                 chain of the URDF `{urdf}` from link `{base}` to link `{tip}` (joint origins, axes \
                 and limits as the URDF gives them; `robots/src/urdf.rs`)."
            );
        }
        Kinematics::NLink(n) => {
            let _ = writeln!(
                s,
                "The synthetic {n}-link arm: a yaw joint and {} pitch joints (`robots/src/nlink.rs`).",
                n - 1
            );
        }
    }
    s
}

/// The scheme's QP as formulas (the scheme modules' docs; parameters by the papers' names).
fn formula(form: SchemeForm) -> &'static str {
    match form {
        SchemeForm::Vltco => {
            "jia2019 (2.17)-(2.20), x = [thetadot; p] in R^(n+1), p = |thetadot|_inf:\n\
             P = diag((phi + tau) I_n, 1 - phi - tau)\n\
             q = [tau Lambda (theta - theta0); 0]        (Lambda = lambda; rmp: the reading of it)\n\
             A = [J 0],  b = rdot*\n\
             G = [I -1; -I -1],  h = 0                    (|thetadot_i| <= p)\n\
             lower = [zeta-; 0],  upper = [zeta+; +inf]\n\
             zeta-_i = max{kappa (theta-_i - theta_i), thetadot-_i}\n\
             zeta+_i = min{kappa (theta+_i - theta_i), thetadot+_i}\n"
        }
        SchemeForm::Cmco => {
            "zhong2021 (2.16)-(2.18), x = [thetadot; k] in R^(n+1), k = |thetadot|_inf:\n\
             P = diag((eta + delta) I_n, 1 - eta - delta)\n\
             q = [delta Lambda (theta - theta0); 0]      (Lambda = lambda; rmp: the reading of it)\n\
             A = [J 0],  b = rdot*\n\
             G = [s; E; -E],  s = [I -1; -I -1],  E = I_(n+1)\n\
             h = [0; x+; -x-],  x- = [zeta-; 0],  x+ = [zeta+; +inf]\n\
             zeta-_i = upsilon (theta-_i - theta_i) if theta_i <= theta-_i - thetadot-_i / upsilon, else thetadot-_i\n\
             zeta+_i = thetadot+_i if theta_i <= theta+_i - thetadot+_i / upsilon, else upsilon (theta+_i - theta_i)\n\
             lower, upper = -inf, +inf (every bound is a row of G)\n"
        }
        SchemeForm::HlJdf => {
            "zhang2018 (2.5)-(2.6), acceleration level, x = thetaddot in R^n:\n\
             P = zeta I + (1 - zeta) H^2\n\
             q = zeta sigma + (1 - zeta) H'(c + g),  sigma = (alpha + beta) thetadot + alpha beta (theta - theta0)\n\
             A = J,  b = rddot* - Jdot thetadot + rho_v (rdot* - J thetadot) + rho_p (r* - f(theta))\n\
             no inequalities, no bounds (H, c, g: the arm's inertia, Coriolis and gravity terms)\n"
        }
        SchemeForm::FiniteTimeRmp => {
            "kong2019 (14), x = thetadot in R^n:\n\
             P = I\n\
             q = beta_theta c,  c_i = |e_i|^alpha sgn(e_i),  e = theta - theta*0\n\
             \x20   (smoothed: c_i = e_i (e_i^2 + delta^2)^((alpha - 1)/2), delta = 1e-6 rad)\n\
             A = J,  b = rdot* + k_p (r* - f(theta))\n\
             no inequalities, no bounds\n"
        }
        SchemeForm::ZnnRmp => {
            "kong2019 (22), x = thetadot in R^n:\n\
             P = I\n\
             q = mu (theta - theta*0)\n\
             A = J,  b = rdot* + k_p (r* - f(theta))\n\
             no inequalities, no bounds\n"
        }
        SchemeForm::Terms => "its terms, below (docs/schemes.md)\n",
    }
}

/// The QP's numbers, one block per non-empty part.
fn qp(qp: &QpCard) -> String {
    let mut s = String::new();
    for (name, m) in [("P", &qp.p), ("A", &qp.a), ("G", &qp.g)] {
        if !m.is_empty() {
            let _ = write!(s, "{name} =\n{}", matrix(m));
        }
    }
    for (name, v) in [
        ("q", &qp.q),
        ("b", &qp.b),
        ("h", &qp.h),
        ("lower", &qp.lower),
        ("upper", &qp.upper),
    ] {
        if !v.is_empty() {
            let _ = writeln!(s, "{name} = {}", vector(v));
        }
    }
    s
}

fn vector(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
    format!("[{}]", items.join(", "))
}

fn matrix(rows: &[Vec<f64>]) -> String {
    rows.iter().map(|r| format!("  {}\n", vector(r))).collect()
}

/// A value as a TOML inline table, as experiment files write it.
fn inline(v: &toml::Value) -> String {
    match v {
        toml::Value::Table(t) => {
            let items: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k} = {}", inline(v)))
                .collect();
            format!("{{ {} }}", items.join(", "))
        }
        toml::Value::Array(a) => {
            let items: Vec<String> = a.iter().map(inline).collect();
            format!("[{}]", items.join(", "))
        }
        toml::Value::Float(x) => format!("{x:?}"),
        other => other.to_string(),
    }
}
