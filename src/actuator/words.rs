//! The words a kind is said in: what the comments call it and its sensors
//! and coils, the verbs of its moves, and the sentences of its messages
//! (a conflict, an output kept through an EMERGENCY STOP, a load it
//! ignores, a position it cannot hold). Every stage that names an actuator
//! to the engineer asks here, so a new kind brings its own words and no
//! message outside the model says "cylinder" of something that is not.

use super::ActuatorKind;

impl ActuatorKind {
    /// Why one of its outputs may not stay on through an EMERGENCY STOP:
    /// `output` is its symbol (`y1+`), `actuator` its number.
    pub fn kept_through_estop(self, output: &str, actuator: u32) -> String {
        if self == ActuatorKind::Swivel {
            format!(
                "{output} is a valve coil of swivel drive C{actuator}: left on, it swings the arm on to its end stop from wherever it stood when the EMERGENCY STOP came; only a machine output that holds a part (a vacuum, a clamp as Y:clamp) may stay on"
            )
        } else if self.is_drive() {
            format!(
                "{output} is a contactor of drive C{actuator} (valve type motor): left on, it keeps the drive running through the EMERGENCY STOP; every drive stops"
            )
        } else {
            format!(
                "{output} is a valve coil of C{actuator}: left on, it drives the piston on from wherever it stood when the EMERGENCY STOP came; only a machine output that holds a part (a vacuum, a clamp as Y:clamp) may stay on, and a clamp on a 52bi valve keeps its position with both coils off"
            )
        }
    }

    /// A coil's verb said of its actuator, the actuator after the verb's
    /// first word: `extend C1`, `run C1 forward`, `swivel C3 back to 0°`.
    pub fn verb_of(verb: &str, actuator: &str) -> String {
        match verb.split_once(' ') {
            Some((first, rest)) => format!("{first} {actuator} {rest}"),
            None => format!("{verb} {actuator}"),
        }
    }

    /// What its one coil does, for the comments of the rungs that switch
    /// it: on, then off (`52mono`: extend, the spring retracts).
    pub fn single_coil_words(self) -> (&'static str, &'static str) {
        if self.holds_part() {
            ("vacuum on, grip", "vacuum off, release")
        } else {
            ("extend", "the spring retracts")
        }
    }

