#pragma once
// Battery state of charge from the power drawn, paper 004 eq. 12: the battery of what flies,
// vehicle/battery.hpp, named in energy as before.

#include "swath/vehicle/battery.hpp"

namespace swath::energy {

using vehicle::Battery;
using vehicle::battery_current_a;
using vehicle::max_power_w;
using vehicle::seconds_to_soc;
using vehicle::soc_after;
using vehicle::soc_after_charge;
using vehicle::soc_of_charge;
using vehicle::usable_energy_j;

}  // namespace swath::energy
