//! The field table of the payload: one row per state component, in state order.

use core::f64::consts::{FRAC_PI_2, TAU};

/// How a field's integer code is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Two bytes, signed, big-endian, codes −32767..=32767.
    I16,
    /// One byte, signed, codes −127..=127.
    I8,
    /// One byte, unsigned, codes 0..=255.
    U8,
    /// One byte over the full circle; codes wrap modulo 256.
    Circle,
}

impl Encoding {
    /// Bytes on the wire.
    pub fn bytes(self) -> usize {
        match self {
            Encoding::I16 => 2,
            _ => 1,
        }
    }
    /// Smallest and largest code (`Circle` wraps instead).
    pub fn code_range(self) -> (i64, i64) {
        match self {
            Encoding::I16 => (-32767, 32767),
            Encoding::I8 => (-127, 127),
            Encoding::U8 | Encoding::Circle => (0, 255),
        }
    }
}

/// One payload field: its name, unit, encoding and quantisation step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldSpec {
    /// State component name (`x`, `theta`, …).
    pub name: &'static str,
    /// What it is, in words (`turn rate ω`).
    pub quantity: &'static str,
    /// Unit of the decoded value.
    pub unit: &'static str,
    /// Storage.
    pub encoding: Encoding,
    /// Quantisation step in `unit`; the decoded value is code × step.
    pub step: f64,
}

impl FieldSpec {
    /// The largest value that encodes without saturating (`Circle`: none saturate).
    pub fn max(&self) -> f64 {
        self.encoding.code_range().1 as f64 * self.step
    }
    /// The smallest value that encodes without saturating.
    pub fn min(&self) -> f64 {
        self.encoding.code_range().0 as f64 * self.step
    }

    /// The values it sends as themselves, in words, to two decimals: `±6553.4 m`, `0–25.5 m/s`,
    /// `±2 rad/s` (a heading: `any`, since it wraps).
    ///
    /// ```
    /// use loratrack::FIELDS;
    /// assert_eq!(FIELDS[5].range_words(), "0–25.5 m/s");
    /// assert_eq!(FIELDS[6].range_words(), "±6.35 m/s²");
    /// ```
    pub fn range_words(&self) -> String {
        let unit = self.unit.replace("^2", "²");
        let number = |x: f64| {
            let s = format!("{x:.2}");
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        };
        match self.encoding {
            Encoding::Circle => "any".into(),
            _ if self.min() == -self.max() => format!("±{} {unit}", number(self.max())),
            _ => format!("{}–{} {unit}", number(self.min()), number(self.max())),
        }
    }

    /// What it is and what it sends as itself, in words: `turn rate ω, ±2 rad/s`.
    pub fn words(&self) -> String {
        format!("{}, {}", self.quantity, self.range_words())
    }
}

/// The fields of the 3D-CTRA state in order; DR uses the first 6, CTRA+ the first 8.
pub const FIELDS: [FieldSpec; 9] = [
    FieldSpec {
        name: "x",
        quantity: "distance east of the flight's start",
        unit: "m",
        encoding: Encoding::I16,
        step: 0.2,
    },
    FieldSpec {
        name: "y",
        quantity: "distance north of the flight's start",
        unit: "m",
        encoding: Encoding::I16,
        step: 0.2,
    },
    FieldSpec {
        name: "z",
        quantity: "height above the flight's start",
        unit: "m",
        encoding: Encoding::I16,
        step: 0.2,
    },
    FieldSpec {
        name: "theta",
        quantity: "heading θ",
        unit: "rad",
        encoding: Encoding::Circle,
        step: TAU / 256.0,
    },
    FieldSpec {
        name: "phi",
        quantity: "pitch φ",
        unit: "rad",
        encoding: Encoding::I8,
        step: FRAC_PI_2 / 127.0,
    },
    FieldSpec {
        name: "v",
        quantity: "speed",
        unit: "m/s",
        encoding: Encoding::U8,
        step: 0.1,
    },
    FieldSpec {
        name: "a",
        quantity: "acceleration",
        unit: "m/s^2",
        encoding: Encoding::I8,
        step: 0.05,
    },
    FieldSpec {
        name: "omega",
        quantity: "turn rate ω",
        unit: "rad/s",
        encoding: Encoding::I8,
        step: 2.0 / 127.0,
    },
    FieldSpec {
        name: "psi",
        quantity: "tilt rate ψ",
        unit: "rad/s",
        encoding: Encoding::I8,
        step: 2.0 / 127.0,
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::ModelKind;

    #[test]
    fn payload_sizes_are_9_11_12_bytes() {
        for m in ModelKind::ALL {
            let bytes: usize = FIELDS[..m.state_len()]
                .iter()
                .map(|f| f.encoding.bytes())
                .sum();
            assert_eq!(bytes, m.payload_bytes(), "{m}");
        }
    }

    #[test]
    fn position_covers_a_13_km_box_at_10_cm_error() {
        assert!(FIELDS[0].max() - FIELDS[0].min() > 13_100.0);
        assert!(FIELDS[0].step / 2.0 <= 0.1);
        assert!((FIELDS[3].step / 2.0).to_degrees() < 0.71);
    }
}
