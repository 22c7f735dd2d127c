//! How fast an autopilot lets a vehicle climb and descend on a mission leg (reference §16): a
//! plan's speed is held down on a steep leg, for the flown plan and the mission station alike.

use super::Cornering;

/// The fastest climb and descent an autopilot flies on a mission leg, m/s.
///
/// An autopilot limits the vertical speed apart from the speed along the path: on a leg that
/// climbs or descends steeply it slows down along the leg until the vertical part of its speed
/// is within the limit (ArduPilot's `kinematic_limit` in `AP_Math/control.cpp`, used for every
/// waypoint leg). A plan that asks for 8 m/s up a 45° slope is flown at 2.5 m/s up, 3.5 m/s
/// along the leg. (ArduPilot reads a planned speed as horizontal; a plan's speed here is along the
/// leg, which on the gentle legs of most missions is the same to within a few per cent.)
///
/// ```
/// use loratrack::ClimbLimits;
/// let copter = ClimbLimits::MULTICOPTER;
/// // Straight up at a planned 5 m/s: 2.5 m/s.
/// assert_eq!(copter.speed_along(1.0, 5.0), 2.5);
/// // A gentle climb keeps the planned speed.
/// assert_eq!(copter.speed_along(0.1, 5.0), 5.0);
/// // Down a 30° slope (a sine of 0.5) at 8 m/s: 1.5 m/s down, 3 m/s along the leg.
/// assert_eq!(copter.speed_along(-0.5, 8.0), 3.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClimbLimits {
    /// The fastest climb, m/s.
    pub up: f64,
    /// The fastest descent, m/s.
    pub down: f64,
}

impl ClimbLimits {
    /// A multicopter's: ArduPilot Copter's defaults, `WPNAV_SPEED_UP` 2.5 m/s and `WPNAV_SPEED_DN`
    /// 1.5 m/s (PX4's `MPC_Z_V_AUTO_UP` and `MPC_Z_V_AUTO_DN` are 3 and 1.5 m/s).
    pub const MULTICOPTER: ClimbLimits = ClimbLimits { up: 2.5, down: 1.5 };
    /// A fixed-wing aircraft's: ArduPlane's `TECS_CLMB_MAX` and `TECS_SINK_MAX`, 5 m/s each (PX4's
    /// `FW_T_CLMB_MAX` and `FW_T_SINK_MAX` alike).
    pub const FIXED_WING: ClimbLimits = ClimbLimits { up: 5.0, down: 5.0 };

    /// The limits of `vehicle`: [`Self::MULTICOPTER`] or [`Self::FIXED_WING`].
    pub fn of(vehicle: Cornering) -> ClimbLimits {
        match vehicle {
            Cornering::Multicopter => Self::MULTICOPTER,
            Cornering::FixedWing => Self::FIXED_WING,
        }
    }

    /// The speed along a leg, m/s, at which `speed` (m/s) stays within these limits on a leg
    /// whose height changes by `rise` metres per metre flown along it (the sine of its slope, −1
    /// to 1).
    pub fn speed_along(&self, rise: f64, speed: f64) -> f64 {
        let limit = if rise > 0.0 { self.up } else { self.down };
        if rise.abs() * speed > limit {
            limit / rise.abs()
        } else {
            speed
        }
    }
}
