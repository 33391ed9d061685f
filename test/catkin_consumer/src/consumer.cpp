// Uses acc_identification as another package would: headers of three components, their
// libraries, and a generated message. Prints what the test checks; exits 1 on a wrong value.
#include <cmath>
#include <cstdio>

#include <acc_identification/AccParameters.h>

#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/string_stability.h"
#include "acc_identification/relative_state/vehicle_geometry.h"

int main()
{
  // Table II, minimum setting: lambda2 = 70.67 (acc_model).
  const double lambda2 = acc::lambda2(acc::paperMinimumSetting());
  // One u-blox GGA sentence (acc_gnss).
  acc::NmeaSentence sentence;
  const bool parsed = acc::parseNmeaSentence(
                          "$GNGGA,101530.00,4508.12345,N,00827.12345,E,1,12,0.80,120.0,M,47.0,M,,*4B", sentence) ==
                      acc::NmeaParseOutcome::kOk;
  // One degree of latitude on the WGS84 ellipsoid at 45 N: 111,132 m (acc_relative_state, GeographicLib).
  const double distance_m = acc::geodesicDistance(44.5, 8.0, 45.5, 8.0);
  // The generated message, filled from the library's numbers.
  acc_identification::AccParameters message;
  message.lambda2 = lambda2;
  std::printf("consumer: lambda2 %.2f, gga %s, one degree %.0f m, message lambda2 %.2f\n", lambda2,
              parsed ? "parsed" : "rejected", distance_m, message.lambda2);
  const bool ok = std::fabs(lambda2 - 70.67) < 0.01 && parsed && std::fabs(distance_m - 111132.0) < 5.0;
  return ok ? 0 : 1;
}
