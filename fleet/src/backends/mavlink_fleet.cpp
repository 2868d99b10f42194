#include "swath/fleet/mavlink_fleet.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <thread>

#include "swath/fleet/envelope.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/geometry/polygon.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/mavlink/copter_driver.hpp"
#include "swath/mavlink/px4_driver.hpp"
#include "swath/mavlink/shared_link.hpp"
#include "swath/mavlink/signing_link.hpp"

namespace swath::fleet {

namespace {

// Longer than the vehicle's 1 Hz status messages: an accepted command shows in the state by then.
constexpr double kSettleS = 1.2;

// A vehicle rejecting one step of the steering this many times (since it last accepted it) will
// not do it (a pre-arm check, a mode it refuses): retrying forever would hide that.
constexpr int kMaxRejections = 3;

// Arming is asked again for this long (seconds since its first refusal) before the vehicle is
// given up: pre-arm checks clear on their own after boot — ArduCopter SITL refused an arm 23 s
// after start with "Need Position Estimate" (its pre-arm bit already set) and armed at 41 s,
// once the EKF used GPS. An uncalibrated compass never clears: the vehicle leaves after this.
constexpr double kArmPatienceS = 60;
constexpr double kArmRetryS = 2;  // between asks

// The fence as MAVLink fence items (MAV_MISSION_TYPE_FENCE): a polygon is one item per vertex,
// each carrying the polygon's vertex count in param1 (MAV_CMD_NAV_FENCE_POLYGON_VERTEX_*),
// positions in MAV_FRAME_GLOBAL (ArduPilot keeps latitude and longitude only).
std::vector<mavlink::MissionItemInt> fence_mission_items(const LocalEnvelope& fence,
                                                         const geometry::LocalFrame& frame) {
  std::vector<mavlink::MissionItemInt> items;
  const auto add = [&](const std::vector<std::array<double, 2>>& ring, mavlink::Cmd cmd) {
    for (const auto& [x, y] : ring) {
      const geometry::GeoPoint g = frame.to_geo({x, y});
      mavlink::MissionItemInt m;
      m.command = static_cast<std::uint16_t>(cmd);
      m.frame = static_cast<std::uint8_t>(mavlink::MavFrame::global);
      m.param1 = static_cast<float>(ring.size());
      m.x = static_cast<std::int32_t>(std::lround(g.lat_deg * mavlink::kDegE7));
      m.y = static_cast<std::int32_t>(std::lround(g.lon_deg * mavlink::kDegE7));
      m.autocontinue = 1;
      items.push_back(m);
    }
  };
  for (const auto& r : fence.inclusions) add(r, mavlink::Cmd::nav_fence_polygon_vertex_inclusion);
  for (const auto& r : fence.exclusions) add(r, mavlink::Cmd::nav_fence_polygon_vertex_exclusion);
  return items;
}

}  // namespace

// What the runtime last asked of a vehicle, and where its steering stands.
struct MavlinkFleet::Vehicle {
  enum class Want { ground, go, home, land };
  enum class Step { mode, arm, takeoff, rtl, land, disarm };  // the steering's gated steps
  static constexpr int kSteps = 6;
  static std::string refusal_text(Step step, const mavlink::Driver& d) {
    switch (step) {
      case Step::mode:
        return "refused " + d.guided_name();
      case Step::arm:
        return "refused to arm";
      case Step::takeoff:
        return "refused to take off";
      case Step::rtl:
        return "refused to return to launch";
      case Step::land:
        return "refused to land";
      case Step::disarm:
        return "refused to disarm";
    }
    return "refused";
  }
  std::unique_ptr<mavlink::Link> link;
  std::unique_ptr<mavlink::Endpoint> keepalive;  // the keep-alive thread's own, on the same link
  mavlink::DriverSettings driver_settings;
  // Until the vehicle's first HEARTBEAT says which autopilot it runs, the link is read here; then
  // the driver for it is made and handed what was read.
  std::unique_ptr<mavlink::Endpoint> probe;
  double probe_heartbeat_s = -std::numeric_limits<double>::infinity();  // its GCS heartbeat
  std::unique_ptr<mavlink::Driver> driver;
  std::size_t warnings_told = 0;  // of driver->state().warnings
  Want want = Want::ground;
  double lat_deg = 0, lon_deg = 0, alt_m = 0;
  double cruise_m_s = 10, approach_m_s = 2, approach_within_m = 20;
  bool target_sent = false, slowed = false;
  int speed_cmd = -1;  // the cruise DO_CHANGE_SPEED that goes before the target
  int gate = -1;       // a command the steering waits for (mode, arm, take-off, RTL)
  Step gate_step = Step::mode;
  std::array<int, kSteps> rejections{};  // of each step since it was last accepted
  double first_arm_refusal_s = -1;       // of the current run of refused arms; -1: none
  double settle_until_s = 0;             // an accepted command shows in the state only after this
  std::string refusal;
};

MavlinkFleet::MavlinkFleet(std::vector<std::unique_ptr<mavlink::Link>> links,
                           const std::vector<std::uint8_t>& sysids, MavlinkFleetSettings settings)
    : settings_(std::move(settings)) {
  if (links.size() != sysids.size())
    throw std::invalid_argument("MavlinkFleet: one system id per link");
  if (!(settings_.end_timeout_s >= 0))
    throw std::invalid_argument("MavlinkFleet: end_timeout_s must be >= 0");
  if (!(settings_.poll_step_s > 0))
    throw std::invalid_argument("MavlinkFleet: poll_step_s must be > 0");
  const geometry::LocalFrame frame(settings_.origin);
  LocalEnvelope fence;  // its fence rings only
  fence.inclusions = settings_.inclusions_m;
  fence.exclusions = settings_.exclusions_m;
  if (settings_.fence_m.size() >= 3) fence.inclusions.push_back(settings_.fence_m);
  fence_items_ = fence_mission_items(fence, frame);
  for (std::size_t i = 0; i < links.size(); ++i) {
    auto v = std::make_unique<Vehicle>();
    v->link = std::move(links[i]);
    if (settings_.signing_key)
      v->link = std::make_unique<mavlink::SigningLink>(std::move(v->link), *settings_.signing_key,
                                                       static_cast<std::uint8_t>(i));
    if (settings_.wall_clock && settings_.keepalive) {
      v->link = std::make_unique<mavlink::SharedLink>(std::move(v->link));
      v->keepalive =
          std::make_unique<mavlink::Endpoint>(*v->link, mavlink::kGcsSysid, mavlink::kGcsCompid);
    }
    mavlink::DriverSettings d = settings_.driver;
    d.vehicle_sysid = sysids[i];
    if (!fence.inclusions.empty() || !fence.exclusions.empty()) {
      d.inside_fence = [fence, frame](double lat_deg, double lon_deg) {
        const geometry::Point2 p = frame.to_local({lat_deg, lon_deg});
        return fence.refusal_xy(p.x, p.y).empty();
      };
    }
    v->driver_settings = std::move(d);
    v->probe =
        std::make_unique<mavlink::Endpoint>(*v->link, mavlink::kGcsSysid, mavlink::kGcsCompid);
    vehicles_.push_back(std::move(v));
  }
  if (settings_.wall_clock && settings_.keepalive)
    keepalive_ = std::thread([this] { keep_alive(); });
}

MavlinkFleet::~MavlinkFleet() {
  if (!keepalive_.joinable()) return;
  {
    const std::lock_guard lock(keepalive_mutex_);
    stopping_ = true;
  }
  keepalive_stop_.notify_all();
  keepalive_.join();
}

// The keep-alive thread: every quarter period it looks at when the runtime last polled; silent
// for a heartbeat period or more (compute() or the scheduler holding the runtime's thread), it
// sends each vehicle the ground station's HEARTBEAT itself, through the shared link and its own
// sequence. While the runtime polls, the drivers' own heartbeats go out and it sends nothing.
void MavlinkFleet::keep_alive() {
  using clock = std::chrono::steady_clock;
  const auto period = std::chrono::duration_cast<clock::duration>(
      std::chrono::duration<double>(settings_.driver.heartbeat_period_s));
  auto last_sent = clock::now();
  std::unique_lock lock(keepalive_mutex_);
  while (!keepalive_stop_.wait_for(lock, period / 4, [this] { return stopping_; })) {
    const auto now = clock::now();
    const clock::time_point polled{clock::duration(last_poll_ns_.load())};
    if (now - polled < period || now - last_sent < period) continue;
    for (const auto& v : vehicles_) v->keepalive->send(mavlink::gcs_heartbeat());
    last_sent = now;
  }
}

MavlinkFleet::Vehicle& MavlinkFleet::at(int drone) const {
  return *vehicles_.at(static_cast<std::size_t>(drone));
}

const mavlink::Driver* MavlinkFleet::driver(int drone) const {
  return at(drone).driver.get();
}

void MavlinkFleet::warn(int drone, const std::string& text) const {
  if (settings_.warn)
    settings_.warn(drone, text);
  else
    std::cerr << "swath-fleet: vehicle " << drone + 1 << ": warning: " << text << "\n";
}

// Reads the link until the vehicle's HEARTBEAT names its autopilot (MAV_AUTOPILOT 12: PX4; any
// other: ArduPilot's driver, the tested one), then polls its driver.
void MavlinkFleet::poll(Vehicle& v, int drone) {
  if (v.driver) {
    v.driver->poll(now_s_);
  } else {
    // The ground station's heartbeat goes out meanwhile: a vehicle listening on UDP learns from
    // it where to send.
    if (now_s_ - v.probe_heartbeat_s >= v.driver_settings.heartbeat_period_s) {
      v.probe->send(mavlink::gcs_heartbeat());
      v.probe_heartbeat_s = now_s_;
    }
    const std::vector<mavlink::Frame> frames = v.probe->receive();
    for (const mavlink::Frame& f : frames) {
      const auto hb = mavlink::unpack<mavlink::Heartbeat>(f);
      if (!hb || f.header.sysid != v.driver_settings.vehicle_sysid ||
          f.header.compid != v.driver_settings.vehicle_compid)
        continue;
      v.probe.reset();
      if (hb->autopilot == mavlink::kAutopilotPx4) {
        warn(drone,
             "a PX4 autopilot (HEARTBEAT autopilot 12): swath's PX4 driver is written from PX4's "
             "documentation and untested on PX4 (confirm in PX4 SITL before flying it)");
        v.driver = std::make_unique<mavlink::Px4Driver>(*v.link, v.driver_settings);
      } else {
        v.driver = std::make_unique<mavlink::CopterDriver>(*v.link, v.driver_settings);
      }
      v.driver->poll(now_s_, frames);
      break;
    }
    if (!v.driver) return;
  }
  if (settings_.upload_fence && !fence_items_.empty() &&
      v.driver->fence_state() == mavlink::FenceState::none)
    v.driver->upload_fence(fence_items_);
  const std::vector<std::string>& w = v.driver->state().warnings;
  for (; v.warnings_told < w.size(); ++v.warnings_told) warn(drone, w[v.warnings_told]);
}

void MavlinkFleet::go_to(int drone, double, const Vec3& to_m, double cruise_m_s,
                         double approach_m_s, double approach_within_m) {
  Vehicle& v = at(drone);
  const geometry::GeoPoint g = geometry::LocalFrame(settings_.origin).to_geo({to_m.x, to_m.y});
  // Refused here, before any command for it goes out (on the ground: no arm, no take-off).
  if (v.driver_settings.inside_fence && !v.driver_settings.inside_fence(g.lat_deg, g.lon_deg) &&
      v.refusal.empty())
    v.refusal = "target outside the fence";
  v.want = Vehicle::Want::go;
  v.lat_deg = g.lat_deg;
  v.lon_deg = g.lon_deg;
  v.alt_m = to_m.z;
  v.cruise_m_s = cruise_m_s;
  v.approach_m_s = approach_m_s;
  v.approach_within_m = approach_within_m;
  v.target_sent = false;
  v.slowed = false;
  v.speed_cmd = -1;
  steer(v);
}

void MavlinkFleet::act(int drone, const std::string&, bool sense) {
  // Hover, custom: GUIDED holds the place. A sense: the vehicle's photo (the reading itself is the
  // world's sensor at the reported position, docs/swath-fleet.md).
  Vehicle& v = at(drone);
  if (sense && v.driver) v.driver->capture_image();
}

void MavlinkFleet::return_home(int drone, double) {
  Vehicle& v = at(drone);
  v.want = Vehicle::Want::home;
  v.target_sent = false;
  steer(v);
}

void MavlinkFleet::land(int drone, double) {
  Vehicle& v = at(drone);
  v.want = Vehicle::Want::land;
  v.target_sent = false;
  steer(v);
}

// Holds where the vehicle last reported itself: its own position as the GUIDED target (a vehicle
// not heard yet, or without a position, has nowhere to be stopped at and is left as it is).
void MavlinkFleet::pause(int drone, double t_s) {
  Vehicle& v = at(drone);
  if (!v.driver || !v.driver->state().position) return;
  const mavlink::GlobalPositionInt& p = *v.driver->state().position;
  const geometry::Point2 here =
      geometry::LocalFrame(settings_.origin)
          .to_local({p.lat_degE7 / mavlink::kDegE7, p.lon_degE7 / mavlink::kDegE7});
  go_to(drone, t_s, {here.x, here.y, std::max(1.0, p.relative_alt_mm / 1000.0)}, v.cruise_m_s,
        v.approach_m_s, v.approach_within_m);
}

// After an abort: polls (the ground station's heartbeat going on) until every vehicle told to
// return or land has taken the order — in RTL or LAND, or down — or settings.abort_timeout_s.
// They fly the rest on their own.
void MavlinkFleet::end_abort() {
  const double deadline_s = now_s_ + settings_.abort_timeout_s;
  while (now_s_ < deadline_s && !all_told()) advance_to(std::min(deadline_s, now_s_ + 0.5));
}

bool MavlinkFleet::all_told() const {
  for (const auto& v : vehicles_) {
    if (v->want != Vehicle::Want::home && v->want != Vehicle::Want::land) continue;
    if (!v->driver) continue;  // never heard: nothing to tell it
    const mavlink::VehicleState& s = v->driver->state();
    // Armed on the ground: told once disarmed, or once it has refused the disarm.
    const bool refused_disarm =
        v->rejections[static_cast<std::size_t>(Vehicle::Step::disarm)] >= kMaxRejections;
    if (s.armed && s.landed == mavlink::LandedState::on_ground && !refused_disarm) return false;
    const bool down = !s.armed || s.landed == mavlink::LandedState::on_ground;
    if (!down && !v->driver->returning()) return false;
  }
  return true;
}

void MavlinkFleet::end_run() {
  for (auto& v : vehicles_)
    if (v->want == Vehicle::Want::go) return_home(static_cast<int>(&v - vehicles_.data()), now_s_);
  // The RTL goes out only from poll(): keep polling (and the ground station's heartbeat) until
  // every vehicle is down, or the deadline, before the caller closes the links. Asked to stop
  // waiting, it still waits until every vehicle has taken its RTL.
  const double deadline_s = now_s_ + settings_.end_timeout_s;
  const auto stop = [&] {
    return settings_.stop_waiting && settings_.stop_waiting() && all_told();
  };
  while (now_s_ < deadline_s && !all_down() && !stop())
    advance_to(std::min(deadline_s, now_s_ + 1.0));
}

// Every vehicle on the ground (disarmed or landed) or never heard; one heard before but silent
// now may still be flying (its own failsafe brings it home) and is waited for.
bool MavlinkFleet::all_down() const {
  for (const auto& v : vehicles_) {
    if (!v->driver) continue;  // never heard
    const mavlink::VehicleState& s = v->driver->state();
    if (!s.link_alive) {
      if (std::isfinite(s.last_heard_s)) return false;
      continue;
    }
    if (s.armed && s.landed != mavlink::LandedState::on_ground) return false;
  }
  return true;
}

// Home or land: armed on the ground (not yet off it), disarmed — an RTL would climb to its return
// altitude first; off the ground (climbing included: the landed state the vehicle reports is up
// to a second old, so "still climbing" cannot be told from "just in the air"), RTL or LAND as
// asked. A vehicle already returning or landing is left to it. Still steered
// after a refusal of anything else (a target outside the fence mid-air): only a vehicle refusing
// the step itself is left to its own failsafe.
void MavlinkFleet::come_down(Vehicle& v) {
  mavlink::Driver& d = *v.driver;
  const mavlink::VehicleState& s = d.state();
  const auto tries_left = [&](Vehicle::Step step) {
    return v.rejections[static_cast<std::size_t>(step)] < kMaxRejections;
  };
  const auto gate = [&](int id, Vehicle::Step step) {
    v.gate = id;
    v.gate_step = step;
  };
  if (!s.armed || d.returning()) return;
  if (s.landed == mavlink::LandedState::on_ground) {
    if (tries_left(Vehicle::Step::disarm)) gate(d.arm(false), Vehicle::Step::disarm);
    return;
  }
  const bool land = v.want == Vehicle::Want::land;
  if (land && tries_left(Vehicle::Step::land))
    gate(d.land(), Vehicle::Step::land);
  else if (!land && tries_left(Vehicle::Step::rtl))
    gate(d.return_to_launch(), Vehicle::Step::rtl);
}

// One step of the steering toward what the runtime wants, from the vehicle's reported state.
void MavlinkFleet::steer(Vehicle& v) {
  if (!v.driver) return;
  mavlink::Driver& d = *v.driver;
  const mavlink::VehicleState& s = d.state();
  if (v.gate >= 0) {
    const mavlink::CommandState c = d.command_state(v.gate);
    if (c == mavlink::CommandState::pending) return;
    int& rejected = v.rejections[static_cast<std::size_t>(v.gate_step)];
    const bool arm = v.gate_step == Vehicle::Step::arm;
    if (c == mavlink::CommandState::rejected && arm) {
      if (v.first_arm_refusal_s < 0) v.first_arm_refusal_s = now_s_;
      v.settle_until_s = now_s_ + kArmRetryS;  // asked again in a while, not at every poll
    } else if (c == mavlink::CommandState::rejected) {
      // Asked again once the state has been reported since: ArduCopter SITL under load took a
      // take-off whose acknowledgement never came, failed its resend (already taking off), and
      // three new take-offs sent within 60 ms of that refusal were failed too before its landed
      // state said "taking off".
      v.settle_until_s = now_s_ + kSettleS;
    }
    const bool patience_over = !arm || now_s_ - v.first_arm_refusal_s >= kArmPatienceS;
    if (c == mavlink::CommandState::rejected && ++rejected >= kMaxRejections && patience_over &&
        v.refusal.empty())
      v.refusal = Vehicle::refusal_text(v.gate_step, d) +
                  (s.status_texts.empty() ? std::string() : ": " + s.status_texts.back());
    // Mode and armed come with the 1 Hz HEARTBEAT, landed with the 1 Hz EXTENDED_SYS_STATE:
    // after an acceptance the state is trusted again once both have been sent since.
    if (c == mavlink::CommandState::accepted) {
      v.settle_until_s = now_s_ + kSettleS;
      rejected = 0;
      if (arm) v.first_arm_refusal_s = -1;
    }
    v.gate = -1;  // accepted, refused or timed out: the state says what comes next
  }
  if (now_s_ < v.settle_until_s) return;
  if (!s.link_alive) return;
  const bool armed = s.armed;
  const bool down = !armed || s.landed == mavlink::LandedState::on_ground;
  const auto gate = [&](int id, Vehicle::Step step) {
    v.gate = id;
    v.gate_step = step;
  };
  switch (v.want) {
    case Vehicle::Want::ground:
      return;
    case Vehicle::Want::home:
    case Vehicle::Want::land:
      come_down(v);
      return;
    case Vehicle::Want::go:
      break;
  }
  if (!v.refusal.empty()) return;                  // a refusal blocks going anywhere but home
  if (down && !settings_.allow_no_gcs_failsafe) {  // no take-off without the lost-link failsafe
    const std::optional<bool> off = d.failsafe_off();
    if (!off) return;  // the check still reads
    if (*off) {
      v.refusal = "its lost-link failsafe is off (" + s.warnings.back() +
                  "); --allow-no-gcs-failsafe flies it anyway";
      return;
    }
  }
  if (down && settings_.upload_fence && !fence_items_.empty()) {  // no take-off without it
    if (d.fence_state() == mavlink::FenceState::failed) {
      v.refusal = "its fence was not verified (" + d.fence_error() + ")";
      return;
    }
    if (d.fence_state() != mavlink::FenceState::verified) return;  // still on its way
  }
  if (!d.in_guided()) {  // from the ground, or after a failsafe RTL
    v.target_sent = false;
    v.speed_cmd = -1;
    gate(d.enter_guided(), Vehicle::Step::mode);
    return;
  }
  if (!armed) {
    gate(d.arm(), Vehicle::Step::arm);
    return;
  }
  if (s.landed == mavlink::LandedState::on_ground) {
    gate(d.takeoff(v.alt_m), Vehicle::Step::takeoff);
    return;
  }
  if (s.landed == mavlink::LandedState::takeoff) return;  // climbing to the layer
  if (!v.target_sent) {
    // ArduCopter's GUIDED plans a leg at the speed limit in force when its target arrives; a
    // DO_CHANGE_SPEED during the leg changes only the limit the next leg is planned with
    // (ModeGuided::set_speed_xy_cms sets AC_PosControl's limit; AC_WPNav plans the s-curve with
    // it). Sent beside the target, a cruise speed that was lost once, or waited behind another
    // DO_CHANGE_SPEED, arrived after it and the leg flew at the last approach speed. So the
    // cruise speed goes first, the target once the vehicle has answered it (accepted, refused or
    // timed out).
    if (v.speed_cmd < 0) {
      v.speed_cmd = d.set_speed(v.cruise_m_s);
      return;
    }
    if (d.command_state(v.speed_cmd) == mavlink::CommandState::pending) return;
    if (!d.go_to(v.lat_deg, v.lon_deg, v.alt_m)) {
      v.refusal = "target outside the fence";
      return;
    }
    v.target_sent = true;
    v.slowed = false;
  }
  if (!v.slowed && d.distance_to_target_m() <= v.approach_within_m) {
    d.set_speed(v.approach_m_s);  // paper 000 §4.2's approach rule
    v.slowed = true;
  }
}

void MavlinkFleet::advance_to(double t_s) {
  if (settings_.wall_clock && !start_) start_ = std::chrono::steady_clock::now();
  do {
    const double next = std::min(t_s, now_s_ + settings_.poll_step_s);
    if (settings_.wall_clock)
      std::this_thread::sleep_until(*start_ + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                  std::chrono::duration<double>(next)));
    else if (settings_.before_poll)
      settings_.before_poll(next);
    now_s_ = std::max(now_s_, next);
    last_poll_ns_.store(std::chrono::steady_clock::now().time_since_epoch().count());
    for (std::size_t i = 0; i < vehicles_.size(); ++i) {
      poll(*vehicles_[i], static_cast<int>(i));
      steer(*vehicles_[i]);
    }
  } while (now_s_ < t_s);
}

