#pragma once
// Fleet apps in Python (docs/swath-fleet.md "Apps in Python"): `swath-fleet run APP.py ...` runs a
// Python file defining `APP = function(bee)` in BeeCluster's API (paper 000 Table 1) through an
// embedded interpreter. Only the swath-fleet program links Python (SWATH_PYTHON on).

namespace swath::apps {

/// fleet_main, after loading the Python app named by an argument ending in ".py" (if any) and
/// registering it under that name. A file that cannot be loaded: one sentence, exit code 2.
int fleet_main_with_python(int argc, char** argv);

}  // namespace swath::apps
