//! The mission-aware station (reference §16): what it claims on the synthetic set, that a plan
//! given as a file is read and followed, that it falls back to bounded 3D-CTRA off its plan, and
//! that the settings it needs are checked first.

use loratrack::api::{clean_message, simulate, swarm};
use loratrack::{
    fly_plan, synthetic_flight, ClimbLimits, Cornering, FlightPlan, ModelResult, Scenario,
    Simulator, StationModel, CORNER_ACCEL, CORNER_RADIUS, MAX_FLOWN_S, PLAN_ACCEL, PLAN_CRUISE,
    TRACE_TOLERANCE,
};
use serde_json::{json, Value};

fn run(settings: Value) -> Vec<ModelResult> {
    let s = Scenario::default().with(&settings).unwrap();
    simulate(&mut Simulator::new(), &s).unwrap().results
}

fn p75(results: &[ModelResult], model: &str) -> f64 {
    results
        .iter()
        .find(|r| r.model.name() == model)
        .unwrap()
        .error3d
        .p75
}

#[test]
fn the_mission_station_beats_every_other_station_where_packets_are_scarce() {
    for (sf, bw) in [(10, 125.0), (12, 125.0)] {
        let r = run(
            json!({"synthetic": "all", "model": "all,imm,mission", "prediction": "bounded",
                            "sf": sf, "bw": bw, "overhead": 0}),
        );
        let mission = p75(&r, "mission");
        for other in ["dr", "ctra-plus", "3d-ctra", "imm"] {
            assert!(
                mission < 0.5 * p75(&r, other),
                "SF{sf}: mission {mission} against {other} {}",
                p75(&r, other)
            );
        }
    }
}

#[test]
fn with_packets_every_two_seconds_it_still_beats_bounded_3d_ctra() {
    let r = run(
        json!({"synthetic": "all", "model": "3d-ctra,mission", "prediction": "bounded",
                        "overhead": 0}),
    );
    assert!(p75(&r, "mission") < p75(&r, "3d-ctra"), "{r:?}");
}

#[test]
fn its_uncertainty_is_honest_on_the_synthetic_set() {
    for sf in [7, 9, 12] {
        let bw = if sf == 7 { 250.0 } else { 125.0 };
        let r = run(json!({"synthetic": "all", "model": "mission", "sf": sf, "bw": bw}));
        let c = r[0].coverage95;
        assert!((0.93..=0.995).contains(&c), "SF{sf}: coverage95 {c}");
    }
}

#[test]
fn a_plan_file_is_followed_as_the_synthetic_flight_follows_its_own() {
    // A plan file is one for an autopilot, flown within a multicopter's climb limits, which a
    // traced plan is not: a flight none of whose legs climbs or descends past them.
    let within = |plan: &FlightPlan| {
        (0..plan.waypoints().len() - 1).all(|leg| {
            let limited = plan.clone().with_climb(Some(ClimbLimits::MULTICOPTER));
            limited.flown_speed(leg, 0.0) == plan.flown_speed(leg, 0.0)
        })
    };
    let (i, flight, traced) = (1..=30)
        .map(|i| {
            let flight = synthetic_flight(i).unwrap();
            let traced = FlightPlan::traced(&flight, TRACE_TOLERANCE);
            (i, flight, traced)
        })
        .find(|(_, _, traced)| within(traced))
        .expect("a synthetic flight within the climb limits");
    let settings = json!({"trajectory": flight.to_csv(), "model": "3d-ctra,mission",
                          "prediction": "bounded", "sf": 9, "bw": 125.0,
                          "plan": traced.to_csv()});
    let from_file = run(settings.clone());
    let own = run(
        json!({"synthetic": i, "model": "3d-ctra,mission", "prediction": "bounded",
                         "sf": 9, "bw": 125.0}),
    );
    let (a, b) = (p75(&from_file, "mission"), p75(&own, "mission"));
    assert!(
        (a - b).abs() <= 1e-6 * b.max(1.0),
        "file {a} against own {b}"
    );
    // A plan 1 km away is never the drone's: every packet hands over to bounded 3D-CTRA.
    let away: Vec<[f64; 3]> = traced
        .waypoints()
        .iter()
        .map(|w| [w[0] + 1000.0, w[1], w[2]])
        .collect();
    let speeds = vec![None; away.len() - 1];
    let mut far = settings;
    far["plan"] = json!(FlightPlan::new(away, speeds).unwrap().to_csv());
    let r = run(far);
    assert_eq!(r[1].error3d, r[0].error3d);
    assert_eq!(r[1].coverage95, r[0].coverage95);
}

