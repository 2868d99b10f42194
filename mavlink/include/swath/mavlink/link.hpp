#pragma once
// Byte links a MAVLink node talks over: an interface, and POSIX UDP on IPv4 (ArduPilot SITL and
// companion routers speak UDP; TCP to SITL's port 5760 + 10 x instance is the same interface).

#include <netinet/in.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace swath::mavlink {

/// The most bytes one receive() appends. A peer that streams faster than the caller reads (junk
/// from a local process drove a reader without this bound to 16 GB) leaves the rest in the
/// socket's buffer for the next call, where TCP's flow control holds the sender back; 1 MiB is
/// ~4,000 full MAVLink 2 frames, far more than a fleet sends between two runtime ticks.
inline constexpr std::size_t kMaxReceiveBytes = std::size_t{1} << 20;

/// Where datagrams or bytes go and come from. Never blocks.
class Link {
 public:
  virtual ~Link() = default;
  /// Sends bytes to the peer (dropped if there is no peer yet, as a radio would).
  virtual void send(std::span<const std::uint8_t> bytes) = 0;
  /// Appends what arrived since the last call to `out`, at most kMaxReceiveBytes (plus one
  /// datagram); returns the number of bytes appended.
  virtual std::size_t receive(std::vector<std::uint8_t>& out) = 0;
};

/// UDP on IPv4. A listening link learns its peer from the datagrams it receives (what ArduPilot's
/// `--out udp:` and MAVProxy expect of a ground station): the sender of the latest datagram that
/// holds a good MAVLink frame from the expected system; other datagrams from other senders are
/// dropped unread. A connected link sends to a fixed peer. Socket errors throw std::system_error
/// naming the address.
class UdpLink final : public Link {
 public:
  /// Listens on host:port (port 0: any free port, see local_port()), taking as its peer only a
  /// sender of good MAVLink frames from system `peer_sysid` (0: from any system).
  static UdpLink listen(const std::string& host, std::uint16_t port, std::uint8_t peer_sysid = 0);
  /// Sends to host:port from an ephemeral local port.
  static UdpLink connect(const std::string& host, std::uint16_t port);
  UdpLink(UdpLink&& other) noexcept;
  UdpLink& operator=(UdpLink&& other) noexcept;
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;
  ~UdpLink() override;

  void send(std::span<const std::uint8_t> bytes) override;
  std::size_t receive(std::vector<std::uint8_t>& out) override;
  std::uint16_t local_port() const;

 private:
  UdpLink() = default;
  bool from_peer(const sockaddr_in& from, std::span<const std::uint8_t> datagram);
  int fd_ = -1;
  bool has_peer_ = false;
  bool learn_peer_ = false;
  std::uint32_t peer_address_ = 0;  // network byte order
  std::uint16_t peer_port_ = 0;     // network byte order
  std::uint8_t peer_sysid_ = 0;     // 0: any system
};

/// TCP on IPv4, as a client (ArduPilot SITL listens on port 5760 + 10 x instance). A byte stream:
/// frames may arrive split, which the parser joins. Once the peer closes, sends are dropped and
/// closed() is true. Errors connecting throw std::system_error naming the address.
class TcpLink final : public Link {
 public:
  /// Connects to host:port (blocking until connected or refused), then works without blocking.
  static TcpLink connect(const std::string& host, std::uint16_t port);
  TcpLink(TcpLink&& other) noexcept;
  TcpLink& operator=(TcpLink&& other) noexcept;
  TcpLink(const TcpLink&) = delete;
  TcpLink& operator=(const TcpLink&) = delete;
  ~TcpLink() override;

  void send(std::span<const std::uint8_t> bytes) override;
  std::size_t receive(std::vector<std::uint8_t>& out) override;
  bool closed() const { return fd_ < 0; }

 private:
  TcpLink() = default;
  void close_socket();
  int fd_ = -1;
};

}  // namespace swath::mavlink
