//! A robot written outside the library, run through a paper's scheme.
//!
//! A 4-joint arm: a yaw joint at the base, then three pitch joints in the vertical plane it
//! turns (links 0.30, 0.25, 0.15 m; shoulder 0.20 m above the base). With cumulative pitch
//! angles phi_k = theta_2 + ... + theta_k, horizontal reach r = sum l_k cos(phi_k) and height
//! z = h + sum l_k sin(phi_k), the tip is f(theta) = (cos(theta_1) r, sin(theta_1) r, z), and
//!
//! ```text
//! J_1 = (-sin(theta_1) r, cos(theta_1) r, 0),
//! J_j = (-cos(theta_1) S_j, -sin(theta_1) S_j, C_j)    (j >= 2),
//! ```
//!
//! with the suffix sums S_j = sum_{k>=j} l_k sin(phi_k), C_j = sum_{k>=j} l_k cos(phi_k).
//! `Robot::jacobian_dot` is taken here by a central difference of J along thetadot (h = 1e-6):
//! a user can start that way and write the exact derivative later. Implementing
//! `robots::Robot` (joint vectors as slices, Jacobians written into the caller's 3 x n buffer,
//! column-major) is all the suite asks; `simulation::simulate` then runs it
//! through kong2019's ZNN scheme (eq. 22) on a circle, solved exactly and by kong2019's ZNN.
//!
//! `cargo run --release --example user_robot`

use catalog::default_exact_integrator;
use nalgebra::{DVector, Vector3};
use robots::{JointLimits, Robot};
use schemes::build_scheme;
use schemes::paths::build_path;
use settings::IntegratorSettings;
use settings::SolverSpec;
use simulation::build_network;
use simulation::{simulate, Outcome, Settings, Solver};
use spec::NetworkInit;
use spec::PathSpec;
use spec::SchemeSpec;
use spec::Scoring;
use std::sync::Arc;

/// The 4-joint arm of the module docs.
struct FourJointArm {
    shoulder: f64,
    links: [f64; 3],
    limits: JointLimits,
}

impl FourJointArm {
    /// (r, z, S_2..S_4, C_2..C_4) at theta.
    fn sums(&self, theta: &[f64]) -> (f64, f64, [f64; 3], [f64; 3]) {
        let mut phi = 0.0;
        let mut s = [0.0; 3];
        let mut c = [0.0; 3];
        for k in 0..3 {
            phi += theta[k + 1];
            s[k] = self.links[k] * phi.sin();
            c[k] = self.links[k] * phi.cos();
        }
        // Suffix sums: entry j holds the sum over links j.. .
        for k in (0..2).rev() {
            s[k] += s[k + 1];
            c[k] += c[k + 1];
        }
        (c[0], self.shoulder + s[0], s, c)
    }
}

impl Robot for FourJointArm {
    fn name(&self) -> &'static str {
        "four-joint-arm (user)"
    }

    fn dof(&self) -> usize {
        4
    }

    fn position(&self, theta: &[f64]) -> Vector3<f64> {
        let (r, z, _, _) = self.sums(theta);
        Vector3::new(theta[0].cos() * r, theta[0].sin() * r, z)
    }

    fn jacobian(&self, theta: &[f64], j: &mut [f64]) {
        let (r, _, s, c) = self.sums(theta);
        let (s1, c1) = theta[0].sin_cos();
        j[..3].copy_from_slice(&[-s1 * r, c1 * r, 0.0]);
        for k in 0..3 {
            j[3 * (k + 1)..3 * (k + 2)].copy_from_slice(&[-c1 * s[k], -s1 * s[k], c[k]]);
        }
    }

    fn jacobian_dot(&self, theta: &[f64], thetadot: &[f64], jdot: &mut [f64]) {
        let h = 1e-6;
        let (mut plus, mut minus) = ([0.0; 4], [0.0; 4]);
        for i in 0..4 {
            plus[i] = theta[i] + thetadot[i] * h;
            minus[i] = theta[i] - thetadot[i] * h;
        }
        let mut jm = [0.0; 12];
        self.jacobian(&plus, jdot);
        self.jacobian(&minus, &mut jm);
        for (d, m) in jdot.iter_mut().zip(jm) {
            *d = (*d - m) / (2.0 * h);
        }
    }

    fn limits(&self) -> &JointLimits {
        &self.limits
    }
}

/// Drift and tracking error of the exact column and of kong2019's ZNN on the user's arm.
fn run() -> Vec<(String, f64, f64)> {
    let robot = Arc::new(FourJointArm {
        shoulder: 0.20,
        links: [0.30, 0.25, 0.15],
        limits: JointLimits {
            theta_min: DVector::repeat(4, -3.0),
            theta_max: DVector::repeat(4, 3.0),
            thetadot_min: DVector::repeat(4, -2.0),
            thetadot_max: DVector::repeat(4, 2.0),
        },
    });
    let theta_star = [0.3, 0.9, -1.2, -0.6];
    let path: Arc<dyn schemes::paths::Path> = Arc::from(
        build_path(&PathSpec::new("circle", 9.0), robot.position(&theta_star))
            .expect("the circle is a known path"),
    );
    // kong2019 eq. 22 with mu = 1, k_p = 1.
    let spec = SchemeSpec::ZnnRmp { mu: 1.0, k_p: 1.0 };
    let scheme = build_scheme(&spec, robot.clone(), None, path.clone(), &theta_star)
        .expect("kong2019's ZNN scheme with valid gains");
    let dims = scheme.dims();
    // The networks as the papers integrate them (BDF, RelTol 1e-6, AbsTol 1e-8, as ode15s);
    // the exact column as the suite does (Dormand-Prince, RelTol 1e-11: converged).
    let networks = Settings {
        integrator: IntegratorSettings::default(),
        scoring: Scoring::EveryStep,
        network_init: NetworkInit::Zero,
    };
    let exact = Settings {
        integrator: default_exact_integrator(),
        ..networks.clone()
    };
    let scheme_name = scheme.name();
    let znn = move || build_network(&SolverSpec::Znn { gamma: 1.0 }, dims, &scheme_name);
    [
        ("exact", Solver::Exact),
        ("ZNN (kong2019, gamma = 1)", Solver::Network(&znn)),
    ]
    .into_iter()
    .map(|(name, solver)| {
        let settings = if matches!(solver, Solver::Exact) {
            &exact
        } else {
            &networks
        };
        let run = simulate(
            robot.as_ref(),
            path.as_ref(),
            scheme.as_ref(),
            solver,
            &theta_star,
            &theta_star,
            settings,
        )
        .expect("the run starts");
        match &run.outcome {
            Outcome::Completed(m) => (name.to_string(), m.drift_norm, m.max_position_error),
            Outcome::Failed { error, .. } => panic!("{name}: {error}"),
        }
    })
    .collect()
}

fn main() {
    println!("kong2019 ZNN scheme on a circle (T = 9 s), a 4-joint arm written in this example");
    println!("{:<28} {:>10} {:>10}", "solver", "|drift|", "max err");
    for (name, drift, err) in run() {
        println!("{name:<28} {drift:>10.3e} {err:>10.3e}");
    }
}
