//! CSV import of a flight (reference §11).

use super::geodetic::{east_north, on_earth};
use super::{Trajectory, TrajectoryError};

/// Fewest data rows accepted: a filter needs a few samples to start and a derivative needs
/// neighbours.
pub const MIN_ROWS: usize = 10;
/// Most data rows accepted (a day at 10 Hz is 864 000).
pub const MAX_ROWS: usize = 1_000_000;
/// Largest coordinate magnitude accepted, m (beyond, a frame is clearly not local ENU).
const MAX_COORDINATE: f64 = 1e6;
/// Longest flight accepted, s.
const MAX_DURATION: f64 = 86_400.0;
/// Largest speed accepted, m/s.
const MAX_SPEED: f64 = 300.0;
/// Largest acceleration accepted, m/s² (30 g: far beyond a multirotor, and small enough that
/// the filters stay finite).
const MAX_ACCELERATION: f64 = 300.0;
/// Shortest time step accepted, s (1 µs; a derivative over a shorter step is noise).
pub const MIN_TIME_STEP: f64 = 1e-6;
/// Largest CSV text accepted, bytes (64 MiB: a million rows of ten columns fit; the page applies
/// the same limit to uploads).
pub const MAX_CSV_BYTES: usize = 64 << 20;

/// Accepted names per column, matched case-insensitively.
const ALIASES: [(&str, &[&str]); 9] = [
    (
        "t",
        &[
            "t",
            "time",
            "t_s",
            "t_seconds",
            "time_s",
            "timestamp",
            "seconds",
        ],
    ),
    ("x", &["x", "x_m", "east", "e", "east_m"]),
    ("y", &["y", "y_m", "north", "n", "north_m"]),
    (
        "z",
        &["z", "z_m", "up", "u", "up_m", "alt", "altitude", "alt_m"],
    ),
    ("vx", &["vx", "vx_mps", "vx_m_s", "v_x", "ve", "vel_x"]),
    ("vy", &["vy", "vy_mps", "vy_m_s", "v_y", "vn", "vel_y"]),
    ("vz", &["vz", "vz_mps", "vz_m_s", "v_z", "vu", "vel_z"]),
    ("ax", &["ax", "ax_mps2", "ax_m_s2", "a_x", "acc_x"]),
    ("ay", &["ay", "ay_mps2", "ay_m_s2", "a_y", "acc_y"]),
];
const AZ_ALIASES: &[&str] = &["az", "az_mps2", "az_m_s2", "a_z", "acc_z"];
/// Latitude and longitude (degrees) where the file has no x and y: a flight logged by GPS.
const LAT_ALIASES: &[&str] = &["lat", "latitude", "lat_deg"];
const LON_ALIASES: &[&str] = &["lon", "lng", "longitude", "lon_deg", "lng_deg"];

fn find(header: &[String], names: &[&str]) -> Option<usize> {
    header.iter().position(|h| names.contains(&h.as_str()))
}

/// Parses a CSV flight: a header row with at least `t,x,y,z` (seconds, metres, local ENU), or
/// `t,lat,lon,alt` (degrees and metres: a GPS log, read as metres east, north and up of its first
/// row by the equirectangular projection about it, reference §11), and optionally `vx,vy,vz`
/// (m/s, east, north, up) and `ax,ay,az` (m/s²). Missing velocities or accelerations are
/// derived by smoothed differentiation (local linear regression over ±0.15 s for velocity,
/// ±0.3 s for acceleration). Blank lines and lines starting with `#` are skipped.
///
/// ```
/// let csv = "t,x,y,z\n".to_string() + &(0..20).map(|i| format!("{},{},0,10\n", i as f64 * 0.1, i)).collect::<String>();
/// let tr = loratrack::parse_csv(&csv, "demo").unwrap();
/// assert!((tr.vel[10][0] - 10.0).abs() < 1e-9);
/// ```
pub fn parse_csv(text: &str, name: &str) -> Result<Trajectory, TrajectoryError> {
    parse_csv_with_progress(text, name, &mut |_, _| true)
        .map(|read| read.expect("a reading whose progress never says stop reads to the end"))
}

