#include "view_command.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/fleet/event_replay.hpp"
#include "swath/web/live_page.hpp"

namespace swath::apps {

void FleetViewCommand::setup(CLI::App& app) {
  app.add_option("RUN", run_, "A run's directory (run -o DIR)")->required();
  app.add_option("-o,--output", output_, "The page to write (default: RUN/view.html)");
}

int FleetViewCommand::run() {
  namespace fs = std::filesystem;
  const std::string events_path = run_ + "/events.jsonl";
  const std::string events = base::read_text_file(events_path, "event log");
  // The page draws what it is given: a log that is not a run's is refused here, not in the page.
  const fleet::RunRecord record = fleet::replay_record(events, events_path);
  const fs::path page = output_.empty() ? fs::path(run_) / "view.html" : fs::path(output_);
  const std::string html = web::replay_page(run_, events);
  // Whole or not at all: written beside the page, then renamed onto it.
  const fs::path partial = page.string() + ".partial-" + std::to_string(::getpid());
  {
    std::ofstream out(partial, std::ios::binary);
    out << html;
    if (!out.flush()) {
      std::error_code ignored;
      fs::remove(partial, ignored);
      throw base::InputError(page.string() + ": cannot be written");
    }
  }
  fs::rename(partial, page);
  std::cout << page.string() << ": " << record.drones.size() << " drone"
            << (record.drones.size() == 1 ? "" : "s") << ", " << base::fixed_text(record.end_s, 1)
            << " s\n";
  return 0;
}

}  // namespace swath::apps
