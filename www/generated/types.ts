// Generated from the Rust types by `UPDATE_TYPES=1 cargo test --lib typescript` (src/typescript.rs).
// Do not edit: a test fails when this file differs from what the Rust source generates.

/** A motion model: what predict, encode and decode take. */
export type MotionModelName = 'dr' | 'ctra-plus' | '3d-ctra';
/** A station: one motion model, the IMM mixture of the three, or the mission-aware station. */
export type ModelName = MotionModelName | 'imm' | 'mission';
/** `all` (the paper's three), one station, a comma list such as `dr,3d-ctra,imm`, or an array. */
export type ModelChoice = ModelName | 'all' | (string & {}) | ModelName[];

export type ModelKind = "dr" | "ctra-plus" | "3d-ctra";

export type LdroMode = "auto" | "on" | "off";

export type Prediction = "paper" | "bounded";

export type HeadingNoise = "fixed" | "adaptive";

export type PlanPace = "plan" | "packet";

export type SenderKind = "periodic" | "error";

export type ChannelSense = "off" | "cad";

export type DutyCycleMode = "per-packet" | "budget";

export type PayloadChoice = "full" | "lean";

export type AdrMode = "off" | "lorawan" | "tracking";

export type Region = "eu868" | "us915" | "au915" | "as923" | "in865";

export type PlanRate = { 
/**
 * DR index in the plan.
 */
dr: number, 
/**
 * Spreading factor.
 */
sf: number, 
/**
 * Bandwidth.
 */
bw: number, 
/**
 * Largest FRMPayload, bytes; `None` (`null`) where the plan bars the rate.
 */
maxPayload: number | null, };

export type Plan = { 
/**
 * The CLI/JS name.
 */
region: Region, 
/**
 * The name people write.
 */
label: string, 
/**
 * Uplink data rates, slowest first.
 */
rates: Array<PlanRate>, 
/**
 * Longest time on air of one uplink, s (`null`: no limit).
 */
dwellTime: number | null, 
/**
 * Duty cycle of the uplink channels (`null`: none; the sending interval is a setting).
 */
dutyCycle: number | null, 
/**
 * Uplink channels hopped over.
 */
channels: number, 
/**
 * Largest transmit power (EIRP), dBm.
 */
maxEirpDbm: number, 
/**
 * Whether LoRa outside the data rates is allowed (EU868).
 */
rawLora: boolean, };

export type FairUse = "off" | "ttn";

export type ShadowingModel = "path" | "field";

export type ChannelAccess = "duty-cycle" | "lbt";

export type SfPlan = "spread" | "fixed";

export type Schedule = "aloha" | "slotted";

export type GatewaySite = { 
/**
 * Metres east of the origin.
 */
east: number, 
/**
 * Metres north of the origin.
 */
north: number, 
/**
 * Antenna height, m; `None` for the `gatewayHeight` setting.
 */
height?: number, };

export type FlightSettings = { 
/**
 * Synthetic flight(s): `all` or 1..30.
 */
synthetic?: number | 'all', 
/**
 * A bundled real flight: `canberra`.
 */
sample?: string, };

export type StationSettings = { 
/**
 * Which station(s): `all`, or a comma list of `dr`, `ctra-plus`, `3d-ctra`, `imm`,
 * `mission`.
 */
model: ModelChoice, 
/**
 * The station's prediction between packets: `paper` (default) or `bounded`.
 */
prediction: Prediction, 
/**
 * The bounded station's direct noise on heading and pitch: `fixed` (default) or `adaptive`.
 */
headingNoise: HeadingNoise, 
/**
 * Station prediction step T, s.
 */
step: number, 
/**
 * Tilt-rate decay per station step.
 */
eta: number, 
/**
 * How the mission station paces the drone along its plan.
 */
planPace: PlanPace, 
/**
 * The mission station's off-plan distance, m.
 */
planTolerance: number, };

export type Sending = { 
/**
 * The sending policy.
 */
sender: SenderKind, 
/**
 * Error-triggered threshold, m.
 */
threshold: number, 
/**
 * Error-triggered heartbeat, s.
 */
maxInterval: number, 
/**
 * Error-triggered sending: whether the drone listens to its channel and sends less where
 * it is crowded ([`ChannelSense`]).
 */
channelSense: ChannelSense, 
/**
 * The duty-cycle rule.
 */
dutyCycleMode: DutyCycleMode, 
/**
 * Which payload each packet takes: `full` (the model's own, the paper) or `lean`.
 */
payload: PayloadChoice, 
/**
 * Budget capacity, packets.
 */
burst: number, };

export type RadioSettings = { 
/**
 * Spreading factor 7..12 (with ADR: the start).
 */
sf: number, 
/**
 * Bandwidth, kHz.
 */
bw: number, 
/**
 * Coding rate index 1..4.
 */
cr: number, 
/**
 * MAC overhead, bytes (LoRaWAN 13; the paper's Table II: 0).
 */
overhead: number, 
/**
 * Duty-cycle limit, fraction.
 */
dutyCycle: number, 
/**
 * Transmit power, dBm.
 */
txPower: number, };

export type ChannelSettings = { 
/**
 * simulate: distance from the flight's first point to the default gateway (refused where
 * `gateways` are listed, which replace it); swarm: every drone's starting distance from the
 * centre, m.
 */
distance: number, 
/**
 * Path-loss exponent.
 */
pathLossExponent: number, 
/**
 * Shadowing standard deviation, dB (0: off).
 */
shadowing: number, 
/**
 * Whether shadowing varies along the drone's path (the default) or is fixed in space.
 */
shadowingModel: ShadowingModel, 
/**
 * Antenna height of every gateway not given its own, m.
 */
gatewayHeight: number, };

export type NetworkSettings = { 
/**
 * The gateways; empty for the one default gateway (simulate: `distance` m east of the
 * flight's first point; swarm: at the centre).
 */
gateways: Array<GatewaySite>, 
/**
 * Uplink channels: 1, or the plan's (the default, when unset).
 */
channels?: number, 
/**
 * Same-SF capture at 6 dB (off: every same-SF overlap is fatal).
 */
capture: boolean, 
/**
 * Inter-SF interference by the rejection matrix (off: SFs are orthogonal).
 */
interSf: boolean, 
/**
 * Adaptive data rate: `off`, `lorawan` or `tracking`.
 */
adr: AdrMode, 
/**
 * LoRaWAN ADR's device margin, dB.
 */
adrMargin: number, 
/**
 * LoRaWAN ADR's history, uplinks.
 */
adrHistory: number, };

export type DroneSettings = { 
/**
 * Sensor and filter rate, Hz.
 */
sensorRate: number, 
/**
 * Process noise q of Q = q·I (drone and station).
 */
q: number, 
/**
 * The vehicle: `auto` (default: a QGroundControl `.plan`'s `vehicleType` or a CSV plan's
 * `# vehicle:` line, else a multicopter), `multicopter` or `fixed-wing`.
 */
vehicle: VehicleChoice, };