/// The latitude and longitude (degrees) of the point `p` m east and north of `home`: the inverse
/// of the projection plans and GPS logs are read through (reference §11).
fn lat_lon(home: [f64; 3], p: &[f64; 3]) -> [f64; 2] {
    let k = std::f64::consts::PI / 180.0 * 6_371_000.0;
    [
        home[0] + p[1] / k,
        home[1] + p[0] / (k * home[0].to_radians().cos()),
    ]
}

/// `plan` as QGroundControl saves a mission (`fileType: "Plan"`): home at `home` (latitude,
/// longitude, degrees; altitude m), then for each leg a speed change and a waypoint at relative
/// altitude with its hold, its position turned into latitude and longitude about home.
fn qgroundcontrol_plan(plan: &FlightPlan, home: [f64; 3]) -> String {
    let mut items = Vec::new();
    let speeds = leg_speeds(plan);
    for (i, w) in plan.waypoints().iter().enumerate() {
        if let Some(v) = i.checked_sub(1).and_then(|leg| speeds[leg]) {
            items.push(
                json!({"type": "SimpleItem", "command": 178, "frame": 2, "autoContinue": true,
                              "params": [1, v, -1, 0, 0, 0, 0]}),
            );
        }
        let [lat, lon] = lat_lon(home, w);
        items.push(
            json!({"type": "SimpleItem", "command": 16, "frame": 3, "autoContinue": true,
                          "AMSLAltAboveTerrain": null, "Altitude": w[2], "AltitudeMode": 1,
                          "params": [plan.holds()[i], 0, 0, null, lat, lon, w[2]]}),
        );
    }
    json!({"fileType": "Plan", "version": 1, "groundStation": "QGroundControl",
           "geoFence": {"circles": [], "polygons": [], "version": 2},
           "rallyPoints": {"points": [], "version": 2},
           "mission": {"version": 2, "firmwareType": 3, "vehicleType": 2, "cruiseSpeed": 15,
                       "hoverSpeed": 5, "plannedHomePosition": home, "items": items}})
    .to_string()
}

/// `plan` as Mission Planner saves a mission (`QGC WPL 110`, tab-separated): home as item 0,
/// then for each leg a speed change and a waypoint at relative altitude with its hold.
fn waypoint_list(plan: &FlightPlan, home: [f64; 3]) -> String {
    let mut lines = vec![
        "QGC WPL 110".to_string(),
        format!(
            "0\t1\t0\t16\t0\t0\t0\t0\t{}\t{}\t{}\t1",
            home[0], home[1], home[2]
        ),
    ];
    let speeds = leg_speeds(plan);
    for (i, w) in plan.waypoints().iter().enumerate().skip(1) {
        if let Some(v) = speeds[i - 1] {
            let n = lines.len() - 1;
            lines.push(format!("{n}\t0\t3\t178\t1\t{v}\t-1\t0\t0\t0\t0\t1"));
        }
        let [lat, lon] = lat_lon(home, w);
        let n = lines.len() - 1;
        lines.push(format!(
            "{n}\t0\t3\t16\t{}\t0\t0\t0\t{lat}\t{lon}\t{}\t1",
            plan.holds()[i],
            w[2]
        ));
    }
    lines.join("\n") + "\n"
}