/// [`parse_csv`], calling `progress(lines read, lines)` about a hundred times as it reads, so a
/// page can show how far a large file is. Where `progress` returns `false` the reading ends there
/// with `Ok(None)`: a page whose user chose another file need not wait for this one (10⁶ rows
/// take about 2 s in a browser).
pub fn parse_csv_with_progress(
    text: &str,
    name: &str,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<Option<Trajectory>, TrajectoryError> {
    if text.len() > MAX_CSV_BYTES {
        return Err(TrajectoryError::TooLarge { bytes: text.len() });
    }
    let text = text.trim_start_matches('\u{feff}');
    let mut lines = data_lines(text);
    let (header_at, header_line) = lines.next().ok_or(TrajectoryError::Empty)?;
    let columns = Columns::from_header(header_at, header_line)?;
    let mut read = Read::new(&columns);
    let total = text.bytes().filter(|&b| b == b'\n').count().max(1);
    let every = (total / 100).max(1);
    for (line, l) in lines {
        if line % every == 0 && !progress(line.min(total), total) {
            return Ok(None);
        }
        if read.t.len() >= MAX_ROWS {
            return Err(TrajectoryError::TooManyRows { max: MAX_ROWS });
        }
        let row = columns.row(line, l, &mut read.fields)?;
        read.push(line, row)?;
    }
    read.finish(name).map(Some)
}

/// The lines that hold data or the header, numbered from 1 and trimmed: blank lines and `#`
/// comments are skipped.
fn data_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    // Classic Mac files end lines with a lone CR.
    let split: Box<dyn Iterator<Item = &str>> = if !text.contains('\n') && text.contains('\r') {
        Box::new(text.split('\r'))
    } else {
        Box::new(text.lines())
    };
    split
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
}

/// Where each quantity is in a row: the header's names, lower-cased and unquoted, and the field
/// of t, x, y, z, vx, vy, vz, ax, ay, az (the last six optional).
struct Columns {
    header: Vec<String>,
    index: [Option<usize>; 10],
    /// The file gives longitude and latitude (degrees) where x and y would be, and z is an
    /// altitude: the flight is read in metres from its first row.
    geodetic: bool,
    /// The row gives velocities.
    has_vel: bool,
    /// The row gives velocities and accelerations.
    has_acc: bool,
}

impl Columns {
    /// Reads the header row (line `line`); t, x, y and z must be there.
    fn from_header(line: usize, header_line: &str) -> Result<Self, TrajectoryError> {
        let header: Vec<String> = header_line
            .split(',')
            .map(|h| h.trim().trim_matches('"').to_ascii_lowercase())
            .collect();
        let mut index = [None; 10];
        for (k, (_, names)) in ALIASES.iter().enumerate() {
            index[k] = find(&header, names);
        }
        index[9] = find(&header, AZ_ALIASES);
        let (lat, lon) = (find(&header, LAT_ALIASES), find(&header, LON_ALIASES));
        let geodetic = (index[1].is_none() || index[2].is_none()) && lat.is_some() && lon.is_some();
        if geodetic {
            (index[1], index[2]) = (lon, lat);
        }
        if let Some((canonical, _)) = ALIASES[..4]
            .iter()
            .zip(&index)
            .find_map(|(a, i)| i.is_none().then_some(a))
        {
            return Err(TrajectoryError::MissingColumn {
                line,
                column: canonical,
                header: header_line.to_string(),
            });
        }
        let has_vel = index[4..7].iter().all(Option::is_some);
        let has_acc = has_vel && index[7..10].iter().all(Option::is_some);
        Ok(Columns {
            header,
            index,
            geodetic,
            has_vel,
            has_acc,
        })
    }

    /// The ten quantities of data line `line` (those the file lacks 0), read with `fields` as
    /// scratch space.
    fn row<'a>(
        &self,
        line: usize,
        text: &'a str,
        fields: &mut Vec<&'a str>,
    ) -> Result<[f64; 10], TrajectoryError> {
        fields.clear();
        split_fields(text, fields);
        if fields.len() != self.header.len() {
            return Err(TrajectoryError::FieldCount {
                line,
                got: fields.len(),
                expected: self.header.len(),
            });
        }
        let mut row = [0.0; 10];
        for (k, c) in self.index.iter().enumerate() {
            let Some(c) = *c else { continue };
            let text = unquoted(fields[c]);
            let v: f64 = text.parse().map_err(|_| TrajectoryError::NotANumber {
                line,
                column: self.header[c].clone(),
                text: text.chars().take(40).collect(),
            })?;
            if !v.is_finite() {
                return Err(TrajectoryError::NonFinite {
                    line,
                    column: self.header[c].clone(),
                });
            }
            row[k] = v;
        }
        Ok(row)
    }
}