export type AccessSettings = { 
/**
 * The regional plan.
 */
region: Region, 
/**
 * Where the plan has no duty cycle: seconds between uplink starts.
 */
interval?: number, 
/**
 * How a drone earns the right to send: the plan's duty cycle, or listen-before-talk.
 */
access: ChannelAccess, 
/**
 * A network's fair-use policy: `off` or `ttn`.
 */
fairUse: FairUse, 
/**
 * The longest random delay before each uplink, s.
 */
jitter?: number, 
/**
 * The largest clock error, ppm.
 */
clockDrift?: number, 
/**
 * How a swarm's drones share the air: `aloha` or `slotted`.
 */
schedule: Schedule, };

export type SwarmSettings = { 
/**
 * Number of drones.
 */
drones: number, 
/**
 * Seconds of chained synthetic flight per drone (when no flight is chosen).
 */
duration: number, 
/**
 * How SFs are shared out.
 */
sfPlan: SfPlan, };

export type RunSettings = { 
/**
 * Seed of every random draw; `"random"` draws one ([`random_seed`]), which the echo gives.
 */
seed: number, 
/**
 * How many seeds `simulate` runs (`seed`, `seed + 1`, …), pooled, with 95 % intervals
 * (`docs/reference.md` §12); a swarm runs one.
 */
seeds: number, 
/**
 * Include time series of the first flight (simulate).
 */
series: boolean, };

export type Scenario = FlightSettings & StationSettings & Sending & RadioSettings & ChannelSettings & NetworkSettings & DroneSettings & AccessSettings & SwarmSettings & RunSettings;

export type Summary = { 
/**
 * Arithmetic mean.
 */
mean: number | null, 
/**
 * Median.
 */
p50: number | null, 
/**
 * 75th percentile (the paper's headline statistic).
 */
p75: number | null, 
/**
 * 95th percentile.
 */
p95: number | null, 
/**
 * Largest error.
 */
max: number | null, 
/**
 * Number of samples.
 */
count: number, };

export type WholeFlightError = { 
/**
 * Share of the evaluation times (every T over the flights) at which the station had
 * received a packet, 0–1 (`null` when there were none at all).
 */
tracked: number | null, 
/**
 * Median over the whole flight time, m (`null` when half of it or more was untracked).
 */
p50: number | null, 
/**
 * 75th percentile over the whole flight time, m (`null` when a quarter or more was
 * untracked).
 */
p75: number | null, 
/**
 * 95th percentile over the whole flight time, m (`null` when 5 % or more was untracked).
 */
p95: number | null, 
/**
 * Whether the untracked time is worth saying beside the errors: `tracked` in whole percent
 * is below [`TRACKED_IN_FULL_PERCENT`] (or nothing was evaluated). The CLI's line under its
 * table and the page's notes follow it, so that both say it for the same runs.
 */
partlyTracked: boolean, };

export type Caveats = { 
/**
 * Fewer than [`FEW_PACKETS`] packets received.
 */
fewPackets: boolean, 
/**
 * Error-triggered sending, more than [`SILENCE_LOSS`] of its packets lost.
 */
silenceAfterLoss: boolean, 
/**
 * Received packets that carried a value beyond its payload field's range, sent as the
 * range's edge ([`SaturatedFields`]; the payload is sized for a quadcopter, reference §5):
 * the station started from a state other than the drone's estimate.
 */
saturatedPackets: number, 
/**
 * The fields those packets saturated, in state order (empty when none did).
 */
saturated: string[], };

export type DeliverySpread = { 
/**
 * The station whose packets arrived least often.
 */
lowest: ModelName, 
/**
 * Its delivery ratio, 0..1.
 */
lowestRatio: number, 
/**
 * The station whose packets arrived most often.
 */
highest: ModelName, 
/**
 * Its delivery ratio, 0..1.
 */
highestRatio: number, };

export type Intervals = { 
/**
 * Independent runs resampled (flights × seeds).
 */
runs: number, 
/**
 * Of the mean.
 */
mean: [number, number], 
/**
 * Of the median.
 */
p50: [number, number], 
/**
 * Of the 75th percentile.
 */
p75: [number, number], 
/**
 * Of the 95th percentile.
 */
p95: [number, number], 
/**
 * Of the largest error.
 */
max: [number, number], };

export type VersusLowest = { 
/**
 * The station with the lowest p75.
 */
lowest: ModelName, 
/**
 * p75 / the lowest station's p75, each over every run pooled (≥ 1).
 */
ratio: number, 
/**
 * 95 % interval of the ratio, every run resampled for both stations at once: wholly
 * above 1 where the runs tell the two apart.
 */
interval: [number, number], 
/**
 * Runs resampled (flights × seeds).
 */
runs: number, };

export type Draws = { 
/**
 * The seed the draws were made from (the run's own).
 */
seed: number, 
/**
 * Runs drawn from (flights × seeds), runs without errors included.
 */
runs: number, 
/**
 * The p75 of each draw, m; `null` (NaN) where a draw holds none of the station's errors.
 */
p75: (number | null)[], 
/**
 * The p95 of each draw, m, likewise.
 */
p95: (number | null)[], };

export type Boxplot = { 
/**
 * Lower whisker.
 */
whiskerLow: number | null, 
/**
 * First quartile.
 */
q1: number | null, 
/**
 * Median.
 */
median: number | null, 
/**
 * Third quartile.
 */
q3: number | null, 
/**
 * Upper whisker.
 */
whiskerHigh: number | null, 
/**
 * Samples beyond the whiskers.
 */
outliers: number, 
/**
 * Number of samples.
 */
count: number, };

export type Boxplots = { 
/**
 * 3D error.
 */
error3d: Boxplot, 
/**
 * |x error|.
 */
errorX: Boxplot, 
/**
 * |y error|.
 */
errorY: Boxplot, 
/**
 * |z error|.
 */
errorZ: Boxplot, };

export type DataRateUse = { 
/**
 * EU868 data rate index (`null` when the SF and bandwidth form none, e.g. SF8 at 500 kHz).
 */
dr: number | null, 
/**
 * Spreading factor.
 */
sf: number, 
/**
 * Bandwidth, kHz.
 */
bw: number, 
/**
 * Packets sent at it.
 */
packets: number, 
/**
 * Of those, received.
 */
received: number, 
/**
 * Time on air of one packet at it, s: its longest (with `--payload lean` some are shorter).
 */
timeOnAir: number, 
/**
 * The duty-cycle interval after that longest packet, s (reference §6.1): with ADR each
 * rate's own, where the result's `interval` is the starting rate's.
 */
interval: number, };

export type FrameTiming = { 
/**
 * Time on air, s.
 */
timeOnAir: number, 
/**
 * The shortest interval the duty cycle allows after it, s.
 */
interval: number, };

