//! The repetitive-motion (RMP) term's linear coefficient: three readings of the papers.
//!
//! jia2019 and zhong2021 both minimise w ||thetadot + C||^2 / 2 with C = gain (theta - theta0)
//! (w = tau in jia2019, delta in zhong2021). Expanded, the term is
//! w (thetadot' thetadot + 2 C' thetadot + C' C) / 2, so the QP's linear term is
//! g = w gain (theta - theta0). The papers write it differently in three places:
//!
//! - **jia2019**: C = mu (theta - theta0) (jia2019 (2.3), (2.7)), mu "set as mu = 5" (text
//!   after jia2019 (2.9)); jia2019 (2.11) writes tau ||thetadot + C||^2 / 2 =
//!   tau (thetadot' I thetadot + Lambda thetadot) / 2 with Lambda = 2 mu, i.e. linear term
//!   tau (Lambda / 2) (theta - theta0); the QP data of jia2019 (2.17)-(2.20) print
//!   g = [tau Lambda (theta - theta0); 0], and section III sets Lambda = 20.
//! - **zhong2021**: c = tau (theta - theta0), tau > 0 (text after zhong2021 (2.3)/(2.4); the
//!   value of this tau, a gain and not jia2019's weight, is never given); zhong2021 (2.10)
//!   writes delta ||thetadot + c||^2 / 2 = delta (thetadot' I thetadot + Lambda thetadot)
//!   (without the / 2) with Lambda = 2 tau; the QP data of zhong2021 (2.16)-(2.18) print
//!   g = [delta Lambda (theta - theta0); 0], and section III (A and B) sets Lambda = 20.
//!
//! The readings of the coefficient k in g = [w k (theta - theta0); 0] ([`RmpReading::coefficient`]):
//!
//! | reading | k | jia2019 at Lambda = 20, mu = 5 | zhong2021 at Lambda = 20 |
//! |---|---|---|---|
//! | `printed` (default) | Lambda | 20 | 20 |
//! | `expansion` | Lambda / 2 | 10 | 10 |
//! | `text-mu` (alias `text-tau`) | the text's gain (jia2019 mu, zhong2021 tau) | 5 | tau (default 10 = Lambda / 2) |
//!
//! `printed` is what the QPs print and what every result so far uses.

use serde::{Deserialize, Serialize};

/// Which reading of the RMP term's linear coefficient a scheme uses (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RmpReading {
    /// k = Lambda, the QP data as printed (jia2019 (2.17)-(2.20), zhong2021 (2.16)-(2.18)).
    #[default]
    Printed,
    /// k = Lambda / 2, the expansion of ||thetadot + C||^2 / 2 with Lambda = 2 gain
    /// (jia2019 (2.11), zhong2021 (2.10)).
    Expansion,
    /// k = the text's gain itself: jia2019's mu (= 5 in the text), zhong2021's tau.
    #[serde(rename = "text-mu", alias = "text-tau")]
    TextGain,
}

impl RmpReading {
    /// The coefficient k of g = w k (theta - theta0), given Lambda and the text's gain
    /// (jia2019 mu, zhong2021 tau; used only by [`RmpReading::TextGain`]).
    pub fn coefficient(self, lambda: f64, gain: f64) -> f64 {
        match self {
            Self::Printed => lambda,
            Self::Expansion => 0.5 * lambda,
            Self::TextGain => gain,
        }
    }

    /// The serde name: `printed`, `expansion` or `text-mu`.
    pub fn label(self) -> &'static str {
        match self {
            Self::Printed => "printed",
            Self::Expansion => "expansion",
            Self::TextGain => "text-mu",
        }
    }

    /// Whether this is the default reading ([`RmpReading::Printed`]).
    pub fn is_printed(&self) -> bool {
        *self == Self::Printed
    }
}
