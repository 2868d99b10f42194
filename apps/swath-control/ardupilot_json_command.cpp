// swath-control ardupilot-json: the UDP side of control::ArduPilotJsonServer. One datagram in,
// one JSON line back to its sender, lock-step (ArduPilot waits for every answer).
#include "ardupilot_json_command.hpp"

#include "flight_inputs.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "data_dir.hpp"
#include "seed_option.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/control/ardupilot_json.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/vehicle/vehicle_files.hpp"

namespace swath::apps {
namespace {

using base::InputError;
namespace fs = std::filesystem;

volatile sig_atomic_t g_stop = 0;  // set by the SIGINT/SIGTERM/SIGHUP handler only
extern "C" void note_stop(int) {
  g_stop = 1;
}

// SIGINT, SIGTERM and SIGHUP end the serving loop (poll returns EINTR), not the process: the
// summary and the CSV are still written.
class ServeStopSignals {
 public:
  ServeStopSignals() {
    g_stop = 0;
    struct sigaction action {};
    action.sa_handler = note_stop;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, &previous_int_);
    ::sigaction(SIGTERM, &action, &previous_term_);
    ::sigaction(SIGHUP, &action, &previous_hup_);
  }
  ~ServeStopSignals() {
    ::sigaction(SIGINT, &previous_int_, nullptr);
    ::sigaction(SIGTERM, &previous_term_, nullptr);
    ::sigaction(SIGHUP, &previous_hup_, nullptr);
  }
  ServeStopSignals(const ServeStopSignals&) = delete;
  ServeStopSignals& operator=(const ServeStopSignals&) = delete;

 private:
  struct sigaction previous_int_ {
  }, previous_term_{}, previous_hup_{};
};

class JsonUdpSocket {
 public:
  JsonUdpSocket(const std::string& address, int port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    if (::inet_pton(AF_INET, address.c_str(), &a.sin_addr) != 1)
      throw InputError("--address " + address + ": expected an IPv4 address such as 127.0.0.1");
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd_);
      throw InputError("--port " + std::to_string(port) + ": cannot listen on " + address + ":" +
                       std::to_string(port) + " (" + reason + ")");
    }
  }
  ~JsonUdpSocket() { ::close(fd_); }
  JsonUdpSocket(const JsonUdpSocket&) = delete;
  JsonUdpSocket& operator=(const JsonUdpSocket&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

std::string flight_csv_header(std::size_t rotors) {
  std::string h =
      "time_s,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,roll_deg,pitch_deg,yaw_deg,on_ground,"
      "motor_power_w";
  for (std::size_t i = 1; i <= rotors; ++i) h += ",rotor" + std::to_string(i) + "_pwm_us";
  return h + ",energy_wh,soc,battery_v\n";
}

std::string flight_csv_row(const control::JsonFlightRow& r) {
  using base::fixed_text;
  constexpr double kToDeg = 180.0 / std::numbers::pi;
  std::string s = fixed_text(r.time_s, 3);
  for (double v : {r.position_m_enu.x, r.position_m_enu.y, r.position_m_enu.z, r.velocity_m_s_enu.x,
                   r.velocity_m_s_enu.y, r.velocity_m_s_enu.z})
    s += "," + fixed_text(v, 3);
  for (double v : {r.attitude_rad.x, r.attitude_rad.y, r.attitude_rad.z})
    s += "," + fixed_text(v * kToDeg, 2);
  s += r.on_ground ? ",1," : ",0,";
  s += fixed_text(r.motor_power_w, 1);
  for (double p : r.pwm_us) s += "," + fixed_text(p, 0);
  s += "," + fixed_text(r.energy_wh, 4) + "," + fixed_text(r.soc, 5) + "," +
       fixed_text(r.battery_v, 3);
  return s + "\n";
}

// summary.json: what was served, the battery, the flight's time off the ground.
std::string summary_json(const control::ArduPilotJsonServer& server,
                         const std::string& vehicle_name, const std::string& environment,
                         std::uint64_t seed) {
  using nlohmann::ordered_json;
  const control::JsonEnergy& e = server.energy();
  const auto round_to = [](double v, int digits) {
    const double scale = std::pow(10.0, digits);
    return std::round(v * scale) / scale;
  };
  ordered_json j;
  j["vehicle"] = vehicle_name;
  j["environment"] = environment;
  j["seed"] = seed;
  j["frames_served"] = server.frames_served();
  j["resends"] = server.resends();
  j["bad_packets"] = server.bad_packets();
  j["simulated_s"] = round_to(server.sim_time_s(), 3);
  j["airborne_s"] = round_to(server.airborne_s(), 3);
  j["max_tilt_deg"] = round_to(server.max_tilt_deg(), 2);
  j["energy"] = {{"total_wh", round_to(e.total_j() / 3600.0, 4)},
                 {"motors_wh", round_to(e.motors_j / 3600.0, 4)},
                 {"avionics_wh", round_to(e.avionics_j / 3600.0, 4)},
                 {"final_soc", round_to(e.soc, 6)},
                 {"final_voltage_v", round_to(e.voltage_v, 3)},
                 {"battery_empty", e.battery_empty}};
  return base::json_text(j, 1) + "\n";
}

}  // namespace

