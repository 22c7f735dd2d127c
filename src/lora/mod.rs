//! The LoRa link: time on air, duty cycle, channel (path loss, sensitivity, shadowing).
//!
//! Sources: Semtech SX1276 datasheet §4.1.1.7 (time on air), ETSI EN 300 220 / LoRaWAN Regional
//! Parameters RP002 (EU868 duty cycle), and the ns-3 `lorawan` module used in the paper's
//! evaluation (channel defaults; SPEC §6).

mod adr;
mod airtime;
mod channel;
mod data_rate;
mod duty_cycle;
mod error;
mod gateway;
mod interference;
mod shadowing;
mod snr;

pub use adr::{
    expected_age_cost, AdrDevice, AdrMode, AdrNetwork, AdrParams, LinkAdrReq, LorawanAdr,
    TrackingAdr, UplinkFrame, UplinkReport, ADR_ACK_DELAY, ADR_ACK_LIMIT, DEFAULT_ADR_HISTORY,
    DEFAULT_ADR_MARGIN_DB, ERROR_GROWTH, GATEWAY_TX_POWER_DBM, MAX_POWER_REDUCTION_DB,
    RECEIVE_DELAY1_S, TRACKING_HYSTERESIS, TRACKING_WINDOW, TX_POWER_STEP_DB,
};
pub use airtime::{
    time_on_air, Airtime, Bandwidth, CodingRate, LdroMode, LoraParams, SpreadingFactor,
    LORAWAN_OVERHEAD_BYTES,
};
pub use channel::{Channel, ChannelParams};
pub use data_rate::DataRate;
pub use duty_cycle::{
    min_interval, DutyCycle, DutyCycleMode, SubBand, MAX_BURST, MIN_DUTY_CYCLE,
    TTN_FAIR_USE_SECONDS_PER_DAY,
};
pub use error::LoraError;
pub use gateway::{Gateway, Outcome, Uplink, SX1301_DEMODULATORS};
pub use interference::{
    sum_dbm, survives, InterferenceModel, CAPTURE_THRESHOLD_DB, INTER_SF_SIR_DB,
};
pub use shadowing::Shadowing;
pub use snr::{demodulation_floor_db, noise_floor_dbm, snr_db, NOISE_FIGURE_DB};