export type GatewayReport = { 
/**
 * Metres east of the scenario's origin.
 */
east: number, 
/**
 * Metres north of the scenario's origin.
 */
north: number, 
/**
 * Antenna height, m.
 */
height: number, 
/**
 * Uplinks it received.
 */
heard: number, 
/**
 * Uplinks only it received (what the network would lose without it).
 */
onlyHeard: number, 
/**
 * ADR downlinks it sent.
 */
downlinksSent: number, 
/**
 * Downlinks the network server wanted to send through it but its duty cycle forbade in
 * both receive windows.
 */
downlinksDropped: number, 
/**
 * Downlinks the network server held back for a later uplink: its duty cycle forbade RX1,
 * and the ADR keeps its answers out of RX2 while the gateway's other devices are expected
 * on air meanwhile (`AdrNetwork::spares_the_gateway`; the tracking-aware ADR, reference
 * §6.5). Always 0 under LoRaWAN ADR, whose server uses RX2 whenever RX1 is not free.
 */
downlinksHeldBack: number, 
/**
 * Uplinks it would have had to hear while it transmitted a downlink, and so lost (a gateway
 * is half-duplex, reference §6.3).
 */
missedWhileTransmitting: number, };

export type Delivery = { 
/**
 * Uplinks sent by every drone.
 */
packetsSent: number, 
/**
 * Distinct uplinks the network server passed on (each once, however many gateways heard it).
 */
packetsReceived: number, 
/**
 * `packetsReceived / packetsSent` (`null` when nothing was sent: no share of nothing).
 */
deliveryRatio: number | null, 
/**
 * Copies the server removed: receptions beyond the first of each packet.
 */
duplicates: number, 
/**
 * Per gateway.
 */
gateways: Array<GatewayReport>, };

export type Energy = { 
/**
 * Mean charge of one uplink with its receive windows, mC (`null` when no uplink was sent:
 * there is no uplink to average, and 0 would read as free).
 */
chargePerUplink: number | null, 
/**
 * Charge per hour of tracking (uplinks, windows and sleep between), mAh (`null` for no
 * flight time; a flight with no uplink slept throughout).
 */
chargePerHour: number | null, };

export type ModelResult = Delivery & { 
/**
 * The station: `dr`, `ctra-plus`, `3d-ctra` or `imm`.
 */
model: ModelName, 
/**
 * Payload, bytes.
 */
payloadBytes: number, 
/**
 * Packets that left out the manoeuvre fields within their significance and went with
 * DR's or CTRA+'s smaller payload (`--payload lean`, reference §5); 0 with the full payload.
 */
leanPackets: number, 
/**
 * Time on air of one packet (payload + overhead), s (with ADR: at the starting data rate).
 * With lean payloads a full packet's; the shortest lean one is the next field's.
 */
timeOnAir: number, 
/**
 * Interval between transmissions under the duty cycle, s (with ADR: at the starting data
 * rate). With lean payloads a full packet's; the shortest lean one is the next field's.
 */
interval: number, 
/**
 * The duty-cycle interval over the packets sent, s: the mean of `dataRateUse`'s intervals,
 * each rate's weighted by its packets. With ADR it says how often the drone could send
 * where `interval` is the starting rate's; at a fixed rate it is `interval`. `null` when no
 * packet was sent.
 */
meanInterval: number | null, 
/**
 * The time on air over the packets sent, s, weighted alike (`null` when none was sent).
 */
meanTimeOnAir: number | null, 
/**
 * The mean time between two packets the drone sent in one flight, s (`null` where no
 * flight sent two): how often it did send, where `interval` is how often it may. Longer
 * than the interval where a packet waits for a sensor step (reference §6.4: at 1 Hz SF7's
 * 3.08 s become 4 s), where error-triggered sending waits for its threshold, where ADR
 * slowed the rate or a random delay falls between packets.
 */
sentEvery: number | null, 
/**
 * Whether the packets went notably less often than the interval the tables show
 * (`meanInterval`, or `interval` where none was sent): `sentEvery` over `SENT_EVERY_NOTED`
 * times it (src/sim/report.rs), so that the interval alone would mislead a reader counting
 * packets.
 * Decided once, here; the CLI's line under a station and the page's "sent every" read it.
 */
sentSlower: boolean, 
/**
 * With `--payload lean`, the shortest frame a lean packet took at the starting data rate
 * (reference §5); `null` when no lean packet went there.
 */
leanFrame: FrameTiming | null, 
/**
 * Total time on air of the packets sent over all flights, s.
 */
airtime: number, 
/**
 * 3D error, m, at the evaluation times after each flight's first packet arrived.
 */
error3d: Summary, 
/**
 * The share of the flight time with a packet, and the 3D error's percentiles over the
 * whole flight time (time before a flight's first packet counting as the largest error).
 */
wholeFlight: WholeFlightError, 
/**
 * What these numbers rest on, where a reader could be misled: too few packets received, an
 * error-triggered drone whose packets were lost ([`Caveats`]).
 */
caveats: Caveats, 
/**
 * 95 % intervals of `error3d`'s statistics, by bootstrap over the runs (flights × seeds)
 * pooled in it (`docs/reference.md` §12); `null` for a single run, which cannot show its
 * own spread.
 */
ci95: Intervals | null, 
/**
 * This station's p75 against the lowest station's on the same runs, with the ratio's 95 %
 * interval from resampling both together (`docs/reference.md` §12); `null` for the lowest
 * station itself, a station alone, a single run, or errors in fewer than two runs.
 */
p75VsLowest: VersusLowest | null, 
/**
 * The p75 and p95 of each bootstrap draw of the runs, drawn alike for every station of the
 * run (and of any run of the same seeds and flights), from which `p75VsLowest` is paired
 * (`docs/reference.md` §12; the page pairs the stations its workers ran apart with
 * `versusLowest`); `null` where `ci95` is.
 */
draws: Draws | null, 
/**
 * |x error|, m.
 */
errorX: Summary, 
/**
 * |y error|, m.
 */
errorY: Summary, 
/**
 * |z error|, m.
 */
errorZ: Summary, 
/**
 * Boxplot statistics of the same samples.
 */
boxplot: Boxplots, 
/**
 * Covariance repairs in the drone filter (0 in a healthy run).
 */
filterRecoveries: number, 
/**
 * Fraction of evaluated steps whose true position lay inside the station's 95 % position
 * ellipsoid (chi-square, 3 degrees of freedom); a consistent station scores near 0.95,
 * an overconfident one lower. `null` when nothing was evaluated.
 */
coverage95: number | null, 
/**
 * Fraction of the same steps whose error was no longer than the station's own 95 % bound
 * (`bound95` of the series, the error chart's band: docs/reference.md §12); an honest
 * station's Gaussian error scores near 0.95. `null` when nothing was evaluated.
 */
underBound95: number | null, 
/**
 * Mean normalised estimation error squared of the station's position (Bar-Shalom et al.
 * 2001, §5.4) over the same steps: 3 for a station whose covariance is honest, above 3 when
 * it claims too little uncertainty, below 3 too much. `null` when nothing was evaluated.
 */
nees: number | null, 
/**
 * The packets sent at each data rate (one entry without ADR), slowest rate first.
 */
dataRateUse: Array<DataRateUse>, 
/**
 * The drone radio's charge.
 */
energy: Energy, 
/**
 * IMM only: the mean probability of each member over the evaluated steps.
 */
modelProbability?: Partial<Record<MotionModelName, number>>, };

