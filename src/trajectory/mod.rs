//! Ground-truth flights: the synthetic Mid-Air-like set, CSV import, the bundled real flight
//! (reference §11), mission plans and flights flown from them (§16).

mod chain;
mod climb;
mod cornering;
mod csv;
mod error;
mod flown_plan;
mod geodetic;
mod kinematics;
mod mission_items;
mod plan;
mod plan_file;
mod qgc_plan;
mod sample;
mod synthetic;
mod track;
mod waypoint_list;

pub use chain::chain_flights;
pub use climb::ClimbLimits;
pub use cornering::{
    corners, Corner, CornerSpeeds, Cornering, VehicleChoice, CORNER_ACCEL, CORNER_RADIUS,
    PLANE_WP_RADIUS,
};
pub use csv::{
    parse_csv, parse_csv_with_progress, MAX_CSV_BYTES, MAX_ROWS, MIN_ROWS, MIN_TIME_STEP,
};
pub use error::TrajectoryError;
pub use flown_plan::{
    flown_duration, fly_plan, inspection_plan, rounded, INSPECTION_HOLDS, INSPECTION_POINTS,
    MAX_FLOWN_S, PLAN_ACCEL, PLAN_CRUISE, PLAN_RATE_HZ,
};
pub use kinematics::{heading_angles, kinematic_state, kinematic_states, HOVER_SPEED};
pub use mission_items::{
    CIRCLE_RATE, LAND_ALT_LOW, LAND_SPEED, LOITER_RADIUS, RTL_ALT, RTL_CONE_SLOPE, RTL_LOITER,
};
pub use plan::{
    FlightPlan, OnPlan, MAX_HOLD, MAX_PLAN_COORDINATE, MAX_PLAN_SPEED, MAX_WAYPOINTS,
    TRACE_TOLERANCE,
};
pub use plan_file::{parse_plan, parse_plan_as, PlanError, TRACED_MARK, VEHICLE_MARK};
pub use sample::{canberra_flight, CANBERRA_CREDIT};
pub use synthetic::{
    synthetic_flight, synthetic_set, SYNTHETIC_FLIGHTS, SYNTHETIC_SEED, SYNTHETIC_TOTAL_SECONDS,
};
pub use track::Trajectory;