/// Each leg's planned speed, read at the leg's middle.
fn leg_speeds(plan: &FlightPlan) -> Vec<Option<f64>> {
    let mut along = 0.0;
    plan.waypoints()
        .windows(2)
        .map(|leg| {
            let length = (0..3)
                .map(|k| (leg[1][k] - leg[0][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            along += length;
            plan.speed_at(along - length / 2.0)
        })
        .collect()
}

#[test]
fn a_qgroundcontrol_plan_or_waypoint_list_is_followed_as_the_same_plan_in_csv() {
    let flight = synthetic_flight(5).unwrap();
    let traced = FlightPlan::traced(&flight, TRACE_TOLERANCE);
    // QGroundControl's plan starts at home, on the ground: the CSV plan does too.
    let mut points = vec![[0.0, 0.0, 0.0]];
    points.extend_from_slice(traced.waypoints());
    let mut speeds = vec![None];
    speeds.extend(leg_speeds(&traced));
    let csv_plan = FlightPlan::new(points, speeds).unwrap();
    let settings = |plan: String| {
        json!({"trajectory": flight.to_csv(), "model": "mission", "prediction": "bounded",
               "sf": 10, "bw": 125.0, "plan": plan})
    };
    let from_csv = run(settings(csv_plan.to_csv()));
    let from_qgc = run(settings(qgroundcontrol_plan(
        &csv_plan,
        [-35.3632, 149.1652, 584.0],
    )));
    let (a, b) = (p75(&from_qgc, "mission"), p75(&from_csv, "mission"));
    assert!(
        (a - b).abs() <= 1e-6 * b.max(1.0),
        "QGroundControl {a} against CSV {b}"
    );
    assert_eq!(
        from_qgc[0].delivery.packets_received,
        from_csv[0].delivery.packets_received
    );
    // And as Mission Planner's waypoint list, its home as item 0.
    let from_list = run(settings(waypoint_list(&csv_plan, [47.3977, 8.5456, 488.0])));
    let c = p75(&from_list, "mission");
    assert!(
        (c - b).abs() <= 1e-6 * b.max(1.0),
        "waypoint list {c} against CSV {b}"
    );
}

#[test]
fn a_gps_log_with_a_plan_about_its_first_fix_is_tracked_as_the_same_flight_in_metres() {
    let flight = synthetic_flight(5).unwrap();
    let home = [-35.3632, 149.1652, 584.0];
    let start = flight.pos[0];
    let (mut gps, mut local) = (
        String::from("t,lat,lon,alt,vx,vy,vz,ax,ay,az\n"),
        String::from("t,x,y,z,vx,vy,vz,ax,ay,az\n"),
    );
    for i in 0..flight.t.len() {
        let p = [0, 1, 2].map(|c| flight.pos[i][c] - start[c]);
        let (v, a) = (flight.vel[i], flight.acc[i]);
        let rates = format!("{},{},{},{},{},{}", v[0], v[1], v[2], a[0], a[1], a[2]);
        let [lat, lon] = lat_lon(home, &p);
        gps += &format!("{},{lat},{lon},{},{rates}\n", flight.t[i], home[2] + p[2]);
        local += &format!("{},{},{},{},{rates}\n", flight.t[i], p[0], p[1], p[2]);
    }
    // Its plan, in the same frame: as CSV for the flight in metres, as a waypoint list about the
    // same home for the GPS log.
    let traced = FlightPlan::traced(&flight, TRACE_TOLERANCE);
    let shifted: Vec<[f64; 3]> = traced
        .waypoints()
        .iter()
        .map(|w| [0, 1, 2].map(|c| w[c] - start[c]))
        .collect();
    let mut points = vec![[0.0, 0.0, 0.0]];
    points.extend(shifted);
    let mut speeds = vec![None];
    speeds.extend(leg_speeds(&traced));
    let plan = FlightPlan::new(points, speeds).unwrap();
    let settings = |trajectory: String, plan: String| {
        json!({"trajectory": trajectory, "model": "3d-ctra,mission", "prediction": "bounded",
               "sf": 9, "bw": 125.0, "plan": plan})
    };
    let metres = run(settings(local, plan.to_csv()));
    let logged = run(settings(gps, waypoint_list(&plan, home)));
    for model in ["3d-ctra", "mission"] {
        let (a, b) = (p75(&logged, model), p75(&metres, model));
        assert!(
            (a - b).abs() <= 1e-6 * b.max(1.0),
            "{model}: GPS log {a} against metres {b}"
        );
    }
}

#[test]
fn a_station_that_reads_the_plans_holds_waits_with_the_drone() {
    // An inspection: take off, hover at four of six points for 15–60 s, come back and land.
    let points = vec![
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 30.0],
        [250.0, 40.0, 30.0],
        [310.0, 260.0, 45.0],
        [60.0, 330.0, 45.0],
        [-200.0, 180.0, 35.0],
        [-240.0, -150.0, 35.0],
        [30.0, -220.0, 30.0],
        [0.0, 0.0, 30.0],
        [0.0, 0.0, 0.0],
    ];
    let mut speeds = vec![Some(3.0)];
    speeds.extend([Some(8.0); 7]);
    speeds.push(Some(2.0));
    let holds = vec![0.0, 0.0, 30.0, 0.0, 60.0, 15.0, 0.0, 45.0, 0.0, 0.0];
    let plan = FlightPlan::with_holds(points, speeds, holds).unwrap();
    let flight = fly_plan(&plan, "inspection").unwrap().to_csv();
    let with = |plan: String| {
        json!({"trajectory": flight, "model": "mission", "prediction": "bounded",
               "sf": 9, "bw": 125.0, "plan": plan})
    };
    let holding = p75(&run(with(plan.to_csv())), "mission");
    let flying_on = p75(&run(with(plan.without_holds().to_csv())), "mission");
    // Without the holds the station flies on while the drone hovers, 30–60 s at a time.
    assert!(
        holding < 0.2 * flying_on,
        "with holds {holding}, without {flying_on}"
    );
    // The holds are read from a QGroundControl plan and a waypoint list as from the CSV.
    let home = [-35.3632, 149.1652, 584.0];
    for (kind, text) in [
        ("QGroundControl", qgroundcontrol_plan(&plan, home)),
        ("waypoint list", waypoint_list(&plan, home)),
    ] {
        let read = p75(&run(with(text)), "mission");
        assert!(
            (read - holding).abs() <= 1e-6 * holding.max(1.0),
            "{kind} {read} against CSV {holding}"
        );
    }
}

#[test]
fn a_plan_alone_is_flown_as_fly_plan_flies_it() {
    let plan = FlightPlan::with_holds(
        vec![
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 30.0],
            [300.0, 0.0, 30.0],
            [300.0, 200.0, 40.0],
        ],
        vec![Some(3.0), Some(8.0), None],
        vec![0.0, 0.0, 20.0, 10.0],
    )
    .unwrap();
    let settings =
        json!({"model": "3d-ctra,mission", "prediction": "bounded", "sf": 9, "bw": 125.0});
    let with = |extra: Value| {
        let mut s = settings.clone();
        s.as_object_mut()
            .unwrap()
            .extend(extra.as_object().unwrap().clone());
        let s = Scenario::default().with(&s).unwrap();
        simulate(&mut Simulator::new(), &s).unwrap()
    };
    let alone = with(json!({"plan": plan.to_csv()}));
    let flown = fly_plan(&plan, "flight").unwrap();
    let logged = with(json!({"plan": plan.to_csv(), "trajectory": flown.to_csv()}));
    assert_eq!(alone.config.trajectory, "flown plan");
    assert_eq!(alone.results.len(), 2);
    assert!((alone.config.flight_time - flown.duration()).abs() < 1e-9);
    for (a, b) in alone.results.iter().zip(&logged.results) {
        assert_eq!(a.error3d, b.error3d, "{}", a.model.name());
    }
    // A swarm flies it too, every drone.
    let s = Scenario::default()
        .with(&json!({"plan": plan.to_csv(), "drones": 3}))
        .unwrap();
    assert_eq!(swarm(&s).unwrap().drones.len(), 3);
}

/// A QGroundControl mission for `vehicle` (its `vehicleType`: 1 a plane, 2 a multicopter) at
/// `speed` m/s: 80 m up, 600 m east, 300 m north, 600 m west.
fn qgc_lines(vehicle: u8, speed: f64) -> String {
    let home = [-35.3632, 149.1652, 584.0];
    let items: Vec<Value> = [
        [0.0, 0.0, 80.0],
        [600.0, 0.0, 80.0],
        [600.0, 300.0, 80.0],
        [0.0, 300.0, 80.0],
    ]
    .iter()
    .map(|w| {
        let [lat, lon] = lat_lon(home, w);
        json!({"type": "SimpleItem", "command": 16, "frame": 3, "params": [0, 0, 0, null, lat, lon, w[2]]})
    })
    .collect();
    json!({"fileType": "Plan", "version": 1, "groundStation": "QGroundControl",
           "mission": {"version": 2, "firmwareType": 3, "vehicleType": vehicle, "cruiseSpeed": speed,
                       "hoverSpeed": speed, "plannedHomePosition": home, "items": items}})
    .to_string()
}

/// The report names the vehicle a plan is flown as, read from a `.plan`'s `vehicleType`, so that
/// a page can say whether the drone turned as a plane or as a multicopter.
#[test]
fn the_report_says_which_vehicle_a_plan_is_flown_as() {
    let cornering = |settings: Value| {
        let s = Scenario::default().with(&settings).unwrap();
        simulate(&mut Simulator::new(), &s)
            .unwrap()
            .config
            .plan_cornering
    };
    assert_eq!(
        cornering(json!({"plan": qgc_lines(1, 18.0)})),
        Some(Cornering::FixedWing)
    );
    assert_eq!(
        cornering(json!({"plan": qgc_lines(2, 5.0)})),
        Some(Cornering::Multicopter)
    );
    assert_eq!(
        cornering(json!({"plan": "x,y,z\n0,0,30\n300,0,30\n"})),
        Some(Cornering::Multicopter)
    );
    assert_eq!(cornering(json!({"synthetic": 1})), None);
    // A swarm flying the plan says it as well; one of chained synthetic flights has none.
    let swarmed = |settings: Value| {
        let s = Scenario::default().with(&settings).unwrap();
        swarm(&s).unwrap().config.plan_cornering
    };
    let small = json!({"drones": 2, "plan": qgc_lines(1, 18.0)});
    assert_eq!(swarmed(small), Some(Cornering::FixedWing));
    assert_eq!(swarmed(json!({"drones": 2, "duration": 60})), None);
}

/// A plane faster than a quadcopter's top speed is tracked at its own: held to 20 m/s, the
/// mission station fell 4 m/s behind a 24 m/s plane from each packet (p75 8.1 m at SF9).
#[test]
fn a_plane_faster_than_a_quadcopter_is_followed_at_its_speed() {
    let r = run(
        json!({"plan": qgc_lines(1, 24.0), "model": "mission", "prediction": "bounded",
                       "sf": 9, "bw": 125.0, "seeds": 2}),
    );
    assert!(p75(&r, "mission") < 2.0, "{}", p75(&r, "mission"));
}

/// A plane's survey at 24 m/s ([`qgc_lines`]): its plan, and the CSV log (positions only) of
/// the plane flying it.
fn planes_survey() -> (FlightPlan, String) {
    let plan = loratrack::parse_plan(&qgc_lines(1, 24.0)).unwrap();
    let flown = fly_plan(&plan, "survey").unwrap();
    let mut log = String::from("t,x,y,z\n");
    for (t, p) in flown.t.iter().zip(&flown.pos) {
        log += &format!("{t},{},{},{}\n", p[0], p[1], p[2]);
    }
    (plan, log)
}

/// A plane's own log and its plan as a CSV without the line that says it is a plane's: with
/// `vehicle` `fixed-wing` the mission station follows the plan as the plane flew it (its wide
/// turns, at its 24 m/s), where read as a multicopter's it fell behind at every corner; the
/// plan as `to_csv` writes it, with that line, is a plane's as the file says.
#[test]
fn a_planes_csv_log_and_csv_plan_are_followed_as_a_planes_when_the_vehicle_is_set() {
    let (plan, log) = planes_survey();
    let marked = plan.to_csv();
    let unmarked = marked.replace("# vehicle: fixed-wing\n", "");
    assert_ne!(marked, unmarked);
    let run_as = |csv: &str, vehicle: &str| {
        let s = Scenario::default()
            .with(&json!({"trajectory": log, "plan": csv, "vehicle": vehicle,
                "model": "mission", "prediction": "bounded", "sf": 9, "bw": 125.0, "seeds": 2}))
            .unwrap();
        let r = simulate(&mut Simulator::new(), &s).unwrap();
        (r.config.plan_cornering, p75(&r.results, "mission"))
    };
    let (copter, plane) = (run_as(&unmarked, "auto"), run_as(&unmarked, "fixed-wing"));
    assert_eq!(copter.0, Some(Cornering::Multicopter));
    assert_eq!(plane.0, Some(Cornering::FixedWing));
    assert!(
        plane.1 < 2.0 && plane.1 < copter.1 / 4.0,
        "{plane:?} against {copter:?}"
    );
    assert_eq!(run_as(&marked, "auto"), plane);
    assert_eq!(run_as(&marked, "multicopter"), copter);
    // The bundled flights are multicopters: a plane is refused there, not quietly bounded as one.
    for flight in [json!({"synthetic": 1}), json!({"sample": "canberra"})] {
        let mut settings = flight.clone();
        settings["vehicle"] = json!("fixed-wing");
        let e = Scenario::default()
            .with(&settings)
            .unwrap()
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("multicopters"), "{e}");
        // Named outright it is read by a bounded station (its top speed), and refused where
        // nothing reads it.
        settings["vehicle"] = json!("multicopter");
        let e = Scenario::default()
            .with(&settings)
            .unwrap()
            .validate()
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("`vehicle` is read only where a plan is flown or followed"),
            "{e}"
        );
        settings["prediction"] = json!("bounded");
        assert!(Scenario::default()
            .with(&settings)
            .unwrap()
            .validate()
            .is_ok());
    }
}

