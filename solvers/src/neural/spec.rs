//! The factory that builds the network of an experiment file's solver specification
//! ([`SolverSpec`], crate `settings`: the specification and its defaults) for a QP of
//! given sizes, checking the gains on the way.

use super::activation::Activation;
use super::cdnn::{fp_cdnn, vp_cdnn};
use super::group::group_znn;
use super::projection::{LviPdnn, SLviPdnn};
use super::vp_rnn_pf::VpRnnPf;
use super::znn::{finite_time, znn};
use super::NeuralSolver;
use schemes::qp::QpDims;
use settings::error::NetworkError;
use settings::solver_spec::SolverSpec;

fn check_gain(network: &'static str, symbol: &'static str, v: f64) -> Result<(), NetworkError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(NetworkError::Gain {
            network,
            symbol,
            value: v,
        })
    }
}

/// Build the network of `spec` for QPs of sizes `dims` (scratch preallocated for them).
pub fn build_solver(
    spec: &SolverSpec,
    dims: QpDims,
) -> Result<Box<dyn NeuralSolver>, NetworkError> {
    Ok(match *spec {
        SolverSpec::LviPdnn { gamma } => {
            check_gain("LVI-PDNN", "gamma", gamma)?;
            Box::new(LviPdnn::new(gamma, dims))
        }
        SolverSpec::SLviPdnn { beta } => {
            check_gain("S-LVI-PDNN", "beta", beta)?;
            Box::new(SLviPdnn::new(beta, dims))
        }
        SolverSpec::VpRnnPf {
            p,
            sigma,
            gamma,
            activation,
        } => {
            check_gain("VP-RNN-PF", "gamma", gamma)?;
            Box::new(VpRnnPf::new(
                p,
                sigma,
                gamma,
                Activation::from(activation),
                dims,
            )?)
        }
        SolverSpec::FpCdnn {
            gamma,
            activation,
            perturbation,
        } => {
            check_gain("FP-CDNN", "gamma", gamma)?;
            Box::new(fp_cdnn(gamma, activation.into(), perturbation, dims)?)
        }
        SolverSpec::VpCdnn {
            gamma,
            activation,
            perturbation,
        } => {
            check_gain("VP-CDNN", "gamma", gamma)?;
            Box::new(vp_cdnn(gamma, activation.into(), perturbation, dims)?)
        }
        SolverSpec::FiniteTime {
            beta,
            alpha,
            smoothing,
        } => {
            check_gain("FTNN", "beta", beta)?;
            Box::new(finite_time(beta, alpha, smoothing, dims)?)
        }
        SolverSpec::Znn { gamma } => {
            check_gain("ZNN", "gamma", gamma)?;
            Box::new(znn(gamma, dims)?)
        }
        SolverSpec::GroupZnn {
            gamma,
            nu,
            activation,
            perturbation,
            udot_rmp,
        } => {
            check_gain("group ZNN", "gamma", gamma)?;
            let act = activation.into();
            Box::new(group_znn(gamma, nu, act, perturbation, udot_rmp, dims)?)
        }
    })
}
