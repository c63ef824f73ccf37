//! The factory that builds the network of an experiment file's solver specification
//! ([`SolverSpec`], crate `settings`: the specification and its defaults) for a QP of
//! given sizes, checking the gains on the way.

use super::activation::Activation;
use super::projection::{LviPdnn, SLviPdnn};
use super::vp_rnn_pf::VpRnnPf;
use super::zeroing::ZeroingNetwork;
use super::NeuralSolver;
use qp::QpDims;
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

/// Build the network of `spec` for QPs of sizes `dims` (scratch preallocated for them). The
/// zeroing networks (the presets FP-CDNN, VP-CDNN, FTNN, ZNN, the group's, and any point of the
/// vocabulary) are built from their expansion [`SolverSpec::zeroing`].
pub fn build_solver(
    spec: &SolverSpec,
    dims: QpDims,
) -> Result<Box<dyn NeuralSolver>, NetworkError> {
    // The presets' own gain checks first, so their messages name the paper's symbol.
    match *spec {
        SolverSpec::FpCdnn { gamma, .. } => check_gain("FP-CDNN", "gamma", gamma)?,
        SolverSpec::VpCdnn { gamma, .. } => check_gain("VP-CDNN", "gamma", gamma)?,
        SolverSpec::FiniteTime { beta, alpha, .. } => {
            check_gain("FTNN", "beta", beta)?;
            if !(alpha > 0.0 && alpha < 1.0) {
                return Err(NetworkError::FiniteTimeAlpha(alpha));
            }
        }
        SolverSpec::Znn { gamma } => check_gain("ZNN", "gamma", gamma)?,
        SolverSpec::GroupZnn { gamma, .. } => check_gain("group ZNN", "gamma", gamma)?,
        _ => {}
    }
    if let Some(zeroing) = spec.zeroing() {
        return Ok(Box::new(ZeroingNetwork::from_spec(&zeroing, dims)?));
    }
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
        SolverSpec::FpCdnn { .. }
        | SolverSpec::VpCdnn { .. }
        | SolverSpec::FiniteTime { .. }
        | SolverSpec::Znn { .. }
        | SolverSpec::GroupZnn { .. }
        | SolverSpec::Zeroing { .. } => unreachable!("a zeroing network, built above"),
    })
}
