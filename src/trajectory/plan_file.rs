//! Reading a mission plan (reference §16): a CSV of `x,y,z[,speed]` in the flight's frame, or a
//! QGroundControl `.plan` file (JSON; its planned home position is the frame's origin).

use super::plan::FlightPlan;
use super::MAX_CSV_BYTES;
use core::fmt;
use serde_json::Value;

/// Why a plan could not be read. Line numbers count from 1.
#[derive(Clone, Debug, PartialEq)]
pub enum PlanError {
    /// No waypoint at all.
    Empty,
    /// Fewer than two distinct waypoints: no leg to fly.
    TooFewWaypoints,
    /// More waypoints than loratrack reads.
    TooManyWaypoints {
        /// The most accepted.
        max: usize,
    },
    /// A plan text larger than a CSV flight may be.
    TooLarge {
        /// Its size, bytes.
        bytes: usize,
    },
    /// A CSV line that is not `x,y,z[,speed]`.
    Line {
        /// Line number.
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// A QGroundControl file loratrack cannot read (what, and where).
    Qgc(String),
    /// Values that do not make a plan.
    Invalid(String),
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlanError::Empty => write!(f, "the plan has no waypoints"),
            PlanError::TooFewWaypoints => {
                write!(f, "the plan needs at least two distinct waypoints")
            }
            PlanError::TooManyWaypoints { max } => {
                write!(f, "the plan has more than {max} waypoints")
            }
            PlanError::TooLarge { bytes } => write!(
                f,
                "the plan is {:.1} MiB; at most {} MiB is read",
                *bytes as f64 / (1024.0 * 1024.0),
                MAX_CSV_BYTES >> 20
            ),
            PlanError::Line { line, what } => write!(f, "plan line {line}: {what}"),
            PlanError::Qgc(what) => write!(f, "QGroundControl plan: {what}"),
            PlanError::Invalid(what) => write!(f, "plan: {what}"),
        }
    }
}

impl std::error::Error for PlanError {}

/// Reads a plan: QGroundControl JSON when the text starts with `{`, else CSV.
///
/// CSV: one waypoint per line, `x,y,z` or `x,y,z,speed` (m east, north, up in the flight's
/// frame; the speed, m/s, is for the leg that ends at that waypoint); a header line of names,
/// blank lines and lines starting with `#` are skipped.
///
/// ```
/// let plan = loratrack::parse_plan("x,y,z,speed\n0,0,20\n100,0,20,8\n").unwrap();
/// assert_eq!(plan.speed_at(50.0), Some(8.0));
/// ```
pub fn parse_plan(text: &str) -> Result<FlightPlan, PlanError> {
    if text.len() > MAX_CSV_BYTES {
        return Err(PlanError::TooLarge { bytes: text.len() });
    }
    if text.trim_start().starts_with('{') {
        parse_qgc(text)
    } else {
        parse_csv_plan(text)
    }
}

fn parse_csv_plan(text: &str) -> Result<FlightPlan, PlanError> {
    let mut points = Vec::new();
    let mut speeds = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let numbers: Result<Vec<f64>, _> = fields.iter().map(|f| f.parse::<f64>()).collect();
        let Ok(numbers) = numbers else {
            if points.is_empty() && fields.iter().all(|f| f.parse::<f64>().is_err()) {
                continue; // a header
            }
            return Err(PlanError::Line {
                line: i + 1,
                what: format!("expected x,y,z[,speed] numbers, got '{}'", excerpt(line)),
            });
        };
        if !(3..=4).contains(&numbers.len()) {
            return Err(PlanError::Line {
                line: i + 1,
                what: format!("{} fields; a waypoint is x,y,z[,speed]", numbers.len()),
            });
        }
        if !points.is_empty() {
            speeds.push(numbers.get(3).copied());
        }
        points.push([numbers[0], numbers[1], numbers[2]]);
        if points.len() > super::MAX_WAYPOINTS {
            return Err(PlanError::TooManyWaypoints {
                max: super::MAX_WAYPOINTS,
            });
        }
    }
    if points.is_empty() {
        return Err(PlanError::Empty);
    }
    FlightPlan::new(points, speeds)
}

