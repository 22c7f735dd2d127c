//! MAVLink mission items, as ground stations save them, turned into a plan's waypoints (reference
//! §16): what a QGroundControl `.plan` and a plain-text waypoint list (`QGC WPL`) share.

use super::geodetic::east_north;
use super::plan::{FlightPlan, MAX_WAYPOINTS};
use super::plan_file::PlanError;
use super::{ClimbLimits, Cornering, MAX_PLAN_SPEED, PLAN_CRUISE};
use crate::math::{atan2, cos, hypot, sin_cos};
use core::f64::consts::{PI, TAU};

/// MAVLink commands (`MAV_CMD`) that loratrack reads.
const NAV_WAYPOINT: u64 = 16;
const NAV_LOITER_UNLIM: u64 = 17;
const NAV_LOITER_TURNS: u64 = 18;
const NAV_LOITER_TIME: u64 = 19;
const NAV_RETURN_TO_LAUNCH: u64 = 20;
const NAV_LAND: u64 = 21;
const NAV_TAKEOFF: u64 = 22;
const NAV_LOITER_TO_ALT: u64 = 31;
const NAV_DELAY: u64 = 93;
const NAV_SPLINE_WAYPOINT: u64 = 82;
const NAV_VTOL_TAKEOFF: u64 = 84;
const NAV_VTOL_LAND: u64 = 85;
const DO_CHANGE_SPEED: u64 = 178;
/// Commands that fly to their own latitude and longitude: a waypoint, a spline waypoint (its leg
/// read as straight) and the loiters (read as their centre, but for [`Flown::circle`]'s turns).
const FLY_TO: [u64; 6] = [
    NAV_WAYPOINT,
    NAV_LOITER_UNLIM,
    NAV_LOITER_TURNS,
    NAV_LOITER_TIME,
    NAV_LOITER_TO_ALT,
    NAV_SPLINE_WAYPOINT,
];

/// The rate a multicopter circles at, rad/s: ArduPilot Copter's `CIRCLE_RATE` default, 20°/s
/// (`AC_Circle`), at which a loiter's turns are flown unless the mission's speed is lower.
pub const CIRCLE_RATE: f64 = 20.0 * core::f64::consts::PI / 180.0;
/// The points each turn of a loiter is flown through: one every 30°.
const CIRCLE_POINTS: f64 = 12.0;
/// The radius a plane circles at where a loiter gives none, m: ArduPlane's `WP_LOITER_RAD`
/// default (clockwise). A plane cannot hover, so it circles a timed loiter and a delay too.
pub const LOITER_RADIUS: f64 = 60.0;
/// How a multicopter returns to launch and lands: ArduPilot Copter's defaults. It climbs to
/// `RTL_ALT` (15 m above home) before it heads home, unless it is higher (then it returns at its
/// own height) or near home (`RTL_CONE_SLOPE` 3: at most 3 m up a metre from home), hovers
/// above home for `RTL_LOIT_TIME` (5 s) and lands.
pub const RTL_ALT: f64 = 15.0;
/// See [`RTL_ALT`].
pub const RTL_CONE_SLOPE: f64 = 3.0;
/// See [`RTL_ALT`], s.
pub const RTL_LOITER: f64 = 5.0;
/// A multicopter lands at its descent limit (`WPNAV_SPEED_DN`, [`ClimbLimits::down`]) down to
/// `LAND_ALT_LOW` (10 m), then at `LAND_SPEED` (0.5 m/s) to the ground: ArduPilot Copter's
/// defaults (PX4's `MPC_LAND_SPEED` is 0.7 m/s).
pub const LAND_ALT_LOW: f64 = 10.0;
/// See [`LAND_ALT_LOW`], m/s.
pub const LAND_SPEED: f64 = 0.5;

/// One MAVLink mission item (`MISSION_ITEM`): its command, coordinate frame and seven
/// parameters (5–7: latitude and longitude, degrees, and altitude, m, for the commands that
/// fly somewhere). A parameter a file leaves empty (`null`, NaN) is `None`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct MissionItem {
    pub command: u64,
    pub frame: Option<u64>,
    pub params: [Option<f64>; 7],
}

/// A mission as its items are read in order: the waypoints so far (home first), the speed of
/// each leg, the time held at each waypoint, and the speed the next leg will have.
pub(super) struct Flown {
    /// Home: latitude and longitude, degrees, and altitude above mean sea level, m.
    home: [f64; 3],
    speed: Option<f64>,
    points: Vec<[f64; 3]>,
    speeds: Vec<Option<f64>>,
    holds: Vec<f64>,
    /// The vehicle's climb and descent limits, as the next leg will have them, and each leg's.
    climb: ClimbLimits,
    climbs: Vec<ClimbLimits>,
    /// How the vehicle turns through a waypoint.
    cornering: Cornering,
    /// The waypoints a plane's take-off climbs to, which [`Flown::climb_out`] places.
    takeoffs: Vec<usize>,
}