/// Beside a logged flight a plan is read by the mission station, and otherwise only by a bounded
/// station over a CSV log with the vehicle left to it (a plane's top speed); elsewhere it changed
/// nothing though the header named it, so it is refused.
#[test]
fn a_plan_beside_a_logged_flight_is_refused_where_nothing_reads_it() {
    let (_, log) = planes_survey();
    let try_with = |extra: Value| {
        let mut settings = json!({"trajectory": log, "model": "3d-ctra", "sf": 9, "bw": 125.0});
        for (k, v) in extra.as_object().unwrap() {
            settings[k] = v.clone();
        }
        let s = Scenario::default().with(&settings).unwrap();
        simulate(&mut Simulator::new(), &s).map(|r| p75(&r.results, "3d-ctra"))
    };
    let plane = qgc_lines(1, 24.0);
    for unread in [
        json!({"plan": plane}),
        json!({"plan": plane, "prediction": "bounded", "vehicle": "multicopter"}),
        json!({"plan": plane, "prediction": "bounded", "vehicle": "fixed-wing"}),
    ] {
        let e = try_with(unread.clone()).unwrap_err().to_string();
        assert!(
            e.starts_with("`plan` is read over a logged flight by the mission station alone")
                && e.ends_with("add mission to `model`"),
            "{unread}: {e}"
        );
    }
    // The Canberra flight is a multicopter's: nothing but the mission station reads a plan there.
    let canberra = |model: &str| {
        let settings = json!({"sample": "canberra", "plan": plane, "model": model,
                              "prediction": "bounded"});
        let s = Scenario::default().with(&settings).unwrap();
        simulate(&mut Simulator::new(), &s).map(|_| ())
    };
    let e = canberra("3d-ctra").unwrap_err().to_string();
    assert!(e.ends_with("add mission to `model`"), "{e}");
    assert!(canberra("mission").is_ok());
    // Read for its vehicle: the plane's plan lets the bounded station follow it at 24 m/s.
    let bounded = json!({"prediction": "bounded"});
    let mut with_plan = bounded.clone();
    with_plan["plan"] = json!(plane);
    let (without, with) = (try_with(bounded).unwrap(), try_with(with_plan).unwrap());
    assert!(with < without, "{with} against {without}");
    // Followed by the mission station, bounded or not.
    assert!(try_with(json!({"plan": plane, "model": "3d-ctra,mission"})).is_ok());
}

