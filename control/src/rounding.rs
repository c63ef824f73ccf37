//! The rounding-noise probe: a run repeated with its state moved by one unit in the last place
//! (ulp), a model of what another order of the same floating-point operations does to the
//! state (a Schur complement instead of an LU solves the same system to within its last bits).
//! A quantity that the probe moves by a relative r is reproducible to about -log10(r) digits;
//! the digits beyond are rounding noise (crate `records`: `control-noise.csv`, and the
//! `class_under_noise` and `rate_noise` columns of `cycles-trend.csv`).
//!
//! With [`Rounding::OneUlp`], after every tick k of the discrete loop (module `control_loop`:
//! the arm has moved to theta_{k+1} under the held command) each joint angle is replaced by a
//! floating-point neighbour,
//!
//!   theta_{k+1,j} <- next_up(theta_{k+1,j})   if u_{k N + j} = 1,
//!   theta_{k+1,j} <- next_down(theta_{k+1,j}) otherwise,
//!
//! for the joints j = 0 ... N - 1, where u_i is the top bit of the i-th output of splitmix64
//! (Steele, Lea and Flood, OOPSLA 2014) seeded by [`SEED`]: one draw per joint and tick, in
//! the order of the ticks and the joints, the same sequence in every run. next_up(v) is the
//! least f64 above v, next_down(v) the greatest below (`f64::next_up`, `f64::next_down`), so
//! each angle moves by exactly one ulp of its own value. The joint rates (the acceleration
//! level's thetadot) are not moved. A run in continuous time (module `continuous`) has no
//! ticks: there theta_0 is moved once, the same way (draws 0 ... N - 1), before the first cycle.
//!
//! [`Rounding::AsComputed`] moves nothing: the run is the one the loop computes, bit for bit.

/// The splitmix64 state the moves' sequence starts from (a constant: every probe is the same).
pub const SEED: u64 = 0x6472_6966_7462_656e;

/// Splitmix64's increment, the golden ratio's 64-bit fraction.
const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// How a run treats the state after each tick.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Rounding {
    /// The state as computed (the results' runs).
    #[default]
    AsComputed,
    /// Every joint angle moved by one ulp, up or down, after every tick (module docs).
    OneUlp,
}

impl Rounding {
    /// The moves of a run with this rounding, from the start of their sequence: none for
    /// [`Rounding::AsComputed`].
    pub(crate) fn moves(self) -> Option<UlpMoves> {
        match self {
            Rounding::AsComputed => None,
            Rounding::OneUlp => Some(UlpMoves { state: SEED }),
        }
    }
}

/// The sequence of one-ulp moves of a run (module docs): a splitmix64 generator.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct UlpMoves {
    state: u64,
}

impl UlpMoves {
    /// Splitmix64's next output.
    fn next(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GAMMA);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// The next draw's direction: up when the top bit of splitmix64's next output is set.
    fn next_is_up(&mut self) -> bool {
        self.next() >> 63 == 1
    }

    /// Moves every angle of `theta` by one ulp, each in the direction of the next draw.
    pub(crate) fn apply(&mut self, theta: &mut [f64]) {
        for v in theta {
            *v = one_ulp(*v, self.next_is_up());
        }
    }
}

/// `v`'s floating-point neighbour above (`up`) or below.
fn one_ulp(v: f64, up: bool) -> f64 {
    if up {
        v.next_up()
    } else {
        v.next_down()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_ulp_moves_by_exactly_one_unit_in_the_last_place() {
        for v in [
            0.3,
            -1.7,
            1.0,
            -1.0,
            2.0f64.powi(-3),
            1e-300,
            12.5,
            -0.0,
            0.0,
        ] {
            let (up, down) = (one_ulp(v, true), one_ulp(v, false));
            assert!(up > v && down < v, "{v}");
            // Adjacent: nothing lies strictly between v and either neighbour, and the bit
            // patterns of same-signed finite values are consecutive integers.
            if v > 0.0 {
                assert_eq!(up.to_bits(), v.to_bits() + 1, "{v}");
                assert_eq!(down.to_bits(), v.to_bits() - 1, "{v}");
            } else if v < 0.0 {
                assert_eq!(up.to_bits(), v.to_bits() - 1, "{v}");
                assert_eq!(down.to_bits(), v.to_bits() + 1, "{v}");
            } else {
                assert_eq!((up, down), (f64::from_bits(1), -f64::from_bits(1)));
            }
        }
        // At a power of two the ulp below is half the ulp above.
        assert_eq!(1.0 - one_ulp(1.0, false), (one_ulp(1.0, true) - 1.0) / 2.0);
    }

    #[test]
    fn the_moves_are_one_fixed_sequence() {
        let mut a = Rounding::OneUlp.moves().unwrap();
        let mut b = Rounding::OneUlp.moves().unwrap();
        let draws: Vec<bool> = (0..4096).map(|_| a.next_is_up()).collect();
        assert!(draws.iter().all(|&u| u == b.next_is_up()));
        // Both directions, about evenly.
        let ups = draws.iter().filter(|&&u| u).count();
        assert!((1800..2300).contains(&ups), "{ups}");
        // Splitmix64's first outputs from the seed 0 (the reference implementation's).
        let mut zero = UlpMoves { state: 0 };
        assert_eq!(zero.next(), 0xe220_a839_7b1d_cdaf);
        assert_eq!(zero.next(), 0x6e78_9e6a_a1b9_65f4);
        assert!(Rounding::AsComputed.moves().is_none());
    }

    #[test]
    fn apply_moves_each_angle_one_ulp_in_the_sequence_order() {
        let theta0 = [0.1, -2.3, 1.5, 0.0, 3.0];
        let mut theta = theta0;
        let mut moves = Rounding::OneUlp.moves().unwrap();
        let mut reference = moves.clone();
        moves.apply(&mut theta);
        for (v, v0) in theta.iter().zip(theta0) {
            assert_eq!(*v, one_ulp(v0, reference.next_is_up()));
        }
        // The sequence goes on: the next tick's draws follow the first tick's.
        assert_eq!(moves, reference);
    }
}