impl Flown {
    /// Starts at home (latitude, longitude, degrees; altitude above mean sea level, m), the
    /// origin of the plan's east-north-up frame, with legs at `speed` (m/s) until a speed change.
    pub fn new(home: [f64; 3], speed: Option<f64>) -> Self {
        Flown {
            home,
            speed,
            points: vec![[0.0, 0.0, 0.0]],
            speeds: Vec::new(),
            holds: vec![0.0],
            climb: ClimbLimits::of(Cornering::Multicopter),
            climbs: Vec::new(),
            cornering: Cornering::Multicopter,
            takeoffs: Vec::new(),
        }
    }

    /// The same for a fixed-wing vehicle, which flies through a waypoint's hold time, circles its
    /// timed loiters and delays for their time ([`LOITER_RADIUS`] where a loiter gives no
    /// radius), climbs and descends faster, and turns through a waypoint wide and at its speed
    /// ([`Cornering::FixedWing`]).
    pub fn fixed_wing(self) -> Self {
        Flown {
            climb: ClimbLimits::of(Cornering::FixedWing),
            cornering: Cornering::FixedWing,
            ..self
        }
    }

    /// Whether a waypoint's hold time is flown: MAVLink's `NAV_WAYPOINT` says fixed-wing
    /// vehicles ignore it.
    fn waypoint_holds(&self) -> bool {
        self.cornering == Cornering::Multicopter
    }

    /// Reads one mission item: a speed change, a leg to a new waypoint, a wait where the vehicle
    /// is, or nothing that moves the vehicle. The refusal says what is wrong with the item.
    pub fn item(&mut self, item: &MissionItem) -> Result<(), String> {
        if item.command == DO_CHANGE_SPEED {
            return self.change_speed(item);
        }
        let hold = self.hold_of(item);
        match self.destination(item, hold)? {
            Some(point) => self.fly_to(item, point, hold),
            None => Ok(()),
        }
    }

    /// The time `item` holds where it leads, s. Parameter 1 of a waypoint, a timed loiter and a
    /// delay is that time (a negative one, as `NAV_DELAY` writes for "until a time of day", is
    /// not read); an unlimited loiter holds for the longest hold, since the mission goes no
    /// further.
    fn hold_of(&self, item: &MissionItem) -> f64 {
        match item.command {
            NAV_WAYPOINT if !self.waypoint_holds() => None,
            NAV_WAYPOINT | NAV_LOITER_TIME | NAV_DELAY => item.params[0].filter(|h| *h > 0.0),
            NAV_LOITER_UNLIM => Some(super::plan::MAX_HOLD),
            _ => None,
        }
        .unwrap_or(0.0)
    }

    /// A `DO_CHANGE_SPEED`: parameter 1 is the speed's type: 0 (airspeed) and 1 (ground speed)
    /// change the speed along the path, 2 the climb speed and 3 the descent speed (ArduPilot's
    /// Copter), each given by parameter 2 (−1: no change).
    fn change_speed(&mut self, item: &MissionItem) -> Result<(), String> {
        let Some(speed) = item.params[1].filter(|s| *s > 0.0) else {
            return Ok(());
        };
        let vertical = match item.params[0] {
            Some(2.0) => &mut self.climb.up,
            Some(3.0) => &mut self.climb.down,
            _ => {
                self.speed = Some(speed);
                return Ok(());
            }
        };
        if speed > MAX_PLAN_SPEED {
            return Err(format!(
                "a climb or descent speed must be in (0, {MAX_PLAN_SPEED}] m/s, got {speed}"
            ));
        }
        *vertical = speed;
        Ok(())
    }