VehicleReport MavlinkFleet::report(int drone) const {
  const Vehicle& v = at(drone);
  VehicleReport r;
  r.refusal = v.refusal;
  if (!v.driver) return r;  // never heard
  const mavlink::VehicleState& s = v.driver->state();
  r.link_up = s.link_alive;
  if (s.position) {
    const geometry::Point2 p = geometry::LocalFrame(settings_.origin)
                                   .to_local({s.position->lat_degE7 / mavlink::kDegE7,
                                              s.position->lon_degE7 / mavlink::kDegE7});
    r.position_known = true;
    r.position_m = {p.x, p.y, s.position->relative_alt_mm / 1000.0};
  }
  if (s.battery_remaining_percent >= 0) r.battery_soc = s.battery_remaining_percent / 100.0;
  if (!s.link_alive) return r;  // what it said last is stale: no arrival, no landing
  r.arrived = v.want == Vehicle::Want::go && v.target_sent && v.driver->arrived();
  r.landed_home =
      v.want == Vehicle::Want::home && !s.armed && s.landed == mavlink::LandedState::on_ground;
  return r;
}

std::unique_ptr<MavlinkFleet> open_mavlink_fleet(const std::vector<VehicleAddress>& urls,
                                                 MavlinkFleetSettings settings) {
  std::vector<std::unique_ptr<mavlink::Link>> links;
  std::vector<std::uint8_t> sysids;
  for (const VehicleAddress& u : urls) {
    if (u.tcp)
      links.push_back(
          std::make_unique<mavlink::TcpLink>(mavlink::TcpLink::connect(u.host, u.port)));
    else
      links.push_back(std::make_unique<mavlink::UdpLink>(  // answers only its vehicle's system
          mavlink::UdpLink::listen(u.host, u.port, u.sysid)));
    sysids.push_back(u.sysid);
  }
  return std::make_unique<MavlinkFleet>(std::move(links), sysids, std::move(settings));
}

}  // namespace swath::fleet