/// The flight as read so far, column by column (no table of rows: a 10⁶-row file's would be
/// 80 MB), with the line of each row only where a derivative's refusal may need to name it.
struct Read<'a> {
    /// The rows give longitude, latitude and altitude ([`Columns::geodetic`]).
    geodetic: bool,
    /// A geodetic flight's first row: latitude, longitude, degrees, and altitude, m.
    origin: Option<[f64; 3]>,
    has_vel: bool,
    has_acc: bool,
    t: Vec<f64>,
    pos: Vec<[f64; 3]>,
    vel: Vec<[f64; 3]>,
    acc: Vec<[f64; 3]>,
    line_numbers: Vec<usize>,
    /// Scratch space for a row's fields.
    fields: Vec<&'a str>,
}

impl Read<'_> {
    fn new(columns: &Columns) -> Self {
        Read {
            geodetic: columns.geodetic,
            origin: None,
            has_vel: columns.has_vel,
            has_acc: columns.has_acc,
            t: Vec::new(),
            pos: Vec::new(),
            vel: Vec::new(),
            acc: Vec::new(),
            line_numbers: Vec::new(),
            fields: Vec::with_capacity(columns.header.len()),
        }
    }

    /// Adds data line `line`'s quantities, once they pass [`Read::check`]. A row that repeats
    /// the one before it exactly, time and all (a logger that wrote a sample twice), is the same
    /// sample and is passed over; a repeated time with other values stays refused.
    fn push(&mut self, line: usize, mut row: [f64; 10]) -> Result<(), TrajectoryError> {
        if self.geodetic {
            self.localise(line, &mut row)?;
        }
        if self.repeats_last(&row) {
            return Ok(());
        }
        self.check(line, &row)?;
        self.t.push(row[0]);
        self.pos.push([row[1], row[2], row[3]]);
        if self.has_vel {
            self.vel.push([row[4], row[5], row[6]]);
        }
        if self.has_acc {
            self.acc.push([row[7], row[8], row[9]]);
        } else {
            self.line_numbers.push(line);
        }
        Ok(())
    }

    /// A geodetic row's longitude, latitude and altitude as metres east, north and up of the
    /// flight's first row ([`east_north`]).
    fn localise(&mut self, line: usize, row: &mut [f64; 10]) -> Result<(), TrajectoryError> {
        let (lon, lat, alt) = (row[1], row[2], row[3]);
        if !on_earth(lat, lon) {
            return Err(TrajectoryError::Absurd {
                line,
                what: "a latitude beyond ±90° or a longitude beyond ±180°".into(),
            });
        }
        let origin = *self.origin.get_or_insert([lat, lon, alt]);
        let [east, north] = east_north([origin[0], origin[1]], lat, lon);
        (row[1], row[2], row[3]) = (east, north, alt - origin[2]);
        Ok(())
    }

    /// Whether `row` holds exactly the values of the row read last.
    fn repeats_last(&self, row: &[f64; 10]) -> bool {
        let (Some(&t), Some(pos)) = (self.t.last(), self.pos.last()) else {
            return false;
        };
        let same = |a: &[f64], b: &[f64]| a == b;
        t == row[0]
            && same(pos, &row[1..4])
            && (!self.has_vel || self.vel.last().is_some_and(|v| same(v, &row[4..7])))
            && (!self.has_acc || self.acc.last().is_some_and(|a| same(a, &row[7..10])))
    }

    /// Refuses a row whose time does not follow the last one's, or whose position, speed or
    /// acceleration no drone could have (reference §11).
    fn check(&self, line: usize, row: &[f64; 10]) -> Result<(), TrajectoryError> {
        let absurd = |what: String| Err(TrajectoryError::Absurd { line, what });
        if let Some(&prev) = self.t.last() {
            if row[0] <= prev {
                return Err(TrajectoryError::TimeNotIncreasing { line });
            }
            if row[0] - prev < MIN_TIME_STEP {
                return Err(TrajectoryError::TimeStep {
                    line,
                    step: row[0] - prev,
                });
            }
        }
        if row[1..4].iter().any(|v| v.abs() > MAX_COORDINATE) {
            return absurd(format!(
                "a coordinate beyond {MAX_COORDINATE} m from the origin"
            ));
        }
        if self.has_vel && (row[4] * row[4] + row[5] * row[5] + row[6] * row[6]).sqrt() > MAX_SPEED
        {
            return absurd(format!("a speed over {MAX_SPEED} m/s"));
        }
        if self.has_acc
            && (row[7] * row[7] + row[8] * row[8] + row[9] * row[9]).sqrt() > MAX_ACCELERATION
        {
            return absurd(format!("an acceleration over {MAX_ACCELERATION} m/s²"));
        }
        match self.t.first() {
            Some(&first) if row[0] - first > MAX_DURATION => {
                absurd(format!("a flight longer than {MAX_DURATION} s"))
            }
            _ => Ok(()),
        }
    }

    /// The flight, with the velocities and accelerations the file lacks derived from it.
    fn finish(mut self, name: &str) -> Result<Trajectory, TrajectoryError> {
        if self.t.is_empty() {
            return Err(TrajectoryError::HeaderOnly);
        }
        if self.t.len() < MIN_ROWS {
            return Err(TrajectoryError::TooFewRows {
                rows: self.t.len(),
                min: MIN_ROWS,
            });
        }
        if !self.has_vel {
            let refusal = format!("positions imply a speed over {MAX_SPEED} m/s");
            self.vel = self.derived(&self.pos, 0.15, MAX_SPEED, refusal)?;
        }
        if !self.has_acc {
            let refusal =
                format!("the motion implies an acceleration over {MAX_ACCELERATION} m/s²");
            self.acc = self.derived(&self.vel, 0.3, MAX_ACCELERATION, refusal)?;
        }
        Trajectory::new(name.to_string(), self.t, self.pos, self.vel, self.acc)
    }

    /// The derivative of `values` over ±`half_window` s ([`smoothed_derivative`]), refused
    /// with `refusal` at the first sample where its length exceeds `limit`.
    fn derived(
        &self,
        values: &[[f64; 3]],
        half_window: f64,
        limit: f64,
        refusal: String,
    ) -> Result<Vec<[f64; 3]>, TrajectoryError> {
        let derivative = smoothed_derivative(&self.t, values, half_window);
        match derivative.iter().position(|v| !within(v, limit)) {
            Some(i) => Err(TrajectoryError::Absurd {
                line: self.line_numbers[i],
                what: refusal,
            }),
            None => Ok(derivative),
        }
    }
}

