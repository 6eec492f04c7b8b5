//! The plant model: pistons with stroke times, position sensors with a
//! detection window, and the valve each actuator sits on (DESIGN §5).

use crate::actuator::ActuatorKind;
pub use crate::actuator::Spool;
use crate::cell::Sign;
use crate::stroke::Stroke;

/// One actuator of the plant.
#[derive(Debug, Clone, PartialEq)]
pub struct Piston {
    pub number: u32,
    pub max_position: u32,
    pub valve: ActuatorKind,
    /// Stroke fraction per scan the piston moves with no coil on: towards
    /// home under the load for an exhausted centre, outwards for a
    /// pressurised centre; zero otherwise.
    drift_per_scan: f64,
    /// Piston position as a fraction of the stroke, 0 (home) … 1 (end).
    pub s: f64,
    pub spool: Spool,
    /// Stroke fraction per scan when extending / retracting.
    extend_per_scan: f64,
    retract_per_scan: f64,
    /// `0.4 / max_position` and the points of the first sensors, computed
    /// once: a sensor is read at every scan of every run, and the two
    /// divisions were most of the reading.
    narrowest: f64,
    points: [f64; POINTS],
}

/// The sensors whose points a piston keeps at hand.
const POINTS: usize = 8;

impl Piston {
    /// A piston with the default valve for its positions.
    pub fn new(number: u32, max_position: u32, stroke: Stroke, scan_ms: u32) -> Self {
        Self::with_valve(
            number,
            max_position,
            stroke,
            scan_ms,
            ActuatorKind::default_for(max_position),
            0.0,
        )
    }

    /// A piston on `valve`; `drift` is the stroke fraction per second it moves
    /// with no coil on (the load on an exhausted centre, the creep of a
    /// pressurised one; ignored by other valves).
    pub fn with_valve(
        number: u32,
        max_position: u32,
        stroke: Stroke,
        scan_ms: u32,
        valve: ActuatorKind,
        drift: f64,
    ) -> Self {
        let per_scan = |ms: u32| scan_ms as f64 / ms.max(1) as f64;
        let drift_per_scan = valve.drift_per_second(drift) * scan_ms as f64 / 1000.0;
        let point = |position: u32| position as f64 / max_position.max(1) as f64;
        Piston {
            narrowest: 0.4 / max_position.max(1) as f64,
            points: std::array::from_fn(|p| point(p as u32)),
            number,
            max_position,
            valve,
            drift_per_scan,
            s: 0.0,
            spool: valve.rest_spool(),
            extend_per_scan: per_scan(stroke.extend_ms),
            retract_per_scan: per_scan(stroke.retract_ms),
        }
    }

    /// The stroke fraction of sensor `position`.
    pub fn sensor_point(&self, position: u32) -> f64 {
        match self.points.get(position as usize) {
            Some(point) => *point,
            None => position as f64 / self.max_position.max(1) as f64,
        }
    }

    /// The half-width a sensor of this actuator sees: `window`, narrowed on
    /// an actuator with so many positions that neighbouring sensors would
    /// otherwise overlap (real sensors are placed so that they do not).
    pub fn window(&self, window: f64) -> f64 {
        window.min(self.narrowest)
    }

    /// Whether sensor `position` sees the piston (within `window` of its point).
    /// A kind's own switch (a vacuum switch) reads as its kind says.
    #[inline]
    pub fn sensor(&self, position: u32, window: f64) -> bool {
        if let Some(on) = self.valve.switch_reads(position, self.spool, self.s) {
            return on;
        }
        let half = self.window(window) + 1e-9;
        (self.s - self.sensor_point(position)).abs() <= half
    }

