//! How the simulated plant moves each kind: where its spool (or its drive's
//! direction) goes for the outputs of a scan, what it does with none on,
//! and how a load drifts it. The piston itself (stroke, sensors, position)
//! is the simulator's; what differs between kinds is here.

use super::{ActuatorKind, CoilSet};

/// Where the valve's spool is (for a drive: which way it runs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Spool {
    /// Air to the + side: the piston moves towards higher positions.
    Plus,
    /// Air to the - side.
    Minus,
    /// 5/3 closed centre: both ports shut, the piston holds.
    Centre,
}

impl ActuatorKind {
    /// The spool at power-up: centred if the kind has a centre, else
    /// towards home.
    pub fn rest_spool(self) -> Spool {
        if self.has_centre() {
            Spool::Centre
        } else {
            Spool::Minus
        }
    }

    /// The spool after a scan's outputs `plus` and `minus`, from `spool`.
    /// For a single-solenoid valve only `plus` is wired: on extends, off
    /// lets the spring retract.
    pub fn switch(self, spool: Spool, plus: bool, minus: bool) -> Spool {
        if self.coils() == CoilSet::Single {
            return if plus { Spool::Plus } else { Spool::Minus };
        }
        match (plus, minus) {
            (true, false) => Spool::Plus,
            (false, true) => Spool::Minus,
            // No coil: a bistable spool stays, a spring-centred one centres.
            // Both coils: a 5/2 spool stays where it was; a 5/3 spool is
            // pushed from both sides and stays centred.
            (false, false) | (true, true) if self.has_centre() => Spool::Centre,
            _ => spool,
        }
    }

    /// Whether `plus` and `minus` together are a conflict no actuator of
    /// this kind may see (a single coil has no second one to conflict).
    pub fn conflict(self, plus: bool, minus: bool) -> bool {
        self.coils() == CoilSet::Double && plus && minus
    }

    /// The stroke fraction per second it moves with no output on under
    /// `load` (negative towards home): an exhausted centre lets the load
    /// pull it home, a pressurised one creeps outwards; others hold.
    pub fn drift_per_second(self, load: f64) -> f64 {
        match self {
            ActuatorKind::Exhaust53 => -load.abs(),
            ActuatorKind::Pressure53 => load.abs(),
            _ => 0.0,
        }
    }

    /// Whether, cut while running onto a limit switch, it coasts to the
    /// switch's point (a drive's braking distance, the same every time).
    pub fn coasts(self) -> bool {
        self.is_drive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spools_follow_the_outputs_by_kind() {
        use ActuatorKind::*;
        // A bistable spool keeps its place with no coil and with both.
        assert_eq!(Bistable52.switch(Spool::Plus, false, false), Spool::Plus);
        assert_eq!(Bistable52.switch(Spool::Plus, true, true), Spool::Plus);
        // A 5/3 spool centres with none and with both.
        assert_eq!(Closed53.switch(Spool::Plus, false, false), Spool::Centre);
        assert_eq!(Closed53.switch(Spool::Minus, true, true), Spool::Centre);
        // The spring of a 52mono takes it back when its one coil drops.
        assert_eq!(Mono52.switch(Spool::Plus, false, true), Spool::Minus);
        assert!(!Mono52.conflict(true, true));
        assert!(Motor.conflict(true, true));
        assert_eq!(Motor.rest_spool(), Spool::Centre);
        assert_eq!(Bistable52.rest_spool(), Spool::Minus);
        assert_eq!(Exhaust53.drift_per_second(0.2), -0.2);
        assert_eq!(Pressure53.drift_per_second(-0.2), 0.2);
        assert_eq!(Closed53.drift_per_second(0.2), 0.0);
    }
}
