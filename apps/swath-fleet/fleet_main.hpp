#pragma once
// swath-fleet's command line as a function, for the program and for programs of one's own:
//
//   #include "fleet_main.hpp"            // link swath_fleet_commands
//   int main(int argc, char** argv) {
//     swath::fleet::register_app({"perimeter", "fly the sites' hull", perimeter_main}, "sites");
//     return swath::apps::fleet_main(argc, argv);   // run, compare, check, apps, worlds, render
//   }

namespace swath::apps {

/// Parses argv as swath-fleet does and runs the command; the exit code (0, 1, 2, 4:
/// docs/reliability.md, 'Exit codes and errors'). Apps registered with fleet::register_app before
/// the call are listed and run by name.
int fleet_main(int argc, char** argv);

}  // namespace swath::apps
