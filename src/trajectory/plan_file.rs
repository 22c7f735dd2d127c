//! Reading a mission plan (reference §16): a CSV of `x,y,z[,speed[,hold]]` in the flight's frame, a
//! QGroundControl `.plan` file (JSON; its planned home position is the frame's origin) or a
//! plain-text waypoint list (`QGC WPL`, Mission Planner's `.waypoints`; its home, item 0, is).

use super::plan::FlightPlan;
use super::qgc_plan::parse_qgc;
use super::waypoint_list::{parse_waypoint_list, WPL_HEADER};
use super::Cornering;
use super::MAX_CSV_BYTES;
use core::fmt;

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
    /// A CSV line that is not `x,y,z[,speed[,hold]]`.
    Line {
        /// Line number.
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// A QGroundControl `.plan` file loratrack cannot read (what, and where).
    Qgc(String),
    /// Values that do not make a plan.
    Invalid(String),
    /// A plan that takes longer to fly than a flight may last (`fly_plan`).
    TooLongToFly {
        /// How long it takes, s.
        seconds: f64,
    },
}

impl fmt::Display for PlanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlanError::Empty => write!(f, "the plan has no waypoints"),
            PlanError::TooLongToFly { seconds } => write!(
                f,
                "the plan takes {seconds:.0} s to fly; a flown plan lasts at most {:.0} s (an unlimited loiter holds for a day)",
                super::MAX_FLOWN_S
            ),
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

/// Reads a plan: QGroundControl JSON when the text starts with `{`, a waypoint list when it starts
/// with `QGC WPL`, else CSV.
///
/// CSV: one waypoint per line, `x,y,z`, `x,y,z,speed` or `x,y,z,speed,hold` (m east, north,
/// up in the flight's frame; the speed, m/s, is for the leg that ends at that waypoint, and may
/// be left empty; the hold, s, is how long the drone stays at the waypoint); a header line of
/// names, blank lines and lines starting with `#` are skipped, but for the line
/// `# vehicle: fixed-wing` (or `multicopter`, [`VEHICLE_MARK`]), which says which vehicle flies
/// the plan, as a QGroundControl `.plan`'s `vehicleType` does.
///
/// ```
/// let plan = loratrack::parse_plan("x,y,z,speed\n0,0,20\n100,0,20,8\n").unwrap();
/// assert_eq!(plan.speed_at(50.0), Some(8.0));
/// ```
pub fn parse_plan(text: &str) -> Result<FlightPlan, PlanError> {
    parse_plan_as(text, None)
}

/// [`parse_plan`], the plan flown as `vehicle` where it is given (`--vehicle`,
/// [`VehicleChoice::given`](super::VehicleChoice::given)) instead of as the file says: a
/// QGroundControl `.plan`'s `vehicleType`, a CSV's [`VEHICLE_MARK`] line, else a multicopter
/// (a waypoint list names no vehicle). A plane flies through a waypoint's hold and turns wide at
/// its speed; its timed loiters are circles.
///
/// ```
/// use loratrack::{parse_plan_as, Cornering};
/// let text = "x,y,z,speed,hold\n0,0,30\n400,0,30,18,20\n400,400,30,18\n";
/// let plane = parse_plan_as(text, Some(Cornering::FixedWing)).unwrap();
/// assert_eq!(plane.cornering(), Cornering::FixedWing);
/// assert_eq!(plane.holds()[1], 0.0); // a plane flies on through a hold
/// assert_eq!(parse_plan_as(text, None).unwrap().holds()[1], 20.0);
/// ```
pub fn parse_plan_as(text: &str, vehicle: Option<Cornering>) -> Result<FlightPlan, PlanError> {
    if text.len() > MAX_CSV_BYTES {
        return Err(PlanError::TooLarge { bytes: text.len() });
    }
    // A byte-order mark, as Windows editors write one, is not part of the plan.
    let text = text.trim_start_matches('\u{feff}');
    let start = text.trim_start();
    if start.starts_with('{') {
        parse_qgc(text, vehicle)
    } else if start.starts_with(WPL_HEADER) {
        parse_waypoint_list(text, vehicle)
    } else {
        let (plan, named) = parse_csv_plan(text)?;
        Ok(match vehicle.or(named) {
            Some(v) => plan.flown_as(v),
            None => plan,
        })
    }
}

/// A CSV plan, and the vehicle its [`VEHICLE_MARK`] line names, if it has one.
fn parse_csv_plan(text: &str) -> Result<(FlightPlan, Option<Cornering>), PlanError> {
    let mut rows = CsvPlanRows::default();
    for (i, raw) in text.lines().enumerate() {
        rows.read(i + 1, raw.trim())?;
    }
    rows.finish()
}

/// A CSV plan as read so far, line by line.
#[derive(Default)]
struct CsvPlanRows {
    points: Vec<[f64; 3]>,
    /// Each leg's speed, from the second waypoint on (`None`: the plan's cruise speed).
    speeds: Vec<Option<f64>>,
    holds: Vec<f64>,
    /// Whether the [`TRACED_MARK`] line was read.
    traced: bool,
    /// What the [`VEHICLE_MARK`] line named.
    vehicle: Option<Cornering>,
}

