//! Latitude and longitude as metres east and north of an origin (reference §11, §16): the
//! equirectangular projection about the origin, on a sphere of the Earth's mean radius.

/// Mean Earth radius, m: over a flight's or mission's few kilometres the local east-north plane
/// is flat to well under a metre.
const EARTH_RADIUS: f64 = 6_371_000.0;

/// Metres east and north of `origin` (latitude, longitude, degrees) of the point at `lat`, `lon`
/// (degrees).
///
/// ```text
/// east = (lon − lon₀) · π/180 · R · cos(lat₀),  north = (lat − lat₀) · π/180 · R
/// ```
pub(crate) fn east_north(origin: [f64; 2], lat: f64, lon: f64) -> [f64; 2] {
    let k = core::f64::consts::PI / 180.0 * EARTH_RADIUS;
    [
        (lon - origin[1]) * k * crate::math::cos(origin[0].to_radians()),
        (lat - origin[0]) * k,
    ]
}

/// Whether `lat`, `lon` (degrees) name a place on Earth.
pub(crate) fn on_earth(lat: f64, lon: f64) -> bool {
    lat.abs() <= 90.0 && lon.abs() <= 180.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_thousandth_of_a_degree_is_about_a_hundred_metres() {
        // At the equator 0.001° either way is 111.2 m; at 60° a degree of longitude is half.
        let [e, n] = east_north([0.0, 0.0], 0.001, 0.001);
        assert!(
            (e - 111.19).abs() < 0.01 && (n - 111.19).abs() < 0.01,
            "{e} {n}"
        );
        let [e, _] = east_north([60.0, 10.0], 60.0, 10.001);
        assert!((e - 55.6).abs() < 0.05, "{e}");
        assert!(on_earth(-90.0, 180.0) && !on_earth(91.0, 0.0) && !on_earth(0.0, -181.0));
    }
}
