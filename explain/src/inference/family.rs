//! The setup family the inference searches, read from `experiments/`[`FAMILY_FILE`] through
//! the input reader (every member can be switched off there; an absent file means
//! [`Family::default`]).
//!
//! Continuous members: the in-plane rotation psi in [0, 2 pi), the start phase in [0, 1) on
//! the closed curves (where on the figure the start point lies: the placement relative to the
//! start point), the size factor in [1/4, 4] where the size is our assumption, and the tilt of
//! the drawing plane about the base x and y axes, each in [-pi/2, pi/2] (the plane's offsets
//! are mapped by R = Ry(tilt_y) Rx(tilt_x) Rz(psi)). Discrete members: the direction, the RMP
//! reading (tables with an RMP term), the robot model (the declared one and the variants
//! listed per declared robot), and how the drift is computed
//! ([`records::inference::Integration`]).

use super::search::Budget;
use crate::error::{FamilyError, InferenceError};
use records::inference::Integration;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// Where the family is declared, relative to the experiments directory (a subdirectory, which
/// the experiment loader does not read).
pub const FAMILY_FILE: &str = "inference/family.toml";

/// The family and the search budget.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Family {
    pub rotation: bool,
    pub phase: bool,
    pub scale: bool,
    /// The plane's tilt about the base x and y axes.
    pub tilt: bool,
    pub direction: bool,
    pub rmp_readings: bool,
    /// Network hypotheses beside the exact column (always tried).
    pub network: Vec<Integration>,
    /// Per declared robot id, the variants to try beside it.
    pub robot_variants: BTreeMap<String, Vec<String>>,
    /// Global points per discrete combination.
    pub global_per_combo: usize,
    /// Nelder-Mead starts for the whole table.
    pub joint_starts: usize,
    /// Nelder-Mead starts per column fitted alone (0: no column fits of their own).
    pub column_starts: usize,
    /// Nelder-Mead iterations per start.
    pub iterations: u64,
    /// Profiles of the joint optimum.
    pub profiles: bool,
    /// Nelder-Mead iterations re-fitting the other parameters at each profile point (0:
    /// slices).
    pub profile_iterations: u64,
}

impl Default for Family {
    fn default() -> Self {
        Self {
            rotation: true,
            phase: true,
            scale: true,
            tilt: true,
            direction: true,
            rmp_readings: true,
            network: vec![Integration::NetworkMatlabDefault],
            robot_variants: BTreeMap::from([(
                robots::JACO2_PEN.to_string(),
                vec![robots::JACO2_PEN_EXP2.to_string()],
            )]),
            global_per_combo: 16,
            joint_starts: 4,
            column_starts: 1,
            iterations: 50,
            profiles: true,
            profile_iterations: 10,
        }
    }
}

impl Family {
    /// Reads `experiments/`[`FAMILY_FILE`] as an input (`inputs::Kind::InferenceFamily`: a
    /// regular file inside `experiments`, at most 1 MiB, never quoted in an error; an absent
    /// file: the default family); checks the robot ids.
    pub fn load(experiments: &Path) -> Result<Self, InferenceError> {
        let path = experiments.join(FAMILY_FILE);
        let err = |error: FamilyError| InferenceError::Family {
            file: path.clone(),
            error,
        };
        let origin = inputs::Origin::Under(experiments);
        let family: Family = match inputs::read_text(&path, inputs::Kind::InferenceFamily, origin) {
            Ok(text) => inputs::parse_toml(&text).map_err(|e| err(e.into()))?,
            Err(e) if e.is_not_found() => Family::default(),
            Err(e) => return Err(e.into()),
        };
        family.check().map_err(err)?;
        Ok(family)
    }

    /// Every robot id known to the registry, with the declared robot's joint count.
    fn check(&self) -> Result<(), FamilyError> {
        for (declared, variants) in &self.robot_variants {
            let dof = |name: &str| {
                robots::robot_by_name(name)
                    .map(|r| r.dof())
                    .map_err(|e| FamilyError::UnknownRobot(e.to_string()))
            };
            let n = dof(declared)?;
            for v in variants {
                if dof(v)? != n {
                    return Err(FamilyError::JointCount {
                        variant: v.clone(),
                        declared: declared.clone(),
                    });
                }
            }
        }
        if self.network.contains(&Integration::Exact) {
            return Err(FamilyError::ExactNetwork);
        }
        Ok(())
    }

    /// The variants to try beside `robot`.
    pub fn variants_of(&self, robot: &str) -> &[String] {
        self.robot_variants
            .get(robot)
            .map(Vec::as_slice)
            .unwrap_or(&[])
    }

    /// The search budget.
    pub fn budget(&self) -> Budget {
        Budget {
            global_per_combo: self.global_per_combo,
            joint_starts: self.joint_starts,
            column_starts: self.column_starts,
            iterations: self.iterations,
            profiles: self.profiles,
            profile_iterations: self.profile_iterations,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    /// A scratch `experiments/` (with `inference/`) and the directory that holds it (removed
    /// when dropped).
    fn scratch(tag: &str) -> (PathBuf, inputs::Scratch) {
        let base = inputs::Scratch::dir(&format!("family-{tag}"));
        std::fs::create_dir_all(base.join("experiments/inference")).unwrap();
        (base.join("experiments"), base)
    }

    #[test]
    fn the_committed_family_file_reads_and_names_known_robots() {
        let experiments = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments");
        assert!(experiments.join(FAMILY_FILE).exists());
        let f = Family::load(&experiments).unwrap();
        assert!(f.tilt && !f.network.is_empty());
    }

    #[test]
    fn unknown_robots_fields_and_an_exact_network_are_refused() {
        let bad = [
            "robot_variants = { jaco2-pen = [\"no-such-arm\"] }",
            "robot_variants = { jaco2-pen = [\"katana6m180\"] }",
            "network = [\"exact\"]",
            "tilts = true",
        ];
        let (experiments, _base) = scratch("bad");
        for text in bad {
            std::fs::write(experiments.join(FAMILY_FILE), text).unwrap();
            assert!(Family::load(&experiments).is_err(), "{text}");
        }
        std::fs::remove_file(experiments.join(FAMILY_FILE)).unwrap();
        assert_eq!(Family::load(&experiments).unwrap(), Family::default());
    }

    #[cfg(unix)]
    #[test]
    fn a_hostile_family_file_is_refused_without_its_content() {
        let (experiments, _base) = scratch("hostile");
        let dir = experiments.clone();
        inputs::assert_refuses_hostile_files(
            &experiments.join(FAMILY_FILE),
            inputs::Kind::InferenceFamily,
            "tilt = true\n",
            &[format!(
                "# {}\niterations = \"many\"\n",
                inputs::HOSTILE_MARKER
            )],
            move || Family::load(&dir).err().map(|e| e.to_string()),
        );
    }
}