    /// Where `item` (holding `hold` s) leads the vehicle next, or `None` where it moves it no
    /// further, or has flown it already (a plane's delay circled, a multicopter's return or
    /// landing).
    fn destination(&mut self, item: &MissionItem, hold: f64) -> Result<Option<[f64; 3]>, String> {
        let param = |k: usize| item.params[k];
        let last = self.points[self.points.len() - 1];
        let point = match item.command {
            // A plane cannot wait in place: it circles where it is.
            NAV_DELAY if !self.waypoint_holds() && hold > 0.0 => {
                let turns = self.turns_in(hold, LOITER_RADIUS);
                self.circle(last, last, turns, LOITER_RADIUS)?;
                return Ok(None);
            }
            NAV_DELAY => {
                let held = self.holds.len() - 1;
                self.holds[held] += hold;
                return Ok(None);
            }
            NAV_RETURN_TO_LAUNCH if self.waypoint_holds() => {
                self.return_to_launch(last);
                return Ok(None);
            }
            // A plane returns at its own height and circles home (ArduPlane without
            // `RTL_AUTOLAND`): read as home at that height.
            NAV_RETURN_TO_LAUNCH => [0.0, 0.0, last[2]],
            // Take-off and landing often leave the position to the vehicle: in place (a plane's
            // take-off climbs out toward the next waypoint, `climb_out`).
            NAV_TAKEOFF | NAV_VTOL_TAKEOFF => {
                let [x, y] = self
                    .horizontal(param(4), param(5))
                    .unwrap_or([last[0], last[1]]);
                if item.command == NAV_TAKEOFF && self.cornering == Cornering::FixedWing {
                    self.takeoffs.push(self.points.len());
                }
                [x, y, self.altitude(param(6), item.frame)?]
            }
            // A multicopter flies to where it lands at its own height, then lands straight down
            // ([`Flown::land`]); a plane glides there.
            NAV_LAND | NAV_VTOL_LAND => {
                let [x, y] = self
                    .horizontal(param(4), param(5))
                    .unwrap_or([last[0], last[1]]);
                if self.waypoint_holds() {
                    self.push([x, y, last[2]], self.speed, 0.0);
                    self.land();
                    return Ok(None);
                }
                [x, y, 0.0]
            }
            c if FLY_TO.contains(&c) => {
                let [x, y] = self
                    .horizontal(param(4), param(5))
                    .ok_or("a waypoint without latitude and longitude")?;
                [x, y, self.altitude(param(6), item.frame)?]
            }
            // Camera, gimbal and other commands do not move the vehicle.
            _ => return Ok(None),
        };
        Ok(Some(point))
    }

    /// Flies to `point`, where `item` leads, holding `hold` s there, or round it where it is a
    /// loiter's circle. A loiter's turns: parameter 1 the turns, parameter 3 the radius, m
    /// (negative: counter-clockwise). Of radius 0 a multicopter turns on the spot, at the circle
    /// rate. A plane circles its timed loiters too, and its loiters of radius 0 at
    /// [`LOITER_RADIUS`].
    fn fly_to(&mut self, item: &MissionItem, point: [f64; 3], mut hold: f64) -> Result<(), String> {
        let last = self.points[self.points.len() - 1];
        let turns = item.params[0].filter(|t| *t > 0.0 && item.command == NAV_LOITER_TURNS);
        let radius = item.params[2].filter(|r| *r != 0.0);
        match (turns, radius) {
            (Some(turns), Some(r)) => return self.circle(last, point, turns, r),
            (Some(turns), None) if self.waypoint_holds() => hold = turns * TAU / CIRCLE_RATE,
            (Some(turns), None) => return self.circle(last, point, turns, LOITER_RADIUS),
            (None, r)
                if !self.waypoint_holds() && item.command == NAV_LOITER_TIME && hold > 0.0 =>
            {
                let r = r.unwrap_or(LOITER_RADIUS);
                return self.circle(last, point, self.turns_in(hold, r), r);
            }
            _ => {}
        }
        self.push(point, self.speed, hold);
        Ok(())
    }

    /// A waypoint, with the speed of the leg to it and the time held there.
    fn push(&mut self, point: [f64; 3], speed: Option<f64>, hold: f64) {
        self.points.push(point);
        self.speeds.push(speed);
        self.climbs.push(self.climb);
        self.holds.push(hold);
    }

    /// The turns of radius `r` m (either sign) a plane flies in `time` s at the mission's speed
    /// ([`PLAN_CRUISE`] where it has none).
    fn turns_in(&self, time: f64, r: f64) -> f64 {
        time * self.speed.unwrap_or(PLAN_CRUISE) / (TAU * r.abs())
    }

    /// A multicopter's return to launch from `from` ([`RTL_ALT`]): the climb, the way home, the
    /// hover above it and the landing.
    fn return_to_launch(&mut self, from: [f64; 3]) {
        let away = hypot(from[0], from[1]);
        let height = from[2].max(RTL_ALT.min(RTL_CONE_SLOPE * away));
        self.push([from[0], from[1], height], self.speed, 0.0);
        self.push([0.0, 0.0, height], self.speed, RTL_LOITER);
        self.land();
    }

    /// A multicopter's landing straight down from where it is ([`LAND_ALT_LOW`]).
    fn land(&mut self) {
        let [x, y, z] = self.points[self.points.len() - 1];
        self.push([x, y, z.min(LAND_ALT_LOW)], self.speed, 0.0);
        let descent = self.climb;
        self.climb.down = self.climb.down.min(LAND_SPEED);
        self.push([x, y, 0.0], self.speed, 0.0);
        self.climb = descent;
    }

