#pragma once
// The processes that plan a batch's areas (swath batch): a few workers forked from the batch,
// each planning the areas it is sent one after another as `swath plan` would.

#include <string>
#include <vector>

namespace swath::apps {

/// The result of one area's `swath plan`.
struct PlanResult {
  int exit_code = -1;      ///< as `swath plan` exits; 128 + the signal that ended its process
  std::string message;     ///< the first line it wrote to stderr
  bool timed_out = false;  ///< ended for taking longer than the batch's timeout
};

/// A result's word in batch.csv's `status` column: `planned` (exit 0), `refused` (exit 2: the
/// area or its options cannot be planned, swath plan's sentence says why), `timed-out` (ended
/// by --timeout-s), `failed` (anything else: an unexpected failure, a signal).
const char* batch_status(const PlanResult& r);

/// Plans every `swath plan` command line of `commands` (argv, program name first), at most
/// `parallel` at once, in worker processes forked from this one (GDAL's libraries, loaded to list
/// the areas, they find loaded). A worker plans in process, with
/// stdout to /dev/null and stderr to a log in memory, read back after each area. A worker that
/// dies (a crash, a signal) fails only the area it was planning; a fresh worker takes the rest.
/// Results in the order of `commands`; each area writes its own directory, so they do not
/// depend on `parallel` or on which worker planned which area. `progress`: a bar on a terminal.
/// `timeout_s` (> 0): an area still planning after that many seconds of wall-clock time is failed
/// and its worker ended (a plan reading from a pipe nobody writes, a hung network mount); 0: none.
std::vector<PlanResult> plan_in_workers(const std::vector<std::vector<std::string>>& commands,
                                        int parallel, bool progress, double timeout_s = 0);

}  // namespace swath::apps