export type ModelSeries = { 
/**
 * The station.
 */
model: ModelName, 
/**
 * Evaluation times, s.
 */
t: Float64Array, 
/**
 * The station's evaluation times on this flight, all of them: more than `t` holds when the
 * series was thinned to its envelope (a flight of more than 3000).
 */
samples: number, 
/**
 * 3D error at each time, m.
 */
error3d: Float64Array, 
/**
 * The station's own 95 % bound on that error at each time, m: the length an error with its
 * position covariance stays under 95 % of the time ([`crate::bound_95`]).
 */
bound95: Float64Array, 
/**
 * Estimated x, y, z at each time, m.
 */
x: Float64Array, 
/**
 * See `x`.
 */
y: Float64Array, 
/**
 * See `x`.
 */
z: Float64Array, 
/**
 * Arrival times of received packets, s.
 */
arrivals: Float64Array, 
/**
 * Send times of lost packets, s.
 */
lost: Float64Array, 
/**
 * The EU868 data rate of each received packet (`null` for an SF/bandwidth that is none).
 */
arrivalDr: Array<number | null>, 
/**
 * The data rate of each lost packet.
 */
lostDr: Array<number | null>, };

export type Series = { 
/**
 * The flight.
 */
flight: string, 
/**
 * Truth sample times, s (decimated to at most a few thousand points).
 */
t: Float64Array, 
/**
 * True x, m.
 */
x: Float64Array, 
/**
 * True y, m.
 */
y: Float64Array, 
/**
 * True z, m.
 */
z: Float64Array, 
/**
 * The first gateway's position x, y, z, m (the flight's frame).
 */
gateway: [number, number, number], 
/**
 * Every gateway's position x, y, z, m.
 */
gateways: Array<[number, number, number]>, 
/**
 * The waypoints of the plan the mission station flies over this flight, m (only when a
 * mission station ran).
 */
plan?: Array<[number, number, number]>, 
/**
 * Per model.
 */
models: Array<ModelSeries>, };

export type Cornering = "multicopter" | "fixed-wing";

export type VehicleChoice = "auto" | "multicopter" | "fixed-wing";

export type RunConfig = Scenario & { 
/**
 * Flight(s) simulated, by name.
 */
trajectory: string, 
/**
 * Number of flights.
 */
flights: number, 
/**
 * Seconds of flight simulated (all flights).
 */
flightTime: number, 
/**
 * Stations run.
 */
models: ModelName[], 
/**
 * Bandwidth, kHz (as `bw`).
 */
bandwidthKhz: number, 
/**
 * Tilt decay per second, eta^(1/T).
 */
etaPerSecond: number, 
/**
 * Gateway sensitivity for this SF and bandwidth, dBm.
 */
sensitivityDbm: number, 
/**
 * Range where the mean received power meets the sensitivity, m.
 */
rangeM: number, 
/**
 * The regional plan's data rate at `sf`/`bw` (with ADR: the start), `null` for raw LoRa
 * outside the plan's data rates (EU868 allows it: the paper's SF8 at 250 kHz).
 */
dataRate: number | null, 
/**
 * The most seeds these flights take at these sensor and station rates within the work
 * limit (`MAX_FILTER_STEPS`), at most the seeds setting's 100: how far `seeds` may be raised
 * (the whole synthetic set at the defaults: 18).
 */
maxSeeds: number, 
/**
 * How the drone's plan (`plan`) is flown and followed: as a multicopter flies it, or as a
 * plane does ([`Cornering::FixedWing`]: `vehicle` `fixed-wing`, or a QGroundControl `.plan`
 * for a fixed-wing vehicle with `vehicle` `auto`); `null` without a plan.
 */
planCornering: Cornering | null, };

export type SimReport = Delivery & { 
/**
 * Settings and coverage.
 */
config: RunConfig, 
/**
 * One entry per model.
 */
results: Array<ModelResult>, 
/**
 * Time series of the first flight, when asked for.
 */
series: Series | null, };

export type DroneReport = { 
/**
 * 0-based index.
 */
id: number, 
/**
 * Its spreading factor (with ADR, the one it starts at: `dataRateUse` says where its
 * packets went).
 */
sf: number, 
/**
 * Direction from its starting point to the centre, degrees counter-clockwise from east.
 */
bearingDeg: number, 
/**
 * Packets it sent on each channel.
 */
channelUse: Array<number>, 
/**
 * The packets it sent at each data rate, slowest first, as a station's result counts them:
 * one entry without ADR, each rate the network moved it to with.
 */
dataRateUse: Array<DataRateUse>, 
/**
 * Packets sent.
 */
packetsSent: number, 
/**
 * Packets the gateway received.
 */
packetsReceived: number, 
/**
 * Packets lost to interference.
 */
packetsCollided: number, 
/**
 * Its radio's charge.
 */
energy: Energy, 
/**
 * The fraction of its flight time it was on air: its achieved duty cycle (the limit, or
 * less where random delays lengthen the intervals).
 */
dutyCycleUsed: number, 
/**
 * Its slot's frame under a slotted schedule, s: its sending interval (`null` for ALOHA).
 */
frameLength: number | null, 
/**
 * Its station's 3D error, m, after each episode's first packet (`count` 0: nothing arrived,
 * nothing counted).
 */
error3d: Summary, 
/**
 * The share of its flight time after each episode's first packet, and its error's
 * percentiles over the whole flight time ([`WholeFlightError`]).
 */
wholeFlight: WholeFlightError, 
/**
 * What its numbers rest on, as a station's result says it ([`Caveats::of`]): in a swarm of
 * two-minute flights an SF12 drone's p75 rests on a packet or two.
 */
caveats: Caveats, };

export type LargestSwarm = { 
/**
 * ALOHA at ≤ 1 % collisions, drones.
 */
aloha1: number, 
/**
 * ALOHA at ≤ 10 % collisions, drones.
 */
aloha10: number, 
/**
 * Slotted, with no collisions, drones.
 */
slotted: number, };

export type SwarmSaturation = { 
/**
 * Drones with at least one such received packet.
 */
drones: number, 
/**
 * Their received packets that carried one, every drone's summed.
 */
packets: number, 
/**
 * The fields those packets saturated, in state order (empty when none did).
 */
fields: string[], };

export type SfLimit = "adr" | "region" | "interval";