/// At most 60 characters of `text`.
fn excerpt(text: &str) -> String {
    let head: String = text.chars().take(60).collect();
    if text.chars().count() > 60 {
        format!("{head}…")
    } else {
        head
    }
}

/// MAVLink commands (`MAV_CMD`) a QGroundControl mission uses that loratrack reads.
const NAV_WAYPOINT: u64 = 16;
const NAV_LOITER_UNLIM: u64 = 17;
const NAV_LOITER_TURNS: u64 = 18;
const NAV_LOITER_TIME: u64 = 19;
const NAV_RETURN_TO_LAUNCH: u64 = 20;
const NAV_LAND: u64 = 21;
const NAV_TAKEOFF: u64 = 22;
const NAV_LOITER_TO_ALT: u64 = 31;
const NAV_SPLINE_WAYPOINT: u64 = 82;
const NAV_VTOL_TAKEOFF: u64 = 84;
const NAV_VTOL_LAND: u64 = 85;
const DO_CHANGE_SPEED: u64 = 178;
/// Commands that fly to their own latitude and longitude: a waypoint, a spline waypoint (its leg
/// read as straight) and the loiters (read as their centre: the circle is not flown).
const FLY_TO: [u64; 6] = [
    NAV_WAYPOINT,
    NAV_LOITER_UNLIM,
    NAV_LOITER_TURNS,
    NAV_LOITER_TIME,
    NAV_LOITER_TO_ALT,
    NAV_SPLINE_WAYPOINT,
];
/// `MAV_TYPE`s QGroundControl plans at the mission's hover speed (its multi-rotor class):
/// quadrotor, coaxial, helicopter, hexarotor, octorotor, tricopter; any other at the cruise speed.
const MULTIROTORS: [u64; 6] = [2, 3, 4, 13, 14, 15];
/// The `fileType` of a QGroundControl plan file (QGroundControl's "Plan File Format").
const PLAN_FILE_TYPE: &str = "Plan";
/// Mean Earth radius, m: over a mission's few kilometres the local east-north plane is flat to
/// well under a metre.
const EARTH_RADIUS: f64 = 6_371_000.0;

/// A QGroundControl `.plan` (`fileType: "Plan"`): the mission's waypoints (take-off, waypoints,
/// loiters at their centre, spline waypoints as straight legs, landing, return to launch) in the
/// east-north-up frame of its planned home position, at the mission's hover speed (multi-rotor)
/// or cruise speed, changed by `DO_CHANGE_SPEED`. Altitudes are relative to home (frames 3 and
/// 6) or, in frames 0 and 5, above mean sea level less home's. Complex items (surveys, corridor
/// scans) are refused with their name.
fn parse_qgc(text: &str) -> Result<FlightPlan, PlanError> {
    let v: Value =
        serde_json::from_str(text).map_err(|e| PlanError::Qgc(format!("not JSON: {e}")))?;
    match v.get("fileType") {
        Some(Value::String(kind)) if kind == PLAN_FILE_TYPE => {}
        Some(Value::String(kind)) => {
            return Err(PlanError::Qgc(format!(
                "fileType is \"{}\", not \"{PLAN_FILE_TYPE}\"",
                excerpt(kind)
            )))
        }
        _ => {
            return Err(PlanError::Qgc(format!(
                "no fileType \"{PLAN_FILE_TYPE}\": not a plan file"
            )))
        }
    }
    let mission = v
        .get("mission")
        .ok_or_else(|| PlanError::Qgc("no mission".into()))?;
    let mut flown = Flown::new(mission)?;
    let items = mission
        .get("items")
        .and_then(Value::as_array)
        .ok_or_else(|| PlanError::Qgc("mission.items is not a list".into()))?;
    for (i, item) in items.iter().enumerate() {
        flown
            .item(item)
            .map_err(|what| PlanError::Qgc(format!("item {}: {what}", i + 1)))?;
    }
    if flown.points.len() < 2 {
        return Err(PlanError::Empty);
    }
    FlightPlan::new(flown.points, flown.speeds)
}

