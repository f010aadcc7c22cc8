// Vehicle: armed, mode, landed state, battery, altitude, the motor commands and rotor speeds.
#include <cmath>

#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {

void draw_vehicle(Screen& screen, const Rect& r, const VehiclePanel& v) {
  screen.box(r, "Vehicle");
  const Rect in = r.inner();
  if (in.empty()) return;
  int y = in.y;
  if (v.unavailable) {
    for (const auto& line : wrap("n/a: " + *v.unavailable, in.w)) {
      if (y >= in.y + 2) break;
      put(screen, in, in.x, y++, line, {Color::Dim, false, false});
    }
  } else {
    put(screen, in, in.x, y, v.armed ? "ARMED" : "disarmed", v.armed ? Style{Color::Bad, true, true} : Style{Color::Good, false, false});
    put(screen, in, in.x + 10, y, fit(v.mode, 14), {Color::Accent, true, false});
    put(screen, in, in.x + 25, y, v.landed.empty() ? "landed ?" : v.landed);
    ++y;
    std::string battery = "batt " + number(v.battery_V, 1) + " V " + number(v.battery_A, 1) + " A " + number(v.battery_pct, 0) + "%";
    put(screen, in, in.x, y, battery);
    if (v.ready_to_arm)
      put(screen, in, in.x + static_cast<int>(battery.size()) + 2, y, *v.ready_to_arm ? "ready" : "not ready",
          health_style(*v.ready_to_arm ? Health::Good : Health::Degraded));
    ++y;
  }
  std::string alt = "alt " + number(v.altitude_m, 2) + " m est";
  if (v.truth_altitude_m) alt += ", " + number(v.truth_altitude_m, 2) + " m truth";
  put(screen, in, in.x, y++, alt);

  // One line per motor: the command as a bar; wide, the rotor speed as a second bar.
  const bool wide = in.w >= 56;
  for (std::size_t i = 0; i < 4 && y < in.y + in.h; ++i, ++y) {
    const double u = v.motors ? (*v.motors)[i] : NAN;
    const double w_rad_s = v.rotor_speed_rad_s ? (*v.rotor_speed_rad_s)[i] : NAN;
    const std::string speed = v.rotor_speed_rad_s ? format("%5.0f rad/s", w_rad_s) : "";
    const int text_w = 3 + 5 + 1 + static_cast<int>(speed.size());
    const int bars_w = in.w - text_w - 1;
    const int command_w = wide ? bars_w / 2 : bars_w;
    int x = in.x;
    put(screen, in, x, y, format("M%zu ", i), {Color::Dim, false, false});
    x += 3;
    put(screen, in, x, y, v.motors ? bar(u, command_w) : fit("", command_w), {Color::Accent, false, false});
    x += command_w;
    put(screen, in, x, y, right(v.motors ? format("%.2f", u) : "-", 5));
    x += 6;
    if (wide && v.rotor_speed_rad_s && v.rotor_max_rad_s > 0) {
      const int speed_w = bars_w - command_w - 1;
      put(screen, in, x, y, bar(w_rad_s / v.rotor_max_rad_s, speed_w), {Color::Good, false, false});
      x += speed_w + 1;
    }
    put(screen, in, x, y, speed);
  }
}

}  // namespace hitl::tui