export type SwarmEcho = Scenario & { 
/**
 * The one station every drone's ground station ran.
 */
station: ModelName, 
/**
 * Bandwidth, kHz (as `bw`).
 */
bandwidthKhz: number, 
/**
 * How the plan the drones fly (`plan`) is flown, as [`RunConfig::plan_cornering`]
 * says it for `simulate`; `null` without a plan.
 *
 * [`RunConfig::plan_cornering`]: crate::sim::RunConfig::plan_cornering
 */
planCornering: Cornering | null, };

export type SwarmReport = Delivery & { 
/**
 * The settings.
 */
config: SwarmEcho, 
/**
 * Seconds each drone flew (the mean over the drones): `duration` where the drones chain
 * synthetic flights, else the flights chosen, whole (the real Canberra flight's 162 s).
 */
flightTime: number, 
/**
 * Packets lost to interference at every gateway that could hear them / packets sent
 * (`null` when no packet was sent).
 */
collisionRate: number | null, 
/**
 * Pure ALOHA's collision rate (`aloha_collision_rate`) per SF group at the group's mean
 * achieved duty cycle, weighted by the packets each group sent: what the formula predicts
 * for senders at random phases without capture or inter-SF effects (one gateway). With ADR
 * a group is every drone that sent at that SF, at the share of its time it was on air there.
 */
collisionRateTheory: number, 
/**
 * Why the `spread` SF plan dealt fewer SFs than the swarm had drones for (`"adr"`,
 * `"region"`; `null` where it dealt each drone its own up to six): the drones' `sf` say
 * which it dealt.
 */
sfLimit: SfLimit | null, 
/**
 * The schedule's longest frame, s: the slowest drone's sending interval (`null` for
 * ALOHA).
 */
frameLength: number | null, 
/**
 * How many drones one gateway serves under each schedule at these settings.
 */
largestSwarm: LargestSwarm, 
/**
 * Listen-before-talk: how often a drone found its channel busy and moved to another or
 * backed off (`null` without it).
 */
lbtDeferrals: number | null, 
/**
 * Of those, how often the busy channel carried a packet on the drone's own SF, which its
 * packet would have overlapped: collisions avoided. The collisions that remain
 * (`packetsCollided`) are those listening could not avoid: hidden drones, too far apart
 * to hear each other, and packets that start within one listen time.
 */
lbtCollisionsAvoided: number | null, 
/**
 * Packets no gateway received though one locked on (lost to interference).
 */
packetsCollided: number, 
/**
 * Packets below every gateway's sensitivity.
 */
packetsBelowSensitivity: number, 
/**
 * Packets audible somewhere but finding no free demodulation path where they were.
 */
packetsNoDemodulator: number, 
/**
 * Packets audible somewhere but on air, wherever they were, while that gateway transmitted
 * a downlink (half-duplex gateways, reference §6.3); only with ADR, whose answers are the
 * downlinks.
 */
packetsGatewayTransmitting: number, 
/**
 * Packets sent with a smaller payload than the station's model sends (`--payload lean`).
 */
leanPackets: number, 
/**
 * Packets sent at SF7..SF12, every drone's summed: each drone's SF, or with ADR the SFs the
 * network moved it to (the drones' `dataRateUse`, SF7 at either bandwidth as one). The
 * CLI's "ADR sent them at" and the page's note give these as shares.
 */
packetsBySf: number[], 
/**
 * Seconds on air, all drones.
 */
airtime: number, 
/**
 * Every drone's errors pooled, m (after each episode's first packet).
 */
error3d: Summary, 
/**
 * Every drone's tracked share and errors over the whole flight time, pooled.
 */
wholeFlight: WholeFlightError, 
/**
 * The drones whose received packets carried a value beyond the payload's range, pooled from
 * their `caveats` ([`SwarmSaturation`]).
 */
saturation: SwarmSaturation, 
/**
 * The median over drones of each drone's p75, m (`null` when no drone received anything).
 */
medianDroneP75: number | null, 
/**
 * The drone radio's charge, averaged over the drones: per uplink over those that sent one,
 * per hour over all.
 */
energy: Energy, 
/**
 * Per drone.
 */
drones: Array<DroneReport>, };

export type NumberOption = { 
/**
 * The key in JSON and JS (camelCase); the CLI's long option is its kebab-case form.
 */
key: string, 
/**
 * The name the page's form shows.
 */
label: string, 
/**
 * Unit, as shown after a value (`""` for none).
 */
unit: string, 
/**
 * Default value.
 */
default: number, 
/**
 * Smallest accepted value.
 */
min: number, 
/**
 * Largest accepted value.
 */
max: number, 
/**
 * Whether `min` itself is refused (a value must be above it).
 */
aboveMin: boolean, 
/**
 * Whole numbers only.
 */
integer: boolean, 
/**
 * The only values accepted, when not empty.
 */
values: Array<number>, 
/**
 * One sentence: what it is and why these limits.
 */
help: string, 
/**
 * Whether a run's caption lists it with its value when it differs from its default (the
 * CLI's `settings:` line, the page's download and results captions): the settings that no
 * other part of a caption words, so that two runs differing only in it are not captioned alike.
 */
listedWhenChanged: boolean, };

export type AirtimeParams = { 
/**
 * Spreading factor, 7..12.
 */
sf: number, 
/**
 * Bandwidth, kHz: 125, 250 or 500.
 */
bw: number, 
/**
 * Application payload, bytes.
 */
payload: number, 
/**
 * MAC overhead added to the payload, bytes (LoRaWAN: 13; raw LoRa as in the paper: 0).
 */
overhead: number, 
/**
 * Coding rate index 1..4 (4/5..4/8).
 */
cr: number, 
/**
 * Preamble symbols.
 */
preamble: number, 
/**
 * Implicit header mode.
 */
implicitHeader: boolean, 
/**
 * Payload CRC off.
 */
noCrc: boolean, 
/**
 * Low data rate optimisation.
 */
ldro: LdroMode, 
/**
 * Duty-cycle limit as a fraction (EU868 g1 sub-band: 0.01), in plans with a duty cycle.
 */
dutyCycle: number, 
/**
 * The regional plan (reference §14).
 */
region: Region, 
/**
 * Where the plan has no duty cycle: seconds between uplinks (default 1).
 */
interval?: number, 
/**
 * Duty cycle or listen-before-talk.
 */
access: ChannelAccess, 
/**
 * A network's fair-use policy.
 */
fairUse: FairUse, };

export type AirtimeReport = { 
/**
 * Time on air, s.
 */
timeOnAir: number, 
/**
 * Symbol duration, s.
 */
symbolTime: number, 
/**
 * Payload symbols.
 */
payloadSymbols: number, 
/**
 * PHY payload bytes (payload + overhead).
 */
phyPayloadBytes: number, 
/**
 * Whether low data rate optimisation is on.
 */
lowDataRateOptimize: boolean, 
/**
 * Minimum interval between packets under the plan's rule (duty cycle, listen-before-talk's
 * 100 s per hour, or the interval where the plan has none; within fair use), s.
 */
minInterval: number, 
/**
 * The plan's data rate at this SF and bandwidth (`null`: raw LoRa outside the data rates,
 * which EU868 allows).
 */
dataRate: number | null, 
/**
 * Why the plan refuses this packet (no such data rate, payload limit, dwell time); `null`
 * when it carries it.
 */
refused: string | null, 
/**
 * Packets per day within The Things Network's fair-use policy (30 s of airtime a day), for
 * information: loratrack does not enforce it.
 */
ttnPacketsPerDay: number, };