    /// What the comments call it: a gripper, a drive (a motor's limit
    /// switches are no cylinder's), a swivel drive or a cylinder.
    pub fn noun(self) -> &'static str {
        match self {
            _ if self.holds_part() => "gripper",
            _ if self.is_drive() => "drive",
            ActuatorKind::Swivel => "swivel drive",
            _ => "cylinder",
        }
    }

    /// What its sensor at `position` (of `max_position`) is, for the signal
    /// comments: `label` is the actuator as the table names it.
    pub fn sensor_comment(self, label: &str, position: u32, max_position: u32) -> String {
        if self.holds_part() {
            return format!("{} {label}, vacuum switch (on: part held)", self.noun());
        }
        if self == ActuatorKind::Swivel {
            let at = if position == 0 { "0° (home)" } else { "180°" };
            return format!("{} {label}, at {at}", self.noun());
        }
        let which = if position == 0 {
            "home position 0".to_string()
        } else if position == max_position {
            format!("end position {position}")
        } else {
            format!("middle position {position}")
        };
        format!("{} {label}, {which}", self.noun())
    }

    /// What seeing both outputs on means for actuator `number` (the start
    /// of the simulator's hazard).
    pub fn both_on(self, number: u32) -> String {
        if self.is_drive() {
            format!("the drive of C{number} gets forward and reverse")
        } else if self == ActuatorKind::Swivel {
            format!("the 5/2 valve of swivel drive C{number} sees both coils")
        } else {
            format!("the valve of C{number} sees both coils")
        }
    }

    /// The comment of the rung that stops actuator `actuator` at its
    /// sensor `sensor` (a middle stop, or a drive's every target).
    pub fn stop_comment(self, actuator: u32, sensor: &str) -> String {
        if self.is_drive() {
            format!(
                "C{actuator} is a drive: at its limit switch {sensor} both outputs off, it stands"
            )
        } else {
            format!(
                "middle stop: C{actuator} stops at {sensor} (both coils off, the 5/3 valve holds it)"
            )
        }
    }

    /// What its `+` and `-` coils (or jog buttons) do, for their comments
    /// and the actions that set them (`extend`, `retract`).
    pub fn coil_words(self) -> (&'static str, &'static str) {
        match self {
            // A gripper's jog buttons grip and release.
            _ if self.holds_part() => ("grip", "release"),
            // A drive's contactors run it, as its jog buttons say.
            _ if self.is_drive() => ("run forward", "run in reverse"),
            ActuatorKind::Swivel => ("swivel to 180°", "swivel back to 0°"),
            _ => ("extend", "retract"),
        }
    }

    /// What it does while its `+` or `-` output is on, for the manual jog
    /// rungs and the convert report's stroke times (`extends`, `retracts`;
    /// a drive runs forward or in reverse, a gripper grips and releases).
    pub fn move_words(self) -> (&'static str, &'static str) {
        match self {
            _ if self.holds_part() => ("grips", "releases"),
            _ if self.is_drive() => ("runs forward", "runs in reverse"),
            ActuatorKind::Swivel => ("swivels to 180°", "swivels back to 0°"),
            _ => ("extends", "retracts"),
        }
    }

    /// Why a load (`--load`) on actuator `number` of this kind moves
    /// nothing, for W006: a cylinder's valve holds its piston (a 52mono's
    /// spring holds it home), a swivel drive its arm, a drive stands, a
    /// gripper has no piston at all.
    pub fn load_held(self, number: u32) -> String {
        match self {
            _ if self.holds_part() => format!(
                "C{number} is a vacuum {} (valve type {self}), not a cylinder: it has no piston",
                self.noun()
            ),
            _ if self.is_drive() => format!(
                "C{number} is an electric drive (valve type {self}), which stands with both contactors off"
            ),
            ActuatorKind::Mono52 => format!(
                "C{number}'s valve is {self}, whose spring holds the piston home with no coil on"
            ),
            ActuatorKind::Swivel => {
                format!("C{number}'s valve is {self}, which holds the arm at its end stop")
            }
            _ => format!("C{number}'s valve is {self}, which holds the piston"),
        }
    }

    /// Where actuator `actuator` stands in a finding, for a kind whose
    /// positions are no places (`place`: 0 at position 0, 1 between 0 and
    /// 1, 2 at 1; `sensor` the reading of a position): a gripper holds its
    /// part or has released it. `None`: a place on its stroke.
    pub fn place_said(
        self,
        actuator: u32,
        place: u32,
        sensor: &dyn Fn(u32) -> String,
    ) -> Option<String> {
        if !self.holds_part() {
            return None;
        }
        Some(match place {
            0 => format!("C{actuator} released ({})", sensor(0)),
            2 => format!("C{actuator} holding its part ({})", sensor(1)),
            _ => format!("C{actuator} building up or losing its vacuum"),
        })
    }

    /// That actuator `actuator` had not reached position `to` (`sensor` its
    /// reading there), for a kind whose positions are no places: a gripper
    /// had not gripped or released. `None`: "had not reached" a sensor.
    pub fn unreached_said(self, actuator: u32, to: u32, sensor: &str) -> Option<String> {
        if !self.holds_part() {
            return None;
        }
        Some(if to == 0 {
            format!("C{actuator} had not released its part (waiting for {sensor})")
        } else {
            format!("C{actuator} had not gripped its part (waiting for {sensor})")
        })
    }

    /// How the table moves actuator `actuator` of a kind with positions
    /// 0 to [`ActuatorKind::highest_position`] only, for E045.
    pub fn positions_said(self, actuator: u32) -> String {
        if self.holds_part() {
            format!("a vacuum gripper: C{actuator}+1 holds the part, C{actuator}-0 releases it")
        } else if self == ActuatorKind::Swivel {
            format!(
                "a swivel drive: C{actuator}+1 swivels it to 180°, C{actuator}-0 back to 0°, its home; it cannot stop between its end stops"
            )
        } else {
            format!("C{actuator}+1 moves it to its end, C{actuator}-0 home")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every sentence an engineer reads of a swivel drive calls it one and
    /// says where it turns; a cylinder's words stay a cylinder's.
    #[test]
    fn a_swivel_drive_is_said_as_one() {
        let swivel = ActuatorKind::Swivel;
        assert_eq!(swivel.noun(), "swivel drive");
        assert_eq!(
            swivel.sensor_comment("3", 0, 1),
            "swivel drive 3, at 0° (home)"
        );
        assert_eq!(swivel.sensor_comment("3", 1, 1), "swivel drive 3, at 180°");
        assert_eq!(swivel.coil_words(), ("swivel to 180°", "swivel back to 0°"));
        assert_eq!(
            ActuatorKind::verb_of("swivel back to 0°", "C3"),
            "swivel C3 back to 0°"
        );
        assert_eq!(ActuatorKind::verb_of("run forward", "C1"), "run C1 forward");
        assert_eq!(
            ActuatorKind::verb_of("extend", "C1 (clamp)"),
            "extend C1 (clamp)"
        );
        assert_eq!(
            swivel.move_words(),
            ("swivels to 180°", "swivels back to 0°")
        );
        assert!(swivel.both_on(3).contains("swivel drive C3"));
        let kept = swivel.kept_through_estop("y3+", 3);
        assert!(
            kept.contains("swivel drive C3") && !kept.contains("piston"),
            "{kept}"
        );
        assert!(swivel.positions_said(3).contains("C3+1 swivels it to 180°"));
        assert!(swivel.load_held(3).contains("arm at its end stop"));
        let cylinder = ActuatorKind::Bistable52;
        assert_eq!(
            cylinder.sensor_comment("1", 0, 1),
            "cylinder 1, home position 0"
        );
        assert_eq!(cylinder.coil_words(), ("extend", "retract"));
        assert_eq!(
            cylinder.load_held(1),
            "C1's valve is 52bi, which holds the piston"
        );
        assert!(
            !ActuatorKind::Vacuum
                .load_held(2)
                .contains("holds the piston")
        );
        assert!(!ActuatorKind::Motor.load_held(2).contains("piston"));
    }
}