/// The comma-separated fields of `line`, each trimmed of white space, appended to `out`.
///
/// A byte scan: ',' is ASCII, so cutting at its bytes leaves valid UTF-8, and on fields of a few
/// bytes it beats `split(',')`'s searcher; a field that starts and ends with a visible ASCII
/// character (a bare number) has nothing to trim. Together they took a quarter to a third off a
/// 10⁶-row import (perf: the searcher and the trims were 12 % of a long flight's run).
fn split_fields<'a>(line: &'a str, out: &mut Vec<&'a str>) {
    let mut rest = line;
    while let Some(i) = rest.bytes().position(|b| b == b',') {
        out.push(trimmed(&rest[..i]));
        rest = &rest[i + 1..];
    }
    out.push(trimmed(rest));
}

/// `field` without surrounding white space (`str::trim`, skipped where neither end is any).
fn trimmed(field: &str) -> &str {
    match (field.as_bytes().first(), field.as_bytes().last()) {
        (Some(a), Some(b)) if a.is_ascii_graphic() && b.is_ascii_graphic() => field,
        _ => field.trim(),
    }
}

/// `field` without the double quotes around it (`trim_matches('"')`, skipped where it has none).
fn unquoted(field: &str) -> &str {
    if field.starts_with('"') || field.ends_with('"') {
        field.trim_matches('"')
    } else {
        field
    }
}

