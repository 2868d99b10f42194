#pragma once
// The battery of what flies (paper 004 eq. 12): its parameters, the current a power draws, and
// the one state-of-charge integrator every simulation uses (swath-energy's flight and budgets,
// swath-fleet's drones, swath-control's flight): charge drawn, in ampere-seconds, off the
// capacity.

namespace swath::vehicle {

/// A battery. Defaults: Seewald's simulator (paper 004, docs/swath-energy.md).
struct Battery {
  double voltage_v = 14.8;             ///< internal (open-circuit) voltage V, > 0
  double stabilised_voltage_v = 12.0;  ///< stabilised (regulated) voltage V~, > 0
  double resistance_ohm = 0.0012;      ///< internal resistance R_r, > 0
  double capacity_ah = 5.0;            ///< nominal capacity Q_c, ampere-hours, > 0
  double initial_soc = 1.0;            ///< state of charge at take-off, (0, 1]
  double reserve_soc = 0.2;            ///< land with at least this, [0, initial_soc)
  /// Voltage sag (swath-control's plant): cells in series, 0 = off (eq. 12 above as before).
  /// On, the pack's terminal voltage is cells × OCV(SoC) − I × cells × R_cell (lipo_cell_ocv_v).
  int cells = 0;
  double internal_resistance_ohm = 0.006;  ///< R_cell, one cell's DC resistance, Ω
  /// ArduPilot's MOT_BAT_VOLT_MAX / MIN for the whole pack: the motors reach the propeller's
  /// max_speed_rad_s at volt_max_v, and the controller multiplies its thrust outputs by
  /// (volt_max_v / V)², V the filtered terminal voltage clamped to [volt_min_v, volt_max_v].
  double volt_max_v = 16.8;
  double volt_min_v = 13.2;
  /// Whether the controller compensates its outputs for the voltage (ArduPilot does when
  /// MOT_BAT_VOLT_MAX > 0).
  bool thrust_compensation = true;
};

/// The open-circuit voltage of one lithium-polymer cell at state of charge `soc` (clamped to
/// [0, 1]), V: Chen and Rincón-Mora, "Accurate electrical battery model capable of predicting
/// runtime and I–V performance", IEEE Trans. Energy Conversion 21(2), 2006, fitted to a
/// polymer Li-ion cell: −1.031 e^(−35 s) + 3.685 + 0.2156 s − 0.1178 s² + 0.3201 s³
/// (4.10 V full, 3.73 V at 20 %, 2.65 V empty).
double lipo_cell_ocv_v(double soc);

/// The pack's open-circuit voltage, cells × lipo_cell_ocv_v(soc), V (cells > 0).
double open_circuit_voltage_v(const Battery& b, double soc);
/// The pack's internal resistance, cells × R_cell, Ω.
double pack_resistance_ohm(const Battery& b);
/// The terminal voltage while `current_a` flows: OCV(soc) − I R_pack, V.
double terminal_voltage_v(const Battery& b, double soc, double current_a);
/// The current that delivers `power_w` at the terminals, (OCV − √(OCV² − 4 R P)) / 2R, A;
/// NaN when P exceeds OCV² / 4R (the most the pack can deliver).
double sag_current_a(const Battery& b, double soc, double power_w);

/// Current drawn for `power_w` (eq. 12 without the capacity):
/// I = (V - sqrt(V^2 - 4 R V~ P / V)) / (2 R), amperes. NaN when P exceeds max_power_w().
double battery_current_a(const Battery& b, double power_w);

/// The largest power eq. 12 can deliver (its square root's argument is zero): V^3 / (4 R V~), W.
double max_power_w(const Battery& b);

/// The share of the capacity `charge_as` ampere-seconds are: q / (3600 Q_c).
double soc_of_charge(const Battery& b, double charge_as);

/// The state-of-charge integrator: the state of charge after drawing `charge_as` ampere-seconds
/// (the integral of the current), SoC - q / (3600 Q_c). May go below 0 (the caller decides what
/// an empty battery means).
double soc_after_charge(const Battery& b, double soc, double charge_as);

/// State of charge after drawing `power_w` for `seconds`: the charge I t off the state of charge.
/// NaN beyond max_power_w().
double soc_after(const Battery& b, double soc, double power_w, double seconds);

/// Seconds until the state of charge falls from `soc` to `target_soc` at constant `power_w`
/// (infinity when power_w <= 0, 0 when soc <= target_soc).
double seconds_to_soc(const Battery& b, double soc, double target_soc, double power_w);

/// Energy the battery's charge between `soc` and `target_soc` delivers at constant `power_w`, J.
double usable_energy_j(const Battery& b, double soc, double target_soc, double power_w);

}  // namespace swath::vehicle
