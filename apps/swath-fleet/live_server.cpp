#include "live_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include "swath/base/input_error.hpp"

namespace swath::apps {
namespace {

using base::InputError;

// A request line and headers longer than this are no browser's: the connection is closed.
constexpr std::size_t kMaxRequestBytes = 16 * 1024;
// How often the server looks for new lines when nothing else wakes it, ms.
constexpr int kPollMs = 50;

// All of `data`, or false (the peer went away, or did not read for the send timeout).
bool send_all(int fd, const std::string& data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A header's value ("" when absent); names compared without case.
std::string header(const std::string& request, const std::string& name) {
  const std::string text = lower(request), key = "\r\n" + lower(name) + ":";
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return "";
  std::size_t from = at + key.size();
  const std::size_t end = request.find("\r\n", from);
  while (from < end && request[from] == ' ') ++from;
  return request.substr(from, end - from);
}

std::string response(const std::string& status, const std::string& type, const std::string& body) {
  return "HTTP/1.1 " + status + "\r\nContent-Type: " + type +
         "\r\nContent-Length: " + std::to_string(body.size()) +
         "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n" + body;
}

}  // namespace

int live_port(const std::string& text) {
  if (text.empty()) return kDefaultLivePort;
  const bool digits = text.size() <= 5 && std::all_of(text.begin(), text.end(), [](char c) {
                        return std::isdigit(static_cast<unsigned char>(c));
                      });
  if (!digits || std::stoi(text) > 65535)
    throw InputError("--live " + text +
                     ": not a port (0 to 65535; 0 for any free port; put --live after APP)");
  return std::stoi(text);
}

LiveServer::LiveServer(int port, std::string page) : page_(std::move(page)) {
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0)
    throw InputError("--live: cannot open a socket: " + std::string(std::strerror(errno)));
  const int one = 1;  // a port left in TIME_WAIT by the last run may be had again
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // this machine only, never the network
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(listen_fd_, 16) != 0) {
    const int e = errno;
    ::close(listen_fd_);
    throw InputError("--live " + std::to_string(port) + ": 127.0.0.1:" + std::to_string(port) +
                     (e == EADDRINUSE
                          ? " is in use by another program; give another port, or 0 "
                            "for any free one"
                          : " cannot be listened on: " + std::string(std::strerror(e))));
  }
  socklen_t size = sizeof addr;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &size);
  port_ = ntohs(addr.sin_port);
  thread_ = std::thread([this] { serve(); });
}

LiveServer::~LiveServer() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  for (const Client& c : clients_) ::close(c.fd);
  ::close(listen_fd_);
}

std::string LiveServer::url() const {
  return "http://127.0.0.1:" + std::to_string(port_) + "/";
}

void LiveServer::append(const std::string& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  lines_.push_back(line);
}

void LiveServer::serve() {
  while (!stop_) {
    std::vector<pollfd> fds{{listen_fd_, POLLIN, 0}};
    for (const Client& c : clients_) fds.push_back({c.fd, POLLIN, 0});
    if (::poll(fds.data(), fds.size(), kPollMs) < 0 && errno != EINTR) return;
    // A client accepted now was not among those polled: it has no events yet.
    const std::size_t polled = clients_.size();
    if (fds[0].revents & POLLIN) accept_client();
    std::vector<Client> kept;
    for (std::size_t k = 0; k < clients_.size(); ++k) {
      Client& c = clients_[k];
      const short events = k < polled ? fds[k + 1].revents : short{0};
      bool open = true;
      if (events & (POLLIN | POLLHUP | POLLERR)) open = read_request(c);
      if (open && c.streaming) open = send_lines(c);
      if (open)
        kept.push_back(c);
      else
        ::close(c.fd);
    }
    clients_ = std::move(kept);
  }
}

void LiveServer::accept_client() {
  const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
  if (fd < 0) return;
  // A browser that stops reading must not stop the server for longer than this.
  const timeval timeout{2, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
  clients_.push_back(Client{fd, "", false, 0});
}

bool LiveServer::read_request(Client& c) {
  char buffer[4096];
  const ssize_t n = ::recv(c.fd, buffer, sizeof buffer, 0);
  if (n <= 0) return false;
  if (c.streaming) return true;  // nothing more is expected on a stream: ignored
  c.request.append(buffer, static_cast<std::size_t>(n));
  if (c.request.size() > kMaxRequestBytes) return false;
  if (c.request.find("\r\n\r\n") == std::string::npos) return true;
  return answer(c);
}

bool LiveServer::answer(Client& c) {
  const std::size_t line_end = c.request.find("\r\n");
  const std::string line = c.request.substr(0, line_end);
  const std::string host = header(c.request, "Host"), port = ":" + std::to_string(port_);
  // Only pages of this machine's own names: a web page elsewhere that rebinds its DNS name to
  // 127.0.0.1 sends its own Host and is refused.
  if (host != "127.0.0.1" + port && host != "localhost" + port) {
    send_all(c.fd, response("403 Forbidden", "text/plain", "only http://127.0.0.1" + port + "/\n"));
    return false;
  }
  if (line.rfind("GET / ", 0) == 0 || line.rfind("GET /index.html ", 0) == 0) {
    send_all(c.fd, response("200 OK", "text/html; charset=utf-8", page_));
    return false;
  }
  if (line.rfind("GET /events ", 0) != 0) {
    send_all(c.fd, response("404 Not Found", "text/plain", "not found\n"));
    return false;
  }
  // A reconnecting EventSource says the last line it had: the stream goes on after it.
  const std::string last = header(c.request, "Last-Event-ID");
  if (!last.empty() && last.size() < 12 &&
      std::all_of(last.begin(), last.end(), [](char ch) { return ch >= '0' && ch <= '9'; }))
    c.next = std::stoull(last) + 1;
  c.streaming = true;
  return send_all(c.fd,
                  "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: "
                  "no-store\r\nConnection: keep-alive\r\n\r\n");
}

bool LiveServer::send_lines(Client& c) {
  std::string out;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (; c.next < lines_.size(); ++c.next)
      out += "id: " + std::to_string(c.next) + "\ndata: " + lines_[c.next] + "\n\n";
  }
  return out.empty() || send_all(c.fd, out);
}

}  // namespace swath::apps