/// Whether a vector's length is at most `limit` (false for NaN, which a derivative over a
/// vanishing time step can give).
fn within(v: &[f64; 3], limit: f64) -> bool {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() <= limit
}

/// Derivative of `values` over time by local linear regression on the samples within
/// ±`half_window` seconds (at least one neighbour on each side where there is one): a
/// Savitzky–Golay filter of order 1 for uneven sampling, which smooths noise that a plain finite
/// difference would amplify.
///
/// Linear time: the regression's sums slide with the window (each sample enters and leaves once,
/// with Welford's mean-centred updates, so times of hours keep their precision), where summing
/// each window afresh took time proportional to the samples per window — minutes for a
/// high-rate log.
fn smoothed_derivative(t: &[f64], values: &[[f64; 3]], half_window: f64) -> Vec<[f64; 3]> {
    let mut w = Regression::default();
    // The samples a..b (exclusive) are in `w`; every sample in it was added after `fresh_from`
    // was set, so once `a` passes it the sums are rebuilt afresh (each sample is added at most
    // twice: still linear), and rounding from removals never accumulates past one window.
    let (mut a, mut b, mut fresh_from) = (0usize, 0usize, 0usize);
    windows(t, half_window)
        .map(|(from, to)| {
            while b < to {
                w.add(t[b], &values[b]);
                b += 1;
            }
            while a < from {
                w.remove(t[a], &values[a]);
                a += 1;
            }
            if a >= fresh_from {
                w = Regression::default();
                (a..b).for_each(|j| w.add(t[j], &values[j]));
                fresh_from = b;
            }
            w.slope()
        })
        .collect()
}

/// For each sample i, the samples `from..to` its derivative regresses on: those within
/// ±`half_window` s, with at least one neighbour on each side where there is one. Both ends only
/// move forward.
fn windows(t: &[f64], half_window: f64) -> impl Iterator<Item = (usize, usize)> + '_ {
    let n = t.len();
    let (mut lo, mut hi) = (0usize, 0usize);
    (0..n).map(move |i| {
        while t[i] - t[lo] > half_window && lo + 1 < i {
            lo += 1;
        }
        while hi + 1 < n && (t[hi + 1] - t[i] <= half_window || hi <= i) {
            hi += 1;
        }
        (lo.min(i.saturating_sub(1)), hi.max((i + 1).min(n - 1)) + 1)
    })
}

/// Running sums of a least-squares line y = α + β t over a sliding set of samples (Welford):
/// count, means, and the centred sums Σ(t − t̄)² and Σ(t − t̄)(y − ȳ).
#[derive(Default)]
struct Regression {
    m: f64,
    t_mean: f64,
    y_mean: [f64; 3],
    stt: f64,
    sty: [f64; 3],
}

impl Regression {
    fn add(&mut self, t: f64, y: &[f64; 3]) {
        self.m += 1.0;
        let dt = t - self.t_mean;
        self.t_mean += dt / self.m;
        self.stt += dt * (t - self.t_mean);
        for ((mean, sty), &v) in self.y_mean.iter_mut().zip(&mut self.sty).zip(y) {
            *mean += (v - *mean) / self.m;
            *sty += dt * (v - *mean);
        }
    }

    fn remove(&mut self, t: f64, y: &[f64; 3]) {
        if self.m <= 1.0 {
            *self = Regression::default();
            return;
        }
        let m = self.m - 1.0;
        let t_mean = (self.m * self.t_mean - t) / m;
        self.stt -= (t - t_mean) * (t - self.t_mean);
        for ((mean, sty), &v) in self.y_mean.iter_mut().zip(&mut self.sty).zip(y) {
            let without = (self.m * *mean - v) / m;
            *sty -= (t - t_mean) * (v - *mean);
            *mean = without;
        }
        self.t_mean = t_mean;
        self.m = m;
    }