impl CsvPlanRows {
    /// Reads line number `line`, `text` trimmed: a comment, a header, a blank or a waypoint.
    fn read(&mut self, line: usize, text: &str) -> Result<(), PlanError> {
        self.traced |= text == TRACED_MARK;
        if let Some(name) = vehicle_line(text) {
            self.name_vehicle(line, name)?;
        }
        if text.is_empty() || text.starts_with('#') {
            return Ok(());
        }
        match waypoint_numbers(line, text, self.points.is_empty())? {
            Some(numbers) => self.waypoint(&numbers),
            None => Ok(()),
        }
    }

    /// The vehicle `name`d on line `line`: one of the two, and the same as any line before.
    fn name_vehicle(&mut self, line: usize, name: &str) -> Result<(), PlanError> {
        let refuse = |what: String| PlanError::Line { line, what };
        let named = vehicle_named(name).ok_or_else(|| {
            refuse(format!(
                "the vehicle '{}' is neither multicopter nor fixed-wing",
                excerpt(name)
            ))
        })?;
        if self.vehicle.is_some_and(|v| v != named) {
            return Err(refuse(format!(
                "a second vehicle line, naming {} where the first named the other",
                named.name()
            )));
        }
        self.vehicle = Some(named);
        Ok(())
    }

    /// Adds the waypoint `x,y,z[,speed[,hold]]`; a speed given on the first waypoint, which
    /// ends no leg, is not read.
    fn waypoint(&mut self, numbers: &[Option<f64>]) -> Result<(), PlanError> {
        if !self.points.is_empty() {
            self.speeds.push(numbers.get(3).copied().flatten());
        }
        let coordinate = |k: usize| numbers[k].unwrap_or(f64::NAN);
        self.points
            .push([coordinate(0), coordinate(1), coordinate(2)]);
        self.holds
            .push(numbers.get(4).copied().flatten().unwrap_or(0.0));
        if self.points.len() > super::MAX_WAYPOINTS {
            return Err(PlanError::TooManyWaypoints {
                max: super::MAX_WAYPOINTS,
            });
        }
        Ok(())
    }

    /// The plan read, and the vehicle named.
    fn finish(self) -> Result<(FlightPlan, Option<Cornering>), PlanError> {
        if self.points.is_empty() {
            return Err(PlanError::Empty);
        }
        let plan = FlightPlan::with_holds(self.points, self.speeds, self.holds)?;
        let plan = if self.traced {
            plan.with_climb(None)
        } else {
            plan
        };
        Ok((plan, self.vehicle))
    }
}

/// The 3–5 numbers of the waypoint on line `line` (`text`; an empty speed or hold is `None`:
/// `x,y,z,,hold`), or `None` for a header, which only a line before the `first` waypoint may
/// be.
fn waypoint_numbers(
    line: usize,
    text: &str,
    first: bool,
) -> Result<Option<Vec<Option<f64>>>, PlanError> {
    let fields: Vec<&str> = text.split(',').map(str::trim).collect();
    let numbers: Result<Vec<Option<f64>>, _> = fields
        .iter()
        .enumerate()
        .map(|(k, f)| match (k, f.is_empty()) {
            (3.., true) => Ok(None),
            _ => f.parse::<f64>().map(Some),
        })
        .collect();
    let Ok(numbers) = numbers else {
        if first && fields.iter().all(|f| f.parse::<f64>().is_err()) {
            return Ok(None);
        }
        return Err(PlanError::Line {
            line,
            what: format!(
                "expected x,y,z[,speed[,hold]] numbers, got '{}'",
                excerpt(text)
            ),
        });
    };
    if !(3..=5).contains(&numbers.len()) {
        return Err(PlanError::Line {
            line,
            what: format!(
                "{} fields; a waypoint is x,y,z[,speed[,hold]]",
                numbers.len()
            ),
        });
    }
    Ok(Some(numbers))
}

/// What a [`VEHICLE_MARK`] line names, however it is spaced or capitalised (`#Vehicle:plane`
/// too, to be refused by name); `None` for any other line.
fn vehicle_line(line: &str) -> Option<&str> {
    let comment = line.strip_prefix('#')?.trim_start();
    let key = VEHICLE_MARK.trim_start_matches('#').trim_start();
    let head = comment.get(..key.len())?;
    head.eq_ignore_ascii_case(key)
        .then(|| comment[key.len()..].trim())
}

/// The vehicle a [`VEHICLE_MARK`] line names, by its `--vehicle` name in any case.
fn vehicle_named(name: &str) -> Option<Cornering> {
    Cornering::ALL
        .into_iter()
        .find(|v| v.name().eq_ignore_ascii_case(name))
}

/// The comment line with which [`FlightPlan::to_csv`] begins a plan traced through a flight
/// ([`FlightPlan::traced`]), so that reading it back gives the same plan: one whose leg speeds
/// are the flight's own, flown within no autopilot's climb limits and turning on no corners.
/// Any other CSV plan is one for an autopilot.
pub const TRACED_MARK: &str = "# traced from a flight: its legs' speeds are the flight's own";

