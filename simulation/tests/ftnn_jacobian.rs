//! The coupled arm + finite-time network Jacobian (kong2019's FTNN on its finite-time scheme,
//! Katana 6M180, circle) agrees with central differences taken with steps small enough to stay
//! inside the sign-power's band (|dE| << delta = 1e-6), at states along the run where joint 3's
//! error sits inside the band and joint 5's is zero. Differencing F as a whole with step
//! sqrt(eps) (what the Jacobian used to do) gave columns up to ~1000x too small there.

use nalgebra::{DMatrix, SVector};
use robots::Katana6m180;
use robots::Robot;
use schemes::build_scheme;
use schemes::paths::{build_path, Path};
use spec::PathSpec;
use spec::SchemeSpec;

use settings::IntegratorSettings;
use settings::SolverSpec;
use simulation::NeuralLoop;
use solvers::neural::build_solver;
use solvers::ode::{integrate, Control, OdeSystem};
use std::sync::Arc;

#[test]
fn coupled_ftnn_jacobian_matches_fine_central_differences() {
    let robot: Arc<dyn Robot> = Arc::new(Katana6m180::new());
    // kong2019's theta*0: (2 pi/5, pi/2, 0, -pi/6, pi/3).
    let pi = std::f64::consts::PI;
    let theta_ref = SVector::<f64, 5>::from([2.0 * pi / 5.0, pi / 2.0, 0.0, -pi / 6.0, pi / 3.0]);
    let mut theta0 = theta_ref;
    theta0[4] += 0.5;
    let spec: PathSpec = toml::from_str("name = \"circle\"\nduration = 9.0").unwrap();
    let path: Arc<dyn Path> =
        Arc::from(build_path(&spec, robot.position(theta_ref.as_slice())).unwrap());
    let spec = SchemeSpec::FiniteTimeRmp {
        beta_theta: 1.0,
        k_p: 1.0,
        alpha: 0.1,
    };
    let scheme = build_scheme(&spec, robot.clone(), None, path, theta_ref.as_slice()).unwrap();
    let ftnn = SolverSpec::FiniteTime {
        beta: 1.0,
        alpha: 0.1,
        smoothing: 1e-6,
    };
    let net = build_solver(&ftnn, scheme.dims()).unwrap();
    let mut sys = NeuralLoop::new(scheme.as_ref(), net);
    let n = sys.dim();
    let mut y0 = vec![0.0; n];
    y0[..5].copy_from_slice(theta0.as_slice());
    // States at t ~ 0.001 (converging), 0.5 (joint 5 on its way) and 2.5 (joint 5 converged).
    let checkpoints = [1e-3, 0.5, 2.5];
    let mut states: Vec<(f64, Vec<f64>)> = Vec::new();
    integrate(
        &mut sys,
        &y0,
        0.0,
        2.5,
        &IntegratorSettings::default(),
        |t, y| {
            if states.len() < checkpoints.len() && t >= checkpoints[states.len()] {
                states.push((t, y.to_vec()));
            }
            Control::Continue
        },
    )
    .expect("the FTNN run integrates");
    assert_eq!(states.len(), checkpoints.len());
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    for (t, y) in &states {
        // Joint 3's error inside the band: the case the old Jacobian got wrong.
        assert!(
            (y[2] - theta_ref[2]).abs() < 1e-6,
            "e_3 = {}",
            y[2] - theta_ref[2]
        );
        let mut analytic = DMatrix::zeros(n, n);
        assert!(sys.jacobian(*t, y, &mut analytic));
        let mut fd = DMatrix::zeros(n, n);
        for j in 0..n {
            // |dE| <= ~2.5e5 h ~ 1e-8 << delta.
            let h = 4e-14 * y[j].abs().max(1.0);
            let mut yp = y.clone();
            yp[j] = y[j] + h;
            let hi = yp[j];
            sys.rhs(*t, &yp, &mut fp);
            yp[j] = y[j] - h;
            let lo = yp[j];
            sys.rhs(*t, &yp, &mut fm);
            for i in 0..n {
                fd[(i, j)] = (fp[i] - fm[i]) / (hi - lo);
            }
        }
        let scale = fd.amax();
        assert!(scale > 1e9, "the band's slopes show: {scale:e}");
        for j in 0..n {
            for i in 0..n {
                let d = (analytic[(i, j)] - fd[(i, j)]).abs();
                assert!(
                    d <= 1e-2 * fd[(i, j)].abs() + 1e-3 * scale,
                    "t = {t}: J[{i},{j}] = {:e}, central differences {:e}",
                    analytic[(i, j)],
                    fd[(i, j)]
                );
            }
        }
    }
}
