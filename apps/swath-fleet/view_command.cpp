#include "view_command.hpp"

#include <filesystem>
#include <iostream>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
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
  // Whole or not at all, as every output set. In the run's directory (the default) the page never
  // replaces a file no manifest lists (the user's own view.html); a page named with -o is written
  // as asked.
  base::OutputSet::Options options;
  options.mode = base::OutputSet::Mode::amend;  // pages of other names stay
  options.keep_unlisted = output_.empty();
  options.unlisted_remedy = "move it, or name another page with -o";
  base::OutputSet set(page.has_parent_path() ? page.parent_path() : fs::path("."), "fleet-view",
                      options);
  set.add(page.filename().string(), html);
  set.commit();
  std::cout << page.string() << ": " << record.drones.size() << " drone"
            << (record.drones.size() == 1 ? "" : "s") << ", " << base::fixed_text(record.end_s, 1)
            << " s\n";
  return 0;
}

}  // namespace swath::apps