/// How a CSV plan says which vehicle flies it: a comment line `# vehicle: fixed-wing` or
/// `# vehicle: multicopter` (the `--vehicle` names, in any case), anywhere in the file; two
/// that name different vehicles are refused. Without it a CSV plan is a multicopter's, unless
/// `--vehicle` says otherwise (which overrides the line, as it does a `.plan`'s
/// `vehicleType`). [`FlightPlan::to_csv`] writes it for a plane's plan, so that reading it back
/// gives the same plan.
pub const VEHICLE_MARK: &str = "# vehicle:";

/// At most 60 characters of `text`.
pub(super) fn excerpt(text: &str) -> String {
    let head: String = text.chars().take(60).collect();
    if text.chars().count() > 60 {
        format!("{head}…")
    } else {
        head
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
    fn reads_holds_with_or_without_a_speed() {
        let p = parse_plan("x,y,z,speed,hold\n0,0,20,,3\n100,0,20,,30\n100,50,20,5\n").unwrap();
        assert_eq!(p.holds(), &[3.0, 30.0, 0.0]);
        assert_eq!((p.speed_at(10.0), p.speed_at(110.0)), (None, Some(5.0)));
        assert_eq!(parse_plan(&p.to_csv()).unwrap(), p);
        let e = parse_plan("0,0,20\n100,0,20,,-1\n").unwrap_err();
        assert!(e.to_string().contains("waypoint 2: a hold"), "{e}");
        // An empty coordinate is still an error, not a zero.
        assert!(parse_plan("0,,20\n100,0,20\n").is_err());
    }

    /// A CSV without a vehicle line is a multicopter's: flown as a plane, a plan turns as
    /// ArduPlane does, climbs within a plane's limits and flies through its holds; a traced plan
    /// keeps its own leg speeds.
    #[test]
    fn a_csv_plan_is_flown_as_the_vehicle_set() {
        use crate::{ClimbLimits, Cornering};
        let text = "x,y,z,speed,hold\n0,0,20\n100,0,40,8,30\n100,50,40,8\n";
        let copter = parse_plan(text).unwrap();
        assert_eq!(
            parse_plan_as(text, Some(Cornering::Multicopter)).unwrap(),
            copter
        );
        let plane = parse_plan_as(text, Some(Cornering::FixedWing)).unwrap();
        assert_eq!(plane.cornering(), Cornering::FixedWing);
        assert_eq!((copter.holds()[1], plane.holds()[1]), (30.0, 0.0));
        assert_eq!(plane.climbs(), Some(&[ClimbLimits::FIXED_WING; 2][..]));
        assert_eq!(plane.waypoints(), copter.waypoints());
        let traced = format!("{TRACED_MARK}\n{text}");
        let traced = parse_plan_as(&traced, Some(Cornering::FixedWing)).unwrap();
        assert_eq!(
            (traced.climbs(), traced.cornering()),
            (None, Cornering::FixedWing)
        );
    }

    /// A CSV plan may say its vehicle in a comment line, as a `.plan` does in `vehicleType`;
    /// `--vehicle` overrides it, and a plane's plan written as CSV reads back as a plane's.
    #[test]
    fn a_csv_plans_vehicle_line_says_who_flies_it() {
        use crate::Cornering;
        let text = "x,y,z,speed,hold\n0,0,20\n100,0,40,8,30\n100,50,40,8\n";
        let marked = format!("# vehicle: fixed-wing\n{text}");
        let plane = parse_plan(&marked).unwrap();
        assert_eq!(
            plane,
            parse_plan_as(text, Some(Cornering::FixedWing)).unwrap()
        );
        assert_eq!(parse_plan(&plane.to_csv()).unwrap(), plane);
        assert!(plane.to_csv().starts_with("# vehicle: fixed-wing\n"));
        let overridden = parse_plan_as(&marked, Some(Cornering::Multicopter)).unwrap();
        assert_eq!(overridden, parse_plan(text).unwrap());
        // The copter's own line changes nothing, and its plan is written without one.
        let copter = parse_plan(&format!("{text}#Vehicle:  Multicopter \n")).unwrap();
        assert_eq!(copter, parse_plan(text).unwrap());
        assert!(!copter.to_csv().contains(VEHICLE_MARK));
        let e = parse_plan(&format!("{text}#vehicle:plane\n")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "plan line 5: the vehicle 'plane' is neither multicopter nor fixed-wing"
        );
        let e = parse_plan(&format!("{marked}# vehicle: multicopter\n")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "plan line 6: a second vehicle line, naming multicopter where the first named the other"
        );
        assert_eq!(
            parse_plan(&format!("{marked}# Vehicle: Fixed-Wing\n")).unwrap(),
            plane
        );
    }

    #[test]
    fn csv_errors_name_the_line() {
        let e = parse_plan("x,y,z\n0,0,1\n1,abc,1\n").unwrap_err();
        assert_eq!(
            e,
            PlanError::Line {
                line: 3,
                what: "expected x,y,z[,speed[,hold]] numbers, got '1,abc,1'".into()
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
}
