//! Which setting a parameter object got wrong, when it could not be read at all.
//!
//! The JS API takes its parameters as JSON text (`JSON.stringify` of the caller's object, reference
//! §9). serde refuses a value of the wrong type before any of the core's checks run, and its message
//! cannot name the key of a flattened setting ("invalid type: string \"7\", expected u8 at line 1
//! column 9"). This reads the object again and names the first setting whose value could not be
//! read, so that the thrown `Error` carries its `setting` as the core's own refusals do.

use crate::options::{option, whole_refusal, GATEWAYS};
use serde_json::Value;

/// A setting named in `json` whose value serde could not read, as a message and, when the key is a
/// numeric option's ([`crate::options`]), that option's key: the first top-level key whose value is
/// `null` (what `JSON.stringify` makes of NaN and ±Infinity), and otherwise the first numeric option
/// given something other than a number, or a fraction where it takes whole numbers. `None` when
/// `json` is no object or every value has the right kind (serde refused something else, such as an
/// unknown key).
///
/// ```
/// use loratrack::api::misread_setting;
/// let (message, key) = misread_setting(r#"{"synthetic":1,"sf":"7"}"#).unwrap();
/// assert_eq!(key, Some("sf"));
/// assert_eq!(message, "sf must be a number, not the text \"7\"");
/// assert_eq!(misread_setting(r#"{"sf":7}"#), None);
/// ```
pub fn misread_setting(json: &str) -> Option<(String, Option<&'static str>)> {
    let map: serde_json::Map<String, Value> = serde_json::from_str(json).ok()?;
    if let Some((key, _)) = map.iter().find(|(_, v)| v.is_null()) {
        let message = format!(
            "{key} is not a number (NaN, Infinity and null are not accepted): give a finite number or leave it out"
        );
        return Some((message, option(key).map(|o| o.key)));
    }
    map.iter().find_map(|(key, value)| {
        let o = option(key)?;
        // The gateways are a list (the option is their count): each site's coordinates are read.
        if o.key == GATEWAYS.key {
            return misread_gateway(value).map(|m| (m, Some(o.key)));
        }
        let found = match value {
            Value::Number(n) if o.integer && n.as_f64().is_some_and(|x| x.fract() != 0.0) => {
                return Some((
                    format!("{key} must be a whole number, not {n}"),
                    Some(o.key),
                ));
            }
            // A negative whole number where the setting's type holds none (`overhead`, `drones`,
            // `seeds`, …: serde's "expected usize"): refused in the range's words.
            Value::Number(n) if o.integer && n.as_i64().is_some_and(|x| x < 0) && o.min >= 0.0 => {
                let value = n.as_f64().unwrap_or(f64::NAN);
                return Some((whole_refusal(o.key, value), Some(o.key)));
            }
            Value::Number(_) => return None,
            other => what(other),
        };
        Some((format!("{key} must be a number, not {found}"), Some(o.key)))
    })
}

/// The first site of a `gateways` list whose `east`, `north` or `height` is not a number, as a
/// message ("gateways: gateway 1's east must be a number, not the text \"a\""); `None` where
/// each is one (serde's own message then says what else is wrong, such as a missing `north`).
fn misread_gateway(value: &Value) -> Option<String> {
    let sites = value.as_array()?;
    sites.iter().enumerate().find_map(|(i, site)| {
        ["east", "north", "height"].iter().find_map(|field| {
            let found = match site.get(field)? {
                Value::Number(_) => return None,
                other => what(other),
            };
            Some(format!(
                "gateways: gateway {}'s {field} must be a number, not {found}",
                i + 1
            ))
        })
    })
}

/// A JSON value that is not a number, in words.
fn what(value: &Value) -> String {
    match value {
        Value::String(s) => format!("the text {}", Value::String(s.clone())),
        Value::Bool(b) => format!("{b}"),
        Value::Array(_) => "a list".to_owned(),
        Value::Object(_) => "an object".to_owned(),
        Value::Null => "null".to_owned(),
        Value::Number(n) => format!("{n}"),
    }
}

