// swath-fleet run's orders from outside (run_control.hpp).
#include "run_control.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "swath/base/input_error.hpp"

namespace swath::apps {

namespace {

volatile sig_atomic_t g_signal = 0;  // the first SIGINT/SIGTERM; set by the handler only
struct sigaction g_previous_int {
}, g_previous_term{};
sigset_t g_mask_before;

extern "C" void note_signal(int signal_number) {
  if (g_signal == 0) g_signal = signal_number;
}

void install_handlers() {
  g_signal = 0;
  struct sigaction action {};
  action.sa_handler = note_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, &g_previous_int);
  ::sigaction(SIGTERM, &action, &g_previous_term);
}

void restore_handlers() {
  ::sigaction(SIGINT, &g_previous_int, nullptr);
  ::sigaction(SIGTERM, &g_previous_term, nullptr);
}

std::string errno_text() {
  return std::strerror(errno);
}

// The socket's directory must be the user's own and closed to others: nobody else can then put
// a socket of theirs at the path, or replace ours.
void check_directory(const std::string& socket_path) {
  std::filesystem::path dir = std::filesystem::path(socket_path).parent_path();
  if (dir.empty()) dir = ".";
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0)
    throw base::InputError("--ctl-socket " + socket_path + ": its directory " + dir.string() +
                           " cannot be read (" + errno_text() + ")");
  if (!S_ISDIR(st.st_mode))
    throw base::InputError("--ctl-socket " + socket_path + ": " + dir.string() +
                           " is not a directory");
  if (st.st_uid != ::geteuid() || (st.st_mode & (S_IWGRP | S_IWOTH)) != 0)
    throw base::InputError("--ctl-socket " + socket_path + ": the directory " + dir.string() +
                           " must be yours and not writable by others (e.g. $XDG_RUNTIME_DIR)");
}

sockaddr_un socket_address(const std::string& path, const char* option) {
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  if (path.size() >= sizeof(a.sun_path))
    throw base::InputError(std::string(option) + " " + path + ": longer than " +
                           std::to_string(sizeof(a.sun_path) - 1) + " bytes (a socket's limit)");
  std::memcpy(a.sun_path, path.data(), path.size());
  return a;
}

// Whether a run listens at `path` (a connection is taken).
bool someone_listens(const sockaddr_un& address) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  const bool up = ::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
  ::close(fd);
  return up;
}

// Makes the listening socket at `path`, mode 0600 from the start (umask around bind).
int listen_at(const std::string& path) {
  check_directory(path);
  const sockaddr_un address = socket_address(path, "--ctl-socket");
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode))
      throw base::InputError("--ctl-socket " + path +
                             ": the path exists and is not a socket; refusing to replace it");
    if (someone_listens(address))
      throw base::InputError("--ctl-socket " + path + ": another swath-fleet run listens there");
    ::unlink(path.c_str());  // left by a run that was killed
  }
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw base::InputError("--ctl-socket " + path + ": socket: " + errno_text());
  const mode_t before = ::umask(0177);
  const int bound = ::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address));
  const int bind_errno = errno;
  ::umask(before);
  if (bound != 0 || ::listen(fd, 8) != 0) {
    ::close(fd);
    errno = bind_errno;
    throw base::InputError("--ctl-socket " + path + ": cannot listen there (" + errno_text() + ")");
  }
  return fd;
}

// One client's line, waited for at most 50 ms (ctl sends it as soon as it is connected): the
// runtime's loop, and with it the vehicles' heartbeat, is never held longer.
std::string read_line(int fd) {
  std::string line;
  char buffer[64];
  while (line.size() < 64 && line.find('\n') == std::string::npos) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) break;
    const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
    if (n <= 0) break;
    line.append(buffer, static_cast<std::size_t>(n));
  }
  const std::size_t end = line.find_first_of("\r\n");
  return end == std::string::npos ? line : line.substr(0, end);
}

}  // namespace

std::optional<fleet::ControlOrder> ctl_order(const std::string& verb) {
  if (verb == "pause") return fleet::ControlOrder::pause;
  if (verb == "resume") return fleet::ControlOrder::resume;
  if (verb == "rtl-all") return fleet::ControlOrder::rtl_all;
  if (verb == "land-all") return fleet::ControlOrder::land_all;
  return std::nullopt;
}

RunControl::RunControl(fleet::AbortAction on_abort, std::string socket_path)
    : on_abort_(on_abort), socket_path_(std::move(socket_path)) {
  if (!socket_path_.empty()) listen_fd_ = listen_at(socket_path_);
  install_handlers();
}

RunControl::~RunControl() {
  restore_handlers();
  if (signals_held_) ::pthread_sigmask(SIG_SETMASK, &g_mask_before, nullptr);
  if (listen_fd_ >= 0) {
    ::close(listen_fd_);
    ::unlink(socket_path_.c_str());
  }
}

int noted_signal() {
  return g_signal;
}

int RunControl::signal_number() const {
  return g_signal;
}

void RunControl::hold_signals() {
  if (signals_held_) return;
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  ::pthread_sigmask(SIG_BLOCK, &set, &g_mask_before);
  signals_held_ = true;
}

// Every client waiting: its verb read, answered ("ok VERB" or why not) and queued.
void RunControl::accept_clients() {
  for (;;) {
    const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) return;
    const std::string verb = read_line(client);
    const std::optional<fleet::ControlOrder> order = ctl_order(verb);
    const std::string reply =
        order ? "ok " + verb + "\n"
              : "error: unknown order \"" + verb + "\"; use pause, resume, rtl-all or land-all\n";
    ::send(client, reply.data(), reply.size(), MSG_NOSIGNAL);
    ::close(client);
    if (order) orders_.push_back({*order, "ctl " + verb});
  }
}

fleet::ControlRequest RunControl::poll() {
  const int s = g_signal;
  if (s != 0 && !signal_taken_) {
    signal_taken_ = true;
    return {on_abort_ == fleet::AbortAction::land ? fleet::ControlOrder::land_all
                                                  : fleet::ControlOrder::rtl_all,
            s == SIGINT ? "SIGINT" : "SIGTERM"};
  }
  if (listen_fd_ >= 0) accept_clients();
  if (orders_.empty()) return {};
  fleet::ControlRequest r = std::move(orders_.front());
  orders_.pop_front();
  return r;
}

}  // namespace swath::apps
