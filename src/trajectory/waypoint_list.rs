//! A plain-text MAVLink waypoint list (`QGC WPL 110`: Mission Planner's and ArduPilot's
//! `.waypoints` files, QGroundControl's older export), read into a plan in the east-north-up frame
//! of its home, item 0 (reference §16).

use super::mission_items::{Flown, MissionItem};
use super::plan::FlightPlan;
use super::plan_file::{excerpt, PlanError};
use super::Cornering;

/// The first line's first word pair: the format's name (then its version, 110 or 120).
pub(super) const WPL_HEADER: &str = "QGC WPL";
/// Fields per item: index, current, frame, command, parameters 1–4, latitude, longitude,
/// altitude, autocontinue (MAVLink's "Mission Plain-Text File Format").
const FIELDS: usize = 12;

/// Reads a waypoint list: item 0 is home (its latitude, longitude and altitude above mean sea
/// level: the plan's origin, as ArduPilot's ground stations write it); the other items are read
/// as a QGroundControl plan's (take-off, waypoints, loiters, landing, return to launch, speed
/// changes). The list carries no default speed: a leg before any `DO_CHANGE_SPEED` has none,
/// and the mission station paces it by the packet's speed. Fields are separated by tabs or
/// spaces; blank lines are skipped; a refusal names the line. It names no vehicle: flown as a
/// multicopter unless `vehicle` says otherwise.
pub(super) fn parse_waypoint_list(
    text: &str,
    vehicle: Option<Cornering>,
) -> Result<FlightPlan, PlanError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    match lines.next() {
        Some((_, header)) if header.starts_with(WPL_HEADER) => {}
        _ => {
            return Err(PlanError::Invalid(format!(
                "no \"{WPL_HEADER}\" first line"
            )))
        }
    }
    let mut flown: Option<Flown> = None;
    for (line, text) in lines {
        let (index, item) = item(text).map_err(|what| PlanError::Line { line, what })?;
        match flown.as_mut() {
            None if index == 0 => {
                let [lat, lon, alt] = [4, 5, 6].map(|k| item.params[k]);
                let (Some(lat), Some(lon), Some(alt)) = (lat, lon, alt) else {
                    return Err(PlanError::Line {
                        line,
                        what: "home (item 0) needs a latitude, longitude and altitude".into(),
                    });
                };
                let home = Flown::new([lat, lon, alt], None);
                flown = Some(match vehicle {
                    Some(Cornering::FixedWing) => home.fixed_wing(),
                    _ => home,
                });
            }
            None => {
                return Err(PlanError::Line {
                    line,
                    what: "the first item is not home (item 0)".into(),
                })
            }
            Some(flown) => flown
                .item(&item)
                .map_err(|what| PlanError::Line { line, what })?,
        }
    }
    flown.ok_or(PlanError::Empty)?.plan()
}

/// One line: its index and its mission item.
fn item(text: &str) -> Result<(u64, MissionItem), String> {
    let fields: Vec<&str> = text.split_whitespace().collect();
    if fields.len() != FIELDS {
        return Err(format!(
            "{} fields; a waypoint list's item has {FIELDS} (index, current, frame, command, \
             four parameters, latitude, longitude, altitude, autocontinue)",
            fields.len()
        ));
    }
    let whole = |k: usize| {
        fields[k]
            .parse::<u64>()
            .map_err(|_| format!("expected a whole number, got '{}'", excerpt(fields[k])))
    };
    let mut params = [None; 7];
    for (k, p) in params.iter_mut().enumerate() {
        let v: f64 = fields[4 + k]
            .parse()
            .map_err(|_| format!("expected a number, got '{}'", excerpt(fields[4 + k])))?;
        // An empty parameter is written as NaN (a take-off's yaw, say).
        *p = v.is_finite().then_some(v);
    }
    let item = MissionItem {
        command: whole(3)?,
        frame: Some(whole(2)?),
        params,
    };
    Ok((whole(0)?, item))
}

#[cfg(test)]
mod tests {
    use super::super::parse_plan;
    use super::*;

