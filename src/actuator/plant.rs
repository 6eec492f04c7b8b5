//! How the simulated plant moves each kind: where its spool (or its drive's
//! direction) goes for the outputs of a scan, what it does with none on,
//! and how a load drifts it. The piston itself (stroke, sensors, position)
//! is the simulator's; what differs between kinds is here.

use super::{ActuatorKind, CoilSet};
use crate::stroke::Stroke;

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

    /// Its own times, if its kind has them, for an actuator the engineer
    /// gave none (`--stroke`, the actuator table): a suction cup's vacuum
    /// builds up in 300 ms (its switch then reads 1) and is gone 200 ms
    /// after the coil drops, where a cylinder's default stroke is 1 s.
    ///
    /// A swivel drive turns its 180° in 500 ms each way. Festo gives a
    /// DSM-16 vane drive (part 547574) a swivel frequency of at most 2 Hz
    /// at 6 bar, a swing of 250 ms at the least; its DSR/DSRL catalogue
    /// asks for 6 bar once throttled below 180°/s, a swing of 1 s. A swivel
    /// arm with its load is throttled between the two: 500 ms for 180°.
    pub fn default_stroke(self) -> Option<Stroke> {
        match self {
            ActuatorKind::Vacuum => Some(Stroke {
                extend_ms: 300,
                retract_ms: 200,
            }),
            ActuatorKind::Swivel => Some(Stroke {
                extend_ms: 500,
                retract_ms: 500,
            }),
            _ => None,
        }
    }

    /// What its switch at `position` reads at `s`, the fraction of its
    /// stroke (for a gripper: of its full vacuum), for a kind whose switch
    /// is no position sensor seen within a window: a vacuum switch reads 1
    /// once the vacuum has fully built up while the coil is on (after the
    /// build-up time), and keeps reading 1 while the coil is off until the
    /// vacuum has fully decayed (the part drops then, after the whole
    /// release time, not the moment the coil drops, nor the 4 % before
    /// the end at which a cylinder's sensor sees its piston). `None`: a
    /// position sensor.
    pub fn switch_reads(self, position: u32, spool: Spool, s: f64) -> Option<bool> {
        // Rounding of the per-scan steps, not a window.
        const FULL: f64 = 1e-9;
        match (self, position) {
            (ActuatorKind::Vacuum, 1) => Some(match spool {
                Spool::Plus => s >= 1.0 - FULL,
                Spool::Minus | Spool::Centre => s > FULL,
            }),
            _ => None,
        }
    }

    /// Whether it may move on once a jog button is released (a 5/2
    /// bistable or a swivel drive finishes the swing a jog began, a spring
    /// retracts, a 5/3 centre lets a load drift): the simulator counts that
    /// motion as the operator's. A 5/3 closed centre and a drive stop on
    /// release, so any motion of theirs without the button is unintended.
    pub fn moves_on_after_a_jog(self) -> bool {
        !matches!(self, ActuatorKind::Closed53 | ActuatorKind::Motor)
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

    /// A swivel drive's 5/2 valve keeps its spool as a `52bi` does: the arm
    /// turns on to the end stop last chosen, and both coils conflict.
    #[test]
    fn a_swivel_drive_keeps_turning_to_its_last_end_stop() {
        use ActuatorKind::*;
        assert_eq!(Swivel.rest_spool(), Spool::Minus);
        assert_eq!(Swivel.switch(Spool::Plus, false, false), Spool::Plus);
        assert_eq!(Swivel.switch(Spool::Minus, true, false), Spool::Plus);
        assert_eq!(Swivel.switch(Spool::Plus, false, true), Spool::Minus);
        assert!(Swivel.conflict(true, true));
        assert_eq!(Swivel.drift_per_second(0.5), 0.0);
        assert!(!Swivel.coasts());
        assert!(Swivel.moves_on_after_a_jog() && Bistable52.moves_on_after_a_jog());
        assert!(!Closed53.moves_on_after_a_jog() && !Motor.moves_on_after_a_jog());
        assert_eq!(Swivel.switch_reads(1, Spool::Plus, 1.0), None);
    }

    #[test]
    fn a_vacuum_gripper_holds_while_its_coil_is_on_and_releases_without() {
        use ActuatorKind::*;
        assert_eq!(Vacuum.rest_spool(), Spool::Minus);
        assert_eq!(Vacuum.switch(Spool::Minus, true, false), Spool::Plus);
        assert_eq!(Vacuum.switch(Spool::Plus, false, false), Spool::Minus);
        assert!(!Vacuum.conflict(true, true));
        assert_eq!(Vacuum.drift_per_second(0.5), 0.0);
        assert!(!Vacuum.coasts());
        // Built up only when full; held until the vacuum is all gone.
        assert_eq!(Vacuum.switch_reads(1, Spool::Plus, 0.5), Some(false));
        assert_eq!(Vacuum.switch_reads(1, Spool::Plus, 0.97), Some(false));
        assert_eq!(Vacuum.switch_reads(1, Spool::Plus, 1.0), Some(true));
        assert_eq!(Vacuum.switch_reads(1, Spool::Minus, 0.5), Some(true));
        assert_eq!(Vacuum.switch_reads(1, Spool::Minus, 0.01), Some(true));
        assert_eq!(Vacuum.switch_reads(1, Spool::Minus, 0.0), Some(false));
        assert_eq!(Mono52.switch_reads(1, Spool::Plus, 1.0), None);
        let times = Vacuum.default_stroke().expect("a gripper's own times");
        let swing = Swivel.default_stroke().expect("a swivel drive's own time");
        assert_eq!((swing.extend_ms, swing.retract_ms), (500, 500));
        assert!(times.extend_ms < Stroke::default().extend_ms);
        assert_eq!(Bistable52.default_stroke(), None);
    }
}