export type LinkBudgetParams = { 
/**
 * Bandwidth, kHz.
 */
bw: number, 
/**
 * Transmit power, dBm.
 */
txPower: number, 
/**
 * Path-loss exponent.
 */
pathLossExponent: number, 
/**
 * Shadowing standard deviation, dB.
 */
shadowing: number, 
/**
 * Gateway antenna height, m.
 */
gatewayHeight: number, 
/**
 * Horizontal distances, m (at most 1000 of them, each 1..100000).
 */
distances: Array<number>, 
/**
 * The regional plan: each SF's data rate at `bw`, or that the plan lacks it (§14).
 */
region: Region, };

export type SfBudget = { 
/**
 * Spreading factor.
 */
sf: number, 
/**
 * Gateway sensitivity at the bandwidth, dBm.
 */
sensitivityDbm: number, 
/**
 * Horizontal distance at which the mean power meets the sensitivity, m.
 */
rangeM: number, 
/**
 * Share of packets received at each distance: Φ((mean power − sensitivity) / σ).
 */
delivery: Array<number>, 
/**
 * The plan's data rate at this SF and the bandwidth (`null`: none; then `inPlan` says
 * whether the plan allows the SF as raw LoRa, as EU868 does).
 */
dataRate: number | null, 
/**
 * Whether the plan lets a drone send at this SF and bandwidth.
 */
inPlan: boolean, };

export type LinkBudgetReport = { 
/**
 * The distances, m.
 */
distances: Array<number>, 
/**
 * Mean received power at each, dBm (before shadowing), for a drone on the ground
 * (3D distance from the gateway's antenna).
 */
meanRxDbm: Array<number>, 
/**
 * The transmit power the mean rests on, dBm.
 */
txPower: number, 
/**
 * The path-loss exponent the mean rests on.
 */
pathLossExponent: number, 
/**
 * The shadowing σ, dB: 90 % of packets arrive within ±1.645 σ of the mean.
 */
shadowing: number, 
/**
 * SF7..SF12.
 */
sfs: Array<SfBudget>, };

export type PredictParams = { 
/**
 * `dr`, `ctra-plus` or `3d-ctra`.
 */
model: ModelKind, 
/**
 * The state, reference §2 order and units.
 */
state: Array<number>, 
/**
 * Time to propagate over, s (≥ 0).
 */
dt: number, 
/**
 * Run in steps of this length (s), multiplying psi by eta after each, as the station does.
 */
step: number | null, 
/**
 * Tilt-rate decay per step, [0, 1]; only with `step` (default 0.9, paper Table I).
 */
eta: number | null, };

export type PredictReport = { 
/**
 * The model.
 */
model: ModelKind, 
/**
 * The propagated state.
 */
state: Array<number>, };

export type EncodeParams = { 
/**
 * The model (fixes the payload size).
 */
model: ModelKind, 
/**
 * The state, reference §2 order.
 */
state: Array<number>, 
/**
 * Origin both ends agree on, ENU m (default 0,0,0).
 */
origin: [number, number, number] | null, };

export type EncodeReport = { 
/**
 * The payload as lowercase hex.
 */
hex: string, 
/**
 * Fields that were out of range and saturated.
 */
saturated: Array<string>, };

export type DecodeParams = { 
/**
 * The model (fixes the payload size).
 */
model: ModelKind, 
/**
 * The payload as hex (upper or lower case).
 */
hex: string, 
/**
 * Origin both ends agree on, ENU m (default 0,0,0).
 */
origin: [number, number, number] | null, };

export type DecodeReport = { 
/**
 * The model.
 */
model: ModelKind, 
/**
 * The decoded state.
 */
state: Array<number>, };