    /// A Mission Planner mission: home in Canberra, take-off to 30 m, two waypoints (the second
    /// after a change to 8 m/s), a 30 s loiter and a return to launch.
    const MISSION_PLANNER: &str = "QGC WPL 110\n\
        0\t1\t0\t16\t0\t0\t0\t0\t-35.363262\t149.165237\t584.000000\t1\n\
        1\t0\t3\t22\t0.000000\t0.000000\t0.000000\tnan\t0.000000\t0.000000\t30.000000\t1\n\
        2\t0\t3\t16\t0.000000\t0.000000\t0.000000\t0.000000\t-35.363262\t149.166337\t30.000000\t1\n\
        3\t0\t3\t178\t1.000000\t8.000000\t-1.000000\t0.000000\t0.000000\t0.000000\t0.000000\t1\n\
        4\t0\t3\t16\t0.000000\t0.000000\t0.000000\t0.000000\t-35.362362\t149.166337\t40.000000\t1\n\
        5\t0\t3\t19\t30.000000\t0.000000\t0.000000\t0.000000\t-35.362362\t149.165237\t40.000000\t1\n\
        6\t0\t3\t20\t0.000000\t0.000000\t0.000000\t0.000000\t0.000000\t0.000000\t0.000000\t1\n";

    #[test]
    fn reads_a_mission_planner_waypoint_file_as_the_same_qgroundcontrol_plan() {
        let wpl = parse_plan(MISSION_PLANNER).unwrap();
        let w = wpl.waypoints();
        // Home, take-off, two waypoints, the loiter, home at 40 m and the landing (10 m, 0 m).
        assert_eq!(w.len(), 8, "{w:?}");
        assert_eq!(w[1], [0.0, 0.0, 30.0]);
        assert!(
            (w[2][0] - 99.8).abs() < 0.5 && w[2][2] == 30.0,
            "{:?}",
            w[2]
        );
        assert_eq!(w[5], [0.0, 0.0, 40.0]);
        // No default speed in the list: none until the change to 8 m/s.
        assert_eq!(wpl.speed_at(1.0), None);
        assert_eq!(wpl.speed_at(wpl.length() - 1.0), Some(8.0));
        // The same items in a QGroundControl plan without speeds give the same plan, bit for bit.
        let items: Vec<String> = MISSION_PLANNER
            .lines()
            .skip(2)
            .map(|l| {
                let f: Vec<&str> = l.split('\t').collect();
                let p: Vec<String> = f[4..11]
                    .iter()
                    .map(|v| {
                        if *v == "nan" {
                            "null".into()
                        } else {
                            v.to_string()
                        }
                    })
                    .collect();
                format!(
                    r#"{{"type": "SimpleItem", "command": {}, "frame": {}, "params": [{}]}}"#,
                    f[3],
                    f[2],
                    p.join(", ")
                )
            })
            .collect();
        let qgc = format!(
            r#"{{"fileType": "Plan", "mission": {{"plannedHomePosition": [-35.363262, 149.165237, 584],
                "items": [{}]}}}}"#,
            items.join(", ")
        );
        assert_eq!(parse_plan(&qgc).unwrap(), wpl);
        // Saved on Windows: a byte-order mark and CRLF line ends.
        let windows = format!("\u{feff}{}", MISSION_PLANNER.replace('\n', "\r\n"));
        assert_eq!(parse_plan(&windows).unwrap(), wpl);
    }

    /// A waypoint list names no vehicle: a multicopter's unless `--vehicle` says it is a plane,
    /// which then circles the timed loiter instead of hovering and turns wide.
    #[test]
    fn a_waypoint_list_is_a_multicopters_unless_the_vehicle_is_set() {
        use crate::Cornering::{FixedWing, Multicopter};
        let read = |vehicle| super::super::parse_plan_as(MISSION_PLANNER, vehicle).unwrap();
        assert_eq!(read(None), read(Some(Multicopter)));
        assert_eq!(read(None).cornering(), Multicopter);
        let plane = read(Some(FixedWing));
        assert_eq!(plane.cornering(), FixedWing);
        assert!(read(None).holds().iter().any(|h| *h > 0.0));
        assert!(
            plane.holds().iter().all(|h| *h == 0.0),
            "{:?}",
            plane.holds()
        );
        assert!(plane.waypoints().len() > read(None).waypoints().len());
    }

    #[test]
    fn a_waypoint_list_refusal_names_its_line() {
        let short = MISSION_PLANNER.replace("\t40.000000\t1\n5", "\t40.000000\n5");
        let e = parse_plan(&short).unwrap_err();
        assert!(
            matches!(&e, PlanError::Line { line: 6, what } if what.contains("11 fields")),
            "{e}"
        );
        let bad = MISSION_PLANNER.replace("149.166337\t30", "east\t30");
        let e = parse_plan(&bad).unwrap_err().to_string();
        assert!(e.starts_with("plan line 4:") && e.contains("'east'"), "{e}");
        let no_home = MISSION_PLANNER.replacen("0\t1\t0\t16", "1\t1\t0\t16", 1);
        let e = parse_plan(&no_home).unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("not home"), "{e}");
        assert_eq!(parse_plan("QGC WPL 110\n"), Err(PlanError::Empty));
    }
}
