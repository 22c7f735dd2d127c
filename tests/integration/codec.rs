//! The payload codec: round trip within half a quantisation step, saturation, and no input that
//! makes the decoder fail other than by a length error (reference §5).

use loratrack::{decode, encode, wrap_angle, ModelKind, FIELDS};
use proptest::prelude::*;

fn model() -> impl Strategy<Value = ModelKind> {
    prop_oneof![
        Just(ModelKind::Dr),
        Just(ModelKind::CtraPlus),
        Just(ModelKind::Ctra3d)
    ]
}

/// A state inside every field's range (phi within ±pi/2, so no loop rewriting).
fn in_range_state() -> impl Strategy<Value = Vec<f64>> {
    (
        -6500.0f64..6500.0,
        -6500.0f64..6500.0,
        -6500.0f64..6500.0,
        -3.2f64..3.2,
        -1.57f64..1.57,
        0.0f64..25.5,
        -6.35f64..6.35,
        -2.0f64..2.0,
        -2.0f64..2.0,
    )
        .prop_map(|(x, y, z, th, ph, v, a, w, p)| vec![x, y, z, th, ph, v, a, w, p])
}

proptest! {
    #[test]
    fn round_trip_is_within_half_a_step(m in model(), s in in_range_state(), ox in -1e5f64..1e5, oy in -1e5f64..1e5) {
        let origin = [ox, oy, 0.0];
        let state: Vec<f64> = s[..m.state_len()].iter().enumerate()
            .map(|(i, v)| if i < 2 { v + origin[i] } else { *v }).collect();
        let e = encode(m, &state, origin).unwrap();
        prop_assert_eq!(e.bytes.len(), m.payload_bytes());
        prop_assert!(e.saturated.is_empty(), "saturated {:?}", e.saturated);
        let back = decode(m, &e.bytes, origin).unwrap();
        for (i, f) in FIELDS[..m.state_len()].iter().enumerate() {
            let diff = if i == 3 { wrap_angle(back[i] - state[i]) } else { back[i] - state[i] };
            // Half a step, plus the rounding of the origin offset in f64.
            prop_assert!(diff.abs() <= f.step / 2.0 + 1e-9, "{}: {} -> {} (step {})", f.name, state[i], back[i], f.step);
        }
        prop_assert!((back[0] - state[0]).abs() <= 0.1 + 1e-9);
    }

    #[test]
    fn out_of_range_values_saturate_to_the_range_edge(m in model(), s in in_range_state(), scale in 2.0f64..1e6) {
        let mut state = s[..m.state_len()].to_vec();
        state[5] = 25.5 * scale; // v beyond 25.5 m/s
        state[0] = -7000.0 * scale;
        let e = encode(m, &state, [0.0; 3]).unwrap();
        prop_assert!(e.saturated.contains("v") && e.saturated.contains("x"));
        let back = decode(m, &e.bytes, [0.0; 3]).unwrap();
        prop_assert!((back[5] - FIELDS[5].max()).abs() < 1e-9);
        prop_assert!((back[0] - FIELDS[0].min()).abs() < 1e-9);
    }

    #[test]
    fn decoding_any_bytes_of_the_right_length_gives_finite_numbers(m in model(), bytes in prop::collection::vec(any::<u8>(), 12)) {
        let state = decode(m, &bytes[..m.payload_bytes()], [0.0; 3]).unwrap();
        prop_assert!(state.iter().all(|v| v.is_finite()));
        // Every decoded state is inside the ranges: it re-encodes without saturation to a payload
        // that decodes to the same state.
        let again = encode(m, &state, [0.0; 3]).unwrap();
        prop_assert!(again.saturated.is_empty(), "{:?}", again.saturated);
        prop_assert_eq!(decode(m, &again.bytes, [0.0; 3]).unwrap(), state);
    }

    #[test]
    fn decoding_the_wrong_length_is_an_error_naming_the_size(m in model(), bytes in prop::collection::vec(any::<u8>(), 0..40)) {
        prop_assume!(bytes.len() != m.payload_bytes());
        let err = decode(m, &bytes, [0.0; 3]).unwrap_err().to_string();
        let expected = format!("{} bytes", m.payload_bytes());
        prop_assert!(err.contains(&expected));
    }
}

#[test]
fn the_cli_names_each_saturated_field_with_the_range_it_was_held_to() {
    let text = |state: &str| {
        let out = crate::cli(&["encode", "--model", "ctra-plus", "--state", state]);
        assert!(out.status.success(), "{state}");
        String::from_utf8(out.stdout).unwrap()
    };
    let clipped = text("9000,0,0,0,0,40,-9,0");
    let line = clipped.lines().nth(1).unwrap_or_default();
    let ranges: Vec<String> = [0, 5, 6]
        .map(|i| format!("{} ({})", FIELDS[i].name, FIELDS[i].range_words()))
        .into();
    assert_eq!(line, format!("saturated: {}", ranges.join(", ")));
    // Reference §5's table: the speed byte holds 0..25.5 m/s.
    assert!(line.contains("v (0–25.5 m/s)"), "{line}");
    assert_eq!(
        text("1,0,0,0,0,4,0,0").lines().count(),
        1,
        "nothing saturated, nothing said"
    );
}