/** Every numeric setting's default and accepted range, as the core validates them (src/options.rs). */
export const OPTIONS: NumberOption[] = [
  {
    "key": "sf",
    "label": "Spreading factor",
    "unit": "",
    "default": 7.0,
    "min": 7.0,
    "max": 12.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Spreading factor; with ADR, the one the drone starts at.",
    "listedWhenChanged": false
  },
  {
    "key": "bw",
    "label": "Bandwidth",
    "unit": "kHz",
    "default": 250.0,
    "min": 125.0,
    "max": 500.0,
    "aboveMin": false,
    "integer": false,
    "values": [
      125.0,
      250.0,
      500.0
    ],
    "help": "LoRa bandwidth.",
    "listedWhenChanged": false
  },
  {
    "key": "cr",
    "label": "Coding rate",
    "unit": "",
    "default": 1.0,
    "min": 1.0,
    "max": 4.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Coding rate n of 4/(4+n).",
    "listedWhenChanged": true
  },
  {
    "key": "overhead",
    "label": "LoRaWAN overhead",
    "unit": "bytes",
    "default": 13.0,
    "min": 0.0,
    "max": 255.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "MAC overhead added to each payload: 13 for LoRaWAN, 0 as in the paper's Table II.",
    "listedWhenChanged": false
  },
  {
    "key": "dutyCycle",
    "label": "Duty cycle",
    "unit": "",
    "default": 0.01,
    "min": 0.0001,
    "max": 1.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Duty-cycle limit as a fraction: 0.01, EU868's default channels; 0.02, two 1 % sub-bands alternated (The Things Network's eight channels); 0.0001 is ten times below EU868's strictest sub-band.",
    "listedWhenChanged": false
  },
  {
    "key": "txPower",
    "label": "Tx power",
    "unit": "dBm",
    "default": 14.0,
    "min": -30.0,
    "max": 30.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Drone transmit power.",
    "listedWhenChanged": true
  },
  {
    "key": "distance",
    "label": "Distance",
    "unit": "m",
    "default": 1000.0,
    "min": 0.0,
    "max": 100000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "simulate: horizontal distance from the flight's first point to the gateway (placed east of it) when no gateway is given; swarm: every drone's starting distance from the centre.",
    "listedWhenChanged": false
  },
  {
    "key": "pathLossExponent",
    "label": "Path-loss exponent",
    "unit": "",
    "default": 3.76,
    "min": 1.5,
    "max": 6.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Exponent of the log-distance path loss: free space 2, obstructed paths up to 6.",
    "listedWhenChanged": true
  },
  {
    "key": "shadowing",
    "label": "Shadowing sigma",
    "unit": "dB",
    "default": 4.0,
    "min": 0.0,
    "max": 20.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Standard deviation of log-normal shadowing (0 turns it off).",
    "listedWhenChanged": true
  },
  {
    "key": "gatewayHeight",
    "label": "Gateway height",
    "unit": "m",
    "default": 15.0,
    "min": 0.0,
    "max": 1000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Antenna height of every gateway not given its own.",
    "listedWhenChanged": true
  },
  {
    "key": "gateway",
    "label": "Gateway coordinate",
    "unit": "m",
    "default": 0.0,
    "min": -100000.0,
    "max": 100000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "A gateway's east or north coordinate in the scenario's frame.",
    "listedWhenChanged": false
  },
  {
    "key": "gateways",
    "label": "Gateways",
    "unit": "",
    "default": 1.0,
    "min": 1.0,
    "max": 16.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Number of gateways.",
    "listedWhenChanged": false
  },
  {
    "key": "sensorRate",
    "label": "Sensor rate",
    "unit": "Hz",
    "default": 10.0,
    "min": 0.1,
    "max": 1000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Drone sensor and filter rate.",
    "listedWhenChanged": true
  },
  {
    "key": "step",
    "label": "Prediction step T",
    "unit": "s",
    "default": 0.1,
    "min": 0.001,
    "max": 10.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Station prediction step T.",
    "listedWhenChanged": true
  },
  {
    "key": "eta",
    "label": "Tilt decay eta",
    "unit": "",
    "default": 0.9,
    "min": 0.0,
    "max": 1.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "3D-CTRA's tilt-rate decay per station step.",
    "listedWhenChanged": true
  },
  {
    "key": "q",
    "label": "Process noise q",
    "unit": "",
    "default": 0.1,
    "min": 0.0,
    "max": 1000.0,
    "aboveMin": true,
    "integer": false,
    "values": [],
    "help": "Process noise q of Q = q I per second.",
    "listedWhenChanged": true
  },
  {
    "key": "planTolerance",
    "label": "Off-plan distance",
    "unit": "m",
    "default": 10.0,
    "min": 0.1,
    "max": 1000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Mission station: a packet farther than this from the plan hands over to bounded 3D-CTRA.",
    "listedWhenChanged": true
  },
  {
    "key": "threshold",
    "label": "Threshold",
    "unit": "m",
    "default": 2.0,
    "min": 0.0,
    "max": 10000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Error-triggered sending: the drift between the mirrored station and the drone's own estimate that triggers a packet.",
    "listedWhenChanged": false
  },
  {
    "key": "maxInterval",
    "label": "Heartbeat",
    "unit": "s",
    "default": 10.0,
    "min": 0.0,
    "max": 3600.0,
    "aboveMin": true,
    "integer": false,
    "values": [],
    "help": "Error-triggered sending: the longest silence (at least every drone's duty-cycle interval).",
    "listedWhenChanged": false
  },
  {
    "key": "burst",
    "label": "Burst",
    "unit": "packets",
    "default": 10.0,
    "min": 1.0,
    "max": 3600.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Budget duty-cycle rule: the most packets' airtime the credit holds (1 is per-packet).",
    "listedWhenChanged": false
  },
  {
    "key": "adrMargin",
    "label": "ADR margin",
    "unit": "dB",
    "default": 10.0,
    "min": 0.0,
    "max": 30.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "LoRaWAN ADR: the device margin.",
    "listedWhenChanged": false
  },
  {
    "key": "adrHistory",
    "label": "ADR history",
    "unit": "uplinks",
    "default": 20.0,
    "min": 1.0,
    "max": 100.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "LoRaWAN ADR: the uplinks whose best SNR decides.",
    "listedWhenChanged": false
  },
  {
    "key": "channels",
    "label": "Channels",
    "unit": "",
    "default": 3.0,
    "min": 1.0,
    "max": 8.0,
    "aboveMin": false,
    "integer": false,
    "values": [
      1.0,
      2.0,
      3.0,
      8.0
    ],
    "help": "Uplink channels: 1, or the plan's default channels with a random one per packet (EU868 868.1/868.3/868.5 MHz, under one 1 % duty cycle; US915 and AU915 8 of a sub-band; AS923 2; IN865 3), the default. swarm only.",
    "listedWhenChanged": false
  },
  {
    "key": "interval",
    "label": "Interval",
    "unit": "s",
    "default": 1.0,
    "min": 0.05,
    "max": 3600.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Where the plan has no duty cycle (US915, AU915, IN865): seconds from one uplink's start to the next (default 1 s, Remote ID's rate); at least the time on air.",
    "listedWhenChanged": false
  },
  {
    "key": "jitter",
    "label": "Jitter",
    "unit": "s",
    "default": 1.0,
    "min": 0.0,
    "max": 60.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "The longest random delay a drone adds before each uplink (swarm default 1 s as LoRaMac-node's example; simulate default 0, the paper's timing).",
    "listedWhenChanged": true
  },
  {
    "key": "clockDrift",
    "label": "Clock drift",
    "unit": "ppm",
    "default": 20.0,
    "min": 0.0,
    "max": 1000.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Each drone's clock runs up to this fast or slow, drawn per drone (swarm default 20 ppm, a common crystal; simulate default 0).",
    "listedWhenChanged": true
  },
  {
    "key": "drones",
    "label": "Drones",
    "unit": "",
    "default": 12.0,
    "min": 1.0,
    "max": 500.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Number of drones sharing the gateways.",
    "listedWhenChanged": false
  },
  {
    "key": "duration",
    "label": "Duration",
    "unit": "s",
    "default": 600.0,
    "min": 10.0,
    "max": 3600.0,
    "aboveMin": false,
    "integer": false,
    "values": [],
    "help": "Seconds of flight per drone when the drones fly chained synthetic flights (refused with a chosen flight, flown whole).",
    "listedWhenChanged": false
  },
  {
    "key": "seed",
    "label": "Seed",
    "unit": "",
    "default": 1.0,
    "min": 0.0,
    "max": 9007199254740991.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Seed of every random draw; the largest is 2^53 - 1, the largest integer a JavaScript number holds exactly.",
    "listedWhenChanged": false
  },
  {
    "key": "seeds",
    "label": "Seeds",
    "unit": "",
    "default": 1.0,
    "min": 1.0,
    "max": 100.0,
    "aboveMin": false,
    "integer": true,
    "values": [],
    "help": "Repeat the simulation with this many seeds (seed, seed + 1, ...): the statistics pool every run and each gets a 95 % interval.",
    "listedWhenChanged": false
  }
];

/** The default of every setting chosen by name, as `Scenario::default` gives it (src/sim/scenario/mod.rs). */
export const CHOICE_DEFAULTS: Pick<Scenario, 'access' | 'adr' | 'channelSense' | 'dutyCycleMode' | 'fairUse' | 'headingNoise' | 'model' | 'payload' | 'planPace' | 'prediction' | 'region' | 'schedule' | 'sender' | 'sfPlan' | 'shadowingModel' | 'vehicle'> = {
  "access": "duty-cycle",
  "adr": "off",
  "channelSense": "cad",
  "dutyCycleMode": "per-packet",
  "fairUse": "off",
  "headingNoise": "fixed",
  "model": "all",
  "payload": "full",
  "planPace": "plan",
  "prediction": "paper",
  "region": "eu868",
  "schedule": "aloha",
  "sender": "periodic",
  "sfPlan": "spread",
  "shadowingModel": "path",
  "vehicle": "auto"
};