/// Mission and 3D-CTRA p75 (m) on `plan` flown alone, bounded, SF12/125 kHz, 8 seeds.
fn flown_alone_at_sf12(plan: &str) -> (f64, f64) {
    let r = run(
        json!({"plan": plan, "model": "3d-ctra,mission", "prediction": "bounded",
        "sf": 12, "bw": 125.0, "seeds": 8}),
    );
    (p75(&r, "mission"), p75(&r, "3d-ctra"))
}

#[test]
fn a_plan_flown_out_and_back_over_itself_is_followed_both_ways() {
    // 300 m east and back, twice: every point of the line is on four legs.
    let (mission, ctra) =
        flown_alone_at_sf12("x,y,z,speed\n0,0,30,\n300,0,30,8\n0,0,30,8\n300,0,30,8\n0,0,30,8\n");
    // Followed on the way out while the drone came back, it was 91.7 m.
    assert!(mission < 2.0, "{mission}");
    assert!(ctra > 100.0 * mission, "{ctra} against {mission}");
}

/// Three laps of a 150 m octagon at 10 m/s, a lap 92 s, as a CSV plan.
fn octagon_laps() -> String {
    let mut csv = String::from("x,y,z,speed\n0,0,0,\n0,0,30,10\n");
    for k in 0..=24 {
        let a = core::f64::consts::FRAC_PI_4 * f64::from(k);
        csv += &format!("{},{},30,10\n", 150.0 * a.cos(), 150.0 * a.sin());
    }
    csv + "0,0,30,10\n"
}

