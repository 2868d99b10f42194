#pragma once
// swath-fleet run --live: a tiny HTTP/1.1 server on 127.0.0.1 in a background thread.
//   GET /        the live page (web/live_page.hpp)
//   GET /events  the run's events.jsonl lines as server-sent events (text/event-stream), from the
//                first line (a page opened late catches up) or after Last-Event-ID, then each line
//                as the run logs it.
// The run stays single-threaded and deterministic: it only appends its lines to a queue under a
// mutex (append()); the server thread reads the queue and never touches the run.

#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace swath::apps {

/// "--live [PORT]"'s value: empty (the option alone) is kDefaultLivePort; else 0 to 65535.
/// Throws base::InputError for anything else.
int live_port(const std::string& text);
inline constexpr int kDefaultLivePort = 8765;

class LiveServer {
 public:
  /// Listens on 127.0.0.1:port (0: a free port the system picks) and starts serving `page`.
  /// Throws base::InputError when the port is taken or cannot be had.
  LiveServer(int port, std::string page);
  /// Stops serving: closes every connection.
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const { return port_; }
  std::string url() const;
  /// One line of events.jsonl (without its newline), from the run's thread.
  void append(const std::string& line);

 private:
  struct Client {
    int fd = -1;
    std::string request;     ///< received so far, until the blank line
    bool streaming = false;  ///< GET /events answered: lines follow
    std::size_t next = 0;    ///< the next line to send
  };
  void serve();
  void accept_client();
  bool read_request(Client& c);  ///< false: the connection is done with
  bool answer(Client& c);
  bool send_lines(Client& c);

  int listen_fd_ = -1, port_ = 0;
  std::string page_;
  std::mutex mutex_;
  std::vector<std::string> lines_;  ///< guarded by mutex_
  std::vector<Client> clients_;     ///< the server thread's own
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace swath::apps
