#pragma once

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// Injections of a known effect into a recorded run, for semi-real checks of the diagnosis: the
/// real run keeps whatever it already has, and the diagnosis should find the injected effect on
/// top of that. Each injection changes the columns consistently (the gap follows the speeds), and
/// a zero magnitude returns the run unchanged.

/// Sensor time offset delta, in the convention of EffectSettings::sensor_time_offset_s and
/// synthesizeWithheldRun: the recorded leader speed becomes u(t - delta) (linear interpolation in
/// the run's own time, held at the ends) and the recorded gap s(t) minus the distance the leader
/// covers over [t - delta, t] (trapezoid rule on the interpolated speed), so that a diagnosis of
/// the result reads a time offset larger by delta. Any sign; the run's time may be non-uniform.
CarFollowingRun injectSensorTimeOffset(const CarFollowingRun& run, double offset_s);

/// Actuation lag T on the follower, open loop: its speed passes through v_lag' = (v - v_lag) / T
/// from v_lag(t0) = v(t0), discretised exactly for a speed linear between samples, and the gap
/// becomes s(t) + T v_lag(t), the gap a car driving v_lag all along would keep (it is T v_lag
/// behind the recorded car: T v0 at the start plus integral_t0^t (v - v_lag) dt, trapezoid). The
/// lag acts on the recorded car's acceleration, not on a command computed from the lagged car's
/// own state, so it reads in the model as less than T: closedLoopLagReading. lag_s >= 0 (0:
/// unchanged).
CarFollowingRun injectActuationLag(const CarFollowingRun& run, double lag_s);

/// What injectActuationLag(T) makes of a car that follows the model p (with or without a clock
/// offset on its leader data): exactly the model with an actuation lag T / c, gains k1 / c and k2
/// / c, time gap tau_e + T and the same jam distance, c = 1 + T (k1 tau_e + k2) (derived in
/// docs/DIAGNOSIS.md, "Semi-real checks"). Returns T / c, the lag the diagnosis should read.
double closedLoopLagReading(double lag_s, const AccParameters& p);

/// The whole model closedLoopLagReading describes: p's counterpart in the lagged record.
AccParameters closedLoopLagParameters(double lag_s, const AccParameters& p);

/// Linear interpolation of values (sampled at time_s, strictly increasing) at t, held at the ends.
double interpolateHeld(const std::vector<double>& time_s, const std::vector<double>& values, double t);

}  // namespace acc
