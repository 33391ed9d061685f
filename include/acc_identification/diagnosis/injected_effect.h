#pragma once

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

/// Actuation lag T on the follower: its speed passes through v_lag' = (v - v_lag) / T from
/// v_lag(t0) = v(t0), discretised exactly for a speed linear between samples, and the gap becomes
/// s(t) + integral_t0^t (v - v_lag) dt (trapezoid), the gap a car driving v_lag would keep. A lag
/// of the speed is a lag of its derivative too (T a_lag' + a_lag = a), i.e. the model's
/// actuation lag on top of the car's own. lag_s >= 0 (0: unchanged).
CarFollowingRun injectActuationLag(const CarFollowingRun& run, double lag_s);

/// Linear interpolation of values (sampled at time_s, strictly increasing) at t, held at the ends.
double interpolateHeld(const std::vector<double>& time_s, const std::vector<double>& values, double t);

}  // namespace acc
