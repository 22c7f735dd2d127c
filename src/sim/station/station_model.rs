//! What the station runs: one of the paper's motion models, or the IMM mixture of all three.

use crate::models::{ModelError, ModelKind};
use core::fmt;
use core::str::FromStr;
use serde::{Serialize, Serializer};

/// The station's predictor, chosen with `--model`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum StationModel {
    /// One of the paper's models; the drone sends that model's payload.
    Single(ModelKind),
    /// An Interacting Multiple Model station over DR, CTRA+ and 3D-CTRA
    /// ([`Imm`](super::Imm)); the drone sends the 12-byte 3D-CTRA payload.
    Imm,
    /// The mission-aware station ([`MissionStation`](super::MissionStation)): along the drone's
    /// plan between packets, a bounded 3D-CTRA off it; the drone sends the 3D-CTRA payload.
    Mission,
}

impl StationModel {
    /// The paper's three models, in its order (`--model all`).
    pub const PAPER: [StationModel; 3] = [
        StationModel::Single(ModelKind::Dr),
        StationModel::Single(ModelKind::CtraPlus),
        StationModel::Single(ModelKind::Ctra3d),
    ];

    /// Every station, in the order the CLI's help lists them.
    pub const ALL: [StationModel; 5] = [
        StationModel::Single(ModelKind::Dr),
        StationModel::Single(ModelKind::CtraPlus),
        StationModel::Single(ModelKind::Ctra3d),
        StationModel::Imm,
        StationModel::Mission,
    ];

    /// Every station's CLI/JS name, as a refusal lists them: "dr, ctra-plus, 3d-ctra, imm, mission".
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// The model whose state the drone filters and sends.
    pub fn sent_model(self) -> ModelKind {
        match self {
            StationModel::Single(m) => m,
            StationModel::Imm | StationModel::Mission => ModelKind::Ctra3d,
        }
    }

    /// Payload bytes per packet (9, 11 or 12).
    pub fn payload_bytes(self) -> usize {
        self.sent_model().payload_bytes()
    }

    /// The CLI/JS name: `dr`, `ctra-plus`, `3d-ctra`, `imm`, `mission`.
    pub fn name(self) -> &'static str {
        match self {
            StationModel::Single(m) => m.name(),
            StationModel::Imm => "imm",
            StationModel::Mission => "mission",
        }
    }

    /// The display name: DR, CTRA+, 3D-CTRA, IMM, Mission.
    pub fn label(self) -> &'static str {
        match self {
            StationModel::Single(m) => m.label(),
            StationModel::Imm => "IMM",
            StationModel::Mission => "Mission",
        }
    }
}

impl From<ModelKind> for StationModel {
    fn from(m: ModelKind) -> Self {
        StationModel::Single(m)
    }
}

impl fmt::Display for StationModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Serialize for StationModel {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl FromStr for StationModel {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, ModelError> {
        if s.eq_ignore_ascii_case("imm") {
            return Ok(StationModel::Imm);
        }
        if s.eq_ignore_ascii_case("mission") {
            return Ok(StationModel::Mission);
        }
        s.parse().map(StationModel::Single)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_station_parses_from_its_name() {
        for m in StationModel::ALL {
            assert_eq!(m.name().parse::<StationModel>().unwrap(), m);
        }
        assert_eq!(
            StationModel::names(),
            "dr, ctra-plus, 3d-ctra, imm, mission"
        );
    }

    #[test]
    fn imm_sends_the_3d_ctra_payload() {
        assert_eq!(StationModel::Imm.payload_bytes(), 12);
        assert_eq!(StationModel::Imm.sent_model(), ModelKind::Ctra3d);
    }

    #[test]
    fn names_round_trip() {
        for m in StationModel::PAPER
            .into_iter()
            .chain([StationModel::Imm, StationModel::Mission])
        {
            assert_eq!(m.name().parse::<StationModel>().unwrap(), m);
        }
        assert!("kalman".parse::<StationModel>().is_err());
    }
}
