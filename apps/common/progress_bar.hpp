#pragma once
// A progress bar on stderr, drawn only when stderr is a terminal (never into logs or pipes).

#include <string>

namespace swath::apps {

class ProgressBar {
 public:
  /// `wanted`: the user asked for it (--progress); it still stays silent off a terminal.
  ProgressBar(bool wanted, std::string label);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Redraws for `fraction` in [0, 1] when the shown percentage changes.
  void update(double fraction);

 private:
  bool enabled_;
  std::string label_;
  int shown_ = -1;
};

}  // namespace swath::apps