    /// A loiter of `turns` turns about `centre` at `radius` m (clockwise seen from above;
    /// counter-clockwise where negative), as ArduPilot's Copter flies `NAV_LOITER_TURNS`: from
    /// `from` to the nearest point of the circle, then round it through a point every 30° (its
    /// corners flown as any other's), at the mission's speed or, for a multicopter, at most
    /// [`CIRCLE_RATE`] × radius (a 10 m circle at 3.5 m/s). A fixed-wing vehicle circles at its
    /// speed, through points 1/cos 15° farther out, so that its corners' arcs, which meet
    /// ([`Cornering::FixedWing`]), are the circle itself, flown for the loiter's time.
    fn circle(
        &mut self,
        from: [f64; 3],
        centre: [f64; 3],
        turns: f64,
        radius: f64,
    ) -> Result<(), String> {
        let points = (turns * CIRCLE_POINTS).ceil();
        if !radius.is_finite() || points > MAX_WAYPOINTS as f64 {
            return Err(format!(
                "a loiter of {turns} turns of radius {radius} m is not read (at most {} turns)",
                (MAX_WAYPOINTS as f64 / CIRCLE_POINTS).floor()
            ));
        }
        let (dx, dy) = (from[0] - centre[0], from[1] - centre[1]);
        let start = if dx == 0.0 && dy == 0.0 {
            0.0
        } else {
            atan2(dy, dx)
        };
        let way = if radius < 0.0 { 1.0 } else { -1.0 };
        let r = match self.cornering {
            Cornering::FixedWing => radius.abs() / cos(PI / CIRCLE_POINTS),
            Cornering::Multicopter => radius.abs(),
        };
        let at = |angle: f64| {
            let (s, c) = sin_cos(angle);
            [centre[0] + r * c, centre[1] + r * s, centre[2]]
        };
        let round = match self.speed {
            _ if !self.waypoint_holds() => self.speed,
            Some(v) => Some(v.min(CIRCLE_RATE * r)),
            None => Some(PLAN_CRUISE.min(CIRCLE_RATE * r)),
        };
        self.push(at(start), self.speed, 0.0);
        for k in 1..=points as usize {
            let angle = (k as f64 * TAU / CIRCLE_POINTS).min(turns * TAU);
            self.push(at(start + way * angle), round, 0.0);
        }
        Ok(())
    }

    /// A plane's take-offs, as ArduPlane flies `NAV_TAKEOFF`: it cannot climb straight up, so it
    /// climbs out along its heading at its speed, at most its climb limit up (TECS's
    /// `TECS_CLMB_MAX`), reaching the take-off's height `h` after h·√(v² − c²)/c m (277 m to 80 m
    /// at 18 m/s and 5 m/s up). Its heading is taken toward the next waypoint elsewhere (a
    /// plane is launched into its mission), at most as far as that waypoint. A take-off given a
    /// position of its own, and a VTOL's, climb where they are told.
    fn climb_out(&mut self) {
        for &k in &self.takeoffs {
            let (from, top) = (self.points[k - 1], self.points[k]);
            let rise = top[2] - from[2];
            let (v, c) = (
                self.speeds[k - 1].unwrap_or(PLAN_CRUISE),
                self.climbs[k - 1].up,
            );
            let next = self.points[k + 1..]
                .iter()
                .find(|p| p[0] != top[0] || p[1] != top[1]);
            let (Some(next), true) = (next, from[..2] == top[..2] && rise > 0.0 && v > c) else {
                continue;
            };
            let (dx, dy) = (next[0] - top[0], next[1] - top[1]);
            let away = hypot(dx, dy);
            let run = (rise * (v * v - c * c).sqrt() / c).min(away);
            self.points[k] = [top[0] + dx / away * run, top[1] + dy / away * run, top[2]];
        }
    }

    /// The plan flown: home and every waypoint read, in order, with their holds.
    pub fn plan(mut self) -> Result<FlightPlan, PlanError> {
        if self.points.len() < 2 {
            return Err(PlanError::Empty);
        }
        self.climb_out();
        let holds = self
            .holds
            .into_iter()
            .map(|h| h.min(super::plan::MAX_HOLD))
            .collect();
        FlightPlan::with_holds_and_climbs(self.points, self.speeds, holds, self.climbs)
            .map(|p| p.with_cornering(self.cornering))
    }

    /// East and north of home, m, of an item's latitude and longitude (degrees); `None` where it
    /// gives none (missing, or 0, 0: the vehicle's own position).
    fn horizontal(&self, lat: Option<f64>, lon: Option<f64>) -> Option<[f64; 2]> {
        let (lat, lon) = (lat?, lon?);
        if lat == 0.0 && lon == 0.0 {
            return None;
        }
        Some(east_north([self.home[0], self.home[1]], lat, lon))
    }

