//! A QGroundControl `.plan` file (JSON; QGroundControl's "Plan File Format"), read into a plan in
//! the east-north-up frame of its planned home position (reference §16).

use super::mission_items::{Flown, MissionItem};
use super::plan::FlightPlan;
use super::plan_file::{excerpt, PlanError};
use super::Cornering;
use serde_json::Value;

/// `MAV_TYPE`s QGroundControl plans at the mission's hover speed (its multi-rotor class):
/// quadrotor, coaxial, helicopter, hexarotor, octorotor, tricopter; any other at the cruise speed.
const MULTIROTORS: [u64; 6] = [2, 3, 4, 13, 14, 15];
/// The `fileType` of a QGroundControl plan file.
const PLAN_FILE_TYPE: &str = "Plan";

/// A QGroundControl `.plan` (`fileType: "Plan"`): the mission's items (reference §16:
/// take-off, waypoints, timed loiters at their centre, loiter turns round their circle, spline
/// waypoints as straight legs, landing, return to launch) from its planned home position, at the
/// mission's hover speed (multi-rotor) or cruise speed, changed by `DO_CHANGE_SPEED`, flown as
/// `vehicle` where given, else as its `vehicleType` names. Complex items (surveys, corridor
/// scans) are refused with their name.
pub(super) fn parse_qgc(text: &str, vehicle: Option<Cornering>) -> Result<FlightPlan, PlanError> {
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
    let named = mission.get("vehicleType").and_then(Value::as_u64);
    let multirotor = match vehicle {
        Some(v) => v == Cornering::Multicopter,
        None => named.is_some_and(|t| MULTIROTORS.contains(&t)),
    };
    let mut flown = Flown::new(home(mission)?, speed(mission, multirotor));
    // A plan that names no vehicle keeps the holds it gives.
    if !multirotor && (vehicle.is_some() || named.is_some()) {
        flown = flown.fixed_wing();
    }
    let items = mission
        .get("items")
        .and_then(Value::as_array)
        .ok_or_else(|| PlanError::Qgc("mission.items is not a list".into()))?;
    for (i, item) in items.iter().enumerate() {
        simple_item(item)
            .and_then(|item| flown.item(&item))
            .map_err(|what| PlanError::Qgc(format!("item {}: {what}", i + 1)))?;
    }
    flown.plan()
}

/// The planned home position: latitude and longitude, degrees, and altitude above mean sea
/// level, m.
fn home(mission: &Value) -> Result<[f64; 3], PlanError> {
    mission
        .get("plannedHomePosition")
        .and_then(Value::as_array)
        .and_then(|h| {
            let n: Vec<f64> = h.iter().filter_map(Value::as_f64).collect();
            (n.len() == 3).then(|| [n[0], n[1], n[2]])
        })
        .ok_or_else(|| PlanError::Qgc("no plannedHomePosition [lat, lon, alt]".into()))
}

/// The mission's default speed, m/s: its hover speed for a multi-rotor, else its cruise speed.
fn speed(mission: &Value, multirotor: bool) -> Option<f64> {
    let key = if multirotor {
        "hoverSpeed"
    } else {
        "cruiseSpeed"
    };
    mission.get(key).and_then(Value::as_f64)
}

/// A `SimpleItem` as a mission item; a complex item is refused with its name.
fn simple_item(item: &Value) -> Result<MissionItem, String> {
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
    let params = item.get("params").and_then(Value::as_array);
    Ok(MissionItem {
        command: item.get("command").and_then(Value::as_u64).unwrap_or(0),
        frame: item.get("frame").and_then(Value::as_u64),
        params: core::array::from_fn(|k| params.and_then(|p| p.get(k)).and_then(Value::as_f64)),
    })
}