#[test]
fn a_plan_flown_in_laps_is_followed_on_the_right_lap() {
    // A packet every 148 s.
    let r = run(
        json!({"plan": octagon_laps(), "model": "mission", "prediction": "bounded",
        "sf": 12, "bw": 125.0, "seeds": 8}),
    );
    let e = &r[0].error3d;
    // A first packet put on the first lap left the station a lap behind: p95 147 m.
    assert!(e.p95 < 20.0, "{e:?}");
}

#[test]
fn a_log_that_begins_on_the_ground_is_timed_from_when_the_drone_set_out() {
    // The octagon's laps flown, logged from a minute before take-off, tracked with the plan.
    let plan = loratrack::parse_plan(&octagon_laps()).unwrap();
    let flown = fly_plan(&plan, "laps").unwrap();
    let mut log = String::from("t,x,y,z\n");
    for k in 0..600 {
        log += &format!("{},0,0,0\n", 0.1 * f64::from(k));
    }
    for (t, p) in flown.t.iter().zip(&flown.pos) {
        log += &format!("{},{},{},{}\n", 60.0 + t, p[0], p[1], p[2]);
    }
    for sf in [11, 12] {
        let r = run(
            json!({"trajectory": log, "plan": octagon_laps(), "model": "mission",
            "prediction": "bounded", "sf": sf, "bw": 125.0, "seeds": 8}),
        );
        let e = &r[0].error3d;
        // Timed from the log's first time the station put first packets a lap ahead (p95 145 m
        // at SF12), and flew off along the plan from a packet on the ground (33 m at SF11).
        assert!(e.p95 < 15.0, "SF{sf}: {e:?}");
    }
}

