//! The LoRa link: time on air, duty cycle, channel (path loss, sensitivity, shadowing).
//!
//! Sources: Semtech SX1276 datasheet §4.1.1.7 (time on air), ETSI EN 300 220 / LoRaWAN Regional
//! Parameters RP002 (EU868 duty cycle), and the ns-3 `lorawan` module used in the paper's
//! evaluation (channel defaults; reference §6).

mod adr;
mod airtime;
mod channel;
mod data_rate;
mod downlink;
mod duty_cycle;
mod energy;
mod error;
mod interference;
pub mod lbt;
mod reception;
mod region;
mod shadowing;
mod shadowing_field;
mod snr;

pub use adr::{
    expected_age_cost, tracking_ack_limits, AckLimits, AdrDevice, AdrMode, AdrNetwork, AdrParams,
    LinkAdrReq, LorawanAdr, TrackingAdr, UplinkFrame, UplinkReport, ADR_ACK_DELAY, ADR_ACK_LIMIT,
    DEFAULT_ADR_HISTORY, DEFAULT_ADR_MARGIN_DB, ERROR_GROWTH, GATEWAY_TX_POWER_DBM,
    LORAWAN_ADR_MAX_DR, MAX_POWER_REDUCTION_DB, RECEIVE_DELAY1_S, TRACKING_HYSTERESIS,
    TRACKING_WINDOW, TX_POWER_STEP_DB,
};
pub use airtime::{
    time_on_air, Airtime, Bandwidth, CodingRate, LdroMode, LoraParams, SpreadingFactor,
    LORAWAN_OVERHEAD_BYTES,
};
pub use channel::{Channel, ChannelParams};
pub use data_rate::DataRate;
pub use downlink::{
    downlink_time_on_air, Window, ACK_DOWNLINK_BYTES, ADR_DOWNLINK_BYTES, RECEIVE_DELAY2_S,
};
pub use duty_cycle::{
    min_interval, DutyCycle, DutyCycleMode, FairUse, SubBand, MAX_BURST, MIN_DUTY_CYCLE,
    TTN_FAIR_USE_SECONDS_PER_DAY,
};
pub use energy::{
    empty_window_s, rx_current_ma, tx_current_ma, UplinkActivity, RX_WINDOW_SYMBOLS,
    SX1276_RX_CURRENT_125_MA, SX1276_RX_CURRENT_500_MA, SX1276_SLEEP_CURRENT_MA,
    SX1276_TX_CURRENT_MA,
};
pub use error::LoraError;
pub use interference::{
    sum_dbm, survives, InterferenceModel, CAPTURE_THRESHOLD_DB, INTER_SF_SIR_DB,
};
pub use lbt::ChannelAccess;
pub use reception::{audible, decide, resolve, Outcome, Receiver, Uplink, SX1301_DEMODULATORS};
pub use region::{Plan, PlanRate, Region, RegionError};
pub use shadowing::Shadowing;
pub use shadowing_field::{ShadowingField, ShadowingModel, FIELD_FEATURES};
pub use snr::{demodulation_floor_db, noise_floor_dbm, snr_db, NOISE_FIGURE_DB};
