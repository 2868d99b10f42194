// swath-fleet: applications written against virtual drones, run on a simulated fleet by a
// runtime that assigns drones to requests moment by moment (paper 000, BeeCluster).
#include "fleet_main.hpp"
#ifdef SWATH_FLEET_PYTHON
#include "python_app.hpp"
#endif

int main(int argc, char** argv) {
#ifdef SWATH_FLEET_PYTHON
  return swath::apps::fleet_main_with_python(argc, argv);
#else
  return swath::apps::fleet_main(argc, argv);
#endif
}
