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

fn error_message(e: JsValue) -> String {
    e.dyn_into::<js_sys::Error>()
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

/// A refusal that knows the value of its setting with which the run would go ahead carries it as
/// a number (`valueThatFits`), beside the message that says it in words, so that the page can
/// offer it: the seeds that fit, a swarm's drones that fit, the heartbeat the slowest data rate
/// needs; other refusals carry none.
#[wasm_bindgen_test]
fn a_refusal_says_which_value_of_its_setting_fits() {
    let fit = |e: &JsValue| get(e, "valueThatFits").as_f64();
    let setting = |e: &JsValue| get(e, "setting").as_string();
    let e = wasm::simulate(
        obj(&[("synthetic", "all".into()), ("seeds", 50.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("seeds"));
    assert_eq!(fit(&e), Some(18.0));
    assert!(error_message(e).contains("at most 18 seeds"));
    let heartbeat = obj(&[
        ("synthetic", 1.into()),
        ("sf", 12.into()),
        ("bw", 125.into()),
        ("sender", "error".into()),
    ]);
    let e = wasm::simulate(heartbeat, JsValue::UNDEFINED).unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("maxInterval"));
    let needed = fit(&e).expect("a heartbeat that fits");
    assert!(error_message(e).contains(&format!("{needed} s), got 10")));
    let kept = obj(&[
        ("synthetic", 1.into()),
        ("sf", 12.into()),
        ("bw", 125.into()),
        ("sender", "error".into()),
        ("maxInterval", needed.into()),
    ]);
    assert!(wasm::simulate(kept, JsValue::UNDEFINED).is_ok());
    // A setting nothing would read, by its key, with what makes it apply.
    let unread = obj(&[("synthetic", 1.into()), ("threshold", 5.into())]);
    let e = wasm::simulate(unread, JsValue::UNDEFINED).unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("threshold"));
    assert!(error_message(e).ends_with("set sender to error"));
    // A swarm too long for its drones: as many as fit (refused before it flies).
    let e = wasm::swarm(
        obj(&[
            ("drones", 500.into()),
            ("duration", 3600.into()),
            ("sensorRate", 20.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("drones"));
    assert_eq!(fit(&e), Some(333.0));
    assert!(error_message(e).contains("at most 333 drones"));
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("sf", 13.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(fit(&e), None);
}

/// The JS API's promise (README, JavaScript API): where one setting is at fault the thrown Error
/// names it as `setting`, the key the functions take, so that a caller need not parse messages.
#[wasm_bindgen_test]
fn a_refused_setting_is_named_on_the_thrown_error() {
    let setting = |e: &JsValue| get(e, "setting").as_string();
    let e = wasm::time_on_air(obj(&[
        ("sf", 13.into()),
        ("bw", 125.into()),
        ("payload", 12.into()),
    ]))
    .unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("sf"));
    // A heartbeat shorter than SF12's interval: a limit that depends on another setting.
    let e = wasm::simulate(
        obj(&[
            ("synthetic", 1.into()),
            ("sf", 12.into()),
            ("bw", 125.into()),
            ("sender", "error".into()),
            ("maxInterval", 10.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e.clone()).starts_with("maxInterval must be"));
    assert_eq!(setting(&e).as_deref(), Some("maxInterval"));
    // NaN reaches the core as null (JSON.stringify): refused while the settings are read, and named.
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("distance", f64::NAN.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(
        setting(&e).as_deref(),
        Some("distance"),
        "{}",
        error_message(e)
    );
    // So does a number given as text, which serde refuses before the core's checks.
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("sf", "7".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("sf"), "{}", error_message(e));
    // And a negative count, which serde refuses as no usize: named, in the range's words.
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("overhead", (-1).into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert_eq!(setting(&e).as_deref(), Some("overhead"));
    assert!(error_message(e).ends_with("overhead must be 0..255 bytes, a whole number, got -1"));
    // An unknown choice names its key, and no message points into JSON text the caller never wrote.
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("region", "xx".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    let message = error_message(e);
    assert!(
        message.contains("region: unknown variant `xx`"),
        "{message}"
    );
    assert!(!message.contains("line 1"), "{message}");
    // A misspelt key is no setting the core knows: the message says so, and names none.
    let e = wasm::simulate(obj(&[("bogus", 1.into())]), JsValue::UNDEFINED).unwrap_err();
    assert_eq!(setting(&e), None);
}

fn array(values: &[f64]) -> JsValue {
    values
        .iter()
        .map(|v| JsValue::from_f64(*v))
        .collect::<js_sys::Array>()
        .into()
}

fn numbers(v: &JsValue, key: &str) -> Vec<f64> {
    js_sys::Array::from(&get(v, key))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[wasm_bindgen_test]
fn predict_reproduces_the_2d_ctra_reference_and_rejects_bad_states() {
    let r = wasm::predict(obj(&[
        ("model", "ctra-plus".into()),
        ("state", array(&[0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0])),
        ("dt", 0.5.into()),
    ]))
    .unwrap();
    let s = numbers(&r, "state");
    assert!(
        (s[0] - 0.5967208697966773).abs() < 1e-12 && (s[1] - 0.16305169576864387).abs() < 1e-12
    );
    assert_eq!(get(&r, "model").as_string().as_deref(), Some("ctra-plus"));
    let e = wasm::predict(obj(&[
        ("model", "3d-ctra".into()),
        ("state", array(&[0.0; 8])),
        ("dt", 1.into()),
    ]))
    .unwrap_err();
    assert!(error_message(e).contains("9 numbers"));
    let e = wasm::predict(obj(&[
        ("model", "dr".into()),
        ("state", array(&[0.0; 6])),
        ("dt", (-1).into()),
    ]))
    .unwrap_err();
    assert!(error_message(e).contains("dt must be 0..86400 s"));
    let e = wasm::predict(obj(&[
        ("model", "3d-ctra".into()),
        ("state", array(&[0.0; 9])),
        ("dt", 1.into()),
        ("step", 0.1.into()),
        ("eta", 1.5.into()),
    ]))
    .unwrap_err();
    assert!(error_message(e).contains("eta"));
}

#[wasm_bindgen_test]
fn encode_then_decode_round_trips_and_wrong_lengths_throw() {
    let state = [12.3, -40.0, 55.5, 0.5, 0.1, 7.2, 0.3, 0.2, -0.1];
    let e = wasm::encode(obj(&[
        ("model", "3d-ctra".into()),
        ("state", array(&state)),
    ]))
    .unwrap();
    let hex = get(&e, "hex").as_string().unwrap();
    assert_eq!(hex.len(), 24);
    let d = wasm::decode(obj(&[("model", "3d-ctra".into()), ("hex", hex.into())])).unwrap();
    let back = numbers(&d, "state");
    assert!((back[0] - 12.3).abs() <= 0.1 + 1e-9);
    let err = wasm::decode(obj(&[("model", "dr".into()), ("hex", "00ff".into())])).unwrap_err();
    assert!(error_message(err).contains("9 bytes"));
}

#[wasm_bindgen_test]
fn simulate_returns_the_cli_shape_and_refuses_a_bad_csv() {
    let r = wasm::simulate(
        obj(&[
            ("synthetic", 1.into()),
            ("model", "all".into()),
            ("sf", 7.into()),
            ("bw", 250.into()),
            ("distance", 1000.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let results = js_sys::Array::from(&get(&r, "results"));
    assert_eq!(results.length(), 3);
    let first = results.get(0);
    assert_eq!(get(&first, "model").as_string().as_deref(), Some("dr"));
    assert!(num(&get(&first, "error3d"), "p75") > 0.0);
    assert!(num(&get(&r, "config"), "flightTime") > 50.0);
    let e = wasm::simulate(
        obj(&[("trajectory", "t,x,y,z\n1,2,3\n".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("line 2"));
    let e = wasm::simulate(obj(&[("synthetic", 31.into())]), JsValue::UNDEFINED).unwrap_err();
    assert!(error_message(e).contains("1..30"));
}

#[wasm_bindgen_test]
fn a_plan_crosses_the_boundary_and_a_mission_station_needs_one() {
    // A straight leg east at 20 m altitude, and a flight along it at 5 m/s.
    let rows: String = (0..=200)
        .map(|i| format!("{},{},0,20\n", f64::from(i) * 0.1, f64::from(i) * 0.5))
        .collect();
    let csv = format!("t,x,y,z\n{rows}");
    let run = |plan: Option<&str>| {
        let mut settings = vec![
            ("trajectory", csv.as_str().into()),
            ("model", "mission".into()),
            ("planTolerance", 5.into()),
        ];
        if let Some(p) = plan {
            settings.push(("plan", p.into()));
        }
        wasm::simulate(obj(&settings), JsValue::UNDEFINED)
    };
    let r = run(Some("x,y,z,speed\n0,0,20\n100,0,20,5\n")).unwrap();
    let results = js_sys::Array::from(&get(&r, "results"));
    assert_eq!(
        get(&results.get(0), "model").as_string().as_deref(),
        Some("mission")
    );
    let e = run(None).unwrap_err();
    // The settings it names are JS keys, without the marks the CLI turns into its flags.
    assert!(error_message(e).contains("needs the plan the drone flies: give plan (a CSV"));
    let e = run(Some("0,0,20\n1,zero,20\n")).unwrap_err();
    // The page shows a plan's error beside the plan control by this name.
    assert_eq!(get(&e, "setting").as_string().as_deref(), Some("plan"));
    assert!(error_message(e).contains("plan line 2"));
}

#[wasm_bindgen_test]
fn simulate_reports_progress_up_to_the_total() {
    use std::cell::RefCell;
    use std::rc::Rc;
    use wasm_bindgen::closure::Closure;
    let calls: Rc<RefCell<Vec<(f64, f64)>>> = Rc::default();
    let sink = Rc::clone(&calls);
    let cb = Closure::<dyn FnMut(f64, f64)>::new(move |d, t| sink.borrow_mut().push((d, t)));
    let f: &js_sys::Function = cb.as_ref().unchecked_ref();
    wasm::simulate(
        obj(&[("synthetic", 2.into()), ("seed", 99.into())]),
        f.clone().into(),
    )
    .unwrap();
    let calls = calls.borrow();
    // One flight, three models: a drone run and a station run each.
    assert_eq!(calls.len(), 6);
    assert_eq!(calls.last(), Some(&(6.0, 6.0)));
    assert!(calls.windows(2).all(|w| w[1].0 > w[0].0));
}

#[wasm_bindgen_test]
fn a_progress_callback_that_returns_false_stops_the_run_before_its_next_flight() {
    use std::cell::RefCell;
    use std::rc::Rc;
    use wasm_bindgen::closure::Closure;
    let set = |seed: i32| obj(&[("synthetic", "all".into()), ("seed", seed.into())]);
    let json = |v: &JsValue| String::from(js_sys::JSON::stringify(v).unwrap());
    let before = json(&wasm::simulate(set(41), JsValue::UNDEFINED).unwrap());
    let calls: Rc<RefCell<usize>> = Rc::default();
    let sink = Rc::clone(&calls);
    // Go on for the first two flights' drone runs, then stop.
    let cb = Closure::<dyn FnMut(f64, f64) -> bool>::new(move |_, _| {
        *sink.borrow_mut() += 1;
        *sink.borrow() < 3
    });
    let f: &js_sys::Function = cb.as_ref().unchecked_ref();
    let e = wasm::simulate(set(42), f.clone().into()).unwrap_err();
    assert_eq!(
        error_message(e),
        "the run was stopped by its progress callback"
    );
    // In turn, one flight at a time: no flight starts after the tick that said stop.
    assert_eq!(*calls.borrow(), 3);
    // A callback that returns anything but false goes on to the end; the stopped run left the
    // module's simulator giving the numbers it gave before.
    let on = Closure::<dyn FnMut(f64, f64) -> JsValue>::new(|_, _| JsValue::from_str("no"));
    let f: &js_sys::Function = on.as_ref().unchecked_ref();
    assert_eq!(
        json(&wasm::simulate(set(41), f.clone().into()).unwrap()),
        before
    );
    // Stopped among the stations' flights (the 90 drone runs, 30 flights × 3 models, come from
    // the cache and tick first), whose remembered predictions it has begun to extend: the same.
    let late: Rc<RefCell<usize>> = Rc::default();
    let sink = Rc::clone(&late);
    let cb = Closure::<dyn FnMut(f64, f64) -> bool>::new(move |_, _| {
        *sink.borrow_mut() += 1;
        *sink.borrow() < 100
    });
    let f: &js_sys::Function = cb.as_ref().unchecked_ref();
    assert!(wasm::simulate(set(41), f.clone().into()).is_err());
    assert_eq!(*late.borrow(), 100);
    assert_eq!(
        json(&wasm::simulate(set(41), JsValue::UNDEFINED).unwrap()),
        before
    );
    assert!(wasm::simulate(set(42), JsValue::UNDEFINED).is_ok());
}

#[wasm_bindgen_test]
fn a_progress_callback_that_calls_simulate_gets_an_error_not_a_trap() {
    use std::cell::RefCell;
    use std::rc::Rc;
    use wasm_bindgen::closure::Closure;
    let inner: Rc<RefCell<Option<String>>> = Rc::default();
    let sink = Rc::clone(&inner);
    let cb = Closure::<dyn FnMut(f64, f64)>::new(move |_, _| {
        if sink.borrow().is_none() {
            let e =
                wasm::simulate(obj(&[("synthetic", 3.into())]), JsValue::UNDEFINED).unwrap_err();
            *sink.borrow_mut() = Some(error_message(e));
        }
    });
    let f: &js_sys::Function = cb.as_ref().unchecked_ref();
    wasm::simulate(obj(&[("synthetic", 3.into())]), f.clone().into()).unwrap();
    assert!(inner
        .borrow()
        .as_deref()
        .unwrap_or("")
        .contains("progress callback"));
    assert!(wasm::simulate(obj(&[("synthetic", 3.into())]), JsValue::UNDEFINED).is_ok());
}

#[wasm_bindgen_test]
fn simulate_takes_station_and_sending_options_across_the_boundary() {
    let models = js_sys::Array::of2(&"dr".into(), &"imm".into());
    let r = wasm::simulate(
        obj(&[
            ("synthetic", 2.into()),
            ("model", models.into()),
            ("prediction", "bounded".into()),
            ("sender", "error".into()),
            ("threshold", 1.5.into()),
            ("dutyCycleMode", "budget".into()),
            ("burst", 5.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let config = get(&r, "config");
    assert_eq!(
        get(&config, "prediction").as_string().as_deref(),
        Some("bounded")
    );
    assert_eq!(
        get(&config, "dutyCycleMode").as_string().as_deref(),
        Some("budget")
    );
    let results = js_sys::Array::from(&get(&r, "results"));
    let imm = results.get(1);
    assert_eq!(get(&imm, "model").as_string().as_deref(), Some("imm"));
    let p = get(&imm, "modelProbability");
    let sum = num(&p, "dr") + num(&p, "ctra-plus") + num(&p, "3d-ctra");
    assert!((sum - 1.0).abs() < 1e-9, "{sum}");
    assert!((0.0..=1.0).contains(&num(&imm, "coverage95")));
    assert!(num(&imm, "airtime") > 0.0);
    let e = wasm::simulate(
        obj(&[("synthetic", 2.into()), ("prediction", "psychic".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("psychic"));
    let e = wasm::simulate(
        obj(&[("synthetic", 2.into()), ("model", "dr,kalman".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("unknown model 'kalman'"));
}

#[wasm_bindgen_test]
fn adr_crosses_the_boundary_and_reports_the_packets_per_data_rate() {
    let r = wasm::simulate(
        obj(&[
            ("synthetic", 4.into()),
            ("model", "3d-ctra".into()),
            ("adr", "lorawan".into()),
            ("adrHistory", 2.into()),
            ("sf", 12.into()),
            ("bw", 125.into()),
            ("series", true.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let config = get(&r, "config");
    assert_eq!(get(&config, "adr").as_string().as_deref(), Some("lorawan"));
    assert_eq!(num(&config, "adrHistory"), 2.0);
    let result = js_sys::Array::from(&get(&r, "results")).get(0);
    let uses = js_sys::Array::from(&get(&result, "dataRateUse"));
    let packets: f64 = uses.iter().map(|u| num(&u, "packets")).sum();
    assert_eq!(packets, num(&result, "packetsSent"));
    let e = wasm::simulate(
        obj(&[("synthetic", 4.into()), ("adr", "sometimes".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("sometimes"));
}

#[wasm_bindgen_test]
fn a_random_seed_comes_from_web_crypto_and_is_reported() {
    let run = || {
        let r = wasm::simulate(
            obj(&[
                ("synthetic", 2.into()),
                ("model", "dr".into()),
                ("seed", "random".into()),
            ]),
            JsValue::UNDEFINED,
        )
        .unwrap();
        num(&get(&r, "config"), "seed")
    };
    let (a, b) = (run(), run());
    assert_ne!(a, b);
    assert!((0.0..=9_007_199_254_740_991.0).contains(&a) && a.fract() == 0.0);
}

/// Nests `{zz: {zz: ...}}` `depth` levels deep.
fn deep(depth: usize) -> JsValue {
    let mut v: JsValue = js_sys::Object::new().into();
    for _ in 0..depth {
        v = obj(&[("zz", v)]);
    }
    v
}

#[wasm_bindgen_test]
fn a_deeply_nested_argument_throws_and_the_module_keeps_working() {
    let p = obj(&[
        ("sf", 7.into()),
        ("bw", 125.into()),
        ("payload", 9.into()),
        ("zz", deep(4000)),
    ]);
    let e = wasm::time_on_air(p).unwrap_err();
    assert!(error_message(e).contains("invalid parameters"));
    let ok = wasm::time_on_air(obj(&[
        ("sf", 7.into()),
        ("bw", 125.into()),
        ("payload", 12.into()),
        ("overhead", 0.into()),
    ]))
    .unwrap();
    assert!((num(&ok, "timeOnAir") - 0.041216).abs() < 1e-9);
}

#[wasm_bindgen_test]
fn a_progress_that_is_not_a_function_is_refused() {
    let e = wasm::simulate(obj(&[("synthetic", 3.into())]), 42.into()).unwrap_err();
    assert!(error_message(e).contains("progress must be a function"));
    assert!(wasm::simulate(obj(&[("synthetic", 3.into())]), JsValue::NULL).is_ok());
}

#[wasm_bindgen_test]
fn statistics_of_an_empty_sample_are_null_as_in_the_cli() {
    // 100 km: nothing arrives, so nothing is counted.
    let r = wasm::simulate(
        obj(&[
            ("synthetic", 3.into()),
            ("model", "dr".into()),
            ("distance", 100_000.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let first = js_sys::Array::from(&get(&r, "results")).get(0);
    let e3 = get(&first, "error3d");
    assert_eq!(num(&e3, "count"), 0.0);
    assert!(get(&e3, "mean").is_null());
    assert!(get(&first, "coverage95").is_null());
}

#[wasm_bindgen_test]
fn a_seed_javascript_cannot_hold_is_refused_up_front() {
    let e = wasm::simulate(
        obj(&[("synthetic", 3.into()), ("seed", 2f64.powi(60).into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("seed must be"));
}

#[wasm_bindgen_test]
fn swarm_runs_across_the_boundary_with_progress() {
    let calls = std::rc::Rc::new(std::cell::Cell::new(0u32));
    let seen = calls.clone();
    let f = wasm_bindgen::closure::Closure::<dyn FnMut(u32, u32)>::new(
        move |_done: u32, _total: u32| {
            seen.set(seen.get() + 1);
        },
    );
    let r = wasm::swarm(
        obj(&[
            ("drones", 4.into()),
            ("duration", 30.into()),
            ("channels", 1.into()),
            ("sfPlan", "fixed".into()),
        ]),
        f.as_ref().clone(),
    )
    .unwrap();
    assert!(
        calls.get() >= 2,
        "progress was called {} times",
        calls.get()
    );
    assert_eq!(js_sys::Array::from(&get(&r, "drones")).length(), 4);
    assert!((0.0..=1.0).contains(&num(&r, "collisionRate")));
    assert!(num(&r, "packetsSent") > 0.0);
    let e = wasm::swarm(obj(&[("drones", 501.into())]), JsValue::UNDEFINED).unwrap_err();
    assert!(error_message(e).contains("drones must be 1..500"));
}

#[wasm_bindgen_test]
fn a_swarm_progress_callback_that_returns_false_stops_the_swarm_there() {
    use std::cell::Cell;
    use std::rc::Rc;
    use wasm_bindgen::closure::Closure;
    let calls = Rc::new(Cell::new(0u32));
    let seen = Rc::clone(&calls);
    // Go on once (the loop's first stretch computed ahead), then stop.
    let cb = Closure::<dyn FnMut(u32, u32) -> bool>::new(move |_, _| {
        seen.set(seen.get() + 1);
        seen.get() < 2
    });
    let params = || {
        obj(&[
            ("drones", 40.into()),
            ("duration", 120.into()),
            ("sensorRate", 1.into()),
            ("step", 1.into()),
        ])
    };
    let e = wasm::swarm(params(), cb.as_ref().clone()).unwrap_err();
    assert_eq!(
        error_message(e),
        "the run was stopped by its progress callback"
    );
    assert_eq!(calls.get(), 2);
    // Any other answer goes on to the end.
    let on = Closure::<dyn FnMut(u32, u32) -> JsValue>::new(|_, _| JsValue::UNDEFINED);
    let r = wasm::swarm(params(), on.as_ref().clone()).unwrap();
    assert_eq!(js_sys::Array::from(&get(&r, "drones")).length(), 40);
}

#[wasm_bindgen_test]
fn gateways_cross_the_boundary_and_each_is_reported() {
    let gateways = js_sys::JSON::parse(
        r#"[{"east": 5000, "north": 0}, {"east": 0, "north": 0, "height": 30}]"#,
    )
    .unwrap();
    let r = wasm::simulate(
        obj(&[
            ("synthetic", 1.into()),
            ("model", "dr".into()),
            ("gateways", gateways),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let g: js_sys::Array = get(&r, "gateways").dyn_into().unwrap();
    assert_eq!(g.length(), 2);
    assert_eq!(num(&g.get(1), "height"), 30.0);
    let heard = num(&g.get(0), "heard") + num(&g.get(1), "heard");
    assert_eq!(heard - num(&r, "duplicates"), num(&r, "packetsReceived"));
    assert!(num(&r, "packetsReceived") > 0.0);
    let e = wasm::simulate(
        obj(&[
            ("synthetic", 1.into()),
            (
                "gateways",
                js_sys::JSON::parse(r#"[{"east": 1e9, "north": 0}]"#).unwrap(),
            ),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("gateway must be -100000..100000 m"));
}

#[wasm_bindgen_test]
fn limits_and_stations_come_from_the_core() {
    let limits: js_sys::Array = wasm::limits().unwrap().dyn_into().unwrap();
    let sf = limits
        .iter()
        .find(|o| get(o, "key").as_string().as_deref() == Some("sf"))
        .expect("sf is in the table");
    assert_eq!(
        (num(&sf, "min"), num(&sf, "max"), num(&sf, "default")),
        (7.0, 12.0, 7.0)
    );
    let all: js_sys::Array = wasm::stations_of(obj(&[("model", "all,imm".into())]))
        .unwrap()
        .dyn_into()
        .unwrap();
    let names: Vec<String> = all.iter().filter_map(|v| v.as_string()).collect();
    assert_eq!(names, ["dr", "ctra-plus", "3d-ctra", "imm"]);
    // The worker pool's groups: every station once, as the core splits them.
    let groups: js_sys::Array =
        wasm::split_stations(obj(&[("model", "all".into()), ("workers", 2.into())]))
            .unwrap()
            .dyn_into()
            .unwrap();
    let groups: Vec<Vec<String>> = groups
        .iter()
        .map(|g| {
            let g: js_sys::Array = g.dyn_into().unwrap();
            g.iter().filter_map(|v| v.as_string()).collect()
        })
        .collect();
    assert_eq!(groups, [vec!["dr", "ctra-plus"], vec!["3d-ctra"]]);
    let e = wasm::split_stations(obj(&[("model", "all".into())])).unwrap_err();
    assert!(error_message(e).contains("workers"));
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("spreadingFactor", 9.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("unknown setting 'spreadingFactor'"));
}

#[wasm_bindgen_test]
fn a_nan_names_its_key_and_messages_carry_no_control_characters() {
    let e = wasm::simulate(
        obj(&[("synthetic", 1.into()), ("sf", f64::NAN.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    let m = error_message(e);
    assert!(m.contains("sf is not a number"), "{m}");
    let e = wasm::simulate(
        obj(&[(
            "sample",
            format!("\u{1b}]0;owned\u{7}{}", "x".repeat(300)).into(),
        )]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    let m = error_message(e);
    assert!(!m.chars().any(char::is_control), "{m:?}");
    assert!(m.len() < 300, "{m}");
}

#[wasm_bindgen_test]
fn a_large_csv_is_read_with_progress_and_then_simulated_from_the_cache() {
    let mut text = String::from("t,x,y,z\n");
    for i in 0..3000 {
        let t = f64::from(i) * 0.1;
        text += &format!("{t},{},{},{}\n", 3.0 * t, (0.1 * t).sin() * 40.0, 20.0);
    }
    let calls = std::rc::Rc::new(std::cell::RefCell::new(Vec::<(f64, f64)>::new()));
    let seen = calls.clone();
    let progress = wasm_bindgen::closure::Closure::<dyn FnMut(f64, f64)>::new(move |d, t| {
        seen.borrow_mut().push((d, t));
    });
    let r = wasm::load_csv(
        obj(&[
            ("trajectory", text.clone().into()),
            ("trajectoryName", "big.csv".into()),
        ]),
        progress.as_ref().clone(),
    )
    .unwrap();
    assert_eq!(num(&r, "rows"), 3000.0);
    let calls = calls.borrow();
    assert!(calls.len() >= 50, "{} progress calls", calls.len());
    assert!(calls.windows(2).all(|w| w[1].0 > w[0].0));
    let sim = wasm::simulate(
        obj(&[
            ("trajectory", text.into()),
            ("trajectoryName", "big.csv".into()),
            ("model", "dr".into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    assert_eq!(
        get(&get(&sim, "config"), "trajectory")
            .as_string()
            .as_deref(),
        Some("big.csv")
    );
    assert!(num(&sim, "packetsReceived") > 10.0);
    let e = wasm::load_csv(
        obj(&[("trajectory", "t,x\n1,2\n".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("no 'y' column"));
}

#[wasm_bindgen_test]
fn a_csv_reading_whose_progress_returns_false_stops_and_is_read_again_whole() {
    use std::cell::Cell;
    use std::rc::Rc;
    use wasm_bindgen::closure::Closure;
    let mut text = String::from("t,x,y,z\n");
    for i in 0..2000 {
        text += &format!("{},{},0,20\n", f64::from(i) * 0.1, 0.5 * f64::from(i));
    }
    let calls = Rc::new(Cell::new(0u32));
    let seen = Rc::clone(&calls);
    let stop = Closure::<dyn FnMut(u32, u32) -> bool>::new(move |_, _| {
        seen.set(seen.get() + 1);
        seen.get() < 5
    });
    let params = || obj(&[("trajectory", text.clone().into())]);
    let e = wasm::load_csv(params(), stop.as_ref().clone()).unwrap_err();
    assert_eq!(
        error_message(e),
        "the run was stopped by its progress callback"
    );
    assert_eq!(calls.get(), 5, "asked nothing after the stop");
    // Nothing of the stopped reading was kept: the next reads the file again, with its progress.
    let again = Rc::new(Cell::new(0u32));
    let count = Rc::clone(&again);
    let on = Closure::<dyn FnMut(u32, u32) -> JsValue>::new(move |_, _| {
        count.set(count.get() + 1);
        JsValue::UNDEFINED
    });
    let r = wasm::load_csv(params(), on.as_ref().clone()).unwrap();
    assert_eq!(num(&r, "rows"), 2000.0);
    assert!(again.get() >= 50, "{} progress calls", again.get());
}

#[wasm_bindgen_test]
fn seeds_give_each_result_an_interval_and_a_swarm_refuses_them() {
    let one = wasm::simulate(
        obj(&[("synthetic", 2.into()), ("model", "dr".into())]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let first = js_sys::Array::from(&get(&one, "results")).get(0);
    assert!(get(&first, "ci95").is_null(), "one run: no interval");
    let r = wasm::simulate(
        obj(&[
            ("synthetic", 2.into()),
            ("model", "dr".into()),
            ("seeds", 3.into()),
        ]),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let result = js_sys::Array::from(&get(&r, "results")).get(0);
    let ci = get(&result, "ci95");
    assert_eq!(num(&ci, "runs"), 3.0);
    let p75 = numbers(&ci, "p75");
    assert!(p75[0] <= p75[1]);
    let e = wasm::swarm(
        obj(&[("drones", 2.into()), ("seeds", 2.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("a swarm runs one seed"));
    let e = wasm::simulate(
        obj(&[("synthetic", 2.into()), ("seeds", 0.into())]),
        JsValue::UNDEFINED,
    )
    .unwrap_err();
    assert!(error_message(e).contains("seeds must be 1..100"));
}

#[wasm_bindgen_test]
fn pooling_stations_run_apart_gives_the_totals_of_one_run_of_them_all() {
    // At 3 km packets are lost, and each station's drone loses its own.
    let settings = |model: &str| {
        obj(&[
            ("synthetic", 2.into()),
            ("model", model.into()),
            ("distance", 3000.into()),
        ])
    };
    let together = wasm::simulate(settings("all"), JsValue::UNDEFINED).unwrap();
    // The page's pool: each station on a worker of its own, then their results pooled.
    let apart = js_sys::Array::new();
    for model in ["dr", "ctra-plus", "3d-ctra"] {
        let one = wasm::simulate(settings(model), JsValue::UNDEFINED).unwrap();
        apart.push(&js_sys::Array::from(&get(&one, "results")).get(0));
    }
    let pooled = wasm::pool_delivery(obj(&[("results", apart.into())])).unwrap();
    for key in [
        "packetsSent",
        "packetsReceived",
        "deliveryRatio",
        "duplicates",
    ] {
        assert_eq!(num(&pooled, key), num(&together, key), "{key}");
    }
    assert!(num(&pooled, "packetsReceived") < num(&pooled, "packetsSent"));
    let heard = |r: &JsValue| num(&js_sys::Array::from(&get(r, "gateways")).get(0), "heard");
    assert_eq!(heard(&pooled), heard(&together));
    let e = wasm::pool_delivery(obj(&[("results", 3.into())])).unwrap_err();
    assert!(error_message(e).contains("invalid parameters"));
}

#[wasm_bindgen_test]
fn the_delivery_spread_of_results_run_apart_is_the_one_the_core_finds_in_one_run() {
    // The real flight at 3.3 km, SF7 / 125 kHz, 16 seeds: DR's frames arrive more often than the
    // richer stations' (docs/paper-reproduction.md).
    let settings = |model: &str| {
        obj(&[
            ("sample", "canberra".into()),
            ("model", model.into()),
            ("sf", 7.into()),
            ("bw", 125.into()),
            ("distance", 3300.into()),
            ("seeds", 16.into()),
            ("prediction", "bounded".into()),
        ])
    };
    let apart = js_sys::Array::new();
    for model in ["dr", "ctra-plus"] {
        let one = wasm::simulate(settings(model), JsValue::UNDEFINED).unwrap();
        apart.push(&js_sys::Array::from(&get(&one, "results")).get(0));
    }
    let spread = wasm::delivery_spread(obj(&[("results", apart.clone().into())])).unwrap();
    assert_eq!(get(&spread, "highest").as_string().as_deref(), Some("dr"));
    assert_eq!(
        get(&spread, "lowest").as_string().as_deref(),
        Some("ctra-plus")
    );
    assert!(num(&spread, "highestRatio") - num(&spread, "lowestRatio") > 0.05);
    // One station alone has nothing to differ from; an unknown station is refused.
    let alone = js_sys::Array::of1(&apart.get(0));
    assert!(wasm::delivery_spread(obj(&[("results", alone.into())]))
        .unwrap()
        .is_null());
    let odd = obj(&[
        ("model", "kalman".into()),
        ("packetsSent", 1.into()),
        ("packetsReceived", 1.into()),
        ("deliveryRatio", 1.into()),
        ("duplicates", 0.into()),
        ("gateways", js_sys::Array::new().into()),
    ]);
    let e = wasm::delivery_spread(obj(&[("results", js_sys::Array::of1(&odd).into())]));
    assert!(e.is_err());
}

#[wasm_bindgen_test]
fn stations_run_apart_are_paired_with_the_lowest_as_one_run_pairs_them() {
    let settings = |model: &str| {
        obj(&[
            ("synthetic", 2.into()),
            ("model", model.into()),
            ("seeds", 6.into()),
        ])
    };
    let together = wasm::simulate(settings("dr,ctra-plus,3d-ctra"), JsValue::UNDEFINED).unwrap();
    let together = js_sys::Array::from(&get(&together, "results"));
    let apart = js_sys::Array::new();
    for model in ["dr", "ctra-plus", "3d-ctra"] {
        let one = wasm::simulate(settings(model), JsValue::UNDEFINED).unwrap();
        let result = js_sys::Array::from(&get(&one, "results")).get(0);
        // Alone, a station has nothing to be compared with.
        assert!(get(&result, "p75VsLowest").is_null());
        apart.push(&result);
    }
    let paired =
        js_sys::Array::from(&wasm::versus_lowest(obj(&[("results", apart.into())])).unwrap());
    let mut nulls = 0;
    for i in 0..3 {
        let (p, t) = (paired.get(i), get(&together.get(i), "p75VsLowest"));
        if t.is_null() {
            nulls += 1;
            assert!(p.is_null(), "the lowest is the lowest apart too");
            continue;
        }
        assert_eq!(get(&p, "lowest").as_string(), get(&t, "lowest").as_string());
        for key in ["ratio", "runs"] {
            assert_eq!(num(&p, key), num(&t, key), "{key}");
        }
        let interval = |v: &JsValue| js_sys::Array::from(&get(v, "interval")).to_vec();
        assert_eq!(format!("{:?}", interval(&p)), format!("{:?}", interval(&t)));
    }
    assert_eq!(nulls, 1);
    let e = wasm::versus_lowest(obj(&[("results", 3.into())])).unwrap_err();
    assert!(error_message(e).contains("invalid parameters"));
}

#[wasm_bindgen_test]
fn the_series_arrive_as_float64_arrays_holding_the_cores_numbers() {
    let settings = serde_json::json!({"synthetic": 2, "model": "dr,3d-ctra", "series": true});
    let r = wasm::simulate(
        js_sys::JSON::parse(&settings.to_string()).unwrap(),
        JsValue::UNDEFINED,
    )
    .unwrap();
    let scenario: loratrack::Scenario = serde_json::from_value(settings).unwrap();
    let core = loratrack::api::simulate(&mut loratrack::Simulator::new(), &scenario)
        .unwrap()
        .series
        .unwrap();
    let numbers = |v: &JsValue, key: &str| {
        get(v, key)
            .dyn_into::<js_sys::Float64Array>()
            .unwrap_or_else(|_| panic!("{key} is not a Float64Array"))
            .to_vec()
    };
    let series = get(&r, "series");
    assert_eq!(get(&series, "flight").as_string(), Some(core.flight));
    assert_eq!(
        [
            numbers(&series, "t"),
            numbers(&series, "x"),
            numbers(&series, "y"),
            numbers(&series, "z")
        ],
        [core.t, core.x, core.y, core.z]
    );
    let models = js_sys::Array::from(&get(&series, "models"));
    assert_eq!(models.length() as usize, core.models.len());
    for (m, c) in models.iter().zip(&core.models) {
        assert_eq!(
            get(&m, "model").as_string().as_deref(),
            Some(c.model.name())
        );
        for (key, expected) in [
            ("t", &c.t),
            ("error3d", &c.error3d),
            ("bound95", &c.bound95),
            ("x", &c.x),
            ("y", &c.y),
            ("z", &c.z),
            ("arrivals", &c.arrivals),
            ("lost", &c.lost),
        ] {
            assert_eq!(&numbers(&m, key), expected, "{key}");
        }
        // The data rates, which may be null, stay a plain array.
        let rates = get(&m, "arrivalDr");
        assert!(js_sys::Array::is_array(&rates));
        assert_eq!(
            js_sys::Array::from(&rates).length() as usize,
            c.arrival_dr.len()
        );
    }
}

#[wasm_bindgen_test]
fn the_command_line_of_a_page_run_names_its_settings_and_its_files() {
    let line = |params: JsValue, command: JsValue| {
        wasm::command_line(params, command)
            .map(|v| v.as_string().expect("a string"))
            .map_err(error_message)
    };
    let page = obj(&[
        ("trajectoryName", "my flight.csv".into()),
        ("planName", "survey.plan".into()),
        ("model", "3d-ctra,mission".into()),
        ("sf", 10.into()),
        (
            "gateways",
            js_sys::JSON::parse(r#"[{"east": 500, "north": -20}]"#).unwrap(),
        ),
    ]);
    assert_eq!(
        line(page, JsValue::UNDEFINED).unwrap(),
        "loratrack simulate --trajectory 'my flight.csv' --plan survey.plan --model 3d-ctra,mission --sf 10 --gateway 500,-20"
    );
    let crowd = obj(&[("drones", 72.into()), ("sfPlan", "fixed".into())]);
    assert_eq!(
        line(crowd, "swarm".into()).unwrap(),
        "loratrack swarm --drones 72 --sf-plan fixed"
    );
    let e = line(obj(&[("sf", 9.into())]), "sweep".into()).unwrap_err();
    assert!(e.contains("'simulate' or 'swarm'"), "{e}");
    let e = line(obj(&[("spreadingFactor", 9.into())]), JsValue::UNDEFINED).unwrap_err();
    assert!(e.contains("unknown setting 'spreadingFactor'"), "{e}");
    // A seed drawn for the command would not be the run's.
    let e = line(obj(&[("seed", "random".into())]), JsValue::UNDEFINED).unwrap_err();
    assert!(e.contains("config.seed"), "{e}");
}
