#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <system_error>
#include <utility>

#include "swath/mavlink/link.hpp"

#include "swath/mavlink/frame.hpp"

namespace swath::mavlink {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

sockaddr_in address_of(const std::string& host, std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  if (inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1) {
    errno = EINVAL;
    fail("UDP address " + host + ": not an IPv4 address");
  }
  return a;
}

int open_socket(const std::string& where) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) fail("UDP socket for " + where);
  return fd;
}

}  // namespace

UdpLink UdpLink::listen(const std::string& host, std::uint16_t port, std::uint8_t peer_sysid) {
  const std::string where = host + ":" + std::to_string(port);
  const sockaddr_in a = address_of(host, port);
  UdpLink link;
  link.fd_ = open_socket(where);
  if (bind(link.fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0)
    fail("UDP listen on " + where);
  link.learn_peer_ = true;
  link.peer_sysid_ = peer_sysid;
  return link;
}

UdpLink UdpLink::connect(const std::string& host, std::uint16_t port) {
  const sockaddr_in a = address_of(host, port);
  UdpLink link;
  link.fd_ = open_socket(host + ":" + std::to_string(port));
  link.has_peer_ = true;
  link.peer_address_ = a.sin_addr.s_addr;
  link.peer_port_ = a.sin_port;
  return link;
}

UdpLink::UdpLink(UdpLink&& other) noexcept {
  *this = std::move(other);
}

UdpLink& UdpLink::operator=(UdpLink&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    has_peer_ = other.has_peer_;
    learn_peer_ = other.learn_peer_;
    peer_address_ = other.peer_address_;
    peer_port_ = other.peer_port_;
    peer_sysid_ = other.peer_sysid_;
  }
  return *this;
}

UdpLink::~UdpLink() {
  if (fd_ >= 0) close(fd_);
}

void UdpLink::send(std::span<const std::uint8_t> bytes) {
  if (!has_peer_ || bytes.empty()) return;
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = peer_address_;
  to.sin_port = peer_port_;
  // A full buffer or a peer gone drops the datagram, as the radio link would: MAVLink resends.
  (void)sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to),
               sizeof to);
}

std::size_t UdpLink::receive(std::vector<std::uint8_t>& out) {
  std::size_t total = 0;
  std::array<std::uint8_t, 65536> buffer;
  while (total < kMaxReceiveBytes) {
    sockaddr_in from{};
    socklen_t from_length = sizeof from;
    const ssize_t n = recvfrom(fd_, buffer.data(), buffer.size(), 0,
                               reinterpret_cast<sockaddr*>(&from), &from_length);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == ECONNREFUSED) return total;
      if (errno == EINTR) continue;
      fail("UDP receive");
    }
    if (learn_peer_ && !from_peer(from, {buffer.data(), static_cast<std::size_t>(n)})) continue;
    out.insert(out.end(), buffer.begin(), buffer.begin() + n);
    total += static_cast<std::size_t>(n);
  }
  return total;
}

// The peer is the sender of the latest datagram that holds a good MAVLink frame (CRC and
// length right, a message swath knows) from the expected system: junk and strangers' datagrams
// are dropped, so a 1-byte sender no longer takes the vehicle's place as the peer that swath's
// commands go to. A vehicle that restarts on another port is followed by its first good frame.
bool UdpLink::from_peer(const sockaddr_in& from, std::span<const std::uint8_t> datagram) {
  const bool same =
      has_peer_ && from.sin_addr.s_addr == peer_address_ && from.sin_port == peer_port_;
  if (same) return true;
  FrameParser parser;
  parser.feed(datagram);
  parser.finish();
  bool good = false;
  for (Frame f; parser.next(f);) good = good || peer_sysid_ == 0 || f.header.sysid == peer_sysid_;
  // A signed frame (MAVLink 2 signing, signing_link.hpp) with a good checksum, from the expected
  // system, also names the peer: the link cannot check its signature, the SigningLink above does.
  good = good || (parser.stats().signed_dropped > 0 && datagram.size() > 5 &&
                  datagram[0] == kStxV2 && (peer_sysid_ == 0 || datagram[5] == peer_sysid_));
  if (!good) return false;
  has_peer_ = true;
  peer_address_ = from.sin_addr.s_addr;
  peer_port_ = from.sin_port;
  return true;
}

std::uint16_t UdpLink::local_port() const {
  sockaddr_in a{};
  socklen_t length = sizeof a;
  if (getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &length) != 0) fail("UDP local port");
  return ntohs(a.sin_port);
}

TcpLink TcpLink::connect(const std::string& host, std::uint16_t port) {
  const std::string where = host + ":" + std::to_string(port);
  const sockaddr_in a = address_of(host, port);
  TcpLink link;
  link.fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (link.fd_ < 0) fail("TCP socket for " + where);
  if (::connect(link.fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0)
    fail("TCP connect to " + where);
  const int one = 1;  // frames are small and latency matters more than packing
  (void)setsockopt(link.fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  if (fcntl(link.fd_, F_SETFL, fcntl(link.fd_, F_GETFL) | O_NONBLOCK) != 0)
    fail("TCP non-blocking mode for " + where);
  return link;
}

TcpLink::TcpLink(TcpLink&& other) noexcept {
  *this = std::move(other);
}

TcpLink& TcpLink::operator=(TcpLink&& other) noexcept {
  if (this != &other) {
    close_socket();
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

TcpLink::~TcpLink() {
  close_socket();
}

void TcpLink::close_socket() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

void TcpLink::send(std::span<const std::uint8_t> bytes) {
  std::size_t done = 0;
  while (fd_ >= 0 && done < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + done, bytes.size() - done, MSG_NOSIGNAL);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      return;  // a full socket drops the rest of this frame, as a saturated radio would
    } else {
      close_socket();  // the peer is gone
    }
  }
}

std::size_t TcpLink::receive(std::vector<std::uint8_t>& out) {
  std::size_t total = 0;
  std::array<std::uint8_t, 65536> buffer;
  while (fd_ >= 0 && total < kMaxReceiveBytes) {
    const ssize_t n =
        recv(fd_, buffer.data(), std::min(buffer.size(), kMaxReceiveBytes - total), 0);
    if (n > 0) {
      out.insert(out.end(), buffer.begin(), buffer.begin() + n);
      total += static_cast<std::size_t>(n);
    } else if (n == 0) {
      close_socket();  // orderly shutdown by the peer
    } else if (errno == EINTR) {
      continue;
    } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
      break;
    } else {
      close_socket();
    }
  }
  return total;
}

}  // namespace swath::mavlink