#[test]
fn a_loiters_turns_are_flown_round_their_circle_and_followed() {
    // Take-off, 8 m/s, 200 m east, three turns of 30 m about home's north, back home.
    let list = "QGC WPL 110\n\
        0\t1\t0\t16\t0\t0\t0\t0\t-35.0\t149.0\t500.0\t1\n\
        1\t0\t3\t22\t0\t0\t0\t0\t0\t0\t30\t1\n\
        2\t0\t3\t178\t1\t8\t-1\t0\t0\t0\t0\t1\n\
        3\t0\t3\t16\t0\t0\t0\t0\t-35.0\t149.0022\t30\t1\n\
        4\t0\t3\t18\t3\t0\t30\t0\t-34.999\t149.0011\t30\t1\n\
        5\t0\t3\t20\t0\t0\t0\t0\t0\t0\t0\t1\n";
    let plan = loratrack::parse_plan(list).unwrap();
    let flown = fly_plan(&plan, "orbit").unwrap();
    // Home, take-off, the waypoint, the circle's edge, then 36 points round it; home at 30 m and
    // the landing (10 m, the ground).
    let w = plan.waypoints();
    assert_eq!(w.len(), 4 + 36 + 3);
    let centre: [f64; 2] =
        core::array::from_fn(|k| w[4..40].iter().map(|p| p[k]).sum::<f64>() / 36.0);
    let round = |p: &[f64; 3]| (p[0] - centre[0]).hypot(p[1] - centre[1]);
    // A third of the flight on the circle (within its 2 m corners), none of it at its centre.
    let on = flown
        .pos
        .iter()
        .filter(|p| (round(p) - 30.0).abs() < 2.0)
        .count();
    assert!(3 * on > flown.pos.len(), "{on} of {}", flown.pos.len());
    assert!(flown.pos.iter().all(|p| round(p) > 25.0 || p[1] < 60.0));
    let (mission, ctra) = flown_alone_at_sf12(list);
    assert!(
        mission < 5.0 && ctra > 10.0 * mission,
        "{mission} against {ctra}"
    );
}

#[test]
fn a_return_to_launch_is_flown_home_and_down_to_the_ground_slowly_at_the_end() {
    // Take-off to 8 m, 150 m north, return to launch.
    let list = "QGC WPL 110\n\
        0\t1\t0\t16\t0\t0\t0\t0\t-35.0\t149.0\t500.0\t1\n\
        1\t0\t3\t22\t0\t0\t0\t0\t0\t0\t8\t1\n\
        2\t0\t3\t16\t0\t0\t0\t0\t-34.99865\t149.0\t8\t1\n\
        3\t0\t3\t20\t0\t0\t0\t0\t0\t0\t0\t1\n";
    let plan = loratrack::parse_plan(list).unwrap();
    let flown = fly_plan(&plan, "home").unwrap();
    let (pos, t) = (&flown.pos, &flown.t);
    let top = pos.iter().map(|p| p[2]).fold(0.0, f64::max);
    // Up to RTL_ALT before it turns home, and on the ground, home, at the end.
    assert!((top - loratrack::RTL_ALT).abs() < 0.1, "{top}");
    let end = pos[pos.len() - 1];
    assert!(end[0].hypot(end[1]) < 0.1 && end[2] < 0.1, "{end:?}");
    // Below LAND_ALT_LOW it descends no faster than LAND_SPEED.
    let fastest_low = (1..pos.len())
        .filter(|&k| pos[k][2] < loratrack::LAND_ALT_LOW - 0.1)
        .map(|k| (pos[k - 1][2] - pos[k][2]) / (t[k] - t[k - 1]))
        .fold(0.0, f64::max);
    assert!(fastest_low <= loratrack::LAND_SPEED + 1e-6, "{fastest_low}");
}

#[test]
fn a_plan_that_would_fly_for_more_than_a_long_flight_is_refused_before_it_is_flown() {
    // An unlimited loiter holds for a day.
    let s = Scenario::default()
        .with(&json!({"plan": "x,y,z,speed,hold\n0,0,30\n30,0,30,3,86400\n"}))
        .unwrap();
    let e = simulate(&mut Simulator::new(), &s).unwrap_err().to_string();
    assert!(
        e.contains("takes 86412 s to fly") && e.contains("at most 40000 s"),
        "{e}"
    );
}

