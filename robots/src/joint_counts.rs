//! The joint counts a robot file may have: those the simulation is instantiated for (Katana 5,
//! Jaco2 6, Panda 7, and the registry's n-link sizes). One list (`with_joint_counts!`), from
//! which both [`JOINT_COUNTS`] (checked when a robot file is parsed, [`crate::robot_file`]) and
//! the data model of each count ([`crate::data_robot::DataModel`]) are declared, so the two
//! cannot disagree.

/// Calls the macro `$declare` with the joint counts, each as `Variant = count` (the name of its
/// [`crate::data_robot::DataModel`] variant).
macro_rules! with_joint_counts {
    ($declare:ident) => {
        $declare!(
            J3 = 3,
            J5 = 5,
            J6 = 6,
            J7 = 7,
            J10 = 10,
            J15 = 15,
            J20 = 20,
            J30 = 30
        );
    };
}
pub(crate) use with_joint_counts;

/// Declares [`JOINT_COUNTS`] from the list.
macro_rules! joint_count_list {
    ($($variant:ident = $n:literal),* $(,)?) => {
        /// The joint counts a robot file may have (module docs).
        pub const JOINT_COUNTS: &[usize] = &[$($n),*];
    };
}
with_joint_counts!(joint_count_list);