/// A QGroundControl mission as its items are read in order: the waypoints so far (home first),
/// the speed of each leg, and the speed the next leg will have.
struct Flown {
    /// Home: latitude and longitude, degrees, and altitude above mean sea level, m.
    home: [f64; 3],
    speed: Option<f64>,
    points: Vec<[f64; 3]>,
    speeds: Vec<Option<f64>>,
}

impl Flown {
    /// Starts at the mission's planned home position, at its hover speed (multirotor) or cruise
    /// speed.
    fn new(mission: &Value) -> Result<Self, PlanError> {
        let home = mission
            .get("plannedHomePosition")
            .and_then(Value::as_array)
            .and_then(|h| {
                let n: Vec<f64> = h.iter().filter_map(Value::as_f64).collect();
                (n.len() == 3).then(|| [n[0], n[1], n[2]])
            })
            .ok_or_else(|| PlanError::Qgc("no plannedHomePosition [lat, lon, alt]".into()))?;
        let multirotor = mission
            .get("vehicleType")
            .and_then(Value::as_u64)
            .is_some_and(|t| MULTIROTORS.contains(&t));
        let default_speed = if multirotor {
            "hoverSpeed"
        } else {
            "cruiseSpeed"
        };
        Ok(Flown {
            home,
            speed: mission.get(default_speed).and_then(Value::as_f64),
            points: vec![[0.0, 0.0, 0.0]],
            speeds: Vec::new(),
        })
    }

    /// Reads one mission item: a speed change, a leg to a new waypoint, or nothing that moves
    /// the vehicle. The refusal says what is wrong with the item.
    fn item(&mut self, item: &Value) -> Result<(), String> {
        if item.get("type").and_then(Value::as_str) != Some("SimpleItem") {
            let kind = item
                .get("complexItemType")
                .and_then(Value::as_str)
                .unwrap_or("unknown");
            return Err(format!(
                "complex item '{}' is not read; convert it to waypoints in QGroundControl",
                excerpt(kind)
            ));
        }
        let command = item.get("command").and_then(Value::as_u64).unwrap_or(0);
        let params: Vec<Option<f64>> = item
            .get("params")
            .and_then(Value::as_array)
            .map(|p| p.iter().map(Value::as_f64).collect())
            .unwrap_or_default();
        let param = |k: usize| params.get(k).copied().flatten();
        let last = self.points[self.points.len() - 1];
        let point = match command {
            DO_CHANGE_SPEED => {
                self.speed = param(1).filter(|s| *s > 0.0).or(self.speed);
                return Ok(());
            }
            NAV_RETURN_TO_LAUNCH => [0.0, 0.0, last[2]],
            // Take-off and landing often leave the position to the vehicle: in place.
            NAV_TAKEOFF | NAV_VTOL_TAKEOFF => {
                let [x, y] = self
                    .horizontal(param(4), param(5))
                    .unwrap_or([last[0], last[1]]);
                [x, y, self.altitude(param(6), item)?]
            }
            NAV_LAND | NAV_VTOL_LAND => {
                let [x, y] = self
                    .horizontal(param(4), param(5))
                    .unwrap_or([last[0], last[1]]);
                [x, y, 0.0]
            }
            c if FLY_TO.contains(&c) => {
                let [x, y] = self
                    .horizontal(param(4), param(5))
                    .ok_or("a waypoint without latitude and longitude")?;
                [x, y, self.altitude(param(6), item)?]
            }
            // Camera, gimbal, delay and other commands do not move the vehicle.
            _ => return Ok(()),
        };
        self.points.push(point);
        self.speeds.push(self.speed);
        Ok(())
    }

    /// East and north of home, m, of an item's latitude and longitude (degrees); `None` where it
    /// gives none (missing, or 0, 0: the vehicle's own position).
    fn horizontal(&self, lat: Option<f64>, lon: Option<f64>) -> Option<[f64; 2]> {
        let (lat, lon) = (lat?, lon?);
        if lat == 0.0 && lon == 0.0 {
            return None;
        }
        let k = core::f64::consts::PI / 180.0 * EARTH_RADIUS;
        Some([
            (lon - self.home[1]) * k * crate::math::cos(self.home[0].to_radians()),
            (lat - self.home[0]) * k,
        ])
    }