#[test]
fn the_cli_help_gives_the_flown_plans_own_constants() {
    let help = crate::cli_help("simulate");
    for said in [
        format!("speeding up and braking at {PLAN_ACCEL} m/s²"),
        format!("on an arc within {CORNER_RADIUS} m of it (at most {CORNER_ACCEL} m/s² sideways)"),
        format!("({PLAN_CRUISE} m/s where none is given;"),
        format!(
            "climbs over {} m/s or descends over {} m/s",
            ClimbLimits::MULTICOPTER.up,
            ClimbLimits::MULTICOPTER.down
        ),
        format!("at most {MAX_FLOWN_S} s"),
        format!(
            "multicopter (up to {} m/s) or fixed-wing (a plane: wide turns at its speed, no holds, up to {} m/s)",
            loratrack::Bounds::default().v_max,
            loratrack::PLANE_V_MAX
        ),
        format!("a CSV plan's line '{} fixed-wing'", loratrack::VEHICLE_MARK),
    ] {
        assert!(help.contains(&said), "{said}: {help}");
    }
}

#[test]
fn packet_pace_ignores_the_plans_speeds() {
    let r = |pace: &str| {
        run(json!({"synthetic": 2, "model": "mission", "sf": 10, "bw": 125.0, "planPace": pace}))
    };
    assert_ne!(r("plan")[0].error3d, r("packet")[0].error3d);
}

#[test]
fn error_triggered_sending_along_the_plan_beats_periodic_sending_at_equal_airtime() {
    let periodic = run(json!({"synthetic": "all", "model": "mission", "overhead": 0}));
    let error = run(
        json!({"synthetic": "all", "model": "mission", "overhead": 0,
                           "sender": "error", "threshold": 2}),
    );
    // On its plan the drone's mirror drifts little: it sends far less than periodically...
    let share = error[0].airtime / periodic[0].airtime;
    assert!(share < 0.8, "{share}");
    // ...and tracks better than a periodic drone given the same airtime.
    let equal = run(
        json!({"synthetic": "all", "model": "mission", "overhead": 0,
                           "dutyCycle": 0.01 * share}),
    );
    let (e, q) = (&error[0].error3d, &equal[0].error3d);
    assert!(
        e.p75 < 0.9 * q.p75 && e.p95 < 0.6 * q.p95,
        "{e:?} against {q:?}"
    );
}

#[test]
fn what_the_mission_station_needs_is_checked_before_any_run() {
    let refuse = |settings: Value| -> String {
        let s = Scenario::default().with(&settings).unwrap();
        let e = simulate(&mut Simulator::new(), &s).unwrap_err().to_string();
        // Printed whole by the CLI and the bindings: no apostrophe opens a quote to be cut.
        assert_eq!(clean_message(&e), e);
        e
    };
    let e = refuse(json!({"sample": "canberra", "model": "mission"}));
    assert!(e.contains("needs the plan the drone flies"), "{e}");
    let e = refuse(json!({"synthetic": 1, "plan": "0,0,10\n10,0,10\n"}));
    assert!(e.contains("carry their own plans"), "{e}");
    let e = refuse(json!({"sample": "canberra", "model": "mission", "plan": "0,0,10\n1,x,2\n"}));
    assert!(e.contains("plan line 2"), "{e}");
    let e = refuse(json!({"synthetic": 1, "model": "mission", "planTolerance": 0}));
    assert!(e.contains("planTolerance"), "{e}");
    let s = Scenario::default()
        .with(&json!({"drones": 3, "duration": 60, "model": "mission"}))
        .unwrap();
    let e = swarm(&s).unwrap_err().to_string();
    assert!(e.contains("no mission station"), "{e}");
}

#[test]
fn the_mission_station_sends_the_3d_ctra_payload() {
    assert_eq!(StationModel::Mission.payload_bytes(), 12);
    let r = run(json!({"synthetic": 1, "model": "3d-ctra,mission"}));
    assert_eq!(r[0].delivery, r[1].delivery);
}

#[test]
fn the_series_carries_the_plan_only_when_a_mission_station_runs() {
    let series = |model: &str| {
        let s = Scenario::default()
            .with(&json!({"synthetic": 3, "model": model, "series": true}))
            .unwrap();
        simulate(&mut Simulator::new(), &s).unwrap().series.unwrap()
    };
    let traced = FlightPlan::traced(&synthetic_flight(3).unwrap(), TRACE_TOLERANCE);
    assert_eq!(
        series("3d-ctra,mission").plan.as_deref(),
        Some(traced.waypoints())
    );
    assert_eq!(series("3d-ctra").plan, None);
}