#[cfg(test)]
mod tests {
    use super::super::parse_plan;

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
        assert_eq!(w.len(), 7, "{w:?}");
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
        // Home at the height it returns at (above RTL_ALT), hovered over for RTL_LOIT_TIME, and
        // the landing: at the descent limit to 10 m, then at LAND_SPEED.
        assert_eq!(
            w[4..],
            [[0.0, 0.0, 40.0], [0.0, 0.0, 10.0], [0.0, 0.0, 0.0]]
        );
        assert_eq!(p.holds()[4], crate::trajectory::RTL_LOITER);
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
        // Home, take-off above it, the waypoint, the loiter's centre, the spline waypoint, and
        // the landing in place: down to 10 m, then to the ground.
        assert_eq!(w.len(), 7, "{w:?}");
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
        assert_eq!(w[5..], [[w[4][0], w[4][1], 10.0], [w[4][0], w[4][1], 0.0]]);
        // A hexarotor flies at the hover speed, as QGroundControl plans a multi-rotor.
        assert_eq!(p.speed_at(1.0), Some(4.0));
        // The timed loiter holds 30 s at its centre.
        assert_eq!(p.holds(), &[0.0, 0.0, 0.0, 30.0, 0.0, 0.0, 0.0]);
        let fixed_wing = QGC4_HEXAROTOR.replace(r#""vehicleType": 13"#, r#""vehicleType": 1"#);
        assert_eq!(parse_plan(&fixed_wing).unwrap().speed_at(1.0), Some(15.0));
        // A plane turns through its waypoints as ArduPlane does, a multi-rotor as Copter does.
        let cornering = |plan: &str| parse_plan(plan).unwrap().cornering();
        assert_eq!(cornering(&fixed_wing), crate::Cornering::FixedWing);
        assert_eq!(cornering(QGC4_HEXAROTOR), crate::Cornering::Multicopter);
        // A waypoint's hold time: a multi-rotor hovers there, a fixed-wing flies through it.
        let held = |plan: &str| {
            let held = plan.replace(
                "[0, 0, 0, null, -35.3632, 149.1663, 25]",
                "[12, 0, 0, null, -35.3632, 149.1663, 25]",
            );
            parse_plan(&held).unwrap().holds().to_vec()
        };
        assert_eq!(held(QGC4_HEXAROTOR), [0.0, 0.0, 12.0, 30.0, 0.0, 0.0, 0.0]);
        // A plane holds nowhere: it circles the timed loiter's 10 m for its 30 s at 15 m/s
        // (7.2 turns, 86 points after the circle's edge) and glides to the landing.
        let plane = held(&fixed_wing);
        assert_eq!(plane.len(), 3 + 1 + 86 + 2, "{plane:?}");
        assert!(plane.iter().all(|h| *h == 0.0), "{plane:?}");
    }

    /// `--vehicle` overrides the plan's `vehicleType`: all a plane flies differently (no holds,
    /// its cruise speed, its turns) follows it, and a plan read as its own vehicle is unchanged.
    #[test]
    fn a_vehicle_set_overrides_the_plans_vehicle_type() {
        use crate::Cornering::{FixedWing, Multicopter};
        let plane = QGC4_HEXAROTOR.replace(r#""vehicleType": 13"#, r#""vehicleType": 1"#);
        let read = |plan: &str, vehicle| super::super::parse_plan_as(plan, vehicle).unwrap();
        assert_eq!(read(QGC4_HEXAROTOR, Some(FixedWing)), read(&plane, None));
        assert_eq!(read(&plane, Some(Multicopter)), read(QGC4_HEXAROTOR, None));
        assert_eq!(read(&plane, Some(FixedWing)), read(&plane, None));
        let hexarotor = read(QGC4_HEXAROTOR, None);
        let as_plane = read(QGC4_HEXAROTOR, Some(FixedWing));
        assert_eq!(as_plane.cornering(), FixedWing);
        assert_eq!(
            (hexarotor.speed_at(1.0), as_plane.speed_at(1.0)),
            (Some(4.0), Some(15.0))
        );
        assert!(as_plane.holds().iter().all(|h| *h == 0.0));
        assert_eq!(hexarotor.holds()[3], 30.0);
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
