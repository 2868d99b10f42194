#pragma once
// A Link two threads can use: every send and receive of the link it wraps under one mutex.
// MavlinkFleet's keep-alive thread sends the ground station's HEARTBEAT through it while the
// runtime's thread is busy (docs/swath-fleet.md, "The heartbeat").

#include <memory>
#include <mutex>

#include "swath/mavlink/link.hpp"

namespace swath::mavlink {

class SharedLink final : public Link {
 public:
  explicit SharedLink(std::unique_ptr<Link> link) : link_(std::move(link)) {}
  void send(std::span<const std::uint8_t> bytes) override {
    const std::lock_guard lock(mutex_);
    link_->send(bytes);
  }
  std::size_t receive(std::vector<std::uint8_t>& out) override {
    const std::lock_guard lock(mutex_);
    return link_->receive(out);
  }

 private:
  std::unique_ptr<Link> link_;
  std::mutex mutex_;
};

}  // namespace swath::mavlink
