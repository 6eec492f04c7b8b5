//! The plant model: pistons with stroke times, position sensors with a
//! detection window, and the valve each actuator sits on (DESIGN §5).

use crate::cell::Sign;
use crate::timing::Stroke;

/// Where the valve's spool is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spool {
    /// Air to the + side: the piston moves towards higher positions.
    Plus,
    /// Air to the - side.
    Minus,
    /// 5/3 closed centre: both ports shut, the piston holds.
    Centre,
}

/// The valve type. Two-position actuators get a bistable 5/2 valve (keeps the
/// last coil's position); actuators with middle stops a 5/3 closed-centre valve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Valve {
    Bistable52,
    ClosedCentre53,
}

/// One actuator of the plant.
#[derive(Debug, Clone, PartialEq)]
pub struct Piston {
    pub number: u32,
    pub max_position: u32,
    pub valve: Valve,
    /// Piston position as a fraction of the stroke, 0 (home) … 1 (end).
    pub s: f64,
    pub spool: Spool,
    /// Stroke fraction per scan when extending / retracting.
    extend_per_scan: f64,
    retract_per_scan: f64,
}

impl Piston {
    pub fn new(number: u32, max_position: u32, stroke: Stroke, scan_ms: u32) -> Self {
        let per_scan = |ms: u32| scan_ms as f64 / ms.max(1) as f64;
        Piston {
            number,
            max_position,
            valve: if max_position > 1 {
                Valve::ClosedCentre53
            } else {
                Valve::Bistable52
            },
            s: 0.0,
            spool: match max_position {
                0 | 1 => Spool::Minus,
                _ => Spool::Centre,
            },
            extend_per_scan: per_scan(stroke.extend_ms),
            retract_per_scan: per_scan(stroke.retract_ms),
        }
    }

    /// The stroke fraction of sensor `position`.
    pub fn sensor_point(&self, position: u32) -> f64 {
        position as f64 / self.max_position.max(1) as f64
    }

    /// Whether sensor `position` sees the piston (within `window` of its point).
    pub fn sensor(&self, position: u32, window: f64) -> bool {
        (self.s - self.sensor_point(position)).abs() <= window + 1e-9
    }

    /// The sensor that currently sees the piston, if any.
    pub fn sensor_on(&self, window: f64) -> Option<u32> {
        (0..=self.max_position).find(|p| self.sensor(*p, window))
    }

    /// The position in sensor units (`s · pmax`), for diagrams.
    pub fn position_units(&self) -> f64 {
        self.s * self.max_position.max(1) as f64
    }

    /// Applies the two coils to the valve. Returns `true` when both are on,
    /// which no valve may see.
    pub fn drive(&mut self, plus: bool, minus: bool) -> bool {
        match (plus, minus, self.valve) {
            (true, false, _) => self.spool = Spool::Plus,
            (false, true, _) => self.spool = Spool::Minus,
            (false, false, Valve::Bistable52) => {}
            (false, false, Valve::ClosedCentre53) => self.spool = Spool::Centre,
            // Both coils: a 5/2 spool stays where it was; a spring-centred 5/3
            // spool is pushed from both sides and stays centred.
            (true, true, Valve::Bistable52) => {}
            (true, true, Valve::ClosedCentre53) => self.spool = Spool::Centre,
        }
        plus && minus
    }

    /// Advances the piston by one scan. Returns the direction it moved, if any.
    pub fn advance(&mut self) -> Option<Sign> {
        let before = self.s;
        match self.spool {
            Spool::Plus => self.s = (self.s + self.extend_per_scan).min(1.0),
            Spool::Minus => self.s = (self.s - self.retract_per_scan).max(0.0),
            Spool::Centre => {}
        }
        if self.s > before {
            Some(Sign::Plus)
        } else if self.s < before {
            Some(Sign::Minus)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bistable_valve_keeps_its_last_coil() {
        let mut p = Piston::new(1, 1, Stroke::default(), 10);
        p.drive(true, false);
        p.drive(false, false);
        for _ in 0..200 {
            p.advance();
        }
        assert_eq!(p.s, 1.0);
        assert!(p.sensor(1, 0.02));
    }

    #[test]
    fn closed_centre_valve_holds_with_no_coil() {
        let mut p = Piston::new(2, 3, Stroke::default(), 10);
        p.drive(true, false);
        for _ in 0..30 {
            p.advance();
        }
        p.drive(false, false);
        let held = p.s;
        assert_eq!(p.advance(), None);
        assert_eq!(p.s, held);
        assert!(p.drive(true, true), "both coils is a conflict");
    }
}
