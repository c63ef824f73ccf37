//! The factory that builds the network of an experiment file's solver specification
//! ([`SolverSpec`], crate `settings`: the specification and its defaults) for a QP of
//! given sizes, checking the gains on the way.

use super::projection::ProjectionNetwork;
use super::zeroing::ZeroingNetwork;
use super::NeuralSolver;
use qp::QpDims;
use settings::NetworkError;
use settings::SolverSpec;

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

/// Build the network of `spec` for QPs of sizes `dims` (scratch preallocated for them). Every
/// network is a point of one of the two families' vocabularies and is built from its expansion:
/// the zeroing family ([`SolverSpec::zeroing`]: the presets FP-CDNN, VP-CDNN, FTNN, ZNN, the
/// group's, and any zeroing point) or the projection family ([`SolverSpec::projection`]: the
/// presets LVI-PDNN, S-LVI-PDNN, VP-RNN-PF, and any projection point).
pub fn build_solver(
    spec: &SolverSpec,
    dims: QpDims,
) -> Result<Box<dyn NeuralSolver>, NetworkError> {
    // The presets' own gain checks first, so their messages name the paper's symbol.
    match *spec {
        SolverSpec::LviPdnn { gamma } => check_gain("LVI-PDNN", "gamma", gamma)?,
        SolverSpec::SLviPdnn { beta } => check_gain("S-LVI-PDNN", "beta", beta)?,
        SolverSpec::VpRnnPf { gamma, .. } => check_gain("VP-RNN-PF", "gamma", gamma)?,
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
        SolverSpec::Zeroing { .. } | SolverSpec::Projection { .. } => {}
    }
    match (spec.zeroing(), spec.projection()) {
        (Some(zeroing), _) => Ok(Box::new(ZeroingNetwork::from_spec(&zeroing, dims)?)),
        (None, Some(projection)) => Ok(Box::new(ProjectionNetwork::from_spec(&projection, dims)?)),
        (None, None) => unreachable!("every network is of one of the two families"),
    }
}