/// serde's refusal of the parameter object `json` (`message`) as a JS caller can use it: without
/// its position in the JSON text, which the caller never wrote ("at line 1 column 29"), and an
/// unknown choice with the key it was given for ("region: unknown variant `xx`, expected one of
/// `eu868`, …"), which a flattened setting's message lacks.
///
/// ```
/// use loratrack::api::explain_serde_error;
/// let json = r#"{"synthetic":1,"region":"xx"}"#;
/// let message = "unknown variant `xx`, expected one of `eu868`, `us915` at line 1 column 29";
/// assert_eq!(explain_serde_error(json, message), "region: unknown variant `xx`, expected one of `eu868`, `us915`");
/// ```
pub fn explain_serde_error(json: &str, message: &str) -> String {
    let plain = match message.rfind(" at line ") {
        Some(i) if message[i..].contains(" column ") => &message[..i],
        _ => message,
    };
    let map: serde_json::Map<String, Value> = serde_json::from_str(json).unwrap_or_default();
    let key_of = |wanted: &dyn Fn(&Value) -> bool| {
        map.iter()
            .find(|(_, value)| wanted(value))
            .map(|(key, _)| key.clone())
    };
    // A negative count (`payload: -1`): serde expects an unsigned type, which it names in Rust's words.
    if let Some((n, expected)) = plain
        .strip_prefix("invalid value: integer `")
        .and_then(|rest| rest.split_once("`, expected "))
    {
        let unsigned = ["usize", "u8", "u16", "u32", "u64"].contains(&expected);
        if let (Some(given), true) = (n.parse::<i64>().ok(), unsigned) {
            if let Some(key) = key_of(&|v| v.as_i64() == Some(given)) {
                return whole_refusal(&key, given as f64);
            }
        }
    }
    let quoted = |prefix: &str, close: char| {
        plain
            .strip_prefix(prefix)
            .and_then(|rest| rest.split(close).next())
            .map(str::to_owned)
    };
    let key = if let Some(v) = quoted("unknown variant `", '`') {
        key_of(&|value| value.as_str() == Some(v.as_str()))
    } else if let Some(v) = quoted("invalid type: string \"", '"') {
        key_of(&|value| value.as_str() == Some(v.as_str()))
    } else if ["missing field `east`", "missing field `north`"].contains(&plain) {
        // Only a gateway site has these fields.
        map.contains_key(GATEWAYS.key)
            .then(|| GATEWAYS.key.to_owned())
    } else {
        None
    };
    match key {
        Some(key) => format!("{key}: {plain}"),
        None => plain.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_null_is_named_first_and_keyed_only_when_it_is_an_option() {
        let (m, key) = misread_setting(r#"{"sf":"7","distance":null}"#).unwrap();
        assert!(m.starts_with("distance is not a number"), "{m}");
        assert_eq!(key, Some("distance"));
        let (m, key) = misread_setting(r#"{"sample":null}"#).unwrap();
        assert!(m.starts_with("sample is not a number"), "{m}");
        assert_eq!(key, None);
    }

    #[test]
    fn a_numeric_option_given_text_a_boolean_a_list_or_an_object_is_named() {
        for (value, what) in [
            (r#""1000""#, "the text \"1000\""),
            ("true", "true"),
            ("[1000]", "a list"),
            (r#"{"m":1000}"#, "an object"),
        ] {
            let json = format!(r#"{{"model":"dr","distance":{value}}}"#);
            let (m, key) = misread_setting(&json).unwrap();
            assert_eq!(m, format!("distance must be a number, not {what}"));
            assert_eq!(key, Some("distance"));
        }
    }

    #[test]
    fn a_fraction_is_named_only_where_whole_numbers_are_asked() {
        let (m, key) = misread_setting(r#"{"sf":7.5}"#).unwrap();
        assert_eq!(
            (m.as_str(), key),
            ("sf must be a whole number, not 7.5", Some("sf"))
        );
        assert_eq!(misread_setting(r#"{"distance":1000.5}"#), None);
    }

    #[test]
    fn a_negative_whole_number_where_none_is_held_is_refused_in_the_range_words() {
        let (m, key) = misread_setting(r#"{"synthetic":1,"overhead":-1}"#).unwrap();
        assert_eq!(
            (m.as_str(), key),
            (
                "overhead must be 0..255 bytes, a whole number, got -1",
                Some("overhead")
            )
        );
        // Where the type holds it, the core's range check says it, with every other setting.
        assert_eq!(misread_setting(r#"{"txPower":-5}"#), None);
    }

    #[test]
    fn a_gateway_site_is_read_field_by_field_not_as_a_number() {
        let (m, key) = misread_setting(
            r#"{"synthetic":1,"gateways":[{"east":0,"north":0},{"east":"a","north":0}]}"#,
        )
        .unwrap();
        assert_eq!(
            (m.as_str(), key),
            (
                "gateways: gateway 2's east must be a number, not the text \"a\"",
                Some("gateways")
            )
        );
        // A site missing a field is serde's to say: nothing here claims the list should be a number.
        assert_eq!(misread_setting(r#"{"gateways":[{"east":1}]}"#), None);
    }

    #[test]
    fn serde_messages_lose_their_json_position_and_an_unknown_choice_names_its_key() {
        let json = r#"{"synthetic":1,"adr":"yes"}"#;
        assert_eq!(
            explain_serde_error(json, "unknown variant `yes`, expected one of `off`, `lorawan`, `tracking` at line 1 column 27"),
            "adr: unknown variant `yes`, expected one of `off`, `lorawan`, `tracking`"
        );
        assert_eq!(
            explain_serde_error(
                r#"{"gateways":[{"east":1}]}"#,
                "missing field `north` at line 1 column 24"
            ),
            "gateways: missing field `north`"
        );
        assert_eq!(
            explain_serde_error("{}", "missing field `x` at line 1 column 2"),
            "missing field `x`"
        );
        // A negative count and a text where a list is asked name their keys, in words.
        assert_eq!(
            explain_serde_error(
                r#"{"sf":7,"payload":-1}"#,
                "invalid value: integer `-1`, expected usize at line 1 column 20"
            ),
            "payload must be a whole number, not negative, got -1"
        );
        assert_eq!(
            explain_serde_error(
                r#"{"model":"dr","state":"a"}"#,
                "invalid type: string \"a\", expected a sequence at line 1 column 25"
            ),
            "state: invalid type: string \"a\", expected a sequence"
        );
    }

    #[test]
    fn keys_that_are_no_numeric_option_and_text_that_is_no_object_name_nothing() {
        assert_eq!(misread_setting(r#"{"model":3,"bogus":"x"}"#), None);
        assert_eq!(misread_setting("[1,2]"), None);
        assert_eq!(misread_setting("not json"), None);
    }
}
