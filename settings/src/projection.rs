//! The projection family as a point of the network vocabulary ([`ProjectionSpec`]): networks
//! that drive an error of the QP's optimality conditions with its inequality rows and bounds to
//! zero, told apart by the error's form, a gain law ([`GainLaw`], the zeroing family's
//! vocabulary) and an activation (`docs/networks.md` lists every term).
//!
//! # The error forms ([`ProjectionErrorForm`])
//!
//! `lvi`: the projection equation of the QP's linear variational inequality (jia2019 (2.21),
//! M, q and the box Omega there), on the state y = [x; u; v] (nx + n_eq + n_in entries),
//!
//! ```text
//! e(y) = P_Omega(y - (M y + q)) - y                                     jia2019 (2.22)
//! ydot = g(t) S Phi(e(y))
//! ```
//!
//! with the scaling S ([`Scaling`]) `i-plus-mt`: S = I + M' (LVI-PDNN, jia2019 (2.23)) or
//! `identity`: S = I (S-LVI-PDNN, zhong2021 (2.35)).
//!
//! `penalty`: the inequality rows and bounds moved into the objective by the exponential penalty
//! p sum_i exp(-sigma N_i(x)), N_i = h_i - B_i x (zhong2021 (2.19)-(2.21)); the error is the
//! penalised Lagrangian's gradient phi(y) on y = [x; lambda] (zhong2021 (2.24)-(2.25)), and
//! the zeroing design formula phidot = -g(t) Phi(phi) (zhong2021 (2.26)) gives the implicit
//! network W ydot = -S y - g(t) Phi(phi) + mu of zhong2021 (2.30) (W = dphi/dy).
//!
//! # The presets
//!
//! The papers' networks of this family are presets ([`crate::SolverSpec::projection`]):
//! `lvi-pdnn` = `lvi` with `i-plus-mt`, constant gain gamma, linear; `s-lvi-pdnn` = `lvi` with
//! `identity`, constant gain beta, linear; `vp-rnn-pf` = `penalty` (p, sigma), exponential gain
//! gamma exp(t), its activation.

use crate::activation::ActivationSpec;
use crate::zeroing::GainLaw;
use serde::{Deserialize, Serialize};

/// The matrix S in front of the activated projection residual of the `lvi` form (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scaling {
    /// S = I + M' (jia2019 (2.23), LVI-PDNN).
    IPlusMt,
    /// S = I (zhong2021 (2.35), S-LVI-PDNN).
    Identity,
}

impl Scaling {
    /// The scaling's name in files and ids.
    pub fn id(self) -> &'static str {
        match self {
            Scaling::IPlusMt => "i-plus-mt",
            Scaling::Identity => "identity",
        }
    }
}

/// The error a projection-family network drives to zero (module docs), written in files as a
/// table with its `form`.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(tag = "form", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ProjectionErrorForm {
    /// e = P_Omega(y - (M y + q)) - y (jia2019 (2.22)); ydot = g(t) S Phi(e).
    Lvi {
        /// S.
        scaling: Scaling,
    },
    /// The penalised Lagrangian's gradient (zhong2021 (2.19)-(2.25)) under the zeroing design
    /// formula (zhong2021 (2.26), (2.30)).
    Penalty {
        /// The penalty factor p (>= 0).
        p: f64,
        /// The penalty's sharpness sigma (> 0).
        sigma: f64,
    },
}

impl ProjectionErrorForm {
    /// The form with its parameters, e.g. `lvi(i-plus-mt)`, `penalty(p=0.0001,sigma=400)`.
    pub fn name(&self) -> String {
        match self {
            ProjectionErrorForm::Lvi { scaling } => format!("lvi({})", scaling.id()),
            ProjectionErrorForm::Penalty { p, sigma } => format!("penalty(p={p},sigma={sigma})"),
        }
    }
}

/// A projection-family network, every part named (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectionSpec {
    /// The name errors and labels use (a preset's paper name, e.g. `LVI-PDNN`, or `projection`).
    pub name: &'static str,
    /// The error driven to zero, with its scaling or penalty.
    pub error: ProjectionErrorForm,
    /// g(t).
    pub gain: GainLaw,
    /// Phi.
    pub activation: ActivationSpec,
}

impl ProjectionSpec {
    /// Whether the network needs dQP/dt: the `penalty` form's zeroing design does, the `lvi`
    /// form does not.
    pub fn needs_qp_dot(&self) -> bool {
        matches!(self.error, ProjectionErrorForm::Penalty { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize)]
    struct Holder {
        error: ProjectionErrorForm,
    }

    #[test]
    fn forms_read_with_their_parameters_and_nothing_else() {
        let lvi: Holder =
            toml::from_str("error = { form = \"lvi\", scaling = \"identity\" }").expect("lvi form");
        assert_eq!(
            lvi.error,
            ProjectionErrorForm::Lvi {
                scaling: Scaling::Identity
            }
        );
        assert_eq!(lvi.error.name(), "lvi(identity)");
        for (bad, named) in [
            (
                "error = { form = \"lvi\", scaling = \"diag\" }",
                "i-plus-mt",
            ),
            (
                "error = { form = \"lvi\", scaling = \"identity\", p = 1.0 }",
                "scaling",
            ),
            (
                "error = { form = \"penalty\", p = 1.0, sigma = 2.0, scaling = \"identity\" }",
                "sigma",
            ),
            ("error = { form = \"kkt\" }", "penalty"),
        ] {
            let e = toml::from_str::<Holder>(bad).err().expect(bad).to_string();
            assert!(e.contains(named), "{bad}: {e}");
        }
    }
}