void ControlArduPilotJsonCommand::setup(CLI::App& app) {
  app.add_option(
         "--vehicle", vehicle_,
         "Vehicle file, or a bundled one (quad-f450; its rotors must be an ArduCopter "
         "quad X, quad X_REV or hexa X; the program prints the FRAME_CLASS and FRAME_TYPE to set)")
      ->capture_default_str();
  app.add_option("--environment", environment_,
                 "Wind: calm, lab, rugby, arch (paper 002's places) or an environment file")
      ->capture_default_str();
  app.add_option("--port", port_,
                 "UDP port ArduPilot sends its servo packets to (arducopter's JSON default 9002)")
      ->check(CLI::Range(1, 65535))
      ->capture_default_str();
  app.add_option("--address", address_, "IPv4 address to listen on")->capture_default_str();
  app.add_option("--seed", seed_, "Seed of the wind's turbulence and gusts and the torque noise")
      ->check(seed_check())
      ->capture_default_str();
  app.add_option("-o,--output", output_,
                 "Directory for flight.csv: the true state at 50 Hz of simulated time (world ENU "
                 "about the start point, attitude roll/pitch/yaw in degrees NED, PWM per swath "
                 "rotor, the battery's energy drawn, SoC and voltage) and summary.json (energy, "
                 "time airborne, largest tilt), written when serving stops");
  app.add_option("--idle-exit", idle_exit_s_,
                 "Stop after this many wall-clock seconds without a packet once packets have "
                 "come (0: only Ctrl-C stops)")
      ->check(CLI::Range(0.0, 86'400.0))
      ->capture_default_str();
}

int ControlArduPilotJsonCommand::run() {
  // 1. Everything checked before serving: files, the frame, the output directory, the port.
  control::ArduPilotJsonSettings settings;
  const ConfigFile vehicle_file = config_file(vehicle_, "vehicles", "vehicle", "--vehicle");
  settings.physics = vehicle::parse_vehicle(vehicle_file.text, vehicle_file.source);
  const ConfigFile environment_file =
      config_file(environment_, "environments", "environment", "--environment");
  settings.environment = vehicle::parse_environment(environment_file.text, environment_file.source);
  for (const auto* warnings : {&settings.physics.warnings, &settings.environment.warnings})
    for (const std::string& w : *warnings) std::cerr << "warning: " << w << '\n';
  settings.battery = energy::parse_battery_section(vehicle_file.text, vehicle_file.source);
  settings.seed = seed_;
  settings.source = vehicle_file.source;
  control::ArduPilotJsonServer server(settings);
  if (!output_.empty()) {  // refused before serving, not after the flight
    const base::OutputSet probe(output_, "control-ardupilot-json");  // not committed
    base::check_output_names(output_, "control-ardupilot-json", {"flight.csv", "summary.json"});
  }
  JsonUdpSocket socket(address_, port_);

  const control::MotorMap& map = server.motor_map();
  std::cout << "swath-control ardupilot-json: " << settings.physics.airframe.name
            << " as ArduCopter " << map.frame << " on " << address_ << ":" << port_ << "; outputs";
  for (std::size_t m = 0; m < map.rotor.size(); ++m)
    std::cout << (m ? ", " : " ") << m + 1 << "->rotor " << map.rotor[m] + 1
              << (map.spin[m] > 0 ? " ccw" : " cw");
  std::cout << "; Ctrl-C stops" << std::endl;

  // 2. Serving, until a signal (or --idle-exit).
  std::string csv = flight_csv_header(settings.physics.airframe.rotors.size());
  long long next_row = 0;  // in 20 ms ticks of simulated time
  {
    ServeStopSignals signals;
    std::array<std::uint8_t, 2048> buffer{};
    auto last_packet = std::chrono::steady_clock::now();
    bool any = false;
    while (!g_stop) {
      pollfd p{socket.fd(), POLLIN, 0};
      const int ready = ::poll(&p, 1, 200);
      if (ready < 0 && errno != EINTR)
        throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
      if (ready <= 0) {
        const double idle_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - last_packet).count();
        if (any && idle_exit_s_ > 0 && idle_s > idle_exit_s_) break;
        continue;
      }
      sockaddr_storage from{};
      socklen_t from_size = sizeof from;
      const ssize_t n = ::recvfrom(socket.fd(), buffer.data(), buffer.size(), 0,
                                   reinterpret_cast<sockaddr*>(&from), &from_size);
      if (n < 0) continue;
      last_packet = std::chrono::steady_clock::now();
      any = true;
      const auto reply = server.handle(buffer.data(), static_cast<std::size_t>(n));
      if (!reply) continue;
      ::sendto(socket.fd(), reply->data(), reply->size(), 0, reinterpret_cast<sockaddr*>(&from),
               from_size);
      if (!output_.empty() && server.sim_time_s() * 50 >= static_cast<double>(next_row)) {
        csv += flight_csv_row(server.row());
        next_row = static_cast<long long>(std::floor(server.sim_time_s() * 50)) + 1;
      }
    }
  }

  // 3. What was served.
  if (!output_.empty()) {
    base::OutputSet set(output_, "control-ardupilot-json");
    set.add("flight.csv", csv);
    set.add("summary.json",
            summary_json(server, settings.physics.airframe.name, environment_, seed_));
    set.commit();
  }
  std::cout << "swath-control ardupilot-json: served " << server.frames_served() << " frames ("
            << server.resends() << " resends answered again, " << server.bad_packets()
            << " bad packets ignored), " << base::fixed_text(server.sim_time_s(), 1)
            << " s simulated, " << base::fixed_text(server.airborne_s(), 1) << " s airborne; "
            << base::fixed_text(server.energy().total_j() / 3600.0, 2) << " Wh drawn (motors "
            << base::fixed_text(server.energy().motors_j / 3600.0, 2) << "), SoC "
            << base::fixed_text(server.energy().soc, 3);
  if (!output_.empty()) std::cout << "; wrote " << output_;
  std::cout << '\n';
  return base::kExitSuccess;
}

}  // namespace swath::apps
