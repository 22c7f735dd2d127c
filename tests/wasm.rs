//! The WebAssembly boundary, under Node: `cargo test --target wasm32-unknown-unknown --test wasm`.
//! Each export must accept the documented plain object, return the CLI's JSON shape, and turn
//! bad input into a thrown Error without poisoning the module.
#![cfg(target_arch = "wasm32")]

use js_sys::{Object, Reflect};
use loratrack::wasm;
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

fn obj(pairs: &[(&str, JsValue)]) -> JsValue {
    let o = Object::new();
    for (k, v) in pairs {
        Reflect::set(&o, &JsValue::from_str(k), v).unwrap();
    }
    o.into()
}

fn get(v: &JsValue, key: &str) -> JsValue {
    Reflect::get(v, &JsValue::from_str(key)).unwrap()
}

fn num(v: &JsValue, key: &str) -> f64 {
    get(v, key)
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number"))
}

fn error_message(e: wasm_bindgen::JsError) -> String {
    let v: JsValue = e.into();
    v.dyn_into::<js_sys::Error>()
        .map(|e| String::from(e.message()))
        .unwrap_or_default()
}

#[wasm_bindgen_test]
fn time_on_air_matches_the_reference_and_reports_the_interval() {
    let r = wasm::time_on_air(obj(&[
        ("sf", 7.into()),
        ("bw", 125.into()),
        ("payload", 14.into()),
        ("overhead", 0.into()),
    ]))
    .unwrap();
    assert!((num(&r, "timeOnAir") - 0.046336).abs() < 1e-9);
    assert!((num(&r, "minInterval") - 4.6336).abs() < 1e-9);
    assert_eq!(num(&r, "payloadSymbols"), 33.0);
    assert_eq!(get(&r, "lowDataRateOptimize").as_bool(), Some(false));
}

#[wasm_bindgen_test]
fn bad_input_throws_a_readable_error_and_the_module_keeps_working() {
    let e = wasm::time_on_air(obj(&[
        ("sf", 13.into()),
        ("bw", 125.into()),
        ("payload", 12.into()),
    ]))
    .unwrap_err();
    assert!(error_message(e).contains("spreading factor"));
    let e = wasm::time_on_air(obj(&[("sf", 7.into()), ("bw", 125.into())])).unwrap_err();
    assert!(error_message(e).contains("payload"));
    let e = wasm::time_on_air(obj(&[
        ("sf", 7.into()),
        ("bw", 125.into()),
        ("payload", 12.into()),
        ("bogus", 1.into()),
    ]))
    .unwrap_err();
    assert!(error_message(e).contains("bogus"));
    let ok = wasm::time_on_air(obj(&[
        ("sf", 8.into()),
        ("bw", 125.into()),
        ("payload", 9.into()),
        ("overhead", 0.into()),
    ]))
    .unwrap();
    assert!((num(&ok, "timeOnAir") - 0.072192).abs() < 1e-9);
}
