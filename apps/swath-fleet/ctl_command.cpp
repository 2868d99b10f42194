// swath-fleet ctl (ctl_command.hpp): connects to the run's socket, sends the verb as one line,
// prints the run's answer.
#include "ctl_command.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "swath/base/input_error.hpp"

namespace swath::apps {

namespace {
// Where run --ctl-socket and ctl --socket meet when ctl is given no --socket.
std::string default_socket() {
  const char* dir = std::getenv("XDG_RUNTIME_DIR");
  return dir && *dir ? std::string(dir) + "/swath-fleet.sock" : std::string();
}
}  // namespace

void FleetCtlCommand::setup(CLI::App& app) {
  app.add_option("VERB", verb_,
                 "pause: the vehicles hold where they are and nothing is dispatched; resume; "
                 "rtl-all: every airborne vehicle returns to launch and the run ends; land-all: "
                 "every airborne vehicle lands where it is and the run ends")
      ->required()
      ->check(CLI::IsMember({"pause", "resume", "rtl-all", "land-all"}));
  app.add_option("--socket", socket_,
                 "The run's control socket (run --ctl-socket PATH); default "
                 "$XDG_RUNTIME_DIR/swath-fleet.sock");
}

int FleetCtlCommand::run() {
  std::string path = socket_.empty() ? default_socket() : socket_;
  if (path.empty())
    throw base::InputError("--socket: give the run's socket (XDG_RUNTIME_DIR is not set)");
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.size() >= sizeof(address.sun_path))
    throw base::InputError("--socket " + path + ": longer than " +
                           std::to_string(sizeof(address.sun_path) - 1) + " bytes");
  std::memcpy(address.sun_path, path.data(), path.size());
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0 || ::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    throw base::InputError("--socket " + path + ": no swath-fleet run listens there (" + why + ")");
  }
  const std::string line = verb_ + "\n";
  ::send(fd, line.data(), line.size(), MSG_NOSIGNAL);
  ::shutdown(fd, SHUT_WR);
  std::string reply;
  char buffer[256];
  for (;;) {  // the run answers at its next step: a tick, or a few seconds at most
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 10000) <= 0) break;
    const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
    if (n <= 0) break;
    reply.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (reply.rfind("ok ", 0) != 0)
    throw base::InputError("--socket " + path + ": the run did not take \"" + verb_ + "\"" +
                           (reply.empty() ? std::string(" (no answer)") : ": " + reply));
  std::cout << "swath-fleet ctl: " << reply;
  return base::kExitSuccess;
}

}  // namespace swath::apps