    fn slope(&self) -> [f64; 3] {
        self.sty.map(|s| s / self.stt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The regression summed afresh for every window (the former, quadratic implementation).
    fn two_pass(t: &[f64], values: &[[f64; 3]], half_window: f64) -> Vec<[f64; 3]> {
        windows(t, half_window)
            .map(|(a, to)| {
                let b = to - 1;
                let m = (b - a + 1) as f64;
                let t_mean = t[a..=b].iter().sum::<f64>() / m;
                let stt: f64 = t[a..=b].iter().map(|x| (x - t_mean).powi(2)).sum();
                core::array::from_fn(|k| {
                    let y_mean = values[a..=b].iter().map(|v| v[k]).sum::<f64>() / m;
                    let sty: f64 = (a..=b)
                        .map(|j| (t[j] - t_mean) * (values[j][k] - y_mean))
                        .sum();
                    sty / stt
                })
            })
            .collect()
    }

    #[test]
    fn reading_reports_its_progress_about_a_hundred_times_in_order() {
        let text = csv(2000);
        let mut seen = Vec::new();
        let tr = parse_csv_with_progress(&text, "p", &mut |done, total| {
            seen.push((done, total));
            true
        })
        .unwrap()
        .unwrap();
        assert_eq!(tr.t.len(), 2000);
        assert!((90..=110).contains(&seen.len()), "{} reports", seen.len());
        assert!(seen.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 == w[0].1));
        assert!(seen.iter().all(|&(d, t)| d <= t));
    }

    #[test]
    fn a_reading_told_to_stop_ends_there_and_asks_no_more() {
        let text = csv(2000);
        let mut asked = 0;
        let read = parse_csv_with_progress(&text, "p", &mut |_, _| {
            asked += 1;
            asked < 3
        })
        .unwrap();
        assert!(read.is_none(), "a stopped reading gives no flight");
        assert_eq!(asked, 3, "nothing is asked after the answer stop");
    }

    #[test]
    fn a_missing_column_names_the_header_line_after_comments() {
        let e = parse_csv("# logged by hand\n\n# units: s, m\nt,x,y\n0,0,0\n", "f").unwrap_err();
        assert!(e.to_string().starts_with("line 4: no 'z' column"), "{e}");
    }

    #[test]
    fn the_sliding_regression_equals_summing_each_window_afresh() {
        let mut rng = crate::rng::Rng::derive(5, 0);
        for (rate, start) in [
            (10.0, 0.0),
            (1000.0, 0.0),
            (25.0, 36_000.0),
            (7.0, 80_000.0),
        ] {
            let mut t = vec![start];
            for _ in 1..4000 {
                // Uneven sampling: ±30 % jitter around the rate.
                t.push(t[t.len() - 1] + (0.7 + 0.6 * rng.uniform()) / rate);
            }
            let v: Vec<[f64; 3]> = t
                .iter()
                .map(|&x| {
                    let s = x - start;
                    [3.0 * s + rng.normal(), (0.2 * s).sin() * 50.0, 0.01 * s * s]
                })
                .collect();
            for half in [0.15, 0.3] {
                let fast = smoothed_derivative(&t, &v, half);
                let slow = two_pass(&t, &v, half);
                for (f, s) in fast.iter().zip(&slow) {
                    for k in 0..3 {
                        assert!(
                            (f[k] - s[k]).abs() <= 1e-8 * (1.0 + s[k].abs()),
                            "rate {rate} start {start}: {f:?} vs {s:?}"
                        );
                    }
                }
            }
        }
    }

    fn csv(rows: usize) -> String {
        let mut s = String::from("t_seconds,x_m,y_m,z_m\n");
        for i in 0..rows {
            let t = i as f64 * 0.1;
            s += &format!("{t},{},{},{}\n", 3.0 * t, 0.5 * t * t, 20.0);
        }
        s
    }

    #[test]
    fn a_gps_log_is_read_in_metres_from_its_first_row() {
        // A climbing turn logged as latitude, longitude and altitude above sea level, and the
        // same flight in metres from its first fix.
        let (lat0, lon0, alt0) = (-35.3632, 149.1652, 584.0);
        let k = core::f64::consts::PI / 180.0 * 6_371_000.0;
        let (mut gps, mut local) = (
            String::from("time,Lat,Lng,Alt\n"),
            String::from("t,x,y,z\n"),
        );
        for i in 0..100 {
            let t = i as f64 * 0.1;
            let (x, y, z) = (
                40.0 * (0.2 * t).sin(),
                40.0 - 40.0 * (0.2 * t).cos(),
                2.0 * t,
            );
            let lat = lat0 + y / k;
            let lon = lon0 + x / (k * lat0.to_radians().cos());
            gps += &format!("{t},{lat},{lon},{}\n", alt0 + z);
            local += &format!("{t},{x},{y},{z}\n");
        }
        let (a, b) = (
            parse_csv(&gps, "gps").unwrap(),
            parse_csv(&local, "local").unwrap(),
        );
        for i in [0, 37, 99] {
            for k in 0..3 {
                assert!(
                    (a.pos[i][k] - b.pos[i][k]).abs() < 1e-6,
                    "{i}: {:?} {:?}",
                    a.pos[i],
                    b.pos[i]
                );
                assert!((a.vel[i][k] - b.vel[i][k]).abs() < 1e-6);
            }
        }
        // With x and y given, latitude and longitude columns are only other columns.
        let both: String = local
            .lines()
            .enumerate()
            .map(|(i, l)| format!("{l},{}\n", if i == 0 { "lat,lon" } else { "1,2" }))
            .collect();
        assert_eq!(parse_csv(&both, "local").unwrap().pos, b.pos);
        let off = gps.replacen(&format!("{lat0},"), "95,", 1);
        let e = parse_csv(&off, "gps").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("latitude"), "{e}");
    }