    /// Whether the program's reading of `position` holds (its own sensor
    /// on; a vacuum gripper's "released" is its vacuum switch off): what
    /// says a move to `position` has arrived.
    pub fn reads(&self, position: u32, window: f64) -> bool {
        let reading = self.valve.reading(position);
        self.sensor(reading.sensor, window) == reading.on
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
    /// For a single-solenoid valve only `plus` is wired: on extends, off lets
    /// the spring retract.
    pub fn drive(&mut self, plus: bool, minus: bool) -> bool {
        self.spool = self.valve.switch(self.spool, plus, minus);
        self.valve.conflict(plus, minus)
    }

    /// A drive cut (its outputs just went off, `was` driving it) while it
    /// ran onto a limit switch coasts to the switch's point: it overruns
    /// the trip point by its braking distance, the same every time, so
    /// that every cycle starts where the last one ended (a cylinder does
    /// the same against its end stop). Cut while leaving a switch, it
    /// stands where it is.
    pub fn settle(&mut self, was: Spool, window: f64) {
        if !self.valve.coasts() || self.spool != Spool::Centre {
            return;
        }
        let Some(p) = self.sensor_on(window) else {
            return;
        };
        let point = self.sensor_point(p);
        let onto = match was {
            Spool::Plus => self.s < point,
            Spool::Minus => self.s > point,
            Spool::Centre => false,
        };
        if onto {
            self.s = point;
        }
    }

    /// Whether the piston has come to rest: its spool drives it against an
    /// end stop, or it sits on a centred spool (whose drift is the valve's
    /// doing, judged while the machine idles).
    pub fn at_rest(&self) -> bool {
        match self.spool {
            Spool::Plus => self.s >= 1.0,
            Spool::Minus => self.s <= 0.0,
            Spool::Centre => true,
        }
    }

    /// The stroke fraction the piston moves per scan as its spool stands
    /// (negative towards home, 0 at rest).
    pub fn velocity(&self) -> f64 {
        match self.spool {
            Spool::Plus if self.s < 1.0 => self.extend_per_scan,
            Spool::Minus if self.s > 0.0 => -self.retract_per_scan,
            Spool::Centre
                if (self.drift_per_scan > 0.0 && self.s < 1.0)
                    || (self.drift_per_scan < 0.0 && self.s > 0.0) =>
            {
                self.drift_per_scan
            }
            _ => 0.0,
        }
    }

    /// How many of the next `limit` scans the piston advances with no
    /// sensor switching on or off, no change of [`Piston::place`], without
    /// coming to rest at an end and
    /// without passing `mark` (`(low, high)`: the stroke fractions below and
    /// above which the caller's check fires).
    pub fn scans_before_an_event(&self, window: f64, mark: Option<(f64, f64)>, limit: u64) -> u64 {
        let v = self.velocity();
        if v == 0.0 || limit == 0 {
            return limit;
        }
        let half = self.window(window) + 1e-9;
        let distance = (0..=self.max_position)
            .map(|p| self.sensor_point(p))
            .flat_map(|c| [c - half, c, c + half])
            .chain([0.0, 1.0])
            .chain(mark.into_iter().flat_map(|(low, high)| [low, high]))
            .map(|t| (t - self.s) * v.signum())
            .filter(|d| *d >= 0.0)
            .fold(f64::INFINITY, f64::min);
        let estimate = ((distance / v.abs()).floor() as u64).min(limit);
        // The sums of per-scan steps may round a hair past the nearest
        // threshold (never past the next: a step is far wider than the
        // rounding); step a copy as the run will and check where it ends.
        // Every sensor's reading, not only the place: a vacuum switch
        // drops at the vacuum's full decay, within the home window.
        let watched = |p: &Piston| {
            let beyond = mark.map(|(low, high)| (p.s < low, p.s > high));
            let sensors = (0..=p.max_position.min(63))
                .fold(0u64, |bits, q| bits | u64::from(p.sensor(q, window)) << q);
            (p.place(window), p.at_rest(), beyond, sensors)
        };
        let mut copy = self.clone();
        for _ in 0..estimate {
            copy.advance();
        }
        if watched(&copy) == watched(self) {
            estimate
        } else {
            estimate.saturating_sub(1)
        }
    }

    /// Where the piston is, coarsely: `2p` on sensor `p`, `2p + 1` between
    /// sensors `p` and `p + 1`. The combination of every piston's place is
    /// what the collision check compares with the healthy cycle.
    pub fn place(&self, window: f64) -> u32 {
        match self.sensor_on(window) {
            Some(p) => 2 * p,
            None => {
                let below = (self.s * self.max_position.max(1) as f64).floor() as u32;
                2 * below.min(self.max_position.saturating_sub(1)) + 1
            }
        }
    }

    /// Advances the piston by one scan. Returns the direction it moved, if any.
    pub fn advance(&mut self) -> Option<Sign> {
        let before = self.s;
        match self.spool {
            Spool::Plus => self.s = (self.s + self.extend_per_scan).min(1.0),
            Spool::Minus => self.s = (self.s - self.retract_per_scan).max(0.0),
            Spool::Centre => self.s = (self.s + self.drift_per_scan).clamp(0.0, 1.0),
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

    /// Drives to the middle sensor of a 3-position piston, switches every
    /// coil off and lets 2 s pass: where does the piston end?
    fn middle_then_off(valve: ActuatorKind, drift: f64) -> (f64, f64) {
        let mut p = Piston::with_valve(1, 2, Stroke::default(), 10, valve, drift);
        p.drive(true, false);
        while !p.sensor(1, 0.02) {
            p.advance();
        }
        p.drive(false, false);
        let stopped = p.s;
        for _ in 0..200 {
            p.advance();
        }
        (stopped, p.s)
    }

    #[test]
    fn each_valve_type_at_a_middle_stop_and_with_every_coil_off() {
        // Closed centre: holds at the middle sensor.
        let (stopped, after) = middle_then_off(ActuatorKind::Closed53, 0.2);
        assert!((stopped - 0.5).abs() < 0.03 && after == stopped);
        // Exhausted centre: the load drifts it home (0.2 stroke/s for 2 s = 0.4).
        let (stopped, after) = middle_then_off(ActuatorKind::Exhaust53, 0.2);
        assert!(
            (after - (stopped - 0.4)).abs() < 0.01,
            "{stopped} -> {after}"
        );
        // Pressurised centre: creeps out towards the end.
        let (stopped, after) = middle_then_off(ActuatorKind::Pressure53, 0.2);
        assert!(
            (after - (stopped + 0.4)).abs() < 0.01,
            "{stopped} -> {after}"
        );
        // 5/2 bistable: no centre, keeps moving to the end with no coil on.
        let (_, after) = middle_then_off(ActuatorKind::Bistable52, 0.2);
        assert_eq!(after, 1.0);
        // 5/2 single solenoid: coil off means the spring drives it home.
        let (_, after) = middle_then_off(ActuatorKind::Mono52, 0.2);
        assert_eq!(after, 0.0);
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