    /// An item's altitude above home, m, from its altitude parameter in its frame.
    fn altitude(&self, alt: Option<f64>, item: &Value) -> Result<f64, String> {
        let alt = alt.ok_or("no altitude")?;
        // MAV_FRAME_GLOBAL (0) and its integer twin (5) are above mean sea level; the relative
        // frames (3, 6) above home; terrain-following ones need a terrain model loratrack lacks.
        match item.get("frame").and_then(Value::as_u64) {
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

    #[test]
    fn reads_csv_with_and_without_header_and_speed() {
        let p = parse_plan("# survey\nx,y,z,speed\n0,0,20\n\n100,0,20,8\n100,50,30\n").unwrap();
        assert_eq!(p.waypoints().len(), 3);
        assert_eq!(p.speed_at(10.0), Some(8.0));
        assert_eq!(p.speed_at(110.0), None);
        let q = parse_plan("0,0,20\n0,10,20\n").unwrap();
        assert_eq!(q.length(), 10.0);
    }

    #[test]
    fn csv_errors_name_the_line() {
        let e = parse_plan("x,y,z\n0,0,1\n1,abc,1\n").unwrap_err();
        assert_eq!(
            e,
            PlanError::Line {
                line: 3,
                what: "expected x,y,z[,speed] numbers, got '1,abc,1'".into()
            }
        );
        assert!(e.to_string().starts_with("plan line 3:"));
        assert!(matches!(
            parse_plan("0,0\n1,1\n"),
            Err(PlanError::Line { line: 1, .. })
        ));
        assert_eq!(parse_plan("x,y,z\n"), Err(PlanError::Empty));
        assert_eq!(parse_plan("0,0,1\n"), Err(PlanError::TooFewWaypoints));
    }

    fn qgc(items: &str) -> String {
        format!(
            r#"{{"fileType": "Plan", "mission": {{"vehicleType": 2, "hoverSpeed": 5, "cruiseSpeed": 15,
            "plannedHomePosition": [-35.3632, 149.1652, 584], "items": [{items}]}}}}"#
        )
    }

    #[test]
    fn reads_a_qgroundcontrol_mission_in_the_home_frame() {
        let text = qgc(
            r#"{"type": "SimpleItem", "command": 22, "frame": 3, "params": [0, 0, 0, null, 0, 0, 30]},
               {"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0, null, -35.3632, 149.1663, 30]},
               {"type": "SimpleItem", "command": 178, "frame": 2, "params": [1, 8, -1, 0, 0, 0, 0]},
               {"type": "SimpleItem", "command": 16, "frame": 0, "params": [0, 0, 0, null, -35.3623, 149.1663, 624]},
               {"type": "SimpleItem", "command": 20, "frame": 2, "params": [0, 0, 0, 0, 0, 0, 0]}"#,
        );
        let p = parse_plan(&text).unwrap();
        let w = p.waypoints();
        assert_eq!(w.len(), 5);
        assert_eq!(w[1], [0.0, 0.0, 30.0]);
        // 0.0011° of longitude at -35.36°: about 99.8 m east; 0.0009° of latitude: 100.1 m north.
        assert!(
            (w[2][0] - 99.8).abs() < 0.5 && w[2][1].abs() < 1e-9,
            "{:?}",
            w[2]
        );
        assert!(
            (w[3][1] - 100.1).abs() < 0.5 && (w[3][2] - 40.0).abs() < 1e-9,
            "{:?}",
            w[3]
        );
        assert_eq!(w[4], [0.0, 0.0, 40.0]);
        assert_eq!(p.speed_at(1.0), Some(5.0));
        assert_eq!(p.speed_at(p.length() - 1.0), Some(8.0));
    }

    /// A mission as QGroundControl 4 saves it (its "Plan File Format": the top level's version,
    /// ground station, geofence and rally points, each item's altitude fields, jump id and a yaw
    /// of null), for a hexarotor: take-off, a waypoint in frame 6, a loiter, a spline waypoint
    /// and a landing in place.
    const QGC4_HEXAROTOR: &str = r#"{
        "fileType": "Plan",
        "geoFence": {"circles": [], "polygons": [], "version": 2},
        "groundStation": "QGroundControl",
        "mission": {
            "cruiseSpeed": 15, "firmwareType": 3, "globalPlanAltitudeMode": 1, "hoverSpeed": 4,
            "items": [
                {"AMSLAltAboveTerrain": null, "Altitude": 25, "AltitudeMode": 1, "autoContinue": true,
                 "command": 22, "doJumpId": 1, "frame": 3,
                 "params": [0, 0, 0, null, -35.3632, 149.1652, 25], "type": "SimpleItem"},
                {"AMSLAltAboveTerrain": null, "Altitude": 25, "AltitudeMode": 1, "autoContinue": true,
                 "command": 16, "doJumpId": 2, "frame": 6,
                 "params": [0, 0, 0, null, -35.3632, 149.1663, 25], "type": "SimpleItem"},
                {"autoContinue": true, "command": 19, "doJumpId": 3, "frame": 3,
                 "params": [30, 0, 10, 0, -35.3623, 149.1663, 35], "type": "SimpleItem"},
                {"autoContinue": true, "command": 82, "doJumpId": 4, "frame": 3,
                 "params": [0, 0, 0, 0, -35.3623, 149.1652, 35], "type": "SimpleItem"},
                {"autoContinue": true, "command": 21, "doJumpId": 5, "frame": 3,
                 "params": [0, 0, 0, null, 0, 0, 0], "type": "SimpleItem"}
            ],
            "plannedHomePosition": [-35.3632, 149.1652, 584],
            "vehicleType": 13,
            "version": 2
        },
        "rallyPoints": {"points": [], "version": 2},
        "version": 1
    }"#;

    #[test]
    fn reads_a_mission_as_qgroundcontrol_saves_it() {
        let p = parse_plan(QGC4_HEXAROTOR).unwrap();
        let w = p.waypoints();
        // Home, take-off above it, the waypoint, the loiter's centre, the spline waypoint, landing.
        assert_eq!(w.len(), 6, "{w:?}");
        assert_eq!(w[1], [0.0, 0.0, 25.0]);
        assert!(
            (w[2][0] - 99.8).abs() < 0.5 && w[2][2] == 25.0,
            "{:?}",
            w[2]
        );
        assert!(
            (w[3][1] - 100.1).abs() < 0.5 && w[3][2] == 35.0,
            "{:?}",
            w[3]
        );
        assert!(
            w[4][0].abs() < 1e-9 && (w[4][1] - 100.1).abs() < 0.5,
            "{:?}",
            w[4]
        );
        assert_eq!(w[5], [w[4][0], w[4][1], 0.0]);
        // A hexarotor flies at the hover speed, as QGroundControl plans a multi-rotor.
        assert_eq!(p.speed_at(1.0), Some(4.0));
        let fixed_wing = QGC4_HEXAROTOR.replace(r#""vehicleType": 13"#, r#""vehicleType": 1"#);
        assert_eq!(parse_plan(&fixed_wing).unwrap().speed_at(1.0), Some(15.0));
    }

    #[test]
    fn qgroundcontrol_refusals_say_what_and_where() {
        let survey = qgc(r#"{"type": "ComplexItem", "complexItemType": "survey"}"#);
        let e = parse_plan(&survey).unwrap_err().to_string();
        assert!(e.contains("item 1") && e.contains("survey"), "{e}");
        let other = QGC4_HEXAROTOR.replace(r#""fileType": "Plan""#, r#""fileType": "FlightPlan""#);
        let e = parse_plan(&other).unwrap_err().to_string();
        assert!(e.contains(r#"fileType is "FlightPlan", not "Plan""#), "{e}");
        let e = parse_plan("{\"mission\": {}}").unwrap_err().to_string();
        assert!(e.contains("not a plan file"), "{e}");
        let terrain = QGC4_HEXAROTOR.replace(r#""frame": 6"#, r#""frame": 10"#);
        let e = parse_plan(&terrain).unwrap_err().to_string();
        assert!(e.contains("item 2") && e.contains("frame 10"), "{e}");
        assert!(parse_plan("{ not json")
            .unwrap_err()
            .to_string()
            .contains("not JSON"));
    }
}
