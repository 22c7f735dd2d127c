//! Any text as a mission plan (CSV, a QGroundControl `.plan`, a `QGC WPL` waypoint list): the
//! reader returns a plan or an error naming what is wrong, never panics, and every plan it
//! returns has at least two waypoints, all finite, and a finite length; one short enough to fly
//! quickly (10 min) is flown into a flight ending at its last waypoint. The input's length picks
//! the vehicle it is read as (`--vehicle`): the file's, a multicopter or a plane.
#![no_main]
use libfuzzer_sys::fuzz_target;
use loratrack::Cornering;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let vehicle = [None, Some(Cornering::Multicopter), Some(Cornering::FixedWing)][data.len() % 3];
    if let Ok(plan) = loratrack::parse_plan_as(&text, vehicle) {
        assert!(plan.waypoints().len() >= 2);
        assert!(plan.waypoints().iter().flatten().all(|v| v.is_finite()));
        assert!(plan.length().is_finite() && plan.length() > 0.0);
        if loratrack::flown_duration(&plan) <= 600.0 {
            let flight = loratrack::fly_plan(&plan, "fuzz").unwrap();
            let (end, last) = (flight.pos[flight.pos.len() - 1], plan.waypoints().last().unwrap());
            assert!(end.iter().zip(last).all(|(a, b)| a == b));
        }
    }
});