    /// An item's altitude above home, m, from its altitude parameter in its `frame`.
    fn altitude(&self, alt: Option<f64>, frame: Option<u64>) -> Result<f64, String> {
        let alt = alt.ok_or("no altitude")?;
        // MAV_FRAME_GLOBAL (0) and its integer twin (5) are above mean sea level; the relative
        // frames (3, 6) above home; terrain-following ones need a terrain model loratrack lacks.
        match frame {
            Some(0 | 5) => Ok(alt - self.home[2]),
            Some(3 | 6) | None => Ok(alt),
            Some(f) => Err(format!(
                "altitude frame {f} is not read (use relative altitude, frame 3)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn item(command: u64, frame: u64, lat: f64, lon: f64, alt: f64) -> MissionItem {
        MissionItem {
            command,
            frame: Some(frame),
            params: [Some(0.0), None, None, None, Some(lat), Some(lon), Some(alt)],
        }
    }

    /// A `NAV_DELAY` with its four parameters: seconds, or −1 and an hour, minute and second.
    fn delay(params: [f64; 4]) -> MissionItem {
        let [a, b, c, d] = params.map(Some);
        MissionItem {
            command: 93,
            frame: Some(2),
            params: [a, b, c, d, None, None, None],
        }
    }

    #[test]
    fn a_loiter_is_flown_to_its_centre_and_a_camera_command_is_not_flown() {
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(5.0));
        f.item(&item(19, 3, -35.0, 149.001, 30.0)).unwrap();
        f.item(&item(206, 2, 0.0, 0.0, 0.0)).unwrap();
        f.item(&item(16, 0, -35.001, 149.001, 540.0)).unwrap();
        let p = f.plan().unwrap();
        let w = p.waypoints();
        assert_eq!(w.len(), 3, "{w:?}");
        // 0.001° of longitude at −35°: 91.1 m east; 0.001° of latitude: 111.2 m south.
        assert!(
            (w[1][0] - 91.1).abs() < 0.1 && w[1][2] == 30.0,
            "{:?}",
            w[1]
        );
        assert!(
            (w[2][1] + 111.2).abs() < 0.1 && w[2][2] == 40.0,
            "{:?}",
            w[2]
        );
        assert_eq!(p.speed_at(1.0), Some(5.0));
    }

    /// A `NAV_LOITER_TURNS` of `turns` turns of `radius` m (negative: counter-clockwise) about
    /// `lat`, `lon`, 30 m up.
    fn loiter_turns(lat: f64, lon: f64, turns: f64, radius: f64) -> MissionItem {
        let mut loiter = item(18, 3, lat, lon, 30.0);
        loiter.params[0] = Some(turns);
        loiter.params[2] = Some(radius);
        loiter
    }

    #[test]
    fn a_loiters_turns_are_flown_round_its_circle_from_the_nearest_edge() {
        // 91.1 m east, then two turns of 10 m clockwise about home, 30 m up.
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(8.0));
        f.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        f.item(&loiter_turns(-35.0, 149.0, 2.0, 10.0)).unwrap();
        let p = f.plan().unwrap();
        let w = p.waypoints();
        // Home, the waypoint, the edge nearest it, then 24 points a 30° apart.
        assert_eq!(w.len(), 2 + 1 + 24, "{w:?}");
        let edge = [10.0, 0.0, 30.0];
        assert!(crate::math::distance(&w[2], &edge) < 1e-9, "{:?}", w[2]);
        assert!(w[3..]
            .iter()
            .all(|q| (q[0].hypot(q[1]) - 10.0).abs() < 1e-9 && q[2] == 30.0));
        // Clockwise seen from above: the first step goes south.
        assert!(w[3][1] < -4.9, "{:?}", w[3]);
        assert!(crate::math::distance(&w[26], &edge) < 1e-9);
        // To the edge at the mission's 8 m/s, round at 20°/s: 3.49 m/s.
        assert_eq!(p.leg_speed(1), Some(8.0));
        assert!((p.leg_speed(2).unwrap() - 10.0 * CIRCLE_RATE).abs() < 1e-12);
        assert!((CIRCLE_RATE * 10.0 - 3.49).abs() < 0.01);
        // Half a turn of 30 m counter-clockwise: 6 points north of the edge, at the 8 m/s.
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(8.0));
        f.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        f.item(&loiter_turns(-35.0, 149.0, 0.5, -30.0)).unwrap();
        let p = f.plan().unwrap();
        let w = p.waypoints();
        assert_eq!(w.len(), 2 + 1 + 6);
        assert!(w[3][1] > 14.9 && w[8][0] < -29.9, "{w:?}");
        assert_eq!(p.leg_speed(3), Some(8.0));
        // Of radius 0 a multicopter turns on the spot: 18 s a turn, held at the centre.
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(8.0));
        f.item(&loiter_turns(-35.0, 149.001, 2.0, 0.0)).unwrap();
        assert_eq!(f.plan().unwrap().holds(), &[0.0, 36.0]);
        // A fixed-wing vehicle circles at its speed.
        let mut plane = Flown::new([-35.0, 149.0, 500.0], Some(15.0)).fixed_wing();
        plane
            .item(&loiter_turns(-35.0, 149.001, 1.0, 80.0))
            .unwrap();
        assert_eq!(plane.plan().unwrap().leg_speed(3), Some(15.0));
        // Absurd turns are refused, not read into millions of points.
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(8.0));
        let e = f
            .item(&loiter_turns(-35.0, 149.001, 1e9, 10.0))
            .unwrap_err();
        assert!(e.contains("turns"), "{e}");
    }

    #[test]
    fn holds_are_read_from_waypoints_timed_loiters_and_delays() {
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(5.0));
        let mut wp = item(16, 3, -35.0, 149.001, 30.0);
        wp.params[0] = Some(12.0);
        f.item(&wp).unwrap();
        f.item(&delay([8.0, -1.0, -1.0, -1.0])).unwrap();
        let mut loiter = item(19, 3, -35.001, 149.001, 30.0);
        loiter.params[0] = Some(40.0);
        f.item(&loiter).unwrap();
        // A delay "until a time of day" (−1) holds nothing loratrack can time.
        f.item(&delay([-1.0, 10.0, 30.0, 0.0])).unwrap();
        f.item(&item(16, 3, -35.002, 149.001, 30.0)).unwrap();
        f.item(&item(17, 3, -35.002, 149.002, 30.0)).unwrap();
        assert_eq!(
            f.plan().unwrap().holds(),
            &[0.0, 20.0, 40.0, 0.0, crate::trajectory::MAX_HOLD]
        );
        // A fixed-wing vehicle flies through a waypoint's hold and circles a timed loiter
        // (a_plane_circles_its_timed_loiters_and_delays_and_its_loiters_of_radius_0_at_60_m):
        // it holds nowhere.
        let mut plane = Flown::new([-35.0, 149.0, 500.0], Some(15.0)).fixed_wing();
        plane.item(&wp).unwrap();
        plane.item(&loiter).unwrap();
        assert!(plane.plan().unwrap().holds().iter().all(|h| *h == 0.0));
    }

    #[test]
    fn a_plane_climbs_out_toward_its_first_waypoint_and_a_multicopter_straight_up() {
        let takeoff = item(22, 3, 0.0, 0.0, 80.0);
        // 1 km east of home.
        let east = item(16, 3, -35.0, 149.0 + 1000.0 / 91_000.0, 80.0);
        let fly = |f: Flown| {
            let mut f = f;
            let mut t = takeoff;
            t.params[4] = None;
            t.params[5] = None;
            f.item(&t).unwrap();
            f.item(&east).unwrap();
            f.plan().unwrap()
        };
        let plane = fly(Flown::new([-35.0, 149.0, 500.0], Some(18.0)).fixed_wing());
        let top = plane.waypoints()[1];
        // 80 m up at 5 m/s while flying 18 m/s: 80 × √(18² − 5²) / 5 = 277 m east.
        let run = 80.0 * (18.0f64 * 18.0 - 25.0).sqrt() / 5.0;
        assert!(
            (top[0] - run).abs() < 1e-9 && top[1].abs() < 1e-9,
            "{top:?}"
        );
        assert_eq!(top[2], 80.0);
        // Flown at its speed: the climb limit is met, not exceeded.
        assert_eq!(plane.flown_speed(0, 5.0), 18.0);
        let copter = fly(Flown::new([-35.0, 149.0, 500.0], Some(18.0)));
        assert_eq!(copter.waypoints()[1], [0.0, 0.0, 80.0]);
    }

    /// A `DO_CHANGE_SPEED` of `kind` (0 airspeed, 1 ground speed, 2 climb, 3 descent) to `speed`.
    fn change_speed(kind: f64, speed: f64) -> MissionItem {
        MissionItem {
            command: 178,
            frame: Some(2),
            params: [Some(kind), Some(speed), Some(-1.0), None, None, None, None],
        }
    }

    #[test]
    fn a_change_of_climb_or_descent_speed_limits_the_legs_after_it() {
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(5.0));
        // Up 30 m at the default limits, then up 30 m more at 1 m/s, then down 60 m at 0.5 m/s.
        f.item(&item(16, 3, -35.0, 149.0, 30.0)).unwrap();
        f.item(&change_speed(2.0, 1.0)).unwrap();
        f.item(&change_speed(3.0, 0.5)).unwrap();
        f.item(&item(16, 3, -35.0, 149.0, 60.0)).unwrap();
        f.item(&change_speed(1.0, 9.0)).unwrap();
        f.item(&item(16, 3, -35.0, 149.0, 0.0)).unwrap();
        let p = f.plan().unwrap();
        // The speed along the path is not the climb's.
        assert_eq!(p.leg_speed(0), Some(5.0));
        assert_eq!(p.leg_speed(1), Some(5.0));
        assert_eq!(p.leg_speed(2), Some(9.0));
        let flown: Vec<f64> = (0..3).map(|leg| p.flown_speed(leg, 5.0)).collect();
        assert_eq!(flown, [ClimbLimits::MULTICOPTER.up, 1.0, 0.5]);
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(5.0));
        let e = f.item(&change_speed(2.0, 1000.0)).unwrap_err();
        assert!(e.contains("climb or descent speed"), "{e}");
    }

    #[test]
    fn a_loiter_over_the_waypoint_before_adds_its_time_there() {
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(5.0));
        f.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        let mut loiter = item(19, 3, -35.0, 149.001, 30.0);
        loiter.params[0] = Some(25.0);
        f.item(&loiter).unwrap();
        f.item(&item(16, 3, -35.001, 149.001, 30.0)).unwrap();
        let p = f.plan().unwrap();
        assert_eq!(p.holds(), &[0.0, 25.0, 0.0]);
        assert_eq!(p.climbs().map(<[_]>::len), Some(2));
    }

    #[test]
    fn a_multicopter_climbs_slower_than_a_plane_on_the_same_steep_leg() {
        // Straight up 30 m at a planned 5 m/s, then level.
        let fly = |f: Flown| {
            let mut f = f;
            f.item(&item(16, 3, -35.0, 149.0, 30.0)).unwrap();
            f.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
            f.plan().unwrap()
        };
        let copter = fly(Flown::new([-35.0, 149.0, 500.0], Some(5.0)));
        let plane = fly(Flown::new([-35.0, 149.0, 500.0], Some(5.0)).fixed_wing());
        assert_eq!(copter.flown_speed(0, 5.0), ClimbLimits::MULTICOPTER.up);
        assert_eq!(plane.flown_speed(0, 5.0), 5.0);
        assert_eq!(
            (copter.flown_speed(1, 5.0), plane.flown_speed(1, 5.0)),
            (5.0, 5.0)
        );
    }

    /// The waypoints a multicopter (or, `plane`, a fixed-wing vehicle) flies for a return to
    /// launch from `from` (east, north, up of home, m), and the climb limits of the last leg.
    fn returned(from: [f64; 3], plane: bool) -> (FlightPlan, ClimbLimits) {
        let home = [-35.0, 149.0, 500.0];
        let mut f = Flown::new(home, Some(5.0));
        if plane {
            f = f.fixed_wing();
        }
        // 0.001° of latitude is 111.2 m: a waypoint `from[1]` m north of home.
        let lat = home[0] + from[1] / 111_195.0;
        f.item(&item(16, 3, lat, home[1], from[2])).unwrap();
        f.item(&item(20, 2, 0.0, 0.0, 0.0)).unwrap();
        let p = f.plan().unwrap();
        let last = *p.climbs().unwrap().last().unwrap();
        (p, last)
    }

    #[test]
    fn a_multicopter_returns_to_launch_as_ardupilots_copter_flies_it_and_lands() {
        // From 8 m up, 100 m away: up to RTL_ALT in place, home, RTL_LOITER over it, down.
        let (p, last) = returned([0.0, 100.0, 8.0], false);
        let w: Vec<[f64; 3]> = p.waypoints().iter().map(|q| q.map(|c| c.round())).collect();
        assert_eq!(
            w[2..],
            [
                [0.0, 100.0, 15.0],
                [0.0, 0.0, 15.0],
                [0.0, 0.0, 10.0],
                [0.0, 0.0, 0.0]
            ]
        );
        assert_eq!(p.holds()[3], RTL_LOITER);
        // The last 10 m at LAND_SPEED, the metres above at the descent limit.
        assert_eq!(last.down, LAND_SPEED);
        assert_eq!(p.climbs().unwrap()[3].down, ClimbLimits::MULTICOPTER.down);
        // Higher than RTL_ALT: home at its own height. Near home: at most 3 m up per metre away.
        let (high, _) = returned([0.0, 100.0, 40.0], false);
        let rounded = |p: &FlightPlan| -> Vec<[f64; 3]> {
            p.waypoints().iter().map(|q| q.map(|c| c.round())).collect()
        };
        assert_eq!(rounded(&high)[1..3], [[0.0, 100.0, 40.0], [0.0, 0.0, 40.0]]);
        let (near, _) = returned([0.0, 2.0, 1.0], false);
        assert!(
            (near.waypoints()[2][2] - 6.0).abs() < 1e-3,
            "{:?}",
            near.waypoints()
        );
        // A plane returns at its own height and stays there.
        let (plane, _) = returned([0.0, 100.0, 8.0], true);
        assert_eq!(plane.waypoints().last(), Some(&[0.0, 0.0, 8.0]));
    }

    #[test]
    fn a_multicopter_flies_to_its_landing_point_at_its_height_then_lands_straight_down() {
        let mut f = Flown::new([-35.0, 149.0, 500.0], Some(5.0));
        f.item(&item(16, 3, -35.0, 149.0, 30.0)).unwrap();
        f.item(&item(21, 3, -35.0, 149.001, 0.0)).unwrap();
        let w = f.plan().unwrap().waypoints().to_vec();
        let east = w[2][0];
        assert!((east - 91.1).abs() < 0.1, "{w:?}");
        assert_eq!(
            w[2..],
            [[east, 0.0, 30.0], [east, 0.0, 10.0], [east, 0.0, 0.0]]
        );
    }

    #[test]
    fn a_plane_circles_its_timed_loiters_and_delays_and_its_loiters_of_radius_0_at_60_m() {
        let plane = || Flown::new([-35.0, 149.0, 500.0], Some(15.0)).fixed_wing();
        // The distances from the waypoint 91.1 m east of home (`points[1]`, the loiters' centre)
        // of the points from `from` on.
        let radii = |f: &Flown, from: usize| -> Vec<f64> {
            let c = f.points[1];
            f.points[from..]
                .iter()
                .map(|p| (p[0] - c[0]).hypot(p[1] - c[1]))
                .collect()
        };
        // The points a plane's circle of radius r passes through: r / cos 15° out, so that the
        // arcs it turns on between them are the circle.
        let out = |r: f64| r / (PI / 12.0).cos();
        // 60 s at 15 m/s round a circle of 60 m: 2.39 turns, 29 points after its edge.
        let mut timed = plane();
        timed.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        let mut loiter = item(19, 3, -35.0, 149.001, 30.0);
        loiter.params[0] = Some(60.0);
        timed.item(&loiter).unwrap();
        assert_eq!(timed.points.len(), 2 + 1 + 29, "{:?}", timed.points);
        assert!(radii(&timed, 2)
            .iter()
            .all(|r| (r - out(LOITER_RADIUS)).abs() < 1e-9));
        assert!(timed.holds.iter().all(|h| *h == 0.0));
        // Its timed loiter's own radius, and a delay: circled where the plane is.
        let mut own = plane();
        own.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        loiter.params[2] = Some(-20.0);
        own.item(&loiter).unwrap();
        assert!(radii(&own, 2).iter().all(|r| (r - out(20.0)).abs() < 1e-9));
        let mut delayed = plane();
        delayed.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        delayed.item(&delay([60.0, -1.0, -1.0, -1.0])).unwrap();
        assert_eq!(delayed.points.len(), 2 + 1 + 29);
        assert!(radii(&delayed, 2)
            .iter()
            .all(|r| (r - out(LOITER_RADIUS)).abs() < 1e-9));
        // Turns of radius 0: at 60 m for a plane, on the spot for a multicopter.
        let mut turns = plane();
        turns.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        turns.item(&loiter_turns(-35.0, 149.001, 2.0, 0.0)).unwrap();
        assert_eq!(turns.points.len(), 2 + 1 + 24);
        assert!(radii(&turns, 2)
            .iter()
            .all(|r| (r - out(LOITER_RADIUS)).abs() < 1e-9));
        let mut copter = Flown::new([-35.0, 149.0, 500.0], Some(15.0));
        copter.item(&item(16, 3, -35.0, 149.001, 30.0)).unwrap();
        copter
            .item(&loiter_turns(-35.0, 149.001, 2.0, 0.0))
            .unwrap();
        assert_eq!(copter.points.len(), 3);
        // Flown, the plane's timed loiter is the circle of 60 m, for its 60 s (on its way to a
        // waypoint 1 km north, not braking to the plan's end).
        let c = timed.points[1];
        timed.item(&item(16, 3, -34.991, 149.001, 30.0)).unwrap();
        let flight = crate::fly_plan(&timed.plan().unwrap(), "loiter").unwrap();
        let on_circle: Vec<usize> = (0..flight.len())
            .filter(|&i| {
                let p = flight.pos[i];
                ((p[0] - c[0]).hypot(p[1] - c[1]) - LOITER_RADIUS).abs() < 0.5
            })
            .collect();
        // Past the way in from the centre (a leg and a turn onto the circle).
        let n = on_circle.len();
        let r = on_circle[n / 10..n - n / 10]
            .iter()
            .map(|&i| (flight.pos[i][0] - c[0]).hypot(flight.pos[i][1] - c[1]));
        let spread = r.fold(0.0f64, |m, r| m.max((r - LOITER_RADIUS).abs()));
        assert!(spread < 1e-6, "{spread}");
        let time = on_circle.len() as f64 / crate::PLAN_RATE_HZ;
        // Less the turns onto the circle and off it, which are arcs of their own.
        assert!(time > 57.0 && time <= 60.0, "{time}");
    }

    #[test]
    fn a_waypoint_without_a_position_or_in_a_terrain_frame_is_refused() {
        let mut f = Flown::new([0.0, 0.0, 0.0], None);
        let e = f.item(&item(16, 3, 0.0, 0.0, 30.0)).unwrap_err();
        assert!(e.contains("without latitude"), "{e}");
        let e = f.item(&item(16, 10, 1.0, 1.0, 30.0)).unwrap_err();
        assert!(e.contains("frame 10"), "{e}");
        assert_eq!(f.plan(), Err(PlanError::Empty));
    }
}