/** Every regional plan's data rates and limits, as the core checks them (src/lora/region.rs). */
export const PLANS: Plan[] = [
  {
    "region": "eu868",
    "label": "EU868",
    "rates": [
      {
        "dr": 0,
        "sf": 12,
        "bw": 125.0,
        "maxPayload": 51
      },
      {
        "dr": 1,
        "sf": 11,
        "bw": 125.0,
        "maxPayload": 51
      },
      {
        "dr": 2,
        "sf": 10,
        "bw": 125.0,
        "maxPayload": 51
      },
      {
        "dr": 3,
        "sf": 9,
        "bw": 125.0,
        "maxPayload": 115
      },
      {
        "dr": 4,
        "sf": 8,
        "bw": 125.0,
        "maxPayload": 242
      },
      {
        "dr": 5,
        "sf": 7,
        "bw": 125.0,
        "maxPayload": 242
      },
      {
        "dr": 6,
        "sf": 7,
        "bw": 250.0,
        "maxPayload": 242
      }
    ],
    "dwellTime": null,
    "dutyCycle": 0.01,
    "channels": 3,
    "maxEirpDbm": 16.0,
    "rawLora": true
  },
  {
    "region": "us915",
    "label": "US915",
    "rates": [
      {
        "dr": 0,
        "sf": 10,
        "bw": 125.0,
        "maxPayload": 11
      },
      {
        "dr": 1,
        "sf": 9,
        "bw": 125.0,
        "maxPayload": 53
      },
      {
        "dr": 2,
        "sf": 8,
        "bw": 125.0,
        "maxPayload": 125
      },
      {
        "dr": 3,
        "sf": 7,
        "bw": 125.0,
        "maxPayload": 242
      },
      {
        "dr": 4,
        "sf": 8,
        "bw": 500.0,
        "maxPayload": 242
      }
    ],
    "dwellTime": 0.4,
    "dutyCycle": null,
    "channels": 8,
    "maxEirpDbm": 30.0,
    "rawLora": false
  },
  {
    "region": "au915",
    "label": "AU915",
    "rates": [
      {
        "dr": 0,
        "sf": 12,
        "bw": 125.0,
        "maxPayload": null
      },
      {
        "dr": 1,
        "sf": 11,
        "bw": 125.0,
        "maxPayload": null
      },
      {
        "dr": 2,
        "sf": 10,
        "bw": 125.0,
        "maxPayload": 11
      },
      {
        "dr": 3,
        "sf": 9,
        "bw": 125.0,
        "maxPayload": 53
      },
      {
        "dr": 4,
        "sf": 8,
        "bw": 125.0,
        "maxPayload": 125
      },
      {
        "dr": 5,
        "sf": 7,
        "bw": 125.0,
        "maxPayload": 242
      },
      {
        "dr": 6,
        "sf": 8,
        "bw": 500.0,
        "maxPayload": 242
      }
    ],
    "dwellTime": 0.4,
    "dutyCycle": null,
    "channels": 8,
    "maxEirpDbm": 30.0,
    "rawLora": false
  },
  {
    "region": "as923",
    "label": "AS923",
    "rates": [
      {
        "dr": 0,
        "sf": 12,
        "bw": 125.0,
        "maxPayload": null
      },
      {
        "dr": 1,
        "sf": 11,
        "bw": 125.0,
        "maxPayload": null
      },
      {
        "dr": 2,
        "sf": 10,
        "bw": 125.0,
        "maxPayload": 11
      },
      {
        "dr": 3,
        "sf": 9,
        "bw": 125.0,
        "maxPayload": 53
      },
      {
        "dr": 4,
        "sf": 8,
        "bw": 125.0,
        "maxPayload": 125
      },
      {
        "dr": 5,
        "sf": 7,
        "bw": 125.0,
        "maxPayload": 242
      },
      {
        "dr": 6,
        "sf": 7,
        "bw": 250.0,
        "maxPayload": 242
      }
    ],
    "dwellTime": 0.4,
    "dutyCycle": 0.01,
    "channels": 2,
    "maxEirpDbm": 16.0,
    "rawLora": false
  },
  {
    "region": "in865",
    "label": "IN865",
    "rates": [
      {
        "dr": 0,
        "sf": 12,
        "bw": 125.0,
        "maxPayload": 51
      },
      {
        "dr": 1,
        "sf": 11,
        "bw": 125.0,
        "maxPayload": 51
      },
      {
        "dr": 2,
        "sf": 10,
        "bw": 125.0,
        "maxPayload": 51
      },
      {
        "dr": 3,
        "sf": 9,
        "bw": 125.0,
        "maxPayload": 115
      },
      {
        "dr": 4,
        "sf": 8,
        "bw": 125.0,
        "maxPayload": 242
      },
      {
        "dr": 5,
        "sf": 7,
        "bw": 125.0,
        "maxPayload": 242
      }
    ],
    "dwellTime": null,
    "dutyCycle": null,
    "channels": 3,
    "maxEirpDbm": 30.0,
    "rawLora": false
  }
];

/** Each station's payload, bytes: the model whose state its drone sends (src/sim/station/station_model.rs). */
export const PAYLOAD_BYTES: Record<ModelName, number> = {
  'dr': 9,
  'ctra-plus': 11,
  '3d-ctra': 12,
  'imm': 12,
  'mission': 12
};

/** The top speed, m/s, a bounded or mission station holds each vehicle to (src/sim/station/prediction.rs, `Bounds::for_vehicle`). */
export const TOP_SPEEDS: Record<Cornering, number> = {
  'multicopter': 20,
  'fixed-wing': 25.5
};

/** Each payload field, what it is and the values it sends as themselves, in words; beyond them a value is sent as the range's edge (src/codec/fields.rs, reference §5). */
export const PAYLOAD_FIELDS: Record<string, string> = {
  x: "distance east of the flight's start, ±6553.4 m",
  y: "distance north of the flight's start, ±6553.4 m",
  z: "height above the flight's start, ±6553.4 m",
  theta: "heading θ, any",
  phi: "pitch φ, ±1.57 rad",
  v: "speed, 0–25.5 m/s",
  a: "acceleration, ±6.35 m/s²",
  omega: "turn rate ω, ±2 rad/s",
  psi: "tilt rate ψ, ±2 rad/s"
};

/** How many of the drone filter's settled standard deviations a manoeuvre field (a, ω, ψ) may reach and still be left out of a lean payload (src/sim/sender/payload.rs). */
export const LEAN_SIGNIFICANCE = 10;
