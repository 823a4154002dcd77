#include "peri/box_check.h"

#include <cstdio>

namespace PeriSISSM {

std::string periodic_box_problem(const ReferenceBox &box, const int periodic[3], double horizon)
{
  double width[3];
  box.face_distances(width);
  for (int d = 0; d < 3; d++) {
    if (!periodic[d] || width[d] >= 2.0 * horizon) continue;
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "Pair style peri/nosb: the periodic box is %.8g wide in %c, shorter than two "
                  "horizons (2 x %.8g): enlarge the box or make that direction non-periodic",
                  width[d], "xyz"[d], horizon);
    return buf;
  }
  return "";
}

}    // namespace PeriSISSM