    #[test]
    fn derives_velocity_and_acceleration_of_a_parabola() {
        let tr = parse_csv(&csv(100), "p").unwrap();
        let i = 50;
        assert!((tr.vel[i][0] - 3.0).abs() < 1e-9);
        assert!((tr.vel[i][1] - tr.t[i]).abs() < 1e-9);
        assert!((tr.acc[i][1] - 1.0).abs() < 1e-6);
        assert!((0..tr.len()).all(|i| tr.state(i).iter().all(|v| v.is_finite())));
    }

    #[test]
    fn a_row_written_twice_is_read_once_and_a_repeated_time_with_other_values_refused() {
        let text = csv(20);
        let lines: Vec<&str> = text.lines().collect();
        let mut twice = lines.clone();
        twice.insert(8, lines[7]);
        let read = parse_csv(&(twice.join("\n") + "\n"), "twice").unwrap();
        let once = parse_csv(&text, "once").unwrap();
        assert_eq!(
            (read.t.clone(), read.pos.clone()),
            (once.t.clone(), once.pos.clone())
        );
        let mut other = lines.clone();
        let moved = format!("{},99", lines[7].rsplit_once(',').unwrap().0);
        other.insert(8, &moved);
        let err = parse_csv(&(other.join("\n") + "\n"), "other").unwrap_err();
        assert_eq!(err.to_string(), "line 9: time is not strictly increasing");
    }

    #[test]
    fn refuses_bad_files_with_a_message_naming_the_line() {
        let cases: [(String, &str); 9] = [
            (String::new(), "empty"),
            ("t,x,y,z\n".into(), "no data rows"),
            (csv(5), "at least 10"),
            ("t,x,y\n1,2,3\n".into(), "'z' column"),
            (csv(20).replace("\n1,", "\n1,abc"), "not a number"),
            (
                csv(20).replacen(",20\n", ",NaN\n", 1),
                "line 2: column 'z_m' is not a finite number",
            ),
            (
                csv(20) + "0.5,1,1,1\n",
                "line 22: time is not strictly increasing",
            ),
            (csv(20) + "9,1,1\n", "line 22: 3 fields"),
            (csv(20) + "9,1e9,1,1\n", "line 22: a coordinate"),
        ];
        for (text, expected) in cases {
            let err = parse_csv(&text, "bad").unwrap_err().to_string();
            assert!(
                err.contains(expected),
                "{err:?} should contain {expected:?}"
            );
        }
    }

    #[test]
    fn accepts_aliases_case_insensitively_and_uses_given_velocities() {
        let mut s = String::from("Time,X,Y,Z,VX,VY,VZ\n");
        for i in 0..20 {
            s += &format!("{},0,0,0,1,2,3\n", i);
        }
        let tr = parse_csv(&s, "v").unwrap();
        assert_eq!(tr.vel[3], [1.0, 2.0, 3.0]);
    }
}
